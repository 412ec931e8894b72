;;; (downstroke renderer): the debug overlay, drawn into a software renderer
;;; on a surface and read back. The map and its tileset image are made here.

(import scheme (chicken base) (chicken file) (chicken format) (chicken string)
        srfi-4 (downstroke test) (downstroke sdl2) (downstroke entity)
        (downstroke scene) (downstroke tilemap) (downstroke renderer))
;; Bad entities are made here on purpose; their warnings would only be noise.
(scene-checks #f)

(include-relative "../../tests/pixels.scm")

(init!)

(define ov-dir (create-temporary-directory))
(define (ov-path name) (string-append ov-dir "/" name))

;; An 8x8-tile map of W x H empty cells (its tileset image is never drawn).
(define (ov-map w h)
  (let ((s (create-rgba-surface! 8 8)))
    (img-save-png! s (ov-path "t.png"))
    (free-surface! s))
  (with-output-to-file (ov-path "m.tmx")
    (lambda ()
      (printf "<?xml version=\"1.0\" encoding=\"UTF-8\"?>~%")
      (printf "<map version=\"1.10\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"~a\" height=\"~a\" tilewidth=\"8\" tileheight=\"8\" infinite=\"0\">~%" w h)
      (printf " <tileset firstgid=\"1\" name=\"t\" tilewidth=\"8\" tileheight=\"8\" tilecount=\"1\" columns=\"1\">~%")
      (printf "  <image source=\"t.png\" width=\"8\" height=\"8\"/>~% </tileset>~%")
      (printf " <layer id=\"1\" name=\"l\" width=\"~a\" height=\"~a\">~%  <data encoding=\"csv\">~%" w h)
      (printf "~a~%  </data>~% </layer>~%</map>~%"
              (string-intersperse (let loop ((i 0) (out '()))
                                    (if (= i (* w h)) out (loop (+ i 1) (cons "0" out))))
                                  ","))))
  (load-tilemap (ov-path "m.tmx")))

(define ov-tm (ov-map 8 6))

(define ov-w 64)
(define ov-h 48)
(define ov-surface (create-rgba-surface! ov-w ov-h))
(define ov-renderer (create-software-renderer! ov-surface))

(define ov-bg '(10 20 30 255))
(define ov-green *debug-hitbox-color*)
(define ov-blue *debug-cell-color*)
(define ov-yellow *debug-velocity-color*)
(define ov-red *debug-warning-color*)

(test "the four overlay colours differ" 4
      (length (let loop ((cs (list ov-green ov-blue ov-yellow ov-red)) (out '()))
                (cond ((null? cs) out)
                      ((member (car cs) out) (loop (cdr cs) out))
                      (else (loop (cdr cs) (cons (car cs) out)))))))

;; Clear to the background, draw the overlay (or the whole scene with
;; debug?), answer (x y) -> (r g b a).
(define (ov-read)
  (renderer-pixels ov-renderer))

(define (ov-draw scene)
  (render-draw-blend-mode-set! ov-renderer 'none)
  (apply render-draw-color-set! ov-renderer ov-bg)
  (render-clear! ov-renderer)
  (render-debug-overlay! ov-renderer scene)
  (ov-read))

;; The pixels that differ from `expected` (x y) -> pixel: a list of (x y got).
(define (ov-mismatches px expected)
  (let loop ((y 0) (out '()))
    (if (= y ov-h)
        (reverse out)
        (loop (+ y 1)
              (let row ((x 0) (out out))
                (if (= x ov-w)
                    out
                    (row (+ x 1)
                         (if (equal? (px x y) (expected x y)) out (cons (list x y (px x y)) out)))))))))

(define (ov-body x y w h . more)
  (append (list #:x x #:y y #:width w #:height h) more))

(test-group "overlay: hitboxes"
  ;; x 10 y 12, 6 x 5, camera (2, 4): screen columns 8..13, rows 8..12
  (let ((px (ov-draw (update-scene (make-sprite-scene entities: (list (ov-body 10 12 6 5)))
                                   camera: (make-camera x: 2 y: 4)))))
    (test "outline colour on every edge pixel, background everywhere else (inside too)" '()
          (ov-mismatches px (lambda (x y)
                              (if (and (<= 8 x 13) (<= 8 y 12)
                                       (or (= x 8) (= x 13) (= y 8) (= y 12)))
                                  ov-green
                                  ov-bg)))))
  (let ((px (ov-draw (make-sprite-scene entities: (list (ov-body 3.5 2.25 4 4)
                                                        (list #:x 30 #:y 30 #:color '(1 2 3)))))))
    (test "fractional positions follow the rounding rule (x 3..6, y 2..5)"
          (list ov-green ov-green ov-green ov-bg ov-bg)
          (list (px 3 2) (px 6 5) (px 5 5) (px 4 3) (px 7 2)))
    (test "an entity without a size has no overlay" ov-bg (px 30 30)))
  (test "a body with a NaN position or infinite velocity is skipped or drawn without a line"
        (list ov-green ov-bg)
        (let ((px (ov-draw (make-sprite-scene
                            entities: (list (ov-body +nan.0 0 4 4)
                                            (ov-body 20 20 4 4 #:vx +inf.0))))))
          (list (px 20 20) (px 30 22)))))

(test-group "overlay: covered tile cells"
  ;; x 10..15, y 12..16: column 1, rows 1 and 2: cells at (8..15, 8..15), (8..15, 16..23)
  (let ((px (ov-draw (make-scene tilemap: ov-tm collision-mode: 'discrete
                                 entities: (list (ov-body 10 12 6 5))))))
    (test "the covered cells' outlines"
          (list ov-blue ov-blue ov-blue ov-blue ov-blue ov-blue ov-blue)
          (list (px 8 8) (px 12 8) (px 15 8) (px 8 20) (px 15 20) (px 12 23) (px 8 23)))
    (test "the boundary between the two cells" (list ov-blue ov-blue) (list (px 12 15) (px 9 16)))
    (test "the hitbox on top" (list ov-green ov-green ov-green) (list (px 10 12) (px 15 14) (px 12 16)))
    (test "no cells beyond: left, right, above, below"
          (list ov-bg ov-bg ov-bg ov-bg) (list (px 7 10) (px 16 10) (px 10 7) (px 10 24)))
    (test "inside a cell, off the hitbox, is background" ov-bg (px 11 20)))
  (let ((px (ov-draw (make-scene tilemap: ov-tm entities: (list (ov-body 8 8 8 8))))))
    (test "a body flush with a tile's edges covers that one cell" '()
          (ov-mismatches px (lambda (x y)
                              (if (and (<= 8 x 15) (<= 8 y 15)
                                       (or (= x 8) (= x 15) (= y 8) (= y 15)))
                                  ov-green
                                  ov-bg)))))
  (let ((px (ov-draw (make-scene tilemap: ov-tm camera: (make-camera x: 4 y: 0)
                                 entities: (list (ov-body 17 1 2 2))))))
    (test "cells move with the camera: column 2 at 16 - 4 = 12"
          (list ov-blue ov-blue ov-bg) (list (px 12 0) (px 19 7) (px 20 0)))))

(test-group "overlay: velocity"
  ;; centre (22, 22); scale 4
  (let ((px (ov-draw (make-sprite-scene entities: (list (ov-body 20 20 4 4 #:vx 3 #:vy 0))))))
    (test "a line from the centre along vx, 4 frames long"
          (list ov-yellow ov-yellow ov-yellow ov-yellow ov-bg ov-bg)
          (list (px 22 22) (px 26 22) (px 30 22) (px 34 22) (px 35 22) (px 30 21))))
  (let ((px (ov-draw (make-sprite-scene entities: (list (ov-body 20 20 4 4 #:vx 2 #:vy -2))))))
    (test "a diagonal line" (list ov-yellow ov-yellow ov-bg) (list (px 26 18) (px 30 14) (px 31 13))))
  (let ((px (begin (render-draw-blend-mode-set! ov-renderer 'none)
                   (apply render-draw-color-set! ov-renderer ov-bg)
                   (render-clear! ov-renderer)
                   (render-debug-overlay!
                    ov-renderer (make-sprite-scene entities: (list (ov-body 20 20 4 4 #:vx 1 #:vy 0)))
                    velocity-scale: 10)
                   (ov-read))))
    (test "velocity-scale: sets the length" (list ov-yellow ov-bg) (list (px 32 22) (px 33 22))))
  (let ((px (ov-draw (make-sprite-scene entities: (list (ov-body 20 20 4 4))))))
    (test "a body at rest draws no line" ov-bg (px 26 22)))
  (let ((px (ov-draw (make-sprite-scene entities: (list (ov-body 20 20 4 4 #:vx 1000000000 #:vy 0))))))
    (test "a huge velocity is clipped to the view" (list ov-yellow ov-yellow) (list (px 40 22) (px 63 22)))))

(test-group "overlay: tunnelling warning"
  ;; 6 px wide on 8 px tiles: discrete is safe below 14 px/frame
  (define (ov-hitbox-and-line mode vx . extra)
    (let ((px (ov-draw (make-scene tilemap: ov-tm collision-mode: mode
                                   entities: (list (apply ov-body 10 10 6 6 #:vx vx #:vy 0 extra))))))
      (list (px 10 10) (px 40 13))))
  (test "a fast body in discrete mode is drawn in the warning colour"
        (list ov-red ov-red) (ov-hitbox-and-line 'discrete 14))
  (test "the same body in swept mode is not"
        (list ov-green ov-yellow) (ov-hitbox-and-line 'swept 14))
  (test "just below the safe speed is not"
        (list ov-green ov-yellow) (ov-hitbox-and-line 'discrete 13))
  (test "moving left counts too"
        ov-red (car (ov-hitbox-and-line 'discrete -14)))
  (test "an entity's own #:collision-mode swept overrides the scene's"
        (list ov-green ov-yellow) (ov-hitbox-and-line 'discrete 14 #:collision-mode 'swept))
  (test "vertical speed against the tile height"
        ov-red
        ((ov-draw (make-scene tilemap: ov-tm collision-mode: 'discrete
                              entities: (list (ov-body 10 10 6 6 #:vy 14))))
         10 10)))

(test-group "overlay: render-scene! debug?:"
  (let* ((scene (make-scene tilemap: ov-tm background: '(10 20 30) collision-mode: 'discrete
                            entities: (list (ov-body 10 12 6 5 #:color '(200 0 0)))))
         (plain (begin (render-scene! ov-renderer scene) (ov-read)))
         (debug (begin (render-scene! ov-renderer scene debug?: #t) (ov-read))))
    (test "without debug? no overlay" (list '(200 0 0 255) ov-bg) (list (plain 10 12) (plain 8 8)))
    (test "with debug? #t the overlay is drawn over the scene"
          (list ov-green ov-blue '(200 0 0 255)) (list (debug 10 12) (debug 8 8) (debug 12 14)))))

(free-surface! ov-surface)
(delete-directory ov-dir #t)
