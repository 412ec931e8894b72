;;; The spatial hash gives exactly the all-pairs result, every frame.

(import scheme (chicken base) (chicken format) (downstroke test) (downstroke entity)
        (downstroke scene) (downstroke physics))

(define bp-seed 7)
(define (bp-rand n)
  (set! bp-seed (modulo (+ (* 1103515245 bp-seed) 12345) 2147483648))
  (modulo bp-seed n))

;; A crowd of `n` bodies in an arena of `side` px: mostly small, some large
;; (walls and slabs), some immovable, some of zero width, some skipping.
(define (bp-crowd n side)
  (let loop ((k 0) (out '()))
    (if (= k n)
        (reverse out)
        (let* ((kind (bp-rand 20))
               (w (cond ((= kind 0) (+ 200 (bp-rand 400)))    ; large
                        ((= kind 1) 0)                        ; zero width
                        (else (+ 2 (bp-rand 14)))))
               (h (if (= kind 0) (+ 4 (bp-rand 20)) (+ 2 (bp-rand 14)))))
          (loop (+ k 1)
                (cons (list (cons #:id k) (cons #:solid? #t)
                            (cons #:x (bp-rand side)) (cons #:y (bp-rand side))
                            (cons #:width w) (cons #:height h)
                            (cons #:vx (- (bp-rand 7) 3)) (cons #:vy (- (bp-rand 7) 3))
                            (cons #:immovable? (= kind 2))
                            (cons #:skip-pipelines (if (= kind 3) '(entity-collisions) '())))
                      out))))))

(define (bp-move es)
  (map (lambda (e) (apply-velocity-y #f (apply-velocity-x #f e 16) 16)) es))

;; Runs both methods side by side; counts frames where they differ.
(define (bp-compare n side frames)
  (bp-compare-with n side frames (lambda (es) es)))

;; The same on the crowd as `prepare` makes it.
(define (bp-compare-with n side frames prepare)
  (let loop ((f 0) (a (prepare (bp-crowd n side))) (b #f) (differ 0))
    (let ((b (or b a)))
      (if (= f frames)
          differ
          (let ((a2 (resolve-entity-collisions (bp-move a) 'all-pairs))
                (b2 (resolve-entity-collisions (bp-move b) 'spatial-hash)))
            (loop (+ f 1) a2 b2 (if (equal? a2 b2) differ (+ differ 1))))))))

(test-group "spatial hash against all pairs"
  (test "200 bodies, a dense 300 px arena, 100 frames" 0 (bp-compare 200 300 100))
  (test "400 bodies, a sparse 2000 px arena, 50 frames" 0 (bp-compare 400 2000 50))
  (test "60 bodies piled in 40 px, 100 frames" 0 (bp-compare 60 40 100))
  ;; flonum positions (the hash's cells then come from C's doubles), some
  ;; negative, some a hair below a cell's edge
  (test "300 bodies at flonum positions, a 400 px arena around 0, 60 frames" 0
        (bp-compare-with 300 400 60
                         (lambda (es)
                           (map (lambda (e)
                                  (let ((x (entity-ref e #:x)) (y (entity-ref e #:y)))
                                    (entity-set* e #:x (- (* 1.0 x) 200.25) #:y (- y 200 (* 1e-13 (bp-rand 3))))))
                                es))))
  ;; far out: cells about 1e15 (where C's cells stop and Scheme's take
  ;; over) and past every fixnum (1e300)
  (for-each (lambda (offset)
              (test (sprintf "60 bodies at flonum positions about ~a, 20 frames" offset) 0
                    (bp-compare-with 60 300 20
                                     (lambda (es)
                                       (map (lambda (e)
                                              (entity-set* e #:x (+ offset (entity-ref e #:x))
                                                           #:y (- (entity-ref e #:y) offset)))
                                            es)))))
            '(1.6e16 3.2e16 1e300))
  (let ((es (bp-crowd 300 250)))
    (test-assert "the crowd really collides"
                 (not (equal? es (resolve-entity-collisions es 'all-pairs)))))
  (test-error "an unknown method" (resolve-entity-collisions (bp-crowd 3 10) 'magic)))

(test-group "the cascade rule holds in the spatial hash"
  (define (box x) (list (cons #:solid? #t) (cons #:x x) (cons #:y 0) (cons #:width 10) (cons #:height 10)))
  (test "later pairs see earlier pushes" '(-1 17/2 37/2)
        (map (lambda (e) (entity-ref e #:x))
             (resolve-entity-collisions (list (box 0) (box 8) (box 18)) 'spatial-hash))))

(test-group "the spatial hash at the edge of the fixnum range"
  ;; boxes whose cell index is the largest fixnum: the cell walk must step
  ;; past it into bignums and stop, not wrap around
  (import (chicken fixnum))
  (define far (* most-positive-fixnum 16))
  (define (box k x) (list (cons #:id k) (cons #:solid? #t) (cons #:x x) (cons #:y 0)
                          (cons #:width 8) (cons #:height 8)))
  (let ((crowd (cons (box 0 far)
                     (cons (box 1 (+ far 4))
                           (let loop ((k 2)) (if (= k 40) '() (cons (box k (* k 100)) (loop (+ k 1)))))))))
    (test "the same as all pairs" #t
          (equal? (resolve-entity-collisions crowd 'all-pairs)
                  (resolve-entity-collisions crowd 'spatial-hash)))
    (test "the two far boxes are pushed apart" (list (- far 2) (+ far 6))
          (map (lambda (e) (entity-ref e #:x))
               (let ((out (resolve-entity-collisions crowd 'spatial-hash)))
                 (list (car out) (cadr out)))))))
