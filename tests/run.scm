;;; Runs every suite: each tests/*-test.scm file, in name order.
;;; `make test` and `chicken-install -test` both run this file from tests/.
(import scheme (chicken base) (chicken file) (chicken sort) (chicken platform)
        (chicken process-context))

;; Under `chicken-install -n -test` nothing is installed: the compiled modules
;; are in the egg's own directory, one level up. `make test` puts build/ on
;; CHICKEN_REPOSITORY_PATH itself.
(unless (get-environment-variable "DOWNSTROKE_MAKE")
  (repository-path (cons ".." (repository-path))))

;; The suites run headless however they are started: SDL's dummy video and
;; audio drivers unless the caller chose others (`make test` sets the same).
(unless (get-environment-variable "SDL_VIDEODRIVER")
  (set-environment-variable! "SDL_VIDEODRIVER" "dummy"))
(unless (get-environment-variable "SDL_AUDIODRIVER")
  (set-environment-variable! "SDL_AUDIODRIVER" "dummy"))

(import (downstroke test))

(import (chicken string) (chicken pathname) (chicken process)
        (chicken process-context posix) (chicken format))

;; This process's module path, absolute, for the programs the suites start
;; (under chicken-install -n -test it was extended in-process only). The
;; suites are loaded into this toplevel and use it too.
(define (absolute-repository-path)
  (string-intersperse
   (map (lambda (dir) (if (absolute-pathname? dir) dir
                          (normalize-pathname (make-pathname (current-directory) dir))))
        (repository-path))
   ":"))

;; The demos' art, made when missing or stale (the generator decides), so
;; `chicken-install -test` from a fresh clone has what the demos load.
(unless (zero? (system (sprintf "cd .. && CHICKEN_REPOSITORY_PATH=~a csi -q -s tools/make-assets.scm >/dev/null"
                                (qs (absolute-repository-path)))))
  (print "run.scm: tools/make-assets.scm failed; the demo and docs suites need its files")
  (exit 1))

;; DOWNSTROKE_SUITES="physics scene" runs only those suites.
(define (suite-files)
  (let ((only (get-environment-variable "DOWNSTROKE_SUITES")))
    (if only
        (map (lambda (name) (string-append name "-test.scm")) (string-split only))
        (sort (glob "*-test.scm") string<?))))

(for-each load (suite-files))

;; The demo suites' scratch directory (tests/demo-support.scm), if any.
(let ((dir (make-pathname (or (get-environment-variable "TMPDIR") "/tmp")
                          (sprintf "downstroke-tests-~a" (current-process-id)))))
  (when (directory-exists? dir) (delete-directory dir #t)))
(test-exit)
