;;; Shmup: the scene's engine update is 'none, so update: moves everything.
;;; Arrows move the ship, `a` (z or j) fires; enemies come in waves and
;;; burst into sparks when hit. The art is demo/assets/shmup.png (made by
;;; tools/make-assets.scm), a sheet of four 16 x 16 tiles: ship, enemy,
;;; bullet, spark. Stars and sparks are particles (docs/rendering.org).
(import scheme (chicken base) (chicken format) (chicken file)
        (downstroke entity) (downstroke scene) (downstroke input)
        (downstroke physics) (downstroke overlap) (downstroke engine)
        (downstroke tilemap) (downstroke particles) (downstroke text)
        (only (downstroke sdl2) render-draw-color-set! render-fill-rect! make-rect))
(include-relative "common.scm")

(define width 320)
(define height 240)

;; The sheet's tiles (gids of a sheet whose first gid is 1).
(define ship-tile 1) (define enemy-tile 2) (define bullet-tile 3) (define spark-tile 4)

;; Each wave is a list of columns (0-6); the waves repeat in this order.
(define waves '((1 3 5) (0 2 4 6) (2 3 4) (0 1 5 6) (3)))
(define wave-every 60)                  ; frames between two waves

;; The ship's hitbox is 14 x 14; its 16 x 16 sprite hangs one pixel out
;; on each side (#:sprite-offset-x / -y), and it banks when it turns.
(define (ship)
  (list #:type 'ship #:tags '(ship) #:x 153 #:y 210 #:width 14 #:height 14
        #:tile-id ship-tile #:sprite-offset-x -1 #:sprite-offset-y -1))

;; A bullet's hitbox is 3 x 8; the bolt sits at (6, 3) of its tile.
(define (bullet ship)
  (list #:type 'bullet #:tags '(bullet) #:width 3 #:height 8 #:vx 0 #:vy -6
        #:x (+ (entity-ref ship #:x) 6) #:y (- (entity-ref ship #:y) 8)
        #:tile-id bullet-tile #:sprite-offset-x -6 #:sprite-offset-y -3))

(define (enemy column wave)
  (list #:type 'enemy #:tags '(enemy) #:width 16 #:height 16
        #:x (+ 20 (* column 44)) #:y -16
        #:vx (if (even? wave) 1/2 -1/2) #:vy 1
        #:tile-id enemy-tile))

;; Sparks where an enemy was: a burst of 16 spark tiles flying out,
;; yellow fading to a transparent red; the emitter's seed is the frame,
;; so every run is the same.
(define (blast e frame)
  (list #:type 'blast #:x (+ (entity-ref e #:x) 8) #:y (+ (entity-ref e #:y) 8) #:width 0 #:height 0
        #:emitter (emitter-burst (make-emitter speed: '(1/2 5/2) angle: '(0 360) lifetime: '(12 24)
                                               color: '(255 230 120) end-color: '(230 60 40 0)
                                               tile-id: spark-tile seed: (+ 1 frame))
                                 16)))

;; Stars: 1 x 1 particles born along the top edge, drifting down at
;; different speeds; #:z -1 keeps them under everything else. They are
;; stepped ahead 240 frames (their lifetime) so that the sky starts full.
(define (stars)
  (let ((e (list #:type 'stars #:x 0 #:y 0 #:width width #:height 0 #:z -1
                 #:emitter (make-emitter rate: 1 speed: '(1 2) angle: 90 lifetime: 240
                                         size: '(1 1) color: '(200 200 255) seed: 2026))))
    (let loop ((i 0) (e (plist->entity e)))
      (if (= i 240) e (loop (+ i 1) (step-particles #f e 0))))))

(define (move scene e)
  (case (entity-type e)
    ((stars blast) (step-particles scene e 0))
    (else (apply-velocity-y scene (apply-velocity-x scene e 0) 0))))

(define (clamp lo x hi) (max lo (min x hi)))

;; The ship follows the arrows, stays on screen and banks 12 degrees
;; into a turn.
(define (steer input ship)
  (let ((dx (cond ((input-held? input 'left) -3) ((input-held? input 'right) 3) (else 0)))
        (dy (cond ((input-held? input 'up) -3) ((input-held? input 'down) 3) (else 0))))
    (entity-set* ship
                 #:x (clamp 0 (+ (entity-ref ship #:x) dx) (- width 14))
                 #:y (clamp 0 (+ (entity-ref ship #:y) dy) (- height 14))
                 #:angle (* 4 dx))))

(define (in? e pairs side)
  (let loop ((ps pairs))
    (and (pair? ps) (or (eq? e (side (car ps))) (loop (cdr ps))))))

(define (gone? e)
  (case (entity-type e)
    ((blast) (emitter-done? (entity-ref e #:emitter)))
    ((stars) #f)
    (else (or (< (entity-ref e #:y) -20) (> (entity-ref e #:y) height)))))

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
         ;; every (bullet . enemy) that touch: both go, the enemy in sparks
         (hits (overlapping-pairs bullets enemies))
         (scene (foldl (lambda (s e) (if (in? e hits cdr) (scene-add-entity s (blast e frame)) s))
                       scene enemies))
         (scene (scene-remove-entities
                 scene (lambda (e)
                         (or (gone? e) (in? e hits car) (in? e hits cdr)))))
         (scene (if (zero? (modulo frame wave-every))
                    (spawn-wave scene (quotient frame wave-every))
                    scene)))
    (game-asset-set! game 'score (+ (game-asset game 'score)
                                    (foldl (lambda (n e) (if (in? e hits cdr) (+ n 1) n)) 0 enemies)))
    (game-scene-set! game scene)))

;; The score as text when the DejaVu font is installed (fonts-dejavu-core),
;; else as one pip per enemy destroyed.
(define font-file "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf")
(define score-colour '(255 210 80))

(define (draw-score! game)
  (let ((r (game-renderer game)) (font (game-asset game 'font)) (score (game-asset game 'score)))
    (if font
        (draw-text! r font (sprintf "SCORE ~a" score) 6 4 color: score-colour)
        (begin
          (apply render-draw-color-set! r score-colour)
          (do ((i 0 (+ i 1))) ((= i score))
            (render-fill-rect! r (make-rect (+ 4 (* 6 (modulo i 50))) (+ 4 (* 6 (quotient i 50))) 4 4)))))))

(define game
  (make-game
   title: "Shmup" width: width height: height
   create: (lambda (game)
             (let ((sheet (make-sheet-tileset "demo/assets/shmup.png" tile-width: 16 tile-height: 16
                                              columns: 4 name: "shmup")))
               (game-load-tilesets! game (list sheet))
               (game-asset-set! game 'score 0)
               (game-asset-set! game 'font (and (file-exists? font-file) (open-font font-file 14)))
               (game-scene-set! game (make-sprite-scene background: '(10 10 30)
                                                        tileset: sheet
                                                        entities: (list (stars) (ship))
                                                        camera-target: #f
                                                        engine-update: 'none))))
   update: update
   render: draw-score!))

(demo-run! game)
(let ((particles (foldl (lambda (n e) (if (memq (entity-type e) '(blast))
                                          (+ n (emitter-count (entity-ref e #:emitter)))
                                          n))
                        0 (scene-entities (game-scene game)))))
  (printf "shmup: enemies destroyed ~a, sparks ~a~%" (game-asset game 'score) particles))
