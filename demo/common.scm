;;; What every demo shares: its command line, which is every game's
;;; (game-run! reads it, see docs/guide.org "Headless runs"):
;;;   bin/demo-NAME [--headless] [--frames N] [--screenshot FILE] [--script FILE]
;;;                 [--screenshot-at N FILE]... [--trace WHO:KEY,...]... [--trace-file FILE]
;;; A demo also runs headless, 300 frames, when there is no display.
;;; Demos are run by csi from the repository root (see bin/).

(import scheme (chicken base) (chicken process-context) (chicken format)
        (downstroke engine))

(define (demo-flag? name) (and (member name (command-line-arguments)) #t))

(define (no-display?)
  (or (not (or (get-environment-variable "DISPLAY")
               (get-environment-variable "WAYLAND_DISPLAY")))
      (equal? (get-environment-variable "SDL_VIDEODRIVER") "dummy")))

;; Whether this run is headless (the platformer reports where it ended).
(define (demo-headless?) (or (demo-flag? "--headless") (no-display?)))

;; Runs `game` as the command line says; with no display to open a window
;; on, headless (for 300 frames unless --frames says).
(define (demo-run! game)
  (if (and (no-display?) (not (demo-flag? "--headless")))
      (let ((frames (if (demo-flag? "--frames") #f 300)))
        ;; no window wanted: do not let SDL probe for a display server
        (set-environment-variable! "SDL_VIDEODRIVER" "dummy")
        (when frames (printf "~a: no display, running ~a frames headless~%" (game-title game) frames))
        (if frames
            (game-run! game headless?: #t frames: frames)
            (game-run! game headless?: #t)))
      (begin
        (when (demo-flag? "--headless") (set-environment-variable! "SDL_VIDEODRIVER" "dummy"))
        (game-run! game))))
