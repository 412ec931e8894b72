;;; (downstroke escape): the shortest way out of solid tiles for a box that is inside them.
;;;
;;; Swept mode takes a body that starts a frame inside solid tiles out of
;;; them before it moves (docs/physics.org, "A body that starts a frame
;;; inside solid tiles"); tile-way-out is that search, exact, in time that
;;; grows with the map's lines near the box, not with the box's size.

(module (downstroke escape)
  (tile-way-out
   ;; for sibling modules only: where the escape puts a body
   escape-place
   ;; for tests only: escape.c's answer, and the search with it or without;
   ;; escape.c's test of diagonal-may-be-nearer?, and that procedure
   straight-in-c search-way-out diagonal-in-c diagonal-may-be-nearer?)

  (import scheme (chicken base) (chicken fixnum) (chicken sort) (chicken foreign) srfi-4
          (downstroke map) (downstroke tile-grid))

  (foreign-declare "#include <math.h>")
  (foreign-declare "#include \"physics/escape.c\"")

  ;; The shortest move out of solid tiles, as two values dx dy (0 0 for
  ;; a box in none): where escape-place puts the box, less where it was.
  (define (tile-way-out tm x y w h)
    (let-values (((nx ny) (escape-place tm x y w h)))
      (values (if (eqv? nx x) 0 (- nx x)) (if (eqv? ny y) 0 (- ny y)))))

  ;; Where the escape puts a box at (x, y) of w x h: the same (x, y) when
  ;; it covers no solid tile, else the nearest place where it covers none
  ;; (docs/physics.org, "A body that starts a frame inside solid tiles"):
  ;; the search's move, exact for exact numbers. With flonums the move
  ;; can round to a place a few 1e-15 px inside the tile it was to leave;
  ;; a flonum coordinate the search moved is then stepped on, one flonum
  ;; at a time in the direction of its move, until the box, computed in
  ;; flonums as the tile passes compute it, covers no solid tile (at most
  ;; a few steps), so the tile passes that follow never see it inside.
  ;; c? #f: without escape.c (tests compare the two).
  (define (escape-place tm x y w h #!optional (c? #t))
    (let-values (((dx dy) (search-way-out tm x y w h c?)))
      (if (and (eqv? dx 0) (eqv? dy 0))
          (values x y)
          (let ((tw (tilemap-tile-width tm)) (th (tilemap-tile-height tm)) (rows (row-grid tm)))
            (define (free? x y)
              (let ((known (and c? (straight-in-c tm x y w h #f))))
                (if known
                    (eq? known #t)
                    (not (nearest-solid-line rows (span-first y th) (span-last y h th) 1
                                             (span-first x tw) (span-last x w tw))))))
            (let settle ((nx (+ x dx)) (ny (+ y dy)) (tries 0))
              (if (or (fx= tries 8) (free? nx ny))
                  (values nx ny)
                  (settle (step-on nx dx) (step-on ny dy) (fx+ tries 1))))))))

  ;; The next flonum after p in the direction of d (p itself when d is 0
  ;; or p is exact).
  (define next-flonum (foreign-lambda double "nextafter" double double))
  (define (step-on p d)
    (cond ((or (eqv? d 0) (exact? p)) p)
          ((negative? d) (next-flonum p -inf.0))
          (else (next-flonum p +inf.0))))

  ;; What escape.c says of the box: #f when its numbers are not for it
  ;; (then the Scheme below decides), #t when the box covers no solid
  ;; tile; else, with race? #f, 0, and with race? #t the winner of
  ;; shortest-straight's race as 4 line + i (runner i, ended by tile line
  ;; `line`). It is the first part of the search in C: most bodies a
  ;; crowd pushes into a wall leave by a straight move, and the search
  ;; in generic arithmetic costs tens of thousands of instructions where
  ;; this costs hundreds (docs/performance.org, "The escape in C"). Only
  ;; its decisions come from C: the move's numbers are made below.
  (define straight-in-c
    (let ((race (foreign-lambda scheme-object "ds_escape_straight" u8vector scheme-object scheme-object
                                scheme-object scheme-object scheme-object scheme-object scheme-object)))
      (lambda (tm x y w h race?)
        (let ((m (pass-map tm)) (bytes (tilemap-solid-grid tm)))
          (and m (race bytes (u8vector-length bytes) m race? x y w h))))))

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
  ;; in time that grows with the candidates, not with their pairs. The
  ;; test whether the box is free and the race of the straight moves are
  ;; asked of escape.c first (straight-in-c), unless c? is #f.
  (define (search-way-out tm x y w h #!optional (c? #t))
    (let* ((tw (tilemap-tile-width tm)) (th (tilemap-tile-height tm))
           (rows (row-grid tm)) (cols (column-grid tm)))
      ;; where straight move i puts the box's coordinate on its axis when
      ;; tile line `line` blocks it: past that line
      (define (runner-place i line)
        (case i
          ((0) (- (* line th) h))
          ((1) (* (+ line 1) th))
          ((2) (- (* line tw) w))
          (else (* (+ line 1) tw))))
      ;; the move of runner i, stopped last by `line`
      (define (runner-move i line)
        (let ((p (runner-place i line)))
          (if (fx< i 2) (cons 0 (- p y)) (cons (- p x) 0))))
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
                        (vector-set! at i (runner-place i line))
                        (vector-set! done i #t))
                    (race)))))))
      (let ((known (and c? (straight-in-c tm x y w h #t))))
        (if (or (eq? known #t) (and (not known) (free? x y)))
          (values 0 0)
          (let* ((best (if known
                           (runner-move (fxand known 3) (fxshr known 2))
                           (shortest-straight)))
                 (best (if (diagonal-may-be-nearer? best x y w h tw th)
                           (nearest-free-pair tm x y w h best (sqrt-ceiling (norm2 best)))
                           best)))
            (values (car best) (cdr best)))))))

  ;; Whether a move on both axes at once could be nearer than `best`, the
  ;; nearest straight move (one of its two offsets is 0), of length d:
  ;; such a move is made of two candidates (below), each nonzero and
  ;; shorter than d, so both axes need a tile edge closer than d to a
  ;; side of the box that is not on it already. When one axis has none,
  ;; the pair search would keep `best`, and is not run: a body pushed a
  ;; little way into a wall (the common case in a crowd) costs the
  ;; straight moves only. Flonums are compared with a margin far above
  ;; their rounding, so that the answer is never a wrong "no".
  (define (diagonal-may-be-nearer? best x y w h tw th)
    (let ((d (abs (if (eqv? (car best) 0) (cdr best) (car best)))))
      (and (edge-closer-than? x w d tw) (edge-closer-than? y h d th))))

  ;; A multiple of `tile` within d of pos or of pos + size, other than
  ;; those sides themselves.
  (define (edge-closer-than? pos size d tile)
    (define (near? side)
      (let* ((margin (if (and (exact? side) (exact? d)) 0 (* 1e-9 (+ 1 (abs side) d))))
             (reach (+ d margin))
             (e (* (+ (floor (/ (- side reach) tile)) 1) tile)))   ; the first edge past side - reach
        (if (= e side)
            (< (+ e tile) (+ side reach))
            (< e (+ side reach)))))
    (or (near? pos) (near? (+ pos size))))

  ;; escape.c's diagonal-may-be-nearer? (ds_esc_diagonal_may), which the
  ;; motion kernel asks (motion.c, ds_flo_escape): 1 or 0, or #f when it
  ;; does not take the numbers. For tests, which compare the two.
  (define diagonal-in-c
    (let ((c (foreign-lambda scheme-object "ds_escape_diagonal" scheme-object scheme-object scheme-object
                             scheme-object scheme-object scheme-object scheme-object scheme-object)))
      (lambda (best x y w h tw th) (c (car best) (cdr best) x y w h tw th))))

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

)
