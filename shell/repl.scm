;;; (downstroke repl): a read-eval-print loop that a running game serves
;;; between its frames, on standard input and/or a TCP port of the loopback
;;; address (127.0.0.1, so only this machine can reach it).
;;;
;;; Nothing blocks: repl-poll! takes what input is there, and evaluates
;;; each complete expression in the interaction environment (csi's
;;; toplevel, or a compiled program's globals), its output and its value
;;; going back where it came from, then a "> " prompt. An error in an
;;; expression is printed there too, and the loop goes on.

(module (downstroke repl)
  (make-repl repl? repl-port repl-poll! repl-close! repl-say!)

  (import scheme (chicken base) (chicken format) (chicken port) (chicken tcp)
          (chicken condition) (chicken string) (chicken io))

  ;; A client: its ports and the text read from it not yet evaluated.
  (define-record-type client
    (make-client in out buffer)
    client?
    (in client-in) (out client-out) (buffer client-buffer client-buffer-set!))

  (define-record-type repl
    (%make-repl listener clients)
    repl?
    (listener repl-listener)
    (clients repl-clients repl-clients-set!))

  ;; port: a TCP port number (0: any free one, see repl-port), or #f;
  ;; stdin?: serve standard input too.
  (define (make-repl #!key (port #f) (stdin? #f))
    (unless (or (not port) (and (exact-integer? port) (<= 0 port 65535)))
      (error (sprintf "repl: the port ~s must be an integer from 0 to 65535, or #f" port)))
    (let ((r (%make-repl (and port (tcp-listen port 4 "127.0.0.1")) '())))
      (when stdin?
        (let ((c (make-client (current-input-port) (current-output-port) "")))
          (repl-clients-set! r (list c))
          (prompt c)))
      r))

  ;; The TCP port it listens on, or #f.
  (define (repl-port r)
    (and (repl-listener r) (tcp-listener-port (repl-listener r))))

  (define (prompt c)
    (display "> " (client-out c))
    (flush-output (client-out c)))

  ;; A message to every client (the game shell says a hook failed).
  (define (repl-say! r text)
    (for-each (lambda (c)
                (display text (client-out c))
                (newline (client-out c))
                (prompt c))
              (repl-clients r)))

  ;; Accepts who is waiting, reads what each client sent, evaluates every
  ;; complete expression. Never waits.
  (define (repl-poll! r)
    (let ((l (repl-listener r)))
      (when (and l (tcp-accept-ready? l))
        (let-values (((in out) (tcp-accept l)))
          (let ((c (make-client in out "")))
            (repl-clients-set! r (append (repl-clients r) (list c)))
            (display "downstroke repl: expressions are evaluated between frames\n" out)
            (prompt c)))))
    (repl-clients-set! r (let loop ((cs (repl-clients r)) (out '()))
                           (cond ((null? cs) (reverse out))
                                 ((serve! (car cs)) (loop (cdr cs) (cons (car cs) out)))
                                 (else (loop (cdr cs) out))))))

  ;; Reads the characters there are; #f when the client has gone.
  (define (serve! c)
    (let loop ((got '()))
      (if (char-ready? (client-in c))
          (let ((ch (read-char (client-in c))))
            (if (eof-object? ch)
                (begin (take! c got) (evaluate-all! c) (hang-up! c) #f)
                (loop (cons ch got))))
          (begin (take! c got) (evaluate-all! c) #t))))

  (define (take! c chars)
    (unless (null? chars)
      (client-buffer-set! c (string-append (client-buffer c) (reverse-list->string chars)))))

  (define (hang-up! c)
    (unless (eq? (client-in c) (current-input-port))
      (close-input-port (client-in c))
      (close-output-port (client-out c))))

  ;; Each complete expression of the buffer, in order; an incomplete one
  ;; stays for the next poll.
  (define (evaluate-all! c)
    (let loop ()
      (let ((next (read-one (client-buffer c))))
        (case (car next)
          ((datum)
           (client-buffer-set! c (caddr next))
           (evaluate! c (cadr next))
           (loop))
          ((bad)
           (client-buffer-set! c "")
           (say-error! c (cadr next)))
          (else (void))))))

  ;; (datum d rest), (none) when the text holds no complete expression
  ;; yet, or (bad condition) for text that cannot be read.
  (define (read-one text)
    (if (blank? text)
        '(none)
        (condition-case
            (call-with-input-string text
              (lambda (port)
                (let ((d (read port)))
                  (if (eof-object? d)
                      '(none)
                      (let ((rest (read-string #f port)))   ; #!eof when nothing is left
                        (list 'datum d (if (string? rest) rest "")))))))
          (e (exn syntax)
             (if (substring-index "end of file" ((condition-property-accessor 'exn 'message "") e))
                 '(none)
                 (list 'bad e))))))

  (define (blank? text)
    (let loop ((i 0))
      (or (= i (string-length text))
          (and (char-whitespace? (string-ref text i)) (loop (+ i 1))))))

  (define (say-error! c e)
    (let ((out (client-out c)))
      (print-error-message e out)
      (prompt c)))

  (define (evaluate! c datum)
    (let ((out (client-out c)))
      (condition-case
          (let ((results (call-with-values
                          (lambda () (with-output-to-port out (lambda () (eval datum))))
                          list)))
            (for-each (lambda (v)
                        (unless (eq? v (void)) (write v out) (newline out)))
                      results)
            (prompt c))
        (e () (say-error! c e)))))

  (define (repl-close! r)
    (for-each hang-up! (repl-clients r))
    (repl-clients-set! r '())
    (when (repl-listener r) (tcp-close (repl-listener r)))))
