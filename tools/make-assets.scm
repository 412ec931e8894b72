;;; Generates the demos' art and sound into demo/assets/ (git-ignored).
;;;   CHICKEN_REPOSITORY_PATH=$PWD/build:$(chicken-install -repository) \
;;;   SDL_VIDEODRIVER=dummy csi -q -s tools/make-assets.scm
;;; Run from the repository root; running it again rewrites the same files.
;;;
;;; Images are drawn with filled rectangles through a software renderer on
;;; an RGBA surface and saved with img-save-png!. Sounds are 8-bit mono PCM
;;; WAV files whose bytes are written here.
;;;
;;; tiles.png, 8 columns of 16 x 16 tiles (gid = column + 1 in the levels):
;;;   1 ground  2 brick  3 grass top  4 platform  5 spikes  6 coin
;;;   7 background block  8 stone
;;; sprites.png, 16 x 16 frames:
;;;   0 player idle  1 walk A  2 walk B  3 jump  4 enemy  5 bullet

(import scheme (chicken base) (chicken format) (chicken file)
        (chicken bitwise) (chicken io) (downstroke sdl2))

(define T 16)
(define out-dir "demo/assets")

;; Draw on a w x h transparent surface with (draw renderer); save as PNG.
(define (make-png! path w h draw)
  (let* ((s (create-rgba-surface! w h))
         (r (create-software-renderer! s)))
    (draw r)
    (img-save-png! s path)
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

(define (draw-tiles! r)
  (for-each (lambda (draw c) (draw r c))
            (list draw-ground! draw-brick! draw-grass-top! draw-platform!
                  draw-spikes! draw-coin! draw-background-block! draw-stone!)
            '(0 1 2 3 4 5 6 7)))

;; The player: a 16 x 16 frame, body 12 px wide (x 2..13), facing right.
;; legs: a list of (x height) for the two legs.
(define (draw-player! r c legs-y left-leg right-leg)
  (let ((skin '(250 200 160)) (shirt '(40 120 230)) (hair '(90 50 20))
        (pants '(40 40 80)) (eye '(20 20 30)))
    (tile-rect! r c hair 4 0 8 3)
    (tile-rect! r c skin 4 3 8 5)
    (tile-rect! r c eye 9 4 2 2)
    (tile-rect! r c shirt 2 8 12 4)
    (tile-rect! r c pants (car left-leg) legs-y 3 (cadr left-leg))
    (tile-rect! r c pants (car right-leg) legs-y 3 (cadr right-leg))))

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
  (tile-rect! r 5 '(255 230 120) 8 7 4 2))

;;; ------------------------------------------------------------------
;;; WAV: RIFF, "WAVE", a fmt chunk (PCM, mono, 8 bit) and a data chunk.

(define rate 22050)

(define (u32le n) (list->string (map (lambda (i) (integer->char (bitwise-and (arithmetic-shift n (* -8 i)) 255)))
                                     '(0 1 2 3))))
(define (u16le n) (substring (u32le n) 0 2))

;; samples: a list of integers 0..255 (128 is silence).
(define (write-wav! path samples)
  (let ((n (length samples)))
    (with-output-to-file path
      (lambda ()
        (write-string (string-append
                       "RIFF" (u32le (+ 36 n)) "WAVE"
                       "fmt " (u32le 16) (u16le 1) (u16le 1) (u32le rate) (u32le rate)
                       (u16le 1) (u16le 8)
                       "data" (u32le n)))
        (for-each (lambda (s) (write-char (integer->char s))) samples))
      #:binary)
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

;;; ------------------------------------------------------------------

(create-directory out-dir #t)
(init! '(video))
(make-png! (string-append out-dir "/tiles.png") (* 8 T) T draw-tiles!)
(make-png! (string-append out-dir "/sprites.png") (* 6 T) T draw-sprites!)
(quit!)
(write-wav! (string-append out-dir "/jump.wav") (square-sweep 300 700 150))
(write-wav! (string-append out-dir "/coin.wav")
            (append (square-sweep 990 990 60) (square-sweep 1320 1320 120)))
