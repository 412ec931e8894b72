;;; Keyword arguments are checked (keywords.scm): every public procedure
;;; that takes them rejects an unknown keyword with an error naming the
;;; procedure, the keyword and the nearest valid one. Each call below
;;; fails in the check, before its other arguments are looked at.

(import scheme (chicken base) (chicken condition) (chicken string) (chicken format)
        (downstroke test) (downstroke keywords)
        (downstroke decode) (downstroke engine) (downstroke input)
        (downstroke tilemap) (downstroke prefabs) (downstroke renderer) (downstroke scene)
        (downstroke sdl2) (downstroke sound) (downstroke text) (downstroke tween) (downstroke overlap) (downstroke physics))

(define (kw-message thunk)
  (handle-exceptions e ((condition-property-accessor 'exn 'message "") e) (thunk) "no error"))

;; (name thunk-with-a-misspelt-keyword expected-suggestion)
(define kw-cases
  (list
   (list "zlib-inflate" (lambda () (zlib-inflate #f max-szie: 1)) "max-size:")
   (list "gzip-inflate" (lambda () (gzip-inflate #f max-szie: 1)) "max-size:")
   (list "zstd-decompress" (lambda () (zstd-decompress #f max-szie: 1)) "max-size:")
   (list "zlib-deflate" (lambda () (zlib-deflate #f levle: 1)) "level:")
   (list "gzip-deflate" (lambda () (gzip-deflate #f levle: 1)) "level:")
   (list "zstd-compress" (lambda () (zstd-compress #f levle: 1)) "level:")
   (list "game-run!" (lambda () (game-run! #f frmaes: 1)) "frames:")
   (list "make-game" (lambda () (make-game widht: 320)) "width:")
   (list "game-add-state!" (lambda () (game-add-state! #f 'play updte: #f)) "update:")
   (list "make-input-config" (lambda () (make-input-config keyz: '())) "keys:")
   (list "game-load-scene!" (lambda () (game-load-scene! #f "m.tmx" entites: '())) "entities:")
   (list "make-layer" (lambda () (make-layer "l" 1 1 #f visble?: #t)) "visible?:")
   (list "list->tilemap" (lambda () (list->tilemap '((0)) tile-widht: 8)) "tile-width:")
   (list "make-sheet-tileset" (lambda () (make-sheet-tileset "s.png" tile-widht: 8)) "tile-width:")
   (list "map-object->entity" (lambda () (map-object->entity #f #f prefab: #f)) "prefabs:")
   (list "tilemap-objects->entities" (lambda () (tilemap-objects->entities #f layer: #t)) "layers:")
   (list "parse-prefabs" (lambda () (parse-prefabs '() sorce: "x")) "source:")
   (list "instantiate-prefab" (lambda () (instantiate-prefab #f 'p override: '())) "overrides:")
   (list "render-debug-overlay!" (lambda () (render-debug-overlay! #f #f view-widht: 1)) "view-width:")
   (list "render-scene!" (lambda () (render-scene! #f #f texture: '())) "textures:")
   (list "make-camera" (lambda () (make-camera xx: 1)) "x:")
   (list "make-scene" (lambda () (make-scene entites: '())) "entities:")
   (list "make-sprite-scene" (lambda () (make-sprite-scene entites: '())) "entities:")
   (list "update-scene" (lambda () (update-scene #f entites: '())) "entities:")
   (list "create-renderer!" (lambda () (create-renderer! #f vsync: #t)) "vsync?:")
   (list "render-copy!" (lambda () (render-copy! #f #f #f #f flips: '())) "flip:")
   (list "push-key-event!" (lambda () (push-key-event! 'key-down 'a repeat: #t)) "repeat?:")
   (list "init-audio!" (lambda () (init-audio! frequncy: 1)) "frequency:")
   (list "play-music!" (lambda () (play-music! volum: 1)) "volume:")
   (list "draw-text!" (lambda () (draw-text! #f #f "t" 0 0 colour: '())) "color:")
   (list "make-sprite-font" (lambda () (make-sprite-font #f glyph-widht: 6)) "glyph-width:")
   (list "sprite-text-size" (lambda () (sprite-text-size #f "t" scal: 2)) "scale:")
   (list "draw-sprite-text!" (lambda () (draw-sprite-text! #f #f "t" 0 0 scal: 2)) "scale:")
   (list "load-tileset" (lambda () (load-tileset "t.tsx" first-git: 1)) "first-gid:")
   (list "make-tween" (lambda () (make-tween '() duraton: 10)) "duration:")
   (list "camera-shake" (lambda () (camera-shake (make-camera) 2 decy: 1/2)) "decay:")
   (list "scene-overlapping" (lambda () (scene-overlapping (make-scene) '() wher: #f)) "where:")
   (list "tune-physics!" (lambda () (tune-physics! gravty: 2)) "gravity:")))

(test-group "keywords: an unknown keyword names the procedure and the nearest one"
  (for-each
   (lambda (c)
     (let ((msg (kw-message (cadr c))))
       (test-assert (sprintf "~a: ~a" (car c) msg)
                    (and (string? msg)
                         (substring-index (string-append (car c) ": unknown keyword ") msg)
                         (substring-index (string-append "(did you mean " (caddr c) "?)") msg)))))
   kw-cases)
  (test "38 procedures checked" 38 (length kw-cases)))

(test-group "keywords: the other mistakes with keywords"
  (test "a keyword with no value" "make-game: keyword width: has no value"
        (kw-message (lambda () (make-game width:))))
  (test "a value where a keyword goes"
        "make-camera: expected a keyword, got 3 (keywords: x: y: deadzone: follow-rate: bounds: zoom:)"
        (kw-message (lambda () (make-camera 3))))
  (test "nothing near: the valid keywords are listed"
        "make-camera: unknown keyword colour: (keywords: x: y: deadzone: follow-rate: bounds: zoom:)"
        (kw-message (lambda () (make-camera colour: 1))))
  (test "two equally near ones are both named"
        "make-camera: unknown keyword z: (did you mean x: or y:?)"
        (kw-message (lambda () (make-camera z: 1))))
  (test "valid keywords still work" '(3 4)
        (let ((c (make-camera x: 3 y: 4))) (list (camera-x c) (camera-y c)))))
