;;; What the suites that test a cost share (included, not a suite): a
;;; program run in a child csi with a limit on its CPU time, at a size
;;; where a cost that grew with the square of the input would take
;;; minutes; such a regression fails here (the child is stopped before
;;; it prints) instead of making the suite take minutes.

(import (chicken base) (chicken io) (chicken process) (chicken file) (chicken format)
        (chicken condition))

;; The data `program` (a list of expressions, run in order as a script)
;; writes on its standard output, read back; what it had not written
;; when `seconds` of CPU time ran out is missing.
(define (bounded-run seconds program)
  (let ((file (create-temporary-file ".scm")))
    (with-output-to-file file (lambda () (for-each (lambda (x) (write x) (newline)) program)))
    (let ((out (with-input-from-pipe
                (sprintf "ulimit -t ~a; CHICKEN_REPOSITORY_PATH=~a csi -q -s ~a 2>/dev/null"
                         seconds (qs (absolute-repository-path)) (qs file))
                (lambda () (let loop ((out '()))
                             (let ((x (handle-exceptions e #!eof (read))))
                               (if (eof-object? x) (reverse out) (loop (cons x out)))))))))
      (delete-file* file)
      out)))

;; The value a bounded program wrote as (name value), or a symbol saying
;; it wrote none.
(define (bounded-result results name)
  (let ((r (assoc name (let keep ((xs results))
                         (cond ((null? xs) '())
                               ((and (pair? (car xs)) (string? (caar xs)) (pair? (cdar xs)))
                                (cons (car xs) (keep (cdr xs))))
                               (else (keep (cdr xs))))))))
    (if r (cadr r) 'missing:-the-child-stopped-or-ran-out-of-time)))
