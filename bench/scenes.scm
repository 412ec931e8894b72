;;; The benchmark scenes of docs/performance.org (S1 to S7, written down
;;; under "The scenes" there), run by `make bench`.
;;; Prints a table, the checksum lines of each scene, and writes one CSV
;;; row per (scene, mode, n or speed):
;;;   scene,mode,n,speed,frames,ms_per_frame,us_per_entity_frame,tunnel_pct,wrong_pct
;;; Usage: bench [--runs R] [--csv FILE] [--quick] [--n N] [--mode M] [--warm-up W] [--frames F]
;;;              [S1 S2 S3 S4 S5 S6 S7 steps ...]

(import scheme (chicken base) (chicken format) (chicken time) (chicken process-context)
        (chicken string) (chicken sort) (chicken gc) (chicken io) (chicken condition)
        (only (chicken file) directory-exists?) (only (chicken pathname) pathname-directory)
        (downstroke entity) (downstroke scene) (downstroke tilemap)
        (downstroke physics) (downstroke overlap) (downstroke engine) (downstroke pipeline) (downstroke tween) (downstroke animation))

;;; The scenes' generator: s := (1103515245 s + 12345) mod 2^31.
(define seed 0)
(define (reseed!) (set! seed 20261121))
(define (rand)
  (set! seed (modulo (+ (* 1103515245 seed) 12345) 2147483648))
  seed)

;;; The map of S1: border and 12% of the cells solid, one draw per cell.
(define (generate-map w h)
  (list->tilemap (generate-rows w h)))

(define (generate-rows w h)
   (let rows ((j 0))
     (if (= j h) '()
         (cons (let cols ((i 0))
                 (if (= i w) '()
                     (let ((r (rand)))
                       (cons (if (or (= i 0) (= j 0) (= i (- w 1)) (= j (- h 1))
                                     (< (modulo r 100) 12))
                                 1 0)
                             (cols (+ i 1))))))
               (rows (+ j 1))))))

(define (median xs)
  (let ((v (list->vector (sort xs <))))
    (vector-ref v (quotient (vector-length v) 2))))

(define (now) (current-process-milliseconds))

(define csv-rows '())
;; speed, tunnel and wrong are #f where a scene has none; ms is #f for S3,
;; whose movers each run their own number of frames.
(define (report! scene mode n speed frames ms us tunnel wrong)
  (define (cell v) (if v v ""))
  (set! csv-rows (cons (sprintf "~a,~a,~a,~a,~a,~a,~a,~a,~a"
                                scene mode n (cell speed) frames (cell (and ms (fixed ms 4)))
                                (fixed us 4) (cell tunnel) (cell wrong))
                       csv-rows))
  (printf "~a ~a n=~a~a~a  ~a us/entity-frame~a~%"
          scene mode n (if speed (sprintf " v=~a" speed) "")
          (if ms (sprintf "  ~a ms/frame" (fixed ms 3)) "")
          (fixed us 4)
          (if tunnel (sprintf "  tunnelled ~a%  wrong ~a%" tunnel wrong) "")))

(define (fixed x digits)
  (let* ((scale (expt 10 digits))
         (r (/ (round (* (inexact->exact x) scale)) scale)))
    (number->string (exact->inexact r))))

;; The collector's work, counted by a hook CHICKEN's runtime calls after
;; every collection: how many minor and major ones, and how many bytes the
;; minor ones moved from the nursery to the heap (the growth of the heap's
;; used part across each). Every collection empties the nursery (CHICKEN's
;; C stack, which holds the calls' frames as well as new objects), so the
;; nursery's size times the collections is what the run used of it.
(foreign-declare "
static long bench_minors, bench_majors, bench_promoted;
static C_byte *bench_top;
static void bench_count_gc(int mode, C_long ms) {
  if (mode == 0) { bench_minors++; bench_promoted += C_fromspace_top - bench_top; }
  else if (mode == 1) bench_majors++;
  bench_top = C_fromspace_top;
}")
(foreign-code "bench_top = C_fromspace_top; C_post_gc_hook = bench_count_gc;")
(define (gc-counts)
  (list ((foreign-lambda* long () "C_return(bench_minors);"))
        ((foreign-lambda* long () "C_return(bench_majors);"))
        ((foreign-lambda* long () "C_return(bench_promoted);"))))
(define nursery-bytes (vector-ref (##sys#memory-info) 1))
(define counts-at-start '(0 0 0))

;; The start of a timed run. current-gc-milliseconds counts the time of
;; major collections since it was last called: calling it here starts
;; that count too, and report-gc! reads it at the end.
(define (start-timing!)
  (current-gc-milliseconds)
  (set! counts-at-start (gc-counts))
  (now))

;; The garbage collector's share of a timed run (terminal only), and per
;; body-frame (bodies times timed frames) how much of the nursery the run
;; used and how many bytes it promoted to the heap.
(define (report-gc! gc-ms total-ms body-frames)
  (let* ((c (map - (gc-counts) counts-at-start))
         (minors (car c)) (majors (cadr c)) (promoted (caddr c)))
    (printf "  run: ~a ms, of which garbage collection ~a ms (~a%)~%" total-ms gc-ms
            (if (> total-ms 0) (round (/ (* 100 gc-ms) total-ms)) 0))
    (printf "  gc: ~a minor, ~a major; per body-frame ~a bytes of nursery, ~a bytes promoted~%"
            minors majors
            (round (/ (* (+ minors majors) nursery-bytes) body-frames))
            (round (/ promoted body-frames)))))

(define (sum key es) (foldl (lambda (acc e) (+ acc (entity-ref e key 0))) 0 es))

;;; S1: platformer crowd.
(define s1-map #f)
(define (s1-scene n mode)
  (reseed!)
  (set! s1-map (generate-map 256 256))
  (s1-movers n mode))

;; S1's bodies on s1-map, and their speeds.
(define (s1-movers n mode)
  (let loop ((k 0) (movers '()) (speeds '()))
    (if (= k n)
        (values (make-scene tilemap: s1-map collision-mode: mode entities: (reverse movers))
                (list->vector (reverse speeds)))
        (let* ((cx (+ 1 (modulo (rand) 254)))
               (cy (+ 1 (modulo (rand) 254))))
          (if (tilemap-solid? s1-map cx cy)
              (loop k movers speeds)
              (let ((s (let ((s (- (modulo (rand) 9) 4))) (if (zero? s) 1 s))))
                (loop (+ k 1)
                      (cons (list (cons #:x (* cx 16)) (cons #:y (* cy 16))
                                  (cons #:width 12) (cons #:height 12)
                                  (cons #:vx 0) (cons #:vy 0) (cons #:ay 0)
                                  (cons #:gravity? #t) (cons #:on-ground? #f))
                            movers)
                      (cons s speeds))))))))

;;; S7: S1 with a quarter of its map's solid tiles turned into slopes
;;; (docs/performance.org, "S7"): the same draws, the same bodies (placed
;;; by S1's map), then, in row-major order, every fourth solid cell off the
;;; border (the 4th, 8th, ...) becomes a slope, taking in turn the tiles
;;; 3 (0 -> 16 px), 4 (16 -> 0), 5 (0 -> 8) and 6 (8 -> 16).
(define s7-slopes '((3 0 16) (4 16 0) (5 0 8) (6 8 16)))
(define (s7-map rows)
  (let ((h (length rows)) (w (length (car rows))) (count 0))
    (list->tilemap
     (let each-row ((rows rows) (j 0))
       (if (null? rows) '()
           (cons (let each ((cells (car rows)) (i 0))
                   (if (null? cells) '()
                       (cons (if (and (= (car cells) 1) (< 0 i (- w 1)) (< 0 j (- h 1)))
                                 (begin (set! count (+ count 1))
                                        (if (= 0 (modulo count 4))
                                            (+ 3 (modulo (- (quotient count 4) 1) 4))
                                            1))
                                 (car cells))
                             (each (cdr cells) (+ i 1)))))
                 (each-row (cdr rows) (+ j 1)))))
     slopes: s7-slopes)))

(define (s7-scene n mode)
  (reseed!)
  (let ((rows (generate-rows 256 256)))
    (set! s1-map (list->tilemap rows))
    (let-values (((scene speeds) (s1-movers n mode)))
      (values (update-scene scene tilemap: (s7-map rows)) speeds))))

(define (s1-logic scene speeds f)
  (let loop ((es (scene-entities scene)) (k 0) (out '()))
    (if (null? es)
        (update-scene scene entities: (reverse out))
        (let* ((e (car es))
               (s (vector-ref speeds k))
               (s (if (and (zero? (entity-ref e #:vx)) (> f 0))
                      (let ((s (- s))) (vector-set! speeds k s) s)
                      s))
               (e (entity-set e #:vx s))
               (e (if (and (entity-ref e #:on-ground?) (zero? (modulo (+ f k) 60)))
                      (entity-set e #:ay -10)
                      e)))
          (loop (cdr es) (+ k 1) (cons e out))))))

(define (run-s1 n modes runs #!optional (scene-name "S1") (build s1-scene))
  ;; One timed run of each mode in turn, `runs` times over, so that a slow
  ;; spell of a noisy machine falls on every mode alike and the ratios
  ;; between modes stay meaningful.
  (let ((times (let repeat ((r 0) (times (map list modes)))
                 (if (= r runs)
                     times
                     (repeat (+ r 1)
                             (map (lambda (mode-times)
                                    (cons (car mode-times)
                                          (cons (s1-run n (car mode-times) (= r 0) scene-name build)
                                                (cdr mode-times))))
                                  times))))))
    (for-each (lambda (mode-times)
                (let ((ms (/ (median (cdr mode-times)) (exact->inexact (timed 600)))))
                  (report! scene-name (car mode-times) n #f (timed 600) ms (/ (* 1000 ms) n) #f #f)))
              times)
    (printf "  peak resident set of the process so far: ~a MB~%" (peak-megabytes))))

;; One run of 660 frames, the last 600 timed (ms); the first run of each
;; mode prints the checksum line.
(define (s1-run n mode checksum? #!optional (scene-name "S1") (build s1-scene))
  (let-values (((scene speeds) (build n mode)))
    (let frames ((f 0) (scene scene) (start #f))
      (cond ((= f (+ (warm-up 60) (timed 600)))
             (when checksum?
               (let ((es (scene-entities scene)))
                 (printf "checksum ~a ~a n=~a sum-x=~a sum-y=~a on-ground=~a~%"
                         scene-name mode n (sum #:x es) (sum #:y es)
                         (length (filter-on-ground es)))))
             (let ((ms (- (now) start)))
               (report-gc! (current-gc-milliseconds) ms (* n (timed 600)))
               ms))
            (else
             (let ((start (if (= f (warm-up 60)) (start-timing!) start)))
               (frames (+ f 1) (s1-logic (engine-pipeline scene 16) speeds f) start)))))))

(define (filter-on-ground es)
  (let loop ((es es) (out '()))
    (cond ((null? es) out)
          ((entity-ref (car es) #:on-ground?) (loop (cdr es) (cons (car es) out)))
          (else (loop (cdr es) out)))))

;; VmHWM of /proc/self/status (Linux), in MB; "?" where there is none.
;; S1 runs its sizes in increasing order, so after the largest this is
;; that size's peak.
(define (peak-megabytes)
  (handle-exceptions exn "?"
    (let ((line (with-input-from-file "/proc/self/status"
                  (lambda ()
                    (let loop ()
                      (let ((l (read-line)))
                        (cond ((eof-object? l) #f)
                              ((substring=? l "VmHWM:") l)
                              (else (loop)))))))))
      (if line
          (let ((kb (string->number (car (string-split (substring line 6))))))
            (if kb (quotient (+ kb 512) 1024) "?"))
          "?"))))

;;; What each step of the pipeline costs on the S1 crowd, one pass at a time
;;; (the scene after the warm-up). Steps no entity of S1 needs (tweens,
;;; entity collisions, groups, animation) should cost one walk of the list.
(define (run-s1-steps n runs)
  (let-values (((scene speeds) (s1-scene n 'discrete)))
    (let* ((scene (let warm ((f 0) (scene scene))
                    (if (= f 60) scene (warm (+ f 1) (s1-logic (engine-pipeline scene 16) speeds f)))))
           (per-entity (lambda (step) (lambda (s) (scene-map-entities s (lambda (sc e) (step sc e 16))))))
           (bulk (lambda (step) (lambda (s) (scene-transform-entities s step))))
           (steps `(("step-tweens" . ,(per-entity step-tweens))
                    ("apply-acceleration" . ,(per-entity apply-acceleration))
                    ("apply-gravity" . ,(per-entity apply-gravity))
                    ("apply-velocity-x" . ,(per-entity apply-velocity-x))
                    ("resolve-tile-collisions-x" . ,(per-entity resolve-tile-collisions-x))
                    ("apply-velocity-y" . ,(per-entity apply-velocity-y))
                    ("resolve-tile-collisions-y" . ,(per-entity resolve-tile-collisions-y))
                    ("detect-on-solid" . ,(per-entity detect-on-solid))
                    ("resolve-entity-collisions" . ,(bulk resolve-entity-collisions))
                    ("sync-groups" . ,(bulk sync-groups))
                    ("apply-animation" . ,(per-entity apply-animation))
                    ("whole pipeline" . ,(lambda (s) (engine-pipeline s 16))))))
      (for-each
       (lambda (step)
         (let ((times (let repeat ((r 0) (times '()))
                        (if (= r runs)
                            times
                            (let ((start (now)))
                              (do ((i 0 (+ i 1))) ((= i 20)) ((cdr step) scene))
                              (repeat (+ r 1) (cons (/ (- (now) start) 20.0) times)))))))
           (report! "S1-step" (car step) n #f 1 (median times) (/ (* 1000 (median times)) n) #f #f)))
       steps))))

;;; S2: solid crowd.
;; flonum?: positions as flonums (the mode 'flonum of S2, the spatial hash
;; on the same movers at the same places).
(define (s2-scene n flonum?)
  (reseed!)
  (let loop ((k 0) (movers '()))
    (if (= k n)
        (make-sprite-scene entities: (reverse movers))
        (let* ((x (modulo (rand) 2040)) (y (modulo (rand) 2040))
               (x (if flonum? (exact->inexact x) x)) (y (if flonum? (exact->inexact y) y))
               (vx (- (modulo (rand) 5) 2)) (vy (- (modulo (rand) 5) 2)))
          (loop (+ k 1)
                (cons (list (cons #:x x) (cons #:y y) (cons #:width 8) (cons #:height 8)
                            (cons #:vx vx) (cons #:vy vy) (cons #:solid? #t))
                      movers))))))

;; Velocity x then y is what the motion pass does for a body without gravity
;; in a scene without a map: one pass, as engine-pipeline runs it for these
;; bodies (solid, so no ground detection in the pass; no body controls, no
;; climber: nothing to ask each body about).
(define (s2-step scene method)
  (let ((scene (let ((move (motion-pass scene 16 #f #f #f))) (scene-map-entities scene (lambda (s e) (move e))))))
    (scene-transform-entities scene (lambda (es) (resolve-entity-collisions es method)))))

;; The walls in the position's own kind: CHICKEN compares a flonum with an
;; exact integer exactly (the flonum's integral part made an exact
;; integer), some 600 instructions a comparison, where two flonums take a
;; few. The same answers, since 0 and 2040 are doubles exactly.
(define (clamp-axis e pos vel)
  (let* ((p (entity-ref e pos))
         (low (if (flonum? p) 0.0 0))
         (high (if (flonum? p) 2040.0 2040)))
    (cond ((< p low) (entity-set (entity-set e pos low) vel (- (entity-ref e vel))))
          ((> p high) (entity-set (entity-set e pos high) vel (- (entity-ref e vel))))
          (else e))))

(define (s2-logic scene)
  (scene-map-entities scene (lambda (s e) (clamp-axis (clamp-axis e #:x #:vx) #:y #:vy))))

(define (run-s2 n method runs)
  (let ((times
         (let repeat ((r 0) (times '()))
           (if (= r runs)
               times
               (let frames ((f 0) (scene (s2-scene n (eq? method 'flonum))) (start #f))
                 (cond ((= f (+ (warm-up 60) (timed 600)))
                        (when (= r 0)
                          (let ((es (scene-entities scene)))
                            (printf "checksum S2 ~a n=~a sum-x=~a sum-y=~a~%" method n
                                    (sum #:x es) (sum #:y es))))
                        (report-gc! (current-gc-milliseconds) (- (now) start) (* n (timed 600)))
                        (repeat (+ r 1) (cons (- (now) start) times)))
                       (else
                        (let ((start (if (= f (warm-up 60)) (start-timing!) start)))
                          (frames (+ f 1) (s2-logic (s2-step scene (if (eq? method 'flonum) 'spatial-hash method)))
                                  start)))))))))
    (let ((ms (/ (median times) (exact->inexact (timed 600)))))
      (report! "S2" method n #f (timed 600) ms (/ (* 1000 ms) n) #f #f))))

;;; S3: accuracy against speed.
(define s3-map
  (list->tilemap
   (let rows ((j 0))
     (if (= j 4) '()
         (cons (let cols ((i 0)) (if (= i 400) '() (cons (if (= i 300) 1 0) (cols (+ i 1)))))
               (rows (+ j 1)))))))

(define (run-s3 v mode runs)
  (let ((scene0 (make-scene tilemap: s3-map collision-mode: mode)))
    (let repeat ((r 0) (times '()) (tunnelled 0) (wrong 0) (mover-frames 0))
      (if (= r runs)
          (let ((ms (median times)))
            (report! "S3" mode 1000 v mover-frames #f (/ (* 1000.0 ms) mover-frames)
                     (/ tunnelled 10.0) (/ wrong 10.0)))
          (begin
            (reseed!)
            (let ((start (now)))
              (let movers ((k 0) (tun 0) (wr 0) (mf 0))
                (if (= k 1000)
                    (repeat (+ r 1) (cons (- (now) start) times) tun wr mf)
                    (let* ((x (min (+ 16 (/ (modulo (rand) 4000) 4)) 4788))
                           (n (+ 1 (ceiling (/ (- 4816 x) v)))))
                      (let frames ((i 0) (scene (update-scene scene0 entities:
                                                               (list (list (cons #:x x) (cons #:y 16)
                                                                           (cons #:width 12) (cons #:height 12)
                                                                           (cons #:vx v) (cons #:vy 0))))))
                        (if (= i n)
                            (let ((fx (entity-ref (car (scene-entities scene)) #:x)))
                              (movers (+ k 1)
                                      (if (>= fx 4816) (+ tun 1) tun)
                                      (if (= fx 4788) wr (+ wr 1))
                                      (+ mf n)))
                            (frames (+ i 1) (engine-pipeline scene 16)))))))))))))

;;; S4: bullets against enemies (docs/performance.org writes the scene
;;; down): every overlapping (bullet . enemy) pair of every frame, found by
;;; overlapping-pairs and by the double loop a user would write; then each
;;; body moves and wraps around.
(define s4-side 1024)

(define (s4-entities n size speed)
  (let loop ((k 0) (out '()))
    (if (= k n)
        (reverse out)
        (let* ((x (modulo (rand) (- s4-side size))) (y (modulo (rand) (- s4-side size)))
               (vx (- (modulo (rand) (+ (* 2 speed) 1)) speed))
               (vy (- (modulo (rand) (+ (* 2 speed) 1)) speed)))
          (loop (+ k 1)
                (cons (list (cons #:x x) (cons #:y y) (cons #:width size) (cons #:height size)
                            (cons #:vx vx) (cons #:vy vy))
                      out))))))

;; Each body moves by its velocity and wraps around the arena.
(define (s4-move es)
  (map (lambda (e)
         (entity-set* e
                      #:x (modulo (+ (entity-ref e #:x) (entity-ref e #:vx)) s4-side)
                      #:y (modulo (+ (entity-ref e #:y) (entity-ref e #:vy)) s4-side)))
       es))

(define (s4-all-pairs bullets enemies)
  (let outer ((bs bullets) (out '()))
    (if (null? bs)
        (reverse out)
        (outer (cdr bs)
               (let inner ((es enemies) (out out))
                 (cond ((null? es) out)
                       ((entity-overlap? (car bs) (car es)) (inner (cdr es) (cons (cons (car bs) (car es)) out)))
                       (else (inner (cdr es) out))))))))

(define (run-s4 method bullets enemies runs)
  (let* ((find (if (eq? method 'overlapping-pairs) overlapping-pairs s4-all-pairs))
         (frames 60) (warm 10) (pairs 0)
         (times
          (let repeat ((r 0) (times '()))
            (if (= r runs)
                times
                (begin
                  (reseed!)
                  (let* ((bs0 (s4-entities bullets 4 4))      ; bullets first, then enemies
                         (es0 (s4-entities enemies 16 1)))
                   (let loop ((f 0) (bs bs0) (es es0) (start #f) (found 0))
                    (cond ((= f (+ warm frames))
                           (set! pairs found)
                           (repeat (+ r 1) (cons (- (now) start) times)))
                          (else
                           (let* ((start (if (= f warm) (now) start))
                                  (hits (length (find bs es))))
                             (loop (+ f 1) (s4-move bs) (s4-move es) start
                                   (if (>= f warm) (+ found hits) found))))))))))))
    (printf "checksum S4 ~a bullets=~a enemies=~a pairs=~a~%" method bullets enemies pairs)
    (let ((ms (/ (median times) (exact->inexact frames))))
      (report! "S4" method (+ bullets enemies) #f frames ms (/ (* 1000 ms) (+ bullets enemies)) #f #f)
      ms)))

;;; S5: S1's map and movers, every mover #:solid? #t (docs/performance.org):
;;; entity push-apart and ground detection on solid entities in a crowd.
;;; 10 frames of warm-up, 60 timed: the largest crowd is slow.
;;; mode swept: S5 itself, exact positions. mode flonum: the same movers at
;;; the same places with flonum positions (a tile stop still puts a body on
;;; an exact pixel, as the tile rules say), to tell the engine's own cost
;;; per body from the digits that pushes by halves give exact positions.
(define (s5-scene n mode)
  (let-values (((scene speeds) (s1-scene n 'swept)))
    (values (scene-map-entities scene
                                (lambda (s e)
                                  (let ((e (entity-set e #:solid? #t)))
                                    (if (eq? mode 'flonum)
                                        (entity-set* e #:x (exact->inexact (entity-ref e #:x))
                                                     #:y (exact->inexact (entity-ref e #:y)))
                                        e))))
            speeds)))

(define (run-s5 n mode runs)
  (let ((times
         (let repeat ((r 0) (times '()))
           (if (= r runs)
               times
               (let-values (((scene speeds) (s5-scene n mode)))
                 (let frames ((f 0) (scene scene) (start #f))
                   (cond ((= f (+ (warm-up 10) (timed 60)))
                          (when (= r 0)
                            (let ((es (scene-entities scene)))
                              (printf "checksum S5 ~an=~a sum-x=~a sum-y=~a on-ground=~a~%"
                                      (if (eq? mode 'flonum) "flonum " "")
                                      n (sum #:x es) (sum #:y es) (length (filter-on-ground es)))))
                          (report-gc! (current-gc-milliseconds) (- (now) start) (* n (timed 60)))
                          (repeat (+ r 1) (cons (- (now) start) times)))
                         (else
                          (let ((start (if (= f (warm-up 10)) (start-timing!) start)))
                            (frames (+ f 1) (s1-logic (engine-pipeline scene 16) speeds f) start))))))))))
    (let ((ms (/ (median times) (exact->inexact (timed 60)))))
      (report! "S5" mode n #f (timed 60) ms (/ (* 1000 ms) n) #f #f))))

;;; S6: n solid 16 px bodies piled on one spot, no map (docs/performance.org):
;;; every pair overlaps, so the push-apart of docs/physics.org visits all n(n-1)/2
;;; of them, and exact positions pushed apart by halves gain a binary
;;; digit with every push. The first 3 frames, integer positions (exact)
;;; against flonum positions (40.0): what exactness costs in a pile.
(define (run-s6 n kind runs)
  (let* ((start (if (eq? kind 'exact) 40 40.0))
         (pile (make-scene entities: (let loop ((k 0) (out '()))
                                       (if (= k n) out
                                           (loop (+ k 1) (cons (list (cons #:x start) (cons #:y start)
                                                                     (cons #:width 16) (cons #:height 16)
                                                                     (cons #:solid? #t))
                                                               out))))))
         (times (let repeat ((r 0) (times '()))
                  (if (= r runs)
                      times
                      (let ((t0 (now)))
                        (let frames ((f 0) (scene pile))
                          (if (= f 3)
                              (begin
                                (when (= r 0)
                                  (printf "checksum S6 ~a n=~a sum-x=~a~%" kind n
                                          (exact->inexact (sum #:x (scene-entities scene)))))
                                (repeat (+ r 1) (cons (- (now) t0) times)))
                              (frames (+ f 1) (engine-pipeline scene 16)))))))))
    (let ((ms (/ (median times) 3.0)))
      (report! "S6" kind n #f 3 ms (/ (* 1000 ms) n) #f #f))))

;;; Command line.
(define args (command-line-arguments))
(define (flag-value name default)
  (let ((m (member name args))) (if (and m (pair? (cdr m))) (cadr m) default)))
(define runs (string->number (flag-value "--runs" "3")))
(define csv-file (flag-value "--csv" "bench/results.csv"))
;; Said before the runs, not after minutes of them.
(let ((dir (pathname-directory csv-file)))
  (when (and dir (not (directory-exists? dir)))
    (error 'bench (sprintf "no directory ~s for the CSV file ~s (run from the repository root, or give --csv FILE)"
                           dir csv-file))))
(define quick? (member "--quick" args))
;; --mode M keeps only that mode: discrete or swept (S1, S3), all-pairs,
;; spatial-hash or flonum (S2: the spatial hash with flonum positions),
;; swept (S5's exact positions) or flonum (S5 with flonum positions).
(define only-mode (let ((m (flag-value "--mode" #f))) (and m (string->symbol m))))
;; --n N keeps only that size of S1 and S2 (and the step table's size).
(define only-n (let ((n (flag-value "--n" #f))) (and n (string->number n))))
;; --warm-up W and --frames F replace the warm-up and timed frame counts of
;; S1, S2 and S5 (for measuring under a profiler; the checksums are then
;; not those of the scenes' definition).
(define only-warm-up (let ((w (flag-value "--warm-up" #f))) (and w (string->number w))))
(define only-frames (let ((f (flag-value "--frames" #f))) (and f (string->number f))))
(define (warm-up default) (or only-warm-up default))
(define (timed default) (or only-frames default))
(define (sizes ns) (if only-n (if (memv only-n ns) (list only-n) '()) ns))
(define (modes ms) (if only-mode (if (memq only-mode ms) (list only-mode) '()) ms))
(define (wanted? s)
  (let ((named (filter-scenes args)))
    (or (null? named) (member s named))))
(define (filter-scenes args)
  (let loop ((as args) (out '()))
    (cond ((null? as) out)
          ((member (car as) '("S1" "S2" "S3" "S4" "S5" "S6" "S7" "steps")) (loop (cdr as) (cons (car as) out)))
          (else (loop (cdr as) out)))))

(when (wanted? "S1")
  (let ((ms (modes '(discrete swept))))
    (unless (null? ms)
      (for-each (lambda (n) (run-s1 n ms runs))
                (sizes (if quick? '(100 1000) '(100 1000 10000 16000)))))))
(when (wanted? "S7")
  (let ((ms (modes '(discrete swept))))
    (unless (null? ms)
      (for-each (lambda (n) (run-s1 n ms runs "S7" s7-scene))
                (sizes (if quick? '(100 1000) '(100 1000 10000)))))))
(when (wanted? "steps")
  (run-s1-steps (or only-n (if quick? 1000 10000)) runs))
(when (wanted? "S2")
  ;; all pairs is quadratic: 5000 would take minutes a frame
  (when (memq 'all-pairs (modes '(all-pairs)))
    (for-each (lambda (n) (run-s2 n 'all-pairs runs)) (sizes (if quick? '(100) '(100 1000)))))
  (when (memq 'spatial-hash (modes '(spatial-hash)))
    (for-each (lambda (n) (run-s2 n 'spatial-hash runs)) (sizes (if quick? '(100) '(100 1000 5000)))))
  (when (memq 'flonum (modes '(flonum)))
    (for-each (lambda (n) (run-s2 n 'flonum runs)) (sizes (if quick? '(100) '(100 1000 5000))))))
(when (wanted? "S3")
  (for-each (lambda (mode)
              (for-each (lambda (v) (run-s3 v mode runs))
                        '(1 8 16 27 28 29 40 64 200 1000 1000000)))
            (modes '(discrete swept))))

(when (wanted? "S4")
  (let* ((bullets (if quick? 500 2000)) (enemies (if quick? 125 500))
         (fast (run-s4 'overlapping-pairs bullets enemies runs))
         (slow (run-s4 'all-pairs bullets enemies runs)))
    (printf "S4 all-pairs / overlapping-pairs: ~a~%" (fixed (/ slow fast) 2))))
(when (wanted? "S5")
  (for-each (lambda (mode)
              (for-each (lambda (n) (run-s5 n mode runs)) (sizes (if quick? '(1000) '(1000 4000 16000)))))
            (modes '(swept flonum))))
(when (wanted? "S6")
  (for-each (lambda (kind)
              (for-each (lambda (n) (run-s6 n kind runs)) (sizes (if quick? '(100) '(100 200 400)))))
            '(exact inexact)))

;; Written last, so every scene run has its row (S4 to S6 included).
(with-output-to-file csv-file
  (lambda ()
    (print "scene,mode,n,speed,frames,ms_per_frame,us_per_entity_frame,tunnel_pct,wrong_pct")
    (for-each print (reverse csv-rows))))
(printf "wrote ~a~%" csv-file)
