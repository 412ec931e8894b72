;;; bin/demo-platformer, what it shows (tests/demo-smoke-test.scm checks
;;; the player and the lift): coins are map objects turned entities that
;;; the player takes, in a puff of sparkles (particles), counted as text;
;;; the towers of the background layer are drawn at 35% opacity over the
;;; sky; the moving platform and the lift are drawn from the tiles sheet.
;;; The window scale is 2: a world pixel is 2 x 2 screenshot pixels.

(import scheme (chicken base) (chicken io) (chicken process) (chicken file)
        (chicken string) (chicken format) (downstroke test))
(include-relative "pixels.scm")
(include-relative "demo-support.scm")

(define pl-script '((0 right) (40 right a) (41 right) (90)))

;; Runs the demo for `frames`; answers its two last lines.
(define (pl-demo! frames shot)
  (when (file-exists? shot) (delete-file shot))
  (with-output-to-file (demo-tmp "pl-script.scm") (lambda () (write pl-script)))
  (let ((lines (demo-output (sprintf "bin/demo-platformer --headless --frames ~a --screenshot ~a --script ~a"
                                     frames shot (demo-tmp "pl-script.scm")))))
    (list (cadr (reverse lines)) (last-line lines))))

;; The integers of a line.
(define (pl-numbers line)
  (map string->number
       (string-split (list->string (map (lambda (c) (if (char-numeric? c) c #\space)) (string->list line))))))

(define pl-shot (demo-tmp "pl-150.png"))
(define pl-puff (demo-tmp "pl-46.png"))
(define pl-sky '(92 148 252))

(test-group "demo: platformer"
  (let* ((lines (pl-demo! 150 pl-shot))
         (numbers (pl-numbers (cadr lines)))
         (cx (list-ref numbers 2)) (cy (list-ref numbers 3)))
    (test "jumping at frame 40 takes one of the 15 coins" "platformer: coins 1 left 14 sparkles 0"
          (car lines))
    (test-assert "the count is drawn as text at the top left"
                 (> (png-count pl-shot (near-colour? '(255 240 120) 40) 0 0 200 40) 30))
    (test "the towers' dark tiles never appear opaque" 0
          (png-count pl-shot (lambda (c) (member (list (car c) (cadr c) (caddr c))
                                                 '((52 60 100) (64 74 120))))))
    ;; the tower of columns 3-4, rows 8-12: its tiles at 35% over the sky
    (test-assert "the tower at (48, 128) is its tile blended 35% over the sky"
                 (> (png-count pl-shot (near-colour? '(78 117 199) 3)
                               (* 2 (- 48 cx)) (* 2 (- 128 cy)) 64 160)
                    200))
    (test-assert "the spinning coins are drawn (their gold)"
                 (> (png-count pl-shot (near-colour? '(252 210 60))) 50))
    (test-assert "the moving platform is the plank tile: its dark body shows"
                 (> (png-count pl-shot (near-colour? '(150 104 56))) 40)))
  (let* ((lines (pl-demo! 46 pl-puff))
         (numbers (pl-numbers (cadr lines)))
         (cx (list-ref numbers 2)) (cy (list-ref numbers 3)))
    (test "four frames after the coin is taken its 12 sparkles fly" "platformer: coins 1 left 14 sparkles 12"
          (car lines))
    ;; around where the coin at (112, 176) was: warm blends over the sky,
    ;; which the coins' own colours (drawn unblended) are not
    (test-assert "and are drawn where the coin was"
                 (> (png-count pl-puff
                               (lambda (c)
                                 (let ((r (car c)) (g (cadr c)) (b (caddr c)))
                                   (and (> r 150) (> g b) (< b 240)
                                        (not (member (list r g b) '((255 250 180) (252 210 60) (200 140 20)
                                                                    (250 200 160)))))))
                               (* 2 (- 96 cx)) (* 2 (- 150 cy)) 96 96)
                    10))))
