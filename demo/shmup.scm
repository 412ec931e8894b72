;;; Shmup: the scene's engine update is 'none, so update: moves everything.
;;; Arrows move the ship, `a` (z or j) fires; enemies come in waves.
(import scheme (chicken base) (chicken format)
        (downstroke entity) (downstroke scene) (downstroke input)
        (downstroke physics) (downstroke overlap) (downstroke engine)
        (only (downstroke sdl2) render-draw-color-set! render-fill-rect! make-rect))
(include-relative "common.scm")

(define width 320)
(define height 240)

;; Each wave is a list of columns (0-6); the waves repeat in this order.
(define waves '((1 3 5) (0 2 4 6) (2 3 4) (0 1 5 6) (3)))
(define wave-every 60)                  ; frames between two waves

(define (ship)
  (list #:type 'ship #:tags '(ship) #:x 153 #:y 210 #:width 14 #:height 14
        #:color '(120 220 255)))

(define (bullet ship)
  (list #:type 'bullet #:tags '(bullet) #:width 3 #:height 8 #:vx 0 #:vy -6
        #:x (+ (entity-ref ship #:x) 6) #:y (- (entity-ref ship #:y) 8)
        #:color '(255 255 160)))

(define (enemy column wave)
  (list #:type 'enemy #:tags '(enemy) #:width 16 #:height 16
        #:x (+ 20 (* column 44)) #:y -16
        #:vx (if (even? wave) 1/2 -1/2) #:vy 1
        #:color '(230 80 90)))

(define (move scene e) (apply-velocity-y scene (apply-velocity-x scene e 0) 0))

(define (clamp lo x hi) (max lo (min x hi)))

;; The ship follows the arrows and stays on screen.
(define (steer input ship)
  (let ((dx (cond ((input-held? input 'left) -3) ((input-held? input 'right) 3) (else 0)))
        (dy (cond ((input-held? input 'up) -3) ((input-held? input 'down) 3) (else 0))))
    (entity-set (entity-set ship #:x (clamp 0 (+ (entity-ref ship #:x) dx) (- width 14)))
                #:y (clamp 0 (+ (entity-ref ship #:y) dy) (- height 14)))))

(define (in? e pairs side)
  (let loop ((ps pairs))
    (and (pair? ps) (or (eq? e (side (car ps))) (loop (cdr ps))))))

(define (off-screen? e)
  (or (< (entity-ref e #:y) -20) (> (entity-ref e #:y) height)))

(define (spawn-wave scene n)
  (foldl (lambda (s column) (scene-add-entity s (enemy column n)))
         scene (list-ref waves (modulo n (length waves)))))

(define (update game dt)
  (let* ((frame (game-frame game))
         (input (game-input game))
         (scene (scene-map-entities (game-scene game)
                                    (lambda (s e)
                                      (if (eq? (entity-type e) 'ship) (steer input e) (move s e)))))
         ;; hold `a` to fire, one bullet every 8 frames
         (scene (if (and (input-held? input 'a) (zero? (modulo frame 8)))
                    (scene-add-entity scene (bullet (scene-find-tagged scene 'ship)))
                    scene))
         (bullets (scene-find-all-tagged scene 'bullet))
         (enemies (scene-find-all-tagged scene 'enemy))
         ;; every (bullet . enemy) that touch: both go
         (hits (overlapping-pairs bullets enemies))
         (scene (scene-remove-entities
                 scene (lambda (e)
                         (or (off-screen? e) (in? e hits car) (in? e hits cdr)))))
         (scene (if (zero? (modulo frame wave-every))
                    (spawn-wave scene (quotient frame wave-every))
                    scene)))
    (game-asset-set! game 'score (+ (game-asset game 'score)
                                    (foldl (lambda (n e) (if (in? e hits cdr) (+ n 1) n)) 0 enemies)))
    (game-scene-set! game scene)))

(define game
  (make-game
   title: "Shmup" width: width height: height
   create: (lambda (game)
             (game-asset-set! game 'score 0)
             (game-scene-set! game (make-sprite-scene background: '(10 10 30)
                                                      entities: (list (ship))
                                                      camera-target: #f
                                                      engine-update: 'none)))
   update: update
   ;; the score: one pip per enemy destroyed, top left
   render: (lambda (game)
             (let ((r (game-renderer game)))
               (render-draw-color-set! r 255 210 80)
               (do ((i 0 (+ i 1))) ((= i (game-asset game 'score)))
                 (render-fill-rect! r (make-rect (+ 4 (* 6 (modulo i 50))) (+ 4 (* 6 (quotient i 50))) 4 4)))))))

(demo-run! game)
(printf "shmup: enemies destroyed ~a~%" (game-asset game 'score))
