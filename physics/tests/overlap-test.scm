;;; Overlap queries: entity-overlap?, scene-overlapping, overlapping-pairs.

(import scheme (chicken base) (chicken format) (chicken condition)
        (downstroke test) (downstroke entity) (downstroke scene) (downstroke overlap))

(define (ov-box x y w h . more)
  (plist->entity (append (list #:x x #:y y #:width w #:height h) more)))

(test-group "entity-overlap?: strict, as aabb-overlap?"
  (test-assert "boxes that share area" (entity-overlap? (ov-box 0 0 10 10) (ov-box 9 9 10 10)))
  (test "boxes that share only an edge" #f (entity-overlap? (ov-box 0 0 10 10) (ov-box 10 0 10 10)))
  (test "boxes that share only a corner" #f (entity-overlap? (ov-box 0 0 10 10) (ov-box 10 10 5 5)))
  (test "a box of zero width inside another overlaps it, as aabb-overlap? says" #t
        (entity-overlap? (ov-box 5 5 0 10) (ov-box 0 0 20 20)))
  (test "a box of zero width on another's edge does not" #f
        (entity-overlap? (ov-box 20 5 0 10) (ov-box 0 0 20 20)))
  (test "a box without #:width is one of zero width" #t
        (entity-overlap? (plist->entity (list #:x 5 #:y 5 #:height 4)) (ov-box 0 0 20 20)))
  (test-assert "exact rationals: 1/3 px of overlap counts"
               (entity-overlap? (ov-box 0 0 10 10) (ov-box (- 10 1/3) 0 10 10)))
  (test "exact rationals: touching at 10/3" #f
        (entity-overlap? (ov-box 0 0 10/3 1) (ov-box 10/3 0 1 1)))
  (test-assert "flonums" (entity-overlap? (ov-box 0.5 0.5 1.0 1.0) (ov-box 1.25 1.25 1 1)))
  (test "a NaN is an error naming the entity and the key"
        "entity enemy: #:x is +nan.0, not a finite real number"
        (condition-case (entity-overlap? (ov-box +nan.0 0 1 1 #:type 'enemy) (ov-box 0 0 1 1))
          (e (exn) ((condition-property-accessor 'exn 'message) e)))))

(test-group "scene-overlapping: the entities touching one, in scene order"
  (let* ((me (ov-box 10 10 10 10 #:tags '(player)))
         (a (ov-box 0 0 11 11 #:tags '(coin)))          ; overlaps
         (b (ov-box 20 10 5 5 #:tags '(coin)))          ; edge only
         (c (ov-box 15 15 2 2 #:tags '(enemy)))         ; inside
         (d (ov-box 19 0 4 40 #:tags '(coin) #:value 5)) ; overlaps
         (scene (make-scene entities: (list a me b c d))))
    (test "every overlapping entity, not itself" (list a c d) (scene-overlapping scene me))
    (test "tag:" (list a d) (scene-overlapping scene me tag: 'coin))
    (test "where:" (list d) (scene-overlapping scene me where: (lambda (e) (entity-ref e #:value #f))))
    (test "tag: and where: together" '()
          (scene-overlapping scene me tag: 'enemy where: (lambda (e) (entity-ref e #:value #f))))
    (test "an entity not in the scene is asked about the same way" (list a me c)
          (scene-overlapping scene (ov-box 8 5 8 12)))
    (test "a misspelt keyword is named"
          "scene-overlapping: unknown keyword tags: (did you mean tag:?)"
          (condition-case (scene-overlapping scene me tags: 'coin)
            (e (exn) ((condition-property-accessor 'exn 'message) e))))))

;; The pairs of the double loop a user would write.
(define (ov-loop as bs)
  (let outer ((as as) (out '()))
    (if (null? as)
        (reverse out)
        (outer (cdr as)
               (let inner ((bs bs) (out out))
                 (cond ((null? bs) out)
                       ((and (not (eq? (car as) (car bs))) (entity-overlap? (car as) (car bs)))
                        (inner (cdr bs) (cons (cons (car as) (car bs)) out)))
                       (else (inner (cdr bs) out))))))))

(define ov-seed 11)
(define (ov-rand n)
  (set! ov-seed (modulo (+ (* 1103515245 ov-seed) 12345) 2147483648))
  (modulo ov-seed n))

;; n boxes in a side x side arena: small ones with integer, rational and
;; flonum corners, some large, some of zero size, some far outside.
(define (ov-boxes n side)
  (let loop ((k 0) (out '()))
    (if (= k n)
        (reverse out)
        (let* ((kind (ov-rand 12))
               (x (case kind
                    ((0) (+ (ov-rand side) (/ (ov-rand 7) 8)))
                    ((1) (exact->inexact (+ (ov-rand side) (/ (ov-rand 4) 4))))
                    ((2) (- (ov-rand side) (* 1000 side)))
                    (else (ov-rand side))))
               (w (case kind ((3) (+ 100 (ov-rand 300))) ((4) 0) (else (+ 1 (ov-rand 12)))))
               (h (case kind ((3) (+ 1 (ov-rand 8))) (else (+ 1 (ov-rand 12))))))
          (loop (+ k 1) (cons (ov-box x (ov-rand side) w h #:id k) out))))))

(test-group "overlapping-pairs: exactly the double loop's pairs, in its order"
  (for-each
   (lambda (sizes)
     (let* ((as (ov-boxes (car sizes) (caddr sizes)))
            (bs (ov-boxes (cadr sizes) (caddr sizes)))
            (expected (ov-loop as bs)))
       (test (sprintf "~a x ~a in ~a px: the pairs (~a of them)" (car sizes) (cadr sizes) (caddr sizes)
                      (length expected))
             expected (overlapping-pairs as bs))))
   '((3 4 50) (10 10 40) (200 50 300) (600 300 400) (50 900 200)))
  (let ((es (ov-boxes 400 200)))
    (test "one list against itself: every touching pair both ways, never an entity with itself"
          (ov-loop es es) (overlapping-pairs es es)))
  (test "an empty list gives no pairs" '() (overlapping-pairs '() (ov-boxes 400 100)))
  (test "against an empty list, no pairs" '() (overlapping-pairs (ov-boxes 400 100) '())))
