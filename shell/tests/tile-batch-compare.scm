;;; Included by tile-batch-test.scm, in its own process and in the child it
;;; runs in a real window: maps drawn with mapdraw.scm's C walk of tile
;;; layers (tile-layer-fast-path?, the default) against the cell-by-cell
;;; walk, pixel for pixel. Not a suite.

(import scheme (chicken base) (chicken format) (chicken file) (chicken pathname) srfi-4
        (downstroke sdl2) (downstroke scene) (downstroke camera) (downstroke tilemap)
        (downstroke renderer) (downstroke mapdraw) (downstroke level))

;; An 8 x 8 tile sheet of 4 x 2 tiles that tell every flip apart: each its
;; own colour, a white 3 x 2 mark in its top-left corner and a black pixel
;; at its top-right.
(define (tb-write-sheet! path shade)
  (let* ((s (create-rgba-surface! 32 16)) (r (create-software-renderer! s)))
    (do ((i 0 (+ i 1))) ((= i 8))
      (let ((x (* 8 (modulo i 4))) (y (* 8 (quotient i 4))))
        (render-draw-color-set! r (modulo (* 70 i) 256) (modulo (+ shade (* 40 i)) 256) (- 255 (* 30 i)))
        (render-fill-rect! r (make-rect x y 8 8))
        (render-draw-color-set! r 255 255 255)
        (render-fill-rect! r (make-rect x y 3 2))
        (render-draw-color-set! r 0 0 0)
        (render-fill-rect! r (make-rect (+ x 7) y 1 1))))
    (img-save-png! s path)
    (free-surface! s)))

;; The cell at (col, row) of layer k: every gid of both tilesets with
;; every combination of the three flip flags, and empty cells.
(define (tb-cell k col row)
  (let* ((h (modulo (+ (* 7 col) (* 13 row) (* 5 k) (* col row)) 23))
         (gid (+ 1 (modulo (+ col (* 3 row) k) 16)))
         (flags (list-ref '(0 #x80000000 #x40000000 #x20000000 #xC0000000 #xA0000000 #x60000000 #xE0000000)
                          (modulo (+ h row) 8))))
    (if (< h (+ 3 (* 4 k))) 0 (+ gid flags))))

(define (tb-layer-csv k w h)
  (let rows ((row 0) (out ""))
    (if (= row h)
        out
        (rows (+ row 1)
              (string-append out
                             (let cols ((col 0) (line ""))
                               (if (= col w)
                                   line
                                   (cols (+ col 1)
                                         (string-append line (number->string (tb-cell k col row))
                                                        (if (and (= row (- h 1)) (= col (- w 1))) "" ",")))))
                             "\n")))))

;; A 40 x 30 map in `order` of 8 x 8 cells: two tilesets (the second with
;; a tile offset and an animated tile), a plain layer, a translucent
;; tinted one and one with parallax and an offset.
(define (tb-write-map! dir order #!optional (a-height 8))
  (let ((path (make-pathname dir (string-append "batch-" order (if (= a-height 8) "" "-cut")) "tmx")))
    (with-output-to-file path
      (lambda ()
        (printf "<?xml version=\"1.0\" encoding=\"UTF-8\"?>
<map version=\"1.8\" orientation=\"orthogonal\" renderorder=\"~a\" width=\"40\" height=\"30\" tilewidth=\"8\" tileheight=\"8\" infinite=\"0\">
 <tileset firstgid=\"1\" name=\"a\" tilewidth=\"8\" tileheight=\"~a\" tilecount=\"8\" columns=\"4\">
  <image source=\"sheet-a.png\" width=\"32\" height=\"16\"/>
 </tileset>
 <tileset firstgid=\"9\" name=\"b\" tilewidth=\"8\" tileheight=\"8\" tilecount=\"8\" columns=\"4\">
  <tileoffset x=\"3\" y=\"-2\"/>
  <image source=\"sheet-b.png\" width=\"32\" height=\"16\"/>
  <tile id=\"1\"><animation><frame tileid=\"1\" duration=\"100\"/><frame tileid=\"5\" duration=\"100\"/></animation></tile>
 </tileset>
 <layer id=\"1\" name=\"ground\" width=\"40\" height=\"30\"><data encoding=\"csv\">
~a</data></layer>
 <layer id=\"2\" name=\"glass\" width=\"40\" height=\"30\" opacity=\"0.6\" tintcolor=\"#ff80c0\"><data encoding=\"csv\">
~a</data></layer>
 <layer id=\"3\" name=\"far\" width=\"40\" height=\"30\" offsetx=\"5\" offsety=\"-3\" parallaxx=\"0.5\" parallaxy=\"0.75\"><data encoding=\"csv\">
~a</data></layer>
</map>
" order a-height (tb-layer-csv 0 40 30) (tb-layer-csv 1 40 30) (tb-layer-csv 2 40 30))))
    path))

(define (tb-write-maps! dir)
  (tb-write-sheet! (make-pathname dir "sheet-a.png") 0)
  (tb-write-sheet! (make-pathname dir "sheet-b.png") 120)
  ;; the last: tileset a's tiles 8 x 12 on its 32 x 16 image, so the
  ;; second row's sources reach beyond the texture (SDL cuts them)
  (append (map (lambda (order) (tb-write-map! dir order)) '("right-down" "left-down" "right-up" "left-up"))
          (list (tb-write-map! dir "right-down" 12))))

;; The renderer's picture of the map through a camera at (x, y) at `time`
;; ms, with the fast path on or off.
(define (tb-picture r tm textures x y time fast?)
  (parameterize ((tile-layer-fast-path? fast?))
    (render-scene! r (make-scene tilemap: tm background: '(10 20 30)
                                 camera: (make-camera x: x y: y bounds: #f))
                   textures: textures time: time))
  (receive (bytes w h) (render-read-pixels r) bytes))

(define (tb-differing a b)
  (let loop ((i 0) (n 0))
    (if (>= i (u8vector-length a))
        n
        (loop (+ i 4)
              (if (and (= (u8vector-ref a i) (u8vector-ref b i))
                       (= (u8vector-ref a (+ i 1)) (u8vector-ref b (+ i 1)))
                       (= (u8vector-ref a (+ i 2)) (u8vector-ref b (+ i 2))))
                  n
                  (+ n 1))))))

;; For each camera and time: (label . pixels that differ) between the two
;; walks, and (label . pixels that are not the background) to show that
;; something was drawn.
(define tb-views '((0 0 0) (37 23 0) (-13 -9 150) (150 130 250) (5/2 7/3 99)))

(define (tb-compare r path)
  (let* ((tm (load-tilemap path))
         (textures (load-tilemap-textures! r tm)))
    (map (lambda (view)
           (let ((fast (apply tb-picture r tm textures (append view '(#t))))
                 (slow (apply tb-picture r tm textures (append view '(#f)))))
             (list (sprintf "~a at ~a" (pathname-file path) view)
                   (tb-differing fast slow)
                   (let loop ((i 0) (n 0))
                     (if (>= i (u8vector-length fast))
                         n
                         (loop (+ i 4) (if (= (u8vector-ref fast i) 10) n (+ n 1))))))))
         tb-views)))

;; Sprites drawn by the C walk with the copy queue (sprite-fast-path? and
;; render-batching?, the defaults) against one copy at a time by the
;; Scheme path: crowds of plain, mirrored, scaled, tinted, translucent and
;; turned sprites of two sheets, by #:z, between boxes, at whole and
;; fractional places, through cameras at whole and fractional places.
(define (tb-sprite-scenes dir)
  (let* ((a (make-pathname dir "sheet-a.png")) (b (make-pathname dir "sheet-b.png"))
         (sheet-a (make-sheet-tileset a tile-width: 8 tile-height: 8 columns: 4 name: "a"))
         (sheet-b (make-sheet-tileset b tile-width: 8 tile-height: 8 columns: 4 name: "b"))
         (crowd (lambda (n extra)
                  (let loop ((i 0) (out '()))
                    (if (= i n)
                        (reverse out)
                        (loop (+ i 1)
                              (cons (let* ((more (extra i))
                                           (given? (lambda (k) (let find ((l more))
                                                                 (and (pair? l) (or (eq? (car l) k) (find (cddr l)))))))
                                           (unless-given (lambda (k v) (if (given? k) '() (list k v)))))
                                      (append more
                                              (unless-given #:x (modulo (* i 37) 190))
                                              (unless-given #:y (modulo (* i 23) 140))
                                              (list #:width 8 #:height 8)
                                              (if (given? #:color) '() (unless-given #:tile-id (+ 1 (modulo i 8))))))
                                    out))))))
         (pick (lambda (i l) (list-ref l (modulo i (length l))))))
    (list
     (list "plain" sheet-a sheet-b (crowd 300 (lambda (i) '())) '(0 0))
     (list "mirrored and facing" sheet-a sheet-b
           (crowd 300 (lambda (i) (case (modulo i 4) ((0) '(#:flip-x? #t)) ((1) '(#:flip-y? #t))
                                        ((2) '(#:facing -1)) (else '(#:flip-x? #t #:facing -1)))))
           '(0 0))
     (list "two sheets, by z, between boxes" sheet-a sheet-b
           (crowd 300 (lambda (i) (append (list #:z (modulo i 3))
                                          (if (odd? i) '(#:tileset "b") '())
                                          (if (= 0 (modulo i 7)) '(#:color (200 10 10 180)) '()))))
           '(0 0))
     (list "scaled, tinted, translucent" sheet-a sheet-b
           (crowd 300 (lambda (i) (case (modulo i 3) ((0) '(#:scale 3/2)) ((1) '(#:tint (255 128 64)))
                                        (else '(#:alpha 150)))))
           '(0 0))
     (list "turned" sheet-a sheet-b
           (crowd 200 (lambda (i) (if (even? i) (list #:angle (* 7 i)) '())))
           '(0 0))
     (list "turned at many angles and scales, origins, offsets" sheet-a sheet-b
           (crowd 360 (lambda (i)
                        (list #:angle (pick i (list (* 7 i) (+ 0.5 (* 13 i)) 90 -270 180.0 45/2 (* 1.1 i)))
                              #:scale (pick i '(1 1/2 3/2 2 0.75 1.25 5/4 3))
                              #:origin-x (pick i '(0 4 8 1/2 2.5 -3))
                              #:origin-y (pick i '(0 4 7 3/4 6.25))
                              #:sprite-offset-x (pick i '(0 -3 5/2 1.5))
                              #:alpha (pick i '(255 200 127.5 90)))))
           '(0 0))
     (list "turned and mirrored, tinted, whole turns" sheet-a sheet-b
           (crowd 300 (lambda (i)
                        (append (list #:angle (pick i (list (+ 3 (* 11 i)) 360 -720 (+ 0.25 (* 5 i)) 1e-7 359.99)))
                                (pick i '((#:flip-x? #t) (#:flip-y? #t) (#:flip-x? #t #:flip-y? #t) () (#:facing -1)))
                                (pick i '(() (#:tint (255 128 64)) (#:alpha 100) (#:scale-x 3/2 #:scale-y 1/2))))))
           '(0 0))
     (list "fractional places and cameras, scales apart" sheet-a sheet-b
           (crowd 300 (lambda (i)
                        (append (list #:x (+ (modulo (* i 37) 190) (pick i '(0.37 -0.5 1/4 0.999 0)))
                                      #:y (+ (modulo (* i 23) 140) (pick i '(0.5 3/8 -0.25 0))))
                                (pick i '(() (#:scale-x 5/4 #:scale-y 0.8) (#:scale-x 1.5 #:flip-y? #t)
                                          (#:sprite-offset-y -2.75 #:facing -1) (#:scale 1/2 #:origin-x 0))))))
           '(2.5 -1.75))
     (list "tints and alphas held to 0-255, boxes, nothing" sheet-a sheet-b
           (crowd 300 (lambda (i)
                        (pick i (list '(#:tint (300 -5 127.5)) '(#:tint (10 20 30 40)) '(#:alpha 127.5)
                                      '(#:alpha 0) '(#:alpha -3 #:tint (0 255 0)) '(#:alpha 1000)
                                      '(#:color (0 200 0)) '(#:tint (color 90 90 250)) '(#:alpha 2.5)
                                      '(#:tile-id #f #:animations #f) '(#:scale 0 #:tint (1 2 3))))))
           '(3/2 -5/4))
     (list "what the walk leaves to Scheme: far, huge, thirds" sheet-a sheet-b
           (crowd 120 (lambda (i)
                        (pick i (list '(#:x 1000000000) (list #:x (+ 20 (/ i 3))) '(#:scale 1e200)
                                      (list #:y (- 1/3 (modulo i 50)) #:angle 10)
                                      '(#:sprite-offset-x 20000) '(#:tile-id 100000)
                                      '()))))
           '(0 0))
     (list "through a camera at thirds (left to Scheme)" sheet-a sheet-b
           (crowd 100 (lambda (i) (if (even? i) '(#:scale 3/2 #:angle 30) '())))
           '(1/3 2/3))
     ;; more quads than one run of the copy queue holds (tiles.c's
     ;; DS_BATCH_QUADS, 4,096): three runs, in order
     (list "a crowd longer than two runs (9,000)" sheet-a sheet-b
           (crowd 9000 (lambda (i) (case (modulo i 5) ((0) '(#:alpha 160)) ((1) (list #:angle (* 3 i)))
                                         ((2) '(#:tint (255 128 64))) (else '()))))
           '(0 0)))))

(define (tb-compare-sprites r dir)
  (let ((tex-a (img-load-texture! r (make-pathname dir "sheet-a.png")))
        (tex-b (img-load-texture! r (make-pathname dir "sheet-b.png"))))
    (map (lambda (case)
           (let* ((camera (list-ref case 4))
                  (scene (make-sprite-scene tileset: (cadr case) tileset-texture: tex-a
                                            tilesets: (list (caddr case)) background: '(10 20 30)
                                            camera: (make-camera x: (car camera) y: (cadr camera) bounds: #f)
                                            entities: (cadddr case)))
                  (textures (list (cons (make-pathname dir "sheet-b.png") tex-b)
                                  (cons (make-pathname dir "sheet-a.png") tex-a)))
                  (picture (lambda (fast? batch?)
                             (parameterize ((render-batching? batch?) (sprite-fast-path? fast?))
                               (render-scene! r scene textures: textures))
                             (receive (bytes w h) (render-read-pixels r) bytes)))
                  ;; the C walk queued, the C walk copy by copy, against Scheme copy by copy
                  (walk (picture #t #t)) (walk-direct (picture #t #f)) (scheme (picture #f #f)))
             (list (sprintf "sprites: ~a" (car case))
                   (+ (tb-differing walk scheme) (tb-differing walk-direct scheme))
                   (let loop ((i 0) (n 0))
                     (if (>= i (u8vector-length walk)) n
                         (loop (+ i 4) (if (= (u8vector-ref walk i) 10) n (+ n 1))))))))
         (tb-sprite-scenes dir))))
