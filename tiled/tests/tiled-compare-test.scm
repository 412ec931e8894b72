;;; Maps drawn by Downstroke next to Tiled's own renderer, tmxrasterizer
;;; (Tiled 1.8): Tiled's example maps (tests/data, tools/fetch-tiled-examples.sh)
;;; and small maps written here, one per drawing feature.
;;;
;;; How a case compares. tmxrasterizer draws the map into a picture the size
;;; of the map's screen size (tilemap-screen-size) grown by the layers' offsets
;;; (Tiled's margins: a layer at offset -0.5 adds a pixel on the left); it
;;; leaves the background transparent, so its picture is laid over black.
;;; Downstroke draws the same map over black through a camera at minus the
;;; left and top margins, so both pictures share their origin. Tiled is
;;; run with --no-smoothing: a game scales images to the nearest pixel. A region of
;;; both is compared pixel by pixel; a pixel differs when a channel differs
;;; by more than the case's tolerance (default 2: Qt and SDL round alpha
;;; blending differently by a unit or two), and a case passes when at most
;;; the case's `allowed` pixels differ (default 0).
;;;
;;; Without tmxrasterizer (CI installs Tiled with tools/install-deps.sh;
;;; a machine without it still runs these), the region is compared with the
;;; reference picture tests/tiled-refs/NAME.png, which is tmxrasterizer's
;;; own output for that region, written by running this suite with
;;; DOWNSTROKE_WRITE_REFS=1 where Tiled is installed (DOWNSTROKE_NO_TILED=1
;;; uses the references even then). With
;;; DOWNSTROKE_TILED_OUT=DIR, Downstroke's and Tiled's pictures of every
;;; case are written to DIR (to look at them), and NAME-side.png with the
;;; two side by side (docs/images/tiled-*.png are some of those).

(import scheme (chicken base) (chicken file) (chicken format) (chicken string)
        (chicken process) (chicken pathname) (chicken process-context) srfi-4
        (downstroke test) (downstroke sdl2) (downstroke scene) (downstroke camera)
        (downstroke tilemap) (downstroke renderer) (downstroke level) (downstroke mapdraw))
(include-relative "../../tests/pixels.scm")

(init!)

(define tc-dir (create-temporary-directory))
(define (tc-path name) (string-append tc-dir "/" name))
(define tc-refs "tiled-refs")
(define tc-examples "data/tiled-examples")
(define tc-out (get-environment-variable "DOWNSTROKE_TILED_OUT"))
(define tc-write-refs? (get-environment-variable "DOWNSTROKE_WRITE_REFS"))

;; DOWNSTROKE_NO_TILED=1 compares with the reference pictures even where
;; Tiled is installed (to check them).
(define tc-tiled?
  (and (not (get-environment-variable "DOWNSTROKE_NO_TILED"))
       (zero? (system "command -v tmxrasterizer >/dev/null 2>&1"))))
(unless (file-exists? (make-pathname tc-examples ".complete"))
  (system "sh ../tools/fetch-tiled-examples.sh >/dev/null 2>&1"))
(define tc-examples? (file-exists? (make-pathname tc-examples ".complete")))

;; Tiled's margins around the map for its layers' offsets:
;; (values left top right bottom), whole pixels.
(define (tc-margins tm)
  (let loop ((ls (tilemap-all-layers tm)) (l 0) (t 0) (r 0) (b 0))
    (if (null? ls)
        (values l t r b)
        (let ((ox (layer-offset-x (car ls))) (oy (layer-offset-y (car ls))))
          (loop (cdr ls)
                (max l (ceiling-int (- ox))) (max t (ceiling-int (- oy)))
                (max r (ceiling-int ox)) (max b (ceiling-int oy)))))))

;; The map's part of Tiled's picture: (values width height x y), x y the
;; map pixel at its top-left corner. An infinite orthogonal map's picture
;; covers its chunks' bounds rounded out to Tiled's 16-cell chunks (the
;; staggered example's start at 0 and need no rounding).
(define (tc-picture tm)
  (receive (w h) (tilemap-screen-size tm)
    (if (and (tilemap-infinite? tm) (eq? (tilemap-orientation tm) 'orthogonal))
        (let* ((c0 (* 16 (floor-int (/ (tilemap-origin-col tm) 16))))
               (r0 (* 16 (floor-int (/ (tilemap-origin-row tm) 16))))
               (c1 (* 16 (ceiling-int (/ (+ (tilemap-origin-col tm) (tilemap-width tm)) 16))))
               (r1 (* 16 (ceiling-int (/ (+ (tilemap-origin-row tm) (tilemap-height tm)) 16))))
               (tw (tilemap-tile-width tm)) (th (tilemap-tile-height tm)))
          (values (* tw (- c1 c0)) (* th (- r1 r0)) (* tw c0) (* th r0)))
        (values w h 0 0))))

;; RGBA bytes of a w x h picture laid over opaque black.
(define (tc-over-black bytes)
  (let* ((n (u8vector-length bytes)) (out (make-u8vector n 255)))
    (do ((i 0 (+ i 4))) ((= i n) out)
      (let ((a (u8vector-ref bytes (+ i 3))))
        (do ((c 0 (+ c 1))) ((= c 3))
          (u8vector-set! out (+ i c) (quotient (+ (* (u8vector-ref bytes (+ i c)) a) 127) 255)))))))

;; The region (x y w h) of RGBA bytes w pixels wide.
(define (tc-crop bytes bw x y w h)
  (let ((out (make-u8vector (* w h 4) 0)))
    (do ((j 0 (+ j 1))) ((= j h) out)
      (do ((i 0 (+ i 1))) ((= i (* 4 w)))
        (u8vector-set! out (+ (* j w 4) i) (u8vector-ref bytes (+ (* (+ y j) bw 4) (* x 4) i)))))))

;; Downstroke's picture and Tiled's side by side, 8 white pixels apart,
;; a picture narrower than 300 pixels enlarged (nearest pixel) 2 to 4 times.
(define (tc-save-side! ours tiled w h path)
  (let* ((k (max 1 (min 4 (quotient 600 w))))
         (sw (+ (* k w) 8 (* k w))) (sh (* k h))
         (out (make-u8vector (* sw sh 4) 255)))
    (do ((y 0 (+ y 1))) ((= y sh))
      (do ((x 0 (+ x 1))) ((= x (* k w)))
        (do ((c 0 (+ c 1))) ((= c 4))
          (let ((from (+ (* (quotient y k) w 4) (* (quotient x k) 4) c)))
            (u8vector-set! out (+ (* y sw 4) (* x 4) c) (u8vector-ref ours from))
            (u8vector-set! out (+ (* y sw 4) (* (+ x (* k w) 8) 4) c) (u8vector-ref tiled from))))))
    (tc-save! out sw sh path)))

(define (tc-save! bytes w h path)
  (let ((s (rgba-pixels->surface! bytes w h)))
    (img-save-png! s path)
    (free-surface! s)))

;; How many pixels differ by more than `tolerance` in a channel.
(define (tc-diff-count a b tolerance)
  (let ((n (u8vector-length a)))
    (let loop ((i 0) (count 0))
      (if (>= i n)
          count
          (loop (+ i 4)
                (if (or (> (abs (- (u8vector-ref a i) (u8vector-ref b i))) tolerance)
                        (> (abs (- (u8vector-ref a (+ i 1)) (u8vector-ref b (+ i 1)))) tolerance)
                        (> (abs (- (u8vector-ref a (+ i 2)) (u8vector-ref b (+ i 2)))) tolerance))
                    (+ count 1)
                    count))))))

;; Downstroke's picture of the map: (values bytes w h) for the region
;; (x y w h) of Tiled's picture, whose origin is at (-left, -top) margins.
(define (tc-draw tm left top x y w h time)
  (let* ((s (create-rgba-surface! w h))
         (r (create-software-renderer! s))
         (textures (load-tilemap-textures! r tm)))
    (render-scene! r (make-scene tilemap: tm background: '(0 0 0)
                                 camera: (make-camera x: (- x left) y: (- y top) bounds: #f))
                   textures: textures time: time)
    (receive (bytes bw bh) (render-read-pixels r)
      (for-each (lambda (p) (destroy-texture! (cdr p))) textures)
      (destroy-renderer! r)
      (free-surface! s)
      (values bytes bw bh))))

;; Tiled's picture of the region, over black: live from tmxrasterizer, or
;; the reference picture. #f when neither is there.
(define (tc-tiled name tmx hide time region expect-w expect-h)
  (let ((ref (make-pathname tc-refs name "png")))
    (cond (tc-tiled?
           (let ((out (tc-path (string-append name "-tiled.png"))))
             (system (sprintf "QT_QPA_PLATFORM=offscreen tmxrasterizer --no-smoothing ~a --advance-animations ~a ~a ~a >/dev/null 2>&1"
                              (string-intersperse (map (lambda (l) (sprintf "--hide-layer ~a" (qs l))) hide) " ")
                              time (qs tmx) (qs out)))
             (receive (bytes w h) (png-rgba out)
               (test (sprintf "~a: Tiled's picture is ~ax~a (the map's screen size and margins)"
                              name expect-w expect-h)
                     (list expect-w expect-h) (list w h))
               (let ((cut (apply tc-crop bytes w region)))
                 (when tc-write-refs?
                   (tc-save! cut (caddr region) (cadddr region) ref))
                 (tc-over-black cut)))))
          ((file-exists? ref)
           (receive (bytes w h) (png-rgba ref) (tc-over-black bytes)))
          (else #f))))

;; One comparison (see the head of this file). hide: layer names hidden
;; in both pictures (shapes Downstroke draws only in its debug overlay);
;; region: (x y w h) of Tiled's picture, default all of it; known: why
;; Tiled 1.8 is wrong here, when it is (the allowance then says how much).
(define (tc-compare name tmx #!key (hide '()) (time 0) (region #f) (tolerance 2) (allowed 0)
                    (known #f))
  (let* ((tm0 (load-tilemap tmx))
         (tm (if (null? hide) tm0
                 (tilemap-hide-layers tm0 (lambda (l) (member (layer-name l) hide))))))
    (receive (mw mh ox oy) (tc-picture tm)
      (receive (ml mt mr mb) (tc-margins tm)
        (let* ((pw (+ mw ml mr)) (ph (+ mh mt mb))
               (ml (- ml ox)) (mt (- mt oy))
               (region (or region (list 0 0 pw ph)))
               (tiled (tc-tiled name tmx hide time region pw ph)))
          (if (not tiled)
              (print "  (skipped " name ": no tmxrasterizer and no reference picture)")
              (receive (ours w h) (apply tc-draw tm ml mt (append region (list time)))
                (when tc-out
                  (create-directory tc-out #t)
                  (tc-save! ours w h (make-pathname tc-out (string-append name "-downstroke") "png"))
                  (tc-save! tiled w h (make-pathname tc-out (string-append name "-tiled") "png"))
                  (tc-save-side! ours tiled w h (make-pathname tc-out (string-append name "-side") "png")))
                (let ((n (tc-diff-count ours tiled tolerance)))
                  (test (sprintf "~a: at most ~a of ~a pixels differ from Tiled's~a"
                                 name allowed (* w h) (if known (string-append " (" known ")") ""))
                        #t (<= n allowed))
                  (when (> n allowed)
                    (print "    " n " pixels differ"))))))))))

;;; ------------------------------------------------------------------
;;; Tiled's example maps

(when tc-examples?
  (test-group "Tiled's examples next to tmxrasterizer"
    (define (ex f) (make-pathname tc-examples f))
    (tc-compare "desert" (ex "desert.tmx") region: '(0 0 320 320))
    (tc-compare "sewers" (ex "sewers.tmx") region: '(96 96 288 240))
    ;; its tileset's <image> has no width or height: read from the PNG
    (let ((ts (car (tilemap-tilesets (load-tilemap (ex "perspective_walls.tmx"))))))
      (test "perspective_walls: columns and tile count from the image itself (256 x 256 of 64 x 64)"
            '(4 16 256 256)
            (list (tileset-columns ts) (tileset-tile-count ts)
                  (image-width (tileset-image ts)) (image-height (tileset-image ts)))))
    (tc-compare "perspective-walls" (ex "perspective_walls.tmx") region: '(160 160 320 320))
    (tc-compare "island" (ex "rpg/island.tmx") hide: '("Objects") region: '(160 96 320 320))
    ;; The layer "game" is hidden: its objects come from templates, and
    ;; tmxrasterizer 1.8 draws a template's tile object as an empty
    ;; rectangle (it does not load the template's tileset; the editor draws
    ;; them). The layer "shading" is drawn at opacity 0.36 from images
    ;; without an alpha channel.
    (tc-compare "sticker-knight" (ex "sticker-knight/map/sandbox.tmx") hide: '("game")
                region: '(1056 544 400 300) tolerance: 4)
    ;; the second sandbox: 0.16 shading and 0.5 light layers, rotated and
    ;; flipped tile objects
    (tc-compare "sticker-knight-2" (ex "sticker-knight/map/sandbox2.tmx") hide: '("game")
                region: '(800 440 480 320) tolerance: 4)
    ;; Isometric tiles overlap along translucent edges, which SDL and Qt
    ;; blend a few units apart: tolerance 4.
    (tc-compare "isometric" (ex "isometric_grass_and_water.tmx") region: '(704 320 192 128)
                tolerance: 4)
    (tc-compare "staggered" (ex "isometric_staggered_grass_and_water.tmx") region: '(64 64 192 128)
                tolerance: 4)
    (tc-compare "hexagonal-mini" (ex "hexagonal-mini.tmx"))
    ;; Tiles turned 60 and 120 degrees (the diagonal and hex-120 flags):
    ;; SDL and Qt sample a turned image's edge pixels differently, so up to
    ;; 3% of pixels (the hexagons' rims) may differ.
    (tc-compare "hexagonal-60" (ex "test_hexagonal_tile_60x60x30.tmx") region: '(0 0 480 320)
                allowed: 4600)))

;;; ------------------------------------------------------------------
;;; Small maps, one per feature

(define tc-colours '((200 40 40) (40 160 60) (50 80 220) (230 200 40)
                     (160 60 200) (40 200 200) (240 130 30) (120 120 120)))

;; A sheet of `n` tiles of w x h in `columns` columns, each its own colour
;; with a white top-left quarter and a black right edge, so every flip and
;; turn shows. magenta?: a magenta frame round each tile (for trans).
(define (tc-sheet! path w h n columns #!optional (magenta? #f))
  (let* ((rows (quotient (+ n columns -1) columns))
         (s (create-rgba-surface! (* w columns) (* h rows)))
         (r (create-software-renderer! s))
         (fill (lambda (c x y w h) (apply render-draw-color-set! r c)
                       (render-fill-rect! r (make-rect x y w h)))))
    (do ((i 0 (+ i 1))) ((= i n))
      (let ((x (* w (modulo i columns))) (y (* h (quotient i columns))))
        (fill (list-ref tc-colours (modulo i 8)) x y w h)
        (fill '(255 255 255) x y (quotient w 2) (quotient h 2))
        (fill '(0 0 0) (+ x w -2) y 2 h)
        (when magenta?
          (fill '(255 0 255) x y w 1) (fill '(255 0 255) x (+ y h -1) w 1))))
    (img-save-png! s path)
    (free-surface! s)))

;; A map file: attrs of <map>, tilesets and layers as XML text.
(define (tc-map! name attrs tilesets layers)
  (let ((path (tc-path (string-append name ".tmx"))))
    (with-output-to-file path
      (lambda ()
        (print "<?xml version=\"1.0\" encoding=\"UTF-8\"?>")
        (print "<map version=\"1.8\" tiledversion=\"1.8.2\" infinite=\"0\" " attrs ">")
        (for-each print tilesets)
        (for-each print layers)
        (print "</map>")))
    path))

(define (tc-tileset first name tw th n columns image iw ih #!optional (extra "") (inner ""))
  (sprintf "<tileset firstgid=\"~a\" name=\"~a\" tilewidth=\"~a\" tileheight=\"~a\" tilecount=\"~a\" columns=\"~a\" ~a>~a<image source=\"~a\" width=\"~a\" height=\"~a\"/></tileset>"
           first name tw th n columns extra inner image iw ih))

;; A tile layer of w x h cells from a list of cell values (flags allowed).
(define (tc-layer id name w h cells #!optional (extra ""))
  (sprintf "<layer id=\"~a\" name=\"~a\" width=\"~a\" height=\"~a\" ~a><data encoding=\"csv\">~a</data></layer>"
           id name w h extra (string-intersperse (map number->string cells) ",")))

(define tc-h #x80000000)
(define tc-v #x40000000)
(define tc-d #x20000000)
(define tc-flag-sets (list 0 tc-h tc-v tc-d (+ tc-h tc-v) (+ tc-h tc-d) (+ tc-v tc-d) (+ tc-h tc-v tc-d)))

;; n cells with every other one empty: gid with each flag set in turn.
(define (tc-flag-row gid)
  (foldr (lambda (f acc) (cons (+ gid f) (cons 0 acc))) '() tc-flag-sets))

(tc-sheet! (tc-path "sq.png") 8 8 8 4)
(tc-sheet! (tc-path "wide.png") 16 8 4 2)
(tc-sheet! (tc-path "tall.png") 8 16 4 4)
(tc-sheet! (tc-path "big.png") 16 16 8 4)
(tc-sheet! (tc-path "keyed.png") 8 8 4 4 #t)

(define (tc-ortho attrs w h tw th)
  (sprintf "orientation=\"orthogonal\" width=\"~a\" height=\"~a\" tilewidth=\"~a\" tileheight=\"~a\" ~a"
           w h tw th attrs))

(test-group "feature maps next to tmxrasterizer"
  ;; every flip on square tiles
  (tc-compare "flips-square"
              (tc-map! "flips-square" (tc-ortho "renderorder=\"right-down\"" 16 1 8 8)
                       (list (tc-tileset 1 "sq" 8 8 8 4 "sq.png" 32 16))
                       (list (tc-layer 1 "l" 16 1 (tc-flag-row 2)))))
  ;; every flip on wide and on tall tiles (16x8 and 8x16 on a 16x16 grid)
  (tc-compare "flips-wide"
              (tc-map! "flips-wide" (tc-ortho "renderorder=\"right-down\"" 16 2 16 16)
                       (list (tc-tileset 1 "wide" 16 8 4 2 "wide.png" 32 16)
                             (tc-tileset 5 "tall" 8 16 4 4 "tall.png" 32 16))
                       (list (tc-layer 1 "l" 16 2 (append (tc-flag-row 2) (tc-flag-row 6))))))
  ;; render orders: 16x16 tiles on an 8x8 grid overlap their neighbours
  (for-each
   (lambda (order)
     (let ((name (string-append "order-" order)))
       (tc-compare name
                   (tc-map! name (tc-ortho (sprintf "renderorder=\"~a\"" order) 4 3 8 8)
                            (list (tc-tileset 1 "big" 16 16 8 4 "big.png" 64 32))
                            (list (tc-layer 1 "l" 4 3 '(1 2 3 4 5 6 7 8 1 2 3 4)))))))
   '("right-down" "left-down" "right-up" "left-up"))
  ;; layer opacity on an RGBA sheet and on an RGB one (no alpha channel)
  (let ((rgb (tc-path "rgb.png")))
    (copy-file "maps/images/rgb-tiles.png" rgb #t)
    (for-each
     (lambda (sheet)
       (let ((name (string-append "opacity-" (car sheet))))
         (tc-compare name
                     (tc-map! name (tc-ortho "renderorder=\"right-down\"" 4 2 8 8)
                              (list (tc-tileset 1 "s" 8 8 4 4 (cadr sheet) 32 8))
                              (list (tc-layer 1 "base" 4 2 '(1 2 3 4 1 2 3 4))
                                    (tc-layer 2 "top" 4 2 '(4 3 2 1 0 0 0 0) "opacity=\"0.4\"")
                                    (tc-layer 3 "faint" 4 2 '(0 0 0 0 2 2 2 2) "opacity=\"0.1\"")))
                     ;; Qt and SDL round the blend of a translucent layer a unit apart
                     tolerance: 3)))
     '(("rgba" "sq.png") ("rgb" "rgb.png"))))
  ;; the tileset's trans colour keyed out (the tiles' magenta rims)
  (tc-compare "trans"
              (tc-map! "trans" (tc-ortho "renderorder=\"right-down\"" 4 1 8 8)
                       (list (sprintf "<tileset firstgid=\"1\" name=\"k\" tilewidth=\"8\" tileheight=\"8\" tilecount=\"4\" columns=\"4\"><image source=\"keyed.png\" trans=\"ff00ff\" width=\"32\" height=\"8\"/></tileset>"))
                       (list (tc-layer 1 "l" 4 1 '(1 2 3 4)))))
  ;; and an image layer's trans colour, at half opacity
  (tc-compare "trans-image-layer"
              (tc-map! "trans-image-layer" (tc-ortho "renderorder=\"right-down\"" 5 2 8 8)
                       '()
                       (list "<imagelayer id=\"1\" name=\"k\" offsetx=\"3\" offsety=\"2\" opacity=\"0.5\"><image source=\"keyed.png\" trans=\"ff00ff\" width=\"32\" height=\"8\"/></imagelayer>"))
              tolerance: 3)
  ;; an image without width and height: columns from the image itself
  (tc-compare "image-size"
              (tc-map! "image-size" (tc-ortho "renderorder=\"right-down\"" 4 2 8 8)
                       (list "<tileset firstgid=\"1\" name=\"s\" tilewidth=\"8\" tileheight=\"8\"><image source=\"sq.png\"/></tileset>")
                       (list (tc-layer 1 "l" 4 2 '(1 2 3 4 5 6 7 8)))))
  ;; tile offsets, half-pixel layer offsets, an image layer's old x/y
  (tc-compare "offsets"
              (tc-map! "offsets" (tc-ortho "renderorder=\"right-down\"" 4 3 8 8)
                       (list (tc-tileset 1 "s" 8 8 8 4 "sq.png" 32 16 "" "<tileoffset x=\"3\" y=\"-2\"/>"))
                       (list (tc-layer 1 "a" 4 3 '(1 0 0 0 0 0 0 0 0 0 0 0))
                             (tc-layer 2 "b" 4 3 '(0 0 0 0 0 2 0 0 0 0 0 0) "offsetx=\"0.5\" offsety=\"1.5\"")
                             (tc-layer 3 "c" 4 3 '(0 0 0 0 0 0 0 0 0 0 3 0) "offsetx=\"-0.5\" offsety=\"-2.5\"")
                             "<imagelayer id=\"4\" name=\"old\" x=\"20\" y=\"3\"><image source=\"wide.png\" width=\"32\" height=\"16\"/></imagelayer>")))
  ;; animated tiles at several times: frames of 100, 50 and 200 ms
  (for-each
   (lambda (time)
     (tc-compare (sprintf "animation-~a" time)
                 (tc-map! "animation" (tc-ortho "renderorder=\"right-down\"" 2 1 8 8)
                          (list (tc-tileset 1 "s" 8 8 8 4 "sq.png" 32 16 ""
                                            "<tile id=\"0\"><animation><frame tileid=\"1\" duration=\"100\"/><frame tileid=\"2\" duration=\"50\"/><frame tileid=\"3\" duration=\"200\"/></animation></tile>"))
                          (list (tc-layer 1 "l" 2 1 (list 1 (+ 1 tc-h)))))
                 time: time))
   '(0 100 101 150 151 350 351 1000))
  ;; tile objects: scaled, flipped, turned a quarter and a half, animated,
  ;; from tilesets of each objectalignment
  (tc-compare "tile-objects"
              (tc-map! "tile-objects" (tc-ortho "renderorder=\"right-down\"" 8 6 8 8)
                       (list (tc-tileset 1 "s" 8 8 8 4 "sq.png" 32 16 ""
                                         "<tile id=\"5\"><animation><frame tileid=\"6\" duration=\"10\"/><frame tileid=\"7\" duration=\"10\"/></animation></tile>")
                             (tc-tileset 9 "c" 8 8 8 4 "sq.png" 32 16 "objectalignment=\"center\"")
                             (tc-tileset 17 "tr" 8 8 8 4 "sq.png" 32 16 "objectalignment=\"topright\""))
                       (list (string-append
                              "<objectgroup id=\"1\" name=\"o\">"
                              "<object id=\"1\" gid=\"1\" x=\"0\" y=\"16\" width=\"16\" height=\"16\"/>"
                              (sprintf "<object id=\"2\" gid=\"~a\" x=\"24\" y=\"16\" width=\"8\" height=\"8\"/>" (+ 2 tc-h))
                              (sprintf "<object id=\"3\" gid=\"~a\" x=\"40\" y=\"16\" width=\"8\" height=\"16\"/>" (+ 3 tc-v))
                              "<object id=\"4\" gid=\"4\" x=\"8\" y=\"40\" width=\"16\" height=\"8\" rotation=\"90\"/>"
                              "<object id=\"5\" gid=\"5\" x=\"40\" y=\"40\" width=\"8\" height=\"8\" rotation=\"180\"/>"
                              "<object id=\"6\" gid=\"6\" x=\"48\" y=\"16\" width=\"8\" height=\"8\"/>"
                              "<object id=\"7\" gid=\"10\" x=\"56\" y=\"32\" width=\"8\" height=\"8\"/>"
                              "<object id=\"8\" gid=\"20\" x=\"56\" y=\"40\" width=\"8\" height=\"8\"/>"
                              "</objectgroup>")))
              time: 15)
  ;; a tinted layer and a group's tint over it
  (tc-compare "tint"
              (tc-map! "tint" (tc-ortho "renderorder=\"right-down\"" 4 2 8 8)
                       (list (tc-tileset 1 "s" 8 8 8 4 "sq.png" 32 16))
                       (list (tc-layer 1 "a" 4 2 '(1 2 3 4 5 6 7 8) "tintcolor=\"#ff8040\"")))
              tolerance: 3)
  ;; an image layer repeated across the map
  (tc-compare "repeat"
              (tc-map! "repeat" (tc-ortho "renderorder=\"right-down\"" 8 4 8 8)
                       '()
                       (list "<imagelayer id=\"1\" name=\"r\" offsetx=\"5\" offsety=\"3\" repeatx=\"1\"><image source=\"wide.png\" width=\"32\" height=\"16\"/></imagelayer>")))
  ;; an infinite map with chunks at negative cells
  (tc-compare "infinite" "maps/infinite.tmx" region: '(128 64 256 256))
  ;; every orientation and stagger, with tiles taller than their cells so
  ;; the stacking order shows, the first cells flipped every way, and tile
  ;; objects
  (let ((cells (map + '(1 2 3 4 5 6 7 8 1 2 3 4 5 6 7 8 1 2 3 4)
                     (append (list 0 tc-h tc-v tc-d (+ tc-h tc-d) (+ tc-v tc-d) (+ tc-h tc-v tc-d))
                             (quote (0 0 0 0 0 0 0 0 0 0 0 0 0)))))
        (objects "<objectgroup id=\"2\" name=\"o\"><object id=\"1\" gid=\"3\" x=\"20\" y=\"30\" width=\"16\" height=\"16\"/><object id=\"2\" gid=\"5\" x=\"40\" y=\"16\" width=\"16\" height=\"24\"/><object id=\"3\" gid=\"6\" x=\"8\" y=\"8\" width=\"16\" height=\"8\" rotation=\"90\"/></objectgroup>"))
    (for-each
     (lambda (o)
       (let ((name (car o)))
         (tc-compare name
                     (tc-map! name (sprintf "orientation=\"~a\" renderorder=\"right-down\" width=\"5\" height=\"4\" tilewidth=\"16\" tileheight=\"8\" ~a"
                                            (cadr o) (caddr o))
                              (list (tc-tileset 1 "big" 16 16 8 4 "big.png" 64 32))
                              (list (tc-layer 1 "l" 5 4 cells) objects))
                     ;; on hexagonal maps the flipped cells turn by 60 and
                     ;; 120 degrees: their rims are sampled differently
                     ;; (see hexagonal-60), up to 3% of the pixels
                     allowed: (if (equal? (cadr o) "hexagonal") 66 0))))
     '(("isometric-small" "isometric" "")
       ("staggered-y-odd" "staggered" "staggeraxis=\"y\" staggerindex=\"odd\"")
       ("staggered-y-even" "staggered" "staggeraxis=\"y\" staggerindex=\"even\"")
       ("staggered-x-odd" "staggered" "staggeraxis=\"x\" staggerindex=\"odd\"")
       ("staggered-x-even" "staggered" "staggeraxis=\"x\" staggerindex=\"even\"")
       ("hexagonal-y-odd" "hexagonal" "hexsidelength=\"4\" staggeraxis=\"y\" staggerindex=\"odd\"")
       ("hexagonal-y-even" "hexagonal" "hexsidelength=\"4\" staggeraxis=\"y\" staggerindex=\"even\"")
       ("hexagonal-x-odd" "hexagonal" "hexsidelength=\"6\" staggeraxis=\"x\" staggerindex=\"odd\"")
       ("hexagonal-x-even" "hexagonal" "hexsidelength=\"6\" staggeraxis=\"x\" staggerindex=\"even\"")))))

;;; Only the cells the view can show are visited, on every orientation: a
;;; 200 x 200 map viewed 64 x 48 pixels at a time asks for the textures of
;;; a few hundred cells (the view's bounding box in cells), not 40,000
;;; (the textures procedure is asked once per cell considered).
(test-group "other orientations: only what the camera sees"
  (for-each
   (lambda (o)
     (let* ((name (string-append "big-" (car o)))
            (path (tc-map! name (sprintf "orientation=\"~a\" renderorder=\"right-down\" width=\"200\" height=\"200\" tilewidth=\"16\" tileheight=\"8\" ~a"
                                         (car o) (cadr o))
                           (list (tc-tileset 1 "big" 16 16 8 4 "big.png" 64 32))
                           (list (tc-layer 1 "l" 200 200 (let loop ((n 40000) (acc '()))
                                                          (if (= n 0) acc (loop (- n 1) (cons 1 acc))))))))
            (tm (load-tilemap path))
            (s (create-rgba-surface! 64 48))
            (r (create-software-renderer! s))
            (tex (img-load-texture! r (tc-path "big.png")))
            (asked 0))
       (render-scene! r (make-scene tilemap: tm camera: (make-camera x: 1000 y: 600 bounds: #f))
                      textures: (lambda (p) (set! asked (+ asked 1)) tex))
       (test-assert (sprintf "~a: ~a cells considered, fewer than 1,000" (car o) asked)
                    (< 0 asked 1000))
       (free-surface! s)))
   '(("isometric" "") ("staggered" "staggeraxis=\"x\" staggerindex=\"even\"")
     ("hexagonal" "hexsidelength=\"4\" staggeraxis=\"y\" staggerindex=\"odd\""))))
