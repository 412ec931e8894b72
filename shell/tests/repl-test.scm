;;; The live REPL: a game run with repl: serves expressions between frames
;;; on a loopback TCP port. The game runs in a child csi; this suite is the
;;; client, as a user's editor would be.

(import scheme (chicken base) (chicken format) (chicken io) (chicken process)
        (chicken tcp) (chicken string) (chicken file) (chicken process-context)
        (chicken condition) (downstroke test) (downstroke engine))

(define (last-word line) (let ((ws (string-split line))) (and (pair? ws) (list-ref ws (- (length ws) 1)))))

(define rp-script (sprintf "/tmp/downstroke-repl-~a.scm" (current-process-id)))

(with-output-to-file rp-script
  (lambda ()
    (write '(import scheme (chicken base) (downstroke engine) (downstroke scene)))
    (write '(define boom #f))
    (write '(define game
              (make-game headless?: #t width: 32 height: 24
                         update: (lambda (g dt) (when boom (error "boom went the update hook"))))))
    (write '(game-scene-set! game (make-scene)))
    (write '(game-run! game repl: 0))
    (write '(print "repl-test: the game ended at frame " (game-frame game)))
    (write '(flush-output))))

;; Reads from the port until the text ends with the prompt; the text before it.
(define (rp-until-prompt in)
  (let loop ((acc '()))
    (let ((c (read-char in)))
      (cond ((eof-object? c) (reverse-list->string acc))
            ((and (char=? c #\space) (pair? acc) (char=? (car acc) #\>))
             (reverse-list->string (cdr acc)))
            (else (loop (cons c acc)))))))

(define (rp-eval in out text)
  (display text out) (newline out) (flush-output out)
  (string-chomp (rp-until-prompt in)))

(test-group "repl: a running game evaluates what a client sends"
  (let-values (((child-out child-in pid)
                (process (sprintf "SDL_VIDEODRIVER=dummy SDL_AUDIODRIVER=dummy CHICKEN_REPOSITORY_PATH=~a csi -q -s ~a"
                                  (qs (get-environment-variable "CHICKEN_REPOSITORY_PATH")) rp-script))))
    (let* ((line (let loop () (let ((l (read-line child-out)))
                                (if (or (eof-object? l) (substring-index "repl on" l)) l (loop)))))
           (port (and (string? line) (string->number (last-word line)))))
      (test-assert "the game says which port it serves" (and port (> port 0)))
      (parameterize ((tcp-read-timeout 30000))
        (let-values (((in out) (tcp-connect "127.0.0.1" port)))
          (test-assert "a greeting, then the prompt" (substring-index "evaluated between frames" (rp-until-prompt in)))
          (test "an expression's value comes back" "3" (rp-eval in out "(+ 1 2)"))
          (test "an expression over two lines is read whole" "10" (rp-eval in out "(+ 4\n 6)"))
          (test-assert "an error is printed" (substring-index "Error" (rp-eval in out "(car '())")))
          (test "and the game goes on serving" "42" (rp-eval in out "(* 6 7)"))
          (test-assert "the game is running: its frame count grows"
                       (let ((a (string->number (rp-eval in out "(game-frame game)"))))
                         (sleep 1)
                         (> (string->number (rp-eval in out "(game-frame game)")) a)))
          (test "the game's scene can be inspected" "#t" (rp-eval in out "(scene? (game-scene game))"))
          ;; an error in the update hook pauses the game and is told here
          (test "arming the hook's error" "armed" (rp-eval in out "(begin (set! boom #t) 'armed)"))
          (test-assert "the hook's error is reported, and the game paused"
                       (let ((told (rp-until-prompt in)))
                         (and (substring-index "the game is paused" told)
                              (substring-index "boom went the update hook" told))))
          (test "paused: game-paused? says so" "#t" (rp-eval in out "(game-paused? game)"))
          (test-assert "paused: the frame count stands still"
                       (let ((a (rp-eval in out "(game-frame game)")))
                         (sleep 1)
                         (equal? a (rp-eval in out "(game-frame game)"))))
          (test "fixed and resumed from the REPL" "resumed"
                (rp-eval in out "(begin (set! boom #f) (game-resume! game) 'resumed)"))
          (test-assert "and running again"
                       (let ((a (string->number (rp-eval in out "(game-frame game)"))))
                         (sleep 1)
                         (> (string->number (rp-eval in out "(game-frame game)")) a)))
          (display "(game-quit! game)\n" out) (flush-output out)
          (test-assert "game-quit! ends the run"
                       (let loop () (let ((l (read-line child-out)))
                                      (cond ((eof-object? l) #f)
                                            ((substring-index "the game ended" l) #t)
                                            (else (loop))))))
          (close-input-port in) (close-output-port out))))
    (let-values (((p ok? status) (process-wait pid)))
      (test "the child exits normally" 0 status))
    (close-input-port child-out) (close-output-port child-in)
    (delete-file* rp-script)))

(test-group "repl: bad settings are refused"
  (test-assert "a port out of range names repl:"
               (substring-index "repl: 70000"
                                (condition-case (game-run! (make-game headless?: #t) frames: 1 repl: 70000)
                                  (e (exn) ((condition-property-accessor 'exn 'message) e))))))
