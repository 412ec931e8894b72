;;; The sprite and particle pictures of docs/rendering.org, drawn headless
;;; by the library itself from the demos' art (make assets first):
;;;   SDL_VIDEODRIVER=dummy CHICKEN_REPOSITORY_PATH=$PWD/build:$(env -u CHICKEN_INSTALL_REPOSITORY chicken-install -repository) \
;;;     csi -q -s tools/make-sprite-images.scm
;;; run from the top of the source tree. It writes
;;;   docs/images/rendering-sprites.png     one sprite, each key in turn
;;;   docs/images/rendering-particles.png   a fountain and a burst of sparks
;;; Scenes are drawn at 2x (SDL's scale), the labels at 1x under them.

(import scheme (chicken base) (chicken file) (chicken format) (chicken string)
        (downstroke sdl2) (downstroke scene) (downstroke entity) (downstroke tilemap)
        (downstroke renderer) (downstroke particles) (downstroke text))

(init!)
(define font (open-font "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf" 11))
(define scale 2)

;; Draws `scene` at 2x on a w x h (logical) canvas with a label under
;; each cell, `cell` logical pixels wide, and saves it as `path`.
(define (picture! path w h cell scene labels textures)
  (let* ((s (create-rgba-surface! (* scale w) (* scale (+ h 14))))
         (r (create-software-renderer! s))
         (texs (map (lambda (p) (cons (car p) (img-load-texture! r (cdr p)))) textures)))
    (render-scale-set! r scale scale)
    (render-scene! r scene view-width: w view-height: h textures: (map (lambda (p) (cons (car p) (cdr p))) texs))
    (render-scale-set! r 1 1)
    (let loop ((ls labels) (i 0))
      (unless (null? ls)
        (receive (tw th) (text-size font (car ls))
          (draw-text! r font (car ls) (- (* scale (+ (* i cell) (/ cell 2))) (quotient tw 2)) (+ (* scale h) 6)
                      color: '(230 230 240)))
        (loop (cdr ls) (+ i 1))))
    (img-save-png! s path)
    (for-each (lambda (p) (destroy-texture! (cdr p))) texs)
    (free-surface! s)
    (print "wrote " path)))

;;; Sprites: the demos' player (sprites.png, gid 1) under each key.

(define sprites (make-sheet-tileset "demo/assets/sprites.png" tile-width: 16 tile-height: 16
                                    columns: 6 name: "sprites"))
(define cell 56)
;; The player in cell i, the keys given replacing the defaults.
(define (at i . keys)
  (let loop ((ks keys) (e (plist->entity (list #:x (+ (* i cell) 20) #:y 20 #:tile-id 1))))
    (if (null? ks) e (loop (cddr ks) (entity-set e (car ks) (cadr ks))))))

(define sprite-cells
  (list (cons "plain" (list (at 0)))
        (cons "#:flip-x? #t" (list (at 1 #:flip-x? #t)))
        (cons "#:flip-y? #t" (list (at 2 #:flip-y? #t)))
        (cons "#:angle 30" (list (at 3 #:angle 30)))
        (cons "#:scale 2" (list (at 4 #:scale 2)))
        (cons "#:alpha 100" (list (at 5 #:alpha 100)))
        (cons "#:tint (255 90 90)" (list (at 6 #:tint '(255 90 90))))
        ;; the hitbox (drawn as a box) and the sprite 6 px above it
        (cons "#:sprite-offset-y -6"
              (list (list #:x (+ (* 7 cell) 22) #:y 26 #:width 12 #:height 16 #:color '(60 200 90 120))
                    (at 7 #:x (+ (* 7 cell) 20) #:y 26 #:sprite-offset-y -6)))
        ;; first in the list, but drawn last: its #:z is higher
        (cons "#:z 1 over #:z 0" (list (at 8 #:tile-id 13 #:z 1 #:x (+ (* 8 cell) 24) #:y 24)
                                       (at 8 #:tile-id 5)))))

(picture! "docs/images/rendering-sprites.png" (* cell (length sprite-cells)) 56 cell
          (make-sprite-scene tileset: sprites background: '(52 60 84)
                             entities: (apply append (map cdr sprite-cells)))
          (map car sprite-cells)
          (list (cons (image-source (tileset-image sprites)) "demo/assets/sprites.png")))

;;; Particles: a fountain of 2 x 2 boxes under gravity, yellow to a
;;; transparent red, and a burst of the shmup's spark tile.

(define shmup (make-sheet-tileset "demo/assets/shmup.png" tile-width: 16 tile-height: 16
                                  columns: 4 name: "shmup"))

(define (stepped entity n)
  (let loop ((i 0) (e (plist->entity entity)))
    (if (= i n) e (loop (+ i 1) (step-particles #f e 0)))))

(define fountain
  (stepped (list #:x 60 #:y 100 #:width 4 #:height 0
                 #:emitter (make-emitter rate: 2 speed: '(3 4) angle: '(-105 -75) gravity: 1/8
                                         lifetime: '(40 60) size: '(2 2)
                                         color: '(255 240 120) end-color: '(230 40 40 0) seed: 9))
           80))

(define burst
  (stepped (list #:x 180 #:y 60 #:width 0 #:height 0 #:tileset "shmup"
                 #:emitter (emitter-burst (make-emitter speed: '(1/2 5/2) angle: '(0 360) lifetime: '(14 24)
                                                        color: '(255 230 120) end-color: '(230 60 40 0)
                                                        tile-id: 4 seed: 5)
                                          24))
           8))

(picture! "docs/images/rendering-particles.png" 240 120 120
          (make-sprite-scene tilesets: (list shmup) background: '(16 16 36)
                             entities: (list fountain burst))
          '("rate 2, gravity 1/8, 2 x 2 boxes" "a burst of 24 spark tiles, 8 frames on")
          (list (cons (image-source (tileset-image shmup)) "demo/assets/shmup.png")))

(close-font! font)
(quit!)
