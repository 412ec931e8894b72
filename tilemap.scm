;;; (downstroke tilemap): tile maps as immutable data.
;;;
;;; A tilemap is a grid of W x H cells in one or more layers, each cell a tile
;;; id (0 = empty). Layer data is a u32vector in row-major order, so
;;; `tilemap-tile-at` is O(1). Collision asks one question of a cell, "is it
;;; solid?", and that answer is precomputed once per map into a single byte
;;; grid merged from every colliding layer.
;;;
;;; Which layers collide: every tile layer, unless the layer has the property
;;; `collides` set to #f. So the contract's default holds (any non-zero tile
;;; is solid) and a decoration layer opts out with one property in Tiled.

(module (downstroke tilemap)
  (make-tilemap list->tilemap tilemap?
   tilemap-width tilemap-height tilemap-tile-width tilemap-tile-height
   tilemap-pixel-width tilemap-pixel-height
   tilemap-layers tilemap-layer tilemap-properties
   tilemap-tile-at tilemap-solid? tilemap-solid-grid
   tilemap-origin-col tilemap-origin-row
   make-layer layer? layer-name layer-width layer-height layer-data
   layer-visible? layer-properties layer-collides?)

  (import scheme (chicken base) (chicken fixnum) (chicken format) srfi-4)

  (define-record-type layer
    (%make-layer name width height data visible? properties)
    layer?
    (name layer-name)
    (width layer-width)
    (height layer-height)
    (data layer-data)
    (visible? layer-visible?)
    (properties layer-properties))

  (define (make-layer name width height data #!key (visible? #t) (properties '()))
    (unless (and (u32vector? data) (= (u32vector-length data) (* width height)))
      (error 'make-layer
             (sprintf "layer ~s: data must be a u32vector of ~a cells" name (* width height))))
    (%make-layer name width height data visible? properties))

  (define (layer-collides? layer)
    (let ((p (assoc "collides" (layer-properties layer))))
      (not (and p (not (cdr p))))))

  (define-record-type tilemap
    (%make-tilemap width height tile-width tile-height layers properties solid)
    tilemap?
    (width tilemap-width)
    (height tilemap-height)
    (tile-width tilemap-tile-width)
    (tile-height tilemap-tile-height)
    (layers tilemap-layers)
    (properties tilemap-properties)
    (solid tilemap-solid-grid))

  (define (solid-grid width height layers)
    (let ((grid (make-u8vector (* width height) 0)))
      (for-each
       (lambda (layer)
         (when (layer-collides? layer)
           (let ((data (layer-data layer)))
             (do ((i 0 (fx+ i 1))) ((fx= i (* width height)))
               (unless (zero? (u32vector-ref data i))
                 (u8vector-set! grid i 1))))))
       layers)
      grid))

  (define (make-tilemap width height tile-width tile-height layers #!key (properties '()))
    (for-each
     (lambda (layer)
       (unless (and (= (layer-width layer) width) (= (layer-height layer) height))
         (error 'make-tilemap
                (sprintf "layer ~s is ~ax~a, the map is ~ax~a"
                         (layer-name layer) (layer-width layer) (layer-height layer)
                         width height))))
     layers)
    (unless (and (fixnum? tile-width) (fx> tile-width 0)
                 (fixnum? tile-height) (fx> tile-height 0))
      (error 'make-tilemap "tile size must be positive integers" tile-width tile-height))
    (%make-tilemap width height tile-width tile-height layers properties
                   (solid-grid width height layers)))

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

  ;; The top-left cell: 0, 0 for a finite map.
  (define (tilemap-origin-col tm) 0)
  (define (tilemap-origin-row tm) 0)

  (define (tilemap-pixel-width tm) (* (tilemap-width tm) (tilemap-tile-width tm)))
  (define (tilemap-pixel-height tm) (* (tilemap-height tm) (tilemap-tile-height tm)))

  ;; A layer by index (0 = first) or by name.
  (define (tilemap-layer tm which)
    (let loop ((layers (tilemap-layers tm)) (i 0))
      (cond ((null? layers) (error 'tilemap-layer "no such layer" which))
            ((if (string? which)
                 (equal? which (layer-name (car layers)))
                 (eqv? which i))
             (car layers))
            (else (loop (cdr layers) (+ i 1))))))

  (define (in-map? tm col row)
    (and (fixnum? col) (fixnum? row)
         (fx>= col 0) (fx< col (tilemap-width tm))
         (fx>= row 0) (fx< row (tilemap-height tm))))

  ;; The tile id at a cell; 0 when empty or outside the map.
  (define (tilemap-tile-at tm col row #!optional (which 0))
    (if (in-map? tm col row)
        (u32vector-ref (layer-data (tilemap-layer tm which))
                       (fx+ (fx* row (tilemap-width tm)) col))
        0))

  ;; Whether any colliding layer has a tile at the cell; outside is empty.
  (define (tilemap-solid? tm col row)
    (and (in-map? tm col row)
         (fx= 1 (u8vector-ref (tilemap-solid-grid tm)
                              (fx+ (fx* row (tilemap-width tm)) col))))))
