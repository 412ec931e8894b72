;;; The fast paths of the default pipeline give exactly what the steps of
;;; docs/physics.org ("The pipeline") give when run one by one:
;;;   - step-motion (one walk, one copy) against acceleration, gravity,
;;;     velocity x, tile x, velocity y, tile y in turn;
;;;   - engine-pipeline, the fast path, which skips the steps no entity
;;;     needs, against the library's contract-pipeline, and that against
;;;     every step run over every entity as written here;
;;;   - entity-set* against repeated entity-set.
;;; Compared with equal? (same keys, same order, same values) on random
;;; entities: keys present or not, fixnums, exact rationals and flonums,
;;; skip lists, per-entity collision modes, solids, groups, tweens,
;;; animations, and climbers on maps with ladders.

(import scheme (chicken base) (chicken condition) (chicken format) srfi-4 (downstroke test)
        (downstroke entity) (downstroke tilemap) (downstroke scene) (downstroke physics)
        (downstroke tween) (downstroke animation) (downstroke pipeline) (downstroke particles)
        (only (downstroke motion) motion-kernel-declines))

;; Random bodies often lack a size on purpose: the checks would say so.
(scene-checks #f)

(define pl-seed 4242)
(define (pl-rand n)
  (set! pl-seed (modulo (+ (* 1103515245 pl-seed) 12345) 2147483648))
  (modulo (quotient pl-seed 7) n))
(define (pl-chance percent) (< (pl-rand 100) percent))
(define (pl-pick . xs) (list-ref xs (pl-rand (length xs))))

(define (pl-number range)
  (let ((n (- (pl-rand (* 2 range)) range)))
    (case (pl-rand 4)
      ((0 1) n)
      ((2) (/ n (pl-pick 2 3 4 10)))
      (else (+ n (/ (pl-rand 1000) 1000.0))))))

;; Half the maps have slope tiles (3 to 6: 45 and 22.5 degrees, both
;; ways; docs/physics.org, "Slopes") and ceiling slopes (8 to 11, and
;; floor slopes flipped vertically; "Ceiling slopes"), which the fast
;; path hands to the readable steps.
(define (pl-map)
  (let ((slopes? (pl-chance 50)))
    (list->tilemap
     (let rows ((j 0))
       (if (= j 12)
           '()
           (cons (let cols ((i 0))
                   (if (= i 12)
                       '()
                       (cons (cond ((or (= j 11) (pl-chance 15)) 1) ((pl-chance 10) 2) ((pl-chance 12) 7)
                                   ((and slopes? (pl-chance 12))
                                    (pl-pick 3 4 5 6 8 9 10 11 (+ 3 #x40000000) (+ 6 #x40000000)))
                                   (else 0))
                             (cols (+ i 1)))))
                 (rows (+ j 1)))))
     one-way: '(2) ladders: '(7) slopes: '((3 0 16) (4 16 0) (5 0 8) (6 8 16))
     ceiling-slopes: '((8 0 16) (9 16 0) (10 0 8) (11 8 16)))))

;; A random entity: every key appears only sometimes, in a random order.
(define (pl-entity k)
  (let* ((pairs
          (list (and (pl-chance 95) (cons #:x (+ 40 (pl-number 60))))
                (and (pl-chance 95) (cons #:y (+ 40 (pl-number 60))))
                (and (pl-chance 90) (cons #:width (pl-pick 0 1 8 12 16 20 15/2 10.5)))
                (and (pl-chance 90) (cons #:height (pl-pick 0 1 8 12 16 20 15/2 10.5)))
                (and (pl-chance 85) (cons #:vx (pl-number 30)))
                (and (pl-chance 85) (cons #:vy (pl-number 30)))
                (and (pl-chance 50) (cons #:ay (pl-pick 0 0 -10 0.0 5/2)))
                (and (pl-chance 60) (cons #:gravity? (pl-pick #t #f)))
                (and (pl-chance 40) (cons #:on-ground? (pl-pick #t #f)))
                (and (pl-chance 10) (cons #:skip-pipelines
                                          (pl-pick '() '(gravity) '(velocity-x tile-collisions-y)
                                                   '(acceleration on-solid) '(tile-collisions-x))))
                (and (pl-chance 15) (cons #:collision-mode (pl-pick 'swept 'discrete)))
                (and (pl-chance 25) (cons #:solid? (pl-pick #t #f)))
                (and (pl-chance 8) (cons #:immovable? #t))
                (and (pl-chance 8) (cons #:one-way? #t))
                (and (pl-chance 10) (cons #:drop-through? (pl-pick #t #f)))
                (and (pl-chance 10) (cons #:group-id (pl-pick 'a 'b)))
                (and (pl-chance 5) (cons #:group-origin? #t))
                (and (pl-chance 10) (cons #:group-local-x (pl-rand 20)))
                (and (pl-chance 10)
                     (cons #:animations
                           (list (list (cons #:name 'walk) (cons #:frames '(1 2 3)) (cons #:duration 2)))))
                (and (pl-chance 10) (cons #:contacts? #t))
                (and (pl-chance 5) (cons #:drag (pl-pick 1 1/2 0.25)))
                (and (pl-chance 5) (cons #:air-drag (pl-pick 1 1/4)))
                (and (pl-chance 5) (cons #:max-vx (pl-pick 3 5/2 4.0)))
                (and (pl-chance 5) (cons #:max-vy (pl-pick 6 12)))
                (and (pl-chance 8) (cons #:bounce (pl-pick 1/2 1 0.75 0)))
                (and (pl-chance 35) (cons #:climber? (pl-pick #t #t #f)))
                (and (pl-chance 50) (cons #:climb (pl-pick -1 0 1 1/2 -1.0)))
                (and (pl-chance 10) (cons #:climbing? (pl-pick #t #f)))
                (and (pl-chance 5) (cons #:climb-speed (pl-pick 1 3 5/2 16)))
                (cons #:id k)))
         (present (let loop ((ps pairs) (out '()))
                    (cond ((null? ps) out)
                          ((car ps) (loop (cdr ps) (cons (car ps) out)))
                          (else (loop (cdr ps) out))))))
    ;; shuffle by repeatedly taking a random element
    (let shuffle ((ps present) (out '()))
      (if (null? ps)
          out
          (let ((p (list-ref ps (pl-rand (length ps)))))
            (shuffle (let drop ((ps ps)) (if (eq? (car ps) p) (cdr ps) (cons (car ps) (drop (cdr ps)))))
                     (cons p out)))))))

(define (pl-with-tween e)
  (if (and (pl-chance 10) (entity-ref e #:x #f))
      (entity-set e #:tween (make-tween e props: (list (cons #:x (+ 10 (entity-ref e #:x 0))))
                                        duration: (pl-pick 16 48) ease: 'quad-in))
      e))

;; The result of (thunk), or the message of the error it raises.
(define (pl-outcome thunk)
  (handle-exceptions exn (list 'error ((condition-property-accessor 'exn 'message) exn))
    (thunk)))

(define (pl-six-steps scene e)
  (let* ((e (apply-acceleration scene e 16))
         (e (apply-gravity scene e 16))
         (e (apply-body-controls scene e 16))
         (e (apply-velocity-x scene e 16))
         (e (resolve-tile-collisions-x scene e 16))
         (e (apply-velocity-y scene e 16)))
    (resolve-tile-collisions-y scene e 16)))

(test-group "step-motion is the six motion steps in one pass"
  (let loop ((k 0) (same 0) (different 0) (changed 0) (first-difference #f))
    (if (= k 6000)
        (begin
          (test "6000 random entities: identical results" 0 different)
          (when first-difference (print "pipeline: first difference " first-difference))
          (test-assert "most of them moved" (> changed 4000)))
        (let* ((scene (make-scene tilemap: (if (pl-chance 85) (pl-map) #f)
                                  collision-mode: (pl-pick 'swept 'discrete)))
               (e (pl-entity k))
               (fast (pl-outcome (lambda () (step-motion scene e 16))))
               (slow (pl-outcome (lambda () (pl-six-steps scene e)))))
          (if (equal? fast slow)
              (loop (+ k 1) (+ same 1) different (if (equal? fast e) changed (+ changed 1)) first-difference)
              (loop (+ k 1) same (+ different 1) changed
                    (or first-difference (list e fast slow))))))))

(test-group "step-motion checks numbers like the steps do"
  (let ((scene (make-scene tilemap: (list->tilemap '((0 0) (1 1))))))
    (test-error "a NaN x" (step-motion scene (plist->entity (list #:x +nan.0 #:y 0 #:vx 1)) 16))
    (test "the error names the entity and the key"
          "entity box: #:vy is +inf.0, not a finite real number"
          (cadr (pl-outcome (lambda () (step-motion scene (plist->entity (list #:type 'box #:x 0 #:y 0 #:vy +inf.0)) 16)))))
    ;; Without a map the motion pass takes its own path for such numbers
    ;; (free-motion); it must refuse the same value with the same words.
    (for-each
     (lambda (grav)
       (for-each
        (lambda (key)
          (let* ((e (entity-set (plist->entity (list #:type 'box #:x 1/2 #:y 3 #:vx 1 #:vy 2.5 #:ay -10
                                                     #:gravity? grav))
                                key +nan.0))
                 (fast (pl-outcome (lambda () (step-motion (make-scene) e 16))))
                 (slow (pl-outcome (lambda () (pl-six-steps (make-scene) e)))))
            (test (sprintf "no map, gravity ~a, NaN ~s: the steps' error" grav key) slow fast)
            (test-assert "... which is an error" (eq? 'error (car fast)))))
        (if grav '(#:x #:y #:vx #:vy #:ay) '(#:x #:y #:vx #:vy))))
     '(#t #f))
    ;; Without a map, bodies at flonum positions: ten frames of each, as
    ;; the six steps make them.
    (for-each
     (lambda (plist)
       (let loop ((k 0) (e (plist->entity plist)))
         (when (< k 10)
           (let ((fast (step-motion (make-scene) e 16))
                 (slow (pl-six-steps (make-scene) e)))
             (if (or (= k 9) (not (equal? fast slow)))
                 (test (sprintf "no map, flonum position ~s, frame ~a: the steps' result" plist k) slow fast))
             (loop (+ k 1) slow)))))
     (list (list #:x 0.1 #:y 3 #:vx 3 #:vy -2)
           (list #:x -0.0 #:y -0.0 #:vx 0 #:vy 0)
           (list #:x 5 #:y 2.75 #:vx -1 #:vy 1 #:gravity? #t #:ay -10 #:on-ground? #t)
           (list #:y 1e300 #:vx 2 #:gravity? #t)
           (list #:x 1.5 #:y 0.5 #:vx 1 #:vy 0 #:gravity? #t #:ay 0)))
    (test "an entity that does not move comes back itself" #t
          (let ((e (plist->entity (list #:x 0 #:y 0 #:vx 0 #:vy 0))))
            (eq? e (step-motion scene e 16))))))

;; Without a map, a body at flonum positions takes the flonum kernel
;; (physics/motion.c), which writes only what changes: a body at rest is
;; not copied, as a fixnum one is not.
(test-group "the flonum kernel: scenes without a map"
  (let ((e (plist->entity (list #:x 1.5 #:y -0.25 #:vx 0 #:vy 0 #:width 8 #:height 8))))
    (test-assert "a body at rest at flonum positions comes back itself"
                 (eq? e (step-motion (make-scene) e 16))))
  (let ((e (plist->entity (list #:x 1.5 #:y 3 #:vx 2 #:vy 0.5 #:gravity? #t #:ay -1))))
    (test "one frame of a falling body, with acceleration consumed"
          (list 3.5 (+ 3 (+ (+ 0.5 -1) *gravity*)) 2 (+ (+ 0.5 -1) *gravity*) 0)
          (let ((moved (step-motion (make-scene) e 16)))
            (map (lambda (k) (entity-ref moved k)) '(#:x #:y #:vx #:vy #:ay)))))
  (let ((e (plist->entity (list #:type 'rock #:x 1.5e308 #:y 0 #:vx 1.5e308))))
    (test "a sum past the largest double is the step's error, with its words"
          (pl-outcome (lambda () (pl-six-steps (make-scene) e)))
          (pl-outcome (lambda () (step-motion (make-scene) e 16)))))
  ;; random bodies of flonums and fixnums (and some rationals and bignums,
  ;; which go to the readable steps), five frames each
  (let loop ((k 0) (different 0) (first-difference #f))
    (if (= k 2000)
        (begin
          (test "2000 random bodies, five frames each: the six steps' results" 0 different)
          (when first-difference (print "pipeline: first difference " first-difference)))
        (let* ((num (lambda (range)
                      (case (pl-rand 9)
                        ((0 1 2) (- (pl-rand (* 2 range)) range))
                        ((3) (/ (- (pl-rand (* 2 range)) range) 4))
                        ((4) (* (- (pl-rand 3) 1) (expt 2 70)))
                        ;; now and then what the steps refuse or overflow on
                        ((5) (if (pl-chance 20)
                                 (pl-pick +nan.0 +inf.0 -inf.0 1.7e308 -1.7e308 1e300 4.9e-324)
                                 (- (/ (pl-rand 100000) 1000.0) (/ range 2.0))))
                        (else (- (/ (pl-rand 100000) 1000.0) (/ range 2.0))))))
               (pairs (list (and (pl-chance 95) (cons #:x (num 100)))
                            (and (pl-chance 95) (cons #:y (num 100)))
                            (and (pl-chance 80) (cons #:width (pl-pick 8 12 0.5)))
                            (and (pl-chance 80) (cons #:height (pl-pick 8 12 0.5)))
                            (and (pl-chance 85) (cons #:vx (num 10)))
                            (and (pl-chance 85) (cons #:vy (num 10)))
                            (and (pl-chance 50) (cons #:ay (pl-pick 0 0 -10 0.0 -0.0 2.5)))
                            (and (pl-chance 60) (cons #:gravity? (pl-pick #t #f)))
                            (and (pl-chance 40) (cons #:on-ground? (pl-pick #t #f)))
                            (and (pl-chance 5) (cons #:skip-pipelines '(gravity)))))
               (e (let keep ((ps pairs))
                    (cond ((null? ps) '())
                          ((car ps) (cons (car ps) (keep (cdr ps))))
                          (else (keep (cdr ps))))))
               (frames (lambda (step)
                         (pl-outcome (lambda ()
                                       (let run ((f 0) (e e))
                                         (if (= f 5) e (run (+ f 1) (step e))))))))
               (fast (frames (lambda (e) (step-motion (make-scene) e 16))))
               (slow (frames (lambda (e) (pl-six-steps (make-scene) e)))))
          (if (equal? fast slow)
              (loop (+ k 1) different first-difference)
              (loop (+ k 1) (+ different 1) (or first-difference (list e fast slow))))))))

;; Fixnum entities take the motion pass's fixnum path: random maps of
;; several tile sizes, with their origin anywhere, and bodies anywhere
;; (far outside the map too, and around the path's +-2^40 limit, where
;; they go back to generic arithmetic).
;; Half of them have slope tiles (3 to 6) and ceiling slopes (8 to 11),
;; which the kernel leaves to the readable steps for a body near one
;; (physics/motion.c, ds_near_slope).
(define (pl-origin-map)
  (let* ((w (+ 1 (pl-rand 14))) (h (+ 1 (pl-rand 14)))
         (density (pl-pick 5 30 60 80))
         (slopes? (pl-chance 50))
         (data (make-u32vector (* w h) 0)))
    (do ((i 0 (+ i 1))) ((= i (* w h)))
      (when (pl-chance density)
        (u32vector-set! data i (if (and slopes? (pl-chance 30)) (pl-pick 3 4 5 6 8 9 10 11) (pl-pick 1 1 1 2 7)))))
    (let ((th (pl-pick 16 8 12 16 1)))
      (make-tilemap w h (pl-pick 16 8 10 16 1) th
                    (list (make-layer "solid" w h data)) one-way: '(2) ladders: '(7)
                    slopes: (list (list 3 0 th) (list 4 th 0) (list 5 0 (quotient th 2))
                                  (list 6 (quotient th 2) th))
                    ceiling-slopes: (list (list 8 0 th) (list 9 th 0) (list 10 0 (quotient th 2))
                                          (list 11 (quotient th 2) th))
                    origin-col: (- (pl-rand 12) 6) origin-row: (- (pl-rand 12) 6)))))

(define (pl-fixnum range)
  (case (pl-rand 24)
    ((0) (pl-pick 1099511627775 -1099511627775 1099511627776 -1099511627776 1099511627700))
    ((1) (* (pl-pick 1 -1) (pl-rand 100000)))
    (else (- (pl-rand (* 2 range)) range))))

;; Around the middle of the map, when there is one.
(define (pl-fixnum-entity k tm)
  (define (around origin size tile)
    (+ (* origin tile) (quotient (* size tile) 2) (pl-fixnum (+ 8 (quotient (* size tile) 2)))))
  (filter-present
   (list (and (pl-chance 97) (cons #:x (if tm
                                           (around (tilemap-origin-col tm) (tilemap-width tm) (tilemap-tile-width tm))
                                           (pl-fixnum 90))))
         (and (pl-chance 97) (cons #:y (if tm
                                           (around (tilemap-origin-row tm) (tilemap-height tm) (tilemap-tile-height tm))
                                           (pl-fixnum 90))))
         (and (pl-chance 95) (cons #:width (pl-pick 0 1 8 12 16 20 33)))
         (and (pl-chance 95) (cons #:height (pl-pick 0 1 8 12 16 20 33)))
         (and (pl-chance 90) (cons #:vx (pl-fixnum 40)))
         (and (pl-chance 90) (cons #:vy (pl-fixnum 40)))
         (and (pl-chance 50) (cons #:ay (pl-pick 0 0 -10 3)))
         (and (pl-chance 70) (cons #:gravity? (pl-pick #t #t #f)))
         (and (pl-chance 50) (cons #:on-ground? (pl-pick #t #f)))
         (and (pl-chance 15) (cons #:collision-mode (pl-pick 'swept 'discrete)))
         (and (pl-chance 15) (cons #:drop-through? (pl-pick #t #f)))
         (and (pl-chance 10) (cons #:climber? #t))
         (and (pl-chance 10) (cons #:climbing? #t))
         (cons #:id k))))

(define (filter-present ps)
  (cond ((null? ps) '())
        ((car ps) (cons (car ps) (filter-present (cdr ps))))
        (else (filter-present (cdr ps)))))

;; A fixnum entity whose position is moved by an exact fraction (as
;; push-apart and quarter-pixel starts leave them): the kernel takes these.
(define (pl-exact-entity k tm)
  (map (lambda (p)
         (if (and (memq (car p) '(#:x #:y)) (pl-chance 80))
             (cons (car p) (+ (cdr p) (/ (+ 1 (pl-rand 15)) (pl-pick 2 3 4 7 16 1024))))
             p))
       (pl-fixnum-entity k tm)))

(test-group "the motion pass's exact path (rational positions) is the six steps and ground detection"
  (let loop ((k 0) (different 0) (rational 0) (first-difference #f))
    (if (= k 8000)
        (begin
          (test "8000 random entities with rational positions: identical results" 0 different)
          (when first-difference (print "pipeline: first difference " first-difference))
          (test-assert "most of them still hold a rational after the frame" (> rational 3000)))
        (let* ((scene (make-scene tilemap: (if (pl-chance 90) (pl-origin-map) #f)
                                  collision-mode: (pl-pick 'swept 'discrete)))
               (e (pl-exact-entity k (scene-tilemap scene)))
               (fast (pl-outcome (lambda () ((motion-pass scene 16 #t) e))))
               (slow (pl-outcome (lambda () (detect-on-solid scene (pl-six-steps scene e) 16)))))
          (loop (+ k 1)
                (if (equal? fast slow) different (+ different 1))
                (if (and (pair? fast) (or (ratnum? (entity-ref fast #:x 0)) (ratnum? (entity-ref fast #:y 0))))
                    (+ rational 1)
                    rational)
                (or first-difference (and (not (equal? fast slow)) (list e fast slow))))))))

;; Positions with long denominators, as a crowd pushed apart by halves
;; for many frames leaves them (2^21 to 2^61, and 3^30), some so long that
;; the kernel's sums would overflow (it must leave those to the readable
;; steps, physics/motion.c's ds_room).
(define (pl-wide-entity k tm)
  (map (lambda (p)
         (if (and (memq (car p) '(#:x #:y)) (pl-chance 85))
             (cons (car p) (+ (cdr p) (/ (+ 1 (* 2 (pl-rand 100000)))
                                         (pl-pick 2097152 1073741824 1099511627776 140737488355328
                                                  205891132094649 36028797018963968 2305843009213693952))))
             p))
       (pl-fixnum-entity k tm)))

;; Rational positions are the kernel's on 64-bit CHICKEN only (31-bit
;; fixnums, as on wasm32, leave them all to the readable steps).
;; Read at run time: the compiler folds what it can see (for wasm32 it is
;; the 64-bit host's csc, whose answer would be #t), and it does not
;; fold through a variable that is assigned.
(define pl-2^40-text "1099511627776")
(set! pl-2^40-text pl-2^40-text)
(define pl-64-bit? (fixnum? (string->number pl-2^40-text)))

;; The random flonum comparisons below, fewer where fixnums are 31 bits
;; wide: make wasm32-check runs this suite under node, many times slower.
(define pl-flo-bodies (if pl-64-bit? 6000 1500))
(define pl-flo-scenes (if pl-64-bit? 150 40))

(test-group "the motion pass's kernel takes positions with long denominators"
  ;; 2^30 and 2^33 in the denominators, a crowd's digits after some
  ;; frames: before, the kernel took denominators below 2^20 only
  (let* ((scene (make-scene tilemap: (list->tilemap '((0 0 0 0) (0 0 0 0) (1 1 1 1)) tile-width: 16 tile-height: 16)
                            collision-mode: 'swept))
         (e (list (cons #:x (+ 20 1/1073741824)) (cons #:y (+ 10 3/8589934592)) (cons #:width 12) (cons #:height 12)
                  (cons #:vx 2) (cons #:vy 1) (cons #:gravity? #t)))
         (before (motion-kernel-declines))
         (fast ((motion-pass scene 16 #t) e)))
    (test (if pl-64-bit? "the kernel took it" "the kernel left it (31-bit fixnums)")
          (if pl-64-bit? before (+ before 1)) (motion-kernel-declines))
    (test "x moved by vx, its denominator kept" (+ 22 1/1073741824) (entity-ref fast #:x))
    (test "y moved by vy + gravity" (+ 12 3/8589934592) (entity-ref fast #:y))
    (test "the readable steps say the same" fast
          (detect-on-solid scene (pl-six-steps scene e) 16)))
  (let loop ((k 0) (different 0) (taken 0) (first-difference #f))
    (if (= k 8000)
        (begin
          (test "8000 random entities with long denominators: identical results" 0 different)
          (when first-difference (print "pipeline: first difference " first-difference))
          (if pl-64-bit?
              (test-assert "the kernel took many of them, and left many" (< 2000 taken 6000))
              (test-assert "the kernel took only those at integer positions" (< taken 2000))))
        (let* ((scene (make-scene tilemap: (if (pl-chance 90) (pl-origin-map) #f)
                                  collision-mode: (pl-pick 'swept 'discrete)))
               (e (pl-wide-entity k (scene-tilemap scene)))
               (declined (motion-kernel-declines))
               (fast (pl-outcome (lambda () ((motion-pass scene 16 #t) e))))
               (slow (pl-outcome (lambda () (detect-on-solid scene (pl-six-steps scene e) 16)))))
          (loop (+ k 1)
                (if (equal? fast slow) different (+ different 1))
                (if (= declined (motion-kernel-declines)) (+ taken 1) taken)
                (or first-difference (and (not (equal? fast slow)) (list e fast slow))))))))

(test-group "the motion pass's fixnum path is the six steps and ground detection"
  (define no-map (make-scene))
  (let loop ((k 0) (different 0) (moved 0) (landed 0) (first-difference #f))
    (if (= k 8000)
        (begin
          (test "8000 random fixnum entities: identical results" 0 different)
          (when first-difference (print "pipeline: first difference " first-difference))
          (test-assert "most of them moved" (> moved 6000))
          (test-assert "a tile stopped a fifth of them or more" (> landed 1600)))
        (let* ((scene (make-scene tilemap: (if (pl-chance 90) (pl-origin-map) #f)
                                  collision-mode: (pl-pick 'swept 'discrete)))
               (e (pl-fixnum-entity k (scene-tilemap scene)))
               (fast (pl-outcome (lambda () ((motion-pass scene 16 #t) e))))
               (slow (pl-outcome (lambda () (detect-on-solid scene (pl-six-steps scene e) 16)))))
          (loop (+ k 1)
                (if (equal? fast slow) different (+ different 1))
                (if (equal? fast e) moved (+ moved 1))
                ;; a tile made a difference: without the map it moves on
                (if (and (pair? fast) (scene-tilemap scene)
                         (not (equal? (pl-outcome (lambda () (step-motion scene e 16)))
                                      (pl-outcome (lambda () (step-motion no-map e 16))))))
                    (+ landed 1)
                    landed)
                (or first-difference (and (not (equal? fast slow)) (list e fast slow))))))))

;; Bodies of flonums on a map take the flonum kernel (physics/motion.c,
;; ds_flonum_motion) with the tile steps. Compared field by field with
;; eqv?, so that -0.0 against 0.0, a fixnum against a flonum, and a NaN
;; count: random maps (origin anywhere, tile sizes 1 to 16; some with
;; slopes, which the kernel leaves to the readable steps), random bodies
;; of flonums and fixnums, some on a tile edge or the double next to it,
;; some at 2^52, 2^53, 1e300, infinities or a NaN.
(define (pl-eqv-entity? a b)
  (cond ((and (pair? a) (pair? b) (pair? (car a)) (pair? (car b)))
         (and (eq? (caar a) (caar b))
              (let ((u (cdar a)) (v (cdar b)))
                (if (number? u) (eqv? u v) (equal? u v)))
              (pl-eqv-entity? (cdr a) (cdr b))))
        (else (equal? a b))))

(define (pl-eqv-entities? as bs)
  (if (and (pair? as) (pair? bs))
      (and (pl-eqv-entity? (car as) (car bs)) (pl-eqv-entities? (cdr as) (cdr bs)))
      (and (null? as) (null? bs))))

(define (pl-flo-map slopes?)
  (let* ((w (+ 1 (pl-rand 14))) (h (+ 1 (pl-rand 14)))
         (density (pl-pick 5 20 40 70))
         (data (make-u32vector (* w h) 0)))
    (do ((i 0 (+ i 1))) ((= i (* w h)))
      (when (pl-chance density)
        (u32vector-set! data i (if (and slopes? (pl-chance 30)) (pl-pick 3 4 8 9) (pl-pick 1 1 1 2 2 7)))))
    (let ((tw (pl-pick 16 8 10 16 1 3)) (th (pl-pick 16 8 12 16 1 5)))
      (make-tilemap w h tw th
                    (list (make-layer "solid" w h data)) one-way: '(2) ladders: '(7)
                    slopes: (list (list 3 0 th) (list 4 th 0))
                    ceiling-slopes: (list (list 8 0 th) (list 9 th 0))
                    origin-col: (- (pl-rand 12) 6) origin-row: (- (pl-rand 12) 6)))))

;; p and the doubles on either side of it, and a little way off
(define (pl-near-double p)
  (let ((ulp (* (max (abs p) 1e-300) 1.2e-16)))
    (pl-pick p (- p ulp) (+ p ulp) (- p 1e-9) (+ p 1e-7) (- p 0.5) p)))

(define (pl-flo-coord origin count tile)
  (let ((mid (+ (* origin tile) (quotient (* count tile) 2)))
        (spread (+ 8 (quotient (* count tile) 2))))
    (case (pl-rand 20)
      ((0 1 2 3 4 5) (+ mid (- (pl-rand (* 2 spread)) spread) (/ (pl-rand 1000) 1000.0)))
      ((6 7 8 9 10) (pl-near-double (exact->inexact (* (+ origin (pl-rand (+ count 1))) tile))))
      ((11 12) (+ mid (- (pl-rand (* 2 spread)) spread)))
      ((13) (pl-pick -0.0 0.0 (exact->inexact mid)))
      ((14) (pl-pick 4503599627370496.0 9007199254740992.0 -4503599627370496.0 -9007199254740993.0
                     1e300 -1e300 1099511627775.5 -1099511627776.0 1099511627776.0 549755813888.25))
      ((15) (pl-pick +nan.0 +inf.0 -inf.0 (exact->inexact mid)))
      (else (exact->inexact (+ mid (- (pl-rand (* 2 spread)) spread)))))))

(define (pl-flo-speed)
  (case (pl-rand 12)
    ((0 1 2) (- (/ (pl-rand 40000) 1000.0) 20.0))
    ((3 4) (- (pl-rand 41) 20))
    ((5) (pl-pick 0.0 -0.0 0 0.1 -0.1 1e-300))
    ((6) (pl-near-double (exact->inexact (* (pl-pick 1 -1) (pl-pick 1 8 16 10 3)))))
    ((7) (pl-pick 40.5 -63.25 100.0 1e300 -1e300 4503599627370496.0 +nan.0 +inf.0))
    (else (- (/ (pl-rand 8000) 1000.0) 4.0))))

(define (pl-all-finite? xs)
  (or (null? xs) (and (= (car xs) (car xs)) (< (abs (car xs)) +inf.0) (pl-all-finite? (cdr xs)))))

(define (pl-flo-entity k tm)
  (filter-present
   (list (and (pl-chance 97) (cons #:x (pl-flo-coord (tilemap-origin-col tm) (tilemap-width tm) (tilemap-tile-width tm))))
         (and (pl-chance 97) (cons #:y (pl-flo-coord (tilemap-origin-row tm) (tilemap-height tm) (tilemap-tile-height tm))))
         (and (pl-chance 95) (cons #:width (pl-pick 0 1 8 12 16 20 33 0.5)))
         (and (pl-chance 95) (cons #:height (pl-pick 0 1 8 12 16 20 33 12.0)))
         (and (pl-chance 90) (cons #:vx (pl-flo-speed)))
         (and (pl-chance 90) (cons #:vy (pl-flo-speed)))
         (and (pl-chance 50) (cons #:ay (pl-pick 0 0 -10 0.0 -0.0 2.5 -0.75)))
         (and (pl-chance 70) (cons #:gravity? (pl-pick #t #t #f)))
         (and (pl-chance 50) (cons #:on-ground? (pl-pick #t #f)))
         (and (pl-chance 15) (cons #:collision-mode (pl-pick 'swept 'discrete)))
         (and (pl-chance 15) (cons #:drop-through? (pl-pick #t #f)))
         (and (pl-chance 5) (cons #:climber? #t))
         (and (pl-chance 5) (cons #:climbing? #t))
         (cons #:id k))))

(test-group "the flonum kernel on a map is the six steps and ground detection"
  ;; bodies the random ones rarely make: a swept body at y = -0.0 moving
  ;; only on x (the escape's y + 0 makes it 0.0), one on a tile edge
  ;; moving into the wall beyond, one a double short of it
  (let ((tm (list->tilemap '((0 0 0 1) (0 0 0 1) (1 1 1 1)) tile-width: 16 tile-height: 16)))
    (for-each
     (lambda (mode plist)
       (let* ((scene (make-scene tilemap: tm collision-mode: mode))
              (e (plist->entity plist))
              (fast ((motion-pass scene 16 #t) e))
              (slow (detect-on-solid scene (pl-six-steps scene e) 16)))
         (test-assert (sprintf "~a ~s: the steps' result, field by field ~s" mode plist slow)
                      (pl-eqv-entity? fast slow))))
     '(swept discrete swept swept discrete)
     (list (list #:x 4.5 #:y -0.0 #:vx 1 #:vy -0.0 #:width 8 #:height 8)
           (list #:x 4.5 #:y -0.0 #:vx 1.0 #:vy -0.0 #:width 8 #:height 8)
           (list #:x 40.0 #:y 4.25 #:vx 2.5 #:vy 0 #:width 8 #:height 8 #:gravity? #t)
           (list #:x 39.99999999999999 #:y 23.5 #:vx 0.5 #:vy 0.0 #:width 8 #:height 8 #:gravity? #t)
           (list #:x 10.0 #:y 15.999999999999998 #:vx -0.0 #:vy 0.25 #:width 8 #:height 16))))
  (let loop ((k 0) (different 0) (taken 0) (plain 0) (stopped 0) (first-difference #f))
    (if (= k pl-flo-bodies)
        (begin
          (test (sprintf "~a random flonum bodies, five frames each: identical results, field by field (eqv?)"
                         pl-flo-bodies)
                0 different)
          (when first-difference (print "pipeline: first difference " first-difference))
          ;; plain: a body of finite numbers near a map without slopes,
          ;; of fixnum size, no skips: the kernel's to take
          (test-assert (sprintf "the kernel took most plain ones (~a of ~a)" taken plain)
                       (> taken (* 3/4 plain)))
          (test-assert (sprintf "a tile stopped or held many it took (~a)" stopped)
                       (> stopped (quotient pl-flo-bodies 20))))
        (let* ((slopes? (pl-chance 15))
               (tm (pl-flo-map slopes?))
               (scene (make-scene tilemap: tm collision-mode: (pl-pick 'swept 'discrete)))
               (ground? (pl-chance 50))
               (e (pl-flo-entity k tm))
               (slow-step (lambda (e) (let ((moved (pl-six-steps scene e)))
                                        (if ground? (detect-on-solid scene moved 16) moved))))
               (fast-step (lambda (e) ((motion-pass scene 16 ground?) e)))
               (frames (lambda (step)
                         (pl-outcome (lambda ()
                                       (let run ((f 0) (e e))
                                         (if (= f 5) e (run (+ f 1) (step e))))))))
               (declined (motion-kernel-declines))
               (once (pl-outcome (lambda () (fast-step e))))
               (took? (= declined (motion-kernel-declines)))
               (plain? (and (not slopes?)
                            (let ((num (lambda (key) (entity-ref e key 0))))
                              (and (fixnum? (num #:width)) (fixnum? (num #:height))
                                   (or (flonum? (num #:x)) (flonum? (num #:y))
                                       (flonum? (num #:vx)) (flonum? (num #:vy)))
                                   (pl-all-finite? (map num '(#:x #:y #:vx #:vy)))
                                   (< (abs (num #:x)) 1e6) (< (abs (num #:y)) 1e6)
                                   (< (abs (num #:vx)) 1e3) (< (abs (num #:vy)) 1e3)))))
               (fast (frames fast-step))
               (slow (frames slow-step)))
          (loop (+ k 1)
                (if (pl-eqv-entity? fast slow) different (+ different 1))
                (if (and plain? took?) (+ taken 1) taken)
                (if plain? (+ plain 1) plain)
                (if (and took? (pair? once)
                         (not (pl-eqv-entity? once (pl-outcome (lambda () ((motion-pass (make-scene) 16 ground?) e))))))
                    (+ stopped 1)
                    stopped)
                (or first-difference (and (not (pl-eqv-entity? fast slow)) (list e fast slow))))))))

;; A swept body that moves from inside solid tiles: the flonum kernel
;; takes it out of them itself when the escape's search ends with a
;; straight move (physics/motion.c, ds_flo_escape; escape.c decides, the
;; kernel makes the numbers as escape.scm makes them), and leaves the
;; others (a move on both axes may be nearer, a #:tween, numbers beyond
;; the escape's C) to the readable steps. Random maps, bodies sunk into a
;; solid cell from any side or corner, of flonums and fixnums (a tile
;; edge, the double next to it, -0.0, 2^52, 2^53, a NaN, far outside the
;; map), five frames each, field by field with eqv?.
(test-group "the flonum kernel takes bodies out of solid tiles as the readable steps do"
  (define (solid-cell tm)               ; a random solid cell's (col . row), or #f
    (let try ((n 0))
      (and (< n 30)
           (let ((c (pl-rand (tilemap-width tm))) (r (pl-rand (tilemap-height tm))))
             (if (= 1 (tilemap-tile-at tm (+ c (tilemap-origin-col tm)) (+ r (tilemap-origin-row tm))))
                 (cons c r)
                 (try (+ n 1)))))))
  ;; a coordinate whose box of `size` overlaps the cell at line `line`
  (define (sunk line tile size)
    (let ((v (+ (* line tile) (- (pl-rand (+ tile size 4)) size 2))))
      (case (pl-rand 12)
        ((0 1 2 3 4) (+ v (/ (pl-rand 1000) 1000.0)))
        ((5 6) v)
        ((7 8) (exact->inexact v))
        ((9) (pl-near-double (exact->inexact (* line tile))))
        ((10) (pl-pick -0.0 0.0 4503599627370496.0 9007199254740992.0 +nan.0 -1e300 1099511627775.5))
        (else (+ v (pl-pick 0.25 -0.5 1e-9 -1e-9))))))
  (let loop ((k 0) (different 0) (inside 0) (taken 0) (first-difference #f))
    (if (= k pl-flo-bodies)
        (begin
          (test (sprintf "~a random bodies in and near solid tiles, five frames each: identical (eqv?)" pl-flo-bodies)
                0 different)
          (when first-difference (print "pipeline: first difference " first-difference))
          (test-assert (sprintf "the kernel took many that started inside (~a of ~a)" taken inside)
                       (> taken (quotient inside 6))))
        (let* ((tm (pl-flo-map #f))
               (cell (or (solid-cell tm) (cons 0 0)))
               (w (pl-pick 1 8 12 12 16 20 33)) (h (pl-pick 1 8 12 12 16 20 33))
               (x (sunk (+ (car cell) (tilemap-origin-col tm)) (tilemap-tile-width tm) w))
               (y (sunk (+ (cdr cell) (tilemap-origin-row tm)) (tilemap-tile-height tm) h))
               (e (filter-present
                   (list (cons #:x x) (cons #:y y) (cons #:width w) (cons #:height h)
                         (cons #:vx (pl-pick 1 -1 2 0.5 -0.25 3.75 -4.0 0 (pl-flo-speed)))
                         (cons #:vy (pl-pick 0 1 -1 0.5 -2.5 (pl-flo-speed)))
                         (and (pl-chance 60) (cons #:gravity? #t))
                         (and (pl-chance 30) (cons #:on-ground? (pl-pick #t #f)))
                         (and (pl-chance 10) (cons #:drop-through? #t))
                         (cons #:id k))))
               (e (if (and (pl-chance 5) (pl-all-finite? (list x)) (< (abs x) 1e9))
                      (entity-set e #:tween (make-tween e props: (list (cons #:x (+ 40 (entity-ref e #:x))))
                                                        duration: 100))
                      e))
               (scene (make-scene tilemap: tm collision-mode: 'swept))
               (slow-step (lambda (e) (pl-six-steps scene e)))
               (fast-step (lambda (e) ((motion-pass scene 16 #f) e)))
               (frames (lambda (step)
                         (pl-outcome (lambda ()
                                       (let run ((f 0) (e e))
                                         (if (= f 5) e (run (+ f 1) (step e))))))))
               (start-inside? (and (pl-all-finite? (list x y))
                                   (handle-exceptions exn #f
                                     (let-values (((dx dy) (tile-way-out tm x y w h)))
                                       (not (and (eqv? dx 0) (eqv? dy 0)))))))
               (declined (motion-kernel-declines))
               (once (pl-outcome (lambda () (fast-step e))))
               (took? (= declined (motion-kernel-declines)))
               (fast (frames fast-step))
               (slow (frames slow-step)))
          (loop (+ k 1)
                (if (pl-eqv-entity? fast slow) different (+ different 1))
                (if start-inside? (+ inside 1) inside)
                (if (and start-inside? took? (pair? once)) (+ taken 1) taken)
                (or first-difference (and (not (pl-eqv-entity? fast slow)) (list e fast slow))))))))

;; Whole frames: flonum crowds on maps (no solid entities, so ground
;; detection joins the motion pass) through engine-pipeline, against
;; contract-pipeline (the readable steps), for ten frames.
(test-group "engine-pipeline equals contract-pipeline for flonum bodies on maps"
  (let loop ((k 0) (different 0) (frames 0))
    (if (= k pl-flo-scenes)
        (begin (test (sprintf "~a random scenes, 10 frames each: identical entities (eqv?)" pl-flo-scenes)
                     0 different)
               (test "every frame compared" (* 10 pl-flo-scenes) frames))
        (let* ((tm (pl-flo-map (pl-chance 15)))
               (n (pl-pick 1 3 8 20))
               (entities (let make ((i 0))
                           (if (= i n)
                               '()
                               (cons (filter-present (map (lambda (p) (and (not (memq (car p) '(#:climber? #:climbing?))) p))
                                                          (pl-flo-entity i tm)))
                                     (make (+ i 1))))))
               (scene (make-scene tilemap: tm collision-mode: (pl-pick 'swept 'discrete) entities: entities)))
          (let frame ((f 0) (fast scene) (slow scene) (different different) (frames frames))
            (if (= f 10)
                (loop (+ k 1) different frames)
                (let ((fast2 (pl-outcome (lambda () (engine-pipeline fast 16))))
                      (slow2 (pl-outcome (lambda () (contract-pipeline slow 16)))))
                  (cond ((and (scene? fast2) (scene? slow2))
                         (frame (+ f 1) fast2 slow2
                                (if (pl-eqv-entities? (scene-entities fast2) (scene-entities slow2))
                                    different
                                    (begin (when (= different 0)
                                             (print "pipeline: first frame difference "
                                                    (list (scene-entities fast) (scene-entities fast2)
                                                          (scene-entities slow2))))
                                           (+ different 1)))
                                (+ frames 1)))
                        ;; both must fail (with several bad bodies, the
                        ;; two may name different ones first)
                        (else
                         (frame 10 fast slow (if (or (scene? fast2) (scene? slow2)) (+ different 1) different)
                                (+ frames (- 10 f))))))))))))

;; Every step over every entity, as docs/physics.org lists them.
(define (pl-reference-pipeline scene dt)
  (let* ((each (lambda (step) (lambda (s) (scene-map-entities s (lambda (s e) (step s e dt))))))
         (scene ((each record-frame-start) scene))
         (scene ((each step-tweens) scene))
         (scene ((each apply-climbing) scene))
         (scene ((each apply-acceleration) scene))
         (scene ((each apply-gravity) scene))
         (scene ((each apply-body-controls) scene))
         (scene ((each apply-velocity-x) scene))
         (scene ((each resolve-tile-collisions-x) scene))
         (scene ((each apply-velocity-y) scene))
         (scene ((each resolve-tile-collisions-y) scene))
         (scene ((each detect-on-solid) scene))
         (scene (scene-transform-entities scene resolve-entity-collisions))
         (scene (scene-transform-entities scene sync-groups))
         (scene ((each detect-contacts) scene))
         (scene ((each apply-animation) scene)))
    ((each step-particles) scene)))

(define pl-particles-seen 0)
;; climbers that grabbed a ladder in a frame compared (not climbing
;; before it, climbing after), and that let go of one
(define pl-grabs 0)
(define pl-let-go 0)
(define (pl-count-climbs! before after)
  (for-each (lambda (a b)
              (let ((was (entity-ref a #:climbing? #f)) (now (entity-ref b #:climbing? #f)))
                (when (and (entity-ref b #:climber? #f) (not was) now) (set! pl-grabs (+ pl-grabs 1)))
                (when (and (entity-ref b #:climber? #f) was (not now)) (set! pl-let-go (+ pl-let-go 1)))))
            before after))

;; Sometimes an emitter (particles.scm), born in the entity's box.
(define (pl-with-emitter e)
  (if (pl-chance 10)
      (entity-set e #:emitter (make-emitter rate: (pl-pick 0 1/2 2) burst: (pl-pick 0 5)
                                            speed: '(0 3) lifetime: '(2 6) gravity: (pl-pick 0 1/4)
                                            seed: (+ 1 (pl-rand 1000))))
      e))

(test-group "engine-pipeline (the fast path) equals contract-pipeline and the steps in turn"
  (let loop ((k 0) (different 0) (frames 0))
    (if (= k 300)
        (begin (test "300 random scenes, 10 frames each: identical entities" 0 different)
               (test "every frame compared" 3000 frames)
               (test-assert "emitters among them were stepped (particles were alive)"
                            (> pl-particles-seen 100))
               (test-assert "climbers among them grabbed ladders and let go of them"
                            (and (> pl-grabs 20) (> pl-let-go 20))))
        (let* ((n (pl-pick 0 1 2 3 5 8 40))
               (entities (let make ((i 0)) (if (= i n) '() (cons (pl-with-emitter (pl-with-tween (pl-entity i))) (make (+ i 1))))))
               (scene (make-scene tilemap: (if (pl-chance 80) (pl-map) #f)
                                  collision-mode: (pl-pick 'swept 'discrete) entities: entities)))
          (let frame ((f 0) (fast scene) (slow scene) (different different) (frames frames))
            (if (= f 10)
                (loop (+ k 1) different frames)
                (let* ((fast2 (pl-outcome (lambda () (engine-pipeline fast 16))))
                       (slow2 (pl-outcome (lambda () (contract-pipeline slow 16))))
                       (ref2 (pl-outcome (lambda () (pl-reference-pipeline slow 16))))
                       (slow2 (if (or (and (scene? slow2) (scene? ref2)
                                           (equal? (scene-entities slow2) (scene-entities ref2)))
                                      (equal? slow2 ref2))
                                  slow2
                                  '(contract-pipeline differs from the steps run in turn))))
                  (cond ((and (scene? fast2) (scene? slow2)
                              (equal? (scene-entities fast2) (scene-entities slow2)))
                         (for-each (lambda (e)
                                     (let ((em (entity-ref e #:emitter #f)))
                                       (when em (set! pl-particles-seen (+ pl-particles-seen (emitter-count em))))))
                                   (scene-entities fast2))
                         (when (= (length (scene-entities fast)) (length (scene-entities fast2)))
                           (pl-count-climbs! (scene-entities fast) (scene-entities fast2)))
                         (frame (+ f 1) fast2 slow2 different (+ frames 1)))
                        ((and (pair? fast2) (equal? fast2 slow2))
                         ;; both raised the same error: the scene stops here
                         (frame 10 fast slow different (+ frames (- 10 f))))
                        (else (frame 10 fast slow (+ different 1) (+ frames (- 10 f))))))))))))

(test-group "entity-set* is entity-set repeated"
  (let loop ((k 0) (different 0))
    (if (= k 3000)
        (test "3000 random entities and settings" 0 different)
        (let* ((e (pl-entity k))
               (keys (list #:x #:vy #:ay #:tween #:x #:id #:width))
               (kvs (let make ((i (pl-rand 6)))
                      (if (= i 0) '() (cons (list-ref keys (pl-rand (length keys))) (cons i (make (- i 1)))))))
               (slow (let set ((e e) (kvs kvs)) (if (null? kvs) e (set (entity-set e (car kvs) (cadr kvs)) (cddr kvs))))))
          (loop (+ k 1) (if (equal? (apply entity-set* e kvs) slow) different (+ different 1))))))
  (let ((e (list (cons #:a 1) (cons #:b 2) (cons #:c 3))))
    (test "present keys keep their place, absent ones go first, the last set first"
          (list (cons #:e 5) (cons #:d 4) (cons #:a 1) (cons #:b 20) (cons #:c 3))
          (entity-set* e #:d 4 #:b 20 #:e 5))
    (test "the tail after the last key set is shared" #t
          (eq? (cddr e) (cddr (entity-set* e #:a 10 #:b 20))))))

;; The steps by name, which the engine runs one at a time to say which
;; step raised an error: in turn they make contract-pipeline's frames, and
;; pipeline-failing-step names the step whose error contract-pipeline raises.
(test-group "contract-steps: contract-pipeline's steps by name; pipeline-failing-step"
  (test "named as #:skip-pipelines names them"
        '(frame-start tweens climbing acceleration gravity controls velocity-x tile-collisions-x velocity-y
          tile-collisions-y on-solid entity-collisions groups contacts animation particles)
        (map car contract-steps))
  (let loop ((k 0) (different 0) (errors 0))
    (if (= k 60)
        (begin (test "60 random scenes, 10 frames each: the same frames, the same errors" 0 different)
               (test-assert "some of them raised an error" (> errors 0)))
        (let* ((n (pl-pick 1 2 3 5 8))
               (entities (let make ((i 0)) (if (= i n) '() (cons (pl-with-tween (pl-entity i)) (make (+ i 1))))))
               ;; a third of the scenes hold a body with a bad number
               (bad (list (cons #:type 'bad) (cons #:x 0) (cons #:y 0) (cons #:width 4) (cons #:height 4)
                          (cons #:gravity? (pl-chance 50)) (cons #:solid? (pl-chance 50))
                          (cons (pl-pick #:vx #:vy #:x #:width) (pl-pick (/ 0. 0.) "3" (/ 1. 0.)))))
               (scene (parameterize ((scene-checks #f))
                        (make-scene tilemap: (if (pl-chance 80) (pl-map) #f)
                                    collision-mode: (pl-pick 'swept 'discrete)
                                    entities: (if (pl-chance 33) (append entities (list bad)) entities)))))
          (let frame ((f 0) (scene scene) (different different) (errors errors))
            (if (= f 10)
                (loop (+ k 1) different errors)
                (let ((whole (pl-outcome (lambda () (contract-pipeline scene 16))))
                      (stepped (pl-outcome (lambda () (foldl (lambda (s step) ((cdr step) s 16)) scene contract-steps)))))
                  (receive (step c) (pipeline-failing-step scene 16)
                    (cond ((not (or (and (scene? whole) (scene? stepped)
                                         (equal? (scene-entities whole) (scene-entities stepped)))
                                    (equal? whole stepped)))
                           (frame 10 scene (+ different 1) errors))
                          ((scene? whole)
                           (frame (+ f 1) whole (if step (+ different 1) different) errors))
                          (else
                           (frame 10 scene
                                  (if (and step (equal? (cadr whole) ((condition-property-accessor 'exn 'message) c)))
                                      different
                                      (+ different 1))
                                  (+ errors 1))))))))))))
