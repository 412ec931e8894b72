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
   swept-mode? stop-at-tiles-x stop-at-tiles-y tile-ground? climbing? slope-cut-of ceiling-cut-of)

  (import scheme (chicken base) (chicken format) (chicken foreign)
          (downstroke entity) (downstroke scene) (downstroke map)
          (downstroke body) (downstroke tile-grid) (downstroke escape) (downstroke slopes))

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
  ;; where it stops, or #f when no solid tile is in its way. `start` is
  ;; where the frame's motion on this axis started: pos - v, or pos when
  ;; the body skips that axis's velocity step, or where the escape put it
  ;; (velocity-moved, leave-solids). swept: the scan starts there (a sweep
  ;; covers only the motion made this frame). one-way?: one-way tiles
  ;; whose top the body's bottom was at or above at that start count too
  ;; (the y pass of a falling body).
  ;; push-size: the size the stop position is computed with (size, but a
  ;; body near a slope tests a box shorter than itself, docs/physics.org
  ;; "Slopes").
  (define (tile-stop v pos size across across-size swept start one-way? tile tile-across grid
                     #!optional (push-size size))
    ;; swept: from the line of cells the leading edge was in at the start,
    ;; the cell holding it on the side it moves to: moving right (down),
    ;; the cell of start + size, floor((start + size) / T); moving left
    ;; (up), the cell just below start, ceil(start / T) - 1. An edge off
    ;; the grid lines is in the box's last (first) cell; an edge exactly
    ;; on a grid line is in the cell beyond it, which the box does not
    ;; cover, so a box that starts inside a solid cell (a tweened body is
    ;; not taken out) is not thrown back by that cell as it leaves it. The
    ;; scan never starts past the line the discrete step starts at. Only
    ;; the leading edge counts, so a body leaving a wall it touched is not
    ;; caught by that wall when pos - v rounds (flonums) to just inside it.
    (let* ((l0 (span-first pos tile)) (l1 (span-last pos size tile))
           (c0 (span-first across tile-across)) (c1 (span-last across across-size tile-across))
           (one-way-top (and one-way? (+ start size))))
      (let ((line (if (> v 0)
                      (nearest-solid-line grid
                                          (if swept (min (cell-of (+ start size) tile) l0) l0)
                                          l1 1 c0 c1 one-way-top tile)
                      (nearest-solid-line grid
                                          (if swept (max (- (cell-ceiling start tile) 1) l1) l1)
                                          l0 -1 c0 c1))))
        (and line (tile-push-pos v line tile push-size)))))

  ;; Whether a body is on a ladder (docs/physics.org, "Ladders"): a
  ;; #:climber? whose #:climbing? the climbing step set. Gravity leaves it
  ;; alone and it passes one-way tiles (a ladder's top) as a body with
  ;; #:drop-through? does.
  (define (climbing? entity)
    (and (entity-ref entity #:climbing? #f) (entity-ref entity #:climber? #f)))

  ;; Both tile passes: pos-key is the axis resolved, across-key the other,
  ;; `start` where this axis's motion started. A velocity of 0 snaps
  ;; nothing. A body with #:drop-through?, or climbing, falls through
  ;; one-way tiles (passes-one-way?). The box tested is the body's,
  ;; except near a slope (cut: how much the y extent is shortened at the
  ;; bottom, 0 elsewhere). climbers?: whether the body may be climbing
  ;; (the motion pass asks only in a scene with a climber).
  (define (resolve-tiles entity swept start pos-key size-key vel-key across-key across-size-key
                         tile tile-across grid #!optional (cut 0) (climbers? #t) (top-cut 0))
    (let ((v (num entity vel-key)))
      (if (zero? v)
          entity
          (let ((stop (tile-box-stop entity v swept start pos-key size-key across-key across-size-key
                                     tile tile-across grid cut climbers? top-cut)))
            (if stop
                (entity-set* entity pos-key stop vel-key (rebound entity v))
                entity)))))

  ;; Where the (cut) box stops on that axis, or #f.
  (define (passes-one-way? entity climbers?)
    (or (entity-ref entity #:drop-through? #f)
        (and climbers? (climbing? entity))))

  ;; top-cut: how much the box is shortened at the top near a ceiling
  ;; slope (0 elsewhere). On y, `start` is where the body's top started;
  ;; the answer is the body's y: a stop going down puts the whole box on
  ;; the tile, one going up the whole box under it.
  (define (tile-box-stop entity v swept start pos-key size-key across-key across-size-key
                         tile tile-across grid cut climbers? #!optional (top-cut 0))
    (let ((size (num entity size-key)) (across-size (num entity across-size-key)))
      (if (eq? pos-key #:y)
          (tile-stop v (+ (num entity pos-key) top-cut) (- size cut top-cut) (num entity across-key) across-size
                     swept (+ start top-cut)
                     (and (> v 0) (not (passes-one-way? entity climbers?)))
                     tile tile-across grid size)
          (tile-stop v (num entity pos-key) size (+ (num entity across-key) top-cut) (- across-size cut top-cut)
                     swept start #f tile tile-across grid))))

  ;; The velocity a body leaves a tile with on the axis it hit it: 0, or
  ;; with #:bounce b, -v * b (docs/physics.org, "Body controls"). A body
  ;; that hits at 1 px/frame or less stops, so one resting on a floor
  ;; under gravity settles.
  (define (rebound entity v)
    (let ((b (assq #:bounce entity)))
      (if (and b (> (abs v) 1))
          (- (* v (num entity #:bounce)))
          0)))

  ;; Swept mode, before a body's first tile pass of the frame: a body that
  ;; starts the frame inside solid tiles (an entity push can leave it
  ;; there) and moves is first taken out of them by the shortest way, so
  ;; that no push ever carries a body through a wall (docs/physics.org, "A
  ;; body that starts a frame inside solid tiles"). A body at rest (both
  ;; velocities 0) is left where it is, as the tile passes leave it. Where
  ;; a body's frame started is pos - v only for a body its velocity moves:
  ;; one with a #:tween, or one that skips both velocity steps (a tween or
  ;; the game places it), is left to the tile passes, as discrete mode
  ;; resolves it. (sx, sy) is where the frame's motion started, (mx, my)
  ;; how far the velocity steps have moved the body since. The escape
  ;; puts the start where escape-place says and the body as far from it
  ;; as it was; the answer is the entity and the new start on `axis`
  ;; (#:x or #:y), which that axis's sweep starts from, as it is, not
  ;; recomputed from the new position (flonums would round it).
  (define (leave-solids entity tm sx sy mx my axis #!optional (cut 0) (top-cut 0))
    (if (or (and (zero? (num entity #:vx)) (zero? (num entity #:vy)))
            (entity-ref entity #:tween #f)
            (and (entity-skips-pipeline? entity 'velocity-x)
                 (entity-skips-pipeline? entity 'velocity-y)))
        (values entity (if (eq? axis #:x) sx sy))
        (let-values (((nx ny) (let-values (((nx ny) (escape-place tm sx (+ sy top-cut) (num entity #:width)
                                                                  (- (num entity #:height) cut top-cut))))
                                (values nx (if (eqv? top-cut 0) ny (- ny top-cut))))))
          (values (if (and (eqv? nx sx) (eqv? ny sy))
                      entity
                      (entity-set* entity
                                   #:x (if (eqv? nx sx) (num entity #:x) (+ nx mx))
                                   #:y (if (eqv? ny sy) (num entity #:y) (+ ny my))))
                  (if (eq? axis #:x) nx ny)))))

  ;; How far the velocity step moved the body on one axis this frame:
  ;; its velocity, or nothing when it skips that step.
  (define (velocity-moved entity vel-key velocity-step)
    (if (entity-skips-pipeline? entity velocity-step) 0 (num entity vel-key)))

  ;; Near a slope (docs/physics.org, "Slopes"): how much of the box's
  ;; bottom the tile passes leave out, when a slope cell lies in the
  ;; columns the foot crossed on x this frame (x - mx + w/2 to x + w/2),
  ;; in the rows within that much of the foot's path on y (y + h - my to
  ;; y + h); 0 elsewhere and on maps without slopes. It is slope-cut's
  ;; w/2 + |mx| + max(my, 0) (at most the height): a lower corner sinks
  ;; up to w/2 below the foot on a 45 degree floor, and the foot itself
  ;; is up to |mx| below the floor that rose under it this frame and my
  ;; below where it started on y.
  (define (slope-cut-of tm entity mx my)
    (if (slope-map? tm)
        (let* ((x (num entity #:x)) (w (num entity #:width)) (h (num entity #:height))
               (b (+ (num entity #:y) h))
               (d (slope-cut w mx my h))
               (fx (+ x (/ w 2))))
          (if (foot-near-slope? tm (- fx mx) fx (- (min b (- b my)) d) (+ (max b (- b my)) d))
              d
              0))
        0))

  ;; Near a ceiling slope (docs/physics.org, "Ceiling slopes"): how much
  ;; of the box's top the tile passes leave out, when a ceiling slope cell
  ;; lies in the columns the head crossed on x this frame (x - mx + w/2 to
  ;; x + w/2), in the rows within that much of its path on y (y - my to
  ;; y); #f elsewhere and on maps without ceiling slopes. It is
  ;; w/2 + |mx| + max(-my, 0), but never more than h - 1 - cut (cut: the
  ;; bottom's, slope-cut-of), so that a pixel row of the box is left; it
  ;; may be 0, and the head's rules apply all the same.
  (define (ceiling-cut-of tm entity mx my cut)
    (and (ceiling-map? tm)
         (let* ((x (num entity #:x)) (w (num entity #:width)) (h (num entity #:height))
                (y (num entity #:y))
                (d (max 0 (min (- h 1 cut) (+ (/ w 2) (abs mx) (max (- my) 0)))))
                (hx (+ x (/ w 2))))
           (and (head-near-ceiling? tm (- hx mx) hx (- (min y (- y my)) d) (+ (max y (- y my)) d))
                d))))

  ;; The x pass: a swept body first leaves solid tiles, from where its
  ;; frame started, (x - vx, y). Near a ceiling slope the head is swept
  ;; too (head-wall): of the box's stop and the head's, the first met.
  (define (stop-at-tiles-x scene entity)
    (let* ((tm (scene-tilemap scene))
           (swept (swept? scene entity))
           (mx (velocity-moved entity #:vx 'velocity-x))
           (sx (- (num entity #:x) mx))
           (cut (slope-cut-of tm entity mx 0))
           (head? (ceiling-cut-of tm entity mx 0 cut))
           (top-cut (or head? 0)))
      (let-values (((entity sx) (if swept
                                    (leave-solids entity tm sx (num entity #:y) mx 0 #:x cut top-cut)
                                    (values entity sx))))
        (let ((stopped (if head?
                           (stop-head-x entity tm swept sx cut top-cut)
                           (resolve-tiles entity swept sx #:x #:width #:vx #:y #:height
                                          (tilemap-tile-width tm) (tilemap-tile-height tm) (column-grid tm) cut #f))))
          (if (slope-map? tm)     ; any slope cells, floor or ceiling
              (note-x-start stopped (and (or (not (eqv? cut 0)) head?)
                                         (not (and (eqv? (num stopped #:x) (num entity #:x))
                                                   (eqv? (num stopped #:vx) (num entity #:vx))))
                                         sx))
              stopped)))))

  ;; A body near a slope that the x pass stopped (at a wall, or its head
  ;; at a ceiling slope) has moved less on x than its #:vx, which the stop
  ;; changed: the y pass, whose rules depend on that motion, reads it from
  ;; where the frame's x motion started, noted here as #:x-pass-start (x
  ;; - vx, or where the escape put it) and removed by the y pass. A note
  ;; left from an earlier frame (a body that skipped the y pass) goes.
  (define (note-x-start entity start)
    (cond (start (entity-set entity #:x-pass-start start))
          ((assq #:x-pass-start entity) (entity-remove entity #:x-pass-start))
          (else entity)))

  ;; The x pass near a ceiling slope: the box without its lowest `cut`
  ;; and its top `top-cut` px meets solid tiles; the head, x + w/2 at
  ;; height y, is swept from where this frame's x motion started (sx)
  ;; and stops where it would pass into a ceiling slope's solid part or a
  ;; solid cell of its row; the nearer stop holds.
  (define (stop-head-x entity tm swept sx cut top-cut)
    (let ((v (num entity #:vx)))
      (if (zero? v)
          entity
          (let* ((w (num entity #:width)) (x (num entity #:x))
                 (box (tile-box-stop entity v swept sx #:x #:width #:y #:height
                                     (tilemap-tile-width tm) (tilemap-tile-height tm) (column-grid tm)
                                     cut #f top-cut))
                 (head (and (not (= sx x))
                            (let ((p (head-wall tm (num entity #:y) (+ sx (/ w 2)) (+ x (/ w 2)))))
                              (and p (- p (/ w 2))))))
                 (stop (cond ((and box head) (if (> v 0) (min box head) (max box head)))
                             (else (or box head)))))
            (if stop
                (entity-set* entity #:x stop #:vx (rebound entity v))
                entity)))))

  ;; The y pass. A swept body that skips the x tile pass leaves solid
  ;; tiles here, from where its frame started on both axes, (x - vx,
  ;; y - vy).
  (define (stop-at-tiles-y scene entity #!optional (climbers? #t))
    (let* ((tm (scene-tilemap scene))
           (x-start (and (slope-map? tm) (assq #:x-pass-start entity)))
           (entity (if x-start (entity-remove entity #:x-pass-start) entity))
           (swept (swept? scene entity))
           (my (velocity-moved entity #:vy 'velocity-y))
           (sy (- (num entity #:y) my))
           ;; how far the body moved on x this frame: its #:vx, unless the
           ;; x pass stopped it (note-x-start)
           (mx (if x-start (- (num entity #:x) (cdr x-start)) (velocity-moved entity #:vx 'velocity-x)))
           (cut (slope-cut-of tm entity mx my))
           (head? (ceiling-cut-of tm entity mx my cut))
           (top-cut (or head? 0)))
      (let-values (((entity sy)
                    (if (and swept (entity-skips-pipeline? entity 'tile-collisions-x))
                        (leave-solids entity tm (- (num entity #:x) mx) sy mx my #:y cut top-cut)
                        (values entity sy))))
        (if (and (eqv? cut 0) (not head?))
            (resolve-tiles entity swept sy #:y #:height #:vy #:x #:width
                           (tilemap-tile-height tm) (tilemap-tile-width tm) (row-grid tm) 0 climbers?)
            (land-near-slope entity tm swept sy mx cut climbers? head? top-cut (and x-start #t))))))

  ;; The y pass near a slope (docs/physics.org, "Slopes"). The box without
  ;; its lowest `cut` px (slope-cut-of) meets solid and one-way tiles as any box does (a
  ;; stop going down puts the whole box on the tile); a body going down
  ;; (vy > 0) also has its foot, x + w/2, swept from where the frame's
  ;; motion left it on y, y + h - my, raised by |mx| (the most a floor of
  ;; at most 45 degrees rises under a foot that moved mx on x), down to
  ;; y + h, and by |mx| more for a body that was on the ground (so that
  ;; it follows a floor going down): the first floor in that span stops
  ;; it there. Of the two stops, the higher one holds.
  ;; Near a ceiling slope (head?) the box is also without its top
  ;; `top-cut` px, and a body going up (vy < 0) has its head, x + w/2,
  ;; swept from where the frame's y motion started, sy, up to y: the
  ;; first ceiling in that span stops it there (head-ceiling). Of the
  ;; box's stop and the head's, the lower one holds.
  ;; stopped-on-x?: the x pass stopped the body this frame, and set its
  ;; #:vx.
  (define (land-near-slope entity tm swept sy mx cut climbers? #!optional head? (top-cut 0) stopped-on-x?)
    (let* ((v (num entity #:vy))
           (h (num entity #:height))
           (box (and (not (zero? v))
                     (tile-box-stop entity v swept sy #:y #:height #:x #:width
                                    (tilemap-tile-height tm) (tilemap-tile-width tm) (row-grid tm)
                                    cut climbers? top-cut)))
           (head (and head? (< v 0)
                      (head-ceiling tm (+ (num entity #:x) (/ (num entity #:width) 2)) (num entity #:y) sy)))
           (foot (and (> v 0) (not (eqv? cut 0))
                      (let* ((b (+ (num entity #:y) h))
                             (from (+ sy h))
                             (level (foot-ground tm (+ (num entity #:x) (/ (num entity #:width) 2))
                                                 (- from (abs mx))
                                                 (if (entity-ref entity #:on-ground? #f) (+ b (abs mx)) b)
                                                 from (passes-one-way? entity climbers?))))
                        (and level (- level h)))))
           (stop (cond ((and box foot) (min box foot))
                       ((and box head) (max box head))
                       (else (or box foot head)))))
      (cond ((and stop (> v 0) (< stop (num entity #:y)) (not (zero? mx))
                  (or (let ((ceiling (head-ceiling tm (+ (num entity #:x) (/ (num entity #:width) 2))
                                                   stop (num entity #:y))))
                        (and ceiling (> ceiling stop)))
                      (lifted-into-solid? tm entity stop h)))
             ;; lifted by the floor into a ceiling (at its head, or the box
             ;; at rest into solid cells): the body does not fit there, and
             ;; goes back to where this frame's x motion started, stopped on
             ;; x as by a wall (by the x pass's stop, when it made one)
             (land-near-slope (entity-set* entity #:x (- (num entity #:x) mx)
                                           #:vx (if stopped-on-x? (num entity #:vx) (rebound entity (num entity #:vx))))
                              tm swept sy 0 cut climbers? head? top-cut stopped-on-x?))
            (stop (entity-set* entity #:y stop #:vy (rebound entity v)))
            (else entity))))

  ;; Whether a solid cell lies in the band [top, bottom) of the columns a
  ;; box of width w at x covers.
  (define (solid-across? tm x w top bottom)
    (let ((tw (tilemap-tile-width tm)) (th (tilemap-tile-height tm))
          (col0 (tilemap-origin-col tm)) (row0 (tilemap-origin-row tm)))
      ;; only the map's cells: a body far outside it (any number) costs
      ;; no more than one inside
      (let ((c0 (max col0 (span-first x tw)))
            (c1 (min (+ col0 (tilemap-width tm) -1) (span-last x w tw)))
            (r0 (max row0 (span-first top th)))
            (r1 (min (+ row0 (tilemap-height tm) -1) (span-last top (- bottom top) th))))
        (let cols ((c c0))
          (and (<= c c1)
               (or (let rows ((r r0))
                     (and (<= r r1) (or (tilemap-solid? tm c r) (rows (+ r 1)))))
                   (cols (+ c 1))))))))

  ;; Whether a body h px tall lifted to y has its box, less what its cuts
  ;; at rest leave out, in solid cells. Most lifts clear the whole box,
  ;; which needs no cuts; the cuts only ever narrow it.
  (define (lifted-into-solid? tm entity y h)
    (let ((x (num entity #:x)) (w (num entity #:width)))
      (and (solid-across? tm x w y (+ y h))
           (let-values (((bottom-cut top-cut) (cuts-at-rest tm (entity-set entity #:y y))))
             (solid-across? tm x w (+ y top-cut) (- (+ y h) bottom-cut))))))

  ;; What a body's box leaves out at its bottom and top where it is, with
  ;; no motion: near a slope its lower corners, near a ceiling slope its
  ;; upper ones, may be in the cells beside the foot and the head, as the
  ;; tile passes let them be (the cuts contacts use too).
  (define (cuts-at-rest tm entity)
    (let ((cut (slope-cut-of tm entity 0 0)))
      (values cut (or (ceiling-cut-of tm entity 0 0 cut) 0))))

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
    (or (box-ground? tm x y w h drop?)
        (and (slope-map? tm) (foot-on-slope? tm x y w h))))

  (define (box-ground? tm x y w h drop?)
    (let* ((th (tilemap-tile-height tm))
           (row (cell-of (+ y h 1) th))
           (c0 (span-first x (tilemap-tile-width tm)))
           (c1 (max c0 (span-last x w (tilemap-tile-width tm))))
           (platform? (and (not drop?) (<= (+ y h) (* row th)))))
      (or (tilemap-solid? tm c0 row)
          (tilemap-solid? tm c1 row)
          (and platform? (or (tilemap-one-way? tm c0 row) (tilemap-one-way? tm c1 row))))))

)
