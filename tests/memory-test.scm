;;; Memory stays flat over a long run that replaces its textures.
;;;
;;; 10,000 headless frames (real SDL, dummy video driver, software renderer)
;;; of a scene whose update: loads a fresh texture from a PNG file every
;;; frame (img-load-texture!) and destroys the previous one, and every 10th
;;; frame reloads the whole scene with game-load-scene! (a TMX map and its
;;; tileset texture; the loader destroys the previous scene's textures).
;;; render: draws the texture, so it is really used.
;;;
;;; What is measured: the process's resident set (VmRSS in
;;; /proc/self/status) after a full GC at frame 1,000 (every allocator and
;;; heap has reached its working size by then) and at frame 10,000, and
;;; the number of native resources alive ((downstroke sdl2)'s
;;; live-resource-counts) at the same frames.
;;;
;;; The bound, 8 MB: the per-frame texture is 64 x 64 RGBA, so its pixels
;;; alone are 16 KB (the software renderer keeps them in an SDL_Surface,
;;; plus the decoded PNG surface IMG_LoadTexture makes and frees). Leaking
;;; the texture of each of the 9,000 frames between the two readings would
;;; grow the RSS by at least 9,000 * 16 KB = 144 MB; leaking only the
;;; texture records or finalizers (~100 bytes each) is caught by the counts
;;; instead. A scene reload every 10 frames leaking its 16 x 16 tileset
;;; texture would add 900 * 1 KB ~ 1 MB at least, which the counts catch
;;; too. The 8 MB of slack covers what legitimately moves while the run
;;; warms up: CHICKEN's heap may double for a while (6 -> 12 MB here, the
;;; GC trace shows; it is back to 6 MB at both readings, but pages it
;;; touched stay resident), and malloc's arenas settle after the first
;;; map loads. Measured: +2.6 to +4.0 MB between frames 1,000 and 10,000, and
;;; in a 40,000-frame run nothing more after frame 10,000 (23.4 MB at
;;; 10,000, 23.6 MB at 40,000).
;;;
;;; Before (downstroke sdl2) ran a major GC every 2,048 explicit destroys,
;;; this failed (+7.5 to +9 MB, and 18 -> 41 MB over 150,000 frames): a
;;; destroyed record keeps its CHICKEN finalizer until a major GC, so the
;;; heap and finalizer table kept doubling.

(import scheme (chicken base) (chicken string) (chicken file) (chicken io)
        (chicken gc) (chicken format) srfi-4
        (downstroke test) (downstroke sdl2) (downstroke entity) (downstroke scene)
        (downstroke engine))
(include-relative "pixels.scm")

(when (sdl-initialized?) (quit!))

;; VmRSS of this process, in kB.
(define (mem-rss-kb)
  (with-input-from-file "/proc/self/status"
    (lambda ()
      (let loop ()
        (let ((line (read-line)))
          (cond ((eof-object? line) (error 'mem-rss-kb "no VmRSS in /proc/self/status"))
                ((substring=? "VmRSS:" line)
                 (string->number (car (string-split (substring line 6) " \t"))))
                (else (loop))))))))

(define mem-frames 10000)
(define mem-first-reading 1000)
(define mem-bound-kb (* 8 1024))

(test-group "memory: 10,000 frames replacing textures"
  (let* ((dir (create-temporary-directory))
         (path (lambda (n) (string-append dir "/" n)))
         (tex #f)
         (loads 0)
         (readings '())                 ; (frame rss-kb counts), newest first
         ;; earlier suites' garbage resources are freed by finalizers
         ;; first, so they do not count against this run
         (before (begin (gc #t) (live-resource-counts)))
         (read! (lambda (g)
                  (gc #t)
                  (set! readings (cons (list (+ (game-frame g) 1) (mem-rss-kb) (live-resource-counts)
                                             (quotient (vector-ref (memory-statistics) 0) 1024))
                                       readings))))
         (g (make-game
             headless?: #t width: 64 height: 48
             preload: (lambda (g)
                        (write-solid-png! (path "a.png") 64 64 255 0 0)
                        (write-solid-png! (path "b.png") 64 64 0 0 255)
                        (write-solid-png! (path "tiles.png") 16 16 0 255 0)
                        (write-csv-tmx! (path "m.tmx") "tiles.png" 8 2 2
                                        '((1 2 3 4) (0 1 0 2) (4 0 0 3))))
             create: (lambda (g)
                       (game-load-scene! g (path "m.tmx") background: '(0 0 0) camera-target: #f))
             update: (lambda (g dt)
                       (let ((f (game-frame g))
                             (old tex))
                         (set! tex (img-load-texture! (game-renderer g)
                                                      (path (if (even? f) "a.png" "b.png"))))
                         (set! loads (+ loads 1))
                         (when old (destroy-texture! old))
                         (when (zero? (modulo f 10))
                           (game-load-scene! g (path "m.tmx") background: '(0 0 0)
                                             camera-target: #f))
                         ;; game-frame counts the frames finished before this one
                         (when (memv (+ f 1) (list mem-first-reading mem-frames))
                           (read! g))))
             render: (lambda (g)
                       (render-copy! (game-renderer g) tex #f (make-rect 0 0 16 16))))))
    (test "all frames ran" mem-frames (game-run! g frames: mem-frames))
    (when tex (destroy-texture! tex))
    (test "a texture was loaded every frame" mem-frames loads)
    (test "two readings" (list mem-frames mem-first-reading) (map car readings))
    (when (= (length readings) 2)
      (let* ((late (car readings))
             (early (cadr readings))
             (growth (- (cadr late) (cadr early))))
        (printf "memory: VmRSS ~a kB at frame ~a, ~a kB at frame ~a (growth ~a kB, bound ~a kB; CHICKEN heap ~a -> ~a kB)~%"
                (cadr early) (car early) (cadr late) (car late) growth mem-bound-kb
                (cadddr early) (cadddr late))
        (test-assert (sprintf "VmRSS grows less than 8 MB (grew ~a kB)" growth)
                     (< growth mem-bound-kb))
        (test "native resources alive do not grow between the readings"
              (caddr early) (caddr late))
        (test "during the run: one renderer, one surface, the per-frame texture and the tileset's"
              '((windows . 0) (renderers . 1) (textures . 2) (surfaces . 1))
              (map (lambda (p b) (cons (car p) (- (cdr p) (cdr b))))
                   (caddr late) before))))
    (test "after the run every native resource is released"
          before (live-resource-counts))))
