;;; bin/demo-platformer, what it shows (tests/demo-smoke-test.scm checks
;;; the player and the lift): coins are map objects turned entities that
;;; the player takes, in a puff of sparkles (particles), counted as text;
;;; the towers of the background layer are drawn at 35% opacity over the
;;; sky; the moving platform and the lift are drawn from the tiles sheet.
;;; The window scale is 2: a world pixel is 2 x 2 screenshot pixels.
;;; The demo starts on its title, over the frozen level: the scripts press
;;; start on frame 0, so play begins on frame 1.
;;; Its states: the title, a pause pushed over the frozen level, a fade to
;;; the game over screen when the last of 3 lives is lost.

(import scheme (chicken base) (chicken io) (chicken process) (chicken file)
        (chicken string) (chicken format) (downstroke test))
(include-relative "pixels.scm")
(include-relative "demo-support.scm")

(define pl-script '((0 start) (1 right) (41 right a) (42 right) (91)))

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

(define pl-shot (demo-tmp "pl-151.png"))
(define pl-puff (demo-tmp "pl-47.png"))
(define pl-sky '(92 148 252))

(test-group "demo: platformer"
  (let* ((lines (pl-demo! 151 pl-shot))
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
  (let* ((lines (pl-demo! 47 pl-puff))
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

;; Runs the demo with `script` (a list) for `frames`, a screenshot to
;; `shot`; answers its lines of state, coins and player ("" when missing).
(define (pl-run! script frames shot)
  (when (file-exists? shot) (delete-file shot))
  (with-output-to-file (demo-tmp "pl-states.scm") (lambda () (write script)))
  (let ((lines (demo-output (sprintf "bin/demo-platformer --headless --frames ~a --screenshot ~a --script ~a"
                                     frames shot (demo-tmp "pl-states.scm")))))
    ;; the game over screen's scene has no player: no coins nor player line
    (map (lambda (start) (let ((l (filter-lines start lines))) (if (pair? l) (car l) "")))
         '("platformer: state" "platformer: coins" "platformer: player"))))

;; Walks right, jumping every 30 frames from frame 50 to `until`: the
;; player takes coins and falls into the spike pit, again and again.
(define (pl-reckless until . more)
  (append '((0 start))
          (let loop ((n 50) (out '()))
            (if (>= n until) (reverse out) (loop (+ n 30) (cons (list (+ n 1) 'right) (cons (list n 'right 'a) out)))))
          more))

(test-group "demo: platformer's states"
  (let* ((shot (demo-tmp "pl-title.png"))
         (lines (pl-run! '() 1 shot)))
    (test "it starts on the title, pushed over the game's own hooks" "platformer: state (title #f) lives 3" (car lines))
    (test "the level under it is frozen: the player has not fallen yet, the lift not moved"
          '(32 192 0 0 200) (pl-numbers (caddr lines)))
    ;; the shirt (40 120 230) under the title's dimming (0 0 20, alpha 120)
    (test-assert "the player is drawn on the frozen title, though no frame ran (its animation's first frame)"
                 (> (png-count shot (near-colour? '(21 64 131) 3) 64 384 32 32) 20)))
  (let* ((script '((0 start) (1 right) (30 right start) (31 right)))
         (at-35 (pl-run! script 35 (demo-tmp "pl-pause-35.png")))
         (at-45 (pl-run! script 45 (demo-tmp "pl-pause-45.png"))))
    (test "start in play pushes the pause over the level" "platformer: state (pause #f) lives 3" (car at-45))
    (test "the level is frozen under it: the player and the lift have not moved in 10 frames"
          (caddr at-35) (caddr at-45))
    (test-assert "the pause's text is drawn (white)"
                 (> (png-count (demo-tmp "pl-pause-45.png") (near-colour? '(255 255 255) 0) 200 180 240 100) 50)))
  (let ((over (pl-run! (pl-reckless 540) 540 (demo-tmp "pl-over.png"))))
    (test "three falls into the spikes: the game over screen" "platformer: state (game-over) lives 0" (car over))
    (test-assert "its own scene is drawn (dark purple)"
                 (> (png-count (demo-tmp "pl-over.png") (near-colour? '(30 10 30) 0)) 200000)))
  (let ((mid (pl-run! (pl-reckless 540) 480 (demo-tmp "pl-fading.png"))))
    (test "on the way there the level fades out, frozen" "platformer: state () lives 0" (car mid))
    (test "no pixel of the frame is still the bright sky" 0
          (png-count (demo-tmp "pl-fading.png") (near-colour? pl-sky 10))))
  (test "start on the game over screen fades back to a fresh level and its title"
        "platformer: state (title #f) lives 3"
        (car (pl-run! (pl-reckless 540 '(560 start) '(561)) 620 (demo-tmp "pl-again.png")))))

;; The end of the level, at once (--start-x 858: the player starts on the
;; ground beside the ladder of column 54, x 864): the ladder of the tile
;; layer "ladders" climbed through the library's ladder step, the ledge
;; it leads to, and the enemies of the object layer "enemies".
(define (pl-end! script frames #!optional shot (start 858))
  (with-output-to-file (demo-tmp "pl-end.scm") (lambda () (write script)))
  (when (and shot (file-exists? shot)) (delete-file shot))
  (let ((lines (demo-output (sprintf "bin/demo-platformer --headless --start-x ~a --frames ~a --script ~a~a"
                                     start frames (demo-tmp "pl-end.scm")
                                     (if shot (string-append " --screenshot " shot) "")))))
    (map (lambda (start) (let ((l (filter-lines start lines))) (if (pair? l) (car l) "")))
         '("platformer: state" "platformer: coins" "platformer: enemies" "platformer: player"))))

(test-group "demo: platformer's ladder"
  (let ((mid (pl-end! '((0 start) (1 up)) 40 (demo-tmp "pl-ladder.png"))))
    ;; up read in frame 1's update, so 38 frames of climbing from y 192
    (test "holding up: the player grabbed the ladder, centred on it, and climbs 2 px a frame"
          '("platformer: enemies 2 squashed 0 climbing #t" (864 116))
          (list (caddr mid) (let ((n (pl-numbers (cadddr mid)))) (list (car n) (cadr n)))))
    (test-assert "the ladder's rails are drawn"
                 (> (png-count (demo-tmp "pl-ladder.png") (near-colour? '(120 78 40) 0)) 100)))
  (test "at its top (row 5, y 80) the player stands on it, no longer climbing"
        '("platformer: enemies 2 squashed 0 climbing #f" "platformer: player at (864, 64) on-ground #t")
        (let ((l (pl-end! '((0 start) (1 up)) 70)))
          (list (caddr l) (substring (cadddr l) 0 44))))
  (test "then right along the ledge: the two coins up there are taken"
        "platformer: coins 2 left 13"
        (substring (cadr (pl-end! '((0 start) (1 up) (70 right)) 100)) 0 27))
  (test "back left, down: it climbs down through the top and stands at the foot"
        "platformer: player at (864, 192) on-ground #t"
        (substring (cadddr (pl-end! '((0 start) (1 up) (70 right) (100 left) (128 down)) 240)) 0 45)))

(test-group "demo: platformer's enemies"
  ;; the enemy at x 784 walks left, turns at the wall (x 752) by its
  ;; contacts, and walks back into the player, who starts at x 800
  (test "standing still: the enemy walks into its side, which costs a life"
        '("platformer: state () lives 2" "platformer: enemies 2 squashed 0 climbing #f")
        (let ((l (pl-end! '((0 start) (1)) 90 #f 800))) (list (car l) (caddr l))))
  (test "jumping as it comes: the player lands on it from above and squashes it"
        '("platformer: state () lives 3" "platformer: enemies 1 squashed 1 climbing #f")
        (let ((l (pl-end! '((0 start) (1) (50 a) (51)) 90 #f 800))) (list (car l) (caddr l)))))
