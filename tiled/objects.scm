;;; (downstroke objects): the objects of a Tiled map's object layers as
;;; entities, through prefabs when given. Pure; (downstroke tilemap) offers
;;; it with the maps, and game-load-scene! uses it.

(module (downstroke objects)
  (map-object->entity tilemap-objects->entities
   ;; for sibling modules only: the level loader's choice of layers
   object-layer-selector)

  (import (downstroke keywords))
  (import scheme (chicken base) (chicken format) (chicken keyword) (chicken string)
          (chicken condition)
          (downstroke map)
          (only (downstroke prefabs) prefabs? prefab-names instantiate-prefab)
          (only (downstroke util) list-min))

  ;;; ------------------------------------------------------------------
  ;;; Map objects as entities.
  ;;;
  ;;; (map-object->entity tm object #!key prefabs layer frame-delay) -> an entity alist
  ;;; (tilemap-objects->entities tm #!key prefabs (layers #t) frame-delay) -> a list
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
  ;;;   #:animations tile objects whose tile Tiled animates: that animation,
  ;;;                named tiled, its frames (gid . ticks), a tick being
  ;;;                frame-delay: ms (16 unless given; game-load-scene! gives
  ;;;                the game's); each frame ends on the tick nearest to
  ;;;                where Tiled ends it (so the rounding never adds up),
  ;;;                and lasts at least one. A prefab's #:animations win;
  ;;;   #:rotation   degrees clockwise, when not 0 (the box is unrotated);
  ;;;   #:shape      ellipse, capsule, point, polygon, polyline or text (rectangles
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

  (define/keywords (map-object->entity tm o #!key (prefabs #f) (layer #f) (frame-delay 16))
    (unless (and (real? frame-delay) (exact? frame-delay) (> frame-delay 0))
      (error 'map-object->entity (sprintf "frame-delay: must be an exact number of ms > 0, got ~s" frame-delay)))
    (with-tiled-animation tm o (object->entity tm o prefabs layer) frame-delay))

  (define (object->entity tm o prefabs layer)
    (when (and prefabs (not (prefabs? prefabs)))
      (error 'map-object->entity "prefabs: must be a prefab collection (load-prefabs) or #f"
             prefabs))
    (receive (bx by w h) (tilemap-object-box tm o)
      (let* ((x (if layer (+ bx (layer-offset-x layer)) bx))
             (y (if layer (+ by (layer-offset-y layer)) by))
             (type (object-type-symbol o))
             (shape (object-shape o))
             (points (object-points o))
             (x0 (if (pair? points) (list-min (map car points)) 0))
             (y0 (if (pair? points) (list-min (map cdr points)) 0))
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

;; The tile's Tiled animation as the entity's, unless it has animations.
  (define (with-tiled-animation tm o e frame-delay)
    (let* ((info (and (eq? (object-shape o) 'tile) (tilemap-tile-info tm (object-gid o))))
           (frames (and info (tile-animation info))))
      (if (or (not (pair? frames)) (assq #:animations e))
          e
          (let ((first (tileset-first-gid (tilemap-tileset-for tm (object-gid o)))))
            (append e (list (cons #:animations
                                  (list (list (cons #:name 'tiled)
                                              (cons #:frames (tiled-frames frames first frame-delay)))))))))))

  ;; ((local-id . ms) ...) -> ((gid . ticks) ...): frame k ends on the tick
  ;; nearest to the sum of the ms of frames 0..k.
  (define (tiled-frames frames first frame-delay)
    (let loop ((fs frames) (ms 0) (ticks 0) (out '()))
      (if (null? fs)
          (reverse out)
          (let* ((ms (+ ms (cdar fs)))
                 (n (max 1 (- (round (/ ms frame-delay)) ticks))))
            (loop (cdr fs) ms (+ ticks n)
                  (cons (cons (+ first (caar fs)) n) out))))))

  ;; A predicate on layers from a layers: value (#t, names, or a predicate).
  ;; Given the map, a name that is none of its object layers is an error
  ;; naming the file and listing them: a misspelt name would otherwise
  ;; convert nothing, without a word.
  (define (object-layer-selector who layers #!optional tm)
    (cond ((eq? layers #t) (lambda (l) #t))
          ((not layers) (lambda (l) #f))
          ((procedure? layers) layers)
          ((and (list? layers) (every-string? layers))
           (when tm (for-each (lambda (name) (check-object-layer-name who tm name)) layers))
           (lambda (l) (and (member (layer-name l) layers) #t)))
          (else (error who "layers: must be #t, #f, a list of layer names or a predicate"
                       layers))))

  (define (check-object-layer-name who tm name)
    (let ((names (map layer-name (tilemap-object-layers tm))))
      (unless (member name names)
        (error who
               (sprintf "~a: no object layer named ~s~a; its object layers are ~s"
                        (or (tilemap-source tm) "map made in code") name
                        (if (let tile? ((ls (tilemap-all-layers tm)))
                              (and (pair? ls)
                                   (or (and (equal? (layer-name (car ls)) name)
                                            (not (eq? (layer-kind (car ls)) 'object)))
                                       (tile? (cdr ls)))))
                            " (a layer of that name holds no objects)"
                            "")
                        names)))))

  (define (every-string? l) (or (null? l) (and (string? (car l)) (every-string? (cdr l)))))

  ;; Errors name the map, the layer and the object.
  (define (object->entity/named tm layer o prefabs frame-delay)
    (handle-exceptions exn
        (error 'tilemap-objects->entities
               (sprintf "~a: object layer ~s, object ~a~a: ~a"
                        (or (tilemap-source tm) "map made in code")
                        (layer-name layer) (object-id o)
                        (if (equal? (object-name o) "") "" (sprintf " (~s)" (object-name o)))
                        ((condition-property-accessor 'exn 'message "unknown error") exn)))
      (map-object->entity tm o prefabs: prefabs layer: layer frame-delay: frame-delay)))

  (define/keywords (tilemap-objects->entities tm #!key (prefabs #f) (layers #t) (frame-delay 16))
    (when (and prefabs (not (prefabs? prefabs)))
      (error 'tilemap-objects->entities
             "prefabs: must be a prefab collection (load-prefabs) or #f" prefabs))
    (let ((keep? (object-layer-selector 'tilemap-objects->entities layers tm)))
      (let loop ((ls (tilemap-object-layers tm)) (out '()))
        (cond ((null? ls) (reverse out))
              ((keep? (car ls))
               (loop (cdr ls)
                     (let add ((os (layer-objects (car ls))) (out out))
                       (if (null? os)
                           out
                           (add (cdr os)
                                (cons (object->entity/named tm (car ls) (car os) prefabs frame-delay)
                                      out))))))
              (else (loop (cdr ls) out)))))))
