(import scheme (chicken base) (downstroke entity) (downstroke scene)
        (downstroke physics) (downstroke engine))

(define (player) (list #:type 'player #:tags '(player camera-target)
                       #:x 32 #:y 160 #:width 16 #:height 16 #:gravity? #t))

;; update: jumps on the first frame the player stands on the ground, and
;; keeps the highest point reached (smallest y) in the game's assets.
(define (update game dt)
  (let* ((scene (game-scene game))
         (p (scene-find-tagged scene 'player))
         (y (entity-ref p #:y)))
    (game-asset-set! game 'top (min y (game-asset game 'top y)))
    (when (and (entity-ref p #:on-ground? #f) (not (game-asset game 'jumped #f)))
      (print "frame " (game-frame game) ": on the ground at y " y ", jump")
      (game-asset-set! game 'jumped #t)
      (game-asset-set! game 'top y)
      (game-scene-set! game
        (scene-map-entities scene
          (lambda (s e)
            (if (entity-has-tag? e 'player) (entity-set e #:ay (- *jump-force*)) e)))))))

(define game
  (make-game
   title: "Jump" width: 320 height: 240
   create: (lambda (game)
             (game-load-scene! game "demo/levels/platformer.tmx"
                               entities: (list (player))))
   update: update))

(game-run! game frames: 40 headless?: #t)
(let ((p (scene-find-tagged (game-scene game) 'player)))
  (print "highest y " (game-asset game 'top) ", now y " (entity-ref p #:y)
         ", on the ground " (entity-ref p #:on-ground?)))
