;;; (downstroke scene): a scene is an immutable record of what one screen
;;; holds: its entities, tilemap, camera, background and engine update.
;;; Every "change" returns a new scene.

(module (downstroke scene)
  (make-scene make-sprite-scene update-scene scene?
   scene-entities scene-tilemap scene-tileset scene-tileset-texture
   scene-camera scene-camera-target scene-background scene-engine-update
   scene-collision-mode *default-collision-mode*
   scene-solid-entities
   scene-map-entities scene-transform-entities
   scene-add-entity scene-remove-entities scene-find-tagged scene-find-all-tagged
   make-camera camera? camera-x camera-y camera-follow scene-follow-camera
   ;; map objects as entities
   map-object->entity tilemap-objects->entities object-layer-selector)

  (import scheme (chicken base) (chicken format) (chicken fixnum) (chicken keyword) (chicken string)
          (chicken condition)
          (downstroke entity) (downstroke map)
          (only (downstroke prefabs) prefabs? prefab-names instantiate-prefab))

  (define-record-type camera
    (%make-camera x y)
    camera?
    (x camera-x)
    (y camera-y))

  (define (make-camera #!key (x 0) (y 0)) (%make-camera x y))

  ;; `solids` caches the solid entities of this scene's entity list, which
  ;; ground detection asks for once per gravity entity. It is derived data:
  ;; every new scene starts without it.
  (define-record-type scene
    (%make-scene entities tilemap tileset tileset-texture camera camera-target
                 background engine-update collision-mode solids)
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
    (solids scene-solids-cache scene-solids-cache-set!))

  (define (check-engine-update eu)
    (unless (or (not eu) (eq? eu 'none) (procedure? eu))
      (error 'make-scene "engine-update: must be #f, a procedure or 'none" eu))
    eu)

  (define (check-collision-mode mode)
    (unless (memq mode '(discrete swept))
      (error 'make-scene "collision-mode: must be 'discrete or 'swept" mode))
    mode)

  (define (check-entities entities)
    (unless (list? entities)
      (error 'make-scene "entities: must be a list of entities" entities))
    ;; alists come back as they are, so the list is shared, not copied
    (map/shared as-entity entities))

  ;; How tile collisions are resolved unless a scene or an entity says
  ;; otherwise (see physics.scm and docs/physics.org).
  (define *default-collision-mode* 'swept)

  ;; camera-target: the tag of the entity the camera centres on after each
  ;; update: ('camera-target unless given), or #f for a camera that stays put.
  (define (make-scene #!key (entities '()) (tilemap #f) (tileset #f)
                      (tileset-texture #f) (camera (make-camera))
                      (camera-target 'camera-target) (background #f)
                      (engine-update #f) (collision-mode *default-collision-mode*))
    (%make-scene (check-entities entities) tilemap tileset tileset-texture
                 camera camera-target background
                 (check-engine-update engine-update)
                 (check-collision-mode collision-mode) #f))

  ;; A scene with no map: sprites over a background.
  (define (make-sprite-scene #!key (entities '()) (tileset #f) (tileset-texture #f)
                             (camera (make-camera)) (camera-target 'camera-target)
                             (background #f) (engine-update #f))
    (make-scene entities: entities tileset: tileset tileset-texture: tileset-texture
                camera: camera camera-target: camera-target background: background
                engine-update: engine-update collision-mode: *default-collision-mode*))

  ;; A marker for "keyword not given", distinct from every value a user passes.
  (define unset (list 'unset))
  (define (given? v) (not (eq? v unset)))

  (define (update-scene s #!key (entities unset) (tilemap unset) (tileset unset)
                        (tileset-texture unset) (camera unset) (camera-target unset)
                        (background unset) (engine-update unset) (collision-mode unset))
    (let ((pick (lambda (new old) (if (given? new) new old))))
      (%make-scene (if (given? entities) (check-entities entities) (scene-entities s))
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
                   ;; the cache survives only when the entity list does
                   (if (given? entities) #f (scene-solids-cache s)))))

  ;; The same scene holding a new entity list (already entity alists).
  (define (with-entities s entities)
    (%make-scene entities (scene-tilemap s) (scene-tileset s) (scene-tileset-texture s)
                 (scene-camera s) (scene-camera-target s) (scene-background s)
                 (scene-engine-update s) (scene-collision-mode s) #f))

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
  (define (map/shared f ls)
    ;; results pile up in reverse; `changed` is the index of the last one
    ;; that differs from its argument (-1: none does)
    (let loop ((rest ls) (acc '()) (n 0) (changed -1))
      (if (null? rest)
          (if (fx< changed 0)
              ls
              (let rebuild ((acc (list-tail acc (fx- (fx- n 1) changed)))
                            (out (list-tail ls (fx+ changed 1))))
                (if (null? acc) out (rebuild (cdr acc) (cons (car acc) out)))))
          (let ((y (f (car rest))))
            (loop (cdr rest) (cons y acc) (fx+ n 1) (if (eq? y (car rest)) changed n))))))

  ;; (proc scene entity) -> entity, for every entity; proc sees this scene,
  ;; i.e. every entity as it was before the map. When proc changes nothing
  ;; the scene itself comes back.
  (define (scene-map-entities s proc)
    (let ((out (map/shared (lambda (e) (proc s e)) (scene-entities s))))
      (if (eq? out (scene-entities s)) s (with-entities s out))))

  ;; (proc entities) -> entities, over the whole list at once.
  (define (scene-transform-entities s proc)
    (let ((out (proc (scene-entities s))))
      (if (eq? out (scene-entities s)) s (with-entities s out))))

  (define (scene-add-entity s e)
    (with-entities s (append (scene-entities s) (list (as-entity e)))))

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

  ;; The camera that centres a view of view-w x view-h on `target`, kept
  ;; inside the map when there is one (a map smaller than the view pins the
  ;; camera to the map's top or left edge). An infinite map's edges are
  ;; those of its chunks, negative ones included. Values stay exact; the
  ;; renderer rounds.
  (define (camera-follow camera target view-w view-h tilemap)
    (define (axis centre view lo extent)
      (let ((pos (- centre (/ view 2))))
        (if extent (max lo (min pos (- (+ lo extent) view))) pos)))
    (let* ((target (as-entity target))    ; a plist target works too
           (cx (+ (entity-ref target #:x 0) (/ (entity-ref target #:width 0) 2)))
           (cy (+ (entity-ref target #:y 0) (/ (entity-ref target #:height 0) 2))))
      (%make-camera (axis cx view-w
                          (if tilemap (* (tilemap-origin-col tilemap) (tilemap-tile-width tilemap)) 0)
                          (and tilemap (tilemap-pixel-width tilemap)))
                    (axis cy view-h
                          (if tilemap (* (tilemap-origin-row tilemap) (tilemap-tile-height tilemap)) 0)
                          (and tilemap (tilemap-pixel-height tilemap))))))

  ;; What the engine does after update:, as a pure function of the scene.
  (define (scene-follow-camera s view-w view-h)
    (let* ((tag (scene-camera-target s))
           (target (and tag (scene-find-tagged s tag))))
      (if target
          (update-scene s camera: (camera-follow (scene-camera s) target view-w view-h
                                                 (scene-tilemap s)))
          s)))

  ;;; ------------------------------------------------------------------
  ;;; Map objects as entities.
  ;;;
  ;;; (map-object->entity tm object #!key prefabs layer) -> an entity alist
  ;;; (tilemap-objects->entities tm #!key prefabs (layers #t)) -> a list
  ;;;
  ;;; An object of a Tiled object layer becomes an entity with, in order:
  ;;;   #:type       the object's class (its `type` before Tiled 1.9) as a
  ;;;                symbol, or #f when it has none;
  ;;;   #:x #:y #:width #:height
  ;;;                its box (tilemap-object-box): the top-left corner, so a
  ;;;                tile object, which Tiled anchors at its bottom-left,
  ;;;                gets #:y = y - height; a polygon its points' bounding
  ;;;                box; a point 0 x 0. Given the object's layer (layer:,
  ;;;                which tilemap-objects->entities always gives), the
  ;;;                layer's offset (its groups' included) is added, so the
  ;;;                entity is where Tiled shows the object;
  ;;;   #:object-id  Tiled's object id;
  ;;;   #:name       the object's name, when it has one;
  ;;;   #:tile-id    tile objects: the tile's gid (flags cleared), the number
  ;;;                the renderer draws from the scene's tileset; and
  ;;;                #:facing -1 when the tile is flipped horizontally;
  ;;;   #:rotation   degrees clockwise, when not 0 (the box is unrotated);
  ;;;   #:shape      ellipse, point, polygon, polyline or text (rectangles
  ;;;                and tile objects have none); #:points for polygons and
  ;;;                polylines, ((x . y) ...) relative to #:x #:y;
  ;;;   then every custom property, its name as a keyword ("hp" -> #:hp,
  ;;;   "gravity?" -> #:gravity?), replacing a key above of the same name.
  ;;;   Values are as the loader reads them except: colours become the
  ;;;   (r g b a) lists entities draw with (an unset colour #f), and a
  ;;;   property named "tags" holding a string ("enemy, solid" or
  ;;;   "enemy solid") or a list of strings becomes a list of symbols.
  ;;;
  ;;; With prefabs: (a collection from load-prefabs), an object whose #:type
  ;;; names a prefab is instantiated from it (instantiate-prefab), the keys
  ;;; above as overrides, except a #:width or #:height of 0 (points, empty
  ;;; rectangles), which would hide the prefab's size. Other objects are
  ;;; converted as if no prefabs were given.
  ;;;
  ;;; layers: which object layers: #t (all), a list of layer names, or a
  ;;; predicate on layer records. Entities come in file order: layer by
  ;;; layer, each layer's objects as written. Hidden layers and objects are
  ;;; converted too (visibility is about drawing; a hidden spawn point is
  ;;; still a spawn point).

  (define (colour-value v)
    (if (and (pair? v) (eq? (car v) 'color))
        (if (null? (cdr v)) #f (cdr v))
        v))

  (define (tags-value v)
    (cond ((string? v)
           (map string->symbol (string-split v " ,\t\n")))
          ((and (pair? v) (eq? (car v) 'list))
           (map (lambda (x) (if (string? x) (string->symbol x) x)) (cdr v)))
          (else v)))

  (define (property-entry p)
    (let ((key (string->keyword (car p))))
      (cons key (if (equal? (car p) "tags") (tags-value (cdr p)) (colour-value (cdr p))))))

  ;; Later pairs replace earlier ones of the same key, which keep their place.
  (define (merge-keys base extra)
    (let loop ((rest extra) (acc base))
      (if (null? rest)
          acc
          (loop (cdr rest)
                (if (assq (caar rest) acc)
                    (map (lambda (p) (if (eq? (car p) (caar rest)) (car rest) p)) acc)
                    (append acc (list (car rest))))))))

  (define (object-type-symbol o)
    (let ((c (object-class o)))
      (and (not (equal? c "")) (string->symbol c))))

  (define (map-object->entity tm o #!key (prefabs #f) (layer #f))
    (when (and prefabs (not (prefabs? prefabs)))
      (error 'map-object->entity "prefabs: must be a prefab collection (load-prefabs) or #f"
             prefabs))
    (receive (bx by w h) (tilemap-object-box tm o)
      (let* ((x (if layer (+ bx (layer-offset-x layer)) bx))
             (y (if layer (+ by (layer-offset-y layer)) by))
             (type (object-type-symbol o))
             (shape (object-shape o))
             (points (object-points o))
             (x0 (if (pair? points) (apply min (map car points)) 0))
             (y0 (if (pair? points) (apply min (map cdr points)) 0))
             (own
              (append
               (list (cons #:type type) (cons #:x x) (cons #:y y)
                     (cons #:width w) (cons #:height h)
                     (cons #:object-id (object-id o)))
               (if (equal? (object-name o) "") '() (list (cons #:name (object-name o))))
               (if (eq? shape 'tile)
                   (cons (cons #:tile-id (object-gid o))
                         (if (cell-flipped-horizontally? (object-cell o))
                             (list (cons #:facing -1))
                             '()))
                   '())
               (if (zero? (object-rotation o)) '() (list (cons #:rotation (object-rotation o))))
               (if (memq shape '(rectangle tile)) '() (list (cons #:shape shape)))
               (if (memq shape '(polygon polyline))
                   (list (cons #:points (map (lambda (p) (cons (- (car p) x0) (- (cdr p) y0)))
                                             points)))
                   '())))
             (e (merge-keys own (map property-entry (object-properties o)))))
        (if (and prefabs type (memq type (prefab-names prefabs)))
            (instantiate-prefab
             prefabs type
             overrides: (let loop ((ps e) (out '()))
                          (cond ((null? ps) (reverse out))
                                ((eq? (caar ps) #:type) (loop (cdr ps) out))
                                ((and (memq (caar ps) '(#:width #:height))
                                      (eqv? (cdar ps) 0))
                                 (loop (cdr ps) out))
                                (else (loop (cdr ps) (cons (car ps) out))))))
            e))))

  ;; A predicate on layers from a layers: value (#t, names, or a predicate).
  (define (object-layer-selector who layers)
    (cond ((eq? layers #t) (lambda (l) #t))
          ((not layers) (lambda (l) #f))
          ((procedure? layers) layers)
          ((and (list? layers) (every-string? layers))
           (lambda (l) (and (member (layer-name l) layers) #t)))
          (else (error who "layers: must be #t, #f, a list of layer names or a predicate"
                       layers))))

  (define (every-string? l) (or (null? l) (and (string? (car l)) (every-string? (cdr l)))))

  ;; Errors name the map, the layer and the object.
  (define (object->entity/named tm layer o prefabs)
    (handle-exceptions exn
        (error 'tilemap-objects->entities
               (sprintf "~a: object layer ~s, object ~a~a: ~a"
                        (or (tilemap-source tm) "map made in code")
                        (layer-name layer) (object-id o)
                        (if (equal? (object-name o) "") "" (sprintf " (~s)" (object-name o)))
                        ((condition-property-accessor 'exn 'message "unknown error") exn)))
      (map-object->entity tm o prefabs: prefabs layer: layer)))

  (define (tilemap-objects->entities tm #!key (prefabs #f) (layers #t))
    (when (and prefabs (not (prefabs? prefabs)))
      (error 'tilemap-objects->entities
             "prefabs: must be a prefab collection (load-prefabs) or #f" prefabs))
    (let ((keep? (object-layer-selector 'tilemap-objects->entities layers)))
      (let loop ((ls (tilemap-object-layers tm)) (out '()))
        (cond ((null? ls) (reverse out))
              ((keep? (car ls))
               (loop (cdr ls)
                     (let add ((os (layer-objects (car ls))) (out out))
                       (if (null? os)
                           out
                           (add (cdr os)
                                (cons (object->entity/named tm (car ls) (car os) prefabs)
                                      out))))))
              (else (loop (cdr ls) out)))))))
