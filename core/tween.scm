;;; (downstroke tween): time-based interpolation of entity keys.
;;;
;;; A tween moves some numeric keys of an entity (its "props") from the
;;; values they had when the tween was made to target values, over a
;;; duration in milliseconds, shaped by an easing procedure:
;;;
;;;   (entity-set e #:tween (make-tween e props: '((#:x . 200) (#:y . 40))
;;;                                       duration: 800 ease: 'cubic-in-out))
;;;
;;; The pipeline step `step-tweens` advances the #:tween of an entity each
;;; frame; `tween-step` does the same for a tween held anywhere else.
;;;
;;; Timing model
;;;   - Nothing is written while the delay runs. The delay happens once,
;;;     before the first run, never between repeats.
;;;   - A tween makes 1 + repeat runs (repeat -1: it never finishes).
;;;     Time left over when a run ends carries into the next run, so a
;;;     tween's state depends only on the total time it was given, not on
;;;     how that time was split into steps.
;;;   - With yoyo? every odd-numbered run (the 2nd, 4th, ...) plays the run
;;;     backwards in time, from target to start: its value at time u into
;;;     the run is the forward value at time (duration - u). An asymmetric
;;;     easing therefore retraces the same curve on the way back.
;;;   - When the last run ends its props are written exactly as the end
;;;     value (the target, or the start when a yoyo tween ends on a return
;;;     run), not computed through the easing, so no rounding is left.
;;;   - Duration 0 is allowed: the first step after the delay finishes every
;;;     run at once. Duration 0 with repeat -1 has no meaning (infinitely
;;;     many runs in no time) and is refused by make-tween.
;;;   - Exact inputs stay exact: with an integer dt, integer (or rational)
;;;     starts, targets, duration and delay, and a polynomial easing
;;;     (linear, quad, cubic, quart, quint) every value written is an exact
;;;     rational. Bounce is built from exact constants and stays exact too.
;;;   - A tween is an immutable record; tween-step returns a new one.
;;;   - tween-step never calls on-complete: step-tweens does, after it has
;;;     removed #:tween from the entity, so on-complete may start a new tween
;;;     by setting #:tween on the entity it returns.
;;;
;;; Easing names
;;;   The table uses FAMILY-in, FAMILY-out and FAMILY-in-out ('quad-in,
;;;   'bounce-in-out), family first, so the names of one family sit together
;;;   in a listing and read the way the families are usually described
;;;   ("quad, in-out"). Each family is defined once by its "in" curve f;
;;;   the other two are derived from it:
;;;     out(t)    = 1 - f(1 - t)
;;;     in-out(t) = f(2t) / 2            for t < 1/2
;;;               = 1 - f(2 - 2t) / 2    otherwise
;;;   Every table procedure returns exactly 0 for t <= 0 and exactly 1 for
;;;   t >= 1 (inputs outside [0,1] are clamped), which matters for expo and
;;;   elastic whose formulas do not reach 0 or 1 on their own.

(module (downstroke tween)
  (make-tween tween? tween-step tween-finished? tween-active?
   step-tweens *ease-table* ease-procedure)

  (import (downstroke keywords) (only (downstroke numbers) finite-real? lerp))
  (import scheme (chicken base) (chicken format) (chicken keyword)
          (downstroke entity))

  ;; ------------------------------------------------------------------
  ;; Easings

  (define pi (* 4 (atan 1)))

  ;; Clamp to [0,1] and pin the ends to exact 0 and 1.
  (define (pinned f)
    (lambda (t)
      (cond ((<= t 0) 0)
            ((>= t 1) 1)
            (else (f t)))))

  (define (out-of f) (lambda (t) (- 1 (f (- 1 t)))))

  (define (in-out-of f)
    (lambda (t)
      (if (< t 1/2)
          (/ (f (* 2 t)) 2)
          (- 1 (/ (f (- 2 (* 2 t))) 2)))))

  ;; name -> the three table entries of the family
  ;; The derived curves are built on the pinned "in" curve, so they meet
  ;; exactly at their ends and in-out passes exactly through 1/2.
  (define (family name f)
    (define (sym suffix) (string->symbol (string-append name suffix)))
    (let ((f (pinned f)))
      (list (cons (sym "-in") f)
            (cons (sym "-out") (pinned (out-of f)))
            (cons (sym "-in-out") (pinned (in-out-of f))))))

  (define (power n) (lambda (t) (expt t n)))

  (define (sine-in t) (- 1 (cos (/ (* t pi) 2))))

  (define (expo-in t) (expt 2 (- (* 10 t) 10)))

  (define (circ-in t) (- 1 (sqrt (- 1 (* t t)))))

  ;; Overshoot constant of the usual back easing (about 10% overshoot).
  (define back-c1 1.70158)
  (define (back-in t)
    (- (* (+ back-c1 1) t t t) (* back-c1 t t)))

  (define elastic-c (/ (* 2 pi) 3))
  (define (elastic-in t)
    (- (* (expt 2 (- (* 10 t) 10))
          (sin (* (- (* 10 t) 43/4) elastic-c)))))

  ;; The classic bounce is defined as an "out" curve: four parabolic arcs
  ;; of a ball settling at 1. Its constants are exact (7.5625 = 121/16,
  ;; 2.75 = 11/4), so exact input gives exact output.
  (define (bounce-out t)
    (let ((n 121/16))
      (cond ((< t 4/11) (* n t t))
            ((< t 8/11) (let ((u (- t 6/11))) (+ (* n u u) 3/4)))
            ((< t 10/11) (let ((u (- t 9/11))) (+ (* n u u) 15/16)))
            (else (let ((u (- t 21/22))) (+ (* n u u) 63/64))))))
  (define (bounce-in t) (- 1 (bounce-out (- 1 t))))

  (define *ease-table*
    (append
     (list (cons 'linear (pinned (lambda (t) t))))
     (family "quad" (power 2))
     (family "cubic" (power 3))
     (family "quart" (power 4))
     (family "quint" (power 5))
     (family "sine" sine-in)
     (family "expo" expo-in)
     (family "circ" circ-in)
     (family "back" back-in)
     (family "elastic" elastic-in)
     (family "bounce" bounce-in)))

  ;; A symbol of the table, or any procedure of one argument.
  (define (ease-procedure ease)
    (cond ((procedure? ease) ease)
          ((and (symbol? ease) (assq ease *ease-table*)) => cdr)
          ((symbol? ease)
           (error 'ease-procedure
                  (sprintf "ease: unknown easing ~s (known: ~a)"
                           ease (map car *ease-table*))))
          (else
           (error 'ease-procedure
                  (sprintf "ease: expected an easing symbol or a procedure, got ~s"
                           ease)))))

  ;; ------------------------------------------------------------------
  ;; The tween record

  ;; props: list of (key start . target)
  ;; delay-left: delay still to run; run: index of the current run (0-based);
  ;; run-time: time into the current run.
  (define-record-type tween
    (%make-tween props duration delay ease on-complete repeat yoyo?
                 delay-left run run-time finished?)
    tween?
    (props tween-props)
    (duration tween-duration)
    (delay tween-delay)
    (ease tween-ease)
    (on-complete tween-on-complete)
    (repeat tween-repeat)
    (yoyo? tween-yoyo?)
    (delay-left tween-delay-left)
    (run tween-run)
    (run-time tween-run-time)
    (finished? tween-finished?))

  (set-record-printer! tween
    (lambda (t port)
      (fprintf port "#<tween ~s ~a run ~a at ~a/~a>"
               (map car (tween-props t))
               (cond ((tween-finished? t) "finished")
                     ((> (tween-delay-left t) 0) "delayed")
                     (else "active"))
               (tween-run t) (tween-run-time t) (tween-duration t))))

  (define (check-time who what x)
    (unless (and (finite-real? x) (>= x 0))
      (error who (sprintf "~a: expected a finite real number >= 0, got ~s" what x))))

  ;; Each prop: (key . target) with a finite real target and a key the
  ;; entity holds as a finite real number (its start value).
  (define (check-props e props)
    (unless (list? props)
      (error 'make-tween
             (sprintf "props: expected an alist of (keyword . target), got ~s" props)))
    (let loop ((rest props) (seen '()) (out '()))
      (if (null? rest)
          (reverse out)
          (let ((p (car rest)))
            (unless (and (pair? p) (keyword? (car p)))
              (error 'make-tween
                     (sprintf "props: expected (keyword . target) pairs, got ~s in ~s"
                              p props)))
            (let ((key (car p)) (target (cdr p)))
              (when (memq key seen)
                (error 'make-tween (sprintf "props: key ~s given twice" key)))
              (unless (finite-real? target)
                (error 'make-tween
                       (sprintf "props: target of ~s must be a finite real number, got ~s"
                                key target)))
              (let ((start (assq key e)))
                (unless start
                  (error 'make-tween
                         (sprintf "props: entity ~a has no key ~s to tween"
                                  (entity-label e) key)))
                (unless (finite-real? (cdr start))
                  (error 'make-tween
                         (sprintf "props: entity ~a has ~s = ~s, not a finite real number"
                                  (entity-label e) key (cdr start))))
                (loop (cdr rest) (cons key seen)
                      (cons (cons key (cons (cdr start) target)) out))))))))

  (define/keywords (make-tween entity #!key props (duration 500) (delay 0) (ease 'linear)
                      (on-complete #f) (repeat 0) (yoyo? #f))
    (let ((e (as-entity entity)))
      (unless props
        (error 'make-tween "props: required, an alist of (keyword . target)"))
      (check-time 'make-tween "duration" duration)
      (check-time 'make-tween "delay" delay)
      (unless (and (exact-integer? repeat) (>= repeat -1))
        (error 'make-tween
               (sprintf "repeat: expected an exact integer >= 0, or -1 for forever, got ~s"
                        repeat)))
      (when (and (= repeat -1) (zero? duration))
        (error 'make-tween
               "repeat: -1 (forever) needs a duration > 0, got duration 0"))
      (unless (boolean? yoyo?)
        (error 'make-tween (sprintf "yoyo?: expected #t or #f, got ~s" yoyo?)))
      (unless (or (not on-complete) (procedure? on-complete))
        (error 'make-tween
               (sprintf "on-complete: expected a procedure or #f, got ~s" on-complete)))
      (let ((ease-proc (ease-procedure ease))
            (props (check-props e props)))
        (%make-tween props duration delay ease-proc on-complete repeat yoyo?
                     delay 0 0 #f))))

  ;; Delay over and not finished.
  (define (tween-active? t)
    (and (not (tween-finished? t)) (zero? (tween-delay-left t))))

  ;; ------------------------------------------------------------------
  ;; Stepping

  (define (backwards-run? t run) (and (tween-yoyo? t) (odd? run)))

  (define (write-props entity props value-of)
    (let loop ((props props) (e entity))
      (if (null? props)
          e
          (let ((p (car props)))
            (loop (cdr props) (entity-set e (car p) (value-of (car p) (cadr p) (cddr p))))))))

  ;; The exact end value of run `run`.
  (define (write-run-end t entity run)
    (if (backwards-run? t run)
        (write-props entity (tween-props t) (lambda (key start target) start))
        (write-props entity (tween-props t) (lambda (key start target) target))))

  ;; The props at time run-time into run `run`: start to target by the
  ;; eased fraction k, through lerp, so that a span wider than the largest
  ;; flonum (-1e308 to 1e308) is still walked. Only an easing that
  ;; overshoots (back, elastic, a procedure of the game's) can leave the
  ;; flonums' range: that is an error naming the entity and the key.
  (define (write-at t entity run run-time)
    (let* ((u (/ run-time (tween-duration t)))
           (k ((tween-ease t) (if (backwards-run? t run) (- 1 u) u))))
      (write-props entity (tween-props t)
                   (lambda (key start target)
                     (let ((v (lerp start target k)))
                       (if (finite-real? v)
                           v
                           (error 'tween-step
                                  (sprintf "entity ~a: the tween of ~s from ~s to ~s eased to ~s gives ~s, not a finite number"
                                           (entity-label entity) key start target k v))))))))

  (define (finish t entity last-run)
    (values (%make-tween (tween-props t) (tween-duration t) (tween-delay t)
                         (tween-ease t) (tween-on-complete t) (tween-repeat t)
                         (tween-yoyo? t) 0 last-run (tween-duration t) #t)
            (write-run-end t entity last-run)))

  ;; How many whole runs `time` covers and the time left into the next:
  ;; (values n rest) with n an exact integer and 0 <= rest < duration.
  ;; Flonums divide as flonums while the count is below 2^52 (and rest is
  ;; corrected for their rounding); a count beyond (a run of 5e-324 ms, or
  ;; time near the largest flonum) is counted exactly instead, however
  ;; large, where time / duration would be +inf.0.
  (define (whole-runs time duration)
    (let ((q (/ time duration)))
      (if (or (exact? q) (< q 4503599627370496.))
          (let* ((n (let ((f (floor q))) (if (exact? f) f (inexact->exact f))))
                 (n (if (< time (* n duration)) (- n 1) n))
                 (n (if (>= (- time (* n duration)) duration) (+ n 1) n)))
            (values n (- time (* n duration))))
          (let* ((t (inexact->exact time)) (d (inexact->exact duration))
                 (n (floor (/ t d))))
            (values n (exact->inexact (- t (* n d))))))))

  ;; An entity argument as an alist: a plist is converted as make-tween
  ;; does; anything that is neither is an error naming `who`.
  (define (entity-argument who x)
    (if (or (null? x)
            (and (pair? x) (or (pair? (car x)) (keyword? (car x)))))
        (as-entity x)
        (error who (sprintf "entity: expected an entity (a keyword alist or plist), got ~s" x))))

  (define (tween-step t entity dt)
    (unless (tween? t)
      (error 'tween-step (sprintf "expected a tween, got ~s" t)))
    (check-time 'tween-step "dt" dt)
    (let ((entity (entity-argument 'tween-step entity)))
      (step t entity dt)))

  (define (step t entity dt)
    (cond
     ((tween-finished? t) (values t entity))
     ((> (tween-delay-left t) dt)
      ;; Still waiting: only the clock moves.
      (values (%make-tween (tween-props t) (tween-duration t) (tween-delay t)
                           (tween-ease t) (tween-on-complete t) (tween-repeat t)
                           (tween-yoyo? t) (- (tween-delay-left t) dt) 0 0 #f)
              entity))
     (else
      (let* ((time (elapsed (tween-run-time t) (- dt (tween-delay-left t))))
             (duration (tween-duration t))
             (repeat (tween-repeat t))
             (last-run (and (>= repeat 0) repeat)))
        (if (zero? duration)
            (finish t entity last-run)
            (receive (n run-time) (whole-runs time duration)
              (let ((run (+ (tween-run t) n)))
                (if (and last-run (> run last-run))
                    (finish t entity last-run)
                    (values (%make-tween (tween-props t) duration (tween-delay t)
                                         (tween-ease t) (tween-on-complete t) repeat
                                         (tween-yoyo? t) 0 run run-time #f)
                            (write-at t entity run run-time))))))))))

  ;; a + b of two finite times, exact when the flonum sum would overflow.
  (define (elapsed a b)
    (let ((s (+ a b)))
      (if (finite-real? s) s (+ (inexact->exact a) (inexact->exact b)))))

  ;; Pipeline step: advance #:tween. A tween that finishes is removed from
  ;; the entity, then its on-complete (if any) gets the entity and returns
  ;; the entity to keep. A tween found already finished is only removed.
  (define-pipeline (step-tweens tweens) (scene entity dt)
    guard: (entity-ref entity #:tween #f)
    (let ((t (entity-ref entity #:tween)))
      (unless (tween? t)
        (error 'step-tweens
               (sprintf "entity ~a: #:tween is ~s, not a tween (make one with make-tween)"
                        (entity-label entity) t)))
      (if (tween-finished? t)
          (entity-remove entity #:tween)
          (let-values (((t2 e2) (tween-step t entity dt)))
            (if (not (tween-finished? t2))
                (entity-set e2 #:tween t2)
                (let ((done (entity-remove e2 #:tween))
                      (on-complete (tween-on-complete t2)))
                  (if (not on-complete)
                      done
                      (let ((result (on-complete done)))
                        (unless (entity? result)
                          (error 'step-tweens
                                 (sprintf "entity ~a: the tween's on-complete returned ~s, not an entity alist"
                                          (entity-label done) result)))
                        result)))))))))
