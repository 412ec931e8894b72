;;; Getting started: a square moved by the arrows.
;;;
;;; The window, the keyboard and the drawing arrive with the game shell; until
;;; then this demo runs headless: a script stands in for the arrow keys, and
;;; the square's position is printed instead of drawn.
(import scheme (chicken base) (chicken format)
        (downstroke entity) (downstroke scene) (downstroke engine))

;; Which arrows are "held" on each frame: right for 30 frames, then down.
(define (arrows frame) (if (< frame 30) '(right) '(down)))

(define (axis held minus plus)
  (cond ((memq minus held) -2) ((memq plus held) 2) (else 0)))

;; Velocity is intent: set it every frame, the pipeline moves the square.
(define (move square held)
  (entity-set (entity-set square #:vx (axis held 'left 'right))
              #:vy (axis held 'up 'down)))

(define game
  (make-game
   title: "Getting started" width: 320 height: 240
   create: (lambda (game)
             (game-scene-set! game (make-sprite-scene
                                    background: '(32 32 48)
                                    entities: (list (list #:type 'square #:x 150 #:y 110
                                                          #:width 20 #:height 20
                                                          #:color '(240 200 60))))))
   update: (lambda (game dt)
             (let ((scene (game-scene game)))
               (game-scene-set! game (scene-map-entities
                                      scene
                                      (lambda (s e) (move e (arrows (game-frame game))))))))))

(game-start! game)
(do ((f 0 (+ f 1))) ((= f 60))
  (game-step! game))
(let ((square (car (scene-entities (game-scene game)))))
  (printf "getting-started (headless, no window yet): after ~a frames the square is at (~a, ~a)~%"
          (game-frame game) (entity-ref square #:x) (entity-ref square #:y)))
