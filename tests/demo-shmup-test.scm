;;; bin/demo-shmup, run headless as a user would: without input nothing is
;;; destroyed; holding fire shoots down what crosses the ship's line of fire,
;;; and the screenshot shows fewer enemies, the bullets above the ship and
;;; one score pip per enemy destroyed. The arrows move the ship.
;;; The demo draws at 320 x 240 with no scale: screenshot pixels are world
;;; pixels. The ship starts at (153, 210), 14 x 14; bullets (3 x 8) leave
;;; from x + 6; enemies are 16 x 16; score pips are 4 x 4 from (4, 4).

(import scheme (chicken base) (chicken io) (chicken process) (chicken file)
        (chicken string) (chicken format) (downstroke test))
(include-relative "pixels.scm")
(include-relative "demo-support.scm")

;; Runs the demo for `frames` with `script` (or none); returns its last line.
(define (sh-demo! frames script shot)
  (when (file-exists? shot) (delete-file shot))
  (when script (with-output-to-file (demo-tmp "sh-script.scm") (lambda () (write script))))
  (last-line (demo-output (sprintf "bin/demo-shmup --headless --frames ~a --screenshot ~a~a"
                                 frames shot (if script (string-append " --script " (demo-tmp "sh-script.scm")) "")))))

(define sh-ship '(120 220 255))
(define sh-enemy '(230 80 90))
(define sh-bullet '(255 255 160))
(define sh-pip '(255 210 80))

(define (sh-count shot colour . rect) (apply png-count shot (near-colour? colour) rect))

(define sh-idle (demo-tmp "sh-idle.png"))
(define sh-fire (demo-tmp "sh-fire.png"))

(test-group "demo: shmup"
  (test-group "200 frames without input"
    (test "nothing is destroyed" "shmup: enemies destroyed 0" (sh-demo! 200 #f sh-idle))
    (test-assert "a 320 x 240 screenshot"
                 (receive (bytes w h) (png-rgba sh-idle) (and (= w 320) (= h 240))))
    (test "the ship (14 x 14) is where it starts" (* 14 14) (sh-count sh-idle sh-ship 153 210 14 14))
    (test "no bullet, no score pip" '(0 0) (list (sh-count sh-idle sh-bullet) (sh-count sh-idle sh-pip)))
    (test-assert "enemies of waves 2 and 3 cross the ship's column (x 157..164)"
                 (> (sh-count sh-idle sh-enemy 157 0 8 200) 0)))

  (test-group "200 frames holding fire"
    (test "four enemies are destroyed" "shmup: enemies destroyed 4" (sh-demo! 200 '((0 a)) sh-fire))
    (test "one 4 x 4 score pip per enemy destroyed" (* 4 16) (sh-count sh-fire sh-pip 0 0 40 12))
    (test "no enemy is left in the line of fire" 0 (sh-count sh-fire sh-enemy 157 0 8 200))
    (test-assert "fewer enemies than without fire: at least one 16 x 16 enemy fewer"
                 (<= (sh-count sh-fire sh-enemy) (- (sh-count sh-idle sh-enemy) 256)))
    (let ((bullets (sh-count sh-fire sh-bullet)))
      (test-assert "bullets are in flight" (>= bullets (* 3 8)))
      (test "every bullet pixel is above the ship, in its column"
            bullets (sh-count sh-fire sh-bullet 159 0 3 210))))

  (test-group "the arrows steer the ship"
    ;; left for 20 frames at 3 px a frame, then fire alone
    (sh-demo! 30 '((0 left) (20 a)) sh-fire)
    (test "the ship is 60 px left of its start" (* 14 14) (sh-count sh-fire sh-ship 93 210 14 14))
    (test "and only there" (* 14 14) (sh-count sh-fire sh-ship))))
