;;; The demos run headless as a user would start them (bin/demo-NAME) and
;;; end where their input says. Screenshots are checked to exist.

(import scheme (chicken base) (chicken io) (chicken process) (chicken file)
        (chicken file posix) (chicken string) (downstroke test))
(include-relative "pixels.scm")
(include-relative "demo-support.scm")

;; The integers of a line, in order ("at (32, 192) ... (0, 0)" -> (32 192 0 0)).
(define (ds-numbers line)
  (let loop ((cs (string->list line)) (digits '()) (out '()))
    (define (flush) (if (null? digits) out (cons (string->number (list->string (reverse digits))) out)))
    (cond ((null? cs) (reverse (flush)))
          ((or (char-numeric? (car cs))
               (and (char=? (car cs) #\-) (null? digits)
                    (pair? (cdr cs)) (char-numeric? (cadr cs))))
           (loop (cdr cs) (cons (car cs) digits) out))
          (else (loop (cdr cs) '() (flush))))))

(test-group "demo: getting-started"
  (with-output-to-file (demo-tmp "ds-gs-script.scm") (lambda () (write '((0 right) (10)))))
  (test "ten frames of the right arrow move the square 30 px"
        "getting-started: square at 180 110"
        (last-line (demo-output (string-append "bin/demo-getting-started --headless --frames 30 --script " (demo-tmp "ds-gs-script.scm")))))
  (with-output-to-file (demo-tmp "ds-gs-corner.scm") (lambda () (write '((0 right down)))))
  (test "held against a corner for 100 frames, it stops at the edges of the 320 x 240 view"
        "getting-started: square at 300 220"
        (last-line (demo-output (string-append "bin/demo-getting-started --headless --frames 100 --script "
                                               (demo-tmp "ds-gs-corner.scm") " --screenshot " (demo-tmp "ds-gs-corner.png")))))
  (test "and is drawn whole in the corner" 400
        (png-count (demo-tmp "ds-gs-corner.png") (near-colour? '(240 200 60)) 300 220 20 20))
  (with-output-to-file (demo-tmp "ds-gs-left.scm") (lambda () (write '((0 left up)))))
  (test "likewise at the top left" "getting-started: square at 0 0"
        (last-line (demo-output (string-append "bin/demo-getting-started --headless --frames 100 --script "
                                               (demo-tmp "ds-gs-left.scm"))))))

(test-group "demo: platformer"
  (when (file-exists? (demo-tmp "ds-platformer.png")) (delete-file (demo-tmp "ds-platformer.png")))
  ;; start pressed on frame 0 leaves the title; 120 frames of play follow
  (with-output-to-file (demo-tmp "ds-start.scm") (lambda () (write '((0 start) (1)))))
  (let ((line (last-line (demo-output (string-append "bin/demo-platformer --headless --frames 121 --script "
                                                     (demo-tmp "ds-start.scm") " --screenshot "
                                                     (demo-tmp "ds-platformer.png"))))))
    (test-assert "the player stands on the ground after 120 frames"
                 (substring-index "on-ground #t" line))
    ;; the lift's tween runs 2 s each way: after 120 frames of 16 ms it is
    ;; nearly at its top (y 120)
    (test-assert "the tweened lift has moved up from y 200"
                 (let ((y (list-ref (ds-numbers line) 4))) (<= 120 y 199)))
    ;; the line's numbers, read back: x y camera-x camera-y
    (let* ((numbers (ds-numbers line))
           (x (list-ref numbers 0)) (y (list-ref numbers 1))
           (cx (list-ref numbers 2)) (cy (list-ref numbers 3))
           (shot (demo-tmp "ds-platformer.png"))
           (scale 2)                    ; the demo's window scale
           (sx (* scale (- x cx))) (sy (* scale (- y cy))))
      (test "the player's shirt (12 x 4 px) is drawn where the line says"
            (* 12 4 scale scale)
            (png-count shot (near-colour? '(40 120 230)) sx sy (* 16 scale) (* 16 scale)))
      (test "the row under its feet is ground, not sky" 0
            (png-count shot (near-colour? '(92 148 252)) sx (+ sy (* 16 scale)) (* 16 scale) scale))
      (test-assert "and the sky is just above its head"
                   (> (png-count shot (near-colour? '(92 148 252)) sx (- sy scale) (* 16 scale) scale) 0)))))

(test-group "demo: getting-started screenshot"
  (when (file-exists? (demo-tmp "ds-gs.png")) (delete-file (demo-tmp "ds-gs.png")))
  (demo-output (string-append "bin/demo-getting-started --headless --frames 30 --script " (demo-tmp "ds-gs-script.scm") " --screenshot " (demo-tmp "ds-gs.png")))
  (test "the square is a 20 x 20 rect of its colour at (180, 110)" 400
        (png-count (demo-tmp "ds-gs.png") (near-colour? '(240 200 60)) 180 110 20 20))
  (test "and nowhere else" 400 (png-count (demo-tmp "ds-gs.png") (near-colour? '(240 200 60)))))

;; ALSA with a device that does not exist stands for a machine without a
;; sound card: alsa-lib would print its own complaints on stderr.
(test-group "demo: quiet without an audio device"
  (with-output-to-file (demo-tmp "ds-start.scm") (lambda () (write '((0 start) (1)))))
  (let* ((err (demo-tmp "ds-quiet.err"))
         (out (with-input-from-pipe
               (string-append "cd .. && SDL_AUDIODRIVER=alsa AUDIODEV=downstroke-no-such-pcm "
                              "bin/demo-platformer --headless --frames 6 --script " (demo-tmp "ds-start.scm")
                              " 2>" err)
               read-lines))
         (errors (with-input-from-file err read-lines)))
    (test "nothing on stderr" '() errors)
    (test "one line says there is no sound, and why" 1
          (length (filter-lines "platformer: no sound (Mix_OpenAudio: ALSA: " out)))
    (test-assert "and the demo ran to its end"
                 (substring-index "on-ground #t" (last-line out)))))

;; A private install sets CHICKEN_INSTALL_REPOSITORY, and then
;; `chicken-install -repository` names that directory: the launcher must
;; still find CHICKEN's own modules (chicken.format ...).
(test-group "demo: the launcher finds CHICKEN's own repository"
  (let ((empty (demo-tmp "empty-repository")))
    (create-directory empty #t)
    (test "with CHICKEN_INSTALL_REPOSITORY naming an empty directory"
          "getting-started: square at 150 110"
          (last-line (demo-output (string-append "env -u CHICKEN_REPOSITORY_PATH CHICKEN_INSTALL_REPOSITORY="
                                                 empty " bin/demo-getting-started --headless --frames 2"))))))

;; The launcher makes the demos' art only when it is missing or older than
;; its generator (tools/make-assets.scm), not on every run.
(test-group "demo: assets are made only when missing or stale"
  (import (chicken file posix))
  (let ((tiles "../demo/assets/tiles.png") (coin "../demo/assets/coin.wav")
        (run (lambda () (demo-output "bin/demo-getting-started --headless --frames 1"))))
    (run)
    (let ((before (file-modification-time tiles)))
      (sleep 1)
      (run)
      (test "a second run leaves tiles.png as it was" before (file-modification-time tiles)))
    ;; Stale, not deleted: the demo suites running beside this one read
    ;; coin.wav, and a missing one fails them.
    (set-file-times! coin 0 0)
    (run)
    (test-assert "a stale coin.wav is made again"
                 (>= (file-modification-time coin) (file-modification-time "../tools/make-assets.scm")))))
