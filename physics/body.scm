;;; (downstroke body): a body's numbers read and checked as every physics rule reads them.
;;;
;;; The hot path reads a dozen numbers per entity per step, so these are
;;; macros: the numbers check-entity-number lets through (fixnums,
;;; bignums, exact rationals, finite flonums) pass a test of their type
;;; tags in C, with no call; anything else goes to check-entity-number,
;;; whose error names the entity and the key. Calling check-entity-number
;;; for every number of a pushed-apart crowd cost a tenth of that scene's
;;; time, and an `or` of predicates compiles to a closure for its join. A
;;; module that uses these includes physics/body.h, where the test is:
;;;   (foreign-declare "#include \"physics/body.h\"")

(module (downstroke body)
  (plain-number? read-number num let-numbers sum
   ;; for sibling modules only: what the macros expand into
   plain-number-bit fxand* overflowed reject-numbers)

  (import scheme (chicken base) (chicken fixnum) (chicken format) (downstroke entity))

  ;; 1 or 0, a fixnum: the type test of physics/body.h, inline.
  (define-syntax plain-number-bit
    (syntax-rules ()
      ((_ v) (##core#inline "ds_plain_number" v))))

  (define-syntax plain-number?
    (syntax-rules ()
      ((_ v) (eq? (plain-number-bit v) 1))))

  ;; (fxand a b ...) for any count, so a test of many values has no branches.
  (define-syntax fxand*
    (syntax-rules ()
      ((_ a) a)
      ((_ a b ...) (fxand a (fxand* b ...)))))

  ;; (read-number e p key): the number in e's pair p for key (0 when e has
  ;; no such pair, p #f).
  (define-syntax read-number
    (syntax-rules ()
      ((_ e p key)
       (let ((pair p))
         (if pair
             (let ((v (cdr pair))) (if (plain-number? v) v (check-entity-number e key v)))
             0)))))

  ;; (num e key): the number entity e holds for key (0 when absent).
  (define-syntax num
    (syntax-rules ()
      ((_ e key) (let ((entity e) (k key)) (read-number entity (assq k entity) k)))))

  ;; (let-numbers e ((var key) ...) body ...): body with each var bound to
  ;; the number entity e holds for key (0 when absent), all checked at once.
  ;; num checks each read with a call on its slow side, and in CHICKEN such
  ;; a call, even one never taken, costs a continuation closure holding
  ;; every live value; here the only call is the report of a bad value, in
  ;; tail position. e must be a variable.
  (define-syntax let-numbers
    (syntax-rules ()
      ((_ e ((var key) ...) body ...)
       (let ((var (let ((p (assq key e))) (if p (cdr p) 0))) ...)
         (if (eq? (fxand* (plain-number-bit var) ...) 1)
             (let () body ...)
             (reject-numbers e (list key ...) (list var ...)))))))

  ;; (sum e key a b): a + b for the step that moves key. A sum of finite
  ;; numbers that overflows to an infinity is that step's error, naming
  ;; the entity and the key, not a failure later in a tile lookup.
  (define-syntax sum
    (syntax-rules ()
      ((_ e key a b)
       (let* ((x a) (y b) (v (+ x y)))
         (if (plain-number? v) v (overflowed e key x y))))))

  (define (overflowed e key a b)
    (error 'downstroke
           (sprintf "entity ~a: ~s overflowed to ~s (~s + ~s); positions and velocities must stay finite"
                    (entity-label e) key (+ a b) a b)))

  ;; The error check-entity-number raises for the first bad value.
  (define (reject-numbers e keys values)
    (for-each (lambda (key v) (check-entity-number e key v)) keys values)
    (error 'reject-numbers "no bad value among" keys values)))
