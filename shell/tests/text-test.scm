;;; (downstroke text): TTF text and sprite fonts drawn into a software
;;; renderer on a surface, pixels read back. The sprite sheet is made here.

(import (chicken condition) scheme (chicken base) (chicken file) (chicken format) (chicken string)
        (chicken gc) srfi-4 (downstroke test) (downstroke sdl2) (downstroke text))
(include-relative "../../tests/pixels.scm")

(init!)

(define tx-font-path "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf")
(define tx-dir (create-temporary-directory))
(define (tx-path name) (string-append tx-dir "/" name))

(define tx-w 96)
(define tx-h 40)
(define tx-surface (create-rgba-surface! tx-w tx-h))
(define tx-renderer (create-software-renderer! tx-surface))

(define (tx-clear!)
  (render-draw-blend-mode-set! tx-renderer 'none)
  (render-draw-color-set! tx-renderer 0 0 0)
  (render-clear! tx-renderer))

;; The frame as a procedure (x y) -> (r g b a).
(define (tx-pixels)
  (renderer-pixels tx-renderer))

;; Count the pixels satisfying `pred`, inside and outside the box [x0,x1) x [y0,y1).
(define (tx-count px pred x0 y0 x1 y1)
  (let loop ((y 0) (in 0) (out 0))
    (if (= y tx-h)
        (values in out)
        (let row ((x 0) (in in) (out out))
          (if (= x tx-w)
              (loop (+ y 1) in out)
              (let ((hit (pred (px x y)))
                    (inside (and (<= x0 x) (< x x1) (<= y0 y) (< y y1))))
                (row (+ x 1)
                     (if (and hit inside) (+ in 1) in)
                     (if (and hit (not inside)) (+ out 1) out))))))))

;; Resident memory in kB (Linux /proc).
(define (tx-rss-kb)
  (with-input-from-file "/proc/self/statm"
    (lambda () (read) (* 4 (read)))))

(test-group "text: TTF"
  (let ((font (open-font tx-font-path 16)))
    (test-assert "open-font answers an open font" (and (font? font) (font-alive? font)))
    (receive (w1 h1) (text-size font "Hi")
      (receive (w2 h2) (text-size font "Hi there")
        (test-assert "text-size is positive" (and (> w1 0) (> h1 0)))
        (test-assert "text-size grows with the string" (> w2 w1))
        (test "one line keeps its height" h1 h2)))
    (receive (w h) (text-size font "Hi")
      (tx-clear!)
      (receive (dw dh) (draw-text! tx-renderer font "Hi" 10 5 color: '(255 0 0))
        (test "draw-text! answers the size it drew" (list w h) (list dw dh)))
      (let ((px (tx-pixels)))
        (receive (in out)
            (tx-count px (lambda (p) (equal? p '(255 0 0 255))) 10 5 (+ 10 w) (+ 5 h))
          (test-assert "pixels of the text colour inside the text's box" (> in 10))
          (test "none outside it" 0 out))
        (receive (in out)
            (tx-count px (lambda (p) (not (equal? p '(0 0 0 255)))) 10 5 (+ 10 w) (+ 5 h))
          (test "nothing at all is drawn outside the box" 0 out))
        (test-assert "only red: anti-aliasing blends red into black"
                     (let loop ((y 0))
                       (or (= y tx-h)
                           (and (let row ((x 0))
                                  (or (= x tx-w)
                                      (let ((p (px x y)))
                                        (and (= 0 (cadr p)) (= 0 (caddr p)) (row (+ x 1))))))
                                (loop (+ y 1))))))))
    (tx-clear!)
    (draw-text! tx-renderer font "Hi" 40.7 20.2)
    (receive (w h) (text-size font "Hi")
      (receive (in out)
          (tx-count (tx-pixels) (lambda (p) (equal? p '(255 255 255 255))) 40 20 (+ 40 w) (+ 20 h))
        (test-assert "default colour white, position floored" (and (> in 10) (= out 0)))))
    (tx-clear!)
    (test "UTF-8 text draws" #t
          (receive (w h) (draw-text! tx-renderer font "héllo ✓" 0 0) (> w 0)))
    (test "the empty string draws nothing" '(0 0)
          (receive (w h) (draw-text! tx-renderer font "" 0 0) (list w h)))
    (test-assert "text-size of UTF-8 counts characters, not bytes"
                 (receive (w1 h1) (text-size font "é")
                   (receive (w2 h2) (text-size font "e") (< (abs (- w1 w2)) 3))))
    (test-error "a bad colour is an error" (draw-text! tx-renderer font "x" 0 0 color: '(300 0 0)))
    (close-font! font)
    (test-assert "close-font! closes" (not (font-alive? font)))
    (close-font! font)
    (test-assert "closing twice is safe" (not (font-alive? font)))
    (test-error "a closed font is an error" (text-size font "x"))
    (test-error "drawing with a closed font is an error" (draw-text! tx-renderer font "x" 0 0)))
  (test-error "a missing font is an error naming the path"
              (lambda (e) (substring-index "/nonexistent/nofont.ttf" (error-text e)))
              (open-font "/nonexistent/nofont.ttf" 12))
  (with-output-to-file (tx-path "bad.ttf") (lambda () (display "not a font")))
  (test-error "an unreadable font is an error naming the path"
              (lambda (e) (substring-index (tx-path "bad.ttf") (error-text e)))
              (open-font (tx-path "bad.ttf") 12))
  (test-assert "fonts left open are closed by their finalizers, without error"
               (begin
                 (do ((i 0 (+ i 1))) ((= i 200))
                   (let ((f (open-font tx-font-path 10)))
                     (draw-text! tx-renderer f "leak?" 0 0)
                     (when (even? i) (close-font! f))))
                 (gc #t)
                 #t))
  (let ((font (open-font tx-font-path 24)))
    (define (draw-many n)
      (do ((i 0 (+ i 1))) ((= i n))
        (draw-text! tx-renderer font (string-append "frame " (number->string i)) 0 0)))
    (draw-many 500)
    (gc #t)
    (let ((before (tx-rss-kb)))
      (draw-many 5000)
      (gc #t)
      (let ((growth (- (tx-rss-kb) before)))
        (test-assert (sprintf "5000 draw-text! calls keep memory flat (grew ~a kB)" growth)
                     (< growth 2048))))
    (close-font! font)))

;;; Sprite font: 4x4 glyphs, 4 columns, first char #\A, 2 rows (A..H), each
;;; cell one colour; the cell of H is left transparent.
(define tx-glyph-colors
  '((#\A 255 0 0) (#\B 0 255 0) (#\C 0 0 255) (#\D 255 255 0)
    (#\E 0 255 255) (#\F 255 0 255) (#\G 128 128 255)))

(define (tx-make-sheet path)
  (let* ((s (create-rgba-surface! 16 8))
         (r (create-software-renderer! s)))
    (render-draw-color-set! r 0 0 0 0)
    (render-clear! r)
    (let loop ((i 0) (gs tx-glyph-colors))
      (unless (null? gs)
        (apply render-draw-color-set! r (cdar gs))
        (render-fill-rect! r (make-rect (* 4 (modulo i 4)) (* 4 (quotient i 4)) 4 4))
        (loop (+ i 1) (cdr gs))))
    (img-save-png! s path)
    (free-surface! s)))

(tx-make-sheet (tx-path "font.png"))

(define (tx-glyph c) (append (cdr (assv c tx-glyph-colors)) '(255)))

(test-group "text: sprite font"
  (let* ((tex (img-load-texture! tx-renderer (tx-path "font.png")))
         (sf (make-sprite-font tex glyph-width: 4 glyph-height: 4 first-char: #\A columns: 4))
         (black '(0 0 0 255)))
    (tx-clear!)
    (receive (w h) (draw-sprite-text! tx-renderer sf "BAG\nFC" 10 3)
      (test "it answers the text's size" '(12 8) (list w h)))
    (let ((px (tx-pixels)))
      (test "B at x, A next, G third (second row of the sheet)"
            (list (tx-glyph #\B) (tx-glyph #\B) (tx-glyph #\A) (tx-glyph #\A) (tx-glyph #\G) (tx-glyph #\G))
            (list (px 10 3) (px 13 6) (px 14 3) (px 17 6) (px 18 3) (px 21 6)))
      (test "the line ends after G" black (px 22 3))
      (test "nothing above or left" (list black black) (list (px 10 2) (px 9 3)))
      (test "a newline starts the next line below, at x"
            (list (tx-glyph #\F) (tx-glyph #\F) (tx-glyph #\C) (tx-glyph #\C) black)
            (list (px 10 7) (px 13 10) (px 14 7) (px 17 10) (px 10 11))))
    (tx-clear!)
    (draw-sprite-text! tx-renderer sf "a D ZE" 0 0)
    (let ((px (tx-pixels)))
      (test "characters with no cell leave a blank glyph"
            (list black black black (tx-glyph #\D) black black black (tx-glyph #\E))
            (list (px 0 0) (px 4 0) (px 7 3) (px 8 0) (px 12 0) (px 16 0) (px 19 3) (px 20 0))))
    (tx-clear!)
    (draw-sprite-text! tx-renderer sf "CA" 1 1 scale: 2)
    (let ((px (tx-pixels)))
      (test "scale: 2 doubles the cells"
            (list (tx-glyph #\C) (tx-glyph #\C) (tx-glyph #\A) (tx-glyph #\A) black)
            (list (px 1 1) (px 8 8) (px 9 1) (px 16 8) (px 17 1))))
    (test "sprite-text-size" '(16 8) (receive (w h) (sprite-text-size sf "ABCD\nE") (list w h)))
    (test-error "glyph-width is required" (make-sprite-font tex glyph-height: 4))
    (destroy-texture! tex)))

(test-group "text: far away and bad coordinates"
  (let ((font (open-font tx-font-path 12))
        (lit (lambda () (let-values (((in out) (tx-count (tx-pixels) (lambda (p) (> (car p) 0)) 0 0 tx-w tx-h)))
                          (+ in out)))))
    (tx-clear!)
    (draw-text! tx-renderer font "HH" 2 2)
    (test-assert "near the view it draws" (> (lit) 20))
    (for-each (lambda (x)
                (tx-clear!)
                (let-values (((w h) (draw-text! tx-renderer font "HH" x 2)))
                  (test (sprintf "at x = ~a nothing wraps into the view, and the size is still answered" x)
                        (list 0 #t) (list (lit) (> w 10)))))
              (list (+ 2 (expt 2 32)) (- 2 (expt 2 32)) 1e308 (- (expt 2 63)) (expt 2 80)))
    (test-error "NaN names the procedure and the coordinate"
                (lambda (e) (and (substring-index "y is +nan.0, not a finite number" (error-text e)) (eq? (quote draw-text!) ((condition-property-accessor (quote exn) (quote location) #f) e))))
                (draw-text! tx-renderer font "HH" 0 +nan.0))
    (close-font! font)))

(test-group "text: limits"
  (define (message thunk)
    (handle-exceptions e (error-text e) (thunk) "no error"))
  (test-assert "a font size of 2^32 is an error naming the file and max-font-size"
               (let ((m (message (lambda () (open-font tx-font-path 4294967296)))))
                 (and (substring-index "DejaVuSans.ttf" m) (substring-index "above max-font-size (1000)" m))))
  (test-assert "(max-font-size N) allows more"
               (parameterize ((max-font-size 2000))
                 (let ((f (open-font tx-font-path 1500))) (close-font! f) #t)))
  (let ((font (open-font tx-font-path 10))
        (long (make-string 20000 #\a)))
    (test-assert "a text of 20,000 characters is an error naming max-text-length"
                 (substring-index "draw-text!: a text of 20000 characters is above max-text-length (10000)"
                                  (message (lambda () (draw-text! tx-renderer font long 0 0)))))
    (test-assert "text-size says the same"
                 (substring-index "text-size: a text of 20000 characters"
                                  (message (lambda () (text-size font long)))))
    (test-assert "(max-text-length N) allows more"
                 (parameterize ((max-text-length 30000))
                   (receive (w h) (text-size font long) (> w 20000))))
    (close-font! font)))

(free-surface! tx-surface)
(delete-directory tx-dir #t)

