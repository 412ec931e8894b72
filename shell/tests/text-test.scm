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

;;; The textures of texts drawn again are kept (text.scm, "The textures
;;; of the texts drawn last"): what is drawn stays the same.
(define (tx-frame)
  (let ((px (tx-pixels)))
    (let loop ((y 0) (out '()))
      (if (= y tx-h) out
          (loop (+ y 1) (let row ((x 0) (out out))
                          (if (= x tx-w) out (row (+ x 1) (cons (px x y) out)))))))))

(test-group "text: kept textures"
  (let ((font (open-font tx-font-path 16))
        (made (lambda () (text-textures-made))))
    (tx-clear!)
    (let ((n0 (made)))
      (draw-text! tx-renderer font "Score 10" 3 4 color: '(0 255 0))
      (let ((first (tx-frame)))
        (do ((i 0 (+ i 1))) ((= i 10))
          (tx-clear!)
          (draw-text! tx-renderer font "Score 10" 3 4 color: '(0 255 0)))
        (test "the same text drawn 11 times makes one texture" 1 (- (made) n0))
        (test-assert "and draws the same pixels each time" (equal? first (tx-frame)))))
    (let ((n0 (made)))
      (tx-clear!)
      (draw-text! tx-renderer font "Score 10" 3 4 color: '(255 0 0))
      (test "another colour makes another texture" 1 (- (made) n0))
      (receive (in out) (tx-count (tx-pixels) (lambda (p) (equal? p '(0 255 0 255))) 0 0 tx-w tx-h)
        (test "drawn in that colour, none of the first" 0 in)))
    (let* ((s (string-copy "AB")) (n0 (made)))
      (tx-clear!)
      (draw-text! tx-renderer font s 0 0)
      (let ((ab (tx-frame)))
        (string-set! s 0 #\X)
        (tx-clear!)
        (draw-text! tx-renderer font s 0 0)
        (test "a string changed after it was drawn is drawn anew" 2 (- (made) n0))
        (test-assert "with its new text" (not (equal? ab (tx-frame))))))
    (let ((big (open-font tx-font-path 200)) (n0 (made)))
      (draw-text! tx-renderer big "WWWW" 0 0)
      (draw-text! tx-renderer big "WWWW" 0 0)
      (test "a text above 256 x 256 pixels is made each time it is drawn" 2 (- (made) n0))
      (close-font! big))
    ;; a renderer that ended took its textures with it: another one,
    ;; perhaps at the same address, makes its own
    (define (frame-of r)
      (let ((px (renderer-pixels r)))
        (let loop ((y 0) (out '()))
          (if (= y tx-h) out
              (loop (+ y 1) (let row ((x 0) (out out))
                              (if (= x tx-w) out (row (+ x 1) (cons (px x y) out)))))))))
    (define (fresh-renderer)
      (let ((r (create-software-renderer! (create-rgba-surface! tx-w tx-h))))
        (render-draw-blend-mode-set! r 'none)
        (render-draw-color-set! r 0 0 0)
        (render-clear! r)
        r))
    (let ((r2 (fresh-renderer)) (n0 (made)))
      (draw-text! r2 font "Hi" 10 5 color: '(255 0 0))
      (let ((before (frame-of r2)))
        (destroy-renderer! r2)
        (let ((r3 (fresh-renderer)))
          (draw-text! r3 font "Hi" 10 5 color: '(255 0 0))
          (test "a renderer made after one ended makes its own texture" 2 (- (made) n0))
          (test-assert "and draws the same pixels" (equal? before (frame-of r3)))
          (destroy-renderer! r3))))
    ;; a closed font's texts go with it; a font opened afterwards draws
    (close-font! font)
    (let ((font2 (open-font tx-font-path 16)) (n0 (made)))
      (tx-clear!)
      (draw-text! tx-renderer font2 "Hi" 10 5 color: '(255 0 0))
      (test "a font opened after one closed makes its own texture" 1 (- (made) n0))
      (close-font! font2))))

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

(define (append-map* f l) (if (null? l) '() (append (f (car l)) (append-map* f (cdr l)))))
(define (iota* n) (let loop ((i (- n 1)) (out '())) (if (< i 0) out (loop (- i 1) (cons i out)))))

;; Layout as LÖVE's printf lays out: lines broken at newlines and at the
;; last space that fits a width, long words between characters, each line
;; placed by the alignment. A sprite font's widths are exact: 4 px a glyph.
(test-group "text: layout with a sprite font (exact)"
  (let* ((tex (img-load-texture! tx-renderer (tx-path "font.png")))
         (sf (make-sprite-font tex glyph-width: 4 glyph-height: 4 first-char: #\A columns: 4))
         (lay (lambda args (receive (lines w h) (apply text-layout sf args) (list lines w h))))
         (black '(0 0 0 255)))
    (test "wrapped at the last space that fits 20 px; lines, width, height"
          '((("AB CD" 0 0 20) ("EFG" 0 4 12)) 20 8)
          (lay "AB CD EFG" width: 20))
    (test "align: center places each line in the middle of the width"
          '((("AB CD" 0 0 20) ("EFG" 4 4 12)) 20 8)
          (lay "AB CD EFG" width: 20 align: 'center))
    (test "centre is center" (lay "AB CD EFG" width: 20 align: 'center) (lay "AB CD EFG" width: 20 align: 'centre))
    (test "align: right against the width's right edge"
          '((("AB CD" 0 0 20) ("EFG" 8 4 12)) 20 8)
          (lay "AB CD EFG" width: 20 align: 'right))
    (test "a word wider than the width breaks between characters"
          '((("ABC" 0 0 12) ("DEF" 0 4 12) ("G" 0 8 4)) 12 12)
          (lay "ABCDEFG" width: 12))
    (test "the spaces at a break are dropped"
          '((("AB" 0 0 8) ("CD" 0 4 8)) 12 8)
          (lay "AB   CD" width: 12))
    (test "a newline always breaks; an empty line keeps its place"
          '((("AB" 0 0 8) ("" 0 4 0) ("C" 0 8 4)) 8 12)
          (lay "AB\n\nC"))
    (test "without a width, lines align within the widest"
          '((("ABCD" 0 0 16) ("AB" 8 4 8)) 16 8)
          (lay "ABCD\nAB" align: 'right))
    (test "a paragraph's leading spaces are kept"
          '((("  AB" 0 0 16)) 100 4)
          (lay "  AB" width: 100))
    (test "scale: 2 doubles the glyphs and the line height"
          '((("AB" 0 0 16) ("CD" 0 8 16)) 20 16)
          (lay "AB CD" width: 20 scale: 2))
    (test "the empty text has no lines" '(() 0 0) (lay ""))
    (test-error "align: must be left, center or right" (text-layout sf "A" align: 'middle))
    (test-error "width: must be a positive integer" (text-layout sf "A" width: 0))
    ;; drawn: "AB" right-aligned in 20 px starts at 12, "C" at 16 below it
    (tx-clear!)
    (receive (w h) (draw-sprite-text! tx-renderer sf "AB\nC" 0 0 width: 20 align: 'right)
      (test "draw-sprite-text! answers the layout's size" '(20 8) (list w h)))
    (let ((px (tx-pixels)))
      (test "the lines drawn where the layout puts them"
            (list black (tx-glyph #\A) (tx-glyph #\B) black (tx-glyph #\C))
            (list (px 11 0) (px 12 0) (px 19 3) (px 15 4) (px 16 4))))
    (destroy-texture! tex)))

(test-group "text: layout with a TrueType font"
  (let* ((font (open-font tx-font-path 12))
         (text "the quick brown fox jumps over the lazy dog")
         (width 80))
    (receive (lines w h) (text-layout font text width: width)
      (test-assert "more than one line" (> (length lines) 1))
      (test-assert "every line fits the width, and its width is its text's"
                   (let ok ((ls lines))
                     (or (null? ls)
                         (and (<= (cadddr (car ls)) width)
                              (= (cadddr (car ls)) (receive (tw th) (text-size font (caar ls)) tw))
                              (ok (cdr ls))))))
      (test "no word is lost or split" (string-split text " ")
            (append-map* (lambda (l) (string-split (car l) " ")) lines))
      (test "lines are a line skip apart" (map (lambda (i) (* i (font-line-skip font))) (iota* (length lines)))
            (map caddr lines))
      (test "w is the width given" width w)
      (test "h: the font's height and a line skip per further line"
            (+ (receive (tw th) (text-size font "x") th) (* (font-line-skip font) (- (length lines) 1)))
            h))
    (receive (lines w h) (text-layout font text width: width align: 'center)
      (test "centred: each line's x is half the room left"
            (map (lambda (l) (quotient (- width (cadddr l)) 2)) lines)
            (map cadr lines)))
    (test-error "scale: is for sprite fonts" (text-layout font "x" scale: 2))
    ;; a centred title: the lit columns are as far from both edges
    (tx-clear!)
    (draw-text! tx-renderer font "HH" 0 0 width: tx-w align: 'center)
    (let* ((px (tx-pixels))
           (lit? (lambda (x) (let col ((y 0)) (and (< y tx-h) (or (> (car (px x y)) 100) (col (+ y 1)))))))
           (left (let l ((x 0)) (if (or (= x tx-w) (lit? x)) x (l (+ x 1)))))
           (right (let r ((x (- tx-w 1))) (if (or (< x 0) (lit? x)) x (r (- x 1))))))
      (test-assert (sprintf "draw-text! align: center: ~a px left, ~a px right" left (- tx-w 1 right))
                   (and (> left 20) (<= (abs (- left (- tx-w 1 right))) 2))))
    (tx-clear!)
    (draw-text! tx-renderer font "H\nH" 0 0)
    (let ((px (tx-pixels)) (skip (font-line-skip font)))
      (test-assert "a newline draws the next line a line skip below"
                   (let row ((y skip) (found #f))
                     (if (>= y (min tx-h (* 2 skip))) found
                         (row (+ y 1) (or found (let col ((x 0)) (and (< x 12) (or (> (car (px x y)) 100) (col (+ x 1)))))))))))
    (close-font! font)))

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

