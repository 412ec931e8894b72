;;; (downstroke slopes): slope tiles, the body's foot, and the ground under it.
;;;
;;; docs/physics.org, "Slopes". A slope cell (tilemap-slope) has a floor
;;; that is a straight line from a height at its left edge to one at its
;;; right edge. Boxes do not meet slope cells; a body's foot does: the
;;; middle of its bottom edge, (x + w/2, y + h). Near a slope the tile
;;; passes test the box without its lowest w/2 px (the most a box's
;;; corner sinks below the foot on a 45 degree floor), and the y pass
;;; puts the foot on the first floor it meets (foot-ground). Everything
;;; here is exact for exact numbers.

(module (downstroke slopes)
  (slope-surface
   ;; for sibling modules only: the rules the tile passes and ground
   ;; detection read
   slope-map? slope-cut foot-near-slope? foot-ground foot-on-slope? foot-slope-cell)

  (import scheme (chicken base) (downstroke map) (downstroke tile-grid))

  ;; Whether the map has slope cells at all: a map without any pays this
  ;; one test per tile pass.
  (define (slope-map? tm) (and (tilemap-slopes tm) #t))

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
  (define (foot-near-slope? tm x0 x1 lo hi)
    (let-values (((c0 c1) (clip (min x0 x1) (max x0 x1) (tilemap-tile-width tm)
                                (tilemap-origin-col tm) (tilemap-width tm)))
                 ((r0 r1) (clip lo hi (tilemap-tile-height tm)
                                (tilemap-origin-row tm) (tilemap-height tm))))
      (let cols ((c c0))
        (and (<= c c1)
             (or (let rows ((r r0))
                   (and (<= r r1) (or (and (tilemap-slope tm c r) #t) (rows (+ r 1)))))
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
)
