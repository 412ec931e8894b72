(import (downstroke test) (downstroke entity) (downstroke animation)
        scheme (chicken base) (chicken string) (chicken condition))

;;; Helpers (prefixed an- because every suite is loaded into one toplevel).

(define (an-says? . parts)
  (lambda (exn)
    (let ((text (error-text exn)))
      (let loop ((parts parts))
        (or (null? parts)
            (and (substring-index (car parts) text) (loop (cdr parts))))))))

;; The error's location (the procedure that raised it) is `who`.
(define ((an-located? who) exn)
  (eq? who ((condition-property-accessor 'exn 'location #f) exn)))

(define an-walk '((#:name . walk) (#:frames . (28 29 30)) (#:duration . 2)))
(define an-run '((#:name . run) (#:frames . (10 (11 . 3) 12)) (#:duration . 1)))
(define an-idle '((#:name . idle) (#:frames . ((5 . 2) (6 . 1)))))
(define an-die '((#:name . die) (#:frames . (1 2 3)) (#:duration . 2) (#:loop? . #f)))
(define an-jump '((#:name . jump) (#:frames . (40 41)) (#:duration . 3)))

(define (an-hero . animations)
  (list (cons #:type 'hero) (cons #:id 1) (cons #:x 0) (cons #:y 0)
        (cons #:animations animations)))

(define (an-steps e n #!optional (dt 16))
  (if (= n 0) e (an-steps (apply-animation #f e dt) (- n 1) dt)))

;; `key` after each of `n` steps.
(define (an-trace e key n #!optional (dt 16))
  (let loop ((i 0) (e e) (out '()))
    (if (= i n)
        (reverse out)
        (let ((e2 (apply-animation #f e dt)))
          (loop (+ i 1) e2 (cons (entity-ref e2 key) out))))))

(define (an-cycle pattern n) ; the first n items of pattern repeated
  (let loop ((i 0) (rest pattern) (out '()))
    (cond ((= i n) (reverse out))
          ((null? rest) (loop i pattern out))
          (else (loop (+ i 1) (cdr rest) (cons (car rest) out))))))

;;; ------------------------------------------------------------------

(test-group "uniform durations"
  (let ((e (an-hero an-walk)))
    (test "tile ids, 2 ticks a frame, looping" '(28 28 29 29 30 30 28 28 29 29 30 30 28)
          (an-trace e #:tile-id 13))
    (test "frame indices" '(0 0 1 1 2 2 0 0 1 1 2 2 0)
          (an-trace e #:anim-frame 13))
    (test "ticks count the steps the frame has been shown, this one included"
          '(1 2 1 2 1 2 1 2)
          (an-trace e #:anim-tick 8))
    (test "#:anim-duration is the current frame's ticks" '(2 2 2 2)
          (an-trace e #:anim-duration 4))
    (test "the default animation is the first one, and it is written" 'walk
          (entity-ref (an-steps e 1) #:anim-name))
    (test "10,000 steps: the exact sequence" (an-cycle '(28 28 29 29 30 30) 10000)
          (an-trace e #:tile-id 10000))))

(test-group "per-frame durations"
  (let ((e (an-hero an-run)))
    (test "a (tile . ticks) frame lasts its own ticks" '(10 11 11 11 12 10 11 11 11 12 10)
          (an-trace e #:tile-id 11))
    (test "#:anim-duration follows the frame" '(1 3 3 3 1 1 3)
          (an-trace e #:anim-duration 7))
    (test "ticks" '(1 1 2 3 1 1 1 2 3)
          (an-trace e #:anim-tick 9))
    (test "10,000 steps: the exact sequence" (an-cycle '(10 11 11 11 12) 10000)
          (an-trace e #:tile-id 10000))
    (test "10,000 steps: 2000 full cycles end on the last frame, its tick 1 of 1" '(2 1 12)
          (let ((e2 (an-steps e 10000)))
            (map (lambda (k) (entity-ref e2 k)) '(#:anim-frame #:anim-tick #:tile-id)))))
  (test "every frame carrying its own duration, no #:duration needed" '(5 5 6 5 5 6 5)
        (an-trace (an-hero an-idle) #:tile-id 7))
  (test "a one-frame loop shows its frame forever, tick going 1..duration"
        '(9 9 9 9 9 9 1 2 1 2 1 2)
        (let ((e (an-hero '((#:name . still) (#:frames . (9)) (#:duration . 2)))))
          (append (an-trace e #:tile-id 6) (an-trace e #:anim-tick 6))))
  (test "an animation written as a plist (as prefabs load them)" '(7 7 8 7 7 8)
        (an-trace (an-hero '(#:name blink #:frames (7 (8 . 1)) #:duration 2)) #:tile-id 6)))

(test-group "starting state"
  (test "#:anim-name picks an animation other than the first" '(40 40 40 41)
        (an-trace (entity-set (an-hero an-walk an-jump) #:anim-name 'jump) #:tile-id 4))
  (test "a saved frame and tick continue where they were" '(29 30 30 28)
        (an-trace (entity-set (entity-set (an-hero an-walk) #:anim-frame 1) #:anim-tick 1)
                  #:tile-id 4))
  (test "a tick past the frame's duration advances on the next step" '(30 1)
        (let ((e (apply-animation #f (entity-set (entity-set (an-hero an-walk) #:anim-frame 1)
                                                 #:anim-tick 50)
                                  16)))
          (list (entity-ref e #:tile-id) (entity-ref e #:anim-tick))))
  (test "dt is ignored: 1000 ms steps give the same sequence as 16 ms steps"
        (an-trace (an-hero an-run) #:tile-id 20 16)
        (an-trace (an-hero an-run) #:tile-id 20 1000))
  (test-assert "the scene argument is not used"
    (equal? (apply-animation #f (an-hero an-walk) 16)
            (apply-animation 'some-scene (an-hero an-walk) 16))))

(test-group "one-shot"
  (let ((e (an-hero an-die)))
    (test "holds its last frame" '(1 1 2 2 3 3 3 3 3 3)
          (an-trace e #:tile-id 10))
    (test "#:anim-finished? from the step the last frame completes its duration"
          '(#f #f #f #f #f #t #t #t)
          (an-trace e #:anim-finished? 8))
    (test "holding: frame and tick stay put" '(2 2 #t)
          (let ((e2 (an-steps e 500)))
            (list (entity-ref e2 #:anim-frame) (entity-ref e2 #:anim-tick)
                  (entity-ref e2 #:anim-finished?))))
    (test "holding: the entity no longer changes" #t
          (let ((e2 (an-steps e 6)))
            (equal? e2 (an-steps e2 100)))))
  (test "a one-frame one-shot of 1 tick finishes on the first step" #t
        (entity-ref (an-steps (an-hero '((#:name . pop) (#:frames . (4)) (#:duration . 1) (#:loop? . #f))) 1)
                    #:anim-finished?))
  (test "a looping animation never writes #:anim-finished?" #f
        (assq #:anim-finished? (an-steps (an-hero an-walk) 100)))
  (test "#:loop? #t loops" '(1 2 1 2)
        (an-trace (an-hero '((#:name . l) (#:frames . (1 2)) (#:duration . 1) (#:loop? . #t))) #:tile-id 4)))

(test-group "set-animation"
  (let* ((e (an-steps (an-hero an-walk an-jump an-die) 3))
         (j (set-animation e 'jump)))
    (test "switches the name" 'jump (entity-ref j #:anim-name))
    (test "resets frame and tick to 0" '(0 0)
          (list (entity-ref j #:anim-frame) (entity-ref j #:anim-tick)))
    (test "leaves #:tile-id to the next step" 29 (entity-ref j #:tile-id))
    (test "the first frame after it is shown for its whole duration" '(40 40 40 41 41 41 40)
          (an-trace j #:tile-id 7))
    (test-assert "the same name returns the entity unchanged"
      (eq? j (set-animation j 'jump)))
    (test-assert "the same name, called every frame, does not restart it"
      (let loop ((i 0) (e j) (out '()))
        (if (= i 7)
            (equal? (reverse out) '(40 40 40 41 41 41 40))
            (let ((e2 (apply-animation #f (set-animation e 'jump) 16)))
              (loop (+ i 1) e2 (cons (entity-ref e2 #:tile-id) out))))))
    (test-assert "the first animation's name is current when #:anim-name is absent"
      (let ((fresh (an-hero an-walk an-jump)))
        (eq? fresh (set-animation fresh 'walk))))
    (test "clears #:anim-finished? (removes the key)" '(#t gone)
          (let* ((d (an-steps (set-animation e 'die) 20))
                 (w (set-animation d 'walk)))
            (list (entity-ref d #:anim-finished? #f) (entity-ref w #:anim-finished? 'gone))))
    (test "... and a one-shot played again finishes again" '(1 1 2 2 3 3 3)
          (an-trace (set-animation (set-animation (an-steps (set-animation e 'die) 20) 'walk) 'die)
                    #:tile-id 7))
    (test-error "an unknown name is an error naming it and the entity" (an-says? "fly" "hero 1")
                (set-animation e 'fly))
    (test-error "an entity without #:animations" (an-says? "#:animations" "hero 1")
                (set-animation (entity-remove e #:animations) 'walk))
    (test "it does not change its argument" 'walk (begin (set-animation e 'jump) (entity-ref e #:anim-name)))))

(test-group "pipeline step"
  (test-assert "guard: no #:animations, the entity comes back as is"
    (let ((e '((#:type . rock) (#:x . 1)))) (eq? e (apply-animation #f e 16))))
  (test-assert "guard: #:animations #f, the entity comes back as is"
    (let ((e '((#:type . rock) (#:animations . #f)))) (eq? e (apply-animation #f e 16))))
  (test-assert "skip symbol animation: the entity comes back as is"
    (let ((e (entity-set (an-hero an-walk) #:skip-pipelines '(gravity animation))))
      (eq? e (apply-animation #f e 16))))
  (test "another skip symbol does not stop it" 28
        (entity-ref (apply-animation #f (entity-set (an-hero an-walk) #:skip-pipelines '(tweens)) 16)
                    #:tile-id))
  (test-error "an unknown #:anim-name names the entity and the name" (an-says? "hero 1" "swim")
              (apply-animation #f (entity-set (an-hero an-walk) #:anim-name 'swim) 16))
  (test-error "a frame index past the last frame names the entity" (an-says? "hero 1" "#:anim-frame")
              (apply-animation #f (entity-set (an-hero an-walk) #:anim-frame 3) 16))
  (test-error "a bad #:anim-tick names the entity" (an-says? "hero 1" "#:anim-tick")
              (apply-animation #f (entity-set (an-hero an-walk) #:anim-tick -1) 16))
  (test-error "#:animations that is not a list names the entity" (an-says? "hero 1" "#:animations")
              (apply-animation #f (entity-set (an-hero an-walk) #:animations 'walk) 16))
  (test-assert "it does not change its argument"
    (let* ((e (an-hero an-walk)) (copy (append e '())))
      (apply-animation #f e 16)
      (equal? e copy)))
  (let ((e (an-hero an-walk an-run)))
    (test "the entity alist never grows over 10,000 steps" '(10 10)
          (list (length (an-steps e 1)) (length (an-steps e 10000))))
    (test "nor while switching animations every 7 steps" 10
          (let loop ((i 0) (e e))
            (if (= i 10000)
                (length e)
                (loop (+ i 1)
                      (apply-animation #f (if (= 0 (modulo i 7))
                                              (set-animation e (if (odd? (quotient i 7)) 'walk 'run))
                                              e)
                                       16)))))
    (test "nor for a one-shot that finished" 11
          (length (an-steps (an-hero an-die) 10000)))))

(test-group "animation-frame-duration, animation-frame-tile, animation-named"
  (test "uniform" 2 (animation-frame-duration an-walk 1))
  (test "a frame's own duration wins" 3 (animation-frame-duration an-run 1))
  (test "the animation's duration for plain frames" 1 (animation-frame-duration an-run 2))
  (test "without #:duration" 2 (animation-frame-duration an-idle 0))
  (test "a plist animation" 2 (animation-frame-duration '(#:name a #:frames (1 2) #:duration 2) 1))
  (test "tile of a plain frame" 29 (animation-frame-tile an-walk 1))
  (test "tile of a (tile . ticks) frame" 11 (animation-frame-tile an-run 1))
  (test-error "an index past the end" (an-says? "walk" "3") (animation-frame-duration an-walk 3))
  (test-error "a negative index" (an-says? "walk" "-1") (animation-frame-duration an-walk -1))
  (test-error "no duration anywhere names the animation" (an-says? "bare" "duration")
              (animation-frame-duration '((#:name . bare) (#:frames . (1 2))) 0))
  (test-error "zero ticks" (an-says? "z" "0")
              (animation-frame-duration '((#:name . z) (#:frames . (1)) (#:duration . 0)) 0))
  (test-error "fractional ticks" (an-says? "f" "1.5")
              (animation-frame-duration '((#:name . f) (#:frames . ((1 . 1.5)))) 0))
  (test-error "empty #:frames" (an-says? "e" "#:frames")
              (animation-frame-duration '((#:name . e) (#:frames . ()) (#:duration . 1)) 0))
  (test-error "empty #:frames: the location is the procedure called"
              (an-located? 'animation-frame-duration)
              (animation-frame-duration '((#:name . e) (#:frames . ()) (#:duration . 1)) 0))
  (test-error "#:frames not a list: located at animation-frame-tile"
              (an-located? 'animation-frame-tile)
              (animation-frame-tile '((#:name . e) (#:frames . 7)) 0))
  (test-error "empty #:frames in apply-animation: located there"
              (an-located? 'apply-animation)
              (apply-animation #f (an-hero '((#:name . e) (#:frames . ()) (#:duration . 1))) 16))
  (test "animation-named finds one" an-jump (animation-named (list an-walk an-jump) 'jump))
  (test "animation-named: #f when absent" #f (animation-named (list an-walk an-jump) 'fly))
  (test "animation-named returns a plist animation as an alist" '((#:name . p) (#:frames . (1)))
        (animation-named '((#:name p #:frames (1))) 'p)))

(test-group "set-animation replays a finished one-shot"
  (let* ((done (an-steps (an-hero an-die) 20))
         (again (set-animation done 'die)))
    (test "finished first" #t (entity-ref done #:anim-finished? #f))
    (test "setting it again restarts it" '(0 0 none)
          (list (entity-ref again #:anim-frame) (entity-ref again #:anim-tick)
                (entity-ref again #:anim-finished? 'none)))
    (test "and it plays its frames again" 1 (entity-ref (apply-animation #f again 16) #:tile-id))))

(test-group "animation-tile: the frame shown before any step"
  (test "the first animation's first frame" 28 (animation-tile (list (cons #:animations (list an-walk an-run)))))
  (test "the animation #:anim-name names, at #:anim-frame" 12
        (animation-tile (list (cons #:animations (list an-walk an-run)) (cons #:anim-name 'run) (cons #:anim-frame 2))))
  (test "a plist animation" 5 (animation-tile (list (cons #:animations (list '(#:name idle #:frames ((5 . 2))))))))
  (test "no #:animations: #f" #f (animation-tile '((#:type . box))))
  (test-error "an unknown #:anim-name is named" (an-says? "no animation named" "fly")
              (animation-tile (list (cons #:animations (list an-walk)) (cons #:anim-name 'fly)))))

;; #:anim-event on each of n steps.
(define (an-events e n)
  (let loop ((i 0) (e e) (out '()))
    (if (= i n)
        (reverse out)
        (let ((e2 (apply-animation #f e 16)))
          (loop (+ i 1) e2 (cons (entity-ref e2 #:anim-event #f) out))))))

(test-group "frame events: #:anim-event on the step a frame starts"
  (let ((steps '((#:name . walk) (#:frames . (28 29 30 31)) (#:duration . 2)
                 (#:events . ((1 . step) (3 . step)))))
        (swing '((#:name . swing) (#:frames . (40 41 42)) (#:duration . 2) (#:loop? . #f)
                 (#:events . ((0 . wind-up) (2 . hit))))))
    (test "footsteps on frames 1 and 3, once each, every loop"
          '(#f #f step #f #f #f step #f #f #f step #f)
          (an-events (list (cons #:animations (list steps))) 12))
    (test "frame 0's event on the very first step; a one-shot's last frame fires once"
          '(wind-up #f #f #f hit #f #f #f)
          (an-events (list (cons #:animations (list swing))) 8))
    (test "a one-frame loop fires on each restart" '(tick #f tick #f)
          (an-events (list (cons #:animations (list '((#:name . t) (#:frames . (1)) (#:duration . 2)
                                                       (#:events . ((0 . tick)))))))
                     4))
    (test "after set-animation the new animation's first frame fires" '(wind-up)
          (an-events (set-animation (list (cons #:animations (list steps swing)) (cons #:anim-frame 2)
                                          (cons #:anim-tick 1))
                                    'swing)
                     1))
    (test "the entity alist does not grow over 100 steps" #t
          (let loop ((i 0) (e (list (cons #:animations (list steps)))) (n #f))
            (if (= i 100)
                (<= (length e) (+ n 1))
                (let ((e2 (apply-animation #f e 16)))
                  (loop (+ i 1) e2 (or n (length e2)))))))
    (test-error "bad #:events are named" (an-says? "#:events" "walk")
                (apply-animation #f (list (cons #:animations (list (cons '(#:events . (oops)) an-walk)))) 16))))
