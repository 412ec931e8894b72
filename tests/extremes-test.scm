;;; The library at numerical extremes: tiny and huge speeds, huge and
;;; negative coordinates, zero-size bodies, non-finite numbers, very long
;;; runs. Exact assertions; documented in docs/performance.org.

(import scheme (chicken base) (chicken gc) (chicken string) (chicken format) (chicken file)
        (chicken pathname) srfi-4
        (downstroke test) (downstroke entity) (downstroke tilemap) (downstroke tween)
        (downstroke scene) (downstroke physics) (downstroke engine) (downstroke pipeline))

;; Bad entities are made here on purpose; their warnings would only be noise.
(scene-checks #f)

(define (ex-ent . plist) (plist->entity plist))

;; The S3 corridor: 400 x 4 tiles, column 300 solid (faces at 4800, 4816).
(define ex-corridor
  (list->tilemap
   (let rows ((j 0))
     (if (= j 4) '()
         (cons (let cols ((i 0)) (if (= i 400) '() (cons (if (= i 300) 1 0) (cols (+ i 1)))))
               (rows (+ j 1)))))))

;; A 20 x 15 room with a floor on the last row (top at y = 224).
(define ex-room
  (list->tilemap
   (let rows ((j 0))
     (if (= j 15) '()
         (cons (let cols ((i 0)) (if (= i 20) '() (cons (if (or (= j 14) (= i 0) (= i 19)) 1 0) (cols (+ i 1)))))
               (rows (+ j 1)))))))

(define (ex-run scene frames)
  (if (= frames 0) scene (ex-run (engine-pipeline scene 16) (- frames 1))))

(define (ex-first scene) (car (scene-entities scene)))

(define (ex-mover mode x v)
  (make-scene tilemap: ex-corridor collision-mode: mode
              entities: (list (ex-ent #:x x #:y 16 #:width 12 #:height 12 #:vx v))))

(test-group "speeds from 1e-9 to 1e6 px/frame"
  (for-each
   (lambda (mode speeds)
     (for-each
      (lambda (v)
        (test (sprintf "~a: flush against the wall at v = ~a stays flush" mode v)
              '(4788 0)
              (let ((e (ex-first (ex-run (ex-mover mode 4788 v) 3))))
                (list (entity-ref e #:x) (entity-ref e #:vx)))))
      speeds))
   '(discrete swept)
   ;; discrete is only asked below its safe speed (see below)
   '((1e-9 1/1000000000 1e-3 1 27) (1e-9 1/1000000000 1e-3 1 27 1000 1e6 1e9)))
  (test "an exact 1e-9 px/frame moves exactly 1e-6 px in 1000 frames" 1000001/1000000
        (entity-ref (ex-first (ex-run (ex-mover 'swept 1 1/1000000000) 1000)) #:x))
  (for-each
   (lambda (v)
     (test (sprintf "swept from far away at v = ~a stops on the wall" v) 4788
           (entity-ref (ex-first (ex-run (ex-mover 'swept 16 v) (+ 2 (ceiling (/ 4800 v))))) #:x)))
   '(1e-3 0.5 27 28 1000 1e6 1e9))
  ;; Discrete is exact below the safe speed, from every quarter-pixel start.
  (let ((wrong 0))
    (do ((x 4700 (+ x 1/4))) ((> x 4788))
      (for-each (lambda (v)
                  (unless (= 4788 (entity-ref (ex-first (ex-run (ex-mover 'discrete x v) (+ 2 (ceiling (/ (- 4816 x) v))))) #:x))
                    (set! wrong (+ wrong 1))))
                '(1 13 27 55/2)))
    (test "discrete below size + tile (28 px/frame) never tunnels" 0 wrong))
  ;; At and above the safe speed, discrete tunnels exactly where
  ;; docs/physics.org says: when its last position short of the wall
  ;; (x + 12 <= 4800) is one frame's move or less from the far face (4816).
  ;; Everywhere else it stops flush, as swept does.
  (for-each
   (lambda (v)
     (let loop ((x 4500) (unexpected 0) (tunnelled 0))
       (if (> x 4788)
           (begin
             (test (sprintf "discrete at v = ~a tunnels exactly where predicted" v) 0 unexpected)
             (test-assert (sprintf "... which happens at v = ~a" v) (> tunnelled 0)))
           (let* ((last (+ x (* v (floor (/ (- 4788 x) v)))))
                  (predicted (>= (+ last v) 4816))
                  (fx (entity-ref (ex-first (ex-run (ex-mover 'discrete x v) (+ 2 (ceiling (/ (- 4816 x) v)))))
                                  #:x))
                  (ok (if predicted (>= fx 4816) (= fx 4788))))
             (loop (+ x 1/4) (if ok unexpected (+ unexpected 1))
                   (if predicted (+ tunnelled 1) tunnelled))))))
   '(28 29 40 64 200 1000))
  (test "the safe speed of a 12 px body against 16 px tiles" 28 (discrete-safe-speed 12 16))
  (test-assert "tunnel-risk? at the safe speed in discrete mode"
               (tunnel-risk? (ex-mover 'discrete 16 28) (ex-first (ex-mover 'discrete 16 28))))
  (test-assert "no tunnel risk just below it"
               (not (tunnel-risk? (ex-mover 'discrete 16 27) (ex-first (ex-mover 'discrete 16 27)))))
  (test-assert "no tunnel risk in swept mode"
               (not (tunnel-risk? (ex-mover 'swept 16 1e6) (ex-first (ex-mover 'swept 16 1e6))))))

(test-group "huge and negative coordinates"
  (test "fixnum coordinates around 1e9 stay exact" 1000000001
        (entity-ref (ex-first (ex-run (ex-mover 'discrete 1000000000 1) 1)) #:x))
  (test "beyond 2^62 (bignums) stays exact" (+ (expt 2 70) 3)
        (entity-ref (ex-first (ex-run (ex-mover 'swept (expt 2 70) 1) 3)) #:x))
  (test "a flonum beyond 2^53 cannot move by 1 px (IEEE spacing is 2)" 9007199254740992.0
        (entity-ref (ex-first (ex-run (ex-mover 'discrete 9007199254740992.0 1) 1)) #:x))
  (test "a body from -1e9 crossing the whole map at 2e9 px/frame stops on the wall" 4788
        (entity-ref (ex-first (ex-run (ex-mover 'swept -1000000000 2000000000) 1)) #:x))
  (test "far outside the map there is nothing to hit" (+ 1e15 1e6)
        (entity-ref (ex-first (ex-run (ex-mover 'swept 1e15 1e6) 1)) #:x))
  (test "negative coordinates move with exact floor cells" -101
        (entity-ref (ex-first (ex-run (ex-mover 'discrete -100 -1/3) 3)) #:x)))

(test-group "zero-width and zero-height bodies"
  ;; A zero-size body covers the cell it lies in, and no cell when it lies
  ;; on a cell edge (docs/physics.org).
  (let ((s (make-scene tilemap: ex-corridor)))
    (test "zero width inside the wall's column is pushed out" '(4800 0)
          (let ((e (resolve-tile-collisions-x s (ex-ent #:x 4805 #:y 16 #:width 0 #:height 12 #:vx 5) 16)))
            (list (entity-ref e #:x) (entity-ref e #:vx))))
    (test "zero width on the wall's face touches nothing" '(4800 5)
          (let ((e (resolve-tile-collisions-x s (ex-ent #:x 4800 #:y 16 #:width 0 #:height 12 #:vx 5) 16)))
            (list (entity-ref e #:x) (entity-ref e #:vx))))
    (test "swept: a zero-width body cannot pass the wall" 4800
          (entity-ref (ex-first (ex-run (make-scene tilemap: ex-corridor collision-mode: 'swept
                                                    entities: (list (ex-ent #:x 16 #:y 16 #:width 0
                                                                            #:height 12 #:vx 1000)))
                                        6))
                      #:x)))
  (let ((s (ex-run (make-scene tilemap: ex-room
                               entities: (list (ex-ent #:x 40 #:y 0 #:width 0 #:height 0 #:gravity? #t)))
                   60)))
    (test "a zero-size body falls onto the floor and rests on it" '(224 #t)
          (list (entity-ref (ex-first s) #:y) (entity-ref (ex-first s) #:on-ground?))))
  (test-assert "zero-size boxes overlap only strictly inside" (aabb-overlap? 5 5 0 0 0 0 10 10))
  (test-assert "... not on an edge" (not (aabb-overlap? 10 5 0 0 0 0 10 10))))

(test-group "non-finite numbers are refused, naming the key"
  (for-each
   (lambda (key)
     (for-each
      (lambda (bad)
        (let ((scene (make-scene tilemap: ex-room
                                 entities: (list (entity-set (ex-ent #:type 'crate #:x 40 #:y 40 #:width 16
                                                                     #:height 16 #:vx 1 #:vy 1 #:ay 0
                                                                     #:gravity? #t)
                                                             key bad)))))
          (test-error (sprintf "~s = ~s" key bad)
                      (lambda (exn) (and (substring-index (sprintf "~s" key) (error-text exn))
                                         (substring-index "crate" (error-text exn))))
                      (engine-pipeline scene 16))))
      (list +nan.0 +inf.0 -inf.0 "12")))
   '(#:x #:y #:width #:height #:vx #:vy #:ay)))

(test-group "the pair pass refuses non-finite numbers too, naming the key"
  ;; resolve-entity-collisions reads boxes on its own path (all four
  ;; numbers checked at once); each method must still name what is wrong.
  (for-each
   (lambda (method)
     (for-each
      (lambda (key)
        (let ((crowd (cons (entity-set (ex-ent #:type 'crate #:x 40 #:y 40 #:width 16 #:height 16
                                               #:solid? #t)
                                       key +nan.0)
                           (let more ((k 0))
                             (if (= k 40) '()
                                 (cons (ex-ent #:type 'box #:x (* 3 k) #:y 45 #:width 16 #:height 16
                                               #:solid? #t)
                                       (more (+ k 1))))))))
          (test-error (sprintf "~s ~s = +nan.0" method key)
                      (lambda (exn) (and (substring-index (sprintf "~s" key) (error-text exn))
                                         (substring-index "crate" (error-text exn))))
                      (resolve-entity-collisions crowd method))))
      '(#:x #:y #:width #:height)))
   '(all-pairs spatial-hash)))

;; Each number here is finite; what overflows is a sum, a product or a
;; quotient made later. Each is refused where it enters, naming where it
;; came from, or computed as its true value. (The drawing cases are in
;; sprites-test.scm, renderer-test.scm and sdl2-test.scm.)
(define (ex-message thunk)
  (handle-exceptions exn (error-text exn) (thunk) "no error"))

(define (ex-says? text . parts)
  (let loop ((ps parts)) (or (null? ps) (and (substring-index (car ps) text) (loop (cdr ps))))))

(test-group "finite values that overflow later: tweens"
  ;; (x active?) after stepping a tween of e's #:x by each dt of dts
  (define (x-after e dts . options)
    (let loop ((t (apply make-tween e options)) (e e) (dts dts))
      (if (null? dts)
          (list (entity-ref e #:x) (tween-active? t))
          (receive (t e) (tween-step t e (car dts)) (loop t e (cdr dts))))))
  (define star (ex-ent #:type 'star #:x 0))
  ;; 16 ms hold 2^1078 runs of 5e-324 (= 2^-1074) ms: 16 / 5e-324 is +inf.0
  ;; (a step that ends runs shows the last one's end; a step of 0 after it
  ;; shows where the clock is)
  (test "a run of 5e-324 ms repeating forever, stepped 16 ms twice: 2^1078 whole runs each, x back at its start, still running"
        '(0 #t) (x-after star '(16 16 0) props: '((#:x . 10)) duration: 5e-324 repeat: -1))
  (test "the step that ends those runs shows the end of the last one" '(10 #t)
        (x-after star '(16 16) props: '((#:x . 10)) duration: 5e-324 repeat: -1))
  (test "with yoyo?, 2^52 + 1 runs of 5e-324 ms (counted exactly) end on a backward run, at the target"
        '(10 #t) (x-after star (list (* (+ (expt 2 52) 1) 5e-324)) props: '((#:x . 10)) duration: 5e-324
                          repeat: -1 yoyo?: #t))
  ;; 2^-1020 ms is 2^54 units of 5e-324: 6004799503160661 runs of 3 units, 1 unit left
  (test "runs counted beyond 2^52 leave the exact remainder: a third of a run" (/ 10. 3)
        (car (x-after star (list (expt 2. -1020) 0) props: '((#:x . 10)) duration: (* 3 5e-324) repeat: -1)))
  (let ((far (ex-ent #:type 'star #:x -1e308)))
    (test "a tween of #:x from -1e308 to 1e308: halfway is 0, not +inf.0" '(0. #t)
          (x-after far '(50) props: '((#:x . 1e308)) duration: 100))
    (test "a quarter of the way is -5e307" '(-5e307 #t)
          (x-after far '(25) props: '((#:x . 1e308)) duration: 100))
    (test "the end is the target exactly" '(1e308 #f)
          (x-after far '(100) props: '((#:x . 1e308)) duration: 100)))
  (test "exact ends still give exact values on the way" '(5/2 #t)
        (x-after star '(25) props: '((#:x . 10)) duration: 100))
  (test-assert "an easing that overshoots past the largest flonum is an error naming the entity and the key"
               (ex-says? (ex-message (lambda () (x-after (ex-ent #:type 'star #:id 7 #:x 0) '(75)
                                                         props: '((#:x . 1.5e308)) duration: 100
                                                         ease: (lambda (u) (* 2 u)))))
                         "entity star 7" "#:x" "1.5e+308" "not a finite number")))

(test-group "finite values that overflow later: the camera"
  (test "make-camera zoom: +inf.0 is refused, naming the keyword"
        "make-camera: zoom: +inf.0 must be a positive finite number"
        (ex-message (lambda () (make-camera zoom: +inf.0))))
  (test "a zoom beyond SDL's float scale is refused too"
        "make-camera: zoom: 1e+300 must be from 1/64 to 64"
        (ex-message (lambda () (make-camera zoom: 1e300))))
  (test "NaN bounds are refused"
        "make-camera: bounds: (0 +nan.0 320 240) must be 'map, #f or (x y width height) of finite numbers"
        (ex-message (lambda () (make-camera bounds: (list 0 +nan.0 320 240)))))
  (test "an infinite position is refused"
        "make-camera: x: -inf.0 must be a finite number"
        (ex-message (lambda () (make-camera x: -inf.0))))
  (test "camera-shake of +inf.0 is refused"
        "camera-shake: amplitude +inf.0 must be a positive finite number"
        (ex-message (lambda () (camera-shake (make-camera) +inf.0))))
  (test "a shake of 1e308 plays out: the camera is drawn from whole pixels, then settles" '(#t 0)
        (let loop ((c (camera-shake (make-camera bounds: #f) 1e308)) (f 0) (whole? #t))
          (if (camera-shaking? c)
              (let ((c (camera-follow c #f 320 240 #f)))
                (loop c (+ f 1) (and whole? (exact-integer? (camera-x c)))))
              (list whole? (camera-x (camera-follow c #f 320 240 #f))))))
  (test-assert "following a target whose #:x is NaN names the target and the key"
               (ex-says? (ex-message (lambda () (camera-follow (make-camera) (ex-ent #:type 'hero #:x +nan.0) 320 240 #f)))
                         "entity hero" "#:x" "+nan.0"))
  (test-assert "a target whose centre is past the largest flonum names the target"
               (ex-says? (ex-message (lambda () (camera-follow (make-camera bounds: #f)
                                                               (ex-ent #:type 'hero #:x 1.7e308 #:width 1e308)
                                                               320 240 #f)))
                         "camera-follow" "entity hero" "x")))

(test-group "finite values that overflow later: maps"
  (let* ((dir (create-temporary-directory))
         (write-map (lambda (name group-attrs layer-attrs)
                      (let ((path (make-pathname dir name)))
                        (with-output-to-file path
                          (lambda ()
                            (print "<?xml version=\"1.0\"?><map version=\"1.10\" orientation=\"orthogonal\" width=\"2\" height=\"1\" tilewidth=\"8\" tileheight=\"8\">")
                            (print "<group id=\"1\" name=\"far\" " group-attrs ">")
                            (print "<layer id=\"2\" name=\"ground\" width=\"2\" height=\"1\" " layer-attrs "><data encoding=\"csv\">0,0</data></layer>")
                            (print "</group></map>")))
                        path))))
    (for-each
     (lambda (attr)
       (let ((path (write-map (string-append attr ".tmx")
                              (string-append attr "=\"1e308\"") (string-append attr "=\"1e308\""))))
         (test-assert (sprintf "a group and its layer both with ~a 1e308: refused at load, naming the file, the layer and ~a" attr attr)
                      (ex-says? (ex-message (lambda () (load-tilemap path)))
                                path "layer \"ground\"" attr "not a finite number"))))
     '("offsetx" "offsety" "parallaxx" "parallaxy"))
    (let ((path (make-pathname dir "far.tmj")))
      (with-output-to-file path
        (lambda ()
          (print "{\"type\":\"map\",\"version\":\"1.10\",\"orientation\":\"orthogonal\",\"renderorder\":\"right-down\",\"width\":2,\"height\":1,\"tilewidth\":8,\"tileheight\":8,\"infinite\":false,\"tilesets\":[],")
          (print " \"layers\":[{\"type\":\"group\",\"id\":1,\"name\":\"far\",\"parallaxx\":1e308,\"visible\":true,\"opacity\":1,\"x\":0,\"y\":0,")
          (print "  \"layers\":[{\"type\":\"tilelayer\",\"id\":2,\"name\":\"ground\",\"width\":2,\"height\":1,\"parallaxx\":1e308,\"data\":[0,0],\"visible\":true,\"opacity\":1,\"x\":0,\"y\":0}]}]}")))
      (test-assert "the same in a JSON map: refused at load, naming the file, the layer and parallaxx"
                   (ex-says? (ex-message (lambda () (load-tilemap path)))
                             path "layer \"ground\"" "parallaxx" "not a finite number")))
    (test "one of the two alone loads, its value kept" 1e308
          (layer-offset-x (car (tilemap-layers (load-tilemap (write-map "one.tmx" "offsetx=\"1e308\"" ""))))))
    (delete-directory dir #t))
  (test "make-layer refuses an infinite offset, naming the layer and the keyword"
        "make-layer: layer \"sky\": offset-x: +inf.0 must be a finite number"
        (ex-message (lambda () (make-layer "sky" 1 1 (u32vector 0) offset-x: +inf.0))))
  (test "... and a NaN parallax"
        "make-layer: layer \"sky\": parallax-y: +nan.0 must be a finite number"
        (ex-message (lambda () (make-layer "sky" 1 1 (u32vector 0) parallax-y: +nan.0)))))

(test-group "a body resting on a floor for 100,000 frames"
  (for-each
   (lambda (y)
     (let loop ((f 0) (s (make-scene tilemap: ex-room
                                     entities: (list (ex-ent #:x 121/3 #:y y #:width 16 #:height 16 #:gravity? #t))))
                (moved 0) (off 0))
       (if (< f 100000)
           (let* ((s (engine-pipeline s 16)) (e (ex-first s)))
             (loop (+ f 1) s
                   (if (= (entity-ref e #:y) y) moved (+ moved 1))
                   (if (entity-ref e #:on-ground?) off (+ off 1))))
           (begin
             (test (sprintf "y = ~s never changes" y) 0 moved)
             (test (sprintf "y = ~s never leaves the ground" y) 0 off)))))
   (list 208 208.0)))

(define (every-x-is? s x)
  (let loop ((es (scene-entities s)))
    (or (null? es) (and (= (entity-ref (car es) #:x) x) (loop (cdr es))))))

(test-group "a stack of solid boxes stays bounded"
  ;; Five 16 px boxes on the floor. Each pair pushes apart by halves, so the
  ;; stack settles compressed and jitters; docs/performance.org has the
  ;; measured figures. Flonums: exact halves grow long denominators.
  (let loop ((f 0)
             (s (make-scene tilemap: ex-room
                            entities: (let boxes ((k 0))
                                        (if (= k 5) '()
                                            (cons (ex-ent #:id k #:x 40.0 #:y (- 208.0 (* 16 k))
                                                          #:width 16 #:height 16 #:gravity? #t #:solid? #t)
                                                  (boxes (+ k 1)))))))
             (lo #f) (hi #f) (xs-moved 0))
    (if (< f 10000)
        (let* ((s (engine-pipeline s 16))
               (ys (map (lambda (e) (entity-ref e #:y)) (scene-entities s))))
          (loop (+ f 1) s
                (if (and lo (> f 100)) (map min lo ys) ys)
                (if (and hi (> f 100)) (map max hi ys) ys)
                (if (every-x-is? s 40.0) xs-moved (+ xs-moved 1))))
        (let ((jitter (apply max (map - hi lo))))
          ;; the figures docs/performance.org quotes
          (print "extremes: stack jitter " jitter " px, bottom box "
                 (- (+ (car hi) 16) 224) " px into the floor")
          (test "no box moves sideways" 0 xs-moved)
          (test-assert "after settling, every box stays within 1 px" (< jitter 1))
          (test-assert "the bottom box sinks less than half its height into the floor"
                       (< (- (+ (car hi) 16) 224) 8))
          (test-assert "the stack keeps its order, top box highest"
                       (apply > hi))))))

(test-group "a chaotic sandbox is deterministic over 10,000 frames"
  (define (sandbox)
    (let ((seed 99))
      (define (rand n) (set! seed (modulo (+ (* 1103515245 seed) 12345) 2147483648)) (modulo seed n))
      (make-scene tilemap: ex-room collision-mode: 'swept
                  entities: (let movers ((k 0))
                              (if (= k 16) '()
                                  (cons (ex-ent #:id k #:x (+ 16.0 (rand 260)) #:y (+ 16.0 (rand 180))
                                                #:width (+ 4 (rand 12)) #:height (+ 4 (rand 12))
                                                #:vx (- (rand 9) 4.5) #:vy (- (rand 9) 4.0)
                                                #:gravity? (even? k) #:solid? #t)
                                        (movers (+ k 1))))))))
  (define (kick s f)
    ;; every 97 frames each body is thrown again, from its own state
    (if (zero? (modulo f 97))
        (scene-map-entities s (lambda (sc e)
                                (entity-set (entity-set e #:vx (- 3.5 (entity-ref e #:id 0) (* 0.25 (modulo f 5))))
                                            #:ay (if (entity-ref e #:on-ground?) -10 0))))
        s))
  (define (run)
    (let loop ((f 0) (s (sandbox)))
      (if (= f 10000) (scene-entities s) (loop (+ f 1) (kick (engine-pipeline s 16) f)))))
  (let ((a (run)) (b (run)))
    (test-assert "two runs end in the same state" (equal? a b))
    (test-assert "and the bodies did move" (not (equal? a (scene-entities (sandbox)))))))

(test-group "exact arithmetic as an accuracy knob"
  (define (slide vx frames)
    (entity-ref (ex-first (ex-run (make-scene entities: (list (ex-ent #:x 0 #:vx vx))) frames)) #:x))
  (test "1/10 px/frame for 10,000 frames is exactly 1000 px" 1000 (slide 1/10 10000))
  (let ((drift (- (slide 0.1 10000) 1000)))
    (print "extremes: 0.1 px/frame as a flonum, 10,000 frames: drift " drift " px")
    (test-assert "0.1 as a flonum drifts" (not (zero? drift)))
    (test-assert "by less than a millionth of a pixel" (< (abs drift) 1e-6))))

(test-group "a million frames keep memory flat"
  (let* ((scene (make-scene tilemap: ex-room
                            entities: (list (ex-ent #:x 40 #:y 208 #:width 16 #:height 16 #:vx 3 #:gravity? #t))))
         (bounce (lambda (s)
                   (scene-map-entities s (lambda (sc e) (if (zero? (entity-ref e #:vx))
                                                            (entity-set e #:vx (if (< (entity-ref e #:x) 100) 3 -3))
                                                            e)))))
         (heap-after (lambda (s) (gc #t) (vector-ref (memory-statistics) 1))))
    (let loop ((f 0) (s scene) (at-100k #f))
      (cond ((= f 1000000)
             (let ((at-1m (heap-after s)))
               (test-assert "heap in use grows by less than 256 KiB from frame 100,000 to 1,000,000"
                            (< (- at-1m at-100k) 262144))
               (test "the body is still in the room" #t (< 16 (entity-ref (ex-first s) #:x) 288))))
            ((= f 100000) (loop (+ f 1) (bounce (engine-pipeline s 16)) (heap-after s)))
            (else (loop (+ f 1) (bounce (engine-pipeline s 16)) at-100k))))))
