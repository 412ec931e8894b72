;;; bin/demo-audio, run headless as a user would, with SDL's dummy audio
;;; driver: scripted key presses play the effects and toggle the music, the
;;; mixer says so at the end, and the screenshot shows it. With no audio
;;; device at all the demo still runs, silent.

(import scheme (chicken base) (chicken io) (chicken process) (chicken file)
        (chicken string) (downstroke test))
(include-relative "pixels.scm")
(include-relative "demo-support.scm")

;; The lines a demo prints, then "exit N" with its exit status.
(define (au-run env args)
  (with-input-from-pipe (string-append "cd .. && " env " " args " 2>/dev/null; echo exit $?")
                        read-lines))

;; The demo's last line (before the exit status line), and that status.
(define (au-final lines)
  (let ((r (reverse lines)))
    (if (and (pair? r) (pair? (cdr r))) (cadr r) "")))
(define (au-exit lines) (if (null? lines) "" (car (reverse lines))))

(define (au-script! path script) (with-output-to-file path (lambda () (write script))))

(define au-shot (demo-tmp "au-demo-audio.png"))
(define au-silent-shot (demo-tmp "au-demo-audio-silent.png"))

;; A colour test over the screenshot `path`.
(define (au-count path colour x y w h) (png-count path (near-colour? colour 4) x y w h))

(test-group "demo: audio"
  ;; 1 (jump) on frame 10, 2 (coin) on 20, m twice (music off, on again),
  ;; 3 (boom) on frame 50: its card is still lit on frame 59.
  (au-script! (demo-tmp "au-script-all.scm")
              '((10 (tap a)) (20 (tap b)) (30 (tap start)) (40 (tap start)) (50 (tap select))))
  (when (file-exists? au-shot) (delete-file au-shot))
  (let ((lines (au-run "SDL_AUDIODRIVER=dummy"
                       (string-append "bin/demo-audio --headless --frames 60 --script " (demo-tmp "au-script-all.scm") " --screenshot " au-shot))))
    (test "the three keys played the three effects, and the music plays again after m, m"
          "audio: device open #t, music playing #t, effects played (jump coin boom)"
          (au-final lines))
    (test "it exits normally" "exit 0" (au-exit lines)))
  (test-assert "a screenshot was saved" (file-exists? au-shot))
  (when (file-exists? au-shot)
    (test-assert "the boom card (3), pressed 9 frames ago, is lit in red"
                 (> (au-count au-shot '(240 100 80) 430 262 170 104) 12000))
    (test "the jump card (1), pressed 49 frames ago, is dark again"
          '(46 50 76 255) (png-pixel au-shot 45 360))
    (test "no card but boom shows a lit colour as its fill"
          '(0 0) (list (au-count au-shot '(90 200 120) 40 340 170 26)
                       (au-count au-shot '(250 200 70) 235 340 170 26)))
    (test-assert "the equaliser bars are blue: the music plays"
                 (> (au-count au-shot '(110 190 255) 40 170 570 60) 1500))
    (test-assert "\"Music: playing\" is written in green"
                 (> (au-count au-shot '(120 220 140) 40 126 250 34) 300))
    (test-assert "the key help is written in white"
                 (> (au-count au-shot '(255 255 255) 40 400 450 20) 150)))

  ;; m once: the music stops; no effect is played.
  (au-script! (demo-tmp "au-script-stop.scm") '((10 (tap start))))
  (let ((lines (au-run "SDL_AUDIODRIVER=dummy"
                       (string-append "bin/demo-audio --headless --frames 20 --script " (demo-tmp "au-script-stop.scm") " --screenshot " au-shot))))
    (test "m stops the music"
          "audio: device open #t, music playing #f, effects played ()" (au-final lines)))
  (when (file-exists? au-shot)
    (test "stopped, the bars are flat and grey: no blue left"
          0 (au-count au-shot '(110 190 255) 40 170 570 60))
    (test-assert "the flat bars are there, grey"
                 (> (au-count au-shot '(70 74 100) 40 226 570 4) 1500)))

  ;; An audio driver that does not exist: no device, and the demo runs anyway.
  (when (file-exists? au-silent-shot) (delete-file au-silent-shot))
  (let ((lines (au-run "SDL_AUDIODRIVER=no-such-driver"
                       (string-append "bin/demo-audio --headless --frames 30 --script " (demo-tmp "au-script-all.scm") " --screenshot " au-silent-shot))))
    (test "with no audio device nothing plays, and the demo ends normally"
          '("audio: device open #f, music playing #f, effects played ()" "exit 0")
          (list (au-final lines) (au-exit lines))))
  (when (file-exists? au-silent-shot)
    (test-assert "the screen says there is no sound, in orange"
                 (> (au-count au-silent-shot '(250 170 80) 40 84 300 20) 100))
    (test-assert "the jump key still lights its card (pressed on frame 10, 30 frames lit)"
                 (> (au-count au-silent-shot '(90 200 120) 40 262 170 104) 12000))))
