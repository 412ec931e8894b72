;;; (downstroke level): a Tiled map into the game's scene, with the
;;; textures its images need; tilesets' textures for scenes built in code.
;;; It needs the game's renderer, so it is called from a hook while
;;; game-run! runs; (downstroke engine) offers it to games.

(module (downstroke level)
  (game-load-scene! game-load-tilesets! load-tilemap-textures!
   ;; for sibling modules only: the engine frees a game's textures when it stops
   free-textures!)

  (import (downstroke keywords))
  (import scheme (chicken base) (chicken format) (chicken condition)
          (downstroke game) (downstroke scene) (downstroke tilemap)
          (downstroke objects) (downstroke sdl2) (downstroke renderer)
          (only (downstroke util) filter every append-map delete-duplicates))

  ;;; ------------------------------------------------------------------
  ;;; (game-load-scene! game tmx-path #!key entities background camera
  ;;;                   camera-target engine-update objects->entities prefabs)
  ;;;
  ;;; Loads the TMX map (load-tilemap), a texture with the game's renderer
  ;;; for every tileset image (and every tile image of image-collection
  ;;; tilesets) and every image layer's image, and makes a scene of them
  ;;; the game's scene, which it also returns. The scene's tileset-texture
  ;;; is the first tileset's texture (entity sprites); every texture is in
  ;;; game-textures, which the frame loop passes to render-scene!. An
  ;;; image's `trans` colour is keyed out of its texture. The scene's
  ;;; background is background: when given, else the map's backgroundcolor
  ;;; (else black). It needs
  ;;; the renderer, so it is called from a hook during game-run! (create:
  ;;; is the usual place). Loading another scene destroys the previous
  ;;; scene's textures (each is freed once); the rest are freed when
  ;;; game-run! ends.
  ;;;
  ;;; Map objects become entities only when asked (existing callers, which
  ;;; pass their entities with entities:, see no change):
  ;;;   objects->entities: #t converts the objects of every object layer,
  ;;;     a list of layer names those layers' only, a predicate on layer
  ;;;     records the layers it accepts; #f none. Default: #f, or #t when
  ;;;     prefabs: is given.
  ;;;   prefabs: a collection from load-prefabs: an object whose type (class)
  ;;;     names a prefab is instantiated from it.
  ;;; The conversion is (downstroke objects)' tilemap-objects->entities (see
  ;;; there for the keys an object gives). The scene's entities are the
  ;;; map's, in file order, followed by entities:, so the caller's (a
  ;;; player, say) draw on top. The object layers converted are hidden in
  ;;; the scene's map (tilemap-hide-layers: their objects are still listed
  ;;; by tilemap-objects), so a tile object is drawn once, as its entity.
  ;;;
  ;;; Nothing is changed before the map has loaded, its orientation is
  ;;; known to be drawable (orthogonal, isometric, staggered or hexagonal;
  ;;; physics sees every map as an orthogonal grid: see docs/tilemaps.org), its
  ;;; objects are converted and every texture is loaded; a texture that
  ;;; fails to load frees the ones loaded before it.

  (define (free-textures! game)
    (for-each (lambda (p) (destroy-texture! (cdr p))) (game-textures game))
    (game-textures-set! game '()))

  ;; Every image the map draws: tileset images, tile images of image
  ;; collections, image layers' images; each once, in that order, as
  ;; image records (their path and transparent colour).
  (define (tilemap-images tm)
    (distinct-images
     (append (tileset-images (tilemap-tilesets tm))
             (map layer-image (tilemap-image-layers tm)))))

  ;; A tileset's image, or its tiles' images for an image collection (#f
  ;; where a tile has none).
  (define (tileset-images tilesets)
    (append-map
     (lambda (ts)
       (let ((img (tileset-image ts)))
         (if img
             (list img)
             (map tile-image (tileset-tiles ts)))))
     tilesets))

  ;; The images with a path, each path once, in their first order (an
  ;; image named twice is keyed out if any of its uses says so).
  (define (distinct-images imgs)
    (let* ((imgs (filter (lambda (i) (and i (string? (image-source i)))) imgs))
           (paths (delete-duplicates (map image-source imgs))))
      (map (lambda (p)
             (let ((same (filter (lambda (i) (equal? (image-source i) p)) imgs)))
               (or (find-first (lambda (i) (image-trans i)) same) (car same))))
           paths)))

  (define (find-first ok? l) (cond ((null? l) #f) ((ok? (car l)) (car l)) (else (find-first ok? (cdr l)))))

  ;; The colour key of an image: its trans colour as (r g b), or #f.
  (define (image-key img)
    (let ((t (image-trans img)))
      (and t (pair? t) (eq? (car t) 'color) (pair? (cdr t))
           (list (cadr t) (caddr t) (cadddr t)))))

  ;;; (load-tilemap-textures! renderer tilemap) loads a texture for every
  ;;; image the map draws (tileset images, image collections' tile images,
  ;;; image layers' images), with an image's `trans` colour keyed out, and
  ;;; returns them as an alist (path . texture), what render-scene!'s
  ;;; textures: takes. All are loaded or none: a failure frees the ones
  ;;; loaded before it and raises. The caller owns the textures.
  (define (load-tilemap-textures! r tm)
    (load-textures! r (tilemap-images tm)))

  (define unset-key (list 'unset))

  ;; The map's backgroundcolor as a scene background (r g b a), or #f.
  (define (map-background tm)
    (let ((c (tilemap-background-color tm)))
      (and c (pair? c) (eq? (car c) 'color) (pair? (cdr c)) (cdr c))))

  (define (live-game-renderer who game what)
    (let ((r (game-renderer game)))
      (unless (and r (renderer-alive? r))
        (error who (sprintf "no renderer: call it from a hook during game-run! (loading ~a)" what)))
      r))

  (define/keywords (game-load-scene! game tmx-path #!key (entities '()) (background #f)
                            (camera (make-camera)) (camera-target 'camera-target)
                            (engine-update #f) (objects->entities unset-key) (prefabs #f))
    (let ((r (live-game-renderer 'game-load-scene! game (sprintf "~s" tmx-path))))
      (let* ((tm (load-tilemap tmx-path))
             (_ (check-map-orientation 'game-load-scene! tm))
             (convert (if (eq? objects->entities unset-key) (and prefabs #t) objects->entities))
             (convert? (object-layer-selector 'game-load-scene! convert tm))
             (map-entities (tilemap-objects->entities tm prefabs: prefabs layers: convert?
                                                         frame-delay: (game-frame-delay game)))
             (textures (load-textures! r (tilemap-images tm)))
             (first-ts (and (pair? (tilemap-tilesets tm)) (car (tilemap-tilesets tm))))
             (first-img (and first-ts (tileset-image first-ts)))
             (first-tex (and first-img (let ((p (assoc (image-source first-img) textures)))
                                         (and p (cdr p)))))
             (shown (if convert
                        (tilemap-hide-layers tm (lambda (l) (and (eq? (layer-kind l) 'object)
                                                                 (convert? l))))
                        tm))
             (scene (make-scene entities: (append map-entities entities)
                                tilemap: shown tileset-texture: first-tex
                                background: (or background (map-background tm))
                                camera: camera
                                camera-target: camera-target engine-update: engine-update)))
        (free-textures! game)
        (game-textures-set! game textures)
        (game-scene-set! game scene)
        scene)))

  ;;; (game-load-tilesets! game tilesets) loads a texture for every image
  ;;; of these tilesets (from load-tileset, make-sheet-tileset or a map)
  ;;; that the game has none for yet, and adds them to game-textures: a
  ;;; scene whose map or sprites are built in code draws from them. They
  ;;; belong to the game like a loaded scene's: the next game-load-scene!
  ;;; or the end of game-run! frees them. All are loaded or none (a failure
  ;;; frees what it loaded and changes nothing). Returns the tilesets.
  (define (game-load-tilesets! game tilesets)
    (unless (and (list? tilesets) (every tileset? tilesets))
      (error 'game-load-tilesets! "expected a list of tilesets" tilesets))
    (let* ((r (live-game-renderer 'game-load-tilesets! game
                                  (sprintf "~a tileset~a" (length tilesets)
                                           (if (= 1 (length tilesets)) "" "s"))))
           (have (game-textures game))
           (imgs (filter (lambda (i) (not (assoc (image-source i) have)))
                         (distinct-images (tileset-images tilesets)))))
      (game-textures-set! game (append have (load-textures! r imgs)))
      tilesets))

  ;; (path . texture) for each image; on a failure the ones loaded are freed.
  (define (load-textures! r imgs)
    (let loop ((is imgs) (out '()))
      (if (null? is)
          (reverse out)
          (let ((tex (handle-exceptions exn
                         (begin (for-each (lambda (p) (destroy-texture! (cdr p))) out)
                                (signal exn))
                       (img-load-texture! r (image-source (car is)) (image-key (car is))))))
            (loop (cdr is) (cons (cons (image-source (car is)) tex) out)))))))
