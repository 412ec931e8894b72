;;; A real window: a short game run under an X server. Every other suite
;;; draws headless (SDL's dummy video driver, a software renderer on a
;;; surface); this one runs a small game script in a child process under
;;; `xvfb-run` (Debian's xvfb, which `make test` installs) with
;;; SDL_VIDEODRIVER unset, so SDL opens a real X11 window. The child
;;; prints what SDL reports (video driver, renderer, window size, frames
;;; run) and saves a screenshot, which this suite checks pixel by pixel.
;;; Without xvfb-run the suite fails: a skipped window test would hide a
;;; broken windowed path.

(import scheme (chicken base) (chicken file) (chicken format) (chicken string)
        (chicken process) (chicken platform) (chicken io) (chicken pathname)
        (chicken process-context)
        srfi-4 (only (downstroke util) take) (downstroke test) (downstroke sdl2))
(include-relative "pixels.scm")

(define win-dir (create-temporary-directory))
(define (win-path name) (string-append win-dir "/" name))

(define win-xvfb-run?
  (zero? (system "command -v xvfb-run >/dev/null 2>&1")))

;; The game the child runs: a 64x48 logical screen at scale 2, a TMX map
;; (red tile at cell (0, 0), blue at (3, 2)) over a green background, and
;; a yellow square entity at (16, 8).
(define win-script "
(import scheme (chicken base) (chicken format) (chicken process-context)
        (downstroke sdl2) (downstroke scene) (downstroke engine))
(define args (command-line-arguments))
(define game
  (make-game
   title: \"downstroke window test\" width: 64 height: 48 scale: 2
   create: (lambda (g)
             (printf \"driver ~a~%\" (current-video-driver))
             (printf \"renderer ~a~%\" (renderer-name (game-renderer g)))
             (receive (w h) (window-size (game-window g))
               (printf \"window ~ax~a~%\" w h))
             (game-load-scene! g (cadr args) background: '(0 255 0) camera-target: #f
                               entities: (list (list #:x 16 #:y 8 #:width 8 #:height 8
                                                     #:color '(255 255 0)))))))
(printf \"frames ~a~%\" (game-run! game headless?: #f frames: 30 screenshot: (car args)))
")

(define (win-write-files!)
  (init!)
  (write-tiles-png! (win-path "t.png") 8 '((255 0 0) (0 0 255)))
  (write-csv-tmx! (win-path "m.tmx") "t.png" 8 2 1
                  '((1 0 0 0 0 0 0 0) (0 0 0 0 0 0 0 0) (0 0 0 2 0 0 0 0)
                    (0 0 0 0 0 0 0 0) (0 0 0 0 0 0 0 0) (0 0 0 0 0 0 0 0)))
  (with-output-to-file (win-path "game.scm") (lambda () (display win-script))))

;; The shell command: the child sees this process's module repository,
;; the real video driver (SDL_VIDEODRIVER removed) and no audio device.
(define (win-command)
  (sprintf "env -u SDL_VIDEODRIVER SDL_AUDIODRIVER=dummy CHICKEN_REPOSITORY_PATH=~a timeout 120 xvfb-run -a -s '-screen 0 640x480x24' csi -q -s ~a ~a ~a 2>&1"
           (qs (string-intersperse
                (map (lambda (p) (if (absolute-pathname? p) p
                                     (make-absolute-pathname (current-directory) p)))
                     (repository-path))
                ":"))
           (qs (win-path "game.scm")) (qs (win-path "shot.png")) (qs (win-path "m.tmx"))))

;; (values output exit-status) of a shell command.
(define (win-run cmd)
  (let* ((port (open-input-pipe cmd))
         (out (read-string #f port))
         (status (close-input-pipe port)))
    (values (if (eof-object? out) "" out) status)))

(test-group "window: a real X11 window under xvfb-run"
  (test-assert "xvfb-run is installed (install the Debian packages xvfb and xauth; `make test` installs them)"
               win-xvfb-run?)
  (when win-xvfb-run?
    (win-write-files!)
    (receive (out status) (win-run (win-command))
      (let ((has? (lambda (line) (and (substring-index line out) #t))))
        (test "the child game exits cleanly" 0 status)
        (unless (zero? status) (printf "     child output:~%~a~%" out))
        (test-assert "SDL's video driver is x11 (a real window, not the dummy driver)"
                     (has? "driver x11\n"))
        (test-assert "the window is width * scale by height * scale" (has? "window 128x96\n"))
        (test-assert "the renderer names its backend" (has? "renderer "))
        (test-assert "30 frames ran" (has? "frames 30\n"))
        (test-assert "the screenshot was saved" (file-exists? (win-path "shot.png")))
        (when (file-exists? (win-path "shot.png"))
          (let ((at (lambda (x y) (take (png-pixel (win-path "shot.png") x y) 3))))
            (test "the screenshot is the window's size" '(128 96) (png-size (win-path "shot.png")))
            (test "the red tile at cell (0, 0), 2x: pixels 0..15" '((255 0 0) (255 0 0) (0 255 0))
                  (list (at 0 0) (at 15 15) (at 16 0)))
            (test "the blue tile at cell (3, 2): pixels (48..63, 32..47)"
                  '((0 0 255) (0 0 255) (0 255 0) (0 255 0))
                  (list (at 48 32) (at 63 47) (at 47 32) (at 64 47)))
            (test "the yellow entity at (16, 8): pixels (32..47, 16..31)"
                  '((255 255 0) (255 255 0) (0 255 0))
                  (list (at 32 16) (at 47 31) (at 48 31)))
            (test "the background elsewhere" '(0 255 0) (at 100 80))))))))

(delete-directory win-dir #t)
