;;; (downstroke scene): a scene is an immutable record of what one screen
;;; holds: its entities, tilemap, camera, background and engine update.
;;; Every "change" returns a new scene.

(module (downstroke scene)
  (make-scene make-sprite-scene update-scene scene?
   scene-entities scene-tilemap scene-tileset scene-tileset-texture scene-tilesets
   scene-camera scene-camera-target scene-background scene-engine-update
   scene-collision-mode *default-collision-mode*
   scene-solid-entities
   scene-map-entities scene-transform-entities
   scene-add-entity scene-remove-entities scene-find-tagged scene-find-all-tagged
   scene-follow-camera scene-problems scene-checks
   scene-timers)

  ;; a scene is made with its camera: the camera's names come with it
  (import (chicken module))
  (reexport (downstroke camera))

  (import (downstroke keywords))
  (import scheme (chicken base) (chicken format) (chicken fixnum) (chicken keyword) (chicken string)
          (chicken condition)
          (downstroke entity) (downstroke map) (downstroke camera)
          (only (downstroke check) entity-list-problems report-entity-problems! scene-checks))

  ;; `solids` caches the solid entities of this scene's entity list, which
  ;; ground detection asks for once per gravity entity. It is derived data:
  ;; every new scene starts without it.
  (define-record-type scene
    (%make-scene entities tilemap tileset tileset-texture camera camera-target
                 background engine-update collision-mode tilesets timers solids)
    scene?
    (entities scene-entities)
    (tilemap scene-tilemap)
    (tileset scene-tileset)
    (tileset-texture scene-tileset-texture)
    (camera scene-camera)
    (camera-target scene-camera-target)
    (background scene-background)
    (engine-update scene-engine-update)
    (collision-mode scene-collision-mode)
    (tilesets scene-tilesets)
    ;; timers and scripts of waits and calls ((downstroke timer))
    (timers scene-timers)
    (solids scene-solids-cache scene-solids-cache-set!))

  (define (check-engine-update eu)
    (unless (or (not eu) (eq? eu 'none) (procedure? eu))
      (error 'make-scene "engine-update: must be #f, a procedure or 'none" eu))
    eu)

  (define (check-collision-mode mode)
    (unless (memq mode '(discrete swept))
      (error 'make-scene "collision-mode: must be 'discrete or 'swept" mode))
    mode)

  ;; A keyword alist, ((#:x . 0) ...): its pairs have keyword cars and
  ;; some cdr is not a list (an entity plist in a list always has one).
  (define (one-alist? es)
    (let loop ((es es) (dotted? #f))
      (cond ((null? es) dotted?)
            ((and (pair? (car es)) (keyword? (caar es)))
             (loop (cdr es) (or dotted? (not (pair? (cdar es))))))
            (else #f))))

  ;; One entity given where a list of them belongs is the usual slip:
  ;; (make-scene entities: (list #:type 'player ...)) reads a plist as a
  ;; list of a keyword, a symbol ... and would fail deep inside.
  (define (check-entities entities #!optional (who 'make-scene))
    (unless (list? entities)
      (error (sprintf "~a: entities: must be a list of entities, got ~s" who entities)))
    (when (and (pair? entities)
               (or (keyword? (car entities))     ; a plist
                   (one-alist? entities)))
      (error (sprintf "~a: entities: is one entity, not a list of them (wrap it: (list e))" who)))
    ;; alists come back as they are, so the list is shared, not copied;
    ;; as-entity names an element that is no entity
    (let ((es (map/shared as-entity entities)))
      (when (if (eq? who 'update-scene) (eq? (scene-checks) 'always) (scene-checks))
        (report-entity-problems! es))
      es))

  ;; What (downstroke check) finds wrong with the scene's entities: a list
  ;; of strings, each naming the entity (docs/entities.org).
  (define (scene-problems s) (entity-list-problems (scene-entities s)))

  ;; How tile collisions are resolved unless a scene or an entity says
  ;; otherwise (see physics/tile-collisions.scm and docs/physics.org).
  (define *default-collision-mode* 'swept)

  ;; tilesets: more sprite sheets, which an entity names with #:tileset
  ;; (docs/rendering.org, "Sprites").
  (define (check-tilesets who tss)
    (unless (and (list? tss) (let all ((l tss)) (or (null? l) (and (tileset? (car l)) (all (cdr l))))))
      (error who "tilesets: must be a list of tilesets (load-tileset, make-sheet-tileset)" tss))
    tss)

  ;; timers: a list of what (downstroke timer) steps; their kind is
  ;; checked there, when they are added or stepped.
  (define (check-timers who ts)
    (unless (list? ts)
      (error who "timers: must be a list (timer-after, timer-every, tween-sequence ...)" ts))
    ts)

  ;; camera-target: the tag of the entity the camera centres on after each
  ;; update: ('camera-target unless given), or #f for a camera that stays put.
  (define/keywords (make-scene #!key (entities '()) (tilemap #f) (tileset #f)
                      (tileset-texture #f) (camera (make-camera))
                      (camera-target 'camera-target) (background #f)
                      (engine-update #f) (collision-mode *default-collision-mode*)
                      (tilesets '()) (timers '()))
    (%make-scene (check-entities entities) tilemap tileset tileset-texture
                 camera camera-target background
                 (check-engine-update engine-update)
                 (check-collision-mode collision-mode)
                 (check-tilesets 'make-scene tilesets)
                 (check-timers 'make-scene timers) #f))

  ;; A scene with no map: sprites over a background.
  (define/keywords (make-sprite-scene #!key (entities '()) (tileset #f) (tileset-texture #f)
                             (camera (make-camera)) (camera-target 'camera-target)
                             (background #f) (engine-update #f) (tilesets '()) (timers '()))
    (make-scene entities: entities tileset: tileset tileset-texture: tileset-texture
                camera: camera camera-target: camera-target background: background
                engine-update: engine-update collision-mode: *default-collision-mode*
                tilesets: tilesets timers: timers))

  ;; A marker for "keyword not given", distinct from every value a user passes.
  (define unset (list 'unset))
  (define (given? v) (not (eq? v unset)))

  (define/keywords (update-scene s #!key (entities unset) (tilemap unset) (tileset unset)
                        (tileset-texture unset) (camera unset) (camera-target unset)
                        (background unset) (engine-update unset) (collision-mode unset)
                        (tilesets unset) (timers unset))
    (let ((pick (lambda (new old) (if (given? new) new old))))
      (%make-scene (if (given? entities) (check-entities entities (quote update-scene)) (scene-entities s))
                   (pick tilemap (scene-tilemap s))
                   (pick tileset (scene-tileset s))
                   (pick tileset-texture (scene-tileset-texture s))
                   (pick camera (scene-camera s))
                   (pick camera-target (scene-camera-target s))
                   (pick background (scene-background s))
                   (if (given? engine-update)
                       (check-engine-update engine-update)
                       (scene-engine-update s))
                   (if (given? collision-mode)
                       (check-collision-mode collision-mode)
                       (scene-collision-mode s))
                   (if (given? tilesets) (check-tilesets 'update-scene tilesets) (scene-tilesets s))
                   (if (given? timers) (check-timers 'update-scene timers) (scene-timers s))
                   ;; the cache survives only when the entity list does
                   (if (given? entities) #f (scene-solids-cache s)))))

  ;; The same scene holding a new entity list (already entity alists).
  (define (with-entities s entities)
    (%make-scene entities (scene-tilemap s) (scene-tileset s) (scene-tileset-texture s)
                 (scene-camera s) (scene-camera-target s) (scene-background s)
                 (scene-engine-update s) (scene-collision-mode s) (scene-tilesets s)
                 (scene-timers s) #f))

  (define (scene-solid-entities s)
    (or (scene-solids-cache s)
        (let ((solids (let loop ((es (scene-entities s)) (out '()))
                        (cond ((null? es) (reverse out))
                              ((entity-ref (car es) #:solid? #f)
                               (loop (cdr es) (cons (car es) out)))
                              (else (loop (cdr es) out))))))
          (scene-solids-cache-set! s solids)
          solids)))

  ;; map that returns the list itself, sharing its unchanged tail, when
  ;; `f` returns its argument: a step that changes no entity allocates
  ;; nothing, so a pipeline step a scene does not need costs one walk.
  ;; A loop, not a recursion: a scene of 10,000 entities would otherwise
  ;; hold 10,000 pending calls, which the garbage collector copies.
  ;; The result is built front to back (append-changed!): `first` is a
  ;; cell made at the first change, before the result's first cell, `last`
  ;; the result's last cell, `run` the first element not copied yet.
  (define (map/shared f ls)
    (let loop ((rest ls) (first #f) (last #f) (run ls))
      (if (null? rest)
          (shared-result ls first last run)
          (let* ((x (car rest)) (y (f x)))
            (if (eq? y x)
                (loop (cdr rest) first last run)
                (let ((first (or first (list #f))))
                  (loop (cdr rest) first (append-changed! (or last first) run rest y) (cdr rest))))))))

  ;; After the cell `last`, copies of the elements from `run` up to `rest`
  ;; (they came back unchanged), then y, the changed result at `rest`;
  ;; answers the last cell. The cells are made here and held by no one
  ;; else, so set-cdr! changes nothing anyone can see. (Built in reverse
  ;; and turned round, the result took a second cell per entity, which
  ;; every frame's minor collections copied: docs/performance.org, "The
  ;; main thread against LÖVE's".)
  (define (append-changed! last run rest y)
    (let ((cell (cons (if (eq? run rest) y (car run)) '())))
      (set-cdr! last cell)
      (if (eq? run rest) cell (append-changed! cell (cdr run) rest y))))

  ;; map/shared's list: ls itself when nothing changed, else the cells
  ;; made, ending in the tail of ls from `run`, shared.
  (define (shared-result ls first last run)
    (if first
        (begin (set-cdr! last run) (cdr first))
        ls))

  ;; (proc scene entity) -> entity, for every entity; proc sees this scene,
  ;; i.e. every entity as it was before the map. When proc changes nothing
  ;; the scene itself comes back. map/shared's loop, calling proc itself:
  ;; every frame of a game runs it over every entity, a call less each.
  (define (scene-map-entities s proc)
    (let ((es (scene-entities s)))
      (let loop ((rest es) (first #f) (last #f) (run es))
        (if (null? rest)
            (let ((out (shared-result es first last run)))
              (if (eq? out es) s (with-entities s out)))
            (let* ((x (car rest)) (y (proc s x)))
              (if (eq? y x)
                  (loop (cdr rest) first last run)
                  (let ((first (or first (list #f))))
                    (if (eq? run rest)  ; the one before changed too: y's cell alone
                        (let ((cell (cons y '())))
                          (set-cdr! (or last first) cell)
                          (loop (cdr rest) first cell (cdr rest)))
                        (loop (cdr rest) first (append-changed! (or last first) run rest y) (cdr rest))))))))))

  ;; (proc entities) -> entities, over the whole list at once.
  (define (scene-transform-entities s proc)
    (let ((out (proc (scene-entities s))))
      (if (eq? out (scene-entities s)) s (with-entities s out))))

  (define (scene-add-entity s e)
    (let ((e (as-entity e)))
      (when (scene-checks) (report-entity-problems! (list e)))
      (with-entities s (append (scene-entities s) (list e)))))

  (define (scene-remove-entities s pred)
    (with-entities s (let loop ((es (scene-entities s)) (out '()))
                       (cond ((null? es) (reverse out))
                             ((pred (car es)) (loop (cdr es) out))
                             (else (loop (cdr es) (cons (car es) out)))))))

  (define (scene-find-tagged s tag)
    (let loop ((es (scene-entities s)))
      (cond ((null? es) #f)
            ((entity-has-tag? (car es) tag) (car es))
            (else (loop (cdr es))))))

  (define (scene-find-all-tagged s tag)
    (let loop ((es (scene-entities s)) (out '()))
      (cond ((null? es) (reverse out))
            ((entity-has-tag? (car es) tag) (loop (cdr es) (cons (car es) out)))
            (else (loop (cdr es) out)))))

  ;; What the engine does after update:, as a pure function of the scene.
  (define (scene-follow-camera s view-w view-h)
    (let* ((tag (scene-camera-target s))
           (target (and tag (scene-find-tagged s tag))))
      (cond (target
             (update-scene s camera: (camera-follow (scene-camera s) target view-w view-h
                                                    (scene-tilemap s))))
            ;; without a target a shake still plays out
            ((and (scene-camera s) (camera-shaking? (scene-camera s)))
             (update-scene s camera: (camera-follow (scene-camera s) #f view-w view-h
                                                    (scene-tilemap s))))
            (else s)))))
