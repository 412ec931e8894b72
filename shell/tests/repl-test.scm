;;; The live REPL: only the game's owner may use it, and no client, however
;;; hostile, can stop, freeze or fool the game it serves.
;;;
;;; Part one serves a REPL in this process, calling repl-poll! itself (each
;;; call a frame), with clients whose every byte it places. Part two runs a
;;; game (game-run! ... repl: 0) in a child process while clients attack it
;;; from forked children (one of them as another user, when this suite runs
;;; as root); after each attack the owner's client checks that the frames go
;;; on and that nothing the attacker sent was evaluated. The clients are in
;;; tests/repl-clients.scm, compiled here.

(import scheme (chicken base) (chicken format) (chicken io) (chicken process)
        (chicken string) (chicken file) (chicken file posix) (chicken pathname)
        (chicken process-context) (chicken process-context posix) (chicken condition)
        (chicken bitwise)
        (downstroke test) (downstroke repl))

(define rt-dir (sprintf "/tmp/downstroke-repl-test-~a" (current-process-id)))
(when (directory-exists? rt-dir) (delete-directory rt-dir #t))
(create-directory rt-dir #t)

(let ((so (make-pathname rt-dir "repl-clients.so")))
  (unless (zero? (system (sprintf "csc -s -O2 -d0 repl-clients.scm -o ~a" (qs so))))
    (error "repl-test: cannot compile tests/repl-clients.scm"))
  (load so))

(define rt-root? (= (current-effective-user-id) 0))
(define rt-nobody 65534)

;; What the attackers send: evaluated, it would count here (the REPL
;; evaluates in this toplevel) or in the game's.
(define rt-hits 0)
(define rt-hit "(set! rt-hits (+ rt-hits 1))\n")
(define rt-pwn "(set! rt-pwned (+ rt-pwned 1))\n")
(define (rt-http body)
  (string-append "POST / HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: text/plain\r\n"
                 (sprintf "Content-Length: ~a\r\n\r\n" (string-length body)) body))

(define (rt-suffix? s text)
  (let ((n (string-length s)) (m (string-length text)))
    (and (>= m n) (string=? s (substring text (- m n))))))
(define (rt-file-text f) (with-input-from-file f read-string))
(define (rt-error-text thunk)
  (handle-exceptions e ((condition-property-accessor 'exn 'message "") e) (thunk) "no error"))
(define (rt-mode f) (bitwise-and (file-permissions f) #o777))
(define (rt-count-true ls) (cond ((null? ls) 0) ((car ls) (+ 1 (rt-count-true (cdr ls)))) (else (rt-count-true (cdr ls)))))

;;; ------------------------------------------------------------------
;;; Part one: a REPL served by this process.

;; What the REPLs here tell the owner (on the standard error) is kept.
(define rt-log (open-output-string))

(define rt-secrets (make-pathname rt-dir "secrets"))

;; Polls r, waiting up to 1 ms each time for fd's answer, until it ends
;; with the prompt, the connection ends ("<closed>" is appended), or
;; `polls` polls pass.
(define (rt-answer r fd #!optional (polls 3000))
  (let loop ((i 0) (got ""))
    (repl-poll! r)
    (let* ((n (rc-recv fd rc-buffer (string-length rc-buffer) 1))
           (got (if (> n 0) (string-append got (substring rc-buffer 0 n)) got)))
      (cond ((and (> n 0) (rt-suffix? "> " got)) got)
            ((or (= n 0) (= n -2)) (string-append got "<closed>"))
            ((>= i polls) got)
            (else (loop (+ i 1) got))))))

(define (rt-ask r fd text) (rc-send fd text) (rt-answer r fd))

;; #t when nothing comes back to fd during `polls` polls.
(define (rt-quiet? r fd polls)
  (let loop ((i 0))
    (repl-poll! r)
    (cond ((rc-readable? fd 1) #f)
          ((>= i polls) #t)
          (else (loop (+ i 1))))))

(define (rt-secret r) (string-chomp (rt-file-text (repl-secret-file r))))

;; A client that has proved itself: its socket, past the greeting.
(define (rt-owner r)
  (let ((fd (rc-connect (repl-port r))))
    (and (substring-index "evaluated between frames" (rt-ask r fd (string-append (rt-secret r) "\n")))
         fd)))

(define (rt-hex-line? text)
  (and (= (string-length text) 65)
       (char=? (string-ref text 64) #\newline)
       (let loop ((i 0))
         (or (= i 64)
             (and (memv (string-ref text i) (string->list "0123456789abcdef")) (loop (+ i 1)))))))

(parameterize ((current-error-port rt-log))

(test-group "repl: the owner's secret, in a file only the owner can read"
  (let* ((r1 (make-repl port: 0 secret-directory: rt-secrets))
         (r2 (make-repl port: 0 secret-directory: rt-secrets))
         (f1 (repl-secret-file r1))
         (f2 (repl-secret-file r2)))
    (test "the file is named by the port" (sprintf "repl-~a" (repl-port r1)) (pathname-strip-directory f1))
    (test "its directory is this user's alone (0700)" #o700 (rt-mode rt-secrets))
    (test "and the file too (0600)" #o600 (rt-mode f1))
    (test "owned by this user" (current-effective-user-id) (file-owner f1))
    (test-assert "it holds 32 random bytes as 64 hex digits, and a newline" (rt-hex-line? (rt-file-text f1)))
    (test-assert "each REPL has its own" (not (equal? (rt-file-text f1) (rt-file-text f2))))
    (repl-close! r1)
    (repl-close! r2)
    (test "repl-close! removes both" '(#f #f) (list (file-exists? f1) (file-exists? f2))))
  (let ((r (make-repl)))
    (test "no port, no secret file" #f (repl-secret-file r))
    (repl-close! r)))

(test-group "repl: the secret's directory must be this user's alone"
  (let ((open-dir (make-pathname rt-dir "open"))
        (link (make-pathname rt-dir "link"))
        (theirs (make-pathname rt-dir "theirs")))
    (create-directory open-dir)
    (set-file-permissions! open-dir #o755)
    (test-assert "one other users can open is refused, and named"
                 (let ((t (rt-error-text (lambda () (make-repl port: 0 secret-directory: open-dir)))))
                   (and (substring-index open-dir t) (substring-index "other users" t))))
    (test "nothing was written in it" '() (directory open-dir))
    (create-symbolic-link rt-secrets link)
    (test-assert "a symbolic link is not followed"
                 (substring-index link (rt-error-text (lambda () (make-repl port: 0 secret-directory: link)))))
    (if rt-root?
        (begin
          (create-directory theirs)
          (set-file-permissions! theirs #o700)
          (set-file-owner! theirs rt-nobody)
          (test-assert "another user's is refused"
                       (substring-index "belongs to another user"
                                        (rt-error-text (lambda () (make-repl port: 0 secret-directory: theirs))))))
        (print "repl-test: not root, so no directory of another user's is tried"))))

(test-group "repl: before the secret nothing is read as Scheme"
  (let ((r (make-repl port: 0 secret-directory: rt-secrets timeout: 200)))
    ;; connects, sends first, polls: #t when closed with nothing said
    (define (refused? first)
      (let ((fd (rc-connect (repl-port r))))
        (rc-send fd first)
        (let ((got (rt-answer r fd 3000)))
          (rc-close fd)
          (equal? got "<closed>"))))
    (define (changed text)
      (string-append (substring text 0 10)
                     (if (char=? (string-ref text 10) #\a) "b" "a")
                     (substring text 11)))
    (test-assert "an expression first: closed, unanswered" (refused? rt-hit))
    (test-assert "a wrong secret, then an expression"
                 (refused? (string-append (make-string 64 #\0) "\n" rt-hit)))
    (test-assert "the secret with one digit changed"
                 (refused? (string-append (changed (rt-secret r)) "\n" rt-hit)))
    (test-assert "the secret with more after it on its line"
                 (refused? (string-append (rt-secret r) " " rt-hit)))
    (test-assert "an HTTP request, as any web page can send to 127.0.0.1" (refused? (rt-http rt-hit)))
    (test-assert "junk with no line end" (refused? (make-string 100 #\x)))
    (test-assert "nothing at all, for longer than the timeout" (refused? ""))
    (test "none of it was evaluated" 0 rt-hits)
    (let ((fd (rt-owner r)))
      (test-assert "the owner's client is greeted" fd)
      (test "and answered" "3\n> " (rt-ask r fd "(+ 1 2)\n"))
      (test "the secret and an expression in one packet" "7\n> "
            (let ((fd2 (rc-connect (repl-port r))))
              (rc-send fd2 (string-append (rt-secret r) "\n(+ 3 4)\n"))
              (let ((got (rt-answer r fd2)))
                (rc-close fd2)
                (if (substring-index "> " got) (substring got (+ 2 (substring-index "> " got))) got))))
      (rc-close fd))
    (repl-close! r)))

;; Expressions whose ends a naive reading gets wrong, and their answers.
(define rt-corpus
  '(("(+ 1 2)" . "3\n> ")
    ("(when #f (rt-no-such-procedure))" . "> ")
    ("(string-length \"a;b)\\\"(\")" . "6\n> ")
    ("(list #\\( #\\) #\\; #\\\")" . "(#\\( #\\) #\\; #\\\")\n> ")
    ("'|a b)|" . "|a b)|\n> ")
    ("#| ( #| nested ) |# |# (+ 2 3)" . "5\n> ")
    ("(+ 1 #;(oops 2) 3)" . "4\n> ")
    ("#!eof" . "#!eof\n> ")
    ("#<<END\n((\nEND" . "\"((\"\n> ")
    ("(vector-length #(1 (2) 3))" . "3\n> ")
    ("`(1 ,(+ 1 1))" . "(1 2)\n> ")
    ("[+ 1 {+ 1 1}]" . "3\n> ")
    ("; a comment (\n(+ 7 0)" . "7\n> ")
    ("#${0aff}" . "#${0aff}\n> ")
    ("(quote abc)" . "abc\n> ")
    ("\"a\\\\\"" . "\"a\\\\\"\n> ")))

(test-group "repl: an expression is evaluated once, whole, however its bytes arrive"
  (let* ((r (make-repl port: 0 secret-directory: rt-secrets))
         (fd (rt-owner r)))
    (for-each
     (lambda (c)
       (let ((text (car c)) (answer (cdr c)))
         (test (sprintf "sent whole: ~s" text) answer (rt-ask r fd (string-append text "\n")))
         ;; the first k bytes, frames, then the rest: no answer before the
         ;; rest, then the answer to the whole
         (test (sprintf "split at each of its ~a points: ~s" (- (string-length text) 1) text) '()
               (let loop ((k 1) (wrong '()))
                 (if (= k (string-length text))
                     (reverse wrong)
                     (begin
                       (rc-send fd (substring text 0 k))
                       (let* ((waited? (rt-quiet? r fd 3))
                              (got (rt-ask r fd (string-append (substring text k) "\n"))))
                         (loop (+ k 1) (if (and waited? (equal? got answer)) wrong (cons (list k got) wrong))))))))))
     rt-corpus)
    (test "all of them one byte at a time, a frame after each byte"
          (apply string-append (map cdr rt-corpus))
          (let ((all (apply string-append (map (lambda (c) (string-append (car c) "\n")) rt-corpus)))
                (size (apply + (map (lambda (c) (string-length (cdr c))) rt-corpus))))
            (define (more got wait)
              (let ((n (rc-recv fd rc-buffer (string-length rc-buffer) wait)))
                (if (> n 0) (string-append got (substring rc-buffer 0 n)) got)))
            (let loop ((i 0) (got ""))
              (cond ((< i (string-length all))
                     (rc-send fd (string (string-ref all i)))
                     (repl-poll! r)
                     (loop (+ i 1) (more got 0)))
                    ((or (>= (string-length got) size) (> i (+ (string-length all) 2000))) got)
                    (else (repl-poll! r) (loop (+ i 1) (more got 1)))))))
    (test-assert "an unreadable expression is an error at its line's end"
                 (substring-index "unreadable object" (rt-ask r fd "(list #<junk> 1\n")))
    (rc-send fd (string-append "(car " rt-hit "))\n"))
    (test-assert "and its later lines are skipped, unevaluated" (rt-quiet? r fd 20))
    (test-assert "unreadable text before an unfinished expression is an error at once"
                 (substring-index "unreadable object" (rt-ask r fd "#<junk> (list 1\n")))
    (rc-send fd (string-append rt-hit ")\n"))
    (test-assert "the rest of that expression, arriving later, is skipped, not evaluated" (rt-quiet? r fd 20))
    (test "and the session goes on" "2\n> " (rt-ask r fd "(+ 1 1)\n"))
    (test-assert "an unfinished expression at the end of the input is an error, not silence"
                 (begin (rc-send fd "(+ 1")
                        (rc-shutdown-write fd)
                        (substring-index "unterminated list" (rt-answer r fd))))
    (test "none of it was evaluated" 0 rt-hits)
    (rc-close fd)
    (repl-close! r)))

(test-group "repl: limits a game can raise"
  (test-assert "repl-max-input refuses a value that is no positive integer, by name"
               (substring-index "repl-max-input: 0 must be" (rt-error-text (lambda () (repl-max-input 0)))))
  (test-assert "make-repl refuses a bad max-output:, by name"
               (substring-index "make-repl: max-output: lots must be" (rt-error-text (lambda () (make-repl max-output: 'lots)))))
  (let* ((r (parameterize ((repl-max-clients 2)) (make-repl port: 0 secret-directory: rt-secrets)))
         (a (rt-owner r))
         (b (rt-owner r))
         (c (rc-connect (repl-port r))))
    (rc-send c (string-append (rt-secret r) "\n" rt-hit))
    (test "past repl-max-clients a connection is closed at once, even with the secret"
          "<closed>" (rt-answer r c))
    (test "the others are served" '("1\n> " "2\n> ") (list (rt-ask r a "1\n") (rt-ask r b "2\n")))
    (for-each rc-close (list a b c))
    (repl-close! r))
  ;; silent connections (anyone on the machine can open them) hold every
  ;; place: each new connection takes the place of the oldest of them
  (let* ((r (parameterize ((repl-max-clients 2)) (make-repl port: 0 secret-directory: rt-secrets)))
         (silent-a (rc-connect (repl-port r)))
         (silent-b (rc-connect (repl-port r))))
    (test-assert "two silent connections are taken, and told nothing" (rt-quiet? r silent-a 20))
    (let ((owner (rt-owner r)))
      (test-assert "the owner still gets in" owner)
      (test "and is served" "3\n> " (and owner (rt-ask r owner "(+ 1 2)\n")))
      (test "the older silent connection was closed for it" "<closed>" (rt-answer r silent-a 50))
      (test-assert "the younger one is still open" (rt-quiet? r silent-b 20))
      (let ((next (rt-owner r)))
        (test "the next owner takes the younger one's place, and is served" "4\n> "
              (and next (rt-ask r next "(+ 2 2)\n")))
        (test "which is closed" "<closed>" (rt-answer r silent-b 50))
        (let ((c (rc-connect (repl-port r))))
          (rc-send c (string-append (rt-secret r) "\n" rt-hit))
          (test "with every place held by owners, one more is closed at once, even with the secret"
                "<closed>" (rt-answer r c))
          (rc-close c))
        (when next (rc-close next)))
      (when owner (rc-close owner)))
    (for-each rc-close (list silent-a silent-b))
    (repl-close! r))
  ;; a connection whose secret has arrived, not yet read, is not silent
  (let* ((r (parameterize ((repl-max-clients 1)) (make-repl port: 0 secret-directory: rt-secrets)))
         (hits rt-hits)
         (first (rc-connect (repl-port r))))
    (rc-send first (string-append (rt-secret r) "\n"))
    (let ((second (rc-connect (repl-port r))))
      (rc-send second (string-append (rt-secret r) "\n" rt-hit))
      (test "both wait to be accepted; the first, its secret read when the second needs its place, keeps it"
            "<closed>" (rt-answer r second))
      (test-assert "and is served"
                   (substring-index "evaluated between frames" (rt-answer r first)))
      (test "the second's expression was not evaluated" hits rt-hits)
      (for-each rc-close (list first second)))
    (repl-close! r))
  (let* ((r (make-repl port: 0 secret-directory: rt-secrets max-input: 1000))
         (fd (rt-owner r)))
    (rc-send fd (string-append "(list \"" (make-string 3000 #\a)))
    (test-assert "an expression longer than max-input: closed, and told why"
                 (let ((got (rt-answer r fd)))
                   (and (substring-index "longer than 1000 bytes" got) (rt-suffix? "<closed>" got))))
    (rc-close fd)
    (let ((fd (rt-owner r)))
      (test "the REPL goes on" "5\n> " (rt-ask r fd "(+ 2 3)\n"))
      (rc-close fd))
    (repl-close! r))
  (let* ((r (make-repl port: 0 secret-directory: rt-secrets max-output: 100000))
         (fd (rt-owner r)))
    (rc-send fd "(make-string 20000000 #\\a)\n")
    (let loop ((i 0)) (when (< i 50) (repl-poll! r) (loop (+ i 1))))
    (test-assert "a client that reads none of an answer past max-output is dropped: it gets less, then the end"
                 (let-values (((n ended?) (rc-drain fd 2000))) (and ended? (< n 20000000))))
    (rc-close fd)
    (repl-close! r))
  (let* ((r (make-repl port: 0 secret-directory: rt-secrets max-output: 100000000 timeout: 200))
         (fd (rt-owner r)))
    (rc-send fd "(make-string 12000000 #\\a)\n")
    (let loop ((i 0)) (when (< i 400) (repl-poll! r) (rc-sleep 1) (loop (+ i 1))))
    (test-assert "a client that reads nothing for the timeout is dropped: it gets less than its answer, then the end"
                 (let-values (((n ended?) (rc-drain fd 2000))) (and ended? (< n 12000000))))
    (rc-close fd)
    (repl-close! r)))

(test-group "repl: refusals and drops are told to the owner"
  ;; each REPL's first; those following within a second are counted
  (let ((log (get-output-string rt-log)))
    (for-each (lambda (line) (test-assert line (substring-index line log)))
              '("refused a connection: its first line was not the secret"
                "refused a connection: 2 are open (repl-max-clients)"
                "dropped a connection that had not sent the secret, to make room for a new one (repl-max-clients)"
                "dropped a client: it sent an expression longer than 1000 bytes (repl-max-input)"
                "dropped a client: more than 100000 bytes of output were waiting for it (repl-max-output)"
                "dropped a client: it read none of its output for 200 ms (repl-timeout)")))))

;;; ------------------------------------------------------------------
;;; Part two: a game serving its REPL in a child process.

(define rt-home (make-pathname rt-dir "home"))
(create-directory rt-home)

;; limits: the game's small ones, so that the attackers reach them quickly
(define (rt-game-script file limits)
  (with-output-to-file file
    (lambda ()
      (for-each write
                `((import scheme (chicken base) (downstroke engine) (downstroke scene) (downstroke repl))
                  (define rt-pwned 0)
                  (define boom #f)
                  ,@limits
                  (define game
                    (make-game headless?: #t width: 32 height: 24
                               update: (lambda (g dt) (when boom (error "boom went the update hook")))))
                  (game-scene-set! game (make-scene))
                  (game-run! game repl: 0)
                  (print "repl-test: the game ended at frame " (game-frame game))
                  (flush-output))))))

;; The games started and not yet seen to end, stopped at the end of the
;; suite should a failure leave one running.
(define rt-games '())

;; (values stdout pid port secret-file) of a game started with the shell
;; prefix (a ulimit), its standard error going to err.
(define (rt-start-game script prefix err)
  (let-values (((out in pid)
                (process (sprintf "~a exec env -u XDG_RUNTIME_DIR HOME=~a SDL_VIDEODRIVER=dummy SDL_AUDIODRIVER=dummy CHICKEN_REPOSITORY_PATH=~a csi -q -s ~a 2>~a"
                                  prefix (qs rt-home) (qs (absolute-repository-path)) (qs script) (qs err)))))
    (close-output-port in)
    (set! rt-games (cons pid rt-games))
    (let* ((line (let loop ((k 0))
                   (let ((l (read-line out)))
                     (cond ((eof-object? l) "")
                           ((substring-index "repl on" l) l)
                           ((> k 50) "")
                           (else (loop (+ k 1)))))))
           (at (substring-index "port " line))
           (port (and at (string->number (let digits ((i (+ at 5)) (acc '()))
                                           (if (and (< i (string-length line)) (char-numeric? (string-ref line i)))
                                               (digits (+ i 1) (cons (string-ref line i) acc))
                                               (reverse-list->string acc))))))
           (s (substring-index "(secret in " line))
           (file (and s (substring line (+ s 11) (- (string-length line) 1)))))
      (values out pid port file))))

;; Text received by the owner's clients past the answer last read.
(define gc-unread '())

;; Reads fd up to the next prompt: the text before it, or #f when none
;; came in 10 s.
(define (gc-answer fd)
  (let* ((had (cond ((assv fd gc-unread) => cdr) (else "")))
         (prompt (lambda (t) (substring-index "> " t))))
    (let-values (((t how) (if (prompt had) (values had 'done) (rc-read-until fd prompt))))
      (let ((t (if (prompt had) had (string-append had t))))
        (and (prompt t)
             (let ((at (prompt t)))
               (set! gc-unread (cons (cons fd (substring t (+ at 2))) gc-unread))
               (string-chomp (substring t 0 at))))))))

;; The owner's client: its socket past the greeting, or #f.
(define (gc-open port secret)
  (let ((fd (rc-connect port)))
    (set! gc-unread (cons (cons fd "") gc-unread))
    (and (>= fd 0)
         (rc-send fd (string-append secret "\n(quote rt-sync)\n"))
         (let loop ((k 0))
           (let ((a (gc-answer fd)))
             (cond ((equal? a "rt-sync") fd)
                   ((or (not a) (= k 3)) #f)
                   (else (loop (+ k 1)))))))))

;; What evaluating text printed before the prompt, or #f when no prompt
;; came in 10 s.
(define (gc-eval fd text)
  (and fd (rc-send fd (string-append text "\n")) (gc-answer fd)))

(define (gc-frame fd) (let ((a (gc-eval fd "(game-frame game)"))) (and a (string->number a))))

;; #t once the game's frame count passes what it was (asked every 20 ms,
;; `tries` times).
(define (rt-frames-go-on? fd #!optional (tries 100))
  (let ((a (gc-frame fd)))
    (and a (let loop ((k 0))
             (let ((b (gc-frame fd)))
               (cond ((and b (> b a)) #t)
                     ((or (not b) (= k tries)) #f)
                     (else (rc-sleep 20) (loop (+ k 1)))))))))

(define (rt-goes-on fd what)
  (test-assert (sprintf "~a: the game goes on, and answers its owner" what) (rt-frames-go-on? fd)))

;; A forked child running thunk, whose result is its exit status.
(define (rt-fork thunk)
  (flush-output)
  (flush-output (current-error-port))
  (process-fork (lambda () (rc-exit (handle-exceptions e 99 (thunk))))))
(define (rt-status pid)
  (let-values (((p ok? status) (process-wait pid)))
    (set! rt-games (let drop ((ps rt-games)) (cond ((null? ps) '()) ((= (car ps) pid) (cdr ps)) (else (cons (car ps) (drop (cdr ps)))))))
    status))
(define (rt-child thunk) (rt-status (rt-fork thunk)))

;; A child's verdict: 0 when the connection ended having sent nothing.
(define (rt-ended-unanswered fd)
  (let-values (((n ended?) (rc-drain fd 10000)))
    (rc-close fd)
    (if (and ended? (= n 0)) 0 1)))

;; Sends text in 64 KiB pieces until the peer stops it: the bytes it took.
(define (rt-flood fd text total)
  (let loop ((sent 0))
    (if (or (>= sent total) (not (rc-send fd text 5000)))
        sent
        (loop (+ sent (string-length text))))))

(test-group "repl: a game's REPL, attacked while it runs"
  (let ((script (make-pathname rt-dir "game.scm"))
        (err (make-pathname rt-dir "game.err")))
    (rt-game-script script '((repl-timeout 1000) (repl-max-clients 6)
                             (repl-max-input 65536) (repl-max-output 262144)))
    (let-values (((out pid port file) (rt-start-game script "" err)))
      (test-assert "the game says its port" (and port (> port 0)))
      (test-assert "and where its secret is, in a file only its user can read"
                   (and file (file-exists? file) (= (rt-mode file) #o600)))
      (let* ((secret (if (and file (file-exists? file)) (string-chomp (rt-file-text file)) ""))
             (owner (gc-open port secret)))
        (define (goes-on what) (rt-goes-on owner what))
        (test "the owner's client is answered" "3" (gc-eval owner "(+ 1 2)"))

        (test "no secret, an expression: closed unanswered" 0
              (rt-child (lambda () (let ((fd (rc-connect port))) (rc-send fd rt-pwn) (rt-ended-unanswered fd)))))
        (test "a wrong secret: closed unanswered" 0
              (rt-child (lambda () (let ((fd (rc-connect port)))
                                     (rc-send fd (string-append (make-string 64 #\7) "\n" rt-pwn))
                                     (rt-ended-unanswered fd)))))
        (test "an HTTP POST with an expression as its body: closed unanswered" 0
              (rt-child (lambda () (let ((fd (rc-connect port))) (rc-send fd (rt-http rt-pwn)) (rt-ended-unanswered fd)))))
        (test "a client that sends nothing: closed after the timeout" 0
              (rt-child (lambda () (rt-ended-unanswered (rc-connect port)))))
        (test "20 MB of junk with no line end: cut off within the first 4 MB" 0
              (rt-child (lambda () (let* ((fd (rc-connect port))
                                          (sent (rt-flood fd (make-string 65536 #\x) 20000000)))
                                     (rc-close fd)
                                     (if (< sent 4000000) 0 1)))))
        (goes-on "after those")
        (if rt-root?
            (test "another user, who cannot read the secret, is closed unanswered" 0
                  (rt-child (lambda ()
                              (cond ((not (rc-become rt-nobody rt-nobody)) 2)
                                    ((rc-can-read? file) 3)
                                    (else (let ((fd (rc-connect port)))
                                            (rc-send fd (string-append (make-string 64 #\a) "\n" rt-pwn))
                                            (rt-ended-unanswered fd)))))))
            (print "repl-test: not root, so no other user's client is tried"))

        (test "a connection reset at once (a port scanner)" 0
              (rt-child (lambda () (rc-reset (rc-connect port)) 0)))
        (test "a connection reset with its answer unread" 0
              (rt-child (lambda () (let ((fd (rc-connect port)))
                                     (rc-send fd (string-append secret "\n(make-string 1000 #\\a)\n"))
                                     (rc-readable? fd 5000)
                                     (rc-reset fd)
                                     0))))
        (test "a client that closes before its answer is written" 0
              (rt-child (lambda () (let ((fd (rc-connect port)))
                                     (rc-send fd (string-append secret "\n(make-string 200000 #\\a)\n"))
                                     (rc-close fd)
                                     0))))
        (goes-on "after resets and early closes")

        ;; a client that asks for 20 MB and reads nothing until told; the
        ;; owner meanwhile is answered
        (let-values (((told-in told-out) (create-pipe))
                     ((sent-in sent-out) (create-pipe)))
          (let ((pid (rt-fork (lambda ()
                                (let ((fd (rc-connect port)))
                                  (rc-send fd (string-append secret "\n(make-string 20000000 #\\a)\n"))
                                  (file-write sent-out "s")
                                  (file-read told-in 1)
                                  ;; the game may still be writing the answer when this
                                  ;; starts (on a loaded machine, seconds): wait up to a
                                  ;; minute for each piece, so that only a game that never
                                  ;; drops the client fails
                                  (let-values (((n ended?) (rc-drain fd 60000)))
                                    (if (and ended? (< n 20000000)) 0 1)))))))
            (file-read sent-in 1)
            (goes-on "while a client reads none of a large answer")
            ;; Each poll serves the owner before that client, so an answer
            ;; to the owner can come just before the game evaluates the
            ;; client's request; had the client begun to read then, it
            ;; would rightly get all of the answer. Two more round trips
            ;; are two more polls: the request has been evaluated.
            (test "the owner, twice more" '("3" "3") (list (gc-eval owner "(+ 1 2)") (gc-eval owner "(+ 1 2)")))
            (file-write told-out "t")
            (test "that client was dropped before its answer was all sent" 0 (rt-status pid))
            (for-each file-close (list told-in told-out sent-in sent-out))))

        (test "20 MB on one line after the secret: cut off within the first 4 MB" 0
              (rt-child (lambda () (let ((fd (rc-connect port)))
                                     (rc-send fd (string-append secret "\n(quote "))
                                     (let ((sent (rt-flood fd (make-string 65536 #\a) 20000000)))
                                       (rc-close fd)
                                       (if (< sent 4000000) 0 1))))))
        (goes-on "after the floods")

        ;; the owner holds one of the 6 connections; 10 more try
        (test "past repl-max-clients connections are closed at once" 0
              (rt-child (lambda ()
                          (let* ((fds (let loop ((k 0) (acc '()))
                                        (if (= k 10) (reverse acc)
                                            (let ((fd (rc-connect port)))
                                              (rc-send fd (string-append secret "\n(quote rt-here)\n"))
                                              (loop (+ k 1) (cons fd acc))))))
                                 (answered (map (lambda (fd)
                                                  (let-values (((t how) (rc-read-until fd (lambda (t) (substring-index "rt-here" t)) 3000)))
                                                    (eq? how 'done)))
                                                fds))
                                 (served (rt-count-true answered)))
                            (for-each rc-close fds)
                            (if (and (<= served 5) (>= (- 10 served) 5)) 0 1)))))
        (goes-on "after too many connections")

        ;; an expression split as a line-at-a-time client sends it, with
        ;; frames between; a second owner's client makes sure of a frame
        (let ((other (gc-open port secret)))
          (rc-send owner "(when #f\n")
          (test "the other client is answered while the first one's expression is unfinished" "rt-barrier"
                (gc-eval other "(quote rt-barrier)"))
          (test "the rest arrives: the whole (when #f ...) is evaluated, nothing else" ""
                (gc-eval owner (string-append "(set! rt-pwned (+ rt-pwned 1)))")))
          (rc-close other))
        (test "#!eof is answered as a value" "#!eof" (gc-eval owner "#!eof"))
        (test "and the session goes on" "2" (gc-eval owner "(+ 1 1)"))
        (test "nothing any attacker sent was evaluated" "0" (gc-eval owner "rt-pwned"))

        ;; the client a user types
        (test-assert "bin/downstroke-repl PORT sends the secret and relays both ways"
                     (let-values (((cout cin cpid)
                                   (process (sprintf "env -u XDG_RUNTIME_DIR HOME=~a CHICKEN_REPOSITORY_PATH=~a ../bin/downstroke-repl ~a"
                                                     (qs rt-home) (qs (absolute-repository-path)) port))))
                       (display "(+ 20 22)\n(quote rt-done)\n" cin)
                       (close-output-port cin)
                       (let ((text (read-string #f cout)))
                         (close-input-port cout)
                         (and (string? text) (substring-index "\n> 42\n> rt-done\n" text)))))

        ;; an error in a hook pauses the game and is told to the owner
        (test "arming the hook's error" "armed" (gc-eval owner "(begin (set! boom #t) 'armed)"))
        (test-assert "the hook's error is reported, and the game paused"
                     (let ((told (gc-answer owner)))
                       (and told
                            (substring-index "the game is paused" told)
                            (substring-index "boom went the update hook" told))))
        (test "paused: game-paused? says so" "#t" (gc-eval owner "(game-paused? game)"))
        (test-assert "paused: the frame count stands still" (not (rt-frames-go-on? owner 25)))
        (test "fixed and resumed from the REPL" "resumed"
              (gc-eval owner "(begin (set! boom #f) (game-resume! game) 'resumed)"))
        (goes-on "resumed")

        (rc-send owner "(game-quit! game)\n")
        (test-assert "game-quit! ends the run"
                     (let loop ()
                       (let ((l (read-line out)))
                         (cond ((eof-object? l) #f)
                               ((substring-index "the game ended" l) #t)
                               (else (loop))))))
        (rc-close owner)
        (test "the game exits normally" 0 (rt-status pid))
        (close-input-port out)
        (test "its secret file is gone" #f (and file (file-exists? file)))
        (test-assert "the refusals are told on its standard error"
                     (substring-index "refused a connection: its first line was not the secret" (rt-file-text err)))))))

(test-group "repl: out of file descriptors, the game goes on"
  (let ((script (make-pathname rt-dir "game2.scm"))
        (err (make-pathname rt-dir "game2.err")))
    (rt-game-script script '((repl-max-clients 1000)))
    ;; 100 silent connections against a limit of 64 descriptors (a headless
    ;; game uses about a dozen)
    (let-values (((out pid port file) (rt-start-game script "ulimit -n 64;" err)))
      (let* ((secret (if (and file (file-exists? file)) (string-chomp (rt-file-text file)) ""))
             (owner (gc-open port secret)))
        (test "the owner's client is answered" "3" (gc-eval owner "(+ 1 2)"))
        (let-values (((told-in told-out) (create-pipe))
                     ((held-in held-out) (create-pipe)))
          (let ((child (rt-fork (lambda ()
                                  (let ((fds (let loop ((k 0) (acc '()))
                                               (if (= k 100) acc (loop (+ k 1) (cons (rc-connect port) acc))))))
                                    (file-write held-out "h")
                                    (file-read told-in 1)
                                    (for-each rc-close fds)
                                    0)))))
            (file-read held-in 1)
            (rt-goes-on owner "with its descriptors used up")
            (file-write told-out "t")
            (rt-status child)
            (for-each file-close (list told-in told-out held-in held-out))))
        ;; a frame after they closed, their descriptors are free
        (gc-eval owner "(+ 1 1)")
        (let ((again (gc-open port secret)))
          (test "once they are closed, a new client is served" "4" (gc-eval again "(+ 2 2)"))
          (when again (rc-close again)))
        (test-assert "the game said it closed connections for want of descriptors"
                     (substring-index "out of descriptors" (rt-file-text err)))
        (rc-send owner "(game-quit! game)\n")
        (rc-close owner)
        (test "the game exits normally" 0 (rt-status pid))
        (close-input-port out)))))

(test-group "repl-connect"
  (test-assert "with no secret file it says which file and port"
               (let ((t (rt-error-text (lambda () (repl-connect 7 (make-pathname rt-dir "none"))))))
                 (and (substring-index "none" t) (substring-index "port 7" t)))))

(for-each (lambda (pid) (handle-exceptions e #f (process-signal pid signal/kill) (process-wait pid))) rt-games)
(delete-directory rt-dir #t)
