;;; Run by hostile-test.scm in a child process under a time limit (a
;;; regression would hang rather than fail): each shape prints
;;; (name value) for the parent to check.

(import scheme (chicken base) (chicken string) (chicken format) (chicken file)
        (chicken pathname) (chicken process-context) (chicken process-context posix) (chicken port)
        (downstroke tilemap) (downstroke util))

(define ho-dir (make-pathname (or (get-environment-variable "TMPDIR") "/tmp")
                              (sprintf "downstroke-hostile-~a" (current-process-id))))
(create-directory ho-dir #t)

(define (ho-write name text)
  (let ((path (make-pathname ho-dir name)))
    (with-output-to-file path (lambda () (display text)))
    path))

;; n copies of (piece i), joined.
(define (ho-repeat n piece)
  (with-output-to-string
    (lambda () (let loop ((i 0)) (when (< i n) (display (piece i)) (loop (+ i 1)))))))

(define ho-n 100000)

;; A map whose one tileset is an image-less collection (no image to find).
(define (ho-map body #!key (attrs "") (width 1) (height 1) (tileset ""))
  (string-append
   "<?xml version=\"1.0\"?><map version=\"1.10\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\""
   (number->string width) "\" height=\"" (number->string height)
   "\" tilewidth=\"8\" tileheight=\"8\"" attrs ">" tileset body "</map>"))

(define (test name expected #!optional (value expected)) (write (list name value)) (newline))
(import (chicken condition))
(define (ho-error thunk)
  (handle-exceptions e ((condition-property-accessor 'exn 'message "?") e) (thunk) "no error"))
(let ()
  (test "list-max and list-min over 100,000 numbers" '(99999 0)
        (let ((l (iota ho-n))) (list (list-max l) (list-min l))))
  (test "string-concatenate of 100,000 strings" 200000
        (string-length (string-concatenate (map (lambda (i) "ab") (iota ho-n)))))

  ;; a polygon of 100,000 points: its box, and its entity
  (let* ((points (ho-repeat ho-n (lambda (i) (sprintf "~a,~a " (modulo i 1000) (quotient i 100)))))
         (p (ho-write "polygon.tmx"
                      (ho-map (string-append "<layer id=\"1\" name=\"g\" width=\"1\" height=\"1\"><data encoding=\"csv\">0</data></layer>"
                                             "<objectgroup id=\"2\" name=\"o\"><object id=\"1\" x=\"5\" y=\"7\"><polygon points=\""
                                             points "\"/></object></objectgroup>"))))
         (tm (load-tilemap p))
         (e (car (tilemap-objects->entities tm))))
    (test "the polygon's box spans its points" '(5 7 999 999)
          (map (lambda (k) (cdr (assq k e))) '(#:x #:y #:width #:height)))
    (test "every point is kept" ho-n (length (cdr (assq #:points e)))))

  ;; an infinite map of 100,000 one-cell chunks in a row
  (let* ((chunks (ho-repeat ho-n (lambda (i) (sprintf "<chunk x=\"~a\" y=\"0\" width=\"1\" height=\"1\">1</chunk>" (- i 50000)))))
         (p (ho-write "chunks.tmx"
                      (ho-map (string-append "<layer id=\"1\" name=\"g\" width=\"1\" height=\"1\"><data encoding=\"csv\">"
                                             chunks "</data></layer>")
                              attrs: " infinite=\"1\""
                              tileset: "<tileset firstgid=\"1\" name=\"t\" tilewidth=\"8\" tileheight=\"8\" tilecount=\"1\" columns=\"0\"><tile id=\"0\"/></tileset>")))
         (tm (load-tilemap p)))
    (test "the map covers the union of 100,000 chunks" (list -50000 ho-n)
          (list (tilemap-origin-col tm) (tilemap-width tm)))
    (test "the last chunk's cell" 1 (tilemap-tile-at tm 49999 0)))

  ;; a property whose text reaches the loader in 100,000 pieces, split by
  ;; elements between them (xml.scm joins the runs expat hands over, but
  ;; not across an element)
  (let* ((text (ho-repeat ho-n (lambda (i) "ab<x/>")))
         (p (ho-write "pieces.tmx"
                      (ho-map (string-append "<properties><property name=\"long\">" text "</property></properties>"
                                             "<layer id=\"1\" name=\"g\" width=\"1\" height=\"1\"><data encoding=\"csv\">0</data></layer>"))))
         (tm (load-tilemap p)))
    (test "the property is whole" (* 2 ho-n)
          (string-length (property-ref (tilemap-properties tm) "long"))))

  ;; a tileset listing 100,000 tiles: the map's gid range is computed from their ids
  (let* ((tiles (ho-repeat ho-n (lambda (i) (sprintf "<tile id=\"~a\"/>" i))))
         (p (ho-write "tiles.tmx"
                      (ho-map "<layer id=\"1\" name=\"g\" width=\"1\" height=\"1\"><data encoding=\"csv\">100000</data></layer>"
                              tileset: (string-append "<tileset firstgid=\"1\" name=\"t\" tilewidth=\"8\" tileheight=\"8\" tilecount=\"0\" columns=\"0\">"
                                                      tiles "</tileset>"))))
         (tm (load-tilemap p)))
    (test "the cell names the 100,000th tile" ho-n (tilemap-tile-at tm 0 0)))

  ;; 100,000 layers side by side, and 100,000 groups one in another (with
  ;; the depth limit raised): built in one pass, and the error context of
  ;; the innermost costs memory in proportion to the depth (this child runs
  ;; in a bounded address space; the nesting once needed over 3 GB)
  (let* ((layers (ho-repeat ho-n (lambda (i) (sprintf "<objectgroup id=\"~a\" name=\"o~a\"/>" (+ i 1) i))))
         (tm (load-tilemap (ho-write "layers.tmx" (ho-map layers)))))
    (test "100,000 object layers, in order" (list ho-n "o0" "o99999")
          (let ((tree (tilemap-layer-tree tm)))
            (list (length tree) (layer-name (car tree)) (layer-name (list-ref tree (- ho-n 1)))))))
  (let* ((open (ho-repeat ho-n (lambda (i) (sprintf "<group id=\"~a\" name=\"g~a\" offsetx=\"1\">" (+ i 1) i))))
         (close (ho-repeat ho-n (lambda (i) "</group>")))
         (p (ho-write "nested.tmx"
                      (ho-map (string-append open "<layer id=\"0\" name=\"deep\" width=\"1\" height=\"1\"><data encoding=\"csv\">0</data></layer>" close))))
         (tm (parameterize ((tilemap-max-depth (+ ho-n 1))) (load-tilemap p))))
    (test "100,000 nested groups load when the limit allows them, offsets added" ho-n
          (layer-offset-x (car (tilemap-layers tm))))
    (test "past tilemap-max-depth: an error naming the file, the group and the limit"
          (ho-error (lambda () (load-tilemap p)))))
  (let ((p (ho-write "nested-bad.tmx"
                     (ho-map (string-append (ho-repeat 20000 (lambda (i) (sprintf "<group name=\"g~a\">" i)))
                                            "<group name=\"bad\" offsetx=\"abc\"/>"
                                            (ho-repeat 20000 (lambda (i) "</group>")))))))
    (test "a bad group 20,000 groups deep (limit raised): the error names its path, briefly"
          (parameterize ((tilemap-max-depth 30000)) (ho-error (lambda () (load-tilemap p))))))

  ;; four 8192 x 8192 zstd layers in a map of a few hundred bytes: the
  ;; limit on cells is the map's, checked before anything is decoded
  (let ((p (ho-write "big.tmx"
                     (ho-map (ho-repeat 4 (lambda (i) (sprintf "<layer id=\"~a\" name=\"l~a\" width=\"8192\" height=\"8192\"><data encoding=\"base64\" compression=\"zstd\">KLUv/QBYAAA=</data></layer>" (+ i 1) i)))
                             width: 8192 height: 8192))))
    (test "four 8192 x 8192 layers: more than tilemap-max-cells in all"
          (ho-error (lambda () (load-tilemap p)))))
  (let ((p (ho-write "big-chunks.tmx"
                     (ho-map (string-append "<layer id=\"1\" name=\"l\" width=\"1\" height=\"1\"><data encoding=\"csv\">"
                                            (ho-repeat 5 (lambda (i) (sprintf "<chunk x=\"~a\" y=\"0\" width=\"4096\" height=\"4096\">0</chunk>" (* i 4096))))
                                            "</data></layer>")
                             attrs: " infinite=\"1\""))))
    (test "an infinite map's chunks, 5 x 4096 x 4096: more than tilemap-max-cells, before decoding any"
          (ho-error (lambda () (load-tilemap p))))))


;; The same shapes in Tiled's JSON format: arrays of 100,000 cells, points,
;; chunks, objects and properties, and a 200,000-character string with
;; escapes, each read in time linear in its length.
(define (ho-json-map layers #!key (more "") (width 1) (height 1)
                     (tileset "{\"firstgid\":1,\"name\":\"t\",\"tilewidth\":8,\"tileheight\":8,\"tilecount\":1,\"columns\":0,\"tiles\":[{\"id\":0}]}"))
  (string-append "{\"type\":\"map\",\"orientation\":\"orthogonal\",\"width\":" (number->string width)
                 ",\"height\":" (number->string height) ",\"tilewidth\":8,\"tileheight\":8," more
                 "\"tilesets\":[" tileset "],\"layers\":[" layers "]}"))
(define (ho-join n piece)
  (with-output-to-string
    (lambda () (let loop ((i 0)) (when (< i n) (when (> i 0) (display ",")) (display (piece i)) (loop (+ i 1)))))))
(let ()
  (let* ((p (ho-write "cells.tmj"
                      (ho-json-map (string-append "{\"type\":\"tilelayer\",\"name\":\"g\",\"width\":1000,\"height\":100,\"data\":["
                                                  (ho-join ho-n (lambda (i) (if (= i (- ho-n 1)) 1 (modulo i 2)))) "]}")
                                   width: 1000 height: 100)))
         (tm (load-tilemap p)))
    (test "json: 100,000 cells, the last one" '(1000 100 1) (list (tilemap-width tm) (tilemap-height tm) (tilemap-tile-at tm 999 99))))
  (let* ((p (ho-write "polygon.tmj"
                      (ho-json-map (string-append "{\"type\":\"objectgroup\",\"name\":\"o\",\"objects\":[{\"id\":1,\"x\":5,\"y\":7,\"polygon\":["
                                                  (ho-join ho-n (lambda (i) (sprintf "{\"x\":~a,\"y\":~a}" (modulo i 1000) (quotient i 100))))
                                                  "]}]}"))))
         (o (car (tilemap-objects (load-tilemap p)))))
    (test "json: a polygon of 100,000 points" (list ho-n '(999 . 999)) (list (length (object-points o)) (list-ref (object-points o) 99999))))
  (let* ((p (ho-write "chunks.tmj"
                      (ho-json-map (string-append "{\"type\":\"tilelayer\",\"name\":\"g\",\"width\":1,\"height\":1,\"chunks\":["
                                                  (ho-join ho-n (lambda (i) (sprintf "{\"x\":~a,\"y\":0,\"width\":1,\"height\":1,\"data\":[1]}" (- i 50000))))
                                                  "]}")
                                   more: "\"infinite\":true,")))
         (tm (load-tilemap p)))
    (test "json: 100,000 chunks" (list -50000 ho-n 1) (list (tilemap-origin-col tm) (tilemap-width tm) (tilemap-tile-at tm 49999 0))))
  (let* ((p (ho-write "objects.tmj"
                      (ho-json-map (string-append "{\"type\":\"objectgroup\",\"name\":\"o\",\"objects\":["
                                                  (ho-join ho-n (lambda (i) (sprintf "{\"id\":~a,\"x\":~a,\"y\":0}" (+ i 1) i)))
                                                  "]}")
                                   more: (string-append "\"properties\":["
                                                        (ho-join ho-n (lambda (i) (sprintf "{\"name\":\"p~a\",\"type\":\"int\",\"value\":~a}" i i)))
                                                        "],"))))
         (tm (load-tilemap p)))
    (test "json: 100,000 objects and 100,000 properties" (list ho-n ho-n 99999)
          (list (length (tilemap-objects tm)) (length (tilemap-properties tm))
                (property-ref (tilemap-properties tm) "p99999"))))
  (let* ((p (ho-write "string.tmj"
                      (ho-json-map "" more: (string-append "\"properties\":[{\"name\":\"long\",\"value\":\""
                                                           (ho-repeat ho-n (lambda (i) "a\\n")) "\"}],"))))
         (tm (load-tilemap p)))
    (test "json: a string of 200,000 characters with 100,000 escapes" (* 2 ho-n)
          (string-length (property-ref (tilemap-properties tm) "long")))))

;; Map sources that are not regular files: each load must fail at once
;; with an error naming the map and the source (before, a FIFO or
;; /dev/stdin blocked the loader for ever).
(import (chicken process))
(define fifo (make-pathname ho-dir "pipe.tsx"))
(system (sprintf "mkfifo '~a'" fifo))
(define (map-with-tileset source)
  (ho-write "source.tmx"
            (ho-map (string-append "<tileset firstgid=\"1\" source=\"" source "\"/>"
                                   "<layer id=\"1\" name=\"g\" width=\"1\" height=\"1\"><data encoding=\"csv\">0</data></layer>"))))
(let ((p (map-with-tileset "/dev/stdin")))
  (write (list "a tileset source of /dev/stdin" (ho-error (lambda () (load-tilemap p))))) (newline))
(let ((p (map-with-tileset fifo)))
  (write (list "a tileset source that is a FIFO" (ho-error (lambda () (load-tilemap p))))) (newline))
(write (list "a map that is a FIFO" (ho-error (lambda () (load-tilemap fifo))))) (newline)
(define json-fifo (make-pathname ho-dir "pipe.tmj"))
(system (sprintf "mkfifo '~a'" json-fifo))
(write (list "a .tmj map that is a FIFO" (ho-error (lambda () (load-tilemap json-fifo))))) (newline)
(let ((p (map-with-tileset json-fifo)))
  (write (list "a .tsj tileset source that is a FIFO" (ho-error (lambda () (load-tilemap p))))) (newline))
(write (list "a map path with a NUL byte" (ho-error (lambda () (load-tilemap (string-append "le" (string (integer->char 0)) "vel.tmx")))))) (newline)

(delete-directory ho-dir #t)
