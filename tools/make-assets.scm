;;; Generates the demos' art and sound into demo/assets/ (git-ignored).
;;;   CHICKEN_REPOSITORY_PATH=$PWD/build:$(env -u CHICKEN_INSTALL_REPOSITORY chicken-install -repository) \
;;;   SDL_VIDEODRIVER=dummy csi -q -s tools/make-assets.scm
;;; Run from the repository root. It does nothing (and says nothing) when
;;; every file is there and newer than this script; --force rewrites them.
;;;
;;; Images are drawn with filled rectangles through a software renderer on
;;; an RGBA surface and saved with img-save-png!. Sounds are 8-bit mono PCM
;;; WAV files whose bytes are written here.
;;;
;;; tiles.png, 8 columns of 16 x 16 tiles (gid = column + 1 in the levels):
;;;   1 ground  2 brick  3 grass top  4 platform  5 spikes  6 coin
;;;   7 background block  8 stone
;;; sprites.png, 16 x 16 frames, 6 to a row (gid = index + 9 in the levels,
;;; where sprites.tsx is the second tileset):
;;;   row 0:  0 player idle  1 walk A  2 walk B  3 jump  4 enemy  5 bullet
;;;   row 1:  6 player blink  7 enemy squashed  8 enemy stretched
;;;           9 bird wings up  10 wings level  11 wings down
;;;   row 2: 12 coin  13 coin turning  14 coin edge-on
;;;          15 16 17 torch flame (three flickers)
;;; ladder.png, one 16 x 16 tile: a wooden ladder (ladders.tsx, the
;;;   platformer's third tileset, gives it the tile property ladder).
;;; slopes.png, 3 slope tiles of 16 x 16 (slopes.tsx, the platformer's fourth
;;; tileset): 0 rises 0 -> 16 px (45 degrees), 1 rises 0 -> 8, 2 rises
;;; 8 -> 16 (a 22.5 degree pair); the level flips them for the way down.
;;; shmup.png, 4 tiles of 16 x 16 for the shmup (ship, enemy, bullet, spark).
;;; font.png, a sprite font: printable ASCII (32..126) in 6 x 8 cells, 16 to
;;; a row; white 5 x 7 glyphs with a dark shadow one pixel down and right.
;;; Sounds: jump.wav, coin.wav, boom.wav (effects); music.wav, a 4 s loop.

(import scheme (chicken base) (chicken format) (chicken file) (chicken file posix)
        (chicken process-context) (only (chicken process-context posix) current-process-id)
        (chicken bitwise) (chicken io) (downstroke sdl2))

(define T 16)
(define out-dir "demo/assets")

;; Writes a file under a temporary name, then renames it into place: a demo
;; or a test suite reading the asset while it is remade (each launcher runs
;; this generator, and suites run side by side) sees the old file or the
;; new one, never a missing or half-written one.
(define (write-in-place! path write!)
  (let ((tmp (sprintf "~a.~a.tmp" path (current-process-id))))
    (write! tmp)
    (rename-file tmp path #t)))

;; Draw on a w x h transparent surface with (draw renderer); save as PNG.
(define (make-png! path w h draw)
  (let* ((s (create-rgba-surface! w h))
         (r (create-software-renderer! s)))
    (draw r)
    (write-in-place! path (lambda (tmp) (img-save-png! s tmp)))
    (destroy-renderer! r)
    (free-surface! s)
    (printf "wrote ~a (~a x ~a)~%" path w h)))

;; (rect! r color x y w h) with color (r g b [a]).
(define (rect! r color x y w h)
  (apply render-draw-color-set! r color)
  (render-fill-rect! r (make-rect x y w h)))

;; Tile helpers: everything is drawn relative to column `c`'s left edge.
(define (tile-rect! r c color x y w h) (rect! r color (+ (* c T) x) y w h))

(define dirt '(134 86 48))
(define dirt-dark '(104 64 36))
(define grass '(76 176 60))
(define grass-light '(124 212 84))

(define (draw-ground! r c)
  (tile-rect! r c dirt 0 0 T T)
  (for-each (lambda (p) (tile-rect! r c dirt-dark (car p) (cadr p) 2 2))
            '((2 3) (9 1) (13 6) (5 9) (11 12) (1 13) (7 14))))

(define (draw-brick! r c)
  (tile-rect! r c '(96 60 52) 0 0 T T)              ; mortar
  (for-each (lambda (row)
              (let ((y (* row 4)) (shift (if (even? row) 0 4)))
                (do ((x (- shift 8) (+ x 8))) ((>= x T))
                  (let ((x0 (max 0 (+ x 1))) (x1 (min T (+ x 8))))
                    (when (> x1 x0)
                      (tile-rect! r c '(178 74 56) x0 (+ y 1) (- x1 x0) 3))))))
            '(0 1 2 3)))

(define (draw-grass-top! r c)
  (draw-ground! r c)
  (tile-rect! r c grass 0 0 T 5)
  (for-each (lambda (x) (tile-rect! r c grass x 5 2 2)) '(1 6 10 14))
  (tile-rect! r c grass-light 0 0 T 1))

(define (draw-platform! r c)
  (tile-rect! r c '(150 104 56) 0 0 T 6)
  (tile-rect! r c '(196 146 84) 0 0 T 2)
  (tile-rect! r c '(92 60 32) 0 5 T 1)
  (tile-rect! r c '(92 60 32) 7 0 1 6))

(define (draw-spikes! r c)
  (tile-rect! r c '(70 70 80) 0 13 T 3)
  (for-each (lambda (x0)                 ; a triangle as a stack of rows
              (do ((i 0 (+ i 1))) ((= i 4))
                (tile-rect! r c '(200 204 214) (- (+ x0 3) i) (+ 5 (* 2 i)) (+ 2 (* 2 i)) 2)))
            '(0 8))
  (for-each (lambda (x0) (tile-rect! r c '(240 240 250) (+ x0 3) 5 2 2)) '(0 8)))

(define (draw-coin! r c)
  (tile-rect! r c '(200 140 20) 5 2 6 12)
  (tile-rect! r c '(200 140 20) 3 4 10 8)
  (tile-rect! r c '(252 210 60) 5 3 6 10)
  (tile-rect! r c '(252 210 60) 4 5 8 6)
  (tile-rect! r c '(255 250 180) 6 5 2 5))

(define (draw-background-block! r c)
  (tile-rect! r c '(52 60 100) 0 0 T T)
  (tile-rect! r c '(64 74 120) 1 1 14 14)
  (tile-rect! r c '(52 60 100) 4 4 8 8))

(define (draw-stone! r c)
  (tile-rect! r c '(112 116 128) 0 0 T T)
  (tile-rect! r c '(150 154 166) 0 0 T 2)
  (tile-rect! r c '(150 154 166) 0 0 2 T)
  (tile-rect! r c '(76 78 90) 0 14 T 2)
  (tile-rect! r c '(76 78 90) 14 0 2 T))

;; A slope tile: grass-topped dirt up to the line from `left` px high at
;; the left edge to `right` px at the right, one pixel column at a time
;; (the height at the column's middle, rounded).
(define (draw-slope! r c left right)
  (do ((x 0 (+ x 1))) ((= x T))
    (let ((h (inexact->exact (round (+ left (/ (* (- right left) (+ x 1/2)) T))))))
      (when (> h 0)
        (tile-rect! r c dirt x (- T h) 1 h)
        (tile-rect! r c grass x (- T h) 1 (min h 3))))))

(define (draw-slopes! r)
  (draw-slope! r 0 0 16)
  (draw-slope! r 1 0 8)
  (draw-slope! r 2 8 16))

(define (draw-tiles! r)
  (for-each (lambda (draw c) (draw r c))
            (list draw-ground! draw-brick! draw-grass-top! draw-platform!
                  draw-spikes! draw-coin! draw-background-block! draw-stone!)
            '(0 1 2 3 4 5 6 7)))

;; Two rails and four rungs, on a transparent tile, so that the sky or a
;; wall shows through.
(define (draw-ladder! r)
  (tile-rect! r 0 '(120 78 40) 2 0 3 T)
  (tile-rect! r 0 '(120 78 40) 11 0 3 T)
  (for-each (lambda (y) (tile-rect! r 0 '(176 122 64) 5 y 6 2)) '(1 5 9 13))
  (tile-rect! r 0 '(168 116 62) 2 0 1 T)
  (tile-rect! r 0 '(168 116 62) 11 0 1 T))

;; Sprite helper: frame `i` of sprites.png (6 frames to a row).
(define sprite-columns 6)
(define (sprite-rect! r i color x y w h)
  (rect! r color (+ (* (modulo i sprite-columns) T) x) (+ (* (quotient i sprite-columns) T) y) w h))

;; The player: a 16 x 16 frame, body 12 px wide (x 2..13), facing right.
;; legs: a list of (x height) for the two legs.
(define (draw-player! r c legs-y left-leg right-leg)
  (let ((skin '(250 200 160)) (shirt '(40 120 230)) (hair '(90 50 20))
        (pants '(40 40 80)) (eye '(20 20 30)))
    (sprite-rect! r c hair 4 0 8 3)
    (sprite-rect! r c skin 4 3 8 5)
    (sprite-rect! r c eye 9 4 2 2)
    (sprite-rect! r c shirt 2 8 12 4)
    (sprite-rect! r c pants (car left-leg) legs-y 3 (cadr left-leg))
    (sprite-rect! r c pants (car right-leg) legs-y 3 (cadr right-leg))))

;; The enemy blob, body from (x, y) of size w x h, eyes `eye-y` down.
(define (draw-blob! r i x y w h eye-y)
  (let ((purple '(150 50 170)))
    (sprite-rect! r i purple x y w h)
    (sprite-rect! r i purple (+ x 2) (- y 2) (- w 4) 2)
    (sprite-rect! r i '(255 255 255) 4 eye-y 3 3)
    (sprite-rect! r i '(255 255 255) 9 eye-y 3 3)
    (sprite-rect! r i '(0 0 0) 5 (+ eye-y 1) 1 2)
    (sprite-rect! r i '(0 0 0) 10 (+ eye-y 1) 1 2)))

;; A red bird facing right; wing: (x y w h) of its wing.
(define (draw-bird! r i wing)
  (sprite-rect! r i '(220 70 50) 4 6 8 5)            ; body
  (sprite-rect! r i '(220 70 50) 10 4 4 4)           ; head
  (sprite-rect! r i '(250 220 190) 6 9 5 2)          ; belly
  (sprite-rect! r i '(160 40 30) 2 6 2 3)            ; tail
  (sprite-rect! r i '(255 200 40) 14 6 2 1)          ; beak
  (sprite-rect! r i '(20 20 30) 12 5 1 1)            ; eye
  (apply sprite-rect! r i '(160 40 30) wing))

;; A coin seen from the front (w 10), turning (w 6) or edge-on (w 2).
(define (draw-coin-frame! r i w)
  (let ((x (quotient (- T w) 2)))
    (sprite-rect! r i '(200 140 20) x 3 w 10)
    (sprite-rect! r i '(200 140 20) (+ x 1) 2 (max 1 (- w 2)) 12)
    (when (> w 2)
      (sprite-rect! r i '(252 210 60) (+ x 1) 3 (- w 2) 10)
      (sprite-rect! r i '(255 250 180) (+ x 2) 5 1 5))))

;; A torch: a stick and a flame whose tip leans by `lean` px, `height` tall.
(define (draw-torch! r i lean height)
  (sprite-rect! r i '(110 70 40) 7 10 2 6)
  (sprite-rect! r i '(140 140 150) 6 9 4 2)
  (sprite-rect! r i '(230 80 30) 5 (- 9 height) 6 height)
  (sprite-rect! r i '(255 170 40) (+ 6 (quotient lean 2)) (- 9 (- height 2)) 4 (- height 2))
  (sprite-rect! r i '(255 240 150) (+ 7 lean) (- 9 (- height 4)) 2 (- height 5)))

(define (draw-sprites! r)
  (draw-player! r 0 12 '(4 4) '(9 4))        ; idle
  (draw-player! r 1 12 '(2 4) '(11 3))       ; walk A
  (draw-player! r 2 12 '(6 3) '(7 4))        ; walk B
  (draw-player! r 3 11 '(3 3) '(10 5))       ; jump
  (tile-rect! r 3 '(40 120 230) 0 7 2 3)     ;   arms up
  (tile-rect! r 3 '(40 120 230) 14 7 2 3)
  ;; enemy: a purple blob with eyes
  (tile-rect! r 4 '(150 50 170) 2 4 12 12)
  (tile-rect! r 4 '(150 50 170) 4 2 8 2)
  (tile-rect! r 4 '(255 255 255) 4 6 3 3)
  (tile-rect! r 4 '(255 255 255) 9 6 3 3)
  (tile-rect! r 4 '(0 0 0) 5 7 1 2)
  (tile-rect! r 4 '(0 0 0) 10 7 1 2)
  ;; bullet: a small bright slug
  (tile-rect! r 5 '(255 140 40) 4 6 8 4)
  (tile-rect! r 5 '(255 230 120) 8 7 4 2)
  ;; row 1: the player blinking, the blob squashed and stretched, the bird
  (draw-player! r 6 12 '(4 4) '(9 4))
  (sprite-rect! r 6 '(250 200 160) 9 4 2 2)
  (sprite-rect! r 6 '(20 20 30) 9 5 2 1)
  (draw-blob! r 7 1 8 14 8 9)
  (draw-blob! r 8 3 2 10 14 4)
  (draw-bird! r 9 '(5 2 4 5))
  (draw-bird! r 10 '(3 6 6 2))
  (draw-bird! r 11 '(5 10 4 4))
  ;; row 2: a spinning coin and a flickering torch
  (draw-coin-frame! r 12 10)
  (draw-coin-frame! r 13 6)
  (draw-coin-frame! r 14 2)
  (draw-torch! r 15 0 7)
  (draw-torch! r 16 1 8)
  (draw-torch! r 17 -1 6))

;;; ------------------------------------------------------------------
;;; shmup.png: the shmup's sheet, 16 x 16 tiles in one row (gid = index + 1):
;;;   0 the ship (pointing up)  1 an enemy saucer  2 a bullet  3 a spark,
;;;   white so that particles tint it (a round blob, brighter at its heart)

(define (draw-shmup! r)
  ;; the ship: a cyan arrow with a cockpit and two orange engine flames
  (tile-rect! r 0 '(120 220 255) 7 1 2 12)
  (tile-rect! r 0 '(120 220 255) 5 5 6 8)
  (tile-rect! r 0 '(120 220 255) 2 9 12 4)
  (tile-rect! r 0 '(60 140 200) 1 11 2 4)
  (tile-rect! r 0 '(60 140 200) 13 11 2 4)
  (tile-rect! r 0 '(30 40 90) 7 6 2 3)
  (tile-rect! r 0 '(255 170 40) 5 13 2 3)
  (tile-rect! r 0 '(255 170 40) 9 13 2 3)
  ;; an enemy: a red saucer with a pale dome and lights
  (tile-rect! r 1 '(230 80 90) 1 7 14 5)
  (tile-rect! r 1 '(230 80 90) 3 5 10 8)
  (tile-rect! r 1 '(255 200 210) 5 2 6 4)
  (tile-rect! r 1 '(150 40 60) 2 12 12 2)
  (for-each (lambda (x) (tile-rect! r 1 '(255 240 120) x 9 2 2)) '(3 7 11))
  ;; a bullet: a pale yellow bolt, 3 px wide, centred
  (tile-rect! r 2 '(255 255 160) 6 3 4 10)
  (tile-rect! r 2 '(255 255 255) 7 4 2 8)
  ;; a spark: white, a plus of 8 px with a 4 x 4 heart
  (tile-rect! r 3 '(255 255 255 160) 4 6 8 4)
  (tile-rect! r 3 '(255 255 255 160) 6 4 4 8)
  (tile-rect! r 3 '(255 255 255) 6 6 4 4))

;;; ------------------------------------------------------------------
;;; font.png: 5 x 7 glyphs, each given as 7 rows of 5 bits (bit 4 = left).

(define glyph-rows
  '((#\space 0 0 0 0 0 0 0) (#\! 4 4 4 4 0 0 4) (#\" 10 10 10 0 0 0 0)
    (#\# 10 10 31 10 31 10 10) (#\$ 4 15 20 14 5 30 4) (#\% 24 25 2 4 8 19 3)
    (#\& 12 18 20 8 21 18 13) (#\' 12 4 8 0 0 0 0) (#\( 2 4 8 8 8 4 2)
    (#\) 8 4 2 2 2 4 8) (#\* 0 4 21 14 21 4 0) (#\+ 0 4 4 31 4 4 0)
    (#\, 0 0 0 0 12 4 8) (#\- 0 0 0 31 0 0 0) (#\. 0 0 0 0 0 12 12)
    (#\/ 0 1 2 4 8 16 0) (#\0 14 17 19 21 25 17 14) (#\1 4 12 4 4 4 4 14)
    (#\2 14 17 1 2 4 8 31) (#\3 31 2 4 2 1 17 14) (#\4 2 6 10 18 31 2 2)
    (#\5 31 16 30 1 1 17 14) (#\6 6 8 16 30 17 17 14) (#\7 31 1 2 4 8 8 8)
    (#\8 14 17 17 14 17 17 14) (#\9 14 17 17 15 1 2 12) (#\: 0 12 12 0 12 12 0)
    (#\; 0 12 12 0 12 4 8) (#\< 2 4 8 16 8 4 2) (#\= 0 0 31 0 31 0 0)
    (#\> 8 4 2 1 2 4 8) (#\? 14 17 1 2 4 0 4) (#\@ 14 17 1 13 21 21 14)
    (#\A 14 17 17 17 31 17 17) (#\B 30 17 17 30 17 17 30) (#\C 14 17 16 16 16 17 14)
    (#\D 28 18 17 17 17 18 28) (#\E 31 16 16 30 16 16 31) (#\F 31 16 16 30 16 16 16)
    (#\G 14 17 16 23 17 17 15) (#\H 17 17 17 31 17 17 17) (#\I 14 4 4 4 4 4 14)
    (#\J 7 2 2 2 2 18 12) (#\K 17 18 20 24 20 18 17) (#\L 16 16 16 16 16 16 31)
    (#\M 17 27 21 21 17 17 17) (#\N 17 17 25 21 19 17 17) (#\O 14 17 17 17 17 17 14)
    (#\P 30 17 17 30 16 16 16) (#\Q 14 17 17 17 21 18 13) (#\R 30 17 17 30 20 18 17)
    (#\S 15 16 16 14 1 1 30) (#\T 31 4 4 4 4 4 4) (#\U 17 17 17 17 17 17 14)
    (#\V 17 17 17 17 17 10 4) (#\W 17 17 17 21 21 21 10) (#\X 17 17 10 4 10 17 17)
    (#\Y 17 17 17 10 4 4 4) (#\Z 31 1 2 4 8 16 31) (#\[ 14 8 8 8 8 8 14)
    (#\\ 0 16 8 4 2 1 0) (#\] 14 2 2 2 2 2 14) (#\^ 4 10 17 0 0 0 0)
    (#\_ 0 0 0 0 0 0 31) (#\` 8 4 2 0 0 0 0) (#\a 0 0 14 1 15 17 15)
    (#\b 16 16 22 25 17 17 30) (#\c 0 0 14 16 16 17 14) (#\d 1 1 13 19 17 17 15)
    (#\e 0 0 14 17 31 16 14) (#\f 6 9 8 28 8 8 8) (#\g 0 15 17 17 15 1 14)
    (#\h 16 16 22 25 17 17 17) (#\i 4 0 12 4 4 4 14) (#\j 2 0 6 2 2 18 12)
    (#\k 16 16 18 20 24 20 18) (#\l 12 4 4 4 4 4 14) (#\m 0 0 26 21 21 17 17)
    (#\n 0 0 22 25 17 17 17) (#\o 0 0 14 17 17 17 14) (#\p 0 0 30 17 30 16 16)
    (#\q 0 0 13 19 15 1 1) (#\r 0 0 22 25 16 16 16) (#\s 0 0 14 16 14 1 30)
    (#\t 8 8 28 8 8 9 6) (#\u 0 0 17 17 17 19 13) (#\v 0 0 17 17 17 10 4)
    (#\w 0 0 17 17 21 21 10) (#\x 0 0 17 10 4 10 17) (#\y 0 0 17 17 15 1 14)
    (#\z 0 0 31 2 4 8 31) (#\{ 2 4 4 8 4 4 2) (#\| 4 4 4 4 4 4 4)
    (#\} 8 4 4 2 4 4 8) (#\~ 0 0 8 21 2 0 0)))

(define glyph-w 6)                       ; cell size, glyph 5 x 7 + shadow
(define glyph-h 8)
(define font-columns 16)

;; Each set bit becomes a pixel at (dx + column, dy + row) of the cell.
(define (draw-glyph! r index rows color dx dy)
  (let ((x0 (* glyph-w (modulo index font-columns)))
        (y0 (* glyph-h (quotient index font-columns))))
    (let loop ((rows rows) (y 0))
      (unless (null? rows)
        (do ((bit 0 (+ bit 1))) ((= bit 5))
          (when (odd? (arithmetic-shift (car rows) (- bit 4)))
            (rect! r color (+ x0 dx bit) (+ y0 dy y) 1 1)))
        (loop (cdr rows) (+ y 1))))))

(define (draw-font! r)
  (for-each (lambda (g)
              (let ((index (- (char->integer (car g)) 32)))
                (draw-glyph! r index (cdr g) '(24 20 40) 1 1)
                (draw-glyph! r index (cdr g) '(255 255 255) 0 0)))
            glyph-rows))

;;; ------------------------------------------------------------------
;;; WAV: RIFF, "WAVE", a fmt chunk (PCM, mono, 8 bit) and a data chunk.

(define rate 22050)

(define (u32le n) (list->string (map (lambda (i) (integer->char (bitwise-and (arithmetic-shift n (* -8 i)) 255)))
                                     '(0 1 2 3))))
(define (u16le n) (substring (u32le n) 0 2))

;; samples: a list of integers 0..255 (128 is silence).
(define (write-wav! path samples)
  (let ((n (length samples)))
    (write-in-place! path (lambda (tmp) (with-output-to-file tmp
      (lambda ()
        (write-string (string-append
                       "RIFF" (u32le (+ 36 n)) "WAVE"
                       "fmt " (u32le 16) (u16le 1) (u16le 1) (u32le rate) (u32le rate)
                       (u16le 1) (u16le 8)
                       "data" (u32le n)))
        (for-each (lambda (s) (write-char (integer->char s))) samples))
      #:binary)))
    (printf "wrote ~a (~a samples, ~a ms)~%" path n (quotient (* 1000 n) rate))))

;; A square wave whose frequency goes from f0 to f1 Hz over `ms`, fading out.
(define (square-sweep f0 f1 ms)
  (let ((n (quotient (* rate ms) 1000)))
    (let loop ((i 0) (phase 0.0) (out '()))
      (if (= i n)
          (reverse out)
          (let* ((t (/ i n))
                 (f (+ f0 (* (- f1 f0) t)))
                 (amp (* 60 (- 1 t)))
                 (v (if (< phase 0.5) amp (- amp)))
                 (next (let ((p (+ phase (/ f rate)))) (- p (floor p)))))
            (loop (+ i 1) next (cons (inexact->exact (round (+ 128 v))) out)))))))

;; Noise from a 16-bit shift register (the same bytes every run), its
;; amplitude falling over `ms`, its pitch (register steps per sample)
;; lowered every `hold` samples: an explosion.
(define (noise-burst ms)
  (let ((n (quotient (* rate ms) 1000)))
    (let loop ((i 0) (reg #xACE1) (v 0) (out '()))
      (if (= i n)
          (reverse out)
          (let* ((t (/ i n))
                 (hold (+ 1 (quotient (* i 6) n)))   ; 1 .. 6: darker as it fades
                 (step? (zero? (modulo i hold)))
                 (bit (bitwise-and (bitwise-xor reg (arithmetic-shift reg -2)) 1))
                 (reg (if step? (bitwise-ior (arithmetic-shift reg -1) (arithmetic-shift bit 15)) reg))
                 (v (if step? (if (odd? reg) 1 -1) v))
                 (amp (* 70 (- 1 t) (- 1 t))))
            (loop (+ i 1) reg v (cons (inexact->exact (round (+ 128 (* amp v)))) out)))))))

;;; The music: two bars of eighth notes at 120 bpm (4 s), an arpeggio on a
;;; square wave over a triangle bass, C Am F G. Every note fades to silence
;;; before the next begins, so the end joins the start without a click and
;;; the file loops.

(define eighth (quotient rate 4))         ; samples in an eighth note
(define (midi->hz m) (* 440 (expt 2 (/ (- m 69) 12))))

(define melody                          ; MIDI notes, one per eighth
  '(72 76 79 76 69 72 76 72 65 69 72 77 67 71 74 79))
(define bass                            ; one per quarter: root, octave
  '(48 60 45 57 41 53 43 55))

;; The sample (-1..1) of a voice `k` samples into a note of `len` samples.
(define (square-voice hz k len)
  (let ((phase (let ((p (/ (* hz k) rate))) (- p (floor p))))
        (env (* (min 1 (/ k 64)) (expt (- 1 (/ k len)) 2))))
    (* env (if (< phase 0.5) 1 -1))))

(define (triangle-voice hz k len)
  (let ((phase (let ((p (/ (* hz k) rate))) (- p (floor p))))
        (env (* (min 1 (/ k 64)) (- 1 (/ k len)))))
    (* env (- (* 4 (abs (- phase 0.5))) 1))))

(define (music-loop)
  (let ((n (* eighth (length melody))))
    (let loop ((i (- n 1)) (out '()))
      (if (< i 0)
          out
          (let* ((lead (square-voice (midi->hz (list-ref melody (quotient i eighth)))
                                     (modulo i eighth) eighth))
                 (quarter (* 2 eighth))
                 (low (triangle-voice (midi->hz (list-ref bass (quotient i quarter)))
                                      (modulo i quarter) quarter))
                 (v (+ 128 (* 30 lead) (* 50 low))))
            (loop (- i 1) (cons (max 0 (min 255 (inexact->exact (round v)))) out)))))))

;;; ------------------------------------------------------------------

(define asset-names
  '("tiles.png" "slopes.png" "sprites.png" "ladder.png" "shmup.png" "font.png" "jump.wav" "coin.wav" "boom.wav" "music.wav"))

;; Every asset is there and newer than this generator: nothing to do.
(define (assets-fresh?)
  (let ((made (file-modification-time "tools/make-assets.scm")))
    (every (lambda (name)
             (let ((path (string-append out-dir "/" name)))
               (and (file-exists? path) (>= (file-modification-time path) made))))
           asset-names)))

(define (every ok? ls) (or (null? ls) (and (ok? (car ls)) (every ok? (cdr ls)))))

(define (make-assets!)
  (create-directory out-dir #t)
  (init! '(video))
  (make-png! (string-append out-dir "/tiles.png") (* 8 T) T draw-tiles!)
  (make-png! (string-append out-dir "/slopes.png") (* 3 T) T draw-slopes!)
  (make-png! (string-append out-dir "/sprites.png") (* 6 T) (* 3 T) draw-sprites!)
  (make-png! (string-append out-dir "/ladder.png") T T draw-ladder!)
  (make-png! (string-append out-dir "/shmup.png") (* 4 T) T draw-shmup!)
  (make-png! (string-append out-dir "/font.png") (* font-columns glyph-w) (* 6 glyph-h) draw-font!)
  (quit!)
  (write-wav! (string-append out-dir "/jump.wav") (square-sweep 300 700 150))
  (write-wav! (string-append out-dir "/coin.wav")
              (append (square-sweep 990 990 60) (square-sweep 1320 1320 120)))
  (write-wav! (string-append out-dir "/boom.wav") (noise-burst 500))
  (write-wav! (string-append out-dir "/music.wav") (music-loop)))

;; --force rewrites them all; otherwise only missing or stale assets are made.
(if (or (member "--force" (command-line-arguments)) (not (assets-fresh?)))
    (make-assets!)
    (void))
