;;; What every demo shares: its command line.
;;;   bin/demo-NAME [--headless] [--frames N] [--screenshot FILE] [--script FILE]
;;; --headless runs without a window (also when there is no display);
;;; --frames stops after N logical frames; --screenshot saves the last frame
;;; as a PNG; --script reads an input script ((frame . actions) ...) from FILE.
;;; Demos are run by csi from the repository root (see bin/).

(import scheme (chicken base) (chicken process-context) (chicken format)
        (downstroke engine))

(define (demo-option name)
  (let ((m (member name (command-line-arguments))))
    (and m (pair? (cdr m)) (cadr m))))

(define (demo-flag? name) (and (member name (command-line-arguments)) #t))

;; Headless when asked, or when there is no display to open a window on.
(define (demo-headless?)
  (or (demo-flag? "--headless")
      (not (or (get-environment-variable "DISPLAY")
               (get-environment-variable "WAYLAND_DISPLAY")))
      (equal? (get-environment-variable "SDL_VIDEODRIVER") "dummy")))

;; Runs `game` as the command line says. A headless run without --frames
;; would never end, so it defaults to 300 frames.
(define (demo-run! game)
  (let* ((headless (demo-headless?))
         (frames (cond ((demo-option "--frames") => string->number)
                       (headless 300)
                       (else #f)))
         (script-file (demo-option "--script"))
         (script (and script-file (with-input-from-file script-file read))))
    ;; no window wanted: do not let SDL probe for a display server
    (when headless (set-environment-variable! "SDL_VIDEODRIVER" "dummy"))
    (when (and headless (not (demo-flag? "--headless")))
      (printf "~a: no display, running ~a frames headless~%" (game-title game) frames))
    (game-run! game frames: frames input-script: script
               screenshot: (demo-option "--screenshot")
               headless?: headless)))
