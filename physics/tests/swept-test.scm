;;; Swept tile collisions: no tunnelling at any speed, and the same result
;;; as the discrete step wherever the discrete step does not pass a wall.

(import scheme (chicken base) (downstroke test) (downstroke entity)
        (downstroke tilemap) (downstroke scene) (downstroke physics) (downstroke pipeline))

(define (sw-ent . plist) (plist->entity plist))

;; One frame of the default pipeline for one body; the body after it.
(define (engine-pipeline-once scene body)
  (car (scene-entities (engine-pipeline (update-scene scene entities: (list body)) 16))))

;; The bench's 31-bit LCG, so failures can be replayed from the seed.
(define sw-seed 20261121)
(define (sw-rand n)
  (set! sw-seed (modulo (+ (* 1103515245 sw-seed) 12345) 2147483648))
  (modulo sw-seed n))

(define (sw-random-map w h)
  (list->tilemap
   (let rows ((j 0))
     (if (= j h) '()
         (cons (let cols ((i 0))
                 (if (= i w) '() (cons (if (< (sw-rand 100) 15) 1 0) (cols (+ i 1)))))
               (rows (+ j 1)))))))

;; Independent of the library's cell arithmetic: walk every pixel column
;; (row) the body swept through and ask the map about each one.
(define (sw-solid-line? tm axis line lo hi)
  (let loop ((p lo))
    (and (< p hi)
         (or (not (zero? (if (eq? axis 'x)
                             (tilemap-tile-at tm line (floor (/ p 16)))
                             (tilemap-tile-at tm (floor (/ p 16)) line))))
             (loop (+ p 1))))))

;; The line (tile column for x, row for y) of the first solid tile met by a
;; body whose span moves from [pos0, pos0+size) to [pos1, pos1+size), pixel
;; by pixel; #f if none. `lo`..`hi` is the body's span on the other axis.
;; What it meets: every pixel its leading edge crosses, and every pixel it
;; covers at the end (a wall it only leaves behind does not stop it).
(define (sw-first-wall tm axis pos0 pos1 size lo hi)
  (let ((step (if (> pos1 pos0) 1 -1)))
    (let loop ((p (if (> step 0)
                      (min (+ pos0 size -1) pos1)
                      (max pos0 (+ pos1 size -1)))))
      (let ((line (floor (/ p 16))))
        (cond ((if (> step 0) (>= p (+ pos1 size)) (< p pos1)) #f)
              ((sw-solid-line? tm axis line lo hi) line)
              (else (loop (+ p step))))))))

;; Whether the box at (x, y) of w x h (integers) covers a solid tile. A
;; body that starts its frame so, and moves, is first taken out of the
;; tiles in swept mode (escape-test.scm): there the two modes may differ.
(define (sw-box-solid? tm x y w h)
  (let rows ((r (floor (/ y 16))))
    (and (<= r (floor (/ (+ y h -1) 16)))
         (or (let cols ((c (floor (/ x 16))))
               (and (<= c (floor (/ (+ x w -1) 16)))
                    (or (= 1 (tilemap-tile-at tm c r)) (cols (+ c 1)))))
             (rows (+ r 1))))))

(test-group "swept against discrete: 4000 random bodies, maps and velocities"
  (let ((same 0) (differ-without-tunnel 0) (tunnels 0) (swept-passed-wall 0) (swept-wrong 0)
        (started-inside 0))
    (do ((k 0 (+ k 1))) ((= k 4000))
      (let* ((tm (sw-random-map 12 12))
             (axis (if (even? k) 'x 'y))
             (size (+ 1 (sw-rand 20)))
             (across (+ 1 (sw-rand 20)))
             (v (let ((v (- (sw-rand 81) 40))) (if (zero? v) 7 v)))
             (pos1 (sw-rand 192))
             (pos0 (- pos1 v))
             (other (sw-rand 180))
             (body (if (eq? axis 'x)
                       (sw-ent #:x pos1 #:y other #:width size #:height across #:vx v)
                       (sw-ent #:x other #:y pos1 #:width across #:height size #:vy v)))
             (scene (make-scene tilemap: tm))
             (step (if (eq? axis 'x) resolve-tile-collisions-x resolve-tile-collisions-y))
             (pos-key (if (eq? axis 'x) #:x #:y))
             (discrete (step scene (entity-set body #:collision-mode 'discrete) 16))
             (swept (step scene (entity-set body #:collision-mode 'swept) 16))
             (wall (sw-first-wall tm axis pos0 pos1 size other (+ other across)))
             ;; where the body ends if it stops at that wall
             (expected (cond ((not wall) pos1)
                             ((> v 0) (- (* 16 wall) size))
                             (else (* 16 (+ wall 1)))))
             ;; the discrete step passed a wall when it ended beyond the first one
             (tunnelled (and wall (if (> v 0)
                                      (> (entity-ref discrete pos-key) expected)
                                      (< (entity-ref discrete pos-key) expected)))))
        (cond ((if (eq? axis 'x)
                   (sw-box-solid? tm pos0 other size across)
                   (sw-box-solid? tm other pos0 across size))
               (set! started-inside (+ started-inside 1)))
              (else
               (unless (= (entity-ref swept pos-key) expected) (set! swept-wrong (+ swept-wrong 1)))
               (when (and wall (if (> v 0) (> (entity-ref swept pos-key) expected)
                                   (< (entity-ref swept pos-key) expected)))
                 (set! swept-passed-wall (+ swept-passed-wall 1)))
               (cond (tunnelled (set! tunnels (+ tunnels 1)))
                     ((equal? (entity-remove discrete #:collision-mode)
                              (entity-remove swept #:collision-mode))
                      (set! same (+ same 1)))
                     (else (set! differ-without-tunnel (+ differ-without-tunnel 1))))))))
    (test-assert "some bodies started inside a wall, and are left out of this comparison"
                 (> started-inside 100))
    (test "swept never passes a wall" 0 swept-passed-wall)
    (test "swept stops exactly at the first wall on the way" 0 swept-wrong)
    (test "where discrete does not tunnel, both agree exactly" 0 differ-without-tunnel)
    (test-assert "the sample has many agreeing cases" (> same 2000))
    (test-assert "and some where discrete tunnels" (> tunnels 50))))

(test-group "S3 speeds: a one-tile wall at every speed"
  ;; 400 x 4 map, column 300 solid: the wall's left face is at x = 4800.
  (define tm (list->tilemap
              (let rows ((j 0))
                (if (= j 4) '()
                    (cons (let cols ((i 0)) (if (= i 400) '() (cons (if (= i 300) 1 0) (cols (+ i 1)))))
                          (rows (+ j 1)))))))
  (define (final-x mode x0 v)
    (let ((scene (make-scene tilemap: tm collision-mode: mode)))
      (let loop ((e (sw-ent #:x x0 #:y 16 #:width 12 #:height 12 #:vx v))
                 (frames (+ 1 (ceiling (/ (- 4816 x0) v)))))
        (if (zero? frames)
            (list (entity-ref e #:x) (entity-ref e #:vx))
            (loop (resolve-tile-collisions-x scene (apply-velocity-x scene e 16) 16)
                  (- frames 1))))))
  (for-each
   (lambda (v)
     (test (string-append "swept, v = " (number->string v)) '(4788 0) (final-x 'swept 1633/4 v))
     (test (string-append "swept from a fraction, v = " (number->string v)) '(4788 0) (final-x 'swept 4787/4 v)))
   '(1 8 16 27 28 29 40 64 200 1000 1000000))
  (test "discrete holds at 27 px/frame" '(4788 0) (final-x 'discrete 16 27))
  (test-assert "discrete passes the wall at 1000 px/frame" (>= (car (final-x 'discrete 16 1000)) 4816)))

(test-group "swept: leaving a wall with a flonum speed"
  ;; pos - v rounds: 256 + 1.383 - 1.383 is not 256 in flonums, and the
  ;; start computed from it lies just inside the wall the body touched.
  (let* ((tm (list->tilemap (list (let cols ((i 0)) (if (= i 40) '() (cons (if (= i 15) 1 0) (cols (+ i 1))))))))
         (scene (make-scene tilemap: tm collision-mode: 'swept))
         (move (lambda (e) (resolve-tile-collisions-x scene (apply-velocity-x scene e 16) 16))))
    (test "a box touching the wall's right face moves away from it" (+ 256 1.383)
          (entity-ref (move (sw-ent #:x 256 #:y 0 #:width 8 #:height 8 #:vx 1.383)) #:x))
    (test "a box touching its left face moves away from it" (- 232 1.383)
          (entity-ref (move (sw-ent #:x 232 #:y 0 #:width 8 #:height 8 #:vx -1.383)) #:x))
    ;; many flonum speeds, from both faces: never on the far side
    (let loop ((k 1) (wrong 0))
      (if (> k 2000)
          (test "2000 flonum speeds away from both faces: none crosses the wall" 0 wrong)
          (let* ((v (+ 0.001 (* k 0.0137)))
                 (right (entity-ref (move (sw-ent #:x 256 #:y 0 #:width 8 #:height 8 #:vx v)) #:x))
                 (left (entity-ref (move (sw-ent #:x 232 #:y 0 #:width 8 #:height 8 #:vx (- v))) #:x)))
            (loop (+ k 1) (+ wrong (if (< right 256) 1 0) (if (> left 232) 1 0))))))))

(test-group "collision mode selection"
  (let* ((tm (list->tilemap '((0 0 0 1 0 0 0 0))))
         (fast (sw-ent #:x 70 #:y 0 #:width 8 #:height 8 #:vx 40)))
    (test "the scene's mode applies" 40
          (entity-ref (resolve-tile-collisions-x (make-scene tilemap: tm collision-mode: 'swept) fast 16) #:x))
    (test "discrete lets the same body through" 70
          (entity-ref (resolve-tile-collisions-x (make-scene tilemap: tm collision-mode: 'discrete) fast 16) #:x))
    (test "an entity's own mode wins over the scene's" 40
          (entity-ref (resolve-tile-collisions-x (make-scene tilemap: tm collision-mode: 'discrete)
                                                 (entity-set fast #:collision-mode 'swept) 16)
                      #:x))
    (test-error "an unknown mode names the entity" (resolve-tile-collisions-x (make-scene tilemap: tm)
                                                                              (entity-set fast #:collision-mode 'fast) 16))
    (test-error "an unknown scene mode" (make-scene collision-mode: 'fast))))

;; A body that skips its velocity step did not move this frame, so its
;; sweep covers nothing: swept mode does what discrete does.
(test-group "swept: a body that skips a velocity step sweeps nothing"
  (let* ((tm (list->tilemap '((0) (1) (0) (0) (0))))
         (body (lambda (mode) (sw-ent #:x 0 #:y 40 #:width 16 #:height 16 #:vy 30
                                      #:collision-mode mode #:skip-pipelines '(velocity-y))))
         (run (lambda (mode) (engine-pipeline-once (make-scene tilemap: tm) (body mode)))))
    (test "discrete: it stays at y 40 with vy 30" '(40 30)
          (let ((e (run 'discrete))) (list (entity-ref e #:y) (entity-ref e #:vy))))
    (test "swept: the same, not snapped onto the tile above" '(40 30)
          (let ((e (run 'swept))) (list (entity-ref e #:y) (entity-ref e #:vy)))))
  (let* ((tm (list->tilemap '((0 0 0 0 1 0))))
         (e (resolve-tile-collisions-x
             (make-scene tilemap: tm)
             (sw-ent #:x 40 #:y 0 #:width 16 #:height 16 #:vx -30
                     #:collision-mode 'swept #:skip-pipelines '(velocity-x))
             16)))
    (test "on x too: a body skipping velocity-x is not put beyond a wall it never touched"
          '(40 -30) (list (entity-ref e #:x) (entity-ref e #:vx))))
  ;; random bodies that skip a velocity step: swept and discrete agree on
  ;; every one (none of them moved, so none can have tunnelled)
  (let ((differ 0) (inside 0))
    (do ((k 0 (+ k 1))) ((= k 2000))
      (let* ((tm (sw-random-map 12 12))
             (axis (if (even? k) 'x 'y))
             (skip (if (eq? axis 'x) 'velocity-x 'velocity-y))
             (v (let ((v (- (sw-rand 81) 40))) (if (zero? v) 5 v)))
             (body (sw-ent #:x (sw-rand 180) #:y (sw-rand 180)
                           #:width (+ 1 (sw-rand 20)) #:height (+ 1 (sw-rand 20))
                           (if (eq? axis 'x) #:vx #:vy) v #:skip-pipelines (list skip)))
             (d (engine-pipeline-once (make-scene tilemap: tm) (entity-set body #:collision-mode 'discrete)))
             (s (engine-pipeline-once (make-scene tilemap: tm) (entity-set body #:collision-mode 'swept))))
        (cond ((sw-box-solid? tm (entity-ref body #:x) (entity-ref body #:y)
                              (entity-ref body #:width) (entity-ref body #:height))
               (set! inside (+ inside 1)))
              ((not (equal? (entity-remove d #:collision-mode) (entity-remove s #:collision-mode)))
               (set! differ (+ differ 1))))))
    (test-assert "some started inside a wall (taken out first in swept mode)" (> inside 100))
    (test "2000 random skipping bodies: swept equals discrete on every one that started free" 0 differ)))
