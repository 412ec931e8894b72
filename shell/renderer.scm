;;; (downstroke renderer): drawing a scene with an SDL renderer.
;;;
;;;   (render-scene! renderer scene #!key view-width view-height textures debug? time)
;;;
;;; draws, in this order:
;;;   1. the whole target cleared to the scene's background, a list
;;;      (r g b [a]) of 0..255 values; black when the background is #f;
;;;   2. every visible layer of the scene's tilemap, as Tiled 1.8 draws it:
;;;      (downstroke mapdraw)'s render-map-layers! (tile, image and object
;;;      layers; parallax, offsets, opacity, tints; every orientation;
;;;      animated tiles at `time` ms, default 0, which game-run! sets to the
;;;      game time);
;;;   3. the entities, in list order: with #:tile-id, that tile of the
;;;      scene's tileset (scene-tileset, else the tilemap's first tileset)
;;;      from scene-tileset-texture (else the texture `textures` gives for
;;;      the tileset's image) at the entity's #:x #:y, at the tileset's tile
;;;      size, mirrored horizontally when #:facing is -1; else, with #:color
;;;      (r g b [a]), a filled #:width x #:height rectangle of that colour
;;;      (alpha below 255 blends); else nothing. An entity whose #:tile-id
;;;      cannot be drawn (no tileset or texture) falls through to #:color.
;;;      An entity with #:animations and no #:tile-id yet (the pipeline
;;;      has not run) is drawn with its current frame's tile
;;;      (animation.scm's animation-tile).
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
;;;      the same single C walk (keys.c) that reads #:tile-id and the rest.
;;;      The entities are drawn by one walk in C (shell/sprites.c) with
;;;      these rules' arithmetic; what it cannot draw exactly so goes to
;;;      the Scheme below, in order (render-entities!);
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
;;; the map. Far-away numbers (mapdraw.scm's whole-pixel, sdl2.scm's
;;; downstroke_rect and render-copy!): a pixel stays an exact integer
;;; however large; an edge that overflowed to an infinity lies beyond every
;;; view and a NaN nowhere; SDL is handed only what it holds, and a copy far
;;; beyond the view is cut on whole texels, so a sprite of #:scale 1e308
;;; (its box computed again in exact numbers) shows the texels the view sees.
;;; An entity's #:x #:y #:width #:height that is not a finite number is an
;;; error naming the entity and the key (entity.scm's check-entity-number).
;;;
;;; The layer camera. A layer with parallax factors (px, py) (Tiled's
;;; parallaxx / parallaxy, multiplied through groups) in a map whose
;;; parallax origin is (ox, oy) is seen through
;;;     lx = ox + (camera-x - ox) * px - round(offset-x)    (ly likewise)
;;; (an offset rounded to whole pixels half up, as Tiled draws it)
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
;;; the box (object-screen-box: tilemap-object-box, projected on isometric
;;; maps) of every visible object of every visible
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
;;; Not drawn: shapes other than tile objects (except as debug outlines)
;;; and text objects. Entities are drawn above every layer of the map.

(module (downstroke renderer)
  (render-scene! render-map-layers! render-entities! render-entity!
   screen-coordinate tileset-source-rect layer-camera
   sprite-fast-path? entities-drawn-by-scheme
   render-debug-overlay! render-draw-line!
   *debug-hitbox-color* *debug-cell-color* *debug-velocity-color*
   *debug-warning-color* *debug-velocity-scale* *debug-object-color*
   ;; for sibling modules only: the level loader refuses a map it cannot draw
   check-map-orientation)

  (import (downstroke keywords) (only (downstroke check) report-entity-problems!)
          (only (downstroke numbers) finite-real?))
  (import scheme (chicken base) (chicken format) (chicken sort) (chicken fixnum) (chicken foreign)
          srfi-4
          (downstroke sdl2) (downstroke entity) (downstroke scene)
          (downstroke map) (downstroke mapdraw)
          (only (downstroke physics) entity-cell-span tunnel-risk?)
          (only (downstroke animation) animation-tile)
          (only (downstroke particles) emitter? emitter-for-each emitter-tile-id emitter-size
                emitter-color emitter-end-color))

  ;; The texture for an image path, from a procedure or an alist; #f if none.
  (define (lookup-texture textures path)
    (cond ((not textures) #f)
          ((procedure? textures) (textures path))
          ((list? textures) (let ((p (assoc path textures))) (and p (cdr p))))
          (else (error 'render-scene! "textures: must be a procedure or an alist" textures))))

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
  ;;; Entities

  (define (color-components who c)
    (unless (and (list? c) (<= 3 (length c) 4))
      (error who "#:color must be (r g b [a])" c))
    (if (= (length c) 3) (append c '(255)) c))

  ;; The keys an entity is drawn by, read in one C walk (keys.c) instead
  ;; of an assq each: the first five are those of plain entities, the
  ;; rest the sprite keys. An entity holding none of the sprite keys is
  ;; drawn by the code of before them; the others by draw-sprite!. The
  ;; bit of each key in the walk's answer is 2 to the power of its index,
  ;; which define-drawn-keys writes down from the one list below.
  (define-syntax define-drawn-keys
    (er-macro-transformer
     (lambda (x r c)
       (let ((keys-name (cadr x)) (entries (cddr x)))     ; (bit-name #:key) ...
         `(,(r 'begin)
           (,(r 'define) ,keys-name (,(r 'vector) ,@(map cadr entries)))
           ,@(let loop ((es entries) (bit 1) (out '()))
               (if (null? es)
                   (reverse out)
                   (loop (cdr es) (* 2 bit) (cons `(,(r 'define-constant) ,(caar es) ,bit) out)))))))))
  (foreign-declare "#include \"shell/keys.c\"")
  (define-drawn-keys entity-keys
    (bit-tile-id #:tile-id) (bit-color #:color) (bit-x #:x) (bit-y #:y) (bit-facing #:facing)
    (bit-animations #:animations)
    (bit-offset-x #:sprite-offset-x) (bit-offset-y #:sprite-offset-y)
    (bit-origin-x #:origin-x) (bit-origin-y #:origin-y) (bit-flip-x #:flip-x?) (bit-flip-y #:flip-y?)
    (bit-angle #:angle) (bit-scale #:scale) (bit-scale-x #:scale-x) (bit-scale-y #:scale-y)
    (bit-alpha #:alpha) (bit-tint #:tint) (bit-tileset #:tileset) (bit-emitter #:emitter))
  (define plain-keys bit-offset-x)      ; the bits below the first sprite key's
  (define key-values (make-vector (vector-length entity-keys) #f))
  (define read-keys! (foreign-lambda scheme-object "ds_entity_keys" scheme-object scheme-object scheme-object))
  (define any-has-key? (foreign-lambda scheme-object "ds_any_has_key" scheme-object scheme-object))

  ;; A key's number, checked: the error names the entity and the key.
  (define (sprite-number e key default)
    (let ((v (entity-ref e key default)))
      (if (finite-real? v)
          v
          (error 'render-scene! (sprintf "entity ~a: ~s is ~s, not a finite number"
                                         (entity-label e) key v)))))

  ;; A colour or alpha component, rounded and held to 0-255 (a tint of
  ;; 300 or +inf.0 is full, -1 none); x is a finite number or an infinity.
  (define (byte-of x) (cond ((>= x 255) 255) ((<= x 0) 0) (else (round-int x))))

  (define (components? c)
    (or (null? c) (and (real? (car c)) (not (nan? (car c))) (components? (cdr c)))))

  ;; An entity's position or size as the renderer reads it: #f is the
  ;; default 0, a fixnum passes at no cost, anything else is checked as
  ;; physics checks it (an error naming the entity and the key).
  (define-inline (drawn-number e key v)
    (cond ((fixnum? v) v)
          ((not v) 0)
          (else (check-entity-number e key v))))

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
             (draw-plain! r (or (vector-ref key-values 0)
                                ;; animated, not stepped yet: its first frame
                                (and (vector-ref key-values 5) (animation-tile e)))
                          (vector-ref key-values 1)
                          (drawn-number e #:x (vector-ref key-values 2))
                          (drawn-number e #:y (vector-ref key-values 3))
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
                            (drawn-number e #:width (entity-ref e #:width 0))
                            (drawn-number e #:height (entity-ref e #:height 0)) cx cy))
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
      (let* ((tile-id (or (entity-ref e #:tile-id #f)
                          (and (has? bit-animations) (animation-tile e))))
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
                                 (drawn-number e #:x (entity-ref e #:x 0))
                                 (drawn-number e #:y (entity-ref e #:y 0))
                                 (drawn-number e #:width (entity-ref e #:width 0))
                                 (drawn-number e #:height (entity-ref e #:height 0)) cx cy))))
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
           (x (drawn-number e #:x (entity-ref e #:x 0)))
           (y (drawn-number e #:y (entity-ref e #:y 0)))
           (offset-x (num bit-offset-x #:sprite-offset-x 0))
           (offset-y (num bit-offset-y #:sprite-offset-y 0))
           (box (sprite-box x y offset-x offset-y kx ky ox oy sw sh angle))
           (box (if (finite-box? box)
                    box
                    ;; past the largest flonum (#:scale 1e308): the same
                    ;; box in exact numbers, whose edges sdl2.scm cuts to
                    ;; the view on whole texels
                    (apply sprite-box (map exact-number (list x y offset-x offset-y kx ky ox oy sw sh angle)))))
           (x0 (screen-coordinate (car box) cx))
           (y0 (screen-coordinate (cadr box) cy))
           (x1 (screen-coordinate (caddr box) cx))
           (y1 (screen-coordinate (cadddr box) cy))
           (flip-x? (not (eq? (and (has? bit-flip-x) #t) (eqv? (entity-ref e #:facing 1) -1))))
           (tint (and (has? bit-tint) (entity-ref e #:tint))))
      (when (or (< kx 0) (< ky 0))
        (error 'render-scene! (sprintf "entity ~a: a negative scale (~s x ~s); mirror with #:flip-x? / #:flip-y?"
                                       (entity-label e) kx ky)))
      (when (and (> x1 x0) (> y1 y0))
        (when tint
          (let ((c (tint-components tint)))
            ;; components beyond 0-255 are held to it; a NaN has no colour
            (unless (and (list? c) (= (length c) 4) (components? c))
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

  ;; The world box (x0 y0 x1 y1) of a sprite sw x sh at x + offset-x (y
  ;; likewise) scaled by kx, ky about its origin (ox, oy) and turned
  ;; `angle` degrees about it: SDL turns a copy about its own centre, so
  ;; a turned box is the unturned one moved to the turned centre.
  (define (sprite-box x y offset-x offset-y kx ky ox oy sw sh angle)
    (let ((px (+ x offset-x ox)) (py (+ y offset-y oy)))   ; the origin in the world
      (if (zero? angle)
          (list (- px (* kx ox)) (- py (* ky oy)) (+ px (* kx (- sw ox))) (+ py (* ky (- sh oy))))
          (let* ((dx (* kx (- (/ sw 2) ox))) (dy (* ky (- (/ sh 2) oy)))   ; centre from the origin
                 (mx (+ px (- (* dx (cosine angle)) (* dy (sine angle)))))
                 (my (+ py (* dx (sine angle)) (* dy (cosine angle))))
                 (hw (/ (* kx sw) 2)) (hh (/ (* ky sh) 2)))
            (list (- mx hw) (- my hh) (+ mx hw) (+ my hh))))))

  (define (finite-box? b)
    (or (null? b) (and (finite-real? (car b)) (finite-box? (cdr b)))))

  (define (exact-number v) (if (exact? v) v (inexact->exact v)))

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
  ;; On an accelerated renderer the unturned copies of a run of entities
  ;; sharing a texture go to SDL as one call (sdl2.scm's render-batched).
  ;; With sprite-fast-path? (the default) the entities are drawn by one
  ;; walk in C (sdl2.scm's render-sprite-walk!, shell/sprites.c), which
  ;; hands back to draw-entity! each entity it does not draw itself: the
  ;; same copies either way (shell/tests/tile-batch-test.scm compares them
  ;; pixel for pixel). (entities-drawn-by-scheme): how many entities of the
  ;; last call went to draw-entity!.
  (define sprite-fast-path? (make-parameter #t))
  (define scheme-drawn 0)
  (define (entities-drawn-by-scheme) scheme-drawn)

  ;; The sheet's numbers for the walk: first gid, tile width and height,
  ;; spacing, margin, columns as tileset-source-rect counts them (columns
  ;; 0: no sheet, or numbers the walk does not take).
  (define (sheet-numbers ts)
    (let ((ns (and ts (list (tileset-first-gid ts) (tileset-tile-width ts) (tileset-tile-height ts)
                            (or (tileset-spacing ts) 0) (or (tileset-margin ts) 0)
                            (let ((c (or (tileset-columns ts) 1))) (if (and (fixnum? c) (fx< c 1)) 1 c))))))
      (if (and ns (let small? ((l ns)) (or (null? l) (and (fixnum? (car l)) (fx>= (car l) 0) (fx< (car l) 65536)
                                                          (small? (cdr l))))))
          (list->s32vector ns)
          (s32vector 0 0 0 0 0 0))))

  (define (render-entities! r entities cx cy tileset texture #!optional (sheet-for no-sheets))
    (let ((ordered (if (any-has-key? entities #:z)
                       (map cdr (sort (map (lambda (e) (cons (sprite-number e #:z 0) e)) entities)
                                      (lambda (a b) (< (car a) (car b)))))
                       entities)))
      (set! scheme-drawn 0)
      (render-batched
       r
       (if (sprite-fast-path?)
           (lambda ()
             (let ((sheet (sheet-numbers tileset)))
               (let walk ((es ordered))
                 (let ((rest (render-sprite-walk! r texture es entity-keys sheet cx cy)))
                   (unless (null? rest)
                     (set! scheme-drawn (fx+ scheme-drawn 1))
                     (draw-entity! r (car rest) cx cy tileset texture sheet-for)
                     (walk (cdr rest)))))))
           (lambda ()
             (set! scheme-drawn (length ordered))
             (for-each (lambda (e) (draw-entity! r e cx cy tileset texture sheet-for)) ordered))))))

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

  ;; Entities the overlay draws: finite numbers for #:width and #:height,
  ;; and for #:x and #:y when present, with a far edge that is finite too
  ;; (a broken body is physics' to report).
  (define (sized? e)
    (let ((x (entity-ref e #:x 0)) (y (entity-ref e #:y 0))
          (w (entity-ref e #:width #f)) (h (entity-ref e #:height #f)))
      (and (finite-real? w) (finite-real? h) (finite-real? x) (finite-real? y)
           (finite-real? (+ x w)) (finite-real? (+ y h)))))

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
             (receive (lx ly) (layer-camera tm layer cx cy)
               ;; a layer further than any flonum is not drawn (mapdraw.scm)
               (when (and (layer-visible? layer) (finite? lx) (finite? ly))
                 (for-each
                  (lambda (o)
                    (when (object-visible? o)
                      (receive (x y w h) (object-screen-box tm o)
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
                         (debug? #f) (time 0))
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
                (when tm (render-map-layers! r tm cx cy vw vh tex-for time))
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
