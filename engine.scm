;;; (downstroke engine): the game record and the per-frame sequence.
;;;
;;; `make-game` only builds a record: no SDL call is made until the game
;;; shell opens a window, so the pipeline and the hooks run in csi with no
;;; display. One logical frame is
;;;   input -> the scene's engine update -> update: -> camera follow -> render
;;; and `game-step!` runs the middle three, the part that needs no device.

(module (downstroke engine)
  (make-game game?
   game-title game-width game-height game-scale game-frame-delay
   game-input-config game-debug? game-headless?
   game-preload-hook game-create-hook game-update-hook game-render-hook
   game-scene game-scene-set! game-input game-input-set!
   game-renderer game-renderer-set! game-window game-window-set!
   game-frame game-asset game-asset-set!
   engine-pipeline default-engine-update run-engine-update!
   game-start! game-step!)

  (import scheme (chicken base) (chicken format)
          (downstroke entity) (downstroke scene) (downstroke physics)
          (downstroke tween) (downstroke animation) (downstroke srfi-197))

  (define-record-type game
    (%make-game title width height scale frame-delay input-config
                preload create update render debug? headless?
                scene input renderer window frame assets)
    game?
    (title game-title)
    (width game-width)
    (height game-height)
    (scale game-scale)
    (frame-delay game-frame-delay)
    (input-config game-input-config)
    (preload game-preload-hook)
    (create game-create-hook)
    (update game-update-hook)
    (render game-render-hook)
    (debug? game-debug?)
    (headless? game-headless?)
    (scene game-scene game-scene-set!)
    (input game-input game-input-set!)
    (renderer game-renderer game-renderer-set!)
    (window game-window game-window-set!)
    (frame game-frame game-frame-set!)
    (assets game-assets game-assets-set!))

  (define (check what ok? value)
    (unless (ok? value)
      (error 'make-game (sprintf "~a: bad value ~s" what value)))
    value)

  (define (positive-integer? v) (and (exact-integer? v) (positive? v)))
  (define (hook? v) (or (not v) (procedure? v)))

  ;; width x height is the logical resolution the game draws at; the window
  ;; is `scale` times larger on each axis. input-config #f stands for the
  ;; input module's default configuration.
  (define (make-game #!key (title "Downstroke Game") (width 640) (height 480)
                     (scale 1) (frame-delay 16) (input-config #f)
                     (preload #f) (create #f) (update #f) (render #f)
                     (debug? #f) (headless? #f))
    (%make-game (check "title:" string? title)
                (check "width:" positive-integer? width)
                (check "height:" positive-integer? height)
                (check "scale:" positive-integer? scale)
                (check "frame-delay:" positive-integer? frame-delay)
                input-config
                (check "preload:" hook? preload)
                (check "create:" hook? create)
                (check "update:" hook? update)
                (check "render:" hook? render)
                debug? headless?
                #f #f #f #f 0 '()))

  ;; (game-asset game key [default]): a missing key without a default is an
  ;; error naming the key.
  (define (game-asset game key #!optional (default (void)))
    (let ((p (assoc key (game-assets game))))
      (cond (p (cdr p))
            ((not (eq? default (void))) default)
            (else (error 'game-asset (sprintf "no asset named ~s" key))))))

  (define (game-asset-set! game key value)
    (game-assets-set! game (cons (cons key value)
                                 (let loop ((as (game-assets game)))
                                   (cond ((null? as) '())
                                         ((equal? (caar as) key) (cdr as))
                                         (else (cons (car as) (loop (cdr as)))))))))

  ;; Steps 1-7 of the contract for one entity. None of them reads another
  ;; entity, so running them back to back per entity gives exactly what
  ;; seven passes over the list would, with one list built instead of seven.
  (define (move-entity scene entity dt)
    (chain entity
           (step-tweens scene _ dt)
           (apply-acceleration scene _ dt)
           (apply-gravity scene _ dt)
           (apply-velocity-x scene _ dt)
           (resolve-tile-collisions-x scene _ dt)
           (apply-velocity-y scene _ dt)
           (resolve-tile-collisions-y scene _ dt)))

  ;; The contract's pipeline, as a pure function of a scene.
  ;; Ground detection sees every entity after its tile passes; then the
  ;; bulk steps; then animation.
  (define (engine-pipeline scene dt)
    (chain scene
           (scene-map-entities _ (lambda (s e) (move-entity s e dt)))
           (scene-map-entities _ (lambda (s e) (detect-on-solid s e dt)))
           (scene-transform-entities _ resolve-entity-collisions)
           (scene-transform-entities _ sync-groups)
           (scene-map-entities _ (lambda (s e) (apply-animation s e dt)))))

  (define (default-engine-update game dt)
    (let ((scene (game-scene game)))
      (when scene
        (game-scene-set! game (engine-pipeline scene dt)))))

  ;; The scene's engine-update field: #f runs the default pipeline, a
  ;; procedure runs instead of it as (proc game dt), 'none runs nothing.
  (define (run-engine-update! game dt)
    (let ((scene (game-scene game)))
      (when scene
        (let ((eu (scene-engine-update scene)))
          (cond ((not eu) (default-engine-update game dt))
                ((procedure? eu) (eu game dt))
                ((eq? eu 'none))
                (else (error 'run-engine-update!
                             "scene engine-update must be #f, a procedure or 'none" eu)))))))

  ;; What a game does once before its first frame.
  (define (game-start! game)
    (let ((preload (game-preload-hook game))
          (create (game-create-hook game)))
      (when preload (preload game))
      (when create (create game))))

  ;; One logical frame without devices: engine update, update:, camera
  ;; follow. dt defaults to the game's frame delay (ms).
  (define (game-step! game #!optional (dt (game-frame-delay game)))
    (run-engine-update! game dt)
    (let ((update (game-update-hook game)))
      (when update (update game dt)))
    (let ((scene (game-scene game)))
      (when scene
        (game-scene-set! game (scene-follow-camera scene (game-width game)
                                                   (game-height game)))))
    (game-frame-set! game (+ (game-frame game) 1))))
