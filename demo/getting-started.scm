;;; Getting started: a square moved by the arrow keys.
(import scheme (chicken base) (chicken format)
        (downstroke entity) (downstroke scene) (downstroke input) (downstroke engine))
(include-relative "common.scm")

;; -3, 0 or 3 px/frame along one axis, from two opposite arrows.
(define (axis input minus plus)
  (cond ((input-held? input minus) -3) ((input-held? input plus) 3) (else 0)))

(define game
  (make-game
   title: "Getting started" width: 320 height: 240
   create: (lambda (game)
             (game-scene-set! game (make-sprite-scene
                                    background: '(32 32 48)
                                    entities: (list (list #:type 'square #:x 150 #:y 110
                                                          #:width 20 #:height 20
                                                          #:color '(240 200 60))))))
   ;; Velocity is intent: set it from the arrows, the pipeline moves the
   ;; square; a velocity that would take it past an edge of the 320 x 240
   ;; view is cut so that it stops there.
   update: (lambda (game dt)
             (let ((input (game-input game)))
               (game-scene-set! game (scene-map-entities
                                      (game-scene game)
                                      (lambda (scene square)
                                        (entity-set (entity-set square #:vx (inside (entity-ref square #:x)
                                                                                    (axis input 'left 'right)
                                                                                    (- 320 20)))
                                                    #:vy (inside (entity-ref square #:y)
                                                                 (axis input 'up 'down)
                                                                 (- 240 20))))))))))

;; A velocity v from position p, cut to stay within 0 .. limit.
(define (inside p v limit) (- (max 0 (min limit (+ p v))) p))

(demo-run! game)
(let ((square (car (scene-entities (game-scene game)))))
  (printf "getting-started: square at ~a ~a~%" (entity-ref square #:x) (entity-ref square #:y)))
