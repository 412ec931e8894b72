;;; (downstroke particles): emitters stepped as pure data, exactly; the
;;; pipeline steps them only in a scene that has one; the renderer draws
;;; them (pixels read back).

(import scheme (chicken base) (chicken condition) (chicken string) (chicken file) srfi-4
        (downstroke tilemap)
        (downstroke test) (downstroke entity) (downstroke scene) (downstroke particles)
        (downstroke pipeline) (downstroke sdl2) (downstroke renderer))
(include-relative "../../tests/pixels.scm")

(define (every? ok? l) (or (null? l) (and (ok? (car l)) (every? ok? (cdr l)))))
(define (square x) (* x x))

(define (pt-message thunk)
  (handle-exceptions e ((condition-property-accessor 'exn 'message) e) (thunk) "no error"))

;; The emitter stepped n times in the box x y w h.
(define (pt-steps e n #!optional (x 0) (y 0) (w 0) (h 0))
  (if (= n 0) e (pt-steps (emitter-step e x y w h) (- n 1) x y w h)))

(define (pt-state p) (list (particle-x p) (particle-y p) (particle-vx p) (particle-vy p)
                           (particle-age p) (particle-life p)))

(test-group "particles: the generator"
  (test "Park and Miller's minimal standard from seed 1: 16807, 282475249, 1622650073"
        '(16807 282475249 1622650073)
        (let* ((a (random-next 1)) (b (random-next a))) (list a b (random-next b))))
  (test "its 10,000th value from seed 1 is 1043618065, as the paper says"
        1043618065 (let loop ((i 0) (s 1)) (if (= i 10000) s (loop (+ i 1) (random-next s))))))

(test-group "particles: a burst, exactly"
  (let* ((e (emitter-burst (make-emitter speed: 2 angle: 90 lifetime: 3) 2))
         (e1 (emitter-step e 10 20 0 0)))
    (test "nothing before the first step" 0 (emitter-count e))
    (test "the burst is born at the point, speed 2 straight down (angle 90), age 0"
          '((10. 20. 0. 2. 0 3) (10. 20. 0. 2. 0 3)) (map pt-state (emitter-particles e1)))
    (test "next frame they have moved by their velocity" '((10. 22. 0. 2. 1 3) (10. 22. 0. 2. 1 3))
          (map pt-state (emitter-particles (emitter-step e1 10 20 0 0))))
    (test "a lifetime of 3: alive for 3 frames, gone on the step that ages it to 3"
          '(2 2 2 0) (map (lambda (n) (emitter-count (pt-steps e n 10 20))) '(1 2 3 4)))
    (test "then the emitter is done" '(#f #t)
          (list (emitter-done? (pt-steps e 3)) (emitter-done? (pt-steps e 4))))))

(test-group "particles: rate, gravity, colour"
  (test "rate 1/4: one particle every fourth frame" '(0 0 0 1 1 1 1 2)
        (map (lambda (n) (emitter-count (pt-steps (make-emitter rate: 1/4 lifetime: 100) n)))
             '(1 2 3 4 5 6 7 8)))
  (test "rate 3 with lifetime 2: 3, then 6 alive for ever after" '(3 6 6 6)
        (map (lambda (n) (emitter-count (pt-steps (make-emitter rate: 3 lifetime: 2) n))) '(1 2 3 4)))
  (test "max-particles caps the living" 5
        (emitter-count (pt-steps (make-emitter rate: 3 lifetime: 50 max-particles: 5) 10)))
  (test "gravity 1/2 adds to vy each frame, before the move (exactly: halves are flonums without error)"
        '(0. (1. .5) (2. 1.5) (3. 3.))
        (map (lambda (n)
               (let ((p (car (emitter-particles (pt-steps (emitter-burst (make-emitter speed: 1 angle: 0 gravity: 1/2 lifetime: 10) 1) n)))))
                 (if (= n 1) (particle-y p) (list (particle-x p) (particle-y p)))))
             '(1 2 3 4)))
  (let ((e (make-emitter color: '(200 100 0) end-color: '(0 100 200 0) lifetime: 4)))
    (test "colour over life: born `color`, a quarter of the way on at each of 4 frames"
          '((200 100 0 255) (150 100 50 192) (100 100 100 128) (50 100 150 64))
          (map (lambda (n) (particle-color e (car (emitter-particles (pt-steps (emitter-burst e 1) n)))))
               '(1 2 3 4))))
  (test "without end-color the colour stays" '(9 8 7 255)
        (let ((e (make-emitter color: '(9 8 7) lifetime: 4)))
          (particle-color e (car (emitter-particles (pt-steps (emitter-burst e 1) 3))))))
  (test "emitter-stop ends the flow, and the last particles die out"
        '(2 1 0)
        (let* ((e (pt-steps (make-emitter rate: 1 lifetime: 2) 3))
               (stopped (emitter-stop e)))
          (list (emitter-count e) (emitter-count (emitter-step stopped 0 0 0 0))
                (emitter-count (pt-steps stopped 2))))))

(test-group "particles: seeded randomness"
  (define (spray seed)
    (map pt-state (emitter-particles (pt-steps (make-emitter rate: 5 lifetime: '(5 9) speed: '(1 3)
                                                             angle: '(-120 -60) seed: seed)
                                               4 100 50 16 8))))
  (test "the same seed gives the same particles, bit for bit" (spray 42) (spray 42))
  (test-assert "another seed other particles" (not (equal? (spray 42) (spray 43))))
  (let ((ps (spray 7)))
    (test "20 particles after 4 frames of 5" 20 (length ps))
    (test-assert "every lifetime is a whole number from 5 to 9"
                 (every? (lambda (p) (and (exact-integer? (list-ref p 5)) (<= 5 (list-ref p 5) 9))) ps))
    (test-assert "every speed is from 1 to 3"
                 (every? (lambda (p) (<= (- 1 1e-9) (sqrt (+ (square (list-ref p 2)) (square (list-ref p 3)))) (+ 3 1e-9)))
                         ps))
    (test-assert "every direction is upward (-120 to -60 degrees): vy < 0, |vx| <= |vy|"
                 (every? (lambda (p) (and (< (list-ref p 3) 0) (<= (abs (list-ref p 2)) (abs (list-ref p 3))))) ps))
    (test-assert "every newborn is inside the box 100 50 16 8"
                 (every? (lambda (p) (or (> (list-ref p 4) 0)
                                         (and (<= 100 (car p) 116) (<= 50 (cadr p) 58))))
                         ps))))

(test-group "particles: bad configuration names the key"
  (test "rate" "rate: is -1, not an exact number of particles per frame (0 or more; 1/4 is one every 4 frames)"
        (pt-message (lambda () (make-emitter rate: -1))))
  (test "lifetime" "lifetime: is (5 2), not an integer or a list (low high) of integers, low <= high"
        (pt-message (lambda () (make-emitter lifetime: '(5 2)))))
  (test "colour" "end-color: is (300 0 0), not a colour (r g b [a]) of integers 0-255"
        (pt-message (lambda () (make-emitter end-color: '(300 0 0)))))
  (test-error "an unknown keyword" (make-emitter speeed: 2))
  (test "a million particles at most"
        "max-particles: is 1000001, not a whole number from 0 to 1000000 (an emitter's particles are one vector)"
        (pt-message (lambda () (make-emitter max-particles: 1000001))))
  (test "a burst of a billion is cut to max-particles" 1000
        (emitter-count (emitter-step (emitter-burst (make-emitter) 1000000000) 0 0 0 0)))
  (test "an #:emitter that is no emitter, in the step"
        "entity spark: #:emitter is 3, not an emitter (make-emitter)"
        (pt-message (lambda () (step-particles #f (plist->entity (list #:type 'spark #:emitter 3)) 16)))))

(test-group "particles: the pipeline"
  (let* ((em (emitter-burst (make-emitter speed: 1 angle: 0 lifetime: 10) 1))
         (scene (make-sprite-scene entities: (list (list #:type 'fx #:x 4 #:y 4 #:emitter em)
                                                   (list #:type 'rock #:x 0 #:y 0)))))
    (define (fx-state s) (map pt-state (emitter-particles (entity-ref (car (scene-entities s)) #:emitter))))
    (test "engine-pipeline steps an entity's #:emitter once a frame" '((5. 4. 1. 0. 1 10))
          (fx-state (engine-pipeline (engine-pipeline scene 16) 16)))
    (test "as contract-pipeline does"
          (fx-state (contract-pipeline (contract-pipeline scene 16) 16))
          (fx-state (engine-pipeline (engine-pipeline scene 16) 16)))
    (test "#:skip-pipelines (particles) holds it still" 0
          (emitter-count (entity-ref (car (scene-entities
                                            (engine-pipeline
                                             (update-scene scene entities: (list (list #:x 4 #:y 4 #:emitter em
                                                                                       #:skip-pipelines '(particles))))
                                             16)))
                                     #:emitter))))
  (let ((still (make-sprite-scene entities: (list (list #:x 1 #:y 2) (list #:x 3 #:y 4 #:width 2 #:height 2)))))
    (test-assert "a scene without emitters comes back as it was: the step is not run"
                 (eq? (scene-entities (engine-pipeline still 16)) (scene-entities still)))))

(test-group "particles: drawn"
  (init!)
  (let* ((target (create-rgba-surface! 32 24))
         (r (create-software-renderer! target))
         (em (pt-steps (emitter-burst (make-emitter speed: 4 angle: '(0 0) lifetime: 10 size: '(2 2)
                                                    color: '(255 0 0) end-color: '(0 0 255)) 1)
                       2 10 10 0 0)))
    (render-scene! r (make-sprite-scene background: '(0 0 0) camera: (make-camera x: 2 y: 0)
                                        entities: (list (list #:x 10 #:y 10 #:emitter em))))
    ;; after 2 steps: x = 10 + 4, age 1 of 10: colour (230 0 25)
    (let ((px (renderer-pixels r)))
      (test "a 2 x 2 box centred on the particle (x 14 - camera 2 = 12), in its colour by age"
            '((230 0 25 255) (230 0 25 255) (230 0 25 255) (230 0 25 255))
            (list (px 11 9) (px 12 9) (px 11 10) (px 12 10)))
      (test "nothing around it" '((0 0 0 255) (0 0 0 255) (0 0 0 255))
            (list (px 10 9) (px 13 10) (px 11 11))))
    ;; a white 4 x 4 tile: particles of it take their colour
    (let* ((png (create-temporary-file ".png"))
           (_ (write-solid-png! png 4 4 255 255 255))
           (sheet (make-sheet-tileset png tile-width: 4 tile-height: 4 columns: 1 name: "dot"))
           (tex (img-load-texture! r png))
           (em (emitter-step (emitter-burst (make-emitter speed: 0 lifetime: 5 tile-id: 1
                                                          color: '(200 100 50)) 1)
                             8 8 0 0)))
      (render-scene! r (make-sprite-scene background: '(0 0 0) tilesets: (list sheet)
                                          entities: (list (list #:x 8 #:y 8 #:tileset 'dot #:emitter em)
                                                          (list #:x 20 #:y 2 #:tileset 'dot #:tile-id 1)))
                     textures: (list (cons (image-source (tileset-image sheet)) tex)))
      (let ((px (renderer-pixels r)))
        (test "a tile particle is the tile centred on it (6..9), in the particle's colour"
              '((200 100 50 255) (200 100 50 255) (0 0 0 255) (0 0 0 255))
              (list (px 6 6) (px 9 9) (px 5 6) (px 10 9)))
        (test "and the sheet is unmodulated again for the sprite after it" '(255 255 255 255) (px 21 3)))
      (destroy-texture! tex)
      (delete-file png))
    (free-surface! target)))
