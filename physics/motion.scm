;;; (downstroke motion): steps 2-7 of the pipeline: acceleration, gravity, velocity, and the motion pass that runs them with the tile steps.
;;;
;;; docs/physics.org, "The pipeline". Each step is a rule behind its guard
;;; and skip symbol; motion-pass runs steps 2-7 (and ground detection when
;;; asked) for a whole frame, through the C kernel motion.c for the
;;; entities whose numbers it takes, through the rules for any other.

(module (downstroke motion)
  (apply-acceleration apply-gravity apply-body-controls apply-velocity-x apply-velocity-y
   step-motion motion-pass
   ;; for sibling modules only (and tests and measurements): how many
   ;; entities the kernel has left to the readable steps so far
   motion-kernel-declines)

  (import scheme (chicken base) (chicken fixnum) (chicken foreign) srfi-4
          (downstroke entity) (downstroke scene) (downstroke map) (downstroke c-constants)
          (downstroke body) (downstroke tuning) (downstroke tile-grid)
          (downstroke tile-collisions) (downstroke contacts))

  (foreign-declare "#include \"physics/body.h\"")
  (foreign-declare "#include \"physics/motion.c\"")

  ;;; Per-entity steps, in pipeline order

  ;; Each motion step is its rule (a procedure of the scene and the entity)
  ;; behind its guard and skip symbol. The rules are docs/physics.org's motion,
  ;; written once: the steps run them, and so does the motion pass for
  ;; every entity its C kernel does not take (motion-steps, below).

  ;; The guard of acceleration and gravity.
  (define (gravity-on? entity) (entity-ref entity #:gravity? #f))

  ;; #:ay is added to #:vy and consumed (set to 0).
  (define (accelerate scene entity)
    (let ((ay (num entity #:ay)))
      (if (and (eq? ay 0) (assq #:ay entity))
          entity                        ; nothing to consume: no new entity
          (entity-set (entity-set entity #:vy (sum entity #:vy (num entity #:vy) ay)) #:ay 0))))

  (define (fall scene entity)
    (entity-set entity #:vy (sum entity #:vy (num entity #:vy) *gravity*)))

  (define (move-x scene entity)
    (entity-set entity #:x (sum entity #:x (num entity #:x) (num entity #:vx))))

  (define (move-y scene entity)
    (entity-set entity #:y (sum entity #:y (num entity #:y) (num entity #:vy))))

  (define-pipeline (apply-acceleration acceleration) (scene entity dt)
    guard: (gravity-on? entity)
    (accelerate scene entity))

  ;; A climbing body (docs/physics.org, "Ladders") is out of gravity's reach.
  (define-pipeline (apply-gravity gravity) (scene entity dt)
    guard: (and (gravity-on? entity) (not (climbing? entity)))
    (fall scene entity))

  ;; Body controls (docs/physics.org, "Body controls"), opt-in keys:
  ;; #:drag (on the ground: #:on-ground? from the frame before) or
  ;; #:air-drag (otherwise) takes that much off |vx|, never past 0; then
  ;; #:max-vx and #:max-vy clamp |vx| and |vy|. Exact with exact numbers.
  (define (has-controls? e)
    (or (assq #:drag e) (assq #:air-drag e) (assq #:max-vx e) (assq #:max-vy e)))

  ;; Only a velocity that changes is written.
  (define (control scene e)
    (let* ((vx0 (num e #:vx)) (vy0 (num e #:vy))
           (drag (num e (if (entity-ref e #:on-ground? #f) #:drag #:air-drag)))
           (vx (cond ((zero? drag) vx0)
                     ((> vx0 0) (let ((v (- vx0 drag))) (if (> v 0) v 0)))
                     ((< vx0 0) (let ((v (+ vx0 drag))) (if (< v 0) v 0)))
                     (else vx0)))
           (vx (if (assq #:max-vx e) (clamp vx (num e #:max-vx)) vx))
           (vy (if (assq #:max-vy e) (clamp vy0 (num e #:max-vy)) vy0))
           (e (if (eqv? vx vx0) e (entity-set e #:vx vx))))
      (if (eqv? vy vy0) e (entity-set e #:vy vy))))

  ;; v, or the limit it passes (no inexact contagion when it is within)
  (define (clamp v limit) (cond ((> v limit) limit) ((< v (- limit)) (- limit)) (else v)))

  (define-pipeline (apply-body-controls controls) (scene entity dt)
    guard: (has-controls? entity)
    (control scene entity))

  (define-pipeline (apply-velocity-x velocity-x) (scene entity dt)
    (move-x scene entity))

  (define-pipeline (apply-velocity-y velocity-y) (scene entity dt)
    (move-y scene entity))

  ;;; Steps 2-7 in one pass

  ;; Steps 2-7 of docs/physics.org's pipeline (acceleration, gravity, velocity x, tile
  ;; collisions x, velocity y, tile collisions y) for one entity, giving
  ;; exactly what running those six steps one after the other gives: the
  ;; motion pass of a one-entity frame (below).
  (define (step-motion scene e dt)
    ((motion-pass scene dt) e))

  ;; The six steps one after the other, as the pipeline runs them. An
  ;; entity without #:skip-pipelines has each guard read once and each rule
  ;; called directly; any other runs the steps themselves.
  ;; controls?: whether the entity may have body controls (the pass asks
  ;; only when some entity of the scene has them); climbers?: whether it
  ;; may be climbing a ladder, likewise.
  (define (motion-steps scene e dt controls? climbers?)
    (if (entity-ref e #:skip-pipelines #f)  ; a list, or the steps' error
        (let* ((e (apply-acceleration scene e dt))
               (e (apply-gravity scene e dt))
               (e (if controls? (apply-body-controls scene e dt) e))
               (e (apply-velocity-x scene e dt))
               (e (resolve-tile-collisions-x scene e dt))
               (e (apply-velocity-y scene e dt)))
          (resolve-tile-collisions-y scene e dt))
        (let* ((map? (scene-tilemap scene))
               (e (if (gravity-on? e)
                      (let ((e (accelerate scene e)))
                        (if (and climbers? (climbing? e)) e (fall scene e)))
                      e))
               (e (if (and controls? (has-controls? e)) (control scene e) e))
               (e (move-x scene e))
               (e (if map? (stop-at-tiles-x scene e) e))
               (e (move-y scene e)))
          (if map? (stop-at-tiles-y scene e climbers?) e))))

  ;; What rewrite-motion's callers pass for a key they leave as it is: the
  ;; symbol keep, which no value they write (a number or a boolean) can be.

  ;; The entity with the motion keys written: a present key is replaced
  ;; where it is, in a copy that stops after the last one (the rest is
  ;; shared); an absent key goes in front, in the order the steps would add
  ;; them (with gravity vy, ay, x, vx, y; without x, vx, y, vy), and
  ;; #:on-ground? (ground detection, after them) in front of all.
  (define (rewrite-motion e grav xp x yp y vxp vx vyp vy ayp ay onp on)
    (define (replaced? p v) (and p (not (eq? v 'keep))))
    (define (added? p v) (and (not p) (not (eq? v 'keep))))
    (let* ((n (fx+ (fx+ (fx+ (if (replaced? xp x) 1 0) (if (replaced? yp y) 1 0))
                        (if (replaced? onp on) 1 0))
                   (fx+ (fx+ (if (replaced? vxp vx) 1 0) (if (replaced? vyp vy) 1 0))
                        (if (replaced? ayp ay) 1 0))))
           (copy (let copy ((rest e) (n n))
                   (if (fx= n 0)
                       rest
                       (let ((p (car rest)))
                         (cond ((and (eq? p xp) (replaced? xp x)) (cons (cons #:x x) (copy (cdr rest) (fx- n 1))))
                               ((and (eq? p yp) (replaced? yp y)) (cons (cons #:y y) (copy (cdr rest) (fx- n 1))))
                               ((and (eq? p vxp) (replaced? vxp vx)) (cons (cons #:vx vx) (copy (cdr rest) (fx- n 1))))
                               ((and (eq? p vyp) (replaced? vyp vy)) (cons (cons #:vy vy) (copy (cdr rest) (fx- n 1))))
                               ((and (eq? p ayp) (replaced? ayp ay)) (cons (cons #:ay ay) (copy (cdr rest) (fx- n 1))))
                               ((and (eq? p onp) (replaced? onp on)) (cons (cons #:on-ground? on) (copy (cdr rest) (fx- n 1))))
                               (else (cons p (copy (cdr rest) n))))))))
           (add (lambda (p v key out) (if (added? p v) (cons (cons key v) out) out))))
      (add onp on #:on-ground?
           (if grav
               (add yp y #:y (add vxp vx #:vx (add xp x #:x (add ayp ay #:ay (add vyp vy #:vy copy)))))
               (add vyp vy #:vy (add yp y #:y (add vxp vx #:vx (add xp x #:x copy))))))))

  ;;; The motion pass of a frame

  ;; The exact twin of motion-steps (and of ground detection), in C.
  ;; CHICKEN compiles every value-producing conditional and loop of such a
  ;; body into a closure holding its two dozen live values; those closures
  ;; cost more than the arithmetic and kept the garbage collector busy.
  ;; This C allocates nothing: it reads the entity's numbers (fixnums
  ;; within +-2^40, and positions that are exact rationals of fixnums
  ;; small enough, for the body's speed, size and tiles, that no sum
  ;; overflows: on 64-bit, denominators up to about 2^48 for a body on a
  ;; 4096 px map; see ds_room) and
  ;; `flags`, puts the new values in `out` and returns which keys to write
  ;; (a key that holds its new value already is not written, as entity-set
  ;; does). Same formulas in
  ;; the same order; physics/tests/pipeline-test.scm compares the two paths. The
  ;; code is motion.c; the flags and answers are motion.h's, by name.
  ;; Each flag is a Scheme constant, so that the flag expressions of
  ;; motion-pass fold and stay closure-free (a foreign variable there cost
  ;; a fifth more instructions in the S1 crowd); the C compiler checks every
  ;; one against motion.h's value of the same name.
  (define-c-constant flag-map DS_HAS_MAP 1)
  (define-c-constant flag-gravity DS_GRAVITY 2)
  (define-c-constant flag-swept DS_SWEPT 4)
  (define-c-constant flag-ground DS_GROUND 8)
  (define-c-constant flag-x DS_HAS_X 16)
  (define-c-constant flag-y DS_HAS_Y 32)
  (define-c-constant flag-vx DS_HAS_VX 64)
  (define-c-constant flag-vy DS_HAS_VY 128)
  (define-c-constant flag-ay DS_HAS_AY 256)
  (define-c-constant flag-on DS_HAS_ON 512)
  (define-c-constant flag-not-here DS_NOT_HERE 1024)
  (define-c-constant flag-drop DS_DROP 2048)
  (define-c-constant flag-slopes DS_SLOPES 4096)
  (define-c-constant flag-escape DS_ESCAPE 8192)
  (define-c-constant inside DS_INSIDE -2)
  (define-c-constant write-x DS_WRITE_X 1)
  (define-c-constant write-y DS_WRITE_Y 2)
  (define-c-constant write-vx DS_WRITE_VX 4)
  (define-c-constant write-vy DS_WRITE_VY 8)
  (define-c-constant write-ay DS_WRITE_AY 16)
  (define-c-constant write-on DS_WRITE_ON 32)
  (define-c-constant x-ratio DS_X_RATIO 64)
  (define-c-constant y-ratio DS_Y_RATIO 128)
  (define-c-constant x-flonum DS_X_FLONUM 256)
  (define-c-constant y-flonum DS_Y_FLONUM 512)
  (define-c-constant vy-flonum DS_VY_FLONUM 1024)

  (define fixnum-motion!
    (foreign-lambda scheme-object "ds_fixnum_motion" scheme-object u8vector scheme-object
                    scheme-object scheme-object scheme-object scheme-object scheme-object
                    scheme-object scheme-object scheme-object scheme-object scheme-object
                    scheme-object))

  ;; The flonum kernel (motion.c), for bodies of flonums (and small
  ;; fixnums), with or without a map: the same arguments, but the solid
  ;; grid (a u8vector) given as it is, read only with a map (a scene
  ;; without one pays no conversion).
  (define flonum-motion!
    (foreign-lambda scheme-object "ds_flonum_motion" scheme-object scheme-object scheme-object
                    scheme-object scheme-object scheme-object scheme-object scheme-object
                    scheme-object scheme-object scheme-object scheme-object scheme-object
                    scheme-object))

  ;; A kernel's answer for x, y or vy: 'keep; with the flonum bit the
  ;; double the flonum kernel left in its slot n-slot (motion.c); with the
  ;; ratio bit the rational out[n-slot] / out[d-slot], in lowest terms
  ;; already, so the ratnum is made without a gcd; else the fixnum
  ;; out[n-slot].
  (define (kernel-number out writes write-bit ratio-bit flonum-bit n-slot d-slot)
    (cond ((fx= 0 (fxand writes write-bit)) 'keep)
          ((not (fx= 0 (fxand writes flonum-bit)))
           (##core#inline_allocate ("ds_flonum_out_ref" 4) n-slot))
          ((fx= 0 (fxand writes ratio-bit)) (vector-ref out n-slot))
          (else (##core#inline_allocate ("C_a_i_ratnum" 3) (vector-ref out n-slot)
                                        (vector-ref out d-slot)))))

  ;; The entity with a kernel's answer written, when a new number must be
  ;; made (a rational or a flonum). Apart from the pass's walk of the
  ;; entity, and called from two places there, so that CHICKEN keeps it a
  ;; procedure of its own: the walk then allocates nothing, and CHICKEN
  ;; reserves a lambda's allocation on the C stack, the nursery, at every
  ;; turn of its loops, so every key of every body paid for these numbers.
  (define (rewrite-made e grav writes out xp yp vxp vyp ayp onp)
    (rewrite-motion e grav
                    xp (kernel-number out writes write-x x-ratio x-flonum 0 6)
                    yp (kernel-number out writes write-y y-ratio y-flonum 1 7)
                    vxp (if (fx= 0 (fxand writes write-vx)) 'keep (vector-ref out 2))
                    vyp (if (fx= 0 (fxand writes write-vy)) 'keep (kernel-number out writes write-vy 0 vy-flonum 3 3))
                    ayp (if (fx= 0 (fxand writes write-ay)) 'keep (vector-ref out 4))
                    onp (if (fx= 0 (fxand writes write-on)) 'keep (vector-ref out 5))))

  ;; (kernel-inputs e (one-way? scene-flags own-mode-flags)
  ;;                (xp yp vxp vyp ayp onp skips grav x y w h vx vy ay on flags)
  ;;   body ...)
  ;; body with what the kernel is given for entity e, read in one walk:
  ;; the pairs of the motion keys (#f when absent), #:skip-pipelines'
  ;; value, whether gravity is on, the numbers (0 when absent), the
  ;; #:on-ground? value and the flags, the scene's bits (first line) joined
  ;; with the entity's. Written as plain expressions, not nested
  ;; conditionals, so that CHICKEN makes no closures here (see above).
  (define-syntax kernel-inputs
    (syntax-rules ()
      ((_ e (one-way? scene-flags own-mode-flags)
          (xp yp vxp vyp ayp onp skips grav x y w h vx vy ay on flags) body ...)
       (entity-let e ((xp #:x) (yp #:y) (wp #:width) (hp #:height) (vxp #:vx) (vyp #:vy)
                      (ayp #:ay) (gp #:gravity?) (skipp #:skip-pipelines)
                      (modep #:collision-mode) (onp #:on-ground?) (dropp #:drop-through?))
         (let ((grav (and gp (cdr gp)))
               (x (if xp (cdr xp) 0)) (y (if yp (cdr yp) 0))
               (w (if wp (cdr wp) 0)) (h (if hp (cdr hp) 0))
               (vx (if vxp (cdr vxp) 0)) (vy (if vyp (cdr vyp) 0))
               (ay (if ayp (cdr ayp) 0))
               (own (and modep (cdr modep))))
           (let* ((flags (fxior
                          ;; an unknown mode is the tile steps' error to raise
                          (fxior (fxior (if own own-mode-flags scene-flags)
                                        (if (and one-way? dropp (cdr dropp)) flag-drop 0))
                                 (fxior (if (eq? own 'swept) flag-swept 0)
                                        (if (memq own '(#f swept discrete)) 0 flag-not-here)))
                          (fxior (fxior (if grav flag-gravity 0) (if xp flag-x 0))
                                 (fxior (fxior (if yp flag-y 0) (if vxp flag-vx 0))
                                        (fxior (if vyp flag-vy 0)
                                               (fxior (if ayp flag-ay 0) (if onp flag-on 0)))))))
                  (skips (and skipp (cdr skipp)))
                  (on (and onp (cdr onp))))
             body ...))))))

  ;; Whether entity e takes the readable steps whatever its numbers: body
  ;; controls (when the scene may have them), a ladder climb (likewise).
  (define-syntax readable-only?
    (syntax-rules ()
      ((_ e controls? climbers?)
       (or (and controls? (or (has-controls? e) (assq #:bounce e)))
           (and climbers? (climbing? e))))))

  ;; The entities both kernels have left to the readable steps since the
  ;; program started (not counting those readable-only? sends there).
  (define declines 0)
  (define (motion-kernel-declines) declines)

  ;; What the C code is given in a scene without a map (it reads neither).
  (define no-grid (make-u8vector 0))
  (define no-map (vector 0 0 0 0 1 1))

  ;; What every entity of a frame shares (the map's solid grid, size and
  ;; origin, the tile size, whether it has slopes, the scene's collision
  ;; mode) is read once. On a map with slope cells the kernel leaves a body
  ;; that could come near one this frame to the readable steps
  ;; (docs/physics.org, "Slopes"); a map without them never asks. Each
  ;; entity whose numbers the kernel takes (above), with no
  ;; #:skip-pipelines, then goes through fixnum-motion!; any other one
  ;; (flonums, other rationals, bignums, a NaN, skips, an unknown mode)
  ;; through motion-steps, the readable steps, except that one the
  ;; fixnum kernel refuses is offered to flonum-motion! first (finite
  ;; flonums and small fixnums, with or without a map), with what the
  ;; same walk read.
  ;; With ground? the pass also does ground detection (step 8), which
  ;; is only right when no entity of the scene is solid: the engine passes
  ;; it then, and only then.
  ;; controls? (default #t): whether some entity may have body controls
  ;; (#:drag, #:air-drag, #:max-vx, #:max-vy, #:bounce); such an entity
  ;; takes the readable steps. The engine passes #f when none has them,
  ;; so that no entity is asked.
  ;; climbers? (default #t): whether some entity may be climbing a ladder
  ;; (#:climber? and #:climbing?); such an entity takes the readable
  ;; steps. The engine passes #f in a scene without a climber.
  (define (motion-pass scene dt #!optional ground? (controls? #t) (climbers? #t))
    (let* ((tm (scene-tilemap scene))
           (map-data (and tm (pass-map tm)))
           (map? (and map-data #t))
           (bytes (if map? (tilemap-solid-grid tm) no-grid))
           (map (or map-data no-map))
           (one-way? (and map? (one-way-map? tm)))
           ;; the bits of fixnum-motion!'s flags the scene decides
           (scene-flags (fxior (fxior (if map? flag-map 0) (if (and map? (tilemap-slopes tm)) flag-slopes 0))
                               (fxior (if (and map? (swept-mode? scene '() #f)) flag-swept 0)
                                      (if ground? flag-ground 0))))
           ;; an entity's own mode replaces the scene's
           (own-mode-flags (fxand scene-flags (fxnot flag-swept)))
           (gravity *gravity*)
           (out (make-vector 8 1)))
      ;; An entity the C code leaves (see above).
      (define (general e)
        (let ((moved (motion-steps scene e dt controls? climbers?)))
          (if ground? (detect-on-solid scene moved dt) moved)))
      ;; An entity the flonum kernel left: `inside` is a swept body that
      ;; moves from inside solid tiles, which it takes out of them when the
      ;; escape's search ends with a straight move (motion.c,
      ;; ds_flo_escape), if it has no #:tween (leave-solids leaves a
      ;; tweened body to the tile passes). Apart from the walk, which
      ;; asks no key more of every body.
      (define (declined e writes)
        (let ((writes (if (and (fx= writes inside) (not (entity-ref e #:tween #f)))
                          (kernel-inputs e (one-way? scene-flags own-mode-flags)
                                         (xp yp vxp vyp ayp onp skips grav x y w h vx vy ay on flags)
                            (let ((writes (flonum-motion! out bytes map (fxior flags flag-escape) gravity skips
                                                          x y w h vx vy ay on)))
                              (if (fx> writes 0)
                                  (rewrite-made e grav writes out xp yp vxp vyp ayp onp)
                                  writes)))
                          -1)))
          (cond ((not (fixnum? writes)) writes)
                ((fx= writes 0) e)
                (else (set! declines (fx+ declines 1))
                      (general e)))))
      (if (and tm (not map?))
          general
          (lambda (e)
           (if (readable-only? e controls? climbers?)
            (general e)
            (kernel-inputs e (one-way? scene-flags own-mode-flags)
                           (xp yp vxp vyp ayp onp skips grav x y w h vx vy ay on flags)
                (let* ((writes (fixnum-motion! out bytes map flags gravity skips
                                               x y w h vx vy ay on)))
                  (cond ((fx= writes 0) e)
                        ((fx< writes 0)
                         ;; the flonum kernel's turn (it refuses what is
                         ;; not its, at once)
                         (let ((writes (flonum-motion! out bytes map flags gravity skips
                                                       x y w h vx vy ay on)))
                           (cond ((fx= writes 0) e)
                                 ((fx< writes 0) (declined e writes))
                                 (else (rewrite-made e grav writes out xp yp vxp vyp ayp onp)))))
                        ((fx= 0 (fxand writes (fxior x-ratio y-ratio)))
                         (rewrite-motion e grav
                                         xp (if (fx= 0 (fxand writes write-x)) 'keep (vector-ref out 0))
                                         yp (if (fx= 0 (fxand writes write-y)) 'keep (vector-ref out 1))
                                         vxp (if (fx= 0 (fxand writes write-vx)) 'keep (vector-ref out 2))
                                         vyp (if (fx= 0 (fxand writes write-vy)) 'keep (vector-ref out 3))
                                         ayp (if (fx= 0 (fxand writes write-ay)) 'keep (vector-ref out 4))
                                         onp (if (fx= 0 (fxand writes write-on)) 'keep (vector-ref out 5))))
                        (else                   ; a rational position
                         (rewrite-made e grav writes out xp yp vxp vyp ayp onp))))))))))

)
