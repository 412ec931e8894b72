;;; (downstroke tilemap): tile maps as immutable data, and the TMX loader.
;;;
;;; A tilemap is a grid of W x H cells in one or more tile layers, each cell a
;;; 32-bit value as Tiled writes it: the global tile id (gid) in the low 28
;;; bits, the flip flags in the top four (bit 31 horizontal, 30 vertical,
;;; 29 diagonal, 28 hexagonal 120-degree rotation). Layer data is a u32vector
;;; in row-major order, so `tilemap-tile-at` is O(1). `tilemap-tile-at` answers
;;; the flag-free gid, `tilemap-cell-at` the raw value with its flags.
;;;
;;; Collision asks one question of a cell, "is it solid?", and that answer is
;;; precomputed once per map into a single byte grid merged from every
;;; colliding tile layer (those nested in groups included), using the
;;; flag-free gid: a cell is solid when that gid is not 0.
;;;
;;; Which layers collide: every tile layer, unless the layer has the property
;;; `collides` set to #f (a bool property; the string "false" or the int 0
;;; do not opt out). So the contract's default holds (any non-zero tile
;;; is solid) and a decoration layer opts out with one property in Tiled.
;;;
;;; Infinite maps. Tiled stores an infinite map's layers as chunks at any
;;; tile position, negative ones included. The loaded map covers the union of
;;; all chunks of all tile layers: `tilemap-origin-col`/`-row` is the
;;; top-left cell of that rectangle (0 and 0 for finite maps), and
;;; `tilemap-width`/`-height` its size. Every cell accessor takes the column
;;; and row Tiled shows, so valid columns are [origin-col, origin-col + width)
;;; and valid rows [origin-row, origin-row + height). Cells outside are empty
;;; (any exact integer is a cell, bignums included); a column or row that is
;;; not an exact integer is an error, and so is an unknown layer, whether the
;;; cell is inside the map or not.
;;;
;;; The loader. `(load-tilemap path)` reads a TMX file with its external
;;; tilesets (.tsx), templates (.tx) and checks that every image they name
;;; exists (images are not decoded). It never crashes the process: every
;;; problem is raised as an error whose message starts with the file it is in
;;; and says what is wrong; the condition also has the kind `tmx` with the
;;; property `file`.
;;;
;;; Representation of what a map holds (all immutable after loading):
;;; - layers: `layer` records of kind tile, object, image or group. Offsets
;;;   and parallax factors are the effective ones (a group's offset is added to
;;;   its children's, its parallax multiplied), as are opacity (multiplied)
;;;   and visibility (and-ed); tint is the layer's own.
;;; - tilesets: `tileset` records, in firstgid order; per-tile data in `tile`
;;;   records (properties, image, animation frames, collision shapes).
;;; - objects: `map-object` records; shape is one of the symbols rectangle,
;;;   ellipse, point, polygon, polyline, text, tile.
;;; - properties: an alist (name . value) in file order. Values: string,
;;;   exact integer (int), flonum (float), #t/#f (bool), and tagged lists for
;;;   the rest: (color R G B A) or (color) when unset, (file "resolved/path"),
;;;   (object ID), (class "TypeName" ((member . value) ...)), (list v ...).
;;; - colors (background, tint, object layer colour, image transparency) are
;;;   (color R G B A) lists too.

(module (downstroke tilemap)
  (;; in-memory maps
   make-tilemap list->tilemap tilemap?
   tilemap-width tilemap-height tilemap-tile-width tilemap-tile-height
   tilemap-pixel-width tilemap-pixel-height tilemap-origin-col tilemap-origin-row
   tilemap-layers tilemap-layer tilemap-properties
   tilemap-tile-at tilemap-cell-at tilemap-flags-at tilemap-solid? tilemap-solid-grid
   ;; map attributes
   tilemap-source tilemap-version tilemap-tiled-version tilemap-class
   tilemap-orientation tilemap-render-order tilemap-infinite?
   tilemap-hex-side-length tilemap-stagger-axis tilemap-stagger-index
   tilemap-parallax-origin-x tilemap-parallax-origin-y tilemap-background-color
   tilemap-tilesets tilemap-layer-tree tilemap-all-layers tilemap-object-layers
   tilemap-image-layers tilemap-objects tilemap-tileset-for tilemap-tile-info
   tilemap-hide-layers tilemap-object-box tilemap-object-anchor
   ;; cells
   cell-gid cell-flags cell-flipped-horizontally? cell-flipped-vertically?
   cell-flipped-diagonally? cell-rotated-hex-120?
   ;; layers
   make-layer layer? layer-kind layer-id layer-name layer-class layer-width
   layer-height layer-data layer-visible? layer-opacity layer-tint
   layer-offset-x layer-offset-y layer-parallax-x layer-parallax-y
   layer-locked? layer-properties layer-collides? layer-objects
   layer-draw-order layer-color layer-image layer-repeat-x? layer-repeat-y?
   layer-children
   ;; tilesets and tiles
   tileset? tileset-first-gid tileset-name tileset-class tileset-source
   tileset-tile-width tileset-tile-height tileset-spacing tileset-margin
   tileset-tile-count tileset-columns tileset-image tileset-offset-x
   tileset-offset-y tileset-object-alignment tileset-grid tileset-properties
   tileset-tiles tileset-tile tileset-covers?
   tile? tile-id tile-class tile-probability tile-properties tile-image
   tile-x tile-y tile-width tile-height tile-animation tile-shapes
   image? image-source image-width image-height image-trans
   ;; objects
   map-object? object-id object-name object-class object-type object-x
   object-y object-width object-height object-rotation object-gid
   object-cell object-visible? object-shape object-points object-text
   object-properties object-template
   ;; properties
   property-ref property-type
   ;; loading
   load-tilemap tilemap-max-cells
   ;; tilesets without a map (sprite scenes)
   load-tileset make-sheet-tileset)

  (import scheme (chicken base) (chicken fixnum) (chicken format)
          (chicken bitwise) (chicken pathname) (chicken condition)
          (chicken string) (chicken file) srfi-4
          (downstroke xml) (downstroke decode)
          (only (downstroke util) filter append-map any
                make-hash-table hash-table-ref/default hash-table-set!
                hash-table-exists?))

  ;;; ------------------------------------------------------------------
  ;;; Cells: a gid and four flag bits.

  (define gid-mask #x0FFFFFFF)
  (define flag-horizontal #x80000000)
  (define flag-vertical #x40000000)
  (define flag-diagonal #x20000000)
  (define flag-hex-120 #x10000000)

  (define (cell-gid cell) (bitwise-and cell gid-mask))
  (define (cell-flipped-horizontally? cell) (not (zero? (bitwise-and cell flag-horizontal))))
  (define (cell-flipped-vertically? cell) (not (zero? (bitwise-and cell flag-vertical))))
  (define (cell-flipped-diagonally? cell) (not (zero? (bitwise-and cell flag-diagonal))))
  (define (cell-rotated-hex-120? cell) (not (zero? (bitwise-and cell flag-hex-120))))

  ;; The flags of a cell as a list of symbols, in bit order (31 down to 28).
  (define (cell-flags cell)
    (append (if (cell-flipped-horizontally? cell) '(horizontal) '())
            (if (cell-flipped-vertically? cell) '(vertical) '())
            (if (cell-flipped-diagonally? cell) '(diagonal) '())
            (if (cell-rotated-hex-120? cell) '(hex-120) '())))

  ;;; ------------------------------------------------------------------
  ;;; Records

  (define-record-type layer
    (%make-layer kind id name class width height data visible? opacity tint
                 offset-x offset-y parallax-x parallax-y locked? properties
                 objects draw-order color image repeat-x? repeat-y? children)
    layer?
    (kind layer-kind)                   ; tile | object | image | group
    (id layer-id)                       ; Tiled's layer id, or #f
    (name layer-name)
    (class layer-class)                 ; "" when none
    (width layer-width)                 ; tile layers: the map's size
    (height layer-height)
    (data layer-data)                   ; tile layers: u32vector of cells
    (visible? layer-visible?)           ; effective (groups and-ed)
    (opacity layer-opacity)             ; effective (groups multiplied)
    (tint layer-tint)                   ; own: (color R G B A) or #f
    (offset-x layer-offset-x)           ; effective (groups added), pixels
    (offset-y layer-offset-y)
    (parallax-x layer-parallax-x)       ; effective (groups multiplied)
    (parallax-y layer-parallax-y)
    (locked? layer-locked?)
    (properties layer-properties)
    (objects layer-objects)             ; object layers: list of map-object
    (draw-order layer-draw-order)       ; object layers: topdown | index
    (color layer-color)                 ; object layers: (color ...) or #f
    (image layer-image)                 ; image layers: image record or #f
    (repeat-x? layer-repeat-x?)
    (repeat-y? layer-repeat-y?)
    (children layer-children))          ; group layers: list of layers

  (define (make-layer name width height data #!key (visible? #t) (properties '())
                      (id #f) (class "") (opacity 1) (tint #f) (offset-x 0)
                      (offset-y 0) (parallax-x 1) (parallax-y 1) (locked? #f))
    (unless (and (u32vector? data) (= (u32vector-length data) (* width height)))
      (error 'make-layer
             (sprintf "layer ~s: data must be a u32vector of ~a cells" name (* width height))))
    (%make-layer 'tile id name class width height data visible? opacity tint
                 offset-x offset-y parallax-x parallax-y locked? properties
                 '() #f #f #f #f #f '()))

  (define (layer-collides? layer)
    (let ((p (assoc "collides" (layer-properties layer))))
      (not (and p (not (cdr p))))))

  (define-record-type image
    (make-image source width height trans)
    image?
    (source image-source)               ; path resolved against its file, or #f
    (width image-width)                 ; #f when not given
    (height image-height)
    (trans image-trans))                ; (color R G B 255) or #f

  (define-record-type tile
    (make-tile id class probability properties image x y width height animation shapes)
    tile?
    (id tile-id)                        ; local id within its tileset
    (class tile-class)
    (probability tile-probability)
    (properties tile-properties)
    (image tile-image)                  ; image collections: its own image
    (x tile-x) (y tile-y)               ; sub-rectangle of the image (Tiled 1.9)
    (width tile-width) (height tile-height)
    (animation tile-animation)          ; list of (local-tile-id . duration-ms)
    (shapes tile-shapes))               ; collision shapes: list of map-object

  (define-record-type tileset
    (make-tileset first-gid name class source tile-width tile-height spacing
                  margin tile-count columns image offset-x offset-y
                  object-alignment grid properties tiles)
    tileset?
    (first-gid tileset-first-gid)
    (name tileset-name)
    (class tileset-class)
    (source tileset-source)             ; the .tsx path, or #f when embedded
    (tile-width tileset-tile-width)
    (tile-height tileset-tile-height)
    (spacing tileset-spacing)
    (margin tileset-margin)
    (tile-count tileset-tile-count)     ; #f when it cannot be known
    (columns tileset-columns)
    (image tileset-image)               ; image record, #f for image collections
    (offset-x tileset-offset-x)
    (offset-y tileset-offset-y)
    (object-alignment tileset-object-alignment)
    (grid tileset-grid)                 ; (orientation width height) or #f
    (properties tileset-properties)
    (tiles tileset-tile-table))

  ;; Per-tile data by local id, or #f.
  (define (tileset-tile ts id)
    (hash-table-ref/default (tileset-tile-table ts) id #f))

  (define (tileset-tiles ts)
    (map (lambda (id) (tileset-tile ts id)) (tileset-tile-ids ts)))

  (define (tileset-tile-ids ts)
    (hash-table-ref/default (tileset-tile-table ts) 'order '()))

  ;; Whether a flag-free gid names a tile of this tileset. An image tileset
  ;; covers tile-count ids; an image collection only the ids it lists.
  (define (tileset-covers? ts gid)
    (let ((local (- gid (tileset-first-gid ts))))
      (and (>= local 0)
           (if (tileset-image ts)
               (let ((n (tileset-tile-count ts))) (or (not n) (< local n)))
               (and (tileset-tile ts local) #t)))))

  (define-record-type map-object
    (make-map-object id name class x y width height rotation cell visible?
                     shape points text properties template)
    map-object?
    (id object-id)
    (name object-name)
    (class object-class)                ; `type` before Tiled 1.9
    (x object-x) (y object-y)
    (width object-width) (height object-height)
    (rotation object-rotation)          ; degrees, clockwise
    (cell object-cell)                  ; raw gid with flags, 0 when not a tile
    (visible? object-visible?)
    (shape object-shape)
    (points object-points)              ; polygon/polyline: list of (x . y)
    (text object-text)                  ; text objects: alist, else #f
    (properties object-properties)
    (template object-template))         ; the .tx path, or #f

  (define (object-type o) (object-class o))
  (define (object-gid o) (cell-gid (object-cell o)))

  (define-record-type tilemap
    (%make-tilemap width height tile-width tile-height layers properties solid
                   origin-col origin-row info tilesets layer-tree)
    tilemap?
    (width tilemap-width)
    (height tilemap-height)
    (tile-width tilemap-tile-width)
    (tile-height tilemap-tile-height)
    (layers tilemap-layers)             ; tile layers, groups flattened
    (properties tilemap-properties)
    (solid tilemap-solid-grid)
    (origin-col tilemap-origin-col)
    (origin-row tilemap-origin-row)
    (info tilemap-info)                 ; alist of the map's attributes
    (tilesets tilemap-tilesets)
    (layer-tree tilemap-layer-tree))    ; every layer, as nested in Tiled

  (define (info-ref tm key default)
    (let ((p (assq key (tilemap-info tm)))) (if p (cdr p) default)))

  (define (tilemap-source tm) (info-ref tm 'source #f))
  (define (tilemap-version tm) (info-ref tm 'version #f))
  (define (tilemap-tiled-version tm) (info-ref tm 'tiled-version #f))
  (define (tilemap-class tm) (info-ref tm 'class ""))
  (define (tilemap-orientation tm) (info-ref tm 'orientation 'orthogonal))
  (define (tilemap-render-order tm) (info-ref tm 'render-order 'right-down))
  (define (tilemap-infinite? tm) (info-ref tm 'infinite? #f))
  (define (tilemap-hex-side-length tm) (info-ref tm 'hex-side-length #f))
  (define (tilemap-stagger-axis tm) (info-ref tm 'stagger-axis #f))
  (define (tilemap-stagger-index tm) (info-ref tm 'stagger-index #f))
  (define (tilemap-parallax-origin-x tm) (info-ref tm 'parallax-origin-x 0))
  (define (tilemap-parallax-origin-y tm) (info-ref tm 'parallax-origin-y 0))
  (define (tilemap-background-color tm) (info-ref tm 'background-color #f))

  ;; Every layer in document order, a group before its children.
  (define (tilemap-all-layers tm)
    (let walk ((layers (tilemap-layer-tree tm)))
      (append-map (lambda (l) (cons l (walk (layer-children l)))) layers)))

  (define (layers-of-kind tm kind)
    (filter (lambda (l) (eq? (layer-kind l) kind)) (tilemap-all-layers tm)))
  (define (tilemap-object-layers tm) (layers-of-kind tm 'object))
  (define (tilemap-image-layers tm) (layers-of-kind tm 'image))
  (define (tilemap-objects tm) (append-map layer-objects (tilemap-object-layers tm)))

  ;; A copy of the map in which every layer satisfying (hide? layer) is
  ;; invisible (layer-visible? #f), a group's children included. Nothing
  ;; else changes: cells, objects, and which cells are solid (collision
  ;; ignores visibility) stay as they were. game-load-scene! uses it to hide
  ;; the object layers whose objects became entities, so they are drawn once.
  (define (tilemap-hide-layers tm hide?)
    (define renamed '())                ; (old tile layer . its copy)
    (define (copy l visible? children)
      (%make-layer (layer-kind l) (layer-id l) (layer-name l) (layer-class l)
                   (layer-width l) (layer-height l) (layer-data l)
                   visible? (layer-opacity l) (layer-tint l)
                   (layer-offset-x l) (layer-offset-y l)
                   (layer-parallax-x l) (layer-parallax-y l)
                   (layer-locked? l) (layer-properties l) (layer-objects l)
                   (layer-draw-order l) (layer-color l) (layer-image l)
                   (layer-repeat-x? l) (layer-repeat-y? l) children))
    ;; in-hidden?: inside a group being hidden
    (define (walk l in-hidden?)
      (let* ((h (or in-hidden? (and (hide? l) #t)))
             (new (if (and (not h) (null? (layer-children l)))
                      l
                      (copy l (and (not h) (layer-visible? l))
                            (map (lambda (c) (walk c h)) (layer-children l))))))
        (when (eq? (layer-kind l) 'tile)
          (set! renamed (cons (cons l new) renamed)))
        new))
    (let* ((tree (map (lambda (l) (walk l #f)) (tilemap-layer-tree tm)))
           (layers (map (lambda (l) (let ((p (assq l renamed))) (if p (cdr p) l)))
                        (tilemap-layers tm))))
      (%make-tilemap (tilemap-width tm) (tilemap-height tm)
                     (tilemap-tile-width tm) (tilemap-tile-height tm)
                     layers (tilemap-properties tm) (tilemap-solid-grid tm)
                     (tilemap-origin-col tm) (tilemap-origin-row tm)
                     (tilemap-info tm) (tilemap-tilesets tm) tree)))

  ;; Where a tile object's image hangs from its (x, y): the fractions of
  ;; its width and height left of and above that point, (values ax ay).
  ;; Tiled's default (unspecified) for orthogonal maps is bottom-left.
  (define (tilemap-object-anchor tm object)
    (let* ((ts (tilemap-tileset-for tm (object-cell object)))
           (align (if ts (tileset-object-alignment ts) 'unspecified)))
      (case align
        ((top-left) (values 0 0)) ((top) (values 1/2 0)) ((top-right) (values 1 0))
        ((left) (values 0 1/2)) ((center) (values 1/2 1/2)) ((right) (values 1 1/2))
        ((bottom) (values 1/2 1)) ((bottom-right) (values 1 1))
        (else (values 0 1)))))          ; bottom-left, unspecified

  ;; The unrotated box an object covers, (values x y width height) in map
  ;; pixels, x y its top-left corner:
  ;;   tile objects: the tile's image placed by the anchor above, at the
  ;;     object's size (the tile's own size when the object gives 0),
  ;;     moved by its tileset's <tileoffset>;
  ;;   polygons and polylines: the bounding box of their points;
  ;;   the rest (rectangles, ellipses, text, points): x y width height as
  ;;     written (a point is 0 x 0).
  (define (tilemap-object-box tm object)
    (let ((x (object-x object)) (y (object-y object))
          (w (object-width object)) (h (object-height object)))
      (case (object-shape object)
        ((tile)
         (let* ((ts (tilemap-tileset-for tm (object-cell object)))
                (tile (and ts (tileset-tile ts (- (object-gid object) (tileset-first-gid ts)))))
                (tw (cond ((not ts) 0)
                          ((tileset-image ts) (tileset-tile-width ts))
                          ((and tile (tile-width tile)))
                          ((and tile (tile-image tile) (image-width (tile-image tile))))
                          (else (tileset-tile-width ts))))
                (th (cond ((not ts) 0)
                          ((tileset-image ts) (tileset-tile-height ts))
                          ((and tile (tile-height tile)))
                          ((and tile (tile-image tile) (image-height (tile-image tile))))
                          (else (tileset-tile-height ts))))
                (w (if (zero? w) tw w))
                (h (if (zero? h) th h)))
           (receive (ax ay) (tilemap-object-anchor tm object)
             (values (+ (- x (* ax w)) (if ts (tileset-offset-x ts) 0))
                     (+ (- y (* ay h)) (if ts (tileset-offset-y ts) 0))
                     w h))))
        ((polygon polyline)
         (let ((ps (object-points object)))
           (if (null? ps)
               (values x y 0 0)
               (let ((x0 (apply min (map car ps))) (x1 (apply max (map car ps)))
                     (y0 (apply min (map cdr ps))) (y1 (apply max (map cdr ps))))
                 (values (+ x x0) (+ y y0) (- x1 x0) (- y1 y0))))))
        ((point) (values x y 0 0))
        (else (values x y w h)))))

  ;; The tileset a gid (flags allowed) belongs to: the one with the highest
  ;; firstgid not above it. #f for gid 0 or below every firstgid.
  (define (tilemap-tileset-for tm gid)
    (let ((g (cell-gid gid)))
      (and (> g 0)
           (let loop ((ts (tilemap-tilesets tm)) (best #f))
             (cond ((null? ts) best)
                   ((<= (tileset-first-gid (car ts)) g) (loop (cdr ts) (car ts)))
                   (else best))))))

  ;; The per-tile data (a tile record) of a gid, or #f.
  (define (tilemap-tile-info tm gid)
    (let ((ts (tilemap-tileset-for tm gid)))
      (and ts (tileset-tile ts (- (cell-gid gid) (tileset-first-gid ts))))))

  (define (solid-grid width height layers)
    (let* ((n (* width height))
           (grid (make-u8vector n 0)))
      (for-each
       (lambda (layer)
         (when (layer-collides? layer)
           (let ((data (layer-data layer)))
             (do ((i 0 (fx+ i 1))) ((fx= i n))
               (unless (fx= 0 (fxand (u32vector-ref data i) gid-mask))
                 (u8vector-set! grid i 1))))))
       layers)
      grid))

  (define (make-tilemap width height tile-width tile-height layers
                        #!key (properties '()) (origin-col 0) (origin-row 0)
                        (info '()) (tilesets '()) (layer-tree layers))
    (for-each
     (lambda (layer)
       (unless (and (eq? (layer-kind layer) 'tile)
                    (= (layer-width layer) width) (= (layer-height layer) height))
         (error 'make-tilemap
                (sprintf "layer ~s is ~ax~a, the map is ~ax~a"
                         (layer-name layer) (layer-width layer) (layer-height layer)
                         width height))))
     layers)
    (unless (and (fixnum? tile-width) (fx> tile-width 0)
                 (fixnum? tile-height) (fx> tile-height 0))
      (error 'make-tilemap "tile size must be positive integers" tile-width tile-height))
    (%make-tilemap width height tile-width tile-height layers properties
                   (solid-grid width height layers) origin-col origin-row
                   info tilesets layer-tree))

  ;; A one-layer map from rows of tile ids: procedural levels, tests, the REPL.
  (define (list->tilemap rows #!key (tile-width 16) (tile-height 16) (name "tiles"))
    (let* ((height (length rows))
           (width (if (null? rows) 0 (length (car rows))))
           (data (make-u32vector (* width height) 0)))
      (let loop ((rows rows) (j 0))
        (unless (null? rows)
          (unless (= (length (car rows)) width)
            (error 'list->tilemap
                   (sprintf "row ~a has ~a tiles, row 0 has ~a" j (length (car rows)) width)))
          (let fill ((cells (car rows)) (i 0))
            (unless (null? cells)
              (let ((id (car cells)))
                (unless (and (exact-integer? id) (<= 0 id 4294967295))
                  (error 'list->tilemap (sprintf "cell (~a, ~a) is not a tile id" i j) id))
                (u32vector-set! data (+ (* j width) i) id))
              (fill (cdr cells) (+ i 1))))
          (loop (cdr rows) (+ j 1))))
      (make-tilemap width height tile-width tile-height
                    (list (make-layer name width height data)))))

  (define (tilemap-pixel-width tm) (* (tilemap-width tm) (tilemap-tile-width tm)))
  (define (tilemap-pixel-height tm) (* (tilemap-height tm) (tilemap-tile-height tm)))

  ;; A tile layer by index (0 = first) or by name.
  (define (tilemap-layer tm which)
    (let loop ((layers (tilemap-layers tm)) (i 0))
      (cond ((null? layers) (error 'tilemap-layer "no such layer" which))
            ((if (string? which)
                 (equal? which (layer-name (car layers)))
                 (eqv? which i))
             (car layers))
            (else (loop (cdr layers) (+ i 1))))))

  ;; A coordinate that is not an exact integer is an error naming it; an
  ;; exact integer of any size is a cell, inside the map or not.
  (define (check-coordinate who name x)
    (unless (exact-integer? x)
      (error who (sprintf "~a: expected an exact integer, got ~s" name x))))

  ;; The index of a cell in the layer vectors, or #f outside the map.
  ;; Fixnums take the fast path; anything else is checked (bignums are
  ;; outside every map, the rest an error).
  (define (cell-index who tm col row)
    (if (and (fixnum? col) (fixnum? row))
        (let ((c (- col (tilemap-origin-col tm)))
              (r (- row (tilemap-origin-row tm))))
          (and (fixnum? c) (fixnum? r)
               (fx>= c 0) (fx< c (tilemap-width tm))
               (fx>= r 0) (fx< r (tilemap-height tm))
               (fx+ (fx* r (tilemap-width tm)) c)))
        (begin (check-coordinate who "col" col)
               (check-coordinate who "row" row)
               #f)))

  ;; The cell data of layer `which`, looked up before the cell so that an
  ;; unknown layer is an error wherever the cell is. Layer 0 (the default)
  ;; is the head of the list.
  (define (layer-cells tm which)
    (let ((layers (tilemap-layers tm)))
      (layer-data (if (and (eqv? which 0) (pair? layers))
                      (car layers)
                      (tilemap-layer tm which)))))

  (define (cell-ref who tm col row which)
    (let* ((i (cell-index who tm col row))
           (data (layer-cells tm which)))
      (if i (u32vector-ref data i) 0)))

  ;; The raw cell (gid with flip flags); 0 when empty or outside the map.
  (define (tilemap-cell-at tm col row #!optional (which 0))
    (cell-ref 'tilemap-cell-at tm col row which))

  ;; The tile id (flag-free gid) at a cell; 0 when empty or outside the map.
  (define (tilemap-tile-at tm col row #!optional (which 0))
    (fxand (cell-ref 'tilemap-tile-at tm col row which) gid-mask))

  ;; The flip flags of a cell, as cell-flags gives them.
  (define (tilemap-flags-at tm col row #!optional (which 0))
    (cell-flags (cell-ref 'tilemap-flags-at tm col row which)))

  ;; Whether any colliding layer has a tile at the cell; outside is empty.
  (define (tilemap-solid? tm col row)
    (let ((i (cell-index 'tilemap-solid? tm col row)))
      (and i (fx= 1 (u8vector-ref (tilemap-solid-grid tm) i)))))

  ;;; ------------------------------------------------------------------
  ;;; Properties

  (define (property-ref props name #!optional default)
    (let ((p (assoc name props))) (if p (cdr p) default)))

  ;; The Tiled type of a property value.
  (define (property-type v)
    (cond ((string? v) 'string)
          ((boolean? v) 'bool)
          ((exact-integer? v) 'int)
          ((number? v) 'float)
          ((and (pair? v) (memq (car v) '(color file object class list))) (car v))
          (else #f)))

  ;;; ------------------------------------------------------------------
  ;;; Loading: errors

  ;; The largest number of cells a layer (or the union of an infinite map's
  ;; chunks) may have: 2^26, a 8192 x 8192 map. Larger is an error, never an
  ;; attempt to allocate.
  (define tilemap-max-cells (make-parameter (* 8192 8192)))

  ;; The procedure a loading error is reported from.
  (define loader (make-parameter 'load-tilemap))

  (define (tmx-error file fmt . args)
    (let ((msg (string-append file ": " (apply sprintf fmt args))))
      (abort (make-composite-condition
              (make-property-condition 'exn 'location (loader)
                                       'message msg 'arguments '())
              (make-property-condition 'tmx 'file file)))))

  (define tmx-condition? (condition-predicate 'tmx))

  (define (condition-message exn)
    (if (condition? exn)
        (let ((msg ((condition-property-accessor 'exn 'message #f) exn))
              (args ((condition-property-accessor 'exn 'arguments '()) exn)))
          (if (string? msg)
              (apply string-append msg
                     (map (lambda (a) (sprintf " ~s" a))
                          (if (list? args) args '())))
              (sprintf "~s" exn)))
        (sprintf "~s" exn)))

  ;; Runs thunk; any error that is not already ours becomes one that names
  ;; file and what was being done.
  (define (with-tmx-context file what thunk)
    (handle-exceptions exn
        (if (tmx-condition? exn)
            (abort exn)
            (tmx-error file "~a: ~a" what (condition-message exn)))
      (thunk)))

  ;;; ------------------------------------------------------------------
  ;;; Loading: SXML access and attribute parsing

  (define (element? x) (and (pair? x) (symbol? (car x)) (not (eq? (car x) '@))
                            (not (eq? (car x) '*PI*)) (not (eq? (car x) '*COMMENT*))))

  (define (x-attrs node)
    (let ((rest (cdr node)))
      (if (and (pair? rest) (pair? (car rest)) (eq? (caar rest) '@)) (cdar rest) '())))

  (define (x-attr node name)
    (let ((p (assq name (x-attrs node))))
      (and p (pair? (cdr p)) (cadr p))))

  (define (x-children node #!optional tag)
    (filter (lambda (c) (and (element? c) (or (not tag) (eq? (car c) tag))))
            (cdr node)))

  (define (x-child node tag)
    (let loop ((cs (cdr node)))
      (cond ((null? cs) #f)
            ((and (element? (car cs)) (eq? (caar cs) tag)) (car cs))
            (else (loop (cdr cs))))))

  (define (x-text node)
    (apply string-append (filter string? (cdr node))))

  ;; Each attribute reader takes ctx: (file . "what is being read").
  (define (ctx-file ctx) (car ctx))
  (define (ctx-what ctx) (cdr ctx))
  (define (sub-ctx ctx what) (cons (car ctx) (string-append (cdr ctx) ", " what)))

  (define (bad-attr ctx node name expected)
    (tmx-error (ctx-file ctx) "~a: attribute ~a=~s of <~a> is not ~a"
               (ctx-what ctx) name (x-attr node name) (car node) expected))

  (define (attr-string node name default)
    (or (x-attr node name) default))

  (define (parse-real s)
    (let ((n (and (string? s) (string->number s))))
      (and n (real? n) (not (nan? n)) (finite? n) n)))

  (define (attr-number ctx node name default)
    (let ((s (x-attr node name)))
      (cond ((not s) default)
            ((parse-real s) => values)
            (else (bad-attr ctx node name "a number")))))

  (define (attr-int ctx node name default #!optional (min -inf.0))
    (let ((s (x-attr node name)))
      (if (not s)
          default
          (let ((n (parse-real s)))
            (if (and n (exact-integer? n) (>= n min)
                     (< (abs n) 4294967296))
                n
                (bad-attr ctx node name
                          (if (> min 0) "a positive integer"
                              (if (= min 0) "a non-negative integer" "an integer"))))))))

  (define (attr-bool ctx node name default)
    (let ((s (x-attr node name)))
      (cond ((not s) default)
            ((member s '("1" "true")) #t)
            ((member s '("0" "false")) #f)
            (else (bad-attr ctx node name "0, 1, true or false")))))

  (define (attr-choice ctx node name choices default)
    (let ((s (x-attr node name)))
      (cond ((not s) default)
            ((assoc s choices) => cdr)
            (else (tmx-error (ctx-file ctx) "~a: unsupported ~a ~s of <~a> (expected one of ~a)"
                             (ctx-what ctx) name s (car node)
                             (string-intersperse (map car choices) ", "))))))

  (define (hex-digit c)
    (let ((i (char->integer c)))
      (cond ((and (>= i 48) (<= i 57)) (- i 48))
            ((and (>= i 97) (<= i 102)) (- i 87))
            ((and (>= i 65) (<= i 70)) (- i 55))
            (else #f))))

  ;; "#AARRGGBB", "#RRGGBB" (the # optional) -> (color R G B A); "" -> #f.
  (define (parse-color s)
    (let* ((s (if (and (> (string-length s) 0) (char=? (string-ref s 0) #\#))
                  (substring s 1 (string-length s))
                  s))
           (n (string-length s))
           (byte (lambda (i)
                   (let ((a (hex-digit (string-ref s i)))
                         (b (hex-digit (string-ref s (+ i 1)))))
                     (and a b (+ (* 16 a) b))))))
      (cond ((= n 6)
             (let ((r (byte 0)) (g (byte 2)) (b (byte 4)))
               (and r g b (list 'color r g b 255))))
            ((= n 8)
             (let ((a (byte 0)) (r (byte 2)) (g (byte 4)) (b (byte 6)))
               (and a r g b (list 'color r g b a))))
            (else #f))))

  (define (attr-color ctx node name)
    (let ((s (x-attr node name)))
      (and s (not (string=? s ""))
           (or (parse-color s) (bad-attr ctx node name "a colour (#AARRGGBB or #RRGGBB)")))))

  ;;; ------------------------------------------------------------------
  ;;; Loading: files

  (define (resolve-path relative-to path)
    (if (absolute-pathname? path)
        (normalize-pathname path)
        (normalize-pathname (make-pathname (pathname-directory relative-to) path))))

  ;; A file a path names: present, and not a directory.
  (define (regular-file? path) (and (file-exists? path) (not (directory-exists? path))))

  (define (check-exists ctx path what)
    (unless (regular-file? path)
      (tmx-error (ctx-file ctx) "~a: ~a file ~s not found" (ctx-what ctx) what path)))

  ;; The root element of an XML file, which must be a <tag>.
  (define (read-root ctx path tag)
    (let ((tree (handle-exceptions exn
                    (tmx-error path "malformed XML: ~a" (condition-message exn))
                  (xml-parse-file path))))
      (let ((root (and (pair? tree) (let loop ((cs (cdr tree)))
                                      (cond ((null? cs) #f)
                                            ((element? (car cs)) (car cs))
                                            (else (loop (cdr cs))))))))
        (unless (and root (eq? (car root) tag))
          (tmx-error path "the root element is ~a, expected <~a>"
                     (if root (sprintf "<~a>" (car root)) "missing") tag))
        root)))

  ;;; ------------------------------------------------------------------
  ;;; Loading: properties

  (define (parse-properties ctx node)
    (let ((props (and node (x-child node 'properties))))
      (if props
          (map (lambda (p) (parse-property ctx p)) (x-children props 'property))
          '())))

  (define (parse-property ctx p)
    (let* ((name (or (x-attr p 'name)
                     (tmx-error (ctx-file ctx) "~a: a <property> has no name" (ctx-what ctx))))
           (pctx (sub-ctx ctx (sprintf "property ~s" name))))
      (cons name (property-value pctx p))))

  (define (property-value ctx p)
    (let* ((type (attr-string p 'type "string"))
           (value (or (x-attr p 'value) (x-text p)))
           (fail (lambda (expected)
                   (tmx-error (ctx-file ctx) "~a: value ~s is not ~a" (ctx-what ctx) value expected))))
      (cond ((string=? type "string") value)
            ((string=? type "int")
             (let ((n (parse-real value)))
               (if (and n (exact-integer? n)) n (fail "an integer"))))
            ((string=? type "float")
             (let ((n (parse-real value)))
               (if n (exact->inexact n) (fail "a number"))))
            ((string=? type "bool")
             (cond ((string=? value "true") #t)
                   ((string=? value "false") #f)
                   (else (fail "true or false"))))
            ((string=? type "color")
             (if (string=? value "")
                 '(color)
                 (or (parse-color value) (fail "a colour"))))
            ((string=? type "file")
             (list 'file (if (string=? value "") "" (resolve-path (ctx-file ctx) value))))
            ((string=? type "object")
             (let ((n (parse-real value)))
               (if (and n (exact-integer? n) (>= n 0)) (list 'object n) (fail "an object id"))))
            ((string=? type "class")
             (list 'class (attr-string p 'propertytype "") (parse-properties ctx p)))
            ((string=? type "list")
             (cons 'list
                   (map (lambda (item) (property-value ctx item))
                        (append (x-children p 'item)
                                (let ((ps (x-child p 'properties)))
                                  (if ps (x-children ps 'property) '()))))))
            (else (tmx-error (ctx-file ctx) "~a: unknown property type ~s" (ctx-what ctx) type)))))

  ;;; ------------------------------------------------------------------
  ;;; Loading: images and tilesets

  (define (parse-image ctx node)
    (let ((source (x-attr node 'source)))
      (when (and source (string=? source ""))
        (tmx-error (ctx-file ctx) "~a: <image> has an empty source" (ctx-what ctx)))
      (let ((path (and source (resolve-path (ctx-file ctx) source))))
        (when path (check-exists ctx path "image"))
        (unless (or path (x-child node 'data))
          (tmx-error (ctx-file ctx) "~a: <image> has neither a source nor data" (ctx-what ctx)))
        (make-image path
                    (attr-int ctx node 'width #f 0)
                    (attr-int ctx node 'height #f 0)
                    (attr-color ctx node 'trans)))))

  (define (parse-animation ctx node)
    (let ((anim (x-child node 'animation)))
      (if anim
          (map (lambda (f)
                 (cons (attr-int ctx f 'tileid 0 0) (attr-int ctx f 'duration 0 0)))
               (x-children anim 'frame))
          '())))

  ;; Collision shapes of a tile: the objects of its <objectgroup>.
  (define (parse-tile ctx node gid-of)
    (let* ((id (or (attr-int ctx node 'id #f 0)
                   (tmx-error (ctx-file ctx) "~a: a <tile> has no id" (ctx-what ctx))))
           (tctx (sub-ctx ctx (sprintf "tile ~a" id)))
           (img (x-child node 'image))
           (og (x-child node 'objectgroup)))
      (make-tile id
                 (or (x-attr node 'class) (x-attr node 'type) "")
                 (attr-number tctx node 'probability 1)
                 (parse-properties tctx node)
                 (and img (parse-image tctx img))
                 (attr-int tctx node 'x 0 0) (attr-int tctx node 'y 0 0)
                 (attr-int tctx node 'width #f 0) (attr-int tctx node 'height #f 0)
                 (parse-animation tctx node)
                 (if og
                     (map (lambda (o) (parse-object tctx o gid-of '() #f))
                          (x-children og 'object))
                     '()))))

  ;; A tileset element (embedded in a map, or the root of a .tsx file).
  ;; file is the file holding the element; source the .tsx path or #f.
  (define (parse-tileset file node first-gid source)
    (let* ((name (attr-string node 'name ""))
           (ctx (cons file (sprintf "tileset ~s" name)))
           (tw (attr-int ctx node 'tilewidth #f 1))
           (th (attr-int ctx node 'tileheight #f 1))
           (spacing (attr-int ctx node 'spacing 0 0))
           (margin (attr-int ctx node 'margin 0 0))
           (img-node (x-child node 'image))
           (img (and img-node (parse-image ctx img-node)))
           (offset (x-child node 'tileoffset))
           (grid (x-child node 'grid))
           (table (make-hash-table eqv?))
           (ids '()))
      (unless (and tw th)
        (tmx-error file "~a: tilewidth and tileheight are required" (ctx-what ctx)))
      (for-each
       (lambda (t)
         (let ((tile (parse-tile ctx t #f)))
           (unless (hash-table-exists? table (tile-id tile))
             (set! ids (cons (tile-id tile) ids)))
           (hash-table-set! table (tile-id tile) tile)))
       (x-children node 'tile))
      (hash-table-set! table 'order (reverse ids))
      (let* ((columns (or (attr-int ctx node 'columns #f 0)
                          (and img (image-width img)
                               (max 0 (quotient (+ (- (image-width img) (* 2 margin)) spacing)
                                                (+ tw spacing))))))
             (rows (and img (image-height img)
                        (max 0 (quotient (+ (- (image-height img) (* 2 margin)) spacing)
                                         (+ th spacing)))))
             (count (or (attr-int ctx node 'tilecount #f 0)
                        (and img columns rows (* columns rows)))))
        (make-tileset first-gid name (or (x-attr node 'class) "") source tw th spacing margin
                      count columns img
                      (if offset (attr-number ctx offset 'x 0) 0)
                      (if offset (attr-number ctx offset 'y 0) 0)
                      (attr-choice ctx node 'objectalignment
                                   '(("unspecified" . unspecified) ("topleft" . top-left)
                                     ("top" . top) ("topright" . top-right) ("left" . left)
                                     ("center" . center) ("right" . right)
                                     ("bottomleft" . bottom-left) ("bottom" . bottom)
                                     ("bottomright" . bottom-right))
                                   'unspecified)
                      (and grid (list (attr-string grid 'orientation "orthogonal")
                                      (attr-int ctx grid 'width #f 0)
                                      (attr-int ctx grid 'height #f 0)))
                      (parse-properties ctx node)
                      table))))

  ;; A <tileset> child of a map or template: embedded, or naming a .tsx.
  ;; External tilesets are read once per load (cache: path -> root element).
  (define (load-tileset-ref st file node)
    (let* ((ctx (cons file "tileset"))
           (first-gid (or (attr-int ctx node 'firstgid #f 1)
                          (tmx-error file "a <tileset> has no firstgid")))
           (source (x-attr node 'source)))
      (if source
          (let ((path (resolve-path file source)))
            (check-exists ctx path "tileset")
            (let ((root (or (hash-table-ref/default (state-tsx st) path #f)
                            (let ((r (read-root ctx path 'tileset)))
                              (hash-table-set! (state-tsx st) path r)
                              r))))
              (with-tmx-context path "tileset"
                (lambda () (parse-tileset path root first-gid path)))))
          (parse-tileset file node first-gid #f))))

  ;;; ------------------------------------------------------------------
  ;;; Loading: objects and templates

  ;; Per-load state: caches and the map's tileset list (templates may add
  ;; tilesets the map does not list).
  (define-record-type load-state
    (make-state tsx templates tilesets stack)
    load-state?
    (tsx state-tsx)
    (templates state-templates)
    (tilesets state-tilesets state-tilesets-set!)
    (stack state-stack state-stack-set!))

  (define (parse-points ctx s)
    (let ((pairs (string-split s " \t\n\r")))
      (map (lambda (p)
             (let* ((xy (string-split p "," #t))
                    (x (and (= (length xy) 2) (parse-real (car xy))))
                    (y (and x (parse-real (cadr xy)))))
               (unless (and x y)
                 (tmx-error (ctx-file ctx) "~a: bad point ~s in points ~s" (ctx-what ctx) p s))
               (cons x y)))
           pairs)))

  (define (parse-text ctx node)
    (list (cons 'text (x-text node))
          (cons 'font-family (attr-string node 'fontfamily "sans-serif"))
          (cons 'pixel-size (attr-int ctx node 'pixelsize 16 0))
          (cons 'wrap? (attr-bool ctx node 'wrap #f))
          (cons 'color (or (attr-color ctx node 'color) '(color 0 0 0 255)))
          (cons 'bold? (attr-bool ctx node 'bold #f))
          (cons 'italic? (attr-bool ctx node 'italic #f))
          (cons 'underline? (attr-bool ctx node 'underline #f))
          (cons 'strikeout? (attr-bool ctx node 'strikeout #f))
          (cons 'kerning? (attr-bool ctx node 'kerning #t))
          (cons 'halign (attr-choice ctx node 'halign
                                     '(("left" . left) ("center" . center)
                                       ("right" . right) ("justify" . justify)) 'left))
          (cons 'valign (attr-choice ctx node 'valign
                                     '(("top" . top) ("center" . center)
                                       ("bottom" . bottom)) 'top))))

  ;; Properties of base overridden (by name) by those of the instance.
  (define (merge-properties base own)
    (append (filter (lambda (p) (not (assoc (car p) own))) base) own))

  ;; An <object>. gid-of maps a raw gid written in this file to the map's
  ;; gid space (templates have their own tilesets), or is #f (tile collision
  ;; shapes, which never name tiles). base is the template's object or #f.
  (define (parse-object ctx node gid-of stack st)
    (let* ((id (attr-int ctx node 'id 0 0))
           (octx (sub-ctx ctx (sprintf "object ~a" id)))
           (tpl (x-attr node 'template))
           (base (and tpl st (load-template st (ctx-file octx) octx tpl stack)))
           (inherit (lambda (get default) (if base (get base) default)))
           (raw-gid (attr-int octx node 'gid #f 0))
           (cell (cond (raw-gid (if gid-of (gid-of octx raw-gid) raw-gid))
                       (else (inherit object-cell 0))))
           (shape-node (any (lambda (tag) (x-child node tag))
                            '(ellipse point polygon polyline text)))
           (shape (cond (shape-node (car shape-node))
                        (raw-gid (if (zero? (cell-gid cell)) 'rectangle 'tile))
                        (base (object-shape base))
                        (else 'rectangle))))
      (make-map-object
       id
       (attr-string node 'name (inherit object-name ""))
       (or (x-attr node 'class) (x-attr node 'type) (inherit object-class ""))
       (attr-number octx node 'x (inherit object-x 0))
       (attr-number octx node 'y (inherit object-y 0))
       (attr-number octx node 'width (inherit object-width 0))
       (attr-number octx node 'height (inherit object-height 0))
       (attr-number octx node 'rotation (inherit object-rotation 0))
       cell
       (attr-bool octx node 'visible (inherit object-visible? #t))
       (if (and (eq? shape 'tile) (zero? (cell-gid cell))) 'rectangle shape)
       (cond ((and shape-node (memq shape '(polygon polyline)))
              (parse-points octx (or (x-attr shape-node 'points)
                                     (tmx-error (ctx-file octx) "~a: <~a> has no points"
                                                (ctx-what octx) shape))))
             (shape-node '())
             (else (inherit object-points '())))
       (cond ((and shape-node (eq? shape 'text)) (parse-text octx shape-node))
             (shape-node #f)
             (else (inherit object-text #f)))
       (merge-properties (inherit object-properties '()) (parse-properties octx node))
       (if tpl (resolve-path (ctx-file octx) tpl) #f))))

  ;; Find the map's copy of a tileset (same .tsx), adding it after the last
  ;; gid when the map does not list it. Returns its first gid.
  (define (map-first-gid-for st ts)
    (let ((same (and (tileset-source ts)
                     (let loop ((l (state-tilesets st)))
                       (cond ((null? l) #f)
                             ((equal? (tileset-source (car l)) (tileset-source ts)) (car l))
                             (else (loop (cdr l))))))))
      (if same
          (tileset-first-gid same)
          (let* ((next (fold-max-gid (state-tilesets st)))
                 (copy (make-tileset next (tileset-name ts) (tileset-class ts)
                                     (tileset-source ts) (tileset-tile-width ts)
                                     (tileset-tile-height ts) (tileset-spacing ts)
                                     (tileset-margin ts) (tileset-tile-count ts)
                                     (tileset-columns ts) (tileset-image ts)
                                     (tileset-offset-x ts) (tileset-offset-y ts)
                                     (tileset-object-alignment ts) (tileset-grid ts)
                                     (tileset-properties ts) (tileset-tile-table ts))))
            (state-tilesets-set! st (append (state-tilesets st) (list copy)))
            next))))

  ;; One past the highest gid any tileset can hold.
  (define (fold-max-gid tilesets)
    (let loop ((l tilesets) (m 1))
      (if (null? l)
          m
          (let* ((ts (car l))
                 (n (or (tileset-tile-count ts) 0))
                 (ids (tileset-tile-ids ts))
                 (top (+ (tileset-first-gid ts)
                         (max n (if (null? ids) 0 (+ 1 (apply max ids)))))))
            (loop (cdr l) (max m top))))))

  (define (load-template st file ctx tpl stack)
    (let ((path (resolve-path file tpl)))
      (when (member path stack)
        (tmx-error (ctx-file ctx) "~a: template cycle: ~a"
                   (ctx-what ctx) (string-intersperse (reverse (cons path stack)) " -> ")))
      (or (hash-table-ref/default (state-templates st) path #f)
          (begin
            (check-exists ctx path "template")
            (let* ((root (read-root ctx path 'template))
                   (tctx (cons path "template"))
                   (ts-node (x-child root 'tileset))
                   (ts (and ts-node (load-tileset-ref st path ts-node)))
                   (obj-node (or (x-child root 'object)
                                 (tmx-error path "the template has no <object>")))
                   (gid-of
                    (lambda (octx raw)
                      (let ((g (cell-gid raw)))
                        (cond ((zero? g) raw)
                              ((not ts)
                               (tmx-error path "~a: gid ~a but the template has no tileset"
                                          (ctx-what octx) g))
                              ((not (tileset-covers? ts g))
                               (tmx-error path "~a: gid ~a is not in the template's tileset ~s"
                                          (ctx-what octx) g (tileset-name ts)))
                              (else
                               (let ((first (map-first-gid-for st ts)))
                                 (bitwise-ior (bitwise-and raw (bitwise-not gid-mask))
                                              (+ first (- g (tileset-first-gid ts)))))))))))
              (let ((obj (with-tmx-context path "template"
                           (lambda ()
                             (parse-object tctx obj-node gid-of (cons path stack) st)))))
                (hash-table-set! (state-templates st) path obj)
                obj))))))

  ;;; ------------------------------------------------------------------
  ;;; Loading: layer data

  (define (whitespace? c)
    (or (char=? c #\space) (char=? c #\newline) (char=? c #\return) (char=? c #\tab)))

  (define (strip-whitespace s)
    (let* ((n (string-length s))
           (keep (let loop ((i 0) (k 0))
                   (if (fx= i n) k
                       (loop (fx+ i 1) (if (whitespace? (string-ref s i)) k (fx+ k 1)))))))
      (if (fx= keep n)
          s
          (let ((out (make-string keep)))
            (let loop ((i 0) (k 0))
              (if (fx= i n)
                  out
                  (let ((c (string-ref s i)))
                    (if (whitespace? c)
                        (loop (fx+ i 1) k)
                        (begin (string-set! out k c) (loop (fx+ i 1) (fx+ k 1)))))))))))

  ;; CSV cells: unsigned decimal numbers separated by commas, whitespace
  ;; anywhere between them; one trailing comma is tolerated.
  (define (parse-csv ctx s count)
    (let* ((n (string-length s))
           (commas (let loop ((i 0) (k 0))
                     (if (fx= i n) k
                         (loop (fx+ i 1) (if (char=? (string-ref s i) #\,) (fx+ k 1) k)))))
           (trailing? (let loop ((i (fx- n 1)))
                        (and (fx>= i 0)
                             (let ((c (string-ref s i)))
                               (if (whitespace? c) (loop (fx- i 1)) (char=? c #\,))))))
           (blank? (let loop ((i 0))
                     (or (fx= i n) (and (whitespace? (string-ref s i)) (loop (fx+ i 1))))))
           (cells (cond (blank? 0) (trailing? commas) (else (fx+ commas 1)))))
      (unless (fx= cells count)
        (tmx-error (ctx-file ctx) "~a: csv data has ~a cells, expected ~a"
                   (ctx-what ctx) cells count))
      (let ((out (make-u32vector count 0)))
        (let loop ((i 0) (cell 0) (value 0) (digits 0))
          (define (finish-cell)
            (when (fx= digits 0)
              (tmx-error (ctx-file ctx) "~a: csv cell ~a is empty" (ctx-what ctx) cell))
            (when (fx>= cell count)
              (tmx-error (ctx-file ctx) "~a: csv data has more than ~a cells" (ctx-what ctx) count))
            (u32vector-set! out cell value))
          (if (fx= i n)
              (cond ((fx> digits 0)
                     (finish-cell)
                     (unless (fx= (fx+ cell 1) count)
                       (tmx-error (ctx-file ctx) "~a: csv data has ~a cells, expected ~a"
                                  (ctx-what ctx) (fx+ cell 1) count)))
                    ((not (fx= cell count))
                     (tmx-error (ctx-file ctx) "~a: csv data has ~a cells, expected ~a"
                                (ctx-what ctx) cell count)))
              (let ((c (string-ref s i)))
                (cond ((char-numeric? c)
                       (let ((v (fx+ (fx* value 10) (fx- (char->integer c) 48))))
                         (when (fx> v #xFFFFFFFF)
                           (tmx-error (ctx-file ctx) "~a: csv cell ~a is larger than 32 bits"
                                      (ctx-what ctx) cell))
                         (loop (fx+ i 1) cell v (fx+ digits 1))))
                      ((char=? c #\,)
                       (finish-cell)
                       (loop (fx+ i 1) (fx+ cell 1) 0 0))
                      ((whitespace? c)
                       (if (and (fx> digits 0)
                                (let skip ((j i))
                                  (and (fx< j n)
                                       (let ((d (string-ref s j)))
                                         (if (whitespace? d) (skip (fx+ j 1)) (char-numeric? d))))))
                           (tmx-error (ctx-file ctx) "~a: csv cell ~a: two numbers without a comma"
                                      (ctx-what ctx) cell)
                           (loop (fx+ i 1) cell value digits)))
                      (else
                       (tmx-error (ctx-file ctx) "~a: unexpected character ~s in csv data"
                                  (ctx-what ctx) c))))))
        out)))

  (define (parse-base64 ctx s compression count)
    (let* ((bytes (* 4 count))
           (raw (handle-exceptions exn
                    (tmx-error (ctx-file ctx) "~a: bad base64 data: ~a"
                               (ctx-what ctx) (condition-message exn))
                  (base64-decode (strip-whitespace s))))
           (plain (handle-exceptions exn
                      (if (tmx-condition? exn)
                          (abort exn)
                          (tmx-error (ctx-file ctx) "~a: bad ~a data: ~a"
                                     (ctx-what ctx) compression (condition-message exn)))
                    (case compression
                      ((none) raw)
                      ((zlib) (zlib-inflate raw max-size: (+ bytes 4)))
                      ((gzip) (gzip-inflate raw max-size: (+ bytes 4)))
                      ((zstd) (zstd-decompress raw max-size: (+ bytes 4)))))))
      (unless (= (u8vector-length plain) bytes)
        (tmx-error (ctx-file ctx) "~a: data has ~a bytes~a, expected ~a (~a cells)"
                   (ctx-what ctx) (u8vector-length plain)
                   (if (eq? compression 'none) "" (sprintf " after ~a decompression" compression))
                   bytes count))
      (u8vector->u32vector-le plain)))

  (define (parse-xml-tiles ctx node count)
    (let ((tiles (x-children node 'tile)))
      (unless (= (length tiles) count)
        (tmx-error (ctx-file ctx) "~a: data has ~a <tile> elements, expected ~a"
                   (ctx-what ctx) (length tiles) count))
      (let ((out (make-u32vector count 0)))
        (let loop ((ts tiles) (i 0))
          (unless (null? ts)
            (u32vector-set! out i (attr-int ctx (car ts) 'gid 0 0))
            (loop (cdr ts) (+ i 1))))
        out)))

  (define (check-cells ctx count)
    (when (> count (tilemap-max-cells))
      (tmx-error (ctx-file ctx) "~a: ~a cells is more than the limit of ~a (tilemap-max-cells)"
                 (ctx-what ctx) count (tilemap-max-cells))))

  ;; The cells of a <data> or <chunk>, w x h of them.
  (define (decode-cells ctx node encoding compression w h)
    (let ((count (* w h)))
      (check-cells ctx count)
      (case encoding
        ((xml) (parse-xml-tiles ctx node count))
        ((csv) (parse-csv ctx (x-text node) count))
        ((base64) (parse-base64 ctx (x-text node) compression count)))))

  (define (data-format ctx data)
    (let ((encoding (attr-choice ctx data 'encoding
                                 '(("csv" . csv) ("base64" . base64) ("" . xml)) 'xml))
          (compression (attr-choice ctx data 'compression
                                    '(("zlib" . zlib) ("gzip" . gzip) ("zstd" . zstd)
                                      ("" . none)) 'none)))
      (when (and (not (eq? compression 'none)) (not (eq? encoding 'base64)))
        (tmx-error (ctx-file ctx) "~a: compression ~a needs base64 encoding, not ~a"
                   (ctx-what ctx) compression encoding))
      (values encoding compression)))

  ;;; ------------------------------------------------------------------
  ;;; Loading: layers

  ;; What a layer inherits from its enclosing groups.
  (define-record-type inherited
    (make-inherited offset-x offset-y parallax-x parallax-y opacity visible?)
    inherited?
    (offset-x in-offset-x) (offset-y in-offset-y)
    (parallax-x in-parallax-x) (parallax-y in-parallax-y)
    (opacity in-opacity) (visible? in-visible?))

  (define top-level (make-inherited 0 0 1 1 1 #t))

  ;; Parses the layers under node; tile layers' data is kept as the raw
  ;; element for a second pass (infinite maps need every chunk first).
  ;; Returns a list of (layer-node . inherited) for every layer, in document
  ;; order, and builds records later.
  (define (collect-layers ctx node inh)
    (append-map
     (lambda (child)
       (case (car child)
         ((layer objectgroup imagelayer)
          (list (cons child inh)))
         ((group)
          (let ((gctx (sub-ctx ctx (sprintf "group ~s" (attr-string child 'name "")))))
            (cons (cons child inh)
                  (collect-layers gctx child (compose-inherited gctx child inh)))))
         (else '())))
     (x-children node)))

  (define (compose-inherited ctx node inh)
    (make-inherited (+ (in-offset-x inh) (attr-number ctx node 'offsetx 0))
                    (+ (in-offset-y inh) (attr-number ctx node 'offsety 0))
                    (* (in-parallax-x inh) (attr-number ctx node 'parallaxx 1))
                    (* (in-parallax-y inh) (attr-number ctx node 'parallaxy 1))
                    (* (in-opacity inh) (attr-number ctx node 'opacity 1))
                    (and (in-visible? inh) (attr-bool ctx node 'visible #t))))

  (define (layer-ctx file node)
    (cons file (sprintf "~a ~s"
                        (case (car node)
                          ((layer) "layer") ((objectgroup) "object layer")
                          ((imagelayer) "image layer") (else "group"))
                        (attr-string node 'name ""))))

  ;; A layer record from its element; data is the tile layer's cells or #f;
  ;; children the group's already built children.
  (define (build-layer file node inh data w h st children)
    (let* ((ctx (layer-ctx file node))
           (eff (compose-inherited ctx node inh))
           (kind (case (car node)
                   ((layer) 'tile) ((objectgroup) 'object)
                   ((imagelayer) 'image) (else 'group)))
           (img (and (eq? kind 'image) (x-child node 'image))))
      (%make-layer kind
                   (attr-int ctx node 'id #f 0)
                   (attr-string node 'name "")
                   (attr-string node 'class "")
                   (and (eq? kind 'tile) w) (and (eq? kind 'tile) h)
                   data
                   (in-visible? eff) (in-opacity eff)
                   (attr-color ctx node 'tintcolor)
                   (in-offset-x eff) (in-offset-y eff)
                   (in-parallax-x eff) (in-parallax-y eff)
                   (attr-bool ctx node 'locked #f)
                   (parse-properties ctx node)
                   (if (eq? kind 'object)
                       (map (lambda (o) (parse-object ctx o map-gid '() st))
                            (x-children node 'object))
                       '())
                   (and (eq? kind 'object)
                        (attr-choice ctx node 'draworder
                                     '(("topdown" . topdown) ("index" . index)) 'topdown))
                   (and (eq? kind 'object) (attr-color ctx node 'color))
                   (and img (parse-image ctx img))
                   (attr-bool ctx node 'repeatx #f)
                   (attr-bool ctx node 'repeaty #f)
                   children)))

  ;; Gids written in the map itself are already in the map's gid space.
  (define (map-gid ctx raw) raw)

  ;; Rebuild the nested tree from the flat (node . inherited) list: each
  ;; group's children are the entries whose node is a child of it.
  (define (build-tree file entries cells-of st)
    (let ((built (map (lambda (e) (cons (car e) #f)) entries)))
      ;; Build bottom-up: process entries in reverse so that children exist
      ;; before their group.
      (let loop ((es (reverse entries)))
        (unless (null? es)
          (let* ((node (caar es))
                 (inh (cdar es))
                 (children
                  (if (eq? (car node) 'group)
                      (filter-map-built built (x-children node))
                      '()))
                 (cells (and (eq? (car node) 'layer) (cells-of node))))
            (set-cdr! (assq node built)
                      (build-layer file node inh
                                   (and cells (car cells))
                                   (and cells (cadr cells)) (and cells (caddr cells))
                                   st children)))
          (loop (cdr es))))
      built))

  (define (filter-map-built built nodes)
    (let loop ((ns nodes) (acc '()))
      (if (null? ns)
          (reverse acc)
          (let ((p (assq (car ns) built)))
            (loop (cdr ns) (if (and p (cdr p)) (cons (cdr p) acc) acc))))))

  ;;; ------------------------------------------------------------------
  ;;; Loading: the map

  ;; A predicate: whether some tileset covers gid g (the one with the
  ;; largest first gid not above g).
  (define (gid-covered-by tilesets)
    (let ((sorted (sort-tilesets tilesets)))
      (lambda (g)
        (let loop ((ts sorted) (best #f))
          (cond ((and (pair? ts) (<= (tileset-first-gid (car ts)) g)) (loop (cdr ts) (car ts)))
                (else (and best (tileset-covers? best g))))))))

  (define (check-gids file layers tilesets)
    ;; cells checked with a one-entry memo
    (let ((covered? (gid-covered-by tilesets)))
      (for-each
       (lambda (entry)
         (let* ((layer (car entry))
                (data (layer-data layer))
                (w (layer-width layer))
                (n (u32vector-length data)))
           (let loop ((i 0) (last-ok 0))
             (when (fx< i n)
               (let ((g (fxand (u32vector-ref data i) gid-mask)))
                 (cond ((or (fx= g 0) (fx= g last-ok)) (loop (fx+ i 1) last-ok))
                       ((covered? g) (loop (fx+ i 1) g))
                       (else
                        (tmx-error file "layer ~s: cell (~a, ~a) has gid ~a, which no tileset covers"
                                   (layer-name layer) (+ (cadr entry) (remainder i w))
                                   (+ (cddr entry) (quotient i w)) g))))))))
       layers)))

  (define (sort-tilesets tilesets)
    ;; insertion sort: maps have few tilesets
    (let loop ((l tilesets) (out '()))
      (if (null? l)
          out
          (loop (cdr l)
                (let ins ((o out))
                  (cond ((null? o) (list (car l)))
                        ((< (tileset-first-gid (car l)) (tileset-first-gid (car o)))
                         (cons (car l) o))
                        (else (cons (car o) (ins (cdr o))))))))))

  (define (check-object-gids file layers tilesets)
    (let ((covered? (gid-covered-by tilesets)))
      (for-each
       (lambda (layer)
         (for-each
          (lambda (o)
            (let ((g (object-gid o)))
              (unless (or (zero? g) (covered? g))
                (tmx-error file "object layer ~s: object ~a has gid ~a, which no tileset covers"
                           (layer-name layer) (object-id o) g))))
          (layer-objects layer)))
       layers)))

  (define (read-tilemap path)
    (let* ((root (read-root (cons path "map") path 'map))
           (ctx (cons path "map"))
           (orientation (attr-choice ctx root 'orientation
                                     '(("orthogonal" . orthogonal) ("isometric" . isometric)
                                       ("staggered" . staggered) ("hexagonal" . hexagonal))
                                     #f))
           (infinite? (attr-bool ctx root 'infinite #f))
           (map-w (attr-int ctx root 'width #f 0))
           (map-h (attr-int ctx root 'height #f 0))
           (tw (attr-int ctx root 'tilewidth #f 1))
           (th (attr-int ctx root 'tileheight #f 1))
           (st (make-state (make-hash-table equal?) (make-hash-table equal?) '() '())))
      (unless orientation (tmx-error path "the map has no orientation"))
      (unless (and tw th) (tmx-error path "the map needs tilewidth and tileheight"))
      (unless (or infinite? (and map-w map-h))
        (tmx-error path "the map needs width and height"))
      (when (and (not infinite?) (> (* map-w map-h) (tilemap-max-cells)))
        (tmx-error path "the map is ~ax~a: more than the limit of ~a cells (tilemap-max-cells)"
                   map-w map-h (tilemap-max-cells)))
      ;; Tilesets, in document order.
      (state-tilesets-set! st (map (lambda (t) (load-tileset-ref st path t))
                                   (x-children root 'tileset)))
      (let* ((entries (collect-layers ctx root top-level))
             (tile-nodes (filter (lambda (n) (eq? (car n) 'layer)) (map car entries)))
             ;; node -> decoded data: finite: (u32vector); infinite: chunks
             (decoded
              (map (lambda (node)
                     (let* ((lctx (layer-ctx path node))
                            (data (or (x-child node 'data)
                                      (tmx-error path "~a: the layer has no <data>" (ctx-what lctx)))))
                       (let-values (((encoding compression) (data-format lctx data)))
                         (cons node
                               (if infinite?
                                   (map (lambda (ch)
                                          (let* ((cx (or (attr-int lctx ch 'x #f) 0))
                                                 (cy (or (attr-int lctx ch 'y #f) 0))
                                                 (cw (or (attr-int lctx ch 'width #f 0) 0))
                                                 (chh (or (attr-int lctx ch 'height #f 0) 0))
                                                 (cctx (sub-ctx lctx (sprintf "chunk at (~a, ~a)" cx cy))))
                                            (list cx cy cw chh
                                                  (decode-cells cctx ch encoding compression cw chh))))
                                        (x-children data 'chunk))
                                   (begin
                                     (let ((lw (attr-int lctx node 'width map-w 0))
                                           (lh (attr-int lctx node 'height map-h 0)))
                                       (unless (and (= lw map-w) (= lh map-h))
                                         (tmx-error path "~a: the layer is ~ax~a, the map is ~ax~a"
                                                    (ctx-what lctx) lw lh map-w map-h)))
                                     (decode-cells lctx data encoding compression map-w map-h)))))))
                   tile-nodes))
             (chunks (if infinite? (append-map cdr decoded) '()))
             (x0 (if (null? chunks) 0 (apply min (map car chunks))))
             (y0 (if (null? chunks) 0 (apply min (map cadr chunks))))
             (x1 (if (null? chunks) 0 (apply max (map (lambda (c) (+ (car c) (caddr c))) chunks))))
             (y1 (if (null? chunks) 0 (apply max (map (lambda (c) (+ (cadr c) (cadddr c))) chunks))))
             (w (if infinite? (- x1 x0) map-w))
             (h (if infinite? (- y1 y0) map-h)))
        (when infinite?
          (check-cells (cons path "the union of the chunks") (* w h)))
        (let* ((cells-of
                (lambda (node)
                  (let ((d (cdr (assq node decoded))))
                    (if infinite?
                        (let ((out (make-u32vector (* w h) 0)))
                          (for-each
                           (lambda (c)
                             (let ((cx (- (car c) x0)) (cy (- (cadr c) y0))
                                   (cw (caddr c)) (chh (cadddr c)) (v (list-ref c 4)))
                               (do ((r 0 (fx+ r 1))) ((fx= r chh))
                                 (do ((k 0 (fx+ k 1))) ((fx= k cw))
                                   (u32vector-set! out (fx+ (fx* (fx+ cy r) w) (fx+ cx k))
                                                   (u32vector-ref v (fx+ (fx* r cw) k)))))))
                           d)
                          (list out w h))
                        (list d w h)))))
               (built (build-tree path entries cells-of st))
               (all (map cdr built))
               (tree (filter-map-built built (x-children root)))
               (tile-layers (filter (lambda (l) (eq? (layer-kind l) 'tile)) all))
               (tilesets (sort-tilesets (state-tilesets st))))
          (check-gids path (map (lambda (l) (cons l (cons x0 y0))) tile-layers) tilesets)
          (check-object-gids path (filter (lambda (l) (eq? (layer-kind l) 'object)) all) tilesets)
          (make-tilemap w h tw th tile-layers
                        properties: (parse-properties ctx root)
                        origin-col: x0 origin-row: y0
                        tilesets: tilesets
                        layer-tree: tree
                        info: (list (cons 'source path)
                                    (cons 'version (x-attr root 'version))
                                    (cons 'tiled-version (x-attr root 'tiledversion))
                                    (cons 'class (attr-string root 'class ""))
                                    (cons 'orientation orientation)
                                    (cons 'render-order
                                          (attr-choice ctx root 'renderorder
                                                       '(("right-down" . right-down)
                                                         ("right-up" . right-up)
                                                         ("left-down" . left-down)
                                                         ("left-up" . left-up))
                                                       'right-down))
                                    (cons 'infinite? infinite?)
                                    (cons 'hex-side-length (attr-int ctx root 'hexsidelength #f 0))
                                    (cons 'stagger-axis (attr-choice ctx root 'staggeraxis
                                                                     '(("x" . x) ("y" . y)) #f))
                                    (cons 'stagger-index (attr-choice ctx root 'staggerindex
                                                                      '(("odd" . odd) ("even" . even)) #f))
                                    (cons 'parallax-origin-x (attr-number ctx root 'parallaxoriginx 0))
                                    (cons 'parallax-origin-y (attr-number ctx root 'parallaxoriginy 0))
                                    (cons 'background-color (attr-color ctx root 'backgroundcolor))))))))

  ;; Load a TMX map. Every failure is an error naming the file and the problem.
  (define (load-tilemap path)
    (unless (string? path)
      (error 'load-tilemap "the path must be a string" path))
    (with-tmx-context path "cannot load the map"
      (lambda ()
        (unless (file-exists? path)
          (tmx-error path "no such file"))
        (read-tilemap path))))

  ;;; ------------------------------------------------------------------
  ;;; Tilesets without a map

  ;; A .tsx file on its own: the sprites of a scene without a map
  ;; (make-sprite-scene tileset:). Its gids start at first-gid, as in a map
  ;; that listed the file there, so 1 is its first tile by default. Errors
  ;; are the loader's: they name the file and what is wrong.
  (define (load-tileset path #!key (first-gid 1))
    (unless (string? path)
      (error 'load-tileset "the path must be a string" path))
    (check-integer 'load-tileset "" "first-gid:" first-gid 1)
    (parameterize ((loader 'load-tileset))
      (with-tmx-context path "cannot load the tileset"
        (lambda ()
          (unless (regular-file? path)
            (tmx-error path "no such file"))
          (let ((path (normalize-pathname path)))
            (parse-tileset path (read-root (cons path "tileset") path 'tileset)
                           first-gid path))))))

  ;; A sprite sheet described in code: an image cut into a grid of tiles of
  ;; tile-width x tile-height, columns to a row, read left to right and top
  ;; to bottom (what Tiled calls a tileset based on one image). The image
  ;; must exist; it is not decoded here (the pure core never touches SDL).
  (define (make-sheet-tileset image #!key tile-width tile-height columns
                              (tile-count #f) (spacing 0) (margin 0)
                              (first-gid 1) (name ""))
    (define (natural key v minimum)
      (check-integer 'make-sheet-tileset (sprintf "sheet ~s: " image) key v minimum))
    (unless (string? image)
      (error 'make-sheet-tileset "the image path must be a string" image))
    (natural "tile-width:" tile-width 1)
    (natural "tile-height:" tile-height 1)
    (natural "columns:" columns 1)
    (natural "spacing:" spacing 0)
    (natural "margin:" margin 0)
    (when tile-count (natural "tile-count:" tile-count 0))
    (natural "first-gid:" first-gid 1)
    (unless (regular-file? image)
      (error 'make-sheet-tileset (sprintf "sheet ~s: no such image file" image)))
    (let ((tiles (make-hash-table eqv?)))
      (hash-table-set! tiles 'order '())
      (make-tileset first-gid name "" #f tile-width tile-height spacing margin
                    tile-count columns (make-image (normalize-pathname image) #f #f #f)
                    0 0 'unspecified #f '() tiles)))

  (define (check-integer who prefix key v minimum)
    (unless (and (exact-integer? v) (>= v minimum))
      (error who (sprintf "~a~a is ~s, expected an integer of at least ~a" prefix key v minimum)))))
