;;; bin/demo-animation, run headless as a user would: each character shows
;;; the frame its animation's durations give on the last frame, walkers
;;; rest and turn where their beat ends, and the screenshot shows them.

(import scheme (chicken base) (chicken io) (chicken process) (chicken file)
        (chicken string) (chicken port) (downstroke test))
(include-relative "pixels.scm")
(include-relative "demo-support.scm")

;; "animation: frame N ((type anim tile x) ...)" -> (N characters), or #f.
(define (an-parse line)
  (and (substring=? line "animation: frame ")
       (with-input-from-string (substring line 17 (string-length line))
         (lambda () (let* ((n (read)) (cs (read))) (list n cs))))))

;; The tile a looping animation shows on its `step`th step (from 1) when it
;; starts on frame `first`: frames is ((tile . ticks) ...). Counted here,
;; not with (downstroke animation): each frame lasts exactly its ticks.
(define (an-tile frames step #!optional (first 0))
  (let* ((frames (append (list-tail frames first)
                         (let take ((fs frames) (n first))
                           (if (= n 0) '() (cons (car fs) (take (cdr fs) (- n 1)))))))
         (cycle (foldl + 0 (map cdr frames))))
    (let loop ((fs frames) (k (modulo (- step 1) cycle)))
      (if (< k (cdar fs)) (caar fs) (loop (cdr fs) (- k (cdar fs)))))))

;; The demo's animations (frames are gids of sprites.tsx)
(define an-walk '((10 . 6) (9 . 6) (11 . 6) (9 . 6)))
(define an-idle '((9 . 40) (15 . 6)))
(define an-hop '((16 . 8) (17 . 6) (13 . 10)))
(define an-flap '((18 . 4) (19 . 4) (20 . 4) (19 . 4)))
(define an-spin '((21 . 6) (22 . 6) (23 . 6) (22 . 6)))
(define an-flicker '((24 . 6) (25 . 5) (26 . 7)))

(define an-shot (demo-tmp "an-demo-animation.png"))

(test-group "demo: animation"
  (when (file-exists? an-shot) (delete-file an-shot))
  ;; 100 frames: hero 1 walks right from 40 (1 px a frame, from frame 1);
  ;; hero 2 walked left from 250 and reached 170 on frame 80, where it
  ;; rests (idle from then on: 19 steps); the blob hops at 1/2 px a frame.
  (let ((r (an-parse (last-line (demo-output (string-append "bin/demo-animation --headless --frames 100 --screenshot " an-shot))))))
    (test-assert "the demo prints its characters" r)
    (when r
      (test "it ran 100 frames" 100 (car r))
      (test "every character's animation, tile and x after 100 frames"
            `((torch flicker ,(an-tile an-flicker 100) 16)
              (torch flicker ,(an-tile an-flicker 100) 288)
              (hero walk ,(an-tile an-walk 100) 139)
              (hero idle ,(an-tile an-idle 19) 170)
              (blob hop ,(an-tile an-hop 100) ,(+ 80 99/2))
              (bird flap ,(an-tile an-flap 100) 150)
              (bird flap ,(an-tile an-flap 100) 200)
              ,@(map (lambda (i) `(coin spin ,(an-tile an-spin 100 (modulo i 4)) ,(+ 112 (* 20 i))))
                     '(0 1 2 3 4)))
            (cadr r))
      (test "the five coins show four different frames: full, turning, edge-on, turning, full"
            '(21 22 23 22 21) (map caddr (list-tail (cadr r) 7)))))

  ;; The screenshot is at scale 2: a logical pixel (x, y) is (2x, 2y).
  (test-assert "a screenshot was saved" (file-exists? an-shot))
  (when (file-exists? an-shot)
    (let ((count-in (lambda (colour x y w h)
                      (png-count an-shot (near-colour? colour) (* 2 x) (* 2 y) (* 2 w) (* 2 h)))))
      (test-assert "hero 1's blue shirt is drawn where it stands (x 139)"
                   (> (count-in '(40 120 230) 139 176 16 16) 50))
      (test "and not where it started (x 40)" 0 (count-in '(40 120 230) 40 176 16 16))
      (test-assert "hero 2 faces left (it walked left): its eye is on the left of its face"
                   (and ((near-colour? '(20 20 30)) (png-pixel an-shot (+ 1 (* 2 (+ 170 5))) (+ 1 (* 2 (+ 176 4)))))
                        (not ((near-colour? '(20 20 30)) (png-pixel an-shot (+ 1 (* 2 (+ 170 9))) (+ 1 (* 2 (+ 176 4))))))))
      (test-assert "the first coin shows its face (bright gold)" (> (count-in '(252 210 60) 112 52 16 16) 40))
      (test "the third coin is edge-on: no face, only its rim"
            '(0 #t) (list (count-in '(252 210 60) 152 52 16 16) (> (count-in '(200 140 20) 152 52 16 16) 10)))
      (test-assert "the first bird, red, is at x 150" (> (count-in '(220 70 50) 150 84 16 16) 40))
      (test-assert "hero 1's label (its animation's name) is white text over its head"
                   (> (count-in '(255 255 255) 136 166 24 8) 20))
      (test-assert "the title is drawn in the sprite font at scale 2"
                   (> (count-in '(255 255 255) 8 6 108 16) 150))
      (test-assert "the stage's grass is drawn from tiles.png"
                   (> (count-in '(76 176 60) 0 192 320 5) 1000))
      (test-assert "the sky is the background colour"
                   ((near-colour? '(92 148 252)) (png-pixel an-shot 620 200)))))

  ;; 155 frames: hero 1 reached its right end (150) on frame 110 and has
  ;; rested 44 steps: the blink frame (steps 41-46). Hero 2 rested 60
  ;; frames (81-140), turned and walks right again since frame 142.
  (let ((r (an-parse (last-line (demo-output "bin/demo-animation --headless --frames 155")))))
    (test-assert "the demo prints its characters" r)
    (when r
      (test "hero 1 blinks while it rests at the end of its beat"
            `(hero idle 15 150) (list-ref (cadr r) 2))
      (test "hero 2 has turned and walks back right"
            `(hero walk ,(an-tile an-walk 13) 183) (list-ref (cadr r) 3)))))
