;;; Pixel helpers shared by the suites that draw (included, not a suite):
;;; read back what a renderer drew or a PNG holds, and make small PNGs.
;;; Colours are lists (r g b a) of bytes.

(import (chicken base) srfi-4 (downstroke sdl2))

;; The colour at (x, y) of RGBA bytes laid out w pixels per row.
(define (rgba-at bytes w x y)
  (let ((i (* 4 (+ x (* y w)))))
    (list (u8vector-ref bytes i) (u8vector-ref bytes (+ i 1))
          (u8vector-ref bytes (+ i 2)) (u8vector-ref bytes (+ i 3)))))

(define (renderer-pixel r x y)
  (receive (bytes w h) (render-read-pixels r) (rgba-at bytes w x y)))

;; What the renderer drew, read once, as a procedure (x y) -> colour.
(define (renderer-pixels r)
  (receive (bytes w h) (render-read-pixels r) (lambda (x y) (rgba-at bytes w x y))))

;; (values bytes w h) of a PNG file, as RGBA.
(define (png-rgba path)
  (let ((s (img-load-surface! path)))
    (receive (bytes w h) (surface-pixels s)
      (free-surface! s)
      (values bytes w h))))

(define (png-pixel path x y)
  (receive (bytes w h) (png-rgba path) (rgba-at bytes w x y)))

;; How many pixels of the PNG inside the rectangle (x y w h) satisfy
;; (keep? colour); the rectangle is clipped to the image.
(define (png-count path keep? #!optional (x0 0) (y0 0) rw rh)
  (receive (bytes w h) (png-rgba path)
    (let ((x1 (min w (if rw (+ x0 rw) w))) (y1 (min h (if rh (+ y0 rh) h))))
      (let loop ((x (max 0 x0)) (y (max 0 y0)) (n 0))
        (cond ((>= y y1) n)
              ((>= x x1) (loop (max 0 x0) (+ y 1) n))
              (else (loop (+ x 1) y (if (keep? (rgba-at bytes w x y)) (+ n 1) n))))))))

;; A predicate: the colour's r g b are each within `tolerance` of `rgb`.
(define (near-colour? rgb #!optional (tolerance 0))
  (lambda (c)
    (let loop ((a rgb) (b c))
      (or (null? a)
          (and (<= (abs (- (car a) (car b))) tolerance) (loop (cdr a) (cdr b)))))))

;; A w x h PNG of one colour.
(define (write-solid-png! path w h r g b)
  (let* ((s (create-rgba-surface! w h))
         (rd (create-software-renderer! s)))
    (render-draw-color-set! rd r g b)
    (render-fill-rect! rd #f)
    (img-save-png! s path)
    (free-surface! s)))

(define (png-size path)
  (receive (bytes w h) (png-rgba path) (list w h)))

;; A row of square tiles of `size` px, one per colour (r g b), as a PNG.
(define (write-tiles-png! path size colours)
  (let* ((s (create-rgba-surface! (* size (length colours)) size))
         (rd (create-software-renderer! s)))
    (let loop ((cs colours) (x 0))
      (unless (null? cs)
        (apply render-draw-color-set! rd (car cs))
        (render-fill-rect! rd (make-rect x 0 size size))
        (loop (cdr cs) (+ x size))))
    (img-save-png! s path)
    (free-surface! s)))

;; An orthogonal TMX map of one CSV tile layer, `rows` a list of rows of
;; gids, drawn from one tileset image of `columns` x `tile-rows` tiles.
(define (write-csv-tmx! path image tile columns tile-rows rows)
  (let ((w (length (car rows))) (h (length rows)))
    (with-output-to-file path
      (lambda ()
        (print "<?xml version=\"1.0\" encoding=\"UTF-8\"?>")
        (print "<map version=\"1.10\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"" w
               "\" height=\"" h "\" tilewidth=\"" tile "\" tileheight=\"" tile "\" infinite=\"0\">")
        (print " <tileset firstgid=\"1\" name=\"t\" tilewidth=\"" tile "\" tileheight=\"" tile
               "\" tilecount=\"" (* columns tile-rows) "\" columns=\"" columns "\">")
        (print "  <image source=\"" image "\" width=\"" (* tile columns) "\" height=\"" (* tile tile-rows) "\"/>")
        (print " </tileset>")
        (print " <layer id=\"1\" name=\"g\" width=\"" w "\" height=\"" h "\">")
        (print "  <data encoding=\"csv\">")
        (let loop ((rows rows))
          (unless (null? rows)
            (let row ((gids (car rows)))
              (display (car gids))
              (when (or (pair? (cdr gids)) (pair? (cdr rows))) (display ","))
              (if (pair? (cdr gids)) (row (cdr gids)) (newline)))
            (loop (cdr rows))))
        (print "  </data>")
        (print " </layer>")
        (print "</map>")))))
