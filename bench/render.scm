;;; Render benchmark: a tile map drawn through a 320 x 240 camera at scale 3
;;; with SDL's software renderer (a 960 x 720 RGBA surface, logical size
;;; 320 x 240), the camera moving every frame. For each map size (64 x 64,
;;; 256 x 256, 1024 x 1024 cells of 16 x 16 px) it prints the median over
;;; RUNS runs (default 5) of the mean ms per frame of 300 frames. A frame is
;;; render-scene! (clear, the cells the view touches, no entities) and
;;; render-present!. Only the cells inside the view are drawn, so the cost
;;; must not grow with the map's size.
;;;
;;;   SDL_VIDEODRIVER=dummy CHICKEN_REPOSITORY_PATH=build:$(env -u CHICKEN_INSTALL_REPOSITORY chicken-install -repository) \
;;;     csi -q -s bench/render.scm [RUNS]
;;;
;;; The tileset is a 64 x 64 PNG of 16 tiles (16 x 16 px), generated at run
;;; time in a temporary directory; its tileset record comes from a one-cell
;;; TMX written next to it, and is attached to a list->tilemap map with
;;; make-tilemap's tilesets:; the texture reaches render-scene! through
;;; its textures: option.

(import scheme (chicken base) (chicken format) (chicken file) (chicken time)
        (chicken sort) (chicken process-context) (chicken bitwise) srfi-4
        (downstroke sdl2) (downstroke tilemap) (downstroke scene)
        (downstroke renderer))

(unless (get-environment-variable "SDL_VIDEODRIVER")
  (set-environment-variable! "SDL_VIDEODRIVER" "dummy"))

(define runs (let ((args (command-line-arguments)))
               (or (and (pair? args) (string->number (car args))) 5)))
(define frames 300)
(define view-w 320)
(define view-h 240)
(define scale 3)
(define tile 16)

(define dir (create-temporary-directory))
(define tiles-png (string-append dir "/tiles.png"))
(define tileset-tmx (string-append dir "/tileset.tmx"))

;; 16 tiles in a 4 x 4 grid, each a different colour with a darker border.
(define (write-tileset-png!)
  (let* ((s (create-rgba-surface! 64 64))
         (r (create-software-renderer! s)))
    (do ((i 0 (+ i 1))) ((= i 16))
      (let ((x (* 16 (remainder i 4))) (y (* 16 (quotient i 4))))
        (render-draw-color-set! r (* 15 i) (- 255 (* 15 i)) (* 7 i))
        (render-fill-rect! r (make-rect x y 16 16))
        (render-draw-color-set! r 0 0 0)
        (render-draw-rect! r (make-rect x y 16 16))))
    (img-save-png! s tiles-png)
    (free-surface! s)))

(define (write-tileset-tmx!)
  (with-output-to-file tileset-tmx
    (lambda ()
      (display "<?xml version=\"1.0\" encoding=\"UTF-8\"?>
<map version=\"1.10\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"1\" height=\"1\" tilewidth=\"16\" tileheight=\"16\" infinite=\"0\">
 <tileset firstgid=\"1\" name=\"bench\" tilewidth=\"16\" tileheight=\"16\" tilecount=\"16\" columns=\"4\">
  <image source=\"tiles.png\" width=\"64\" height=\"64\"/>
 </tileset>
 <layer id=\"1\" name=\"l\" width=\"1\" height=\"1\">
  <data encoding=\"csv\">1</data>
 </layer>
</map>
"))))

;; A level-like pattern: mostly filled, some empty cells, some flipped ones.
(define (cell col row)
  (let ((h (remainder (+ (* col 7) (* row 13) (* col row)) 31)))
    (cond ((< h 4) 0)
          ((= h 5) (bitwise-ior (+ 1 (remainder col 16)) #x80000000))
          ((= h 6) (bitwise-ior (+ 1 (remainder row 16)) #x40000000))
          (else (+ 1 (remainder (+ col row) 16))))))

(define (make-map size tilesets)
  (let* ((base (list->tilemap
                (let rows ((row 0))
                  (if (= row size)
                      '()
                      (cons (let cols ((col 0))
                              (if (= col size) '() (cons (cell col row) (cols (+ col 1)))))
                            (rows (+ row 1)))))
                tile-width: tile tile-height: tile)))
    (make-tilemap size size tile tile (tilemap-layers base) tilesets: tilesets)))

;; ms per frame of one run of `frames` frames, the camera moving diagonally
;; (a few pixels a frame, wrapping inside the map).
(define (run-once r tm textures)
  (let* ((max-x (- (tilemap-pixel-width tm) view-w))
         (max-y (- (tilemap-pixel-height tm) view-h))
         (t0 (current-milliseconds)))
    (do ((i 0 (+ i 1))) ((= i frames))
      (let ((scene (make-scene tilemap: tm background: '(20 20 40) camera-target: #f
                               camera: (make-camera x: (remainder (* i 7) max-x)
                                                    y: (remainder (* i 5) max-y)))))
        (render-scene! r scene textures: textures)
        (render-present! r)))
    (/ (- (current-milliseconds) t0) (exact->inexact frames))))

;; The benchmark measures real drawing: cell (1, 0) holds gid 2, whose
;; colour is (15 240 7); at scale 3 its centre is output pixel (72, 24).
(define (check-drawn! r tm textures)
  (render-scene! r (make-scene tilemap: tm camera-target: #f) textures: textures)
  (receive (px w h) (render-read-pixels r)
    (let* ((i (* 4 (+ 72 (* 24 w))))
           (rgb (list (u8vector-ref px i) (u8vector-ref px (+ i 1)) (u8vector-ref px (+ i 2)))))
      (unless (equal? rgb '(15 240 7))
        (error 'bench/render "the tiles were not drawn: pixel (72, 24) is" rgb)))))

(define (median xs)
  (let ((s (sort xs <)) (n (length xs)))
    (if (odd? n)
        (list-ref s (quotient n 2))
        (/ (+ (list-ref s (- (quotient n 2) 1)) (list-ref s (quotient n 2))) 2))))

(init! '(video))
(write-tileset-png!)
(write-tileset-tmx!)
(let* ((surface (create-rgba-surface! (* scale view-w) (* scale view-h)))
       (r (create-software-renderer! surface))
       (tilesets (tilemap-tilesets (load-tilemap tileset-tmx)))
       (tex (img-load-texture! r tiles-png))
       (textures (list (cons (image-source (tileset-image (car tilesets))) tex))))
  (render-set-logical-size! r view-w view-h)
  (for-each
   (lambda (size)
     (let* ((tm (make-map size tilesets))
            (_ (run-once r tm textures))   ; warm-up
            (_ (check-drawn! r tm textures))
            (ms (let loop ((i 0)) (if (= i runs) (quote ()) (cons (run-once r tm textures) (loop (+ i 1)))))))
       (printf "render ~ax~a map, ~ax~a view at scale ~a (software, ~ax~a): ~a ms/frame (median of ~a runs of ~a frames; min ~a, max ~a)~%"
               size size view-w view-h scale (* scale view-w) (* scale view-h)
               (/ (round (* 1000 (median ms))) 1000)
               runs frames
               (/ (round (* 1000 (apply min ms))) 1000)
               (/ (round (* 1000 (apply max ms))) 1000))))
   '(64 256 1024))
  (destroy-texture! tex)
  (free-surface! surface))
(quit!)
(delete-directory dir #t)
