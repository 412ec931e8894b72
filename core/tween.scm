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
;;;     how that time was split into steps. A step that ends a run writes
;;;     that run's end values exactly (every turn of a yoyo shows, even
;;;     between two frames); the time past it shows from the next step.
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
   step-tweens *ease-table* ease-procedure
   tween-to tween-wait tween-call tween-sequence tween-parallel
   tween-track? tween-track-name entity-add-tween
   ;; for sibling modules only: (downstroke timer) steps a scene's timers
   track-step)

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
  ;; lazy?: made by tween-to, its starts not read yet (each prop's start
  ;; is #f until the first run begins and reads them from the entity).
  (define-record-type tween
    (%make-tween props duration delay ease on-complete repeat yoyo?
                 delay-left run run-time finished? lazy?)
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
    (finished? tween-finished?)
    (lazy? tween-lazy?))

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

  ;; Each prop: (key . target) with a keyword given once and a finite
  ;; real target; who: the procedure the error is reported from.
  (define (check-targets who props)
    (unless (list? props)
      (error who
             (sprintf "props: expected an alist of (keyword . target), got ~s" props)))
    (let loop ((rest props) (seen '()))
      (unless (null? rest)
        (let ((p (car rest)))
          (unless (and (pair? p) (keyword? (car p)))
            (error who
                   (sprintf "props: expected (keyword . target) pairs, got ~s in ~s"
                            p props)))
          (when (memq (car p) seen)
            (error who (sprintf "props: key ~s given twice" (car p))))
          (unless (finite-real? (cdr p))
            (error who
                   (sprintf "props: target of ~s must be a finite real number, got ~s"
                            (car p) (cdr p))))
          (loop (cdr rest) (cons (car p) seen))))))

  ;; The start of a prop: the entity's value of `key`, a finite real.
  (define (start-value who e key)
    (let ((start (assq key e)))
      (unless start
        (error who
               (sprintf "props: entity ~a has no key ~s to tween"
                        (entity-label e) key)))
      (unless (finite-real? (cdr start))
        (error who
               (sprintf "props: entity ~a has ~s = ~s, not a finite real number"
                        (entity-label e) key (cdr start))))
      (cdr start)))

  ;; props -> ((key start . target) ...), starts read from e now.
  (define (check-props e props)
    (check-targets 'make-tween props)
    (map (lambda (p) (cons (car p) (cons (start-value 'make-tween e (car p)) (cdr p)))) props))

  ;; The options make-tween and tween-to share, checked; who names the
  ;; procedure in errors.
  (define (check-options who props duration delay repeat yoyo? on-complete)
    (unless props
      (error who "props: required, an alist of (keyword . target)"))
    (check-time who "duration" duration)
    (check-time who "delay" delay)
    (unless (and (exact-integer? repeat) (>= repeat -1))
      (error who
             (sprintf "repeat: expected an exact integer >= 0, or -1 for forever, got ~s"
                      repeat)))
    (when (and (= repeat -1) (zero? duration))
      (error who
             "repeat: -1 (forever) needs a duration > 0, got duration 0"))
    (unless (boolean? yoyo?)
      (error who (sprintf "yoyo?: expected #t or #f, got ~s" yoyo?)))
    (unless (or (not on-complete) (procedure? on-complete))
      (error who
             (sprintf "on-complete: expected a procedure or #f, got ~s" on-complete))))

  (define/keywords (make-tween entity #!key props (duration 500) (delay 0) (ease 'linear)
                      (on-complete #f) (repeat 0) (yoyo? #f))
    (let ((e (as-entity entity)))
      (check-options 'make-tween props duration delay repeat yoyo? on-complete)
      (let ((ease-proc (ease-procedure ease))
            (props (check-props e props)))
        (%make-tween props duration delay ease-proc on-complete repeat yoyo?
                     delay 0 0 #f #f))))

  ;; make-tween without the entity: the starts are read from the entity
  ;; the tween is stepped on, when its first run begins (after the delay),
  ;; so a tween later in a sequence goes on from where the earlier ones
  ;; left the entity.
  (define/keywords (tween-to props #!key (duration 500) (delay 0) (ease 'linear)
                      (on-complete #f) (repeat 0) (yoyo? #f))
    (check-options 'tween-to props duration delay repeat yoyo? on-complete)
    (check-targets 'tween-to props)
    (%make-tween (map (lambda (p) (cons (car p) (cons #f (cdr p)))) props)
                 duration delay (ease-procedure ease) on-complete repeat yoyo?
                 delay 0 0 #f #t))

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
                         (tween-yoyo? t) 0 last-run (tween-duration t) #t #f)
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
                           (tween-yoyo? t) (- (tween-delay-left t) dt) 0 0 #f (tween-lazy? t))
              entity))
     ((tween-lazy? t) (step (read-starts t entity) entity dt))
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
                                         (tween-yoyo? t) 0 run run-time #f #f)
                            ;; a step that ends a run shows that run's end
                            ;; exactly; the time past it shows from the next step
                            (if (> n 0)
                                (write-run-end t entity (- run 1))
                                (write-at t entity run run-time)))))))))))

  ;; A tween-to tween whose first run begins: its starts are the entity's
  ;; values now.
  (define (read-starts t entity)
    (%make-tween (map (lambda (p) (cons (car p) (cons (start-value 'tween-to entity (car p)) (cddr p))))
                      (tween-props t))
                 (tween-duration t) (tween-delay t) (tween-ease t) (tween-on-complete t)
                 (tween-repeat t) (tween-yoyo? t) (tween-delay-left t) (tween-run t)
                 (tween-run-time t) #f #f))

  ;; a + b of two finite times, exact when the flonum sum would overflow.
  (define (elapsed a b)
    (let ((s (+ a b)))
      (if (finite-real? s) s (+ (inexact->exact a) (inexact->exact b)))))

  ;; ------------------------------------------------------------------
  ;; Sequences, parallel groups, waits and calls: what #:tween may hold
  ;; besides a tween (docs/tweens.org, "Sequences and groups").
  ;;
  ;; Each is stepped by track-step over a subject (an entity, or a scene
  ;; for (downstroke timer)'s scene timers), which the callbacks get and
  ;; return. A part that ends within a step hands the time it did not need
  ;; to what follows, in the same step, except a tween that wrote its end
  ;; values: these stay for the step (the end of every part is shown) and
  ;; the time left over is banked and given with the next step's dt. The
  ;; clock therefore loses no time, and a sequence's total is the sum of
  ;; its parts.

  ;; kind: sequence or parallel; items: the parts as made (a new run starts
  ;; from them); pending: the parts still to play (sequence: the current
  ;; one first); banked: time left over by a part that held its end;
  ;; runs-left: runs after this one, -1 for ever, #f once finished.
  (define-record-type tween-group
    (%make-group kind items pending banked runs-left on-complete name)
    tween-group?
    (kind group-kind)
    (items group-items)
    (pending group-pending)
    (banked group-banked)
    (runs-left group-runs-left)
    (on-complete group-on-complete)
    (name group-name))

  (set-record-printer! tween-group
    (lambda (g port)
      (fprintf port "#<tween-~a~a of ~a, ~a left>" (group-kind g)
               (if (group-name g) (sprintf " ~s" (group-name g)) "")
               (length (group-items g)) (length (group-pending g)))))

  (define-record-type tween-call
    (%make-tween-call proc)
    tween-call?
    (proc tween-call-proc))

  ;; What #:tween holds: a tween, a sequence or parallel group, or a call.
  (define (tween-track? x) (or (tween? x) (tween-group? x) (tween-call? x)))

  ;; The name given to a sequence or group (name:), or #f.
  (define (tween-track-name x) (and (tween-group? x) (group-name x)))

  (define (tween-call proc)
    (unless (procedure? proc)
      (error 'tween-call (sprintf "expected a procedure (lambda (entity) ...) -> entity, got ~s" proc)))
    (%make-tween-call proc))

  ;; A part that only takes time.
  (define (tween-wait ms)
    (check-time 'tween-wait "ms" ms)
    (tween-to '() duration: ms))

  ;; (tween-sequence part ... [repeat: n] [on-complete: proc] [name: x]):
  ;; the parts one after the other; (tween-parallel part ...) all at once,
  ;; finished when the last one is.
  (define (tween-sequence . args) (make-group 'tween-sequence 'sequence args))
  (define (tween-parallel . args) (make-group 'tween-parallel 'parallel args))

  (define (make-group who kind args)
    (let split ((as args) (items '()))
      (cond ((or (null? as) (keyword? (car as)))
             (check-keywords who as '(#:repeat #:on-complete #:name))
             (let ((repeat (option as #:repeat 0))
                   (on-complete (option as #:on-complete #f))
                   (items (reverse items)))
               (unless (and (exact-integer? repeat) (>= repeat -1))
                 (error who (sprintf "repeat: expected an exact integer >= 0, or -1 for forever, got ~s"
                                     repeat)))
               (when (and (= repeat -1) (null? items))
                 (error who "repeat: -1 (forever) needs at least one part"))
               (unless (or (not on-complete) (procedure? on-complete))
                 (error who (sprintf "on-complete: expected a procedure or #f, got ~s" on-complete)))
               (%make-group kind items items 0 repeat on-complete (option as #:name #f))))
            ((tween-track? (car as)) (split (cdr as) (cons (car as) items)))
            (else
             (error who (sprintf "part ~a: expected a tween, tween-to, tween-wait, tween-call, sequence or parallel group, got ~s"
                                 (+ 1 (length items)) (car as)))))))

  (define (option kvs key default)
    (cond ((null? kvs) default)
          ((eq? (car kvs) key) (cadr kvs))
          (else (option (cddr kvs) key default))))

  (define (regroup g pending banked runs)
    (%make-group (group-kind g) (group-items g) pending banked runs
                 (group-on-complete g) (group-name g)))

  ;; (values track2 subject2 left held?): left is #f while the track goes
  ;; on, else the part of dt it did not need; held?: it ended by writing
  ;; end values. accept: (what value) -> value, checks what a callback
  ;; returned (what: the callback, for the error).
  (define (track-step x subject dt accept)
    (cond ((tween? x) (tween-track-step x subject dt accept))
          ((tween-call? x) (values x (accept "a tween-call" ((tween-call-proc x) subject)) dt #f))
          ((not (group-runs-left x)) (values x subject dt #f))
          ((eq? (group-kind x) 'sequence) (sequence-step x subject dt accept))
          (else (parallel-step x subject dt accept))))

  ;; The time a tween needs to finish, #f when it never does.
  (define (time-to-finish t)
    (and (>= (tween-repeat t) 0)
         (+ (tween-delay-left t)
            (* (- (tween-repeat t) (tween-run t)) (tween-duration t))
            (- (tween-duration t) (tween-run-time t)))))

  (define (tween-track-step t subject dt accept)
    (cond ((tween-finished? t) (values t subject dt #f))
          ((and (pair? (tween-props t)) (not (pair? subject)))
           (error 'tween-step
                  (sprintf "a tween of ~s needs an entity; a scene's timers can only wait and call"
                           (map car (tween-props t)))))
          (else
           (let ((need (time-to-finish t)))
             (let-values (((t2 s2) (step t subject dt)))
               (if (not (tween-finished? t2))
                   (values t2 s2 #f #f)
                   (let ((done (tween-on-complete t2)))
                     (values t2 (if done (accept "a tween's on-complete" (done s2)) s2)
                             (max 0 (- dt need)) (pair? (tween-props t2))))))))))

  (define (finish-group g s left held? accept)
    (let ((done (group-on-complete g)))
      (values (regroup g '() 0 #f)
              (if done (accept "a group's on-complete" (done s)) s)
              left held?)))

  (define (next-run runs) (if (> runs 0) (- runs 1) runs))

  (define (no-time-error g)
    (error 'step-tweens
           (sprintf "a tween-~a repeating forever took no time in a run (give it a wait or a duration)"
                    (group-kind g))))

  (define (sequence-step g subject dt accept)
    (let loop ((pending (group-pending g)) (s subject) (time (+ dt (group-banked g)))
               (runs (group-runs-left g)) (restarted-at #f) (held? #f))
      (cond ((pair? pending)
             (let-values (((x s left hold?) (track-step (car pending) s time accept)))
               (cond ((not left) (values (regroup g (cons x (cdr pending)) 0 runs) s #f #f))
                     ((and hold? (or (pair? (cdr pending)) (not (eqv? runs 0))))
                      ;; its end stays for this step; what follows starts next step
                      (values (regroup g (cdr pending) left runs) s #f #f))
                     (else (loop (cdr pending) s left runs restarted-at hold?)))))
            ((eqv? runs 0) (finish-group g s time held? accept))
            ((and restarted-at (= restarted-at time) (eqv? runs -1)) (no-time-error g))
            (else (loop (group-items g) s time (next-run runs) time #f)))))

  (define (parallel-step g subject dt accept)
    (let pass ((parts (group-pending g)) (s subject) (time (+ dt (group-banked g)))
               (runs (group-runs-left g)) (restarted-at #f))
      (let loop ((ps parts) (s s) (going '()) (least time) (held? #f))
        (if (pair? ps)
            (let-values (((x s left hold?) (track-step (car ps) s time accept)))
              (if left
                  (loop (cdr ps) s going (min least left) (or held? hold?))
                  (loop (cdr ps) s (cons x going) least held?)))
            (cond ((pair? going) (values (regroup g (reverse going) 0 runs) s #f #f))
                  ((eqv? runs 0) (finish-group g s least held? accept))
                  (held? (values (regroup g '() least runs) s #f #f))
                  ((and restarted-at (= restarted-at least) (eqv? runs -1)) (no-time-error g))
                  (else (pass (group-items g) s least (next-run runs) least)))))))

  ;; The check of what an entity's callbacks return.
  (define (entity-result entity)
    (lambda (what result)
      (unless (entity? result)
        (error 'step-tweens
               (sprintf "entity ~a: ~a returned ~s, not an entity alist"
                        (entity-label entity) what result)))
      result))

  ;; One more tween on the entity, with those it has: (tween-parallel old
  ;; new) when it already has one.
  (define (entity-add-tween e track)
    (unless (tween-track? track)
      (error 'entity-add-tween (sprintf "expected a tween, sequence, group or call, got ~s" track)))
    (let* ((e (as-entity e))
           (old (entity-ref e #:tween #f)))
      (entity-set e #:tween (if old (tween-parallel old track) track))))

  ;; A sequence, group or call on #:tween. Its callbacks get the entity
  ;; without #:tween; a #:tween one of them sets plays alongside it.
  (define (step-track entity t dt)
    (let-values (((t2 e left held?) (track-step t (entity-remove entity #:tween) dt
                                                (entity-result entity))))
      (let ((added (entity-ref e #:tween #f)))
        (cond (left e)
              (added (entity-set e #:tween (tween-parallel t2 added)))
              (else (entity-set e #:tween t2))))))

  ;; Pipeline step: advance #:tween. A tween that finishes is removed from
  ;; the entity, then its on-complete (if any) gets the entity and returns
  ;; the entity to keep. A tween found already finished is only removed.
  (define-pipeline (step-tweens tweens) (scene entity dt)
    guard: (entity-ref entity #:tween #f)
    (let ((t (entity-ref entity #:tween)))
      (unless (tween? t)
        (unless (tween-track? t)
          (error 'step-tweens
                 (sprintf "entity ~a: #:tween is ~s, not a tween (make one with make-tween, tween-to or tween-sequence)"
                          (entity-label entity) t))))
      (cond
       ((not (tween? t)) (step-track entity t dt))
       ((tween-finished? t) (entity-remove entity #:tween))
       (else
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
                      result))))))))))
