;;; A body that starts a frame inside solid tiles (an entity push can leave
;;; it there): swept mode takes it out by the shortest way, so no push
;;; ever carries a body through a wall; discrete mode keeps the plain x
;;; pass (docs/physics.org, "A body that starts a frame inside solid tiles").

(import scheme (chicken base) (chicken format) (chicken process-context) (downstroke test) (downstroke entity)
        (downstroke tilemap) (downstroke scene) (downstroke pipeline) (downstroke util)
        (chicken sort) srfi-4 (only (downstroke tween) make-tween) (only (downstroke physics) *gravity* tile-way-out entity-cell-span)
        (only (downstroke tile-grid) grids) (only (downstroke escape) escape-place straight-in-c search-way-out
                                                      diagonal-in-c diagonal-may-be-nearer?)
        (chicken condition))

(include-relative "../../tests/bounded-support.scm")

(define (es-ent . plist) (plist->entity plist))

;; A closed room: a border of solid tiles around w x h tiles of air.
(define (es-room w h)
  (list->tilemap
   (let rows ((j 0))
     (if (= j (+ h 2)) '()
         (cons (let cols ((i 0))
                 (if (= i (+ w 2)) '()
                     (cons (if (or (= i 0) (= j 0) (= i (+ w 1)) (= j (+ h 1))) 1 0) (cols (+ i 1)))))
               (rows (+ j 1)))))))

;; One frame of `pipeline` for one body; the body's keys after it.
(define (es-frame tm mode body keys #!optional (pipeline engine-pipeline))
  (let ((e (car (scene-entities (pipeline (make-scene tilemap: tm collision-mode: mode
                                                      entities: (list body))
                                          16)))))
    (map (lambda (k) (entity-ref e k)) keys)))

;; Independent of the library's cell arithmetic: whether the box covers a
;; solid tile, pixel row by pixel row (integers and fractions alike).
(define (es-box-solid? tm x y w h)
  (let rows ((py (floor y)))
    (and (< py (+ y h))
         (or (let cols ((px (floor x)))
               (and (< px (+ x w))
                    (or (= 1 (tilemap-tile-at tm (floor (/ px 16)) (floor (/ py 16))))
                        (cols (+ px 1)))))
             (rows (+ py 1))))))

(define xyv '(#:x #:y #:vx #:vy))

(test-group "escape: sunk into a floor, walking 1 px a frame"
  ;; the room's floor top is y 48; the body's bottom is 2 px below it
  (let ((tm (es-room 4 2))
        (body (es-ent #:type 'b #:x 40 #:y 36 #:width 12 #:height 14 #:vx 1 #:gravity? #t)))
    (test "swept: back on the floor, one pixel further on" '(41 34 1 0)
          (es-frame tm 'swept body xyv))
    (test "swept: the readable steps say the same" '(41 34 1 0)
          (es-frame tm 'swept body xyv contract-pipeline))
    (test "discrete: the plain x pass throws it 21 px back" '(20 34 0 0)
          (es-frame tm 'discrete body xyv))))

(test-group "escape: the shortest way, on both axes at once"
  (let ((tm (es-room 4 2)))
    (test "half a pixel into a wall and the floor: out by (1/2, -1/2), then stopped by both" '(16 34 0 0)
          (es-frame tm 'swept (es-ent #:x 31/2 #:y 69/2 #:width 12 #:height 14 #:vx -1 #:gravity? #t) xyv))
    (test "the same with flonums (stops are whole pixels; this corner once threw a body out of the room)" '(16 34 0 0)
          (es-frame tm 'swept (es-ent #:x 15.5 #:y 34.5 #:width 12 #:height 14 #:vx -1 #:gravity? #t) xyv)))
  ;; a 3 x 3 block of solid tiles, 32..80 on both axes, in open air
  (let ((tm (list->tilemap '((0 0 0 0 0 0 0) (0 0 0 0 0 0 0) (0 0 1 1 1 0 0) (0 0 1 1 1 0 0)
                             (0 0 1 1 1 0 0) (0 0 0 0 0 0 0) (0 0 0 0 0 0 0)))))
    (test "in the middle of the block: 28 px every way, so up" '(52 24 0 0)
          (es-frame tm 'swept (es-ent #:x 52 #:y 52 #:width 8 #:height 8 #:vx 0 #:vy 1) xyv))
    (test "a pixel right of the middle: out to the right" '(80 53 0 1)
          (es-frame tm 'swept (es-ent #:x 53 #:y 52 #:width 8 #:height 8 #:vx 0 #:vy 1) xyv))
    (test "a pixel below the middle: out at the bottom" '(52 81 0 1)
          (es-frame tm 'swept (es-ent #:x 52 #:y 53 #:width 8 #:height 8 #:vx 0 #:vy 1) xyv))
    (let ((still (es-ent #:x 52 #:y 52 #:width 8 #:height 8 #:vx 0 #:vy 0)))
      (test "a body at rest is left where it is, as the tile passes leave it" '(52 52 0 0)
            (es-frame tm 'swept still xyv)))
    (test "a body that skips the x tile pass is taken out by the y pass" '(52 24 0 0)
          (es-frame tm 'swept (es-ent #:x 52 #:y 52 #:width 8 #:height 8 #:vx 0 #:vy 1
                                      #:skip-pipelines '(tile-collisions-x))
                    xyv))
    (test "a body that skips both tile passes stays inside" '(52 53 0 1)
          (es-frame tm 'swept (es-ent #:x 52 #:y 52 #:width 8 #:height 8 #:vx 0 #:vy 1
                                      #:skip-pipelines '(tile-collisions-x tile-collisions-y))
                    xyv))))

;; A body pushed a little way into a wall, with no tile edge near its
;; other sides, leaves it by the straight moves alone: the search for a
;; move on both axes at once, and the table of solid cells it reads
;; (slot 4 of the map's grids), are never needed.
(test-group "escape: half a pixel into a wall, out by the straight move alone"
  (for-each
   (lambda (x)
     (let ((tm (es-room 4 2)))
       (test (sprintf "x ~a: out to x 16, then a pixel right" x) (list (+ 16 1) 20 1 0)
             (map (lambda (v) (if (exact? v) v (inexact->exact v)))
                  (es-frame tm 'swept (es-ent #:x x #:y 20 #:width 12 #:height 12 #:vx 1 #:vy 0) xyv)))
       (test (sprintf "x ~a: no table of solid cells was made" x) #f (vector-ref (grids tm) 4))))
   (list 31/2 15.5))
  ;; in a corner the diagonal search runs (and makes the table)
  (let ((tm (es-room 4 2)))
    (test "half a pixel into a wall and the floor: the diagonal way" '(16 34 0 0)
          (es-frame tm 'swept (es-ent #:x 31/2 #:y 69/2 #:width 12 #:height 14 #:vx -1 #:gravity? #t) xyv))
    (test-assert "and it made the table" (vector-ref (grids tm) 4))))

;; Every push a wall, a floor, a ceiling or a corner can receive, less
;; than halfway through a one-tile wall: one swept frame later the body
;; is out of the tiles and inside the room, whatever its velocity.
(test-group "escape: every push into the room's walls, floor, ceiling and corners"
  (let* ((tm (es-room 8 6))               ; air 16..144 x 16..112
         (w 12) (h 14)
         (bad 0) (cases 0)
         (check (lambda (x y vx vy grav)
                  (let* ((after (es-frame tm 'swept (es-ent #:x x #:y y #:width w #:height h
                                                            #:vx vx #:vy vy #:gravity? grav)
                                          '(#:x #:y)))
                         (ax (car after)) (ay (cadr after)))
                    (set! cases (+ cases 1))
                    (unless (and (not (es-box-solid? tm ax ay w h))
                                 (<= 16 ax) (<= (+ ax w) 144) (<= 16 ay) (<= (+ ay h) 112))
                      (set! bad (+ bad 1)))))))
    (do ((d 1 (+ d 1))) ((= d 12))
      (do ((vx -2 (+ vx 1))) ((> vx 2))
        (do ((vy -2 (+ vy 1))) ((> vy 2))
          (for-each
           (lambda (grav)
             ;; (a body whose velocities are both 0 after gravity is at
             ;; rest this frame, and left where it is)
             (unless (and (= vx 0) (= (+ vy (if grav *gravity* 0)) 0))
               (for-each (lambda (p) (check (car p) (cdr p) vx vy grav))
                         (list (cons (- 16 d) 60) (cons (+ 144 (- w) d) 60)       ; walls
                               (cons 70 (- 16 d)) (cons 70 (+ 112 (- h) d))       ; ceiling, floor
                               (cons (- 16 d) (- 16 d)) (cons (+ 144 (- w) d) (- 16 d))
                               (cons (- 16 d) (+ 112 (- h) d)) (cons (+ 144 (- w) d) (+ 112 (- h) d))
                               ;; a quarter pixel in, on both axes
                               (cons (- 16 (/ d 4)) (+ 112 (- h) (/ d 4)))))))
           '(#t #f)))))
    (test-assert (sprintf "~a cases" cases) (> cases 4700))
    (test "every body is out of the tiles, inside the room" 0 bad)))

(test-group "escape: engine-pipeline equals contract-pipeline for bodies that start inside solid tiles"
  ;; random fixnum bodies in random maps, many starting inside solid tiles
  (define seed 20261202)
  (define (rnd n) (set! seed (modulo (+ (* 1103515245 seed) 12345) 2147483648)) (modulo (quotient seed 16) n))
  (let loop ((k 0) (differ 0) (inside 0))
    (if (= k 1500)
        (begin (test-assert "many started inside a solid tile" (> inside 300))
               (test "engine-pipeline equals contract-pipeline on all 1500" 0 differ))
        (let* ((tm (list->tilemap (let rows ((j 0))
                                    (if (= j 10) '()
                                        (cons (let cols ((i 0))
                                                (if (= i 10) '() (cons (if (< (rnd 100) 30) 1 0) (cols (+ i 1)))))
                                              (rows (+ j 1)))))))
               (x (rnd 150)) (y (rnd 150)) (w (+ 1 (rnd 20))) (h (+ 1 (rnd 20)))
               (body (es-ent #:type 'b #:x x #:y y #:width w #:height h
                             #:vx (- (rnd 9) 4) #:vy (- (rnd 9) 4) #:gravity? (even? k)))
               (scene (make-scene tilemap: tm collision-mode: 'swept entities: (list body))))
          (loop (+ k 1)
                (if (equal? (scene-entities (engine-pipeline scene 16))
                            (scene-entities (contract-pipeline scene 16)))
                    differ
                    (+ differ 1))
                (if (es-box-solid? tm x y w h) (+ inside 1) inside))))))

;; The issue's scene, shortened: bodies in a closed room with ledges,
;; walking, jumping and pushing one another. Each frame, no body is more
;; than halfway into a wall (past the middle, the shortest way out is the
;; far side); at the end every body is in the room.
(test-group "escape: a closed room of pushing, jumping bodies"
  (define seed 7)
  (define (rnd n) (set! seed (modulo (+ (* 1103515245 seed) 12345) 2147483648)) (modulo (quotient seed 65536) n))
  (define W 40) (define H 15)
  (define tm (list->tilemap
              (let rows ((j 0))
                (if (= j H) '()
                    (cons (let cols ((i 0))
                            (if (= i W) '()
                                (cons (cond ((or (= i 0) (= i (- W 1)) (= j 0) (= j (- H 1))) 1)
                                            ((and (= j 8) (< 4 i 9)) 1)
                                            ((and (= j 5) (< 11 i 15)) 1)
                                            (else 0))
                                      (cols (+ i 1)))))
                          (rows (+ j 1)))))))
  (define (body k) (es-ent #:type 'b #:x (+ 20 (* 13 k)) #:y 20 #:width 12 #:height 14
                           #:gravity? #t #:solid? #t))
  (define (within-half-wall? e)
    (let ((cx (+ (entity-ref e #:x) 6)) (cy (+ (entity-ref e #:y) 7)))
      (and (< 8 cx (- (* 16 W) 8)) (< 8 cy (- (* 16 H) 8)))))
  (define (in-room? e)
    (let ((x (entity-ref e #:x)) (y (entity-ref e #:y)))
      (and (<= 16 x) (<= (+ x 12) (* 16 (- W 1))) (<= 16 y) (<= (+ y 14) (* 16 (- H 1))))))
  ;; DOWNSTROKE_ROOM_FRAMES=1000000 runs the issue's length
  (define frames (or (string->number (or (get-environment-variable "DOWNSTROKE_ROOM_FRAMES") "")) 4000))
  (let loop ((s (make-scene tilemap: tm entities: (let l ((k 0)) (if (= k 24) '() (cons (body k) (l (+ k 1)))))))
             (f 0) (strays 0))
    (if (< f frames)
        (let* ((s (update-scene
                   s entities:
                   (map (lambda (e)
                          (let* ((e (if (= 0 (rnd 30)) (entity-set e #:vx (- (rnd 5) 2)) e)))
                            (if (and (< f (- frames 200)) (entity-ref e #:on-ground? #f) (= 0 (rnd 40)))
                                (entity-set e #:vy -9)
                                e)))
                        (scene-entities s))))
               (s (engine-pipeline s 16)))
          (loop s (+ f 1) (+ strays (count (lambda (e) (not (within-half-wall? e))) (scene-entities s)))))
        (begin
          (test (sprintf "~a frames, 24 bodies: never halfway into a wall" frames) 0 strays)
          (test "all 24 in the room at the end" 24
                (count in-room? (scene-entities s)))))))

;;; The search for the shortest way out, against the rule as it was first
;;; written: every pair of candidates tried, nearest x first.

;; The rule, written plainly from the public cell functions: the four
;; straight moves, then each pair (dx, dy) of candidate offsets (0, or a
;; side of the box flush with a tile edge, within the best straight
;; move's length), x nearest first, for each x the nearest free y, kept
;; while nearer than the best so far.
(define (es-way-out-by-pairs tm x y w h)
  (let* ((tw (tilemap-tile-width tm)) (th (tilemap-tile-height tm))
         (c-lo (tilemap-origin-col tm)) (c-hi (+ c-lo (tilemap-width tm) -1))
         (r-lo (tilemap-origin-row tm)) (r-hi (+ r-lo (tilemap-height tm) -1)))
    (define (span pos size tile) (call-with-values (lambda () (entity-cell-span pos size tile)) cons))
    ;; a solid cell in line `l` of one axis, across cells a..b
    (define (solid-row? r cs) (let loop ((c (max (car cs) c-lo)))
                                (and (<= c (min (cdr cs) c-hi)) (or (tilemap-solid? tm c r) (loop (+ c 1))))))
    (define (solid-col? c rs) (let loop ((r (max (car rs) r-lo)))
                                (and (<= r (min (cdr rs) r-hi)) (or (tilemap-solid? tm c r) (loop (+ r 1))))))
    ;; the solid line of the box nearest its first (up) or last line
    (define (find-line lines lo hi solid? last?)
      (let ((a (max (car lines) lo)) (b (min (cdr lines) hi)))
        (let loop ((l (if last? b a)))
          (and (<= a l b) (if (solid? l) l (loop (if last? (- l 1) (+ l 1))))))))
    (define (row-block x y last?)
      (let ((cs (span x w tw))) (find-line (span y h th) r-lo r-hi (lambda (r) (solid-row? r cs)) last?)))
    (define (col-block x y last?)
      (let ((rs (span y h th))) (find-line (span x w tw) c-lo c-hi (lambda (c) (solid-col? c rs)) last?)))
    (define (free? x y) (not (row-block x y #t)))
    (define (go-y dir) (let loop ((p y))
                         (let ((l (row-block x p (< dir 0))))
                           (if l (loop (if (< dir 0) (- (* l th) h) (* (+ l 1) th))) (- p y)))))
    (define (go-x dir) (let loop ((p x))
                         (let ((l (col-block p y (< dir 0))))
                           (if l (loop (if (< dir 0) (- (* l tw) w) (* (+ l 1) tw))) (- p x)))))
    (define (n2 m) (+ (* (car m) (car m)) (* (cdr m) (cdr m))))
    (define (offsets pos size tile reach)
      (let loop ((edge (* tile (floor (/ (- pos reach) tile)))) (out (list 0)))
        (let ((edge (if (exact? edge) edge (inexact->exact edge))))
          (if (> edge (+ pos size reach))
              (sort out (lambda (a b) (or (< (abs a) (abs b)) (and (= (abs a) (abs b)) (< a b)))))
              (loop (+ edge tile)
                    (let ((out (if (<= (abs (- edge pos)) reach) (cons (- edge pos) out) out)))
                      (if (<= (abs (- edge size pos)) reach) (cons (- edge size pos) out) out)))))))
    (if (free? x y)
        (list 0 0)
        (let* ((moves (list (cons 0 (go-y -1)) (cons 0 (go-y 1)) (cons (go-x -1) 0) (cons (go-x 1) 0)))
               (best (foldl (lambda (b m) (if (< (n2 m) (n2 b)) m b)) (car moves) (cdr moves)))
               (reach (let* ((v (n2 best)) (v (if (exact? v) (ceiling v) (inexact->exact (ceiling v))))
                             (s (let-values (((s r) (exact-integer-sqrt v))) (if (zero? r) s (+ s 1)))))
                        s))
               (dys (offsets y h th reach)))
          (let try-x ((dxs (offsets x w tw reach)) (best best))
            (if (or (null? dxs) (>= (* (car dxs) (car dxs)) (n2 best)))
                (list (car best) (cdr best))
                (try-x (cdr dxs)
                       (let try-y ((dys dys))
                         (if (null? dys) best
                             (let ((m (cons (car dxs) (car dys))))
                               (cond ((>= (n2 m) (n2 best)) best)
                                     ((free? (+ x (car m)) (+ y (cdr m))) m)
                                     (else (try-y (cdr dys))))))))))))))

(define (es-way-out tm x y w h)
  (call-with-values (lambda () (tile-way-out tm x y w h)) list))

;; A map of the given rows of tile ids (2 is one-way), its first cell at
;; (col0, row0).
(define (es-map rows tw th col0 row0)
  (let* ((h (length rows)) (w (length (car rows))) (data (make-u32vector (* w h) 0)))
    (let loop ((rows rows) (j 0))
      (unless (null? rows)
        (let fill ((cs (car rows)) (i 0))
          (unless (null? cs) (u32vector-set! data (+ (* j w) i) (car cs)) (fill (cdr cs) (+ i 1))))
        (loop (cdr rows) (+ j 1))))
    (make-tilemap w h tw th (list (make-layer "t" w h data)) origin-col: col0 origin-row: row0 one-way: '(2))))

(test-group "escape: the search gives what trying every pair gives"
  (define seed 424242)
  (define (rnd n) (set! seed (modulo (+ (* 1103515245 seed) 12345) 2147483648)) (modulo (quotient seed 16) n))
  (define (pick . xs) (list-ref xs (rnd (length xs))))
  ;; an exact integer, a quarter pixel or a flonum near v
  (define (number-near v) (case (rnd 3) ((0) v) ((1) (+ v (/ (rnd 4) 4))) (else (+ v (/ (rnd 1000) 997.)))))
  (let loop ((k 0) (differ '()) (moved 0) (diagonal 0))
    (if (= k 10000)
        (begin
          (test-assert (sprintf "~a of 10000 boxes moved, ~a both ways" moved diagonal)
                       (and (> moved 3000) (> diagonal 200)))
          (test "no box differs" '() differ))
        (let* ((cols (+ 2 (rnd 10))) (rows (+ 2 (rnd 10)))
               (tw (pick 16 16 8 7 1)) (th (pick 16 16 8 5 3))
               (col0 (pick 0 0 -3 4)) (row0 (pick 0 0 -2 5))
               (kind (rnd 5))
               (tm (es-map (let r ((j 0))
                             (if (= j rows) '()
                                 (cons (let c ((i 0))
                                         (if (= i cols) '()
                                             (cons (case kind
                                                     ((0) (if (< (rnd 100) 30) 1 0))
                                                     ((1 4) (if (< (rnd 100) 85) 1 (pick 0 2)))
                                                     ((2) (if (and (< 0 i (- cols 1)) (< 0 j (- rows 1))) 1 0))
                                                     (else (pick 0 1 1 2)))
                                                   (c (+ i 1)))))
                                       (r (+ j 1)))))
                           tw th col0 row0))
               (w (pick 0 1 (rnd 40) (rnd 40) (* tw (+ 1 (rnd 3))) (+ 0.5 (rnd 30)) (* tw cols (+ 1 (rnd 2)))))
               (h (pick 0 1 (rnd 40) (rnd 40) (* th (+ 1 (rnd 3))) (+ 0.25 (rnd 30)) (* th rows (+ 1 (rnd 2)))))
               (x (number-near (+ (* tw col0) -20 (rnd (+ (* tw cols) 40)))))
               (y (number-near (+ (* th row0) -20 (rnd (+ (* th rows) 40)))))
               (new (es-way-out tm x y w h))
               (old (es-way-out-by-pairs tm x y w h)))
          (loop (+ k 1)
                (if (equal? new old) differ (cons (list x y w h 'new new 'by-pairs old) differ))
                (if (equal? new '(0 0)) moved (+ moved 1))
                (if (and (not (zero? (car new))) (not (zero? (cadr new)))) (+ diagonal 1) diagonal))))))

;; What a frame costs grows with the candidates, not with their pairs,
;; nor with the body's size: eight bodies deep inside a 2000 x 2000
;; block of solid tiles (trying every pair took over 15 s a body), and
;; a body 10^12 px wide across a 3 x 3 map (the candidates along its
;; width alone took hours), one swept frame each, under a limit of 20 s
;; of CPU time. The block is the map, so the only way out is past one of
;; its sides: up for the bodies above its middle, down for the others.
(test-group "escape: the cost of a frame"
  (define n 2000)
  (define side (* 16 n))
  (define c (/ side 2))
  (define bodies (let loop ((i 0))
                   (if (= i 8) '()
                       (cons (list (+ c 7 (* 3 i) (if (odd? i) 1/4 0))
                                   (if (< i 4) (- c 40 (* 5 i)) (+ c 40 (* 5 i)))
                                   (+ 12 i) (+ 14 i))
                             (loop (+ i 1))))))
  (define results
    (bounded-run
     20
     `((import scheme (chicken base) srfi-4 (downstroke tilemap) (downstroke scene)
               (downstroke pipeline) (downstroke entity))
       (define (frame tm bodies)
         (map (lambda (e) (list (entity-ref e #:x) (entity-ref e #:y)))
              (scene-entities (engine-pipeline (make-scene tilemap: tm collision-mode: 'swept entities: bodies)
                                               16))))
       (define (body x y w h vx) (list (cons #:x x) (cons #:y y) (cons #:width w) (cons #:height h)
                                       (cons #:vx vx) (cons #:vy 0)))
       (write (list "block"
                    (frame (make-tilemap ,n ,n 16 16 (list (make-layer "solid" ,n ,n (make-u32vector ,(* n n) 1))))
                           (map (lambda (b) (apply body (append b '(1)))) ',bodies))))
       (newline)
       (write (list "wide"
                    (frame (list->tilemap '((1 1 1) (1 0 1) (1 1 1)) tile-width: 32 tile-height: 32)
                           (list (body ,(- (expt 10 11) (expt 10 12)) 40 ,(expt 10 12) 100 4)))))
       (newline)
       (write (list "wide flonum"
                    (frame (list->tilemap '((1 1 1) (1 0 1) (1 1 1)) tile-width: 32 tile-height: 32)
                           (list (body -9e11 40 1e12 100 4)))))
       (newline))))
  (test "each body out of the block by its nearest side, then 1 px right"
        (map (lambda (b)
               (let ((x (car b)) (y (cadr b)) (h (cadddr b)))
                 (list (+ x 1) (if (< (+ y h) (- side y)) (- h) side))))
              bodies)
        (bounded-result results "block"))
  (test "the wide body out below the map (56 px down), then 4 px right"
        (list (list (+ (- (expt 10 11) (expt 10 12)) 4) 96))
        (bounded-result results "wide"))
  (test "the same body in flonums (1e12 x 100): the same way out" (list (list (+ -9e11 4) 96))
        (bounded-result results "wide flonum")))

;;; Flonums: where the escape puts a body, and where that frame's sweep
;;; starts (docs/physics.org, "A body that starts a frame inside solid
;;; tiles").

(test-group "escape: flonum rounding never leaves a body inside, nor restarts its sweep elsewhere"
  ;; 16 px tiles: a floor in row 1 (y 16 to 32), four columns wide
  (define floor-map (list->tilemap '((0 0 0 0) (1 1 1 1) (0 0 0 0))))
  ;; sunk into the floor: up by 22.72 is nearest, and -19.2 + 176/5 rounds
  ;; to a hair below 16 only if the move is computed with care
  (test "out of the floor by the top, then on along x: x 51/2 (the escape's box is clear of row 1)"
        '(51/2 -96/5 5/2 0)
        (es-frame floor-map 'swept (es-ent #:x 23 #:y 3.52 #:width 16 #:height 176/5 #:vx 5/2 #:vy 2
                                           #:gravity? #t)
                  xyv))
  (test "the same with the readable steps" '(51/2 -96/5 5/2 0)
        (es-frame floor-map 'swept (es-ent #:x 23 #:y 3.52 #:width 16 #:height 176/5 #:vx 5/2 #:vy 2
                                           #:gravity? #t)
                  xyv contract-pipeline))
  (test "tile-way-out's box covers no solid tile, by the tiles' own arithmetic" #f
        (let-values (((dx dy) (tile-way-out floor-map 23 3.52 16 176/5)))
          (let-values (((r0 r1) (entity-cell-span (+ 3.52 dy) 176/5 16)))
            (and (<= r0 1 r1) (list dx dy)))))
  ;; 8 px tiles, row 5 (y 40 to 48) solid: a zero-width body 3.52 px into
  ;; column 1 goes out left to x 8, then its sweep from x 8 meets column 1
  (let ((tm (list->tilemap '((0 0 0 0 0 0) (0 0 0 0 0 0) (0 0 0 0 0 0) (0 0 0 0 0 0) (0 0 0 0 0 0)
                             (1 1 1 1 1 1) (0 0 0 0 0 0) (0 0 0 0 0 0) (0 0 0 0 0 0))
                           tile-width: 8 tile-height: 8)))
    (test "a zero-width body escapes to x 8 and its sweep starts there: stopped at x 8" '(8 44.28 0 16.25)
          (es-frame tm 'swept (es-ent #:x 11.52 #:y 28.03 #:width 0 #:height 25.528 #:vx 14.882 #:vy 16.25)
                    xyv))))

(test-group "escape: ties, starts, tweens"
  ;; a 3 x 3 block of solid tiles, 32..80 on both axes, in open air
  (define block (list->tilemap '((0 0 0 0 0 0 0) (0 0 0 0 0 0 0) (0 0 1 1 1 0 0) (0 0 1 1 1 0 0)
                                 (0 0 1 1 1 0 0) (0 0 0 0 0 0 0) (0 0 0 0 0 0 0))))
  ;; 8 px tiles, a 5 x 5 solid map with holes (0) at the given cells
  (define (holes . cells)
    (list->tilemap (let rows ((j 0))
                     (if (= j 5) '()
                         (cons (let cols ((i 0))
                                 (if (= i 5) '()
                                     (cons (if (member (cons i j) cells) 0 1) (cols (+ i 1)))))
                               (rows (+ j 1)))))
                   tile-width: 8 tile-height: 8))
  ;; the box 8 x 8 at (16, 12) covers column 2, rows 1 and 2; the holes
  ;; up-left and up-right are both (8, 4) away
  (test "equal diagonal moves: leftward before rightward" '(-8 -4)
        (es-way-out (holes '(1 . 1) '(3 . 1)) 16 12 8 8))
  ;; the box 8 x 8 at (12, 16): the holes up-left and down-left are both (4, 8) away
  (test "equal diagonal moves with the same sideways part: upward before downward" '(-4 -8)
        (es-way-out (holes '(1 . 1) '(1 . 3)) 12 16 8 8))
  (test "a body that skips the x tile pass leaves the tiles from where its frame began, (x - vx, y - vy)"
        '(88 53 8 1)
        (es-frame block 'swept (es-ent #:x 76 #:y 52 #:width 8 #:height 8 #:vx 8 #:vy 1
                                       #:skip-pipelines '(tile-collisions-x))
                  xyv))
  (test "a body with a #:tween is not taken out of the tiles: the tile passes resolve it" '(40 40 0 0)
        (es-frame block 'swept (es-ent #:x 52 #:y 52 #:width 8 #:height 8 #:vx 4 #:vy 1
                                       #:tween (make-tween (list (cons #:z 0)) props: '((#:z . 10)) duration: 160))
                  xyv))
  (test "its tile passes still sweep: at 60 px/frame it stops at the block" '(24 36 0 0)
        (es-frame block 'swept (es-ent #:x 0 #:y 36 #:width 8 #:height 8 #:vx 60 #:vy 0
                                       #:tween (make-tween (list (cons #:z 0)) props: '((#:z . 10)) duration: 160))
                  xyv))
  (test "a tweened box inside column 1 whose right edge is on the grid line leaves it forward" '(32 52 4 0)
        ;; from x 28 (4 wide, in solid column 1) at 4 px/frame: its leading
        ;; edge starts on line 32, in column 2, so the sweep starts there
        ;; as the discrete step does, and column 1 does not throw it back
        (es-frame (list->tilemap '((0 0 0 0 0) (0 0 0 0 0) (0 0 0 0 0) (0 1 0 0 0)))
                  'swept (es-ent #:x 28 #:y 52 #:width 4 #:height 8 #:vx 4 #:vy 0
                                 #:tween (make-tween (list (cons #:z 0)) props: '((#:z . 10)) duration: 160))
                  xyv)))

;;; The first part of the search in C (escape.c): whether the box is free
;;; and which straight move wins. Wherever it answers, the escape must
;;; give exactly what the Scheme search gives (the same move, the same
;;; numbers, exact or flonum alike); where it cannot take the numbers it
;;; declines (#f) and the Scheme search answers.

;; whether fixnums are 64-bit, read at run time (a literal would be
;; folded by the compiler of a cross build)
(define es-wide-fixnums? (fixnum? (string->number "1099511627776")))

;; escape-place's answer with escape.c or without, or 'error
(define (es-place tm x y w h c?)
  (condition-case (call-with-values (lambda () (escape-place tm x y w h c?)) list)
    (e () 'error)))
(define (es-search tm x y w h c?)
  (condition-case (call-with-values (lambda () (search-way-out tm x y w h c?)) list)
    (e () 'error)))

(test-group "escape in C: the same answer as the Scheme search, on random boxes in and near solid tiles"
  (define seed 2929)
  (define (rnd n) (set! seed (modulo (+ (* 1103515245 seed) 12345) 2147483648)) (modulo (quotient seed 16) n))
  (define (pick . xs) (list-ref xs (rnd (length xs))))
  (define specials (list +nan.0 +inf.0 -inf.0 1.7e308 -1.7e308 4503599627370496. 9007199254740992.
                         4503599627370496 9007199254740992 16777215 16777216 -16777215 1e-300 -0.0))
  ;; a number near v: an integer, a quarter pixel, a flonum, a rational
  ;; with a long denominator, a flonum that ends on a pixel, or a rare
  ;; special one
  (define (number-near v)
    (case (rnd 12)
      ((0 1 2) v)
      ((3) (+ v (/ (rnd 4) 4)))
      ((4 5 6) (+ v (/ (rnd 1000) 997.)))
      ((7) (+ v (/ (rnd 1000) (+ 1 (expt 2 (+ 3 (rnd 52)))))))
      ((8) (exact->inexact v))
      ((9) (+ v (/ (rnd 7) 7)))
      ((10) (+ v (* 1e-13 (- (rnd 3) 1))))
      (else (if (= 0 (rnd 8)) (list-ref specials (rnd (length specials))) v))))
  ;; flonum sizes are eighths: with a size that rounds (12.0431...), a
  ;; move up to a line's top less the size can round back into that line,
  ;; and the Scheme search then never ends (escape.c gives up after a
  ;; bounded number of steps and declines)
  (define (size-near v) (case (rnd 4) ((0 1) v) ((2) (+ v (/ (rnd 8) 8.))) (else (exact->inexact v))))
  (let loop ((k 0) (differ '()) (taken 0) (moved 0) (declined 0))
    (if (= k 6000)
        (begin
          (test-assert (sprintf "escape.c took ~a of 6000 boxes (~a of them moved), declined ~a" taken moved declined)
                       (and (> taken 3000) (> moved 1500) (> declined 100)))
          (test "no box differs, by search-way-out or escape-place" '() differ))
        (let* ((cols (+ 1 (rnd 12))) (rows (+ 1 (rnd 12)))
               (tw (pick 16 16 8 7 1 3)) (th (pick 16 16 8 5 3 1))
               (col0 (pick 0 0 -3 4)) (row0 (pick 0 0 -2 5))
               (fill (pick 2 3 5 8))
               (tm (es-map (let r ((j 0))
                             (if (= j rows) '()
                                 (cons (let c ((i 0))
                                         (if (= i cols) '()
                                             (cons (case (rnd fill) ((0 1) 1) ((2) (if (= 0 (rnd 4)) 2 0)) (else 0))
                                                   (c (+ i 1)))))
                                       (r (+ j 1)))))
                           tw th col0 row0))
               (w (size-near (pick 0 1 (rnd (* 3 tw)) tw (* 2 tw) (rnd 40))))
               (h (size-near (pick 0 1 (rnd (* 3 th)) th (* 2 th) (rnd 40))))
               (x (number-near (+ (* col0 tw) (- (rnd (* (+ cols 3) tw)) (* 2 tw)))))
               (y (number-near (+ (* row0 th) (- (rnd (* (+ rows 3) th)) (* 2 th)))))
               (known (condition-case (straight-in-c tm x y w h #t) (e () 'error)))
               (c-way (es-search tm x y w h #t)) (s-way (es-search tm x y w h #f))
               (c-place (es-place tm x y w h #t)) (s-place (es-place tm x y w h #f)))
          (loop (+ k 1)
                (if (and (equal? c-way s-way) (equal? c-place s-place))
                    differ
                    (cons (list 'map tw th col0 row0 'box x y w h 'c c-way c-place 'scheme s-way s-place) differ))
                (if (or (eq? known #t) (fixnum? known)) (+ taken 1) taken)
                (if (fixnum? known) (+ moved 1) moved)
                (if known declined (+ declined 1)))))))

(test-group "escape in C: what it takes and what it leaves to the Scheme search"
  ;; 16 px tiles: a floor in row 1 (y 16 to 32), four columns wide
  (define floor-map (list->tilemap '((0 0 0 0) (1 1 1 1) (0 0 0 0))))
  (define (c x y w h) (straight-in-c floor-map x y w h #t))
  ;; a box 10 x 10 at (20, 18), inside the floor: 12 px below its top,
  ;; 14 above its bottom: up (runner 0), ended by row 1
  (test "integers: up, ended by row 1" (+ (* 4 1) 0) (c 20 18 10 10))
  (test "the move is exact" '(0 -12) (es-way-out floor-map 20 18 10 10))
  (test "flonums: the same race" (+ (* 4 1) 0) (c 20.5 18.25 10 10.))
  (test "the move is a flonum" '(0 -12.25) (es-way-out floor-map 20.5 18.25 10 10.))
  (test "2 px lower, down is nearer: runner 1, ended by row 1" (+ (* 4 1) 1) (c 20 20 10 10))
  (test "a box in no solid tile: #t" #t (c 20 0 10 10))
  (test "race? #f: 0 for a box in a solid tile" 0 (straight-in-c floor-map 20 20 10 10 #f))
  (test "a rational of fixnums on a 64-bit build, else left to Scheme"
        (if es-wide-fixnums? 4 #f) (c 20 37/2 10 10))
  (test "the move is exact" '(0 -25/2) (es-way-out floor-map 20 37/2 10 10))
  (test "a rational with a flonum: left to Scheme" #f (c 20.5 37/2 10 10))
  (test "a rational whose denominator is 2^48 or more: left to Scheme" #f
        (c 20 (+ 20 (/ 1 (expt 2 48))) 10 10))
  (test "a bignum rational: left to Scheme" #f (c 20 (+ 20 (/ 1 (expt 3 70))) 10 10))
  (test "a NaN: left to Scheme" #f (c +nan.0 20 10 10))
  (test "an infinity: left to Scheme" #f (c 20 -inf.0 10 10))
  (test "a size that is an infinity: left to Scheme" #f (c 20 20 +inf.0 10))
  (test "a negative size: left to Scheme" #f (c 20 20 -1 10))
  (test "an integer of 2^24 or more: left to Scheme" #f (c 16777216 20 10 10))
  (test "a bignum: left to Scheme" #f (c (expt 2 80) 20 10 10))
  (test "1.7e308, far outside the map: free" #t (c 1.7e308 20 10 10))
  (test "a size of 1.7e308 across the floor: up" (+ (* 4 1) 0) (c 20 18 1.7e308 10))
  (test "not a number: left to Scheme" #f (c 'a 20 10 10))
  (test "a map too large for its numbers: left to Scheme" #f
        (straight-in-c (es-map '((1 1) (1 1)) 16 16 (expt 2 21) 0) 0 0 10 10 #t)))

;; The motion kernel takes a body out of solid tiles itself when the
;; search ends with a straight move (physics/motion.c, ds_flo_escape); it
;; asks escape.c whether a move on both axes could be nearer, which must
;; be diagonal-may-be-nearer?'s answer exactly: a wrong "no" would keep a
;; straight move where the search finds a nearer one. Random straight
;; moves and boxes, sides on tile edges, a double off them, and moves
;; exactly as long as the way to an edge, or a rounding either side.
(test-group "escape in C: diagonal-may-be-nearer? on random boxes"
  (define seed 52929)
  (define (rnd n) (set! seed (modulo (+ (* 1103515245 seed) 12345) 2147483648)) (modulo (quotient seed 16) n))
  (define (pick . xs) (list-ref xs (rnd (length xs))))
  (define (off v)                       ; v, or a little way off it
    (case (rnd 10)
      ((0 1 2 3) v)
      ((4) (exact->inexact v))
      ((5) (+ v (/ (rnd 1000) 997.)))
      ((6) (+ v (* (max 1 (abs v)) 2.3e-16 (pick 1 -1))))
      ((7) (+ v (* 1e-10 (pick 1 -1 3 -3))))
      ((8) (+ v (* (+ 1 (abs v)) 1e-9 (pick 1 -1))))
      (else (pick +nan.0 +inf.0 -0.0 4503599627370496. 9007199254740992. 16777215 16777216 -16777215
                  1.7e308 (+ v 1/2)))))
  (let loop ((k 0) (differ '()) (taken 0) (yes 0))
    (if (= k 20000)
        (begin
          (test-assert (sprintf "escape.c answered ~a of 20000 (~a yes)" taken yes)
                       (and (> taken 12000) (> yes 3000) (> (- taken yes) 3000)))
          (test "no answer differs" '() differ))
        (let* ((tw (pick 16 16 8 7 1 3 12)) (th (pick 16 16 8 5 3 1 12))
               (w (pick 0 1 (rnd 40) tw (* 2 tw) 12 12.0 (+ 12 (/ (rnd 8) 8.))))
               (h (pick 0 1 (rnd 40) th (* 2 th) 12 12.0 (+ 12 (/ (rnd 8) 8.))))
               (x (off (+ (* tw (- (rnd 40) 20)) (pick 0 0 (rnd tw) (- (rnd tw))))))
               (y (off (+ (* th (- (rnd 40) 20)) (pick 0 0 (rnd th) (- (rnd th))))))
               ;; as long as the way from a side to a tile edge, or random
               (to-edge (lambda (side tile) (- (* tile (+ (floor (/ side tile)) (pick 0 1 2 -1))) side)))
               (len (off (pick (rnd 40) (/ (rnd 400) 10.)
                               (if (and (exact? x) (exact? w)) (to-edge (pick x (+ x w)) tw) (rnd 20))
                               (if (and (exact? y) (exact? h)) (to-edge (pick y (+ y h)) th) (rnd 20)))))
               (best (if (= 0 (rnd 2)) (cons 0 (pick len (- len))) (cons (pick len (- len)) 0)))
               (c (condition-case (diagonal-in-c best x y w h tw th) (e () 'error)))
               (s (condition-case (if (diagonal-may-be-nearer? best x y w h tw th) 1 0) (e () 'error))))
          (loop (+ k 1)
                (if (or (not c) (equal? c s)) differ (cons (list best x y w h tw th 'c c 'scheme s) differ))
                (if c (+ taken 1) taken)
                (if (eqv? c 1) (+ yes 1) yes))))))
