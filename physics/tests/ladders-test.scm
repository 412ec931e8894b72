;;; Ladders (docs/physics.org, "Ladders"): ladder cells from tile
;;; properties and maps made in code, their tops one-way for every body,
;;; and the climbing step: a #:climber? grabs when its #:climb asks,
;;; climbs without gravity, stands on the top, climbs down from it, and
;;; lets go by jumping, stepping off, passing the bottom end or reaching
;;; the floor. Exact integers throughout; the engine's fast path and the
;;; readable steps agree on every frame.

(import scheme (chicken base) (chicken format) srfi-4 (downstroke test) (downstroke entity) (downstroke scene)
        (downstroke tilemap) (downstroke physics) (downstroke pipeline))

(define (ld-ent . plist) (plist->entity plist))

;; 16 px tiles, 8 x 8. Tile 3 is a ladder. A ledge in row 2 (y 32) with a
;; ladder in column 3 from row 2 (its top) down to row 5, which stands on
;; the floor of row 6 (y 96); a short ladder in column 6, rows 2-3,
;; hanging over the air.
(define ld-map
  (list->tilemap '((0 0 0 0 0 0 0 0)
                   (0 0 0 0 0 0 0 0)
                   (1 1 1 3 1 1 3 0)
                   (0 0 0 3 0 0 3 0)
                   (0 0 0 3 0 0 0 0)
                   (0 0 0 3 0 0 0 0)
                   (1 1 1 1 1 1 1 1)
                   (1 1 1 1 1 1 1 1))
                 ladders: '(3)))

;; (x y vy climbing? on-ground?) of the first entity after each of n frames.
(define (ld-run e n pipeline #!optional (mode 'swept))
  (let loop ((s (make-scene tilemap: ld-map entities: (list e) collision-mode: mode)) (k 0) (out '()))
    (if (= k n)
        (reverse out)
        (let* ((s (pipeline s 16)) (e (car (scene-entities s))))
          (loop s (+ k 1)
                (cons (map (lambda (key) (entity-ref e key #f)) '(#:x #:y #:vy #:climbing? #:on-ground?))
                      out))))))

;; The frames numbered in `at` (from 1) of an n-frame run, by both
;; pipelines, in both collision modes.
(define (both name expected e n at)
  (define (pick run) (map (lambda (k) (list-ref run (- k 1))) at))
  (for-each (lambda (mode)
              (test (sprintf "~a (engine, ~a)" name mode) expected (pick (ld-run e n engine-pipeline mode)))
              (test (sprintf "~a (readable steps, ~a)" name mode) expected (pick (ld-run e n contract-pipeline mode))))
            '(swept discrete)))

;; A 12 x 16 climber, its own climb intent; `more` keys set over it.
(define (climber x y climb . more)
  (let loop ((e (ld-ent #:type 'climber #:x x #:y y #:width 12 #:height 16 #:vx 0 #:vy 0
                        #:gravity? #t #:climber? #t #:climb climb))
             (more more))
    (if (null? more) e (loop (entity-set e (car more) (cadr more)) (cddr more)))))

(test-group "ladder cells"
  (test "tilemap-ladder?: column 3, rows 2-5" '(#f #t #t #t #t #f)
        (map (lambda (r) (tilemap-ladder? ld-map 3 r)) '(1 2 3 4 5 6)))
  (test "a ladder is not solid" '(#f #f) (list (tilemap-solid? ld-map 3 2) (tilemap-solid? ld-map 3 4)))
  (test "its top cell (no ladder above) is one-way, the others are not" '(#t #f #f)
        (map (lambda (r) (tilemap-one-way? ld-map 3 r)) '(2 3 5)))
  (test "tilemap-ladder-top?" '(#t #f #t)
        (list (tilemap-ladder-top? ld-map 3 2) (tilemap-ladder-top? ld-map 3 3) (tilemap-ladder-top? ld-map 6 2)))
  (test "a map without ladders answers #f" #f (tilemap-ladder? (list->tilemap '((1 3))) 1 0))
  (test "a solid tile of another layer in the cell wins: no ladder there" '(#t #f)
        (let* ((a (list->u32vector '(3 3))) (b (list->u32vector '(0 1)))
               (tm (make-tilemap 1 2 16 16 (list (make-layer "ladder" 1 2 a) (make-layer "wall" 1 2 b))
                                 ladders: '(3))))
          (list (tilemap-ladder? tm 0 0) (tilemap-ladder? tm 0 1)))))

(test-group "a ladder's top is a one-way platform for every body"
  (both "a body with no #:climber? falls onto it and stands there"
        '((50 16 0 #f #t)) (ld-ent #:x 50 #:y 0 #:width 12 #:height 16 #:gravity? #t) 20 '(20))
  (both "jumping from below it passes through the ladder and lands on top"
        '((50 16 0 #f #t)) (ld-ent #:x 50 #:y 56 #:width 12 #:height 16 #:vy -13 #:gravity? #t) 30 '(30))
  (both "with #:drop-through? it falls through to the floor"
        '((50 80 0 #f #t)) (ld-ent #:x 50 #:y 16 #:width 12 #:height 16 #:gravity? #t #:drop-through? #t) 30 '(30)))

(test-group "climbing up"
  (both "up at the foot: grabs, centred on the column (x 48 + 2), climbs 2 px a frame without gravity"
        '((50 78 -2 #t #f) (50 70 -2 #t #f))
        (climber 49 80 -1) 5 '(1 5))
  (both "reaching the top (bottom on y 32 in frame 32): stands on it, no longer climbing"
        '((50 18 -2 #t #f) (50 16 0 #f #t) (50 16 0 #f #t))
        (climber 50 80 -1) 40 '(31 32 40))
  (both "#:climb-speed 5: the last step is cut to the top"
        '((50 20 -5 #t #f) (50 16 0 #f #t))
        (climber 50 80 -1 #:climb-speed 5) 13 '(12 13))
  (both "up in the air over the ladder grabs it mid-fall"
        '((50 58 -2 #t #f))
        (climber 46 60 -1 #:vy 3) 1 '(1))
  (both "no intent: a climber falls past the ladder like any body"
        '((50 80 0 #f #t))
        (climber 50 40 0) 20 '(20)))

(test-group "climbing down"
  (both "down on the top: grabs and climbs down through it"
        '((50 18 2 #t #f) (50 80 2 #t #t))
        (climber 50 16 1) 32 '(1 32))
  (both "down with one foot on the ledge beside the top: the centre decides, it grabs (x 54 to 50)"
        '((50 18 2 #t #f))
        (climber 54 16 1) 1 '(1))
  (both "at the floor, still pressing down: lets go and stands"
        '((50 80 0 #f #t) (50 80 0 #f #t))
        (climber 50 16 1) 40 '(33 40))
  (both "down on the floor at the ladder's foot grabs nothing"
        '((50 80 0 #f #t))
        (climber 50 80 1) 3 '(3))
  (both "past the bottom end of a hanging ladder: lets go and falls"
        '((98 64 2 #t #f) (98 65 1 #f #f))
        (climber 98 40 1 #:climbing? #t) 13 '(12 13)))

(test-group "tune-physics! climb-speed:"
  (tune-physics! climb-speed: 4)
  (both "a climber without #:climb-speed climbs at the tuned 4 px a frame" '((50 76 -4 #t #f))
        (climber 50 80 -1) 1 '(1))
  (tune-physics! climb-speed: 2)
  (test-error "a negative one is an error" (tune-physics! climb-speed: -1))
  (test "and changes nothing" 2 *climb-speed*))

(test-group "letting go"
  (both "holding on with no intent: no gravity, no motion"
        '((50 50 0 #t #f))
        (climber 50 50 0 #:climbing? #t) 5 '(5))
  (both "a jump (#:ay -10) lets go: the jump of the ground, -9 in its first frame"
        '((50 41 -9 #f #f))
        (climber 50 50 0 #:climbing? #t #:ay -10) 1 '(1))
  (both "stepping sideways until the centre leaves the column: falls from rest"
        '((59 50 0 #t #f) (62 51 1 #f #f))
        (climber 50 50 0 #:climbing? #t #:vx 3) 4 '(3 4)))

;; One-way entities (lifts with #:one-way?) let a climbing body through,
;; as one-way tiles do: they neither stop it, carry it nor hold it up; a
;; body that is not climbing meets them again.
(define (lift x y . more)
  (apply ld-ent #:type 'lift #:x x #:y y #:width 32 #:height 8 #:solid? #t #:immovable? #t #:one-way? #t more))

;; (x y vy climbing? on-ground?) of the first entity after the frames
;; numbered in `at`, by both pipelines in both modes.
(define (both-with name expected es n at)
  (define (run pipeline mode)
    (let loop ((s (make-scene tilemap: ld-map entities: es collision-mode: mode)) (k 1) (out '()))
      (if (> k n)
          (reverse out)
          (let* ((s (pipeline s 16)) (e (car (scene-entities s))))
            (loop s (+ k 1)
                  (if (memv k at)
                      (cons (map (lambda (key) (entity-ref e key #f)) '(#:x #:y #:vy #:climbing? #:on-ground?)) out)
                      out))))))
  (for-each (lambda (mode)
              (test (sprintf "~a (engine, ~a)" name mode) expected (run engine-pipeline mode))
              (test (sprintf "~a (readable steps, ~a)" name mode) expected (run contract-pipeline mode)))
            '(swept discrete)))

(test-group "climbing through one-way entities"
  (both-with "down through a one-way lift (top y 64): not stopped, not held up, on to the floor"
             '((50 48 2 #t #f) (50 50 2 #t #f) (50 56 2 #t #f) (50 80 2 #t #t))
             (list (climber 50 16 1 #:solid? #t) (lift 40 64)) 32 '(16 17 20 32))
  (both-with "up through it from the floor"
             '((50 62 -2 #t #f) (50 48 -2 #t #f))
             (list (climber 50 80 -1 #:solid? #t) (lift 40 64)) 16 '(9 16))
  (both-with "a one-way lift going down faster than the climber does not take it along"
             '((98 18 2 #t #f) (98 24 2 #t #f))
             (list (climber 98 16 1 #:solid? #t)
                   (lift 88 33 #:vy 3 #:skip-pipelines '(tile-collisions-x tile-collisions-y)))
             4 '(1 4))
  (both-with "past a hanging ladder's end it lets go, falls and lands on the lift below (top y 88)"
             '((98 64 2 #t #f) (98 65 1 #f #f) (98 72 0 #f #t))
             (list (climber 98 16 1 #:solid? #t) (lift 88 48) (lift 88 88)) 30 '(24 25 30)))

(test-group "contacts see the ladder's top"
  (test "a body standing on it touches, with its floor, the tile ladder" '(ladder)
        (let* ((s (make-scene tilemap: ld-map
                              entities: (list (ld-ent #:x 50 #:y 16 #:width 12 #:height 16 #:gravity? #t
                                                      #:contacts? #t))))
               (s (engine-pipeline s 16)))
          (entity-touch-tiles (car (scene-entities s)) 'floor))))

(test-group "a scene without a climber pays nothing for ladders"
  (define walker (ld-ent #:x 50 #:y 80 #:width 12 #:height 16 #:gravity? #t #:climb -1 #:climbing? #t))
  (test "the engine's fast path leaves the climbing step out of a scene with no #:climber?"
        '(acceleration gravity velocity-x tile-collisions-x velocity-y tile-collisions-y on-solid)
        (engine-pipeline-steps (make-scene tilemap: ld-map entities: (list walker))))
  (test "and runs it in one with a climber" #t
        (and (memq 'climbing (engine-pipeline-steps
                              (make-scene tilemap: ld-map entities: (list walker (climber 50 80 -1)))))
             #t))
  (test "#:climbing? without #:climber? is nothing: gravity pulls, no ladder holds" '((50 80 0 #t #t))
        (ld-run walker 1 engine-pipeline)))

(test-exit)
