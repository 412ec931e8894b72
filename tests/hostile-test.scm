;;; No input hangs the loader or the scene code: CHICKEN 5.3's apply does
;;; not return with about 32,000 arguments, so nothing may apply a
;;; procedure to a list as long as the input. hostile-shapes.scm builds
;;; one map per such list, at 100,000 elements, and loads and converts
;;; it; it runs in a child process with a time limit, so that a
;;; regression fails here instead of hanging the suite.

(import scheme (chicken base) (chicken io) (chicken string) (chicken format)
        (chicken pathname) (chicken process) (chicken condition) (downstroke test))

(define hostile-address-space-kb (* 2 1024 1024))

(define ho-results
  (with-input-from-pipe
   ;; in a bounded address space (2 GB), so that a regression in memory
   ;; fails here instead of exhausting the machine
   (sprintf "ulimit -v ~a; CHICKEN_REPOSITORY_PATH=~a timeout 300 csi -q -s hostile-shapes.scm"
            hostile-address-space-kb (qs (absolute-repository-path)))
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
                  (list "100,000 object layers, in order" '(100000 "o0" "o99999"))
                  (list "100,000 nested groups load when the limit allows them, offsets added" 100000)
                  (list "json: 100,000 cells, the last one" '(1000 100 1))
                  (list "json: a polygon of 100,000 points" '(100000 (999 . 999)))
                  (list "json: 100,000 chunks" '(-50000 100000 1))
                  (list "json: 100,000 objects and 100,000 properties" '(100000 100000 99999))
                  (list "json: a string of 200,000 characters with 100,000 escapes" 200000))))

(define (every-substring? parts text)
  (or (null? parts) (and (substring-index (car parts) text) (every-substring? (cdr parts) text))))

;; (name . texts the error must contain)
(test-group "hostile: limits on what a map may ask for, each named in its error"
  (for-each (lambda (c)
              (let ((msg (ho-result (car c))))
                (test-assert (sprintf "~a: ~a" (car c) msg)
                             (and (string? msg) (every-substring? (cdr c) msg)
                                  (< (string-length msg) 400)))))
            (list (list "past tilemap-max-depth: an error naming the file, the group and the limit"
                        "nested.tmx" "group \"g100\"" "groups nest more than 100 deep (tilemap-max-depth)")
                  (list "a bad group 20,000 groups deep (limit raised): the error names its path, briefly"
                        "nested-bad.tmx" "group \"g0\"" "19995 more groups" "group \"g19999\", group \"bad\""
                        "offsetx=\"abc\"")
                  (list "four 8192 x 8192 layers: more than tilemap-max-cells in all"
                        "big.tmx" "268435456 cells in 4 tile layers" "limit of 67108864 (tilemap-max-cells)")
                  (list "an infinite map's chunks, 5 x 4096 x 4096: more than tilemap-max-cells, before decoding any"
                        "big-chunks.tmx" "83886080 cells in 1 tile layer:" "(tilemap-max-cells)"))))


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
;; Bad entities are made here on purpose; their warnings would only be noise.
(scene-checks #f)
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

;; Images, sounds and text that ask for gigabytes, in a child with 768 MB
;; of address space (hostile-media.scm): each must be a prompt error
;; naming the file or procedure and the limit.
(define hm-results
  (with-input-from-pipe
   (sprintf "ulimit -v 786432; CHICKEN_REPOSITORY_PATH=~a timeout 300 csi -q -s hostile-media.scm"
            (qs (absolute-repository-path)))
   (lambda () (let loop ((out '()))
                (let ((x (handle-exceptions e #!eof (read))))
                  (if (eof-object? x) (reverse out) (loop (cons x out))))))))

(test-group "hostile: media that ask for gigabytes, in a bounded address space"
  (for-each (lambda (c)
              (let* ((r (assoc (car c) (filter-pairs hm-results)))
                     (msg (and r (cadr r))))
                (test-assert (sprintf "~a: ~a" (car c) (or msg "missing: the child stopped"))
                             (and (string? msg) (every-substring? (cdr c) msg)))))
            (list (list "a 33-byte PNG of 20000 x 20000, as a texture" "huge.png" "20000 x 20000 pixels" "(max-image-pixels)")
                  (list "the same PNG as a surface" "huge.png" "(max-image-pixels)")
                  (list "load-sounds! of /dev/zero" "\"/dev/zero\" is not a regular file")
                  (list "load-music! of /dev/zero" "\"/dev/zero\" is not a regular file")
                  (list "a font of 2^32 points" "DejaVuSans.ttf" "max-font-size (1000)")
                  (list "a 1 MB string to draw-text!" "draw-text!" "1048576 characters" "max-text-length (10000)")
                  (list "an image path with a NUL byte" "vel.png\" has a NUL byte in its name")
                  (list "a sound path with a NUL byte" "vel.png\" has a NUL byte in its name")
                  (list "a font path with a NUL byte" "TTF_OpenFont" "has a NUL byte in its name")
                  (list "a font that is a device" "\"/dev/zero\": it is not a regular file"))))
