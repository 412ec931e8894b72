;;; Bodies against bodies in a crowd, where physics/contacts.c answers for
;;; boxes of fixnums and flonums: its answers must be the Scheme
;;; definitions' for every kind of number, and an error where those raise
;;; one.
;;; Ground detection (docs/physics.org, "Standing on things"): from 48
;;; solids on, the candidates near a body's feet come from a hash of their
;;; tops, judged in C (ds_ground_scan).
;;; The pair pass (docs/physics.org, "Solid entities"): a pair the hash
;;; offers whose boxes do not overlap is left in C (ds_kept_apart).

(import scheme (chicken base) (chicken format) (chicken condition)
        (downstroke test) (downstroke entity) (downstroke physics) (chicken fixnum)
        (only (downstroke contacts) push-apart/scheme push-apart/c push-keys))

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

;; docs/physics.org's pair walk: every pair i < j of colliding entities in
;; list order, each seeing the positions the pairs before it left.
(define (pair-walk es)
  (let* ((v (list->vector es)) (n (vector-length v))
         (collides? (lambda (e) (and (entity-ref e #:solid? #f) (not (memq 'entity-collisions (entity-ref e #:skip-pipelines '())))))))
    (do ((i 0 (+ i 1))) ((= i n) (vector->list v))
      (do ((j (+ i 1) (+ j 1))) ((= j n))
        (when (and (collides? (vector-ref v i)) (collides? (vector-ref v j)))
          (let-values (((a b) (resolve-pair (vector-ref v i) (vector-ref v j))))
            (vector-set! v i a)
            (vector-set! v j b)))))))

(define (pair-outcome thunk) (handle-exceptions exn 'error (thunk)))

(test-group "the pair pass: the Scheme definition's pushes for every kind of number"
  (let loop ((round 0) (different 0) (moved 0) (errors 0) (first #f))
    (if (= round 21)
        (begin
          (test "21 crowds of 120 bodies, hash and all pairs: the walk's entities, numbers of the same types" 0 different)
          (test-assert "many bodies were pushed" (> moved 200))
          (test-assert "and a crowd holding a refused number raised an error" (> errors 0))
          (when first (print "pairs: first difference " first)))
        (let* ((base (list-ref bases (modulo round (length bases))))
               (es (map (lambda (e) (if (= (rnd 60) 0) (entity-set e #:x (pick (list +nan.0 +inf.0 'ten))) e))
                        ;; one in five a wall that is not pushed
                        (map (lambda (e) (if (= (rnd 5) 0) (entity-set e #:immovable? #t) e))
                             (crowd base 120 (= (modulo round 4) 3)))))
               (want (pair-outcome (lambda () (pair-walk es)))))
          (let ((hash (pair-outcome (lambda () (resolve-entity-collisions es 'spatial-hash))))
                (all (pair-outcome (lambda () (resolve-entity-collisions es 'all-pairs)))))
            (loop (+ round 1)
                  (+ different (if (equal? hash want) 0 1) (if (equal? all want) 0 1))
                  (if (pair? want)
                      (+ moved (let count ((a es) (b want) (k 0))
                                 (if (null? a) k (count (cdr a) (cdr b) (if (eq? (car a) (car b)) k (+ k 1))))))
                      moved)
                  (if (eq? want 'error) (+ errors 1) errors)
                  (or first (and (not (and (equal? hash want) (equal? all want))) (list round base)))))))))

;; push-apart decides the axis and the side in C for boxes of fixnums
;; below 2^50 and finite flonums (contacts.c, ds_push_sides) and makes
;; the numbers in Scheme: the same two bodies as push-apart/scheme, field
;; by field with eqv? (so -0.0, and a fixnum against a flonum, count), on
;; random overlapping pairs around 0, 2^50, 2^52, 2^53, 10^15 and 2^62,
;; ties of the two overlaps and of the centres among them.
(define (same-body? a b)
  (and (= (length a) (length b))
       (let loop ((a a) (b b))
         (or (null? a)
             (and (eq? (caar a) (caar b)) (eqv? (cdar a) (cdar b)) (loop (cdr a) (cdr b)))))))

(define (every-box-number? ok? a b)
  (let loop ((ks '(#:x #:y #:width #:height)))
    (or (null? ks) (and (ok? (entity-ref a (car ks) 0)) (ok? (entity-ref b (car ks) 0)) (loop (cdr ks))))))

;; A number near `base` for the push tests: base plus 0 to 23 as a
;; fixnum, a flonum (now and then with a fraction), a rational or a zero
;; of either sign at 0; or one of `far`, numbers the C must leave to the
;; Scheme or treat exactly.
(define (number-near base far)
  (case (rnd 10)
    ((0 1 2) (+ base (rnd 24)))
    ((3 4) (exact->inexact (+ base (rnd 24))))
    ((5) (+ (exact->inexact (+ base (rnd 24))) (pick '(0.5 0.25 -0.75 1e-9 2.220446049250313e-16))))
    ((6) (+ base (rnd 24) (/ (- (rnd 7) 3) (pick '(2 3 4)))))
    ((7) (if (= base 0) (pick '(-0.0 0.0 0)) (+ base (rnd 24))))
    ((8) (+ base (rnd 24) (pick '(0 1))))
    (else (pick (cons (+ base 8) far)))))

(test-group "push-apart in C: the Scheme definition's push for every kind of number"
  (define (near base)
    (number-near base (list +nan.0 +inf.0 1.7e308 -1.7e308 (expt 2 50) (- (expt 2 50)) (- (expt 2 50) 1))))
  (define (body k base)
    (ent #:id k #:x (near base) #:y (near base) #:vx (pick '(0 1 -2 0.5))
         #:width (pick (list 8 12 12 16 (+ 1 (rnd 20)) 12.0 0.5))
         #:height (pick (list 8 12 12 16 (+ 1 (rnd 20)) 12.0 3.25))))
  (define pair-bases (list 0 -40 (- (expt 2 50) 12) (- 12 (expt 2 50)) (expt 2 52) (expt 2 53) (expt 10 15) (expt 2 62)))
  ;; where fixnums are 31 bits wide (wasm32), the bases past 2^30 are
  ;; bignums, which the C leaves: fewer pairs, and fewer of them its
  (define wide? (fixnum? (string->number "1099511627776")))
  (define pairs (if wide? 20000 6000))
  (let loop ((k 0) (different 0) (plain 0) (first #f))
    (if (= k pairs)
        (begin
          (test (sprintf "~a random pairs: the same two bodies" pairs) 0 different)
          (test-assert (sprintf "many were boxes of fixnums and flonums it takes (~a)" plain)
                       (> plain (if wide? 5000 600)))
          (when first (print "push-apart: first difference " first)))
        (let* ((base (pick pair-bases))
               (a (body k base)) (b (body (+ k 1) base))
               (got (pair-outcome (lambda () (call-with-values (lambda () (push-apart a b)) list))))
               (want (pair-outcome (lambda () (call-with-values (lambda () (push-apart/scheme a b)) list))))
               (same? (if (pair? want)
                          (and (pair? got) (same-body? (car got) (car want)) (same-body? (cadr got) (cadr want)))
                          (equal? got want)))
               (small? (lambda (v) (or (and (fixnum? v) (< (abs v) (expt 2 50)))
                                       (and (flonum? v) (< (abs v) +inf.0))))))
          (loop (+ k 1)
                (if same? different (+ different 1))
                (if (every-box-number? small? a b) (+ plain 1) plain)
                (or first (and (not same?) (list a b 'c got 'scheme want))))))))

;; The whole push in C (contacts.c, ds_push_pair) makes both pushed
;; bodies itself for boxes of fixnums and flonums: the same two bodies as
;; push-apart/scheme, key by key in order with eqv?, on random pairs of
;; bodies holding both velocities in any order (sometimes one twice, or
;; none), around 0, the 31-bit fixnum limit (2^30), 2^50, 2^52 and 2^53,
;; with -0.0, rationals, odd and even overlaps, and velocities that are
;; already the push's (so a pair is kept, not copied).
(test-group "push-apart/c: the Scheme definition's two bodies, or no answer"
  (define (near base)
    (number-near base (list +nan.0 1.7e308 (expt 2 50) (- (expt 2 50)) (- (expt 2 50) 1)
                            (- (expt 2 30) 1) (- (expt 2 30)) (expt 2 29))))
  (define (shuffle xs)
    (if (null? xs) xs
        (let ((x (list-ref xs (rnd (length xs)))))
          (cons x (shuffle (let drop ((ys xs)) (if (eq? (car ys) x) (cdr ys) (cons (car ys) (drop (cdr ys))))))))))
  (define (body k base)
    (let* ((pairs (list (cons #:id k) (cons #:x (near base)) (cons #:y (near base))
                        (cons #:width (pick (list 8 12 12 16 (+ 1 (rnd 20)) 12.0 0.5)))
                        (cons #:height (pick (list 8 12 12 16 (+ 1 (rnd 20)) 12.0 3.25)))
                        (cons #:vx (pick '(0 1 -1 0.5 -2))) (cons #:vy (pick '(0 1 -1 -0.0 3)))
                        (cons #:solid? #t)))
           (pairs (case (rnd 12)
                    ((0) (cons (cons #:vy 7) pairs))                     ; a key twice
                    ((1) (filter-out #:vy pairs))                         ; a velocity absent
                    ((2) (filter-out #:x pairs))                          ; a position absent (0)
                    (else pairs))))
      (shuffle pairs)))
  (define (filter-out key pairs)
    (let loop ((ps pairs)) (cond ((null? ps) '()) ((eq? (caar ps) key) (loop (cdr ps))) (else (cons (car ps) (loop (cdr ps)))))))
  (define bases (list 0 -40 (- (expt 2 29) 12) (- 12 (expt 2 29)) (- (expt 2 30) 12) (- 12 (expt 2 30))
                      (- (expt 2 50) 12) (- 12 (expt 2 50)) (expt 2 52) (expt 2 53)))
  (define pairs 20000)
  ;; the numbers the C takes: -1 says a box holds another
  (define (small? v) (or (and (fixnum? v) (< (abs v) (expt 2 50))) (and (flonum? v) (< (abs v) +inf.0))))
  ;; where fixnums are 31 bits wide, the bases from 2^30 on are bignums,
  ;; which the C leaves
  (define wide? (fixnum? (string->number "1099511627776")))
  (let loop ((k 0) (different 0) (answered 0) (exact 0) (first #f))
    (if (= k pairs)
        (begin
          (test (sprintf "~a random pairs: the C's answers are the Scheme's bodies" pairs) 0 different)
          (test-assert (sprintf "it answered for many (~a), of integers too (~a)" answered exact)
                       (and (> answered (if wide? 1200 500)) (> exact (if wide? 60 20))))
          (when first (print "push-apart/c: first difference " first))
          (let ((e (ent #:x 0 #:y 0 #:width 8 #:height 8 #:vx 0 #:vy 0)))
            (test "no answer, and no crash, for what is not two bodies and the six keys"
                  '(#f #f #f #f #f)
                  (list (push-apart/c 1 2 3) (push-apart/c e e (vector #:x #:y))
                        (push-apart/c e e 7) (push-apart/c e 'body push-keys)
                        (push-apart/c (cons (cons #:x 1) 2) e push-keys)))))
        (let* ((base (pick bases))
               (a (body k base)) (b (body (+ k 1) base))
               (got (pair-outcome (lambda () (push-apart/c a b push-keys))))
               (want (pair-outcome (lambda () (call-with-values (lambda () (push-apart/scheme a b)) list))))
               (same? (or (eq? got #f)
                          (and (eq? got -1) (not (every-box-number? small? a b)))
                          (and (pair? got) (pair? want)
                               (same-body? (car got) (car want)) (same-body? (cdr got) (cadr want))))))
          (loop (+ k 1)
                (if same? different (+ different 1))
                (if (pair? got) (+ answered 1) answered)
                (if (and (pair? got) (fixnum? (entity-ref (car got) #:x 0)) (fixnum? (entity-ref (car got) #:y 0)))
                    (+ exact 1) exact)
                (or first (and (not same?) (list a b 'c got 'scheme want))))))))
