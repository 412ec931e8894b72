;;; bin/demo-shmup in a real X11 window (xvfb-run, SDL_VIDEODRIVER unset,
;;; as shell/tests/window-test.scm does for the engine): the sprite keys
;;; (offsets, the banking #:angle), tile particles with their colour and
;;; alpha modulation, and the TTF score go through the window's renderer
;;; too, and come out as in the headless run. Without xvfb-run the suite
;;; fails rather than hide the windowed path.

(import scheme (chicken base) (chicken io) (chicken process) (chicken file)
        (chicken string) (chicken format) (downstroke test))
(include-relative "pixels.scm")
(include-relative "demo-support.scm")

(define sw-xvfb-run? (zero? (system "command -v xvfb-run >/dev/null 2>&1")))

;; Runs the demo for `frames` with `script`, windowed under Xvfb or
;; headless; answers its last line.
(define (sw-demo! window? frames script shot)
  (when (file-exists? shot) (delete-file shot))
  (with-output-to-file (demo-tmp "sw-script.scm") (lambda () (write script)))
  (last-line
   (demo-output
    (if window?
        (sprintf "env -u SDL_VIDEODRIVER SDL_AUDIODRIVER=dummy timeout 120 xvfb-run -a -s '-screen 0 640x480x24' bin/demo-shmup --frames ~a --script ~a --screenshot ~a"
                 frames (demo-tmp "sw-script.scm") shot)
        (sprintf "bin/demo-shmup --headless --frames ~a --script ~a --screenshot ~a"
                 frames (demo-tmp "sw-script.scm") shot)))))

(define sw-ship '(120 220 255))
(define (sw-count shot colour . rect) (apply png-count shot (near-colour? colour) rect))

;; How many pixels differ by more than 8 in a channel between two PNGs
;; of the same size. The window's renderer rounds alpha blending a little
;; differently from the software one (by 3 at most, seen here), so blended
;; pixels (sparks, the text's edges) may differ by that much.
(define (sw-differences a b)
  (receive (ba w h) (png-rgba a)
    (receive (bb w2 h2) (png-rgba b)
      (let loop ((i 0) (n 0))
        (if (= i (* w h)) n
            (loop (+ i 1) (if (> (apply max (map (lambda (p q) (abs (- p q)))
                                                 (rgba-at ba w (modulo i w) (quotient i w))
                                                 (rgba-at bb w (modulo i w) (quotient i w))))
                                 8)
                              (+ n 1) n)))))))

(test-group "demo: shmup in a real window"
  (test-assert "xvfb-run is installed (make test installs xvfb)" sw-xvfb-run?)
  (when sw-xvfb-run?
    (let ((win (demo-tmp "sw-window.png")) (head (demo-tmp "sw-headless.png")))
      (test "200 frames holding fire, windowed: the same game as headless"
            "shmup: enemies destroyed 4, sparks 16" (sw-demo! #t 200 '((0 a)) win))
      (sw-demo! #f 200 '((0 a)) head)
      (test "a 320 x 240 screenshot" '(320 240) (png-size win))
      (test "the upright ship's pixels, as headless" (sw-count head sw-ship 152 209 16 16)
            (sw-count win sw-ship 152 209 16 16))
      (test "the frame, stars, sparks and text included, is the headless one (blends within 8)" 0
            (sw-differences win head))
      (sw-demo! #t 10 '((0 left)) win)
      (sw-demo! #f 10 '((0 left)) head)
      (test-assert "banking left, windowed: more of the ship's top half left of its middle"
                   (> (sw-count win sw-ship 118 205 12 12) (sw-count win sw-ship 130 205 12 12)))
      ;; a turned copy is sampled differently by the window's renderer
      ;; (pixels along the edges land one over), so not pixel for pixel
      (test-assert "and about as many of its pixels as headless (within 20%)"
                   (let ((w (sw-count win sw-ship)) (h (sw-count head sw-ship)))
                     (<= (* 8 h) (* 10 w) (* 12 h)))))))
