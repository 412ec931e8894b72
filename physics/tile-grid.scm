;;; (downstroke tile-grid): the cells a body covers and a map's solid grid as the tile rules read it.
;;;
;;; A body covers the cells from floor(pos/T) to ceil((pos+size)/T) - 1 on
;;; each axis (docs/physics.org, "Tile collisions"); the grid is the map's
;;; solid cells seen along an axis, kept for the last map asked about.

(module (downstroke tile-grid)
  (entity-tile-cells entity-cell-span tile-push-pos
   ;; for sibling modules only: the cell arithmetic and the grids the tile
   ;; rules, the escape search and the motion kernel share
   ->integer cell-of cell-ceiling span-first span-last nearest-solid-line grids
   column-grid row-grid pass-map one-way-map?)

  (import scheme (chicken base) (chicken fixnum) (chicken foreign) srfi-4
          (downstroke entity) (downstroke map) (downstroke arith) (downstroke body))

  (foreign-declare "#include \"physics/body.h\"")

  (define (->integer v) (if (exact? v) v (inexact->exact v)))

  ;; The cell index holding coordinate `pos` (tiles of `tile` px).
  (define (cell-of pos tile)
    (if (exact-integer? pos)
        (floor-div pos tile)
        (->integer (floor (/ pos tile)))))

  ;; ceil(pos / T): the cell just past a grid line at pos, and for pos
  ;; off the lines the cell holding it, plus one.
  (define (cell-ceiling pos tile)
    (if (exact-integer? pos)
        (+ (floor-div (- pos 1) tile) 1)
        (->integer (ceiling (/ pos tile)))))

  ;; The first and last cell a span [pos, pos+size) covers on one axis:
  ;; floor(pos/T) to ceil((pos+size)/T) - 1, which for integers is the
  ;; floor((pos+size-1)/T) of docs/physics.org: a body flush with a tile edge does not
  ;; cover that tile. A zero-size span on a tile edge covers no cell (last <
  ;; first); elsewhere it covers the one cell it lies in.
  (define (entity-cell-span pos size tile)
    (values (span-first pos tile) (span-last pos size tile)))

  (define (span-first pos tile)
    (if (exact-integer? pos)
        (floor-div pos tile)
        (->integer (floor (/ pos tile)))))

  (define (span-last pos size tile)
    (if (and (exact-integer? pos) (exact-integer? size))
        (floor-div (+ pos size -1) tile)
        (- (->integer (ceiling (/ (+ pos size) tile))) 1)))

  ;; Every (col . row) cell the entity's AABB covers, row by row.
  (define (entity-tile-cells entity tilemap)
    (let-values (((c0 c1) (entity-cell-span (num entity #:x) (num entity #:width)
                                            (tilemap-tile-width tilemap)))
                 ((r0 r1) (entity-cell-span (num entity #:y) (num entity #:height)
                                            (tilemap-tile-height tilemap))))
      (let rows ((r r1) (out '()))
        (if (< r r0)
            out
            (rows (- r 1)
                  (let cols ((c c1) (out out))
                    (if (< c c0) out (cols (- c 1) (cons (cons c r) out)))))))))

  ;; Where a body of `size` ends up when it meets the tile at `coord`:
  ;; moving forward, its leading edge on the tile's near edge; moving
  ;; backward, its trailing edge on the tile's far edge.
  (define (tile-push-pos v coord tile-size entity-size)
    (if (> v 0)
        (- (* coord tile-size) entity-size)
        (* (+ coord 1) tile-size)))

  ;; The nearest line of cells, in the direction of motion, that holds a
  ;; solid tile: lines `from` .. `to` stepping by `step` (+1 or -1), each line
  ;; spanning cells lo..hi on the other axis. `grid` is the map's solid grid
  ;; seen along this axis: lines and cells are counted from the map's
  ;; origin, and cell (line, cell) is byte line*line-stride + cell*cell-stride.
  ;; Only cells inside the map are visited; outside, every cell is empty.
  (define-record-type axis-grid
    (make-axis-grid bytes line-stride cell-stride line-origin cell-origin line-count cell-count)
    axis-grid?
    (bytes grid-bytes) (line-stride grid-line-stride) (cell-stride grid-cell-stride)
    (line-origin grid-line-origin) (cell-origin grid-cell-origin)
    (line-count grid-line-count) (cell-count grid-cell-count))

  ;; A one-way cell (grid byte 2) counts only when `one-way-top` is a
  ;; number and the cell's line starts at or past it (lines of `tile` px):
  ;; the top of a jump-through platform that a falling body was above.
  (define (nearest-solid-line g from to step lo hi #!optional one-way-top tile)
    (let* ((lo (max (- lo (grid-cell-origin g)) 0))
           (hi (min (- hi (grid-cell-origin g)) (- (grid-cell-count g) 1)))
           (from (- from (grid-line-origin g)))
           (to (- to (grid-line-origin g)))
           (last (- (grid-line-count g) 1))
           (from (if (> step 0) (max from 0) (min from last)))
           (to (if (> step 0) (min to last) (max to 0))))
      (and (<= lo hi)
           (if (> step 0) (<= from to) (>= from to))
           ;; every index is now inside the map, so fixnum arithmetic is safe
           (let ((bytes (grid-bytes g))
                 (line-stride (grid-line-stride g))
                 (cell-stride (grid-cell-stride g)))
             (let next-line ((line from))
               (let ((base (fx* line line-stride)))
                 (let next-cell ((cell lo))
                   (cond ((fx> cell hi)
                          (and (not (fx= line to)) (next-line (fx+ line step))))
                         ((let ((b (u8vector-ref bytes (fx+ base (fx* cell cell-stride)))))
                            (or (fx= b 1)
                                (and (or (fx= b 2) (fx= b 4)) one-way-top
                                     (>= (* (+ line (grid-line-origin g)) tile) one-way-top))))
                          (+ line (grid-line-origin g)))
                         (else (next-cell (fx+ cell 1)))))))))))

  ;; The solid grid of a map, walked by columns (the x pass) or rows (y),
  ;; and the map as the motion pass's C code reads it (below). Every body
  ;; of a frame asks about the same map: the views of the last map asked
  ;; about are kept (a tilemap is immutable, and its solid grid is made
  ;; once).
  (define last-grids (cons #f #f))      ; (tilemap . #(columns rows pass-map one-way? solid-counts))

  (define (grids tm)
    (if (eq? (car last-grids) tm)
        (cdr last-grids)
        (let ((bytes (tilemap-solid-grid tm)))
          (let ((v (vector (make-axis-grid bytes 1 (tilemap-width tm)
                                           (tilemap-origin-col tm) (tilemap-origin-row tm)
                                           (tilemap-width tm) (tilemap-height tm))
                           (make-axis-grid bytes (tilemap-width tm) 1
                                           (tilemap-origin-row tm) (tilemap-origin-col tm)
                                           (tilemap-height tm) (tilemap-width tm))
                           (and (fixnum? (tilemap-width tm)) (fixnum? (tilemap-height tm))
                                (fixnum? (tilemap-origin-col tm)) (fixnum? (tilemap-origin-row tm))
                                (vector (tilemap-width tm) (tilemap-height tm)
                                        (tilemap-origin-col tm) (tilemap-origin-row tm)
                                        (tilemap-tile-width tm) (tilemap-tile-height tm)))
                           (has-one-way? bytes)
                           #f)))                ; solid-counts, made when needed
            (set! last-grids (cons tm v))
            v))))

  (define (has-one-way? bytes)
    (let loop ((i (fx- (u8vector-length bytes) 1)))
      (and (fx>= i 0) (let ((b (u8vector-ref bytes i))) (or (fx= b 2) (fx= b 4) (loop (fx- i 1)))))))

  (define (column-grid tm) (vector-ref (grids tm) 0))
  (define (row-grid tm) (vector-ref (grids tm) 1))
  ;; #(cols rows origin-col origin-row tile-width tile-height), or #f for a
  ;; map whose size or origin is not a fixnum (the C code cannot take it).
  (define (pass-map tm) (vector-ref (grids tm) 2))
  ;; Whether the map has one-way cells at all.
  (define (one-way-map? tm) (vector-ref (grids tm) 3))
)
