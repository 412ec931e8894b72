(import (downstroke test) (downstroke entity) (downstroke scene) (downstroke tween)
        (downstroke timer)
        scheme (chicken base) (chicken string) (chicken condition))

;;; Helpers (prefixed tm- because every suite is loaded into one toplevel).

(define (tm-says? . parts)
  (lambda (exn)
    (let ((text (error-text exn)))
      (let loop ((parts parts))
        (or (null? parts)
            (and (substring-index (car parts) text) (loop (cdr parts))))))))

;; Raised by `who`, its text containing every one of `parts`.
(define (tm-raised? who . parts)
  (lambda (exn)
    (and (eq? who ((condition-property-accessor 'exn 'location #f) exn))
         ((apply tm-says? parts) exn))))

;; A scene with `timers`, stepped n times by dt: the entity count after each.
(define (tm-counts timers n dt)
  (let loop ((s (make-sprite-scene timers: timers)) (i 0) (out '()))
    (if (= i n)
        (reverse out)
        (let ((s2 (step-scene-timers s dt)))
          (loop s2 (+ i 1) (cons (length (scene-entities s2)) out))))))

(define (tm-spawn s) (scene-add-entity s (list #:type 'spawned #:x 0 #:y 0)))

(test-group "scene timers"
  (test "timer-after fires once, on the step that reaches its time" '(0 0 1 1 1)
        (tm-counts (list (timer-after 40 tm-spawn)) 5 16))
  (test "timer-every fires every period; count: stops it" '(0 1 1 2 3 3 3)
        (tm-counts (list (timer-every 16 tm-spawn count: 3)) 7 10))
  (test "a step longer than the period fires once per period in it" '(3 6 9)
        (tm-counts (list (timer-every 10 tm-spawn)) 3 32))
  (test "exact times: 1000/3 ms every step of 16, 3 calls in 1008 ms, not 2" 3
        (car (reverse (tm-counts (list (timer-every 1000/3 tm-spawn)) 63 16))))
  (test "a finished timer is dropped from the scene" '()
        (scene-timers (step-scene-timers (make-sprite-scene timers: (list (timer-after 5 tm-spawn))) 16)))
  (test "timers fire in the order they are listed, each seeing the scene the one before left"
        '(a b)
        (map (lambda (e) (entity-ref e #:type))
             (scene-entities
              (step-scene-timers
               (make-sprite-scene timers: (list (timer-after 10 (lambda (s) (scene-add-entity s (list #:type 'a))))
                                                (timer-after 5 (lambda (s) (scene-add-entity s (list #:type 'b))))))
               16))))
  (test "a timer added by a callback starts on the next step: 16 ms later" (quote (1 2 2))
        (tm-counts (list (timer-after 16 (lambda (s) (scene-add-timer (tm-spawn s) (timer-after 16 tm-spawn)))))
                   3 16))
  (test "scene-add-timer and scene-remove-timers by name" '(1 0)
        (let* ((s (scene-add-timer (make-sprite-scene) (timer-every 100 tm-spawn name: 'spawner)))
               (s (scene-add-timer s (timer-after 100 tm-spawn))))
          (list (length (scene-timers (scene-remove-timers s 'spawner)))
                (length (scene-timers (scene-remove-timers s (lambda (t) #t)))))))
  (test "a script of waits and calls as a scene timer" '(1 1 2 2)
        (tm-counts (list (tween-sequence (tween-wait 10) (tween-call tm-spawn) (tween-wait 20) (tween-call tm-spawn)))
                   4 10))
  (test "update-scene keeps the timers; a new entity list too" 1
        (length (scene-timers (update-scene (make-sprite-scene timers: (list (timer-after 1 tm-spawn)))
                                            entities: '()))))
  (test-error "a callback that returns no scene is named" (tm-says? "returned" "not a scene")
              (step-scene-timers (make-sprite-scene timers: (list (timer-after 1 (lambda (s) 5)))) 16))
  (test-error "a tween of props on a scene is refused" (tm-says? "#:x" "needs an entity")
              (step-scene-timers (make-sprite-scene timers: (list (tween-to '((#:x . 1)) duration: 10))) 16))
  (test-error "count: 0 is refused" (tm-raised? 'timer-every "count")
              (timer-every 10 tm-spawn count: 0))
  (test-error "every 0 ms for ever is refused" (tm-raised? 'timer-every "ms")
              (timer-every 0 tm-spawn))
  (test-error "a scene's timers: holding something else is named when stepped"
              (tm-raised? 'step-scene-timers "soon")
              (step-scene-timers (make-sprite-scene timers: (list 'soon)) 16))
  (test-error "scene-add-timer of something else names it" (tm-raised? 'scene-add-timer "soon")
              (scene-add-timer (make-sprite-scene) 'soon)))

(test-group "timers on an entity"
  (test "timer-every on #:tween calls with the entity" '(0 1 1 2 2 3)
        (let loop ((e (list (cons #:type 'blinker) (cons #:n 0)
                            (cons #:tween (timer-every 20 (lambda (e) (entity-update e #:n (lambda (n) (+ n 1))))))))
                   (i 0) (out '()))
          (if (= i 6)
              (reverse out)
              (let ((e2 (step-tweens #f e 10)))
                (loop e2 (+ i 1) (cons (entity-ref e2 #:n) out)))))))

(test-exit)
