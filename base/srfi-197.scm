;;; (downstroke srfi-197): SRFI 197 "Pipeline Operators".
;;;
;;; A stand-in for the srfi-197 egg, which cannot be installed here:
;;; chain, chain-and, chain-when, chain-lambda, nest and nest-reverse, with
;;; the `_` placeholder, the `...` variadic marker, and the optional custom
;;; placeholder (and, for chain and chain-lambda, ellipsis) symbols.
;;;
;;; The macros are explicit-renaming transformers. Their expansions use only
;;; core forms (let, lambda, if, call-with-values, apply, car, cdr), renamed
;;; so user bindings cannot capture them; there are no runtime helpers, so
;;; nothing can be lost to dead-code removal under -O3. The expansion-time
;;; helpers live in begin-for-syntax, which CHICKEN copies into the import
;;; library.
;;;
;;; Placeholder and ellipsis symbols are recognised as syntax-rules literals
;;; are: by identifier comparison. A `_` that is lexically bound where the
;;; macro is used is therefore that variable, not the placeholder; a custom
;;; placeholder avoids the clash.
;;;
;;; Malformed steps (an empty step, an ellipsis not at the end or not after a
;;; placeholder, a nest step without exactly one placeholder, more than one
;;; placeholder in a chain-and or chain-when step) are syntax errors.

(module (downstroke srfi-197)
  (chain chain-and chain-when chain-lambda nest nest-reverse)

  (import scheme (chicken base) (chicken syntax))
  (import-for-syntax scheme (chicken base) (chicken syntax))

  ;; Prefixed: for-syntax definitions of all modules share one namespace.
  (begin-for-syntax

    (define (s197-proper-list? x)
      (let loop ((x x))
        (cond ((null? x) #t)
              ((pair? x) (loop (cdr x)))
              (else #f))))

    ;; Every operator needs a proper form with at least an initial value.
    (define (s197-check-initial who form)
      (unless (and (s197-proper-list? form) (pair? (cdr form)))
        (syntax-error who "missing initial value" form)))

    (define (s197-same-id? x id compare)
      (and (symbol? x) (compare x id)))

    ;; The optional placeholder (and ellipsis) symbols come right after the
    ;; fixed leading arguments: a step is always a list, so a symbol there
    ;; can only be one of them. Returns the remaining arguments plus the
    ;; placeholder and ellipsis identifiers (defaults renamed, so they mean
    ;; `_` and `...` as seen from this module).
    (define (s197-optional-symbols args allow-ellipsis? rename)
      (let* ((ph? (and (pair? args) (symbol? (car args))))
             (ph (if ph? (car args) (rename '_)))
             (args (if ph? (cdr args) args))
             (ell? (and ph? allow-ellipsis? (pair? args) (symbol? (car args))))
             (ell (if ell? (car args) (rename '...)))
             (args (if ell? (cdr args) args)))
        (values args ph ell)))

    (define (s197-check-step who step form)
      (unless (and (pair? step) (s197-proper-list? step))
        (syntax-error who "a step must be a non-empty list" step form)))

    (define (s197-count-placeholders step ph compare)
      (let loop ((l step) (n 0))
        (if (null? l)
            n
            (loop (cdr l) (if (s197-same-id? (car l) ph compare) (+ n 1) n)))))

    ;; Analyses a chain step. Returns (values n variadic? build) where n is
    ;; the number of fixed placeholders and (build temps rest) makes the
    ;; step's application from the n temporaries and, if variadic?, the
    ;; variable holding the remaining pipeline values as a list.
    (define (s197-analyse-chain-step who step ph ell form rename compare)
      (s197-check-step who step form)
      (let* ((len (length step))
             (variadic? (s197-same-id? (list-ref step (- len 1)) ell compare))
             (fixed (if variadic? (s197-take* step (- len 2)) step)))
        ;; The ellipsis may appear only at the very end, after a placeholder.
        (let loop ((l step) (prev #f))
          (unless (null? l)
            (when (s197-same-id? (car l) ell compare)
              (unless (and (null? (cdr l)) prev (s197-same-id? prev ph compare))
                (syntax-error who
                              "the ellipsis may only end a step, after a placeholder"
                              step form)))
            (loop (cdr l) (car l))))
        (values
         (s197-count-placeholders fixed ph compare)
         variadic?
         (lambda (temps rest)
           (let ((args (let loop ((l fixed) (temps temps) (acc '()))
                         (cond ((null? l) (reverse acc))
                               ((s197-same-id? (car l) ph compare)
                                (loop (cdr l) (cdr temps) (cons (car temps) acc)))
                               (else (loop (cdr l) temps (cons (car l) acc)))))))
             (cond ((not variadic?) args)
                   ;; (_ ...): the first pipeline value is the procedure.
                   ((null? args)
                    (list (rename 'apply)
                          (list (rename 'car) rest)
                          (list (rename 'cdr) rest)))
                   (else
                    (cons (rename 'apply) (append args (list rest))))))))))

    (define (s197-take* l n)
      (if (= n 0) '() (cons (car l) (s197-take* (cdr l) (- n 1)))))

    (define (s197-make-temps n)
      (let loop ((i 0) (acc '()))
        (if (= i n) (reverse acc) (loop (+ i 1) (cons (gensym 'x) acc)))))

    ;; Binds the values of expr for a step needing n fixed values (plus the
    ;; rest, when variadic?) and evaluates body with them. With no
    ;; placeholders, all values are received and ignored.
    (define (s197-bind-values expr temps rest variadic? body rename)
      (cond ((and (not variadic?) (= (length temps) 1))
             (list (rename 'let) (list (list (car temps) expr)) body))
            (else
             (list (rename 'call-with-values)
                   (list (rename 'lambda) '() expr)
                   (list (rename 'lambda)
                         (cond (variadic? (s197-append* temps rest))
                               ((null? temps) (gensym 'ignored))
                               (else temps))
                         body)))))

    ;; (a b) plus c gives (a b . c)
    (define (s197-append* l tail)
      (if (null? l) tail (cons (car l) (s197-append* (cdr l) tail))))

    ;; The application of each step receives the values of the one before;
    ;; nesting is let*-like, so steps run strictly left to right and the last
    ;; step is in tail position.
    (define (s197-expand-chain who expr steps ph ell form rename compare)
      (if (null? steps)
          expr
          (let-values (((n variadic? build)
                        (s197-analyse-chain-step who (car steps) ph ell form
                                                 rename compare)))
            (let ((temps (s197-make-temps n))
                  (rest (gensym 'rest)))
              (s197-bind-values expr temps rest variadic?
                                (s197-expand-chain who (build temps rest) (cdr steps)
                                                   ph ell form rename compare)
                                rename)))))

    ;; For chain-and and chain-when: a step with at most one placeholder,
    ;; which is replaced by var.
    (define (s197-single-step who step ph var form compare)
      (s197-check-step who step form)
      (when (> (s197-count-placeholders step ph compare) 1)
        (syntax-error who "a step may hold at most one placeholder" step form))
      (map (lambda (d) (if (s197-same-id? d ph compare) var d)) step))

    ;; For nest and nest-reverse: the step's one placeholder, replaced by
    ;; the (unevaluated) inner form.
    (define (s197-nest-step who step ph inner form compare)
      (s197-check-step who step form)
      (unless (= (s197-count-placeholders step ph compare) 1)
        (syntax-error who "a step must hold exactly one placeholder" step form))
      (map (lambda (d) (if (s197-same-id? d ph compare) inner d)) step))
    )

  ;; (chain initial-value [placeholder [ellipsis]] step ...)
  (define-syntax chain
    (er-macro-transformer
     (lambda (form rename compare)
       (s197-check-initial 'chain form)
       (let-values (((steps ph ell)
                     (s197-optional-symbols (cddr form) #t rename)))
         (s197-expand-chain 'chain (cadr form) steps ph ell form rename compare)))))

  ;; (chain-lambda [placeholder [ellipsis]] step ...): the first step's
  ;; placeholders are the procedure's parameters.
  (define-syntax chain-lambda
    (er-macro-transformer
     (lambda (form rename compare)
       (unless (s197-proper-list? form)
         (syntax-error 'chain-lambda "bad syntax" form))
       (let-values (((steps ph ell) (s197-optional-symbols (cdr form) #t rename)))
         (when (null? steps)
           (syntax-error 'chain-lambda "at least one step is needed" form))
         (let-values (((n variadic? build)
                       (s197-analyse-chain-step 'chain-lambda (car steps) ph ell
                                                form rename compare)))
           (let ((temps (s197-make-temps n))
                 (rest (gensym 'rest)))
             (list (rename 'lambda)
                   (if variadic? (s197-append* temps rest) temps)
                   (s197-expand-chain 'chain-lambda (build temps rest) (cdr steps)
                                      ph ell form rename compare))))))))

  ;; (chain-and initial-value [placeholder] step ...): stops with #f as soon
  ;; as the initial value or a step's value is #f.
  (define-syntax chain-and
    (er-macro-transformer
     (lambda (form rename compare)
       (s197-check-initial 'chain-and form)
       (let-values (((steps ph ell) (s197-optional-symbols (cddr form) #f rename)))
         (let loop ((expr (cadr form)) (steps steps))
           (if (null? steps)
               expr
               (let ((var (gensym 'x)))
                 (list (rename 'let) (list (list var expr))
                       (list (rename 'if) var
                             (loop (s197-single-step 'chain-and (car steps) ph
                                                     var form compare)
                                   (cdr steps))
                             #f)))))))))

  ;; (chain-when initial-value [placeholder] ([guard] step) ...): a step
  ;; whose guard is #f is skipped and its pipeline value passed on.
  (define-syntax chain-when
    (er-macro-transformer
     (lambda (form rename compare)
       (s197-check-initial 'chain-when form)
       (let-values (((clauses ph ell) (s197-optional-symbols (cddr form) #f rename)))
         (let ((var (gensym 'x)))
           (let loop ((expr (cadr form)) (clauses clauses))
             (list (rename 'let) (list (list var expr))
                   (if (null? clauses)
                       var
                       (let ((clause (car clauses)))
                         (unless (and (pair? clause) (s197-proper-list? clause)
                                      (<= (length clause) 2))
                           (syntax-error 'chain-when
                                         "a clause is ([guard] step)"
                                         clause form))
                         (let ((step (s197-single-step
                                      'chain-when
                                      (list-ref clause (- (length clause) 1))
                                      ph var form compare)))
                           (loop (if (null? (cdr clause))
                                     step
                                     (list (rename 'if) (car clause) step var))
                                 (cdr clauses))))))))))))

  ;; (nest [placeholder] step ... initial-value): the last step's placeholder
  ;; is replaced by initial-value, the one before's by that, and so on.
  (define-syntax nest
    (er-macro-transformer
     (lambda (form rename compare)
       (s197-check-initial 'nest form)
       (let* ((args (cdr form))
              (ph? (and (pair? (cdr args)) (symbol? (car args))))
              (ph (if ph? (car args) (rename '_)))
              (args (if ph? (cdr args) args))
              (rev (reverse args)))
         (let loop ((inner (car rev)) (steps (cdr rev)))
           (if (null? steps)
               inner
               (loop (s197-nest-step 'nest (car steps) ph inner form compare)
                     (cdr steps))))))))

  ;; (nest-reverse initial-value [placeholder] step ...): nests in chain's
  ;; order, the first step innermost.
  (define-syntax nest-reverse
    (er-macro-transformer
     (lambda (form rename compare)
       (s197-check-initial 'nest-reverse form)
       (let-values (((steps ph ell) (s197-optional-symbols (cddr form) #f rename)))
         (let loop ((inner (cadr form)) (steps steps))
           (if (null? steps)
               inner
               (loop (s197-nest-step 'nest-reverse (car steps) ph inner form compare)
                     (cdr steps))))))))
  )
