;;; Platformer: a Tiled level, gravity, jumps, a moving platform, a lift,
;;; jump-through ledges and a camera that glides.
;;;   bin/demo-platformer        arrows or A/D walk, z or j jumps, down drops
;;;                              through a ledge, escape quits
;;; The wooden ledges are one-way tiles: tiles.tsx gives their tile the bool
;;; property one-way, so the player jumps up through them and lands on top.
;;; The level is demo/levels/platformer.tmx (open it in Tiled); the art and
;;; sounds come from tools/make-assets.scm (make assets).
(include "demo/common.scm")
(import (chicken condition) (downstroke srfi-197)
        (downstroke entity) (downstroke scene) (downstroke tilemap)
        (downstroke physics) (downstroke input) (downstroke sound) (downstroke tween))

(define walk-speed 2)                   ; px per frame
(define start-x 32)
(define start-y 192)

;; Sprite frames: gids of sprites.tsx, the level's second tileset (first gid 9).
(define idle 9) (define walk-a 10) (define walk-b 11) (define in-air 12)

(define player
  (list #:type 'player #:tags '(player camera-target)
        #:x start-x #:y start-y #:width 16 #:height 16
        #:gravity? #t #:solid? #t #:tile-id idle))

;; Solid and immovable: whoever lands on it rides along (see docs/physics.org).
(define platform
  (list #:type 'platform #:x 240 #:y 192 #:width 48 #:height 8 #:vx 1
        #:solid? #t #:immovable? #t #:min-x 240 #:max-x 320
        #:color '(196 146 84)))

;; A lift over the second pit: a tween moves it up and down for ever (its
;; velocity steps are skipped), and it carries its rider by what it did.
(define lift
  (let ((e (plist->entity
            (list #:type 'lift #:x 560 #:y 200 #:width 32 #:height 8
                  #:solid? #t #:immovable? #t #:color '(150 150 170)
                  #:skip-pipelines '(velocity-x velocity-y)))))
    (entity-set e #:tween (make-tween e props: '((#:y . 120)) duration: 2000
                                      ease: 'quad-in-out repeat: -1 yoyo?: #t))))

;; The camera glides after the player and lets it move inside a box
;; before it follows (docs/scenes.org).
(define camera (make-camera follow-rate: 1/4 deadzone: '(48 . 64)))

(define (filter-entities keep? es)
  (foldr (lambda (e out) (if (keep? e) (cons e out) out)) '() es))

(define (play-effect name)
  (when (audio-open?) (play-sound name)))

;; Input becomes velocity; a jump is a one-frame impulse, only from the ground.
(define (control-player input p frame)
  (let* ((dir (cond ((input-held? input 'left) -1)
                    ((input-held? input 'right) 1)
                    (else 0)))
         (ground? (entity-ref p #:on-ground? #f))
         (jump? (and ground? (input-pressed? input 'a))))
    (when jump? (play-effect 'jump))
    (chain (if jump? (entity-set p #:ay (- *jump-force*)) p)
           ;; held down: fall through the one-way ledges
           (entity-set _ #:drop-through? (input-held? input 'down))
           (entity-set _ #:vx (* dir walk-speed))
           (entity-set _ #:facing (if (zero? dir) (entity-ref p #:facing 1) dir))
           (entity-set _ #:tile-id (cond ((not ground?) in-air)
                                         ((zero? dir) idle)
                                         ((even? (quotient frame 8)) walk-a)
                                         (else walk-b))))))

;; Below the floor means in a spike pit: back to the start.
(define (respawn-if-fallen p)
  (if (> (entity-ref p #:y) 200)
      (chain p (entity-set _ #:x start-x) (entity-set _ #:y start-y)
             (entity-set _ #:vy 0))
      p))

;; The platform turns around at the ends of its track.
(define (move-platform p)
  (let ((x (entity-ref p #:x)))
    (cond ((<= x (entity-ref p #:min-x)) (entity-set p #:vx 1))
          ((>= x (entity-ref p #:max-x)) (entity-set p #:vx -1))
          (else p))))

(define game
  (make-game
   title: "Downstroke platformer" width: 320 height: 240 scale: 2
   create: (lambda (game)
             (condition-case
                 (begin (init-audio!)
                        (load-sounds! '((jump . "demo/assets/jump.wav"))))
               (e (exn) (print "platformer: no sound (" (get-condition-property e 'exn 'message) ")")))
             (let* ((scene (game-load-scene! game "demo/levels/platformer.tmx"
                                             entities: (list platform lift player)
                                             camera: camera))
                    (sprites (cadr (tilemap-tilesets (scene-tilemap scene)))))
               ;; entities draw their #:tile-id from the sprite sheet
               (game-scene-set! game (update-scene scene tileset: sprites
                                                   tileset-texture: #f))))
   update: (lambda (game dt)
             (game-scene-set!
              game
              (scene-map-entities
               (game-scene game)
               (lambda (scene e)
                 (case (entity-type e)
                   ((player) (respawn-if-fallen
                              (control-player (game-input game) e (game-frame game))))
                   ((platform) (move-platform e))
                   (else e))))))))

(demo-run! game)
(shutdown-audio!)

;; A headless run reports where the player ended (the tests read this line).
(when (demo-headless?)
  (let ((p (scene-find-tagged (game-scene game) 'player))
        (lift (car (filter-entities (lambda (e) (eq? (entity-type e) 'lift))
                                    (scene-entities (game-scene game)))))
        (camera (scene-camera (game-scene game))))
    (printf "platformer: player at (~a, ~a) on-ground ~a camera (~a, ~a) lift at ~a~%"
            (entity-ref p #:x) (entity-ref p #:y) (entity-ref p #:on-ground? #f)
            (camera-x camera) (camera-y camera) (floor (entity-ref lift #:y)))))
