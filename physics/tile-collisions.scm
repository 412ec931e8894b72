;;; (downstroke tile-collisions): the tile steps, bodies stopped by solid and one-way tiles, and tile ground.
;;;
;;; docs/physics.org, "Tile collisions": each axis in turn, after that
;;; axis's velocity step, discrete or swept (the entity's #:collision-mode,
;;; else the scene's). Tile ground (docs/physics.org, "Standing on things")
;;; reads the same grid one pixel below the feet.

(module (downstroke tile-collisions)
  (resolve-tile-collisions-x resolve-tile-collisions-y discrete-safe-speed tunnel-risk?
   ;; for sibling modules only: the rules behind the steps, for the motion
   ;; pass and ground detection
   swept-mode? stop-at-tiles-x stop-at-tiles-y tile-ground?)

  (import scheme (chicken base) (chicken format) (chicken foreign)
          (downstroke entity) (downstroke scene) (downstroke map)
          (downstroke body) (downstroke tile-grid) (downstroke escape))

  (foreign-declare "#include \"physics/body.h\"")

  ;; Which tile step an entity gets: its own #:collision-mode, else the
  ;; scene's.
  ;;   discrete  the plain step: the cells the body covers after moving.
  ;;   swept     also the cells it crossed on the way: the scan starts where
  ;;             the body was before this frame's move (pos - v), so no wall
  ;;             is passed at any speed. Wherever the discrete step does not
  ;;             pass a wall, both give the same result.
  (define (swept? scene entity)
    (swept-mode? scene entity (entity-ref entity #:collision-mode #f)))

  ;; `own` is the entity's #:collision-mode value (#f when it has none).
  (define (swept-mode? scene entity own)
    (case (or own (scene-collision-mode scene))
      ((swept) #t)
      ((discrete) #f)
      (else (error 'downstroke
                   (sprintf "entity ~a: #:collision-mode is ~s, not discrete or swept"
                            (entity-label entity) own)))))

  ;; The discrete step cannot pass a wall one tile thick while the body moves
  ;; less than its own size plus a tile per frame on that axis: some cell it
  ;; covers after the move is then one it could not have jumped over. At or
  ;; above this speed (px/frame) it may tunnel.
  (define (discrete-safe-speed size tile) (+ size tile))

  ;; Whether this entity, in this scene, could pass through a wall this
  ;; frame: discrete mode and a speed at or above the safe speed on an axis.
  ;; The debug overlay marks such bodies.
  (define (tunnel-risk? scene entity)
    (let ((tm (scene-tilemap scene)))
      (and tm
           (not (swept? scene entity))
           (or (>= (abs (num entity #:vx))
                   (discrete-safe-speed (num entity #:width) (tilemap-tile-width tm)))
               (>= (abs (num entity #:vy))
                   (discrete-safe-speed (num entity #:height) (tilemap-tile-height tm)))))))

  ;; One tile pass on one axis, for a body at `pos` of `size` with velocity
  ;; v (not 0), spanning across..across+across-size on the other axis:
  ;; where it stops, or #f when no solid tile is in its way. `moved` is how
  ;; far the velocity step moved the body this frame (v, or 0 when the body
  ;; skips that step), so pos - moved is where the frame's motion started.
  ;; swept: the scan starts there (a sweep covers only the motion made this
  ;; frame). one-way?: one-way tiles whose top the body's bottom was at or
  ;; above at that start count too (the y pass of a falling body).
  (define (tile-stop v pos size across across-size swept moved one-way? tile tile-across grid)
    ;; swept: from the line the leading edge was in before the move. Only
    ;; the leading edge counts, so a body leaving a wall it touched is not
    ;; caught by that wall when pos - v rounds (flonums) to just inside it.
    ;; (A zero-size body on a tile edge covers no line: its leading line is
    ;; the one it moves into.)
    (let* ((l0 (span-first pos tile)) (l1 (span-last pos size tile))
           (c0 (span-first across tile-across)) (c1 (span-last across across-size tile-across))
           (start (- pos moved))
           (one-way-top (and one-way? (+ start size))))
      (let ((line (if (> v 0)
                      (nearest-solid-line grid
                                          (if swept
                                              (min (max (span-first start tile) (span-last start size tile)) l0)
                                              l0)
                                          l1 1 c0 c1 one-way-top tile)
                      (nearest-solid-line grid
                                          (if swept
                                              (max (min (span-first start tile) (span-last start size tile)) l1)
                                              l1)
                                          l0 -1 c0 c1))))
        (and line (tile-push-pos v line tile size)))))

  ;; Both tile passes: pos-key is the axis resolved, across-key the other,
  ;; velocity-step the skip symbol of the step that moves pos-key. A
  ;; velocity of 0 snaps nothing. A body with #:drop-through? falls
  ;; through one-way tiles.
  (define (resolve-tiles entity swept pos-key size-key vel-key velocity-step across-key across-size-key
                         tile tile-across grid)
    (let ((v (num entity vel-key)))
      (if (zero? v)
          entity
          (let ((stop (tile-stop v (num entity pos-key) (num entity size-key)
                                 (num entity across-key) (num entity across-size-key)
                                 swept (if (entity-skips-pipeline? entity velocity-step) 0 v)
                                 (and (eq? pos-key #:y) (> v 0) (not (entity-ref entity #:drop-through? #f)))
                                 tile tile-across grid)))
            (if stop
                (entity-set* entity pos-key stop vel-key 0)
                entity)))))

  ;; Swept mode, before a body's first tile pass of the frame: a body that
  ;; starts the frame inside solid tiles (an entity push can leave it
  ;; there) and moves is first taken out of them by the shortest way, so
  ;; that no push ever carries a body through a wall (docs/physics.org, "A
  ;; body that starts a frame inside solid tiles"). A body at rest (both velocities 0) is left where it is,
  ;; as the tile passes leave it. Where a body's frame started is
  ;; pos - v only for a body its velocity moves: one with a #:tween, or one
  ;; that skips both velocity steps (a tween or the game places it), is
  ;; left to the tile passes, as discrete mode resolves it. (sx, sy) is
  ;; where the frame's motion started; the entity is moved by the same
  ;; amount.
  (define (leave-solids entity tm sx sy)
    (if (or (and (zero? (num entity #:vx)) (zero? (num entity #:vy)))
            (entity-ref entity #:tween #f)
            (and (entity-skips-pipeline? entity 'velocity-x)
                 (entity-skips-pipeline? entity 'velocity-y)))
        entity
        (let-values (((dx dy) (tile-way-out tm sx sy (num entity #:width) (num entity #:height))))
          (if (and (eqv? dx 0) (eqv? dy 0))
              entity
              (entity-set* entity #:x (+ (num entity #:x) dx) #:y (+ (num entity #:y) dy))))))

  ;; Where the frame's motion started on one axis: pos less what the
  ;; velocity step moved (nothing when the body skips that step).
  (define (motion-start entity pos-key vel-key velocity-step)
    (if (entity-skips-pipeline? entity velocity-step)
        (num entity pos-key)
        (- (num entity pos-key) (num entity vel-key))))

  (define (stop-at-tiles-x scene entity)
    (let* ((tm (scene-tilemap scene))
           (swept (swept? scene entity))
           (entity (if swept
                       (leave-solids entity tm (motion-start entity #:x #:vx 'velocity-x) (num entity #:y))
                       entity)))
      (resolve-tiles entity swept #:x #:width #:vx 'velocity-x #:y #:height
                     (tilemap-tile-width tm) (tilemap-tile-height tm) (column-grid tm))))

  ;; A body that skips the x tile pass leaves solid tiles here.
  (define (stop-at-tiles-y scene entity)
    (let* ((tm (scene-tilemap scene))
           (swept (swept? scene entity))
           (entity (if (and swept (entity-skips-pipeline? entity 'tile-collisions-x))
                       (leave-solids entity tm (num entity #:x) (motion-start entity #:y #:vy 'velocity-y))
                       entity)))
      (resolve-tiles entity swept #:y #:height #:vy 'velocity-y #:x #:width
                     (tilemap-tile-height tm) (tilemap-tile-width tm) (row-grid tm))))

  (define-pipeline (resolve-tile-collisions-x tile-collisions-x) (scene entity dt)
    guard: (scene-tilemap scene)
    (stop-at-tiles-x scene entity))

  (define-pipeline (resolve-tile-collisions-y tile-collisions-y) (scene entity dt)
    guard: (scene-tilemap scene)
    (stop-at-tiles-y scene entity))

  ;; Tile ground: the row one pixel below the feet, (+ y h 1), under either
  ;; lower corner. The corners are the first and last columns the body
  ;; covers; a zero-width body on a tile edge probes the one column at x.
  ;; A one-way tile there counts when the body's bottom is at or above its
  ;; top and the body is not dropping through.
  (define (tile-ground? tm x y w h drop?)
    (let* ((th (tilemap-tile-height tm))
           (row (cell-of (+ y h 1) th))
           (c0 (span-first x (tilemap-tile-width tm)))
           (c1 (max c0 (span-last x w (tilemap-tile-width tm))))
           (platform? (and (not drop?) (<= (+ y h) (* row th)))))
      (or (tilemap-solid? tm c0 row)
          (tilemap-solid? tm c1 row)
          (and platform? (or (tilemap-one-way? tm c0 row) (tilemap-one-way? tm c1 row))))))

)
