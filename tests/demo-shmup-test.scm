;;; bin/demo-shmup, run headless as a user would: without input nothing is
;;; destroyed; holding fire shoots down what crosses the ship's line of
;;; fire, in sparks (particles), and the score is text; the arrows move
;;; and bank the ship. Stars (particles) fill the sky.
;;; The demo draws at 320 x 240 with no scale: screenshot pixels are world
;;; pixels. The ship's hitbox starts at (153, 210), 14 x 14, its 16 x 16
;;; sprite one pixel out on each side; bullets leave from x + 6; enemies
;;; are 16 x 16. The art is demo/assets/shmup.png (tools/make-assets.scm):
;;; the ship's body is (120 220 255), the enemies' hull (230 80 90), the
;;; bullets' edge (255 255 160), stars (200 200 255), score (255 210 80).

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
(define sh-star '(200 200 255))
(define sh-score '(255 210 80))

(define (sh-count shot colour . rect) (apply png-count shot (near-colour? colour) rect))

;; Spark pixels: warm colours blended over the night sky, which no tile of
;; the sheet has (its colours are drawn unblended).
(define (sh-spark? c)
  (let ((r (car c)) (g (cadr c)) (b (caddr c)))
    (and (> r 100) (< g r) (< b 80)
         (not (member (list r g b) '((150 40 60) (255 170 40)))))))

(define sh-idle (demo-tmp "sh-idle.png"))
(define sh-fire (demo-tmp "sh-fire.png"))
(define sh-left (demo-tmp "sh-left.png"))

(test-group "demo: shmup"
  (test-group "200 frames without input"
    (test "nothing is destroyed, no sparks" "shmup: enemies destroyed 0, sparks 0" (sh-demo! 200 #f sh-idle))
    (test-assert "a 320 x 240 screenshot"
                 (receive (bytes w h) (png-rgba sh-idle) (and (= w 320) (= h 240))))
    (let ((ship-pixels (sh-count sh-idle sh-ship)))
      (test-assert "the ship sprite is drawn" (> ship-pixels 60))
      (test "all of it in its 16 x 16 box at (152, 209)" ship-pixels (sh-count sh-idle sh-ship 152 209 16 16))
      (test "upright: as much of it left of its middle as right"
            (sh-count sh-idle sh-ship 152 209 8 16) (sh-count sh-idle sh-ship 160 209 8 16)))
    (test "no bullet" 0 (sh-count sh-idle sh-bullet))
    (test "no spark" 0 (png-count sh-idle sh-spark? 0 24 320 176))
    (test-assert "the score is text at the top left" (> (sh-count sh-idle sh-score 0 0 100 22) 20))
    (test "and nowhere else" (sh-count sh-idle sh-score) (sh-count sh-idle sh-score 0 0 100 22))
    (test-assert "a sky of stars (1 x 1 particles)" (> (sh-count sh-idle sh-star) 100))
    (test-assert "enemies of waves 2 and 3 cross the ship's column (x 157..164)"
                 (> (sh-count sh-idle sh-enemy 157 0 8 200) 0)))

  (test-group "200 frames holding fire"
    (test "four enemies are destroyed; the last burst of 16 sparks is flying"
          "shmup: enemies destroyed 4, sparks 16" (sh-demo! 200 '((0 a)) sh-fire))
    (test-assert "sparks are drawn, blended over the sky" (> (png-count sh-fire sh-spark? 0 24 320 176) 10))
    (test-assert "the score's text changed from 0"
                 (not (= (sh-count sh-fire sh-score 0 0 100 22) (sh-count sh-idle sh-score 0 0 100 22))))
    (test "no enemy is left in the line of fire" 0 (sh-count sh-fire sh-enemy 157 0 8 200))
    (test-assert "fewer enemies than without fire"
                 (< (sh-count sh-fire sh-enemy) (sh-count sh-idle sh-enemy)))
    (let ((bullets (sh-count sh-fire sh-bullet)))
      (test-assert "bullets are in flight" (>= bullets 8))
      (test "every bullet pixel is above the ship, in its column"
            bullets (sh-count sh-fire sh-bullet 158 0 6 210))))

  (test-group "the arrows steer and bank the ship"
    ;; left for 20 frames at 3 px a frame, then fire alone
    (sh-demo! 30 '((0 left) (20 a)) sh-fire)
    (test "the ship is 60 px left of its start"
          (sh-count sh-idle sh-ship) (sh-count sh-fire sh-ship 92 209 16 16))
    (test "and only there" (sh-count sh-idle sh-ship) (sh-count sh-fire sh-ship))
    (sh-demo! 10 '((0 left)) sh-left)
    (test-assert "turning left, the ship leans left: more of its top half left of its middle"
                 (> (sh-count sh-left sh-ship 118 205 12 12) (sh-count sh-left sh-ship 130 205 12 12)))))
