;;; Runs one suite alone, in this process: tests/run.scm starts one of
;;; these per suite, so no two suites share a toplevel. From tests/:
;;;   csi -q -s suite.scm ../physics/tests/escape-test.scm
;;; (`make check SUITES=escape` does the same from the top). The last line
;;; printed is the suite's "N passed, N failed"; the exit status is 0 when
;;; nothing failed.
(import scheme (chicken base) (chicken process-context) (chicken string)
        (chicken pathname) (chicken platform) (chicken file))

;; Under `chicken-install -n -test` nothing is installed: the compiled modules
;; are in the egg's own directory, one level up. `make check` and run.scm
;; put the right directories on CHICKEN_REPOSITORY_PATH themselves.
(unless (get-environment-variable "DOWNSTROKE_MAKE")
  (repository-path (cons ".." (repository-path))))

;; Headless however the suite is started, unless the caller chose drivers.
(unless (get-environment-variable "SDL_VIDEODRIVER")
  (set-environment-variable! "SDL_VIDEODRIVER" "dummy"))
(unless (get-environment-variable "SDL_AUDIODRIVER")
  (set-environment-variable! "SDL_AUDIODRIVER" "dummy"))

;; The harness, (downstroke test), is part of the tests, not of the library.
(load "harness.scm")
(import (downstroke test) (chicken format) (chicken process-context posix))

;; This process's module path, absolute, for the programs a suite starts.
(define (absolute-repository-path)
  (string-intersperse
   (map (lambda (dir) (if (absolute-pathname? dir) dir
                          (normalize-pathname (make-pathname (current-directory) dir))))
        (repository-path))
   ":"))

(let ((suite (let ((args (command-line-arguments)))
               (if (= (length args) 1) (car args)
                   (begin (print "usage: csi -q -s suite.scm FILE-test.scm (from tests/)") (exit 2))))))
  (unless (file-exists? suite)
    (print "suite.scm: no suite " suite)
    (exit 2))
  (load suite))

;; The demo suites' scratch directory (tests/demo-support.scm), if any.
(let ((dir (make-pathname (or (get-environment-variable "TMPDIR") "/tmp")
                          (sprintf "downstroke-tests-~a" (current-process-id)))))
  (when (directory-exists? dir) (delete-directory dir #t)))
(test-exit)
