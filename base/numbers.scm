;;; (downstroke numbers): the numbers a game hands the library, checked
;;; where they enter, and arithmetic on them that does not overflow where
;;; its answer fits.
;;;
;;;   (finite-real? v)           v is a real number, not NaN or an infinity
;;;                              (exact numbers always are)
;;;   (check-finite where what v)  v when finite-real?, else the error
;;;                              "WHERE: WHAT V must be a finite number";
;;;                              WHERE names the source (make-camera, an
;;;                              entity, a map's file and layer), WHAT the
;;;                              keyword or key
;;;   (lerp a b t)               the point t of the way from a to b
;;;
;;; A finite flonum can still overflow later: 1e308 + 1e308 is +inf.0,
;;; and (b - a) is infinite for a = -1e308, b = 1e308 although every point
;;; between them is a flonum. lerp computes a + t(b - a), exact for exact
;;; numbers and a itself at t = 0, and only when b - a overflows
;;; a(1 - t) + bt, which stays within [a, b] for t in [0, 1].

(module (downstroke numbers)
  (finite-real? check-finite lerp)

  (import scheme (chicken base) (chicken format))

  (define (finite-real? v) (and (real? v) (or (exact? v) (finite? v))))

  (define (check-finite where what v)
    (if (finite-real? v)
        v
        (error (sprintf "~a: ~a ~s must be a finite number" where what v))))

  (define (lerp a b t)
    (let ((d (- b a)))
      (if (or (exact? d) (finite? d))
          (+ a (* t d))
          (+ (* a (- 1 t)) (* b t))))))
