;;; (downstroke save): values written and read back in a directory,
;;; without SDL; corrupt, truncated, oversized and hostile files; an
;;; unwritable place; a process killed half way through a write; a full
;;; disk; two processes writing one name; planted links and FIFOs; names
;;; the system cannot take; huge numbers. Then the engine's game-save! /
;;; game-load in the directory SDL_GetPrefPath gives.

(import scheme (chicken base) (chicken string) (chicken file) (chicken io)
        (chicken process) (chicken read-syntax) (chicken process-context)
        (chicken file posix) (chicken pathname) (chicken format) (chicken process signal)
        (chicken process-context posix) (chicken keyword) (chicken sort)
        (downstroke test) (downstroke save) (downstroke engine))

(define sv-dir (create-temporary-directory))
(define (sv-file name) (string-append sv-dir "/" name))
(define (sv-put! name text) (with-output-to-file (sv-file name) (lambda () (display text))))
(define (sv-text name) (with-input-from-file (sv-file name) (lambda () (read-string #f))))
(define (sv-says? exn . parts) (every-substring? parts (error-text exn)))
(define (every-substring? parts text)
  (or (null? parts) (and (substring-index (car parts) text) (every-substring? (cdr parts) text))))
;; The temporary files of a name in the directory: NAME.scm.tmp...
(define (sv-temps name)
  (let ((prefix (string-append name ".scm.tmp")))
    (let loop ((l (directory sv-dir #t)) (out '()))
      (cond ((null? l) out)
            ((and (>= (string-length (car l)) (string-length prefix))
                  (string=? prefix (substring (car l) 0 (string-length prefix))))
             (loop (cdr l) (cons (car l) out)))
            (else (loop (cdr l) out))))))

(define sv-values
  (list 0 -17 (expt 3 90) 1/3 2.5 -0.0 +inf.0 #t #f #\a #\space #\x3bb #\( "" "a \"quoted\"\nline\t\\"
        "λ unicode" "\x00;\x07;\x1b;\x7f;\r|" (+ .1 .2) (/ 1. 3) -1/3 1e300 5e-324 -inf.0 #\x0 #\x7f #\|
        'sym '|with space| '|#hash| (string->symbol "ends:") '|1a| '+ '... '|a\|b| (string->symbol "")
        #:key (string->keyword "a b") '#() '(a . #(1))
        '(1 (2 (3 . 4)) #(5 "six" #(seven))) (list 'settings (cons 'volume 0.8) (cons 'keys '((space . jump))))))

(test-group "save: values read back as they were written"
  (for-each (lambda (v)
              (save-data-write! sv-dir 'v v)
              (test (sprintf "~s" v) v (save-data-read sv-dir 'v)))
            sv-values)
  (test "the file is NAME.scm in the directory, readable text" (sv-file "v.scm") (save-data-path sv-dir 'v))
  (save-data-write! sv-dir "high-score" 12500)
  (test "a string name; a second name beside the first" '(12500 #t)
        (list (save-data-read sv-dir "high-score") (save-data-exists? sv-dir 'v)))
  (test "the file is a comment and the value" ";; downstroke save data high-score\n12500\n"
        (sv-text "high-score.scm"))
  (save-data-write! sv-dir 'high-score 13000)
  (test "a write replaces the value, and leaves no temporary file" '(13000 ())
        (list (save-data-read sv-dir 'high-score) (sv-temps "high-score")))
  (save-data-delete! sv-dir 'high-score)
  (test "deleted" #f (save-data-exists? sv-dir 'high-score)))

(test-group "save: missing data"
  (test "a missing name gives the default" 'none (save-data-read sv-dir 'nothing 'none))
  (test "even a #f default" #f (save-data-read sv-dir 'nothing #f))
  (test-error "without a default, an error naming the name and the file"
              (lambda (e) (and (save-data-error? e) (sv-says? e "no save data \"nothing\"" "nothing.scm")))
              (save-data-read sv-dir 'nothing)))

(test-group "save: only data is written"
  (save-data-write! sv-dir 'keep '(1 2 3))
  (define-record-type thing (make-thing a) thing? (a thing-a))
  (test-error "a procedure: named, with the name"
              (lambda (e) (sv-says? e "cannot save \"keep\"" "a procedure"))
              (save-data-write! sv-dir 'keep (list 1 car)))
  (test-error "a record, named with its type"
              (lambda (e) (sv-says? e "cannot save \"keep\"" "a record" "thing"))
              (save-data-write! sv-dir 'keep (vector (make-thing 1))))
  (test-error "the end-of-file object" (lambda (e) (sv-says? e "end-of-file"))
              (save-data-write! sv-dir 'keep (list #!eof)))
  (test-error "a NaN (it would not read back equal)" (lambda (e) (sv-says? e "NaN"))
              (save-data-write! sv-dir 'keep (/ 0. 0.)))
  (test-error "a circular list stops at the object bound"
              (lambda (e) (sv-says? e "circular"))
              (let ((l (list 1 2 3))) (set-cdr! (cddr l) l) (save-data-write! sv-dir 'keep l)))
  (test-error "over the size bound"
              (lambda (e) (sv-says? e "over save-data-max-size (100)"))
              (parameterize ((save-data-max-size 100)) (save-data-write! sv-dir 'keep (make-string 200 #\a))))
  (test "after the refused writes the old value is still there" '(1 2 3) (save-data-read sv-dir 'keep))
  (test-error "a name that is a path is refused"
              (lambda (e) (sv-says? e "\"../x\"" "letters, digits"))
              (save-data-write! sv-dir "../x" 1))
  (test-error "an empty name" (lambda (e) (sv-says? e "1 to 64")) (save-data-write! sv-dir "" 1))
  (test-error "a number for a name" (lambda (e) (sv-says? e "symbol or a string")) (save-data-read sv-dir 7)))

(test-group "save: corrupt files are errors, or the default"
  (define (corrupt text . parts)
    (sv-put! "bad.scm" text)
    (test-error (sprintf "~s: an error naming the file and the fault" text)
                (lambda (e) (and (save-data-error? e) (every-substring? (cons "bad.scm" parts) (error-text e))))
                (save-data-read sv-dir 'bad))
    (test (sprintf "~s: the default when one is given" text) 'dflt (save-data-read sv-dir 'bad 'dflt)))
  (corrupt "(1 2 (3" "corrupt")                       ; truncated
  (corrupt "" "empty")
  (corrupt ";; downstroke save data bad\n" "no value")  ; only the header survived
  (corrupt "1 2" "more than one value")
  (corrupt "\"unterminated" "corrupt")
  (corrupt "#!eof" "#!")
  (corrupt "#${00ff}" "#$")
  (corrupt "#<<EOF\nx\nEOF\n" "#<")
  (corrupt "(a #.(b))" "#.")
  (corrupt "(a ,@#,(b))" "#,")
  (corrupt "(1 . 2 3)" "more than one item after a .")
  (corrupt "1.50" "\"1.50\" is not written as save data writes it")
  (corrupt (list->string (list (integer->char 0) #\( #\))) "corrupt")
  (let ((big (make-string 300 #\space)))
    (sv-put! "bad.scm" (string-append big "1"))
    (test-error "a file over the size bound is refused before it is read"
                (lambda (e) (sv-says? e "301 bytes, over save-data-max-size (100)"))
                (parameterize ((save-data-max-size 100)) (save-data-read sv-dir 'bad))))
  (create-directory (sv-file "dir.scm"))
  (test-error "a directory where the file should be" (lambda (e) (sv-says? e "is a directory"))
              (save-data-read sv-dir 'dir))
  (test "... or the default" 'dflt (save-data-read sv-dir 'dir 'dflt)))

(test-group "save: an error names the file however deep its directory"
  ;; a directory path of over 100 characters, as a temporary directory
  ;; inside a home or a CI checkout gives
  (let* ((deep (string-append sv-dir "/" (make-string 100 #\d)))
         (deeper (string-append deep "/" (make-string 200 #\e))))
    (for-each (lambda (d) (create-directory d #t)) (list deep deeper))
    (for-each (lambda (d)
                (with-output-to-file (string-append d "/broken.scm") (lambda () (display "(1 2")))
                (test-error (sprintf "a directory path of ~a characters: the file's own name is shown"
                                     (string-length d))
                            (lambda (e) (and (save-data-error? e) (sv-says? e "broken.scm" "corrupt")))
                            (save-data-read d 'broken)))
              (list deep deeper))
    (test-error "a path too long to show whole: its start, then its end"
                (lambda (e) (sv-says? e (substring sv-dir 0 (min 10 (string-length sv-dir))) "..." "eeee/broken.scm"))
                (save-data-read deeper 'broken))
    (delete-directory deep #t)))

(test-group "save: reading evaluates nothing"
  (let ((ran #f))
    (define-reader-ctor 'boom (lambda () (set! ran #t) 1))
    (sv-put! "evil.scm" "(score #,(boom))")
    (test-error "a #, constructor is refused" (lambda (e) (sv-says? e "the syntax #,"))
                (save-data-read sv-dir 'evil))
    (test "... and never ran" #f ran)
    (parameterize ((current-read-table (copy-read-table (current-read-table))))
      (set-read-syntax! #\~ (lambda (port) (set! ran #t) 'x))
      (sv-put! "tilde.scm" "(a ~ b)")
      (test "read syntax a game added later is not used: ~ is a plain symbol" '(a ~ b)
            (save-data-read sv-dir 'tilde)))
    (test "... and never ran" #f ran))
  (sv-put! "ok.scm" "; a comment\n(|a#b| #\\# \"#,(x)\" |#,y| #:k #(1) ; another\n #t #f)")
  (test "# inside strings, |symbols| and characters is data, as are comments"
        (list 'a#b #\# "#,(x)" '|#,y| #:k '#(1) #t #f)
        (save-data-read sv-dir 'ok)))

(test-group "save: an unwritable place"
  (sv-put! "plain-file" "x")
  (test-error "a directory that is a file: named"
              (lambda (e) (sv-says? e "cannot save \"n\"" "plain-file"))
              (save-data-write! (sv-file "plain-file") 'n 1))
  (test-error "a directory that does not exist: named"
              (lambda (e) (sv-says? e "no directory" "missing-dir"))
              (save-data-write! (sv-file "missing-dir") 'n 1))
  (create-directory (sv-file "taken.scm"))
  (test-error "the file's place taken by a directory: the rename fails, named"
              (lambda (e) (sv-says? e "cannot save \"taken\"" "renaming"))
              (save-data-write! sv-dir 'taken 1))
  (test "... and the temporary file is removed" '() (sv-temps "taken")))

;; A child process writes a new value and dies (emergency-exit, no
;; cleanup) when half of it is in the temporary file: the old value must
;; still read back, and the next write must succeed.
(test-group "save: a crash half way through a write"
  (save-data-write! sv-dir 'progress '(level 3 (coins 120)))
  (let ((pid (process-fork
              (lambda ()
                (parameterize ((save-data-write-hook
                                (lambda (stage path) (when (eq? stage 'partial) (emergency-exit 42)))))
                  (save-data-write! sv-dir 'progress '(level 4 (coins 250) "a longer value than before")))
                (emergency-exit 0)))))
    (receive (pid ok? status) (process-wait pid)
      (test "the child died in the write" 42 status)))
  (test "a half-written temporary file was left" 1 (length (sv-temps "progress")))
  (test-assert "... and it is not a whole value"
               (not (substring-index "a longer value than before\")" (sv-text (car (sv-temps "progress"))))))
  (test "the old value is intact" '(level 3 (coins 120)) (save-data-read sv-dir 'progress))
  (save-data-write! sv-dir 'progress '(level 4))
  (test "the next write replaces both (the dead writer's temporary file is removed)" '((level 4) ())
        (list (save-data-read sv-dir 'progress) (sv-temps "progress"))))

;; The module path of this process, absolute, for the programs started here.
(define sv-repository
  (string-intersperse
   (map (lambda (d) (if (absolute-pathname? d) d (normalize-pathname (make-pathname (current-directory) d))))
        (repository-path))
   ":"))

;; Runs a shell script; (values exit-code output).
(define (sv-shell script)
  (let* ((out (sv-file "shell-output"))
         (pid (process-run "sh" (list "-c" (sprintf "( ~a ) >~a 2>&1" script (qs out))))))
    (receive (pid normal? code) (process-wait pid)
      (values (if normal? code (- code)) (sv-text "shell-output")))))

;; A program that saves a string of n bytes under the name big and says
;; what happened: exit 0 "ok", 2 and the message of a save-data error, 3
;; and the message of any other error.
(with-output-to-file (sv-file "writer.scm")
  (lambda ()
    (write '(import scheme (chicken base) (chicken condition) (chicken process-context) (downstroke save)))
    (write '(let ((args (command-line-arguments)))
              (handle-exceptions e
                  (begin (display ((condition-property-accessor 'exn 'message "") e))
                         (exit (if (save-data-error? e) 2 3)))
                (save-data-write! (car args) 'big (make-string (string->number (cadr args)) #\z))
                (display "ok")
                (exit 0))))))

;; A full disk, seen as a file-size limit (ulimit -f, SIGXFSZ ignored so
;; that write returns EFBIG instead of the signal ending the process).
;; The new text is one and a half times the limit: its first half fits,
;; its second half is written only in part.
(test-group "save: a full disk (a file-size limit) is an error and the old value stays"
  (save-data-write! sv-dir 'big "the old value")
  ;; the shell's ulimit -f counts blocks of 512 or 1024 bytes: measured
  (let* ((block (receive (code out)
                    (sv-shell (sprintf "trap '' XFSZ; ulimit -f 2; head -c 8192 /dev/zero >~a"
                                       (qs (sv-file "probe"))))
                  (quotient (file-size (sv-file "probe")) 2)))
         (limit (* 16 block))
         (size (quotient (* 3 limit) 2)))
    (test-assert "the probe was cut at the limit" (memv block '(512 1024)))
    (receive (code out)
        (sv-shell (sprintf "trap '' XFSZ; ulimit -f 16; CHICKEN_REPOSITORY_PATH=~a exec csi -q -s ~a ~a ~a"
                           (qs sv-repository) (qs (sv-file "writer.scm")) (qs sv-dir) size))
      (test "the write is a save-data error" 2 code)
      (test-assert (sprintf "naming the file and the system's reason: ~a" out)
                   (every-substring? '("cannot save \"big\"" "big.scm.tmp" "File too large") out)))
    (test "the old value survives" "the old value" (save-data-read sv-dir 'big))
    (test "no temporary file is left" '() (sv-temps "big"))
    (receive (code out)
        (sv-shell (sprintf "trap '' XFSZ; ulimit -f 16; CHICKEN_REPOSITORY_PATH=~a exec csi -q -s ~a ~a ~a"
                           (qs sv-repository) (qs (sv-file "writer.scm")) (qs sv-dir) (quotient limit 2)))
      (test "a value that fits is written under the same limit" '(0 "ok") (list code out))
      (test "... and reads back" (quotient limit 2) (string-length (save-data-read sv-dir 'big))))))

;; A full file system: a small tmpfs, when this process may mount one
;; (root, and a kernel that lets it); elsewhere the group says so and
;; checks nothing.
(test-group "save: a full file system (a small tmpfs) is an error and the old value stays"
  (let ((mnt (sv-file "small-disk")))
    (create-directory mnt)
    (receive (code out) (sv-shell (sprintf "mount -t tmpfs -o size=64k tmpfs ~a" (qs mnt)))
      (if (not (= code 0))
          (print "    (not run: cannot mount a tmpfs here: " out ")")
          (dynamic-wind
           void
           (lambda ()
             (save-data-write! mnt 'game "the old value")
             ;; leave two pages free: the new text's first half fits, its second half not
             (with-output-to-file (make-pathname mnt "filler")
               (lambda () (display (make-string (* 13 4096) #\f))))
             (test-error "the write fails, naming the file and the reason"
                         (lambda (e) (and (save-data-error? e)
                                          (sv-says? e "cannot save \"game\"" "game.scm.tmp" "No space left on device")))
                         (save-data-write! mnt 'game (make-string (* 3 4096) #\n)))
             (test "the old value survives" "the old value" (save-data-read mnt 'game))
             (test "no temporary file is left" '("filler" "game.scm") (sort (directory mnt #t) string<?)))
           (lambda () (sv-shell (sprintf "umount ~a" (qs mnt)))))))))

;; Two processes save the same name many times while this one reads it:
;; every read gives one writer's whole value (or the one before them).
;; Each writer has its own temporary file, so no write of either fails;
;; a writer exits 0 when all its writes succeeded, 2 when some failed
;; with a save-data error giving a real reason, 3 at the first other
;; error (one whose reason is "Success", or not a save-data error).
(test-group "save: two processes writing one name never mix"
  (let* ((value-of (lambda (who) (list who (make-string 30000 (if (eq? who 'a) #\a #\b)))))
         (before '(nobody yet))
         (writer (lambda (who)
                   (process-fork
                    (lambda ()
                      ;; both start together: each says it is ready, then
                      ;; waits for this process to say go
                      (sv-put! (sprintf "ready-~a" who) "")
                      (let wait () (unless (file-exists? (sv-file "go")) (wait)))
                      (let loop ((i 0) (failed 0))
                        (if (= i 60)
                            (emergency-exit (if (= failed 0) 0 2))
                            (let ((outcome (handle-exceptions e
                                               (if (and (save-data-error? e)
                                                        (not (substring-index "Success" (error-text e))))
                                                   'clear-error
                                                   'bad)
                                             (save-data-write! sv-dir 'shared (value-of who))
                                             'ok)))
                              (if (eq? outcome 'bad)
                                  (emergency-exit 3)
                                  (loop (+ i 1) (if (eq? outcome 'ok) failed (+ failed 1))))))))))))
    (save-data-write! sv-dir 'shared before)
    (let* ((a (writer 'a)) (b (writer 'b))
           (reads 0) (wrong 0))
      (let wait () (unless (and (file-exists? (sv-file "ready-a")) (file-exists? (sv-file "ready-b"))) (wait)))
      (sv-put! "go" "")
      (let loop ((running (list a b)) (codes '()))
        (if (null? running)
            (begin
              (test-assert "no writer met an error without a real reason" (not (memv 3 codes)))
              (test "every write of both writers succeeded" '(0 0) codes)
              (test "every read while they ran gave a whole value" 0 wrong)
              (test-assert "... and this process did read while they ran" (> reads 0)))
            (let ((v (save-data-read sv-dir 'shared 'unreadable)))
              (set! reads (+ reads 1))
              (unless (member v (list before (value-of 'a) (value-of 'b))) (set! wrong (+ wrong 1)))
              (let check ((rs running) (still '()) (codes codes))
                (if (null? rs)
                    (loop still codes)
                    (receive (pid normal? code) (process-wait (car rs) #t)
                      (if (eqv? pid 0)
                          (check (cdr rs) (cons (car rs) still) codes)
                          (check (cdr rs) still (cons (if normal? code -1) codes))))))))))
    (test-assert "the last value is one writer's, whole"
                 (member (save-data-read sv-dir 'shared) (list (value-of 'a) (value-of 'b))))
    (test "no temporary file is left" '() (sv-temps "shared"))))

;; A symbolic link where a temporary file or the save file goes: the link
;; is never followed, its target never written or read.
(test-group "save: planted symbolic links are not followed"
  (let ((victim (sv-file "victim")))
    (sv-put! "victim" "(the victim's own data)")
    (save-data-write! sv-dir 'linked "old")
    ;; at the name an earlier version used for its temporary file
    (create-symbolic-link victim (sv-file "linked.scm.tmp"))
    (save-data-write! sv-dir 'linked "new")
    (test "a link at NAME.scm.tmp: the target is untouched" "(the victim's own data)" (sv-text "victim"))
    (test "... and the value is written" "new" (save-data-read sv-dir 'linked))
    (delete-file (sv-file "linked.scm.tmp"))
    ;; at the very temporary name the writer is about to create
    (let ((planted 0))
      (parameterize ((save-data-write-hook
                      (lambda (stage path)
                        (when (and (eq? stage 'create) (= planted 0))
                          (set! planted (+ planted 1))
                          (create-symbolic-link victim path)))))
        (save-data-write! sv-dir 'linked "newer"))
      (test "a link at the temporary name: planted once" 1 planted)
      (test "... the target is untouched" "(the victim's own data)" (sv-text "victim"))
      (test "... and the write went to a fresh name" "newer" (save-data-read sv-dir 'linked)))
    (test-error "a link at every temporary name tried: an error naming the file and the reason"
                (lambda (e) (and (save-data-error? e) (sv-says? e "cannot save \"linked\"" "cannot create" "File exists")))
                (parameterize ((save-data-write-hook
                                (lambda (stage path) (when (eq? stage 'create) (create-symbolic-link victim path)))))
                  (save-data-write! sv-dir 'linked "newest")))
    (test "... the target is untouched" "(the victim's own data)" (sv-text "victim"))
    (test "... and the old value stays" "newer" (save-data-read sv-dir 'linked))
    (for-each (lambda (f) (delete-file (sv-file f))) (sv-temps "linked"))
    ;; at the save name itself
    (create-symbolic-link victim (sv-file "elsewhere.scm"))
    (test "reading a link at the save name gives the default, not the target's data"
          'dflt (save-data-read sv-dir 'elsewhere 'dflt))
    (test-error "... and without a default an error saying so"
                (lambda (e) (and (save-data-error? e) (sv-says? e "elsewhere.scm" "symbolic link")))
                (save-data-read sv-dir 'elsewhere))
    (test "save-data-exists? does not count a link" #f (save-data-exists? sv-dir 'elsewhere))
    (save-data-write! sv-dir 'elsewhere 7)
    (test "writing replaces the link itself; the target is untouched" '(7 "(the victim's own data)")
          (list (save-data-read sv-dir 'elsewhere) (sv-text "victim")))))

;; Texts the writer never writes, each read as the save file: all are
;; refused (the default, or a save-data error), and nothing of them runs.
(test-group "save: the reader takes the writer's syntax only"
  (let ((ran #f))
    (define-reader-ctor 'boom (lambda () (set! ran #t) 1))
    (parameterize ((current-read-table (copy-read-table (current-read-table))))
     (set-sharp-read-syntax! #\@ (lambda (port) (set! ran #t) 'x))
     (for-each
     (lambda (text)
       (sv-put! "hostile.scm" text)
       (test (sprintf "~s: the default" text) 'dflt (save-data-read sv-dir 'hostile 'dflt))
       (test-error (sprintf "~s: without a default, a save-data error" text)
                   (lambda (e) (and (save-data-error? e) (sv-says? e "hostile.scm" "corrupt")))
                   (save-data-read sv-dir 'hostile)))
     (list "(\\\" #,(boom) \\\")" "(\\\" #e1e9 \\\")" "(\\\" #!eof \\\")" "(\\\" #.(boom) \\\")" "\\#,(boom)"
           "#,(boom)" "(a #.(boom))" "#!eof" "#e1e9" "#x10" "#b101" "#i1/3" "#@x" "'x" "`x" ",x"
           "#;1 2" "#|c|# 1" "#!default" "#u8(1)" "#${00ff}" "#<<EOF\nx\nEOF\n" "1#" "a#b" "k:" "|a|b"
           "\"\\q\"" "\"\\x41;\"" "\"a\nb\"" "#\\x41" "#\\ " "1.50" "+5" "-0" "007" "1e400" "+nan.0" "1+2i"
           "(1 . 2 3)" "#(1 . 2)" "(a . (b))" "(a . ())" "#true" "#t1" ")" "(" " . " "|abc|" "#:|k|"
           "(a(b))" "\"x\"y")))
    (test "none of them ran anything" #f ran)))

;; A FIFO where the save file goes: a writer process waits on it with a
;; value, and a reader that opened it would read that value; the reader
;; refuses it at once instead.
(test-group "save: a FIFO is refused without waiting"
  (let ((fifo (sv-file "pipe.scm")))
    (create-fifo fifo)
    (define (with-fifo-writer thunk)
      (let ((pid (process-fork (lambda ()
                                 (let ((fd (file-open fifo open/wronly)))
                                   (file-write fd "42\n")
                                   (file-close fd)
                                   (emergency-exit 0))))))
        (dynamic-wind void thunk (lambda () (process-signal pid signal/kill) (process-wait pid)))))
    (test "the default, not what the FIFO's writer sends" 'dflt
          (with-fifo-writer (lambda () (save-data-read sv-dir 'pipe 'dflt))))
    (test-error "without a default, an error naming the file"
                (lambda (e) (and (save-data-error? e) (sv-says? e "pipe.scm" "not a regular file")))
                (with-fifo-writer (lambda () (save-data-read sv-dir 'pipe))))
    (test "save-data-exists? does not count it" #f (save-data-exists? sv-dir 'pipe))))

;; Directory names the system cannot be given.
(test-group "save: directory names the system cannot take"
  (for-each
   (lambda (c)
     (let ((dir (cadr c)) (says (caddr c)))
       (test (sprintf "~a: reading gives the default" (car c)) 'dflt (save-data-read dir 'x 'dflt))
       (test-error (sprintf "~a: reading without a default, a save-data error" (car c))
                   (lambda (e) (and (save-data-error? e) (sv-says? e says)))
                   (save-data-read dir 'x))
       (test-error (sprintf "~a: writing, a save-data error" (car c))
                   (lambda (e) (and (save-data-error? e) (sv-says? e "cannot save \"x\"" says)))
                   (save-data-write! dir 'x 1))
       (test (sprintf "~a: nothing exists there" (car c)) #f (save-data-exists? dir 'x))
       (test-error (sprintf "~a: deleting, a save-data error" (car c))
                   (lambda (e) (and (save-data-error? e) (sv-says? e says)))
                   (save-data-delete! dir 'x))))
   (list (list "a NUL byte" (string-append sv-dir "/a" (string #\nul) "b") "NUL")
         (list "longer than PATH_MAX" (string-append sv-dir "/" (make-string 5000 #\d)) "PATH_MAX")))
  (test "a directory with a component too long for the file system: the default" 'dflt
        (save-data-read (string-append sv-dir "/" (make-string 300 #\d)) 'x 'dflt)))

;; Numbers: at most (save-data-max-digits) digits each, on both sides, so
;; one number's conversion costs a bounded time and reading is linear in
;; the file's size. A 2,000,000-digit number took 14 s to read before.
(test-group "save: digits per number are bounded"
  (save-data-write! sv-dir 'number 1)
  (test-error "the writer refuses a number over the bound, naming it"
              (lambda (e) (and (save-data-error? e) (sv-says? e "cannot save \"number\"" "save-data-max-digits")))
              (save-data-write! sv-dir 'number (expt 10 20000)))
  (test "... and the old value stays" 1 (save-data-read sv-dir 'number))
  (sv-put! "number.scm" (make-string 2000000 #\7))
  (parameterize ((save-data-max-size (* 3 1024 1024)))
    (test "a file of a 2,000,000-digit number: the default" 'dflt (save-data-read sv-dir 'number 'dflt))
    (test-error "... without one, an error naming the bound"
                (lambda (e) (and (save-data-error? e) (sv-says? e "number.scm" "2000000 digits" "save-data-max-digits")))
                (save-data-read sv-dir 'number)))
  (test "the default bound is 10,000 digits" 10000 (save-data-max-digits))
  (let ((at-bound (list (- (expt 10 10000) 1) (- 1 (expt 10 9999)) (/ 1 (expt 10 5000))
                        (- (expt 10 9999)))))
    (save-data-write! sv-dir 'number at-bound)
    (test "numbers of exactly the bound's digits are written and read back" at-bound
          (save-data-read sv-dir 'number)))
  (parameterize ((save-data-max-digits 5))
    (save-data-write! sv-dir 'number '(12345 -12345 1.5 12/345))
    (test "a smaller bound: numbers within it" '(12345 -12345 1.5 12/345) (save-data-read sv-dir 'number))
    (test-error "... a number of one digit more is refused by the writer"
                (lambda (e) (sv-says? e "6 digits, over save-data-max-digits (5)"))
                (save-data-write! sv-dir 'number 123456))
    (test-error "... a fraction's two parts together count"
                (lambda (e) (sv-says? e "6 digits, over save-data-max-digits (5)"))
                (save-data-write! sv-dir 'number 123/457))
    (sv-put! "number.scm" "(1 123456)")
    (test "... and by the reader" 'dflt (save-data-read sv-dir 'number 'dflt))))

;; The engine puts save data where SDL_GetPrefPath says: on Linux
;; $XDG_DATA_HOME/ORG/APP/.
(test-group "save: game-save! and game-load"
  (let ((old (get-environment-variable "XDG_DATA_HOME")))
    (set-environment-variable! "XDG_DATA_HOME" sv-dir)
    (let ((g (make-game title: "Sky Jump" org: "acme" app: "sky-jump")))
      (test "the directory is XDG_DATA_HOME/org/app/" (string-append sv-dir "/acme/sky-jump/")
            (game-save-directory g))
      (test "nothing saved yet: the default" 0 (game-load g 'best 0))
      (game-save! g 'best 4200)
      (test "saved and loaded" 4200 (game-load g 'best))
      (test-assert "the file is there" (file-exists? (string-append sv-dir "/acme/sky-jump/best.scm")))
      (test "app: defaults to the title" (string-append sv-dir "/downstroke/Sky Jump/")
            (game-save-directory (make-game title: "Sky Jump"))))
    (test "a title with a slash still makes a game (its app name without the slash)"
          (string-append sv-dir "/downstroke/AC-DC/")
          (game-save-directory (make-game title: "AC/DC")))
    (test-error "an org: with a slash is refused by make-game" (lambda (e) (sv-says? e "org:"))
                (make-game org: "a/b"))
    (if old (set-environment-variable! "XDG_DATA_HOME" old) (unset-environment-variable! "XDG_DATA_HOME"))))

(delete-directory sv-dir #t)
