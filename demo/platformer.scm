;;; Platformer: a Tiled level, gravity, jumps, a moving platform, a lift,
;;; jump-through ledges, a ladder, enemies to stomp and a camera that
;;; glides; a title, a pause and a game over (game states, docs/scenes.org).
;;;   bin/demo-platformer        Enter starts and pauses, arrows or A/D
;;;                              walk, z or j jumps, down drops through a
;;;                              ledge, up and down climb the ladder,
;;;                              escape quits
;;; The title is a state pushed over the level, which it freezes and
;;; draws (the player shows, though no frame has run); Enter pops it.
;;; Enter in play pushes the pause over the frozen level. A fall into a
;;; spike pit costs one of 3 lives; the last one fades out to the game
;;; over screen, from which Enter fades back to a fresh level and title.
;;; The player's sprite is its animations (idle, walk, in the air); the
;;; walk's frames 0 and 1 are footsteps (#:events), each kicking up dust.
;;; The wooden ledges are one-way tiles: tiles.tsx gives their tile the bool
;;; property one-way, so the player jumps up through them and lands on top.
;;; The towers behind are a background layer drawn at 35% opacity (the
;;; layer's opacity in Tiled), so they read as scenery, and it does not
;;; collide (its property collides is false). The coins are tile objects
;;; of the object layer "coins", loaded as entities: touching one takes
;;; it, with a sound and a puff of sparkles (particles), and the count is
;;; drawn as text.
;;; The ladder near the end is the tile layer "ladders", drawn with
;;; ladders.tsx's tile, which has the bool property ladder: the player is
;;; a #:climber?, and the library's climbing step does the rest
;;; (docs/physics.org, "Ladders"); the game only says which way the
;;; player wants to climb (#:climb) and lets it jump while climbing. It
;;; leads to a ledge with two coins. The enemies are the tile objects of
;;; the object layer "enemies": they walk and turn round where their
;;; contacts say they touch a wall; landing on one from above squashes it
;;; (entity-overlap-side says above), meeting one from any other side
;;; costs a life.
;;; The level is demo/levels/platformer.tmx (open it in Tiled); the art and
;;; sounds come from tools/make-assets.scm (make assets).
(include "demo/common.scm")
(import (chicken condition) (chicken file) (downstroke srfi-197)
        (downstroke entity) (downstroke scene) (downstroke tilemap)
        (downstroke physics) (downstroke input) (downstroke sound) (downstroke tween)
        (downstroke overlap) (downstroke particles) (downstroke text) (downstroke animation)
        (only (downstroke sdl2) render-draw-blend-mode-set! render-draw-color-set! render-fill-rect! make-rect))

(define walk-speed 2)                   ; px per frame
(define font-file "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf")
;; --start-x N on the command line starts the player at x N (the ladder
;; is at x 864), to try the end of the level at once.
(define start-x
  (let ((arg (member "--start-x" (command-line-arguments))))
    (or (and arg (pair? (cdr arg)) (string->number (cadr arg))) 32)))
(define start-y 192)
(define lives-at-start 3)

;; Sprite frames: gids of sprites.tsx, the level's second tileset (first gid 9).
(define idle 9) (define walk-a 10) (define walk-b 11) (define in-air 12)
(define coin-front 21) (define coin-turning 22) (define coin-edge 23)
(define enemy-walk 13) (define enemy-squashed 16) (define enemy-stretched 17)
(define stomp-bounce -6)                ; the player's #:vy after a stomp
(define squashed-frames 30)             ; how long a squashed enemy stays
(define grace-frames 60)                ; no hurt for this long after a respawn

;; A coin of the map, as game-load-scene! made it (#:type coin, its box,
;; #:tile-id 21), made to spin.
(define (spinning coin)
  (entity-set* coin
               #:tags '(coin)
               #:animations (list (list (cons #:name 'spin)
                                        (cons #:frames (list coin-front coin-turning coin-edge coin-turning))
                                        (cons #:duration 6)))
               #:anim-name 'spin))

;; Where a coin was taken: 12 sparkles thrown up, pale yellow fading out.
(define (sparkles coin)
  (list #:type 'sparkles #:x (+ (entity-ref coin #:x) 8) #:y (+ (entity-ref coin #:y) 8)
        #:width 0 #:height 0
        #:emitter (emitter-burst (make-emitter speed: '(1/2 2) angle: '(200 340) gravity: 1/10
                                               lifetime: '(12 24) size: '(3 3)
                                               color: '(255 250 180) end-color: '(255 200 40 0)
                                               seed: (entity-ref coin #:object-id 1))
                                 12)))

(define player
  (list #:type 'player #:tags '(player camera-target)
        #:x start-x #:y start-y #:width 16 #:height 16
        #:gravity? #t #:solid? #t
        ;; climbs the map's ladders when #:climb (set from input) asks
        #:climber? #t
        ;; no #:tile-id: the renderer shows the first animation's first
        ;; frame until the pipeline writes one (the frozen title shows it)
        #:animations (list (list (cons #:name 'idle) (cons #:frames (list idle)) (cons #:duration 1))
                           (list (cons #:name 'walk) (cons #:frames (list walk-a walk-b))
                                 (cons #:duration 8) (cons #:events '((0 . step) (1 . step))))
                           (list (cons #:name 'air) (cons #:frames (list in-air)) (cons #:duration 1)))))

;; A footstep's puff of dust at the player's feet.
(define (dust p)
  (list #:type 'dust #:x (+ (entity-ref p #:x) 8) #:y (+ (entity-ref p #:y) 15) #:width 0 #:height 0
        #:emitter (emitter-burst (make-emitter speed: '(1/4 3/4) angle: '(190 350) gravity: 0
                                               lifetime: '(8 14) size: '(2 2)
                                               color: '(200 190 170) end-color: '(200 190 170 0)
                                               seed: (entity-ref p #:x 1))
                                 4)))

;; Solid and immovable: whoever lands on it rides along (see docs/physics.org).
;; It is drawn as the ledge tile of the map's first tileset, "tiles" (gid
;; 4, a plank along the top of a 16 x 16 tile), stretched to its 48 px.
(define platform
  (list #:type 'platform #:x 240 #:y 192 #:width 48 #:height 8 #:vx 1
        #:solid? #t #:immovable? #t #:track-left 240 #:track-right 320
        #:tileset "tiles" #:tile-id 4 #:scale-x 3 #:origin-x 0 #:origin-y 0
        #:color '(196 146 84)))

;; A lift over the second pit: a tween sequence moves it up, waits half a
;; second at the top, down, and waits at the bottom, for ever (its
;; velocity steps are skipped); it carries its rider by what it did. Each
;; end is reached exactly (y 120, y 200), whatever the frame length.
;; It is the stone tile (gid 8) squeezed to 32 x 8.
(define lift
  (let ((e (plist->entity
            (list #:type 'lift #:x 560 #:y 200 #:width 32 #:height 8
                  #:solid? #t #:immovable? #t #:color '(150 150 170)
                  #:tileset "tiles" #:tile-id 8 #:scale-x 2 #:scale-y 1/2 #:origin-x 0 #:origin-y 0
                  #:skip-pipelines '(velocity-x velocity-y)))))
    (entity-set e #:tween (tween-sequence (tween-to '((#:y . 120)) duration: 2000 ease: 'quad-in-out)
                                          (tween-wait 500)
                                          (tween-to '((#:y . 200)) duration: 2000 ease: 'quad-in-out)
                                          (tween-wait 500)
                                          repeat: -1))))

;; The camera glides after the player and lets it move inside a box
;; before it follows (docs/scenes.org).
(define camera (make-camera follow-rate: 1/4 deadzone: '(48 . 64)))

(define (filter-entities keep? es)
  (foldr (lambda (e out) (if (keep? e) (cons e out) out)) '() es))

(define (play-effect name)
  (when (audio-open?) (play-sound name)))

;; The coins the player touches go, each in sparkles; sparkles that have
;; died out go too. Answers the new scene and how many coins were taken.
(define (collect-coins scene)
  (let* ((player (scene-find-tagged scene 'player))
         (taken (filter-entities (lambda (c) (entity-overlap? player c))
                                 (scene-find-all-tagged scene 'coin))))
    (unless (null? taken) (play-effect 'coin))
    (values (foldl scene-add-entity
                   (scene-remove-entities
                    scene (lambda (e) (or (memq e taken)
                                          (and (eq? (entity-type e) 'sparkles)
                                               (emitter-done? (entity-ref e #:emitter))))))
                   (map sparkles taken))
            (length taken))))

;; A walking enemy of the map, as game-load-scene! made it (#:type enemy,
;; its box, #:tile-id 13): it falls, walks left, and is told its contacts.
(define (walking enemy)
  (entity-set* enemy
               #:gravity? #t #:vx -1 #:facing -1 #:contacts? #t
               #:animations (list (list (cons #:name 'walk) (cons #:frames (list enemy-walk enemy-stretched))
                                        (cons #:duration 12)))
               #:anim-name 'walk))

;; An enemy turns round when its side touches a wall's tiles (the tile
;; step has stopped it, #:vx 0).
(define (move-enemy e)
  (let ((vx (cond ((pair? (entity-touch-tiles e 'left)) 1)
                  ((pair? (entity-touch-tiles e 'right)) -1)
                  (else (entity-ref e #:vx)))))
    (entity-set* e #:vx vx #:facing vx)))

;; A stomped enemy: flat, still, gone after squashed-frames.
(define (squash e)
  (entity-set* (entity-remove (entity-remove e #:animations) #:contacts?)
               #:type 'squashed #:tile-id enemy-squashed #:vx 0 #:frames-left squashed-frames))

(define (age-squashed e)
  (entity-set e #:frames-left (- (entity-ref e #:frames-left) 1)))

;; The enemies the player met this frame, by the side it met them from
;; (entity-overlap-side): from above it stomps them and bounces up; from
;; any other side it is hurt, unless it has just respawned (#:grace).
;; Answers the new scene and whether it was hurt.
(define (stomp-enemies scene)
  (let* ((p (scene-find-tagged scene 'player))
         (met (foldr (lambda (e out)
                       (let ((side (and (eq? (entity-type e) 'enemy) (entity-overlap-side p e))))
                         (if side (cons (cons e side) out) out)))
                     '() (scene-entities scene)))
         (stomped (map car (filter-entities (lambda (m) (eq? (cdr m) 'above)) met))))
    (unless (null? stomped) (play-effect 'jump))
    (values (scene-map-entities scene (lambda (s e)
                                        (cond ((memq e stomped) (squash e))
                                              ((and (eq? e p) (pair? stomped)) (entity-set e #:vy stomp-bounce))
                                              (else e))))
            (and (not (= (length stomped) (length met)))
                 (<= (entity-ref p #:grace 0) 0)))))

;; Input becomes velocity; a jump is a one-frame impulse, only from the
;; ground or a ladder. Up and down are the climbing intent the ladder
;; step reads (#:climb); climbing, the player faces the ladder.
(define (control-player input p)
  (let* ((dir (cond ((input-held? input 'left) -1)
                    ((input-held? input 'right) 1)
                    (else 0)))
         (climb (cond ((input-held? input 'up) -1)
                      ((input-held? input 'down) 1)
                      (else 0)))
         (ground? (entity-ref p #:on-ground? #f))
         (climbing? (entity-ref p #:climbing? #f))
         (jump? (and (or ground? climbing?) (input-pressed? input 'a))))
    (when jump? (play-effect 'jump))
    (chain (if jump? (entity-set p #:ay (- *jump-force*)) p)
           ;; held down: fall through the one-way ledges (on a ladder's
           ;; top, climbing down comes first)
           (entity-set _ #:drop-through? (input-held? input 'down))
           (entity-set _ #:climb climb)
           (entity-set _ #:grace (max 0 (- (entity-ref p #:grace 0) 1)))
           (entity-set _ #:vx (* dir walk-speed))
           (entity-set _ #:facing (if (zero? dir) (entity-ref p #:facing 1) dir))
           (set-animation _ (cond (climbing? (if (zero? climb) 'idle 'walk))
                                  ((not ground?) 'air) ((zero? dir) 'idle) (else 'walk))))))

;; The dust of the footsteps the walk animation marked this frame.
(define (kick-up-dust scene)
  (let ((p (scene-find-tagged scene 'player)))
    (if (and p (eq? (entity-ref p #:anim-event #f) 'step))
        (scene-add-entity scene (dust p))
        scene)))

;; Below the floor means in a spike pit.
(define (fallen? p) (> (entity-ref p #:y) 200))

(define (respawn p)
  (entity-set* p #:x start-x #:y start-y #:vy 0 #:climbing? #f #:grace grace-frames))

;; The platform turns around at the ends of its track.
(define (move-platform p)
  (let ((x (entity-ref p #:x)))
    (cond ((<= x (entity-ref p #:track-left)) (entity-set p #:vx 1))
          ((>= x (entity-ref p #:track-right)) (entity-set p #:vx -1))
          (else p))))

;; The level, fresh: the map, its coins spinning, 3 lives, no coin taken.
(define (load-level! game)
  (game-asset-set! game 'coins 0)
  (game-asset-set! game 'lives lives-at-start)
  (let* ((scene (game-load-scene! game "demo/levels/platformer.tmx"
                                  entities: (list platform lift player)
                                  objects->entities: '("coins" "enemies")
                                  camera: camera))
         (sprites (cadr (tilemap-tilesets (scene-tilemap scene)))))
    ;; entities draw their #:tile-id from the sprite sheet
    (game-scene-set! game (scene-map-entities
                           (update-scene scene tileset: sprites tileset-texture: #f)
                           (lambda (s e)
                             (case (entity-type e)
                               ((coin) (spinning e))
                               ((enemy) (walking e))
                               (else e)))))))

(define (start-pressed? game) (input-pressed? (game-input game) 'start))

;; One frame of play: enemies met are stomped or hurt the player, the
;; player, the platform and the enemies move, coins are taken, footsteps
;; raise dust; Enter pauses; a fall or a hurt costs a life, the last one
;; the game (a fade to the game over screen).
(define (play! game dt)
  (receive (scene hurt?) (stomp-enemies (game-scene game))
   (receive (scene taken)
      (collect-coins
       (kick-up-dust
        (scene-remove-entities
         (scene-map-entities
          scene
          (lambda (scene e)
            (case (entity-type e)
              ((player) (control-player (game-input game) e))
              ((platform) (move-platform e))
              ((enemy) (move-enemy e))
              ((squashed) (age-squashed e))
              (else e))))
         (lambda (e) (and (eq? (entity-type e) 'squashed) (<= (entity-ref e #:frames-left) 0))))))
    (game-asset-set! game 'coins (+ taken (game-asset game 'coins)))
    (let ((p (scene-find-tagged scene 'player)))
      (cond ((not (or hurt? (fallen? p))) (game-scene-set! game scene))
            ((> (game-asset game 'lives) 1)
             (game-asset-set! game 'lives (- (game-asset game 'lives) 1))
             (game-scene-set! game (scene-map-entities scene (lambda (s e) (if (eq? e p) (respawn e) e)))))
            (else
             (game-asset-set! game 'lives 0)
             (game-scene-set! game scene)
             (game-state-set! game 'game-over transition: (make-fade out: 500 in: 500)))))
    (when (start-pressed? game) (game-state-push! game 'pause)))))

;; Text centred on the view at height y, when the font loaded.
(define (centred-text! game text y color)
  (let ((font (game-asset game 'font)))
    (when font
      (receive (w h) (text-size font text)
        (draw-text! (game-renderer game) font text (quotient (- (game-width game) w) 2) y color: color)))))

;; The frozen level dimmed under a state's text.
(define (dim! game alpha)
  (let ((r (game-renderer game)))
    (render-draw-blend-mode-set! r 'blend)
    (render-draw-color-set! r 0 0 20 alpha)
    (render-fill-rect! r (make-rect 0 0 (game-width game) (game-height game)))
    (render-draw-blend-mode-set! r 'none)))

(define (hud! game)
  (let ((font (game-asset game 'font)))
    (when font
      (draw-text! (game-renderer game) font
                  (sprintf "COINS ~a  LIVES ~a" (game-asset game 'coins) (game-asset game 'lives)) 6 4
                  color: '(255 240 120)))))

(define game
  (make-game
   title: "Downstroke platformer" width: 320 height: 240 scale: 2
   create: (lambda (game)
             (condition-case
                 (begin (init-audio!)
                        (load-sounds! '((jump . "demo/assets/jump.wav") (coin . "demo/assets/coin.wav"))))
               (e (exn) (print "platformer: no sound (" (get-condition-property e 'exn 'message) ")")))
             (game-asset-set! game 'font (and (file-exists? font-file) (open-font font-file 12)))
             (game-asset-set! game 'big-font (and (file-exists? font-file) (open-font font-file 24)))
             (load-level! game)
             (game-state-push! game 'title))
   update: play!
   render: hud!))

;; The title: over the frozen level, until Enter.
(game-add-state! game 'title
  update: (lambda (game dt) (when (start-pressed? game) (game-state-pop! game)))
  render: (lambda (game)
            (dim! game 120)
            (let ((font (game-asset game 'big-font)))
              (when font
                (receive (w h) (text-size font "DOWNSTROKE")
                  (draw-text! (game-renderer game) font "DOWNSTROKE" (quotient (- (game-width game) w) 2) 70
                              color: '(255 240 120)))))
            (centred-text! game "a platformer" 104 '(230 230 255))
            (centred-text! game "press Enter to play" 150 '(255 255 255))))

;; The pause: pushed over play, which it freezes; the HUD still shows.
(game-add-state! game 'pause
  update: (lambda (game dt) (when (start-pressed? game) (game-state-pop! game)))
  render: (lambda (game)
            (dim! game 140)
            (centred-text! game "PAUSED" 100 '(255 255 255))
            (centred-text! game "Enter to go on" 124 '(200 200 220))))

;; Game over: a scene of its own; Enter fades back to a fresh level, its
;; title over it (made under the fade's full cover).
(game-add-state! game 'game-over
  enter: (lambda (game) (game-scene-set! game (make-sprite-scene background: '(30 10 30) camera-target: #f)))
  update: (lambda (game dt)
            (when (start-pressed? game)
              (game-transition! game
                                (lambda (game)
                                  (load-level! game)
                                  (game-state-set! game #f)
                                  (game-state-push! game 'title))
                                transition: (make-fade out: 400 in: 400))))
  render: (lambda (game)
            (centred-text! game "GAME OVER" 90 '(255 90 90))
            (centred-text! game (sprintf "coins ~a" (game-asset game 'coins)) 116 '(255 240 120))
            (centred-text! game "press Enter" 150 '(255 255 255))))

(demo-run! game)
(shutdown-audio!)

;; A headless run reports the state and where the player ended (the tests
;; read these lines).
(when (demo-headless?)
  (printf "platformer: state ~a lives ~a~%" (game-state-stack game) (game-asset game 'lives))
  (let ((p (scene-find-tagged (game-scene game) 'player))
        (lift (filter-entities (lambda (e) (eq? (entity-type e) 'lift))
                               (scene-entities (game-scene game))))
        (camera (scene-camera (game-scene game))))
    (when (and p (pair? lift))
      (printf "platformer: enemies ~a squashed ~a climbing ~a~%"
              (length (filter-entities (lambda (e) (eq? (entity-type e) 'enemy)) (scene-entities (game-scene game))))
              (length (filter-entities (lambda (e) (eq? (entity-type e) 'squashed)) (scene-entities (game-scene game))))
              (entity-ref p #:climbing? #f))
      (printf "platformer: coins ~a left ~a sparkles ~a~%" (game-asset game 'coins)
              (length (scene-find-all-tagged (game-scene game) 'coin))
              (foldl (lambda (n e) (if (eq? (entity-type e) 'sparkles)
                                       (+ n (emitter-count (entity-ref e #:emitter)))
                                       n))
                     0 (scene-entities (game-scene game))))
      (printf "platformer: player at (~a, ~a) on-ground ~a camera (~a, ~a) lift at ~a~%"
              (entity-ref p #:x) (entity-ref p #:y) (entity-ref p #:on-ground? #f)
              (camera-x camera) (camera-y camera) (floor (entity-ref (car lift) #:y))))))
