;;; (downstroke animation): frame-by-frame sprite animation of entities.
;;;
;;; An animation is an alist (a plist is accepted too):
;;;   ((#:name . walk) (#:frames . (28 29 (30 . 4))) (#:duration . 10))
;;;   #:name      any value, compared with equal? (usually a symbol)
;;;   #:frames    a non-empty list of frames; a frame is a tile id, or a pair
;;;               (tile-id . ticks) that carries its own duration
;;;   #:duration  ticks of every frame that does not carry its own; it may be
;;;               left out only when every frame carries one
;;;   #:loop?     #f makes the animation one-shot; absent or anything else
;;;               means it loops
;;;   #:events    optional, ((frame-index . event) ...): on the step that
;;;               starts showing that frame, the step writes #:anim-event
;;;               = event (a footstep, an attack's hit frame); on the other
;;;               steps #:anim-event is absent
;;;
;;; An entity animates when it has #:animations (a list of animations).
;;; apply-animation keeps its state in
;;;   #:anim-name      the current animation (default: the first one's name)
;;;   #:anim-frame     index of the frame shown (default 0)
;;;   #:anim-tick      steps the current frame has been shown, this one
;;;                    included (default 0: not shown yet)
;;; and writes #:tile-id (what the renderer draws) and #:anim-duration (the
;;; ticks of the current frame).
;;;
;;; Why ticks and not milliseconds: durations count calls of the step, one
;;; per engine frame, and the dt argument is ignored. The engine runs its
;;; logical frames at a fixed rate, so counting them is exact and
;;; deterministic: a frame of duration 10 is on screen for exactly 10
;;; logical frames, every run, whatever the wall-clock jitter, with no
;;; rounding of accumulated milliseconds deciding when a frame flips.
;;;
;;; The rule of a step: when the current frame has been shown for its whole
;;; duration (tick >= duration) the animation moves to the next frame and
;;; tick becomes 1; otherwise tick grows by 1. Starting from frame 0, tick 0
;;; (which is what set-animation leaves) every frame, the first included,
;;; is therefore shown for exactly its duration in consecutive steps.
;;;
;;; One-shot animations stop on their last frame and keep it. On the step
;;; where the last frame has been shown for its whole duration the step
;;; writes #:anim-finished? #t; the key stays #t while the animation holds,
;;; and set-animation removes it. Looping animations never write it.
;;;
;;; set-animation does not write #:tile-id: the new animation's first frame
;;; appears on the next apply-animation, and from then on it is shown for
;;; exactly its duration. Until an entity has a #:tile-id the renderer
;;; draws the tile animation-tile gives (the current frame's), so an
;;; animated entity shows its first frame before the pipeline ever ran.

(module (downstroke animation)
  (apply-animation set-animation animation-frame-duration
   animation-frame-tile animation-named animation-tile)

  (import scheme (chicken base) (chicken format) (downstroke entity))

  (define (animation-name a) (entity-ref a #:name #f))

  ;; who: the exported procedure the error is reported from.
  (define (animation-frames who a)
    (let ((frames (entity-ref a #:frames #f)))
      (unless (and (pair? frames) (list? frames))
        (error who
               (sprintf "animation ~s: #:frames must be a non-empty list, got ~s"
                        (animation-name a) frames)))
      frames))

  (define (animation-loops? a) (and (entity-ref a #:loop? #t) #t))

  (define (frame-at who a index)
    (let ((frames (animation-frames who a)))
      (unless (and (exact-integer? index) (>= index 0) (< index (length frames)))
        (error who
               (sprintf "animation ~s: frame index ~s is not in 0..~a"
                        (animation-name a) index (- (length frames) 1))))
      (list-ref frames index)))

  (define (positive-ticks? x) (and (exact-integer? x) (> x 0)))

  ;; Ticks frame `index` of `animation` is shown.
  (define (animation-frame-duration animation index)
    (let* ((a (as-entity animation))
           (frame (frame-at 'animation-frame-duration a index))
           (ticks (if (pair? frame) (cdr frame) (entity-ref a #:duration #f))))
      (unless (positive-ticks? ticks)
        (error 'animation-frame-duration
               (if (or (pair? frame) ticks)
                   (sprintf "animation ~s: frame ~a lasts ~s ticks, expected an exact integer > 0"
                            (animation-name a) index ticks)
                   (sprintf "animation ~s: frame ~a has no duration (give the animation #:duration or the frame as (tile-id . ticks))"
                            (animation-name a) index))))
      ticks))

  ;; The tile id frame `index` of `animation` shows.
  (define (animation-frame-tile animation index)
    (let* ((a (as-entity animation))
           (frame (frame-at 'animation-frame-tile a index)))
      (if (pair? frame) (car frame) frame)))

  ;; The animation called `name` in the list, as an alist, or #f.
  (define (animation-named animations name)
    (let loop ((rest animations))
      (cond ((null? rest) #f)
            ((equal? (animation-name (as-entity (car rest))) name) (as-entity (car rest)))
            (else (loop (cdr rest))))))

  (define (entity-animations who e)
    (let ((animations (entity-ref e #:animations #f)))
      (unless (and (pair? animations) (list? animations))
        (error who
               (sprintf "entity ~a: #:animations must be a non-empty list of animations, got ~s"
                        (entity-label e) animations)))
      animations))

  (define (current-name e animations)
    (entity-ref e #:anim-name (animation-name (as-entity (car animations)))))

  (define (lookup who e animations name)
    (or (animation-named animations name)
        (error who
               (sprintf "entity ~a: no animation named ~s (it has ~s)"
                        (entity-label e) name
                        (map (lambda (a) (animation-name (as-entity a))) animations)))))

  (define (state-number who e key)
    (let ((v (entity-ref e key 0)))
      (unless (and (exact-integer? v) (>= v 0))
        (error who (sprintf "entity ~a: ~s is ~s, expected an exact integer >= 0"
                            (entity-label e) key v)))
      v))

  ;; dt is ignored: durations count steps (see the header).
  (define-pipeline (apply-animation animation) (scene entity dt)
    guard: (entity-ref entity #:animations #f)
    (let* ((animations (entity-animations 'apply-animation entity))
           (name (current-name entity animations))
           (anim (lookup 'apply-animation entity animations name))
           (last (- (length (animation-frames 'apply-animation anim)) 1))
           (frame (state-number 'apply-animation entity #:anim-frame))
           (tick (state-number 'apply-animation entity #:anim-tick)))
      (when (> frame last)
        (error 'apply-animation
               (sprintf "entity ~a: #:anim-frame ~a is past the last frame (~a) of animation ~s; switch animations with set-animation, which resets it"
                        (entity-label entity) frame last name)))
      (let* ((duration (animation-frame-duration anim frame))
             (loops? (animation-loops? anim))
             (advance? (>= tick duration))
             (frame2 (cond ((not advance?) frame)
                           ((< frame last) (+ frame 1))
                           (loops? 0)
                           (else last)))
             (duration2 (animation-frame-duration anim frame2))
             (tick2 (cond ((not advance?) (+ tick 1))
                          ((not (= frame2 frame)) 1)
                          (loops? 1)                 ; a one-frame loop restarts
                          (else duration2)))         ; a one-shot holds
             (e (entity-set entity #:anim-name name))
             (e (entity-set e #:anim-frame frame2))
             (e (entity-set e #:anim-tick tick2))
             (e (entity-set e #:tile-id (animation-frame-tile anim frame2)))
             (e (entity-set e #:anim-duration duration2))
             ;; the frame starts being shown on this step: after a move,
             ;; a one-frame loop's restart, or the animation's first step
             (started? (if advance? (or (not (= frame2 frame)) loops?) (= tick 0)))
             (e (frame-event e anim frame2 started?)))
        (if (and (not loops?) (= frame2 last) (>= tick2 duration2))
            (entity-set e #:anim-finished? #t)
            e))))

  ;; #:anim-event for the step: the frame's event when it starts, else none.
  (define (frame-event e anim frame started?)
    (let* ((events (entity-ref anim #:events '()))
           (hit (and started? (pair? events) (frame-event-of e anim events frame))))
      (cond (hit (entity-set e #:anim-event (cdr hit)))
            ((assq #:anim-event e) (entity-remove e #:anim-event))
            (else e))))

  (define (frame-event-of e anim events frame)
    (unless (and (list? events)
                 (let ok ((es events))
                   (or (null? es) (and (pair? (car es)) (exact-integer? (caar es)) (ok (cdr es))))))
      (error 'apply-animation
             (sprintf "entity ~a: animation ~s: #:events must be a list of (frame-index . event), got ~s"
                      (entity-label e) (animation-name anim) events)))
    (assv frame events))

  ;; The tile the entity's animation shows now: its current animation
  ;; (#:anim-name, else the first) at #:anim-frame (else 0); #f for an
  ;; entity without #:animations.
  (define (animation-tile e)
    (let ((animations (entity-ref e #:animations #f)))
      (and animations
           (let* ((animations (entity-animations 'animation-tile e))
                  (anim (lookup 'animation-tile e animations (current-name e animations)))
                  (frame (state-number 'animation-tile e #:anim-frame))
                  (last (- (length (animation-frames 'animation-tile anim)) 1)))
             (animation-frame-tile anim (min frame last))))))

  ;; Switch to animation `name` from its first frame. Calling it with the
  ;; current animation's name changes nothing, so a game may call it every
  ;; frame with the animation it wants.
  (define (set-animation e name)
    (let* ((animations (entity-animations 'set-animation e)))
      (lookup 'set-animation e animations name)
      ;; The current animation is left running, so a game may call this
      ;; every frame; a finished one-shot starts again.
      (if (and (equal? name (current-name e animations))
               (not (entity-ref e #:anim-finished? #f)))
          e
          (entity-remove
           (entity-set (entity-set (entity-set e #:anim-name name) #:anim-frame 0)
                       #:anim-tick 0)
           #:anim-finished?)))))
