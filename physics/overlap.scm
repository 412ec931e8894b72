;;; (downstroke overlap): which entities touch which.
;;;
;;; A box is an entity's #:x, #:y, #:width and #:height (a missing key reads
;;; as 0). Boxes overlap as aabb-overlap? says: strictly, so boxes that only
;;; share an edge do not (a box of zero width inside another does). Every
;;; number is checked as physics checks it: a NaN or a non-number is an
;;; error naming the entity and the key.

(module (downstroke overlap)
  (entity-overlap? entity-overlap-side scene-overlapping overlapping-pairs)

  (import scheme (chicken base) (chicken fixnum)
          (downstroke entity) (downstroke scene) (downstroke physics)
          (downstroke broadphase) (downstroke keywords))

  (define (box e)
    (values (entity-number e #:x) (entity-number e #:y)
            (entity-number e #:width) (entity-number e #:height)))

  (define (entity-overlap? a b)
    (let-values (((ax ay aw ah) (box a))
                 ((bx by bw bh) (box b)))
      (aabb-overlap? ax ay aw ah bx by bw bh)))

  ;; From which side a met b, when their boxes overlap: above, below,
  ;; left or right (a is above b: a stomp), else #f. Each box is first
  ;; taken back by its velocity (#:vx, #:vy: where this frame's motion
  ;; started); an axis on which those boxes did not overlap is the one
  ;; they met on (y first, when neither did), a on the side its centre was
  ;; then. When they overlapped on both axes already, the axis of the
  ;; smaller overlap now decides (a tie goes to y), and the centres now.
  (define (entity-overlap-side a b)
    (let-values (((ax ay aw ah) (box a))
                 ((bx by bw bh) (box b)))
      (and (aabb-overlap? ax ay aw ah bx by bw bh)
           (let* ((avx (entity-number a #:vx)) (avy (entity-number a #:vy))
                  (bvx (entity-number b #:vx)) (bvy (entity-number b #:vy))
                  (px (- ax avx)) (py (- ay avy)) (qx (- bx bvx)) (qy (- by bvy))
                  (apart? (lambda (p s q t) (not (and (< p (+ q t)) (< q (+ p s))))))
                  (overlap (lambda (p s q t) (- (min (+ p s) (+ q t)) (max p q))))
                  (vertical (lambda (p q) (if (< (+ p p ah) (+ q q bh)) 'above 'below)))
                  (horizontal (lambda (p q) (if (< (+ p p aw) (+ q q bw)) 'left 'right))))
             (cond ((apart? py ah qy bh) (vertical py qy))
                   ((apart? px aw qx bw) (horizontal px qx))
                   ((< (overlap ax aw bx bw) (overlap ay ah by bh)) (horizontal ax bx))
                   (else (vertical ay by)))))))

  ;; The entities of the scene that overlap `entity`, in scene order, not
  ;; counting `entity` itself (the same object). tag: only entities with
  ;; that tag; where: only entities the predicate accepts. One query is one
  ;; walk: no index would make it cheaper.
  (define/keywords (scene-overlapping scene entity #!key (tag #f) (where #f))
    (let-values (((x y w h) (box entity)))
      (let loop ((es (scene-entities scene)) (out '()))
        (if (null? es)
            (reverse out)
            (let ((e (car es)))
              (loop (cdr es)
                    (if (and (not (eq? e entity))
                             (or (not tag) (entity-has-tag? e tag))
                             (or (not where) (where e))
                             (let-values (((ex ey ew eh) (box e)))
                               (aabb-overlap? x y w h ex ey ew eh)))
                        (cons e out)
                        out)))))))

  ;; Below this many candidate pairs the plain double loop is cheaper than
  ;; building a spatial hash.
  (define hash-threshold 256)

  ;; Every pair (a . b), a from `as` and b from `bs`, whose boxes overlap:
  ;; in the order of `as`, and for each a in the order of `bs` (the order
  ;; of the double loop a user would write). An entity never pairs with
  ;; itself, so (overlapping-pairs es es) gives each touching pair twice,
  ;; once each way. Large lists go through a spatial hash of `bs`, so that
  ;; the cost grows with the boxes and the pairs that are close, not with
  ;; every pair.
  (define (overlapping-pairs as bs)
    (let* ((av (list->vector as)) (bv (list->vector bs))
           (m (vector-length av)) (n (vector-length bv))
           (out '()))
      (define (try! j k)
        (let ((a (vector-ref av j)) (b (vector-ref bv k)))
          (when (and (not (eq? a b)) (entity-overlap? a b))
            (set! out (cons (cons a b) out)))))
      (if (< (* m n) hash-threshold)
          (do ((j 0 (fx+ j 1))) ((fx= j m))
            (do ((k 0 (fx+ k 1))) ((fx= k n))
              (try! j k)))
          (visit-near-pairs m (lambda (j) (box (vector-ref av j)))
                            n (lambda (k) (box (vector-ref bv k)))
                            try!))
      (reverse out))))
