;;; (downstroke touch): what a body touches, per side, and since when.
;;;
;;; docs/physics.org, "Contacts". An entity that asks (#:contacts? #t) gets
;;; #:contacts written after the frame's collisions: one entry per side it
;;; touches, (side frames tiles entities). Touching is exact: the side lies
;;; on the face of a solid tile or a solid entity, with a strict overlap
;;; along that face. Nothing here runs for an entity that does not ask,
;;; and the engine runs the step only when one does.

(module (downstroke touch)
  (detect-contacts entity-touching? entity-touch-began? entity-touch-frames
   entity-touch-tiles entity-touch-entities)

  (import scheme (chicken base) (chicken fixnum) (chicken foreign)
          (downstroke entity) (downstroke scene) (downstroke map)
          (downstroke body) (downstroke tile-grid)
          (only (downstroke tile-collisions) slope-cut-of ceiling-cut-of)
          (only (downstroke slopes) slope-map? ceiling-map? foot-slope-cell head-ceiling-cell))

  (foreign-declare "#include \"physics/body.h\"")

  (define sides '(floor ceiling left right))

  ;; The line index of a coordinate that lies exactly on a grid line of
  ;; `tile` px, or #f.
  (define (on-line pos tile)
    (let ((q (/ pos tile)))
      (and (integer? q) (->integer q))))

  ;; What a touched tile is: its kind, else solid, ladder (a ladder's
  ;; one-way top), slope or one-way.
  (define (tile-name tm col row)
    (or (tilemap-kind tm col row)
        (cond ((tilemap-solid? tm col row) 'solid)
              ((tilemap-ladder? tm col row) 'ladder)
              ((tilemap-ceiling-slope tm col row) 'slope)
              ((tilemap-one-way? tm col row) 'one-way)
              (else 'slope))))

  ;; The tiles of line `line` across cells lo..hi that hold a body's side:
  ;; solid ones, and one-way ones when one-way? (a floor). `slope`: the
  ;; slope cell (col . row) the foot (head) is on, or #f; it is named in
  ;; its column's place, before that column's cell on the line.
  (define (touched-tiles tm line lo hi row-line? one-way? #!optional slope)
    (let loop ((c hi) (out '()) (slope slope))
      (if (< c lo)
          (dedupe (if slope (cons (tile-name tm (car slope) (cdr slope)) out) out))
          (let* ((col (if row-line? c line)) (row (if row-line? line c))
                 (out (if (or (tilemap-solid? tm col row)
                              (and one-way? (tilemap-one-way? tm col row)))
                          (cons (tile-name tm col row) out)
                          out))
                 (here? (and slope (= (car slope) c))))
            (loop (- c 1)
                  (if here? (cons (tile-name tm (car slope) (cdr slope)) out) out)
                  (and (not here?) slope))))))

  (define (dedupe ls)
    (let loop ((ls ls) (out '()))
      (cond ((null? ls) (reverse out))
            ((memq (car ls) out) (loop (cdr ls) out))
            (else (loop (cdr ls) (cons (car ls) out))))))

  ;; The tiles one side of the box touches: the side on a grid line, and
  ;; the cells beyond it along the side's span.
  (define (side-tiles tm side x y w h drop?)
    (let ((tw (tilemap-tile-width tm)) (th (tilemap-tile-height tm)))
      (case side
        ;; a foot exactly on a slope's line touches that slope cell
        ((floor) (let ((r (on-line (+ y h) th))
                       (slope (and (slope-map? tm) (foot-slope-cell tm x y w h))))
                   (cond (r (touched-tiles tm r (span-first x tw) (span-last x w tw) #t (not drop?) slope))
                         (slope (list (tile-name tm (car slope) (cdr slope))))
                         (else '()))))
        ;; a head exactly on a ceiling slope's line touches that cell
        ((ceiling) (let ((r (on-line y th))
                         (slope (and (ceiling-map? tm) (head-ceiling-cell tm x y w))))
                     (cond (r (touched-tiles tm (- r 1) (span-first x tw) (span-last x w tw) #t #f slope))
                           (slope (list (tile-name tm (car slope) (cdr slope))))
                           (else '()))))
        ((left) (let ((c (on-line x tw)))
                  (if c (touched-tiles tm (- c 1) (span-first y th) (span-last y h th) #f #f) '())))
        (else (let ((c (on-line (+ x w) tw)))
                (if c (touched-tiles tm c (span-first y th) (span-last y h th) #f #f) '()))))))

  ;; Whether solid entity s touches the body's side: s's face on it, and
  ;; the two overlapping strictly along it. A one-way entity is touched
  ;; only by a floor, not by a body dropping through it.
  (define (entity-on-side? s side x y w h drop?)
    (let ((sx (num s #:x)) (sy (num s #:y)) (sw (num s #:width)) (sh (num s #:height)))
      (case side
        ((floor) (and (= sy (+ y h)) (< sx (+ x w)) (< x (+ sx sw))
                      (not (and drop? (entity-ref s #:one-way? #f)))))
        ((ceiling) (and (= (+ sy sh) y) (< sx (+ x w)) (< x (+ sx sw))
                        (not (entity-ref s #:one-way? #f))))
        ((left) (and (= (+ sx sw) x) (< sy (+ y h)) (< y (+ sy sh))
                     (not (entity-ref s #:one-way? #f))))
        (else (and (= sx (+ x w)) (< sy (+ y h)) (< y (+ sy sh))
                   (not (entity-ref s #:one-way? #f)))))))

  (define (entity-name s) (or (entity-ref s #:id #f) (entity-ref s #:type #f)))

  ;; The pipeline step: #:contacts, from the map, the scene's solid
  ;; entities and the body's own #:contacts of the frame before.
  (define-pipeline (detect-contacts contacts) (scene entity dt)
    guard: (entity-ref entity #:contacts? #f)
    (let* ((tm (scene-tilemap scene))
           (x (num entity #:x)) (y (num entity #:y))
           (w (num entity #:width)) (h (num entity #:height))
           (drop? (entity-ref entity #:drop-through? #f))
           ;; near a slope the sides are the box the tile passes test, the
           ;; body's without its lowest px (docs/physics.org, "Slopes"): the
           ;; flat tile at a slope's top is not a wall to a body on the slope;
           ;; near a ceiling slope, without its top px too
           (cut (if tm (slope-cut-of tm entity 0 0) 0))
           (top-cut (or (and tm (ceiling-cut-of tm entity 0 0 cut)) 0))
           (side-y (+ y top-cut))
           (side-h (- h cut top-cut))
           (before (entity-ref entity #:contacts '()))
           (now (let loop ((ss sides) (out '()))
                  (if (null? ss)
                      (reverse out)
                      (let* ((side (car ss))
                             (tiles (cond ((not tm) '())
                                          ((memq side '(left right)) (side-tiles tm side x side-y w side-h drop?))
                                          (else (side-tiles tm side x y w h drop?))))
                             (bodies (let walk ((es (scene-solid-entities scene)) (acc '()))
                                       (cond ((null? es) (reverse acc))
                                             ((and (not (eq? (car es) entity))
                                                   (entity-on-side? (car es) side x y w h drop?))
                                              (walk (cdr es) (cons (entity-name (car es)) acc)))
                                             (else (walk (cdr es) acc))))))
                        (loop (cdr ss)
                              (if (or (pair? tiles) (pair? bodies))
                                  (let ((old (assq side before)))
                                    (cons (list side (if old (+ (cadr old) 1) 1) tiles bodies) out))
                                  out)))))))
      (if (and (null? now) (null? before))
          (if (assq #:contacts entity) entity (entity-set entity #:contacts '()))
          (entity-set entity #:contacts now))))

  (define (entry e side)
    (let ((cs (entity-ref e #:contacts '())))
      (and (pair? cs) (assq side cs))))

  ;; Whether the body touched that side (floor, ceiling, left or right) at
  ;; the end of the last frame.
  (define (entity-touching? e side) (and (entry e side) #t))
  ;; Whether that contact began in the last frame.
  (define (entity-touch-began? e side) (let ((c (entry e side))) (and c (= 1 (cadr c)))))
  ;; For how many frames in a row the side has touched (0: it does not).
  (define (entity-touch-frames e side) (let ((c (entry e side))) (if c (cadr c) 0)))
  ;; What the tiles on that side are: kinds, else solid or one-way.
  (define (entity-touch-tiles e side) (let ((c (entry e side))) (if c (caddr c) '())))
  ;; The #:id (else #:type) of each solid entity on that side.
  (define (entity-touch-entities e side) (let ((c (entry e side))) (if c (cadddr c) '())))
)
