;;; (downstroke physics): every step of the pipeline docs/physics.org lists.
;;;
;;; Units: positions in pixels, velocities in pixels per frame, gravity in
;;; pixels per frame squared. Per-entity steps have the signature
;;; (step scene entity dt) and return a new entity; the bulk steps map an
;;; entity list to an entity list. Numbers may be fixnums, flonums, bignums
;;; or exact rationals: integer inputs give integer results, and exact
;;; rationals stay exact. A NaN or infinite position, size or velocity is an
;;; error naming the entity and the key (see `entity-number`).

(module (downstroke physics)
  (apply-acceleration apply-gravity apply-velocity-x resolve-tile-collisions-x
   apply-velocity-y resolve-tile-collisions-y step-motion motion-pass detect-on-solid
   record-frame-start resolve-entity-collisions sync-groups
   aabb-overlap? entity-tile-cells entity-cell-span tile-push-pos tile-way-out
   entity-solid-support-below? resolve-pair push-apart
   discrete-safe-speed tunnel-risk?
   *gravity* *jump-force* *entity-ground-contact-tolerance* *entity-ground-vy-max*
   tune-physics!)

  (import scheme (chicken base) (chicken fixnum) (chicken sort) (chicken format) (chicken foreign) srfi-4
          (downstroke keywords) (downstroke entity) (downstroke scene) (downstroke map)
          (downstroke broadphase) (downstroke arith) (downstroke c-constants)
          (only (downstroke util) make-hash-table hash-table-exists? hash-table-set!
                hash-table-ref/default hash-table-count))

  ;;; Constants

  ;; Added to #:vy of gravity entities every frame (px/frame^2).
  (define *gravity* 1)
  ;; A jump is #:ay = (- *jump-force*): the first frame of a jump moves up
  ;; 9 px (10 - gravity), and the body rises 45 px, almost three 16 px tiles,
  ;; in 9 frames.
  (define *jump-force* 10)
  ;; A solid entity whose top is within this many px of a mover's bottom
  ;; supports it (px).
  (define *entity-ground-contact-tolerance* 5)
  ;; A mover falling or rising faster than this (px/frame) is not supported
  ;; by an entity: it would only be passing through the contact band.
  (define *entity-ground-vy-max* 12)

  ;; The supported way to change the constants above (a set! of an
  ;; imported binding works, with a compiler warning): each keyword given
  ;; sets one, after all are checked, so a bad one changes nothing.
  (define/keywords (tune-physics! #!key (gravity *gravity*) (jump-force *jump-force*)
                                  (ground-contact-tolerance *entity-ground-contact-tolerance*)
                                  (ground-vy-max *entity-ground-vy-max*))
    (define (check key v ok? what)
      (unless (and (real? v) (or (exact? v) (finite? v)) (ok? v))
        (error (sprintf "tune-physics!: ~a ~s must be ~a" key v what))))
    (check "gravity:" gravity (lambda (v) #t) "a finite number")
    (check "jump-force:" jump-force (lambda (v) #t) "a finite number")
    (check "ground-contact-tolerance:" ground-contact-tolerance (lambda (v) (>= v 0)) "a finite number >= 0")
    (check "ground-vy-max:" ground-vy-max (lambda (v) (>= v 0)) "a finite number >= 0")
    (set! *gravity* gravity)
    (set! *jump-force* jump-force)
    (set! *entity-ground-contact-tolerance* ground-contact-tolerance)
    (set! *entity-ground-vy-max* ground-vy-max))

  ;;; Reading numbers

  ;; The numbers check-entity-number lets through (fixnums, bignums, exact
  ;; rationals, finite flonums), told apart by their type tags in C: 1 or
  ;; 0. Calling check-entity-number for every rational of a pushed-apart
  ;; crowd cost a tenth of that scene's time, and an `or` of predicates
  ;; compiles to a closure for its join.
  (foreign-declare "#include \"physics/motion.c\"")
  (define plain-number-bit (foreign-lambda scheme-object "ds_plain_number" scheme-object))
  (define-inline (plain-number? v) (eq? (plain-number-bit v) 1))

  ;; (fxand a b ...) for any count, so a test of many values has no branches.
  (define-syntax fxand*
    (syntax-rules ()
      ((_ a) a)
      ((_ a b ...) (fxand a (fxand* b ...)))))

  ;; The hot path reads a dozen numbers per entity per step: inlined, the
  ;; common numbers checked without a call (what entity-number does).
  ;; read-number: the number in e's pair p for key (0 when e has no such
  ;; pair); num: the number e holds for key.
  (define-inline (read-number e p key)
    (if p
        (let ((v (cdr p))) (if (plain-number? v) v (check-entity-number e key v)))
        0))

  (define-inline (num e key)
    (read-number e (assq key e) key))

  ;; (let-numbers e ((var key) ...) body ...): body with each var bound to
  ;; the number entity e holds for key (0 when absent), all checked at once.
  ;; num checks each read with a call on its slow side, and in CHICKEN such
  ;; a call, even one never taken, costs a continuation closure holding
  ;; every live value; here the only call is the report of a bad value, in
  ;; tail position. e must be a variable.
  (define-syntax let-numbers
    (syntax-rules ()
      ((_ e ((var key) ...) body ...)
       (let ((var (let ((p (assq key e))) (if p (cdr p) 0))) ...)
         (if (eq? (fxand* (plain-number-bit var) ...) 1)
             (let () body ...)
             (reject-numbers e (list key ...) (list var ...)))))))

  ;; a + b for the step that moves key: a sum of finite numbers that
  ;; overflows to an infinity is that step's error, naming the entity and
  ;; the key, not a failure later in a tile lookup.
  (define-inline (sum e key a b)
    (let ((v (+ a b))) (if (plain-number? v) v (overflowed e key a b))))

  (define (overflowed e key a b)
    (error 'downstroke
           (sprintf "entity ~a: ~s overflowed to ~s (~s + ~s); positions and velocities must stay finite"
                    (entity-label e) key (+ a b) a b)))

  ;; The error check-entity-number raises for the first bad value.
  (define (reject-numbers e keys values)
    (for-each (lambda (key v) (check-entity-number e key v)) keys values)
    (error 'reject-numbers "no bad value among" keys values))

  ;;; Cells covered by a body

  (define (->integer v) (if (exact? v) v (inexact->exact v)))

  ;; The cell index holding coordinate `pos` (tiles of `tile` px).
  (define (cell-of pos tile)
    (if (exact-integer? pos)
        (floor-div pos tile)
        (->integer (floor (/ pos tile)))))

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
                                (and (fx= b 2) one-way-top
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
      (and (fx>= i 0) (or (fx= 2 (u8vector-ref bytes i)) (loop (fx- i 1))))))

  (define (column-grid tm) (vector-ref (grids tm) 0))
  (define (row-grid tm) (vector-ref (grids tm) 1))
  ;; #(cols rows origin-col origin-row tile-width tile-height), or #f for a
  ;; map whose size or origin is not a fixnum (the C code cannot take it).
  (define (pass-map tm) (vector-ref (grids tm) 2))
  ;; Whether the map has one-way cells at all.
  (define (one-way-map? tm) (vector-ref (grids tm) 3))

  ;;; Per-entity steps, in pipeline order

  ;; Each motion step is its rule (a procedure of the scene and the entity)
  ;; behind its guard and skip symbol. The rules are docs/physics.org's motion,
  ;; written once: the steps run them, and so does the motion pass for
  ;; every entity its C kernel does not take (motion-steps, below).

  ;; The guard of acceleration and gravity.
  (define (gravity-on? entity) (entity-ref entity #:gravity? #f))

  ;; #:ay is added to #:vy and consumed (set to 0).
  (define (accelerate scene entity)
    (let ((ay (num entity #:ay)))
      (if (and (eq? ay 0) (assq #:ay entity))
          entity                        ; nothing to consume: no new entity
          (entity-set (entity-set entity #:vy (sum entity #:vy (num entity #:vy) ay)) #:ay 0))))

  (define (fall scene entity)
    (entity-set entity #:vy (sum entity #:vy (num entity #:vy) *gravity*)))

  (define (move-x scene entity)
    (entity-set entity #:x (sum entity #:x (num entity #:x) (num entity #:vx))))

  (define (move-y scene entity)
    (entity-set entity #:y (sum entity #:y (num entity #:y) (num entity #:vy))))

  (define-pipeline (apply-acceleration acceleration) (scene entity dt)
    guard: (gravity-on? entity)
    (accelerate scene entity))

  (define-pipeline (apply-gravity gravity) (scene entity dt)
    guard: (gravity-on? entity)
    (fall scene entity))

  (define-pipeline (apply-velocity-x velocity-x) (scene entity dt)
    (move-x scene entity))

  (define-pipeline (apply-velocity-y velocity-y) (scene entity dt)
    (move-y scene entity))

  ;; Which tile step an entity gets: its own #:collision-mode, else the
  ;; scene's.
  ;;   discrete  the plain step: the cells the body covers after moving.
  ;;   swept     also the cells it crossed on the way: the scan starts where
  ;;             the body was before this frame's move (pos - v), so no wall
  ;;             is passed at any speed. Wherever the discrete step does not
  ;;             pass a wall, both give the same result.
  (define (swept? scene entity)
    (swept-mode? scene entity (entity-ref entity #:collision-mode #f)))

  ;; `own` is the entity's #:collision-mode value (#f when it has none).
  (define (swept-mode? scene entity own)
    (case (or own (scene-collision-mode scene))
      ((swept) #t)
      ((discrete) #f)
      (else (error 'downstroke
                   (sprintf "entity ~a: #:collision-mode is ~s, not discrete or swept"
                            (entity-label entity) own)))))

  ;; The discrete step cannot pass a wall one tile thick while the body moves
  ;; less than its own size plus a tile per frame on that axis: some cell it
  ;; covers after the move is then one it could not have jumped over. At or
  ;; above this speed (px/frame) it may tunnel.
  (define (discrete-safe-speed size tile) (+ size tile))

  ;; Whether this entity, in this scene, could pass through a wall this
  ;; frame: discrete mode and a speed at or above the safe speed on an axis.
  ;; The debug overlay marks such bodies.
  (define (tunnel-risk? scene entity)
    (let ((tm (scene-tilemap scene)))
      (and tm
           (not (swept? scene entity))
           (or (>= (abs (num entity #:vx))
                   (discrete-safe-speed (num entity #:width) (tilemap-tile-width tm)))
               (>= (abs (num entity #:vy))
                   (discrete-safe-speed (num entity #:height) (tilemap-tile-height tm)))))))

  ;; One tile pass on one axis, for a body at `pos` of `size` with velocity
  ;; v (not 0), spanning across..across+across-size on the other axis:
  ;; where it stops, or #f when no solid tile is in its way. `moved` is how
  ;; far the velocity step moved the body this frame (v, or 0 when the body
  ;; skips that step), so pos - moved is where the frame's motion started.
  ;; swept: the scan starts there (a sweep covers only the motion made this
  ;; frame). one-way?: one-way tiles whose top the body's bottom was at or
  ;; above at that start count too (the y pass of a falling body).
  (define (tile-stop v pos size across across-size swept moved one-way? tile tile-across grid)
    ;; swept: from the line the leading edge was in before the move. Only
    ;; the leading edge counts, so a body leaving a wall it touched is not
    ;; caught by that wall when pos - v rounds (flonums) to just inside it.
    ;; (A zero-size body on a tile edge covers no line: its leading line is
    ;; the one it moves into.)
    (let* ((l0 (span-first pos tile)) (l1 (span-last pos size tile))
           (c0 (span-first across tile-across)) (c1 (span-last across across-size tile-across))
           (start (- pos moved))
           (one-way-top (and one-way? (+ start size))))
      (let ((line (if (> v 0)
                      (nearest-solid-line grid
                                          (if swept
                                              (min (max (span-first start tile) (span-last start size tile)) l0)
                                              l0)
                                          l1 1 c0 c1 one-way-top tile)
                      (nearest-solid-line grid
                                          (if swept
                                              (max (min (span-first start tile) (span-last start size tile)) l1)
                                              l1)
                                          l0 -1 c0 c1))))
        (and line (tile-push-pos v line tile size)))))

  ;; Both tile passes: pos-key is the axis resolved, across-key the other,
  ;; velocity-step the skip symbol of the step that moves pos-key. A
  ;; velocity of 0 snaps nothing. A body with #:drop-through? falls
  ;; through one-way tiles.
  (define (resolve-tiles entity swept pos-key size-key vel-key velocity-step across-key across-size-key
                         tile tile-across grid)
    (let ((v (num entity vel-key)))
      (if (zero? v)
          entity
          (let ((stop (tile-stop v (num entity pos-key) (num entity size-key)
                                 (num entity across-key) (num entity across-size-key)
                                 swept (if (entity-skips-pipeline? entity velocity-step) 0 v)
                                 (and (eq? pos-key #:y) (> v 0) (not (entity-ref entity #:drop-through? #f)))
                                 tile tile-across grid)))
            (if stop
                (entity-set* entity pos-key stop vel-key 0)
                entity)))))

  ;; Swept mode, before a body's first tile pass of the frame: a body that
  ;; starts the frame inside solid tiles (an entity push can leave it
  ;; there) and moves is first taken out of them by the shortest way, so
  ;; that no push ever carries a body through a wall (docs/physics.org, "A
  ;; body that starts a frame inside solid tiles"). A body at rest (both velocities 0) is left where it is,
  ;; as the tile passes leave it. Where a body's frame started is
  ;; pos - v only for a body its velocity moves: one with a #:tween, or one
  ;; that skips both velocity steps (a tween or the game places it), is
  ;; left to the tile passes, as discrete mode resolves it. (sx, sy) is
  ;; where the frame's motion started; the entity is moved by the same
  ;; amount.
  (define (leave-solids entity tm sx sy)
    (if (or (and (zero? (num entity #:vx)) (zero? (num entity #:vy)))
            (entity-ref entity #:tween #f)
            (and (entity-skips-pipeline? entity 'velocity-x)
                 (entity-skips-pipeline? entity 'velocity-y)))
        entity
        (let-values (((dx dy) (tile-way-out tm sx sy (num entity #:width) (num entity #:height))))
          (if (and (eqv? dx 0) (eqv? dy 0))
              entity
              (entity-set* entity #:x (+ (num entity #:x) dx) #:y (+ (num entity #:y) dy))))))

  ;; The shortest move (dx, dy) that takes the box at (x, y) of w x h out
  ;; of every solid tile (one-way tiles do not count): 0 0 when it is in
  ;; none. A box sunk into a floor goes up; one in a corner between a wall
  ;; and a floor goes both ways at once. Exact: the free place nearest to
  ;; the box has each coordinate either unchanged or flush with a tile
  ;; edge, so only those candidates are tried, nearest first, within the
  ;; distance of the best straight move (up, down, left, right: on each
  ;; side the box is moved past the nearest solid line until it is free;
  ;; outside the map every cell is empty, so this ends). Equal distances
  ;; prefer the straight moves in that order, then less sideways motion.
  ;; The search (nearest-free-pair) gives what trying every pair of
  ;; candidates, x candidates outside and y candidates inside, would give,
  ;; in time that grows with the candidates, not with their pairs.
  (define (tile-way-out tm x y w h)
    (let* ((tw (tilemap-tile-width tm)) (th (tilemap-tile-height tm))
           (rows (row-grid tm)) (cols (column-grid tm)))
      ;; the solid line of a box nearest its side `toward` (+1: the far
      ;; side), along the axis of `grid`; #f when the box is free
      (define (blocking grid pos size across across-size tile tile-across toward)
        (let ((l0 (span-first pos tile)) (l1 (span-last pos size tile)))
          (nearest-solid-line grid (if (> toward 0) l1 l0) (if (> toward 0) l0 l1) (- toward)
                              (span-first across tile-across) (span-last across across-size tile-across))))
      (define (free? x y) (not (blocking rows y h x w th tw 1)))
      ;; The four straight moves, up, down, left and right: each moves the
      ;; box past the nearest solid line on that side until it is free,
      ;; each step farther. They are run as a race, always stepping the
      ;; one that has gone least far (of equals, the first), so that the
      ;; one that ends nearest is found without running the others to
      ;; their ends: the shortest, of equals the first in that order.
      (define (shortest-straight)
        (let ((at (vector y y x x)) (done (make-vector 4 #f)))
          ;; the squared distance runner i has gone (read from `at`: a
          ;; vector made of literal numbers would be typed as holding
          ;; fixnums by CHICKEN's optimizer, whatever is stored in it later)
          (define (gone i) (square (- (vector-ref at i) (if (fx< i 2) y x))))
          (let race ()
            (let* ((i (let pick ((i 1) (best 0) (far (gone 0)))
                        (if (fx= i 4) best
                            (let ((d (gone i)))
                              (if (< d far) (pick (fx+ i 1) i d) (pick (fx+ i 1) best far))))))
                   (p (vector-ref at i)))
              (if (vector-ref done i)
                  (if (fx< i 2) (cons 0 (- p y)) (cons (- p x) 0))
                  (let ((line (case i
                                ((0 1) (blocking rows p h x w th tw (if (fx= i 0) 1 -1)))
                                (else (blocking cols p w y h tw th (if (fx= i 2) 1 -1))))))
                    (if line
                        (vector-set! at i (case i
                                            ((0) (- (* line th) h))
                                            ((1) (* (+ line 1) th))
                                            ((2) (- (* line tw) w))
                                            (else (* (+ line 1) tw))))
                        (vector-set! done i #t))
                    (race)))))))
      (if (free? x y)
          (values 0 0)
          (let* ((best (shortest-straight))
                 (best (nearest-free-pair tm x y w h best (sqrt-ceiling (norm2 best)))))
            (values (car best) (cdr best))))))

  (define (square v) (* v v))
  (define (norm2 m) (+ (square (car m)) (square (cdr m))))
  ;; an exact integer at least sqrt(v), for v >= 0
  (define (sqrt-ceiling v)
    (let-values (((s rest) (exact-integer-sqrt (->integer (ceiling v)))))
      (if (zero? rest) s (+ s 1))))

  ;; The offsets within `reach` of pos, on one axis, that put a box of
  ;; `size` flush with a tile edge (its near side on the edge, edge - pos,
  ;; or its far side, edge - size - pos), and 0; nearest first, and of
  ;; two at the same distance the negative one. The map covers lines
  ;; first .. first+count-1 of `tile` px on this axis. An edge more than a
  ;; tile away from both ends of the map, and from both ends shifted by
  ;; the size, is skipped: there the box is outside the map or across all
  ;; of it, as at a nearer candidate, which the search below prefers
  ;; anyway. So a body of any size has at most about four candidates per
  ;; line of the map.
  (define (candidates pos size tile reach first count)
    (let* ((lines (lambda (lo hi)     ; the edges within a tile of lo .. hi (px)
                    (cons (- (->integer (floor (/ lo tile))) 1) (+ (->integer (ceiling (/ hi tile))) 1))))
           (start (* first tile)) (end (* (+ first count) tile))
           (ends (lines start end))
           (near-ends (lines (- start size) (- end size)))
           (far-ends (lines (+ start size) (+ end size)))
           (in? (lambda (k range) (<= (car range) k (cdr range))))
           (limit (+ pos size reach)))
      (define (loop-end out)
        (sort out (lambda (a b) (or (< (abs a) (abs b)) (and (= (abs a) (abs b)) (< a b))))))
      (let loop ((k (cell-of (- pos reach) tile)) (out (list 0)))
        (let ((edge (* k tile)))
          (if (> edge limit)
              (loop-end out)
              (let ((near? (or (in? k ends) (in? k near-ends)))
                    (far? (or (in? k ends) (in? k far-ends))))
                (if (or near? far?)
                    (loop (+ k 1)
                          (let ((out (if (and near? (<= (abs (- edge pos)) reach)) (cons (- edge pos) out) out)))
                            (if (and far? (<= (abs (- edge size pos)) reach)) (cons (- edge size pos) out) out)))
                    ;; on to the next range of edges that count, if any
                    (let ((next (foldl (lambda (n range)
                                         (if (and (> (car range) k) (or (not n) (< (car range) n))) (car range) n))
                                       #f (list ends near-ends far-ends))))
                      (if next
                          (loop next out)
                          (loop-end out))))))))))

  ;; The lines of the map a span [pos, pos+size) covers, counted from the
  ;; map's first line (cells of `tile` px, lines first .. first+count-1):
  ;; (lo . hi), or #f when it covers none (as nearest-solid-line clips).
  (define (map-span pos size tile first count)
    (let ((lo (max (- (span-first pos tile) first) 0))
          (hi (min (- (span-last pos size tile) first) (- count 1))))
      (and (<= lo hi) (cons lo hi))))

  ;; How many solid cells (byte 1) each rectangle of the map from its
  ;; first row and column holds: row r of the table is a u32vector whose
  ;; element c counts rows 0 .. r-1 by columns 0 .. c-1. Made the first
  ;; time a body must leave a map's tiles and kept with its grids; 4 bytes
  ;; per cell, a vector of rows so that no one vector outgrows a 32-bit
  ;; build's limit.
  (define (solid-counts tm)
    (let ((g (grids tm)))
      (or (vector-ref g 4)
          (let* ((bytes (tilemap-solid-grid tm)) (cols (tilemap-width tm)) (rows (tilemap-height tm))
                 (table (make-vector (fx+ rows 1))))
            (vector-set! table 0 (make-u32vector (fx+ cols 1) 0))
            (do ((r 0 (fx+ r 1))) ((fx= r rows))
              (let ((above (vector-ref table r)) (here (make-u32vector (fx+ cols 1) 0)) (base (fx* r cols)))
                (let loop ((c 0) (run 0))
                  (when (fx< c cols)
                    (let ((run (if (fx= 1 (u8vector-ref bytes (fx+ base c))) (fx+ run 1) run)))
                      (u32vector-set! here (fx+ c 1) (fx+ (u32vector-ref above (fx+ c 1)) run))
                      (loop (fx+ c 1) run))))
                (vector-set! table (fx+ r 1) here)))
            (vector-set! g 4 table)
            table))))

  ;; The solid cells in rows p..q, columns a..b of the map (from its
  ;; first row and column, inclusive).
  (define (solids-in table a b p q)
    (let ((top (vector-ref table p)) (bottom (vector-ref table (fx+ q 1))))
      (fx- (fx+ (u32vector-ref bottom (fx+ b 1)) (u32vector-ref top a))
           (fx+ (u32vector-ref top (fx+ b 1)) (u32vector-ref bottom a)))))

  ;; The y candidates on one side of the box: those that move it up
  ;; (negative), or the others, nearest first. Their rows move one way,
  ;; so the search below can skip over the ones a solid row blocks.
  ;; #(indices into dys, first rows, last rows, the first index whose box
  ;; covers no row of the map or #f); the first three hold only boxes that
  ;; cover a row.
  (define (dy-side dys up? y h th first count)
    (let loop ((j (fx- (vector-length dys) 1)) (ks '()) (ps '()) (qs '()) (empty #f))
      (if (fx< j 0)
          (vector (list->vector ks) (list->vector ps) (list->vector qs) empty)
          (let ((dy (vector-ref dys j)))
            (if (eq? up? (negative? dy))
                (let ((span (map-span (+ y dy) h th first count)))
                  (if span
                      (loop (fx- j 1) (cons j ks) (cons (car span) ps) (cons (cdr span) qs) empty)
                      (loop (fx- j 1) ks ps qs j)))
                (loop (fx- j 1) ks ps qs empty))))))

  ;; The first y candidate on one side whose box, over columns a..b,
  ;; holds no solid cell, among those nearer (with dx) than `bound`; #f
  ;; when none is. A blocked box's solid row farthest in the side's
  ;; direction blocks every later candidate that still covers it, and so
  ;; do the rows past it that are solid all across a..b: the search jumps
  ;; past them (binary searches on the table), so a body deep in a solid
  ;; block costs a few steps per x candidate.
  (define (side-first-free side up? table a b dx dys bound last-row)
    (let* ((ks (vector-ref side 0)) (ps (vector-ref side 1)) (qs (vector-ref side 2))
           (n (vector-length ks)) (empty (vector-ref side 3))
           (width (fx+ (fx- b a) 1))
           (near? (lambda (j) (< (+ (square dx) (square (vector-ref dys j))) bound)))
           (solids (lambda (p q) (solids-in table a b p q)))
           (full? (lambda (p q) (fx= (solids p q) (fx* width (fx+ (fx- q p) 1)))))
           ;; the first k in lo..hi-1 with (yes? k), or hi; yes? turns true once
           (bisect (lambda (lo hi yes?)
                     (let loop ((lo lo) (hi hi))
                       (if (fx>= lo hi) hi
                           (let ((mid (fx/ (fx+ lo hi) 2)))
                             (if (yes? mid) (loop lo mid) (loop (fx+ mid 1) hi)))))))
           ;; how many lines past `from`, stepping by `step`, are solid all
           ;; across (bounded by `room`)
           (solid-run (lambda (from step room)
                        (let ((run? (lambda (m) (or (fx= m 0)
                                                    (if (fx> step 0)
                                                        (full? (fx+ from 1) (fx+ from m))
                                                        (full? (fx- from m) (fx- from 1)))))))
                          (let gallop ((good 0) (try 1))
                            (let ((try (fxmin try room)))
                              (if (and (fx> try good) (run? try))
                                  (gallop try (fx* try 2))
                                  (fx- (bisect (fx+ good 1) (fxmax try (fx+ good 1))
                                               (lambda (m) (not (run? m))))
                                       1)))))))
           (found
            (let loop ((k 0))
              (and (fx< k n)
                   (let ((j (vector-ref ks k)))
                     (and (or (not empty) (fx< j empty))
                          (near? j)
                          (let ((p (vector-ref ps k)) (q (vector-ref qs k)))
                            (if (fx= 0 (solids p q))
                                j
                                (if up?
                                    ;; the topmost solid row, and the solid rows above it
                                    (let* ((r (bisect p q (lambda (m) (fx> (solids p m) 0))))
                                           (e (fx- r (solid-run r -1 r))))
                                      (loop (bisect (fx+ k 1) n (lambda (i) (fx< (vector-ref qs i) e)))))
                                    (let* ((r (fx- (bisect p (fx+ q 1) (lambda (m) (fx= 0 (solids m q)))) 1))
                                           (e (fx+ r (solid-run r 1 (fx- last-row r)))))
                                      (loop (bisect (fx+ k 1) n (lambda (i) (fx> (vector-ref ps i) e))))))))))))))
      (if (and empty (near? empty) (or (not found) (fx< empty found)))
          empty
          found)))

  ;; The search among pairs (dx, dy) of candidates: dx in order, nearest
  ;; first, and for each the first free dy, kept when nearer than the best
  ;; so far (`best` starts as the best straight move; `reach` is at least
  ;; its length).
  (define (nearest-free-pair tm x y w h best reach)
    (let* ((tw (tilemap-tile-width tm)) (th (tilemap-tile-height tm))
           (col0 (tilemap-origin-col tm)) (ncols (tilemap-width tm))
           (row0 (tilemap-origin-row tm)) (nrows (tilemap-height tm))
           (dxs (list->vector (candidates x w tw reach col0 ncols)))
           (dys (list->vector (candidates y h th reach row0 nrows)))
           (up (dy-side dys #t y h th row0 nrows))
           (down (dy-side dys #f y h th row0 nrows))
           (table (solid-counts tm)))
      (let try-x ((i 0) (best best))
        (if (or (fx= i (vector-length dxs)) (>= (square (vector-ref dxs i)) (norm2 best)))
            best
            (let* ((dx (vector-ref dxs i))
                   (bound (norm2 best))
                   (span (map-span (+ x dx) w tw col0 ncols))
                   (j (if span
                          (let ((u (side-first-free up #t table (car span) (cdr span) dx dys bound (fx- nrows 1)))
                                (d (side-first-free down #f table (car span) (cdr span) dx dys bound (fx- nrows 1))))
                            (if (and u d) (fxmin u d) (or u d)))
                          ;; a box clear of the map's columns is free at any dy
                          (and (< (norm2 (cons dx (vector-ref dys 0))) bound) 0))))
              (try-x (fx+ i 1) (if j (cons dx (vector-ref dys j)) best)))))))

  ;; Where the frame's motion started on one axis: pos less what the
  ;; velocity step moved (nothing when the body skips that step).
  (define (motion-start entity pos-key vel-key velocity-step)
    (if (entity-skips-pipeline? entity velocity-step)
        (num entity pos-key)
        (- (num entity pos-key) (num entity vel-key))))

  (define (stop-at-tiles-x scene entity)
    (let* ((tm (scene-tilemap scene))
           (swept (swept? scene entity))
           (entity (if swept
                       (leave-solids entity tm (motion-start entity #:x #:vx 'velocity-x) (num entity #:y))
                       entity)))
      (resolve-tiles entity swept #:x #:width #:vx 'velocity-x #:y #:height
                     (tilemap-tile-width tm) (tilemap-tile-height tm) (column-grid tm))))

  ;; A body that skips the x tile pass leaves solid tiles here.
  (define (stop-at-tiles-y scene entity)
    (let* ((tm (scene-tilemap scene))
           (swept (swept? scene entity))
           (entity (if (and swept (entity-skips-pipeline? entity 'tile-collisions-x))
                       (leave-solids entity tm (num entity #:x) (motion-start entity #:y #:vy 'velocity-y))
                       entity)))
      (resolve-tiles entity swept #:y #:height #:vy 'velocity-y #:x #:width
                     (tilemap-tile-height tm) (tilemap-tile-width tm) (row-grid tm))))

  (define-pipeline (resolve-tile-collisions-x tile-collisions-x) (scene entity dt)
    guard: (scene-tilemap scene)
    (stop-at-tiles-x scene entity))

  (define-pipeline (resolve-tile-collisions-y tile-collisions-y) (scene entity dt)
    guard: (scene-tilemap scene)
    (stop-at-tiles-y scene entity))

;;; Steps 2-7 in one pass

  ;; Steps 2-7 of docs/physics.org's pipeline (acceleration, gravity, velocity x, tile
  ;; collisions x, velocity y, tile collisions y) for one entity, giving
  ;; exactly what running those six steps one after the other gives: the
  ;; motion pass of a one-entity frame (below).
  (define (step-motion scene e dt)
    ((motion-pass scene dt) e))

  ;; The six steps one after the other, as the pipeline runs them. An
  ;; entity without #:skip-pipelines has each guard read once and each rule
  ;; called directly; any other runs the steps themselves.
  (define (motion-steps scene e dt)
    (if (entity-ref e #:skip-pipelines #f)  ; a list, or the steps' error
        (let* ((e (apply-acceleration scene e dt))
               (e (apply-gravity scene e dt))
               (e (apply-velocity-x scene e dt))
               (e (resolve-tile-collisions-x scene e dt))
               (e (apply-velocity-y scene e dt)))
          (resolve-tile-collisions-y scene e dt))
        (let* ((map? (scene-tilemap scene))
               (e (if (gravity-on? e) (fall scene (accelerate scene e)) e))
               (e (move-x scene e))
               (e (if map? (stop-at-tiles-x scene e) e))
               (e (move-y scene e)))
          (if map? (stop-at-tiles-y scene e) e))))

  ;; What rewrite-motion's callers pass for a key they leave as it is: the
  ;; symbol keep, which no value they write (a number or a boolean) can be.

  ;; The entity with the motion keys written: a present key is replaced
  ;; where it is, in a copy that stops after the last one (the rest is
  ;; shared); an absent key goes in front, in the order the steps would add
  ;; them (with gravity vy, ay, x, vx, y; without x, vx, y, vy), and
  ;; #:on-ground? (ground detection, after them) in front of all.
  (define (rewrite-motion e grav xp x yp y vxp vx vyp vy ayp ay onp on)
    (define (replaced? p v) (and p (not (eq? v 'keep))))
    (define (added? p v) (and (not p) (not (eq? v 'keep))))
    (let* ((n (fx+ (fx+ (fx+ (if (replaced? xp x) 1 0) (if (replaced? yp y) 1 0))
                        (if (replaced? onp on) 1 0))
                   (fx+ (fx+ (if (replaced? vxp vx) 1 0) (if (replaced? vyp vy) 1 0))
                        (if (replaced? ayp ay) 1 0))))
           (copy (let copy ((rest e) (n n))
                   (if (fx= n 0)
                       rest
                       (let ((p (car rest)))
                         (cond ((and (eq? p xp) (replaced? xp x)) (cons (cons #:x x) (copy (cdr rest) (fx- n 1))))
                               ((and (eq? p yp) (replaced? yp y)) (cons (cons #:y y) (copy (cdr rest) (fx- n 1))))
                               ((and (eq? p vxp) (replaced? vxp vx)) (cons (cons #:vx vx) (copy (cdr rest) (fx- n 1))))
                               ((and (eq? p vyp) (replaced? vyp vy)) (cons (cons #:vy vy) (copy (cdr rest) (fx- n 1))))
                               ((and (eq? p ayp) (replaced? ayp ay)) (cons (cons #:ay ay) (copy (cdr rest) (fx- n 1))))
                               ((and (eq? p onp) (replaced? onp on)) (cons (cons #:on-ground? on) (copy (cdr rest) (fx- n 1))))
                               (else (cons p (copy (cdr rest) n))))))))
           (add (lambda (p v key out) (if (added? p v) (cons (cons key v) out) out))))
      (add onp on #:on-ground?
           (if grav
               (add yp y #:y (add vxp vx #:vx (add xp x #:x (add ayp ay #:ay (add vyp vy #:vy copy)))))
               (add vyp vy #:vy (add yp y #:y (add vxp vx #:vx (add xp x #:x copy))))))))

  ;;; The motion pass of a frame

  ;; The exact twin of motion-steps (and of ground detection), in C.
  ;; CHICKEN compiles every value-producing conditional and loop of such a
  ;; body into a closure holding its two dozen live values; those closures
  ;; cost more than the arithmetic and kept the garbage collector busy.
  ;; This C allocates nothing: it reads the entity's numbers (fixnums
  ;; within +-2^40, and positions that are exact rationals of such
  ;; fixnums with denominators below 2^20, so no sum overflows) and
  ;; `flags`, puts the new values in `out` and returns which keys to write
  ;; (a key that holds its new value already is not written, as entity-set
  ;; does). Same formulas in
  ;; the same order; physics/tests/pipeline-test.scm compares the two paths. The
  ;; code is motion.c; the flags and answers are motion.h's, by name.
  ;; Each flag is a Scheme constant, so that the flag expressions of
  ;; motion-pass fold and stay closure-free (a foreign variable there cost
  ;; a fifth more instructions in the S1 crowd); the C compiler checks every
  ;; one against motion.h's value of the same name.
  (define-c-constant flag-map DS_HAS_MAP 1)
  (define-c-constant flag-gravity DS_GRAVITY 2)
  (define-c-constant flag-swept DS_SWEPT 4)
  (define-c-constant flag-ground DS_GROUND 8)
  (define-c-constant flag-x DS_HAS_X 16)
  (define-c-constant flag-y DS_HAS_Y 32)
  (define-c-constant flag-vx DS_HAS_VX 64)
  (define-c-constant flag-vy DS_HAS_VY 128)
  (define-c-constant flag-ay DS_HAS_AY 256)
  (define-c-constant flag-on DS_HAS_ON 512)
  (define-c-constant flag-not-here DS_NOT_HERE 1024)
  (define-c-constant flag-drop DS_DROP 2048)
  (define-c-constant write-x DS_WRITE_X 1)
  (define-c-constant write-y DS_WRITE_Y 2)
  (define-c-constant write-vx DS_WRITE_VX 4)
  (define-c-constant write-vy DS_WRITE_VY 8)
  (define-c-constant write-ay DS_WRITE_AY 16)
  (define-c-constant write-on DS_WRITE_ON 32)
  (define-c-constant x-ratio DS_X_RATIO 64)
  (define-c-constant y-ratio DS_Y_RATIO 128)

  (define fixnum-motion!
    (foreign-lambda scheme-object "ds_fixnum_motion" scheme-object u8vector scheme-object
                    scheme-object scheme-object scheme-object scheme-object scheme-object
                    scheme-object scheme-object scheme-object scheme-object scheme-object
                    scheme-object))

  ;; The kernel's answer for a position: 'keep, out[n-slot], or with the
  ;; ratio bit the rational out[n-slot] / out[d-slot], in lowest terms
  ;; already, so the ratnum is made without a gcd.
  (define (kernel-position out writes write-bit ratio-bit n-slot d-slot)
    (cond ((fx= 0 (fxand writes write-bit)) 'keep)
          ((fx= 0 (fxand writes ratio-bit)) (vector-ref out n-slot))
          (else (##core#inline_allocate ("C_a_i_ratnum" 3) (vector-ref out n-slot)
                                        (vector-ref out d-slot)))))

  ;; What the C code is given in a scene without a map (it reads neither).
  (define no-grid (make-u8vector 0))
  (define no-map (vector 0 0 0 0 1 1))

  ;; What every entity of a frame shares (the map's solid grid, size and
  ;; origin, the tile size, the scene's collision mode) is read once. Each
  ;; entity whose numbers the kernel takes (above), with no
  ;; #:skip-pipelines, then goes through fixnum-motion!; any other one
  ;; (flonums, other rationals, bignums, a NaN, skips, an unknown mode)
  ;; through motion-steps, the readable steps.
  ;; With ground? the pass also does ground detection (step 8), which
  ;; is only right when no entity of the scene is solid: the engine passes
  ;; it then, and only then.
  (define (motion-pass scene dt #!optional ground?)
    (let* ((tm (scene-tilemap scene))
           (map-data (and tm (pass-map tm)))
           (map? (and map-data #t))
           (bytes (if map? (tilemap-solid-grid tm) no-grid))
           (map (or map-data no-map))
           (one-way? (and map? (one-way-map? tm)))
           ;; the bits of fixnum-motion!'s flags the scene decides
           (scene-flags (fxior (if map? flag-map 0)
                               (fxior (if (and map? (swept-mode? scene '() #f)) flag-swept 0)
                                      (if ground? flag-ground 0))))
           ;; an entity's own mode replaces the scene's
           (own-mode-flags (fxand scene-flags (fxnot flag-swept)))
           (gravity *gravity*)
           (out (make-vector 8 1)))
      ;; An entity the C code leaves (see above).
      (define (general e)
        (let ((moved (motion-steps scene e dt)))
          (if ground? (detect-on-solid scene moved dt) moved)))
      (if (and tm (not map?))
          general
          (lambda (e)
            (entity-let e ((xp #:x) (yp #:y) (wp #:width) (hp #:height) (vxp #:vx) (vyp #:vy)
                           (ayp #:ay) (gp #:gravity?) (skipp #:skip-pipelines)
                           (modep #:collision-mode) (onp #:on-ground?) (dropp #:drop-through?))
              (let ((grav (and gp (cdr gp)))
                    (x (if xp (cdr xp) 0)) (y (if yp (cdr yp) 0))
                    (w (if wp (cdr wp) 0)) (h (if hp (cdr hp) 0))
                    (vx (if vxp (cdr vxp) 0)) (vy (if vyp (cdr vyp) 0))
                    (ay (if ayp (cdr ayp) 0))
                    (own (and modep (cdr modep))))
                ;; Written as plain expressions, not nested conditionals, so
                ;; that CHICKEN makes no closures here (see above).
                (let* ((flags (fxior
                               ;; an unknown mode is the tile steps' error to raise
                               (fxior (fxior (if own own-mode-flags scene-flags)
                                             (if (and one-way? dropp (cdr dropp)) flag-drop 0))
                                      (fxior (if (eq? own 'swept) flag-swept 0)
                                             (if (memq own '(#f swept discrete)) 0 flag-not-here)))
                               (fxior (fxior (if grav flag-gravity 0) (if xp flag-x 0))
                                      (fxior (fxior (if yp flag-y 0) (if vxp flag-vx 0))
                                             (fxior (if vyp flag-vy 0)
                                                    (fxior (if ayp flag-ay 0) (if onp flag-on 0)))))))
                       (writes (fixnum-motion! out bytes map flags gravity (and skipp (cdr skipp))
                                               x y w h vx vy ay (and onp (cdr onp)))))
                  (cond ((fx= writes 0) e)
                        ((fx< writes 0) (general e))
                        ((fx= 0 (fxand writes (fxior x-ratio y-ratio)))
                         (rewrite-motion e grav
                                         xp (if (fx= 0 (fxand writes write-x)) 'keep (vector-ref out 0))
                                         yp (if (fx= 0 (fxand writes write-y)) 'keep (vector-ref out 1))
                                         vxp (if (fx= 0 (fxand writes write-vx)) 'keep (vector-ref out 2))
                                         vyp (if (fx= 0 (fxand writes write-vy)) 'keep (vector-ref out 3))
                                         ayp (if (fx= 0 (fxand writes write-ay)) 'keep (vector-ref out 4))
                                         onp (if (fx= 0 (fxand writes write-on)) 'keep (vector-ref out 5))))
                        (else                   ; a rational position
                         (rewrite-motion e grav
                                         xp (kernel-position out writes write-x x-ratio 0 6)
                                         yp (kernel-position out writes write-y y-ratio 1 7)
                                         vxp (if (fx= 0 (fxand writes write-vx)) 'keep (vector-ref out 2))
                                         vyp (if (fx= 0 (fxand writes write-vy)) 'keep (vector-ref out 3))
                                         ayp (if (fx= 0 (fxand writes write-ay)) 'keep (vector-ref out 4))
                                         onp (if (fx= 0 (fxand writes write-on)) 'keep (vector-ref out 5))))))))))))

  ;; Tile ground: the row one pixel below the feet, (+ y h 1), under either
  ;; lower corner. The corners are the first and last columns the body
  ;; covers; a zero-width body on a tile edge probes the one column at x.
  ;; A one-way tile there counts when the body's bottom is at or above its
  ;; top and the body is not dropping through.
  (define (tile-ground? tm x y w h drop?)
    (let* ((th (tilemap-tile-height tm))
           (row (cell-of (+ y h 1) th))
           (c0 (span-first x (tilemap-tile-width tm)))
           (c1 (max c0 (span-last x w (tilemap-tile-width tm))))
           (platform? (and (not drop?) (<= (+ y h) (* row th)))))
      (or (tilemap-solid? tm c0 row)
          (tilemap-solid? tm c1 row)
          (and platform? (or (tilemap-one-way? tm c0 row) (tilemap-one-way? tm c1 row))))))

  ;; Entity ground: a solid entity other than the mover that overlaps it
  ;; horizontally, whose top is within the contact tolerance of the mover's
  ;; bottom, while the mover's |vy| is within *entity-ground-vy-max*.
  ;; "Other" means not the same object (eq?), as the pipeline passes them.
  (define (entity-solid-support-below? entity solids)
    (entity-ground? entity solids (num entity #:x) (num entity #:width)
                    (+ (num entity #:y) (num entity #:height)) (num entity #:vy)))

  (define (entity-ground? entity solids x w bottom vy)
    (and (pair? solids)
         (<= (abs vy) *entity-ground-vy-max*)
         (if (at-least? solids index-from)
             ;; many solids: only those whose top is near the feet
             (let* ((si (support-index solids))
                    (v (car si))
                    (tol *entity-ground-contact-tolerance*))
               (let loop ((ks (box-index-near (cdr si) x (- bottom tol) w (* 2 tol))))
                 (and (pair? ks)
                      (or (supports? (vector-ref v (car ks)) entity x w bottom vy)
                          (loop (cdr ks))))))
             (let loop ((solids solids))
               (and (pair? solids)
                    (or (supports? (car solids) entity x w bottom vy)
                        (loop (cdr solids))))))))

  (define (supports? s entity x w bottom vy)
    (and (not (eq? s entity))
         (entity-ref s #:solid? #f)
         (< x (+ (num s #:x) (num s #:width)))
         (< (num s #:x) (+ x w))
         (<= (abs (- (num s #:y) bottom))
             *entity-ground-contact-tolerance*)
         ;; a one-way platform holds no one rising through it or
         ;; dropping through it
         (or (not (entity-ref s #:one-way? #f))
             (and (>= vy 0) (not (entity-ref entity #:drop-through? #f))))))

  ;; From this many solid entities on, ground detection asks a spatial
  ;; hash of their tops (broadphase.scm) instead of walking them all for
  ;; every body: the same answer, without the cost growing with the square
  ;; of the crowd. The hash of a frame's solid list is kept while the
  ;; scene's cached list is the same object.
  (define index-from 48)

  (define (at-least? ls n)
    (let loop ((ls ls) (n n)) (or (fx= n 0) (and (pair? ls) (loop (cdr ls) (fx- n 1))))))

  (define last-support (cons #f #f))     ; (solids . (vector . index))

  (define (support-index solids)
    (if (eq? (car last-support) solids)
        (cdr last-support)
        (let* ((v (list->vector solids))
               ;; each solid as its top edge
               (index (make-box-index (vector-length v)
                                      (lambda (k)
                                        (let ((s (vector-ref v k)))
                                          (values (num s #:x) (num s #:y) (num s #:width) 0)))))
               (entry (cons v index)))
          (set! last-support (cons solids entry))
          entry)))

  ;; Ground detection (docs/physics.org, Standing on things), reading the
  ;; entity in one walk.
  (define (detect-on-solid scene entity dt)
    (entity-let entity ((gp #:gravity?) (skipp #:skip-pipelines) (known #:on-ground?)
                        (xp #:x) (yp #:y) (wp #:width) (hp #:height) (vyp #:vy))
      (if (and gp (cdr gp)
               (not (and skipp (cdr skipp) (memq 'on-solid (cdr skipp)))))
          (let* ((read (lambda (p key) (read-number entity p key)))
                 (tm (scene-tilemap scene))
                 (ground? (or (and tm (tile-ground? tm (read xp #:x) (read yp #:y)
                                                    (read wp #:width) (read hp #:height)
                                                    (entity-ref entity #:drop-through? #f)))
                              (entity-ground? entity (scene-solid-entities scene)
                                              (read xp #:x) (read wp #:width)
                                              (+ (read yp #:y) (read hp #:height))
                                              (read vyp #:vy)))))
            (if (and known (eq? (cdr known) ground?))
                entity
                (entity-set entity #:on-ground? ground?)))
          entity)))

  ;;; Entity against entity

  ;; floor(p) for an exact p, inline: a rational n/d (d > 1, in lowest
  ;; terms) is never an integer, so its floor is n quotient d, less one
  ;; below zero.
  (define-inline (integer-part p)
    (if (ratnum? p)
        (let ((q (quotient (numerator p) (denominator p))))
          (if (negative? (numerator p)) (- q 1) q))
        p))

  ;; Whether the spans [p1, p1+s1) and [p2, p2+s2) certainly do not meet,
  ;; judged by floor(p1) and floor(p2) when both are exact and both sizes
  ;; integers: p1 >= floor(p1) >= floor(p2) + 1 + s2 > p2 + s2. #f means
  ;; "not certain", and the exact comparison decides.
  (define-inline (apart-on-axis? p1 s1 p2 s2)
    (and (exact? p1) (exact? p2) (exact-integer? s1) (exact-integer? s2)
         (not (and (fixnum? p1) (fixnum? p2)))   ; integers compare fast anyway
         (let ((f1 (integer-part p1)) (f2 (integer-part p2)))
           (or (>= f1 (+ f2 1 s2)) (>= f2 (+ f1 1 s1))))))

  ;; Strict overlap: rectangles that only share an edge do not overlap.
  ;; Exact rationals (bodies pushed apart by halves) make each comparison
  ;; a multiplication of big integers, so boxes at least a pixel apart
  ;; are told apart first by the integer parts of their coordinates.
  ;; Inline for the pair pass; aabb-overlap? is the same as a procedure.
  (define-inline (boxes-overlap? x1 y1 w1 h1 x2 y2 w2 h2)
    (and (not (apart-on-axis? x1 w1 x2 w2))
         (not (apart-on-axis? y1 h1 y2 h2))
         (< x1 (+ x2 w2)) (< x2 (+ x1 w1))
         (< y1 (+ y2 h2)) (< y2 (+ y1 h1))))

  (define (aabb-overlap? x1 y1 w1 h1 x2 y2 w2 h2)
    (boxes-overlap? x1 y1 w1 h1 x2 y2 w2 h2))

  (define (overlap-1d p1 s1 p2 s2)
    (- (min (+ p1 s1) (+ p2 s2)) (max p1 p2)))

  (define (axis-keys axis)
    (if (eq? axis 'x) (values #:x #:width #:vx) (values #:y #:height #:vy)))

  ;; Whether `a` goes to the negative side of `b` on the axis: its centre is
  ;; smaller; with equal centres the later entity of the pair does.
  (define (goes-negative? a b axis a-is-later?)
    (let-values (((pos size vel) (axis-keys axis)))
      (let ((ca (+ (* 2 (num a pos)) (num a size)))
            (cb (+ (* 2 (num b pos)) (num b size))))
        (or (< ca cb) (and (= ca cb) a-is-later?)))))

  ;; Move `e` by `delta` on the axis and set that axis's velocity.
  (define (shift e axis delta velocity)
    (let-values (((pos size vel) (axis-keys axis)))
      (entity-set (entity-set e pos (+ (num e pos) delta)) vel velocity)))

  ;; The axis of least penetration; a tie goes to y.
  (define (shallow-axis a b)
    (let ((ox (overlap-1d (num a #:x) (num a #:width) (num b #:x) (num b #:width)))
          (oy (overlap-1d (num a #:y) (num a #:height) (num b #:y) (num b #:height))))
      (if (< ox oy) (values 'x ox) (values 'y oy))))

  (define (overlap-on a b axis)
    (let-values (((pos size vel) (axis-keys axis)))
      (overlap-1d (num a pos) (num a size) (num b pos) (num b size))))

  ;; Two movable bodies: each moves half the overlap away from the other
  ;; along the shallow axis, with velocity -1 / +1 on that axis.
  ;; a is the earlier entity of the pair.
  (define (push-apart a b)
    (let-values (((axis depth) (shallow-axis a b)))
      (let ((half (/ depth 2)))
        (if (goes-negative? a b axis #f)
            (values (shift a axis (- half) -1) (shift b axis half 1))
            (values (shift a axis half 1) (shift b axis (- half) -1))))))

  ;; Where an immovable body was at the start of the frame's engine update:
  ;; the pipeline's first step writes it as #:frame-start (x . y), so that
  ;; the entity step knows what the body did this frame, whatever moved it
  ;; (its velocity, a tween, a tile snap, the game).
  (define-pipeline (record-frame-start frame-start) (scene entity dt)
    guard: (entity-ref entity #:immovable? #f)
    (let ((x (num entity #:x)) (y (num entity #:y))
          (old (entity-ref entity #:frame-start #f)))
      (if (and (pair? old) (eqv? (car old) x) (eqv? (cdr old) y))
          entity
          (entity-set entity #:frame-start (cons x y)))))

  ;; How far a body moved since record-frame-start: 0 and 0 without a
  ;; record (a body that did not move, or a pipeline without that step).
  (define (frame-displacement e)
    (let ((start (entity-ref e #:frame-start #f)))
      (if (pair? start)
          (values (- (num e #:x) (car start)) (- (num e #:y) (cdr start)))
          (values 0 0))))

  ;; A movable body against an immovable one: the mover alone moves the full
  ;; overlap, and its velocity on that axis becomes 0. A mover falling onto
  ;; it (vy > 0) while its centre is above the immovable's is separated
  ;; vertically (a landing), so a rider is never shoved sideways off a
  ;; platform's edge. A mover that is not falling (a walker on the floor, a
  ;; top-down body) meets it on the shallow axis like any other contact.
  ;; A mover pushed up off an immovable body rests on it, and is carried by
  ;; that body's displacement on x this frame: a moving platform takes its
  ;; rider along, and one that did not move carries nothing.
  (define (push-off mover fixed mover-is-later?)
    (let-values (((axis depth)
                  (if (and (> (num mover #:vy) 0)
                           (< (+ (* 2 (num mover #:y)) (num mover #:height))
                              (+ (* 2 (num fixed #:y)) (num fixed #:height))))
                      (values 'y (overlap-on mover fixed 'y))
                      (shallow-axis mover fixed))))
      (let* ((up? (goes-negative? mover fixed axis mover-is-later?))
             (moved (shift mover axis (if up? (- depth) depth) 0)))
        (if (and up? (eq? axis 'y))
            (carry moved fixed)
            moved))))

  (define (carry rider platform)
    (let-values (((dx dy) (frame-displacement platform)))
      (if (zero? dx)
          rider
          (entity-set rider #:x (+ (num rider #:x) dx)))))

  ;; A lift going down: `fixed` moved down by dy > 0 this frame, so its top
  ;; swept from y - dy to y. A mover not rising, overlapping it on x, whose
  ;; bottom that top swept past (or reached) stood on it: it goes down with
  ;; it, its bottom on the lift's top and its #:vy 0, and is carried on x.
  ;; (Falling 1 px a frame, it would otherwise be left behind by any lift
  ;; faster than that.)
  (define (ride-down mover fixed dy)
    (let ((top (num fixed #:y))
          (bottom (+ (num mover #:y) (num mover #:height))))
      (if (and (>= (num mover #:vy) 0)
               (<= (- top dy) bottom top)
               (< (num mover #:x) (+ (num fixed #:x) (num fixed #:width)))
               (< (num fixed #:x) (+ (num mover #:x) (num mover #:width))))
          (carry (entity-set* mover #:y (- top (num mover #:height)) #:vy 0) fixed)
          mover)))

  (define (collides? e)
    (and (entity-ref e #:solid? #f)
         (not (entity-skips-pipeline? e 'entity-collisions))))

  ;; One pair, a before b in the entity list. Returns both, unchanged (eq?)
  ;; when they do not interact.
  (define (resolve-pair a b)
    (if (and (collides? a) (collides? b))
        (resolve-colliding-pair a b)
        (values a b)))

  ;; (entity-ref e key #f), inline: no call on the pair pass's path.
  (define-inline (flag e key)
    (let ((p (assq key e))) (and p (cdr p))))

  ;; A one-way entity (#:one-way?) is a jump-through platform, never
  ;; pushed: it stops only a mover falling onto it (vy > 0) whose bottom,
  ;; before this frame's velocity step, was at or above the platform's top
  ;; at the start of the frame (#:frame-start, else where it is). The mover
  ;; is put on its top with #:vy 0 and carried like any rider; from below
  ;; and from the side it passes through, and so does a mover with
  ;; #:drop-through?.
  (define (land-on-one-way mover platform)
    (let* ((vy (num mover #:vy))
           (start (flag platform #:frame-start))
           (top (if (pair? start) (cdr start) (num platform #:y))))
      (if (and (> vy 0)
               (not (flag mover #:drop-through?))
               (<= (+ (- (num mover #:y) vy) (num mover #:height)) top))
          (carry (entity-set* mover #:y (- (num platform #:y) (num mover #:height)) #:vy 0) platform)
          mover)))

  ;; resolve-pair for two entities known to collide (solid, not skipping):
  ;; the pass below checks that once per entity, not once per pair.
  (define (resolve-colliding-pair a b)
    (let-numbers a ((ax #:x) (ay #:y) (aw #:width) (ah #:height))
      (let-numbers b ((bx #:x) (by #:y) (bw #:width) (bh #:height))
        (if (boxes-overlap? ax ay aw ah bx by bw bh)
            (let ((a-fixed (flag a #:immovable?))
                  (b-fixed (flag b #:immovable?)))
              (cond ((flag a #:one-way?) (if (or b-fixed (flag b #:one-way?)) (values a b) (values a (land-on-one-way b a))))
                    ((flag b #:one-way?) (if a-fixed (values a b) (values (land-on-one-way a b) b)))
                    ((and a-fixed b-fixed) (values a b))
                    (a-fixed (values a (push-off b a #t)))
                    (b-fixed (values (push-off a b #f) b))
                    (else (push-apart a b))))
            (values a b)))))

  ;; All pairs i < j in list order; each pair sees the positions left by the
  ;; pairs before it. Only entities that collide take part, so a scene with
  ;; fewer than two of them costs one scan and returns the list itself.
  ;; `method`: 'all-pairs visits every pair, as docs/physics.org describes;
  ;; 'spatial-hash visits only pairs that can overlap at their turn (see
  ;; broadphase.scm), with exactly the same result; 'auto (the default)
  ;; takes the hash from `spatial-hash-threshold` colliding entities on.
  (define spatial-hash-threshold 32)

  ;; resolve-colliding-pair where a or b may be a lift going down (da, db:
  ;; how far it went, or #f).
  (define (resolve-pair-with-lifts a b da db)
    (let-values (((a1 b1) (resolve-colliding-pair a b)))
      (cond ((not (and (eq? a1 a) (eq? b1 b))) (values a1 b1))
            ((and db (not (flag a #:immovable?))) (values (ride-down a b db) b))
            ((and da (not (flag b #:immovable?))) (values a (ride-down b a da)))
            (else (values a b)))))

  ;; How far an immovable body went down this frame, or #f.
  (define (descent e)
    (and (flag e #:frame-start)
         (flag e #:immovable?)
         (let-values (((dx dy) (frame-displacement e)))
           (and (positive? dy) dy))))

  (define (resolve-entity-collisions entities #!optional (method 'auto))
    (let* ((all (list->vector entities))
           (idx (let loop ((i (- (vector-length all) 1)) (out '()))
                  (cond ((< i 0) (list->vector out))
                        ((collides? (vector-ref all i)) (loop (- i 1) (cons i out)))
                        (else (loop (- i 1) out)))))
           (n (vector-length idx))
           ;; lifts going down, by collider; #f when there is none
           (drops (let ((v (make-vector n #f)))
                    (let loop ((p 0) (any? #f))
                      (if (fx= p n)
                          (and any? v)
                          (let ((dy (descent (vector-ref all (vector-ref idx p)))))
                            (vector-set! v p dy)
                            (loop (fx+ p 1) (or any? dy))))))))
      ;; true when the pair moved
      (define (visit! p q)
        (let* ((i (vector-ref idx p)) (j (vector-ref idx q))
               (a0 (vector-ref all i)) (b0 (vector-ref all j)))
          (let-values (((a b) (if drops
                                  (resolve-pair-with-lifts a0 b0 (vector-ref drops p) (vector-ref drops q))
                                  (resolve-colliding-pair a0 b0))))
            (and (not (and (eq? a a0) (eq? b b0)))
                 (begin (vector-set! all i a)
                        (vector-set! all j b)
                        #t)))))
      ;; A lift going down is filed with the space its top swept, so that
      ;; the spatial hash visits the riders it left above it.
      (define (box p)
        (let ((e (vector-ref all (vector-ref idx p))))
          (let-numbers e ((x #:x) (y #:y) (w #:width) (h #:height))
            (let ((dy (and drops (vector-ref drops p))))
              (if dy
                  (values x (- y dy) w (+ h dy))
                  (values x y w h))))))
      (if (< n 2)
          entities
          (begin
            (case (if (eq? method 'auto)
                      (if (< n spatial-hash-threshold) 'all-pairs 'spatial-hash)
                      method)
              ((all-pairs)
               (do ((p 0 (fx+ p 1))) ((fx= p n))
                 (do ((q (fx+ p 1) (fx+ q 1))) ((fx= q n))
                   (visit! p q))))
              ((spatial-hash) (visit-pairs-in-order n box visit!))
              (else (error 'resolve-entity-collisions
                           "method must be 'auto, 'all-pairs or 'spatial-hash" method)))
            (vector->list all)))))

  ;;; Groups

  ;; The first entity with #:group-origin? and a #:group-id is its group's
  ;; origin; every other entity with that #:group-id is placed at the
  ;; origin's position plus its #:group-local-x / #:group-local-y. Ids are
  ;; compared with equal?. The origins are found in one pass and kept by id
  ;; in a hash table, so a frame costs two passes over the entities however
  ;; many groups there are.
  (define (sync-groups entities)
    (let ((origins (make-hash-table equal?)))
      (for-each (lambda (e)
                  (let ((id (and (entity-ref e #:group-origin? #f) (entity-ref e #:group-id #f))))
                    (when (and id (not (hash-table-exists? origins id)))
                      (hash-table-set! origins id e))))
                entities)
      (if (fx= 0 (hash-table-count origins))
          entities
          (map (lambda (e)
                 (let* ((id (entity-ref e #:group-id #f))
                        (o (and id (hash-table-ref/default origins id #f))))
                   (if (and o (not (eq? o e)))
                       (entity-set
                        (entity-set e #:x (+ (num o #:x) (num e #:group-local-x)))
                        #:y (+ (num o #:y) (num e #:group-local-y)))
                       e)))
               entities)))))
