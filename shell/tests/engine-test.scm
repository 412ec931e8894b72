;;; (downstroke engine): the game record, the frame dispatch, the default
;;; pipeline, and scenarios over many frames. No SDL is involved.

(import scheme (chicken base) (chicken string) (chicken format) (chicken process) (chicken file)
        (downstroke test) (downstroke entity) (downstroke tilemap)
        (downstroke scene) (downstroke physics) (downstroke tween) (downstroke animation)
        (downstroke engine) (downstroke pipeline) (downstroke srfi-197))

;; Bad entities are made here on purpose; their warnings would only be noise.
(scene-checks #f)

(define (ent . plist) (plist->entity plist))
(define (repeat n x) (if (= n 0) '() (cons x (repeat (- n 1) x))))

;; A 20 x 15 map of 16 px tiles: a floor on the last row (top at y = 224)
;; and, when `wall-col` is given, a wall filling that column.
(define (room #!optional wall-col)
  (list->tilemap
   (let rows ((j 0))
     (if (= j 15)
         '()
         (cons (let cols ((i 0))
                 (if (= i 20)
                     '()
                     (cons (if (or (= j 14) (eqv? i wall-col)) 1 0) (cols (+ i 1)))))
               (rows (+ j 1)))))))

(define (game-with scene #!optional update)
  (let ((g (make-game update: update)))
    (game-scene-set! g scene)
    g))

(define (first-n n xs) (if (= n 0) '() (cons (car xs) (first-n (- n 1) (cdr xs)))))
(define (first-entity g) (car (scene-entities (game-scene g))))
(define (find-type g type)
  (let loop ((es (scene-entities (game-scene g))))
    (cond ((null? es) #f)
          ((eq? (entity-type (car es)) type) (car es))
          (else (loop (cdr es))))))

;; Runs n frames, calling (watch frame-number game) after each.
(define (run! g n watch)
  (do ((f 1 (+ f 1))) ((> f n))
    (game-step! g)
    (watch f g)))

(test-group "make-game"
  (let ((g (make-game)))
    (test "defaults" '("Downstroke Game" 640 480 16 1 0)
          (list (game-title g) (game-width g) (game-height g) (game-frame-delay g)
                (game-scale g) (game-frame g)))
    (test "no scene yet" #f (game-scene g))
    (game-asset-set! g 'font "f.ttf")
    (game-asset-set! g 'font "g.ttf")
    (test "assets: the last set wins" "g.ttf" (game-asset g 'font))
    (test "a missing asset with a default" 'none (game-asset g 'music 'none))
    (test-error "a missing asset names its key"
                (lambda (exn) (substring-index "music" (error-text exn)))
                (game-asset g 'music)))
  (test-error "width: must be a positive integer"
              (lambda (exn) (substring-index "width:" (error-text exn)))
              (make-game width: 0))
  (test-error "update: must be a procedure"
              (lambda (exn) (substring-index "update:" (error-text exn)))
              (make-game update: 'later))
  (let* ((log '())
         (g (make-game preload: (lambda (g) (set! log (cons 'preload log)))
                       create: (lambda (g) (set! log (cons 'create log))))))
    (game-start! g)
    (test "game-start! runs preload then create" '(preload create) (reverse log))))

(test-group "hooks are checked when the game is made"
  (define (says text thunk)
    (handle-exceptions e (and (substring-index text (error-text e)) #t) (thunk) #f))
  (test-assert "update: taking (game) alone is named, with how it is called"
               (says "make-game: update: hook (? game) takes 1 argument; it is called as (update game dt)"
                     (lambda () (make-game update: (lambda (game) game)))))
  (test-assert "render: taking (game dt)"
               (says "make-game: render: hook (? game dt) takes 2 arguments; it is called as (render game)"
                     (lambda () (make-game render: (lambda (game dt) game)))))
  (test-assert "create: taking nothing"
               (says "make-game: create: hook (?) takes 0 arguments; it is called as (create game)"
                     (lambda () (make-game create: (lambda () 1)))))
  (test-assert "a state's enter: taking two"
               (says "game-add-state!: enter: hook (? a b) takes 2 arguments; it is called as (enter game)"
                     (lambda () (game-add-state! (make-game) 'title enter: (lambda (a b) a)))))
  (test-assert "rest and optional arguments are accepted"
               (game? (make-game update: (lambda (game . more) game)
                                 render: (lambda (game #!optional extra) game)
                                 preload: (lambda args #t))))
  (test-assert "a value that is no procedure"
               (says "make-game: create: must be a procedure or #f, got 5"
                     (lambda () (make-game create: 5)))))

;; Hooks compiled with -d0 carry no argument list, so make-game cannot tell
;; their arity: a wrong one is reported naming the hook when it is called.
(test-group "hooks whose arity CHICKEN cannot tell are checked when called"
  (let* ((src (sprintf "/tmp/downstroke-d0-~a.scm" (current-process-id)))
         (so (sprintf "/tmp/downstroke-d0-~a.so" (current-process-id))))
    (with-output-to-file src
      (lambda ()
        (write '(define (d0-update game) game))                          ; one argument: wrong
        (write '(define (d0-good game dt) (d0-helper 1 2)))              ; calls a helper wrongly
        (write '(define (d0-helper x) x))))
    (system (sprintf "csc -s -d0 ~a -o ~a" src so))
    (load so)
    (define (text thunk) (handle-exceptions e (error-text e) (thunk) "no error"))
    (test "make-game cannot tell its arity and accepts it" #t (game? (make-game update: d0-update)))
    (test-assert "calling it with (game dt) names the hook and how it is called"
                 (substring-index "update: hook #<procedure> cannot take 2 arguments; it is called as (update game dt)"
                                  (text (lambda () (game-step! (make-game update: d0-update))))))
    (test-assert "a wrong call inside a hook is reported as CHICKEN reports it, not blamed on the hook"
                 (let ((t (text (lambda () (game-step! (make-game update: d0-good))))))
                   (and (substring-index "bad argument count" t) (not (substring-index "update: hook" t)))))
    (delete-file* src) (delete-file* so)))

(test-group "A pipeline of your own: engine-update dispatch"
  (let ((g (game-with (make-scene entities: (list (ent #:gravity? #t #:x 0 #:y 0 #:vy 0))))))
    (run-engine-update! g 16)
    (test "#f runs the default pipeline" '(1 1) (list (entity-ref (first-entity g) #:vy)
                                                      (entity-ref (first-entity g) #:y))))
  (let* ((calls '())
         (proc (lambda (game dt) (set! calls (cons dt calls))))
         (scene (make-scene engine-update: proc
                            entities: (list (ent #:gravity? #t #:x 0 #:y 0 #:vy 0))))
         (g (game-with scene)))
    (run-engine-update! g 16)
    (run-engine-update! g 20)
    (test "a procedure is called as (proc game dt)" '(16 20) (reverse calls))
    (test-assert "... instead of the default pipeline" (eq? scene (game-scene g))))
  (let* ((scene (make-scene engine-update: 'none
                            entities: (list (ent #:gravity? #t #:x 0 #:y 0 #:vy 5))))
         (g (game-with scene)))
    (run-engine-update! g 16)
    (test-assert "'none runs nothing" (eq? scene (game-scene g))))
  (let ((g (make-game)))
    (run-engine-update! g 16)
    (test "no scene: nothing to do" #f (game-scene g))))

(test-group "frame order: engine update, then update:, then camera"
  (let* ((seen #f)
         (g (game-with (make-scene entities: (list (ent #:gravity? #t #:x 0 #:y 0 #:vy 0
                                                        #:width 0 #:height 0
                                                        #:tags '(camera-target))))
                       (lambda (game dt)
                         (set! seen (entity-ref (first-entity game) #:y))
                         (game-scene-set! game
                                          (update-scene (game-scene game)
                                                        entities: (list (entity-set (first-entity game) #:x 1000))))))))
    (game-step! g)
    (test "update: sees the entity after this frame's pipeline" 1 seen)
    (test "the camera follows after update:" 680 (camera-x (scene-camera (game-scene g))))
    (test "frame counter" 1 (game-frame g))))

(test-group "The pipeline: the default pipeline's order of the steps"
  ;; ay set by update: acts once, on the next frame, before gravity.
  (let ((g (game-with (make-scene entities: (list (ent #:gravity? #t #:x 0 #:y 0 #:vy 0 #:ay -10))))))
    (game-step! g)
    (test "acceleration then gravity then velocity" '(-9 -9 0)
          (map (lambda (k) (entity-ref (first-entity g) k)) '(#:vy #:y #:ay)))
    (game-step! g)
    (test "ay acts once" '(-8 -17) (map (lambda (k) (entity-ref (first-entity g) k)) '(#:vy #:y))))
  ;; X resolves before Y moves: a body moving diagonally into a corner
  ;; slides along the floor instead of sticking.
  (let ((g (game-with (make-scene tilemap: (room)
                                  entities: (list (ent #:x 0 #:y 208 #:width 16 #:height 16
                                                       #:vx 3 #:vy 5))))))
    (game-step! g)
    (test "x moves, y is stopped by the floor" '(3 208 3 0)
          (map (lambda (k) (entity-ref (first-entity g) k)) '(#:x #:y #:vx #:vy))))
  (let ((g (game-with (make-scene entities: (list (ent #:type 'a #:x 0 #:y 0 #:width 10 #:height 10 #:solid? #t)
                                                  (ent #:type 'b #:x 6 #:y 2 #:width 10 #:height 10 #:solid? #t)
                                                  (ent #:type 'arm #:group-id 'g #:group-local-x 1
                                                       #:group-local-y 0)
                                                  (ent #:type 'origin #:group-id 'g #:group-origin? #t
                                                       #:x 50 #:y 60))))))
    (game-step! g)
    (test "entity collisions run" -2 (entity-ref (find-type g 'a) #:x))
    (test "groups are synced" '(51 60) (list (entity-ref (find-type g 'arm) #:x)
                                             (entity-ref (find-type g 'arm) #:y))))
  (let ((g (game-with (make-scene entities: (list (ent #:type 'p #:x 0 #:vx +nan.0))))))
    (let ((before (game-scene g)))
      (test-error "a NaN velocity stops the frame with an error naming it"
                  (lambda (exn) (substring-index "#:vx" (error-text exn)))
                  (game-step! g))
      (test-assert "... and the scene is left as it was" (eq? before (game-scene g)))))
  ;; The pipeline's look at what entities need is done in C; malformed
  ;; entities are still an error, not a crash.
  (test-error "an entity holding something other than pairs is an error"
              (engine-pipeline (make-scene entities: (list (ent #:x 0) (list (cons #:solid? #t) 'oops)))
                               16))
  (test-error "... and so is an improper entity list"
              (engine-pipeline (make-scene entities: (cons (ent #:x 0) 'oops)) 16)))

(test-group "scenario: a player dropped from y=50 lands and stays for 10,000 frames"
  (let* ((g (game-with (make-scene tilemap: (room)
                                   entities: (list (ent #:type 'player #:x 100 #:y 50
                                                        #:width 16 #:height 16 #:vx 0 #:vy 0
                                                        #:gravity? #t #:on-ground? #f)))))
         (landed #f) (left-ground 0) (moved 0) (inexact 0) (size-after-landing #f) (grew 0))
    (run! g 10000
          (lambda (f g)
            (let ((p (first-entity g)))
              (unless (and (exact-integer? (entity-ref p #:y)) (exact-integer? (entity-ref p #:vy)))
                (set! inexact (+ inexact 1)))
              (cond ((and (not landed) (entity-ref p #:on-ground?))
                     (set! landed f)
                     (set! size-after-landing (length p)))
                    (landed
                     (unless (entity-ref p #:on-ground?) (set! left-ground (+ left-ground 1)))
                     (unless (= (entity-ref p #:y) 208) (set! moved (+ moved 1)))
                     (unless (= (length p) size-after-landing) (set! grew (+ grew 1))))))))
    (test "lands on frame 18 (50 + 1 + 2 + ... + 18 passes the floor)" 18 landed)
    (test "flush on the floor" 208 (entity-ref (first-entity g) #:y))
    (test "never leaves the ground afterwards" 0 left-ground)
    (test "y never changes afterwards" 0 moved)
    (test "integers all along" 0 inexact)
    (test "the entity alist never grows" 0 grew)))

(test-group "scenario: a jump rises and lands back on the same pixel"
  (let* ((jumped #f)
         (g (game-with (make-scene tilemap: (room)
                                   entities: (list (ent #:type 'player #:x 100 #:y 208
                                                        #:width 16 #:height 16 #:gravity? #t)))
                       (lambda (game dt)
                         (let ((p (first-entity game)))
                           (when (and (not jumped) (= (game-frame game) 10)
                                      (entity-ref p #:on-ground?))
                             (set! jumped #t)
                             (game-scene-set! game (update-scene (game-scene game)
                                                                 entities: (list (entity-set p #:ay (- *jump-force*))))))))))
         (top 208) (airborne 0))
    (run! g 60 (lambda (f g)
                 (let ((p (first-entity g)))
                   (set! top (min top (entity-ref p #:y)))
                   (unless (entity-ref p #:on-ground?) (set! airborne (+ airborne 1))))))
    (test-assert "the jump happened" jumped)
    (test "rises 1 + 2 + ... + 9 = 45 px" 163 top)
    (test "lands on the pixel it left" 208 (entity-ref (first-entity g) #:y))
    (test "grounded again" #t (entity-ref (first-entity g) #:on-ground?))
    (test "in the air for 18 frames" 18 airborne)))

(test-group "scenario: a top-down entity without gravity slides along a wall"
  (let* ((push (lambda (game dt)
                 (game-scene-set! game (update-scene (game-scene game)
                                                     entities: (map (lambda (e) (entity-set (entity-set e #:vx 2) #:vy 2))
                                                                    (scene-entities (game-scene game)))))))
         (g (game-with (make-scene tilemap: (room 10)
                                   entities: (list (ent #:type 'walker #:x 100 #:y 20 #:width 16 #:height 16)))
                       push)))
    (push g 16)
    (let ((xs '()))
      (run! g 40 (lambda (f g) (set! xs (cons (entity-ref (first-entity g) #:x) xs))))
      (test "x stops flush with the wall" 144 (car xs))
      (test "and never enters it" 144 (apply max xs))
      (test "y keeps sliding, 2 px a frame" 100 (entity-ref (first-entity g) #:y))
      (test "no ground detection without gravity" #f (entity-ref (first-entity g) #:on-ground? #f)))))

(test-group "scenario: a moving platform carries the player standing on it"
  (let ((g (game-with (make-sprite-scene
                       entities: (list (ent #:type 'platform #:x 100 #:y 100 #:width 48 #:height 8
                                            #:vx 1 #:vy 0 #:solid? #t #:immovable? #t)
                                       ;; both must be solid to meet
                                       (ent #:type 'player #:x 110 #:y 84 #:width 16 #:height 16
                                            #:gravity? #t #:solid? #t)))))
        (off 0))
    (run! g 20 (lambda (f g) (unless (entity-ref (find-type g 'player) #:on-ground?) (set! off (+ off 1)))))
    (test "the platform moved 20 px" 120 (entity-ref (find-type g 'platform) #:x))
    (test "the player moved with it" 130 (entity-ref (find-type g 'player) #:x))
    (test "standing on top all along" 84 (entity-ref (find-type g 'player) #:y))
    (test "grounded every frame" 0 off)))

(test-group "scenario: only a falling body lands on an immovable one"
  ;; A crate 8 px high on the floor of a room. A walker on the floor has
  ;; vy 0 when it reaches the crate (the tile pass zeroed it): it is not
  ;; falling onto the crate, so it is stopped at its side rather than lifted
  ;; on top. A top-down mover beside a block, its centre above the block's,
  ;; is stopped the same way.
  (let ((g (game-with (make-scene tilemap: (room)
                                  entities: (list (ent #:type 'crate #:x 100 #:y 216 #:width 16 #:height 8
                                                       #:solid? #t #:immovable? #t)
                                                  (ent #:type 'walker #:x 40 #:y 208 #:width 16 #:height 16
                                                       #:vx 2 #:gravity? #t #:solid? #t)))
                      (lambda (game dt)
                        (game-scene-set! game
                          (scene-map-entities (game-scene game)
                            (lambda (s e) (if (eq? (entity-type e) 'walker) (entity-set e #:vx 2) e))))))))
    (run! g 60 (lambda (f g) #f))
    (test "the walker is stopped flush at the crate's side, on the floor" '(84 208 #t)
          (map (cut entity-ref (find-type g 'walker) <>) '(#:x #:y #:on-ground?))))
  (let ((g (game-with (make-sprite-scene
                       entities: (list (ent #:type 'block #:x 100 #:y 100 #:width 16 #:height 16
                                            #:solid? #t #:immovable? #t)
                                       (ent #:type 'mover #:x 80 #:y 96 #:width 16 #:height 16 #:vx 2
                                            #:solid? #t))))))
    (run! g 10 (lambda (f g) #f))
    (test "a top-down mover is stopped at the block's side, not lifted over it" '(84 96 0)
          (map (cut entity-ref (find-type g 'mover) <>) '(#:x #:y #:vx))))
  (let ((g (game-with (make-sprite-scene
                       entities: (list (ent #:type 'block #:x 100 #:y 100 #:width 16 #:height 16
                                            #:solid? #t #:immovable? #t)
                                       (ent #:type 'faller #:x 85 #:y 80 #:width 16 #:height 16
                                            #:gravity? #t #:solid? #t))))))
    (run! g 10 (lambda (f g) #f))
    (test "a body falling onto the block's edge (1 px over it) lands on top" '(85 84)
          (map (cut entity-ref (find-type g 'faller) <>) '(#:x #:y)))))

(test-group "scenario: a tweened platform skipping the velocity steps still hits walls"
  ;; The tween drives #:x; update: keeps #:vx at 1 as the direction of
  ;; travel, which is what tile resolution reads (velocity-x is skipped).
  (let* ((platform (ent #:type 'platform #:x 0 #:y 0 #:width 16 #:height 8 #:vx 1 #:vy 0
                        #:skip-pipelines '(acceleration gravity velocity-x velocity-y)))
         (platform (entity-set platform #:tween (make-tween platform props: '((#:x . 60)) duration: 240)))
         (g (game-with (make-scene tilemap: (room 3) entities: (list platform))
                       (lambda (game dt)
                         (game-scene-set! game (update-scene (game-scene game)
                                                             entities: (list (entity-set (first-entity game) #:vx 1)))))))
         (xs '()))
    (run! g 30 (lambda (f g) (set! xs (cons (entity-ref (first-entity g) #:x) xs))))
    (test "the tween moved it 4 px a frame until the wall" '(4 8 12 16 20 24 28 32 32 32)
          (first-n 10 (reverse xs)))
    (test "it never entered the wall" 32 (apply max xs))
    (test "it ends flush with the wall" 32 (entity-ref (first-entity g) #:x))
    (test "the finished tween is removed" #f (entity-ref (first-entity g) #:tween #f))))

(test-group "A pipeline of your own: a custom pipeline with chain and cut"
  (define (my-engine-update game dt)
    (let ((scene (game-scene game)))
      (when scene
        (game-scene-set! game
          (chain scene
            (scene-map-entities _ (cut step-tweens               <> <> dt))
            (scene-map-entities _ (cut apply-acceleration        <> <> dt))
            (scene-map-entities _ (cut apply-gravity             <> <> dt))
            (scene-map-entities _ (cut apply-velocity-x          <> <> dt))
            (scene-map-entities _ (cut resolve-tile-collisions-x <> <> dt))
            (scene-map-entities _ (cut apply-velocity-y          <> <> dt))
            (scene-map-entities _ (cut resolve-tile-collisions-y <> <> dt))
            (scene-transform-entities _ resolve-entity-collisions)
            (scene-map-entities _ (cut detect-on-solid           <> <> dt))
            (scene-transform-entities _ sync-groups)
            (scene-map-entities _ (cut apply-animation           <> <> dt)))))))
  ;; A player falling 10 px into a platform ends 8 px deep, beyond the 5 px
  ;; contact tolerance: the default order checks ground before the push and
  ;; says no; the custom order checks after it and says yes.
  (define (falling-scene engine-update)
    (make-sprite-scene engine-update: engine-update
                       entities: (list (ent #:type 'platform #:x 0 #:y 18 #:width 48 #:height 8
                                            #:solid? #t #:immovable? #t)
                                       (ent #:type 'player #:x 0 #:y 0 #:width 16 #:height 16
                                            #:vy 9 #:gravity? #t #:solid? #t))))
  (let ((default (game-with (falling-scene #f)))
        (custom (game-with (falling-scene my-engine-update))))
    (game-step! default)
    (game-step! custom)
    (test "both end on top of the platform" '(2 2)
          (list (entity-ref (find-type default 'player) #:y) (entity-ref (find-type custom 'player) #:y)))
    (test "the default order does not see the ground this frame" #f
          (entity-ref (find-type default 'player) #:on-ground?))
    (test "the custom order does" #t (entity-ref (find-type custom 'player) #:on-ground?))))
