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

;; What each walk at `speeds` should give: (vx where-it-stops #t), for a
;; walk from x0 by a body that fits while its x is at most `last`.
(define (walks-wanted speeds x0 last)
  (map (lambda (vx) (list vx (last-step x0 last vx) #t)) speeds))

;; What each walk gave: (vx its-last-x every-frame-ok?). walk: a speed's
;; frames, each a list starting (x y ...); ok?: of one frame.
(define (walks-got speeds walk ok?)
  (map (lambda (vx)
         (let loop ((fs (walk vx)) (all? #t))
           (if (null? (cdr fs))
               (list vx (car (car fs)) (and all? (ok? (car fs)) #t))
               (loop (cdr fs) (and all? (ok? (car fs)))))))
       speeds))
