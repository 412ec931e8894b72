;;; Runs of quads drawn by OpenGL itself (shell/gl-batch.c, on SDL's
;;; opengl renderer) against the same runs sent to SDL_RenderGeometry
;;; (render-gl-batching? #f), pixel for pixel, in a child process with a
;;; real window under xvfb-run: tile-batch-compare.scm's maps (every
;;; render order, flips, two tilesets, a translucent tinted layer,
;;; parallax, sources beyond the image) through its cameras, and its
;;; sprite crowds (plain, mirrored, scaled, tinted, translucent, turned,
;;; turned and mirrored, by #:z, between boxes). Each picture also counts the quads OpenGL drew
;;; itself: some with the path on, none with it off, none at a render
;;; scale other than 1 (SDL then scales the vertices, and draws them all).

(import scheme (chicken base) (chicken file) (chicken format) (chicken string)
        (chicken process) (chicken pathname) (chicken process-context) (chicken io)
        (chicken platform) (downstroke test) (downstroke sdl2))

(define gb-child "
(import scheme (chicken base) (chicken format) (chicken process-context) (chicken file)
        (chicken pathname) srfi-4 (downstroke sdl2) (downstroke scene) (downstroke camera)
        (downstroke tilemap) (downstroke renderer) (downstroke mapdraw) (downstroke level))
(define args (command-line-arguments))
(load (car args))
(define dir (cadr args))
(init! '(video))
(define w (create-window! \"gl batch\" 0 0 200 150))
(define r (create-renderer! w))
(printf \"renderer ~a~%\" (renderer-name r))
;; draw! twice, OpenGL's own runs on and off: pixels that differ, quads
;; OpenGL drew itself each time, pixels not the background
(define (both label draw!)
  (let* ((picture (lambda () (draw!) (receive (bytes w h) (render-read-pixels r) bytes)))
         (q0 (render-gl-quads))
         (on (picture))
         (q1 (render-gl-quads))
         (off (parameterize ((render-gl-batching? #f)) (picture)))
         (q2 (render-gl-quads)))
    (printf \"case ~a|~a|~a|~a|~a~%\" label (tb-differing on off) (- q1 q0) (- q2 q1)
            (let loop ((i 0) (n 0))
              (if (>= i (u8vector-length on)) n
                  (loop (+ i 4) (if (= (u8vector-ref on i) 10) n (+ n 1))))))))
(for-each (lambda (path)
            (let* ((tm (load-tilemap path)) (textures (load-tilemap-textures! r tm)))
              (for-each (lambda (view)
                          (both (sprintf \"~a at ~a\" (pathname-file path) view)
                                (lambda () (apply tb-picture r tm textures (append view '(#t))))))
                        tb-views)))
          (tb-write-maps! dir))
(let ((tex-a (img-load-texture! r (make-pathname dir \"sheet-a.png\")))
      (tex-b (img-load-texture! r (make-pathname dir \"sheet-b.png\"))))
  (for-each (lambda (case)
              (let* ((camera (list-ref case 4))
                     (scene (make-sprite-scene tileset: (cadr case) tileset-texture: tex-a
                                               tilesets: (list (caddr case)) background: '(10 20 30)
                                               camera: (make-camera x: (car camera) y: (cadr camera) bounds: #f)
                                               entities: (cadddr case)))
                     (textures (list (cons (make-pathname dir \"sheet-b.png\") tex-b)
                                     (cons (make-pathname dir \"sheet-a.png\") tex-a))))
                (both (sprintf \"sprites: ~a\" (car case))
                      (lambda () (render-scene! r scene textures: textures)))))
            (tb-sprite-scenes dir))
  ;; at a logical size half the window's, SDL's scale is 2: SDL draws
  (render-set-logical-size! r 100 75)
  (let ((scene (make-sprite-scene tileset: (cadr (car (tb-sprite-scenes dir))) tileset-texture: tex-a
                                  background: '(10 20 30) entities: (cadddr (car (tb-sprite-scenes dir))))))
    (both \"scaled renderer: sprites\" (lambda () (render-scene! r scene)))))
(quit!)
")

(define (gb-absolute p) (if (absolute-pathname? p) p (make-absolute-pathname (current-directory) p)))
(define (gb-prefix? p s) (and (>= (string-length s) (string-length p)) (string=? p (substring s 0 (string-length p)))))

(test-group "runs drawn by OpenGL itself: the same pixels as SDL's geometry (a real window)"
  (let ((xvfb? (zero? (system "command -v xvfb-run >/dev/null 2>&1"))))
    (test-assert "xvfb-run is installed (the Debian packages xvfb and xauth)" xvfb?)
    (when xvfb?
      (let* ((dir (create-temporary-directory))
             (_ (with-output-to-file (make-pathname dir "child.scm") (lambda () (display gb-child))))
             (wdir (make-pathname dir "window"))
             (_ (create-directory wdir))
             (cmd (sprintf "env -u SDL_VIDEODRIVER SDL_AUDIODRIVER=dummy CHICKEN_REPOSITORY_PATH=~a timeout 300 xvfb-run -a -s '-screen 0 640x480x24' csi -q -s ~a ~a ~a 2>&1"
                           (qs (string-intersperse (map gb-absolute (repository-path)) ":"))
                           (qs (make-pathname dir "child.scm"))
                           (qs (gb-absolute "../shell/tests/tile-batch-compare.scm"))
                           (qs wdir)))
             (port (open-input-pipe cmd))
             (lines (read-lines port))
             (status (close-input-pipe port))
             (cases (let loop ((ls lines) (out '()))
                      (cond ((null? ls) (reverse out))
                            ((gb-prefix? "case " (car ls))
                             (loop (cdr ls) (cons (string-split (substring (car ls) 5) "|") out)))
                            (else (loop (cdr ls) out)))))
             (number (lambda (c i) (string->number (list-ref c i)))))
        (when (get-environment-variable "GB_SHOW") (for-each print lines))
        (test "the child exits cleanly" 0 status)
        (unless (zero? status) (for-each print lines))
        (test-assert "SDL's renderer is opengl" (and (member "renderer opengl" lines) #t))
        (test "every case compared (25 map views, 12 crowds, the scaled renderer)" 38 (length cases))
        (for-each
         (lambda (c)
           (test (sprintf "~a: same pixels" (car c)) 0 (number c 1))
           (test (sprintf "~a: none by OpenGL with the path off" (car c)) 0 (number c 3))
           (test-assert (sprintf "~a: drawn" (car c)) (> (number c 4) 1000)))
         cases)
        (let ((quads (lambda (label) (let ((c (assoc label cases))) (and c (number c 2))))))
          (test-assert "a plain crowd: most of its 300 sprites by OpenGL itself"
                       (> (or (quads "sprites: plain") 0) 250))
          ;; turned copies are queued too (sdl2.scm's ds_q_copy_turned): one
          ;; texture, so a crowd of them is one run
          (test-assert "a turned crowd: most of its 360 sprites by OpenGL itself"
                       (> (or (quads "sprites: turned at many angles and scales, origins, offsets") 0) 300))
          (test-assert "a turned and mirrored crowd: most of its 300 by OpenGL itself"
                       (> (or (quads "sprites: turned and mirrored, tinted, whole turns") 0) 250))
          (test-assert "a map: its runs of cells by OpenGL itself (a diagonal flip ends a run)"
                       (> (or (quads "batch-right-down at (0 0 0)") 0) 100))
          ;; runs of 4,096, 4,096 and 808 quads, the first of each through SDL
          (test "a crowd of 9,000: three runs, all but their first quads by OpenGL itself" 8997
                (quads "sprites: a crowd longer than two runs (9,000)"))
          (test "a scaled renderer: none by OpenGL itself" 0 (quads "scaled renderer: sprites")))
        (delete-directory dir #t)))))

(test-exit)
