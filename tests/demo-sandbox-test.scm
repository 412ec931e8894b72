;;; bin/demo-sandbox, run headless as a user would: 120 solid movers bounce
;;; around an arena while the windmill group patrols through them. After
;;; hundreds of frames every mover is still inside the walls, no two overlap
;;; by half a mover (4 px; without the push-apart step some overlap by 6 px
;;; or more, and with it the deepest overlaps are pushes the windmill's arms
;;; gave this frame, at most about 3 px), the windmill's hub is where its
;;; patrol puts it, and the screenshot shows all of it there.
;;; The arena (demo/levels/sandbox.tmx) is 320 x 240 with a 16 px brick
;;; border and four 32 x 32 stone pillars; the demo draws at scale 2.

(import scheme (chicken base) (chicken io) (chicken process) (chicken file)
        (chicken string) (chicken port) (chicken format) (downstroke test))
(include-relative "pixels.scm")
(include-relative "demo-support.scm")

;; "sandbox: N movers, N inside, max overlap X px, windmill at (X, Y)"
;; -> (movers inside overlap hub-x hub-y), or #f.
(define (sb-parse line)
  (and (substring=? line "sandbox: ")
       (let ((words (string-split line " ,()")))
         (and (= (length words) 13)
              (map (lambda (i) (string->number (list-ref words i))) '(1 3 7 11 12))))))

;; The hub starts at x 72 moving 1 px a frame and turns at 72 and 236:
;; after n frames it has moved n px along that back-and-forth track.
(define (sb-hub-x n)
  (let ((m (modulo n 328)))
    (if (<= m 164) (+ 72 m) (- 236 (- m 164)))))

(define sb-shot (demo-tmp "sb-demo-sandbox.png"))
(define sb-scale 2)

;; Pixels of a world rectangle (x y w h) in the screenshot that satisfy keep?.
(define (sb-count keep? x y w h)
  (png-count sb-shot keep? (* sb-scale x) (* sb-scale y) (* sb-scale w) (* sb-scale h)))

(define sb-palette '((255 94 87) (255 170 60) (250 226 80) (110 214 110) (80 186 255) (186 124 255)))
(define (sb-mover-colour? c) (and (memq #t (map (lambda (p) ((near-colour? p) c)) sb-palette)) #t))
(define sb-hub '(250 250 250))
(define sb-arm '(200 204 220))

(test-group "demo: sandbox"
  (test "the hub's track: out to 236, back, out again" '(73 236 100 72 194)
        (map sb-hub-x '(1 164 300 328 450)))

  (test-group "450 frames, no screenshot"
    (let ((r (sb-parse (last-line (demo-output "bin/demo-sandbox --headless --frames 450")))))
      (test-assert "the demo prints its final state" r)
      (when r
        (test "120 movers, all inside the walls" '(120 120) (list (car r) (cadr r)))
        (test-assert "no two movers overlap by half a mover (4 px)" (< (caddr r) 4))
        (test "the windmill's hub is on its track" (list (sb-hub-x 450) 114) (cdddr r)))))

  (test-group "300 frames, with a screenshot"
    (when (file-exists? sb-shot) (delete-file sb-shot))
    (let ((r (sb-parse (last-line (demo-output (string-append "bin/demo-sandbox --headless --frames 300 --screenshot " sb-shot))))))
      (test-assert "the demo prints its final state" r)
      (test-assert "a screenshot at twice the logical size"
                   (and (file-exists? sb-shot)
                        (receive (bytes w h) (png-rgba sb-shot) (and (= w 640) (= h 480)))))
      (when (and r (file-exists? sb-shot))
        (test "120 movers, all inside the walls" '(120 120) (list (car r) (cadr r)))
        (test-assert "no two movers overlap by half a mover (4 px)" (< (caddr r) 4))
        (test "the windmill's hub is on its track" (list (sb-hub-x 300) 114) (cdddr r))
        (let ((hx (list-ref r 3)) (hy (list-ref r 4)))
          ;; the hub is drawn after the movers and is never overlapped
          (test "the hub (12 x 12) is drawn whole at its position"
                (* 12 12 sb-scale sb-scale) (sb-count (near-colour? sb-hub) hx hy 12 12))
          (test "and nowhere else" (* 12 12 sb-scale sb-scale) (png-count sb-shot (near-colour? sb-hub)))
          ;; eight 8 x 8 arm blocks, their centres 15 and 27 px from the
          ;; hub's: far enough apart that none covers another at any angle
          (test "the eight arm blocks are drawn whole around it"
                (* 8 8 8 sb-scale sb-scale)
                (sb-count (near-colour? sb-arm) (- (+ hx 6) 34) (- (+ hy 6) 34) 68 68))
          (test "and nowhere else" (* 8 8 8 sb-scale sb-scale) (png-count sb-shot (near-colour? sb-arm))))
        (let ((mover-px (png-count sb-shot sb-mover-colour?)))
          (test-assert (sprintf "about 120 whole 8 x 8 movers are drawn (~a px)" mover-px)
                       (<= (* 0.97 120 64 sb-scale sb-scale) mover-px (* 120 64 sb-scale sb-scale))))
        (test "no mover is drawn on the walls"
              0 (+ (sb-count sb-mover-colour? 0 0 320 16) (sb-count sb-mover-colour? 0 224 320 16)
                   (sb-count sb-mover-colour? 0 0 16 240) (sb-count sb-mover-colour? 304 0 16 240)))
        (test "nor on a pillar"
              0 (apply + (map (lambda (p) (sb-count sb-mover-colour? (car p) (cadr p) 32 32))
                              '((64 32) (224 32) (64 176) (224 176)))))))))
