;;; (downstroke repl): a read-eval-print loop that a running game serves
;;; between its frames, on standard input and/or a loopback TCP port that
;;; only the game's owner can use.
;;;
;;; The port is on 127.0.0.1 and each connection must first prove that its
;;; user is the game's: its first line must be a secret of 32 random bytes
;;; (64 hex digits) that make-repl writes to a file only that user can read
;;; (repl-secret-file), removed by repl-close!. Until then nothing it sends
;;; is read as Scheme; any other first line (an HTTP request, junk) or none
;;; in time closes the connection. repl-connect is the client.
;;;
;;; Nothing blocks a frame: repl-poll! takes what input is there, through
;;; non-blocking sockets, and sends what output the kernel takes now. Each
;;; client is bounded (repl-max-input, repl-max-output, repl-timeout) and so
;;; is their number (repl-max-clients); a client past a bound, or whose
;;; socket fails, is closed, and the game goes on. Each complete expression
;;; is evaluated in the interaction environment (csi's toplevel, or a
;;; compiled program's globals), its output and value going back where it
;;; came from, then a "> " prompt; an error is printed there too.

(module (downstroke repl)
  (make-repl repl? repl-port repl-secret-file repl-poll! repl-close! repl-say!
   repl-max-clients repl-max-input repl-max-output repl-timeout
   repl-secret-directory repl-connect)

  (import scheme (chicken base) (chicken foreign) (chicken format) (chicken port)
          (chicken condition) (chicken string) (chicken io) (chicken time)
          (chicken fixnum) (chicken process-context) (chicken pathname)
          (chicken file) srfi-4)

  (foreign-declare "#include \"shell/repl.c\"")

  ;;; The limits, each a parameter read by make-repl (and a keyword of it).

  ;; what: the parameter or keyword, in the error's words
  (define (check-limit what v)
    (unless (and (exact-integer? v) (> v 0))
      (error (sprintf "~a ~s must be a positive integer" what v)))
    v)

  (define (positive-limit name)
    (lambda (v) (check-limit (sprintf "~a:" name) v)))

  ;; Connections open at once (the terminal aside); one more is closed at
  ;; once, unless one of them has not sent the secret (make-room!).
  (define repl-max-clients (make-parameter 8 (positive-limit 'repl-max-clients)))
  ;; Bytes of one expression still being received. CHICKEN's reader takes
  ;; about 0.4 s per MiB of list text, so this also bounds the frame that
  ;; reads the expression.
  (define repl-max-input (make-parameter 262144 (positive-limit 'repl-max-input)))
  ;; Bytes of output waiting for a client to read them.
  (define repl-max-output (make-parameter 4194304 (positive-limit 'repl-max-output)))
  ;; Milliseconds a connection has to send the secret, and that output may
  ;; wait unread before its client is dropped.
  (define repl-timeout (make-parameter 5000 (positive-limit 'repl-timeout)))

  ;; Bytes taken from one client in one poll, and read as Scheme in one poll
  ;; (at least one whole expression), so a paste or a flood is spread over
  ;; frames.
  (define chunk-size 65536)

  ;; Below this many bytes, unfinished text is read again at each line end.
  (define retry-size 16384)

  (define-foreign-variable repl-again int "REPL_AGAIN")
  (define-foreign-variable repl-dropped int "REPL_DROPPED")
  (define last-failure (foreign-lambda c-string "repl_last_failure"))
  (define c-listen (foreign-lambda int "repl_listen" int int))
  (define c-bound-port (foreign-lambda int "repl_bound_port" int))
  (define c-spare (foreign-lambda int "repl_spare"))
  (define c-accept (foreign-lambda int "repl_accept" int s32vector))
  (define c-recv (foreign-lambda int "repl_recv" int scheme-pointer int))
  (define c-send (foreign-lambda int "repl_send" int scheme-pointer int int))
  (define c-close (foreign-lambda void "repl_close" int))
  (define c-random (foreign-lambda int "repl_random" scheme-pointer int))
  (define c-make-dir (foreign-lambda int "repl_make_dir" c-string))
  (define c-private-dir (foreign-lambda int "repl_private_dir" c-string))
  (define c-write-secret (foreign-lambda int "repl_write_secret" int c-string c-string int))
  (define c-remove-secret (foreign-lambda void "repl_remove_secret" int c-string))
  (define c-connect (foreign-lambda int "repl_connect" int))
  (define c-send-all (foreign-lambda int "repl_send_all" int c-string int))
  (define c-relay (foreign-lambda int "repl_relay" int))

  ;;; The secret file.

  ;; Where the secret files are kept: $XDG_RUNTIME_DIR/downstroke (a
  ;; directory private to the user's session), else $HOME/.cache/downstroke.
  (define (repl-secret-directory)
    (let ((runtime (get-environment-variable "XDG_RUNTIME_DIR"))
          (home (get-environment-variable "HOME")))
      (cond ((and runtime (absolute-pathname? runtime)) (make-pathname runtime "downstroke"))
            ((and home (absolute-pathname? home)) (make-pathname (list home ".cache") "downstroke"))
            (else (error "repl: no place for the secret file: neither XDG_RUNTIME_DIR nor HOME is set")))))

  (define (secret-name port) (sprintf "repl-~a" port))

  (define (hex-secret)
    (let ((bytes (make-string 32)))
      (when (< (c-random bytes 32) 0) (error (sprintf "repl: ~a" (last-failure))))
      (apply string-append
             (map (lambda (ch)
                    (let ((h (number->string (char->integer ch) 16)))
                      (if (= (string-length h) 1) (string-append "0" h) h)))
                  (string->list bytes)))))

  ;; A descriptor of dir, made if missing, after checking it is this
  ;; user's alone. The default directory's parent ($HOME/.cache) is made
  ;; too when missing.
  (define (private-directory dir)
    (let ((parent (pathname-directory dir)))
      (when (and parent (not (directory-exists? parent)))
        (c-make-dir parent)))
    (when (< (c-make-dir dir) 0)
      (error (sprintf "repl: the secret's directory ~a: ~a" dir (last-failure))))
    (let ((fd (c-private-dir dir)))
      (when (< fd 0)
        (error (sprintf "repl: the secret's directory ~a: ~a" dir (last-failure))))
      fd))

  ;;; The REPL and its clients.

  (define-record-type repl
    (%make-repl listener spare dir-fd secret-file secret clients
                max-clients max-input max-output timeout buffer quiet-until unsaid)
    repl?
    (listener repl-listener)
    (spare repl-spare)                  ; s32vector: the spare descriptor
    (dir-fd repl-dir-fd)
    (secret-file repl-secret-file)      ; #f without a port
    (secret repl-secret)
    (clients repl-clients repl-clients-set!)
    (max-clients repl-max-clients-of)
    (max-input repl-max-input-of)
    (max-output repl-max-output-of)
    (timeout repl-timeout-of)
    (buffer repl-buffer)
    (quiet-until repl-quiet-until repl-quiet-until-set!)
    (unsaid repl-unsaid repl-unsaid-set!))

  ;; fd: the socket, or #f for the terminal (in and out are its ports).
  ;; state: proving (no secret yet), open, or closing (its input has
  ;; ended; it goes when its output is sent). text: received, not yet read
  ;; as Scheme. Output waits in head (from head-start), then in tail (a
  ;; string port), out-bytes in all; it is sent when polled, and while an
  ;; evaluation writes, each time out-bytes reaches flush-at. drop: why it
  ;; must go, or #f.
  (define-record-type client
    (%make-client fd in out state deadline text scan try? skipping?
                  head head-start tail out-bytes flush-at waiting-since drop raised? port)
    client?
    (fd client-fd) (in client-in) (out client-out)
    (state client-state client-state-set!)
    (deadline client-deadline)
    (text client-text client-text-set!)
    (scan client-scan)
    (try? client-try? client-try?-set!)
    (skipping? client-skipping? client-skipping?-set!)
    (head client-head client-head-set!)
    (head-start client-head-start client-head-start-set!)
    (tail client-tail client-tail-set!)
    (out-bytes client-out-bytes client-out-bytes-set!)
    (flush-at client-flush-at client-flush-at-set!)
    (waiting-since client-waiting-since client-waiting-since-set!)
    (drop client-drop client-drop-set!)
    (raised? client-raised? client-raised?-set!)
    (port client-port client-port-set!))

  (define (make-client fd in out state deadline)
    (%make-client fd in out state deadline "" (make-scan) #f #f "" 0 (open-output-string) 0 chunk-size 0 #f #f #f))

  ;; port: a TCP port number (0: any free one, see repl-port), or #f;
  ;; stdin?: serve standard input too (the terminal needs no secret).
  (define (make-repl #!key (port #f) (stdin? #f)
                     (max-clients (repl-max-clients)) (max-input (repl-max-input))
                     (max-output (repl-max-output)) (timeout (repl-timeout))
                     (secret-directory #f))
    (unless (or (not port) (and (exact-integer? port) (<= 0 port 65535)))
      (error (sprintf "repl: the port ~s must be an integer from 0 to 65535, or #f" port)))
    (check-limit "make-repl: max-clients:" max-clients)
    (check-limit "make-repl: max-input:" max-input)
    (check-limit "make-repl: max-output:" max-output)
    (check-limit "make-repl: timeout:" timeout)
    (unless (or (not secret-directory) (string? secret-directory))
      (error (sprintf "make-repl: secret-directory: ~s must be a directory name or #f" secret-directory)))
    (let-values (((listener spare dir-fd file secret)
                  (if port (listen-with-secret port (or secret-directory (repl-secret-directory)))
                      (values #f #f -1 #f #f))))
      (let ((r (%make-repl listener spare dir-fd file secret '()
                           max-clients max-input max-output timeout
                           (make-string chunk-size) 0 0)))
        (when stdin?
          (let ((c (make-client #f (current-input-port) (current-output-port) 'open #f)))
            (repl-clients-set! r (list c))
            (prompt! r c)))
        r)))

  ;; The listening socket, then the secret written beside its port number;
  ;; nothing is left open if a step fails.
  (define (listen-with-secret port dir)
    (let ((fd (c-listen port 64)))
      (when (< fd 0) (error (sprintf "repl: ~a port ~a" (last-failure) port)))
      (let ((dir-fd -1))
        (handle-exceptions e
            (begin (c-close fd) (when (>= dir-fd 0) (c-close dir-fd)) (abort e))
          (let* ((bound (c-bound-port fd))
                 (secret (hex-secret))
                 (name (secret-name bound))
                 (line (string-append secret "\n")))
            (when (< bound 0) (error (sprintf "repl: ~a" (last-failure))))
            (set! dir-fd (private-directory dir))
            (when (< (c-write-secret dir-fd name line (string-length line)) 0)
              (error (sprintf "repl: ~a ~a" (last-failure) (make-pathname dir name))))
            (values fd (s32vector (c-spare)) dir-fd (make-pathname dir name) secret))))))

  ;; The TCP port it listens on, or #f.
  (define (repl-port r)
    (and (repl-listener r) (c-bound-port (repl-listener r))))

  (define (repl-close! r)
    (for-each (lambda (c) (when (client-fd c) (flush! c) (c-close (client-fd c))))
              (repl-clients r))
    (repl-clients-set! r '())
    (when (repl-listener r)
      (c-close (repl-listener r))
      (c-close (s32vector-ref (repl-spare r) 0))
      (c-remove-secret (repl-dir-fd r) (pathname-strip-directory (repl-secret-file r)))
      (s32vector-set! (repl-spare r) 0 -1)))

  ;;; A line on the game's standard error for each connection refused or
  ;;; dropped, at most one a second (the rest are counted in the next).

  (define (tell-owner! r text)
    (let ((now (current-process-milliseconds)))
      (if (< now (repl-quiet-until r))
          (repl-unsaid-set! r (+ (repl-unsaid r) 1))
          (let ((p (current-error-port)))
            (display "downstroke repl: " p)
            (display text p)
            (unless (= (repl-unsaid r) 0)
              (display (sprintf " (and ~a more not shown)" (repl-unsaid r)) p))
            (newline p)
            (repl-unsaid-set! r 0)
            (repl-quiet-until-set! r (+ now 1000))))))

  ;;; Output: a socket client's waits in its queue and goes as the kernel
  ;;; takes it; the terminal's is written at once.

  (define (emit! r c text)
    (cond ((not (client-fd c)) (display text (client-out c)))
          ((client-drop c) (void))
          (else
           (let ((n (string-length text)))
             (when (= (client-out-bytes c) 0) (client-waiting-since-set! c (current-process-milliseconds)))
             (display text (client-tail c))
             (client-out-bytes-set! c (+ (client-out-bytes c) n))
             (cond ((> (client-out-bytes c) (repl-max-output-of r))
                    (discard-output! c)
                    (client-drop-set! c (sprintf "dropped a client: more than ~a bytes of output were waiting for it (repl-max-output)"
                                                 (repl-max-output-of r))))
                   ;; a long answer goes out as it is written, a chunk at a time
                   ((>= (client-out-bytes c) (client-flush-at c)) (flush! c)))))))

  (define (discard-output! c)
    (client-head-set! c "") (client-head-start-set! c 0) (client-tail-set! c (open-output-string))
    (client-out-bytes-set! c 0))

  ;; Sends what the kernel takes now.
  (define (flush! c)
    (flush-some! c)
    (client-flush-at-set! c (+ (client-out-bytes c) chunk-size)))

  (define (flush-some! c)
    (let loop ()
      (when (and (> (client-out-bytes c) 0) (not (client-drop c)))
        (when (= (client-head-start c) (string-length (client-head c)))
          (client-head-set! c (get-output-string (client-tail c)))
          (client-head-start-set! c 0)
          (client-tail-set! c (open-output-string)))
        (let* ((head (client-head c))
               (start (client-head-start c))
               (n (c-send (client-fd c) head start (- (string-length head) start))))
          (cond ((> n 0)
                 (client-head-start-set! c (+ start n))
                 (client-out-bytes-set! c (- (client-out-bytes c) n))
                 (client-waiting-since-set! c (current-process-milliseconds))
                 (loop))
                ((= n repl-again) (void))
                (else (discard-output! c)
                      (client-drop-set! c (sprintf "closed a client: ~a" (last-failure)))))))))

  (define (prompt! r c)
    (emit! r c "> ")
    (unless (client-fd c) (flush-output (client-out c))))

  ;; The port an evaluation writes to. CHICKEN's write hands it a
  ;; character at a time, so those gather in a buffer of the port's own.
  ;; Past repl-max-output it raises an error once, which ends an
  ;; evaluation that would print forever (a circular list); the client is
  ;; then dropped.
  (define (output-port r c)
    (or (client-port c)
        (let ((p (if (client-fd c) (socket-output-port r c) (client-out c))))
          (client-port-set! c p)
          p)))

  (define (socket-output-port r c)
    (let* ((size 4096) (buffer (make-string size)) (used 0))
      (define (pass! text)
        (unless (= used 0)
          (emit! r c (substring buffer 0 used))
          (set! used 0))
        (unless (string=? text "") (emit! r c text))
        (when (and (client-drop c) (not (client-raised? c)))
          (client-raised?-set! c #t)
          (error "repl: the output is more than repl-max-output bytes; the client is dropped")))
      (make-output-port
       (lambda (text)
         (let ((n (string-length text)))
           (if (fx< (fx+ used n) size)
               (let copy ((i 0))
                 (if (fx< i n)
                     (begin (string-set! buffer (fx+ used i) (string-ref text i)) (copy (fx+ i 1)))
                     (set! used (fx+ used n))))
               (pass! text))))
       void
       (lambda () (pass! "")))))

  ;; A message to every client past its secret (the game shell says a hook
  ;; failed).
  (define (repl-say! r text)
    (for-each (lambda (c)
                (when (eq? (client-state c) 'open)
                  (emit! r c text)
                  (emit! r c "\n")
                  (prompt! r c)))
              (repl-clients r)))

  ;;; Each poll: serve each client once, then accept who is waiting.

  ;; Serving first closes the clients that have gone, so their
  ;; descriptors are free for the connections accepted next.
  (define (repl-poll! r)
    (let ((now (current-process-milliseconds)))
      (repl-clients-set! r (let loop ((cs (repl-clients r)))
                             (cond ((null? cs) '())
                                   ((serve! r (car cs) now) (cons (car cs) (loop (cdr cs))))
                                   (else (loop (cdr cs)))))))
    (when (repl-listener r) (accept-waiting! r)))

  (define (socket-count r)
    (let loop ((cs (repl-clients r)) (n 0))
      (cond ((null? cs) n)
            ((client-fd (car cs)) (loop (cdr cs) (+ n 1)))
            (else (loop (cdr cs) n)))))

  (define (accept-waiting! r)
    (let loop ((k 0))
      (when (< k 64)
        (let ((fd (c-accept (repl-listener r) (repl-spare r))))
          (cond ((>= fd 0)
                 (if (and (>= (socket-count r) (repl-max-clients-of r))
                          (not (make-room! r)))
                     (begin (c-close fd)
                            (tell-owner! r (sprintf "refused a connection: ~a are open (repl-max-clients)"
                                                    (repl-max-clients-of r))))
                     (repl-clients-set! r (append (repl-clients r)
                                                  (list (make-client fd #f #f 'proving
                                                                     (+ (current-process-milliseconds) (repl-timeout-of r)))))))
                 (loop (+ k 1)))
                ((= fd repl-again) (void))
                ((= fd repl-dropped) (tell-owner! r (last-failure)) (loop (+ k 1)))
                (else (tell-owner! r (last-failure))))))))

  ;; With every connection taken, the oldest one that has still not sent
  ;; the secret gives its place to the new one, so connections that never
  ;; prove themselves (anyone on the machine can open them) cannot keep the
  ;; owner out. Each is first given its chance: a secret already received
  ;; opens it, and it stays. #t when a place was freed.
  (define (make-room! r)
    (let ((now (current-process-milliseconds)))
      (let loop ((cs (repl-clients r)))
        (cond ((null? cs) #f)
              ((and (client-fd (car cs)) (eq? (client-state (car cs)) 'proving))
               (let ((c (car cs)))
                 (prove! r c now)
                 (if (eq? (client-state c) 'open)
                     (loop (cdr cs))
                     (begin
                       (close-client! r c (or (client-drop c)
                                              "dropped a connection that had not sent the secret, to make room for a new one (repl-max-clients)"))
                       (repl-clients-set! r (remove-client (repl-clients r) c))
                       #t))))
              (else (loop (cdr cs)))))))

  ;; A client closed, and the owner told why.
  (define (close-client! r c why)
    (when (client-fd c) (c-close (client-fd c)))
    (tell-owner! r why))

  (define (remove-client cs c)
    (cond ((null? cs) '())
          ((eq? (car cs) c) (cdr cs))
          (else (cons (car cs) (remove-client (cdr cs) c)))))

  ;; #t to keep the client.
  (define (serve! r c now)
    (when (eq? (client-state c) 'proving) (prove! r c now))
    (when (memq (client-state c) '(open closing)) (take-input! r c))
    (when (client-fd c) (flush! c))
    (cond ((client-drop c) => (lambda (why) (close-client! r c why) #f))
          ((and (not (client-fd c)) (eq? (client-state c) 'closing)) #f)
          ((and (eq? (client-state c) 'closing) (= (client-out-bytes c) 0))
           (c-close (client-fd c))
           #f)
          ((and (> (client-out-bytes c) 0)
                (> (- now (client-waiting-since c)) (repl-timeout-of r)))
           (c-close (client-fd c))
           (tell-owner! r (sprintf "dropped a client: it read none of its output for ~a ms (repl-timeout)"
                                   (repl-timeout-of r)))
           #f)
          (else #t)))

  ;;; Before the secret: the first line must be the secret, sent within
  ;;; repl-timeout; nothing else is looked at.

  (define (prove! r c now)
    (let* ((buf (repl-buffer r))
           (room (+ (string-length (repl-secret r)) 2))
           ;; no more than the secret's line can hold: the rest waits in
           ;; the kernel until the client has proved itself
           (n (c-recv (client-fd c) buf (- (+ room 1) (string-length (client-text c))))))
      (cond ((> n 0) (client-text-set! c (string-append (client-text c) (substring buf 0 n))))
            ((= n 0) (client-drop-set! c "refused a connection: it closed before sending the secret"))
            ((= n repl-again) (void))
            (else (client-drop-set! c (sprintf "refused a connection: ~a" (last-failure)))))
      (unless (client-drop c)
        (let* ((text (client-text c))
               (end (substring-index "\n" text)))
          (cond ((and end (<= end room))
                 (if (same-secret? (if (and (> end 0) (char=? (string-ref text (- end 1)) #\return))
                                       (substring text 0 (- end 1))
                                       (substring text 0 end))
                                   (repl-secret r))
                     (begin
                       (client-state-set! c 'open)
                       (client-text-set! c "")
                       (emit! r c "downstroke repl: expressions are evaluated between frames\n")
                       (prompt! r c)
                       (add-text! c (substring text (+ end 1))))
                     (client-drop-set! c "refused a connection: its first line was not the secret")))
                ((>= (string-length text) room)
                 (client-drop-set! c "refused a connection: its first line was not the secret"))
                ((> now (client-deadline c))
                 (client-drop-set! c (sprintf "refused a connection: it sent no secret within ~a ms (repl-timeout)"
                                              (repl-timeout-of r)))))))))

  ;; In constant time for a line of the secret's length.
  (define (same-secret? line secret)
    (let ((n (string-length secret)) (m (string-length line)))
      (let loop ((i 0) (diff (if (= m n) 0 1)))
        (if (= i n)
            (= diff 0)
            (loop (+ i 1)
                  (fxior diff (fxxor (char->integer (string-ref secret i))
                                     (if (< i m) (char->integer (string-ref line i)) 0))))))))

  ;;; Past the secret: text in, expressions out.

  (define (take-input! r c)
    (let ((final? (eq? (client-state c) 'closing)))
      (unless final?
        (if (client-fd c)
            (let* ((buf (repl-buffer r))
                   (n (c-recv (client-fd c) buf chunk-size)))
              (cond ((> n 0) (add-text! c (substring buf 0 n)))
                    ((= n 0) (set! final? #t))
                    ((= n repl-again) (void))
                    (else (client-drop-set! c (sprintf "closed a client: ~a" (last-failure))))))
            (let ((got (read-terminal (client-in c))))
              (if (eof-object? got) (set! final? #t) (add-text! c got)))))
      (unless (client-drop c)
        (when final? (client-state-set! c 'closing))
        (evaluate-text! r c final?)
        (when (> (string-length (client-text c)) (repl-max-input-of r))
          (emit! r c (sprintf "\nrepl: an expression longer than ~a bytes (repl-max-input); closing\n"
                              (repl-max-input-of r)))
          (when (client-fd c) (flush! c))
          (client-drop-set! c (sprintf "dropped a client: it sent an expression longer than ~a bytes (repl-max-input)"
                                       (repl-max-input-of r)))))))

  ;; What the terminal has ready, at most a chunk; #!eof at its end.
  (define (read-terminal in)
    (let loop ((got '()) (n 0))
      (if (and (< n chunk-size) (char-ready? in))
          (let ((ch (read-char in)))
            (if (eof-object? ch)
                (if (null? got) ch (reverse-list->string got))
                (loop (cons ch got) (+ n 1))))
          (reverse-list->string got))))

  ;; After text the reader could not read, the rest of that expression
  ;; is skipped as it arrives, so no part of it is evaluated on its own.
  (define (add-text! c text)
    (let ((s (client-scan c)))
      (if (client-skipping? c)
          (let ((at (scan-until-top! s text)))
            (when at
              (client-skipping?-set! c #f)
              (add-text! c (substring text at))))
          (begin
            (when (or (scan! s text)
                      ;; the reader may find an error the scanner does not
                      ;; see (a bad character in a blob, say): a short text
                      ;; is tried at each line end, so that it is reported
                      (and (< (string-length (client-text c)) retry-size)
                           (substring-index "\n" text)))
              (client-try?-set! c #t))
            (client-text-set! c (string-append (client-text c) text))))))

  ;; Reads and evaluates each complete expression of the text, up to a
  ;; chunk of it per poll; final?: the client's input has ended.
  (define (evaluate-text! r c final?)
    (when (or (client-try? c) final?)
      (client-try?-set! c #f)
      (let ((text (client-text c)))
        (let loop ((start 0))
          (define (keep!) (client-text-set! c (if (= start 0) text (substring text start))))
          (cond ((client-drop c) (client-text-set! c ""))
                ((and (not final?) (>= start chunk-size))
                 (client-try?-set! c #t)
                 (keep!))
                (else
                 (let-values (((kind datum end warnings) (read-datum text start final?)))
                   (case kind
                     ((datum)
                      (unless (string=? warnings "") (emit! r c warnings))
                      (evaluate! r c datum)
                      (loop end))
                     ((error)
                      (client-text-set! c "")
                      (client-skipping?-set! c (not (scan-at-top? (client-scan c))))
                      (say-error! r c datum))
                     (else (keep!))))))))))

  ;; One datum of text from start, by CHICKEN's reader, which decides
  ;; what is complete: a datum whose reading looked past the end of the
  ;; text may go on in text not received yet (a symbol, an unfinished list)
  ;; and waits, unless the input has ended. Returns (values kind datum end
  ;; warnings), kind being datum, more, or error (datum: the condition).
  (define (read-datum text start final?)
    (let* ((n (string-length text)) (i start) (past-end? #f)
           (port (make-input-port
                  (lambda ()
                    (if (fx< i n)
                        (let ((ch (string-ref text i))) (set! i (fx+ i 1)) ch)
                        (begin (set! past-end? #t) #!eof)))
                  (lambda () #t)
                  void
                  (lambda ()
                    (if (fx< i n) (string-ref text i) (begin (set! past-end? #t) #!eof)))))
           (warnings (open-output-string)))
      (condition-case
          (let ((d (parameterize ((current-error-port warnings)) (read port))))
            (cond ((and past-end? (or (not final?) (eof-object? d))) (values 'more #f i ""))
                  (else (values 'datum d i (get-output-string warnings)))))
        (e () (if (and past-end? (not final?))
                  (values 'more #f i "")
                  (values 'error e i ""))))))

  (define (say-error! r c e)
    (let ((out (output-port r c)))
      (print-error-message e out)
      (flush-output out)
      (prompt! r c)))

  (define (evaluate! r c datum)
    (let ((out (output-port r c)))
      (condition-case
          (let ((results (call-with-values
                          (lambda ()
                            (with-output-to-port out
                              (lambda () (with-input-from-string "" (lambda () (eval datum))))))
                          list)))
            (for-each (lambda (v)
                        (unless (eq? v (void)) (write v out) (newline out)))
                      results))
        (e () (print-error-message e out)))
      (condition-case (flush-output out) (e () (void)))
      (prompt! r c)))

  ;;; Where an expression may end. The scanner follows CHICKEN's lexical
  ;;; syntax just far enough to know the list depth: through strings,
  ;;; |symbols|, characters, comments (; #| |# #!), here-strings (#<<TAG
  ;;; #<#TAG) and blobs (#${...}). It tells when a top-level datum may
  ;;; have ended, so the reader runs once per arrival of such a point
  ;;; rather than over the whole text on every poll; what is complete is
  ;;; still the reader's decision. The state: #(mode depth aux aux2).

  (define (make-scan) (vector 'top 0 #f #f))

  (define (scan-at-top? s)
    (and (eq? (vector-ref s 0) 'top) (= (vector-ref s 1) 0)))

  ;; Feeds text; #t when a top-level datum may have ended in it.
  (define (scan! s text)
    (let ((n (string-length text)))
      (let loop ((i 0) (may-end? #f))
        (if (fx= i n)
            may-end?
            (loop (fx+ i 1) (or (scan-char! s (string-ref text i)) may-end?))))))

  ;; Feeds text up to the first point back at the top level: the index
  ;; after it, or #f when text ends first.
  (define (scan-until-top! s text)
    (let ((n (string-length text)))
      (let loop ((i 0))
        (cond ((fx= i n) #f)
              (else (scan-char! s (string-ref text i))
                    (if (scan-at-top? s) (fx+ i 1) (loop (fx+ i 1))))))))

  (define (ends-atom? ch)
    (or (char-whitespace? ch) (memv ch '(#\( #\) #\[ #\] #\{ #\} #\" #\; #\' #\,))))

  ;; #t when a top-level datum may end at this character.
  (define (scan-char! s ch)
    (let ((mode (vector-ref s 0)) (depth (vector-ref s 1)))
      (define (to! m) (vector-set! s 0 m))
      (define (at-top?) (fx= (vector-ref s 1) 0))
      (case mode
        ((top) (top-char! s ch))
        ((atom)
         (cond ((ends-atom? ch) (to! 'top) (or (top-char! s ch) (fx= depth 0)))
               ((char=? ch #\|) (to! 'pipe) #f)
               ((char=? ch #\\) (to! 'atom-escape) #f)
               (else #f)))
        ((atom-escape) (to! 'atom) #f)
        ((pipe) (cond ((char=? ch #\|) (to! 'atom)) ((char=? ch #\\) (to! 'pipe-escape))) #f)
        ((pipe-escape) (to! 'pipe) #f)
        ((string) (cond ((char=? ch #\") (to! 'top) (at-top?))
                        ((char=? ch #\\) (to! 'string-escape) #f)
                        (else #f)))
        ((string-escape) (to! 'string) #f)
        ((line-comment) (when (char=? ch #\newline) (to! 'top)) (and (char=? ch #\newline) (at-top?)))
        ((block) (cond ((char=? ch #\|) (to! 'block-bar)) ((char=? ch #\#) (to! 'block-hash))) #f)
        ((block-bar)
         (cond ((char=? ch #\#)
                (let ((nest (fx- (vector-ref s 2) 1)))
                  (vector-set! s 2 nest)
                  (if (fx= nest 0) (begin (to! 'top) (at-top?)) (begin (to! 'block) #f))))
               ((char=? ch #\|) #f)
               (else (to! 'block) #f)))
        ((block-hash)
         (cond ((char=? ch #\|) (vector-set! s 2 (fx+ (vector-ref s 2) 1)) (to! 'block))
               ((char=? ch #\#) (void))
               (else (to! 'block)))
         #f)
        ((hash)
         (case ch
           ((#\|) (vector-set! s 2 1) (to! 'block) #f)
           ((#\() (vector-set! s 1 (fx+ depth 1)) (to! 'top) #f)
           ((#\\) (to! 'char) #f)
           ((#\!) (to! 'hash-bang) #f)
           ((#\<) (to! 'hash-lt) #f)
           ((#\$) (to! 'hash-dollar) #f)
           ((#\; #\' #\` #\,) (to! 'top) #f)
           (else (to! 'atom) (scan-char! s ch))))
        ((char) (to! 'atom) #f)
        ((hash-bang)
         (cond ((char=? ch #\newline) (to! 'top) (at-top?))
               ((or (char-whitespace? ch) (char=? ch #\/)) (to! 'line-comment) #f)
               (else (to! 'atom) (scan-char! s ch))))
        ((hash-lt)
         (if (memv ch '(#\< #\#))
             (begin (vector-set! s 2 '()) (to! 'here-tag) #f)
             (begin (to! 'atom) (scan-char! s ch))))
        ((here-tag)
         (if (char=? ch #\newline)
             (begin (vector-set! s 2 (reverse-list->string (vector-ref s 2)))
                    (vector-set! s 3 0)
                    (to! 'here-body)
                    #f)
             (begin (vector-set! s 2 (cons ch (vector-ref s 2))) #f)))
        ((here-body)
         ;; aux: the tag; aux2: how much of it this line has matched, or #f
         (let ((tag (vector-ref s 2)) (matched (vector-ref s 3)))
           (cond ((char=? ch #\newline)
                  (if (and matched (fx= matched (string-length tag)))
                      (begin (to! 'top) (at-top?))
                      (begin (vector-set! s 3 0) #f)))
                 ((and matched (fx< matched (string-length tag))
                       (char=? ch (string-ref tag matched)))
                  (vector-set! s 3 (fx+ matched 1))
                  #f)
                 (else (vector-set! s 3 #f) #f))))
        ((hash-dollar)
         (if (char=? ch #\{) (begin (to! 'blob) #f) (begin (to! 'top) (top-char! s ch))))
        ((blob) (if (char=? ch #\}) (begin (to! 'top) (at-top?)) #f))
        (else (error "repl: unknown scanner state" mode)))))

  ;; A character between data.
  (define (top-char! s ch)
    (let ((depth (vector-ref s 1)))
      (define (to! m) (vector-set! s 0 m) #f)
      (case ch
        ((#\( #\[ #\{) (vector-set! s 1 (fx+ depth 1)) #f)
        ((#\) #\] #\}) (vector-set! s 1 (fxmax 0 (fx- depth 1))) (fx<= depth 1))
        ((#\") (to! 'string))
        ((#\;) (to! 'line-comment))
        ((#\|) (to! 'pipe))
        ((#\#) (to! 'hash))
        ((#\\) (to! 'atom-escape))
        ((#\' #\` #\,) (fx= depth 0))
        (else (if (char-whitespace? ch) (fx= depth 0) (to! 'atom))))))

  ;;; The client: this terminal to the game's REPL on port.

  ;; Sends the secret from secret-file (by default the one the game wrote
  ;; for port), then copies standard input to the game and the game's
  ;; answers to standard output until the game closes the connection.
  (define (repl-connect port #!optional secret-file)
    (unless (and (exact-integer? port) (<= 1 port 65535))
      (error (sprintf "repl-connect: the port ~s must be an integer from 1 to 65535" port)))
    (let* ((file (or secret-file (make-pathname (repl-secret-directory) (secret-name port))))
           (secret (and (file-exists? file) (with-input-from-file file read-line))))
      (unless (string? secret)
        (error (sprintf "repl-connect: no secret in ~a: is a game of this user serving a REPL on port ~a?"
                        file port)))
      (let ((fd (c-connect port)))
        (when (< fd 0) (error (sprintf "repl-connect: ~a port ~a" (last-failure) port)))
        (flush-output)
        (let* ((line (string-append secret "\n"))
               (status (if (< (c-send-all fd line (string-length line)) 0) -1 (c-relay fd))))
          (c-close fd)
          (when (< status 0) (error (sprintf "repl-connect: ~a" (last-failure)))))))))
