;;; Tile layers drawn in one call into C (sdl2.scm's render-tile-cells!,
;;; shell/tiles.c; mapdraw.scm's fast path): what it draws, that no input
;;; makes it read outside its arrays, that it draws what the cell-by-cell
;;; walk draws pixel for pixel (with SDL's software renderer here, and in a
;;; child process with a real window under xvfb-run, where SDL's renderer
;;; is opengl and runs of cells go out as SDL_RenderGeometry calls), and
;;; that what it keeps between frames (mapdraw.scm's gid tables) never
;;; shows a stale picture.

(import scheme (chicken base) (chicken file) (chicken format) (chicken string)
        (chicken process) (chicken pathname) (chicken process-context) (chicken io)
        srfi-4 (downstroke test) (downstroke sdl2) (downstroke scene) (downstroke camera)
        (downstroke tilemap) (downstroke renderer) (downstroke mapdraw) (downstroke level))
(include-relative "../../tests/pixels.scm")
(include-relative "tile-batch-compare.scm")

(define (filter-files dir ext)
  (if (directory-exists? dir)
      (let loop ((fs (directory dir)) (out '()))
        (cond ((null? fs) (reverse out))
              ((and (equal? (pathname-extension (car fs)) ext)
                    (not (substring-index "hostile" (car fs)))
                    (not (substring-index "infinite" (car fs))))
               (loop (cdr fs) (cons (make-pathname dir (car fs)) out)))
              (else (loop (cdr fs) out))))
      '()))
(define (filter-map f l)
  (cond ((null? l) '()) ((f (car l)) => (lambda (v) (cons v (filter-map f (cdr l))))) (else (filter-map f (cdr l)))))
(define (string-prefix? p s) (and (>= (string-length s) (string-length p)) (string=? p (substring s 0 (string-length p)))))

(init!)
(define tb-dir (create-temporary-directory))

(define tb-surface (create-rgba-surface! 64 32))
(define tb-r (create-software-renderer! tb-surface))
(tb-write-sheet! (make-pathname tb-dir "sheet-a.png") 0)
(define tb-tex (img-load-texture! tb-r (make-pathname tb-dir "sheet-a.png")))

;; A table for gids 1 and 2: tiles 0 and 3 of sheet-a, no offset.
(define (tb-table . extra)
  (let ((t (make-s32vector 24 0)))
    (for-each (lambda (i v) (s32vector-set! t i v))
              '(8 9 10 11 12 16 17 18 19 20) '(1 0 0 8 8 1 24 0 8 8))
    (let loop ((e extra)) (unless (null? e) (s32vector-set! t (car e) (cadr e)) (loop (cddr e))))
    t))

;; Cells c0..c1 x r0..r1 of a 4 x 2 layer `data` drawn at fx fy over black.
(define (tb-cells data table c0 c1 r0 r1 #!key (fx 0) (fy 0) (textures (vector tb-tex))
                  (width 4) (height 2) (order 0) (pass 1))
  (render-draw-color-set! tb-r 0 0 0)
  (render-clear! tb-r)
  (render-tile-cells! tb-r textures data width height 0 0 c0 c1 r0 r1 order table 8 8 fx fy 64 32 pass
                      (make-u8vector 64 0)))

(define (tb-px x y) (take (renderer-pixel tb-r x y) 3))
(define (take l n) (if (= n 0) '() (cons (car l) (take (cdr l) (- n 1)))))
(define tile0 '(0 0 255))               ; tb-write-sheet!'s colour of tile 0 (shade 0)
(define tile3 '(210 120 165))           ; and of tile 3
(define black '(0 0 0))

(test-group "render-tile-cells!: what it draws"
  (test "tile 0 and tile 3 where their cells are, white marks top-left"
        (list tile0 '(255 255 255) tile3 '(255 255 255) black)
        (begin (tb-cells (u32vector 1 2 0 0 0 0 0 0) (tb-table) 0 3 0 1)
               (list (tb-px 4 4) (tb-px 0 0) (tb-px 12 4) (tb-px 8 0) (tb-px 20 4))))
  (test "a horizontally flipped cell has its mark top-right"
        (list '(255 255 255) tile0 black)
        (begin (tb-cells (u32vector (+ 1 #x80000000) 0 0 0 0 0 0 0) (tb-table) 0 3 0 1)
               (list (tb-px 7 0) (tb-px 1 0) (tb-px 0 0))))
  (test "fx fy move every cell" (list black tile0 '(255 255 255))
        (begin (tb-cells (u32vector 1 0 0 0 0 0 0 0) (tb-table) 0 3 0 1 fx: 10 fy: 5)
               (list (tb-px 4 4) (tb-px 15 10) (tb-px 10 5))))
  (test "pass 0 draws nothing and marks the textures used"
        '((0 0 0) 1)
        (let ((used (make-u8vector 2 0)))
          (render-draw-color-set! tb-r 0 0 0)
          (render-clear! tb-r)
          (render-tile-cells! tb-r (vector tb-tex) (u32vector 1 0 0 0 0 0 0 0) 4 2 0 0 0 3 0 1 0
                              (tb-table) 8 8 0 0 64 32 0 used)
          (list (tb-px 4 4) (u8vector-ref used 0)))))

(test-group "render-tile-cells!: no input reads outside its arrays"
  (test "texture numbers beyond the textures: nothing drawn" black
        (begin (tb-cells (u32vector 1 2 0 0 0 0 0 0) (tb-table 8 99 16 -5) 0 3 0 1) (tb-px 4 4)))
  (test "gids beyond the table: nothing drawn" black
        (begin (tb-cells (u32vector 3 #x0FFFFFFF 4000000000 0 0 0 0 0) (tb-table) 0 3 0 1) (tb-px 4 4)))
  (test "a source of no size: nothing drawn" black
        (begin (tb-cells (u32vector 1 0 0 0 0 0 0 0) (tb-table 11 0 12 -8) 0 3 0 1) (tb-px 4 4)))
  (test "ranges far beyond the layer are cut to it" tile0
        (begin (tb-cells (u32vector 1 0 0 0 0 0 0 0) (tb-table) -100000 100000 -100000 100000) (tb-px 4 4)))
  (test "data shorter than width x height: nothing drawn" black
        (begin (tb-cells (u32vector 1 0 0) (tb-table) 0 3 0 1) (tb-px 4 4)))
  (test "a table shorter than a gid's entry: that gid not drawn" (list tile0 black)
        (begin (tb-cells (u32vector 1 2 0 0 0 0 0 0) (subs32vector (tb-table) 0 20) 0 3 0 1)
               (list (tb-px 4 4) (tb-px 12 4))))
  (test "numbers beyond C's ints: #f, nothing drawn" '(#f (0 0 0))
        (list (tb-cells (u32vector 1 0 0 0 0 0 0 0) (tb-table) 0 3 0 1 fx: (expt 2 40)) (tb-px 4 4)))
  (test "a layer far from the origin whose pixels pass C's ints: #f" #f
        (render-tile-cells! tb-r (vector tb-tex) (u32vector 1 0 0 0 0 0 0 0) 4 2 400000000 0 0 3 0 1 0
                            (tb-table) 8 8 0 0 64 32 1 (make-u8vector 1 0)))
  (test "more than 64 textures: #f" #f
        (tb-cells (u32vector 1 0 0 0 0 0 0 0) (tb-table) 0 3 0 1 textures: (make-vector 65 tb-tex)))
  (test-error "a texture of another renderer is an error"
              (let* ((s (create-rgba-surface! 8 8)) (r2 (create-software-renderer! s)))
                (tb-cells (u32vector 1 0 0 0 0 0 0 0) (tb-table) 0 3 0 1
                          textures: (vector (img-load-texture! r2 (make-pathname tb-dir "sheet-a.png")))))))

(test-group "the fast path draws what the cell-by-cell walk draws (software renderer)"
  (let* ((s (create-rgba-surface! 200 150)) (r (create-software-renderer! s)))
    (for-each
     (lambda (path)
       (for-each (lambda (result)
                   (test (sprintf "~a: same pixels" (car result)) 0 (cadr result))
                   (when (and (substring-index "(0 0 0)" (car result)) (substring-index "batch-" (car result)))
                     (test-assert (sprintf "~a: tiles drawn" (car result)) (> (caddr result) 1000))))
                 (tb-compare r path)))
     (append (tb-write-maps! tb-dir)
             (filter-files "maps" "tmx")
             (filter-files "data/tiled-examples" "tmx")))))


;; The fast path is taken: it asks `textures` for each tileset's image
;; once a layer (and once for each animated tile), where the cell-by-cell
;; walk asks once a visible cell; render-scene! asks once for the sprites.
(test-group "the fast path is the one taken"
  (let* ((s (create-rgba-surface! 200 150)) (r (create-software-renderer! s))
         (tm (load-tilemap (car (tb-write-maps! tb-dir))))
         (loaded (load-tilemap-textures! r tm))
         (asked 0)
         (textures (lambda (path) (set! asked (+ asked 1)) (cdr (assoc path loaded))))
         (count (lambda (fast?)
                  (set! asked 0)
                  (parameterize ((tile-layer-fast-path? fast?))
                    (render-scene! r (make-scene tilemap: tm camera-target: #f) textures: textures))
                  asked)))
    (test "three layers, two tilesets, one animated tile: ten questions" 10 (begin (count #t) (count #t)))
    (test-assert "cell by cell: one a cell" (> (count #f) 500))))

;;; What the fast path keeps between frames is the table of each gid's
;;; image, per map and textures; these would fail if it went stale.
(test-group "nothing stale between frames"
  (let* ((s (create-rgba-surface! 16 8)) (r (create-software-renderer! s))
         (path (make-pathname tb-dir "tiles.png"))
         (_ (write-tiles-png! path 8 '((255 0 0) (0 0 255))))
         (tex (img-load-texture! r path))
         (ts (make-sheet-tileset path tile-width: 8 tile-height: 8 columns: 2))
         (data (u32vector 1 0))
         (tm (make-tilemap 2 1 8 8 (list (make-layer "l" 2 1 data)) tilesets: (list ts)))
         (draw (lambda (textures)
                 (render-scene! r (make-scene tilemap: tm background: '(0 0 0) camera-target: #f)
                                textures: textures)
                 (list (take (renderer-pixel r 4 4) 3) (take (renderer-pixel r 12 4) 3)))))
    (test "first frame" '((255 0 0) (0 0 0)) (draw (list (cons path tex))))
    (let ((asked 0))
      (draw (lambda (p) (set! asked (+ asked 1)) (and (equal? p path) tex)))
      (test "a sheet of unknown tile count takes the fast path: one question for the layer, one for sprites"
            2 asked))
    (u32vector-set! data 0 2)
    (u32vector-set! data 1 1)
    (test "a cell changed between frames shows its new tile"
          '((0 0 255) (255 0 0)) (draw (list (cons path tex))))
    (let* ((path2 (make-pathname tb-dir "tiles2.png"))
           (_ (write-tiles-png! path2 8 '((0 255 0) (255 255 0))))
           (tex2 (img-load-texture! r path2)))
      (test "another texture for the tileset's image is used at once"
            '((255 255 0) (0 255 0)) (draw (list (cons path tex2))))
      (test "and the first again" '((0 0 255) (255 0 0)) (draw (list (cons path tex))))))
  ;; an animated tile: the second tileset of the batch maps, gid 10
  ;; (local 1) shows local 1 then local 5, 100 ms each
  (let* ((s (create-rgba-surface! 8 8)) (r (create-software-renderer! s))
         (path (make-pathname tb-dir "anim.tmx")))
    (with-output-to-file path
      (lambda ()
        (display "<?xml version=\"1.0\" encoding=\"UTF-8\"?>
<map version=\"1.8\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"1\" height=\"1\" tilewidth=\"8\" tileheight=\"8\" infinite=\"0\">
 <tileset firstgid=\"1\" name=\"b\" tilewidth=\"8\" tileheight=\"8\" tilecount=\"8\" columns=\"4\">
  <image source=\"sheet-a.png\" width=\"32\" height=\"16\"/>
  <tile id=\"1\"><animation><frame tileid=\"1\" duration=\"100\"/><frame tileid=\"5\" duration=\"100\"/></animation></tile>
 </tileset>
 <layer id=\"1\" name=\"l\" width=\"1\" height=\"1\"><data encoding=\"csv\">2</data></layer>
</map>
")))
    (let* ((tm (load-tilemap path)) (textures (load-tilemap-textures! r tm))
           (at (lambda (time)
                 (render-scene! r (make-scene tilemap: tm background: '(0 0 0) camera-target: #f)
                                textures: textures time: time)
                 (take (renderer-pixel r 4 4) 3))))
      (test "an animated tile follows the time, frame after frame"
            '((70 40 225) (94 200 105) (70 40 225) (94 200 105))
            (list (at 0) (at 150) (at 201) (at 101))))))

;;; The same comparisons in a real window (opengl under xvfb-run), where
;;; tile runs and queued sprite copies go out as SDL_RenderGeometry calls:
;;; the child prints "renderer NAME" and one line per case.
(define tb-child "
(import scheme (chicken base) (chicken format) (chicken process-context) (chicken file)
        (downstroke sdl2))
(define args (command-line-arguments))
(load (car args))
(init! '(video))
(define w (create-window! \"tile batch\" 0 0 200 150))
(define r (create-renderer! w))
(printf \"renderer ~a~%\" (renderer-name r))
(define (say res) (printf \"case ~a|~a|~a~%\" (car res) (cadr res) (caddr res)))
(for-each (lambda (path) (for-each say (tb-compare r path)))
          (tb-write-maps! (cadr args)))
(for-each say (tb-compare-sprites r (cadr args)))
(quit!)
")

(define (tb-absolute p) (if (absolute-pathname? p) p (make-absolute-pathname (current-directory) p)))

(test-group "sprites: the same pixels queued or not (software: nothing is queued)"
  (let* ((s (create-rgba-surface! 200 150)) (r (create-software-renderer! s)))
    (for-each (lambda (res)
                (test (sprintf "~a: same pixels" (car res)) 0 (cadr res))
                (test-assert (sprintf "~a: drawn" (car res)) (> (caddr res) 1000)))
              (tb-compare-sprites r tb-dir))))

;; The walk in C draws every entity it can (renderer.scm's
;; render-entities!, shell/sprites.c): none of a crowd of plain, scaled,
;; turned, tinted and translucent sprites goes to the Scheme path, and
;; what it leaves (boxes, other sheets, thirds) is counted.
(test-group "sprites: the walk in C draws what it can"
  (let* ((s (create-rgba-surface! 64 32)) (r (create-software-renderer! s))
         (sheet (make-sheet-tileset (make-pathname tb-dir "sheet-a.png") tile-width: 8 tile-height: 8 columns: 4))
         (tex (img-load-texture! r (make-pathname tb-dir "sheet-a.png")))
         (drawn-by-scheme
          (lambda (entities)
            (render-scene! r (make-sprite-scene tileset: sheet tileset-texture: tex entities: entities))
            (entities-drawn-by-scheme))))
    (test "plain, scaled, turned, tinted, translucent, mirrored: none by Scheme" 0
          (drawn-by-scheme (list (list #:x 1 #:y 2 #:tile-id 1)
                                 (list #:x 3.5 #:y 2 #:tile-id 2 #:scale 3/2)
                                 (list #:x 3 #:y 2 #:tile-id 3 #:angle 30 #:origin-x 0)
                                 (list #:x 3 #:y 2.25 #:tile-id 4 #:tint '(255 0 0) #:alpha 99 #:facing -1)
                                 (list #:x 3 #:y 2 #:type 'trigger))))
    (test "a box, another sheet by name, a third of a pixel: three by Scheme" 3
          (drawn-by-scheme (list (list #:x 1 #:y 2 #:tile-id 1)
                                 (list #:x 1 #:y 2 #:width 4 #:height 4 #:color '(0 0 255))
                                 (list #:x 1 #:y 2 #:tile-id 1 #:scale 1/3)
                                 (list #:x 1 #:y 2 #:tile-id 1)
                                 (list #:x 1/3 #:y 2 #:tile-id 1))))
    (test "sprite-fast-path? #f: every one by Scheme" 2
          (parameterize ((sprite-fast-path? #f))
            (drawn-by-scheme (list (list #:x 1 #:y 2 #:tile-id 1) (list #:x 1 #:y 2 #:tile-id 1)))))
    (test-error "an error of the Scheme path is still raised: a negative scale"
                (drawn-by-scheme (list (list #:x 1 #:y 2 #:tile-id 1) (list #:x 1 #:y 2 #:tile-id 1 #:scale -1))))
    (test-error "and a #:tint that is no colour"
                (drawn-by-scheme (list (list #:x 1 #:y 2 #:tile-id 1 #:tint '(1 2)))))
    ;; a sheet's texture destroyed: a scene of boxes is drawn as before,
    ;; a sprite of it is the renderer's error
    (let ((dead (img-load-texture! r (make-pathname tb-dir "sheet-a.png"))))
      (destroy-texture! dead)
      (test "a dead sheet texture and only a box: drawn, no error" '(0 0 255)
            (begin (render-scene! r (make-sprite-scene tileset: sheet tileset-texture: dead
                                                       entities: (list (list #:x 0 #:y 0 #:width 4 #:height 4
                                                                             #:color '(0 0 255)))))
                   (take (renderer-pixel r 1 1) 3)))
      (test-error "a dead sheet texture and a sprite: an error"
                  (render-scene! r (make-sprite-scene tileset: sheet tileset-texture: dead
                                                      entities: (list (list #:x 0 #:y 0 #:tile-id 1))))))))

(test-group "the fast path draws what the cell-by-cell walk draws (a real window, opengl)"
  (let ((xvfb? (zero? (system "command -v xvfb-run >/dev/null 2>&1"))))
    (test-assert "xvfb-run is installed (the Debian packages xvfb and xauth)" xvfb?)
    (when xvfb?
      (with-output-to-file (make-pathname tb-dir "child.scm") (lambda () (display tb-child)))
      (let* ((wdir (make-pathname tb-dir "window"))
             (_ (create-directory wdir))
             (cmd (sprintf "env -u SDL_VIDEODRIVER SDL_AUDIODRIVER=dummy CHICKEN_REPOSITORY_PATH=~a timeout 300 xvfb-run -a -s '-screen 0 640x480x24' csi -q -s ~a ~a ~a 2>&1"
                           (qs (string-intersperse (map tb-absolute (repository-path)) ":"))
                           (qs (make-pathname tb-dir "child.scm"))
                           (qs (tb-absolute "../shell/tests/tile-batch-compare.scm"))
                           (qs wdir)))
             (port (open-input-pipe cmd))
             (lines (read-lines port))
             (status (close-input-pipe port))
             (cases (filter-map (lambda (l) (and (string-prefix? "case " l)
                                                 (string-split (substring l 5) "|")))
                                lines)))
        (test "the child exits cleanly" 0 status)
        (unless (zero? status) (for-each print lines))
        (test-assert "SDL's renderer is an accelerated one (not software)"
                     (and (member "renderer opengl" lines) #t))
        (test "every case compared" 37 (length cases))
        (for-each (lambda (c)
                    (test (sprintf "window, ~a: same pixels" (car c)) "0" (cadr c))
                    (when (or (substring-index "(0 0 0)" (car c)) (substring-index "sprites:" (car c)))
                      (test-assert (sprintf "window, ~a: tiles drawn" (car c))
                                   (> (string->number (caddr c)) 1000))))
                  cases)))))


(test-exit)
