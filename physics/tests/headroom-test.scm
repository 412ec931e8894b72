;;; The engine keeps the heap's free space in proportion to its live data
;;; (physics/pipeline.scm, "The heap's headroom"): once engine-pipeline
;;; has run, a major collection leaves at least as much of a heap half
;;; free as is in use, however much live data the program holds. CHICKEN
;;; alone keeps only a fixed 4 MB free, so that a large crowd is copied by
;;; ever more frequent major collections.

(import scheme (chicken base) (chicken gc) (downstroke test) (downstroke entity) (downstroke scene)
        (downstroke pipeline))

;; About 19 MB of live pairs, kept until the end.
(define live (let loop ((k 0) (out '())) (if (= k 400000) out (loop (+ k 1) (cons (cons k k) out)))))

(define scene
  (make-scene entities: (list (plist->entity '(#:x 0 #:y 0 #:width 8 #:height 8 #:vx 1 #:vy 0)))))

;; The heap grows (doubling) at major collections: a few frames, each
;; followed by one, let it reach its size.
(define stats
  (let loop ((k 0) (scene scene))
    (if (= k 6)
        (memory-statistics)             ; #(half-size used nursery), after a major collection
        (let ((next (engine-pipeline scene 16)))
          (gc #t)
          (loop (+ k 1) next)))))

(test-group "heap headroom"
  (test "a major collection leaves at least as much of a heap half free as it holds" #t
        (<= (* 2 (vector-ref stats 1)) (vector-ref stats 0)))
  (test "the live data is all still there" 400000 (length live)))

(test-exit)
