;;; (downstroke pipeline): the per-frame pipeline of docs/physics.org, twice.
;;;
;;; contract-pipeline is docs/physics.org's list of steps as library code: each
;;; step (a define-pipeline step, its guard and skip symbol in front) over
;;; every entity, in that order. It is the reference, and where a
;;; custom engine-update starts: copy its body and move a step.
;;;
;;; engine-pipeline is what the engine runs (default-engine-update): the
;;; same result from the same steps' rules, fast. It is the one fenced fast
;;; path: it skips steps no entity needs, runs steps 2-7 as one pass
;;; (physics' motion-pass, with its C kernel for small fixnums), and folds
;;; tile ground detection into that pass when its precondition holds (see
;;; ground-joins-motion? below). physics/tests/pipeline-test.scm runs both on random
;;; scenes, frame after frame, and compares every entity.

(module (downstroke pipeline)
  (contract-pipeline engine-pipeline pipeline-failing-step contract-steps engine-pipeline-steps)

  (import scheme (chicken base) (chicken fixnum) (chicken foreign) (chicken condition)
          (downstroke scene) (downstroke physics) (downstroke tween)
          (downstroke animation) (downstroke particles) (downstroke srfi-197)
          (downstroke c-constants))

  ;; The pipeline of docs/physics.org (The pipeline), one step after the
  ;; other over every entity of the scene, then the library's own last
  ;; step, particles (particles.scm), which no other step reads. The first step notes where each
  ;; immovable body starts the frame, so that the entity step carries a
  ;; rider by what its platform did (contacts.scm, record-frame-start).
  (define (contract-pipeline scene dt)
    (chain scene
      (scene-map-entities _ (cut record-frame-start        <> <> dt))
      (scene-map-entities _ (cut step-tweens               <> <> dt))
      (scene-map-entities _ (cut apply-climbing            <> <> dt))
      (scene-map-entities _ (cut apply-acceleration        <> <> dt))
      (scene-map-entities _ (cut apply-gravity             <> <> dt))
      (scene-map-entities _ (cut apply-body-controls       <> <> dt))
      (scene-map-entities _ (cut apply-velocity-x          <> <> dt))
      (scene-map-entities _ (cut resolve-tile-collisions-x <> <> dt))
      (scene-map-entities _ (cut apply-velocity-y          <> <> dt))
      (scene-map-entities _ (cut resolve-tile-collisions-y <> <> dt))
      (scene-map-entities _ (cut detect-on-solid           <> <> dt))
      (scene-transform-entities _ resolve-entity-collisions)
      (scene-transform-entities _ sync-groups)
      (scene-map-entities _ (cut detect-contacts           <> <> dt))
      (scene-map-entities _ (cut apply-animation           <> <> dt))
      (scene-map-entities _ (cut step-particles            <> <> dt))))

  ;; The same steps, in the same order, by the names #:skip-pipelines uses
  ;; (groups and frame-start, which nothing skips, by their own), as
  ;; (name . (scene dt) -> scene); the pipeline's suite checks that they
  ;; make the same frames as the chain above, which a game copies.
  (define (per-entity step) (lambda (scene dt) (scene-map-entities scene (cut step <> <> dt))))
  (define (whole-list step) (lambda (scene dt) (scene-transform-entities scene step)))
  (define contract-steps
    (list (cons 'frame-start       (per-entity record-frame-start))
          (cons 'tweens            (per-entity step-tweens))
          (cons 'climbing          (per-entity apply-climbing))
          (cons 'acceleration      (per-entity apply-acceleration))
          (cons 'gravity           (per-entity apply-gravity))
          (cons 'controls          (per-entity apply-body-controls))
          (cons 'velocity-x        (per-entity apply-velocity-x))
          (cons 'tile-collisions-x (per-entity resolve-tile-collisions-x))
          (cons 'velocity-y        (per-entity apply-velocity-y))
          (cons 'tile-collisions-y (per-entity resolve-tile-collisions-y))
          (cons 'on-solid          (per-entity detect-on-solid))
          (cons 'entity-collisions (whole-list resolve-entity-collisions))
          (cons 'groups            (whole-list sync-groups))
          (cons 'contacts          (per-entity detect-contacts))
          (cons 'animation         (per-entity apply-animation))
          (cons 'particles         (per-entity step-particles))))

  ;; Which step raises an error on this scene, run one step at a time:
  ;; (values name condition), or (values #f #f) when none does. The engine
  ;; asks only after its fused pipeline raised, so that the error it
  ;; passes on names the step; no frame that goes well pays for it.
  (define (pipeline-failing-step scene dt)
    (let loop ((steps contract-steps) (scene scene))
      (if (null? steps)
          (values #f #f)
          (let ((next (call-with-current-continuation
                       (lambda (k)
                         (with-exception-handler
                          (lambda (c) (k (cons 'failed c)))
                          (lambda () ((cdar steps) scene dt)))))))
            (if (and (pair? next) (eq? (car next) 'failed))
                (values (caar steps) (cdr next))
                (loop (cdr steps) next))))))

  ;;; The default pipeline runs only the steps some entity of the scene
  ;;; needs: one walk over each entity finds out which (`pipeline-needs`),
  ;;; and a step no entity needs is not run at all. Skipping such a step
  ;;; changes nothing, because its guard would have left every entity as
  ;;; it was; tests compare this pipeline with every step run in turn.

  ;; Bits of what a list of entities needs, and the keys that ask for
  ;; them: physics/needs.h states both for the C walk below.
  (foreign-declare "#include \"physics/needs.h\"")
  (define-c-constant need-tweens DS_NEED_TWEENS 1)         ; an entity has a #:tween
  (define-c-constant need-ground DS_NEED_GROUND 2)         ; an entity has #:gravity?
  (define-c-constant need-pairs DS_NEED_PAIRS 4)           ; two or more entities have #:solid?
  (define-c-constant need-groups DS_NEED_GROUPS 8)         ; an entity has a #:group-id
  (define-c-constant need-animation DS_NEED_ANIMATION 16)  ; an entity has #:animations
  (define-c-constant need-support DS_NEED_SUPPORT 32)      ; an entity has #:solid? (it may hold others up)
  (define-c-constant need-start DS_NEED_START 64)          ; an entity has #:immovable? or #:one-way? (record-frame-start)
  (define-c-constant need-particles DS_NEED_PARTICLES 128) ; an entity has an #:emitter
  (define-c-constant need-contacts DS_NEED_CONTACTS 256)   ; an entity has #:contacts?
  (define-c-constant need-controls DS_NEED_CONTROLS 512)   ; an entity has a body control
  (define-c-constant need-climbers DS_NEED_CLIMBERS 1024)  ; an entity has #:climber?
  (define-c-constant key-tween DS_KEY_TWEEN 0)
  (define-c-constant key-gravity DS_KEY_GRAVITY 1)
  (define-c-constant key-solid DS_KEY_SOLID 2)
  (define-c-constant key-group-id DS_KEY_GROUP_ID 3)
  (define-c-constant key-animations DS_KEY_ANIMATIONS 4)
  (define-c-constant key-immovable DS_KEY_IMMOVABLE 5)
  (define-c-constant key-emitter DS_KEY_EMITTER 6)
  (define-c-constant key-one-way DS_KEY_ONE_WAY 7)
  (define-c-constant key-contacts DS_KEY_CONTACTS 8)
  (define-c-constant key-drag DS_KEY_DRAG 9)
  (define-c-constant key-air-drag DS_KEY_AIR_DRAG 10)
  (define-c-constant key-max-vx DS_KEY_MAX_VX 11)
  (define-c-constant key-max-vy DS_KEY_MAX_VY 12)
  (define-c-constant key-bounce DS_KEY_BOUNCE 13)
  (define-c-constant key-climber DS_KEY_CLIMBER 14)
  (define-c-constant need-key-count DS_NEED_KEYS 15)
  (define need-keys
    (let ((v (make-vector need-key-count)))
      (for-each (lambda (i k) (vector-set! v i k))
                (list key-tween key-gravity key-solid key-group-id key-animations key-immovable key-emitter
                      key-one-way key-contacts key-drag key-air-drag key-max-vx key-max-vy key-bounce
                      key-climber)
                (list #:tween #:gravity? #:solid? #:group-id #:animations #:immovable? #:emitter #:one-way?
                      #:contacts? #:drag #:air-drag #:max-vx #:max-vy #:bounce #:climber?))
      v))

  ;; The walk below, in C (needs.c): it reads every pair of every entity
  ;; each frame, which in Scheme was a twentieth of a crowd scene's time.
  ;; -1 when an entity is not a list of pairs: the Scheme walk then raises
  ;; the error.
  (foreign-declare "#include \"physics/needs.c\"")
  (define c-needs (foreign-lambda scheme-object "ds_pipeline_needs" scheme-object scheme-object))

  (define (pipeline-needs entities)
    (let ((c (c-needs entities need-keys)))
      (if (fx< c 0) (scheme-pipeline-needs entities) c)))

  (define (scheme-pipeline-needs entities)
    (let next ((es entities) (bits 0) (solids 0))
      (if (null? es)
          (fxior bits (cond ((fx>= solids 2) (fxior need-pairs need-support))
                            ((fx= solids 1) need-support)
                            (else 0)))
          (let walk ((ps (car es)) (bits bits) (solid? #f))
            (if (null? ps)
                (next (cdr es) bits (if solid? (fx+ solids 1) solids))
                (let* ((p (car ps)) (k (car p)))
                  (cond ((not (cdr p)) (walk (cdr ps) bits solid?))
                        ((eq? k #:gravity?) (walk (cdr ps) (fxior bits need-ground) solid?))
                        ((eq? k #:solid?) (walk (cdr ps) bits #t))
                        ((eq? k #:tween) (walk (cdr ps) (fxior bits need-tweens) solid?))
                        ((eq? k #:group-id) (walk (cdr ps) (fxior bits need-groups) solid?))
                        ((eq? k #:animations) (walk (cdr ps) (fxior bits need-animation) solid?))
                        ((or (eq? k #:immovable?) (eq? k #:one-way?)) (walk (cdr ps) (fxior bits need-start) solid?))
                        ((eq? k #:emitter) (walk (cdr ps) (fxior bits need-particles) solid?))
                        ((eq? k #:contacts?) (walk (cdr ps) (fxior bits need-contacts) solid?))
                        ((eq? k #:climber?) (walk (cdr ps) (fxior bits need-climbers) solid?))
                        ((memq k '(#:drag #:air-drag #:max-vx #:max-vy #:bounce))
                         (walk (cdr ps) (fxior bits need-controls) solid?))
                        (else (walk (cdr ps) bits solid?)))))))))

  (define (needs? bits need) (not (fx= 0 (fxand bits need))))

  ;; The same pipeline, as a pure function of a scene.
  ;; Steps 1-7 read no other entity, so they run back to back per entity
  ;; (one list built instead of seven): tweens, then the motion pass
  ;; (steps 2-7 in one walk, see motion.scm). Ground detection sees every
  ;; entity after its tile passes; then the bulk steps; then animation. A
  ;; tween's on-complete may change an entity in any way, so after tweens
  ;; the needs are read again. Without tweens and without solid entities,
  ;; ground detection looks only at the entity itself and the map, so it
  ;; joins the motion pass.
  (define (engine-pipeline scene dt)
    (keep-heap-headroom!)
    (let* ((before (pipeline-needs (scene-entities scene)))
           (tweens? (needs? before need-tweens))
           (ground-in-motion? (ground-joins-motion? before))
           ;; a tween's on-complete may add a body control or make a
           ;; climber: then every entity is asked
           (climbs? (or tweens? (needs? before need-climbers)))
           (move (motion-pass scene dt ground-in-motion? (or tweens? (needs? before need-controls)) climbs?))
           ;; where platforms start, when one may carry a rider this frame,
           ;; and where solid bodies start, when one may land on a one-way one
           (starts? (needs? before need-start))
           (scene (scene-map-entities scene (cond (climbs?
                                                   ;; a scene with a climber (or a tween)
                                                   (lambda (s e)
                                                     (let* ((e (if starts? (record-frame-start s e dt) e))
                                                            (e (if tweens? (step-tweens s e dt) e)))
                                                       (move (apply-climbing s e dt)))))
                                                  ((and tweens? starts?)
                                                   (lambda (s e) (move (step-tweens s (record-frame-start s e dt) dt))))
                                                  (tweens? (lambda (s e) (move (step-tweens s e dt))))
                                                  (starts? (lambda (s e) (move (record-frame-start s e dt))))
                                                  (else (lambda (s e) (move e))))))
           (needs (if tweens? (pipeline-needs (scene-entities scene)) before)))
      (define (when-needed need step scene) (if (needs? needs need) (step scene) scene))
      (define (ground-pass scene)
        (if ground-in-motion?
            scene
            (when-needed need-ground (cut scene-map-entities <> (lambda (s e) (detect-on-solid s e dt))) scene)))
      (chain scene
             (ground-pass _)
             (when-needed need-pairs (cut scene-transform-entities <> resolve-entity-collisions) _)
             (when-needed need-groups (cut scene-transform-entities <> sync-groups) _)
             (when-needed need-contacts
                          (cut scene-map-entities <> (lambda (s e) (detect-contacts s e dt))) _)
             (when-needed need-animation
                          (cut scene-map-entities <> (lambda (s e) (apply-animation s e dt))) _)
             (when-needed need-particles
                          (cut scene-map-entities <> (lambda (s e) (step-particles s e dt))) _))))

  ;; The names (as in contract-steps) of the steps engine-pipeline runs on
  ;; this scene as it is: the motion steps always (the motion pass), each
  ;; other one only when some entity needs it, read from the same bits
  ;; engine-pipeline decides by. A tween's on-complete may make more
  ;; needed within the frame; with a tween, the climbing and controls
  ;; steps are run anyway.
  (define (engine-pipeline-steps scene)
    (let* ((bits (pipeline-needs (scene-entities scene)))
           (tweens? (needs? bits need-tweens)))
      (let loop ((steps contract-steps) (out '()))
        (if (null? steps)
            (reverse out)
            (let* ((name (caar steps))
                   (run? (case name
                           ((frame-start) (needs? bits need-start))
                           ((tweens) tweens?)
                           ((climbing) (or tweens? (needs? bits need-climbers)))
                           ((controls) (or tweens? (needs? bits need-controls)))
                           ((on-solid) (needs? bits need-ground))
                           ((entity-collisions) (needs? bits need-pairs))
                           ((groups) (needs? bits need-groups))
                           ((contacts) (needs? bits need-contacts))
                           ((animation) (needs? bits need-animation))
                           ((particles) (needs? bits need-particles))
                           (else #t))))      ; the motion pass
              (loop (cdr steps) (if run? (cons name out) out)))))))

  ;;; The heap's headroom
  ;; After a major collection CHICKEN grows its heap only when less than a
  ;; fixed amount (4 MB by default, -:hf) would stay free in it. A scene
  ;; whose live entities outgrow that amount then collects ever more often,
  ;; each major collection copying all of them: the collector's work per
  ;; body grew with the crowd (docs/performance.org, "Cost per body as a
  ;; scene grows"). Each frame the engine asks for at least half of a heap
  ;; half to stay free (never less than the program started with), so the
  ;; heap grows with the live data, and a major collection, which copies
  ;; the live data once, comes only after as many bytes were promoted: its
  ;; share of a frame is the same per body at any size.
  (foreign-declare "
extern C_TLS C_uword C_heap_half_min_free;
static C_uword ds_min_free_at_start;
static int ds_min_free_read = 0;
static void ds_keep_headroom(C_word heap_size) {
  C_uword quarter = (C_uword)C_unfix(heap_size) / 4;
  if (!ds_min_free_read) { ds_min_free_at_start = C_heap_half_min_free; ds_min_free_read = 1; }
  C_heap_half_min_free = quarter > ds_min_free_at_start ? quarter : ds_min_free_at_start;
}")
  (define (keep-heap-headroom!)
    ((foreign-lambda void "ds_keep_headroom" scheme-object)
     (vector-ref (##sys#memory-info) 0)))

  ;; Tile ground detection may join the motion pass (one walk instead of
  ;; two) only when it reads nothing but the entity itself and the map:
  ;; with no solid entity, entity ground has no supporter; with no tween,
  ;; no on-complete can change another entity between the two passes.
  (define (ground-joins-motion? needs)
    (and (needs? needs need-ground)
         (not (needs? needs need-tweens))
         (not (needs? needs need-support)))))
