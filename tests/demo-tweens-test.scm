;;; bin/demo-tweens, run headless as a user would: every box is where its
;;; easing puts it on the last frame, and the screenshot shows it there.

(import scheme (chicken base) (chicken io) (chicken process) (chicken file)
        (chicken string) (chicken port) (chicken format) (downstroke test) (downstroke tween))
(include-relative "pixels.scm")
(include-relative "demo-support.scm")

;; "tweens: frame N ((name left-tick x) ...)" -> (N boxes), or #f.
(define (tw-parse line)
  (and (substring=? line "tweens: frame ")
       (with-input-from-string (substring line 14 (string-length line))
         (lambda () (let* ((n (read)) (boxes (read))) (list n boxes))))))

;; The demo's layout: 1000 ms a run, 110 px from tick to tick, yoyo.
(define tw-duration 1000)
(define tw-travel 110)

;; Where a box is after `ms` of a yoyo tween, as docs/tweens.org says:
;; even runs go forward, odd runs retrace the curve backwards.
(define (tw-expected ease start ms)
  (let* ((run (quotient ms tw-duration))
         (u (remainder ms tw-duration))
         (t (if (even? run) (/ u tw-duration) (/ (- tw-duration u) tw-duration))))
    (+ start (* tw-travel ((ease-procedure ease) t)))))

;; Exact results must match exactly; flonums are printed to 15 digits.
(define (tw-same? expected got)
  (if (exact? expected)
      (equal? expected got)
      (and (number? got) (< (abs (- expected got)) 1e-9))))

(define (tw-check-positions boxes frames)
  (let ((wrong (foldr (lambda (b out)
                        (let ((want (tw-expected (car b) (cadr b) (* 16 frames))))
                          (if (tw-same? want (caddr b)) out (cons (list b 'expected want) out))))
                      '() boxes)))
    (test (sprintf "after ~a frames every box is at start + 110 * ease(t)" frames) '() wrong)))

(define tw-shot (demo-tmp "tw-demo-tweens.png"))

(test-group "demo: tweens"
  ;; 50 frames = 800 ms: the first run, going out, t = 4/5
  (let ((r (tw-parse (last-line (demo-output "bin/demo-tweens --headless --frames 50")))))
    (test-assert "the demo prints its boxes" r)
    (when r
      (test "it ran 50 frames" 50 (car r))
      (test "one box per easing, in the table's order"
            (map car *ease-table*) (map car (cadr r)))
      (tw-check-positions (cadr r) 50)
      ;; the same numbers by hand: linear 4/5, quad-in (4/5)^2
      (test "linear is four fifths of the way" 140 (caddr (assq 'linear (cadr r))))
      (test "quad-in is 16/25 of the way" (+ 52 352/5) (caddr (assq 'quad-in (cadr r))))))

  ;; 90 frames = 1440 ms: the second run, coming back, 440 ms in: t = 14/25
  (when (file-exists? tw-shot) (delete-file tw-shot))
  (let ((r (tw-parse (last-line (demo-output (string-append "bin/demo-tweens --headless --frames 90 --screenshot " tw-shot))))))
    (test-assert "the demo prints its boxes" r)
    (when r
      (let ((boxes (cadr r)))
        (tw-check-positions boxes 90)
        (test "coming back, linear is at 14/25" (+ 52 308/5) (caddr (assq 'linear boxes)))
        (test "cubic-out by hand: 1 - (11/25)^3" (+ 260 (* 110 (- 1 (expt 11/25 3)))) (caddr (assq 'cubic-out boxes)))
        (test-assert "elastic-in swings out past its left tick" (< (caddr (assq 'elastic-in boxes)) 52))
        (test-assert "a screenshot was saved" (file-exists? tw-shot))
        (when (file-exists? tw-shot)
          ;; the colour of each row (linear, then quad ... bounce)
          (let* ((palette '((230 230 240) (250 110 110) (250 160 80) (240 210 80) (170 220 90)
                            (90 210 140) (80 200 220) (100 150 250) (160 120 250) (220 110 230)
                            (250 130 180)))
                 (row-of (lambda (i) (if (= i 0) 0 (+ 1 (quotient (- i 1) 3)))))
                 (track-y (lambda (row) (+ 62 (* 38 row) 24)))
                 (misplaced
                  (let loop ((bs boxes) (i 0) (out '()))
                    (if (null? bs)
                        (reverse out)
                        (let* ((b (car bs)) (row (row-of i)) (colour (list-ref palette row))
                               (x (inexact->exact (floor (caddr b))))
                               (here (png-pixel tw-shot (+ x 6) (track-y row)))
                               ;; the left tick, when the box is well away from it
                               (tick (png-pixel tw-shot (+ (cadr b) 6) (track-y row))))
                          (loop (cdr bs) (+ i 1)
                                (if (and ((near-colour? colour) here)
                                         (or (< (abs (- x (cadr b))) 14)
                                             (not ((near-colour? colour) tick))))
                                    out
                                    (cons (car b) out))))))))
            (test "each box is drawn where its x says, in its row's colour, and not at its tick"
                  '() misplaced)
            (test-assert "the background is the demo's dark blue"
                         ((near-colour? '(22 24 38)) (png-pixel tw-shot 630 470)))
            (test-assert "the title is drawn in white text"
                         (> (png-count tw-shot (near-colour? '(255 255 255) 30) 12 12 380 24) 200))
            (test-assert "the bounce-out lane is labelled in its colour"
                         (> (png-count tw-shot (near-colour? '(250 130 180) 40) 220 442 80 14) 20))
            (test "nothing is drawn between the title and the first label"
                  0 (png-count tw-shot (lambda (c) (not ((near-colour? '(22 24 38)) c))) 300 40 330 20))))))))
