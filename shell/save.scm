;;; (downstroke save): a small Scheme value (settings, a high score, the
;;; key bindings) kept in a file under a name, in a given directory.
;;;
;;; (save-data-write! dir name value) stores value as dir/NAME.scm;
;;; (save-data-read dir name [default]) reads it back. NAME is a symbol or
;;; a string of letters, digits, - and _ (at most 64), so a name is never a
;;; path. The engine's game-save! and game-load put the directory where
;;; SDL keeps an application's per-user files (SDL_GetPrefPath); this
;;; module itself knows nothing of SDL.
;;;
;;; Only readable data is stored: booleans, numbers (not NaN), characters,
;;; strings, symbols, keywords, the empty list, pairs and vectors of those,
;;; at most save-data-max-size bytes written and save-data-max-nodes
;;; objects (which also stops a circular list). Anything else (a
;;; procedure, a record, a hash table, eof ...) is an error naming the
;;; name and the kind of the value found.
;;;
;;; Writing never leaves a half-written file: the text goes to NAME.scm.tmp
;;; in the same directory, is flushed to the disk (fsync) and closed, and
;;; only then renamed over NAME.scm (rename is atomic), after which the
;;; directory is synced too. A crash at any point leaves the old value or
;;; the new one, never a mixture (and perhaps a stale NAME.scm.tmp, which
;;; the next write replaces). One writer of a name at a time: two processes
;;; saving the same name at once share the temporary file.
;;;
;;; Reading never evaluates anything: the file (at most save-data-max-size
;;; bytes, else it is refused before it is read) is first scanned so that
;;; the only `#` syntax in it is #t #f, characters #\..,
;;; vectors #( and keywords #: (no #, constructors, #!eof, #$ blobs, #<<
;;; strings or other reader extensions), then read with the reader table
;;; the module started with, and must hold exactly one datum, which is
;;; checked like a value to write. A missing file gives the default, or an
;;; error without one; a corrupt one (unreadable, truncated, too large, of
;;; the wrong kinds) gives the default when one is given, else an error
;;; naming the file and what is wrong. Every error of this module has the
;;; condition kind save-data (save-data-error?).

(module (downstroke save)
  (save-data-write! save-data-read save-data-exists? save-data-delete!
   save-data-path save-data-error? save-data-max-size save-data-max-nodes
   ;; for sibling modules only (and the tests): a procedure called as
   ;; (hook stage path) while writing, stage 'partial when half the bytes
   ;; are in the temporary file; the tests make it end the process there
   save-data-write-hook)

  (import scheme (chicken base) (chicken format) (chicken condition) (chicken port)
          (chicken file) (chicken file posix) (chicken foreign) (chicken io)
          (chicken keyword) (chicken read-syntax) (chicken string) (chicken errno) (chicken blob)
          (only (chicken memory representation) record-instance? record-instance-type))

  (foreign-declare "#include <unistd.h>\n#include <stdio.h>\n#include <string.h>\n#include <fcntl.h>")

  (define save-data-max-size (make-parameter (* 1024 1024)))
  (define save-data-max-nodes (make-parameter 100000))
  (define save-data-write-hook (make-parameter #f))

  ;; The reader table as the module found it, before a game could add
  ;; read syntax that runs code.
  (define pristine-read-table (copy-read-table (current-read-table)))

  (define (fail who fmt . args)
    (signal (make-composite-condition
             (make-property-condition 'exn 'location who 'message (apply sprintf fmt args)
                                      'arguments '())
             (make-property-condition 'save-data))))

  (define (save-data-error? c) (and (condition? c) ((condition-predicate 'save-data) c)))

  ;;; Names and paths.

  (define (name-char? c)
    (or (char-alphabetic? c) (char-numeric? c) (memv c '(#\- #\_))))

  (define (name-string who name)
    (let ((s (cond ((symbol? name) (symbol->string name))
                   ((string? name) name)
                   (else (fail who "the name ~s must be a symbol or a string" name)))))
      (unless (and (< 0 (string-length s) 65)
                   (let loop ((i 0))
                     (or (= i (string-length s))
                         (and (char<? (string-ref s i) #\x80) (name-char? (string-ref s i))
                              (loop (+ i 1))))))
        (fail who "the name ~s must be 1 to 64 letters, digits, - or _" name))
      s))

  (define (check-dir who dir)
    (unless (and (string? dir) (> (string-length dir) 0))
      (fail who "the directory must be a non-empty string, got ~s" dir)))

  (define (save-data-path dir name)
    (check-dir 'save-data-path dir)
    (string-append dir (if (char=? #\/ (string-ref dir (- (string-length dir) 1))) "" "/")
                   (name-string 'save-data-path name) ".scm"))

  ;;; What may be stored.

  ;; The kind of the first object in v that is not data, as a phrase, or
  ;; #f when all of it is; counts objects against the bound.
  (define (non-data v)
    (let ((budget (save-data-max-nodes)))
      (call/cc
       (lambda (return)
         (let walk ((v v))
           (set! budget (- budget 1))
           (when (< budget 0)
             (return (sprintf "more than ~a objects (or a circular list)" (save-data-max-nodes))))
           (cond ((or (boolean? v) (char? v) (string? v) (symbol? v) (keyword? v) (null? v)) #f)
                 ((number? v) (and (not (= v v)) "a NaN number"))
                 ((pair? v) (or (walk (car v)) (walk (cdr v))))
                 ((vector? v) (let loop ((i 0))
                                (and (< i (vector-length v))
                                     (or (walk (vector-ref v i)) (loop (+ i 1))))))
                 (else (return (kind-of v)))))))))

  (define (kind-of v)
    (cond ((procedure? v) "a procedure")
          ((eof-object? v) "the end-of-file object")
          ((port? v) "a port")
          ((condition? v) "a condition")
          ((record-instance? v) (sprintf "a record (~a)" (record-instance-type v)))
          ((blob? v) "a blob")
          (else (sprintf "a ~a" (let ((s (with-output-to-string (lambda () (write v)))))
                                  (if (> (string-length s) 40) (string-append (substring s 0 40) "...") s))))))

  ;;; The safe reader.

  ;; #f when text uses only the allowed # syntax, else a description of
  ;; the first other use and where it is.
  (define (forbidden-syntax text)
    (let ((n (string-length text)))
      (define (at i) (string-ref text i))
      (define (where i)
        (let loop ((j 0) (line 1))
          (if (= j i) line (loop (+ j 1) (if (char=? (at j) #\newline) (+ line 1) line)))))
      ;; what may come before a # that is inside a token (a#b, 1#), not
      ;; the start of a datum: not @ (,@#...) nor . ( .#...)
      (define (constituent? c)
        (or (char-alphabetic? c) (char-numeric? c) (memv c (string->list "!$%&*/:<=>?^_~+-"))))
      ;; the index after a string or |symbol| opening at i
      (define (after-delimited i q)
        (let skip ((j (+ i 1)))
          (cond ((>= j n) j)
                ((char=? (at j) #\\) (skip (+ j 2)))
                ((char=? (at j) q) (+ j 1))
                (else (skip (+ j 1))))))
      (let loop ((i 0))
        (if (>= i n)
            #f
            (let ((c (at i)))
              (cond ((char=? c #\") (loop (after-delimited i #\")))
                    ((char=? c #\|) (loop (after-delimited i #\|)))
                    ((char=? c #\;) (let skip ((j i))
                                      (cond ((>= j n) #f)
                                            ((char=? (at j) #\newline) (loop (+ j 1)))
                                            (else (skip (+ j 1))))))
                    ((and (char=? c #\#) (or (= i 0) (not (constituent? (at (- i 1))))))
                     (if (= (+ i 1) n)
                         (sprintf "a lone # at the end (line ~a)" (where i))
                         (let ((d (at (+ i 1))))
                           (cond ((memv d '(#\t #\f #\( #\:)) (loop (+ i 2)))
                                 ;; a character: the one after #\ is never syntax
                                 ((char=? d #\\) (loop (+ i 3)))
                                 (else (sprintf "the syntax #~a (line ~a): only #t #f #\\ #( and #: are data"
                                                d (where i)))))))
                    (else (loop (+ i 1)))))))))

  ;; The one datum of text, or raises what is wrong as a string.
  (define (read-datum text)
    (let ((bad (forbidden-syntax text)))
      (when bad (raise-text bad)))
    (let ((port (open-input-string text)))
      (let ((v (condition-case
                   (parameterize ((current-read-table pristine-read-table)
                                  (case-sensitive #t) (keyword-style #:suffix))
                     (let* ((v (read port)) (after (read port))) (cons v after)))
                 (e (exn) (raise-text ((condition-property-accessor 'exn 'message "unreadable") e))))))
        (when (eof-object? (car v)) (raise-text "it holds no value (empty or truncated)"))
        (unless (eof-object? (cdr v)) (raise-text "it holds more than one value"))
        (let ((kind (non-data (car v))))
          (when kind (raise-text (sprintf "it holds ~a, which is not data" kind))))
        (car v))))

  (define (raise-text s) (signal (make-property-condition 'save-data-text 'text s)))
  (define text-of (condition-property-accessor 'save-data-text 'text))

  ;;; Writing.

  (define posix-rename (foreign-lambda int "rename" c-string c-string))
  (define posix-fsync (foreign-lambda int "fsync" int))
  (define strerror (foreign-lambda c-string "strerror" int))

  (define (sync-directory! dir)
    ;; best effort: some file systems refuse to sync a directory
    (let ((fd ((foreign-lambda* int ((c-string d)) "C_return(open(d, O_RDONLY));") dir)))
      (when (>= fd 0)
        (posix-fsync fd)
        ((foreign-lambda int "close" int) fd))))

  ;; The file's text: a comment saying what it is, the value, a newline.
  (define (serialize name value)
    (string-append ";; downstroke save data " name "\n"
                   (with-output-to-string
                     (lambda () (parameterize ((keyword-style #:suffix)) (write value))))
                   "\n"))

  (define (save-data-write! dir name value)
    (check-dir 'save-data-write! dir)
    (let* ((n (name-string 'save-data-write! name))
           (path (save-data-path dir name))
           (tmp (string-append path ".tmp"))
           (kind (non-data value)))
      (when kind
        (fail 'save-data-write! "cannot save ~s: the value holds ~a; only data (numbers, strings, symbols, lists, vectors ...) is saved"
              n kind))
      (let ((text (serialize n value)))
        (when (> (string-length text) (save-data-max-size))
          (fail 'save-data-write! "cannot save ~s: ~a bytes written out, over save-data-max-size (~a)"
                n (string-length text) (save-data-max-size)))
        ;; what is written must read back the same
        (let ((back (condition-case (read-datum text)
                      (e (save-data-text) (fail 'save-data-write! "cannot save ~s: ~a" n (text-of e))))))
          (unless (equal? back value)
            (fail 'save-data-write! "cannot save ~s: the value does not read back the same" n)))
        (unless (directory-exists? dir)
          (fail 'save-data-write! "cannot save ~s: no directory ~s" n dir))
        (let ((fd (condition-case (file-open tmp (+ open/wronly open/creat open/trunc) #o644)
                    (e (exn) (fail 'save-data-write! "cannot save ~s: cannot create ~s: ~a" n tmp
                                   ((condition-property-accessor 'exn 'message "") e)))))
              (half (quotient (string-length text) 2)))
          (condition-case
              (begin
                (file-write fd (substring text 0 half))
                (let ((hook (save-data-write-hook))) (when hook (hook 'partial tmp)))
                (file-write fd (substring text half (string-length text)))
                (unless (= 0 (posix-fsync fd))
                  (fail 'save-data-write! "cannot save ~s: fsync of ~s: ~a" n tmp (strerror (errno))))
                (file-close fd)
                (set! fd #f))
            (e (save-data) (when fd (file-close fd)) (delete-file* tmp) (signal e))
            (e (exn) (when fd (file-close fd)) (delete-file* tmp)
               (fail 'save-data-write! "cannot save ~s: writing ~s: ~a" n tmp
                     ((condition-property-accessor 'exn 'message "") e))))
          (unless (= 0 (posix-rename tmp path))
            (let ((why (strerror (errno))))
              (delete-file* tmp)
              (fail 'save-data-write! "cannot save ~s: renaming ~s to ~s: ~a" n tmp path why)))
          (sync-directory! dir)
          (void)))))

  ;;; Reading.

  (define no-default (list 'no-default))

  (define (save-data-read dir name #!optional (default no-default))
    (check-dir 'save-data-read dir)
    (let* ((n (name-string 'save-data-read name))
           (path (save-data-path dir name))
           (corrupt (lambda (what)
                      (if (eq? default no-default)
                          (fail 'save-data-read "the save data ~s (~s) is corrupt: ~a" n path what)
                          default))))
      (cond ((not (file-exists? path))
             (if (eq? default no-default)
                 (fail 'save-data-read "no save data ~s (no file ~s)" n path)
                 default))
            ((directory-exists? path) (corrupt "it is a directory"))
            (else
             (let ((size (file-size path)) (limit (save-data-max-size)))
               (if (> size limit)
                   (corrupt (sprintf "~a bytes, over save-data-max-size (~a)" size limit))
                   (let ((text (condition-case
                                   (call-with-input-file path (lambda (p) (read-string (+ limit 1) p))
                                     #:binary)
                                 (e (exn) (fail 'save-data-read "cannot read the save data ~s (~s): ~a"
                                                n path ((condition-property-accessor 'exn 'message "") e))))))
                     (cond ((eof-object? text) (corrupt "the file is empty"))
                           ((> (string-length text) limit)
                            (corrupt (sprintf "over save-data-max-size (~a)" limit)))
                           (else
                            (condition-case (read-datum text)
                              (e (save-data-text) (corrupt (text-of e)))))))))))))

  (define (save-data-exists? dir name) (and (file-exists? (save-data-path dir name)) #t))

  (define (save-data-delete! dir name)
    (delete-file* (save-data-path dir name))
    (void)))
