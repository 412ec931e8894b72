;;; No input hangs the loader or the scene code: CHICKEN 5.3's apply does
;;; not return with about 32,000 arguments, so nothing may apply a
;;; procedure to a list as long as the input. hostile-shapes.scm builds
;;; one map per such list, at 100,000 elements, and loads and converts
;;; it; it runs in a child process with a time limit, so that a
;;; regression fails here instead of hanging the suite.

(import scheme (chicken base) (chicken io) (chicken string) (chicken format)
        (chicken pathname) (chicken process) (chicken condition) (downstroke test))

(define ho-results
  (with-input-from-pipe
   (sprintf "CHICKEN_REPOSITORY_PATH=~a timeout 300 csi -q -s hostile-shapes.scm"
            (qs (absolute-repository-path)))
   ;; whatever is not a datum (an error's trace) ends the reading
   (lambda () (let loop ((out '()))
                (let ((x (handle-exceptions e #!eof (read))))
                  (if (eof-object? x) (reverse out) (loop (cons x out))))))))

(define (ho-result name)
  (let ((r (assoc name (filter-pairs ho-results))))
    (if r (cadr r) 'missing:-the-child-stopped-or-timed-out)))

(define (filter-pairs xs)
  (cond ((null? xs) '())
        ((and (pair? (car xs)) (string? (caar xs))) (cons (car xs) (filter-pairs (cdr xs))))
        (else (filter-pairs (cdr xs)))))

(test-group "hostile: input-sized lists never go through apply"
  (for-each (lambda (c) (test (car c) (cadr c) (ho-result (car c))))
            (list (list "list-max and list-min over 100,000 numbers" '(99999 0))
                  (list "string-concatenate of 100,000 strings" 200000)
                  (list "the polygon's box spans its points" '(5 7 999 999))
                  (list "every point is kept" 100000)
                  (list "the map covers the union of 100,000 chunks" '(-50000 100000))
                  (list "the last chunk's cell" 1)
                  (list "the property is whole" 200000)
                  (list "the cell names the 100,000th tile" 100000)
                  (list "json: 100,000 cells, the last one" '(1000 100 1))
                  (list "json: a polygon of 100,000 points" '(100000 (999 . 999)))
                  (list "json: 100,000 chunks" '(-50000 100000 1))
                  (list "json: 100,000 objects and 100,000 properties" '(100000 100000 99999))
                  (list "json: a string of 200,000 characters with 100,000 escapes" 200000))))

(define (every-substring? parts text)
  (or (null? parts) (and (substring-index (car parts) text) (every-substring? (cdr parts) text))))

;; (name . texts the error must contain)
(test-group "hostile: map sources are read only from regular files"
  (for-each (lambda (c)
              (let ((msg (ho-result (car c))))
                (test-assert (sprintf "~a: ~a" (car c) msg)
                             (and (string? msg) (every-substring? (cdr c) msg)))))
            (list (list "a tileset source of /dev/stdin" "source.tmx" "\"/dev/stdin\"" "is not a regular file")
                  (list "a tileset source that is a FIFO" "source.tmx" "pipe.tsx" "is not a regular file")
                  (list "a map that is a FIFO" "pipe.tsx" "the map is not a regular file")
                  (list "a .tmj map that is a FIFO" "pipe.tmj" "the map is not a regular file")
                  (list "a .tsj tileset source that is a FIFO" "source.tmx" "pipe.tmj" "is not a regular file")
                  (list "a map path with a NUL byte" "the map has a NUL byte in its name"))))

;; Mistakes that once failed inside the library ([memq] bad argument type,
;; [cddr] bad argument type) and now say what is wrong.
(import (downstroke entity) (downstroke scene) (downstroke pipeline))
(define (ho-message thunk)
  (handle-exceptions e ((condition-property-accessor 'exn 'message "") e) (thunk) "no error"))
(test-group "hostile: errors name the entity, the keyword and the value"
  (test "#:skip-pipelines as a string"
        "entity box: #:skip-pipelines is \"gravity\", expected a list of step symbols such as (gravity)"
        (ho-message (lambda () (engine-pipeline (make-scene entities: (list (list #:type 'box #:x 0 #:y 0
                                                                                  #:skip-pipelines "gravity")))
                                                16))))
  (test "one plist entity given as entities:"
        "make-scene: entities: is one entity, not a list of them (wrap it: (list e))"
        (ho-message (lambda () (make-scene entities: (list #:type 'player #:x 0)))))
  (test "one alist entity given to update-scene"
        "update-scene: entities: is one entity, not a list of them (wrap it: (list e))"
        (ho-message (lambda () (update-scene (make-scene) entities: (list (cons #:x 1) (cons #:y 2))))))
  (test "a list with something that is no entity"
        "not an entity (plist or keyword alist)"
        (ho-message (lambda () (make-scene entities: (list (list #:type 'a) 5)))))
  (test "a list of plist entities is still fine" 2
        (length (scene-entities (make-scene entities: (list (list #:type 'a #:points '((1 . 2)))
                                                            (list #:type 'b)))))))

(test-group "hostile: a sum that overflows to infinity is the step's error"
  (import (downstroke tilemap))
  (define (box . more) (append (list #:type 'box #:x 1e308 #:y 0 #:width 8 #:height 8 #:vx 1e308) more))
  (define expected "entity box: #:x overflowed to +inf.0 (1e+308 + 1e+308); positions and velocities must stay finite")
  (test "without a map" expected
        (ho-message (lambda () (engine-pipeline (make-scene entities: (list (box))) 16))))
  (test "with a map" expected
        (ho-message (lambda () (engine-pipeline (make-scene tilemap: (list->tilemap '((0 0)))
                                                            entities: (list (box))) 16))))
  (test "with a map, moving on both axes" expected
        (ho-message (lambda () (engine-pipeline (make-scene tilemap: (list->tilemap '((0 0)))
                                                            entities: (list (box #:vy 3.5))) 16))))
  (test "the readable pipeline says the same" expected
        (ho-message (lambda () (contract-pipeline (make-scene tilemap: (list->tilemap '((0 0)))
                                                              entities: (list (box))) 16))))
  (test "gravity pushing vy over the edge"
        "entity box: #:vy overflowed to +inf.0 (1.79769313486232e+308 + 1e+308); positions and velocities must stay finite"
        (ho-message (lambda () (engine-pipeline
                                (make-scene entities: (list (list #:type 'box #:x 0 #:y 0 #:vy 1.7976931348623157e308
                                                                  #:ay 1e308 #:gravity? #t)))
                                16)))))
