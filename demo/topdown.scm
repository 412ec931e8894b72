;;; Top-down: a walk through a Tiled level with no gravity.
;;;   bin/demo-topdown        arrows or WASD walk (diagonals too), escape quits
;;; The level is demo/levels/topdown.tmx (open it in Tiled): a floor layer
;;; that does not collide, a walls layer that does, and an object layer with
;;; the player's start and the coins. Walk into a coin to pick it up.
(import scheme (chicken base) (chicken format) (chicken condition)
        (downstroke srfi-197) (downstroke entity) (downstroke scene)
        (downstroke tilemap) (downstroke physics) (downstroke overlap) (downstroke input)
        (downstroke renderer) (downstroke sound) (downstroke engine))
(include-relative "common.scm")

(define speed 2)                        ; px per frame, on each axis

;; Sprite frames: gids of sprites.tsx, the level's second tileset (first gid 9).
(define idle 9) (define walk-a 10) (define walk-b 11)
(define coin 6)                         ; the coin of tiles.tsx (first gid 1)

;; No #:gravity?: the pipeline skips gravity and ground detection, and still
;; moves the player by #:vx / #:vy and stops it at the walls.
(define (make-player spawn)
  (list #:type 'player #:tags '(player camera-target)
        #:x (object-x spawn) #:y (object-y spawn) #:width 16 #:height 16
        #:tile-id idle))

;; A coin is a tile object of the map; Tiled puts a tile object's y at its
;; bottom edge, an entity's y is its top.
(define (object->coin o)
  (plist->entity
   (list #:type 'coin #:x (object-x o) #:y (- (object-y o) (object-height o))
         #:width (object-width o) #:height (object-height o) #:tile-id (object-gid o))))

;; -speed, 0 or speed along one axis, from two opposite arrows.
(define (axis input minus plus)
  (cond ((input-held? input minus) (- speed)) ((input-held? input plus) speed) (else 0)))

;; Input becomes velocity; the sprite faces the way it walks.
(define (walk input p frame)
  (let ((vx (axis input 'left 'right)) (vy (axis input 'up 'down)))
    (chain p (entity-set _ #:vx vx) (entity-set _ #:vy vy)
           (entity-set _ #:facing (cond ((< vx 0) -1) ((> vx 0) 1) (else (entity-ref p #:facing 1))))
           (entity-set _ #:tile-id (cond ((and (zero? vx) (zero? vy)) idle)
                                         ((even? (quotient frame 8)) walk-a)
                                         (else walk-b))))))

(define (objects-of-type objects type)
  (foldr (lambda (o keep) (if (equal? (object-type o) type) (cons o keep) keep)) '() objects))

(define (update game dt)
  (let* ((scene (scene-map-entities (game-scene game)
                                    (lambda (s e) (walk (game-input game) e (game-frame game)))))
         (player (scene-find-tagged scene 'player))
         (coins (game-asset game 'coins))
         (left (foldr (lambda (c keep) (if (entity-overlap? player c) keep (cons c keep))) '() coins)))
    (unless (= (length left) (length coins))
      (when (audio-open?) (play-sound 'coin)))
    (game-asset-set! game 'coins left)
    (game-scene-set! game scene)))

;; The scene's sprites come from sprites.tsx, so the coins (tiles of
;; tiles.tsx) are drawn here rather than as entities or by the map's object
;; layer (hidden below): the ones still in the level, then one per coin
;; picked up, top left.
(define (coin-icons n)
  (let loop ((i 0) (out '()))
    (if (= i n)
        out
        (loop (+ i 1) (cons (entity-set (make-entity (* 11 i) 2 16 16) #:tile-id coin) out)))))

(define (render game)
  (let ((camera (scene-camera (game-scene game)))
        (draw (lambda (coins cx cy)
                (render-entities! (game-renderer game) coins cx cy
                                  (game-asset game 'tiles) (game-asset game 'tiles-texture)))))
    (draw (game-asset game 'coins) (camera-x camera) (camera-y camera))
    (draw (coin-icons (- (game-asset game 'total) (length (game-asset game 'coins)))) 0 0)))

(define game
  (make-game
   title: "Downstroke top-down" width: 320 height: 240 scale: 2
   create: (lambda (game)
             (condition-case (begin (init-audio!) (load-sounds! '((coin . "demo/assets/coin.wav"))))
               (e (exn) (print "topdown: no sound (" (get-condition-property e 'exn 'message) ")")))
             (let* ((scene (game-load-scene! game "demo/levels/topdown.tmx"
                                             background: '(30 26 36)))
                    (level (scene-tilemap scene))
                    (objects (tilemap-objects level))
                    (coins (map object->coin (objects-of-type objects "coin"))))
               (game-asset-set! game 'tiles (car (tilemap-tilesets level)))
               (game-asset-set! game 'tiles-texture (scene-tileset-texture scene))
               (game-asset-set! game 'coins coins)
               (game-asset-set! game 'total (length coins))
               ;; the player's sprite comes from the sprite sheet
               (game-scene-set! game (update-scene scene
                                                   tilemap: (tilemap-hide-layers
                                                             level (lambda (l) (equal? (layer-name l) "objects")))
                                                   entities: (list (make-player (car (objects-of-type objects "spawn"))))
                                                   tileset: (cadr (tilemap-tilesets level))
                                                   tileset-texture: #f))))
   update: update
   render: render))

(demo-run! game)
(shutdown-audio!)

;; The final state, one line (the tests read it).
(let ((p (scene-find-tagged (game-scene game) 'player))
      (camera (scene-camera (game-scene game))))
  (printf "topdown: player at (~a, ~a) coins ~a of ~a camera (~a, ~a)~%"
          (entity-ref p #:x) (entity-ref p #:y)
          (- (game-asset game 'total) (length (game-asset game 'coins))) (game-asset game 'total)
          (camera-x camera) (camera-y camera)))
