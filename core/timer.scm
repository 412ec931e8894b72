;;; (downstroke timer): timers, on an entity or on a scene, as data.
;;;
;;; (timer-after ms proc) calls proc once, ms from now; (timer-every ms
;;; proc [count: n]) calls it every ms, n times or for ever. Both are
;;; tween sequences of waits and calls ((downstroke tween)), so they go
;;; where a tween goes: an entity's #:tween (proc gets and returns the
;;; entity), or the scene's timers (proc gets and returns the scene: it may
;;; add or remove entities, or timers). The engine steps a scene's timers
;;; before its engine update, every frame the scene runs; a step of dt ms
;;; fires a timer as often as its period fits, so no call is lost to the
;;; frame's length. A scene without timers costs one test a frame.

(module (downstroke timer)
  (timer-after timer-every scene-add-timer scene-remove-timers step-scene-timers)

  (import (downstroke keywords))
  (import scheme (chicken base) (chicken format)
          (only (downstroke numbers) finite-real?)
          (downstroke tween) (downstroke scene))

  (define (check-period who ms)
    (unless (and (finite-real? ms) (>= ms 0))
      (error who (sprintf "ms: expected a finite real number >= 0, got ~s" ms))))

  (define (check-proc who proc)
    (unless (procedure? proc)
      (error who (sprintf "expected a procedure of the entity or scene, got ~s" proc))))

  ;; name: lets scene-remove-timers find it.
  (define/keywords (timer-after ms proc #!key (name #f))
    (check-period 'timer-after ms)
    (check-proc 'timer-after proc)
    (tween-sequence (tween-wait ms) (tween-call proc) name: name))

  ;; count: how many calls, -1 (the default) for ever.
  (define/keywords (timer-every ms proc #!key (count -1) (name #f))
    (check-period 'timer-every ms)
    (check-proc 'timer-every proc)
    (unless (and (exact-integer? count) (or (= count -1) (> count 0)))
      (error 'timer-every (sprintf "count: expected an exact integer > 0, or -1 for ever, got ~s" count)))
    (when (and (= count -1) (zero? ms))
      (error 'timer-every "ms: 0 with count -1 would call for ever within one frame"))
    (tween-sequence (tween-wait ms) (tween-call proc)
                    repeat: (if (= count -1) -1 (- count 1)) name: name))

  (define (check-timer who t)
    (unless (tween-track? t)
      (error who (sprintf "expected a timer (timer-after, timer-every, tween-sequence ...), got ~s" t))))

  (define (scene-add-timer scene timer)
    (check-timer 'scene-add-timer timer)
    (update-scene scene timers: (append (scene-timers scene) (list timer))))

  ;; Removes the timers named `name` (name: of timer-after, timer-every,
  ;; tween-sequence), or those a predicate of the timer holds for.
  (define (scene-remove-timers scene which)
    (let ((gone? (if (procedure? which) which (lambda (t) (equal? (tween-track-name t) which)))))
      (update-scene scene timers: (let keep ((ts (scene-timers scene)))
                                    (cond ((null? ts) '())
                                          ((gone? (car ts)) (keep (cdr ts)))
                                          (else (cons (car ts) (keep (cdr ts)))))))))

  (define (scene-result what result)
    (unless (scene? result)
      (error 'step-scene-timers (sprintf "~a returned ~s, not a scene" what result)))
    result)

  (define (checked-timer t) (check-timer 'step-scene-timers t) t)

  ;; Each timer in turn, the scene its callbacks return passed on; finished
  ;; ones are dropped. Timers a callback adds start on the next step.
  (define (step-scene-timers scene dt)
    (let ((timers (scene-timers scene)))
      (if (null? timers)
          scene
          (let loop ((ts timers) (s (update-scene scene timers: '())) (kept '()))
            (if (null? ts)
                (update-scene s timers: (append (reverse kept) (scene-timers s)))
                (receive (t2 s2 left held?) (track-step (checked-timer (car ts)) s dt scene-result)
                  (unless (scene? s2) (scene-result "a timer" s2))
                  (loop (cdr ts) s2 (if left kept (cons t2 kept))))))))))
