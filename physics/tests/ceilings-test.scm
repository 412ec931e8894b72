;;; Ceiling slopes (docs/physics.org, "Ceiling slopes"): a tile solid
;;; above a straight line stops a rising body's head on the line from any
;;; speed, lets a body rising along it slide where it climbs, stops a
;;; body walking into it where its head meets the line (never pushing it
;;; into the floor), and is reported as a ceiling contact. Exact integers
;;; and rationals, both collision modes, the engine's fast path and the
;;; readable steps alike.

(import scheme (chicken base) (chicken format) (downstroke test) (downstroke entity) (downstroke scene)
        (downstroke tilemap) (downstroke physics) (downstroke pipeline))

(scene-checks #f)

;; 16 px tiles, the floor in row 4 (y 64), a solid ceiling in row 0.
;; 45 degrees: in row 1, tile 5 (depth 0 -> 16, lowering to the right) in
;; column 3, solid columns 4 and 5, tile 6 (16 -> 0) in column 6.
(define cs-45
  (list->tilemap '((1 1 1 1 1 1 1 1 1 1)
                   (0 0 0 5 1 1 6 0 0 0)
                   (0 0 0 0 0 0 0 0 0 0)
                   (0 0 0 0 0 0 0 0 0 0)
                   (1 1 1 1 1 1 1 1 1 1))
                 ceiling-slopes: '((5 0 16) (6 16 0))))

;; 22.5 degree pairs: tiles 7 (0 -> 8) and 8 (8 -> 16) in columns 3 and 4,
;; solid 5 and 6, tiles 9 (16 -> 8) and 10 (8 -> 0) in columns 7 and 8.
(define cs-22
  (list->tilemap '((1 1 1 1 1 1 1 1 1 1 1 1)
                   (0 0 0 7 8 1 1 9 10 0 0 0)
                   (0 0 0 0 0 0 0 0 0 0 0 0)
                   (0 0 0 0 0 0 0 0 0 0 0 0)
                   (1 1 1 1 1 1 1 1 1 1 1 1))
                 ceiling-slopes: '((7 0 8) (8 8 16) (9 16 8) (10 8 0))))

(define (cs-body x y w h . more)
  (plist->entity (append (list #:type 'body #:x x #:y y #:width w #:height h) more)))

;; n frames; after each the game sets the keys of `keep` (a plist) again,
;; as an update: hook does from input. The list of (x y on-ground?).
(define (cs-run pipeline mode tm e n . keep)
  (let loop ((s (make-scene tilemap: tm collision-mode: mode entities: (list e))) (k 0) (out '()))
    (if (= k n)
        (reverse out)
        (let* ((s (pipeline s 16)) (e (car (scene-entities s))))
          (loop (scene-map-entities s (lambda (s e) (let set ((e e) (ks keep))
                                                      (if (null? ks) e (set (entity-set e (car ks) (cadr ks)) (cddr ks))))))
                (+ k 1)
                (cons (list (entity-ref e #:x) (entity-ref e #:y) (entity-ref e #:on-ground? #f)) out))))))

(define (cs-last ls) (car (reverse ls)))

(define (cs-all? ok? ls) (or (null? ls) (and (ok? (car ls)) (cs-all? ok? (cdr ls)))))

;; Every (mode, pipeline) pair.
(define (cs-each proc)
  (for-each (lambda (mode)
              (for-each (lambda (pipeline name) (proc mode pipeline name))
                        (list engine-pipeline contract-pipeline) '("engine" "readable steps")))
            '(swept discrete)))

(test-group "ceiling slope cells"
  (test "tilemap-ceiling-slope: (left . right) depths; tilemap-slope #f; not solid; one-way (its top edge)"
        '((0 . 16) (16 . 0) #f #f #t)
        (list (tilemap-ceiling-slope cs-45 3 1) (tilemap-ceiling-slope cs-45 6 1)
              (tilemap-slope cs-45 3 1) (tilemap-solid? cs-45 3 1) (tilemap-one-way? cs-45 3 1)))
  (test "no ceiling slope on other cells or on maps without" '(#f #f #f)
        (list (tilemap-ceiling-slope cs-45 4 1) (tilemap-ceiling-slope cs-45 3 5)
              (tilemap-ceiling-slope (list->tilemap '((1))) 0 0)))
  (test "ceiling-surface: the line's y at x (row*16 + depth)" '(16 24 32 35/2 #f)
        (list (ceiling-surface cs-45 3 1 48) (ceiling-surface cs-45 3 1 56) (ceiling-surface cs-45 3 1 64)
              (ceiling-surface cs-22 3 1 51) (ceiling-surface cs-45 4 1 70)))
  (test-error "ceiling-slopes: with a depth beyond the tile" (list->tilemap '((5)) ceiling-slopes: '((5 0 17)))))

;; A body on the floor walking into a lowering ceiling stops where its
;; head (x + w/2, y) meets the line: a head at depth e below row 1's top
;; (y = 16 + e) meets tile 5's line at x 48 + e, tile 6's at 112 - e; on
;; the 22.5 degree pairs at 48 + 2e (e <= 8) or 64 + 2(e - 8), and at
;; 144 - 2e or 128 - 2(e - 8). Its y never changes: nothing pushes it
;; down into the floor.
(test-group "walking into a lowering ceiling: stopped where the head meets the line"
  (cs-each
   (lambda (mode pipeline name)
     (for-each
      (lambda (tm label stops)
        (for-each
         (lambda (h stop)
           (for-each
            (lambda (vx)
              (let* ((x0 (if (> vx 0) 20 (- (* 16 (tilemap-width tm)) 36)))
                     (fs (cs-run pipeline mode tm (cs-body x0 (- 64 h) 16 h #:vx vx #:gravity? #t) 60 #:vx vx)))
                (test (sprintf "~a, ~a px tall, ~a px/frame (~a, ~a): stops at x ~a, on the ground at y ~a all the way"
                               label h vx name mode (if (> vx 0) (car stop) (cdr stop)) (- 64 h))
                      (list (if (> vx 0) (car stop) (cdr stop)) (- 64 h) #t #t)
                      (let ((end (cs-last fs)))
                        (list (car end) (cadr end) (caddr end)
                              (cs-all? (lambda (f) (and (= (cadr f) (- 64 h)) (caddr f))) fs))))))
            '(1 3 6 -1 -3 -6)))
         '(36 40 44 47)
         stops))
      (list cs-45 cs-22) '("45 degrees" "22.5 degrees")
      ;; (x stop walking right . x stop walking left), x = head - 8
      '(((52 . 92) (48 . 96) (44 . 100) (41 . 103))
        ((64 . 112) (56 . 120) (48 . 128) (42 . 134))))))
  (test "a body whose head is below the lowest line walks under it all" '(124 32)
        (let ((end (cs-last (cs-run engine-pipeline 'swept cs-45 (cs-body 0 32 16 32 #:vx 4 #:gravity? #t) 31 #:vx 4))))
          (list (car end) (cadr end)))))

;; A rising head stops on the line from any speed, in both modes: a head
;; at x 53 meets tile 5's line at y 16 + 5 = 21; on the 22.5 degree tile
;; 7, a head at x 51 meets it at 16 + 3/2 = 35/2, an exact rational.
(test-group "rising into a ceiling slope: the head stops on the line at any speed"
  (cs-each
   (lambda (mode pipeline name)
     (for-each
      (lambda (tm label x line)
        (test (sprintf "~a (~a, ~a): rising 1 to 120 px/frame from y 48 ends at max(48 - v, ~a)" label name mode line)
              #t
              (let loop ((v 1))
                (or (> v 120)
                    (let ((f (car (cs-run pipeline mode tm (cs-body x 48 16 16 #:vy (- v)) 1))))
                      (and (= (cadr f) (max (- 48 v) line)) (= (car f) x) (loop (+ v 1))))))))
      (list cs-45 cs-22) '("45 degrees" "22.5 degrees") '(45 43) '(21 35/2))))
  (test "the stop ends the rise: #:vy 0, then gravity" '((45 21 0) (45 22 1))
        (let loop ((s (make-scene tilemap: cs-45 entities: (list (cs-body 45 30 16 16 #:vy -12 #:gravity? #t))))
                   (k 0) (out '()))
          (if (= k 2)
              (reverse out)
              (let* ((s (engine-pipeline s 16)) (e (car (scene-entities s))))
                (loop s (+ k 1) (cons (list (entity-ref e #:x) (entity-ref e #:y) (entity-ref e #:vy)) out)))))))

;; A ceiling slope's top edge is solid (its solid part lies above the
;; line): a body falling onto it from above lands there, as on a one-way
;; platform, at y = 64 - h, from any fall speed, and stands. Row 4 of
;; cs-float holds tile 5 (0 -> 16) and tile 6 (16 -> 0) with nothing above.
(define cs-float
  (list->tilemap '((0 0 0 0 0 0 0 0)
                   (0 0 0 0 0 0 0 0)
                   (0 0 0 0 0 0 0 0)
                   (0 0 0 0 0 0 0 0)
                   (0 0 0 5 6 0 0 0)
                   (0 0 0 0 0 0 0 0)
                   (1 1 1 1 1 1 1 1))
                 ceiling-slopes: '((5 0 16) (6 16 0))))

(test-group "landing on a ceiling slope's top: its top edge holds a body as a one-way platform does"
  (cs-each
   (lambda (mode pipeline name)
     ;; swept mode from any speed; discrete mode tests where the box ends,
     ;; so (as on any tile) only up to a tile a frame
     (test (sprintf "~a, ~a: falling 1 to ~a px/frame from y 40 onto x 52 ends at y 48" name mode
                    (if (eq? mode 'swept) 60 16))
           #t
           (let loop ((v 1))
             (or (> v (if (eq? mode 'swept) 60 16))
                 (let ((f (car (cs-run pipeline mode cs-float (cs-body 52 40 16 16 #:vy v) 1))))
                   (and (equal? (list (car f) (cadr f)) (list 52 (min 48 (+ 40 v)))) (loop (+ v 1)))))))
     (test (sprintf "~a, ~a: a body standing there with gravity stays 30 frames" name mode)
           '(52 48 #t)
           (cs-last (cs-run pipeline mode cs-float (cs-body 52 48 16 16 #:gravity? #t #:vy 0) 30)))
     (test (sprintf "~a, ~a: a body rising into the cell from below stops its head on the line" name mode)
           '(52 76 #f)
           (car (cs-run pipeline mode cs-float (cs-body 52 80 16 16 #:vy -20) 1))))))

;; Under tile 6 (the ceiling rising to the right) a body rising to the
;; right slides up along it: the game sets #:vx 2 #:vy -3 each frame, and
;; each frame the head ends on the line, y = 16 + 16 - (x + 8 - 96), up
;; to the solid row's bottom (y 16). Going left under it from x 106 (head
;; 114, y 18), it rises to that row in the first frame (head 112, y 16);
;; then the line comes down in front of its head: it is stopped on x
;; there, in every frame.
(test-group "rising along a ceiling slope: sliding"
  (cs-each
   (lambda (mode pipeline name)
     (test (sprintf "up and right under the rising ceiling (~a, ~a)" name mode)
           '((90 30) (92 28) (94 26) (96 24) (98 22) (100 20) (102 18) (104 16) (106 16) (108 16))
           (map (lambda (f) (list (car f) (cadr f)))
                (cs-run pipeline mode cs-45 (cs-body 88 33 16 16 #:vx 2 #:vy -3) 10 #:vx 2 #:vy -3)))
     (test (sprintf "up and left under it: the line lowers to the head, the body stops on x (~a, ~a)" name mode)
           '((104 16) (104 16) (104 16))
           (map (lambda (f) (list (car f) (cadr f)))
                (list-tail (cs-run pipeline mode cs-45 (cs-body 106 18 16 16 #:vx -2 #:vy -3) 5 #:vx -2 #:vy -3) 2))))))

;; A tunnel that narrows from both sides: a 45 degree floor (tile 3, 0 ->
;; 16, row 3, column 3) rises under a 45 degree ceiling (tile 5, 0 -> 16,
;; row 1, column 3). A 24 px tall body walking right is lifted by the
;; floor; where a frame's lift would take its head above the ceiling it
;; does not fit, and the frame's x motion is undone: its head never goes
;; into the ceiling and its foot stays on the floor. It fits up to head
;; x 60 (foot on 64 - 12, head on 16 + 12), so it stops at x 52 when its
;; steps land there (1 and 2 px/frame from x 20) and at x 50 at 3 px/frame.
(define cs-tunnel
  (list->tilemap '((1 1 1 1 1 1 1) (0 0 0 5 1 1 1) (0 0 0 0 0 0 0) (0 0 0 3 1 1 1) (1 1 1 1 1 1 1))
                 ceiling-slopes: '((5 0 16)) slopes: '((3 0 16))))

(test-group "a tunnel narrowing from both sides: stopped where the body no longer fits"
  (define (ceiling-at hx) (cond ((< hx 48) 16) ((< hx 64) (+ 16 (- hx 48))) (else 32)))
  (define (floor-at fx) (cond ((< fx 48) 64) ((< fx 64) (- 64 (- fx 48))) (else 48)))
  (cs-each
   (lambda (mode pipeline name)
     (for-each
      (lambda (vx stop)
        (let ((fs (cs-run pipeline mode cs-tunnel (cs-body 20 40 16 24 #:vx vx #:gravity? #t) 40 #:vx vx)))
          (test (sprintf "~a px/frame (~a, ~a): stops at x ~a, head under the ceiling and foot on the floor every frame"
                         vx name mode stop)
                (list stop #t)
                (list (car (cs-last fs))
                      (cs-all? (lambda (f) (let ((hx (+ (car f) 8)))
                                             (and (>= (cadr f) (ceiling-at hx))
                                                  (= (+ (cadr f) 24) (floor-at hx)))))
                               fs)))))
      '(1 2 3) '(52 52 50)))))

;; The same tunnel at every walking speed the slope rules guarantee (w/2
;; + |vx| + 1 <= h - 1), for bodies 4 to 16 px wide: it fits while its
;; head is at most at x 60, and each walk stops at the last of its steps
;; there, 20 + vx * floor((40 - w/2) / vx). On the way the x pass may stop
;; the head at the ceiling's line; the foot is still raised by how far the
;; body moved on x, so it is never left in the floor.
(include-relative "../../tests/walk-support.scm")
(test-group "a tunnel narrowing from both sides, at every guaranteed walking speed"
  (define (ceiling-at hx) (cond ((< hx 48) 16) ((< hx 64) (+ 16 (- hx 48))) (else 32)))
  (define (floor-at fx) (cond ((< fx 48) 64) ((< fx 64) (- 64 (- fx 48))) (else 48)))
  (cs-each
   (lambda (mode pipeline name)
     (for-each
      (lambda (w)
        (let ((speeds (guaranteed-speeds w 24)))
          (test (sprintf "~a px wide (~a, ~a): ends at its last step that fits, head and foot right every frame"
                         w name mode)
                (walks-wanted speeds 20 (- 60 (/ w 2)))
                (walks-got speeds
                           (lambda (vx) (cs-run pipeline mode cs-tunnel (cs-body 20 40 w 24 #:vx vx #:gravity? #t) 50 #:vx vx))
                           (lambda (f) (let ((hx (+ (car f) (/ w 2))))
                                         (and (>= (cadr f) (ceiling-at hx)) (= (+ (cadr f) 24) (floor-at hx)))))))))
      '(4 8 12 16)))))

;; The tunnel with a wall (column 4, row 2) where it gets too low: a body
;; 4 px wide at 4 px/frame from x 21 reaches x 61 in the frame the wall
;; stops it at 60, and there the floor would lift its head into the
;; ceiling: it goes back to where the frame's motion started, x 57, and
;; keeps the #:vx the wall gave it (its #:bounce once, not twice).
(define cs-tunnel-wall
  (list->tilemap '((1 1 1 1 1 1 1) (0 0 0 5 1 1 1) (0 0 0 0 1 1 1) (0 0 0 3 1 1 1) (1 1 1 1 1 1 1))
                 ceiling-slopes: '((5 0 16)) slopes: '((3 0 16))))

(test-group "a wall where the tunnel gets too low"
  (cs-each
   (lambda (mode pipeline name)
     (for-each
      (lambda (bounce vx-after)
        (let* ((more (if bounce (list #:bounce bounce) '()))
               (s (let loop ((s (make-scene tilemap: cs-tunnel-wall collision-mode: mode
                                            entities: (list (apply cs-body 21 40 4 24 #:vx 4 #:gravity? #t more))))
                             (k 0))
                    (if (= k 9) s
                        (loop (scene-map-entities (pipeline s 16) (lambda (s e) (entity-set e #:vx 4))) (+ k 1)))))
               (e (car (scene-entities (pipeline s 16)))))
          (test (sprintf "#:bounce ~a (~a, ~a): back at x 57, on the floor, #:vx ~a, nothing else left on it"
                         bounce name mode vx-after)
                (list 57 29 vx-after #f)
                (list (entity-ref e #:x) (entity-ref e #:y) (entity-ref e #:vx)
                      (and (assq #:x-pass-start e) #t)))))
      '(#f 1/2) '(0 -2)))))

(test-group "contacts: a head on a ceiling slope's line touches it"
  (define (contacts tm e n . keep)
    (let loop ((s (make-scene tilemap: tm entities: (list e))) (k 0))
      (if (= k n)
          (entity-ref (car (scene-entities s)) #:contacts)
          (loop (scene-map-entities (engine-pipeline s 16)
                                    (lambda (s e) (let set ((e e) (ks keep))
                                                    (if (null? ks) e (set (entity-set e (car ks) (cadr ks)) (cddr ks))))))
                (+ k 1)))))
  (test "walked into it: the floor and the ceiling, the tile named slope" '((floor 10 (solid) ()) (ceiling 3 (slope) ()))
        (contacts cs-45 (cs-body 20 28 16 36 #:vx 4 #:gravity? #t #:contacts? #t) 10 #:vx 4))
  (test "jumped into it: the ceiling, by the tile's kind" '((ceiling 1 (roof) ()))
        (contacts (list->tilemap '((1 1 1) (0 5 0) (0 0 0) (1 1 1)) ceiling-slopes: '((5 0 16)) kinds: '((5 . roof)))
                  (cs-body 13 30 16 16 #:vy -12 #:contacts? #t) 1))
  (test "1 px below the line: no contact" '()
        (contacts cs-45 (cs-body 45 22 16 16 #:contacts? #t) 1)))

(test-group "engine-pipeline equals contract-pipeline near ceiling slopes"
  (for-each
   (lambda (tm label)
     (test (sprintf "~a: walks and jumps both ways, every frame the same" label) #t
           (let loop ((cases '((1 0) (3 0) (6 0) (-2 0) (-5 0) (2 -9) (4 -12) (-3 -10) (-1 -14))))
             (or (null? cases)
                 (let* ((vx (caar cases)) (vy (cadar cases))
                        (e (cs-body (if (> vx 0) 10 150) (if (= vy 0) 24 40) 12 (if (= vy 0) 40 24)
                                    #:vx vx #:vy vy #:gravity? #t)))
                   (and (equal? (cs-run engine-pipeline 'swept tm e 50 #:vx vx)
                                (cs-run contract-pipeline 'swept tm e 50 #:vx vx))
                        (equal? (cs-run engine-pipeline 'discrete tm e 50 #:vx vx)
                                (cs-run contract-pipeline 'discrete tm e 50 #:vx vx))
                        (loop (cdr cases))))))))
   (list cs-45 cs-22) '("45 degrees" "22.5 degrees")))

(test-exit)
