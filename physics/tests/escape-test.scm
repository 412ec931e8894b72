;;; A body that starts a frame inside solid tiles (an entity push can leave
;;; it there): swept mode takes it out by the shortest way, so no push
;;; ever carries a body through a wall; discrete mode keeps the plain x
;;; pass (docs/physics.org, "A body that starts a frame inside solid tiles").

(import scheme (chicken base) (chicken format) (chicken process-context) (downstroke test) (downstroke entity)
        (downstroke tilemap) (downstroke scene) (downstroke pipeline) (downstroke util)
        (only (downstroke physics) *gravity*))

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

(test-group "escape: the kernel leaves such bodies to the readable steps"
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
