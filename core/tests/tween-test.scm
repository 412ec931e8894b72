(import (downstroke test) (downstroke entity) (downstroke tween)
        scheme (chicken base) (chicken string) (chicken format) (chicken condition))

;;; Helpers (prefixed tw- because every suite is loaded into one toplevel).

;; The error's text contains every one of `parts`.
(define (tw-says? . parts)
  (lambda (exn)
    (let ((text (error-text exn)))
      (let loop ((parts parts))
        (or (null? parts)
            (and (substring-index (car parts) text) (loop (cdr parts))))))))

;; Raised by procedure `who`, and the error's text contains every one of `parts`.
(define (tw-raised? who . parts)
  (lambda (exn)
    (and (eq? who ((condition-property-accessor 'exn 'location #f) exn))
         ((apply tw-says? parts) exn))))

;; Step `t` over `e` once per dt in `dts`; returns (values tween entity).
(define (tw-run t e dts)
  (if (null? dts)
      (values t e)
      (let-values (((t2 e2) (tween-step t e (car dts))))
        (tw-run t2 e2 (cdr dts)))))

(define (tw-repeat n x)
  (let loop ((n n) (out '()))
    (if (= n 0) out (loop (- n 1) (cons x out)))))

;; The value of `key` after each of `n` steps of `dt`.
(define (tw-trace t e key n dt)
  (let loop ((i 0) (t t) (e e) (out '()))
    (if (= i n)
        (reverse out)
        (let-values (((t2 e2) (tween-step t e dt)))
          (loop (+ i 1) t2 e2 (cons (entity-ref e2 key) out))))))

;; The tween after `dts`, and the value of `key`.
(define (tw-value t e key dts)
  (let-values (((t2 e2) (tw-run t e dts)))
    (entity-ref e2 key)))

(define (tw-finished-after t e dts)
  (let-values (((t2 e2) (tw-run t e dts)))
    (tween-finished? t2)))

;; Number of steps of `dt` until the tween finishes, or #f within `limit`.
(define (tw-steps-to-finish t e dt limit)
  (let loop ((i 0) (t t) (e e))
    (cond ((tween-finished? t) i)
          ((= i limit) #f)
          (else (let-values (((t2 e2) (tween-step t e dt)))
                  (loop (+ i 1) t2 e2))))))

(define tw-box '((#:type . box) (#:id . 7) (#:x . 0) (#:y . 10) (#:vx . 0)))

(define (tw-x target . options)
  (apply make-tween tw-box props: (list (cons #:x target)) options))

(define tw-families '(quad cubic quart quint sine expo circ back elastic bounce))
(define tw-monotone '(linear quad cubic quart quint sine expo circ))

(define (tw-names family)
  (if (eq? family 'linear)
      '(linear)
      (map (lambda (suffix) (symbol-append family suffix)) '(-in -out -in-out))))

(define (tw-ease name) (cdr (assq name *ease-table*)))

(define (tw-samples n) ; 0, 1/n, ..., 1 exact
  (let loop ((i n) (out '()))
    (if (< i 0) out (loop (- i 1) (cons (/ i n) out)))))

;;; ------------------------------------------------------------------

(test-group "easing table"
  (test-assert "linear is in the table" (assq 'linear *ease-table*))
  (for-each
   (lambda (family)
     (for-each (lambda (name)
                 (test-assert (sprintf "~a is in the table" name) (assq name *ease-table*)))
               (tw-names family)))
   tw-families)
  (test "31 easings: linear + 10 families x 3" 31 (length *ease-table*))
  (for-each
   (lambda (entry)
     (let ((name (car entry)) (f (cdr entry)))
       (test (sprintf "~a maps 0 to exact 0" name) #t (eqv? 0 (f 0)))
       (test (sprintf "~a maps 1 to exact 1" name) #t (eqv? 1 (f 1)))
       (test (sprintf "~a maps 0.0 to exactly 0" name) #t (= 0 (f 0.0)))
       (test (sprintf "~a maps 1.0 to exactly 1" name) #t (= 1 (f 1.0)))))
   *ease-table*)

  (test-group "exact values of the polynomial easings"
    (test "linear 1/3" 1/3 ((tw-ease 'linear) 1/3))
    (test "quad-in 1/3" 1/9 ((tw-ease 'quad-in) 1/3))
    (test "quad-out 1/3 = 1 - (2/3)^2" 5/9 ((tw-ease 'quad-out) 1/3))
    (test "quad-in-out 1/4 = 2 (1/4)^2" 1/8 ((tw-ease 'quad-in-out) 1/4))
    (test "quad-in-out 1/2" 1/2 ((tw-ease 'quad-in-out) 1/2))
    (test "quad-in-out 3/4 = 1 - (1/2)^2 / 2" 7/8 ((tw-ease 'quad-in-out) 3/4))
    (test "cubic-in 1/2" 1/8 ((tw-ease 'cubic-in) 1/2))
    (test "cubic-out 1/2" 7/8 ((tw-ease 'cubic-out) 1/2))
    (test "cubic-in-out 1/4 = 4 (1/4)^3" 1/16 ((tw-ease 'cubic-in-out) 1/4))
    (test "quart-in 1/2" 1/16 ((tw-ease 'quart-in) 1/2))
    (test "quart-out 1/2" 15/16 ((tw-ease 'quart-out) 1/2))
    (test "quart-in-out 1/4 = 8 (1/4)^4" 1/32 ((tw-ease 'quart-in-out) 1/4))
    (test "quint-in 1/2" 1/32 ((tw-ease 'quint-in) 1/2))
    (test "quint-out 1/2" 31/32 ((tw-ease 'quint-out) 1/2))
    (test "quint-in-out 3/4 = 1 - (1/2)^5 / 2" 63/64 ((tw-ease 'quint-in-out) 3/4))
    (test "bounce-out 1/2 (second arc)" 49/64 ((tw-ease 'bounce-out) 1/2))
    (for-each
     (lambda (family)
       (for-each (lambda (name)
                   (test-assert (sprintf "~a stays exact on exact input" name)
                     (let loop ((ts (tw-samples 60)))
                       (or (null? ts)
                           (and (exact? ((tw-ease name) (car ts))) (loop (cdr ts)))))))
                 (tw-names family)))
     '(linear quad cubic quart quint bounce)))

  (test-group "shapes"
    (for-each
     (lambda (family)
       (for-each
        (lambda (name)
          (test-assert (sprintf "~a never decreases over 401 samples" name)
            (let loop ((ts (tw-samples 400)) (prev -1))
              (or (null? ts)
                  (let ((v ((tw-ease name) (car ts))))
                    (and (>= v prev) (loop (cdr ts) v))))))
          (test-assert (sprintf "~a stays within [0,1]" name)
            (let loop ((ts (tw-samples 400)))
              (or (null? ts)
                  (let ((v ((tw-ease name) (car ts))))
                    (and (<= 0 v 1) (loop (cdr ts))))))))
        (tw-names family)))
     tw-monotone)
    (test-assert "back-in overshoots below 0" (< ((tw-ease 'back-in) 0.2) 0))
    (test-assert "back-in goes below 0 and comes back"
      (and (< ((tw-ease 'back-in) 0.5) 0) (> ((tw-ease 'back-in) 0.9) 0)))
    (test-assert "back-out overshoots above 1" (> ((tw-ease 'back-out) 0.8) 1))
    (test-assert "back-in-out dips below 0 and overshoots above 1"
      (and (< ((tw-ease 'back-in-out) 0.1) 0) (> ((tw-ease 'back-in-out) 0.9) 1)))
    (test-assert "elastic-out overshoots above 1"
      (let loop ((ts (tw-samples 100)))
        (and (pair? ts) (or (> ((tw-ease 'elastic-out) (car ts)) 1) (loop (cdr ts))))))
    (test-assert "elastic-in goes below 0"
      (let loop ((ts (tw-samples 100)))
        (and (pair? ts) (or (< ((tw-ease 'elastic-in) (car ts)) 0) (loop (cdr ts))))))
    (test-assert "bounce-out stays within [0,1] and is not monotone"
      (let loop ((ts (tw-samples 400)) (prev -1) (dropped? #f))
        (if (null? ts)
            dropped?
            (let ((v ((tw-ease 'bounce-out) (car ts))))
              (and (<= 0 v 1) (loop (cdr ts) v (or dropped? (< v prev))))))))
    (test "every in-out easing passes through 1/2 at 1/2" '()
          (let loop ((entries *ease-table*) (bad '()))
            (cond ((null? entries) (reverse bad))
                  ((and (substring-index "-in-out" (symbol->string (caar entries)))
                        (not (= 1/2 ((cdar entries) 1/2))))
                   (loop (cdr entries) (cons (caar entries) bad)))
                  (else (loop (cdr entries) bad))))))

  (test-group "ease-procedure"
    (test-assert "a symbol gives the table's procedure"
      (eq? (tw-ease 'cubic-out) (ease-procedure 'cubic-out)))
    (let ((f (lambda (t) t)))
      (test-assert "a procedure is returned as is" (eq? f (ease-procedure f))))
    (test-error "an unknown symbol names it" (tw-says? "wobble-in") (ease-procedure 'wobble-in))
    (test-error "a non-symbol names it" (tw-says? "42") (ease-procedure 42))))

(test-group "make-tween"
  (let ((t (tw-x 100)))
    (test-assert "makes a tween" (tween? t))
    (test-assert "not finished when made" (not (tween-finished? t)))
    (test-assert "active at once without a delay" (tween-active? t)))
  (let ((t (tw-x 100 delay: 10)))
    (test-assert "not active while the delay runs" (not (tween-active? t)))
    (test-assert "not finished while the delay runs" (not (tween-finished? t))))
  (test-assert "the defaults: 500 ms, linear"
    (equal? '(50 100) (tw-trace (tw-x 100) tw-box #:x 2 250)))
  (test-assert "an entity given as a plist works"
    (tween? (make-tween '(#:x 1 #:y 2) props: '((#:x . 5)))))
  (test-assert "no props makes a plain timer"
    (let ((t (make-tween tw-box props: '() duration: 10)))
      (let-values (((t2 e2) (tween-step t tw-box 10)))
        (and (tween-finished? t2) (equal? e2 tw-box)))))
  (test-assert "a tween is not an entity alist" (not (entity? (tw-x 100))))
  (test "tween-step accepts a plist entity and returns an alist" '((#:x . 3) (#:y . 2))
        (let-values (((t2 e2) (tween-step (make-tween '(#:x 1 #:y 2) props: '((#:x . 5)) duration: 4)
                                          '(#:x 1 #:y 2) 2)))
          e2))
  (test "tween-step with a plist, run to the end" '(#t ((#:x . 5) (#:y . 2)))
        (let-values (((t2 e2) (tween-step (make-tween '(#:x 1 #:y 2) props: '((#:x . 5)) duration: 4)
                                          '(#:x 1 #:y 2) 10)))
          (list (tween-finished? t2) e2)))
  (test "tween-step with a plist while the delay runs returns it as an alist" '((#:x . 1))
        (let-values (((t2 e2) (tween-step (make-tween '(#:x 1) props: '((#:x . 5)) delay: 10)
                                          '(#:x 1) 2)))
          e2))

  (test-group "bad arguments raise errors naming them"
    (test-error "props missing" (tw-says? "props") (make-tween tw-box duration: 10))
    (test-error "props not a list" (tw-says? "props" "foo") (make-tween tw-box props: 'foo))
    (test-error "a prop that is not a pair" (tw-says? "props" "#:x")
                (make-tween tw-box props: '(#:x 100)))
    (test-error "a prop key that is not a keyword" (tw-says? "props" "x")
                (make-tween tw-box props: '((x . 100))))
    (test-error "a target that is not a number" (tw-says? "#:x" "far")
                (make-tween tw-box props: '((#:x . far))))
    (test-error "an infinite target" (tw-says? "#:x" "+inf.0")
                (make-tween tw-box props: `((#:x . ,(/ 1. 0.)))))
    (test-error "a key given twice" (tw-says? "#:x" "twice")
                (make-tween tw-box props: '((#:x . 1) (#:x . 2))))
    (test-error "a key the entity lacks names the key and the entity"
                (tw-says? "#:z" "box 7")
                (make-tween tw-box props: '((#:z . 1))))
    (test-error "a start value that is NaN names the key and the entity"
                (tw-says? "#:x" "box 7" "nan")
                (make-tween (entity-set tw-box #:x (/ 0. 0.)) props: '((#:x . 1))))
    (test-error "a start value that is not a number names the key and the entity"
                (tw-says? "#:y" "box 7" "high")
                (make-tween (entity-set tw-box #:y 'high) props: '((#:y . 1))))
    (test-error "negative duration" (tw-says? "duration" "-1") (tw-x 1 duration: -1))
    (test-error "symbolic duration" (tw-says? "duration" "fast") (tw-x 1 duration: 'fast))
    (test-error "infinite duration" (tw-says? "duration" "inf") (tw-x 1 duration: (/ 1. 0.)))
    (test-error "negative delay" (tw-says? "delay" "-5") (tw-x 1 delay: -5))
    (test-error "repeat below -1" (tw-says? "repeat" "-2") (tw-x 1 repeat: -2))
    (test-error "fractional repeat" (tw-says? "repeat" "1.5") (tw-x 1 repeat: 1.5))
    (test-error "symbolic repeat" (tw-says? "repeat" "twice") (tw-x 1 repeat: 'twice))
    (test-error "repeat forever with duration 0" (tw-says? "repeat" "duration")
                (tw-x 1 repeat: -1 duration: 0))
    (test-error "yoyo? not a boolean" (tw-says? "yoyo?" "yes") (tw-x 1 yoyo?: 'yes))
    (test-error "on-complete not a procedure" (tw-says? "on-complete" "5")
                (tw-x 1 on-complete: 5))
    (test-error "an unknown easing names the symbol" (tw-says? "ease" "wobble")
                (tw-x 1 ease: 'wobble))
    (test-error "an easing that is neither symbol nor procedure" (tw-says? "ease" "42")
                (tw-x 1 ease: 42))
    (test-error "tween-step: negative dt" (tw-says? "dt" "-1")
                (tween-step (tw-x 1) tw-box -1))
    (test-error "tween-step: NaN dt" (tw-says? "dt" "nan")
                (tween-step (tw-x 1) tw-box (/ 0. 0.)))
    (test-error "tween-step: not a tween" (tw-says? "tween" "oops")
                (tween-step 'oops tw-box 1))
    (test-error "tween-step: an entity that is neither alist nor plist"
                (tw-raised? 'tween-step "entity" "oops")
                (tween-step (tw-x 1) 'oops 1))
    (test-error "tween-step: a list of numbers is not an entity"
                (tw-raised? 'tween-step "entity" "(1 2)")
                (tween-step (tw-x 1) '(1 2) 1))))

(test-group "values mid-tween"
  (test "linear, 16 ms of 300: 100 * 16/300" 16/3
        (tw-value (tw-x 100 duration: 300) tw-box #:x '(16)))
  (test "linear, 32 ms of 300" 32/3
        (tw-value (tw-x 100 duration: 300) tw-box #:x '(16 16)))
  (test "linear, from a non-zero start: 10 + 10 * 1/3" 40/3
        (tw-value (make-tween '((#:x . 10)) props: '((#:x . 20)) duration: 3) '((#:x . 10)) #:x '(1)))
  (test "linear, downwards: 0 -> -60 over 90, 30 ms" -20
        (tw-value (tw-x -60 duration: 90) tw-box #:x '(30)))
  (test "linear trace 0 -> 100 over 10 ms by 1 ms" '(10 20 30 40 50 60 70 80 90 100 100)
        (tw-trace (tw-x 100 duration: 10) tw-box #:x 11 1))
  (test "quad-in, 16 ms of 300: 90 * (4/75)^2" 32/125
        (tw-value (tw-x 90 duration: 300 ease: 'quad-in) tw-box #:x '(16)))
  (test "quad-in thirds: 90 * 1/9, 90 * 4/9, 90" '(10 40 90)
        (tw-trace (tw-x 90 duration: 300 ease: 'quad-in) tw-box #:x 3 100))
  (test "quad-out thirds: 90 * 5/9, 90 * 8/9, 90" '(50 80 90)
        (tw-trace (tw-x 90 duration: 300 ease: 'quad-out) tw-box #:x 3 100))
  (test "quad-in-out quarters: 80 * 1/8, 1/2, 7/8, 1" '(10 40 70 80)
        (tw-trace (tw-x 80 duration: 400 ease: 'quad-in-out) tw-box #:x 4 100))
  (test "quad-in-out, 16 ms of 400: 80 * 2 (1/25)^2" 32/125
        (tw-value (tw-x 80 duration: 400 ease: 'quad-in-out) tw-box #:x '(16)))
  (test-assert "exact inputs give exact values"
    (let loop ((vs (tw-trace (tw-x 90 duration: 300 ease: 'quad-in-out) tw-box #:x 40 7)))
      (or (null? vs) (and (exact? (car vs)) (loop (cdr vs))))))
  (test "an inexact dt gives inexact values" 5.333333333
        (tw-value (tw-x 100 duration: 300) tw-box #:x '(16.0)))
  (test "a custom easing procedure is used" 25
        (tw-value (tw-x 100 duration: 10 ease: (lambda (t) (* t t))) tw-box #:x '(5)))
  (test "several props move together" '(25 35)
        (let-values (((t e) (tw-run (make-tween tw-box props: '((#:x . 100) (#:y . 110)) duration: 100)
                                    tw-box '(25))))
          (list (entity-ref e #:x) (entity-ref e #:y))))
  (test "keys that are not props are untouched" '(box 7 0)
        (let-values (((t e) (tw-run (tw-x 100 duration: 100) tw-box '(25 25))))
          (list (entity-ref e #:type) (entity-ref e #:id) (entity-ref e #:vx))))
  (test "dt 0 on a fresh tween writes the start value" 0
        (tw-value (tw-x 100 duration: 10) (entity-set tw-box #:x 55) #:x '(0)))
  (test "the end value is the target exactly, even if ease(1) is not 1" 100
        (tw-value (tw-x 100 duration: 10 ease: (lambda (t) (* t 9/10))) tw-box #:x '(4 6)))
  (test "the end value is the target exactly with floats: 1e16 -> 1.0" #t
        (eqv? 1.0 (tw-value (make-tween '((#:x . 1e16)) props: '((#:x . 1.0)) duration: 3.0)
                            '((#:x . 1e16)) #:x '(1.0 1.0 1.0))))
  (test-assert "the inputs are not changed"
    (let* ((e (append tw-box '()))
           (t (tw-x 100 duration: 10)))
      (let-values (((t2 e2) (tween-step t e 5)))
        (and (equal? e tw-box)
             (not (tween-finished? t))
             ;; stepping the same tween again gives the same result
             (= 50 (tw-value t e #:x '(5))))))))

(test-group "delay"
  (let ((t (tw-x 100 duration: 100 delay: 50)))
    (test-assert "three 16 ms steps inside a 50 ms delay write nothing"
      (let-values (((t2 e2) (tw-run t tw-box '(16 16 16))))
        (and (eq? e2 tw-box) (not (tween-active? t2)) (not (tween-finished? t2)))))
    (test "the fourth step is 14 ms into the run" 14 (tw-value t tw-box #:x '(16 16 16 16)))
    (test-assert "active once the delay is over"
      (let-values (((t2 e2) (tw-run t tw-box '(16 16 16 16)))) (tween-active? t2)))
    (test "a key changed during the delay is left alone" 999
          (let-values (((t2 e2) (tw-run t tw-box '(16 16))))
            (tw-value t2 (entity-set e2 #:x 999) #:x '(16))))
    (test "the tween starts from the value the entity had when it was made" 14
          (let-values (((t2 e2) (tw-run t tw-box '(16 16))))
            (tw-value t2 (entity-set e2 #:x 999) #:x '(16 16)))))
  (test "leftover delay time carries into the run: delay 5, dt 8" 30
        (tw-value (tw-x 100 duration: 10 delay: 5) tw-box #:x '(8)))
  (test "the delay applies once, not before each repeat" 6
        (tw-steps-to-finish (tw-x 100 duration: 10 delay: 10 repeat: 1) tw-box 5 100))
  (test "delay then repeat, traced: the end of the first run shows" '(0 0 50 100 50 100)
        (tw-trace (tw-x 100 duration: 10 delay: 10 repeat: 1) tw-box #:x 6 5)))

(test-group "repeat"
  (test "repeat 0: one run of 10 steps" 10 (tw-steps-to-finish (tw-x 100 duration: 10) tw-box 1 1000))
  (test "repeat 2: three runs, 30 steps" 30
        (tw-steps-to-finish (tw-x 100 duration: 10 repeat: 2) tw-box 1 1000))
  (test "repeat 2: not finished after 29 ms" #f
        (tw-finished-after (tw-x 100 duration: 10 repeat: 2) tw-box (tw-repeat 29 1)))
  (test "repeat 5 with 16 ms steps over 100 ms runs: ceiling(600/16) steps" 38
        (tw-steps-to-finish (tw-x 100 duration: 100 repeat: 5) tw-box 16 1000))
  (test "each run restarts from the start, after its end showed" '(80 90 100 10 20)
        (list-tail (tw-trace (tw-x 100 duration: 10 repeat: 2) tw-box #:x 12 1) 7))
  (test "and the third run too" '(90 100 10)
        (list-tail (tw-trace (tw-x 100 duration: 10 repeat: 2) tw-box #:x 21 1) 18))
  (test "a repeating tween ends on the target" 100
        (tw-value (tw-x 100 duration: 10 repeat: 2) tw-box #:x (tw-repeat 40 1)))
  (let ((t (tw-x 100 duration: 7 repeat: -1 ease: 'quad-in-out)))
    (test "repeat -1 never finishes over 10,000 steps" #f
          (tw-steps-to-finish t tw-box 1 10000))
    (test-assert "repeat -1 keeps values within [start, target] over 10,000 steps"
      (let loop ((i 0) (t t) (e tw-box))
        (or (= i 10000)
            (let-values (((t2 e2) (tween-step t e 3)))
              (and (<= 0 (entity-ref e2 #:x) 100) (tween-active? t2)
                   (loop (+ i 1) t2 e2))))))
    (test "repeat -1 after 10,000 ms of 7 ms runs: 4 ms into a run, 100 * (1 - (3/7)^2 * 2)" 3100/49
          (tw-value t tw-box #:x (tw-repeat 10000 1)))))

(test-group "yoyo"
  (let ((t (tw-x 100 duration: 10 repeat: 1 yoyo?: #t)))
    (test "two runs go there and back" '(50 100 50 0)
          (tw-trace t tw-box #:x 4 5))
    (test "two runs take 20 ms" 20 (tw-steps-to-finish t tw-box 1 1000))
    (test "a step across the turn shows the turn" 100 (tw-value t tw-box #:x '(12)))
    (test "and the next step goes on from 12 ms, the way back" 80 (tw-value t tw-box #:x '(12 0))))
  (test "an even number of runs (2) ends on the start" 0
        (tw-value (tw-x 100 duration: 10 repeat: 1 yoyo?: #t) tw-box #:x '(7 7 7)))
  (test "an even number of runs (4) ends on the start" 0
        (tw-value (tw-x 100 duration: 10 repeat: 3 yoyo?: #t ease: 'quad-in) tw-box #:x (tw-repeat 50 1)))
  (test "an odd number of runs (3) ends on the target" 100
        (tw-value (tw-x 100 duration: 10 repeat: 2 yoyo?: #t) tw-box #:x (tw-repeat 50 1)))
  (test "an even number of runs ends on a non-zero start exactly" 3/7
        (let ((e (entity-set tw-box #:x 3/7)))
          (tw-value (make-tween e props: '((#:x . 100)) duration: 9 repeat: 1 yoyo?: #t
                                ease: 'cubic-out)
                    e #:x (tw-repeat 4 5))))
  (test "the return retraces the curve: quad-in 3 ms back is 100 * (7/10)^2" 49
        (tw-value (tw-x 100 duration: 10 repeat: 1 yoyo?: #t ease: 'quad-in) tw-box #:x '(13 0)))
  (test "yoyo forever passes the ends at every run boundary" '(100 0 100 0)
        (let ((vs (tw-trace (tw-x 100 duration: 10 repeat: -1 yoyo?: #t) tw-box #:x 40 1)))
          (map (lambda (i) (list-ref vs i)) '(9 19 29 39)))))

(test-group "leftover time carries over"
  (test "6 ms steps over 10 ms runs: the end shows, then 8 ms into the second run" '(60 100 80 100)
        (tw-trace (tw-x 100 duration: 10 repeat: 1) tw-box #:x 4 6))
  (test "one large step skips whole runs: 35 ms of 10 ms runs is 5 ms into the 4th" 50
        (tw-value (tw-x 100 duration: 10 repeat: 5) tw-box #:x '(35 0)))
  (test-assert "... and the tween is still running"
    (not (tw-finished-after (tw-x 100 duration: 10 repeat: 5) tw-box '(35))))
  (test "a step past the end finishes exactly on the end value" 100
        (tw-value (tw-x 100 duration: 10 repeat: 1) tw-box #:x '(1000)))
  (let ((make (lambda () (make-tween tw-box props: '((#:x . 100) (#:y . -30)) duration: 10
                                      delay: 3 repeat: 4 yoyo?: #t ease: 'quad-in-out))))
    (define (state dts)
      (let-values (((t e) (tw-run (make) tw-box dts)))
        (list (entity-ref e #:x) (entity-ref e #:y) (tween-finished? t))))
    ;; (a step that ends a run shows that end: a last step of 0 shows where the clock is)
    (test "how 40 ms are split does not matter (one step vs 1 ms steps)"
          (state '(40 0)) (state (append (tw-repeat 40 1) '(0))))
    (test "how 40 ms are split does not matter (uneven steps)"
          (state '(40 0)) (state '(2 9 1 13 0 15 0)))
    (test "40 ms: delay 3, three runs, 7 ms into the 4th, a return: quad-in-out(3/10) = 9/50"
          '(18 14/5 #f) (state '(40 0)))
    (test "the step of 40 ms ends the third run, a forward one: it shows the targets"
          '(100 -30 #f) (state '(40)))))

(test-group "duration 0"
  (test "the first step reaches the target" 100 (tw-value (tw-x 100 duration: 0) tw-box #:x '(16)))
  (test-assert "... and finishes" (tw-finished-after (tw-x 100 duration: 0) tw-box '(16)))
  (test-assert "even with dt 0" (tw-finished-after (tw-x 100 duration: 0) tw-box '(0)))
  (test "with a delay, nothing before it ends" 0 (tw-value (tw-x 100 duration: 0 delay: 10) tw-box #:x '(5)))
  (test "with a delay, the target when it ends" 100
        (tw-value (tw-x 100 duration: 0 delay: 10) tw-box #:x '(5 5)))
  (test "yoyo with an even number of runs ends on the start" 0
        (tw-value (tw-x 100 duration: 0 repeat: 1 yoyo?: #t) tw-box #:x '(1))))

(test-group "step-tweens"
  (define (with-tween e . args)
    (entity-set e #:tween (apply make-tween e args)))
  (define (run-steps e n dt)
    (if (= n 0) e (run-steps (step-tweens #f e dt) (- n 1) dt)))
  (let ((e (with-tween tw-box props: '((#:x . 100)) duration: 100)))
    (test "advances the entity's tween" 16 (entity-ref (step-tweens #f e 16) #:x))
    (test-assert "writes the advanced tween back"
      (let ((e2 (step-tweens #f e 16)))
        (and (tween? (entity-ref e2 #:tween))
             (not (eq? (entity-ref e2 #:tween) (entity-ref e #:tween)))
             (= 32 (entity-ref (step-tweens #f e2 16) #:x)))))
    (test "removes #:tween when it finishes" #f
          (assq #:tween (run-steps e 7 16)))
    (test "and leaves the target" 100 (entity-ref (run-steps e 7 16) #:x))
    (test "keeps #:tween until then" #t (tween? (entity-ref (run-steps e 6 16) #:tween)))
    (test "the entity it was given is unchanged" 0 (entity-ref (begin (run-steps e 7 16) e) #:x)))
  (test-assert "guard: no #:tween, the entity comes back as is"
    (eq? tw-box (step-tweens #f tw-box 16)))
  (test-assert "guard: #:tween #f, the entity comes back as is"
    (let ((e (entity-set tw-box #:tween #f))) (eq? e (step-tweens #f e 16))))
  (test-assert "skip symbol tweens: the entity comes back as is"
    (let ((e (entity-set (with-tween tw-box props: '((#:x . 100)) duration: 100)
                         #:skip-pipelines '(gravity tweens))))
      (eq? e (step-tweens #f e 16))))
  (test "another skip symbol does not stop it" 16
        (entity-ref (step-tweens #f (entity-set (with-tween tw-box props: '((#:x . 100)) duration: 100)
                                                #:skip-pipelines '(gravity velocity-x))
                                 16)
                    #:x))
  (test "dt is in ms, exact or inexact" 16.0
        (entity-ref (step-tweens #f (with-tween tw-box props: '((#:x . 100)) duration: 100) 16.0) #:x))
  (test-error "a #:tween that is not a tween names the entity" (tw-says? "box 7" "#:tween")
              (step-tweens #f (entity-set tw-box #:tween 'soon) 16))

  (test-group "on-complete"
    (let* ((calls 0)
           (seen #f)
           (e (with-tween tw-box props: '((#:x . 100)) duration: 50
                          on-complete: (lambda (e)
                                         (set! calls (+ calls 1))
                                         (set! seen e)
                                         (entity-set e #:arrived? #t))))
           (end (run-steps e 200 16)))
      (test "runs exactly once over 200 steps" 1 calls)
      (test "gets the entity without #:tween" #f (assq #:tween seen))
      (test "gets the entity at the target" 100 (entity-ref seen #:x))
      (test "its result is the entity kept" #t (entity-ref end #:arrived? #f))
      (test "the entity keeps the target" 100 (entity-ref end #:x)))
    (let* ((calls 0)
           (e (with-tween tw-box props: '((#:x . 100)) duration: 10 repeat: 3
                          on-complete: (lambda (e) (set! calls (+ calls 1)) e))))
      (run-steps e 100 1)
      (test "once after all repeats, not once per run" 1 calls))
    (test "on-complete may start the next tween" '(100 50 0 #f)
          (let* ((back (lambda (e) (entity-set e #:tween (make-tween e props: '((#:x . 0)) duration: 20))))
                 (e (with-tween tw-box props: '((#:x . 100)) duration: 20 on-complete: back))
                 (e1 (run-steps e 2 10))
                 (e2 (run-steps e1 1 10))
                 (e3 (run-steps e2 1 10)))
            (list (entity-ref e1 #:x) (entity-ref e2 #:x) (entity-ref e3 #:x)
                  (entity-ref e3 #:tween #f))))
    (test-error "an on-complete that returns a non-entity names the entity"
                (tw-says? "box 7" "on-complete" "42")
                (step-tweens #f (with-tween tw-box props: '((#:x . 1)) duration: 0
                                            on-complete: (lambda (e) 42))
                             16))
    (let* ((calls 0)
           (t (make-tween tw-box props: '((#:x . 100)) duration: 10
                          on-complete: (lambda (e) (set! calls (+ calls 1)) e))))
      (let-values (((t2 e2) (tween-step t tw-box 10)))
        (test "tween-step alone never calls on-complete" 0 calls)
        (test-assert "a tween already finished is removed without calling on-complete"
          (let ((e3 (step-tweens #f (entity-set e2 #:tween t2) 16)))
            (and (not (assq #:tween e3)) (= calls 0)))))))

  (test "forever: the entity alist never grows over 10,000 steps" '(6 6)
        (let* ((e (with-tween tw-box props: '((#:x . 100) (#:y . 0)) duration: 33 repeat: -1 yoyo?: #t
                              ease: 'bounce-out))
               (e1 (step-tweens #f e 16)))
          (list (length e1) (length (run-steps e1 10000 16))))))

;;; ------------------------------------------------------------------
;;; Ends that fall between frames, tween-to, sequences and groups.

;; The value of `key` after each of `n` step-tweens of `dt`.
(define (tw-steps e key n dt)
  (let loop ((i 0) (e e) (out '()))
    (if (= i n)
        (reverse out)
        (let ((e2 (step-tweens #f e dt)))
          (loop (+ i 1) e2 (cons (entity-ref e2 key) out))))))

(test-group "an end between two frames shows exactly"
  ;; 2500 ms is not a whole number of 16 ms frames: the frame that passes
  ;; 2500 shows the turn itself, 176, not a value 12 ms on the way back
  (let* ((lift '((#:type . lift) (#:y . 96)))
         (ys (tw-steps (entity-set lift #:tween (make-tween lift props: '((#:y . 176)) duration: 2500
                                                            repeat: -1 yoyo?: #t))
                       #:y 700 16)))
    (test "a 2500 ms yoyo stepped 16 ms turns at exactly 176" 176 (foldl max 0 ys))
    (test "on the frame that passes 2500 ms" 176 (list-ref ys 156))
    (test "and back at exactly 96 on the frame that passes 5000 ms" 96 (list-ref ys 312))
    (test "the frame after the turn is 28 ms on the way back: 176 - 80 * 28/2500" (- 176 (* 80 28/2500))
          (list-ref ys 157))))

(test-group "tween-to: starts read when the first run begins"
  (test "from where the entity is when it starts" '(55 60)
        (tw-steps (entity-set (entity-set tw-box #:x 50) #:tween (tween-to '((#:x . 100)) duration: 80))
                  #:x 2 8))
  (test "a delay: the start is the value when the delay ends" '(999 1099/2 100)
        (let-values (((t e) (tw-run (tween-to '((#:x . 100)) duration: 10 delay: 10) tw-box '(5))))
          (let-values (((t1 e1) (tween-step t (entity-set e #:x 999) 5)))
            (let-values (((t2 e2) (tween-step t1 e1 5)))
              (let-values (((t3 e3) (tween-step t2 e2 5)))
                (map (lambda (e) (entity-ref e #:x)) (list e1 e2 e3)))))))
  (test-error "a key the entity lacks is an error naming it when the tween starts"
              (tw-raised? 'tween-to "box 7" "#:z")
              (step-tweens #f (entity-set tw-box #:tween (tween-to '((#:z . 1)) duration: 10)) 16))
  (test-error "a bad target is an error at once" (tw-raised? 'tween-to "target" "#:x")
              (tween-to '((#:x . "far")))))

(test-group "sequences"
  (define (seq . parts) (entity-set tw-box #:tween (apply tween-sequence parts)))
  (test "one after the other, the second from where the first left" '(50 100 175/2 75 125/2)
        (tw-steps (seq (tween-to '((#:x . 100)) duration: 20) (tween-to '((#:x . 50)) duration: 40))
                  #:x 5 10))
  (test "a part that ends between frames shows its end; its leftover time is not lost"
        '(80 100 86 78 70 62 54 50 50)
        ;; 100 in 25 ms, stepped 20: 25 ends in the 2nd step, its 15 ms left
        ;; are given with the 3rd step: 35 ms into a 125 ms way back is 86 ...
        (tw-steps (seq (tween-to '((#:x . 100)) duration: 25) (tween-to '((#:x . 50)) duration: 125))
                  #:x 9 20))
  (test "waits and calls take no frame of their own" '((0 #f) (0 #t) (50 #t) (100 #t))
        (let loop ((e (seq (tween-wait 20) (tween-call (lambda (e) (entity-set e #:rang? #t)))
                           (tween-to '((#:x . 100)) duration: 20)))
                   (n 0) (out '()))
          (if (= n 4)
              (reverse out)
              (let ((e2 (step-tweens #f e 10)))
                (loop e2 (+ n 1) (cons (list (entity-ref e2 #:x) (entity-ref e2 #:rang? #f)) out))))))
  (test "repeat: 2 plays the parts three times, restarting each from where it is" '(100 0 100 0 100 0 0)
        (tw-steps (seq (tween-to '((#:x . 100)) duration: 10) (tween-to '((#:x . 0)) duration: 10) repeat: 2)
                  #:x 7 10))
  (test "its on-complete runs once, at the end, and #:tween is gone" '(1 #f 0)
        (let* ((n 0)
               (e (seq (tween-to '((#:x . 100)) duration: 10) (tween-to '((#:x . 0)) duration: 10)
                       repeat: 1 on-complete: (lambda (e) (set! n (+ n 1)) e)))
               (end (let loop ((e e) (i 0)) (if (= i 20) e (loop (step-tweens #f e 5) (+ i 1))))))
          (list n (entity-ref end #:tween #f) (entity-ref end #:x))))
  (test "a sequence of make-tween parts keeps each one's own starts" '(100 20 10)
        (tw-steps (seq (tw-x 100 duration: 10) (make-tween (entity-set tw-box #:x 30) props: '((#:x . 10))
                                                           duration: 20))
                  #:x 3 10))
  (test-assert "repeat -1 plays for ever: still there after 1000 steps"
    (tween-track? (entity-ref (let loop ((e (seq (tween-wait 3) (tween-call (lambda (e) e)) repeat: -1)) (i 0))
                                (if (= i 1000) e (loop (step-tweens #f e 16) (+ i 1))))
                              #:tween #f)))
  (test-error "repeat -1 of parts that take no time is an error, not a hang"
              (tw-says? "took no time")
              (step-tweens #f (seq (tween-call (lambda (e) e)) repeat: -1) 16))
  (test-error "a part that is no tween is an error naming its place" (tw-raised? 'tween-sequence "part 2" "42")
              (tween-sequence (tween-wait 1) 42))
  (test-error "an unknown keyword is named" (tw-says? "tween-sequence" "repaet:")
              (tween-sequence (tween-wait 1) repaet: 2))
  (test-error "a call that returns no entity names the entity" (tw-says? "box 7" "tween-call" "nope")
              (step-tweens #f (seq (tween-call (lambda (e) 'nope))) 16)))

(test-group "parallel groups and several tweens on one entity"
  (test "all at once; done when the longest is" '((50 25/2 #t) (100 15 #t) (100 35/2 #t) (100 20 #f))
        (let loop ((e (entity-set tw-box #:tween (tween-parallel (tween-to '((#:x . 100)) duration: 20)
                                                                (tween-to '((#:y . 20)) duration: 40))))
                   (i 0) (out '()))
          (if (= i 4)
              (reverse out)
              (let ((e2 (step-tweens #f e 10)))
                (loop e2 (+ i 1) (cons (list (entity-ref e2 #:x) (entity-ref e2 #:y)
                                             (and (entity-ref e2 #:tween #f) #t))
                                       out))))))
  (test "entity-add-tween runs a second tween beside the first" '((10 15) (20 20))
        (let* ((e (entity-set tw-box #:tween (tween-to '((#:x . 20)) duration: 20)))
               (e (entity-add-tween e (tween-to '((#:y . 20)) duration: 20)))
               (e1 (step-tweens #f e 10))
               (e2 (step-tweens #f e1 10)))
          (list (list (entity-ref e1 #:x) (entity-ref e1 #:y)) (list (entity-ref e2 #:x) (entity-ref e2 #:y)))))
  (test "a callback that sets #:tween adds it to what is playing" '(100 7)
        (let* ((e (entity-set (entity-set tw-box #:z 0) #:tween
                              (tween-sequence (tween-call (lambda (e) (entity-set e #:tween (tween-to '((#:z . 7))
                                                                                                      duration: 30))))
                                              (tween-to '((#:x . 100)) duration: 30))))
               (e (let loop ((e e) (i 0)) (if (= i 4) e (loop (step-tweens #f e 10) (+ i 1))))))
          (list (entity-ref e #:x) (entity-ref e #:z))))
  (test "a group in a sequence, then a call" '(#t 100 30)
        (let* ((e (entity-set tw-box #:tween
                              (tween-sequence (tween-parallel (tween-to '((#:x . 100)) duration: 10)
                                                              (tween-to '((#:y . 30)) duration: 20))
                                              (tween-call (lambda (e) (entity-set e #:done? #t))))))
               (e (let loop ((e e) (i 0)) (if (= i 3) e (loop (step-tweens #f e 10) (+ i 1))))))
          (list (entity-ref e #:done? #f) (entity-ref e #:x) (entity-ref e #:y)))))
