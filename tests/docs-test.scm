;;; Every example in README.org and docs/*.org runs, and prints what the
;;; document says it prints, so no example goes stale.
;;;
;;; The rule the documents follow (see docs/guide.org, "Examples"):
;;;   - every `#+begin_src scheme` block names the file it belongs to with
;;;     `:tangle examples/NAME.scm` (Org's own tangling: C-c C-v t writes
;;;     the files next to the document). Blocks naming the same file are
;;;     one program, in order, so prose can sit between its parts;
;;;   - a `#+RESULTS:` line right after a block, followed by a
;;;     `#+begin_example` block, is what that part prints. A program must
;;;     show at least one result, and its whole output must equal them all.
;;; Programs run with `csi -q -s` from the repository root, each in its own
;;; process, headless like every suite.
;;;   - a `#+begin_src sh` block with `:tangle` is a shell example: the
;;;     document's Scheme examples are first written to their :tangle
;;;     paths (beside the document, as Org would), then the block runs
;;;     with `sh -e` from the repository root and must print its results.
;;;     `:needs installed-egg` marks one that builds against the installed
;;;     egg (csc -static needs its static objects); where none is on the
;;;     repository path (make check, chicken-install -n) it is reported as
;;;     not run, and make test's install step runs it.
;;;     An sh block without :tangle is an illustration and is not run.

(import scheme (chicken base) (chicken io) (chicken string) (chicken file)
        (chicken pathname) (chicken process) (chicken process-context)
        (chicken sort) (chicken format) (chicken platform) (downstroke test))

;; An example: the document, the tangle target, and the program's code
;; lines and expected lines, each in order.
(define-record doc-example document target code expected lang needs)

;; The line without leading and trailing spaces and tabs.
(define (docs-trim line)
  (let* ((n (string-length line))
         (space? (lambda (i) (memv (string-ref line i) '(#\space #\tab))))
         (start (let loop ((i 0)) (if (and (< i n) (space? i)) (loop (+ i 1)) i)))
         (end (let loop ((i n)) (if (and (> i start) (space? (- i 1))) (loop (- i 1)) i))))
    (substring line start end)))

(define (docs-src-lang line)
  (let ((words (string-split line)))
    (and (>= (length words) 2) (string=? "#+begin_src" (car words)) (cadr words))))

;; A scheme block is always an example; an sh block only with :tangle.
(define (docs-src-header? line)
  (let ((lang (docs-src-lang line)))
    (or (equal? lang "scheme")
        (and (equal? lang "sh") (docs-header-arg line ":tangle") #t))))

(define (docs-header-arg line name)
  (let ((words (string-split line)))
    (cond ((member name words) => (lambda (m) (and (pair? (cdr m)) (cadr m))))
          (else #f))))

(define (docs-tangle-target line) (docs-header-arg line ":tangle"))

(define (docs-blank? line) (string=? "" (docs-trim line)))

;; Lines up to (not including) the line satisfying stop?, and the rest after it.
(define (docs-take-until lines stop? document)
  (let loop ((ls lines) (out '()))
    (cond ((null? ls) (error 'docs-test "a block is not closed" document))
          ((stop? (car ls)) (values (reverse out) (cdr ls)))
          (else (loop (cdr ls) (cons (car ls) out))))))

(define (docs-line-is text) (lambda (line) (string=? text (docs-trim line))))

;; If `lines` starts (after blank lines) with #+RESULTS: and an example
;; block, that block's lines and what follows it; else #f and `lines`.
(define (docs-results lines document)
  (let ((ls (let skip ((ls lines)) (if (and (pair? ls) (docs-blank? (car ls))) (skip (cdr ls)) ls))))
    (if (and (pair? ls) (string=? "#+RESULTS:" (docs-trim (car ls)))
             (pair? (cdr ls)) (string=? "#+begin_example" (docs-trim (cadr ls))))
        (docs-take-until (cddr ls) (docs-line-is "#+end_example") document)
        (values #f lines))))

;; The blocks of one document as (target code-lines expected-lines-or-#f
;; lang needs), in order. A scheme block without :tangle has target #f.
(define (docs-blocks document)
  (let loop ((ls (with-input-from-file document read-lines)) (out '()))
    (cond ((null? ls) (reverse out))
          ((docs-src-header? (car ls))
           (let ((target (docs-tangle-target (car ls))))
             (receive (code rest) (docs-take-until (cdr ls) (docs-line-is "#+end_src") document)
               (receive (expected rest) (docs-results rest document)
                 (loop rest (cons (list target code expected (docs-src-lang (car ls))
                                        (docs-header-arg (car ls) ":needs"))
                                  out))))))
          (else (loop (cdr ls) out)))))

;; Blocks grouped into examples by target, in order of first appearance.
(define (docs-examples document)
  (let loop ((blocks (docs-blocks document)) (examples '()))
    (if (null? blocks)
        (reverse examples)
        (let* ((b (car blocks)) (target (car b))
               (known (and target (find (lambda (e) (equal? (doc-example-target e) target)) examples))))
          (cond (known
                 (doc-example-code-set! known (append (doc-example-code known) (cadr b)))
                 (doc-example-expected-set! known (append (doc-example-expected known) (or (caddr b) '())))
                 (loop (cdr blocks) examples))
                (else
                 (loop (cdr blocks)
                       (cons (make-doc-example document target (cadr b) (or (caddr b) '())
                                                   (list-ref b 3) (list-ref b 4))
                             examples))))))))

(define (find ok? ls) (cond ((null? ls) #f) ((ok? (car ls)) (car ls)) (else (find ok? (cdr ls)))))

;; Runs the code with `runner` (csi -q -s, or sh -e) from the repository
;; root; its output lines (stderr kept apart) and whether it exited with
;; status 0.
(define (docs-run code name #!optional (runner "csi -q -s") (extension ".scm"))
  (let ((file (create-temporary-file extension)))
    (with-output-to-file file (lambda () (for-each (lambda (l) (display l) (newline)) code)))
    (let ((out (create-temporary-file ".out")))
      (let ((status (system (sprintf "cd .. && CHICKEN_REPOSITORY_PATH='~a' ~a ~a > ~a 2>~a.err"
                                     (absolute-repository-path) runner (qs file) (qs out) (qs out)))))
        (let ((lines (with-input-from-file out read-lines))
              (errors (with-input-from-file (string-append out ".err") read-string)))
          (unless (zero? status)
            (print "docs: " name " failed:\n" errors))
          (values lines (zero? status)))))))

;; Org's tangling: each Scheme example of the document written to its
;; :tangle path, relative to the document's directory.
(define (docs-tangle! document)
  (for-each (lambda (ex)
              (when (and (doc-example-target ex) (equal? (doc-example-lang ex) "scheme"))
                (let ((file (make-pathname (pathname-directory document) (doc-example-target ex))))
                  (create-directory (pathname-directory file) #t)
                  (with-output-to-file file
                    (lambda () (for-each (lambda (l) (display l) (newline)) (doc-example-code ex)))))))
            (docs-examples document)))

;; An installed egg has static objects (NAME.o) in a repository directory.
(define (docs-egg-installed?)
  (find (lambda (dir) (file-exists? (make-pathname dir "downstroke.engine.o")))
        (repository-path)))

;; A shell example runs after the document's Scheme examples are tangled.
(define (docs-run-sh document code name)
  (docs-tangle! document)
  (docs-run code name "sh -e" ".sh"))

(define docs-documents
  (cons "../README.org" (sort (glob "../docs/*.org") string<?)))

(test-group "docs: every scheme block is part of a named example"
  (for-each (lambda (document)
              (for-each (lambda (b)
                          (test-assert (sprintf "~a: the block starting ~s has :tangle" document
                                                (if (pair? (cadr b)) (car (cadr b)) ""))
                                       (car b)))
                        (docs-blocks document)))
            docs-documents))

(for-each
 (lambda (document)
   (for-each
    (lambda (ex)
      (when (doc-example-target ex)
        (let ((name (sprintf "~a ~a" (pathname-strip-directory document) (doc-example-target ex)))
              (sh? (equal? (doc-example-lang ex) "sh")))
          (if (and (equal? (doc-example-needs ex) "installed-egg") (not (docs-egg-installed?)))
              (print "docs: " name " not run here: it needs the egg installed (make test's install step runs it)")
          (test-group (string-append "docs: " name)
            (test-assert "it shows what it prints" (pair? (doc-example-expected ex)))
            (receive (lines ok?) (if sh?
                                     (docs-run-sh document (doc-example-code ex) name)
                                     (docs-run (doc-example-code ex) name))
              (test-assert "it runs without an error" ok?)
              (test "it prints what the document shows" (doc-example-expected ex) lines)))))))
    (docs-examples document)))
 docs-documents)
