(import scheme (chicken base) (downstroke entity) (downstroke scene)
        (downstroke input) (downstroke engine))

;; -3, 0 or 3 px/frame from two opposite directions
(define (axis input minus plus)
  (cond ((input-held? input minus) -3) ((input-held? input plus) 3) (else 0)))

(define game
  (make-game
   title: "Square" width: 320 height: 240
   create: (lambda (game)
             (game-scene-set! game
               (make-sprite-scene background: '(32 32 48)
                                  entities: (list (list #:type 'square #:x 100 #:y 100
                                                        #:width 20 #:height 20
                                                        #:color '(240 200 60))))))
   update: (lambda (game dt)
             (let ((input (game-input game)))
               (game-scene-set! game
                 (scene-map-entities (game-scene game)
                   (lambda (scene e)
                     (entity-set (entity-set e #:vx (axis input 'left 'right))
                                 #:vy (axis input 'up 'down)))))))))

;; Hold right on frames 0-9, nothing on 10-19, down on 20-24, then let go.
(game-run! game frames: 30 headless?: #t
           input-script: '((0 right) (10) (20 down) (25)))
(let ((square (car (scene-entities (game-scene game)))))
  (print "square at " (entity-ref square #:x) ", " (entity-ref square #:y)))
