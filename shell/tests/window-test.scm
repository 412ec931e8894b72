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
(include-relative "../../tests/pixels.scm")

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


;;; Window modes: a resizable window letterboxed, the pointer mapped to
;;; logical pixels through scale and bars, fullscreen from make-game and
;;; toggled by the fullscreen action (f11) and by procedure.
(define modes-script "
(import scheme (chicken base) (chicken format) (chicken process-context)
        (downstroke sdl2) (downstroke scene) (downstroke input) (downstroke engine))
(define args (command-line-arguments))
(define mode (string->symbol (car args)))
(define stage 0)
(define before #f)
(define (say g what) (receive (w h) (window-size (game-window g))
                       (printf \"~a ~ax~a fullscreen ~a~%\" what w h (window-fullscreen? (game-window g)))))
(define game
  (make-game
   title: \"downstroke window modes\" width: 64 height: (if (eq? mode 'resize) 48 32) scale: 1.5
   resizable?: (eq? mode 'resize) fullscreen?: (eq? mode 'fullscreen)
   create: (lambda (g)
             (say g \"start\")
             (game-scene-set! g (make-sprite-scene background: '(0 255 0)
                                  entities: (list (list #:x 0 #:y 0 #:width 8 #:height 8 #:color '(255 255 0))
                                                  (list #:x 56 #:y 24 #:width 8 #:height 8 #:color '(255 0 0))))))
   update: (lambda (g dt)
             (let ((f (game-frame g)))
               (case mode
                 ((resize)
                  ;; The X server takes its time to resize (seconds on a
                  ;; loaded machine): the pointer moves once it has. A
                  ;; pushed event is read at the next pass of the loop,
                  ;; which may come frames later (a loaded machine runs
                  ;; several frames a pass): a position is said once it
                  ;; has changed.
                  (receive (w h) (window-size (game-window g))
                    (receive (x y) (game-mouse-position g)
                      (let ((pointer (list x y)))
                        (cond ((= f 1) (window-size-set! (game-window g) 200 72))
                              ((and (= stage 0) (= w 200) (= h 72))
                               (set! stage 1) (set! before pointer) (push-mouse-motion-event! 82 15))
                              ((and (= stage 1) (not (equal? pointer before)))
                               (set! stage 2) (set! before pointer)
                               (printf \"mouse ~a ~a~%\" x y)
                               (push-mouse-motion-event! 147 71))
                              ((and (= stage 2) (not (equal? pointer before)))
                               (set! stage 3)
                               (printf \"mouse ~a ~a~%\" x y)
                               (say g \"resized\")))))))
                 ((toggle)
                  (case f
                    ((2) (push-key-event! 'key-down 'f11))
                    ((3) (push-key-event! 'key-up 'f11))
                    ((8) (say g \"f11\") (game-toggle-fullscreen! g))
                    ((14) (say g \"procedure\")))))))))
(printf \"frames ~a~%\" (game-run! game headless?: #f frames: (if (eq? mode 'resize) 300 16) screenshot: (cadr args)))
")

(define (modes-command mode)
  (sprintf "env -u SDL_VIDEODRIVER SDL_AUDIODRIVER=dummy CHICKEN_REPOSITORY_PATH=~a timeout 120 xvfb-run -a -s '-screen 0 640x480x24' csi -q -s ~a ~a ~a 2>&1"
           (qs (string-intersperse
                (map (lambda (p) (if (absolute-pathname? p) p
                                     (make-absolute-pathname (current-directory) p)))
                     (repository-path))
                ":"))
           (qs (win-path "modes.scm")) mode (qs (win-path (string-append mode ".png")))))

(test-group "window: resizable, letterboxed, fullscreen (a real X11 window under xvfb-run)"
  (when win-xvfb-run?
    (with-output-to-file (win-path "modes.scm") (lambda () (display modes-script)))
    (receive (out status) (win-run (modes-command "resize"))
      (let ((has? (lambda (line) (and (substring-index line out) #t)))
            (shot (win-path "resize.png")))
        (test "the resizing game exits cleanly" 0 status)
        (unless (zero? status) (printf "     child output:~%~a~%" out))
        (test-assert "a non-integer scale: 64x48 at 1.5 is a 96x72 window" (has? "start 96x72 fullscreen #f\n"))
        (test-assert "the window resized to 200x72" (has? "resized 200x72 fullscreen #f\n"))
        ;; 200x72 shows the 64x48 game 1.5 times larger (96x72), centred:
        ;; window x 52..147 is the game, x 0..51 and 148..199 the bars
        (test-assert "the pointer at window (82, 15) is logical (20, 10)" (has? "mouse 20 10\n"))
        (test-assert "the pointer at window (147, 71) is logical (63, 47)" (has? "mouse 63 47\n"))
        (when (file-exists? shot)
          (let ((at (lambda (x y) (take (png-pixel shot x y) 3))))
            (test "the screenshot is the resized window" '(200 72) (png-size shot))
            (test "black bars left and right of the game"
                  '((0 0 0) (0 0 0) (0 0 0) (0 0 0))
                  (list (at 0 0) (at 51 71) (at 148 0) (at 199 71)))
            (test "the game between them: the yellow square at logical (0, 0) is window 52..63"
                  '((255 255 0) (255 255 0) (0 255 0))
                  (list (at 52 0) (at 63 11) (at 64 12)))
            (test "the red square at logical (56, 24): window (136..147, 36..47)"
                  '((255 0 0) (255 0 0) (0 255 0))
                  (list (at 136 36) (at 147 47) (at 135 36)))))))
    (receive (out status) (win-run (modes-command "fullscreen"))
      (let ((has? (lambda (line) (and (substring-index line out) #t)))
            (shot (win-path "fullscreen.png")))
        (test "the fullscreen game exits cleanly" 0 status)
        (unless (zero? status) (printf "     child output:~%~a~%" out))
        (test-assert "fullscreen?: #t: SDL gives the window the 640x480 screen" (has? "start 640x480 fullscreen #t\n"))))
    ;; (Xvfb runs no window manager, which a fullscreen X11 window needs to
    ;; be laid over the screen, so the fullscreen pixels are not checked
    ;; here; the letterbox they would show is the resized window's above.)
    (receive (out status) (win-run (modes-command "toggle"))
      (let ((has? (lambda (line) (and (substring-index line out) #t))))
        (test "the toggling game exits cleanly" 0 status)
        (unless (zero? status) (printf "     child output:~%~a~%" out))
        (test-assert "windowed at first" (has? "start 96x48 fullscreen #f\n"))
        (test-assert "f11 (the fullscreen action) made it fullscreen" (has? "f11 640x480 fullscreen #t\n"))
        (test-assert "game-toggle-fullscreen! made it a window again, of its own size"
                     (has? "procedure 96x48 fullscreen #f\n"))))))

(delete-directory win-dir #t)
