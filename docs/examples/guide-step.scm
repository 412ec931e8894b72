(import scheme (chicken base) (downstroke entity) (downstroke scene)
        (downstroke tilemap) (downstroke physics) (downstroke engine))

;; A floor at row 3 of 16 px tiles; the player stands on it (y 32 = 48 - 16).
(define game
  (make-game
   create: (lambda (game)
             (game-scene-set! game
               (make-scene tilemap: (list->tilemap '((0 0 0) (0 0 0) (0 0 0) (1 1 1)))
                           entities: (list (list #:type 'player #:x 16 #:y 32
                                                 #:width 16 #:height 16 #:gravity? #t
                                                 #:ay (- *jump-force*))))))))

(define (player) (car (scene-entities (game-scene game))))

;; No window: start the game, then step it one frame at a time.
(game-start! game)
(let loop ((ys '()))
  (game-step! game)
  (if (entity-ref (player) #:on-ground? #f)
      (print "airborne " (length ys) " frames, back on the ground at y "
             (entity-ref (player) #:y) " on frame " (game-frame game))
      (loop (cons (entity-ref (player) #:y) ys))))
