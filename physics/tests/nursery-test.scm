;;; What the physics' hot paths use of the nursery.
;;;
;;; CHICKEN's nursery is its C stack: every call's C frame and every new
;;; object goes there until a minor collection empties it, so the bytes a
;;; call leaves on the stack are what it allocates (docs/performance.org,
;;; "What a body-frame allocates"). A probe compiled here reads the stack
;;; pointer around one call, made from compiled code, after a minor
;;; collection has emptied the nursery. The assertions compare two calls
;;; of the same code, so they hold whatever C compiler made the library.

(import scheme (chicken base) (chicken format) (chicken file) (chicken process)
        (downstroke test) (downstroke entity) (downstroke scene) (downstroke tilemap) (downstroke physics))

;; Random bodies are not what this suite is about.
(scene-checks #f)

(define probe-source (sprintf "/tmp/downstroke-nursery-~a.scm" (current-process-id)))
(define probe-library (sprintf "/tmp/downstroke-nursery-~a.so" (current-process-id)))
(with-output-to-file probe-source
  (lambda ()
    (write '(import scheme (chicken base) (chicken foreign) (chicken gc)))
    (write '(define stack-address
              (foreign-lambda* unsigned-long () "C_return((unsigned long)C_stack_pointer);")))
    ;; the bytes of C stack (apply proc args) leaves, or #f when a minor
    ;; collection came in between
    (write '(define (nursery-used proc args)
              (gc #f)
              (let* ((before (stack-address)) (result (apply proc args)) (after (stack-address)))
                (and (< after before) (- before after)))))))
(system (sprintf "csc -s -O3 ~a -o ~a" probe-source probe-library))
(load probe-library)
(delete-file* probe-source)
(delete-file* probe-library)

;; The pass's walk of an entity is a loop in one C function, and CHICKEN
;; reserves a function's allocation at each turn of its loops: a pass
;; that made new numbers in that function paid for them at every key of
;; every body (64 bytes a key, before physics/motion.scm's rewrite-made).
(test-group "the motion pass's walk of an entity uses no nursery per key"
  (let ((move (motion-pass (make-scene) 16 #f #f #f))
        ;; a moving body, with n more keys after its own
        (body (lambda (x n)
                (append (list (cons #:x x) (cons #:y x) (cons #:width 8) (cons #:height 8)
                              (cons #:vx 1) (cons #:vy -1) (cons #:solid? #t))
                        (let more ((k 0))
                          (if (= k n)
                              '()
                              (cons (cons (list-ref '(#:tags #:type #:hp #:score) (modulo k 4)) k)
                                    (more (+ k 1)))))))))
    (for-each (lambda (x kind)
                (test (sprintf "a body at ~a positions: 20 more keys, the same bytes" kind) #t
                      (let ((few (nursery-used move (list (body x 0))))
                            (many (nursery-used move (list (body x 20)))))
                        (and few many (= few many)))))
              (list 10 21/2 10.5)
              '("fixnum" "rational" "flonum"))
    (test "... and each body moved by one velocity step on each axis"
          (map (lambda (x) (list (+ x 1) (- x 1))) (list 10 21/2 10.5))
          (map (lambda (x)
                 (let ((moved (move (body x 20))))
                   (list (entity-ref moved #:x) (entity-ref moved #:y))))
               (list 10 21/2 10.5)))))

;; On a map, a body of flonums takes the flonum kernel too (tile steps
;; included): its walk allocates nothing per key either, and the whole
;; call stays within twice what a body of fixnums uses (the readable
;; steps, which took such bodies before, used several times that).
(test-group "the motion pass on a map: flonum bodies use no nursery per key"
  (let* ((tm (list->tilemap '((0 0 0 0 0 0) (0 0 0 0 0 0) (0 0 0 0 0 0) (1 1 1 1 1 1))
                            tile-width: 16 tile-height: 16))
         (move (motion-pass (make-scene tilemap: tm collision-mode: 'swept) 16 #f #f #f))
         ;; a body falling onto the floor (row 3, y = 48), n more keys after its own
         (body (lambda (x y n)
                 (append (list (cons #:x x) (cons #:y y) (cons #:width 8) (cons #:height 8)
                               (cons #:vx 1) (cons #:vy 3) (cons #:gravity? #t) (cons #:solid? #t))
                         (let more ((k 0))
                           (if (= k n)
                               '()
                               (cons (cons (list-ref '(#:tags #:type #:hp #:score) (modulo k 4)) k)
                                     (more (+ k 1)))))))))
    (test "a flonum body: 20 more keys, the same bytes" #t
          (let ((few (nursery-used move (list (body 10.5 20.25 0))))
                (many (nursery-used move (list (body 10.5 20.25 20)))))
            (and few many (= few many))))
    (test "a flonum body: less than twice a fixnum body's bytes" #t
          (let ((fixnum (nursery-used move (list (body 10 20 20))))
                (flonum (nursery-used move (list (body 10.5 20.25 20)))))
            (and fixnum flonum (< flonum (* 2 fixnum)))))
    (test "... and the flonum body fell by vy + gravity, landing on the floor"
          (list 11.5 (+ 20.25 (+ 3 *gravity*)) 40 0)
          (let ((moved (move (body 10.5 20.25 0)))
                (landed (move (body 10.5 39.5 0))))
            (list (entity-ref moved #:x) (entity-ref moved #:y) (entity-ref landed #:y) (entity-ref landed #:vy))))))

;; Two boxes of fixnums or flonums are compared by one C function
;; (physics/contacts.c). The comparisons in Scheme, which rational boxes
;; still take, go through a chain of continuations, each a C frame left on
;; the stack, even for their quickest answer (boxes told apart by the
;; integer parts of their coordinates); the C call leaves less than half
;; of that (on 591b184, fixnum and flonum boxes took 2,128 bytes here and
;; rational ones 2,560).
(test-group "the pair test of two boxes of fixnums or flonums is one C call"
  (let ((scheme (nursery-used aabb-overlap? (list 21/2 21/2 8 8 61/2 61/2 8 8))))
    (for-each (lambda (a b kind)
                (test (sprintf "boxes at ~a positions: less than half the bytes" kind) #t
                      (let ((used (nursery-used aabb-overlap? (list a a 8 8 b b 8 8))))
                        (and used scheme (< (* 2 used) scheme)))))
              (list 10 10.5 10 10.5)
              (list 14 14.5 30 30.5)
              '("fixnum, overlapping" "flonum, overlapping" "fixnum, apart" "flonum, apart"))))

;; Ground detection among many solids judges the candidates near a body's
;; feet (from the hash of their tops) in one C call (physics/contacts.c,
;; ds_ground_scan) when their numbers are fixnums or flonums: the bytes
;; of a query are the same for 2 candidates and for 40. On 20dae7f each
;; candidate was a Scheme call and a pair of the list of candidates.
(test-group "ground detection among many solids: no nursery per candidate"
  (let* ((solid (lambda (x y) (list (cons #:x x) (cons #:y y) (cons #:width 12) (cons #:height 12)
                                    (cons #:solid? #t))))
         ;; n solids under the mover's feet whose tops are 12 px above
         ;; them (too far to stand on), the rest far away: 60 in all
         (solids (lambda (n x y)
                   (let loop ((k 0) (out '()))
                     (if (= k 60)
                         out
                         (loop (+ k 1) (cons (if (< k n) (solid x y) (solid (+ x 1000 (* 30 k)) (+ y 900))) out))))))
         (mover (lambda (x y) (list (cons #:x x) (cons #:y y) (cons #:width 12) (cons #:height 12)
                                    (cons #:vy 0) (cons #:solid? #t))))
         ;; (bytes answer) of a query after one that builds the hash
         (query (lambda (e ss)
                  (entity-solid-support-below? e ss)
                  (list (nursery-used entity-solid-support-below? (list e ss))
                        (entity-solid-support-below? e ss)))))
    (for-each (lambda (x y kind)
                (let ((few (query (mover x y) (solids 2 x y)))
                      (many (query (mover x y) (solids 40 x y))))
                  (test (sprintf "~a positions: 40 candidates, the bytes of 2, and no ground" kind)
                        #t (and (car few) (car many) (= (car few) (car many))
                                (not (cadr few)) (not (cadr many))))))
              (list 100 100.5)
              (list 100 100.25)
              '("fixnum" "flonum"))
    (let ((ss (append (solids 40 100 100) (list (solid 100 112)))))
      (test "... and a supporter after them is found" #t
            (cadr (query (mover 100 100) ss))))))

(test-exit)
