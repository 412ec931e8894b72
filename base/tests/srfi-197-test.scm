;;; Tests for (downstroke srfi-197): SRFI 197 pipeline operators.
;;; Each example of the SRFI text appears here; expected values were worked
;;; out by hand from the SRFI's stated expansions.
(import (downstroke test) (downstroke util) (downstroke srfi-197)
        scheme (chicken base) (chicken syntax))

;; Procedures for the Rationale examples: each records its name, so the
;; result shows the nesting order.
(define (s197-alpha) '(alpha))
(define (s197-beta x) (cons 'beta x))
(define (s197-gamma x) (cons 'gamma x))
(define (s197-delta x) (cons 'delta x))
(define (s197-epsilon x) (cons 'epsilon x))
(define (s197-zeta x) (cons 'zeta x))
(define (s197-eta x) (cons 'eta x))

(define s197-bowl '())
(define (s197-add item bowl) (cons item bowl))
(define (s197-mix bowl) (list 'mixed bowl))
(define (s197-pour bowl) (list 'poured bowl))
(define (s197-bake thing temp) (list 'baked thing temp))
(define (s197-fahrenheit n) (list 'F n))

;; Expansion errors surface only when the form is expanded, so those tests
;; expand a quoted form at run time (expand only: nothing is evaluated, so a
;; run-time error cannot pass for a syntax error).
(define (s197-expand-error? form)
  (handle-exceptions exn #t
    (expand form)
    #f))

(define (s197-describe-number n)
  (chain-when '()
    ((odd? n) (cons "odd" _))
    ((even? n) (cons "even" _))
    ((zero? n) (cons "zero" _))
    ((positive? n) (cons "positive" _))))

;; The SRFI's hygiene motivation: macros that use chain in their templates.
(define-syntax s197-inc-then-double
  (syntax-rules ()
    ((_ x) (chain x <> (+ <> 1) (* <> 2)))))
(define-syntax s197-inc-twice
  (syntax-rules ()
    ((_ x) (chain x (+ _ 1) (+ _ 1)))))

(test-group "SRFI 197 rationale examples"
  (test "(chain (alpha) (beta _) ... (eta _)) nests like the original"
        '(eta zeta epsilon delta gamma beta alpha)
        (chain (s197-alpha) (s197-beta _) (s197-gamma _) (s197-delta _)
               (s197-epsilon _) (s197-zeta _) (s197-eta _)))
  (test "same as the deeply nested expression"
        (s197-eta (s197-zeta (s197-epsilon (s197-delta (s197-gamma (s197-beta (s197-alpha)))))))
        (chain (s197-alpha) (s197-beta _) (s197-gamma _) (s197-delta _)
               (s197-epsilon _) (s197-zeta _) (s197-eta _)))
  (test "recipe"
        '(baked (poured (mixed (eggs sugar flour))) (F 350))
        (chain s197-bowl
               (s197-add 'flour _)
               (s197-add 'sugar _)
               (s197-add 'eggs _)
               (s197-mix _)
               (s197-pour _)
               (s197-bake _ (s197-fahrenheit 350))))
  (test "recipe equals its let* equivalent"
        (let* ((x s197-bowl)
               (x (s197-add 'flour x))
               (x (s197-add 'sugar x))
               (x (s197-add 'eggs x))
               (x (s197-mix x))
               (x (s197-pour x)))
          (s197-bake x (s197-fahrenheit 350)))
        (chain s197-bowl
               (s197-add 'flour _)
               (s197-add 'sugar _)
               (s197-add 'eggs _)
               (s197-mix _)
               (s197-pour _)
               (s197-bake _ (s197-fahrenheit 350))))
  ;; (1 2 3 4 5) -> (2 3 4 5 6) -> (3 5) -> 15
  (test "list pipeline: map, filter, fold" 15
        (let ((xs '(1 2 3 4 5)))
          (chain xs
                 (map (lambda (x) (+ x 1)) _)
                 (filter odd? _)
                 (fold * 1 _))))
  (test "(chain a (b _) (c _)) is (c (b a))" '(c (b a))
        (let ((a 'a) (b (lambda (x) (list 'b x))) (c (lambda (x) (list 'c x))))
          (chain a (b _) (c _))))
  (test "(chain a (b _) (c _)) evaluates in let* order" '(a b c)
        (let* ((log '())
               (note (lambda (name) (set! log (cons name log)) name))
               (b (lambda (x) (note 'b)))
               (c (lambda (x) (note 'c))))
          (chain (note 'a) (b _) (c _))
          (reverse log)))
  (test "(nest (a _) (b _) c) is (a (b c))" '(a (b c))
        (let ((a (lambda (x) (list 'a x))) (b (lambda (x) (list 'b x))) (c 'c))
          (nest (a _) (b _) c))))

(test-group "SRFI 197 chain examples"
  ;; (chain x (a b _)) => (a b x)
  (test "(chain x (a b _))" '(b x)
        (let ((a list) (b 'b) (x 'x)) (chain x (a b _))))
  ;; => (let* ((x (a b)) (x (c x d))) (e f x))
  (test "(chain (a b) (c _ d) (e f _))" '(f (c (b) d))
        (let ((a list) (b 'b) (c (lambda (x y) (list 'c x y))) (d 'd)
              (e list) (f 'f))
          (chain (a b) (c _ d) (e f _))))
  ;; => (let*-values (((x1 x2) (a)) ((x) (b x1 x2))) (c x))
  (test "(chain (a) (b _ _) (c _))" 30
        (let ((a (lambda () (values 1 2))) (b +) (c (lambda (x) (* x 10))))
          (chain (a) (b _ _) (c _))))
  ;; => (let*-values (((x1 . x2) (a)) ((x) (apply b x1 c x2))) (d x))
  (test "(chain (a) (b _ c _ ...) (d _))" '(3 2 c 1)
        (let ((a (lambda () (values 1 2 3))) (b list) (c 'c) (d reverse))
          (chain (a) (b _ c _ ...) (d _))))
  (test "(chain (a b) <> (c <> d) (e f <>))" '(f (c (b) d))
        (let ((a list) (b 'b) (c (lambda (x y) (list 'c x y))) (d 'd)
              (e list) (f 'f))
          (chain (a b) <> (c <> d) (e f <>))))
  (test "(chain (a) - --- (b - c - ---) (d -))" '(3 2 c 1)
        (let ((a (lambda () (values 1 2 3))) (b list) (c 'c) (d reverse))
          (chain (a) - --- (b - c - ---) (d -)))))

(test-group "chain: placeholders and ellipsis"
  (test "no steps" 7 (chain 7))
  (test "no steps, custom placeholder" 7 (chain 7 <>))
  (test "no steps passes multiple values" '(1 2)
        (call-with-values (lambda () (chain (values 1 2))) list))
  (test "placeholder first argument" -7 (chain 3 (- _ 10)))
  (test "placeholder last argument" 7 (chain 3 (- 10 _)))
  (test "placeholder in operator position" 9 (chain (lambda (x) (* x x)) (_ 3)))
  (test "three placeholders, three values" '(a 1 b 2 c 3)
        (chain (values 1 2 3) (list 'a _ 'b _ 'c _)))
  (test "placeholders as operator and arguments" 7
        (chain (values + 3 4) (_ _ _)))
  (test "step without placeholder ignores values" '(fresh)
        (chain (values 1 2 3) (list 'fresh)))
  (test "step without placeholder still evaluates the previous step" '(ran)
        (let ((log '()))
          (chain (set! log (cons 'ran log)) (list 'x))
          log))
  (test "last step's multiple values are returned" '(2 1)
        (call-with-values (lambda () (chain (values 1 2) (values _ _)))
          (lambda (a b) (list b a))))
  (test "multiple values flow between steps" '(3 1)
        (call-with-values
            (lambda () (chain (values 1 3) (values _ _) (values _ _)))
          (lambda (a b) (list b a))))
  (test "ellipsis takes all values" '(1 2 3)
        (chain (values 1 2 3) (list _ ...)))
  (test "ellipsis takes no values" '(x)
        (chain (values) (list 'x _ ...)))
  (test "ellipsis takes the values after fixed placeholders" '(head 1 tail 2 3)
        (chain (values 1 2 3) (list 'head _ 'tail _ ...)))
  (test "ellipsis with exactly the fixed values" '(1 2)
        (chain (values 1 2) (list _ _ _ ...)))
  (test "ellipsis after placeholder operator" 10
        (chain (values + 1 2 3 4) (_ _ ...)))
  (test "lone placeholder and ellipsis: first value is the procedure" 6
        (chain (values * 2 3) (_ ...)))
  (test "ellipsis in the middle of a chain" 6
        (chain (values 1 2 3) (+ _ ...) (* _ 1)))
  (test "chain with util procedures" '(0 4 16)
        (chain (iota 5) (filter even? _) (map (lambda (x) (* x x)) _)))
  ;; Only a step's own elements are placeholders; one inside a nested
  ;; expression is an ordinary reference (here to a variable named <>).
  (test "placeholder inside a nested expression is not replaced" '(inner)
        (let ((<> 'inner)) (chain 1 <> (list (begin <>)))))
  ;; Placeholders are matched like syntax-rules literals: a lexically bound
  ;; _ is that variable, so this step has no placeholder.
  (test "a lexically bound _ is a variable" 6
        (let ((_ 5)) (chain 1 (+ _ 1))))
  (test "wrong number of values is an error" #t
        (handle-exceptions exn #t (chain 1 (list _ _)) #f))
  (test "custom placeholder in a syntax-rules template" 8 (s197-inc-then-double 3))
  (test "default placeholder in a syntax-rules template" 3 (s197-inc-twice 1))
  (test "user bindings of apply, car, cdr, let do not capture the expansion"
        '(6 (1 2))
        (let ((apply #f) (car #f) (cdr #f) (call-with-values #f))
          (list (chain (values * 2 3) (_ ...))
                (chain (values 1 2) (list _ ...))))))

(test-group "chain: syntax errors"
  (test "ellipsis not at the end" #t (s197-expand-error? '(chain 1 (list _ ... 2))))
  (test "ellipsis without placeholder before it" #t
        (s197-expand-error? '(chain 1 (list 2 ...))))
  (test "empty step" #t (s197-expand-error? '(chain 1 ())))
  (test "step that is not a list" #t (s197-expand-error? '(chain 1 _ ... 5)))
  (test "well-formed form expands" #f (s197-expand-error? '(chain 1 (list _ ...)))))

(test-group "SRFI 197 chain-and"
  (test "all steps succeed" 6 (chain-and 1 (+ _ 1) (* _ 3)))
  (test "no steps" 5 (chain-and 5))
  (test "no steps, #f" #f (chain-and #f))
  (test "step returning #f stops the chain" '(#f (a))
        (let* ((log '())
               (note (lambda (x) (set! log (cons x log)) x)))
          (list (chain-and 1 (and (note 'a) #f) (note 'b))
                log)))
  (test "#f initial value runs no step" '(#f ())
        (let* ((log '())
               (note (lambda (x) (set! log (cons x log)) x)))
          (list (chain-and #f (note _)) log)))
  (test "step without placeholder still checks its pipeline value" #f
        (chain-and 1 (memv 9 '(1 2)) (list 'unreached)))
  (test "step without placeholder runs when the value is true" '(ok)
        (chain-and 1 (memv 1 '(1 2)) (list 'ok)))
  (test "last step may return #f" #f (chain-and 1 (+ _ 1) (odd? _)))
  (test "placeholder in first position" 10 (chain-and (lambda (x) (* 2 x)) (_ 5)))
  (test "custom placeholder" 2 (chain-and '(1 2) <> (memv 2 <>) (car <>)))
  (test "assoc chain" "v"
        (chain-and '((k . "v")) (assq 'k _) (cdr _)))
  (test "assoc chain fails" #f
        (chain-and '((k . "v")) (assq 'missing _) (cdr _)))
  (test "user binding of if does not capture the expansion" 3
        (let ((if list)) (chain-and 1 (+ _ 2))))
  (test "two placeholders in a step is a syntax error" #t
        (s197-expand-error? '(chain-and 1 (+ _ _)))))

(test-group "SRFI 197 chain-when"
  (test "describe-number 3" '("positive" "odd") (s197-describe-number 3))
  (test "describe-number 4" '("positive" "even") (s197-describe-number 4))
  (test "describe-number 0" '("zero" "even") (s197-describe-number 0))
  (test "describe-number -3" '("odd") (s197-describe-number -3))
  (test "no clauses" 5 (chain-when 5))
  (test "all skipped returns the initial value" 5
        (chain-when 5 (#f (+ _ 1)) (#f (* _ 2))))
  (test "clause without guard always runs" 20
        (chain-when 1 (#t (+ _ 1)) (#f (* _ 100)) ((* _ 10))))
  (test "custom placeholder" 20
        (chain-when 1 <> (#t (+ <> 1)) (#f (* <> 100)) ((* <> 10))))
  (test "step without placeholder ignores its value" 'fresh
        (chain-when 1 (#t (values 'fresh))))
  (test "guards are evaluated in order, and skipped steps not at all" '((g1 s1 g2) 2)
        (let* ((log '())
               (note (lambda (x) (set! log (cons x log)) x)))
          (let ((r (chain-when 1
                     ((note 'g1) (+ (begin (note 's1) 1) _))
                     ((begin (note 'g2) #f) (* (begin (note 's2) 100) _)))))
            (list (reverse log) r))))
  (test "a skipped step passes its value to the next" 4
        (chain-when 1 (#t (+ _ 1)) (#f (* _ 100)) (#t (* _ 2))))
  (test "two placeholders in a step is a syntax error" #t
        (s197-expand-error? '(chain-when 1 (#t (+ _ _)))))
  (test "a clause of three parts is a syntax error" #t
        (s197-expand-error? '(chain-when 1 (#t #t (+ _ 1))))))

(test-group "SRFI 197 chain-lambda"
  ;; (chain-lambda (a _) (b _)) => (lambda (x) (let* ((x (a x))) (b x)))
  (test "(chain-lambda (a _) (b _))" 11
        (let ((a (lambda (x) (* x 2))) (b (lambda (x) (+ x 1))))
          ((chain-lambda (a _) (b _)) 5)))
  ;; (chain-lambda (a _ _) (b c _)) => (lambda (x1 x2) (let* ((x (a x1 x2))) (b c x)))
  (test "(chain-lambda (a _ _) (b c _))" '(c 3)
        (let ((a +) (b list) (c 'c))
          ((chain-lambda (a _ _) (b c _)) 1 2)))
  (test "arity from the first step" #t
        (handle-exceptions exn #t ((chain-lambda (+ _ _) (* _ 2)) 1) #f))
  (test "first step without placeholder: a thunk" '(x)
        ((chain-lambda (list 'x))))
  (test "ellipsis makes it variadic" 4
        ((chain-lambda (list _ ...) (length _)) 'a 'b 'c 'd))
  (test "variadic with no arguments" 0
        ((chain-lambda (list _ ...) (length _))))
  (test "fixed and rest arguments" '(1 rest 2 3)
        ((chain-lambda (list _ 'rest _ ...)) 1 2 3))
  (test "custom placeholder and ellipsis" '(3 2 1)
        ((chain-lambda % %% (list % %%) (reverse %)) 1 2 3))
  (test "multiple values between steps" 7
        ((chain-lambda (values _ _) (+ _ _)) 3 4))
  (test "a fresh procedure each call" '(2 3)
        (map (chain-lambda (+ _ 1)) '(1 2)))
  (test "no steps is a syntax error" #t (s197-expand-error? '(chain-lambda))))

(test-group "SRFI 197 nest"
  ;; (nest (a b _) (c d _) e) => (a b (c d e))
  (test "(nest (a b _) (c d _) e)" '(b (d e))
        (let ((a list) (b 'b) (c list) (d 'd) (e 'e))
          (nest (a b _) (c d _) e)))
  (test "(nest '_ (1 2 _) (3 _ 5) (_) 4)" '(1 2 (3 (4) 5))
        (nest '_ (1 2 _) (3 _ 5) (_) 4))
  (test "nested nest with a custom placeholder" '(1 2 3 (4 5 6))
        (nest (nest _2 '_2 (1 2 3 _2) _ 6)
              (_ 5 _2)
              4))
  (test "initial value only" 4 (nest 4))
  (test "placeholder and initial value only" 4 (nest <> 4))
  (test "custom placeholder" 7 (nest <> (+ <> 1) (* <> 2) 3))
  (test "special forms: let and if" 6
        (nest (let ((y 2)) _) (if #t _ 'no) (* y 3)))
  (test "special forms: lambda" 16
        ((nest (lambda (x) _) (* x x)) 4))
  (test "placeholder first in a step" 9
        (nest (_ 3) (lambda (x) (* x x))))
  (test "nest does not evaluate the initial value first" '(outer inner)
        ;; it literally nests: here the outer form runs its body before
        ;; evaluating the inner one.
        (let ((log '()))
          (nest (begin (set! log (cons 'outer log)) _)
                (begin (set! log (cons 'inner log)) 'v))
          (reverse log)))
  (test "step without placeholder is a syntax error" #t
        (s197-expand-error? '(nest (list 1) 2)))
  (test "step with two placeholders is a syntax error" #t
        (s197-expand-error? '(nest (list _ _) 2))))

(test-group "SRFI 197 nest-reverse"
  ;; (nest-reverse e (c d _) (a b _)) => (a b (c d e))
  (test "(nest-reverse e (c d _) (a b _))" '(b (d e))
        (let ((a list) (b 'b) (c list) (d 'd) (e 'e))
          (nest-reverse e (c d _) (a b _))))
  (test "same as nest with steps reversed" '(1 2 (3 (4) 5))
        (nest-reverse 4 (_) (3 _ 5) (1 2 _) '_))
  (test "initial value only" 4 (nest-reverse 4))
  (test "custom placeholder" 20 (nest-reverse 1 <> (+ <> 1) (* <> 10)))
  (test "special forms" 10
        (nest-reverse (* y 5) (let ((y 2)) _)))
  (test "step without placeholder is a syntax error" #t
        (s197-expand-error? '(nest-reverse 2 (list 1)))))
