;;; (downstroke save): values written and read back in a directory,
;;; without SDL; corrupt, truncated, oversized and hostile files; an
;;; unwritable place; a process killed half way through a write. Then the
;;; engine's game-save! / game-load in the directory SDL_GetPrefPath gives.

(import scheme (chicken base) (chicken string) (chicken file) (chicken io)
        (chicken process) (chicken read-syntax) (chicken process-context)
        (downstroke test) (downstroke save) (downstroke engine))

(define sv-dir (create-temporary-directory))
(define (sv-file name) (string-append sv-dir "/" name))
(define (sv-put! name text) (with-output-to-file (sv-file name) (lambda () (display text))))
(define (sv-text name) (with-input-from-file (sv-file name) (lambda () (read-string #f))))
(define (sv-says? exn . parts) (every-substring? parts (error-text exn)))
(define (every-substring? parts text)
  (or (null? parts) (and (substring-index (car parts) text) (every-substring? (cdr parts) text))))

(define sv-values
  (list 0 -17 (expt 3 90) 1/3 2.5 -0.0 +inf.0 #t #f #\a #\space #\x3bb #\( "" "a \"quoted\"\nline\t\\"
        "λ unicode" 'sym '|with space| '|#hash| (string->symbol "ends:") #:key '()
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
  (test "a write replaces the value, and leaves no temporary file" '(13000 #f)
        (list (save-data-read sv-dir 'high-score) (file-exists? (sv-file "high-score.scm.tmp"))))
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
  (corrupt (list->string (list (integer->char 0) #\( #\))) "corrupt")
  (let ((big (make-string 300 #\space)))
    (sv-put! "bad.scm" (string-append big "1"))
    (test-error "a file over the size bound is refused before it is read"
                (lambda (e) (sv-says? e "301 bytes, over save-data-max-size (100)"))
                (parameterize ((save-data-max-size 100)) (save-data-read sv-dir 'bad))))
  (create-directory (sv-file "dir.scm"))
  (test-error "a directory where the file should be" (lambda (e) (sv-says? e "is a directory"))
              (save-data-read sv-dir 'dir)))

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
  (sv-put! "ok.scm" "; a comment\n(a#b 1# #\\# \"#,(x)\" |#,y| #:k #(1) #t #f)")
  (test "# inside tokens, strings, |symbols| and characters is data"
        (list 'a#b 10. #\# "#,(x)" '|#,y| #:k '#(1) #t #f)
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
  (test "... and the temporary file is removed" #f (file-exists? (sv-file "taken.scm.tmp"))))

;; A child process writes a new value and dies (emergency-exit, no
;; cleanup) when half of it is in the temporary file: the old value must
;; still read back, and the next write must succeed.
(test-group "save: a crash half way through a write"
  (save-data-write! sv-dir 'progress '(level 3 (coins 120)))
  (let ((pid (process-fork
              (lambda ()
                (parameterize ((save-data-write-hook (lambda (stage path) (emergency-exit 42))))
                  (save-data-write! sv-dir 'progress '(level 4 (coins 250) "a longer value than before")))
                (emergency-exit 0)))))
    (receive (pid ok? status) (process-wait pid)
      (test "the child died in the write" 42 status)))
  (test-assert "a half-written temporary file was left" (file-exists? (sv-file "progress.scm.tmp")))
  (test-assert "... and it is not a whole value"
               (not (substring-index "a longer value than before\")" (sv-text "progress.scm.tmp"))))
  (test "the old value is intact" '(level 3 (coins 120)) (save-data-read sv-dir 'progress))
  (save-data-write! sv-dir 'progress '(level 4))
  (test "the next write replaces both" '((level 4) #f)
        (list (save-data-read sv-dir 'progress) (file-exists? (sv-file "progress.scm.tmp")))))

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
