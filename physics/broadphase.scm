;;; (downstroke broadphase): visit pairs of moving boxes in list order,
;;; without visiting every pair.
;;;
;;; The entity-collision step must behave exactly like the all-pairs walk
;;; of docs/physics.org (Solid entities): pairs (p, q) with p < q in order, each seeing the
;;; positions left by the pairs before it. `visit-pairs-in-order` calls
;;; (visit! p q) in that same order for a subset of the pairs that always
;;; includes every pair whose boxes overlap when its turn comes; skipping
;;; the others is safe because visiting a non-overlapping pair does nothing.
;;;
;;; How: a spatial hash of square cells. Before row p, the candidates are
;;; the boxes sharing a cell with p. During row p only p and the current q
;;; move; whenever p moves into other cells, those cells are asked again, so
;;; a box that p reaches later in the row is still visited at its turn.
;;; Boxes much larger than a cell are kept aside and visited by everyone.

(module (downstroke broadphase)
  (;; for sibling modules only: physics' entity step and ground detection,
   ;; and the overlap queries
   visit-pairs-in-order visit-near-pairs make-box-index box-index-near
   box-index-gather! box-index-buffer)

  (import scheme (chicken base) (chicken fixnum) (chicken foreign) (downstroke arith))

  ;; A box spanning more cells than this on an axis is "large".
  (define large-span 16)

  (define (->integer v) (if (exact? v) v (inexact->exact v)))
  ;; floor(v / size); integers the common case, without making a rational.
  ;; An exact v = n/d (bodies pushed apart by halves soon have such
  ;; coordinates) with an integer size is floor(n / (d size)): integer
  ;; division, no new rational.
  (define (cell-of v size)
    (cond ((and (fixnum? v) (fixnum? size)) (floor-div v size))
          ((and (exact? v) (exact-integer? size))
           (floor-div (numerator v) (* (denominator v) size)))
          (else (->integer (floor (/ v size))))))

  ;; (cell-of (+ v w) size); for v = n/d and integers w and size that is
  ;; floor((n + w d) / (d size)), without making the rational v + w.
  (define (end-cell v w size)
    (if (and (not (fixnum? v)) (exact? v) (exact-integer? w) (exact-integer? size))
        (let ((d (denominator v)))
          (floor-div (+ (numerator v) (* w d)) (* d size)))
        (cell-of (+ v w) size)))

  ;; Cell indices are fixnums unless a box is astronomically far out; the
  ;; step past the largest fixnum goes on in bignums.
  (define-inline (cell> a b)
    (if (and (fixnum? a) (fixnum? b)) (fx> a b) (> a b)))
  (define-inline (cell+1 a)
    (if (and (fixnum? a) (fx< a most-positive-fixnum)) (fx+ a 1) (+ a 1)))

  ;; The C of this module is broadphase.c.
  (foreign-declare "#include \"physics/broadphase.c\"")

  ;; The common case of span-of in C: coordinates that are fixnums,
  ;; rationals of fixnums or flonums (with cell-of's double operations),
  ;; integer sizes and cell size. Fills `span` with the cells
  ;; #(cx0 cy0 cx1 cy1) and returns 1, or 2 for a large box; 0 means "not
  ;; this case" (bignums, a rational or flonum cell size, a cell beyond the
  ;; fixnums) and
  ;; the Scheme code decides. Computing the cells in Scheme made a closure
  ;; for every value a branch could have handed to a procedure call.
  (define fast-span!
    (foreign-lambda scheme-object "ds_span" scheme-object scheme-object scheme-object
                    scheme-object scheme-object scheme-object scheme-object))

  ;; Both 'large, or both the same four fixnum cells.
  (define same-span?
    (foreign-lambda bool "ds_same_span" scheme-object scheme-object))

  ;; The bucket of a cell of fixnum indices, for filing and for gathering.
  ;; gather-cells! is gather's common case: p's span four fixnum cells. It
  ;; walks p's cells and the large boxes, stamps each box after `after` not
  ;; yet stamped for row p, puts them in `buf` in ascending order and
  ;; returns how many; -1 means "not this case". The buckets are lists of
  ;; fixnums, which C reads as they are; it writes only fixnums.
  (define unfile!
    (foreign-lambda scheme-object "ds_unfile" scheme-object scheme-object scheme-object scheme-object))
  (define fixnum-span-bit (foreign-lambda scheme-object "ds_fixnum_span" scheme-object))
  (define fixnum-bucket (foreign-lambda scheme-object "ds_bucket" scheme-object scheme-object scheme-object))
  (define gather-cells!
    (foreign-lambda scheme-object "ds_gather" scheme-object scheme-object scheme-object
                    scheme-object scheme-object scheme-object scheme-object scheme-object))

  ;; span-of for any numbers: generic arithmetic.
  (define (slow-span x y w h size)
    (let ((cx0 (cell-of x size)) (cy0 (cell-of y size))
          (cx1 (end-cell x w size)) (cy1 (end-cell y h size)))
      (if (or (> (- cx1 cx0) large-span) (> (- cy1 cy0) large-span))
          'large
          (vector cx0 cy0 cx1 cy1))))

  (define (bucket-of cx cy mask)
    (if (and (fixnum? cx) (fixnum? cy))
        (fixnum-bucket cx cy mask)
        (modulo (+ (* cx 73856093) (* cy 19349663)) (+ mask 1))))

  ;; The cells #(cx0 cy0 cx1 cy1) of a box, or 'large.
  (define (span-of-box x y w h size)
    (let* ((span (make-vector 4 0))
           (fast (fast-span! span x y w h size large-span)))
      (cond ((eq? fast 1) span)
            ((eq? fast 2) 'large)
            (else (slow-span x y w h size)))))

  (define (for-each-cell span mask proc)
    (do ((cy (vector-ref span 1) (cell+1 cy))) ((cell> cy (vector-ref span 3)))
      (do ((cx (vector-ref span 0) (cell+1 cx))) ((cell> cx (vector-ref span 2)))
        (proc (bucket-of cx cy mask)))))

  ;; Put box k in the bucket of every cell of its (not large) span.
  (define (file-box! buckets mask k span)
    (if (eq? (fixnum-span-bit span) 1)
        ;; loops of fixnums, no closure per cell; they stop at the last
        ;; cell, never stepping past the largest fixnum
        (let ((cx0 (vector-ref span 0)) (cy0 (vector-ref span 1))
              (cx1 (vector-ref span 2)) (cy1 (vector-ref span 3)))
          (unless (or (fx> cx0 cx1) (fx> cy0 cy1))
            (let rows ((cy cy0))
              (let cols ((cx cx0))
                (let ((b (fixnum-bucket cx cy mask)))
                  (vector-set! buckets b (cons k (vector-ref buckets b))))
                (unless (fx= cx cx1) (cols (fx+ cx 1))))
              (unless (fx= cy cy1) (rows (fx+ cy 1))))))
        (for-each-cell span mask (lambda (b) (vector-set! buckets b (cons k (vector-ref buckets b)))))))

  ;; Add to the ascending `queue` every box after `after` in the large
  ;; boxes or in a bucket of `span`, not yet stamped with p (and stamp it).
  (define (gather-near p after span queue buckets large stamp mask buf)
    (define (add-all ls queue)
      (if (null? ls)
          queue
          (add-all (cdr ls)
                   (let ((q (car ls)))
                     (if (and (fx> q after) (not (fx= (vector-ref stamp q) p)))
                         (begin (vector-set! stamp q p) (insert q queue))
                         queue)))))
    (let ((count (gather-cells! buf p after span buckets large stamp mask)))
      (cond ((and (fx>= count 0) (null? queue))
             (let build ((i (fx- count 1)) (out '()))
               (if (fx< i 0) out (build (fx- i 1) (cons (vector-ref buf i) out)))))
            ((fx>= count 0)
             (let merge ((i 0) (queue queue))
               (if (fx= i count) queue (merge (fx+ i 1) (insert (vector-ref buf i) queue)))))
            (else
             (let rows ((cy (vector-ref span 1)) (queue (add-all large queue)))
               (if (cell> cy (vector-ref span 3))
                   queue
                   (let cols ((cx (vector-ref span 0)) (queue queue))
                     (if (cell> cx (vector-ref span 2))
                         (rows (cell+1 cy) queue)
                         (cols (cell+1 cx) (add-all (vector-ref buckets (bucket-of cx cy mask)) queue))))))))))

  ;; n boxes numbered 0..n-1; (box k) returns the current (values x y w h);
  ;; (visit! p q) may move boxes p and q, and returns true when it did
  ;; (only then are their cells looked at again).
  (define (visit-pairs-in-order n box visit!)
    (let* ((size (cell-size n box))
           (buckets (make-vector (bucket-count n) '()))
           (mask (- (vector-length buckets) 1))
           (spans (make-vector n #f))          ; #(cx0 cy0 cx1 cy1) or 'large
           (stamp (make-vector n -1)))
      (define (span-of k)
        (let-values (((x y w h) (box k)))
          (span-of-box x y w h size)))
      (define large '())                      ; indices, ascending
      (define (register! k span)
        (vector-set! spans k span)
        (if (eq? span 'large)
            (set! large (insert k large))
            (file-box! buckets mask k span)))
      (define (unregister! k)
        (let ((span (vector-ref spans k)))
          (cond ((eq? span 'large) (set! large (remove-one k large)))
                ((eq? (fixnum-span-bit span) 1) (unfile! k span buckets mask))
                (else
                 (for-each-cell span mask (lambda (b) (vector-set! buckets b (remove-one k (vector-ref buckets b)))))))))
      ;; Re-file box k if its cells changed; #t when they did. Most visits
      ;; move a box within its cells.
      (define (refresh! k)
        (let ((old (vector-ref spans k))
              (new (span-of k)))
          (and (not (same-span? old new))
               (begin (unregister! k) (register! k new) #t))))
      ;; Add to the ascending `queue` every box after `after` sharing a cell
      ;; with p, or large, not yet queued in row p.
      (define buf (make-vector n 0))
      (define (gather p after queue)
        (gather-near p after (vector-ref spans p) queue buckets large stamp mask buf))
      (do ((k 0 (fx+ k 1))) ((fx= k n)) (register! k (span-of k)))
      (do ((p 0 (fx+ p 1))) ((fx= p n))
        (if (eq? (vector-ref spans p) 'large)
            ;; a large box meets everyone after it
            (do ((q (fx+ p 1) (fx+ q 1))) ((fx= q n))
              (when (visit! p q)
                (refresh! q)
                (refresh! p)))
            (let row ((queue (gather p p '())))
              (unless (null? queue)
                (let* ((q (car queue))
                       (moved? (visit! p q)))
                  (when moved? (refresh! q))
                  (row (cond ((not (and moved? (refresh! p))) (cdr queue))
                             ((eq? (vector-ref spans p) 'large)
                              ;; p grew large mid-row: everyone after q
                              (let tail ((r (- n 1)) (out '()))
                                (if (fx<= r q) out (tail (fx- r 1) (cons r out)))))
                             (else (gather p q (cdr queue))))))))))))

  ;; Boxes that do not move, filed once and asked about many times: n boxes
  ;; numbered 0..n-1, (box k) giving (values x y w h).
  (define-record-type box-index
    (%make-box-index n size buckets mask stamp buf large queries span)
    box-index?
    (n index-n) (size index-size) (buckets index-buckets) (mask index-mask)
    (stamp index-stamp) (buf index-buf) (large index-large)
    (queries index-queries index-queries-set!) (span index-span))

  (define (make-box-index n box)
    (let* ((size (cell-size n box))
           (buckets (make-vector (bucket-count n) '()))
           (mask (- (vector-length buckets) 1))
           (large (let file ((k (fx- n 1)) (large '()))
                    (if (fx< k 0)
                        large
                        (let ((span (let-values (((x y w h) (box k))) (span-of-box x y w h size))))
                          (if (eq? span 'large)
                              (file (fx- k 1) (cons k large))
                              (begin (file-box! buckets mask k span)
                                     (file (fx- k 1) large))))))))
      (%make-box-index n size buckets mask (make-vector (max n 1) -1) (make-vector (max n 1) 0) large 0
                       (make-vector 4 0))))

  ;; The boxes sharing a hash cell with the box x y w h (a superset of
  ;; those it overlaps), ascending, each once.
  (define (box-index-near index x y w h)
    (let ((q (index-queries index))
          (span (span-of-box x y w h (index-size index))))
      (index-queries-set! index (fx+ q 1))
      (if (eq? span 'large)
          (let all ((k (fx- (index-n index) 1)) (out '()))
            (if (fx< k 0) out (all (fx- k 1) (cons k out))))
          (gather-near q -1 span '() (index-buckets index) (index-large index)
                       (index-stamp index) (index-mask index) (index-buf index)))))

  ;; box-index-near's common case without a new list or vector: the query
  ;; box's span four fixnum cells, not large. The boxes it would list are
  ;; put in (box-index-buffer index), ascending, and their count returned;
  ;; -1 otherwise, and box-index-near answers. The buffer holds them until
  ;; the next query.
  (define (box-index-gather! index x y w h)
    (let ((span (index-span index)))
      (if (eq? (fast-span! span x y w h (index-size index) large-span) 1)
          (let ((q (index-queries index)))
            (index-queries-set! index (fx+ q 1))
            (gather-cells! (index-buf index) q -1 span (index-buckets index) (index-large index)
                           (index-stamp index) (index-mask index)))
          -1)))

  (define (box-index-buffer index) (index-buf index))

  ;; m query boxes, (query j) giving (values x y w h), against n filed
  ;; boxes: calls (found j k) for every filed box near query j, j ascending
  ;; and, for each j, k ascending, each pair once. The cost grows with the
  ;; boxes filed and asked and with the pairs that are close.
  (define (visit-near-pairs m query n box found)
    (when (fx> n 0)
      (let ((index (make-box-index n box)))
        (do ((j 0 (fx+ j 1))) ((fx= j m))
          (let-values (((x y w h) (query j)))
            (for-each (lambda (k) (found j k)) (box-index-near index x y w h)))))))

  ;; Cells about twice the mean box size keep a few boxes per cell. The
  ;; size is rounded up to an integer, which the C of fast-span! takes: a
  ;; mean of sizes that are not all alike is a rational, and a rational
  ;; cell size left every box to the generic arithmetic. Any size gives
  ;; the same pairs; only how many are asked changes.
  (define (cell-size n box)
    (let loop ((k 0) (total 0))
      (if (fx= k n)
          (let ((mean (/ total n)))
            (cond ((not (and (real? mean) (> mean 0))) 1)
                  ((exact? mean) (ceiling (* 2 mean)))
                  ((< mean 1e15) (inexact->exact (ceiling (* 2 mean))))
                  (else (* 2 mean))))
          (let-values (((x y w h) (box k)))
            (loop (fx+ k 1) (+ total (max w h)))))))

  (define (bucket-count n)
    (let loop ((m 16)) (if (>= m (* 2 n)) m (loop (* m 2)))))

  (define (insert k ls)
    (cond ((null? ls) (list k))
          ((fx< k (car ls)) (cons k ls))
          ((fx= k (car ls)) ls)
          (else (cons (car ls) (insert k (cdr ls))))))

  (define (remove-one k ls)
    (cond ((null? ls) '())
          ((fx= k (car ls)) (cdr ls))
          (else (cons (car ls) (remove-one k (cdr ls)))))))
