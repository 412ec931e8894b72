;;; Ground detection on solid entities in a crowd (docs/physics.org,
;;; "Standing on things"): from 48 solids on, the candidates near a body's
;;; feet come from a hash of their tops, and those whose numbers are
;;; fixnums or flonums are judged in C (physics/contacts.c,
;;; ds_ground_scan). Its answer must be the Scheme definition's for every
;;; kind of number, and an error where the definition raises one.

(import scheme (chicken base) (chicken format) (chicken condition)
        (downstroke test) (downstroke entity) (downstroke physics))

(define (ent . plist) (plist->entity plist))

(define seed 2929)
(define (rnd n)
  (set! seed (modulo (+ (* 1103515245 seed) 12345) 2147483648))
  (modulo (quotient seed 7) n))
(define (pick xs) (list-ref xs (rnd (length xs))))

;; docs/physics.org's rule, walking every solid, with the default
;; tolerance (5) and largest |vy| (12).
(define (reference e solids)
  (let ((x (entity-ref e #:x 0)) (w (entity-ref e #:width 0))
        (bottom (+ (entity-ref e #:y 0) (entity-ref e #:height 0))) (vy (entity-ref e #:vy 0)))
    (and (<= (abs vy) 12)
         (let loop ((ss solids))
           (and (pair? ss)
                (let ((s (car ss)))
                  (or (and (not (eq? s e)) (entity-ref s #:solid? #f)
                           (< x (+ (entity-ref s #:x 0) (entity-ref s #:width 0)))
                           (< (entity-ref s #:x 0) (+ x w))
                           (<= (abs (- (entity-ref s #:y 0) bottom)) 5)
                           (or (not (entity-ref s #:one-way? #f))
                               (and (>= vy 0)
                                    (not (entity-ref e #:drop-through? #f))
                                    (not (and (entity-ref e #:climbing? #f) (entity-ref e #:climber? #f))))))
                      (loop (cdr ss)))))))))

;; Whether every number of the body is one the rules take (finite).
(define (finite-body? e)
  (let loop ((ks '(#:x #:y #:width #:height #:vy)))
    (or (null? ks)
        (let ((v (entity-ref e (car ks) 0)))
          (and (number? v) (or (exact? v) (and (= v v) (< (abs v) +inf.0))) (loop (cdr ks)))))))

;; A coordinate near `base`, of one of the kinds: a fixnum (or a bignum
;; far out), a flonum, a rational, -0.0 at 0. Near 2^62 exact ones only:
;; the hash's cell of a flonum there is a double's quotient, which can be
;; cells away from an exact neighbour's, so the hash may miss a supporter
;; the walk finds (physics/broadphase.scm, cell-of).
(define (coordinate base)
  (let ((off (- (rnd 41) 20)))
    (case (if (< (abs base) (expt 2 60)) (rnd 7) (pick '(0 5)))
      ((0 1) (+ base off))
      ((2 3) (exact->inexact (+ base off)))
      ((4) (+ (exact->inexact (+ base off)) (pick '(0.5 0.25 -0.75 1e-9))))
      ((5) (+ base off (/ (- (rnd 7) 3) (pick '(2 3 4 1024)))))
      (else (if (= base 0) -0.0 (+ base off))))))

(define (size flonum-sizes?)
  (if (and flonum-sizes? (= (rnd 3) 0)) (pick '(12.0 0.5 3.25)) (+ 1 (rnd 16))))

(define (velocity)
  (case (rnd 6)
    ((0) (exact->inexact (- (rnd 31) 15)))
    ((1) (/ (- (rnd 61) 30) 4))
    ((2) (pick '(12.5 -12 12 -0.0 12.000000000000002)))
    (else (- (rnd 31) 15))))

;; Now and then a mover (never a solid: a solid's bad number stops the
;; hash of their tops for every body) holds a number the rules refuse.
(define (spoil e)
  (if (= (rnd 25) 0)
      (entity-set e (pick '(#:x #:y #:vy #:width)) (pick (list +nan.0 +inf.0 -inf.0 'ten)))
      e))

;; Crowds around each base: near 0, where fixnums stop being doubles
;; exactly (2^52) and beyond (2^53, 10^15), and in the bignums (2^62).
(define bases (list 0 -300 (- (expt 2 52) 10) (- (expt 2 52)) (expt 2 53) (expt 10 15) (expt 2 62)))

(define (crowd base n flonum-sizes?)
  (let make ((k 0) (out '()))
    (if (= k n)
        out
        (let* ((solid? (< (rnd 10) 8))
               (e (ent #:id k #:x (coordinate base) #:y (coordinate base)
                       #:width (size flonum-sizes?) #:height (size flonum-sizes?)
                       #:vy (velocity) #:solid? (if solid? (pick '(#t #t #t yes)) #f)
                       #:one-way? (= (rnd 10) 0) #:drop-through? (= (rnd 12) 0)
                       #:climbing? (= (rnd 8) 0) #:climber? (= (rnd 2) 0))))
          (make (+ k 1) (cons (if solid? e (spoil e)) out))))))

(define (outcome e solids)
  (handle-exceptions exn 'error (and (entity-solid-support-below? e solids) #t)))

(test-group "entity ground among many solids: the Scheme definition's answer for every kind of number"
  (let loop ((round 0) (different 0) (grounded 0) (errors 0) (first #f))
    (if (= round 28)
        (begin
          (test "28 crowds of 260 bodies, every body: identical" 0 different)
          (test-assert "many of them stand on another" (> grounded 500))
          (test-assert "and those holding a refused number raised an error" (> errors 20))
          (when first (print "ground: first difference " first)))
        (let* ((es (crowd (list-ref bases (modulo round (length bases))) 260 (= (modulo round 4) 3)))
               (solids (let keep ((es es))
                         (cond ((null? es) '())
                               ((entity-ref (car es) #:solid? #f) (cons (car es) (keep (cdr es))))
                               (else (keep (cdr es)))))))
          (let each ((bs es) (different different) (grounded grounded) (errors errors) (first first))
            (if (null? bs)
                (loop (+ round 1) different grounded errors first)
                (let* ((b (car bs))
                       (got (outcome b solids))
                       (want (if (finite-body? b) (and (reference b solids) #t) 'error)))
                  (each (cdr bs)
                        (if (eq? got want) different (+ different 1))
                        (if (eq? want #t) (+ grounded 1) grounded)
                        (if (eq? want 'error) (+ errors 1) errors)
                        (or first (and (not (eq? got want)) (list b got want)))))))))))
