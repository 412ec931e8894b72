;;; What the demo suites share (included, not a suite): run a demo as a
;;; user would, from the repository root, and read the lines it prints.

(import (chicken base) (chicken io) (chicken process) (chicken file)
        (chicken pathname) (chicken process-context) (chicken process-context posix)
        (chicken format) (chicken string))

;; The suites' scratch files live in a directory of this run's own, so that
;; two users (or two runs) on one machine never share a path in /tmp.
(define (demo-tmp name)
  (let ((dir (make-pathname (or (get-environment-variable "TMPDIR") "/tmp")
                            (sprintf "downstroke-tests-~a" (current-process-id)))))
    (unless (directory-exists? dir) (create-directory dir #t))
    (make-pathname dir name)))

;; The lines `command` prints on stdout (stderr dropped: SDL's audio chatter).
(define (demo-output command)
  (with-input-from-pipe (string-append "cd .. && " command " 2>/dev/null") read-lines))

(define (filter-lines text lines)
  (cond ((null? lines) '())
        ((substring-index text (car lines)) (cons (car lines) (filter-lines text (cdr lines))))
        (else (filter-lines text (cdr lines)))))

(define (last-line lines) (if (null? lines) "" (car (reverse lines))))
