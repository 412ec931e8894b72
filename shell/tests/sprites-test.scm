;;; Sprites (renderer.scm, docs/rendering.org "Sprites"): offset, origin,
;;; flips, rotation, scale, alpha, tint, per-entity sheets and draw order,
;;; drawn into a software renderer and read back pixel by pixel.

(import scheme (chicken base) (chicken file) (chicken format) (chicken string)
        (chicken condition) srfi-4 (downstroke test) (downstroke sdl2) (downstroke entity)
        (downstroke scene) (downstroke tilemap) (downstroke renderer) (downstroke particles))
;; Bad entities are made here on purpose; their warnings would only be noise.
(scene-checks #f)

(include-relative "../../tests/pixels.scm")

(init!)

(define sp-dir (create-temporary-directory))
(define (sp-path name) (string-append sp-dir "/" name))

(define sp-red '(255 0 0 255))
(define sp-green '(0 255 0 255))
(define sp-blue '(0 0 255 255))
(define sp-white '(255 255 255 255))
(define sp-yellow '(255 255 0 255))
(define sp-cyan '(0 255 255 255))
(define sp-black '(0 0 0 255))

;; Sheet "quads": 8x8 tiles, 2 columns. Tile 1 (gid 1): quadrants
;; red | green / blue | white; tile 2: yellow. Sheet "solids": tile 1 cyan.
(define (sp-make-sheet! path w fills)
  (let* ((s (create-rgba-surface! w 8))
         (r (create-software-renderer! s)))
    (for-each (lambda (f) (apply render-draw-color-set! r (car f))
                      (render-fill-rect! r (apply make-rect (cdr f))))
              fills)
    (img-save-png! s path)
    (free-surface! s)))

(sp-make-sheet! (sp-path "quads.png") 16
                (list (list sp-red 0 0 4 4) (list sp-green 4 0 4 4) (list sp-blue 0 4 4 4)
                      (list sp-white 4 4 4 4) (list sp-yellow 8 0 8 8)))
(sp-make-sheet! (sp-path "solids.png") 8 (list (list sp-cyan 0 0 8 8)))

(define quads (make-sheet-tileset (sp-path "quads.png") tile-width: 8 tile-height: 8 columns: 2
                                  name: "quads"))
(define solids (make-sheet-tileset (sp-path "solids.png") tile-width: 8 tile-height: 8 columns: 1
                                   name: "solids"))

(define sp-surface (create-rgba-surface! 32 24))
(define sp-r (create-software-renderer! sp-surface))
(define quads-tex (img-load-texture! sp-r (sp-path "quads.png")))
(define solids-tex (img-load-texture! sp-r (sp-path "solids.png")))
(define sp-textures (list (cons (image-source (tileset-image quads)) quads-tex)
                          (cons (image-source (tileset-image solids)) solids-tex)))

;; Draws entities (plists) over black with the quads sheet as the scene's
;; sprite sheet and solids as a second one; answers (x y) -> colour.
(define (sp-draw . entities)
  (render-scene! sp-r (make-sprite-scene tileset: quads tilesets: (list solids)
                                         entities: entities background: '(0 0 0))
                 textures: sp-textures)
  (renderer-pixels sp-r))

;; The colours at the centres of the four 4x4 quadrants of the 8x8 box at (x, y).
(define (quadrants px x y)
  (list (px (+ x 1) (+ y 1)) (px (+ x 6) (+ y 1)) (px (+ x 1) (+ y 6)) (px (+ x 6) (+ y 6))))

;; Every pixel of the frame, as a list.
(define (frame px)
  (let loop ((y 23) (x 31) (out '()))
    (cond ((< y 0) out)
          ((< x 0) (loop (- y 1) 31 out))
          (else (loop y (- x 1) (cons (px x y) out))))))

;; The bounding box (x0 y0 x1 y1), inclusive, of the pixels that are not black.
(define (lit-box px)
  (let loop ((i 0) (box #f))
    (if (= i (* 32 24))
        box
        (let ((x (modulo i 32)) (y (quotient i 32)))
          (loop (+ i 1)
                (if (equal? (px x y) sp-black)
                    box
                    (if box
                        (list (min x (car box)) (min y (cadr box)) (max x (caddr box)) (max y (cadddr box)))
                        (list x y x y))))))))

(define (message-of thunk)
  (handle-exceptions e ((condition-property-accessor 'exn 'message) e) (thunk) "no error"))

(test-group "sprites: entities without the new keys"
  (let ((plain (sp-draw (list #:x 3 #:y 2 #:tile-id 1) (list #:x 14 #:y 2 #:tile-id 1 #:facing -1))))
    (test "drawn at #:x #:y at the tile's size" (list sp-red sp-green sp-blue sp-white) (quadrants plain 3 2))
    (test "#:facing -1 mirrors" (list sp-green sp-red sp-white sp-blue) (quadrants plain 14 2))
    (test "neutral values of every new key draw the very same frame"
          (frame plain)
          (frame (sp-draw (list #:x 3 #:y 2 #:tile-id 1 #:angle 0 #:scale 1 #:alpha 255
                                #:tint '(255 255 255) #:sprite-offset-x 0 #:sprite-offset-y 0
                                #:flip-x? #f #:flip-y? #f #:z 0)
                          (list #:x 14 #:y 2 #:tile-id 1 #:facing -1 #:scale-x 1 #:scale-y 1
                                #:origin-x 0 #:origin-y 0 #:tileset 'quads))))))

(test-group "sprites: offset"
  (let ((px (sp-draw (list #:x 10 #:y 10 #:width 4 #:height 4 #:tile-id 1
                           #:sprite-offset-x -2 #:sprite-offset-y -4))))
    (test "the sprite's top-left is at #:x + offset, #:y + offset"
          (list sp-red sp-green sp-blue sp-white) (quadrants px 8 6))
    (test "and nowhere else" '(8 6 15 13) (lit-box px)))
  (test "fractional offsets follow the rounding rule"
        '(9 6 16 13)
        (lit-box (sp-draw (list #:x 10 #:y 10 #:tile-id 1 #:sprite-offset-x -1/2 #:sprite-offset-y -3.5)))))

(test-group "sprites: flips"
  (test "#:flip-x? mirrors left to right" (list sp-green sp-red sp-white sp-blue)
        (quadrants (sp-draw (list #:x 4 #:y 4 #:tile-id 1 #:flip-x? #t)) 4 4))
  (test "#:flip-y? mirrors top to bottom" (list sp-blue sp-white sp-red sp-green)
        (quadrants (sp-draw (list #:x 4 #:y 4 #:tile-id 1 #:flip-y? #t)) 4 4))
  (test "both: a half turn" (list sp-white sp-blue sp-green sp-red)
        (quadrants (sp-draw (list #:x 4 #:y 4 #:tile-id 1 #:flip-x? #t #:flip-y? #t)) 4 4))
  (test "#:flip-x? with #:facing -1: mirrored twice, as drawn" (list sp-red sp-green sp-blue sp-white)
        (quadrants (sp-draw (list #:x 4 #:y 4 #:tile-id 1 #:flip-x? #t #:facing -1)) 4 4)))

(test-group "sprites: rotation"
  (let ((px (sp-draw (list #:x 8 #:y 8 #:tile-id 1 #:angle 90))))
    (test "90 degrees clockwise about the centre: the left column goes on top"
          (list sp-blue sp-red sp-white sp-green) (quadrants px 8 8))
    (test "in the same box" '(8 8 15 15) (lit-box px)))
  (test "180 degrees" (list sp-white sp-blue sp-green sp-red)
        (quadrants (sp-draw (list #:x 8 #:y 8 #:tile-id 1 #:angle 180)) 8 8))
  (test "-90 is 270" (quadrants (sp-draw (list #:x 8 #:y 8 #:tile-id 1 #:angle 270)) 8 8)
        (quadrants (sp-draw (list #:x 8 #:y 8 #:tile-id 1 #:angle -90)) 8 8))
  (let ((px (sp-draw (list #:x 8 #:y 8 #:tile-id 1 #:angle 90 #:origin-x 0 #:origin-y 0))))
    (test "about the origin (0, 0), the top-left corner: the box swings to the left of it"
          '(0 8 7 15) (lit-box px))
    (test "turned the same way" (list sp-blue sp-red sp-white sp-green) (quadrants px 0 8)))
  (let ((px (sp-draw (list #:x 8 #:y 8 #:tile-id 1 #:angle 180 #:origin-x 8 #:origin-y 4))))
    (test "about (8, 4), the middle of the right edge: a half turn lands right of it"
          '(16 8 23 15) (lit-box px)))
  (test "45 degrees: a diamond wider than the tile, about the same centre"
        #t
        (let ((box (lit-box (sp-draw (list #:x 12 #:y 8 #:tile-id 2 #:angle 45)))))
          (and (<= (car box) 11) (>= (caddr box) 20) (= (+ (car box) (caddr box)) 31)))))

(test-group "sprites: scale"
  (let ((px (sp-draw (list #:x 8 #:y 8 #:tile-id 1 #:scale 2))))
    (test "#:scale 2 about the centre (12, 12): 16 x 16 from (4, 4)" '(4 4 19 19) (lit-box px))
    (test "each quadrant 8 x 8" (list sp-red sp-green sp-blue sp-white)
          (list (px 4 4) (px 19 4) (px 4 19) (px 19 19))))
  (test "about the origin (0, 0) it grows right and down" '(8 8 23 23)
        (lit-box (sp-draw (list #:x 8 #:y 8 #:tile-id 1 #:scale 2 #:origin-x 0 #:origin-y 0))))
  (test "#:scale-x and #:scale-y apart: 16 x 4" '(4 10 19 13)
        (lit-box (sp-draw (list #:x 8 #:y 8 #:tile-id 2 #:scale-x 2 #:scale-y 1/2))))
  (test "#:scale-y wins over #:scale on its axis" '(4 8 19 15)
        (lit-box (sp-draw (list #:x 8 #:y 8 #:tile-id 2 #:scale 2 #:scale-y 1))))
  (test "scale 0 draws nothing" #f (lit-box (sp-draw (list #:x 8 #:y 8 #:tile-id 2 #:scale 0))))
  (test "scale and rotation together: 2x about the centre, turned 90"
        (list sp-blue sp-red sp-white sp-green)
        (let ((px (sp-draw (list #:x 8 #:y 8 #:tile-id 1 #:scale 2 #:angle 90))))
          (list (px 5 5) (px 18 5) (px 5 18) (px 18 18))))
  (test "a negative scale is an error naming the entity and saying how to mirror"
        "entity hero: a negative scale (-1 x -1); mirror with #:flip-x? / #:flip-y?"
        (message-of (lambda () (sp-draw (list #:type 'hero #:x 0 #:y 0 #:tile-id 1 #:scale -1))))))

(test-group "sprites: alpha and tint"
  (let ((px (sp-draw (list #:x 0 #:y 0 #:tile-id 2 #:alpha 128)
                     (list #:x 8 #:y 0 #:tile-id 2))))
    (test-assert "#:alpha 128 over black: half the yellow"
                 (let ((c (px 2 2))) (and (<= 126 (car c) 130) (<= 126 (cadr c) 130) (= 0 (caddr c)))))
    (test "the texture is opaque again for the next sprite" sp-yellow (px 10 2)))
  (test "#:alpha 0 draws nothing" #f (lit-box (sp-draw (list #:x 0 #:y 0 #:tile-id 2 #:alpha 0))))
  (let ((px (sp-draw (list #:x 0 #:y 0 #:tile-id 1 #:tint '(255 0 0))
                     (list #:x 10 #:y 0 #:tile-id 1))))
    (test "#:tint (255 0 0) keeps the red of each quadrant" (list sp-red sp-black sp-black sp-red)
          (quadrants px 0 0))
    (test "the next sprite is untinted" (list sp-red sp-green sp-blue sp-white) (quadrants px 10 0)))
  (test "a half tint halves" '(128 128 0 255)
        ((sp-draw (list #:x 0 #:y 0 #:tile-id 2 #:tint '(128 128 128))) 3 3))
  (test "a box's #:alpha multiplies its colour's alpha" '(100 0 0 255)
        ((sp-draw (list #:x 0 #:y 0 #:width 4 #:height 4 #:color '(200 0 0) #:alpha 128)) 1 1))
  (test "a bad tint is an error naming the entity"
        "entity coin: #:tint is red, not (r g b)"
        (message-of (lambda () (sp-draw (list #:type 'coin #:x 0 #:y 0 #:tile-id 1 #:tint 'red))))))

;; The C walk reads the texture's modulation once a walk and skips resets
;; to what is full already (shell/sprites.c): with a modulation set before
;; drawing, it must draw and leave the texture as the Scheme path does.
(test-group "sprites: a texture modulated before the walk"
  (define (draw-with fast?)
    (texture-color-mod-set! quads-tex 200 150 100)
    (texture-alpha-mod-set! quads-tex 100)
    (let ((px (parameterize ((sprite-fast-path? fast?))
                (sp-draw (list #:x 0 #:y 0 #:tile-id 2)
                         (list #:x 8 #:y 0 #:tile-id 2 #:alpha 128)
                         (list #:x 16 #:y 0 #:tile-id 2)
                         (list #:x 0 #:y 8 #:tile-id 2 #:tint '(255 0 0))
                         (list #:x 8 #:y 8 #:tile-id 2)))))
      (let ((out (list (frame px) (call-with-values (lambda () (texture-color-mod quads-tex)) list)
                       (texture-alpha-mod quads-tex))))
        (texture-color-mod-set! quads-tex 255 255 255)
        (texture-alpha-mod-set! quads-tex 255)
        out)))
  (let ((c (draw-with #t)) (scheme (draw-with #f)))
    (test "the same pixels as the Scheme path" #t (equal? (car c) (car scheme)))
    (test "the same modulation left on the texture" (cdr scheme) (cdr c))
    (test "the first sprite drawn with the modulation set before" #t
          (not (equal? ((sp-draw (list #:x 0 #:y 0 #:tile-id 2)) 2 2) (list-ref (car c) (+ 2 (* 2 32))))))
    (test "after the alpha sprite the alpha is full again" 255 (caddr c))))

(test-group "sprites: sheets"
  (test "#:tileset names a scene tileset: gid 1 of solids is cyan" sp-cyan
        ((sp-draw (list #:x 0 #:y 0 #:tile-id 1 #:tileset 'solids)) 3 3))
  (test "by a string too, or the tileset itself" (list sp-cyan sp-cyan)
        (let ((px (sp-draw (list #:x 0 #:y 0 #:tile-id 1 #:tileset "solids")
                           (list #:x 10 #:y 0 #:tile-id 1 #:tileset solids))))
          (list (px 3 3) (px 13 3))))
  (test "entities of two sheets side by side" (list sp-yellow sp-cyan)
        (let ((px (sp-draw (list #:x 0 #:y 0 #:tile-id 2)
                           (list #:x 10 #:y 0 #:tile-id 1 #:tileset 'solids))))
          (list (px 3 3) (px 13 3))))
  (test "the map's tilesets are found by name too" sp-cyan
        (let ((tm (make-tilemap 2 1 8 8 (tilemap-layers (list->tilemap '((0 0)) tile-width: 8 tile-height: 8))
                                tilesets: (list solids))))
          (render-scene! sp-r (make-scene tilemap: tm tileset: quads
                                          entities: (list (list #:x 0 #:y 0 #:tile-id 1 #:tileset 'solids)))
                         textures: sp-textures)
          (renderer-pixel sp-r 3 3)))
  (test "an unknown name is an error naming the entity and the sheets there are"
        "entity ghost: #:tileset enemies names no tileset of the scene (its tilesets: (\"solids\" \"quads\"))"
        (message-of (lambda () (sp-draw (list #:type 'ghost #:x 0 #:y 0 #:tile-id 1 #:tileset 'enemies)))))
  (test-assert "a sheet with no texture is an error naming the entity and the image"
               (substring-index "entity ghost: no texture for the image"
                                (message-of
                                 (lambda ()
                                   (render-scene! sp-r (make-sprite-scene
                                                        tilesets: (list solids)
                                                        entities: (list (list #:type 'ghost #:x 0 #:y 0 #:tile-id 1
                                                                              #:tileset 'solids))))))))
  (test-error "make-scene's tilesets: must be tilesets" (make-scene tilesets: '("solids")))
  (let ((s (make-sprite-scene tilesets: (list solids))))
    (test "update-scene keeps a scene's tilesets" (list solids)
          (scene-tilesets (update-scene s background: '(1 2 3))))
    (test "and replaces them when given" (list quads solids)
          (scene-tilesets (update-scene s tilesets: (list quads solids))))
    (test "a scene operation keeps them" (list solids)
          (scene-tilesets (scene-add-entity s (list #:x 0 #:y 0))))))

(test-group "sprites: draw order"
  (define (at-3-3 . es) ((apply sp-draw es) 3 3))
  (test "without #:z, list order: the later one is on top" sp-cyan
        (at-3-3 (list #:x 0 #:y 0 #:tile-id 2) (list #:x 0 #:y 0 #:tile-id 1 #:tileset 'solids)))
  (test "a higher #:z is drawn later, whatever the list order" sp-yellow
        (at-3-3 (list #:x 0 #:y 0 #:tile-id 2 #:z 1) (list #:x 0 #:y 0 #:tile-id 1 #:tileset 'solids)))
  (test "a negative #:z goes below the default 0" sp-yellow
        (at-3-3 (list #:x 0 #:y 0 #:tile-id 2) (list #:x 0 #:y 0 #:tile-id 1 #:tileset 'solids #:z -1)))
  (test "equal #:z keep list order" '(0 200 0 255)
        (at-3-3 (list #:x 0 #:y 0 #:tile-id 2 #:z 5)
                (list #:x 0 #:y 0 #:width 8 #:height 8 #:color '(200 0 0) #:z 5)
                (list #:x 0 #:y 0 #:width 8 #:height 8 #:color '(0 200 0) #:z 5)
                (list #:x 0 #:y 0 #:width 8 #:height 8 #:color '(0 0 200) #:z 2)))
  (test "a #:z that is not a number is an error naming the entity"
        "entity crate: #:z is top, not a finite number"
        (message-of (lambda () (sp-draw (list #:type 'crate #:x 0 #:y 0 #:tile-id 2 #:z 'top))))))

(test-group "sprites: the scene check knows the keys"
  (test "a misspelt sprite key is named, with the key meant"
        '("entity hero: key #:flip-x is not one Downstroke reads (did you mean #:flip-x?)"
          "entity hero: #:angle is \"90\", not a finite number")
        (scene-problems (make-sprite-scene entities: (list (list #:type 'hero #:x 0 #:y 0 #:flip-x #t
                                                                 #:angle "90")))))
  (test "a tint and an emitter of the wrong kind are named"
        '("entity spark: #:tint is (300 0 0), not (r g b) of integers 0-255"
          "entity spark: #:emitter is burst, not an emitter (make-emitter)")
        (scene-problems (make-sprite-scene entities: (list (list #:type 'spark #:x 0 #:y 0 #:tint '(300 0 0)
                                                                 #:emitter 'burst)))))
  (test "the new keys themselves are no problem" '()
        (scene-problems (make-sprite-scene
                         entities: (list (list #:x 0 #:y 0 #:sprite-offset-x 1 #:sprite-offset-y 1
                                               #:origin-x 0 #:origin-y 0 #:flip-x? #t #:flip-y? #t
                                               #:angle 3 #:scale 2 #:scale-x 1 #:scale-y 1 #:alpha 9
                                               #:tint '(1 2 3) #:tileset 'solids #:z 2))))))

;; Finite numbers that overflow once the renderer works with them: each is
;; drawn as it should be, or refused naming the entity and the key.
(define (lit-count px)
  (let loop ((i 0) (n 0))
    (if (= i (* 32 24)) n (loop (+ i 1) (if (equal? (px (modulo i 32) (quotient i 32)) sp-black) n (+ n 1))))))

(test-group "sprites: finite values that overflow later"
  ;; (proc px) of the frame drawn with these entities, inside each test
  (define (seen proc . entities) (proc (apply sp-draw entities)))
  (define giant (list #:type 'giant #:x 10 #:y 5 #:tile-id 1 #:scale 1e308))
  (test "#:scale 1e308 (about its centre): the sprite covers the whole view" (* 32 24)
        (seen lit-count giant))
  ;; each texel is 1e308 px: the view sees the four about the centre (14, 9)
  (test "... its four middle texels meeting at its centre, exactly there"
        (list sp-red sp-green sp-blue sp-white sp-red sp-green sp-blue sp-white)
        (seen (lambda (px) (list (px 13 8) (px 14 8) (px 13 9) (px 14 9) (px 0 0) (px 31 0) (px 0 23) (px 31 23)))
              giant))
  (test "... mirrored, the texels swap sides" (list sp-green sp-red sp-white sp-blue)
        (seen (lambda (px) (list (px 13 8) (px 14 8) (px 13 9) (px 14 9)))
              (append giant (list #:flip-x? #t))))
  (test "#:scale 1e308 about its top-left corner: it covers the view right of and below #:x #:y, in its first texel"
        (list '(10 5 31 23) sp-red sp-red)
        (seen (lambda (px) (list (lit-box px) (px 10 5) (px 31 23)))
              (append giant (list #:origin-x 0 #:origin-y 0))))
  (test "#:scale-x 1e308 alone: a band the sprite's height, the whole width" '(0 5 31 12)
        (seen lit-box (list #:type 'giant #:x 10 #:y 5 #:tile-id 2 #:scale-x 1e308)))
  (test "#:scale 1000: 8000 px, drawn by SDL as it is, covers the view" (* 32 24)
        (seen lit-count (list #:x 10 #:y 5 #:tile-id 1 #:scale 1000)))
  (test "#:scale 1e6: cut on whole texels like 1e308, its centre exactly where it is"
        (list sp-red sp-green sp-blue sp-white)
        (seen (lambda (px) (list (px 13 8) (px 14 8) (px 13 9) (px 14 9)))
              (list #:x 10 #:y 5 #:tile-id 1 #:scale 1000000)))
  (test "#:scale 1e308 turned 45 degrees is not drawn, and is no error" 0
        (seen lit-count (append giant (list #:angle 45))))
  (test "a sprite at #:x 1e308 with #:sprite-offset-x 1e308 is off the view, not an error" 0
        (seen lit-count (list #:type 'far #:x 1e308 #:y 0 #:tile-id 1 #:sprite-offset-x 1e308)))
  (test "a NaN in #:tint is an error naming the entity and the key"
        "entity coin 3: #:tint is (+nan.0 0 0), not (r g b)"
        (message-of (lambda () (sp-draw (list #:type 'coin #:id 3 #:x 0 #:y 0 #:tile-id 1 #:tint (list +nan.0 0 0))))))
  (test "a tint of (+inf.0 -inf.0 1e308) is held to (255 0 255): red stays, green goes, white is magenta"
        (list sp-red sp-black '(0 0 255 255) '(255 0 255 255))
        (seen (lambda (px) (quadrants px 0 0)) (list #:x 0 #:y 0 #:tile-id 1 #:tint (list +inf.0 -inf.0 1e308))))
  (test "a box entity at #:x +nan.0 is an error naming the entity and the key"
        "entity crate 2: #:x is +nan.0, not a finite real number"
        (message-of (lambda () (sp-draw (list #:type 'crate #:id 2 #:x +nan.0 #:y 0 #:width 4 #:height 4
                                              #:color '(200 0 0))))))
  (test "a box 1.7e308 wide from -1e308 covers the view" (* 32 24)
        (seen lit-count (list #:x -1e308 #:y -10 #:width 1.7e308 #:height 100 #:color '(200 0 0))))
  ;; an emitter whose particles fly 1e308 px a frame: after a step each
  ;; one born before is past the largest flonum, off the view
  (let loop ((frame 0)
             (e (plist->entity
                 (list #:type 'fountain #:x 10 #:y 10
                       #:emitter (make-emitter rate: 1 speed: 1e308 angle: 0 lifetime: 100 size: '(2 2))))))
    (when (< frame 6)
      (let ((e (step-particles #f e 16)))
        (test (sprintf "an emitter speed of 1e308, frame ~a: ~a particles, only the newborn one drawn"
                       frame (+ frame 1))
              '(9 9 10 10) (handle-exceptions exn (error-text exn) (seen lit-box e)))
        (loop (+ frame 1) e)))))

;; An animated entity before apply-animation ever ran (a frozen scene,
;; a title drawn over it): no #:tile-id yet, its current frame is drawn.
(test-group "sprites: an animated entity shows its frame before the pipeline runs"
  (let ((anims (list '((#:name . idle) (#:frames . (2 1)) (#:duration . 5))
                     '((#:name . walk) (#:frames . (1 2)) (#:duration . 5)))))
    (test "no #:tile-id: the first animation's first frame (the yellow tile)" sp-yellow
          ((sp-draw (list #:x 3 #:y 2 #:animations anims)) 5 5))
    (test "#:anim-name and #:anim-frame choose it" (list sp-red sp-green sp-blue sp-white)
          (quadrants (sp-draw (list #:x 3 #:y 2 #:animations anims #:anim-name 'idle #:anim-frame 1)) 3 2))
    (test "the sprite path too (#:alpha)" sp-yellow
          ((sp-draw (list #:x 3 #:y 2 #:animations anims #:alpha 255)) 5 5))
    (test "a #:tile-id, once written, is what is drawn" (list sp-red sp-green sp-blue sp-white)
          (quadrants (sp-draw (list #:x 3 #:y 2 #:animations anims #:tile-id 1)) 3 2))))

(destroy-texture! quads-tex)
(destroy-texture! solids-tex)
(free-surface! sp-surface)
(delete-directory sp-dir #t)
