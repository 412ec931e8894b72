;;; Runs every suite, each alone in its own process (tests/suite.scm), two
;;; at a time, and prints one line per suite and last the total,
;;; "N passed, N failed". `make check` and `chicken-install -test` both run
;;; this file from tests/.
;;;
;;; The suites are the files *-test.scm in each layer's tests/ folder
;;; (base, core, physics, tiled, shell: a module's suites beside it) and in
;;; tests/ (the demos, the docs, the layout, and what spans layers).
;;; DOWNSTROKE_SUITES narrows the run: each word is a suite's name
;;; ("escape" for escape-test.scm) or a folder ending in "/" ("physics/",
;;; "tests/"). DOWNSTROKE_JOBS sets how many run at once (2).
(import scheme (chicken base) (chicken file) (chicken sort) (chicken platform)
        (chicken process-context) (chicken process-context posix) (chicken string)
        (chicken pathname) (chicken process) (chicken format) (chicken io) (chicken time))

;; Under `chicken-install -n -test` nothing is installed: the compiled modules
;; are in the egg's own directory, one level up. `make test` puts build/ on
;; CHICKEN_REPOSITORY_PATH itself.
(unless (get-environment-variable "DOWNSTROKE_MAKE")
  (repository-path (cons ".." (repository-path))))

;; The suites' processes get this module path, absolute, and run headless
;; unless the caller chose other SDL drivers.
(set-environment-variable!
 "CHICKEN_REPOSITORY_PATH"
 (string-intersperse
  (map (lambda (dir) (if (absolute-pathname? dir) dir
                         (normalize-pathname (make-pathname (current-directory) dir))))
       (repository-path))
  ":"))
(set-environment-variable! "DOWNSTROKE_MAKE" "1")
(unless (get-environment-variable "SDL_VIDEODRIVER")
  (set-environment-variable! "SDL_VIDEODRIVER" "dummy"))
(unless (get-environment-variable "SDL_AUDIODRIVER")
  (set-environment-variable! "SDL_AUDIODRIVER" "dummy"))

;; Tiled's example maps, fetched once before any suite runs (make check's
;; `examples` target does it too): two suites fetching them side by side
;; (tmx, tiled-compare) would remove each other's copy half-way. A failed
;; fetch is left to those suites to report.
(system "sh ../tools/fetch-tiled-examples.sh >/dev/null 2>&1")

;; The demos' art, made when missing or stale (the generator decides), so
;; `chicken-install -test` from a fresh clone has what the demos load.
(unless (zero? (system "cd .. && csi -q -s tools/make-assets.scm >/dev/null"))
  (print "run.scm: tools/make-assets.scm failed; the demo and docs suites need its files")
  (exit 1))

(define layers '("base" "core" "physics" "tiled" "shell"))

;; Every suite, as a path from tests/: the layers' in layer order, then tests/'s.
(define all-suites
  (append (apply append (map (lambda (layer) (sort (glob (sprintf "../~a/tests/*-test.scm" layer)) string<?))
                             layers))
          (sort (glob "*-test.scm") string<?)))

(define (suite-name file)              ; "../physics/tests/escape-test.scm" -> "escape"
  (let ((base (pathname-file file)))
    (substring base 0 (- (string-length base) (string-length "-test")))))

(define (suite-folder file)            ; -> "physics/", or "tests/" for tests/'s own
  (let ((parts (string-split (or (pathname-directory file) "") "/")))
    (if (and (= (length parts) 3) (string=? (car parts) ".."))
        (string-append (cadr parts) "/")
        "tests/")))

(define (chosen? words file)
  (or (member (suite-name file) words) (member (suite-folder file) words)))

(define suites
  (let ((only (get-environment-variable "DOWNSTROKE_SUITES")))
    (if only
        (let* ((words (string-split only))
               (chosen (foldr (lambda (f kept) (if (chosen? words f) (cons f kept) kept)) '() all-suites)))
          (when (null? chosen)
            (printf "run.scm: no suite matches ~s (names like escape, folders like physics/)~%" only)
            (exit 2))
          chosen)
        all-suites)))

(define jobs (or (string->number (or (get-environment-variable "DOWNSTROKE_JOBS") "")) 2))

(define scratch
  (let ((dir (make-pathname (or (get-environment-variable "TMPDIR") "/tmp")
                            (sprintf "downstroke-run-~a" (current-process-id)))))
    (create-directory dir #t)
    dir))

(define (output-file file) (make-pathname scratch (suite-name file) "out"))

;; "N passed, N failed" as (N . N), or #f.
(define (counts line)
  (let ((words (string-split line " ,")))
    (and (= (length words) 4) (string=? (cadr words) "passed") (string=? (cadddr words) "failed")
         (let ((p (string->number (car words))) (f (string->number (caddr words))))
           (and p f (cons p f))))))

;; Prints a finished suite's output (its counts line aside) and its line
;; in the summary; gives its counts. A suite that ends without its counts
;; (it crashed, or called exit) counts as one failure.
(define (report! file status seconds)
  (let* ((lines (with-input-from-file (output-file file) read-lines))
         (last-counts (and (pair? lines) (counts (last lines))))
         (body (if last-counts (butlast lines) lines))
         (result (or last-counts (cons 0 1))))
    (for-each print body)
    (printf "~a ~a: ~a passed, ~a failed (~as)~a~%"
            (if (zero? (cdr result)) "ok  " "FAIL") (string-append (suite-folder file) (suite-name file))
            (car result) (cdr result) seconds
            (if last-counts "" (sprintf ", ended without its count, exit status ~a" status)))
    result))

(define (last l) (if (null? (cdr l)) (car l) (last (cdr l))))
(define (butlast l) (if (null? (cdr l)) '() (cons (car l) (butlast (cdr l)))))

(define (start! file)
  (process-run (sprintf "exec csi -q -s suite.scm ~a > ~a 2>&1" (qs file) (qs (output-file file)))))

;; Keeps `jobs` suites running; reports each as it ends.
(define totals
  (let loop ((waiting suites) (running '()) (passed 0) (failed 0))
    (cond ((and (pair? waiting) (< (length running) jobs))
           (loop (cdr waiting)
                 (cons (list (start! (car waiting)) (car waiting) (current-seconds)) running)
                 passed failed))
          ((null? running) (cons passed failed))
          (else
           (receive (pid normal? status) (process-wait)
             (let ((done (assv pid running)))
               (if (not done)
                   (loop waiting running passed failed)
                   (let ((r (report! (cadr done) (if normal? status (sprintf "signal ~a" status))
                                     (- (current-seconds) (caddr done)))))
                     (loop waiting
                           (foldr (lambda (x kept) (if (eqv? (car x) pid) kept (cons x kept))) '() running)
                           (+ passed (car r)) (+ failed (cdr r)))))))))))

(delete-directory scratch #t)
(printf "~a passed, ~a failed~%" (car totals) (cdr totals))
(exit (if (zero? (cdr totals)) 0 1))
