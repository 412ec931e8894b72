;;; (downstroke c-constants): numbers that Scheme and C must agree on (a
;;; flag, a bit, a key's index), written in Scheme once and checked by the
;;; C compiler against the header that states them for C.
;;;
;;; (define-c-constant name C_NAME value) defines name as a constant that
;;; csc folds like a literal, and puts `_Static_assert(C_NAME == value)`
;;; into the module's C, so a header and a module that disagree do not
;;; compile. The header must be included (foreign-declare) before.

(module (downstroke c-constants)
  (define-c-constant)

  (import scheme (chicken base))
  (import-for-syntax scheme (chicken base))

  (define-syntax define-c-constant
    (er-macro-transformer
     (lambda (x r c)
       (let ((name (cadr x)) (c-name (symbol->string (caddr x))) (value (cadddr x)))
         `(,(r 'begin)
           (,(r 'define-constant) ,name ,value)
           (,(r 'foreign-declare)
            ,(string-append "_Static_assert(" c-name " == " (number->string value)
                            ", \"" c-name " is " (number->string value) " in the Scheme that uses it\");"))))))))
