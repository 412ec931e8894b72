;;; Included by physics/tests/slopes-test.scm and ceilings-test.scm: walks
;;; at every speed the slope rules guarantee, and where each one stops.

;; The walking speeds, 1 px/frame and up, that docs/physics.org's slope
;; rules guarantee for a body w px wide and h tall: w/2 + vx + 1 <= h - 1.
(define (guaranteed-speeds w h)
  (let loop ((vx 1) (out '()))
    (if (> (+ (/ w 2) vx 1) (- h 1))
        (reverse out)
        (loop (+ vx 1) (cons vx out)))))

;; Where a walk from x0 at vx px/frame stops when the body fits only while
;; its x is at most `last`: the last of its steps there.
(define (last-step x0 last vx)
  (+ x0 (* vx (quotient (- last x0) vx))))
