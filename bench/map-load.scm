;;; Map-load benchmark: a 1024 x 1024 one-layer map written in base64+zlib and
;;; in CSV (TMX), and in Tiled's JSON as base64+zlib and as an array of
;;; cells (.tmj), into a temporary directory, each loaded several times with
;;; load-tilemap. Prints the median load time and cells per second.
;;;
;;;   CHICKEN_REPOSITORY_PATH=build:$(env -u CHICKEN_INSTALL_REPOSITORY chicken-install -repository) csi -q -s bench/map-load.scm [RUNS]

(import scheme (chicken base) (chicken format) (chicken file) (chicken pathname)
        (chicken time) (chicken sort) (chicken file posix) (chicken process-context) (chicken bitwise)
        srfi-4 (downstroke decode) (downstroke tilemap))

(define size 1024)
(define cells (* size size))
(define runs (let ((args (command-line-arguments)))
               (or (and (pair? args) (string->number (car args))) 7)))

;; A level-like pattern: ground rows, scattered tiles, some flipped cells.
(define (cell i)
  (let ((col (remainder i size)) (row (quotient i size)))
    (cond ((> row 900) (+ 1 (remainder col 8)))
          ((zero? (remainder (* col row) 37)) (bitwise-ior 9 #x80000000))
          ((zero? (remainder (+ col (* 3 row)) 11)) 12)
          (else 0))))

(define (header data)
  (string-append
   "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
   (sprintf "<map version=\"1.10\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"~a\" height=\"~a\" tilewidth=\"16\" tileheight=\"16\" infinite=\"0\">\n" size size)
   " <tileset firstgid=\"1\" name=\"t\" tilewidth=\"16\" tileheight=\"16\" tilecount=\"16\" columns=\"4\">\n"
   "  <image source=\"tiles.png\" width=\"64\" height=\"64\"/>\n </tileset>\n"
   (sprintf " <layer id=\"1\" name=\"ground\" width=\"~a\" height=\"~a\">\n" size size)
   data " </layer>\n</map>\n"))

(define (zlib-map)
  (header (string-append "  <data encoding=\"base64\" compression=\"zlib\">\n   "
                         (zlib-base64) "\n  </data>\n")))

(define (csv-map)
  (let ((out (open-output-string)))
    (do ((i 0 (+ i 1))) ((= i cells))
      (display (cell i) out)
      (unless (= i (- cells 1))
        (display (if (= (remainder (+ i 1) size) 0) ",\n" ",") out)))
    (header (string-append "  <data encoding=\"csv\">\n" (get-output-string out) "\n</data>\n"))))

(define (json-map layer-data)
  (string-append
   (sprintf "{\"type\":\"map\",\"version\":\"1.10\",\"orientation\":\"orthogonal\",\"renderorder\":\"right-down\",\"width\":~a,\"height\":~a,\"tilewidth\":16,\"tileheight\":16,\"infinite\":false,\n" size size)
   " \"tilesets\":[{\"firstgid\":1,\"name\":\"t\",\"tilewidth\":16,\"tileheight\":16,\"tilecount\":16,\"columns\":4,\"image\":\"tiles.png\",\"imagewidth\":64,\"imageheight\":64}],\n"
   (sprintf " \"layers\":[{\"type\":\"tilelayer\",\"id\":1,\"name\":\"ground\",\"width\":~a,\"height\":~a,\"x\":0,\"y\":0,\"opacity\":1,\"visible\":true,\n" size size)
   layer-data "}]}\n"))

(define (zlib-base64)
  (let ((bytes (make-u8vector (* 4 cells) 0)))
    (do ((i 0 (+ i 1))) ((= i cells))
      (let ((c (cell i)))
        (u8vector-set! bytes (* 4 i) (bitwise-and c 255))
        (u8vector-set! bytes (+ (* 4 i) 1) (bitwise-and (arithmetic-shift c -8) 255))
        (u8vector-set! bytes (+ (* 4 i) 2) (bitwise-and (arithmetic-shift c -16) 255))
        (u8vector-set! bytes (+ (* 4 i) 3) (bitwise-and (arithmetic-shift c -24) 255))))
    (base64-encode (zlib-deflate bytes))))

(define (json-zlib-map)
  (json-map (string-append "  \"encoding\":\"base64\",\"compression\":\"zlib\",\"data\":\""
                           (zlib-base64) "\"")))

;; As Tiled writes a JSON layer: one array, a row to a line.
(define (json-array-map)
  (let ((out (open-output-string)))
    (display "  \"data\":[" out)
    (do ((i 0 (+ i 1))) ((= i cells))
      (display (cell i) out)
      (unless (= i (- cells 1))
        (display (if (= (remainder (+ i 1) size) 0) ",\n" ", ") out)))
    (display "]" out)
    (json-map (get-output-string out))))

(define (median xs)
  (let* ((s (sort xs <)) (n (length s)))
    (if (odd? n)
        (list-ref s (quotient n 2))
        (/ (+ (list-ref s (- (quotient n 2) 1)) (list-ref s (quotient n 2))) 2))))

(define dir (create-temporary-directory))
;; The loader checks that the tileset image exists; it never decodes it.
(with-output-to-file (make-pathname dir "tiles.png") (lambda () (display "placeholder")))

(define (bench name text #!optional (ext "tmx"))
  (let ((path (make-pathname dir (string-append name "." ext))))
    (with-output-to-file path (lambda () (display text)))
    (load-tilemap path)                 ; warm-up, and a check that it loads
    (let* ((times (let loop ((k 0) (acc '()))
                    (if (= k runs)
                        acc
                        (let ((t0 (current-process-milliseconds)))
                          (load-tilemap path)
                          (loop (+ k 1) (cons (- (current-process-milliseconds) t0) acc))))))
           (ms (median times)))
      (printf "map-load ~a: ~ax~a, ~a bytes, median of ~a runs: ~a ms, ~a cells/s~%"
              name size size (file-size path) runs (exact->inexact ms)
              (if (> ms 0) (inexact->exact (round (/ (* cells 1000) ms))) "inf"))
      (delete-file path))))

(bench "base64+zlib" (zlib-map))
(bench "csv" (csv-map))
(bench "json base64+zlib" (json-zlib-map) "tmj")
(bench "json array" (json-array-map) "tmj")
(delete-directory dir #t)
