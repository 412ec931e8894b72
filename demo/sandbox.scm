;;; Sandbox: 120 solid movers bounce off each other and the walls, and a
;;; windmill, one group of nine parts, ploughs through the crowd.
;;;   bin/demo-sandbox        nothing to press: watch; escape quits
;;; Movers are #:solid?, so the entity step pushes overlapping pairs apart;
;;; update: turns a mover round on an axis where it was stopped or pushed
;;; back. The windmill's hub is a group origin: the hub moves, sync-groups
;;; puts the arms around it (docs/physics.org, Groups). The arena is
;;; demo/levels/sandbox.tmx.
(import scheme (chicken base) (chicken format) (downstroke srfi-197)
        (downstroke entity) (downstroke scene) (downstroke tilemap)
        (downstroke physics) (downstroke engine))
(include-relative "common.scm")

(define movers 120)
(define size 8)                         ; a mover is size x size px
(define palette '((255 94 87) (255 170 60) (250 226 80) (110 214 110) (80 186 255) (186 124 255)))

;; A number in [0, 1) from two integers: the same every run.
(define (hash01 i k) (/ (modulo (+ (* i 7919) (* k 104729) (* i k 31)) 1000) 1000.))

;; 15 columns of 8, 12 px apart, between the pillars; each heads off at its
;; own speed, 0.5 to 1.5 px per frame on each axis. Flonums: pushes halve
;; overlaps, exact numbers would grow long fractions (docs/physics.org).
(define (mover i)
  (let ((heading (lambda (k) (* (if (< (hash01 i k) 0.5) -1 1) (+ 0.5 (hash01 i (+ k 2)))))))
    (list #:type 'mover #:tags '(mover) #:width size #:height size #:solid? #t
          #:x (+ 96.0 (* 12 (modulo i 15))) #:y (+ 82.0 (* 10 (quotient i 15)))
          #:hx (heading 1) #:hy (heading 2) #:color (list-ref palette (modulo i 6)))))

;; Where the pipeline stopped a mover (a wall, the hub: velocity 0) or pushed
;; it back (a mover, an arm: velocity -1 or 1 against its heading), it turns
;; round on that axis. The heading is next frame's velocity.
(define (bounce e)
  (let* ((turn (lambda (h v) (if (> (* h v) 0) h (- h))))
         (hx (turn (entity-ref e #:hx) (entity-ref e #:vx 1)))
         (hy (turn (entity-ref e #:hy) (entity-ref e #:vy 1))))
    (chain e (entity-set _ #:hx hx) (entity-set _ #:hy hy) (entity-set _ #:vx hx) (entity-set _ #:vy hy))))

;; The windmill: a 12 x 12 hub (the group origin) patrolling from x 72 to
;; 236, and on each of four arms two 8 x 8 blocks, 15 and 27 px out (no part
;; covers another at any angle). The hub is immovable: a mover is pushed off
;; it, it is never pushed. An arm block is pushed apart from a mover like
;; two movers, then sync-groups puts it back in place: only the mover gives.
(define hub
  (list #:type 'hub #:tags '(windmill) #:group-id 'windmill #:group-origin? #t
        #:x 72 #:y 114 #:width 12 #:height 12 #:vx 1
        #:solid? #t #:immovable? #t #:color '(250 250 250)))

(define (arm-block arm radius)
  (plist->entity (list #:type 'arm #:group-id 'windmill #:arm arm #:radius radius
                       #:width 8 #:height 8 #:solid? #t #:color '(200 204 220))))

;; The arms turn 1/20 rad a frame. Only the offsets from the hub change;
;; sync-groups moves the blocks. A block's centre is on a circle around the
;; hub's centre, (6, 6) from its corner.
(define (turn-arm e frame)
  (let ((a (+ (/ frame 20) (* (entity-ref e #:arm) (atan 1) 2)))
        (r (entity-ref e #:radius)))
    (chain e (entity-set _ #:group-local-x (+ 2 (* r (cos a))))
             (entity-set _ #:group-local-y (+ 2 (* r (sin a)))))))

;; Our own engine update (docs/physics.org, "A pipeline of your own"): the
;; steps this scene needs, and one more. A push must not leave a mover in a
;; wall: next frame the tile steps would see the wall from inside and snap
;; the mover out on its far side. So a push ending in a solid tile is undone.
(define (in-wall? tm e)
  (let loop ((cells (entity-tile-cells e tm)))
    (and (pair? cells) (or (tilemap-solid? tm (caar cells) (cdar cells)) (loop (cdr cells))))))

(define (undo-pushes-into-walls tm before after)
  (map (lambda (b a)
         (if (and (not (eq? a b)) (in-wall? tm a))
             (entity-set (entity-set a #:x (entity-ref b #:x)) #:y (entity-ref b #:y))
             a))
       before after))

(define (engine-update game dt)
  (let* ((scene (scene-map-entities
                 (game-scene game)
                 (lambda (s e) (chain e (apply-velocity-x s _ dt) (resolve-tile-collisions-x s _ dt)
                                      (apply-velocity-y s _ dt) (resolve-tile-collisions-y s _ dt)))))
         (tm (scene-tilemap scene)))
    (game-scene-set! game (scene-transform-entities
                           scene (lambda (es) (sync-groups (undo-pushes-into-walls
                                                            tm es (resolve-entity-collisions es))))))))

(define (update game dt)
  (game-scene-set!
   game (scene-map-entities (game-scene game)
                            (lambda (scene e)
                              (case (entity-type e)
                                ((mover) (bounce e))
                                ((arm) (turn-arm e (game-frame game)))
                                ((hub) (cond ((<= (entity-ref e #:x) 72) (entity-set e #:vx 1))
                                             ((>= (entity-ref e #:x) 236) (entity-set e #:vx -1))
                                             (else e)))
                                (else e))))))

(define game
  (make-game
   title: "Downstroke sandbox" width: 320 height: 240 scale: 2
   create: (lambda (game)
             ;; the scene's collision mode is the default, swept
             (game-load-scene!
              game "demo/levels/sandbox.tmx" camera-target: #f engine-update: engine-update
              entities: (append (let loop ((i (- movers 1)) (out '()))
                                  (if (< i 0) out (loop (- i 1) (cons (mover i) out))))
                                (list hub)
                                (map (lambda (arm r) (turn-arm (arm-block arm r) 0))
                                     '(0 0 1 1 2 2 3 3) '(15 27 15 27 15 27 15 27)))))
   update: update))

(demo-run! game)

;; The final state, one line (the tests read it): how many movers are inside
;; the walls, the deepest overlap left between two (px), and the hub.
(define (overlap a b)
  (let ((depth (lambda (p s) (- (min (+ (entity-ref a p) (entity-ref a s)) (+ (entity-ref b p) (entity-ref b s)))
                                (max (entity-ref a p) (entity-ref b p))))))
    (max 0 (min (depth #:x #:width) (depth #:y #:height)))))

(let* ((ms (scene-find-all-tagged (game-scene game) 'mover))
       (deepest (let loop ((ms ms) (worst 0))
                  (if (null? ms) worst
                      (loop (cdr ms) (foldl (lambda (w m) (max w (overlap (car ms) m))) worst (cdr ms))))))
       (inside (foldl (lambda (n m) (if (and (<= 16 (entity-ref m #:x) (- 304 size))
                                             (<= 16 (entity-ref m #:y) (- 224 size)))
                                        (+ n 1) n))
                      0 ms))
       (hub (scene-find-tagged (game-scene game) 'windmill)))
  (printf "sandbox: ~a movers, ~a inside, max overlap ~a px, windmill at (~a, ~a)~%"
          (length ms) inside (/ (round (* 100 deepest)) 100) (entity-ref hub #:x) (entity-ref hub #:y)))
