;;; (downstroke map): tile maps as immutable data. Pure: no C library, no
;;; file format; (downstroke tmx) reads Tiled's files into these records,
;;; and (downstroke tilemap) offers both under the name games import.
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
;;; flag-free gid: a cell is solid when that gid is not 0. A cell is
;;; one-way instead (a jump-through platform: only its top stops a body,
;;; and only one falling onto it) when its tile has the bool property
;;; `one-way` set in its tileset, or its layer has the layer property
;;; `one-way` set; a solid tile of any other layer in the same cell wins.
;;; A tile whose tileset gives it the bool property `collides` false adds
;;; nothing to the grid (tile-property-table lists the names read on tiles).
;;; The grid holds 0 (empty), 1 (solid) or 2 (one-way). A second grid, made
;;; only when some tile has a `kind`, holds each cell's kind (tilemap-kind).
;;; A ladder tile (the bool property `ladder`, on the tile or its layer) is
;;; not solid; the ladder cells are a third grid (tilemap-ladder?), made
;;; only when the map has one, and the top cell of each ladder (no ladder
;;; above it) is one-way in the solid grid, so that every body can stand
;;; on it (docs/physics.org, "Ladders").
;;;
;;; Which layers collide: every tile layer, unless the layer has the property
;;; `collides` set to #f (a bool property; the string "false" or the int 0
;;; do not opt out). So the default of docs/physics.org holds (any non-zero tile
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
;;; Representation of what a map holds (all immutable after loading):
;;; - layers: `layer` records of kind tile, object, image or group. Offsets
;;;   and parallax factors are the effective ones (a group's offset is added to
;;;   its children's, its parallax multiplied), as are opacity (multiplied)
;;;   and visibility (and-ed); tint is the layer's own.
;;; - tilesets: `tileset` records, in firstgid order; per-tile data in `tile`
;;;   records (properties, image, animation frames, collision shapes).
;;; - objects: `map-object` records; shape is one of the symbols rectangle,
;;;   ellipse, capsule (Tiled 1.11's <capsule/>), point, polygon, polyline, text,
;;;   tile.
;;; - properties: an alist (name . value) in file order. Values: string,
;;;   exact integer (int), flonum (float), #t/#f (bool), and tagged lists for
;;;   the rest: (color R G B A) or (color) when unset, (file "resolved/path"),
;;;   (object ID), (class "TypeName" ((member . value) ...)), (list v ...).
;;; - colors (background, tint, object layer colour, image transparency) are
;;;   (color R G B A) lists too.
(module (downstroke map)
  (;; in-memory maps
   make-tilemap list->tilemap tilemap?
   tilemap-width tilemap-height tilemap-tile-width tilemap-tile-height
   tilemap-pixel-width tilemap-pixel-height tilemap-origin-col tilemap-origin-row
   tilemap-screen-size tilemap-cell-anchor tilemap-screen-point
   tilemap-layers tilemap-layer tilemap-properties
   tilemap-tile-at tilemap-cell-at tilemap-flags-at tilemap-solid? tilemap-one-way? tilemap-solid-grid
   tilemap-kind tilemap-ladder? tilemap-ladder-top? tilemap-slope tilemap-ceiling-slope tile-property-table
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
   ;; tilesets described in code (sprite scenes)
   make-sheet-tileset
   ;; for sibling modules only: constructors for the file loader ((downstroke
   ;; tmx)); games build maps with make-tilemap, list->tilemap and make-layer
   %make-layer make-image make-tile make-tileset make-map-object tileset-tile-table
   tileset-tile-ids gid-mask check-integer
   ;; for the physics only: the slope heights by cell, or #f (tilemap-slope,
   ;; tilemap-ceiling-slope)
   tilemap-slopes)


  (import (downstroke keywords) (only (downstroke numbers) check-finite))
  (import scheme (chicken base) (chicken fixnum) (chicken format)
          (chicken bitwise) (chicken pathname) (chicken condition)
          (chicken string) (chicken file) (only (chicken file posix) regular-file?) srfi-4
          (only (downstroke util) filter filter-map append-map any list-min list-max string-concatenate
                make-hash-table hash-table-ref/default hash-table-set!
                hash-table-exists? hash-table-fold))

  ;;; ------------------------------------------------------------------
  ;;; Cells: a gid and four flag bits.

  (define gid-mask #x0FFFFFFF)
  (define flag-horizontal #x80000000)
  (define flag-vertical #x40000000)
  (define flag-diagonal #x20000000)
  (define flag-hex-120 #x10000000)

  ;; A cell is a 32-bit word: with a flip flag from bit 30 up it is a bignum
  ;; where fixnums are 31 bits wide (wasm32), so only a fixnum cell takes
  ;; fxand.
  (define (cell-gid cell)
    (if (fixnum? cell) (fxand cell gid-mask) (bitwise-and cell gid-mask)))
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

  (define/keywords (make-layer name width height data #!key (visible? #t) (properties '())
                      (id #f) (class "") (opacity 1) (tint #f) (offset-x 0)
                      (offset-y 0) (parallax-x 1) (parallax-y 1) (locked? #f))
    (unless (and (u32vector? data) (= (u32vector-length data) (* width height)))
      (error 'make-layer
             (sprintf "layer ~s: data must be a u32vector of ~a cells" name (* width height))))
    ;; numbers a frame would otherwise meet first
    (let ((where (sprintf "make-layer: layer ~s" name)))
      (check-finite where "opacity:" opacity)
      (check-finite where "offset-x:" offset-x)
      (check-finite where "offset-y:" offset-y)
      (check-finite where "parallax-x:" parallax-x)
      (check-finite where "parallax-y:" parallax-y))
    (%make-layer 'tile id name class width height data visible? opacity tint
                 offset-x offset-y parallax-x parallax-y locked? properties
                 '() #f #f #f #f #f '()))

  (define (layer-collides? layer)
    (let ((p (assoc "collides" (layer-properties layer))))
      (not (and p (not (cdr p))))))

  (define (layer-one-way? layer)
    (eq? #t (property-ref (layer-properties layer) "one-way" #f)))

  (define (layer-ladder? layer)
    (eq? #t (property-ref (layer-properties layer) "ladder" #f)))

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
                   origin-col origin-row info tilesets layer-tree kinds ladders slopes)
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
    (layer-tree tilemap-layer-tree)     ; every layer, as nested in Tiled
    (kinds tilemap-kinds)               ; #f, or (u8vector grid . vector of kind symbols)
    (ladders tilemap-ladders)           ; #f, or a u8vector: 1 on each ladder cell
    (slopes tilemap-slopes))            ; #f, or a vector by cell of (left . right) heights (depths)

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
                     (tilemap-info tm) (tilemap-tilesets tm) tree (tilemap-kinds tm)
                     (tilemap-ladders tm) (tilemap-slopes tm))))

  ;; Where a tile object's image hangs from its (x, y): the fractions of
  ;; its width and height left of and above that point, (values ax ay).
  ;; Tiled's default (unspecified) is bottom-left, bottom-centre on
  ;; isometric maps.
  (define (tilemap-object-anchor tm object)
    (let* ((ts (tilemap-tileset-for tm (object-cell object)))
           (align (if ts (tileset-object-alignment ts) 'unspecified))
           (align (if (and (eq? align 'unspecified) (eq? (tilemap-orientation tm) 'isometric))
                      'bottom
                      align)))
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
               (let ((x0 (list-min (map car ps))) (x1 (list-max (map car ps)))
                     (y0 (list-min (map cdr ps))) (y1 (list-max (map cdr ps))))
                 (values (+ x x0) (+ y y0) (- x1 x0) (- y1 y0))))))
        ((point) (values x y 0 0))
        (else (values x y w h)))))

  ;; The tileset a gid (flags allowed) belongs to: the one with the highest
  ;; firstgid not above it. #f for gid 0, below every firstgid, or past the
  ;; last tile of that tileset (Tiled keeps such a cell; nothing is drawn
  ;; there, though it is solid like any non-zero cell).
  (define (tilemap-tileset-for tm gid)
    (let ((g (cell-gid gid)))
      (and (> g 0)
           (let loop ((ts (tilemap-tilesets tm)) (best #f))
             (cond ((and (pair? ts) (<= (tileset-first-gid (car ts)) g)) (loop (cdr ts) (car ts)))
                   (else (and best (tileset-covers? best g) best)))))))

  ;; The per-tile data (a tile record) of a gid, or #f.
  (define (tilemap-tile-info tm gid)
    (let ((ts (tilemap-tileset-for tm gid)))
      (and ts (tileset-tile ts (- (cell-gid gid) (tileset-first-gid ts))))))

  ;;; Tile properties (docs/tilemaps.org, "Tile properties"): the names
  ;;; Downstroke reads on a tile of a tileset, and their Tiled types. A
  ;;; tile with none of them is what its layer makes it (solid on a
  ;;; colliding layer).
  (define tile-property-table
    '(("collides" . bool)       ; #f: never solid, whatever its layer
      ("one-way" . bool)        ; a jump-through platform
      ("kind" . string)         ; what the cell is, for the game (tilemap-kind)
      ("ladder" . bool)         ; a climbable cell, not solid (docs/physics.org, "Ladders")
      ("slope-left" . int)      ; a slope: its floor's height (px) at the tile's left edge
      ("slope-right" . int)     ; ... and at its right edge (both or neither)
      ("ceiling-left" . int)    ; a ceiling slope: its ceiling's depth (px) below the tile's top, left edge
      ("ceiling-right" . int))) ; ... and at its right edge (both or neither; not with slope-*)

  ;; A name folded for comparison: lower case, without '-', '_' or spaces.
  (define (fold-name name)
    (list->string (filter-map (lambda (c) (and (not (memv c '(#\- #\_ #\space))) (char-downcase c)))
                              (string->list name))))

  ;; Whether a and b differ by one edit: a character added, dropped,
  ;; replaced, or two neighbours swapped.
  (define (one-edit-apart? a b)
    (let ((la (string-length a)) (lb (string-length b)))
      (define (same-from? i j) (string=? (substring a i la) (substring b j lb)))
      (let loop ((i 0))
        (cond ((and (fx= i la) (fx= i lb)) #f)
              ((or (fx= i la) (fx= i lb)) (fx= 1 (abs (fx- la lb))))
              ((char=? (string-ref a i) (string-ref b i)) (loop (fx+ i 1)))
              (else (or (and (fx= la lb) (same-from? (fx+ i 1) (fx+ i 1)))
                        (and (fx= la (fx+ lb 1)) (same-from? (fx+ i 1) i))
                        (and (fx= lb (fx+ la 1)) (same-from? i (fx+ i 1)))
                        (and (fx= la lb) (fx< (fx+ i 1) la)
                             (char=? (string-ref a i) (string-ref b (fx+ i 1)))
                             (char=? (string-ref a (fx+ i 1)) (string-ref b i))
                             (same-from? (fx+ i 2) (fx+ i 2)))))))))

  ;; The table's name that `name` looks like a misspelling of, or #f: the
  ;; same once folded, or (for names of five letters or more) one edit
  ;; away.
  (define (misspelt-tile-property name)
    (and (not (assoc name tile-property-table))
         (let loop ((t tile-property-table))
           (and (pair? t)
                (let ((known (caar t)))
                  (if (or (string=? (fold-name name) (fold-name known))
                          (and (fx>= (string-length known) 5) (one-edit-apart? name known)))
                      known
                      (loop (cdr t))))))))

  ;; Where a tileset was read from, for errors: its .tsx, else the map.
  (define (tileset-origin ts map-source)
    (or (tileset-source ts) map-source "a map made in code"))

;; A tile's slope (docs/physics.org, "Slopes"): (floor left . right),
  ;; its floor's heights in px above the tile's bottom edge, or (ceiling
  ;; left . right), its ceiling's depths in px below the tile's top edge;
  ;; from the properties slope-left and slope-right, or ceiling-left and
  ;; ceiling-right (a pair given both or neither, each 0 .. tile height,
  ;; never both pairs), else from a collision polygon drawn in Tiled that
  ;; has points on both the tile's left edge (x 0) and its right edge (x
  ;; tile width): a polygon with both top corners and not both bottom
  ;; ones, every point on the left or right edge, is a ceiling, whose
  ;; lowest point on each edge gives that edge's depth (not both 0); any
  ;; other is a floor, whose highest point on each edge gives that edge's
  ;; height. A floor polygon whose two heights are both the
  ;; tile's full height is a plain solid tile. #f when the tile is no
  ;; slope.
  (define (tile-slope t props tw th where)
    (define (height name v)
      (unless (and (exact-integer? v) (<= 0 v th))
        (error 'load-tilemap (sprintf "~a: property ~s is ~s; a slope ~a is 0 .. ~a (the tile height)"
                                      (where) name v
                                      (if (string=? (substring name 0 5) "slope") "height" "depth") th)))
      v)
    (define (pair kind left right)
      (let ((l (assoc left props)) (r (assoc right props)))
        (cond ((and l r) (cons kind (cons (height left (cdr l)) (height right (cdr r)))))
              ((or l r)
               (error 'load-tilemap (sprintf "~a: property ~s needs ~s beside it (a slope gives both edges)"
                                             (where) (if l left right) (if l right left))))
              (else #f))))
    (let ((floor (pair 'floor "slope-left" "slope-right"))
          (ceiling (pair 'ceiling "ceiling-left" "ceiling-right")))
      (cond ((and floor ceiling)
             (error 'load-tilemap (sprintf "~a: properties slope-left/slope-right and ceiling-left/ceiling-right together; a tile is a floor slope or a ceiling slope"
                                           (where))))
            ((or floor ceiling))
            (else (let loop ((shapes (tile-shapes t)))
                    (and (pair? shapes)
                         (or (polygon-slope (car shapes) tw th) (loop (cdr shapes)))))))))

  ;; The slope of a collision polygon on the tile's two edges, or #f.
  (define (polygon-slope o tw th)
    (and (eq? (object-shape o) 'polygon)
         (let* ((pts (map (lambda (p) (cons (+ (object-x o) (car p)) (+ (object-y o) (cdr p))))
                          (object-points o)))
                (on-edge (lambda (x pick) (foldl (lambda (best p)
                                                    (if (and (= (car p) x) (or (not best) (pick (cdr p) best))) (cdr p) best))
                                                  #f pts)))
                (corner? (lambda (x y) (any (lambda (p) (and (= (car p) x) (= (cdr p) y))) pts))))
           (or (and (corner? 0 0) (corner? tw 0) (not (and (corner? 0 th) (corner? tw th)))
                    (every-on-edge? pts tw)
                    (let ((dl (on-edge 0 >)) (dr (on-edge tw >)))
                      (and (<= 0 dl th) (<= 0 dr th) (not (and (= dl 0) (= dr 0)))
                           (cons 'ceiling (cons (->exact dl) (->exact dr))))))
               (let ((yl (on-edge 0 <)) (yr (on-edge tw <)))
                 (and yl yr (<= 0 yl th) (<= 0 yr th)
                      (let ((l (->exact (- th yl))) (r (->exact (- th yr))))
                        (and (not (and (= l th) (= r th))) (cons 'floor (cons l r))))))))))

  ;; A slope (kind left . right) as a cell's flip flags turn it (Tiled
  ;; flips the diagonal first, then horizontally, then vertically): the
  ;; tile's solid part as a polygon in tile px, transformed, and read back
  ;; as a floor (both bottom corners, every point on the left or right
  ;; edge) or a ceiling (both top corners, the same); #f when it is
  ;; neither (a turned 22.5 degree tile has no straight floor or ceiling
  ;; from edge to edge). A diagonal flip needs square tiles.
  (define (flipped-slope slope cell tw th)
    (let* ((kind (car slope)) (l (cadr slope)) (r (cddr slope))
           (pts (if (eq? kind 'floor)
                    (list (cons 0 (- th l)) (cons tw (- th r)) (cons tw th) (cons 0 th))
                    (list (cons 0 0) (cons tw 0) (cons tw r) (cons 0 l))))
           (pts (if (cell-flipped-diagonally? cell) (map (lambda (p) (cons (cdr p) (car p))) pts) pts))
           (pts (if (cell-flipped-horizontally? cell) (map (lambda (p) (cons (- tw (car p)) (cdr p))) pts) pts))
           (pts (if (cell-flipped-vertically? cell) (map (lambda (p) (cons (car p) (- th (cdr p)))) pts) pts))
           (has? (lambda (x y) (any (lambda (p) (and (= (car p) x) (= (cdr p) y))) pts)))
           (edge (lambda (x pick) (foldl (lambda (best p) (if (and (= (car p) x) (or (not best) (pick (cdr p) best))) (cdr p) best))
                                         #f pts))))
      (and (or (= tw th) (not (cell-flipped-diagonally? cell)))
           (every-on-edge? pts tw)
           (cond ((and (has? 0 th) (has? tw th)) (cons 'floor (cons (- th (edge 0 <)) (- th (edge tw <)))))
                 ((and (has? 0 0) (has? tw 0)) (cons 'ceiling (cons (edge 0 >) (edge tw >))))
                 (else #f)))))

  (define (every-on-edge? pts tw)
    (or (null? pts) (and (or (= 0 (caar pts)) (= tw (caar pts))) (every-on-edge? (cdr pts) tw))))

  (define (->exact v) (if (exact? v) v (inexact->exact v)))

  ;; What the tilesets' tiles say, checked: a table gid -> #(collides one-way
  ;; kind ladder slope) (each #f when the tile does not set it, kind a
  ;; symbol, slope (floor left . right) or (ceiling left . right)) for the
  ;; tiles that set any, plus each gid of `extra-one-way` as one-way (of
  ;; `extra-ladders` as a ladder, of `extra-slopes` as a floor slope, of
  ;; `extra-ceilings` as a ceiling slope); #f when there are none. A property of the
  ;; table of another type, or a name that looks like one of the table's,
  ;; is an error naming the file, the tileset, the tile and the property.
  (define (tile-rules tilesets extra-one-way extra-kinds extra-ladders extra-slopes extra-ceilings
                      tw th map-source)
    (let ((table (make-hash-table)) (any? #f))
      ;; what the code's lists add to a tile's rule: field i set to v
      (define (rule-set! g i v)
        (let ((rule (hash-table-ref/default table g #f)))
          (if rule
              (vector-set! rule i v)
              (let ((rule (make-vector 5 #f)))
                (vector-set! rule i v)
                (hash-table-set! table g rule)))))
      (for-each
       (lambda (ts)
         (for-each
          (lambda (t)
            (let* ((props (tile-properties t))
                   (where (lambda () (sprintf "~a: tileset ~s, tile ~a" (tileset-origin ts map-source)
                                              (tileset-name ts) (tile-id t)))))
              (for-each
               (lambda (p)
                 (let ((known (assoc (car p) tile-property-table))
                       (like (and (string? (car p)) (misspelt-tile-property (car p)))))
                   (cond (like
                          (error 'load-tilemap
                                 (sprintf "~a: property ~s is not one of Downstroke's tile properties; did you mean ~s?"
                                          (where) (car p) like)))
                         ((and known (not (eq? (property-type (cdr p)) (cdr known))))
                          (error 'load-tilemap
                                 (sprintf "~a: property ~s must be of type ~a, not ~a (~s)"
                                          (where) (car p) (cdr known) (property-type (cdr p)) (cdr p)))))))
               props)
              (let ((collides (assoc "collides" props)) (one-way (assoc "one-way" props))
                    (kind (assoc "kind" props)) (ladder (assoc "ladder" props))
                    (slope (tile-slope t props tw th where)))
                (when (or collides one-way kind ladder slope)
                  (set! any? #t)
                  (hash-table-set! table (+ (tileset-first-gid ts) (tile-id t))
                                   (vector (and collides (if (cdr collides) 'yes 'no))
                                           (and one-way (cdr one-way))
                                           (and kind (string->symbol (cdr kind)))
                                           (and ladder (cdr ladder))
                                           slope))))))
          (tileset-tiles ts)))
       tilesets)
      (for-each (lambda (g)
                  (set! any? #t)
                  (rule-set! g 1 #t))
                extra-one-way)
      (for-each (lambda (g)
                  (unless (exact-integer? g)
                    (error 'make-tilemap "ladders: must be a list of tile ids" g))
                  (set! any? #t)
                  (rule-set! g 3 #t))
                extra-ladders)
      (for-each (lambda (p)
                  (unless (and (pair? p) (exact-integer? (car p)) (symbol? (cdr p)))
                    (error 'make-tilemap "kinds: must be a list of (tile-id . symbol)" p))
                  (set! any? #t)
                  (rule-set! (car p) 2 (cdr p)))
                extra-kinds)
      (define (code-slopes kind key ls)
        (for-each (lambda (p)
                    (unless (and (list? p) (= (length p) 3) (exact-integer? (car p))
                                 (exact-integer? (cadr p)) (<= 0 (cadr p) th)
                                 (exact-integer? (caddr p)) (<= 0 (caddr p) th))
                      (error 'make-tilemap
                             (sprintf "~a must be a list of (tile-id left right), ~a 0 .. ~a (the tile height)"
                                      key (if (eq? kind 'floor) "heights" "depths") th)
                             p))
                    (set! any? #t)
                    (rule-set! (car p) 4 (cons kind (cons (cadr p) (caddr p)))))
                  ls))
      (code-slopes 'floor "slopes:" extra-slopes)
      (code-slopes 'ceiling "ceiling-slopes:" extra-ceilings)
      (and any? table)))

  ;; The solid grid: 0 empty, 1 solid, 2 one-way, 3 slope (slope-grid
  ;; then makes a cell whose flips leave a ceiling slope 4). A non-zero gid
  ;; of a colliding layer is solid, unless its tile says collides false or
  ;; ladder (then it adds nothing here), is a slope (3) or one-way (2); a
  ;; solid tile of another layer in the same cell overrides either, and a
  ;; slope a one-way tile; on a one-way layer every other tile is one-way,
  ;; on a ladder layer every tile a ladder (see mark-ladder-tops!).
  (define (solid-grid width height layers rules)
    (let* ((n (* width height))
           (grid (make-u8vector n 0)))
      (for-each
       (lambda (layer)
         (when (layer-collides? layer)
           (let ((data (layer-data layer)))
             (if (or rules (layer-one-way? layer) (layer-ladder? layer))
                 (let ((all? (layer-one-way? layer)) (climb? (layer-ladder? layer)))
                   (do ((i 0 (fx+ i 1))) ((fx= i n))
                     (let ((g (cell-gid (u32vector-ref data i))))
                       (unless (fx= 0 g)
                         (let ((rule (and rules (hash-table-ref/default rules g #f))))
                           (cond ((and rule (eq? (vector-ref rule 0) 'no)))
                                 ((or climb? (and rule (vector-ref rule 3))))
                                 ((and rule (vector-ref rule 4))
                                  (unless (fx= 1 (u8vector-ref grid i)) (u8vector-set! grid i 3)))
                                 ((not (or all? (and rule (vector-ref rule 1))))
                                  (u8vector-set! grid i 1))
                                 ((fx= 0 (u8vector-ref grid i)) (u8vector-set! grid i 2))))))))
                 (do ((i 0 (fx+ i 1))) ((fx= i n))
                   (unless (fx= 0 (cell-gid (u32vector-ref data i)))
                     (u8vector-set! grid i 1)))))))
       layers)
      grid))

  ;; A cell another layer makes solid is no ladder; then each ladder top
  ;; (no ladder in the cell above, or the map's first row) becomes
  ;; one-way in the solid grid, where it is empty.
  (define (mark-ladder-tops! width solid ladders)
    (when ladders
      (let ((n (u8vector-length solid)))
        (do ((i 0 (fx+ i 1))) ((fx= i n))
          (when (fx= 1 (u8vector-ref solid i)) (u8vector-set! ladders i 0)))
        (do ((i 0 (fx+ i 1))) ((fx= i n))
          (when (and (fx= 1 (u8vector-ref ladders i)) (fx= 0 (u8vector-ref solid i))
                     (or (fx< i width) (fx= 0 (u8vector-ref ladders (fx- i width)))))
            (u8vector-set! solid i 2))))))

  ;; The ladder cells: 1 where a colliding layer has a ladder tile (its
  ;; tile says ladder, or its layer does), or #f when there is none. A
  ;; tile that says collides false is no ladder.
  (define (ladder-grid width height layers rules)
    (let* ((n (* width height))
           (grid #f))
      (for-each
       (lambda (layer)
         (when (and (layer-collides? layer) (or rules (layer-ladder? layer)))
           (let ((data (layer-data layer)) (climb? (layer-ladder? layer)))
             (do ((i 0 (fx+ i 1))) ((fx= i n))
               (let ((g (cell-gid (u32vector-ref data i))))
                 (unless (fx= 0 g)
                   (let ((rule (and rules (hash-table-ref/default rules g #f))))
                     (when (and (not (and rule (eq? (vector-ref rule 0) 'no)))
                                (or climb? (and rule (vector-ref rule 3))))
                       (unless grid (set! grid (make-u8vector n 0)))
                       (u8vector-set! grid i 1)))))))))
       layers)
      grid))

  ;; The kind of each cell: (grid . kinds), grid a u8vector of indices
  ;; into the vector `kinds` (0: no kind), or #f when no tile has a kind.
  ;; Every tile layer counts, colliding or not; where several have a tile
  ;; with a kind, the last layer (drawn on top) wins.
  (define (kind-grid width height layers rules map-source)
    (let ((names (if rules
                     (hash-table-fold rules (lambda (g rule acc)
                                              (let ((k (vector-ref rule 2)))
                                                (if (and k (not (memq k acc))) (cons k acc) acc)))
                                      '())
                     '())))
      (and (pair? names)
           (begin
             (when (> (length names) 255)
               (error 'load-tilemap (sprintf "~a: more than 255 tile kinds" (or map-source "a map made in code"))))
             (let* ((n (* width height))
                    (grid (make-u8vector n 0))
                    (kinds (list->vector (cons #f (reverse names)))))
               (define (index-of k) (let loop ((i 1)) (if (eq? (vector-ref kinds i) k) i (loop (fx+ i 1)))))
               (for-each
                (lambda (layer)
                  (let ((data (layer-data layer)))
                    (do ((i 0 (fx+ i 1))) ((fx= i n))
                      (let ((g (fxand (u32vector-ref data i) gid-mask)))
                        (unless (fx= 0 g)
                          (let ((rule (hash-table-ref/default rules g #f)))
                            (when (and rule (vector-ref rule 2))
                              (u8vector-set! grid i (index-of (vector-ref rule 2))))))))))
                layers)
               (cons grid kinds))))))

;; Each slope cell's heights (left . right), by cell index, or #f when
  ;; no cell is a slope: the slope of the last colliding layer that has
  ;; one there, turned by that cell's flip flags (flipped-slope), which
  ;; also decide whether it is a floor slope (grid byte 3, heights above
  ;; the cell's bottom) or a ceiling slope (byte 4, depths below its top).
  ;; A flip that leaves no straight floor or ceiling is an error naming
  ;; the file, the layer, the cell and the tile.
  (define (slope-grid width height layers rules grid tw th origin-col origin-row tilesets source)
    (let ((n (* width height)))
      (and rules
           (let scan ((i 0))
             (and (fx< i n) (or (fx= 3 (u8vector-ref grid i)) (scan (fx+ i 1)))))
           (let ((v (make-vector n #f)))
             (for-each
              (lambda (layer)
                (when (layer-collides? layer)
                  (let ((data (layer-data layer)))
                    (do ((i 0 (fx+ i 1))) ((fx= i n))
                      (let* ((cell (u32vector-ref data i))
                             (rule (hash-table-ref/default rules (cell-gid cell) #f))
                             (slope (and rule (vector-ref rule 4))))
                        (when (and slope (fx>= (u8vector-ref grid i) 3))
                          (let ((turned (flipped-slope slope cell tw th)))
                            (unless turned
                              (error 'load-tilemap
                                     (sprintf "~a: layer ~s, cell (~a, ~a): tile ~a, a ~a slope ~a -> ~a, flipped ~s, has no straight floor or ceiling from edge to edge~a"
                                              (or source "a map made in code") (layer-name layer)
                                              (+ origin-col (fxmod i width)) (+ origin-row (fx/ i width))
                                              (tile-label tilesets (cell-gid cell)) (car slope) (cadr slope) (cddr slope)
                                              (cell-flags cell)
                                              (if (and (cell-flipped-diagonally? cell) (not (= tw th)))
                                                  " (a diagonal flip needs square tiles)"
                                                  ""))))
                            (u8vector-set! grid i (if (eq? (car turned) 'floor) 3 4))
                            (vector-set! v i (cdr turned)))))))))
              layers)
             v))))

  ;; A tile for an error: its tileset and local id, else its gid.
  (define (tile-label tilesets gid)
    (let loop ((ts tilesets) (best #f))
      (cond ((and (pair? ts) (<= (tileset-first-gid (car ts)) gid)) (loop (cdr ts) (car ts)))
            (best (sprintf "~a of tileset ~s" (- gid (tileset-first-gid best)) (tileset-name best)))
            (else (sprintf "id ~a" gid)))))

  (define (make-tilemap width height tile-width tile-height layers
                        #!key (properties '()) (origin-col 0) (origin-row 0)
                        (info '()) (tilesets '()) (layer-tree layers) (one-way '()) (kinds '())
                        (ladders '()) (slopes '()) (ceiling-slopes '()))
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
    (let* ((source (let ((p (assq 'source info))) (and p (cdr p))))
           (rules (tile-rules tilesets one-way kinds ladders slopes ceiling-slopes tile-width tile-height source))
           (climbable (ladder-grid width height layers rules))
           (solid (solid-grid width height layers rules)))
      (mark-ladder-tops! width solid climbable)
      (%make-tilemap width height tile-width tile-height layers properties
                     solid origin-col origin-row
                     info tilesets layer-tree (kind-grid width height layers rules source) climbable
                     (slope-grid width height layers rules solid tile-width tile-height
                                 origin-col origin-row tilesets source))))

  ;; A one-layer map from rows of tile ids: procedural levels, tests, the REPL.
  ;; one-way: the tile ids that are one-way platforms; kinds: an alist
  ;; (tile-id . kind) of the tiles' kinds (as the `kind` tile property);
  ;; ladders: the tile ids that are ladders; slopes: a list (tile-id left
  ;; right) of the slope tiles and their heights (as the slope-left and
  ;; slope-right tile properties); ceiling-slopes: likewise, the ceiling
  ;; slope tiles and their depths (as ceiling-left and ceiling-right).
  (define/keywords (list->tilemap rows #!key (tile-width 16) (tile-height 16) (name "tiles")
                                  (one-way '()) (kinds '()) (ladders '()) (slopes '())
                                  (ceiling-slopes '()))
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
                    (list (make-layer name width height data))
                    one-way: one-way kinds: kinds ladders: ladders slopes: slopes
                    ceiling-slopes: ceiling-slopes)))

  ;;; ------------------------------------------------------------------
  ;;; Where Tiled draws things, for every orientation (the renderer and the
  ;;; camera's map bounds use these; physics stays on the orthogonal grid).

  (define (info-height tm) (tilemap-height tm))

  ;; Tiled's hexagonal parameters (staggered maps are hexagonal maps with
  ;; a side length of 0): a vector
  ;;   #(tw th side-x side-y stagger-x? stagger-even? column-width row-height side-offset-x side-offset-y)
  (define (hex-params tm)
    (let* ((tw (bitwise-and (tilemap-tile-width tm) (bitwise-not 1)))
           (th (bitwise-and (tilemap-tile-height tm) (bitwise-not 1)))
           (hex? (eq? (tilemap-orientation tm) 'hexagonal))
           (stagger-x? (eq? (tilemap-stagger-axis tm) 'x))
           (even? (eq? (tilemap-stagger-index tm) 'even))
           (side (if hex? (or (tilemap-hex-side-length tm) 0) 0))
           (side-x (if stagger-x? side 0))
           (side-y (if stagger-x? 0 side))
           (off-x (quotient (- tw side-x) 2))
           (off-y (quotient (- th side-y) 2)))
      (vector tw th side-x side-y stagger-x? even? (+ off-x side-x) (+ off-y side-y) off-x off-y)))

  (define (staggered? p i) (not (eq? (odd? i) (vector-ref p 5))))

  ;; Where Tiled draws cell (col, row): the bottom-left corner of its
  ;; image, before the tileset's <tileoffset>, in the map's screen pixels
  ;; (the picture Tiled draws, top-left (0, 0)); (values x y).
  (define (tilemap-cell-anchor tm col row)
    (let ((tw (tilemap-tile-width tm)) (th (tilemap-tile-height tm)))
      (case (tilemap-orientation tm)
        ((isometric)
         (values (+ (/ (* (- col row) tw) 2) (/ (* (info-height tm) tw) 2) (- (/ tw 2)))
                 (+ (/ (* (+ col row) th) 2) th)))
        ((staggered hexagonal)
         (let ((p (hex-params tm)))
           (if (vector-ref p 4)           ; stagger axis x
               (values (* col (vector-ref p 6))
                       (+ (* row (+ (vector-ref p 1) (vector-ref p 3)))
                          (if (staggered? p col) (vector-ref p 7) 0)
                          (vector-ref p 1)))
               (values (+ (* col (+ (vector-ref p 0) (vector-ref p 2)))
                          (if (staggered? p row) (vector-ref p 6) 0))
                       (+ (* row (vector-ref p 7)) (vector-ref p 1))))))
        (else (values (* col tw) (* (+ row 1) th))))))

  ;; The size of the picture Tiled draws of the map (its renderer's map
  ;; size, before layer offsets): (values width height). The map's pixel
  ;; size on orthogonal maps.
  (define (tilemap-screen-size tm)
    (let ((w (tilemap-width tm)) (h (tilemap-height tm))
          (tw (tilemap-tile-width tm)) (th (tilemap-tile-height tm)))
      (case (tilemap-orientation tm)
        ((isometric) (values (/ (* (+ w h) tw) 2) (/ (* (+ w h) th) 2)))
        ((staggered hexagonal)
         (let ((p (hex-params tm)))
           (if (vector-ref p 4)
               (values (+ (* w (vector-ref p 6)) (vector-ref p 8))
                       (+ (* h (+ (vector-ref p 1) (vector-ref p 3)))
                          (if (> w 1) (vector-ref p 7) 0)))
               (values (+ (* w (+ (vector-ref p 0) (vector-ref p 2)))
                          (if (> h 1) (vector-ref p 6) 0))
                       (+ (* h (vector-ref p 7)) (vector-ref p 9))))))
        (else (values (* w tw) (* h th))))))

  ;; A map position (x, y) in pixels (an object's) as a screen point:
  ;; isometric maps project it ((x / th, y / th) as cell coordinates), the
  ;; others draw it where it is; (values sx sy).
  (define (tilemap-screen-point tm x y)
    (if (eq? (tilemap-orientation tm) 'isometric)
        (let* ((tw (tilemap-tile-width tm)) (th (tilemap-tile-height tm))
               (cx (/ x th)) (cy (/ y th)))
          (values (+ (/ (* (- cx cy) tw) 2) (/ (* (info-height tm) tw) 2))
                  (/ (* (+ cx cy) th) 2)))
        (values x y)))


  (define (tilemap-pixel-width tm) (* (tilemap-width tm) (tilemap-tile-width tm)))
  (define (tilemap-pixel-height tm) (* (tilemap-height tm) (tilemap-tile-height tm)))

  ;; A tile layer by index (0 = first) or by name.
  (define (tilemap-layer tm which)
    (let loop ((layers (tilemap-layers tm)) (i 0))
      (cond ((null? layers)
             (error 'tilemap-layer
                    (sprintf "~a: no such layer ~s; its tile layers are ~s (by name, or by index from 0)"
                             (or (tilemap-source tm) "the map") which
                             (map layer-name (tilemap-layers tm)))))
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
    (cell-gid (cell-ref 'tilemap-tile-at tm col row which)))

  ;; The flip flags of a cell, as cell-flags gives them.
  (define (tilemap-flags-at tm col row #!optional (which 0))
    (cell-flags (cell-ref 'tilemap-flags-at tm col row which)))

  ;; Whether any colliding layer has a solid tile at the cell; outside is
  ;; empty.
  (define (tilemap-solid? tm col row)
    (let ((i (cell-index 'tilemap-solid? tm col row)))
      (and i (fx= 1 (u8vector-ref (tilemap-solid-grid tm) i)))))

  ;; Whether the cell is a one-way platform (and not solid): a one-way
  ;; tile, a ladder's top, or a ceiling slope, whose top edge is solid.
  (define (tilemap-one-way? tm col row)
    (let ((i (cell-index 'tilemap-one-way? tm col row)))
      (and i (one-way-byte? (u8vector-ref (tilemap-solid-grid tm) i)))))

  ;; The solid grid's bytes whose cell holds a body landing from above and
  ;; lets one through from below (physics/motion.c's DS_ONE_WAY says the same).
  (define (one-way-byte? b) (or (fx= b 2) (fx= b 4)))

  ;; The kind of the cell (a symbol, from its tile's `kind` property), or
  ;; #f: O(1), a byte of a grid made when the map was.
  (define (tilemap-kind tm col row)
    (let ((i (cell-index 'tilemap-kind tm col row)) (k (tilemap-kinds tm)))
      (and i k (vector-ref (cdr k) (u8vector-ref (car k) i)))))

  ;; Whether the cell is a ladder (docs/physics.org, "Ladders"): O(1).
  (define (tilemap-ladder? tm col row)
    (let ((i (cell-index 'tilemap-ladder? tm col row)) (l (tilemap-ladders tm)))
      (and i l (fx= 1 (u8vector-ref l i)))))

  ;; Whether the cell is a ladder's top: a ladder with no ladder above it.
  (define (tilemap-ladder-top? tm col row)
    (and (tilemap-ladder? tm col row)
         (not (tilemap-ladder? tm col (- row 1)))))

  ;; The slope of the cell, (left . right): its floor's heights in px above
  ;; the cell's bottom edge at its left and right edges; #f when the cell
  ;; is no floor slope (docs/physics.org, "Slopes").
  (define (tilemap-slope tm col row)
    (let ((i (cell-index 'tilemap-slope tm col row)) (v (tilemap-slopes tm)))
      (and i v (fx= 3 (u8vector-ref (tilemap-solid-grid tm) i)) (vector-ref v i))))

  ;; The ceiling slope of the cell, (left . right): its ceiling's depths in
  ;; px below the cell's top edge at its left and right edges (its solid
  ;; part lies above that line); #f when the cell is no ceiling slope.
  (define (tilemap-ceiling-slope tm col row)
    (let ((i (cell-index 'tilemap-ceiling-slope tm col row)) (v (tilemap-slopes tm)))
      (and i v (fx= 4 (u8vector-ref (tilemap-solid-grid tm) i)) (vector-ref v i))))

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
  ;;; Tilesets without a map file

  ;; A sprite sheet described in code: an image cut into a grid of tiles of
  ;; tile-width x tile-height, columns to a row, read left to right and top
  ;; to bottom (what Tiled calls a tileset based on one image). The image
  ;; must exist; it is not decoded here (the pure core never touches SDL).
  (define/keywords (make-sheet-tileset image #!key tile-width tile-height columns
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

