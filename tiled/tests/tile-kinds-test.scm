;;; Tiles that say what they are (docs/tilemaps.org, "Tile properties"):
;;; the properties of a tile in its tileset decide whether it collides,
;;; whether it is one-way, and its kind, read per cell; a misspelt or
;;; wrongly typed one is an error naming the file when the map loads.

(import scheme (chicken base) (chicken format) (chicken file) (chicken condition)
        (chicken process-context posix) (chicken string)
        (downstroke test) (downstroke tilemap))

;; A 4 x 2 map of 16 px tiles over a tileset of four tiles whose <tile>
;; elements are `tiles`; row 0 holds gids 1 2 3 4 on layer "ground",
;; row 1 the gids of `second` on a second layer when it is given.
(define (tk-tmx path tiles #!optional second (second-props ""))
  (with-output-to-file path
    (lambda ()
      (print "<?xml version=\"1.0\" encoding=\"UTF-8\"?>")
      (print "<map version=\"1.8\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"4\" height=\"2\" tilewidth=\"16\" tileheight=\"16\" infinite=\"0\" nextlayerid=\"3\" nextobjectid=\"1\">")
      (print " <tileset firstgid=\"1\" name=\"kinds\" tilewidth=\"16\" tileheight=\"16\" tilecount=\"4\" columns=\"4\">")
      (print "  <image source=\"../docs/images/demo-getting-started.png\" width=\"320\" height=\"240\"/>")
      (print tiles)
      (print " </tileset>")
      (print " <layer id=\"1\" name=\"ground\" width=\"4\" height=\"2\">")
      (print "  <data encoding=\"csv\">1,2,3,4,0,0,0,0</data>")
      (print " </layer>")
      (when second
        (print " <layer id=\"2\" name=\"over\" width=\"4\" height=\"2\">")
        (print second-props)
        (print "  <data encoding=\"csv\">" second "</data>")
        (print " </layer>"))
      (print "</map>"))))

(define (tk-tile id . props)
  (sprintf "  <tile id=\"~a\"><properties>~a</properties></tile>" id
           (apply string-append
                  (map (lambda (p) (sprintf "<property name=\"~a\" type=\"~a\" value=\"~a\"/>" (car p) (cadr p) (caddr p)))
                       props))))

;; The message of the error loading raises, or #f.
(define (tk-load-error path)
  (handle-exceptions exn ((condition-property-accessor 'exn 'message "") exn)
    (load-tilemap path)
    #f))

(define tk-path (sprintf "tile-kinds-~a.tmx" (current-process-id)))

(test-group "tile properties: collides, one-way, kind"
  (tk-tmx tk-path (string-append (tk-tile 1 '("collides" "bool" "false"))
                                 (tk-tile 2 '("one-way" "bool" "true"))
                                 (tk-tile 3 '("kind" "string" "hazard"))))
  (let ((tm (load-tilemap tk-path)))
    (test "a tile with no property is solid (the default)" '(#t #f #f)
          (list (tilemap-solid? tm 0 0) (tilemap-one-way? tm 0 0) (tilemap-kind tm 0 0)))
    (test "collides false: not solid, not one-way" '(#f #f)
          (list (tilemap-solid? tm 1 0) (tilemap-one-way? tm 1 0)))
    (test "one-way true: one-way, and tilemap-solid? answers #f on it" '(#t #f)
          (list (tilemap-one-way? tm 2 0) (tilemap-solid? tm 2 0)))
    (test "kind: the cell's kind is the symbol; the tile is still solid" '(hazard #t)
          (list (tilemap-kind tm 3 0) (tilemap-solid? tm 3 0)))
    (test "empty cells and cells outside the map have no kind" '(#f #f #f)
          (list (tilemap-kind tm 3 1) (tilemap-kind tm 9 0) (tilemap-kind tm -1 -1))))
  (tk-tmx tk-path (string-append (tk-tile 0 '("kind" "string" "water") '("collides" "bool" "false"))
                                 (tk-tile 1 '("kind" "string" "spikes")))
          "0,0,0,2,0,0,0,0"
          "<properties><property name=\"collides\" type=\"bool\" value=\"false\"/></properties>")
  (let ((tm (load-tilemap tk-path)))
    (test "the top layer's kind wins, and a decoration layer's kinds count" '(water spikes)
          (list (tilemap-kind tm 0 0) (tilemap-kind tm 3 0)))
    (test "a kind read on a map without kinds is #f" #f
          (tilemap-kind (list->tilemap '((1 1))) 0 0)))
  (test "the table names every property Downstroke reads, with its type"
        '(("collides" . bool) ("one-way" . bool) ("kind" . string) ("ladder" . bool)
          ("slope-left" . int) ("slope-right" . int) ("ceiling-left" . int) ("ceiling-right" . int))
        tile-property-table))

(test-group "tile properties: ladder, on the tile or its layer"
  (tk-tmx tk-path (tk-tile 1 '("ladder" "bool" "true")) "3,2,0,0,3,3,3,3"
          "<properties><property name=\"ladder\" type=\"bool\" value=\"true\"/></properties>")
  (let ((tm (load-tilemap tk-path)))
    (test "the tile with ladder true (row 0, column 1): a ladder, not solid" '(#t #f)
          (list (tilemap-ladder? tm 1 0) (tilemap-solid? tm 1 0)))
    (test "it is the ladder's top (nothing above it): one-way" '(#t #t)
          (list (tilemap-ladder-top? tm 1 0) (tilemap-one-way? tm 1 0)))
    (test "every tile of the layer with the property ladder is a ladder, not solid"
          '(#t #t #t #f)
          (list (tilemap-ladder? tm 0 1) (tilemap-ladder? tm 3 1) (tilemap-ladder? tm 1 1)
                (tilemap-solid? tm 2 1)))
    (test "where the ground layer's tile is solid, the cell is solid and no ladder" '(#t #f)
          (list (tilemap-solid? tm 0 0) (tilemap-ladder? tm 0 0)))
    (test "column 1: row 1 is under row 0's ladder, so no top" #f (tilemap-one-way? tm 1 1)))
  (test-assert "the layer property ladder as a string is an error naming it"
               (let ((msg (begin (tk-tmx tk-path "" "0,0,0,0,1,1,1,1"
                                         "<properties><property name=\"ladder\" value=\"true\"/></properties>")
                                 (tk-load-error tk-path))))
                 (and msg (substring-index "ladder" msg) (substring-index "bool" msg))))
  (test-assert "the tile property \"ladders\" is named as a slip of \"ladder\""
               (let ((msg (begin (tk-tmx tk-path (tk-tile 1 '("ladders" "bool" "true")))
                                 (tk-load-error tk-path))))
                 (and msg (substring-index "\"ladder\"" msg)))))

(test-group "tile properties: a misspelt or wrongly typed one is named at load"
  (define (message tiles)
    (tk-tmx tk-path tiles)
    (tk-load-error tk-path))
  (define (names? msg . words)
    (and msg (let loop ((ws (cons tk-path words)))
               (or (null? ws) (and (substring-index (car ws) msg) (loop (cdr ws)))))))
  (test-assert "\"oneway\": the file, the tile, the name and the one it resembles"
               (names? (message (tk-tile 1 '("oneway" "bool" "true"))) "tile 1" "\"oneway\"" "\"one-way\""))
  (test-assert "\"One_Way\" too" (names? (message (tk-tile 1 '("One_Way" "bool" "true"))) "\"one-way\""))
  (test-assert "\"colides\" (one letter dropped)" (names? (message (tk-tile 0 '("colides" "bool" "false"))) "\"collides\""))
  (test-assert "\"Kind\"" (names? (message (tk-tile 2 '("Kind" "string" "lava"))) "\"kind\""))
  (test-assert "one-way as a string: the expected type is named"
               (names? (message (tk-tile 1 '("one-way" "string" "true"))) "\"one-way\"" "bool" "string"))
  (test-assert "kind as an int" (names? (message (tk-tile 1 '("kind" "int" "3"))) "\"kind\"" "string"))
  (test "a property of the game's own, not like any of the table's, loads" 'lava
        (begin (tk-tmx tk-path (tk-tile 0 '("damage" "int" "3") '("kind" "string" "lava")))
               (tilemap-kind (load-tilemap tk-path) 0 0))))

;; docs/physics.org, "Slopes": a slope's heights from two int
;; properties, or from the collision polygon drawn on the tile in Tiled.
(define (tk-polygon-tile id x y points)
  (sprintf "  <tile id=\"~a\"><objectgroup draworder=\"index\" id=\"2\"><object id=\"1\" x=\"~a\" y=\"~a\"><polygon points=\"~a\"/></object></objectgroup></tile>"
           id x y points))

(test-group "slope tiles: properties and collision polygons"
  (tk-tmx tk-path (string-append (tk-tile 0 '("slope-left" "int" "0") '("slope-right" "int" "16"))
                                 (tk-tile 1 '("slope-left" "int" "8") '("slope-right" "int" "0"))
                                 ;; a triangle rising to the right: (0,16) (16,0) (16,16)
                                 (tk-polygon-tile 2 0 0 "0,16 16,0 16,16")
                                 ;; a 22.5 degree half, drawn with its object moved: its
                                 ;; points are relative to (0, 8)
                                 (tk-polygon-tile 3 0 8 "0,8 16,0 16,8 0,8"))
          "0,0,0,0,0,0,0,0")
  (let ((tm (load-tilemap tk-path)))
    (test "properties: (left . right) heights" '((0 . 16) (8 . 0))
          (list (tilemap-slope tm 0 0) (tilemap-slope tm 1 0)))
    (test "a collision polygon: the highest point on each edge" '((0 . 16) (0 . 8))
          (list (tilemap-slope tm 2 0) (tilemap-slope tm 3 0)))
    (test "a slope cell is neither solid nor one-way" '(#f #f)
          (list (tilemap-solid? tm 0 0) (tilemap-one-way? tm 0 0)))
    (test "no slope on empty cells, outside the map, or on a map without slopes" '(#f #f #f)
          (list (tilemap-slope tm 0 1) (tilemap-slope tm 9 0) (tilemap-slope (list->tilemap '((1))) 0 0))))
  (tk-tmx tk-path (tk-polygon-tile 0 0 0 "0,0 16,0 16,16 0,16"))
  (test "a polygon covering the whole tile is a plain solid tile" '(#f #t)
        (let ((tm (load-tilemap tk-path))) (list (tilemap-slope tm 0 0) (tilemap-solid? tm 0 0))))
  (test "list->tilemap's slopes:, and a cell flipped horizontally swaps the heights"
        '((0 . 8) (8 . 0) #t)
        (let ((tm (list->tilemap (list (list 5 (+ 5 #x80000000) 1)) slopes: '((5 0 8)))))
          (list (tilemap-slope tm 0 0) (tilemap-slope tm 1 0) (tilemap-solid? tm 2 0))))
  (test "a solid tile of another layer in the same cell wins over a slope" '(#f #t)
        (begin (tk-tmx tk-path (tk-tile 0 '("slope-left" "int" "0") '("slope-right" "int" "16"))
                       "2,0,0,0,0,0,0,0")
               (let ((tm (load-tilemap tk-path))) (list (tilemap-slope tm 0 0) (tilemap-solid? tm 0 0))))))

;; docs/physics.org, "Ceiling slopes": depths from two int properties,
;; from a polygon with both top corners, or a floor slope flipped
;; vertically.
(test-group "ceiling slope tiles: properties, collision polygons, vertical flips"
  (tk-tmx tk-path (string-append (tk-tile 0 '("ceiling-left" "int" "0") '("ceiling-right" "int" "16"))
                                 (tk-tile 1 '("slope-left" "int" "0") '("slope-right" "int" "8"))
                                 ;; the top-right triangle: (0,0) (16,0) (16,16)
                                 (tk-polygon-tile 2 0 0 "0,0 16,0 16,16")
                                 ;; a 22.5 degree ceiling, drawn from (0, 0): depths 8 and 0
                                 (tk-polygon-tile 3 0 0 "0,0 16,0 0,8"))
          ;; row 1: tile 2 (a floor slope 0 8) flipped vertically, then
          ;; flipped both ways; tile 1 (a ceiling 0 16) flipped vertically
          (sprintf "0,0,0,0,~a,~a,~a,0" (+ 2 #x40000000) (+ 2 #xC0000000) (+ 1 #x40000000)))
  (let ((tm (load-tilemap tk-path)))
    (test "properties: (left . right) depths; no floor slope there" '((0 . 16) #f)
          (list (tilemap-ceiling-slope tm 0 0) (tilemap-slope tm 0 0)))
    (test "a polygon with both top corners: the lowest point on each edge" '((0 . 16) (8 . 0))
          (list (tilemap-ceiling-slope tm 2 0) (tilemap-ceiling-slope tm 3 0)))
    (test "a floor slope 0 8 flipped vertically: a ceiling 0 8; flipped both ways: 8 0" '((0 . 8) (8 . 0))
          (list (tilemap-ceiling-slope tm 0 1) (tilemap-ceiling-slope tm 1 1)))
    (test "a ceiling slope flipped vertically: a floor slope with its depths as heights" '((0 . 16) #f)
          (list (tilemap-slope tm 2 1) (tilemap-ceiling-slope tm 2 1)))
    (test "not solid; one-way (its top edge holds a body from above)" (quote (#f #t))
          (list (tilemap-solid? tm 0 0) (tilemap-one-way? tm 0 0))))
  (tk-tmx tk-path (tk-polygon-tile 0 0 0 "0,0 16,0 8,8"))
  (test "a triangle hanging from the top corners to a point inside: no ceiling slope, a solid tile" '(#f #f #t)
        (let ((tm (load-tilemap tk-path)))
          (list (tilemap-ceiling-slope tm 0 0) (tilemap-slope tm 0 0) (tilemap-solid? tm 0 0))))
  (test "list->tilemap's ceiling-slopes:, a vertical flip of a slopes: tile" '((0 . 8) (8 . 0) (0 . 8) #t)
        (let ((tm (list->tilemap (list (list 5 (+ 5 #x80000000) (+ 6 #x40000000) 1))
                                 ceiling-slopes: '((5 0 8)) slopes: '((6 0 8)))))
          (list (tilemap-ceiling-slope tm 0 0) (tilemap-ceiling-slope tm 1 0) (tilemap-ceiling-slope tm 2 0)
                (tilemap-solid? tm 3 0)))))

;; docs/physics.org, "Flipped and turned slopes": Tiled's diagonal flip
;; (its 90 degree turns) turns a slope's solid shape; a 45 degree
;; triangle turned is again a floor or a ceiling, a 22.5 degree one is
;; not, and the map does not load.
(test-group "slopes turned by Tiled's diagonal flip"
  (define d #x20000000) (define h #x80000000) (define v #x40000000)
  (tk-tmx tk-path (string-append (tk-tile 0 '("slope-left" "int" "0") '("slope-right" "int" "16"))
                                 (tk-tile 1 '("slope-left" "int" "0") '("slope-right" "int" "8"))
                                 (tk-tile 2 '("ceiling-left" "int" "16") '("ceiling-right" "int" "0")))
          ;; layer "over", row 1: tile 0 (gid 1) flipped diagonally, turned
          ;; 90 degrees clockwise (diagonal + horizontal), anticlockwise
          ;; (diagonal + vertical), and tile 2 (gid 3) flipped diagonally
          (sprintf "0,0,0,0,~a,~a,~a,~a" (+ 1 d) (+ 1 d h) (+ 1 d v) (+ 3 d)))
  (let ((tm (load-tilemap tk-path)))
    (test "the 45 degree floor 0 16 transposed is itself; turned clockwise 16 0; anticlockwise a ceiling 0 16"
          '((0 . 16) (16 . 0) #f (0 . 16))
          (list (tilemap-slope tm 0 1) (tilemap-slope tm 1 1) (tilemap-slope tm 2 1) (tilemap-ceiling-slope tm 2 1)))
    (test "the ceiling 16 0 (the top-left triangle) transposed is itself" '(16 . 0)
          (tilemap-ceiling-slope tm 3 1)))
  (test "list->tilemap: diagonal + both flips of the floor 0 16 is the ceiling 16 0" '(16 . 0)
        (tilemap-ceiling-slope (list->tilemap (list (list (+ 5 d h v))) slopes: '((5 0 16))) 0 0))
  (tk-tmx tk-path (tk-tile 1 '("slope-left" "int" "0") '("slope-right" "int" "8"))
          (sprintf "0,0,0,0,0,~a,0,0" (+ 2 d h)))
  (test-assert "a 22.5 degree slope turned: the error names the file, the layer, the cell and the tile"
               (let ((msg (tk-load-error tk-path)))
                 (and msg
                      (substring-index tk-path msg) (substring-index "\"over\"" msg)
                      (substring-index "(1, 1)" msg) (substring-index "tile 1 of tileset \"kinds\"" msg)
                      #t)))
  (test-error "list->tilemap: a turned 22.5 degree slope is an error"
              (list->tilemap (list (list (+ 5 d))) slopes: '((5 0 8))))
  (test-error "a diagonal flip of a slope on tiles that are not square"
              (list->tilemap (list (list (+ 5 d))) tile-width: 16 tile-height: 8 slopes: '((5 0 8)))))

(test-group "slope tiles: mistakes are named at load"
  (define (names? tiles . words)
    (tk-tmx tk-path tiles)
    (let ((msg (tk-load-error tk-path)))
      (and msg (let loop ((ws (cons tk-path words)))
                 (or (null? ws) (and (substring-index (car ws) msg) (loop (cdr ws))))))))
  (test-assert "\"slope_left\": the name it resembles"
               (names? (tk-tile 1 '("slope_left" "int" "0") '("slope-right" "int" "16")) "tile 1" "\"slope-left\""))
  (test-assert "\"slope-rigth\" (two letters swapped)"
               (names? (tk-tile 1 '("slope-left" "int" "0") '("slope-rigth" "int" "16")) "\"slope-right\""))
  (test-assert "a height as a float: the expected type"
               (names? (tk-tile 1 '("slope-left" "float" "0.5") '("slope-right" "int" "16")) "\"slope-left\"" "int" "float"))
  (test-assert "one height without the other"
               (names? (tk-tile 2 '("slope-left" "int" "4")) "tile 2" "\"slope-left\"" "\"slope-right\""))
  (test-assert "a height beyond the tile"
               (names? (tk-tile 0 '("slope-left" "int" "0") '("slope-right" "int" "17")) "\"slope-right\"" "17" "16"))
  (test-assert "\"ceiling-rigth\""
               (names? (tk-tile 1 '("ceiling-left" "int" "0") '("ceiling-rigth" "int" "16")) "\"ceiling-right\""))
  (test-assert "one depth without the other"
               (names? (tk-tile 2 '("ceiling-right" "int" "4")) "tile 2" "\"ceiling-left\"" "\"ceiling-right\""))
  (test-assert "a depth beyond the tile"
               (names? (tk-tile 0 '("ceiling-left" "int" "-1") '("ceiling-right" "int" "16")) "\"ceiling-left\"" "-1"))
  (test-assert "a floor and a ceiling on one tile"
               (names? (tk-tile 3 '("ceiling-left" "int" "0") '("ceiling-right" "int" "16")
                                '("slope-left" "int" "0") '("slope-right" "int" "16"))
                       "tile 3" "slope-left" "ceiling-left"))
  (test-error "list->tilemap: a slope with a height beyond the tile"
              (list->tilemap '((5)) slopes: '((5 0 20)))))

(delete-file* tk-path)
