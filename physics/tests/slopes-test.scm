;;; Slopes (docs/physics.org, "Slopes"): a body's foot, the middle of its
;;; bottom edge, walks up and down slope tiles exactly on their floor,
;;; lands on them from any fall speed, counts them as ground, and meets
;;; the flat tiles at their top and foot without a bump; the engine's fast
;;; path and the readable steps agree.

(import scheme (chicken base) (chicken format) (downstroke test) (downstroke entity) (downstroke scene)
        (downstroke tilemap) (downstroke physics) (downstroke pipeline))

(scene-checks #f)

;; 16 px tiles. A 45 degree hill: up from column 3 (y 64 at x 48) to a
;; flat top at y 32 (columns 5 and 6), down to column 8; the floor is row 4.
(define sl-hill45
  (list->tilemap '((0 0 0 0 0 0 0 0 0 0 0 0 0 0)
                   (0 0 0 0 0 0 0 0 0 0 0 0 0 0)
                   (0 0 0 0 3 1 1 4 0 0 0 0 0 0)
                   (0 0 0 3 1 1 1 1 4 0 0 0 0 0)
                   (1 1 1 1 1 1 1 1 1 1 1 1 1 1))
                 slopes: '((3 0 16) (4 16 0))))

;; The same with 22.5 degree pairs (each tile rises 8 px).
(define sl-hill22
  (list->tilemap '((0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0)
                   (0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0)
                   (0 0 0 0 0 5 6 1 1 7 8 0 0 0 0 0)
                   (0 0 0 5 6 1 1 1 1 1 1 7 8 0 0 0)
                   (1 1 1 1 1 1 1 1 1 1 1 1 1 1 1 1))
                 slopes: '((5 0 8) (6 8 16) (7 16 8) (8 8 0))))

;; The floor under x, worked out from the map as docs/physics.org
;; states it: the topmost slope line or solid top in the column.
;; The first floor at x from row `from` down (a walker under a ledge
;; scans from its own row).
(define (sl-floor tm x #!optional (from 0))
  (let ((col (floor (/ x 16))))
    (let loop ((r from))
      (cond ((= r (tilemap-height tm)) #f)
            ((tilemap-slope tm col r)
             => (lambda (s) (- (* (+ r 1) 16) (+ (car s) (/ (* (- (cdr s) (car s)) (- x (* col 16))) 16)))))
            ((tilemap-solid? tm col r) (* r 16))
            (else (loop (+ r 1)))))))

(define (sl-body x y w h vx . more)
  (plist->entity (append (list #:type 'walker #:x x #:y y #:width w #:height h #:vx vx #:gravity? #t) more)))

;; n frames of `pipeline`, the walker's #:vx set back to vx after each
;; (as a game's update: does); the list of (x y on-ground?) after each.
(define (sl-walk pipeline tm e vx n #!optional (mode 'swept))
  (let loop ((s (make-scene tilemap: tm collision-mode: mode entities: (list e))) (k 0) (out '()))
    (if (= k n)
        (reverse out)
        (let* ((s (pipeline s 16)) (e (car (scene-entities s))))
          (loop (scene-map-entities s (lambda (s e) (entity-set e #:vx vx))) (+ k 1)
                (cons (list (entity-ref e #:x) (entity-ref e #:y) (entity-ref e #:on-ground? #f)) out))))))

(define (list-tail-n ls from n)
  (let loop ((ls (list-tail ls from)) (n n))
    (if (or (= n 0) (null? ls)) '() (cons (car ls) (loop (cdr ls) (- n 1))))))

(test-group "walking up and down a 45 degree hill"
  (let ((frames (sl-walk engine-pipeline sl-hill45 (sl-body 0 48 16 16 2) 2 80)))
    (test "up the hill: the foot (x + 8) rises 2 px for each 2 px on x, from the foot of the slope"
          '((40 48 #t) (42 46 #t) (44 44 #t) (46 42 #t) (48 40 #t) (50 38 #t) (52 36 #t)
            (54 34 #t) (56 32 #t) (58 30 #t) (60 28 #t) (62 26 #t) (64 24 #t) (66 22 #t)
            (68 20 #t) (70 18 #t) (72 16 #t) (74 16 #t) (76 16 #t))
          (list-tail-n frames 19 19))
    (test "down the other side, onto the floor without a hop"
          '((104 16 #t) (106 18 #t) (108 20 #t) (110 22 #t) (112 24 #t) (114 26 #t) (116 28 #t)
            (118 30 #t) (120 32 #t) (122 34 #t) (124 36 #t) (126 38 #t) (128 40 #t) (130 42 #t)
            (132 44 #t) (134 46 #t) (136 48 #t) (138 48 #t))
          (list-tail-n frames 51 18))))

;; Every frame of a walk across a hill, both ways: the foot is on the
;; floor under it and the body is on the ground.
(define (sl-sweep tm pipeline mode)
  (let ((width (* 16 (tilemap-width tm))) (bad 0) (frames 0) (first #f))
    (for-each
     (lambda (vx)
       (for-each
        (lambda (w)
          (for-each
           (lambda (dir)
             (let* ((v (* dir vx))
                    (x0 (if (> dir 0) 0 (- width 8 w)))
                    (n (quotient (- width 24 w) vx)))
               (for-each (lambda (f)
                           (set! frames (+ frames 1))
                           (let ((foot-x (+ (car f) (/ w 2))) (foot-y (+ (cadr f) 16)))
                             (unless (and (caddr f) (= foot-y (sl-floor tm foot-x)))
                               (set! bad (+ bad 1))
                               (unless first (set! first (list 'vx v 'w w f))))))
                         (sl-walk pipeline tm (sl-body x0 48 w 16 v) v n mode))))
           '(1 -1)))
        '(8 12 15 16)))
     '(1 2 3 4 5 6))
    (list bad frames first)))

(test-group "every frame of every walk: the foot on the floor, on the ground"
  (for-each
   (lambda (tm name)
     (for-each
      (lambda (mode)
        (let ((r (sl-sweep tm engine-pipeline mode)))
          (test (sprintf "~a, ~a, 1 to 6 px/frame, widths 8 12 15 16, both ways: ~a frames" name mode (cadr r))
                '(0 #f) (list (car r) (caddr r)))))
      '(swept discrete)))
   (list sl-hill45 sl-hill22) '("45 degrees" "22.5 degrees")))

(test-group "22.5 degrees: exact rationals where the line is between pixels"
  (let ((frames (sl-walk engine-pipeline sl-hill22 (sl-body 40 48 15 16 1) 1 6)))
    ;; foot x = x + 15/2; on tile 5 (0 -> 8 px over 16) the floor is
    ;; 64 - (foot x - 48) / 2
    (test "x 41 .. 46: y = 48 - (x + 15/2 - 48) / 2"
          (map (lambda (x) (list x (- 48 (/ (- (+ x 15/2) 48) 2)) #t)) '(41 42 43 44 45 46))
          frames)
    (test "one of them, written out" '(45 183/4 #t) (list-ref frames 4))))

(test-group "landing on a slope from any fall speed"
  (define tall (list->tilemap (append (let rows ((k 30)) (if (= k 0) '() (cons '(0 0 0 0 0 0 0 0) (rows (- k 1)))))
                                      '((0 0 3 1 4 5 6 0) (1 1 1 1 1 1 1 1)))
                              slopes: '((3 0 16) (4 16 0) (5 0 8) (6 8 16))))
  (for-each
   (lambda (mode)
     (let loop ((cases (let each ((vys '(13 17 29 31 40 47 64 100)) (out '()))
                         (if (null? vys) out
                             (each (cdr vys) (append (map (lambda (fx) (cons (car vys) fx)) '(33 40 47 66 78 90 100)) out)))))
                (bad '()))
       (if (null? cases)
           (test (sprintf "~a: foot on the floor after falling at 13 to 100 px/frame onto 7 places" mode) '() bad)
           (let* ((vy (caar cases)) (fx (cdar cases))
                  (e (sl-body (- fx 6) 0 12 16 0 #:vy vy #:max-vy vy))
                  (s (let run ((s (make-scene tilemap: tall collision-mode: mode entities: (list e))) (k 0))
                       (if (= k 60) s (run (engine-pipeline s 16) (+ k 1)))))
                  (b (car (scene-entities s))))
             (loop (cdr cases)
                   (if (and (= (+ (entity-ref b #:y) 16) (sl-floor tall fx)) (entity-ref b #:on-ground? #f))
                       bad
                       (cons (list vy fx (entity-ref b #:y)) bad)))))))
   '(swept discrete)))

(test-group "ground detection counts a slope"
  (define one (list->tilemap '((0 0 0) (0 3 0)) slopes: '((3 0 16))))
  ;; foot at x 24: the floor is 32 - 8 = 24; both lower corners over empty cells
  (test "a foot on the line is on the ground" #t
        (entity-ref (detect-on-solid (make-scene tilemap: one) (sl-body 16 8 16 16 0) 16) #:on-ground? #f))
  (test "a foot 1 px above it is not" #f
        (entity-ref (detect-on-solid (make-scene tilemap: one) (sl-body 16 7 16 16 0) 16) #:on-ground? #f))
  (test "slope-surface: the line's y at x" '(24 32 16 #f) 
        (list (slope-surface one 1 1 24) (slope-surface one 1 1 16) (slope-surface one 1 1 32)
              (slope-surface one 0 1 24))))

(test-group "standing still on a slope: no sliding"
  ;; foot (50, 62): the floor of tile (3, 3) at x 50 is 64 - 2
  (test "ten frames at rest mid-slope stay put" '((42 46 #t))
        (let ((fs (sl-walk engine-pipeline sl-hill45 (sl-body 42 46 16 16 0) 0 10)))
          (list (list-ref fs 9)))))

(test-group "rising through a slope from below, jumping off one"
  (test "a jump from a slope leaves it (9 px up the first frame)" '(50 29)
        (let* ((e (sl-body 50 38 16 16 0 #:ay -10 #:on-ground? #t))
               (s (engine-pipeline (make-scene tilemap: sl-hill45 entities: (list e)) 16))
               (b (car (scene-entities s))))
          (list (entity-ref b #:x) (entity-ref b #:y)))))

;; The fast path (engine-pipeline) and the readable steps (contract-pipeline)
;; agree on slope maps: physics/tests/pipeline-test.scm draws slopes into
;; its random scenes too; here, walks.
(test-group "engine-pipeline equals contract-pipeline on slopes"
  (for-each
   (lambda (tm name)
     (test (sprintf "~a: walks both ways, every frame the same" name) #t
           (let loop ((vxs '(1 2 3 5 -1 -2 -3 -5)))
             (or (null? vxs)
                 (let ((e (sl-body (if (> (car vxs) 0) 0 180) 48 12 16 (car vxs))))
                   (and (equal? (sl-walk engine-pipeline tm e (car vxs) 60)
                                (sl-walk contract-pipeline tm e (car vxs) 60))
                        (loop (cdr vxs))))))))
   (list sl-hill45 sl-hill22) '("45 degrees" "22.5 degrees")))

;; A ramp under a low flat ceiling: a 45 degree floor (tile 3, 0 -> 16,
;; column 3, row 3) rising under solid cells whose bottom is at y 32 from
;; column 3 on. A 24 px tall walker is lifted by the floor until its top
;; would pass into the ceiling, at foot x 56 (head 32, foot 56); a lift
;; that would take it there does not happen: the frame's x motion is
;; undone, as a wall would stop it. So each walk ends at its last step
;; where the body fits, 20 + vx * floor((36 - w/2) / vx), and no frame
;; has the box in the ceiling or the foot off the floor.
(include-relative "../../tests/walk-support.scm")
(define sl-low-ceiling
  (list->tilemap '((1 1 1 1 1 1 1) (0 0 0 1 1 1 1) (0 0 0 0 0 0 0) (0 0 0 3 1 1 1) (1 1 1 1 1 1 1))
                 slopes: '((3 0 16))))

(test-group "a ramp under a low ceiling: the walker stops where it no longer fits"
  (for-each
   (lambda (mode)
     (for-each
      (lambda (pipeline name)
        (for-each
         (lambda (w)
           (let ((speeds (guaranteed-speeds w 24)))
             (test (sprintf "~a px wide (~a, ~a): ends at its last step that fits, never in the ceiling"
                            w name mode)
                   (walks-wanted speeds 20 (- 56 (/ w 2)))
                   (walks-got speeds
                              (lambda (vx) (sl-walk pipeline sl-low-ceiling (sl-body 20 40 w 24 vx) vx 60 mode))
                              (lambda (f) (let ((x (car f)) (y (cadr f)))
                                            (and (>= y (if (> (+ x w) 48) 32 16))
                                                 (= (+ y 24) (sl-floor sl-low-ceiling (+ x (/ w 2)) 2)))))))))
         '(4 8 16)))
      (list engine-pipeline contract-pipeline) '("engine" "readable steps")))
   '(swept discrete)))

;; The platformer demo's hill (demo/levels/platformer.tmx, slopes.tsx: two
;; tiles by properties, one by its collision polygon, flipped for the way
;; down), walked over as the demo's player walks (2 px/frame).
(test-group "the platformer demo's hill"
  (let ((tm (load-tilemap "../demo/levels/platformer.tmx")))
    (test "up 45 degrees, a flat top, down a 22.5 degree pair (flipped tiles)"
          '((0 . 16) #f #f (16 . 8) (8 . 0))
          (map (lambda (c) (tilemap-slope tm c 12)) '(48 49 50 51 52)))
    (test "a walk over it: every frame the foot on the floor, on the ground" '(0 0)
          (let loop ((fs (sl-walk engine-pipeline tm (sl-body 736 192 16 16 2) 2 60)) (off 0) (air 0))
            (if (null? fs)
                (list off air)
                (let ((f (car fs)))
                  (loop (cdr fs)
                        (if (= (+ (cadr f) 16) (sl-floor tm (+ (car f) 8) 11)) off (+ off 1))
                        (if (caddr f) air (+ air 1)))))))))

;; Contacts near a slope (docs/physics.org, "Slopes"): a body's sides are
;; the box the tile passes test, so the flat tile at the top of a slope is
;; no wall to a body half way up it; a wall as tall as the body still is.
(test-group "contacts beside a slope"
  (define (right-tiles rows)
    (let* ((tm (list->tilemap rows slopes: '((2 0 16))))
           (body (sl-body 32 8 16 16 0 #:contacts? #t))  ; foot x 40: the floor 8 px up, y + h = 24
           (scene (make-scene tilemap: tm entities: (list body))))
      (entity-touch-tiles (detect-contacts scene body 16) 'right)))
  (test "on the slope, beside the flat tile it leads to: no wall on the right" '()
        (right-tiles '((0 0 0 0) (0 0 2 1) (1 1 1 1))))
  (test "a wall two tiles tall there: a wall on the right" '(solid)
        (right-tiles '((0 0 0 1) (0 0 2 1) (1 1 1 1)))))
