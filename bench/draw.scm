;;; Drawing benchmark against LÖVE (docs/performance.org, "Drawing against
;;; LÖVE"): the same work as bench/love/main.lua, in a real 800 x 600
;;; window through SDL's accelerated renderer (opengl on Mesa llvmpipe
;;; under Xvfb). Scenes:
;;;   sprites N       N 16 x 16 sprites of one 64 x 16 sheet, every one moved
;;;                   each frame (x += 1 + i mod 3, wrapping in the window);
;;;   fancy N         the same with #:angle (turning 2 degrees a frame),
;;;                   #:scale 1.5 and #:alpha 160;
;;;   map             a 200 x 200 map of 16 x 16 tiles in three layers (the
;;;                   ground full, the two others a third and a tenth full)
;;;                   through an 800 x 600 camera moving (3, 2) px a frame.
;;; For each scene it prints the CPU time (user + system, all threads: the
;;; driver's too) per frame, in ms, of FRAMES frames (default 300) after 30
;;; of warm-up; a frame is the update, render-scene! and render-present!;
;;; then the places drawn (as bench/love prints them).
;;;
;;;   xvfb-run -a -s "-screen 0 1024x768x24" env CHICKEN_REPOSITORY_PATH=build:$(env -u CHICKEN_INSTALL_REPOSITORY chicken-install -repository) \
;;;     csi -q -s bench/draw.scm SCENE [N]
;;;
;;; SCENE is sprites, fancy or map. The line printed names the renderer
;;; SDL chose.

(import scheme (chicken base) (chicken format) (chicken file) (chicken time)
        (chicken process-context) (chicken bitwise) srfi-4
        (downstroke sdl2) (downstroke map) (downstroke scene) (downstroke camera) (downstroke entity)
        (downstroke renderer))

(define args (command-line-arguments))
(define scene-name (if (pair? args) (car args) "sprites"))
(define n (or (and (> (length args) 1) (string->number (cadr args))) 1000))
(define frames (string->number (or (get-environment-variable "FRAMES") "300")))
(define warm-up 30)
(define win-w 800)
(define win-h 600)

(init! '(video))
(define window (create-window! "draw bench" 0 0 win-w win-h))
(define r (create-renderer! window))

;; Sheets made at run time: 4 coloured 16 x 16 tiles with a dark border.
(define dir (create-temporary-directory))
(define (write-sheet! path columns rows)
  (let* ((s (create-rgba-surface! (* 16 columns) (* 16 rows)))
         (sr (create-software-renderer! s)))
    (do ((i 0 (+ i 1))) ((= i (* columns rows)))
      (let ((x (* 16 (remainder i columns))) (y (* 16 (quotient i columns))))
        (render-draw-color-set! sr (modulo (* 60 i) 256) 200 (modulo (- 255 (* 37 i)) 256))
        (render-fill-rect! sr (make-rect x y 16 16))
        (render-draw-color-set! sr 0 0 0)
        (render-draw-rect! sr (make-rect x y 16 16))))
    (img-save-png! s path)
    (free-surface! s)))

(define sheet-png (string-append dir "/sheet.png"))
(write-sheet! sheet-png 4 1)
(define sheet (make-sheet-tileset sheet-png tile-width: 16 tile-height: 16 columns: 4))
(define sheet-tex (img-load-texture! r sheet-png))

;; The integer generator of docs/performance.org's scenes.
(define seed 20261121)
(define (draw!) (set! seed (modulo (+ (* 1103515245 seed) 12345) 2147483648)) seed)

;; What the scene drew, printed after the time as bench/love prints it
;; (tools/bench-draw.sh checks that both sides drew the same): sprites, the
;; sums of their first x and y; the map, its cells and the sum of their
;; tile numbers.
(define places "")
(define (places-set! a b) (set! places (sprintf "~a/~a" a b)))

;; The scene is made once, as a game makes its level; each frame its
;; update moves every entity (#:x += #:dx, wrapping; fancy: #:angle += 2),
;; as a game's update: hook would, and the frame draws the scene it
;; returns. (Until this was so, the bench made a new scene every frame,
;; and the new scene's checks of every entity were 6% of a frame that a
;; game does not pay.)
(define (sprite-scene fancy?)
  (let ((entities
         (let make ((i 0) (out '()))
           (if (= i n)
               (reverse out)
               (let* ((x (modulo (draw!) (- win-w 16))) (y (modulo (draw!) (- win-h 16))))
                 (make (+ i 1)
                       (cons (append (list #:x x #:y y #:dx (+ 1 (modulo i 3)) #:tile-id (+ 1 (modulo i 4)))
                                     (if fancy? (list #:angle (modulo (* 2 i) 360) #:scale 3/2 #:alpha 160) '()))
                             out)))))))
    (places-set! (foldl + 0 (map cadr entities)) (foldl + 0 (map cadddr entities)))
    (let ((scene (make-sprite-scene tileset: sheet tileset-texture: sheet-tex background: '(0 0 0)
                                    entities: entities))
          (move (lambda (s e)
                  (let ((e (entity-set e #:x (modulo (+ (entity-ref e #:x) (entity-ref e #:dx)) (- win-w 16)))))
                    (if fancy? (entity-set e #:angle (modulo (+ (entity-ref e #:angle) 2) 360)) e)))))
      (lambda (f)
        (unless (= f 0) (set! scene (scene-map-entities scene move)))
        scene))))

(define map-png (string-append dir "/tiles.png"))
(write-sheet! map-png 4 4)
(define map-tileset (make-sheet-tileset map-png tile-width: 16 tile-height: 16 columns: 4))
(define map-tex (img-load-texture! r map-png))

(define (map-layer name percent)
  (let ((data (make-u32vector (* 200 200) 0)))
    (do ((i 0 (+ i 1))) ((= i (* 200 200)))
      (when (< (modulo (draw!) 100) percent)
        (u32vector-set! data i (+ 1 (modulo (draw!) 16)))))
    (make-layer name 200 200 data)))

(define (map-scene)
  (let* ((layers (list (map-layer "ground" 100) (map-layer "middle" 33) (map-layer "top" 10)))
         (tm (make-tilemap 200 200 16 16 layers tilesets: (list map-tileset)))
         (max-x (- (* 200 16) win-w)) (max-y (- (* 200 16) win-h)))
    (let count ((i 0) (cells 0) (sum 0))
      (if (= i (* 200 200 3))
          (places-set! cells sum)
          (let ((gid (u32vector-ref (layer-data (list-ref layers (quotient i (* 200 200))))
                                    (remainder i (* 200 200)))))
            (count (+ i 1) (if (zero? gid) cells (+ cells 1)) (+ sum gid)))))
    (lambda (f)
      (make-scene tilemap: tm background: '(0 0 0) camera-target: #f
                  camera: (make-camera x: (modulo (* 3 f) max-x) y: (modulo (* 2 f) max-y))))))

(define make-frame
  (cond ((equal? scene-name "sprites") (sprite-scene #f))
        ((equal? scene-name "fancy") (sprite-scene #t))
        ((equal? scene-name "map") (map-scene))
        (else (error 'bench/draw "unknown scene (sprites, fancy, map)" scene-name))))

(define textures (list (cons map-png map-tex)))

(define (frame! f)
  (render-scene! r (make-frame f) textures: textures)
  (render-present! r)
  (poll-events!))

(do ((f 0 (+ f 1))) ((= f warm-up)) (frame! f))
(define (cpu-ms) (receive (user system) (cpu-time) (+ user system)))
(let ((t0 (cpu-ms)) (w0 (current-milliseconds)))
  (do ((f warm-up (+ f 1))) ((= f (+ warm-up frames))) (frame! f))
  (let ((cpu (- (cpu-ms) t0)) (wall (- (current-milliseconds) w0)))
    (printf "draw ~a ~a (~a): ~a ms CPU per frame, ~a ms wall, places ~a~%"
            scene-name (if (equal? scene-name "map") "200x200x3" n) (renderer-name r)
            (/ (round (* 1000 (/ cpu frames))) 1000.)
            (/ (round (* 1000 (/ wall frames))) 1000.)
            places)))
(destroy-texture! sheet-tex)
(destroy-texture! map-tex)
(delete-directory dir #t)
(quit!)
