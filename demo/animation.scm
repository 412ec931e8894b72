;;; Animation: characters made from prefabs, animated from sprites.png.
;;;   bin/demo-animation        watch; escape quits
;;; Each kind of character is a prefab (below, as data: the same form a
;;; prefab file holds) built from mixins, with its #:animations. The
;;; engine's apply-animation step flips #:tile-id every frame; update: only
;;; picks the animation that fits (set-animation keeps a running one going).
;;; Walkers walk to the end of their beat, rest (idle) and turn back. The
;;; name over each head is the animation it plays, in the sprite font.
(import scheme (chicken base) (chicken format) srfi-4
        (downstroke entity) (downstroke scene) (downstroke engine)
        (downstroke tilemap) (downstroke prefabs) (downstroke animation)
        (downstroke text) (only (downstroke sdl2) img-load-texture!))
(include-relative "common.scm")

;; Frames are gids of sprites.tsx (first gid 9; see tools/make-assets.scm).
;; (tile . ticks) gives a frame its own duration, in frames of 16 ms.
(define prefab-data
  '((mixins
     (sprite #:width 16 #:height 16 #:vx 0 #:facing 1)
     (walker #:walker? #t #:label-y -10 #:dir 1 #:pause 0))
    (prefabs
     (hero animated sprite walker #:speed 1 #:rest 60
           #:animations ((#:name walk #:frames (10 9 11 9) #:duration 6)
                         (#:name idle #:frames ((9 . 40) (15 . 6)))))
     (blob animated sprite walker #:speed 1/2 #:rest 90 #:label-y -20
           #:animations ((#:name hop #:frames ((16 . 8) (17 . 6) (13 . 10)))
                         (#:name idle #:frames ((13 . 30) (16 . 12)))))
     (bird animated sprite #:flyer? #t #:label-y -10
           #:animations ((#:name flap #:frames (18 19 20 19) #:duration 4)))
     (coin animated sprite
           #:animations ((#:name spin #:frames (21 22 23 22) #:duration 6)))
     (torch animated sprite
           #:animations ((#:name flicker #:frames ((24 . 6) (25 . 5) (26 . 7))))))))

(define prefabs (parse-prefabs prefab-data source: "demo/animation.scm"))

(define (make kind . overrides) (instantiate-prefab prefabs kind overrides: overrides))

(define characters
  (append
   (list (make 'torch #:x 16 #:y 160) (make 'torch #:x 288 #:y 160)
         (make 'hero #:x 40 #:y 176 #:track-left 40 #:track-right 150)
         (make 'hero #:x 250 #:y 176 #:track-left 170 #:track-right 250 #:dir -1)
         (make 'blob #:x 80 #:y 176 #:track-left 60 #:track-right 240)
         (make 'bird #:x 0 #:y 84 #:vx 3/2)
         (make 'bird #:x 300 #:y 116 #:vx -1 #:facing -1))
   ;; five coins, each starting on a later frame of the spin
   (map (lambda (i) (make 'coin #:x (+ 112 (* 20 i)) #:y 52 #:anim-frame (modulo i 4)))
        '(0 1 2 3 4))))

;; Walk to the end of the beat, rest there, turn back.
(define (walk e)
  (let ((dir (entity-ref e #:dir)) (pause (entity-ref e #:pause)) (x (entity-ref e #:x)))
    (cond ((> pause 0)
           (let ((e (entity-set (entity-set e #:pause (- pause 1)) #:vx 0)))
             (set-animation (if (= pause 1) (entity-set e #:dir (- dir)) e) 'idle)))
          ((if (> dir 0) (>= x (entity-ref e #:track-right)) (<= x (entity-ref e #:track-left)))
           (set-animation (entity-set (entity-set e #:pause (entity-ref e #:rest)) #:vx 0) 'idle))
          (else
           (let ((moving (car (entity-ref e #:animations))))   ; the first: walk or hop
             (set-animation (entity-set (entity-set e #:vx (* dir (entity-ref e #:speed))) #:facing dir)
                            (entity-ref moving #:name)))))))

;; Birds fly across and come back in on the other side.
(define (fly e)
  (let ((x (entity-ref e #:x)))
    (cond ((> x 330) (entity-set e #:x -20))
          ((< x -20) (entity-set e #:x 330))
          (else e))))

;; The stage, 20 x 15 cells of the platformer's tiles, drawn with its
;; level's tilesets: grass over ground, stone under the torches, and
;; background blocks on a layer that does not collide.
(define (span from to) (if (> from to) '() (cons from (span (+ from 1) to))))
(define (block cols rows gid)           ; ((col row gid) ...)
  (foldr (lambda (row out) (append (map (lambda (col) (list col row gid)) cols) out)) '() rows))

(define (layer name cells . properties)
  (let ((data (make-u32vector (* 20 15) 0)))
    (for-each (lambda (c) (u32vector-set! data (+ (car c) (* 20 (cadr c))) (caddr c))) cells)
    (make-layer name 20 15 data properties: properties)))

(define (stage tilesets)
  (make-tilemap 20 15 16 16
                (list (layer "backdrop" (append (block '(4 5) (span 8 11) 7) (block '(13 14) (span 9 11) 7))
                             '("collides" . #f))
                      (layer "ground" (append (block (span 0 19) '(12) 3) (block (span 0 19) '(13 14) 1)
                                              (block '(1 18) '(11) 8))))
                tilesets: tilesets))

(define font #f)                         ; the sprite font, made in create:

(define game
  (make-game
   title: "Downstroke animation" width: 320 height: 240 scale: 2
   create: (lambda (game)
             ;; the level's two tilesets, at the gids the level gives them
             (let ((tilesets (game-load-tilesets!
                              game (list (load-tileset "demo/levels/tiles.tsx")
                                         (load-tileset "demo/levels/sprites.tsx" first-gid: 9)))))
               (game-scene-set! game (make-scene tilemap: (stage tilesets) tileset: (cadr tilesets)
                                                 entities: characters background: '(92 148 252))))
             (set! font (make-sprite-font (img-load-texture! (game-renderer game) "demo/assets/font.png")
                                          glyph-width: 6 glyph-height: 8)))
   update: (lambda (game dt)
             (game-scene-set! game (scene-map-entities (game-scene game)
                                     (lambda (scene e)
                                       (cond ((entity-ref e #:walker? #f) (walk e))
                                             ((entity-ref e #:flyer? #f) (fly e))
                                             (else e))))))
   ;; titles, and each labelled character's animation name over its head
   render: (lambda (game)
             (let ((r (game-renderer game)))
               (draw-sprite-text! r font "Animation" 8 6 scale: 2)
               (draw-sprite-text! r font "prefabs + frames of sprites.png" 8 26)
               (for-each (lambda (e)
                           (when (entity-ref e #:label-y #f)
                             (let ((name (symbol->string (entity-ref e #:anim-name))))
                               (draw-sprite-text! r font name
                                                  (- (+ (entity-ref e #:x) 8) (* 3 (string-length name)))
                                                  (+ (entity-ref e #:y) (entity-ref e #:label-y))))))
                         (scene-entities (game-scene game)))))))

(demo-run! game)

;; On the last frame, every character: (type animation tile x), for the tests.
(printf "animation: frame ~a ~s~%" (game-frame game)
        (map (lambda (e) (map (cut entity-ref e <>) '(#:type #:anim-name #:tile-id #:x)))
             (scene-entities (game-scene game))))
