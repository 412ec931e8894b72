;;; (downstroke tilemap), the TMX loader: Tiled's own example maps, our
;;; fixtures in tests/maps/ (every encoding, infinite maps, every property
;;; type and object shape, groups, templates, image collections, external
;;; tilesets in another directory), and one test per kind of bad input.
;;;
;;; Expected values for Tiled's examples come from tools/tmx-expected.py
;;; (python's standard library only, never this loader), pasted below.

(import scheme (chicken base) (chicken format) (chicken string) (chicken file) (chicken condition) (chicken port)
        (chicken process) (chicken pathname) (chicken bitwise) srfi-4
        (only (downstroke util) find any iota)
        (downstroke test) (downstroke tilemap) (downstroke decode))

(define tmx-examples-dir "data/tiled-examples")

;; Fetch Tiled's examples when `make test` has not already done it.
(unless (file-exists? (make-pathname tmx-examples-dir ".complete"))
  (system "sh ../tools/fetch-tiled-examples.sh >/dev/null 2>&1"))

;; (path layer-count tile-layer-count object-count
;;   ((tile-layer-name non-empty flipped ((col row raw) ...)) ...))
(define tmx-example-expectations
  '(
    ("desert.tmx" 1 1 0
      (("Ground" 1600 0 ((0 0 30) (0 20 39) (39 39 30)))))
    ("hexagonal-mini.tmx" 1 1 0
      (("Ground" 400 0 ((0 0 15) (0 10 14) (19 19 3)))))
    ("isometric_grass_and_water.tmx" 1 1 0
      (("Tile Layer 1" 625 0 ((0 0 24) (12 12 23) (24 24 1)))))
    ("isometric_staggered_grass_and_water.tmx" 1 1 0
      (("Tile Layer 1" 1250 0 ((0 0 24) (1 30 1) (24 49 23)))))
    ("orthogonal-outside.tmx" 3 2 29
      (("Ground" 1395 3 ((0 0 223) (10 10 2147483703) (22 15 222) (44 30 101)))
       ("Fringe" 190 48 ((1 0 93) (23 9 2147483811) (37 16 185) (38 30 287)))))
    ("perspective_walls.tmx" 3 3 0
      (("Walls" 77 0 ((6 11 5) (14 15 14) (13 22 7)))
       ("Walls level 2" 1 0 ((21 13 3)))
       ("Walls level 3" 1 0 ((20 12 3)))))
    ("rpg/island.tmx" 4 3 3
      (("Ground" 2726 4 ((0 0 149) (22 18 1610613107) (29 23 149) (57 46 149)))
       ("Fringe" 81 0 ((48 10 554) (33 26 560) (10 38 623)))
       ("Over" 69 0 ((36 19 476) (27 24 698) (29 30 596)))))
    ("sewer_automap/rule_001.tmx" 3 3 0
      (("Regions" 3 0 ((1 1 73) (3 1 73) (5 1 73)))
       ("Input_set" 3 0 ((1 1 73) (3 1 74) (5 1 75)))
       ("Output_Ground" 3 0 ((1 1 13) (3 1 28) (5 1 34)))))
    ("sewer_automap/rule_002.tmx" 3 3 0
      (("Regions" 8 0 ((1 1 76) (1 2 76) (6 3 76)))
       ("Input_set" 8 0 ((1 1 75) (1 2 74) (6 3 75)))
       ("Output_Ground" 4 0 ((1 1 42) (3 2 26) (6 3 33)))))
    ("sewer_automap/rule_003.tmx" 4 4 0
      (("Regions" 11 0 ((1 1 76) (3 2 76) (1 4 76)))
       ("Input_set" 6 0 ((1 1 73) (1 3 73) (5 3 73)))
       ("Output_Ground" 5 0 ((1 1 2) (1 2 10) (5 3 14)))
       ("Output_Over" 2 0 ((3 1 5) (3 2 13)))))
    ("sewer_automap/rule_004.tmx" 4 4 0
      (("Regions" 16 0 ((1 1 76) (1 3 76) (5 4 76)))
       ("Input_set" 14 0 ((1 1 73) (5 2 73) (5 4 73)))
       ("Output_Ground" 5 0 ((1 1 13) (5 2 12) (5 3 12)))
       ("Output_Over" 2 0 ((1 1 8) (5 1 7)))))
    ("sewer_automap/rule_005.tmx" 4 4 0
      (("Regions" 24 0 ((1 1 76) (7 3 76) (11 4 76)))
       ("Input_set" 8 0 ((1 1 73) (1 3 73) (10 4 73)))
       ("Output_Ground" 6 0 ((1 1 22) (5 2 9) (5 3 17)))
       ("Output_Over" 4 0 ((8 2 4) (8 3 12) (10 3 14)))))
    ("sewer_automap/rule_006.tmx" 6 6 0
      (("Regions" 12 0 ((1 1 76) (4 2 76) (5 3 76)))
       ("Input_set" 6 0 ((2 2 73) (2 3 73) (5 3 73)))
       ("InputNot_set" 2 0 ((1 2 73) (5 2 73)))
       ("Output_Ground" 2 0 ((2 2 13) (4 2 13)))
       ("Output_Over" 2 0 ((2 1 13) (4 1 13)))
       ("Output_Over2" 2 0 ((2 1 31) (4 1 32)))))
    ("sewer_automap/rule_007.tmx" 5 5 0
      (("Regions" 16 0 ((1 1 76) (1 4 76) (5 5 76)))
       ("Input_set" 4 0 ((2 2 75) (2 4 75) (4 4 75)))
       ("InputNot_set" 12 0 ((1 1 75) (1 4 75) (5 5 75)))
       ("InputNot_set" 8 0 ((2 1 73) (1 4 73) (4 5 73)))
       ("Output_Ground" 4 0 ((2 2 25) (2 4 41) (4 4 43)))))
    ("sewer_automap/rule_008.tmx" 4 3 1
      (("regions_input" 2 0 ((1 2 76) (2 2 76)))
       ("regions_output" 1 0 ((1 1 76)))
       ("input_Over" 2 0 ((1 2 4) (2 2 13)))))
    ("sewer_automap/rule_009.tmx" 3 2 1
      (("regions" 2 0 ((1 1 76) (2 1 76)))
       ("input_Ground" 2 0 ((1 1 34) (2 1 42)))))
    ("sewer_automap/sewers.tmx" 1 1 0
      (("set" 961 0 ((0 0 1) (15 15 1) (30 30 1)))))
    ("sewers.tmx" 2 2 0
      (("Bottom" 2500 0 ((0 0 13) (0 25 28) (49 49 28)))
       ("Top" 30 0 ((36 0 54) (5 6 5) (14 21 14)))))
    ("sticker-knight/map/sandbox.tmx" 9 0 114
      ())
    ("sticker-knight/map/sandbox2.tmx" 8 0 103
      ())
    ("test_hexagonal_tile_60x60x30.tmx" 1 1 0
      (("Tile Layer 1" 14 12 ((0 0 1) (1 0 536870913) (0 3 2147483649) (6 3 2147483649)))))
    ))

(define (tmx-count-cells layer pred)
  (let ((data (layer-data layer)))
    (let loop ((i 0) (n 0))
      (if (= i (u32vector-length data))
          n
          (loop (+ i 1) (if (pred (u32vector-ref data i)) (+ n 1) n))))))

(define (tmx-non-empty layer)
  (tmx-count-cells layer (lambda (c) (not (zero? (cell-gid c))))))

(define (tmx-flipped layer)
  (tmx-count-cells layer (lambda (c) (not (null? (cell-flags c))))))

(test-group "Tiled's example maps"
  (test-assert "the examples were fetched"
               (file-exists? (make-pathname tmx-examples-dir ".complete")))
  (when (file-exists? (make-pathname tmx-examples-dir ".complete"))
    (for-each
     (lambda (e)
       (let ((path (make-pathname tmx-examples-dir (car e))))
         (test-group (car e)
           (let ((tm (load-tilemap path)))
             (test "layers" (cadr e) (length (tilemap-all-layers tm)))
             (test "tile layers" (caddr e) (length (tilemap-layers tm)))
             (test "objects" (cadddr e) (length (tilemap-objects tm)))
             (for-each
              (lambda (expected layer index)
                (test-group (sprintf "layer ~a ~s" index (car expected))
                  (test "name" (car expected) (layer-name layer))
                  (test "non-empty cells" (cadr expected) (tmx-non-empty layer))
                  (test "flipped cells" (caddr expected) (tmx-flipped layer))
                  (for-each
                   (lambda (cell)
                     (let ((col (car cell)) (row (cadr cell)) (raw (caddr cell)))
                       (test (sprintf "cell (~a, ~a)" col row)
                             (list raw (bitwise-and raw #x0FFFFFFF))
                             (list (tilemap-cell-at tm col row index)
                                   (tilemap-tile-at tm col row index)))))
                   (cadddr expected))))
              (list-ref e 4) (tilemap-layers tm) (iota (length (tilemap-layers tm))))))))
     tmx-example-expectations)
    (let ((tm (load-tilemap (make-pathname tmx-examples-dir "orthogonal-outside.tmx"))))
      (test "a typed map property" '(("enemyTint" color #xa3 #x36 #x36 #xff))
            (tilemap-properties tm)))
    (let ((tm (load-tilemap (make-pathname tmx-examples-dir "test_hexagonal_tile_60x60x30.tmx"))))
      (test "hexagonal attributes" '(hexagonal 30 x odd)
            (list (tilemap-orientation tm) (tilemap-hex-side-length tm)
                  (tilemap-stagger-axis tm) (tilemap-stagger-index tm)))
      (test "flags of cell (5, 0)" '(horizontal vertical hex-120) (tilemap-flags-at tm 5 0)))
    (let ((tm (load-tilemap (make-pathname tmx-examples-dir "sticker-knight/map/sandbox.tmx"))))
      (test "background colour" '(color #x27 #xb9 #x9a 255) (tilemap-background-color tm))
      (test-assert "template objects remember their template"
                   (any (lambda (o) (and (object-template o)
                                         (substring-index "templates/hero.tx" (object-template o))))
                        (tilemap-objects tm))))))

(define (tmx-fixture name) (make-pathname "maps" name))

;; The 4 x 3 grid every enc-*.tmx holds, written by tools/make-tmx-fixtures.scm.
(define tmx-cells
  (u32vector 1 (+ 2 #x80000000) 0 3
             0 (+ 4 #x40000000) (+ 5 #x20000000) 0
             (+ 6 #x80000000 #x40000000 #x20000000) 0 (+ 7 #x10000000) 8))

(test-group "encodings"
  (for-each
   (lambda (enc)
     (let ((tm (load-tilemap (tmx-fixture (sprintf "enc-~a.tmx" enc)))))
       (test (sprintf "~a: cells with their flags" enc) tmx-cells
             (layer-data (tilemap-layer tm "ground")))
       (test (sprintf "~a: tile-at clears the flags" enc) '(1 2 0 3 6 7)
             (map (lambda (p) (tilemap-tile-at tm (car p) (cdr p)))
                  '((0 . 0) (1 . 0) (2 . 0) (3 . 0) (0 . 2) (2 . 2))))
       (test (sprintf "~a: collision uses the flag-free gid" enc)
             '(#t #t #f #t #f #t #t #f #t #f #t #t)
             (map (lambda (i) (tilemap-solid? tm (remainder i 4) (quotient i 4))) (iota 12)))))
   '("csv" "xml" "base64" "zlib" "gzip" "zstd"))
  (let ((tm (load-tilemap (tmx-fixture "enc-csv.tmx"))))
    (test "each flag bit" '((horizontal) (vertical) (diagonal) (horizontal vertical diagonal) (hex-120))
          (map (lambda (p) (tilemap-flags-at tm (car p) (cdr p)))
               '((1 . 0) (1 . 1) (2 . 1) (0 . 2) (2 . 2))))
    (test "flag predicates" '(#t #f #f #f)
          (let ((c (tilemap-cell-at tm 1 0)))
            (list (cell-flipped-horizontally? c) (cell-flipped-vertically? c)
                  (cell-flipped-diagonally? c) (cell-rotated-hex-120? c))))))

(test-group "external tilesets"
  (let* ((tm (load-tilemap (tmx-fixture "enc-zlib.tmx")))
         (ts (car (tilemap-tilesets tm))))
    (test "the .tsx path" "maps/tilesets/terrain.tsx" (tileset-source ts))
    (test "the image resolved against the .tsx, not the map" "maps/images/terrain.png"
          (image-source (tileset-image ts)))
    (test "size, count, columns, spacing, margin" '(16 16 8 4 0 0 64 32)
          (list (tileset-tile-width ts) (tileset-tile-height ts) (tileset-tile-count ts)
                (tileset-columns ts) (tileset-spacing ts) (tileset-margin ts)
                (image-width (tileset-image ts)) (image-height (tileset-image ts))))
    (test "tile offset and alignment" '(2 -3 bottom-left "Ground")
          (list (tileset-offset-x ts) (tileset-offset-y ts) (tileset-object-alignment ts)
                (tileset-class ts)))
    (test "tileset properties" '(("material" . "grass")) (tileset-properties ts))
    (test "per-tile properties" '("Solid" 0.5 (("friction" . 0.8) ("slippery" . #f)))
          (let ((t (tilemap-tile-info tm 1)))
            (list (tile-class t) (tile-probability t) (tile-properties t))))
    (test "animation frames (tile id . ms)" '((1 . 100) (2 . 150) (3 . 200))
          (tile-animation (tileset-tile ts 1)))
    (test "tile info ignores flip flags" '((1 . 100) (2 . 150) (3 . 200))
          (tile-animation (tilemap-tile-info tm (+ 2 #x80000000))))
    (test "collision shapes" '((rectangle 0 8 16 8 ()) (polygon 0 0 0 0 ((0 . 0) (16 . 0) (8 . 8))))
          (map (lambda (o) (list (object-shape o) (object-x o) (object-y o)
                                 (object-width o) (object-height o) (object-points o)))
               (tile-shapes (tileset-tile ts 2))))
    (test "tiles without data" #f (tilemap-tile-info tm 8))
    (test "the tileset of a gid" '(1 #f) (list (tileset-first-gid (tilemap-tileset-for tm 8))
                                             (tilemap-tileset-for tm 0)))))

(test-group "infinite maps"
  (let ((tm (load-tilemap (tmx-fixture "infinite.tmx"))))
    (test "infinite" #t (tilemap-infinite? tm))
    (test "bounds are the union of the chunks" '(-4 -8 12 12)
          (list (tilemap-origin-col tm) (tilemap-origin-row tm)
                (tilemap-width tm) (tilemap-height tm)))
    (test "cells by Tiled's coordinates, negative ones included" '(1 5 2 6)
          (list (tilemap-tile-at tm -4 -4 "a") (tilemap-tile-at tm -1 -1 "a")
                (tilemap-tile-at tm 0 0 "a") (tilemap-tile-at tm 3 3 "a")))
    (test "a second layer's chunk" (list 3 7 (+ 7 #x40000000))
          (list (tilemap-tile-at tm 4 -8 "b") (tilemap-tile-at tm 7 -5 "b")
                (tilemap-cell-at tm 7 -5 "b")))
    (test "gaps between chunks are empty" '(0 0 0)
          (list (tilemap-tile-at tm 0 -4 "a") (tilemap-tile-at tm -4 0 "a")
                (tilemap-tile-at tm 4 -8 "a")))
    (test "solid across layers and chunks" '(#t #t #t #f #f #f)
          (list (tilemap-solid? tm -4 -4) (tilemap-solid? tm 3 3) (tilemap-solid? tm 7 -5)
                (tilemap-solid? tm -5 -4) (tilemap-solid? tm 8 -5) (tilemap-solid? tm 0 4)))
    (test "outside the union is empty" '(0 0)
          (list (tilemap-tile-at tm -5 0 "a") (tilemap-tile-at tm 0 -9 "b")))
    (test-error "an unknown layer inside the union" (tilemap-tile-at tm -4 -4 "c"))
    (test-error "an unknown layer outside the union" (tilemap-tile-at tm -5 0 "c"))
    (test-error "an unknown layer index outside the union" (tilemap-cell-at tm 100 100 2)))
  (let ((tm (load-tilemap (tmx-fixture "enc-csv.tmx"))))
    (test "finite maps start at (0, 0)" '(0 0 #f)
          (list (tilemap-origin-col tm) (tilemap-origin-row tm) (tilemap-infinite? tm)))))

(test-group "features.tmx"
  (let* ((tm (load-tilemap (tmx-fixture "features.tmx")))
         (props (tilemap-properties tm))
         (layer (lambda (name) (find (lambda (l) (equal? (layer-name l) name))
                                     (tilemap-all-layers tm))))
         (object (lambda (name) (find (lambda (o) (equal? (object-name o) name))
                                      (tilemap-objects tm)))))
    (test-group "map attributes"
      (test "orientation, render order, class" '(orthogonal left-up "Level")
            (list (tilemap-orientation tm) (tilemap-render-order tm) (tilemap-class tm)))
      (test "background colour #AARRGGBB" '(color #x11 #x22 #x33 #x80) (tilemap-background-color tm))
      (test "parallax origin" '(8 -4) (list (tilemap-parallax-origin-x tm) (tilemap-parallax-origin-y tm)))
      (test "versions" '("1.10" "1.10.2") (list (tilemap-version tm) (tilemap-tiled-version tm))))
    (test-group "property types"
      (test "string" "Features" (property-ref props "title"))
      (test "multi-line string as element text" "line one\nline two" (property-ref props "notes"))
      (test "int" -3 (property-ref props "lives"))
      (test "float" 9.5 (property-ref props "gravity"))
      (test "a float written as an integer is a flonum" #t (flonum? (property-ref props "whole")))
      (test "bool" '(#t #f) (list (property-ref props "dark") (property-ref props "light")))
      (test "color" '(color #x33 #x66 #x99 255) (property-ref props "tint"))
      (test "unset color" '(color) (property-ref props "unset"))
      (test "file, resolved against the map" '(file "maps/sounds/theme.ogg") (property-ref props "music"))
      (test "object" '(object 12) (property-ref props "boss"))
      (test "class with a nested class"
            '(class "Spawn" (("x" . 4) ("where" class "Point" (("label" . "inner")))))
            (property-ref props "spawn"))
      (test "list" '(list 1 "two" #t) (property-ref props "waves"))
      (test "property-type" '(string int float bool color file object class list)
            (map (lambda (n) (property-type (property-ref props n)))
                 '("title" "lives" "gravity" "dark" "tint" "music" "boss" "spawn" "waves")))
      (test "a missing property gives the default" 'none (property-ref props "nope" 'none)))
    (test-group "layers"
      (test "document order, groups before their children"
            '((tile "ground") (group "outer") (tile "deco") (group "inner") (object "things") (image "sky"))
            (map (lambda (l) (list (layer-kind l) (layer-name l))) (tilemap-all-layers tm)))
      (test "the tree" '("ground" "outer" "sky") (map layer-name (tilemap-layer-tree tm)))
      (test "group children" '("deco" "inner")
            (map layer-name (layer-children (layer "outer"))))
      (test "tile layers, groups flattened" '("ground" "deco") (map layer-name (tilemap-layers tm)))
      (test "id, class, opacity, tint, locked, properties"
            '(1 "Terrain" 0.75 (color 255 128 0 255) #t (("depth" . 1)))
            (let ((l (layer "ground")))
              (list (layer-id l) (layer-class l) (layer-opacity l) (layer-tint l)
                    (layer-locked? l) (layer-properties l))))
      (test "own offset and parallax" '(3 -2 0.5 2)
            (let ((l (layer "ground")))
              (list (layer-offset-x l) (layer-offset-y l) (layer-parallax-x l) (layer-parallax-y l))))
      (test "group offsets compose" '((11 7) (110 205))
            (list (list (layer-offset-x (layer "deco")) (layer-offset-y (layer "deco")))
                  (list (layer-offset-x (layer "things")) (layer-offset-y (layer "things")))))
      (test "parallax multiplies, opacity multiplies, visibility ands"
            '(0.25 0.25 0.5 #f)
            (let ((l (layer "things")))
              (list (layer-parallax-x l) (layer-parallax-y l) (layer-opacity l) (layer-visible? l))))
      (test "object layer colour and draw order" '((color #xa0 #xa0 #xa4 255) index)
            (list (layer-color (layer "things")) (layer-draw-order (layer "things"))))
      (test "image layer" '("maps/images/sky.png" 32 #t #f 4 8)
            (let ((l (layer "sky")))
              (list (image-source (layer-image l)) (image-width (layer-image l))
                    (layer-repeat-x? l) (layer-repeat-y? l) (layer-offset-x l) (layer-offset-y l))))
      (test "a layer in a group has data (gzip)" '(5 6)
            (list (tilemap-tile-at tm 1 0 "deco") (tilemap-tile-at tm 2 1 "deco")))
      (test "collides=false in a group opts out of collision" '(#f #f #t)
            (list (tilemap-solid? tm 1 0) (tilemap-solid? tm 2 1) (tilemap-solid? tm 0 0))))
    (test-group "objects"
      (test "count" 10 (length (tilemap-objects tm)))
      (test "shapes" '(rectangle ellipse point polygon polyline text tile tile tile text)
            (map object-shape (tilemap-objects tm)))
      (test "rectangle: id, class, position, size, rotation, properties"
            '(1 "Crate" 10 20 30 40 45 #t (("weight" . 7)))
            (let ((o (object "box")))
              (list (object-id o) (object-type o) (object-x o) (object-y o) (object-width o)
                    (object-height o) (object-rotation o) (object-visible? o) (object-properties o))))
      (test "point with fractional position and a class" '(5.5 6.25 "Marker")
            (let ((o (object "spot"))) (list (object-x o) (object-y o) (object-class o))))
      (test "polygon points" '((0 . 0) (10 . 0) (5 . -8.5)) (object-points (object "tri")))
      (test "polyline points, invisible" '(((0 . 0) (4 . 4) (8 . 0) (12 . 4)) #f)
            (list (object-points (object "path")) (object-visible? (object "path"))))
      (test "text" '("Hi there" #t left 16)
            (let ((t (object-text (object "label"))))
              (map (lambda (k) (cdr (assq k t))) '(text wrap? halign pixel-size))))
      (test "tile object: gid and flags" '(9 (horizontal) "Hero")
            (let ((o (object "hero")))
              (list (object-gid o) (cell-flags (object-cell o))
                    (tile-class (tilemap-tile-info tm (object-cell o)))))))
    (test-group "templates"
      (let ((e (object "enemy")) (b (object "boss")))
        (test "instance position, template name, class, size" '(8 64 64 "Enemy" 16 16)
              (list (object-id e) (object-x e) (object-y e) (object-class e)
                    (object-width e) (object-height e)))
        (test "the template's gid is mapped into the map's gids (5+2 in the .tx -> 1+2)" 3
              (object-gid e))
        (test "template properties" '(("hp" . 3) ("speed" . 1.5)) (object-properties e))
        (test "instance name and properties override the template's"
              '("boss" 30 1.5)
              (list (object-name b) (property-ref (object-properties b) "hp")
                    (property-ref (object-properties b) "speed")))
        (test "the template path" "maps/templates/enemy.tx" (object-template e))
        (test "a text template" '("Hello, world" (color 16 32 48 255) center bottom #t 40 1 2)
              (let* ((o (object "sign")) (t (object-text o)))
                (append (map (lambda (k) (cdr (assq k t))) '(text color halign valign bold?))
                        (list (object-width o) (object-x o) (object-y o)))))))
    (test-group "image collection tileset"
      (let ((ts (cadr (tilemap-tilesets tm))))
        (test "no tileset image, sparse ids" '(#f (0 3) 2)
              (list (tileset-image ts) (map tile-id (tileset-tiles ts)) (tileset-tile-count ts)))
        (test "tile images resolved against the map" '("maps/images/hero.png" "maps/images/chest.png")
              (map (lambda (t) (image-source (tile-image t))) (tileset-tiles ts)))
        (test "gid 12 (local id 3) is covered, its properties" '(("loot" . 50))
              (tile-properties (tilemap-tile-info tm 12)))
        (test "grid" '("orthogonal" 1 1) (tileset-grid ts))))))

;;; Bad input: each raises an error whose message names the file and the
;;; problem. The maps are written into a temporary directory.

(define tmx-tmp (create-temporary-directory))

(define (tmx-write name text)
  (let ((path (make-pathname tmx-tmp name)))
    (create-directory (pathname-directory path) #t)
    (with-output-to-file path (lambda () (display text)))
    path))

;; A 2 x 2 map around one layer's <data> element; extra goes after the
;; tilesets (more layers, objects).
(define (tmx-map data #!key (tilesets "<tileset firstgid=\"1\" name=\"t\" tilewidth=\"8\" tileheight=\"8\" tilecount=\"4\" columns=\"2\"><image source=\"img.png\" width=\"16\" height=\"16\"/></tileset>")
                 (attrs "") (extra ""))
  (string-append
   "<?xml version=\"1.0\"?>\n<map version=\"1.10\" orientation=\"orthogonal\" width=\"2\" height=\"2\" "
   "tilewidth=\"8\" tileheight=\"8\"" attrs ">\n" tilesets "\n"
   "<layer id=\"1\" name=\"L\" width=\"2\" height=\"2\">" data "</layer>\n" extra "</map>\n"))

(tmx-write "img.png" "not decoded, only checked for existence")

;; The error names the file and contains every fragment.
(define ((tmx-says path . fragments) exn)
  (let ((text (error-text exn)))
    (and (substring-index path text)
         (tmx-every-fragment? fragments text))))

(define (tmx-every-fragment? fragments text)
  (or (null? fragments)
      (and (substring-index (car fragments) text)
           (tmx-every-fragment? (cdr fragments) text))))

(define (tmx-replace-first text old new)
  (let ((i (substring-index old text)))
    (string-append (substring text 0 i) new
                   (substring text (+ i (string-length old)) (string-length text)))))

(define tmx-csv-data "<data encoding=\"csv\">1,2,3,4</data>")

(define (tmx-b64 bytes) (base64-encode (list->u8vector bytes)))

(test-group "load-time choices: what Tiled itself does"
  ;; A gid past the last tile of its tileset: Tiled loads the map and keeps
  ;; the gid; nothing is drawn there (no tileset answers for it), and the
  ;; cell is solid like any non-zero cell.
  (let* ((p (tmx-write "past.tmx"
                       (tmx-map "<data encoding=\"csv\">1,5,3,2147483654</data>"
                                extra: "<objectgroup name=\"o\"><object id=\"3\" gid=\"9\"/></objectgroup>")))
         (tm (load-tilemap p)))
    (test "the cells keep the gids past the last tile" '(5 2147483654)
          (list (tilemap-cell-at tm 1 0) (tilemap-cell-at tm 1 1)))
    (test "no tileset answers for them, so nothing is drawn" '(#f #f #t)
          (list (tilemap-tileset-for tm 5) (tilemap-tileset-for tm 2147483654)
                (tileset? (tilemap-tileset-for tm 4))))
    (test "they are solid, as every non-zero cell" '(#t #t) (list (tilemap-solid? tm 1 0) (tilemap-solid? tm 1 1)))
    (test "an object past the last tile keeps its gid" 9 (object-gid (car (tilemap-objects tm))))
    (test "and has no tileset" #f (tilemap-tileset-for tm 9)))
  ;; Typed properties written without a value read as the type's empty value.
  (let* ((props (string-append
                 "<properties>"
                 "<property name=\"i\" type=\"int\"/><property name=\"f\" type=\"float\"/>"
                 "<property name=\"b\" type=\"bool\"/><property name=\"s\" type=\"string\"/>"
                 "<property name=\"s2\"/><property name=\"c\" type=\"color\"/>"
                 "<property name=\"fi\" type=\"file\"/><property name=\"o\" type=\"object\"/>"
                 "<property name=\"i2\" type=\"int\" value=\"\"/>"
                 "</properties>"))
         (p (tmx-write "novalue.tmx" (tmx-map tmx-csv-data attrs: "" extra: (string-append "<objectgroup name=\"o\">" props "</objectgroup>"))))
         (tm (load-tilemap p)))
    (test "int 0, float 0.0, bool #f, string \"\", color unset, file \"\", object 0"
          '(("i" . 0) ("f" . 0.0) ("b" . #f) ("s" . "") ("s2" . "") ("c" color) ("fi" file "")
            ("o" object 0) ("i2" . 0))
          (layer-properties (car (tilemap-object-layers tm)))))
  ;; <capsule/> (Tiled 1.11) is a shape of its own.
  (let* ((p (tmx-write "capsule.tmx"
                       (tmx-map tmx-csv-data
                                extra: "<objectgroup name=\"o\"><object id=\"1\" x=\"2\" y=\"3\" width=\"20\" height=\"8\"><capsule/></object></objectgroup>")))
         (o (car (tilemap-objects (load-tilemap p)))))
    (test "a capsule, not a rectangle" '(capsule 2 3 20 8)
          (list (object-shape o) (object-x o) (object-y o) (object-width o) (object-height o)))))

(test-group "errors name the file and the problem"
  (let ((ok (tmx-write "ok.tmx" (tmx-map tmx-csv-data))))
    (test "the well-formed base map loads" 4 (tilemap-tile-at (load-tilemap ok) 1 1)))
  (let ((p (make-pathname tmx-tmp "absent.tmx")))
    (test-error "a missing map" (tmx-says p "no such file") (load-tilemap p)))
  (let ((p (tmx-write "truncated.tmx" (substring (tmx-map tmx-csv-data) 0 150))))
    (test-error "truncated XML" (tmx-says p "malformed XML") (load-tilemap p)))
  (let ((p (tmx-write "notxml.tmx" "<map><layer></map>")))
    (test-error "mismatched tags" (tmx-says p "malformed XML") (load-tilemap p)))
  (let ((p (tmx-write "root.tmx" "<tileset/>")))
    (test-error "the wrong root element" (tmx-says p "root element" "<map>") (load-tilemap p)))
  (let ((p (tmx-write "b64.tmx" (tmx-map "<data encoding=\"base64\">AAAA%AAA</data>"))))
    (test-error "bad base64" (tmx-says p "layer \"L\"" "bad base64") (load-tilemap p)))
  (let ((p (tmx-write "short.tmx"
                      (tmx-map (string-append "<data encoding=\"base64\">"
                                              (tmx-b64 '(1 0 0 0 2 0 0 0 3 0 0 0)) "</data>")))))
    (test-error "uncompressed data of the wrong length" (tmx-says p "12 bytes" "expected 16")
                (load-tilemap p)))
  (let ((p (tmx-write "zshort.tmx"
                      (tmx-map (string-append "<data encoding=\"base64\" compression=\"zlib\">"
                                              (base64-encode (zlib-deflate (make-u8vector 20 0)))
                                              "</data>")))))
    (test-error "decompressed data of the wrong length" (tmx-says p "zlib" "expected 16")
                (load-tilemap p)))
  (let ((p (tmx-write "zbad.tmx"
                      (tmx-map (string-append "<data encoding=\"base64\" compression=\"zstd\">"
                                              (tmx-b64 '(1 2 3 4 5 6 7 8)) "</data>")))))
    (test-error "corrupt compressed data" (tmx-says p "bad zstd data") (load-tilemap p)))
  (let ((p (tmx-write "lzma.tmx" (tmx-map "<data encoding=\"base64\" compression=\"lzma\">AAAA</data>"))))
    (test-error "unknown compression" (tmx-says p "compression" "lzma") (load-tilemap p)))
  (let ((p (tmx-write "hex.tmx" (tmx-map "<data encoding=\"hex\">00</data>"))))
    (test-error "unknown encoding" (tmx-says p "encoding" "hex") (load-tilemap p)))
  (let ((p (tmx-write "csvcomp.tmx" (tmx-map "<data encoding=\"csv\" compression=\"zlib\">1,2,3,4</data>"))))
    (test-error "compression without base64" (tmx-says p "needs base64") (load-tilemap p)))
  (let ((p (tmx-write "csv3.tmx" (tmx-map "<data encoding=\"csv\">1,2,3</data>"))))
    (test-error "too few csv cells" (tmx-says p "3 cells, expected 4") (load-tilemap p)))
  (let ((p (tmx-write "csvx.tmx" (tmx-map "<data encoding=\"csv\">1,2,x,4</data>"))))
    (test-error "a bad csv character" (tmx-says p "unexpected character") (load-tilemap p)))
  (let ((p (tmx-write "csvbig.tmx" (tmx-map "<data encoding=\"csv\">1,2,3,99999999999</data>"))))
    (test-error "a csv cell over 32 bits" (tmx-says p "32 bits") (load-tilemap p)))
  (let ((p (tmx-write "xmltiles.tmx" (tmx-map "<data><tile gid=\"1\"/><tile/></data>"))))
    (test-error "too few <tile> elements" (tmx-says p "2 <tile> elements") (load-tilemap p)))
  (let ((p (tmx-write "gid.tmx" (tmx-map "<data encoding=\"csv\">1,2,3,2</data>"
                                          tilesets: "<tileset firstgid=\"2\" name=\"t\" tilewidth=\"8\" tileheight=\"8\" tilecount=\"4\" columns=\"2\"><image source=\"img.png\" width=\"16\" height=\"16\"/></tileset>"))))
    (test-error "a gid below every tileset's first gid (Tiled: \"Invalid tile\")"
                (tmx-says p "cell (0, 0)" "gid 1" "below the first gid of every tileset")
                (load-tilemap p)))
  (let ((p (tmx-write "gidflip.tmx" (tmx-map "<data encoding=\"csv\">0,0,0,2147483649</data>"
                                              tilesets: "<tileset firstgid=\"2\" name=\"t\" tilewidth=\"8\" tileheight=\"8\" tilecount=\"4\" columns=\"2\"><image source=\"img.png\" width=\"16\" height=\"16\"/></tileset>"))))
    (test-error "an uncovered gid behind flip flags" (tmx-says p "gid 1") (load-tilemap p)))
  (let ((p (tmx-write "objgid.tmx"
                      (tmx-map "<data encoding=\"csv\">0,0,0,0</data>"
                               tilesets: "<tileset firstgid=\"5\" name=\"t\" tilewidth=\"8\" tileheight=\"8\" tilecount=\"4\" columns=\"2\"><image source=\"img.png\" width=\"16\" height=\"16\"/></tileset>"
                               extra: "<objectgroup name=\"o\"><object id=\"3\" gid=\"4\"/></objectgroup>"))))
    (test-error "an object gid below every first gid" (tmx-says p "object 3" "gid 4") (load-tilemap p)))
  (let ((p (tmx-write "notsx.tmx" (tmx-map tmx-csv-data tilesets: "<tileset firstgid=\"1\" source=\"sets/none.tsx\"/>"))))
    (test-error "a missing .tsx" (tmx-says p "tileset file" "sets/none.tsx" "not found") (load-tilemap p)))
  (let ((p (tmx-write "noimg.tmx"
                      (tmx-map tmx-csv-data
                               tilesets: "<tileset firstgid=\"1\" name=\"t\" tilewidth=\"8\" tileheight=\"8\" tilecount=\"4\"><image source=\"gone.png\"/></tileset>"))))
    (test-error "a missing image" (tmx-says p "image file" "gone.png" "not found") (load-tilemap p)))
  (tmx-write "sets/bad.tsx" "<tileset name=\"bad\" tilewidth=\"8\" tileheight=\"8\"><image source=\"../nope.png\"/></tileset>")
  (let ((p (tmx-write "badtsx.tmx" (tmx-map tmx-csv-data tilesets: "<tileset firstgid=\"1\" source=\"sets/bad.tsx\"/>"))))
    (test-error "a missing image named by a .tsx names the .tsx"
                (tmx-says (make-pathname tmx-tmp "sets/bad.tsx") "nope.png" "not found")
                (load-tilemap p)))
  (tmx-write "sets/broken.tsx" "<tileset name=\"b\" tilewidth=\"8\"")
  (let ((p (tmx-write "brokentsx.tmx" (tmx-map tmx-csv-data tilesets: "<tileset firstgid=\"1\" source=\"sets/broken.tsx\"/>"))))
    (test-error "a malformed .tsx names the .tsx"
                (tmx-says (make-pathname tmx-tmp "sets/broken.tsx") "malformed XML")
                (load-tilemap p)))
  (let ((p (tmx-write "notx.tmx"
                      (tmx-map tmx-csv-data
                               extra: "<objectgroup name=\"o\"><object id=\"1\" template=\"t/none.tx\"/></objectgroup>"))))
    (test-error "a missing .tx" (tmx-says p "template file" "none.tx" "not found") (load-tilemap p)))
  (tmx-write "t/a.tx" "<template><object template=\"b.tx\"/></template>")
  (tmx-write "t/b.tx" "<template><object template=\"a.tx\"/></template>")
  (let ((p (tmx-write "cycle.tmx"
                      (tmx-map tmx-csv-data
                               extra: "<objectgroup name=\"o\"><object id=\"1\" template=\"t/a.tx\"/></objectgroup>"))))
    (test-error "a template cycle names the .tx files"
                (tmx-says tmx-tmp "template cycle" "t/a.tx -> " "t/b.tx -> ")
                (load-tilemap p)))
  (let ((p (tmx-write "orient.tmx" (tmx-map tmx-csv-data attrs: " orientation2=\"x\""))))
    (test "an unknown attribute is ignored" 1 (tilemap-tile-at (load-tilemap p) 0 0)))
  (let ((p (tmx-write "orient2.tmx"
                      (string-append "<map orientation=\"spherical\" width=\"1\" height=\"1\" "
                                     "tilewidth=\"8\" tileheight=\"8\"/>"))))
    (test-error "an unsupported orientation" (tmx-says p "orientation" "spherical") (load-tilemap p)))
  (let ((p (tmx-write "width.tmx" (tmx-map tmx-csv-data attrs: " tilewidth=\"-8\""))))
    (test-error "a duplicate attribute is malformed XML" (tmx-says p "malformed XML") (load-tilemap p)))
  (let ((p (tmx-write "badw.tmx" (tmx-replace-first (tmx-map tmx-csv-data) "width=\"2\"" "width=\"two\""))))
    (test-error "a non-numeric width" (tmx-says p "width=\"two\"" "not a non-negative integer")
                (load-tilemap p)))
  (let ((p (tmx-write "badbool.tmx"
                      (tmx-replace-first (tmx-map tmx-csv-data) "<layer id=\"1\" name=\"L\""
                                         "<layer id=\"1\" name=\"L\" visible=\"yes\""))))
    (test-error "a bad boolean says what is accepted"
                (tmx-says p "visible=\"yes\"" "is not 0, 1, true or false")
                (load-tilemap p)))
  (let ((p (tmx-write "textbool.tmx"
                      (tmx-replace-first (tmx-map tmx-csv-data) "<layer id=\"1\" name=\"L\""
                                         "<layer id=\"1\" name=\"L\" visible=\"false\" locked=\"true\""))))
    (test "true and false are accepted as booleans" '(#f #t)
          (let ((l (car (tilemap-layers (load-tilemap p)))))
            (list (layer-visible? l) (layer-locked? l)))))
  (let ((p (tmx-write "huge.tmx" (tmx-replace-first (tmx-map tmx-csv-data) "width=\"2\"" "width=\"4000000000\""))))
    (test-error "a map too large to allocate" (tmx-says p "limit") (load-tilemap p)))
  (let ((p (tmx-write "layersize.tmx"
                      (tmx-replace-first (tmx-map tmx-csv-data) "<layer id=\"1\" name=\"L\" width=\"2\""
                                            "<layer id=\"1\" name=\"L\" width=\"3\""))))
    (test-error "a layer of another size than the map" (tmx-says p "layer \"L\"" "3x2") (load-tilemap p)))
  (let ((p (tmx-write "prop.tmx"
                      (tmx-map tmx-csv-data
                               extra: "<objectgroup name=\"o\"><properties><property name=\"n\" type=\"int\" value=\"1.5\"/></properties></objectgroup>"))))
    (test-error "a bad int property" (tmx-says p "property \"n\"" "not an integer") (load-tilemap p)))
  (let ((p (tmx-write "ptype.tmx"
                      (tmx-map tmx-csv-data
                               extra: "<objectgroup name=\"o\"><properties><property name=\"n\" type=\"vector\" value=\"1\"/></properties></objectgroup>"))))
    (test-error "an unknown property type" (tmx-says p "unknown property type") (load-tilemap p)))
  (let ((p (tmx-write "points.tmx"
                      (tmx-map tmx-csv-data
                               extra: "<objectgroup name=\"o\"><object id=\"2\"><polygon points=\"0,0 1\"/></object></objectgroup>"))))
    (test-error "bad polygon points" (tmx-says p "object 2" "bad point") (load-tilemap p)))
  (let ((p (tmx-write "nodata.tmx"
                      (tmx-replace-first (tmx-map tmx-csv-data) tmx-csv-data ""))))
    (test-error "a layer without data" (tmx-says p "no <data>") (load-tilemap p)))
  (let ((p (tmx-write "chunk.tmx"
                      (tmx-map "<data encoding=\"csv\"><chunk x=\"-3\" y=\"0\" width=\"2\" height=\"1\">1,2,3</chunk></data>"
                               attrs: " infinite=\"1\""))))
    (test-error "a chunk of the wrong length" (tmx-says p "chunk at (-3, 0)" "3 cells, expected 2")
                (load-tilemap p)))
  (test-error "not a string" (load-tilemap 'level1)))

(test-group "only a bool false collides property opts a layer out; any other is named"
  (let* ((layer (lambda (id name prop cells)
                  (string-append
                   "<layer id=\"" id "\" name=\"" name "\" width=\"2\" height=\"2\"><properties>"
                   prop "</properties><data encoding=\"csv\">" cells "</data></layer>")))
         (map-with (lambda (file prop)
                     (tmx-write file
                                (tmx-map "<data encoding=\"csv\">0,0,0,0</data>"
                                         extra: (string-append
                                                 (layer "2" "deco" prop "1,0,0,0")
                                                 (layer "3" "bool" "<property name=\"collides\" type=\"bool\" value=\"false\"/>" "0,0,1,0"))))))
         (message (lambda (thunk)
                    (handle-exceptions e ((condition-property-accessor 'exn 'message "") e) (thunk) "no error")))
         (said (lambda (thunk)
                 (call-with-output-string
                  (lambda (port) (parameterize ((current-error-port port)) (thunk)))))))
    (let ((tm (load-tilemap (map-with "collides-bool.tmx" "<property name=\"hp\" value=\"3\"/>"))))
      (test "a bool false opts its layer out" '(#t #f #f #f)
            (list (tilemap-solid? tm 0 0) (tilemap-solid? tm 1 0)
                  (tilemap-solid? tm 0 1) (tilemap-solid? tm 1 1))))
    (let ((p (map-with "collides-string.tmx" "<property name=\"collides\" value=\"false\"/>")))
      (test-assert "collides without type=\"bool\" (a string): an error naming the file, the layer and the fix"
                   (let ((m (message (lambda () (load-tilemap p)))))
                     (and (substring-index p m) (substring-index "layer \"deco\"" m)
                          (substring-index "collides is \"false\", of type string, not a bool" m)
                          (substring-index "type=\"bool\"" m)))))
    (let ((p (map-with "collides-int.tmx" "<property name=\"collides\" type=\"int\" value=\"0\"/>")))
      (test-assert "an int collides is named too"
                   (substring-index "of type int, not a bool" (message (lambda () (load-tilemap p))))))
    (let ((p (map-with "colides.tmx" "<property name=\"colides\" type=\"bool\" value=\"false\"/>")))
      (test "a misspelt collides: a warning naming the file, the layer and the right name; the map loads"
            (string-append "downstroke: warning: " p ": layer \"deco\": property \"colides\" is not one Downstroke reads; did you mean \"collides\" (a bool)?\n")
            (said (lambda () (load-tilemap p))))
      (test "and its layer collides, as the property is not read" #t
            (parameterize ((current-error-port (open-output-string)))
              (tilemap-solid? (load-tilemap p) 0 0))))
    (let ((p (map-with "one-wya.tmx" "<property name=\"one-wya\" type=\"bool\" value=\"true\"/>")))
      (test-assert "one-way misspelt is said as well"
                   (substring-index "did you mean \"one-way\"" (said (lambda () (load-tilemap p))))))))

(test-group "tilesets without a map: load-tileset and make-sheet-tileset"
  (import (chicken condition))
  (define (from? who) (lambda (exn) (eq? who ((condition-property-accessor 'exn 'location #f) exn))))
  (define (both . preds) (lambda (exn) (let loop ((ps preds)) (or (null? ps) (and ((car ps) exn) (loop (cdr ps)))))))
  (let ((ts (load-tileset (tmx-fixture "tilesets/terrain.tsx"))))
    (test "a lone .tsx reads as it does in a map" '(1 16 16 8 4 "terrain" "Ground" (("material" . "grass")))
          (list (tileset-first-gid ts) (tileset-tile-width ts) (tileset-tile-height ts)
                (tileset-tile-count ts) (tileset-columns ts) (tileset-name ts)
                (tileset-class ts) (tileset-properties ts)))
    (test "its image is resolved against the .tsx" "maps/images/terrain.png"
          (image-source (tileset-image ts)))
    (test "its per-tile data is there" "Solid" (tile-class (tileset-tile ts 0))))
  (let ((ts (load-tileset (tmx-fixture "tilesets/terrain.tsx") first-gid: 9)))
    (test "first-gid: moves its gids" '(#f #t #t #f)
          (map (lambda (gid) (tileset-covers? ts gid)) '(8 9 16 17))))
  (let ((p (make-pathname tmx-tmp "absent.tsx")))
    (test-error "a missing file" (both (tmx-says p "no such file") (from? 'load-tileset))
                (load-tileset p)))
  (let ((p (tmx-write "bad.tsx" "<tileset name=\"x\" tilewidth=\"8\"")))
    (test-error "malformed XML" (both (tmx-says p "malformed XML") (from? 'load-tileset)) (load-tileset p)))
  (let ((p (tmx-write "map-not-tileset.tsx" (tmx-map tmx-csv-data))))
    (test-error "a map is not a tileset" (tmx-says p "root element" "<tileset>") (load-tileset p)))
  (let ((p (tmx-write "no-image.tsx"
                      "<tileset name=\"x\" tilewidth=\"8\" tileheight=\"8\" columns=\"1\"><image source=\"gone.png\"/></tileset>")))
    (test-error "an image that is not there" (tmx-says p "gone.png" "not found") (load-tileset p)))
  (test-error "first-gid: 0" (lambda (exn) (substring-index "first-gid" (error-text exn)))
              (load-tileset (tmx-fixture "tilesets/terrain.tsx") first-gid: 0))
  (test-error "a path that is not a string" (load-tileset 'sprites))
  ;; load-tilemap still reports from load-tilemap after a load-tileset
  (let ((p (make-pathname tmx-tmp "absent.tmx")))
    (test-error "load-tilemap's own errors keep its name" (from? 'load-tilemap) (load-tilemap p)))

  (let* ((img (tmx-fixture "images/terrain.png"))
         (ts (make-sheet-tileset img tile-width: 16 tile-height: 8 columns: 4 tile-count: 16
                                 spacing: 0 margin: 0 first-gid: 5 name: "sheet")))
    (test "a sheet described in code" '(5 16 8 4 16 0 0 "sheet")
          (list (tileset-first-gid ts) (tileset-tile-width ts) (tileset-tile-height ts)
                (tileset-columns ts) (tileset-tile-count ts) (tileset-spacing ts)
                (tileset-margin ts) (tileset-name ts)))
    (test "its image" img (image-source (tileset-image ts)))
    (test "gids from first-gid to first-gid + tile-count - 1" '(#f #t #t #f)
          (map (lambda (gid) (tileset-covers? ts gid)) '(4 5 20 21)))
    (test "no per-tile data" '(#f ()) (list (tileset-tile ts 0) (tileset-tiles ts))))
  (test "without tile-count: every gid from first-gid on" '(#f #t #t)
        (map (lambda (gid) (tileset-covers? (make-sheet-tileset (tmx-fixture "images/terrain.png")
                                                                 tile-width: 16 tile-height: 16 columns: 4)
                                             gid))
             '(0 1 1000)))
  (for-each
   (lambda (key args)
     (test-error (sprintf "make-sheet-tileset: a bad or missing ~a" key)
                 (both (from? 'make-sheet-tileset)
                       (lambda (exn) (and (substring-index key (error-text exn))
                                          (substring-index "terrain.png" (error-text exn)))))
                 (apply make-sheet-tileset (tmx-fixture "images/terrain.png") args)))
   '("tile-width:" "tile-height:" "columns:" "spacing:" "tile-count:")
   '((tile-height: 16 columns: 4)
     (tile-width: 16 tile-height: 0 columns: 4)
     (tile-width: 16 tile-height: 16 columns: 1.5)
     (tile-width: 16 tile-height: 16 columns: 4 spacing: -1)
     (tile-width: 16 tile-height: 16 columns: 4 tile-count: 'all)))
  (test-error "make-sheet-tileset: an image that is not there"
              (lambda (exn) (and (substring-index "nowhere.png" (error-text exn))
                                 (substring-index "no such image" (error-text exn))))
              (make-sheet-tileset "nowhere.png" tile-width: 8 tile-height: 8 columns: 2)))
