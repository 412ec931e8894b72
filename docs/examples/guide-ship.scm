(import scheme (chicken base) (downstroke entity) (downstroke scene)
        (downstroke engine) (downstroke assets))

(define game
  (make-game
   title: "Jam" width: 320 height: 240
   create: (lambda (game)
             (game-load-scene! game (program-relative-path "demo/levels/platformer.tmx")
                               entities: (list (list #:type 'player #:x 32 #:y 150
                                                     #:width 16 #:height 16 #:gravity? #t))))))

(game-run! game frames: 60 headless?: #t)
(let ((p (car (scene-entities (game-scene game)))))
  (print "jam: player at " (entity-ref p #:y) ", on the ground: " (entity-ref p #:on-ground?)))
