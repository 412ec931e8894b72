;;; (downstroke renderer): drawing a scene with an SDL renderer.
;;;
;;;   (render-scene! renderer scene #!key view-width view-height textures debug?)
;;;
;;; draws, in this order:
;;;   1. the whole target cleared to the scene's background, a list
;;;      (r g b [a]) of 0..255 values; black when the background is #f;
;;;   2. every visible layer of the scene's tilemap, in the map's order
;;;      (Tiled's: a group's children where the group is), each through
;;;      its layer camera (parallax and offset, below), with its opacity
;;;      and tint as the textures' alpha and colour modulation (reset to
;;;      none afterwards). A layer's tint is its tintcolor multiplied by
;;;      its groups' tints; a tint's alpha multiplies the opacity.
;;;      - tile layers: only the cells that the view touches are drawn: a
;;;        cell partly inside the view at any edge is drawn. A cell's image
;;;        comes from the tileset covering its gid (columns, spacing,
;;;        margin; image-collection tilesets use each tile's own image),
;;;        moved by the tileset's <tileoffset>, and its flip flags are
;;;        honoured (horizontal, vertical, and diagonal, the last as a 90
;;;        degree rotation, exact for square tiles). A tile whose tileset
;;;        tiles are taller than the map's cells is drawn bottom-aligned to
;;;        its cell, as Tiled does;
;;;      - image layers: the layer's image at the layer's offset, at its own
;;;        size; repeatx / repeaty repeat it along that axis across the
;;;        whole view;
;;;      - object layers: the visible tile objects (those with a gid), each
;;;        the tile's image stretched over the object's box
;;;        (tilemap-object-box: hung from its anchor, bottom-left unless
;;;        the tileset's objectalignment says otherwise), flipped by its
;;;        horizontal / vertical flags, rotated by its rotation (degrees
;;;        clockwise) about its anchor point; in the layer's draw order
;;;        (topdown: by y, ties in file order; index: file order). Other
;;;        shapes are drawn only by the debug overlay;
;;;      Only orthogonal maps are drawn: another orientation is an error
;;;      "unsupported orientation isometric in FILE: only orthogonal maps
;;;      are drawn", raised before anything is drawn;
;;;   3. the entities, in list order: with #:tile-id, that tile of the
;;;      scene's tileset (scene-tileset, else the tilemap's first tileset)
;;;      from scene-tileset-texture (else the texture `textures` gives for
;;;      the tileset's image) at the entity's #:x #:y, at the tileset's tile
;;;      size, mirrored horizontally when #:facing is -1; else, with #:color
;;;      (r g b [a]), a filled #:width x #:height rectangle of that colour
;;;      (alpha below 255 blends); else nothing. An entity whose #:tile-id
;;;      cannot be drawn (no tileset or texture) falls through to #:color.
;;;      #:tile-id numbers tiles as gids of the scene's tileset: local tile
;;;      id + the tileset's first gid (1 for a map's first tileset), the same
;;;      numbers the map's cells use.
;;;      Sprite keys (docs/rendering.org, "Sprites"), all optional: the
;;;      sprite is drawn from #:x + #:sprite-offset-x (y likewise), scaled
;;;      by #:scale-x / #:scale-y (each defaulting to #:scale, 1) and
;;;      turned #:angle degrees clockwise about its origin (#:origin-x,
;;;      #:origin-y: sprite pixels from its top-left, default its centre),
;;;      mirrored by #:flip-x? / #:flip-y?, with #:alpha (0-255) and #:tint
;;;      (r g b) as the texture's alpha and colour modulation, reset after
;;;      the copy; #:tileset names another sheet (a tileset of the scene's
;;;      tilesets:, its own tileset or its map's, by name, or the tileset
;;;      itself). A box honours #:alpha. An entity with an #:emitter has
;;;      its particles drawn first (particles.scm). When any entity has a
;;;      #:z, entities are drawn by #:z (default 0), ties in list order.
;;;      An entity with none of these keys is drawn as before them, read by
;;;      the same single C walk (keys.c) that reads #:tile-id and the rest;
;;;   4. with `debug?: #t` (default #f), the debug overlay (below).
;;;
;;; The rounding rule: a world position x (an exact integer, a rational or
;;; a flonum) is drawn at the whole screen pixel
;;;     screen-x = floor(x - camera-x),   screen-y = floor(y - camera-y)
;;; for entities, and with the layer camera instead of the camera for
;;; tiles (x = column * tile-width), images and objects;
;;; sizes are whole pixels already (tile sizes) or rounded the same way
;;; (an entity's rect covers floor(x - cx) to floor(x + w - cx)).
;;; So everything moves by whole pixels together and nothing jitters against
;;; the map.
;;;
;;; The layer camera. A layer with parallax factors (px, py) (Tiled's
;;; parallaxx / parallaxy, multiplied through groups) in a map whose
;;; parallax origin is (ox, oy) is seen through
;;;     lx = ox + (camera-x - ox) * px - offset-x    (ly likewise)
;;; so it moves px pixels for each pixel the camera moves (0: fixed on the
;;; screen, 1: with the map) and sits at its own offset whenever the camera
;;; is at the parallax origin. Tiled's editor previews parallax about the
;;; centre of its view instead; a game's camera is its top-left corner.
;;;
;;; The view: view-width x view-height pixels starting at the camera; by
;;; default the renderer's logical size, or its output size when none is set.
;;;
;;; Textures: `textures:` maps an image path of a tileset or an image layer
;;; (the resolved path `image-source` gives) to a texture of this renderer
;;; (game-load-scene! loads them all). It is
;;; either a procedure (path -> texture or #f) or an alist of
;;; (path . texture) compared with equal?. The scene's tileset-texture is
;;; used for the scene's tileset when `textures` gives nothing. A layer
;;; needing an image with no texture is an error naming the path (and, for
;;; an image layer, the layer).
;;;
;;; The debug overlay. (render-debug-overlay! renderer scene #!key
;;; view-width view-height velocity-scale), which render-scene! calls last
;;; when given `debug?: #t`, draws first, with a tilemap, the outline of
;;; the box (tilemap-object-box) of every visible object of every visible
;;; object layer, through its layer camera, in *debug-object-color*
;;; (magenta): rectangles, ellipses, text, polygons (their points' bounding
;;; box) and tile objects alike, a point as one pixel, rotation ignored.
;;; Then for every entity with a numeric #:width
;;; and #:height, through the scene's camera and with the rounding rule:
;;;   1. with a tilemap, the outline of every tile cell its AABB covers, in
;;;      *debug-cell-color* (blue): columns floor(x/T) to ceil((x+w)/T) - 1,
;;;      rows likewise with the tile height (physics' entity-cell-span, the
;;;      cells the tile collision step looks at); only cells in the view;
;;;   2. the outline of its hitbox, #:x #:y #:width #:height, in
;;;      *debug-hitbox-color* (green);
;;;   3. a line from the centre of the hitbox to the centre plus
;;;      velocity-scale * (#:vx, #:vy), in *debug-velocity-color* (yellow).
;;;      The default scale, *debug-velocity-scale*, is 4: the line ends where
;;;      the centre will be in 4 frames at this velocity (velocities are
;;;      px/frame). A body at rest draws no line.
;;; A body at risk of tunnelling (physics' tunnel-risk?: discrete collision
;;; mode and a speed of at least its size plus a tile on an axis) has its
;;; hitbox and velocity line drawn in *debug-warning-color* (red) instead.
;;; Outlines are one pixel wide, drawn inside the rectangle (SDL's draw-rect).
;;;
;;; Not drawn: shapes other than tile objects (except as debug outlines),
;;; text objects, an image layer's transparent colour (trans), and
;;; isometric, staggered and hexagonal maps (refused, see above). Entities
;;; are drawn above every layer of the map.

(module (downstroke renderer)
  (render-scene! render-map-layers! render-entities! render-entity!
   screen-coordinate tileset-source-rect layer-camera
   render-debug-overlay! render-draw-line!
   *debug-hitbox-color* *debug-cell-color* *debug-velocity-color*
   *debug-warning-color* *debug-velocity-scale* *debug-object-color*
   ;; for sibling modules only: the level loader refuses a map it cannot draw
   check-map-orientation)

  (import (downstroke keywords) (only (downstroke check) report-entity-problems!))
  (import scheme (chicken base) (chicken format) (chicken sort) (chicken fixnum) (chicken foreign)
          srfi-4
          (downstroke sdl2) (downstroke entity) (downstroke scene)
          (downstroke map)
          (only (downstroke physics) entity-cell-span tunnel-risk?)
          (only (downstroke particles) emitter? emitter-for-each emitter-tile-id emitter-size
                emitter-color emitter-end-color))

  ;; The rounding rule (see above): world coordinate -> whole screen pixel.
  (define (screen-coordinate x camera)
    (let ((v (floor (- x camera))))
      (if (exact? v) v (inexact->exact v))))

  ;; The texture for an image path, from a procedure or an alist; #f if none.
  (define (lookup-texture textures path)
    (cond ((not textures) #f)
          ((procedure? textures) (textures path))
          ((list? textures) (let ((p (assoc path textures))) (and p (cdr p))))
          (else (error 'render-scene! "textures: must be a procedure or an alist" textures))))

  ;; The pixel rectangle of local tile `local` in a tileset image:
  ;; (values x y w h), from the tileset's columns, spacing and margin.
  (define (tileset-source-rect ts local)
    (let* ((tw (tileset-tile-width ts))
           (th (tileset-tile-height ts))
           (cols (max 1 (or (tileset-columns ts) 1)))
           (sp (or (tileset-spacing ts) 0))
           (mg (or (tileset-margin ts) 0)))
      (values (+ mg (* (modulo local cols) (+ tw sp)))
              (+ mg (* (quotient local cols) (+ th sp)))
              tw th)))

  ;; Copy with Tiled's flip flags: diagonal (a transpose, applied first),
  ;; then horizontal, then vertical. SDL flips before it rotates, so the
  ;; transpose followed by h/v flips equals a 90 degree clockwise rotation
  ;; of the image flipped horizontally when v is set and vertically when h
  ;; is not.
  (define (copy-flipped! r tex src dst h? v? d?)
    (if d?
        (render-copy! r tex src dst
                      angle: 90
                      flip: (append (if v? '(horizontal) '()) (if h? '() '(vertical))))
        (render-copy! r tex src dst
                      flip: (append (if h? '(horizontal) '()) (if v? '(vertical) '())))))

  (define (background-color bg)
    (cond ((not bg) '(0 0 0 255))
          ((and (list? bg) (<= 3 (length bg) 4))
           (if (= (length bg) 3) (append bg '(255)) bg))
          ((and (pair? bg) (eq? (car bg) 'color)) (background-color (cdr bg)))
          (else (error 'render-scene! "background: must be (r g b [a]) or #f" bg))))

  ;; The view size: explicit, else logical size, else output size.
  (define (view-size r vw vh)
    (if (and vw vh)
        (values vw vh)
        (receive (lw lh) (render-logical-size r)
          (if (and (> lw 0) (> lh 0))
              (values (or vw lw) (or vh lh))
              (receive (ow oh) (renderer-output-size r)
                (values (or vw ow) (or vh oh)))))))

;;; ------------------------------------------------------------------
  ;;; Map layers

  ;; Everything needed to draw one gid: (values texture sx sy sw sh), with
  ;; texture #f when the gid belongs to no tileset or tile. `tex-for` maps
  ;; (tileset path) to a texture or raises.
  (define (gid-image tm gid tex-for)
    (let ((ts (tilemap-tileset-for tm gid)))
      (if (not ts)
          (values #f 0 0 0 0)
          (let ((local (- gid (tileset-first-gid ts))))
            (if (tileset-image ts)
                (receive (sx sy sw sh) (tileset-source-rect ts local)
                  (values (tex-for ts (image-source (tileset-image ts))) sx sy sw sh))
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

  ;; The camera a layer is seen through, its parallax and offset folded in:
  ;; (values lx ly), so that a point (x, y) of the layer is drawn at
  ;; (floor(x - lx), floor(y - ly)). With the map's parallax origin (ox, oy)
  ;; and the layer's factors (px, py):
  ;;     lx = ox + (camera-x - ox) * px - offset-x
  ;; so a layer moves px pixels for each pixel the camera moves, and every
  ;; layer is at its own offset when the camera is at the parallax origin.
  (define (layer-camera tm layer cx cy)
    (let ((ox (tilemap-parallax-origin-x tm)) (oy (tilemap-parallax-origin-y tm)))
      (values (- (+ ox (* (- cx ox) (layer-parallax-x layer))) (layer-offset-x layer))
              (- (+ oy (* (- cy oy) (layer-parallax-y layer))) (layer-offset-y layer)))))

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
  ;; reset to no modulation (textures are shared with the sprites).
  (define (with-layer-mods tint opacity draw)
    (let* ((alpha (inexact->exact (round (* (cadddr tint) (max 0 (min 1 opacity))))))
           (rgb (list (car tint) (cadr tint) (caddr tint)))
           (touched '())
           (prepare! (lambda (tex)
                       (unless (memq tex touched)
                         (set! touched (cons tex touched))
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

  ;; One tile layer: only the cells that the view vw x vh touches.
  (define (draw-tile-layer! r tm layer cx cy vw vh tex-for prepare!)
    (let ((tw (tilemap-tile-width tm))
          (th (tilemap-tile-height tm))
          (col0 (tilemap-origin-col tm))
          (row0 (tilemap-origin-row tm))
          (width (tilemap-width tm))
          (data (layer-data layer))
          ;; <tileoffset>s are rare: look the tileset up again only then
          (offsets? (let loop ((tss (tilemap-tilesets tm)))
                      (and (pair? tss)
                           (or (not (zero? (tileset-offset-x (car tss))))
                               (not (zero? (tileset-offset-y (car tss))))
                               (loop (cdr tss)))))))
      (receive (lx ly) (layer-camera tm layer cx cy)
        ;; cells whose span [c*tw, (c+1)*tw) meets [lx, lx+vw)
        (let ((c-min (max col0 (floor-int (/ lx tw))))
              (c-max (min (+ col0 width -1) (- (ceiling-int (/ (+ lx vw) tw)) 1)))
              (r-min (max row0 (floor-int (/ ly th))))
              (r-max (min (+ row0 (tilemap-height tm) -1) (- (ceiling-int (/ (+ ly vh) th)) 1))))
          (do ((row r-min (+ row 1))) ((> row r-max))
            (do ((col c-min (+ col 1))) ((> col c-max))
              (let ((cell (u32vector-ref data (+ (* (- row row0) width) (- col col0)))))
                (unless (zero? (cell-gid cell))
                  (receive (tex sx sy sw sh) (gid-image tm (cell-gid cell) tex-for)
                    (when tex
                      (prepare! tex)
                      (let ((ts (and offsets? (tilemap-tileset-for tm cell))))
                        (copy-flipped!
                         r tex (make-rect sx sy sw sh)
                         (make-rect (screen-coordinate (+ (* col tw) (if ts (tileset-offset-x ts) 0)) lx)
                                    ;; taller tiles stand on their cell's bottom
                                    (screen-coordinate (+ (* row th) (- th sh) (if ts (tileset-offset-y ts) 0))
                                                       ly)
                                    sw sh)
                         (cell-flipped-horizontally? cell)
                         (cell-flipped-vertically? cell)
                         (cell-flipped-diagonally? cell)))))))))))))

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
  (define (draw-image-layer! r tm layer cx cy vw vh tex-for prepare!)
    (let ((img (layer-image layer)))
      (when (and img (image-source img))
        (let ((tex (tex-for layer (image-source img))))
          (prepare! tex)
          (receive (iw ih) (texture-size tex)
            (receive (lx ly) (layer-camera tm layer cx cy)
              (for-each
               (lambda (y)
                 (for-each
                  (lambda (x) (render-copy! r tex #f (make-rect x y iw ih)))
                  (repeat-positions (screen-coordinate 0 lx) iw vw (layer-repeat-x? layer))))
               (repeat-positions (screen-coordinate 0 ly) ih vh (layer-repeat-y? layer)))))))))

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
  ;; stretched over the object's box (tilemap-object-box), flipped by its
  ;; flags and rotated by its rotation about its anchor point (x, y), in
  ;; the layer's draw order (topdown: by y, index: as written). Other shapes
  ;; are drawn only by the debug overlay.
  (define (draw-object-layer! r tm layer cx cy tex-for prepare!)
    (receive (lx ly) (layer-camera tm layer cx cy)
      (for-each
       (lambda (o)
         (when (and (object-visible? o) (eq? (object-shape o) 'tile))
           (receive (tex sx sy sw sh) (gid-image tm (object-gid o) tex-for)
             (when tex
               (prepare! tex)
               (receive (bx by bw bh) (tilemap-object-box tm o)
                 (let* ((angle (object-rotation o))
                        ;; the box's centre, turned about the anchor
                        (px (object-x o)) (py (object-y o))
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
                                                 (if v? '(vertical) '()))))))))))
       (if (eq? (layer-draw-order layer) 'index)
           (layer-objects layer)
           (sort (layer-objects layer) (lambda (a b) (< (object-y a) (object-y b))))))))

  ;; Every visible layer of the map, in the map's order (Tiled's, groups'
  ;; children where the group is), through a camera at (cx, cy) and a view
  ;; of vw x vh pixels. `tex-for` is (owner path) -> texture, owner the
  ;; tileset or the image layer needing it.
  (define (render-map-layers! r tm cx cy vw vh tex-for)
    (let walk ((layers (tilemap-layer-tree tm)) (tint no-tint))
      (for-each
       (lambda (layer)
         (let ((tint (tint* tint (layer-tint layer))))
           (if (eq? (layer-kind layer) 'group)
               (walk (layer-children layer) tint)
               (when (and (layer-visible? layer) (> (layer-opacity layer) 0))
                 (with-layer-mods
                  tint (layer-opacity layer)
                  (lambda (prepare!)
                    (case (layer-kind layer)
                      ((tile) (draw-tile-layer! r tm layer cx cy vw vh tex-for prepare!))
                      ((image) (draw-image-layer! r tm layer cx cy vw vh tex-for prepare!))
                      ((object) (draw-object-layer! r tm layer cx cy tex-for prepare!))
                      (else (void)))))))))
       layers)))

  ;; Only orthogonal maps are drawn; the error names the map's file.
  (define (check-map-orientation who tm)
    (let ((o (tilemap-orientation tm)))
      (unless (eq? o 'orthogonal)
        (error who (sprintf "unsupported orientation ~a in ~a: only orthogonal maps are drawn"
                            o (or (tilemap-source tm) "a map made in code"))))))

  (define (floor-int x) (let ((v (floor x))) (if (exact? v) v (inexact->exact v))))
  (define (ceiling-int x) (let ((v (ceiling x))) (if (exact? v) v (inexact->exact v))))

  ;;; ------------------------------------------------------------------
  ;;; Entities

  (define (color-components who c)
    (unless (and (list? c) (<= 3 (length c) 4))
      (error who "#:color must be (r g b [a])" c))
    (if (= (length c) 3) (append c '(255)) c))

  ;; The keys an entity is drawn by, read in one C walk (keys.c) instead
  ;; of an assq each: the first five are those of plain entities, the
  ;; rest the sprite keys. An entity holding none of the sprite keys is
  ;; drawn by the code of before them; the others by draw-sprite!. The
  ;; bit of each key in the walk's answer is its index here.
  (foreign-declare "#include \"keys.c\"")
  (define entity-keys
    (vector #:tile-id #:color #:x #:y #:facing
            #:sprite-offset-x #:sprite-offset-y #:origin-x #:origin-y #:flip-x? #:flip-y?
            #:angle #:scale #:scale-x #:scale-y #:alpha #:tint #:tileset #:emitter))
  (define key-values (make-vector (vector-length entity-keys) #f))
  (define read-keys! (foreign-lambda scheme-object "ds_entity_keys" scheme-object scheme-object scheme-object))
  (define any-has-key? (foreign-lambda scheme-object "ds_any_has_key" scheme-object scheme-object))
  (define plain-keys 32)                ; bits below this: the first five keys
  (define bit-offset-x 32) (define bit-offset-y 64) (define bit-origin-x 128) (define bit-origin-y 256)
  (define bit-flip-x 512) (define bit-flip-y 1024) (define bit-angle 2048) (define bit-scale 4096)
  (define bit-scale-x 8192) (define bit-scale-y 16384) (define bit-alpha 32768) (define bit-tint 65536)
  (define bit-tileset 131072) (define bit-emitter 262144)

  ;; A key's number, checked: the error names the entity and the key.
  (define (sprite-number e key default)
    (let ((v (entity-ref e key default)))
      (if (and (real? v) (or (exact? v) (finite? v)))
          v
          (error 'render-scene! (sprintf "entity ~a: ~s is ~s, not a finite number"
                                         (entity-label e) key v)))))

  (define (byte-of x) (max 0 (min 255 (round-int x))))

  ;; One entity (see the head of this file). tileset/texture: the scene's
  ;; sprite sheet, either may be #f; sheet-for: (entity name) -> (values
  ;; tileset texture) for #:tileset.
  (define (render-entity! r e cx cy tileset texture #!optional (sheet-for no-sheets))
    (draw-entity! r e cx cy tileset texture sheet-for))

  (define (draw-entity! r e cx cy tileset texture sheet-for)
    (let ((mask (read-keys! e entity-keys key-values)))
      (cond ((fx< mask 0)               ; not an alist: entity-ref raises the error
             (draw-plain! r (entity-ref e #:tile-id #f) (entity-ref e #:color #f)
                          (entity-ref e #:x 0) (entity-ref e #:y 0) (entity-ref e #:facing 1)
                          e cx cy tileset texture))
            ((fx< mask plain-keys)
             (draw-plain! r (vector-ref key-values 0) (vector-ref key-values 1)
                          (or (vector-ref key-values 2) 0) (or (vector-ref key-values 3) 0)
                          (vector-ref key-values 4) e cx cy tileset texture))
            (else (draw-sprite! r e mask cx cy tileset texture sheet-for)))))

  ;; An entity without sprite keys: as before them.
  (define (draw-plain! r tile-id color x y facing e cx cy tileset texture)
    (cond ((and tile-id tileset texture
                (>= (- tile-id (tileset-first-gid tileset)) 0))
           (receive (sx sy sw sh)
               (tileset-source-rect tileset (- tile-id (tileset-first-gid tileset)))
             (render-copy! r texture (make-rect sx sy sw sh)
                           (make-rect (screen-coordinate x cx) (screen-coordinate y cy) sw sh)
                           flip: (if (eqv? facing -1) '(horizontal) '()))))
          (color (fill-box! r (color-components 'render-scene! color) x y
                            (entity-ref e #:width 0) (entity-ref e #:height 0) cx cy))
          (else (void))))

  ;; A filled world box x y w h of colour c (r g b a), by the rounding rule.
  (define (fill-box! r c x y w h cx cy)
    (let ((x0 (screen-coordinate x cx))
          (y0 (screen-coordinate y cy))
          (x1 (screen-coordinate (+ x w) cx))
          (y1 (screen-coordinate (+ y h) cy)))
      (when (and (> x1 x0) (> y1 y0))
        (render-draw-blend-mode-set! r (if (< (list-ref c 3) 255) 'blend 'none))
        (apply render-draw-color-set! r c)
        (render-fill-rect! r (make-rect x0 y0 (- x1 x0) (- y1 y0))))))

  (define (no-sheets e name)
    (error 'render-scene! (sprintf "entity ~a: #:tileset ~s, but render-entity! was given no sheets"
                                   (entity-label e) name)))

  ;; The general path: an entity with some of the sprite keys.
  (define (draw-sprite! r e mask cx cy tileset texture sheet-for)
    (define (has? bit) (not (fx= 0 (fxand mask bit))))
    (when (has? bit-emitter)
      (draw-particles! r e cx cy tileset texture sheet-for))
    (receive (tileset texture)
        (if (has? bit-tileset)
            (sheet-for e (entity-ref e #:tileset))
            (values tileset texture))
      (let* ((tile-id (entity-ref e #:tile-id #f))
             (alpha (if (has? bit-alpha) (byte-of (sprite-number e #:alpha 255)) 255)))
        (cond ((and tile-id tileset texture
                    (>= (- tile-id (tileset-first-gid tileset)) 0))
               (when (> alpha 0)
                 (receive (sx sy sw sh)
                     (tileset-source-rect tileset (- tile-id (tileset-first-gid tileset)))
                   (draw-tile! r e mask texture sx sy sw sh alpha cx cy))))
              ((entity-ref e #:color #f)
               => (lambda (color)
                    ;; a box: #:alpha multiplies its colour's alpha; the
                    ;; offset, flips, rotation, scale and tint are for sprites
                    (let ((c (color-components 'render-scene! color)))
                      (fill-box! r (if (= alpha 255)
                                       c
                                       (list (car c) (cadr c) (caddr c)
                                             (quotient (+ (* (cadddr c) alpha) 127) 255)))
                                 (entity-ref e #:x 0) (entity-ref e #:y 0)
                                 (entity-ref e #:width 0) (entity-ref e #:height 0) cx cy))))
              (else (void))))))

  ;; A tile sw x sh drawn for e: its top-left at #:x + #:sprite-offset-x
  ;; (y likewise), scaled by #:scale-x / #:scale-y (each defaulting to
  ;; #:scale, 1) about the origin (#:origin-x #:origin-y, sprite pixels
  ;; from the top-left, default the centre), mirrored by #:flip-x? (or
  ;; #:facing -1, not both) and #:flip-y?, turned #:angle degrees
  ;; clockwise about the origin, colour-modulated by #:tint and
  ;; alpha-modulated by #:alpha (both reset after the copy).
  (define (draw-tile! r e mask texture sx sy sw sh alpha cx cy)
    (define (has? bit) (not (fx= 0 (fxand mask bit))))
    (define (num bit key default) (if (has? bit) (sprite-number e key default) default))
    (let* ((scale (num bit-scale #:scale 1))
           (kx (num bit-scale-x #:scale-x scale))
           (ky (num bit-scale-y #:scale-y scale))
           (ox (num bit-origin-x #:origin-x (/ sw 2)))
           (oy (num bit-origin-y #:origin-y (/ sh 2)))
           (angle (num bit-angle #:angle 0))
           ;; the origin in the world, and the scaled box about it
           (px (+ (entity-ref e #:x 0) (num bit-offset-x #:sprite-offset-x 0) ox))
           (py (+ (entity-ref e #:y 0) (num bit-offset-y #:sprite-offset-y 0) oy))
           (w (* kx sw)) (h (* ky sh))
           ;; the box's centre, turned about the origin: SDL turns a copy
           ;; about its own centre
           (dx (- (/ w 2) (* kx ox))) (dy (- (/ h 2) (* ky oy)))
           (mx (if (zero? angle) (+ px dx) (+ px (- (* dx (cosine angle)) (* dy (sine angle))))))
           (my (if (zero? angle) (+ py dy) (+ py (* dx (sine angle)) (* dy (cosine angle)))))
           (x0 (screen-coordinate (- mx (/ w 2)) cx))
           (y0 (screen-coordinate (- my (/ h 2)) cy))
           (x1 (screen-coordinate (+ mx (/ w 2)) cx))
           (y1 (screen-coordinate (+ my (/ h 2)) cy))
           (flip-x? (not (eq? (and (has? bit-flip-x) #t) (eqv? (entity-ref e #:facing 1) -1))))
           (tint (and (has? bit-tint) (entity-ref e #:tint))))
      (when (or (< kx 0) (< ky 0))
        (error 'render-scene! (sprintf "entity ~a: a negative scale (~s x ~s); mirror with #:flip-x? / #:flip-y?"
                                       (entity-label e) kx ky)))
      (when (and (> x1 x0) (> y1 y0))
        (when tint
          (let ((c (tint-components tint)))
            (unless (and (list? c) (= (length c) 4))
              (error 'render-scene! (sprintf "entity ~a: #:tint is ~s, not (r g b)" (entity-label e) tint)))
            (texture-color-mod-set! texture (byte-of (car c)) (byte-of (cadr c)) (byte-of (caddr c)))))
        (when (< alpha 255) (texture-alpha-mod-set! texture alpha))
        (dynamic-wind
         void
         (lambda ()
           (render-copy! r texture (make-rect sx sy sw sh) (make-rect x0 y0 (- x1 x0) (- y1 y0))
                         angle: angle
                         flip: (append (if flip-x? '(horizontal) '())
                                       (if (has? bit-flip-y) '(vertical) '()))))
         (lambda ()
           (when tint (texture-color-mod-set! texture 255 255 255))
           (when (< alpha 255) (texture-alpha-mod-set! texture 255)))))))

  ;; An emitter's particles (particles.scm), in world coordinates: each a
  ;; filled box of the emitter's size, or its tile of the entity's sheet,
  ;; centred on the particle, in the particle's colour.
  (define (draw-particles! r e cx cy tileset texture sheet-for)
    (let* ((em (entity-ref e #:emitter))
           (_ (unless (emitter? em)
                (error 'render-scene! (sprintf "entity ~a: #:emitter is ~s, not an emitter (make-emitter)"
                                               (entity-label e) em))))
           (tile-id (emitter-tile-id em)))
      (if tile-id
          (receive (tileset texture)
              (if (entity-ref e #:tileset #f)
                  (sheet-for e (entity-ref e #:tileset))
                  (values tileset texture))
            (when (and tileset texture (>= (- tile-id (tileset-first-gid tileset)) 0))
              (receive (sx sy sw sh) (tileset-source-rect tileset (- tile-id (tileset-first-gid tileset)))
                (dynamic-wind
                 void
                 (lambda ()
                   (let ((src (make-rect sx sy sw sh)) (hw (/ sw 2)) (hh (/ sh 2)))
                     (emitter-for-each
                      em
                      (lambda (x y red green blue alpha)
                        (texture-color-mod-set! texture red green blue)
                        (texture-alpha-mod-set! texture alpha)
                        (render-copy! r texture src
                                      (make-rect (screen-coordinate (- x hw) cx)
                                                 (screen-coordinate (- y hh) cy)
                                                 sw sh))))))
                 (lambda ()
                   (texture-color-mod-set! texture 255 255 255)
                   (texture-alpha-mod-set! texture 255))))))
          (let ((w (car (emitter-size em))) (h (cadr (emitter-size em))))
            ;; one blend mode for all; the colour set only when it changes
            (let ((last-colour -1) (hw (/ w 2)) (hh (/ h 2)))
              (render-draw-blend-mode-set!
               r (if (and (= 255 (cadddr (emitter-color em))) (= 255 (cadddr (emitter-end-color em))))
                     'none
                     'blend))
              (emitter-for-each
               em
               (lambda (x y red green blue alpha)
                 (let ((x0 (screen-coordinate (- x hw) cx)) (y0 (screen-coordinate (- y hh) cy))
                       (colour (+ alpha (* 256 (+ blue (* 256 (+ green (* 256 red))))))))
                   (unless (= colour last-colour)
                     (set! last-colour colour)
                     (render-draw-color-set! r red green blue alpha))
                   (render-fill-rect! r (make-rect x0 y0 (- (screen-coordinate (+ x hw) cx) x0)
                                                   (- (screen-coordinate (+ y hh) cy) y0)))))))))))

  ;; Entities in list order, or, when one has #:z, by #:z (default 0),
  ;; ties in list order (a stable sort).
  (define (render-entities! r entities cx cy tileset texture #!optional (sheet-for no-sheets))
    (for-each (lambda (e) (draw-entity! r e cx cy tileset texture sheet-for))
              (if (any-has-key? entities #:z)
                  (map cdr (sort (map (lambda (e) (cons (sprite-number e #:z 0) e)) entities)
                                 (lambda (a b) (< (car a) (car b)))))
                  entities)))

  ;;; ------------------------------------------------------------------
  ;;; Scenes

;;; ------------------------------------------------------------------
  ;;; Debug overlay

  (define *debug-hitbox-color* '(0 255 0 255))
  (define *debug-cell-color* '(0 128 255 255))
  (define *debug-velocity-color* '(255 255 0 255))
  (define *debug-warning-color* '(255 0 0 255))
  (define *debug-object-color* '(255 0 255 255))
  (define *debug-velocity-scale* 4)

  ;; A one-pixel line from (x0, y0) to (x1, y1), screen pixels, both ends
  ;; included, clipped to [0, vw) x [0, vh) first (Liang-Barsky), so a huge
  ;; velocity costs no more than the view's diagonal. Drawn in the current
  ;; draw colour, a pixel at a time (debug drawing: short lines).
  (define (render-draw-line! r x0 y0 x1 y1 vw vh)
    (let ((dx (- x1 x0)) (dy (- y1 y0)))
      (let clip ((ps (list (- dx) dx (- dy) dy))
                 (qs (list x0 (- vw 1 x0) y0 (- vh 1 y0)))
                 (t0 0) (t1 1))
        (cond ((> t0 t1) (void))        ; outside the view
              ((null? ps)
               (let* ((ax (round-int (+ x0 (* t0 dx)))) (ay (round-int (+ y0 (* t0 dy))))
                      (bx (round-int (+ x0 (* t1 dx)))) (by (round-int (+ y0 (* t1 dy))))
                      (n (max (abs (- bx ax)) (abs (- by ay)))))
                 (do ((i 0 (+ i 1))) ((> i n))
                   (let ((x (if (zero? n) ax (round-int (+ ax (/ (* i (- bx ax)) n)))))
                         (y (if (zero? n) ay (round-int (+ ay (/ (* i (- by ay)) n))))))
                     (render-fill-rect! r (make-rect x y 1 1))))))
              (else
               (let ((p (car ps)) (q (car qs)))
                 (cond ((zero? p)
                        (if (< q 0) (void) (clip (cdr ps) (cdr qs) t0 t1)))
                       ((< p 0) (clip (cdr ps) (cdr qs) (max t0 (/ q p)) t1))
                       (else (clip (cdr ps) (cdr qs) t0 (min t1 (/ q p)))))))))))

  (define (round-int x) (let ((v (round x))) (if (exact? v) v (inexact->exact v))))

  (define (overlay-color! r c) (apply render-draw-color-set! r c))

  ;; The outline of the screen rect from world [x, x+w) x [y, y+h).
  (define (outline! r x y w h cx cy)
    (let ((x0 (screen-coordinate x cx)) (y0 (screen-coordinate y cy))
          (x1 (screen-coordinate (+ x w) cx)) (y1 (screen-coordinate (+ y h) cy)))
      (when (and (> x1 x0) (> y1 y0))
        (render-draw-rect! r (make-rect x0 y0 (- x1 x0) (- y1 y0))))))

  (define (finite-real? v) (and (real? v) (finite? v)))

  ;; Entities the overlay draws: finite numbers for #:width and #:height,
  ;; and for #:x and #:y when present (a broken body is physics' to report).
  (define (sized? e)
    (and (finite-real? (entity-ref e #:width #f)) (finite-real? (entity-ref e #:height #f))
         (finite-real? (entity-ref e #:x 0)) (finite-real? (entity-ref e #:y 0))))

  (define/keywords (render-debug-overlay! r scene #!key (view-width #f) (view-height #f)
                                 (velocity-scale *debug-velocity-scale*))
    ;; what is wrong with the entities, said once each on the error port
    (report-entity-problems! (scene-entities scene))
    (let* ((camera (scene-camera scene))
           (cx (if camera (camera-x camera) 0))
           (cy (if camera (camera-y camera) 0))
           (tm (scene-tilemap scene))
           (entities (filter sized? (scene-entities scene))))
      (receive (vw vh) (view-size r view-width view-height)
        (render-draw-blend-mode-set! r 'none)
        ;; 0. the map's objects: the outline of each one's box
        (when tm
          (overlay-color! r *debug-object-color*)
          (for-each
           (lambda (layer)
             (when (layer-visible? layer)
               (receive (lx ly) (layer-camera tm layer cx cy)
                 (for-each
                  (lambda (o)
                    (when (object-visible? o)
                      (receive (x y w h) (tilemap-object-box tm o)
                        (if (and (> w 0) (> h 0))
                            (outline! r x y w h lx ly)
                            (outline! r x y 1 1 lx ly)))))
                  (layer-objects layer)))))
           (tilemap-object-layers tm)))
        ;; 1. covered tile cells, under the hitboxes
        (when tm
          (let ((tw (tilemap-tile-width tm)) (th (tilemap-tile-height tm)))
            (overlay-color! r *debug-cell-color*)
            (for-each
             (lambda (e)
               (receive (c0 c1) (entity-cell-span (entity-ref e #:x 0) (entity-ref e #:width) tw)
                 (receive (r0 r1) (entity-cell-span (entity-ref e #:y 0) (entity-ref e #:height) th)
                   ;; only the cells the view touches
                   (let ((c0 (max c0 (floor-int (/ cx tw))))
                         (c1 (min c1 (- (ceiling-int (/ (+ cx vw) tw)) 1)))
                         (r0 (max r0 (floor-int (/ cy th))))
                         (r1 (min r1 (- (ceiling-int (/ (+ cy vh) th)) 1))))
                     (do ((row r0 (+ row 1))) ((> row r1))
                       (do ((col c0 (+ col 1))) ((> col c1))
                         (outline! r (* col tw) (* row th) tw th cx cy)))))))
             entities)))
        ;; 2. hitboxes and 3. velocity lines
        (for-each
         (lambda (e)
           (let ((x (entity-ref e #:x 0)) (y (entity-ref e #:y 0))
                 (w (entity-ref e #:width)) (h (entity-ref e #:height))
                 (vx (entity-ref e #:vx 0)) (vy (entity-ref e #:vy 0)))
             (let* ((moving? (and (finite-real? vx) (finite-real? vy)
                                  (not (and (zero? vx) (zero? vy)))))
                    (risk? (and moving? (tunnel-risk? scene e))))
               (overlay-color! r (if risk? *debug-warning-color* *debug-hitbox-color*))
               (outline! r x y w h cx cy)
               (when moving?
                 (overlay-color! r (if risk? *debug-warning-color* *debug-velocity-color*))
                 (let ((mx (+ x (/ w 2))) (my (+ y (/ h 2))))
                   (render-draw-line! r
                                      (screen-coordinate mx cx) (screen-coordinate my cy)
                                      (screen-coordinate (+ mx (* velocity-scale vx)) cx)
                                      (screen-coordinate (+ my (* velocity-scale vy)) cy)
                                      vw vh))))))
         entities)
        (void))))

  (define (filter keep? l)
    (cond ((null? l) '())
          ((keep? (car l)) (cons (car l) (filter keep? (cdr l))))
          (else (filter keep? (cdr l)))))

  (define/keywords (render-scene! r scene #!key (view-width #f) (view-height #f) (textures #f)
                         (debug? #f))
    (let* ((camera (scene-camera scene))
           (cx (if camera (camera-x camera) 0))
           (cy (if camera (camera-y camera) 0))
           (tm (scene-tilemap scene))
           (sprite-tileset (or (scene-tileset scene)
                               (and tm (pair? (tilemap-tilesets tm))
                                    (car (tilemap-tilesets tm)))))
           (bg (background-color (scene-background scene))))
      (when tm (check-map-orientation 'render-scene! tm))
      (receive (vw vh) (view-size r view-width view-height)
        (let ((tex-for
               (lambda (owner path)
                 (or (lookup-texture textures path)
                     (and (eq? owner sprite-tileset) (scene-tileset-texture scene))
                     (error 'render-scene!
                            (if (layer? owner)
                                (sprintf "no texture for the image ~s of image layer ~s (pass textures:)"
                                         path (layer-name owner))
                                (sprintf "no texture for the tileset image ~s (pass textures:)"
                                         path)))))))
          (render-draw-blend-mode-set! r 'none)
          (apply render-draw-color-set! r bg)
          (render-clear! r)
          ;; A zoomed camera sees view / zoom world pixels, drawn through
          ;; SDL's scale (on top of the logical size's), restored after.
          (with-zoom r (if camera (camera-zoom camera) 1)
            (lambda (zoom)
              (let ((vw (/ vw zoom)) (vh (/ vh zoom)))
                (when tm (render-map-layers! r tm cx cy vw vh tex-for))
                (render-entities! r (scene-entities scene) cx cy sprite-tileset
                                  (or (scene-tileset-texture scene)
                                      (and sprite-tileset (tileset-image sprite-tileset)
                                           (lookup-texture textures
                                                           (image-source (tileset-image sprite-tileset)))))
                                  (lambda (e name) (entity-sheet scene tm sprite-tileset textures e name)))
                (when debug?
                  (render-debug-overlay! r scene view-width: vw view-height: vh)))))
          (void)))))

  ;; An entity's #:tileset: a tileset, or the name (a string or a symbol)
  ;; of one of the scene's tilesets:, else of its map's tilesets. Its
  ;; texture is the one `textures` gives for its image (or the scene's
  ;; tileset-texture for the scene's own sprite tileset). (values tileset
  ;; texture); an unknown name or a sheet without texture is an error
  ;; naming the entity.
  (define (scene-sheets scene tm sprite-tileset)
    (append (scene-tilesets scene)
            (if (and sprite-tileset (not (memq sprite-tileset (scene-tilesets scene)))
                     (not (and tm (memq sprite-tileset (tilemap-tilesets tm)))))
                (list sprite-tileset)
                '())
            (if tm (tilemap-tilesets tm) '())))

  (define (entity-sheet scene tm sprite-tileset textures e name)
    (let* ((key (if (symbol? name) (symbol->string name) name))
           (ts (cond ((tileset? name) name)
                     ((string? key)
                      (let find ((tss (scene-sheets scene tm sprite-tileset)))
                        (cond ((null? tss) #f)
                              ((equal? (tileset-name (car tss)) key) (car tss))
                              (else (find (cdr tss))))))
                     (else #f))))
      (unless ts
        (error 'render-scene!
               (sprintf "entity ~a: #:tileset ~s names no tileset of the scene (its tilesets: ~s)"
                        (entity-label e) name
                        (map tileset-name (scene-sheets scene tm sprite-tileset)))))
      (let ((tex (or (and (tileset-image ts) (lookup-texture textures (image-source (tileset-image ts))))
                     (and (eq? ts sprite-tileset) (scene-tileset-texture scene)))))
        (unless tex
          (error 'render-scene!
                 (sprintf "entity ~a: no texture for the image ~s of its #:tileset ~s (load it with game-load-tilesets!, or pass textures:)"
                          (entity-label e) (and (tileset-image ts) (image-source (tileset-image ts))) name)))
        (values ts tex))))

  (define (with-zoom r zoom draw)
    (if (= zoom 1)
        (draw 1)
        (receive (sx sy) (render-scale r)
          (render-scale-set! r (* sx zoom) (* sy zoom))
          (dynamic-wind void
                        (lambda () (draw zoom))
                        (lambda () (render-scale-set! r sx sy)))))))
