;;; (downstroke arith): integer arithmetic several modules need, written
;;; once and expanded where it is used (a call across modules would cost
;;; the per-frame steps more than the arithmetic).
;;;
;;; (floor-div a d): floor(a / d) for an integer a and a positive integer
;;; d; fixnums take the fast path, bignums generic-floor-div. C has its
;;; twin, ds_floor_div in physics/arith.h.

(module (downstroke arith)
  (floor-div generic-floor-div)

  (import scheme (chicken base) (chicken fixnum))

  (define (generic-floor-div a d)
    (let ((q (quotient a d)))
      (if (and (negative? a) (not (zero? (remainder a d)))) (- q 1) q)))

  (define-syntax floor-div
    (syntax-rules ()
      ((_ a d)
       (let ((n a) (m d))
         (if (and (fixnum? n) (fixnum? m))
             (if (fx>= n 0) (fx/ n m) (fx- (fx/ (fx+ n 1) m) 1))
             (generic-floor-div n m)))))))
