;;; Drawing a Tiled map's layers (parallax, tint, image layers, object
;;; layers, layer order, debug outlines of objects, orientations) and map
;;; objects as entities (tilemap-objects->entities, game-load-scene!'s
;;; objects->entities: and prefabs:). Pixels are read back from a software
;;; renderer on a surface. The PNGs and TMX maps are made here, in a
;;; temporary directory.

(import scheme (chicken base) (chicken file) (chicken format) (chicken string) (chicken condition)
        srfi-4 (downstroke test) (downstroke sdl2) (downstroke entity)
        (downstroke scene) (downstroke tilemap) (downstroke renderer)
        (downstroke prefabs) (downstroke engine) (only (downstroke animation) apply-animation))
(include-relative "../../tests/pixels.scm")

(unless (sdl-initialized?) (init!))

(define ly-dir (create-temporary-directory))
(define (ly-path name) (string-append ly-dir "/" name))

(define ly-red '(255 0 0 255))
(define ly-green '(0 255 0 255))
(define ly-blue '(0 0 255 255))
(define ly-white '(255 255 255 255))
(define ly-yellow '(255 255 0 255))
(define ly-magenta '(255 0 255 255))
(define ly-cyan '(0 255 255 255))
(define ly-orange '(255 128 0 255))
(define ly-purple '(128 0 128 255))
(define ly-bg '(10 20 30 255))

;; Draw into a fresh W x H RGBA surface, then call (proc r).
(define (ly-with-canvas w h proc)
  (let* ((s (create-rgba-surface! w h))
         (r (create-software-renderer! s)))
    (proc r)
    (img-save-png! s (ly-path "tmp.png"))
    (free-surface! s)))

(define (ly-fill! r c x y w h)
  (apply render-draw-color-set! r c)
  (render-fill-rect! r (make-rect x y w h)))

;; tiles.png: four 8x8 tiles in a row.
;;   gid 1: quadrants red | green / blue | white    gid 2: yellow
;;   gid 3: magenta                                 gid 4: cyan
(let* ((s (create-rgba-surface! 32 8))
       (r (create-software-renderer! s)))
  (ly-fill! r ly-red 0 0 4 4) (ly-fill! r ly-green 4 0 4 4)
  (ly-fill! r ly-blue 0 4 4 4) (ly-fill! r ly-white 4 4 4 4)
  (ly-fill! r ly-yellow 8 0 8 8) (ly-fill! r ly-magenta 16 0 8 8)
  (ly-fill! r ly-cyan 24 0 8 8)
  (img-save-png! s (ly-path "tiles.png"))
  (free-surface! s))

;; back.png, the image layers' picture: 6x4, left half orange, right purple.
(let* ((s (create-rgba-surface! 6 4))
       (r (create-software-renderer! s)))
  (ly-fill! r ly-orange 0 0 3 4) (ly-fill! r ly-purple 3 0 3 4)
  (img-save-png! s (ly-path "back.png"))
  (free-surface! s))

;; A TMX file of 8x8 tiles holding the tileset above twice: gids 1-4
;; (object alignment unspecified) and gids 5-8 (objectalignment topleft).
;; body: the layers' XML; map-attrs: extra attributes of <map>.
(define (ly-write-map! name w h body #!key (map-attrs "") (orientation "orthogonal"))
  (let ((path (ly-path name)))
    (with-output-to-file path
      (lambda ()
        (printf "<?xml version=\"1.0\" encoding=\"UTF-8\"?>~%")
        (printf "<map version=\"1.10\" orientation=\"~a\" renderorder=\"right-down\" width=\"~a\" height=\"~a\" tilewidth=\"8\" tileheight=\"8\" infinite=\"0\" ~a>~%"
                orientation w h map-attrs)
        (printf " <tileset firstgid=\"1\" name=\"t\" tilewidth=\"8\" tileheight=\"8\" tilecount=\"4\" columns=\"4\">~%")
        (printf "  <image source=\"tiles.png\" width=\"32\" height=\"8\"/>~% </tileset>~%")
        (printf " <tileset firstgid=\"5\" name=\"tl\" tilewidth=\"8\" tileheight=\"8\" tilecount=\"4\" columns=\"4\" objectalignment=\"topleft\">~%")
        (printf "  <image source=\"tiles.png\" width=\"32\" height=\"8\"/>~% </tileset>~%")
        (display body)
        (printf "</map>~%")))
    path))

;; A tile layer's XML: cells given as (col row gid) in a W x H grid.
(define (ly-tile-layer name w h attrs . cells)
  (string-append
   (sprintf " <layer name=\"~a\" width=\"~a\" height=\"~a\" ~a>\n  <data encoding=\"csv\">\n" name w h attrs)
   (string-intersperse
    (let rows ((j 0))
      (if (= j h)
          '()
          (cons (string-intersperse
                 (let cols ((i 0))
                   (if (= i w)
                       '()
                       (cons (number->string
                              (let find ((cs cells))
                                (cond ((null? cs) 0)
                                      ((and (= (car (car cs)) i) (= (cadr (car cs)) j)) (caddr (car cs)))
                                      (else (find (cdr cs))))))
                             (cols (+ i 1)))))
                 ",")
                (rows (+ j 1)))))
    ",\n")
   "\n  </data>\n </layer>\n"))

(define ly-surface (create-rgba-surface! 32 24))
(define ly-renderer (create-software-renderer! ly-surface))
(define ly-tex (img-load-texture! ly-renderer (ly-path "tiles.png")))
(define ly-back-tex (img-load-texture! ly-renderer (ly-path "back.png")))
(define ly-textures (list (cons (ly-path "tiles.png") ly-tex)
                          (cons (ly-path "back.png") ly-back-tex)))

;; Draw the map at `path` through a camera at (cx, cy); answer (x y) -> colour.
(define (ly-draw path cx cy #!key (entities '()) (debug? #f) (background '(10 20 30)))
  (render-scene! ly-renderer
                 (make-scene tilemap: (load-tilemap path) entities: entities
                             background: background camera: (make-camera x: cx y: cy))
                 textures: ly-textures debug?: debug?)
  (renderer-pixels ly-renderer))

(define (ly-near? expected actual)
  (let loop ((a expected) (b actual))
    (or (null? a) (and (<= (abs (- (car a) (car b))) 1) (loop (cdr a) (cdr b))))))

(test-group "layers: parallax"
  (let ((px (ly-draw (ly-write-map! "par.tmx" 10 6
                                    (string-append
                                     (ly-tile-layer "plain" 10 6 "" '(3 2 4))
                                     (ly-tile-layer "far" 10 6 "parallaxx=\"0.5\" parallaxy=\"0\"" '(2 0 2))))
                     8 8)))
    (test "factor 1: the tile at x 24 is drawn at 24 - 8" (list ly-bg ly-cyan ly-cyan ly-bg)
          (list (px 15 8) (px 16 8) (px 23 15) (px 24 8)))
    (test "factor 0.5: the camera's 8 px move the layer 4 px (x 16 drawn at 12)"
          (list ly-bg ly-yellow ly-yellow ly-bg)
          (list (px 11 0) (px 12 0) (px 19 7) (px 20 0)))
    (test "parallaxy 0: the layer does not move vertically" (list ly-yellow ly-bg)
          (list (px 12 7) (px 12 8))))
  (let ((px (ly-draw (ly-write-map! "par-origin.tmx" 10 6
                                    (ly-tile-layer "far" 10 6 "parallaxx=\"0.5\"" '(2 0 2))
                                    map-attrs: "parallaxoriginx=\"16\"")
                     8 0)))
    (test "with parallax origin 16 the layer camera is 16 + (8 - 16) * 0.5 = 12"
          (list ly-bg ly-yellow ly-yellow ly-bg)
          (list (px 3 0) (px 4 0) (px 11 0) (px 12 0))))
  (let ((px (ly-draw (ly-write-map! "par-group.tmx" 10 6
                                    (string-append
                                     " <group name=\"g\" parallaxx=\"0.5\">\n"
                                     (ly-tile-layer "far" 10 6 "parallaxx=\"0.5\"" '(2 0 2))
                                     " </group>\n"))
                     16 0)))
    (test "a group's factor multiplies its children's: 0.25 * 16 = 4, x 16 at 12"
          (list ly-bg ly-yellow ly-bg) (list (px 11 0) (px 12 0) (px 20 0))))
  (let ((px (ly-draw (ly-write-map! "par-offset.tmx" 10 6
                                    (ly-tile-layer "far" 10 6 "parallaxx=\"0\" offsetx=\"3\"" '(1 0 3)))
                     40 0)))
    (test "factor 0 with an offset: fixed on screen at x 8 + 3" (list ly-bg ly-magenta ly-magenta ly-bg)
          (list (px 10 0) (px 11 0) (px 18 0) (px 19 0)))))

(test-group "layers: tint"
  (let ((px (ly-draw (ly-write-map! "tint.tmx" 4 3
                                    (ly-tile-layer "t" 4 3 "tintcolor=\"#ff8080\"" '(0 0 2) '(1 0 1)))
                     0 0)))
    (test "tintcolor multiplies the tile's colour: yellow x (255 128 128)" '(255 128 0 255) (px 0 0))
    (test "white x (255 128 128)" '(255 128 128 255) (px 13 5))
    (test "red stays red" ly-red (px 9 1))
    (test "the texture has no colour modulation afterwards" '(255 255 255)
          (receive (r g b) (texture-color-mod ly-tex) (list r g b)))
    (test "nor alpha" 255 (texture-alpha-mod ly-tex)))
  (let ((px (ly-draw (ly-write-map! "tint-group.tmx" 4 3
                                    (string-append
                                     " <group name=\"g\" tintcolor=\"#8080ff\">\n"
                                     (ly-tile-layer "t" 4 3 "tintcolor=\"#ff8080\"" '(0 0 2))
                                     " </group>\n"))
                     0 0)))
    (test "a group's tint multiplies its children's: (128 64 128) on yellow" '(128 64 0 255)
          (px 3 3)))
  (let ((px (ly-draw (ly-write-map! "tint-alpha.tmx" 4 3
                                    (ly-tile-layer "t" 4 3 "tintcolor=\"#80ffffff\"" '(0 0 2)))
                     0 0 background: '(0 0 0))))
    (test-assert "a tint's alpha (#80 = 128) is multiplied into the layer's opacity"
                 (ly-near? '(128 128 0) (px 2 2))))
  (let ((px (ly-draw (ly-write-map! "tint-sprite.tmx" 4 3
                                    (ly-tile-layer "t" 4 3 "tintcolor=\"#0000ff\"" '(0 0 2)))
                     0 0 entities: (list (list #:x 16 #:y 8 #:tile-id 2)))))
    (test "a tinted layer: yellow x blue is black" '(0 0 0 255) (px 1 1))
    (test "a sprite drawn from the same texture afterwards is not tinted" ly-yellow (px 17 9))))

(test-group "layers: image layers"
  (let ((px (ly-draw (ly-write-map! "img.tmx" 4 3
                                    " <imagelayer name=\"sky\" offsetx=\"5\" offsety=\"3\">\n  <image source=\"back.png\" width=\"6\" height=\"4\"/>\n </imagelayer>\n")
                     1 1)))
    (test "the image at its offset minus the camera: (4, 2) to (9, 5)"
          (list ly-orange ly-orange ly-purple ly-purple)
          (list (px 4 2) (px 6 5) (px 7 2) (px 9 5)))
    (test "nothing around it" (list ly-bg ly-bg ly-bg ly-bg)
          (list (px 3 2) (px 10 2) (px 4 1) (px 4 6))))
  (let ((px (ly-draw (ly-write-map! "img-repeat.tmx" 4 3
                                    " <imagelayer name=\"sky\" offsetx=\"2\" offsety=\"3\" repeatx=\"1\">\n  <image source=\"back.png\" width=\"6\" height=\"4\"/>\n </imagelayer>\n")
                     0 0)))
    (test "repeatx: copies every 6 px across the view (..., -4, 2, 8, ..., 26)"
          (list ly-purple ly-purple ly-orange ly-purple ly-orange ly-purple)
          (list (px 0 3) (px 1 3) (px 2 3) (px 5 3) (px 26 3) (px 31 6)))
    (test "only along x" (list ly-bg ly-bg) (list (px 2 2) (px 2 7))))
  (let ((px (ly-draw (ly-write-map! "img-repeat-xy.tmx" 4 3
                                    " <imagelayer name=\"sky\" repeatx=\"1\" repeaty=\"true\">\n  <image source=\"back.png\" width=\"6\" height=\"4\"/>\n </imagelayer>\n")
                     0 2)))
    (test "repeatx and repeaty tile the whole view (camera y 2: rows start at -2)"
          (list ly-orange ly-purple ly-orange ly-orange ly-purple)
          (list (px 0 0) (px 3 1) (px 0 2) (px 6 21) (px 29 23))))
  (let ((px (ly-draw (ly-write-map! "img-par.tmx" 4 3
                                    (string-append
                                     " <imagelayer name=\"sky\" parallaxx=\"0\" opacity=\"0.5\">\n  <image source=\"back.png\" width=\"6\" height=\"4\"/>\n </imagelayer>\n"
                                     " <imagelayer name=\"hidden\" visible=\"0\" parallaxx=\"0\" offsety=\"6\">\n  <image source=\"back.png\" width=\"6\" height=\"4\"/>\n </imagelayer>\n"))
                     20 0 background: '(0 0 0))))
    (test-assert "parallax 0 keeps it at x 0 with the camera at 20; opacity 0.5 halves it"
                 (ly-near? '(128 64 0) (px 0 0)))
    (test "an invisible image layer is not drawn (it would be at y 6..9)" '(0 0 0 255) (px 0 7)))
  (let ((px (ly-draw (ly-write-map! "img-tint.tmx" 4 3
                                    " <imagelayer name=\"tinted\" tintcolor=\"#00ffff\">\n  <image source=\"back.png\" width=\"6\" height=\"4\"/>\n </imagelayer>\n")
                     0 0)))
    (test "an image layer's tint: orange x cyan, purple x cyan" '((0 128 0 255) (0 0 128 255))
          (list (px 0 0) (px 5 0))))
  (test-error "an image with no texture is an error naming the image and the layer"
              (lambda (e) (and (substring-index (ly-path "back.png") (error-text e))
                               (substring-index "image layer \"sky\"" (error-text e))))
              (render-scene! ly-renderer
                             (make-scene tilemap: (load-tilemap (ly-path "img.tmx")))
                             textures: (list (cons (ly-path "tiles.png") ly-tex)))))

;; An object layer's XML from object element strings.
(define (ly-object-layer name attrs . objects)
  (string-append (sprintf " <objectgroup name=\"~a\" ~a>\n" name attrs)
                 (apply string-append objects)
                 " </objectgroup>\n"))

(define (ly-tile-object id gid x y #!optional (extra ""))
  (sprintf "  <object id=\"~a\" gid=\"~a\" x=\"~a\" y=\"~a\" width=\"8\" height=\"8\" ~a/>\n"
           id gid x y extra))

(test-group "layers: tile objects"
  (let ((px (ly-draw (ly-write-map! "obj.tmx" 4 3
                                    (ly-object-layer "o" ""
                                                     (ly-tile-object 1 2 8 16)
                                                     (ly-tile-object 2 (+ 1 #x80000000) 16 8)
                                                     (ly-tile-object 3 2 0 24 "visible=\"0\"")))
                     0 0)))
    (test "a tile object hangs from its bottom-left corner: (8, 16) covers x 8..15, y 8..15"
          (list ly-yellow ly-yellow ly-bg ly-bg ly-bg)
          (list (px 8 8) (px 15 15) (px 8 16) (px 8 7) (px 7 8)))
    (test "a horizontally flipped tile object is mirrored" (list ly-green ly-red ly-white ly-blue)
          (list (px 17 1) (px 22 1) (px 17 6) (px 22 6)))
    (test "an invisible object is not drawn" ly-bg (px 1 20)))
  (let ((px (ly-draw (ly-write-map! "obj-scale.tmx" 4 3
                                    (ly-object-layer "o" ""
                                                     "  <object id=\"1\" gid=\"1\" x=\"0\" y=\"16\" width=\"16\" height=\"16\"/>\n"
                                                     (ly-tile-object 2 6 16 4)))
                     0 0)))
    (test "an object larger than its tile stretches it (quadrants 8x8)"
          (list ly-red ly-red ly-green ly-blue ly-white)
          (list (px 0 0) (px 7 7) (px 8 0) (px 0 8) (px 15 15)))
    (test "objectalignment topleft: (16, 4) is the top-left corner" (list ly-bg ly-yellow ly-yellow ly-bg)
          (list (px 16 3) (px 16 4) (px 23 11) (px 23 12))))
  (let ((px (ly-draw (ly-write-map! "obj-rot.tmx" 4 3
                                    (ly-object-layer "o" "" (ly-tile-object 1 1 0 8 "rotation=\"90\"")))
                     0 0)))
    (test "rotation 90 turns the tile clockwise about its bottom-left corner"
          (list ly-blue ly-red ly-white ly-green ly-bg)
          (list (px 1 9) (px 6 9) (px 1 14) (px 6 14) (px 1 7))))
  (let ((px (ly-draw (ly-write-map! "obj-order.tmx" 4 3
                                    (string-append
                                     (ly-object-layer "top" "draworder=\"topdown\""
                                                      (ly-tile-object 1 3 4 12)
                                                      (ly-tile-object 2 2 0 8))
                                     (ly-object-layer "idx" "draworder=\"index\" offsetx=\"16\""
                                                      (ly-tile-object 3 3 4 12)
                                                      (ly-tile-object 4 2 0 8))))
                     0 0)))
    (test "topdown: the lower object is drawn last, whatever the file order" ly-magenta (px 5 5))
    (test "index: file order; the layer's offset moves its objects" ly-yellow (px 21 5))))

(test-group "layers: tileset offsets"
  (let ((path (ly-path "offset.tmx")))
    (with-output-to-file path
      (lambda ()
        (display "<?xml version=\"1.0\" encoding=\"UTF-8\"?>
<map version=\"1.10\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"4\" height=\"3\" tilewidth=\"8\" tileheight=\"8\" infinite=\"0\">
 <tileset firstgid=\"1\" name=\"t\" tilewidth=\"8\" tileheight=\"8\" tilecount=\"4\" columns=\"4\">
  <tileoffset x=\"2\" y=\"1\"/>
  <image source=\"tiles.png\" width=\"32\" height=\"8\"/>
 </tileset>
 <layer name=\"t\" width=\"4\" height=\"3\"><data encoding=\"csv\">0,0,0,0,0,2,0,0,0,0,0,0</data></layer>
 <objectgroup name=\"o\"><object id=\"1\" gid=\"4\" x=\"0\" y=\"24\" width=\"8\" height=\"8\"/></objectgroup>
</map>
")))
    (let ((px (ly-draw path 0 0)))
      (test "a tile layer's cells move by their tileset's <tileoffset>: (8, 8) + (2, 1)"
            (list ly-bg ly-yellow ly-yellow ly-bg) (list (px 9 9) (px 10 9) (px 17 16) (px 18 16)))
      (test "and so do tile objects: (0, 16) + (2, 1)" (list ly-bg ly-cyan ly-cyan)
            (list (px 1 17) (px 2 17) (px 9 23))))
    (test "the object's box says so too" '(2 17 8 8)
          (receive (x y w h) (tilemap-object-box (load-tilemap path)
                                                 (car (tilemap-objects (load-tilemap path))))
            (list x y w h)))))

(test-group "layers: sdl2 additions"
  (test "current-video-driver under the test suites' dummy driver" "dummy" (current-video-driver))
  (test "renderer-name of a software renderer" "software" (renderer-name ly-renderer))
  (texture-color-mod-set! ly-tex 1 2 3)
  (test "texture-color-mod reads back what was set" '(1 2 3)
        (receive (r g b) (texture-color-mod ly-tex) (list r g b)))
  (texture-color-mod-set! ly-tex 255 255 255)
  (test-error "a colour component out of range" (texture-color-mod-set! ly-tex 256 0 0)))

(test-group "layers: layer order"
  (let ((px (ly-draw (ly-write-map! "order.tmx" 4 3
                                    (string-append
                                     (ly-tile-layer "below" 4 3 "" '(0 0 4) '(1 0 4))
                                     " <imagelayer name=\"img\" offsetx=\"2\">\n  <image source=\"back.png\" width=\"6\" height=\"4\"/>\n </imagelayer>\n"
                                     (ly-object-layer "o" "" (ly-tile-object 1 2 4 8))
                                     (ly-tile-layer "above" 4 3 "" '(1 0 3))))
                     0 0)))
    (test "a tile layer under everything shows where nothing covers it" ly-cyan (px 0 5))
    (test "the image layer over it" ly-orange (px 2 2))
    (test "the object layer over the image layer" ly-yellow (px 4 0))
    (test "the last tile layer on top of the objects" ly-magenta (px 8 0))))

(test-group "layers: debug outlines of objects"
  (let ((px (ly-draw (ly-write-map! "dbg.tmx" 4 3
                                    (ly-object-layer "o" ""
                                                     "  <object id=\"1\" x=\"2\" y=\"3\" width=\"6\" height=\"4\"/>\n"
                                                     "  <object id=\"2\" x=\"20\" y=\"2\" width=\"6\" height=\"6\"><ellipse/></object>\n"
                                                     "  <object id=\"3\" x=\"12\" y=\"12\"><point/></object>\n"))
                     0 0 debug?: #t)))
    (test "a rectangle object's outline, in *debug-object-color*"
          (list ly-magenta ly-magenta ly-magenta ly-bg ly-bg)
          (list (px 2 3) (px 7 6) (px 2 6) (px 4 5) (px 8 3)))
    (test "an ellipse is outlined by its box" (list ly-magenta ly-magenta) (list (px 20 2) (px 25 7)))
    (test "a point is one pixel" (list ly-magenta ly-bg) (list (px 12 12) (px 13 12))))
  (let ((px (ly-draw (ly-path "dbg.tmx") 0 0)))
    (test "without debug?: shapes are not drawn" ly-bg (px 2 3))))

(test-group "layers: orientations other than orthogonal"
  ;; gid 2 at cell (0, 0) of a 4x3 map of 8x8 cells: Tiled puts its image
  ;; at x 0..7, y 0..7 on orthogonal, staggered and hexagonal maps (row 0
  ;; is not staggered), and at x 8..15 on an isometric one (the diamond's
  ;; top corner is at x = 3 rows * 4, the tile's left half a tile before).
  (define (draw o)
    (let ((path (ly-write-map! (string-append o ".tmx") 4 3 (ly-tile-layer "t" 4 3 "" '(0 0 2))
                               orientation: o
                               map-attrs: (if (equal? o "orthogonal") ""
                                              "staggeraxis=\"y\" staggerindex=\"odd\" hexsidelength=\"4\""))))
      (render-scene! ly-renderer (make-scene tilemap: (load-tilemap path) background: '(0 0 0))
                     textures: ly-textures)
      (renderer-pixels ly-renderer)))
  (let ((tile-colour ((draw "orthogonal") 4 4)))
    (test-assert "the tile is not the background" (not (equal? tile-colour '(0 0 0 255))))
    (for-each
     (lambda (o x)
       (let ((px (draw o)))
         (test (string-append "render-scene! draws a " o " map's tile where Tiled does")
               (list tile-colour '(0 0 0 255))
               (list (px x 4) (px (- 16 x) 4)))))
     '("isometric" "staggered" "hexagonal")
     '(12 4 4))))

(test-group "layers: debug outlines of an isometric map's objects"
  ;; a rectangle at (8, 0), 8 x 8 on a 4 x 3 isometric map of 8 x 8 cells:
  ;; its corners project to (16, 4) (20, 8) (12, 8) (16, 12), so its
  ;; outline is the box from (12, 4) to (20, 12)
  (let* ((path (ly-write-map! "iso-objects.tmx" 4 3
                              "<objectgroup id=\"9\" name=\"o\"><object id=\"1\" x=\"8\" y=\"0\" width=\"8\" height=\"8\"/></objectgroup>\n"
                              orientation: "isometric"))
         (px (begin (render-scene! ly-renderer (make-scene tilemap: (load-tilemap path) background: '(0 0 0))
                                   textures: ly-textures debug?: #t)
                    (renderer-pixels ly-renderer))))
    (test "the outline's corners and sides are where the projected box is"
          (list ly-magenta ly-magenta ly-magenta ly-magenta)
          (list (px 12 4) (px 19 4) (px 12 11) (px 19 8)))
    (test "and nothing where the unprojected box would be" '(0 0 0 255) (px 8 2))))

(test-group "layers: tilemap-hide-layers"
  (let* ((tm (load-tilemap
              (ly-write-map! "hide.tmx" 4 3
                             (string-append
                              (ly-tile-layer "ground" 4 3 "" '(0 0 2))
                              " <group name=\"g\">\n"
                              (ly-object-layer "spawns" "" (ly-tile-object 1 2 8 16))
                              (ly-tile-layer "deco" 4 3 "" '(3 2 4))
                              " </group>\n"))))
         (hidden (tilemap-hide-layers tm (lambda (l) (equal? (layer-name l) "spawns"))))
         (group-hidden (tilemap-hide-layers tm (lambda (l) (equal? (layer-name l) "g"))))
         (vis (lambda (m) (map (lambda (l) (list (layer-name l) (layer-visible? l)))
                               (tilemap-all-layers m)))))
    (test "only the chosen layer is hidden"
          '(("ground" #t) ("g" #t) ("spawns" #f) ("deco" #t)) (vis hidden))
    (test "hiding a group hides its children"
          '(("ground" #t) ("g" #f) ("spawns" #f) ("deco" #f)) (vis group-hidden))
    (test "the original is unchanged" '(("ground" #t) ("g" #t) ("spawns" #t) ("deco" #t)) (vis tm))
    (test "objects are still listed" 1 (length (tilemap-objects hidden)))
    (test "tile layers follow the copies; cells and solidity are kept"
          '(#f 4 #t) (list (layer-visible? (tilemap-layer group-hidden "deco"))
                           (tilemap-tile-at group-hidden 3 2 "deco")
                           (tilemap-solid? group-hidden 3 2)))))

;;; ------------------------------------------------------------------
;;; Objects as entities

(define ly-objects-map
  (ly-write-map! "things.tmx" 6 4
                 (string-append
                  (ly-tile-layer "ground" 6 4 "" '(0 3 4))
                  (ly-object-layer
                   "things" ""
                   "  <object id=\"1\" name=\"bag\" type=\"coin\" x=\"16\" y=\"8\" width=\"8\" height=\"6\">
   <properties>
    <property name=\"value\" type=\"int\" value=\"5\"/>
    <property name=\"gravity?\" type=\"bool\" value=\"true\"/>
    <property name=\"color\" type=\"color\" value=\"#ff00ff00\"/>
    <property name=\"tags\" value=\"pickup, shiny\"/>
    <property name=\"width\" type=\"int\" value=\"9\"/>
   </properties>
  </object>\n"
                   (ly-tile-object 2 (+ 2 #x80000000) 8 24 "class=\"crate\"")
                   "  <object id=\"3\" type=\"coin\" x=\"40\" y=\"4\"><point/></object>\n"
                   "  <object id=\"4\" x=\"10\" y=\"10\" rotation=\"30\"><polygon points=\"0,0 6,-2 4,5\"/></object>\n")
                  (ly-object-layer "other" "visible=\"0\" offsetx=\"3\" offsety=\"-2\""
                                   "  <object id=\"5\" type=\"door\" x=\"0\" y=\"0\" width=\"8\" height=\"16\"/>\n"))))

(define ly-prefabs
  (parse-prefabs '((mixins (pickup #:solid? #f #:tags (pickup)))
                   (prefabs (coin pickup #:width 4 #:height 4 #:value 1 #:color (255 255 0))))
                 source: "test prefabs"))

(test-group "objects as entities: tilemap-objects->entities"
  (let* ((es (tilemap-objects->entities (load-tilemap ly-objects-map)))
         (e (lambda (id) (let loop ((es es))
                           (cond ((null? es) #f)
                                 ((eqv? (entity-ref (car es) #:object-id) id) (car es))
                                 (else (loop (cdr es))))))))
    (test "every object of every object layer, in file order (hidden layers too)"
          '(1 2 3 4 5) (map (lambda (e) (entity-ref e #:object-id)) es))
    (test "a rectangle: type, box, name, then its properties (a property replaces a key)"
          '((#:type . coin) (#:x . 16) (#:y . 8) (#:width . 9) (#:height . 6) (#:object-id . 1)
            (#:name . "bag") (#:value . 5) (#:gravity? . #t) (#:color . (0 255 0 255))
            (#:tags . (pickup shiny)))
          (e 1))
    (test "a tile object: its box's top-left (y - height), its gid, facing -1 when flipped"
          '((#:type . crate) (#:x . 8) (#:y . 16) (#:width . 8) (#:height . 8) (#:object-id . 2)
            (#:tile-id . 2) (#:facing . -1))
          (e 2))
    (test "a point has no size" '(40 4 0 0 point)
          (map (lambda (k) (entity-ref (e 3) k)) '(#:x #:y #:width #:height #:shape)))
    (test "a polygon: its points' bounding box, points relative to it, rotation kept"
          '(#f 10 8 6 7 polygon ((0 . 2) (6 . 0) (4 . 7)) 30)
          (map (lambda (k) (entity-ref (e 4) k #f))
               '(#:type #:x #:y #:width #:height #:shape #:points #:rotation))))
  (let ((es (tilemap-objects->entities (load-tilemap ly-objects-map) layers: '("other"))))
    (test "layers: a list of names" '(door) (map entity-type es))
    (test "the layer's offset is added to the position" '(3 -2)
          (list (entity-ref (car es) #:x) (entity-ref (car es) #:y))))
  (let ((message (lambda (thunk)
                   (handle-exceptions e ((condition-property-accessor 'exn 'message "") e) (thunk) "no error"))))
    (test-assert "layers: a name that is no object layer is an error naming the file and listing them"
                 (let ((m (message (lambda () (tilemap-objects->entities (load-tilemap ly-objects-map)
                                                                         layers: '("object"))))))
                   (and (substring-index ly-objects-map m)
                        (substring-index "no object layer named \"object\"; its object layers are (\"things\" \"other\")" m))))
    (test-assert "a tile layer's name is said to hold no objects"
                 (substring-index "\"ground\" (a layer of that name holds no objects)"
                                  (message (lambda () (tilemap-objects->entities (load-tilemap ly-objects-map)
                                                                                 layers: '("ground"))))))
    (test-assert "game-load-scene!'s objects->entities: names the layer too"
                 (substring-index "no object layer named \"thing\""
                                  (message (lambda ()
                                             (game-run! (make-game headless?: #t width: 16 height: 16
                                                                   create: (lambda (g) (game-load-scene! g ly-objects-map objects->entities: '("thing"))))
                                                        frames: 1 command-line: #f))))))
  (let ((es (tilemap-objects->entities (load-tilemap ly-objects-map)
                                       layers: (lambda (l) (not (layer-visible? l))))))
    (test "layers: a predicate" '(5) (map (lambda (e) (entity-ref e #:object-id)) es)))
  (let* ((es (tilemap-objects->entities (load-tilemap ly-objects-map) prefabs: ly-prefabs))
         (bag (car es))
         (point-coin (caddr es)))
    (test "an object whose type names a prefab is instantiated from it"
          '(coin #f (pickup shiny) 5 9 6 (0 255 0 255))
          (map (lambda (k) (entity-ref bag k)) '(#:type #:solid? #:tags #:value #:width #:height #:color)))
    (test "a point keeps the prefab's size and the prefab's values it does not set"
          '(coin 40 4 4 4 1 (pickup) (255 255 0))
          (map (lambda (k) (entity-ref point-coin k))
               '(#:type #:x #:y #:width #:height #:value #:tags #:color)))
    (test "objects of other types are converted plainly" '(crate #f)
          (list (entity-type (cadr es)) (entity-ref (cadr es) #:solid? #f))))
  ;; a prefab that cannot be instantiated: its first animation is not an entity
  (test-error "a failing conversion names the map, the object layer and the object"
              (lambda (e) (substring-index
                           (sprintf "~a: object layer \"things\", object 1 (\"bag\"): " ly-objects-map)
                           (error-text e)))
              (tilemap-objects->entities
               (load-tilemap ly-objects-map)
               prefabs: (parse-prefabs '((prefabs (coin animated #:animations ((1 2))))))))
  (test-error "prefabs: must be a prefab collection"
              (lambda (e) (substring-index "prefabs:" (error-text e)))
              (tilemap-objects->entities (load-tilemap ly-objects-map) prefabs: '(coin)))
  (test-error "layers: must be #t, #f, names or a predicate"
              (lambda (e) (substring-index "layers:" (error-text e)))
              (tilemap-objects->entities (load-tilemap ly-objects-map) layers: 'things)))

;; A headless game whose create: loads a scene with `args`; update: and
;; render: receive the game. Answers the game after `frames` frames.
(define (ly-run-game frames create #!key (update #f) (render #f))
  (let ((g (make-game headless?: #t width: 32 height: 24 create: create
                      update: update render: render)))
    (game-run! g frames: frames)
    g))

(define (ly-game-pixel g x y) (renderer-pixel (game-renderer g) x y))

(test-group "objects as entities: game-load-scene!"
  (let* ((seen #f)
         (g (ly-run-game
             0 (lambda (g)
                 (let ((scene (game-load-scene! g ly-objects-map camera-target: #f
                                                entities: (list (list #:type 'player #:x 0 #:y 0)))))
                   (set! seen (list (map entity-type (scene-entities scene))
                                    (layer-visible? (car (tilemap-object-layers (scene-tilemap scene)))))))))))
    (test "by default no object becomes an entity, and the object layers stay visible"
          '((player) #t) seen))
  (let* ((seen #f)
         (g (ly-run-game
             0 (lambda (g)
                 (let ((scene (game-load-scene! g ly-objects-map camera-target: #f prefabs: ly-prefabs
                                                entities: (list (list #:type 'player #:x 0 #:y 0)))))
                   (set! seen (list (map entity-type (scene-entities scene))
                                    (entity-ref (car (scene-entities scene)) #:solid? 'none)
                                    (map layer-visible? (tilemap-object-layers (scene-tilemap scene)))
                                    (length (tilemap-objects (scene-tilemap scene))))))))))
    (test "prefabs: alone converts every object layer, prefabs applied, the caller's entities last"
          '((coin crate coin #f door player) #f (#f #f) 5) seen))
  (let* ((seen #f)
         (g (ly-run-game
             0 (lambda (g)
                 (let ((scene (game-load-scene! g ly-objects-map camera-target: #f
                                                objects->entities: '("other"))))
                   (set! seen (list (map entity-type (scene-entities scene))
                                    (map layer-visible? (tilemap-object-layers (scene-tilemap scene))))))))))
    (test "objects->entities: names converts and hides those layers only" '((door) (#t #f)) seen))
  ;; A tile object drawn once: as its entity, which update: moves 8 px right.
  (let* ((shots '())
         (path (ly-write-map! "once.tmx" 4 3
                              (ly-object-layer "o" "" (ly-tile-object 1 2 0 8 "class=\"box\""))))
         (run (lambda (convert)
                (let ((g (ly-run-game
                          1 (lambda (g) (game-load-scene! g path camera-target: #f background: '(10 20 30)
                                                          objects->entities: convert))
                          update: (lambda (g dt)
                                    (game-scene-set!
                                     g (scene-map-entities
                                        (game-scene g)
                                        (lambda (s e) (entity-set e #:x (+ (entity-ref e #:x) 8))))))
                          render: (lambda (g)
                                    (set! shots (cons (list (ly-game-pixel g 1 1) (ly-game-pixel g 9 1))
                                                      shots))))))
                  (car shots)))))
    (test "converted: the tile object is drawn only where its entity now is"
          (list ly-bg ly-yellow) (run #t))
    (test "not converted: the object layer draws it where it was" (list ly-yellow ly-bg) (run #f)))
  (let* ((seen #f)
         (path (ly-write-map! "with-image.tmx" 4 3
                              " <imagelayer name=\"sky\" offsetx=\"1\">\n  <image source=\"back.png\" width=\"6\" height=\"4\"/>\n </imagelayer>\n"))
         (g (ly-run-game 1 (lambda (g) (game-load-scene! g path camera-target: #f))
                         render: (lambda (g) (set! seen (list (ly-game-pixel g 1 0) (ly-game-pixel g 6 3)
                                                              (ly-game-pixel g 0 0)))))))
    (test "game-load-scene! loads image layers' images and the game draws them"
          (list ly-orange ly-purple '(0 0 0 255)) seen))
  (let* ((iso (ly-write-map! "iso-game.tmx" 4 3 (ly-tile-layer "t" 4 3 "" '(0 0 2))
                             orientation: "isometric"))
         (outcome #f)
         (before #f)
         (g (ly-run-game
             0 (lambda (g)
                 (game-load-scene! g ly-objects-map camera-target: #f)
                 (set! before (list (game-scene g) (game-textures g)))
                 (set! outcome (game-load-scene! g iso))
                 (set! before (list (eq? (car before) (game-scene g))
                                    (eq? (cadr before) (game-textures g))
                                    (texture-alive? (cdar (game-textures g)))))))))
    (test "game-load-scene! loads an isometric map" #t (scene? outcome))
    (test "and it becomes the game's scene, its textures the game's" '(#f #f #t) before)))

(test-group "game-load-scene!: the map's background colour; animated tiles in game time"
  ;; gid 2 animates: yellow (local 1) for 100 ms, then magenta (local 2)
  ;; for 100 ms, round again; frames are 16 ms, drawn at frames-run * 16.
  (let ((path (ly-path "animated.tmx")))
    (with-output-to-file path
      (lambda ()
        (print "<?xml version=\"1.0\" encoding=\"UTF-8\"?>")
        (print "<map version=\"1.10\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"4\" height=\"3\" tilewidth=\"8\" tileheight=\"8\" infinite=\"0\" backgroundcolor=\"#102030\">")
        (print " <tileset firstgid=\"1\" name=\"t\" tilewidth=\"8\" tileheight=\"8\" tilecount=\"4\" columns=\"4\">")
        (print "  <image source=\"tiles.png\" width=\"32\" height=\"8\"/>")
        (print "  <tile id=\"1\"><animation><frame tileid=\"1\" duration=\"100\"/><frame tileid=\"2\" duration=\"100\"/></animation></tile>")
        (print " </tileset>")
        (print " <layer id=\"1\" name=\"l\" width=\"4\" height=\"3\"><data encoding=\"csv\">2,0,0,0,0,0,0,0,0,0,0,0</data></layer>")
        (print "</map>")))
    (define (run frames #!optional (background #f))
      (let* ((seen #f)
             (g (ly-run-game frames
                             (lambda (g) (if background
                                             (game-load-scene! g path camera-target: #f background: background)
                                             (game-load-scene! g path camera-target: #f)))
                             render: (lambda (g) (set! seen (list (ly-game-pixel g 4 4)
                                                                  (ly-game-pixel g 20 20)))))))
        seen))
    (test "the map's backgroundcolor is the scene's background; the tile's first frame at 16 ms"
          (list ly-yellow '(16 32 48 255)) (run 1))
    (test "background: wins over the map's colour" '(1 2 3 255) (cadr (run 1 '(1 2 3))))
    (test "the second frame at 112 ms" ly-magenta (car (run 7)))
    (test "still the second at 192 ms" ly-magenta (car (run 12)))
    (test "the first again at 208 ms" ly-yellow (car (run 13)))
    (test-error "render-scene!'s time: must be a finite number"
                (lambda (e) (substring-index "time: must be a finite number of milliseconds" (error-text e)))
                (render-scene! ly-renderer (make-scene tilemap: (load-tilemap path))
                               textures: ly-textures time: +nan.0))))

(test-group "objects as entities: a tile object keeps its Tiled animation"
  ;; gid 2 animates: local 1 for 100 ms, local 2 for 150 ms, local 3 for 100 ms
  (let ((path (ly-path "animated-objects.tmx")))
    (with-output-to-file path
      (lambda ()
        (print "<?xml version=\"1.0\" encoding=\"UTF-8\"?>")
        (print "<map version=\"1.10\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"4\" height=\"3\" tilewidth=\"8\" tileheight=\"8\" infinite=\"0\">")
        (print " <tileset firstgid=\"1\" name=\"t\" tilewidth=\"8\" tileheight=\"8\" tilecount=\"4\" columns=\"4\">")
        (print "  <image source=\"tiles.png\" width=\"32\" height=\"8\"/>")
        (print "  <tile id=\"1\"><animation><frame tileid=\"1\" duration=\"100\"/><frame tileid=\"2\" duration=\"150\"/><frame tileid=\"3\" duration=\"100\"/></animation></tile>")
        (print " </tileset>")
        (print " <objectgroup id=\"2\" name=\"coins\">")
        (print "  <object id=\"1\" type=\"coin\" gid=\"2\" x=\"8\" y=\"16\" width=\"8\" height=\"8\"/>")
        (print "  <object id=\"2\" type=\"coin\" gid=\"3\" x=\"16\" y=\"16\" width=\"8\" height=\"8\"/>")
        (print " </objectgroup>")
        (print "</map>")))
    (let* ((tm (load-tilemap path))
           (es (tilemap-objects->entities tm))
           (frames (lambda (e) (let ((as (entity-ref e #:animations #f)))
                                 (and as (entity-ref (car as) #:frames))))))
      ;; ends at 100, 250, 350 ms: ticks 6.25, 15.6, 21.9 -> 6, 16, 22
      (test "its frames are gids, each ending on the 16 ms tick nearest Tiled's end" '((2 . 6) (3 . 10) (4 . 6))
            (frames (car es)))
      (test "the animation is named tiled" 'tiled (entity-ref (car (entity-ref (car es) #:animations)) #:name))
      (test "a tile Tiled does not animate gets none" #f (frames (cadr es)))
      (test "frame-delay: sets the tick (10 ms: 10, 15, 10)" '((2 . 10) (3 . 15) (4 . 10))
            (frames (car (tilemap-objects->entities tm frame-delay: 10))))
      (test "a prefab's own #:animations win" '((7 . 1))
            (frames (car (tilemap-objects->entities
                          tm prefabs: (parse-prefabs '((prefabs (coin #:animations (((#:name . spin) (#:frames . ((7 . 1))))))))
                                                     source: "test prefabs")))))
      (test "it plays with the pipeline's animation step: tile 2 for 6 frames, then 3"
            '(2 2 2 2 2 2 3)
            (let loop ((i 0) (e (car es)) (out '()))
              (if (= i 7)
                  (reverse out)
                  (let ((e2 (apply-animation #f e 16)))
                    (loop (+ i 1) e2 (cons (entity-ref e2 #:tile-id) out)))))))))

(free-surface! ly-surface)
;; ly-dir is removed by written-maps-test.scm, which compares its maps with Tiled's export
