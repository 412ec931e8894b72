;;; (downstroke renderer): render-scene! into a software renderer on a
;;; surface, pixels read back. The tileset PNG and the TMX map are made here.

(import scheme (chicken base) (chicken file) (chicken format) (chicken string)
        srfi-4 (downstroke test) (downstroke sdl2) (downstroke entity)
        (downstroke scene) (downstroke tilemap) (downstroke renderer))
(include-relative "../../tests/pixels.scm")

(init!)

(define rn-dir (create-temporary-directory))
(define (rn-path name) (string-append rn-dir "/" name))

;; The tileset: 8x8 tiles, 2 columns, margin 2, spacing 1 (image 21x21), the
;; margin and spacing grey so a wrong source rect shows.
;;   local 0 (gid 1): quadrants red | green / blue | white
;;   local 1 (gid 2): yellow   local 2 (gid 3): magenta   local 3 (gid 4): cyan
(define rn-red '(255 0 0 255))
(define rn-green '(0 255 0 255))
(define rn-blue '(0 0 255 255))
(define rn-white '(255 255 255 255))
(define rn-yellow '(255 255 0 255))
(define rn-cyan '(0 255 255 255))

(define (rn-make-tileset path)
  (let* ((s (create-rgba-surface! 21 21))
         (r (create-software-renderer! s))
         (fill (lambda (c x y w h)
                 (apply render-draw-color-set! r c)
                 (render-fill-rect! r (make-rect x y w h)))))
    (render-draw-color-set! r 128 128 128)
    (render-clear! r)
    (fill rn-red 2 2 4 4) (fill rn-green 6 2 4 4)
    (fill rn-blue 2 6 4 4) (fill rn-white 6 6 4 4)
    (fill rn-yellow 11 2 8 8)
    (fill '(255 0 255) 2 11 8 8)
    (fill rn-cyan 11 11 8 8)
    (img-save-png! s path)
    (free-surface! s)))

(rn-make-tileset (rn-path "tiles.png"))

;; A TMX map from layers, each (rows . extra-attributes-string).
(define (rn-map name width height layers)
  (let ((path (rn-path name)))
    (with-output-to-file path
      (lambda ()
        (printf "<?xml version=\"1.0\" encoding=\"UTF-8\"?>~%")
        (printf "<map version=\"1.10\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"~a\" height=\"~a\" tilewidth=\"8\" tileheight=\"8\" infinite=\"0\">~%" width height)
        (printf " <tileset firstgid=\"1\" name=\"t\" tilewidth=\"8\" tileheight=\"8\" spacing=\"1\" margin=\"2\" tilecount=\"4\" columns=\"2\">~%")
        (printf "  <image source=\"tiles.png\" width=\"21\" height=\"21\"/>~% </tileset>~%")
        (let loop ((ls layers) (i 1))
          (unless (null? ls)
            (printf " <layer id=\"~a\" name=\"l~a\" width=\"~a\" height=\"~a\" ~a>~%  <data encoding=\"csv\">~%"
                    i i width height (cdar ls))
            (printf "~a~%  </data>~% </layer>~%"
                    (string-intersperse
                     (map (lambda (row) (string-intersperse (map number->string row) ","))
                          (caar ls))
                     ",\n"))
            (loop (cdr ls) (+ i 1))))
        (printf "</map>~%")))
    (load-tilemap path)))

;; An empty W x H grid with `gid` at (col, row).
(define (rn-grid w h . placements)
  (let loop-rows ((j 0) (rows '()))
    (if (= j h)
        (reverse rows)
        (loop-rows (+ j 1)
                   (cons (let loop-cols ((i 0) (row '()))
                           (if (= i w)
                               (reverse row)
                               (loop-cols (+ i 1)
                                          (cons (let find ((ps placements))
                                                  (cond ((null? ps) 0)
                                                        ((and (= (car (car ps)) i) (= (cadr (car ps)) j))
                                                         (caddr (car ps)))
                                                        (else (find (cdr ps)))))
                                                row))))
                         rows)))))

;; The 32x24 target every test draws into, and its one texture.
(define rn-surface (create-rgba-surface! 32 24))
(define rn-renderer (create-software-renderer! rn-surface))
(define rn-texture (img-load-texture! rn-renderer (rn-path "tiles.png")))
(define rn-textures (list (cons (rn-path "tiles.png") rn-texture)))

(define rn-bg '(10 20 30))
(define rn-bg-pixel '(10 20 30 255))

;; Draw a scene and answer a procedure (x y) -> (r g b a).
(define (rn-draw scene . options)
  (apply render-scene! rn-renderer scene options)
  (renderer-pixels rn-renderer))

(define (rn-map-scene tm cam-x cam-y . entities)
  (make-scene tilemap: tm entities: entities background: rn-bg
              camera: (make-camera x: cam-x y: cam-y)))

(define (rn-all-pixels? px pixel)
  (let loop ((y 0))
    (or (= y 24)
        (and (let row ((x 0)) (or (= x 32) (and (equal? (px x y) pixel) (row (+ x 1)))))
             (loop (+ y 1))))))

(test-group "renderer: background"
  (test-assert "the background colour fills the frame"
               (rn-all-pixels? (rn-draw (make-sprite-scene background: rn-bg)) rn-bg-pixel))
  (test-assert "no background is black"
               (rn-all-pixels? (rn-draw (make-sprite-scene)) '(0 0 0 255))))

(test-group "renderer: colour entities"
  (let ((px (rn-draw (make-scene background: rn-bg camera: (make-camera x: 4 y: 2)
                                 entities: (list (list #:x 12 #:y 5 #:width 6 #:height 4
                                                       #:color '(200 100 50)))))))
    (test "top-left corner at its position minus the camera" '(200 100 50 255) (px 8 3))
    (test "bottom-right corner" '(200 100 50 255) (px 13 6))
    (test "nothing left of it" rn-bg-pixel (px 7 3))
    (test "nothing above it" rn-bg-pixel (px 8 2))
    (test "nothing right of it" rn-bg-pixel (px 14 3))
    (test "nothing below it" rn-bg-pixel (px 8 7)))
  (let ((px (rn-draw (make-scene background: rn-bg camera: (make-camera x: 4.5 y: 0)
                                 entities: (list (list #:x 12 #:y 0 #:width 2 #:height 2
                                                       #:color '(1 2 3)))))))
    (test "screen x = floor(x - camera-x): 12 - 4.5 = 7.5 is pixel 7" '(1 2 3 255) (px 7 0))
    (test "and the rect is 2 pixels wide" '((1 2 3 255) (10 20 30 255)) (list (px 8 0) (px 9 0))))
  (let ((px (rn-draw (make-scene background: rn-bg
                                 entities: (list (list #:x 0 #:y 0 #:width 4 #:height 4 #:color '(50 50 50))
                                                 (list #:x 2 #:y 0 #:width 4 #:height 4 #:color '(90 90 90))
                                                 (list #:x 20 #:y 0 #:width 4 #:height 4))))))
    (test "entities draw in list order, later on top" '((50 50 50 255) (90 90 90 255))
          (list (px 1 0) (px 2 0)))
    (test "an entity with neither tile nor colour draws nothing" rn-bg-pixel (px 21 1)))
  (let ((px (rn-draw (make-scene background: '(0 0 0)
                                 entities: (list (list #:x 0 #:y 0 #:width 4 #:height 4
                                                       #:color '(200 0 0 128)))))))
    (test-assert "a colour's alpha blends" (<= 98 (car (px 1 1)) 102))))

(test-group "renderer: a zoomed camera"
  (let ((px (rn-draw (make-scene background: rn-bg camera: (make-camera x: 4 y: 2 zoom: 2)
                                 entities: (list (list #:x 12 #:y 5 #:width 6 #:height 4
                                                       #:color '(200 100 50)))))))
    (test "zoom 2: the top-left corner at twice its position minus the camera" '(200 100 50 255) (px 16 6))
    (test "and the box twice as large" '(200 100 50 255) (px 27 13))
    (test "nothing past it" (list rn-bg-pixel rn-bg-pixel) (list (px 28 13) (px 27 14)))
    (test "nothing before it" (list rn-bg-pixel rn-bg-pixel) (list (px 15 6) (px 16 5))))
  (let* ((scene (make-scene background: rn-bg camera: (make-camera x: 4 y: 2 zoom: 2)
                            entities: (list (list #:x 12 #:y 5 #:width 6 #:height 4 #:color '(9 9 9)))))
         (ignored (rn-draw scene))
         (px (rn-draw (update-scene scene camera: (make-camera x: 4 y: 2)))))
    (test "the renderer's scale is restored: the next unzoomed frame is drawn at 1:1"
          (list '(9 9 9 255) rn-bg-pixel) (list (px 13 6) (px 14 6)))))

(test-group "renderer: tiles"
  (let* ((tm (rn-map "one.tmx" 6 4 (list (cons (rn-grid 6 4 '(3 1 2)) ""))))
         (px (rn-draw (rn-map-scene tm 5 3) textures: rn-textures)))
    (test "a tile appears at its cell minus the camera" rn-yellow (px 19 5))
    (test "its far corner" rn-yellow (px 26 12))
    (test "left of it is background" rn-bg-pixel (px 18 5))
    (test "right of it is background" rn-bg-pixel (px 27 12))
    (test "below it is background" rn-bg-pixel (px 19 13)))
  (let* ((tm (rn-map "cyan.tmx" 4 3 (list (cons (rn-grid 4 3 '(1 1 4)) ""))))
         (px (rn-draw (rn-map-scene tm 0 0) textures: rn-textures)))
    (test "margin and spacing: the last tile is all cyan"
          (list rn-cyan rn-cyan rn-cyan rn-cyan)
          (list (px 8 8) (px 15 8) (px 8 15) (px 15 15))))
  (let* ((tm (rn-map "textures.tmx" 4 3 (list (cons (rn-grid 4 3 '(0 0 2)) ""))))
         (scene (rn-map-scene tm 0 0)))
    (test "textures: may be a procedure" rn-yellow
          ((rn-draw scene textures: (lambda (path) (and (equal? path (rn-path "tiles.png")) rn-texture)))
           0 0))
    (test "the scene's tileset-texture serves its tileset" rn-yellow
          ((rn-draw (update-scene scene tileset-texture: rn-texture)) 0 0))
    (test-error "a tileset image with no texture is an error naming it"
                (lambda (e) (substring-index (rn-path "tiles.png") (error-text e)))
                (rn-draw scene))))

(test-group "renderer: flips"
  (define (quadrants gid)
    (let* ((tm (rn-map (sprintf "flip-~a.tmx" gid) 4 3 (list (cons (rn-grid 4 3 (list 0 0 gid)) ""))))
           (px (rn-draw (rn-map-scene tm 0 0) textures: rn-textures)))
      ;; top-left, top-right, bottom-left, bottom-right
      (list (px 1 1) (px 6 1) (px 1 6) (px 6 6))))
  (test "unflipped" (list rn-red rn-green rn-blue rn-white) (quadrants 1))
  (test "a horizontally flipped tile is mirrored" (list rn-green rn-red rn-white rn-blue)
        (quadrants (+ 1 #x80000000)))
  (test "a vertically flipped tile" (list rn-blue rn-white rn-red rn-green)
        (quadrants (+ 1 #x40000000)))
  (test "a diagonally flipped tile is transposed" (list rn-red rn-blue rn-green rn-white)
        (quadrants (+ 1 #x20000000)))
  (test "diagonal then horizontal" (list rn-blue rn-red rn-white rn-green)
        (quadrants (+ 1 #xA0000000)))
  (test "diagonal then vertical" (list rn-green rn-white rn-red rn-blue)
        (quadrants (+ 1 #x60000000))))

(test-group "renderer: culling keeps partly visible tiles"
  ;; view 32x24 at camera (4, 4): columns 0..4 and rows 0..3 are touched
  (let* ((tm (rn-map "edges.tmx" 10 8
                     (list (cons (rn-grid 10 8 '(0 0 2) '(4 1 2) '(1 3 4)) ""))))
         (px (rn-draw (rn-map-scene tm 4 4) textures: rn-textures)))
    (test "the left edge tile (-4..3) shows its right half" rn-yellow (px 0 0))
    (test "the right edge tile (28..35) shows its left part" rn-yellow (px 31 4))
    (test "the bottom edge tile (20..27) shows its top" rn-cyan (px 4 23)))
  (let* ((tm (rn-map "frac.tmx" 10 8 (list (cons (rn-grid 10 8 '(4 0 2)) ""))))
         (px (rn-draw (rn-map-scene tm 3.5 0) textures: rn-textures)))
    (test "fractional camera: column 4 at floor(32 - 3.5) = 28" (list rn-bg-pixel rn-yellow)
          (list (px 27 0) (px 28 0)))))

(test-group "renderer: layers"
  (let* ((tm (rn-map "layers.tmx" 4 3
                     (list (cons (rn-grid 4 3 '(0 0 2)) "")
                           (cons (rn-grid 4 3 '(0 0 4)) "offsetx=\"3\" offsety=\"2\"")
                           (cons (rn-grid 4 3 '(2 0 2) '(0 0 1)) "visible=\"0\""))))
         (px (rn-draw (rn-map-scene tm 0 0) textures: rn-textures)))
    (test "layers draw in order; the offset layer is on top, moved by its offset"
          (list rn-yellow rn-yellow rn-cyan rn-cyan rn-bg-pixel)
          (list (px 0 0) (px 3 1) (px 3 2) (px 10 9) (px 11 2)))
    (test "an invisible layer is not drawn" rn-bg-pixel (px 17 1)))
  (let* ((tm (rn-map "opacity.tmx" 4 3 (list (cons (rn-grid 4 3 '(0 0 2)) "opacity=\"0.5\""))))
         (px (make-scene tilemap: tm background: '(0 0 0)))
         (pixel ((rn-draw px textures: rn-textures) 0 0)))
    (test-assert "layer opacity is the texture's alpha" (and (<= 125 (car pixel) 130)
                                                            (= 0 (caddr pixel))))
    (test "and the texture is opaque again afterwards" 255 (texture-alpha-mod rn-texture))))

(test-group "renderer: sprites"
  (let* ((tm (rn-map "sprites.tmx" 4 3 (list (cons (rn-grid 4 3) ""))))
         (px (rn-draw (make-scene tilemap: tm background: rn-bg tileset-texture: rn-texture
                                  camera: (make-camera x: 2 y: 1)
                                  entities: (list (list #:x 12 #:y 11 #:width 8 #:height 8 #:tile-id 2)
                                                  (list #:x 2 #:y 1 #:width 8 #:height 8 #:tile-id 1)
                                                  (list #:x 22 #:y 1 #:width 8 #:height 8 #:tile-id 1
                                                        #:facing -1))))))
    (test "a #:tile-id sprite at its position minus the camera" (list rn-yellow rn-yellow rn-bg-pixel)
          (list (px 10 10) (px 17 17) (px 9 10)))
    (test "tile-id 1 is the tileset's first tile" (list rn-red rn-green) (list (px 1 1) (px 6 1)))
    (test "#:facing -1 mirrors the sprite" (list rn-green rn-red) (list (px 21 1) (px 26 1)))))

(test-group "renderer: sprites from a tileset without a map"
  ;; The same sheet twice: described in code, and as a lone .tsx whose gids
  ;; start at 5. Either one draws a sprite scene's #:tile-id.
  (with-output-to-file (rn-path "sheet.tsx")
    (lambda ()
      (display "<?xml version=\"1.0\"?>\n<tileset name=\"t\" tilewidth=\"8\" tileheight=\"8\" spacing=\"1\" margin=\"2\" tilecount=\"4\" columns=\"2\">\n <image source=\"tiles.png\" width=\"21\" height=\"21\"/>\n</tileset>\n")))
  (define (sprites ts first)
    (rn-draw (make-sprite-scene tileset: ts tileset-texture: rn-texture background: rn-bg
                                entities: (list (list #:x 0 #:y 0 #:tile-id first)
                                                (list #:x 10 #:y 0 #:tile-id (+ first 3))
                                                (list #:x 20 #:y 0 #:tile-id (+ first 1) #:facing -1)))))
  (for-each
   (lambda (name ts first)
     (let ((px (sprites ts first)))
       (test (string-append name ": the first tile, cut past margin and spacing")
             (list rn-red rn-green rn-blue rn-white) (list (px 0 0) (px 7 0) (px 0 7) (px 7 7)))
       (test (string-append name ": the fourth tile") (list rn-cyan rn-cyan rn-bg-pixel)
             (list (px 10 0) (px 17 7) (px 18 0)))
       (test (string-append name ": the second tile, mirrored") (list rn-yellow rn-yellow)
             (list (px 20 0) (px 27 7)))))
   '("make-sheet-tileset" "load-tileset")
   (list (make-sheet-tileset (rn-path "tiles.png") tile-width: 8 tile-height: 8 columns: 2
                             spacing: 1 margin: 2 tile-count: 4)
         (load-tileset (rn-path "sheet.tsx") first-gid: 5))
   '(1 5)))


;; Values from a map far outside SDL's int range: each draws (or is
;; culled) without error, and nothing wraps into the view.
(test-group "renderer: far-away layers and objects from a map"
  (let* ((path (rn-path "far.tmx"))
         (_ (with-output-to-file path
              (lambda ()
                (printf "<?xml version=\"1.0\"?><map version=\"1.10\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"4\" height=\"3\" tilewidth=\"8\" tileheight=\"8\">~%")
                (printf "<tileset firstgid=\"1\" name=\"t\" tilewidth=\"8\" tileheight=\"8\" spacing=\"1\" margin=\"2\" tilecount=\"4\" columns=\"2\"><image source=\"tiles.png\" width=\"21\" height=\"21\"/></tileset>~%")
                (printf "<group id=\"1\" name=\"far\" offsetx=\"1e308\"><layer id=\"2\" name=\"g\" width=\"4\" height=\"3\"><data encoding=\"csv\">1,1,1,1,1,1,1,1,1,1,1,1</data></layer></group>~%")
                (printf "<layer id=\"3\" name=\"p\" width=\"4\" height=\"3\" parallaxx=\"1e308\"><data encoding=\"csv\">2,2,2,2,2,2,2,2,2,2,2,2</data></layer>~%")
                (printf "<objectgroup id=\"4\" name=\"o\"><object id=\"1\" x=\"4\" y=\"4\" width=\"8\" height=\"9223372036854775807\"/>~%")
                (printf "<object id=\"2\" gid=\"4\" x=\"-1e300\" y=\"8\" width=\"8\" height=\"8\"/></objectgroup></map>~%"))))
         (tm (load-tilemap path))
         (draw (lambda (cam-x) (rn-draw (make-scene tilemap: tm background: rn-bg
                                                    camera: (make-camera x: cam-x y: 0))
                                        textures: rn-textures))))
    (test "the group's offset is 1e308" 1e308 (layer-offset-x (car (tilemap-layers tm))))
    (let ((px (draw 0)))
      (test "the layer 1e308 px away is not drawn; the parallax layer at camera 0 is"
            (list rn-yellow rn-yellow) (list (px 0 20) (px 31 0)))
      (test "nothing of the 1e300-px tile object wraps into the view" #t
            (not (member rn-cyan (map (lambda (x) (px x 12)) '(0 4 8 16 24 31))))))
    (let* ((px (draw 1))
           (tile-colours (list rn-red rn-green rn-blue rn-white rn-yellow rn-cyan)))
      (test "with the camera at 1 the parallax layer is 1e308 px away too: no tile pixel in the frame" 0
            (let count ((y 0) (x 0) (n 0))
              (cond ((= y 24) n)
                    ((= x 32) (count (+ y 1) 0 n))
                    (else (count y (+ x 1) (if (member (px x y) tile-colours) (+ n 1) n)))))))
    (let* ((tile-colours (list rn-red rn-green rn-blue rn-white rn-yellow rn-cyan))
           (count (lambda (px)
                    (let loop ((y 0) (x 0) (n 0))
                      (cond ((= y 24) n)
                            ((= x 32) (loop (+ y 1) 0 n))
                            (else (loop y (+ x 1) (if (member (px x y) tile-colours) (+ n 1) n))))))))
      ;; the layer camera is 2 * 1e308, past the largest flonum
      (test "with the camera at 2 the parallax layer's camera overflows: not drawn, and no error" 0
            (handle-exceptions exn (error-text exn) (count (draw 2))))
      (test "... nor at -2, nor with a flonum camera" '(0 0)
            (handle-exceptions exn (error-text exn) (list (count (draw -2)) (count (draw 2.5))))))))

(free-surface! rn-surface)
(delete-directory rn-dir #t)
