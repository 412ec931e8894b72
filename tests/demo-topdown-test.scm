;;; bin/demo-topdown, run headless as a user would: the player walks where
;;; its script says, stops at walls, picks up the coins it touches, and the
;;; screenshot shows it (and the coins) where the final line says.
;;; The level is demo/levels/topdown.tmx: the player starts at (304, 336),
;;; coins lie on row 19 (y 304) at x 96, 192, 288 and 384, a stone bar spans
;;; x 256..368 at y 272..288, and the bottom wall's top is at y 368.

(import scheme (chicken base) (chicken io) (chicken process) (chicken file)
        (chicken string) (chicken format) (downstroke test))
(include-relative "pixels.scm")
(include-relative "demo-support.scm")

(define (td-script! path script)
  (with-output-to-file path (lambda () (write script))))

(define td-shot (demo-tmp "td-demo-topdown.png"))
(define td-scale 2)                     ; the demo's window scale

;; Pixels of a 16 x 16 world rectangle at (x, y) seen through a camera at
;; (cx, cy), as the screenshot holds them, that satisfy keep?.
(define (td-count-in-tile keep? x y cx cy)
  (png-count td-shot keep? (* td-scale (- x cx)) (* td-scale (- y cy))
             (* td-scale 16) (* td-scale 16)))

(define td-shirt '(40 120 230))         ; the player sprite's shirt
(define td-coin '(252 210 60))          ; a coin's face

(test-group "demo: topdown"
  (test-group "no input: the player stays at the map's start, the camera centred on it"
    (test "the final line"
          "topdown: player at (304, 336) coins 0 of 19 camera (152, 144)"
          (last-line (demo-output "bin/demo-topdown --headless --frames 20"))))

  (test-group "a diagonal walk slides along a wall"
    ;; up-left for 39 moves of 2 px: up 48 px would cross the stone bar, so
    ;; y stops at 288 until x clears its left end (256 - 16 = 240), then goes
    ;; on up to 272; x goes 78 px left and picks up the coin at (288, 304)
    (td-script! (demo-tmp "td-diagonal.scm") '((0 up left)))
    (test "the final line"
          "topdown: player at (226, 272) coins 1 of 19 camera (74, 144)"
          (last-line (demo-output (string-append "bin/demo-topdown --headless --frames 40 --script " (demo-tmp "td-diagonal.scm"))))))

  (test-group "up, left along the coin row, down into the bottom wall"
    (when (file-exists? td-shot) (delete-file td-shot))
    (td-script! (demo-tmp "td-walk.scm") '((0 up) (16 left) (76 down) (110)))
    (let ((line (last-line
                 (demo-output (string-append "bin/demo-topdown --headless --frames 130 --screenshot "
                                        td-shot (string-append " --script " (demo-tmp "td-walk.scm")))))))
      ;; 32 px up to the coin row, 120 px left over two coins, then down
      ;; until the wall: 368 - 16 = 352
      (test "the final line"
            "topdown: player at (184, 352) coins 2 of 19 camera (32, 144)"
            line)
      (test-assert "a screenshot at twice the logical size was saved"
                   (and (file-exists? td-shot)
                        (receive (bytes w h) (png-rgba td-shot) (and (= w 640) (= h 480)))))
      (when (file-exists? td-shot)
        (test "the player's shirt (12 x 4 px) is drawn at its position minus the camera"
              (* 12 4 td-scale td-scale)
              (td-count-in-tile (near-colour? td-shirt) 184 352 32 144))
        (test "and nowhere else"
              (* 12 4 td-scale td-scale)
              (png-count td-shot (near-colour? td-shirt)))
        (test "the coins it walked over are gone: (288, 304)"
              0 (td-count-in-tile (near-colour? td-coin) 288 304 32 144))
        (test "and (192, 304)"
              0 (td-count-in-tile (near-colour? td-coin) 192 304 32 144))
        (test-assert "the coin it did not reach, (96, 304), is still drawn"
                     (> (td-count-in-tile (near-colour? td-coin) 96 304 32 144) 50))
        ;; the tally: one coin icon per coin picked up, 11 px apart, top
        ;; left; a coin's art is 10 px wide, 3 px in from its tile's edge
        (let ((icon (lambda (i) (png-count td-shot (near-colour? td-coin)
                                           (* td-scale (+ 3 (* 11 i))) (* td-scale 2)
                                           (* td-scale 10) (* td-scale 16)))))
          (test-assert "two coin icons in the tally" (and (> (icon 0) 50) (> (icon 1) 50)))
          (test "and no third" 0 (icon 2)))))))
