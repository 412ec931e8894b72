;;; (downstroke test): a small stand-in for the `test` egg, which cannot be
;;; installed here. Same names and argument order (test, test-assert,
;;; test-error, test-group, test-exit), so suites move to the egg unchanged.
;;; The last line a run prints is "N passed, N failed".

(module (downstroke test)
  (test test-assert test-error test-group test-exit
   current-test-epsilon test-approx-equal? error-text
   test-counts
   ;; used by the macros above, so they must be exported too
   run-test run-test-assert run-test-error run-group)

  (import scheme (chicken base) (chicken condition) (chicken format)
          (chicken port))

  ;; Inexact results are compared within this relative tolerance, as the
  ;; test egg does; exact values are compared with equal?.
  (define current-test-epsilon (make-parameter 1e-5))

  (define passed 0)
  (define failed 0)
  (define group-path '())

  (define (test-counts) (values passed failed))

  (define (test-approx-equal? expected actual)
    (if (and (number? expected) (number? actual)
             (or (inexact? expected) (inexact? actual)))
        (or (= expected actual)
            (let ((scale (max 1.0 (abs expected))))
              (<= (abs (- expected actual)) (* scale (current-test-epsilon)))))
        (equal? expected actual)))

  (define (full-name name)
    (let loop ((path (reverse group-path)) (out ""))
      (if (null? path)
          (string-append out (or name "(unnamed)"))
          (loop (cdr path) (string-append out (car path) " / ")))))

  (define (pass!) (set! passed (+ passed 1)))

  (define (fail! name fmt . args)
    (set! failed (+ failed 1))
    (printf "FAIL ~a~%" (full-name name))
    (apply printf (string-append "     " fmt "~%") args))

  ;; The message and irritants of a condition, as one line.
  (define (error-text exn)
    (if (condition? exn)
        (let ((msg ((condition-property-accessor 'exn 'message "") exn))
              (args ((condition-property-accessor 'exn 'arguments '()) exn)))
          (with-output-to-string
            (lambda ()
              (display msg)
              (for-each (lambda (a) (display " ") (write a)) args))))
        (with-output-to-string (lambda () (display "non-condition: ") (write exn)))))

  (define (run-test name expected thunk)
    (handle-exceptions exn
        (fail! name "raised: ~a" (error-text exn))
      (let ((actual (thunk)))
        (if (test-approx-equal? expected actual)
            (pass!)
            (fail! name "expected ~s~%     got      ~s" expected actual)))))

  (define (run-test-assert name thunk)
    (handle-exceptions exn
        (fail! name "raised: ~a" (error-text exn))
      (if (thunk) (pass!) (fail! name "assertion was #f"))))

  ;; A test-error passes when its expression raises. With a predicate
  ;; (a procedure of the condition) it must also satisfy that predicate.
  (define (run-test-error name pred thunk)
    (let ((outcome
           (call/cc
            (lambda (k)
              (with-exception-handler
               (lambda (exn) (k (cons 'raised exn)))
               (lambda () (cons 'returned (thunk))))))))
      (cond ((eq? (car outcome) 'returned)
             (fail! name "expected an error, got ~s" (cdr outcome)))
            ((or (not pred) (pred (cdr outcome))) (pass!))
            (else (fail! name "wrong error: ~a" (error-text (cdr outcome)))))))

  (define-syntax test
    (syntax-rules ()
      ((_ name expected expr) (run-test name expected (lambda () expr)))
      ((_ expected expr) (run-test #f expected (lambda () expr)))))

  (define-syntax test-assert
    (syntax-rules ()
      ((_ name expr) (run-test-assert name (lambda () expr)))
      ((_ expr) (run-test-assert #f (lambda () expr)))))

  ;; (test-error name expr), (test-error expr), and an extension the suites
  ;; use to check what an error says: (test-error name pred expr).
  (define-syntax test-error
    (syntax-rules ()
      ((_ name pred expr) (run-test-error name pred (lambda () expr)))
      ((_ name expr) (run-test-error name #f (lambda () expr)))
      ((_ expr) (run-test-error #f #f (lambda () expr)))))

  (define (run-group name thunk)
    (set! group-path (cons name group-path))
    (handle-exceptions exn
        (fail! #f "group raised: ~a" (error-text exn))
      (thunk))
    (set! group-path (cdr group-path)))

  (define-syntax test-group
    (syntax-rules ()
      ((_ name body ...) (run-group name (lambda () body ...)))))

  (define (test-exit)
    (printf "~a passed, ~a failed~%" passed failed)
    (exit (if (zero? failed) 0 1))))
