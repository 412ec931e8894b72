;;; (downstroke mapdraw): drawing a tilemap's layers as Tiled 1.8 draws
;;; them (its tmxrasterizer is the reference the tests compare against).
;;; (downstroke renderer) calls it for a scene's map; a game rarely needs
;;; it directly.
;;;
;;;   (render-map-layers! renderer tilemap camera-x camera-y view-width
;;;                       view-height tex-for #!optional (time 0))
;;;
;;; draws every visible layer in the map's order (a group's children where
;;; the group is), each through its layer camera (layer-camera below), with
;;; its opacity and tint as the textures' alpha and colour modulation (a
;;; translucent layer switches its textures to blending, so images without
;;; an alpha channel fade too). `tex-for` is (owner path) -> texture, the
;;; owner being the tileset or image layer that needs the image. `time` is
;;; the elapsed time in milliseconds that animated tiles are shown at.
;;;
;;; Where a tile is drawn. Every orientation places a cell's image by its
;;; bottom-left corner, the cell's anchor (tilemap-cell-anchor of (downstroke
;;; map)), in "screen"
;;; pixels of the map (the picture tmxrasterizer draws, whose top-left is
;;; (0, 0)); then the tileset's <tileoffset> moves it. A tile larger than
;;; the map's cells overhangs up and to the right. The anchors:
;;;   orthogonal  (col * tw, (row + 1) * th)
;;;   isometric   ((col - row) * tw/2 + H * tw/2 - tw/2, (col + row) * th/2 + th),
;;;               H the map's height in cells
;;;   staggered and hexagonal (staggered is hexagonal with a side length
;;;               of 0; tw and th rounded down to even numbers, s the side
;;;               length, cw = (tw - s)/2 + s and rh = (th - s)/2 + s):
;;;               stagger axis y: (col * (tw + s) + [row staggered] * cw, row * rh + th)
;;;               stagger axis x: (col * cw, row * (th + s) + [col staggered] * rh + th)
;;;               where a row (column) is staggered when its index is odd for
;;;               staggerindex odd, even for even.
;;; Cells are drawn in Tiled's order: orthogonal maps follow the map's
;;; renderorder (right-down, left-down, right-up, left-up); isometric maps
;;; go down the screen a diagonal row at a time (col + row), left to right;
;;; staggered and hexagonal maps down the screen a row at a time, the
;;; higher half-row first.
;;;
;;; Flips: horizontal, vertical, then diagonal (a transpose: the image is
;;; turned a quarter and its width and height swap, and it stays anchored by
;;; its bottom-left corner, so a 16x32 tile flipped diagonally covers a 32x16
;;; box standing on the cell's bottom). On hexagonal maps, as in Tiled, the
;;; diagonal flag turns a tile 60 degrees clockwise about its centre and
;;; the hex-120 flag 120 degrees (both: 180), after its h/v flips.
;;;
;;; Animated tiles show the frame Tiled shows after `time` milliseconds:
;;; the first frame for time 0 up to its duration inclusive, then the next
;;; (so at exactly 100 ms a 100 ms first frame still shows), cycling; a
;;; frame of duration 0 is shown for ever once reached. Tile objects of an
;;; animated tile animate alike.
;;;
;;; Rounding: the rounding rule of (downstroke renderer), floor(x - camera),
;;; with a layer's offset first rounded to whole pixels half up (Tiled's:
;;; an offset of 0.5 moves by one pixel, -0.5 by none).
;;;
;;; Objects: tile objects are drawn where Tiled draws them: on orthogonal,
;;; staggered and hexagonal maps their x y are screen pixels; on isometric
;;; maps (x, y) is projected like a tile position (x / th, y / th cells)
;;; and a tile object hangs from it bottom-centre unless its tileset's
;;; objectalignment says otherwise.

(module (downstroke mapdraw)
  (render-map-layers! screen-coordinate tileset-source-rect layer-camera
   check-map-orientation tile-animation-frame object-screen-box floor-int ceiling-int
   sine cosine tint-components tile-layer-fast-path?)

  (import scheme (chicken base) (chicken format) (chicken sort) (chicken condition) srfi-4
          (downstroke sdl2) (downstroke map))

  ;; A drawing coordinate as a whole pixel, floor(v), an exact integer:
  ;; every position this module and the renderer draw at comes through
  ;; here, and sdl2.scm turns it into the C ints SDL takes (cutting what
  ;; lies beyond them without changing what the view shows). A flonum
  ;; beyond 2^53 is converted exactly, however large (1e308 is an integer
  ;; of 1024 bits), so far-away geometry stays true. An infinity, an edge
  ;; that overflowed (1e308 + 1e308), is +-2^31, beyond every view; NaN,
  ;; a position lost to overflow (+inf.0 - +inf.0), stays NaN and nothing
  ;; is drawn there: every comparison with it is false, and sdl2.scm draws
  ;; no rect holding one.
  (define-inline (whole-pixel v)
    (let ((f (floor v)))
      (if (exact? f) f (flonum-pixel f))))

  (define (flonum-pixel f)
    (cond ((finite? f) (inexact->exact f))
          ((nan? f) f)
          ((> f 0) 2147483648)
          (else -2147483648)))

  ;; The rounding rule: world coordinate -> whole screen pixel.
  (define (screen-coordinate x camera) (whole-pixel (- x camera)))

  (define (floor-int x) (whole-pixel x))
  (define (ceiling-int x) (- (whole-pixel (- x))))
  ;; Tiled's rounding of positions: half up.
  (define (round-half-up x) (floor-int (+ x 1/2)))

  ;; The pixel rectangle of local tile `local` in a tileset image:
  ;; (values x y w h), from the tileset's columns, spacing and margin.
  ;; `image-width`: the image's width, for a tileset whose <image> gave
  ;; none (its columns are then counted from the texture).
  (define (tileset-source-rect ts local #!optional image-width)
    (let* ((tw (tileset-tile-width ts))
           (th (tileset-tile-height ts))
           (sp (or (tileset-spacing ts) 0))
           (mg (or (tileset-margin ts) 0))
           (cols (max 1 (or (tileset-columns ts)
                            (and image-width (quotient (+ (- image-width (* 2 mg)) sp) (+ tw sp)))
                            1))))
      (values (+ mg (* (modulo local cols) (+ tw sp)))
              (+ mg (* (quotient local cols) (+ th sp)))
              tw th)))

  ;; The local tile id an animated tile shows after `time` ms (see above).
  (define (tile-animation-frame frames time)
    (let* ((t (max 0 (floor-int time)))
           (total (foldl + 0 (map cdr frames)))
           (cyclic? (let all ((fs frames)) (or (null? fs) (and (> (cdar fs) 0) (all (cdr fs)))))))
      (let walk ((fs frames)
                 (t (if (and cyclic? (> t total)) (+ 1 (modulo (- t 1) total)) t)))
        (let ((d (cdar fs)))
          (if (and (> d 0) (> t d))
              (walk (if (null? (cdr fs)) frames (cdr fs)) (- t d))
              (caar fs))))))

  ;; Everything needed to draw one gid: (values texture sx sy sw sh), with
  ;; texture #f when the gid belongs to no tileset or tile.
  (define (gid-image tm gid tex-for time)
    (let ((ts (tilemap-tileset-for tm gid)))
      (if (not ts)
          (values #f 0 0 0 0)
          (let* ((local0 (- gid (tileset-first-gid ts)))
                 (info (tileset-tile ts local0))
                 (local (if (and info (pair? (tile-animation info)))
                            (tile-animation-frame (tile-animation info) time)
                            local0)))
            (if (tileset-image ts)
                (let ((tex (tex-for ts (image-source (tileset-image ts)))))
                  (receive (sx sy sw sh)
                      (if (tileset-columns ts)
                          (tileset-source-rect ts local)
                          (receive (iw ih) (texture-size tex) (tileset-source-rect ts local iw)))
                    (values tex sx sy sw sh)))
                ;; an image collection: the tile's own image
                (let* ((tile (tileset-tile ts local))
                       (img (and tile (tile-image tile))))
                  (if (not img)
                      (values #f 0 0 0 0)
                      (let ((tex (tex-for ts (image-source img))))
                        (receive (iw ih) (texture-size tex)
                          (values tex (tile-x tile) (tile-y tile)
                                  (or (tile-width tile) iw)
                                  (or (tile-height tile) ih)))))))))))

  ;; One tile image, source (sx sy sw sh), with its bottom-left corner at
  ;; the screen pixel (left, bottom), flipped as Tiled flips: diagonal (a
  ;; transpose) first, then horizontal, then vertical. SDL flips before it
  ;; rotates about the centre of the destination, so the transpose followed
  ;; by h/v flips is a quarter turn clockwise of the image flipped
  ;; horizontally when v is set and vertically when h is not; the turned
  ;; image is sh wide and sw tall, so the unturned destination is centred on
  ;; the centre of that box.
  ;; On hexagonal maps the diagonal flag turns the tile 60 degrees
  ;; clockwise about its centre instead, and the hex-120 flag 120 more;
  ;; `hex-turn` is then that angle (else 0).
  (define (draw-tile! r tex sx sy sw sh left bottom h? v? d? #!optional (hex-turn 0))
    (cond
     ((not (zero? hex-turn))
      (render-copy! r tex (make-rect sx sy sw sh) (make-rect left (- bottom sh) sw sh)
                    angle: hex-turn
                    flip: (append (if h? '(horizontal) '()) (if v? '(vertical) '()))))
     (d?
        (render-copy! r tex (make-rect sx sy sw sh)
                      (make-rect (floor-int (+ left (/ (- sh sw) 2)))
                                 (floor-int (- bottom (/ (+ sw sh) 2)))
                                 sw sh)
                      angle: 90
                      flip: (append (if v? '(horizontal) '()) (if h? '() '(vertical)))))
     (else
        (render-copy! r tex (make-rect sx sy sw sh) (make-rect left (- bottom sh) sw sh)
                      flip: (append (if h? '(horizontal) '()) (if v? '(vertical) '()))))))

  ;; The camera a layer is seen through, its parallax and offset folded in:
  ;; (values lx ly), so that a point (x, y) of the layer is drawn at
  ;; (floor(x - lx), floor(y - ly)). With the map's parallax origin (ox, oy)
  ;; and the layer's factors (px, py):
  ;;     lx = ox + (camera-x - ox) * px - round(offset-x)
  ;; so a layer moves px pixels for each pixel the camera moves, and every
  ;; layer is at its own offset when the camera is at the parallax origin.
  (define (layer-camera tm layer cx cy)
    (let ((ox (tilemap-parallax-origin-x tm)) (oy (tilemap-parallax-origin-y tm)))
      (values (- (+ ox (* (- cx ox) (layer-parallax-x layer))) (round-half-up (layer-offset-x layer)))
              (- (+ oy (* (- cy oy) (layer-parallax-y layer))) (round-half-up (layer-offset-y layer))))))

  ;; Tints are (r g b a) lists; a group's tint multiplies its children's.
  (define no-tint '(255 255 255 255))

  (define (tint-components t)
    (cond ((not t) no-tint)
          ((and (pair? t) (eq? (car t) 'color))
           (if (null? (cdr t)) no-tint (tint-components (cdr t))))
          ((and (list? t) (= (length t) 3)) (append t '(255)))
          (else t)))

  (define (tint* a b)
    (map (lambda (x y) (quotient (+ (* x y) 127) 255)) a (tint-components b)))

  ;; Draws with every texture of a layer colour- and alpha-modulated by the
  ;; layer's tint and opacity: (with-layer-mods tint opacity draw) calls
  ;; (draw prepare!), where (prepare! texture) sets the modulation on a
  ;; texture before its first use; afterwards every texture touched is
  ;; reset to no modulation (textures are shared with the sprites). A
  ;; translucent layer sets its textures to blend: an image without an
  ;; alpha channel loads as `none`, which would ignore the alpha.
  (define (with-layer-mods tint opacity draw)
    (let* ((alpha (inexact->exact (round (* (cadddr tint) (max 0 (min 1 opacity))))))
           (rgb (list (car tint) (cadr tint) (caddr tint)))
           (touched '())
           (prepare! (lambda (tex)
                       (unless (memq tex touched)
                         (set! touched (cons tex touched))
                         (when (< alpha 255) (texture-blend-mode-set! tex 'blend))
                         (texture-alpha-mod-set! tex alpha)
                         (apply texture-color-mod-set! tex rgb)))))
      (when (> alpha 0)
        (dynamic-wind
         void
         (lambda () (draw prepare!))
         (lambda ()
           (for-each (lambda (tex)
                       (when (texture-alive? tex)
                         (texture-alpha-mod-set! tex 255)
                         (texture-color-mod-set! tex 255 255 255)))
                     touched))))))

  ;;; ------------------------------------------------------------------
  ;;; Orientations

  ;; Staggered and hexagonal maps: whether column (stagger axis x) or
  ;; row (y) i is pushed down (right) half a cell.
  (define (stagger-x? tm) (eq? (tilemap-stagger-axis tm) 'x))
  (define (staggered? tm i) (not (eq? (odd? i) (eq? (tilemap-stagger-index tm) 'even))))

  ;; Calls (visit col row) for the cells in Tiled's drawing order (see
  ;; above); cols c0..c1 and rows r0..r1, inclusive.
  ;; A range lost to overflow (a bound that is not an exact integer)
  ;; visits nothing.
  (define (for-each-cell-in-order tm c0 c1 r0 r1 visit)
    (when (and (exact-integer? c0) (exact-integer? c1) (exact-integer? r0) (exact-integer? r1))
      (visit-cells-in-order tm c0 c1 r0 r1 visit)))

  (define (visit-cells-in-order tm c0 c1 r0 r1 visit)
    (case (tilemap-orientation tm)
      ((isometric)
       (do ((s (+ c0 r0) (+ s 1))) ((> s (+ c1 r1)))
         (do ((col (max c0 (- s r1)) (+ col 1))) ((> col (min c1 (- s r0))))
           (visit col (- s col)))))
      ((staggered hexagonal)
       (do ((row r0 (+ row 1))) ((> row r1))
         (if (stagger-x? tm)
             ;; the higher half of the row first
             (begin
               (do ((col c0 (+ col 1))) ((> col c1))
                 (unless (staggered? tm col) (visit col row)))
               (do ((col c0 (+ col 1))) ((> col c1))
                 (when (staggered? tm col) (visit col row))))
             (do ((col c0 (+ col 1))) ((> col c1)) (visit col row)))))
      (else
       (let* ((order (tilemap-render-order tm))
              (left? (memq order '(left-down left-up)))
              (up? (memq order '(right-up left-up))))
         (let rows ((row (if up? r1 r0)))
           (when (if up? (>= row r0) (<= row r1))
             (let cols ((col (if left? c1 c0)))
               (when (if left? (>= col c0) (<= col c1))
                 (visit col row)
                 (cols (if left? (- col 1) (+ col 1)))))
             (rows (if up? (- row 1) (+ row 1)))))))))

  ;; On isometric, staggered and hexagonal maps: a range of cells (values
  ;; col0 col1 row0 row1) holding every cell whose anchor (tilemap-cell-anchor)
  ;; lies in [x0, x1] x [y0, y1], with a cell to spare on each side.
  (define (anchor-cells tm x0 x1 y0 y1)
    (let* ((tw (tilemap-tile-width tm)) (th (tilemap-tile-height tm)))
      (define (span lo hi) (values (- (floor-int lo) 2) (+ (ceiling-int hi) 2)))
      (case (tilemap-orientation tm)
        ((isometric)
         ;; u = col - row and s = col + row are linear in the anchor
         (let* ((u (lambda (x) (/ (+ x (/ tw 2) (- (/ (* (tilemap-height tm) tw) 2))) (/ tw 2))))
                (sm (lambda (y) (/ (- y th) (/ th 2))))
                (u0 (u x0)) (u1 (u x1)) (s0 (sm y0)) (s1 (sm y1)))
           (receive (c0 c1) (span (/ (+ s0 u0) 2) (/ (+ s1 u1) 2))
             (receive (r0 r1) (span (/ (- s0 u1) 2) (/ (- s1 u0) 2))
               (values c0 c1 r0 r1)))))
        (else
         ;; Tiled rounds the cell size down to even numbers; a staggered
         ;; row or column moves by at most a cell; the side length
         ;; stretches the stagger axis only
         (let* ((tw (- tw (modulo tw 2))) (th (- th (modulo th 2)))
                (side (if (eq? (tilemap-orientation tm) 'hexagonal)
                          (or (tilemap-hex-side-length tm) 0)
                          0)))
           (if (stagger-x? tm)
               (let ((cw (+ (quotient (- tw side) 2) side)))
                 (receive (c0 c1) (span (/ x0 (max 1 cw)) (/ x1 (max 1 cw)))
                   (receive (r0 r1) (span (/ (- y0 th th) th) (/ (- y1 th) th))
                     (values c0 c1 r0 r1))))
               (let ((rh (+ (quotient (- th side) 2) side)))
                 (receive (c0 c1) (span (/ (- x0 tw) tw) (/ x1 tw))
                   (receive (r0 r1) (span (/ (- y0 th) (max 1 rh)) (/ (- y1 th) (max 1 rh)))
                     (values c0 c1 r0 r1))))))))))

  ;; How far the tiles of the map's tilesets can reach beyond their cell:
  ;; (values left right up down) in pixels, for culling.
  (define (tile-reach tm)
    (let loop ((tss (tilemap-tilesets tm)) (l 0) (rt 0) (u 0) (d 0))
      (if (null? tss)
          (values l rt u d)
          (let* ((ts (car tss))
                 ;; either side, as a diagonal flip swaps them
                 (size (max (tileset-tile-width ts) (tileset-tile-height ts)
                            (tileset-image-extent ts)))
                 (ox (tileset-offset-x ts)) (oy (tileset-offset-y ts)))
            (loop (cdr tss)
                  (max l (- ox)) (max rt (+ size ox)) (max u (- size oy)) (max d oy))))))

  ;; The largest image of an image collection, when the file gave sizes.
  (define (tileset-image-extent ts)
    (if (tileset-image ts)
        0
        (foldl (lambda (m t)
                 (let ((img (tile-image t)))
                   (max m (or (tile-width t) (and img (image-width img)) 0)
                        (or (tile-height t) (and img (image-height img)) 0))))
               0 (tileset-tiles ts))))

  ;; One tile layer, seen through its layer camera (lx, ly): the cells
  ;; whose image the view vw x vh can show.
  (define (draw-tile-layer! r tm layer lx ly vw vh tex-for prepare! time)
    (let ((tw (tilemap-tile-width tm))
          (th (tilemap-tile-height tm))
          (col0 (tilemap-origin-col tm))
          (row0 (tilemap-origin-row tm))
          (width (tilemap-width tm))
          (data (layer-data layer))
          (ortho? (eq? (tilemap-orientation tm) 'orthogonal))
          (hex? (eq? (tilemap-orientation tm) 'hexagonal))
          ;; <tileoffset>s are rare: look the tileset up again only then
          (offsets? (let loop ((tss (tilemap-tilesets tm)))
                      (and (pair? tss)
                           (or (not (zero? (tileset-offset-x (car tss))))
                               (not (zero? (tileset-offset-y (car tss))))
                               (loop (cdr tss)))))))
      (receive (reach-l reach-r reach-u reach-d) (tile-reach tm)
        (let ((c-lo col0) (c-hi (+ col0 width -1))
              (r-lo row0) (r-hi (+ row0 (tilemap-height tm) -1)))
          (define (draw-cell col row)
            (let ((cell (u32vector-ref data (+ (* (- row row0) width) (- col col0)))))
              (unless (zero? (cell-gid cell))
                (receive (tex sx sy sw sh) (gid-image tm (cell-gid cell) tex-for time)
                  (when tex
                    (receive (ax ay) (tilemap-cell-anchor tm col row)
                      (let* ((ts (and offsets? (tilemap-tileset-for tm cell)))
                             (left (screen-coordinate (+ ax (if ts (tileset-offset-x ts) 0)) lx))
                             (bottom (screen-coordinate (+ ay (if ts (tileset-offset-y ts) 0)) ly))
                             (turn (if hex?
                                       (+ (if (cell-flipped-diagonally? cell) 60 0)
                                          (if (cell-rotated-hex-120? cell) 120 0))
                                       0))
                             (d? (and (not hex?) (cell-flipped-diagonally? cell)))
                             ;; a turned hexagon may reach beyond its box
                             (w (cond (d? sh) ((> turn 0) (max sw sh)) (else sw)))
                             (h (cond (d? sw) ((> turn 0) (max sw sh)) (else sh))))
                        ;; only images that meet the view
                        (when (and (< left vw) (> (+ left w) 0) (< (- bottom h) vh) (> bottom 0))
                          (prepare! tex)
                          (draw-tile! r tex sx sy sw sh left bottom
                                      (cell-flipped-horizontally? cell)
                                      (cell-flipped-vertically? cell)
                                      d? turn)))))))))
          (if ortho?
              ;; the cells whose images can meet [lx, lx+vw) x [ly, ly+vh):
              (let ((c0 (max c-lo (+ 1 (floor-int (/ (- lx reach-r) tw)))))
                    (c1 (min c-hi (- (ceiling-int (/ (+ lx vw reach-l) tw)) 1)))
                    (r0 (max r-lo (floor-int (/ (- ly reach-d) th))))
                    (r1 (min r-hi (- (ceiling-int (/ (+ ly vh reach-u) th)) 2))))
                (unless (draw-cells-at-once! r tm data c0 c1 r0 r1 lx ly vw vh tex-for prepare! time)
                  (for-each-cell-in-order tm c0 c1 r0 r1 draw-cell)))
              ;; image x spans [c*tw + ox, c*tw + ox + w), y spans
              ;; [(r+1)*th + oy - h, (r+1)*th + oy)
              ;; the cells whose anchors can fall in the view grown by
              ;; the tiles' reach, from the inverse of tilemap-cell-anchor
              (receive (c0 c1 r0 r1)
                  (anchor-cells tm (- lx reach-r) (+ lx vw reach-l)
                                (- ly reach-d) (+ ly vh reach-u))
                (for-each-cell-in-order tm (max c-lo c0) (min c-hi c1)
                                        (max r-lo r0) (min r-hi r1) draw-cell)))))))

  ;; An orthogonal layer's cells c0..c1 x r0..r1 in one call into C
  ;; (sdl2.scm's render-tile-cells!, shell/tiles.c): the same copies in
  ;; the same order as draw-cell's, each cell's image found in a table
  ;; by gid (gid-table). #f when the call does not take the layer (the
  ;; caller then walks the cells itself): a range lost to overflow, a map
  ;; whose gids gid-table cannot list, numbers beyond C's ints. The
  ;; textures the visible cells use are found first (pass 0) and get the
  ;; layer's modulation before any is drawn, as draw-cell's prepare! does.
  ;; (tile-layer-fast-path? #f) turns it off: the cell-by-cell walk, for
  ;; the tests that compare the two.
  (define tile-layer-fast-path? (make-parameter #t))

  (define (draw-cells-at-once! r tm data c0 c1 r0 r1 lx ly vw vh tex-for prepare! time)
    (let ((table (and (tile-layer-fast-path?) (exact-integer? c0) (exact-integer? c1) (exact-integer? r0) (exact-integer? r1)
                      (gid-table tm tex-for time))))
      (and table
           (let* ((textures (car table)) (cells (cdr table))
                  (used (make-u8vector (max 1 (vector-length textures)) 0))
                  (order (case (tilemap-render-order tm)
                           ((left-down) 1) ((right-up) 2) ((left-up) 3) (else 0))))
             (define (call pass)
               (render-tile-cells! r textures data (tilemap-width tm) (tilemap-height tm)
                                   (tilemap-origin-col tm) (tilemap-origin-row tm) c0 c1 r0 r1
                                   order cells (tilemap-tile-width tm) (tilemap-tile-height tm)
                                   (floor-int (- lx)) (floor-int (- ly)) (ceiling-int vw) (ceiling-int vh)
                                   pass used))
             (and (call 0)
                  (begin
                    (do ((i 0 (+ i 1))) ((= i (vector-length textures)))
                      (when (= 1 (u8vector-ref used i)) (prepare! (vector-ref textures i))))
                    (call 1)))))))

  ;; Every gid's image for tiles.c, at `time`: (textures . table), the
  ;; table an s32vector of 8 numbers per gid (tiles.c's DS_TILE_FIELDS):
  ;; texture number (from 1; 0: nothing drawn), source x y w h and the
  ;; tileset's offset x y, as gid-image and draw-cell find them. Kept per
  ;; map while the textures tex-for gives stay the same; only animated
  ;; tiles are looked up again each frame. #f for a map it cannot list:
  ;; more than 65,536 gids or 64 textures, a tileset tex-for has no texture
  ;; for (draw-cell then says which).
  (define gid-tables '())               ; ((tm sheets textures table animated) ...)
  (define max-table-gids 65536)

  ;; The last gid a tileset of tm can draw. An image tileset of unknown
  ;; tile count (make-sheet-tileset without tile-count:) reaches as far as
  ;; its texture: a tile whose source starts below the image draws nothing.
  (define (last-gid tm sheets)
    (fold2 (lambda (m ts tex)
             (and m
                  (if (tileset-image ts)
                      (let ((n (or (tileset-tile-count ts) (image-tile-count ts tex))))
                        (and n (max m (+ (tileset-first-gid ts) n -1))))
                      (max m (+ (tileset-first-gid ts) (foldl max 0 (tileset-tile-ids ts)))))))
           0 (tilemap-tilesets tm) sheets))

  (define (fold2 f init l1 l2)         ; foldl over two lists of one length
    (if (null? l1) init (fold2 f (f init (car l1) (car l2)) (cdr l1) (cdr l2))))

  (define (image-tile-count ts tex)
    (and (texture? tex)
         (receive (iw ih) (texture-size tex)
           (let ((mg (or (tileset-margin ts) 0)) (sp (or (tileset-spacing ts) 0))
                 (tw (tileset-tile-width ts)) (th (tileset-tile-height ts)))
             (* (max 1 (or (tileset-columns ts) (quotient (+ (- iw (* 2 mg)) sp) (+ tw sp))))
                ;; rows whose top lies in the image: ceiling((ih - mg) / (th + sp))
                (max 0 (quotient (+ (- ih mg) th sp -1) (+ th sp))))))))

  (define (sheet-textures tm tex-for)
    (map (lambda (ts)
           (if (tileset-image ts)
               (tex-for ts (image-source (tileset-image ts)))
               (map (lambda (t) (and (tile-image t) (tex-for ts (image-source (tile-image t)))))
                    (tileset-tiles ts))))
         (tilemap-tilesets tm)))

  (define (same-textures? a b)
    (cond ((and (pair? a) (pair? b)) (and (same-textures? (car a) (car b)) (same-textures? (cdr a) (cdr b))))
          (else (eq? a b))))

  (define (gid-table tm tex-for time)
    (let ((sheets (handle-exceptions e #f (sheet-textures tm tex-for)))
          (entry (assq tm gid-tables)))
      (and sheets
           (let ((entry (if (and entry (same-textures? (cadr entry) sheets))
                            entry
                            (let ((new (build-gid-table tm tex-for sheets)))
                              (set! gid-tables
                                (if new
                                    (cons new (let keep ((l gid-tables) (n 3))
                                                (cond ((or (null? l) (= n 0)) '())
                                                      ((eq? (caar l) tm) (keep (cdr l) n))
                                                      (else (cons (car l) (keep (cdr l) (- n 1)))))))
                                    gid-tables))
                              new))))
             (and entry
                  (let ((textures (caddr entry)) (table (cadddr entry)))
                    (for-each (lambda (gid) (gid-entry! table textures tm gid tex-for time))
                              (car (cddddr entry)))
                    (cons (list->vector textures) table)))))))

  (define (build-gid-table tm tex-for sheets)
    (let ((n (last-gid tm sheets)))
      (and n (<= n max-table-gids)
           (let ((table (make-s32vector (* 8 (+ n 1)) 0))
                 (textures (let collect ((s sheets) (out '()))
                             (cond ((texture? s) (if (memq s out) out (append out (list s))))
                                   ((pair? s) (collect (cdr s) (collect (car s) out)))
                                   (else out))))
                 (animated '()))
             (and (<= (length textures) 64)
                  (begin
                    (do ((gid 1 (+ gid 1))) ((> gid n))
                      (let* ((ts (tilemap-tileset-for tm gid))
                             (info (and ts (tileset-tile ts (- gid (tileset-first-gid ts))))))
                        (when (and info (pair? (tile-animation info)))
                          (set! animated (cons gid animated)))
                        (gid-entry! table textures tm gid tex-for 0)))
                    (list tm sheets textures table animated)))))))

  (define (gid-entry! table textures tm gid tex-for time)
    (receive (tex sx sy sw sh) (gid-image tm gid tex-for time)
      (let ((ts (tilemap-tileset-for tm gid)) (i (* 8 gid)))
        (define (put! k v) (s32vector-set! table (+ i k) (if (and (fixnum? v) (< (abs v) 536870912)) v 0)))
        (put! 0 (if tex (let find ((l textures) (k 1))
                          (cond ((null? l) 0) ((eq? (car l) tex) k) (else (find (cdr l) (+ k 1)))))
                    0))
        (put! 1 sx) (put! 2 sy) (put! 3 sw) (put! 4 sh)
        (put! 5 (if ts (tileset-offset-x ts) 0)) (put! 6 (if ts (tileset-offset-y ts) 0)))))

  ;; The screen positions at which copies of a span of `size` pixels
  ;; starting at `start` are drawn to cover [0, view) when repeated, or
  ;; just `start` when not.
  (define (repeat-positions start size view repeat?)
    (if (or (not repeat?) (<= size 0))
        (list start)
        (let ((first (let ((m (modulo start size))) (if (> m 0) (- m size) m))))
          (let loop ((p first) (out '()))
            (if (>= p view) (reverse out) (loop (+ p size) (cons p out)))))))

  ;; One image layer: its image at the layer's offset, repeated across the
  ;; view along an axis marked repeatx / repeaty.
  (define (draw-image-layer! r tm layer lx ly vw vh tex-for prepare!)
    (let ((img (layer-image layer)))
      (when (and img (image-source img))
        (let ((tex (tex-for layer (image-source img))))
          (prepare! tex)
          (receive (iw ih) (texture-size tex)
            (for-each
             (lambda (y)
               (for-each
                (lambda (x) (render-copy! r tex #f (make-rect x y iw ih)))
                (repeat-positions (screen-coordinate 0 lx) iw vw (layer-repeat-x? layer))))
             (repeat-positions (screen-coordinate 0 ly) ih vh (layer-repeat-y? layer))))))))

  ;; The box an object covers on the screen, (values x y w h), unrotated:
  ;; tilemap-object-box on orthogonal, staggered and hexagonal maps; on
  ;; isometric ones a tile object's box hangs from its projected anchor,
  ;; and another shape's box is the bounding box of its projected corners
  ;; (a rectangle is drawn by Tiled as a diamond within it).
  (define (object-screen-box tm o)
    (receive (bx by bw bh) (tilemap-object-box tm o)
      (cond ((not (eq? (tilemap-orientation tm) 'isometric)) (values bx by bw bh))
            ((eq? (object-shape o) 'tile)
             (receive (px py) (tilemap-screen-point tm (object-x o) (object-y o))
               (values (+ bx (- px (object-x o))) (+ by (- py (object-y o))) bw bh)))
            (else
             (let ((corners (map (lambda (c)
                                   (receive (sx sy) (tilemap-screen-point tm (car c) (cdr c))
                                     (cons sx sy)))
                                 (list (cons bx by) (cons (+ bx bw) by)
                                       (cons bx (+ by bh)) (cons (+ bx bw) (+ by bh))))))
               (let ((x0 (apply min (map car corners))) (y0 (apply min (map cdr corners))))
                 (values x0 y0 (- (apply max (map car corners)) x0)
                         (- (apply max (map cdr corners)) y0))))))))

  (define pi (* 4 (atan 1)))

  ;; Exact for multiples of 90 degrees, so quarter turns land on whole pixels.
  (define (sine degrees)
    (let ((d (and (exact? degrees) (integer? degrees) (modulo degrees 360))))
      (case d
        ((0 180) 0) ((90) 1) ((270) -1)
        (else (if (and (not d) (integer? degrees) (zero? (modulo degrees 90)))
                  (sine (inexact->exact degrees))
                  (sin (/ (* degrees pi) 180)))))))
  (define (cosine degrees) (sine (+ degrees 90)))

  ;; One object layer: its visible tile objects, each the tile's image
  ;; stretched over the object's box (tilemap-object-box, placed on the
  ;; screen by tilemap-screen-point), flipped by its flags and rotated by its
  ;; rotation about its anchor point, in the layer's draw order (topdown:
  ;; by y, index: as written). Other shapes are drawn only by the debug
  ;; overlay.
  (define (draw-object-layer! r tm layer lx ly tex-for prepare! time)
    (for-each
     (lambda (o)
       (when (and (object-visible? o) (eq? (object-shape o) 'tile))
         (receive (tex sx sy sw sh) (gid-image tm (object-gid o) tex-for time)
           (when tex
             (prepare! tex)
             (receive (bx by bw bh) (object-screen-box tm o)
               (receive (px py) (tilemap-screen-point tm (object-x o) (object-y o))
                 (let* ((angle (object-rotation o))
                        ;; the box's centre, turned about the anchor
                        (dx (- (+ bx (/ bw 2)) px)) (dy (- (+ by (/ bh 2)) py))
                        (mx (+ px (- (* dx (cosine angle)) (* dy (sine angle)))))
                        (my (+ py (* dx (sine angle)) (* dy (cosine angle))))
                        (x0 (screen-coordinate (- mx (/ bw 2)) lx))
                        (y0 (screen-coordinate (- my (/ bh 2)) ly))
                        (x1 (screen-coordinate (+ mx (/ bw 2)) lx))
                        (y1 (screen-coordinate (+ my (/ bh 2)) ly))
                        (cell (object-cell o))
                        (h? (cell-flipped-horizontally? cell))
                        (v? (cell-flipped-vertically? cell)))
                   (when (and (> x1 x0) (> y1 y0))
                     (render-copy! r tex (make-rect sx sy sw sh)
                                   (make-rect x0 y0 (- x1 x0) (- y1 y0))
                                   angle: angle
                                   flip: (append (if h? '(horizontal) '())
                                                 (if v? '(vertical) '())))))))))))
     (if (eq? (layer-draw-order layer) 'index)
         (layer-objects layer)
         (sort (layer-objects layer) (lambda (a b) (< (object-y a) (object-y b)))))))

  ;; Every visible layer of the map, in the map's order (Tiled's, groups'
  ;; children where the group is), through a camera at (cx, cy) and a view
  ;; of vw x vh pixels, animated tiles at `time` ms. A layer whose camera
  ;; overflows (a parallax factor of 1e308 with the camera 2 px from the
  ;; origin) is further away than any flonum: it is not drawn.
  (define (render-map-layers! r tm cx cy vw vh tex-for #!optional (time 0))
    (unless (and (real? time) (finite? time))
      (error 'render-map-layers! "time: must be a finite number of milliseconds" time))
    (let walk ((layers (tilemap-layer-tree tm)) (tint no-tint))
      (for-each
       (lambda (layer)
         (let ((tint (tint* tint (layer-tint layer))))
           (if (eq? (layer-kind layer) 'group)
               (walk (layer-children layer) tint)
               (when (and (layer-visible? layer) (> (layer-opacity layer) 0))
                 (receive (lx ly) (layer-camera tm layer cx cy)
                   (when (and (finite? lx) (finite? ly))
                     (with-layer-mods
                      tint (layer-opacity layer)
                      (lambda (prepare!)
                        (case (layer-kind layer)
                          ((tile) (draw-tile-layer! r tm layer lx ly vw vh tex-for prepare! time))
                          ((image) (draw-image-layer! r tm layer lx ly vw vh tex-for prepare!))
                          ((object) (draw-object-layer! r tm layer lx ly tex-for prepare! time))
                          (else (void)))))))))))
       layers)))

  ;; Every orientation Tiled 1.8 has is drawn; anything else is an error
  ;; naming the map's file.
  (define (check-map-orientation who tm)
    (let ((o (tilemap-orientation tm)))
      (unless (memq o '(orthogonal isometric staggered hexagonal))
        (error who (sprintf "unsupported orientation ~a in ~a"
                            o (or (tilemap-source tm) "a map made in code")))))))
