;;; (downstroke slopes): slope and ceiling slope tiles, the body's foot and head, and the floor under it.
;;;
;;; docs/physics.org, "Slopes". A slope cell (tilemap-slope) has a floor
;;; that is a straight line from a height at its left edge to one at its
;;; right edge. Boxes do not meet slope cells; a body's foot does: the
;;; middle of its bottom edge, (x + w/2, y + h). Near a slope the tile
;;; passes test the box without its lowest w/2 px (the most a box's
;;; corner sinks below the foot on a 45 degree floor), and the y pass
;;; puts the foot on the first floor it meets (foot-ground). Everything
;;; here is exact for exact numbers.
;;;
;;; A ceiling slope cell (tilemap-ceiling-slope) is solid above a straight
;;; line from a depth below its top at its left edge to one at its right
;;; edge. The body's head, the middle of its top edge, (x + w/2, y), meets
;;; it: the x pass stops the head where it would pass into that solid part
;;; (head-wall), the y pass of a rising body stops it on the first ceiling
;;; above (head-ceiling), and near one the tile passes test the box
;;; without its top px as well.

(module (downstroke slopes)
  (slope-surface ceiling-surface
   ;; for sibling modules only: the rules the tile passes and ground
   ;; detection read
   slope-map? ceiling-map? slope-cut foot-near-slope? foot-ground foot-on-slope? foot-slope-cell
   head-near-ceiling? head-ceiling head-wall head-ceiling-cell)

  (import scheme (chicken base) (chicken fixnum) srfi-4 (downstroke map) (downstroke tile-grid))

  ;; Whether the map has slope cells at all: a map without any pays this
  ;; one test per tile pass.
  (define (slope-map? tm) (and (tilemap-slopes tm) #t))

  ;; Whether the map has ceiling slope cells (grid byte 4): a map with
  ;; floor slopes only pays this one test per tile pass for ceilings. The
  ;; answer for the last map asked about is kept.
  (define last-ceiling (cons #f #f))     ; (tilemap . answer)
  (define (ceiling-map? tm)
    (and (tilemap-slopes tm)
         (if (eq? (car last-ceiling) tm)
             (cdr last-ceiling)
             (let* ((bytes (tilemap-solid-grid tm))
                    (answer (let loop ((i (fx- (u8vector-length bytes) 1)))
                              (and (fx>= i 0) (or (fx= 4 (u8vector-ref bytes i)) (loop (fx- i 1)))))))
               (set! last-ceiling (cons tm answer))
               answer))))

  ;; The y of the floor of slope cell (col, row) at x (any x; the line
  ;; goes on beyond the cell's edges), or #f when the cell is no slope.
  ;; Heights count up from the cell's bottom edge:
  ;;   y = (row+1)*th - (left + (right - left) * (x - col*tw) / tw)
  (define (slope-surface tm col row x)
    (let ((s (tilemap-slope tm col row)))
      (and s
           (let ((tw (tilemap-tile-width tm)) (th (tilemap-tile-height tm))
                 (l (car s)) (r (cdr s)))
             (- (* (+ row 1) th)
                (+ l (/ (* (- r l) (- x (* col tw))) tw)))))))

  ;; The y of the ceiling of ceiling slope cell (col, row) at x (the line
  ;; goes on beyond the cell's edges), or #f when the cell is no ceiling
  ;; slope. Depths count down from the cell's top edge:
  ;;   y = row*th + left + (right - left) * (x - col*tw) / tw
  (define (ceiling-surface tm col row x)
    (let ((s (tilemap-ceiling-slope tm col row)))
      (and s
           (let ((tw (tilemap-tile-width tm)) (th (tilemap-tile-height tm))
                 (l (car s)) (r (cdr s)))
             (+ (* row th) l (/ (* (- r l) (- x (* col tw))) tw))))))

  ;; How much of the bottom of a body of w x h that moved (mx, my) this
  ;; frame the tile passes leave out near a slope: w/2 + |mx| + max(my, 0),
  ;; but never more than h - 1, so that at least the body's top pixel row
  ;; still meets walls and ceilings (0 for a body at most 1 px tall).
  (define (slope-cut w mx my h) (max 0 (min (- h 1) (+ (/ w 2) (abs mx) (max my 0)))))

  ;; The map's lines lo .. hi (cells of `tile` px holding those px),
  ;; clipped to the first .. first+count-1 the map has: (values a b), a > b
  ;; when none is left.
  (define (clip lo hi tile first count)
    (values (max (cell-of lo tile) first)
            (min (cell-of hi tile) (+ first count -1))))

  ;; Whether a slope cell lies in columns holding x0 .. x1 (either order)
  ;; and rows holding the px lo .. hi: the body is near a slope.
  (define (foot-near-slope? tm x0 x1 lo hi) (cell-near? tm tilemap-slope x0 x1 lo hi))

  ;; The same for ceiling slope cells: the head is near a ceiling slope.
  (define (head-near-ceiling? tm x0 x1 lo hi) (cell-near? tm tilemap-ceiling-slope x0 x1 lo hi))

  (define (cell-near? tm cell? x0 x1 lo hi)
    (let-values (((c0 c1) (clip (min x0 x1) (max x0 x1) (tilemap-tile-width tm)
                                (tilemap-origin-col tm) (tilemap-width tm)))
                 ((r0 r1) (clip lo hi (tilemap-tile-height tm)
                                (tilemap-origin-row tm) (tilemap-height tm))))
      (let cols ((c c0))
        (and (<= c c1)
             (or (let rows ((r r0))
                   (and (<= r r1) (or (and (cell? tm c r) #t) (rows (+ r 1)))))
                 (cols (+ c 1)))))))

  ;; The first floor a foot at x meets going down from `top` to `bottom`
  ;; (px, inclusive), in the column holding x: a slope cell's floor at x,
  ;; a solid cell's top, or a one-way cell's top when that is at or below
  ;; `one-way-from` (where the foot started) and not drop?. The y of that
  ;; floor, or #f.
  (define (foot-ground tm x top bottom one-way-from drop?)
    (let* ((th (tilemap-tile-height tm))
           (col (cell-of x (tilemap-tile-width tm))))
      (let-values (((r0 r1) (clip top bottom th (tilemap-origin-row tm) (tilemap-height tm))))
        (let rows ((r r0))
          (and (<= r r1)
               (let ((level (cond ((slope-surface tm col r x) => (lambda (s) s))
                                  ((tilemap-solid? tm col r) (* r th))
                                  ((and (tilemap-one-way? tm col r) (not drop?)
                                        (<= one-way-from (* r th)))
                                   (* r th))
                                  (else #f))))
                 (if (and level (<= top level bottom))
                     level
                     (rows (+ r 1)))))))))

  ;; The slope cell (col . row) whose floor the foot of a box at (x, y)
  ;; of w x h stands on exactly, or #f: a slope cell in the foot's column,
  ;; in row floor(b/T) or ceil(b/T) - 1 (b = y + h), whose line at the
  ;; foot's x is b. Ground detection counts it; contacts name it.
  (define (foot-slope-cell tm x y w h)
    (let* ((fx (+ x (/ w 2))) (fy (+ y h))
           (th (tilemap-tile-height tm))
           (col (cell-of fx (tilemap-tile-width tm))))
      (let ((on? (lambda (r) (let ((s (slope-surface tm col r fx))) (and s (= s fy) (cons col r))))))
        (or (on? (cell-of fy th)) (on? (- (cell-ceiling fy th) 1))))))

  ;; Whether the foot of a box at (x, y) of w x h stands on a slope's
  ;; floor: ground detection counts it.
  (define (foot-on-slope? tm x y w h) (and (foot-slope-cell tm x y w h) #t))
;; The first ceiling a head at x meets going up from `bottom` (where it
  ;; started) to `top` (px, inclusive), in the column holding x: a ceiling
  ;; slope cell's line at x, or a solid cell's bottom ((row+1)*T). The y
  ;; of that ceiling (the largest in the span), or #f.
  (define (head-ceiling tm x top bottom)
    (let* ((th (tilemap-tile-height tm))
           (col (cell-of x (tilemap-tile-width tm))))
      (let-values (((r0 r1) (clip top bottom th (tilemap-origin-row tm) (tilemap-height tm))))
        (let rows ((r r1))
          (and (>= r r0)
               (let ((level (cond ((ceiling-surface tm col r x) => (lambda (s) s))
                                  ((tilemap-solid? tm col r) (* (+ r 1) th))
                                  (else #f))))
                 (if (and level (<= top level bottom))
                     level
                     (rows (- r 1)))))))))

  ;; The solid part of the cell (col, row) that a head at depth e below
  ;; the row's top would be inside of, on x: (a . b), the open span of x
  ;; where it is, or #f. A solid cell: the whole cell; a ceiling slope
  ;; cell: where its depth left + (right - left) (p - col*tw) / tw is
  ;; more than e.
  (define (inside-span tm col row e)
    (let* ((tw (tilemap-tile-width tm)) (a (* col tw)) (b (+ a tw)))
      (cond ((tilemap-solid? tm col row) (cons a b))
            ((tilemap-ceiling-slope tm col row)
             => (lambda (s)
                  (let ((l (car s)) (r (cdr s)))
                    (cond ((and (> l e) (> r e)) (cons a b))
                          ((> l e) (cons a (+ a (/ (* (- l e) tw) (- l r)))))
                          ((> r e) (cons (+ a (/ (* (- e l) tw) (- r l))) b))
                          (else #f)))))
            (else #f))))

  ;; Where a head at height y moving on x from x0 to x1 (x0 /= x1) first
  ;; passes from outside into the solid part of the cells of its row,
  ;; floor(y/T) (ceiling slopes above their line, solid cells whole): the
  ;; head's x there, or #f. The spans of neighbouring cells that meet
  ;; are one; a span the head starts inside of is not entered (it may
  ;; leave it), and one whose near end is x0 is entered at once.
  (define (head-wall tm y x0 x1)
    (let* ((th (tilemap-tile-height tm)) (tw (tilemap-tile-width tm))
           (row (cell-of y th)) (e (- y (* row th)))
           (lo (min x0 x1)) (hi (max x0 x1))
           ;; the map's columns around the path (outside it every cell is
           ;; empty), one more on each side
           (first (max (- (cell-of lo tw) 1) (- (tilemap-origin-col tm) 1)))
           (last (min (+ (cell-of hi tw) 1) (+ (tilemap-origin-col tm) (tilemap-width tm))))
           ;; their spans, merged, left to right
           (spans (let loop ((c last) (out '()))
                    (if (< c first)
                        out
                        (let ((s (inside-span tm c row e)))
                          (loop (- c 1)
                                (cond ((not s) out)
                                      ((and (pair? out) (= (cdr s) (caar out))) (cons (cons (car s) (cdar out)) (cdr out)))
                                      (else (cons s out)))))))))
      (if (> x1 x0)
          (let loop ((ss spans))
            (and (pair? ss)
                 (if (and (<= x0 (caar ss)) (< (caar ss) x1)) (caar ss) (loop (cdr ss)))))
          (let loop ((ss (reverse spans)))
            (and (pair? ss)
                 (if (and (<= (cdar ss) x0) (< x1 (cdar ss))) (cdar ss) (loop (cdr ss))))))))

  ;; The ceiling slope cell (col . row) whose line the head of a box at
  ;; (x, y) of width w touches exactly, or #f: in the head's column, row
  ;; floor(y/T) or ceil(y/T) - 1, whose line at the head's x is y.
  (define (head-ceiling-cell tm x y w)
    (let* ((hx (+ x (/ w 2)))
           (th (tilemap-tile-height tm))
           (col (cell-of hx (tilemap-tile-width tm))))
      (let ((on? (lambda (r) (let ((s (ceiling-surface tm col r hx))) (and s (= s y) (cons col r))))))
        (or (on? (cell-of y th)) (on? (- (cell-ceiling y th) 1))))))
)
