;;; Writes the fixture maps of tests/maps/ (run from the egg's directory:
;;;   CHICKEN_REPOSITORY_PATH=build:$(env -u CHICKEN_INSTALL_REPOSITORY chicken-install -repository) \
;;;     csi -q -s tools/make-tmx-fixtures.scm
;;; The files are committed; this script documents how the encoded ones were
;;; made (it uses only the encoders of (downstroke decode), never the loader).
;;; The cell values every encoding holds are `tmx-cells` in tiled/tests/tmx-test.scm.

(import scheme (chicken base) (chicken format) (chicken file) (chicken string)
        (chicken bitwise) srfi-4 (downstroke decode))

(define dir "tests/maps")

;; The 4 x 3 grid every encoding fixture holds (raw 32-bit cells).
(define H #x80000000) (define V #x40000000) (define D #x20000000) (define X #x10000000)
(define cells
  (list 1 (bitwise-ior 2 H) 0 3
        0 (bitwise-ior 4 V) (bitwise-ior 5 D) 0
        (bitwise-ior 6 H V D) 0 (bitwise-ior 7 X) 8))

(define (cells->bytes cells)
  (let ((v (make-u8vector (* 4 (length cells)) 0)))
    (let loop ((cs cells) (i 0))
      (unless (null? cs)
        (let ((c (car cs)))
          (u8vector-set! v i (bitwise-and c 255))
          (u8vector-set! v (+ i 1) (bitwise-and (arithmetic-shift c -8) 255))
          (u8vector-set! v (+ i 2) (bitwise-and (arithmetic-shift c -16) 255))
          (u8vector-set! v (+ i 3) (bitwise-and (arithmetic-shift c -24) 255)))
        (loop (cdr cs) (+ i 4))))
    v))

(define (csv cells width)
  (let loop ((cs cells) (i 0) (out ""))
    (if (null? cs)
        out
        (loop (cdr cs) (+ i 1)
              (string-append out (number->string (car cs))
                             (cond ((null? (cdr cs)) "")
                                   ((= (remainder (+ i 1) width) 0) ",\n")
                                   (else ",")))))))

(define (write-file name text)
  (with-output-to-file (string-append dir "/" name) (lambda () (display text))))

(define (encoding-map data-element)
  (string-append
   "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
   "<map version=\"1.10\" tiledversion=\"1.10.2\" orientation=\"orthogonal\" renderorder=\"right-down\""
   " width=\"4\" height=\"3\" tilewidth=\"16\" tileheight=\"16\" infinite=\"0\" nextlayerid=\"2\" nextobjectid=\"1\">\n"
   " <tileset firstgid=\"1\" source=\"tilesets/terrain.tsx\"/>\n"
   " <layer id=\"1\" name=\"ground\" width=\"4\" height=\"3\">\n"
   data-element
   " </layer>\n"
   "</map>\n"))

(define bytes (cells->bytes cells))

(write-file "enc-csv.tmx"
  (encoding-map (sprintf "  <data encoding=\"csv\">\n~a\n</data>\n" (csv cells 4))))
(write-file "enc-xml.tmx"
  (encoding-map
   (string-append "  <data>\n"
                  (apply string-append
                         (map (lambda (c) (if (zero? c) "   <tile/>\n" (sprintf "   <tile gid=\"~a\"/>\n" c)))
                              cells))
                  "  </data>\n")))
(write-file "enc-base64.tmx"
  (encoding-map (sprintf "  <data encoding=\"base64\">\n   ~a\n  </data>\n" (base64-encode bytes))))
(for-each
 (lambda (name compress)
   (write-file (sprintf "enc-~a.tmx" name)
     (encoding-map (sprintf "  <data encoding=\"base64\" compression=\"~a\">\n   ~a\n  </data>\n"
                            name (base64-encode (compress bytes))))))
 '("zlib" "gzip" "zstd")
 (list zlib-deflate gzip-deflate zstd-compress))

;; Infinite map: layer "a" has chunks at (-4, -4) and (0, 0), layer "b"
;; (base64 + zstd) one at (4, -8); 4 x 4 chunks. Chunk cells: the chunk's
;; first cell is 1 + its index in the file, the others 0, except the last
;; (bottom-right) which is 20 + index, flipped vertically in layer b.
(define (chunk-cells first last)
  (append (list first) (vector->list (make-vector 14 0)) (list last)))
(write-file "infinite.tmx"
  (string-append
   "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
   "<map version=\"1.10\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"30\" height=\"20\""
   " tilewidth=\"16\" tileheight=\"16\" infinite=\"1\" nextlayerid=\"3\" nextobjectid=\"1\">\n"
   " <tileset firstgid=\"1\" source=\"tilesets/terrain.tsx\"/>\n"
   " <layer id=\"1\" name=\"a\" width=\"30\" height=\"20\">\n"
   "  <data encoding=\"csv\">\n"
   (sprintf "   <chunk x=\"-4\" y=\"-4\" width=\"4\" height=\"4\">\n~a\n</chunk>\n" (csv (chunk-cells 1 5) 4))
   (sprintf "   <chunk x=\"0\" y=\"0\" width=\"4\" height=\"4\">\n~a\n</chunk>\n" (csv (chunk-cells 2 6) 4))
   "  </data>\n </layer>\n"
   " <layer id=\"2\" name=\"b\" width=\"30\" height=\"20\">\n"
   "  <data encoding=\"base64\" compression=\"zstd\">\n"
   (sprintf "   <chunk x=\"4\" y=\"-8\" width=\"4\" height=\"4\">~a</chunk>\n"
            (base64-encode (zstd-compress (cells->bytes (chunk-cells 3 (bitwise-ior 7 V))))))
   "  </data>\n </layer>\n"
   "</map>\n"))
(print "fixtures written to " dir)
