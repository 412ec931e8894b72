;;; (downstroke ladders): climbing ladder tiles, the step apply-climbing.
;;;
;;; docs/physics.org, "Ladders". A ladder is a map cell (tilemap-ladder?);
;;; the top cell of each is one-way in the solid grid, so every body stands
;;; on it. A body with #:climber? grabs a ladder when the game's #:climb
;;; (-1 up, 1 down, 0 neither) asks, climbs it at #:climb-speed without
;;; gravity, and lets go by jumping, stepping off its column, climbing past
;;; its bottom end, reaching the floor, or reaching the top, where it
;;; stands. The step runs after tweens and before acceleration; the engine
;;; runs it only in a scene with a climber.

(module (downstroke ladders)
  (apply-climbing entity-ladder-column)

  (import scheme (chicken base) (chicken foreign)
          (downstroke entity) (downstroke scene) (downstroke map)
          (downstroke body) (downstroke tuning) (downstroke tile-grid))

  (foreign-declare "#include \"physics/body.h\"")

  ;; The column of cells holding the body's horizontal centre,
  ;; floor((x + w/2) / T): the ladder it can climb.
  (define (entity-ladder-column entity tm)
    (cell-of (+ (num entity #:x) (/ (num entity #:width) 2)) (tilemap-tile-width tm)))

  ;; Whether column col has a ladder cell among rows r0..r1.
  (define (ladder-in-rows? tm col r0 r1)
    (and (<= r0 r1)
         (or (tilemap-ladder? tm col r0) (ladder-in-rows? tm col (+ r0 1) r1))))

  ;; The highest ladder-top line the body's bottom rises to or past,
  ;; moving from b0 up to b1 (b1 < b0): the top edge L = r*H of a ladder
  ;; top in column col with b1 <= L < b0, the first met (largest L); #f.
  (define (top-reached tm col b0 b1 th)
    (let loop ((r (- (cell-ceiling b0 th) 1)))
      (cond ((< r (cell-ceiling b1 th)) #f)
            ((tilemap-ladder-top? tm col r) (* r th))
            (else (loop (- r 1))))))

  ;; The step's rule, for a climber in a scene with a map.
  (define (climb scene entity)
    (let* ((tm (scene-tilemap scene))
           (tw (tilemap-tile-width tm)) (th (tilemap-tile-height tm))
           (x (num entity #:x)) (y (num entity #:y))
           (w (num entity #:width)) (h (num entity #:height))
           (c (num entity #:climb))
           (jump? (< (num entity #:ay) 0))
           (was? (and (entity-ref entity #:climbing? #f) #t))
           (col (entity-ladder-column entity tm))
           (bottom (+ y h))
           ;; a ladder cell among the rows the body covers
           (covered? (ladder-in-rows? tm col (span-first y th) (span-last y h th)))
           ;; a ladder cell just under its feet (its bottom on a grid line)
           (below? (let ((q (/ bottom th))) (and (integer? q) (tilemap-ladder? tm col (->integer q)))))
           ;; a solid tile under its feet in the ladder's column (the row
           ;; one pixel below them, as for ground): the ladder's foot
           (floor? (lambda () (tilemap-solid? tm col (cell-of (+ bottom 1) th))))
           (on? (cond (jump? #f)
                      (was? (and (or covered? below?) (not (and (> c 0) (floor?)))))
                      ((< c 0) covered?)
                      ((> c 0) (and (or covered? below?) (not (floor?))))
                      (else #f))))
      (cond ((and (not on?) was?) (entity-set* entity #:climbing? #f #:vy 0))
            ((not on?) entity)
            (else
             (let* ((x (if was? x (+ (* col tw) (floor (/ (- tw w) 2)))))
                    (speed (if (assq #:climb-speed entity) (num entity #:climb-speed) *climb-speed*))
                    (vy (* c speed))
                    (top (and (< vy 0) (top-reached tm col bottom (+ bottom vy) th)))
                    (e (if (eqv? x (num entity #:x)) entity (entity-set entity #:x x)))
                    (e (if (or (not (assq #:ay e)) (eqv? 0 (num e #:ay))) e (entity-set e #:ay 0))))
               (if top
                   ;; at the top: standing on it, this frame's gravity lands
                   ;; it there as on any one-way tile
                   (entity-set* e #:y (- top h) #:vy 0 #:climbing? #f)
                   (entity-set* e #:vy vy #:climbing? #t)))))))

  ;; The step: #:climbing? and the velocity of a climber (docs/physics.org,
  ;; "Ladders"). Without a map there is no ladder: a climber lets go.
  (define-pipeline (apply-climbing climbing) (scene entity dt)
    guard: (entity-ref entity #:climber? #f)
    (if (scene-tilemap scene)
        (climb scene entity)
        (if (entity-ref entity #:climbing? #f)
            (entity-set* entity #:climbing? #f #:vy 0)
            entity)))
)
