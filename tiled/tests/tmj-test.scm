;;; Tiled's JSON formats, checked against Tiled itself. For every map the
;;; TMX tests load (tests/maps/*.tmx, the demos' levels, and Tiled's example
;;; maps when fetched), Tiled's own JSON export of it (`tiled --export-map json`,
;;; fresh when tiled runs here, else the copies committed in
;;; maps/tiled-json/, made by tools/export-tiled-json.sh):
;;;  1. says the same as our TMX loader, field by field: layers, cells and
;;;     flips, objects, typed properties, tilesets (the export with
;;;     external tilesets embedded and templates detached, so that those
;;;     are compared as Tiled read them; read by
;;;     tools/tiled-json-expected.py, python's json module, never ours);
;;;  2. loaded with our JSON loader, gives the same tilemap value as the
;;;     .tmx gives our TMX loader.
;;; Where Tiled 1.8 (Debian's) cannot say what a map says (the class
;;; attribute, list properties, a class property's member types are newer;
;;; an unset colour it saves as a string), the difference is listed below,
;;; exactly, so that any other difference fails.

(import scheme (chicken base) (chicken format) (chicken string) (chicken file)
        (chicken process) (chicken pathname) (chicken bitwise) (chicken sort)
        (chicken condition) (chicken io) (chicken process-context) srfi-4
        (only (downstroke util) filter any iota append-map)
        (downstroke test) (downstroke tilemap))

;; DOWNSTROKE_NO_TILED=1 tests the committed copies as a machine without tiled would.
(define tj-have-tiled? (and (not (get-environment-variable "DOWNSTROKE_NO_TILED"))
                            (zero? (system "command -v tiled >/dev/null 2>&1"))))
(define tj-examples? (file-exists? "data/tiled-examples/.complete"))
(define tj-committed "maps/tiled-json")
(define tj-fresh "data/tiled-json")
;; Fresh exports only when tiled exported every map.
(define tj-exported?
  (and tj-have-tiled?
       (zero? (system (sprintf "sh ../tools/export-tiled-json.sh ~a"
                               (qs (normalize-pathname (make-pathname (current-directory) tj-fresh))))))))
(define tj-dir (if tj-exported? tj-fresh tj-committed))

(define tj-maps
  (append (sort (glob "maps/*.tmx") string<?)
          (sort (glob "../demo/levels/*.tmx") string<?)
          (if tj-examples?
              (sort (let walk ((dir "data/tiled-examples"))
                      (append-map (lambda (f)
                                    (let ((p (make-pathname dir f)))
                                      (cond ((directory-exists? p) (walk p))
                                            ((equal? (pathname-extension f) "tmx") (list p))
                                            (else '()))))
                                  (directory dir)))
                    string<?)
              '())))

(define (tj-export-of dir map #!optional (ext ".tmj"))
  (make-pathname dir (string-append (string-translate* (pathname-strip-extension map)
                                                       '(("../" . "") ("/" . "__")))
                                    ext)))

;; What python says each export holds: path -> datum.
(define (tj-expected dir)
  (with-input-from-pipe
   (string-append "python3 ../tools/tiled-json-expected.py "
                  (string-intersperse (map (lambda (m) (qs (tj-export-of dir m ".full.tmj"))) tj-maps) " "))
   (lambda () (let loop ((acc '()))
                (let ((x (read)))
                  (if (eof-object? x) (reverse acc) (loop (cons x acc))))))))

(define tj-expectations (tj-expected tj-dir))

;;; ------------------------------------------------------------------
;;; Our tilemap in the shape of tiled-json-expected.py's data

(define (tj-color c) (and c (cdr c)))

(define (tj-sorted-props props)
  (sort props (lambda (a b) (string<? (car a) (car b)))))

;; A property value as Tiled's JSON says it: (name type value).
(define (tj-value v)
  (case (property-type v)
    ((color) (cdr v))
    ((file object) (cadr v))
    ((class) (map (lambda (m) (list (car m) (tj-member (cdr m))))
                  (tj-sorted-props (caddr v))))
    ((list) (map tj-value (cdr v)))
    (else v)))
(define (tj-member v)
  (if (eq? (property-type v) 'class) (tj-value v) (tj-value v)))
(define (tj-props props)
  (map (lambda (p) (list (car p) (property-type (cdr p)) (tj-value (cdr p))))
       (tj-sorted-props props)))

(define (tj-cells tm layer)
  (let* ((data (layer-data layer)) (w (layer-width layer))
         (c0 (tilemap-origin-col tm)) (r0 (tilemap-origin-row tm)))
    (let loop ((i (- (u32vector-length data) 1)) (acc '()))
      (if (< i 0)
          acc
          (let ((c (u32vector-ref data i)))
            (loop (- i 1) (if (zero? c) acc
                              (cons (list (+ c0 (remainder i w)) (+ r0 (quotient i w)) c) acc))))))))

(define tj-text-keys
  '(("text" . text) ("fontfamily" . font-family) ("pixelsize" . pixel-size) ("wrap" . wrap?)
    ("color" . color) ("bold" . bold?) ("italic" . italic?) ("underline" . underline?)
    ("strikeout" . strikeout?) ("kerning" . kerning?) ("halign" . halign) ("valign" . valign)))

;; Our object's value for one of the keys Tiled's JSON has.
(define (tj-object-field o key expected)
  (cond ((equal? key "id") (object-id o))
        ((equal? key "name") (object-name o))
        ((equal? key "type") (object-class o))
        ((equal? key "x") (object-x o))
        ((equal? key "y") (object-y o))
        ((equal? key "width") (object-width o))
        ((equal? key "height") (object-height o))
        ((equal? key "rotation") (object-rotation o))
        ((equal? key "gid") (object-cell o))
        ((equal? key "visible") (object-visible? o))
        ((equal? key "shape") (object-shape o))
        ((equal? key "points") (map (lambda (p) (list (car p) (cdr p))) (object-points o)))
        ((equal? key "template") (object-template o))
        ((equal? key "text")
         (map (lambda (kv)
                (let* ((sym (cdr (assoc (car kv) tj-text-keys)))
                       (v (cdr (assq sym (object-text o)))))
                  (list (car kv) (if (eq? sym 'color) (tj-color v)
                                     (if (symbol? v) (symbol->string v) v)))))
              expected))
        ;; a template instance: the properties it writes itself win
        ((equal? key "properties")
         (filter (lambda (p) (assoc (car p) expected)) (tj-props (object-properties o))))
        (else (list 'unknown-key key))))

(define (tj-layer-field tm l key)
  (cond ((equal? key "kind") (layer-kind l))
        ((equal? key "name") (layer-name l))
        ((equal? key "id") (layer-id l))
        ((equal? key "offset") (list (layer-offset-x l) (layer-offset-y l)))
        ((equal? key "parallax") (list (layer-parallax-x l) (layer-parallax-y l)))
        ((equal? key "opacity") (layer-opacity l))
        ((equal? key "visible") (layer-visible? l))
        ((equal? key "locked") (layer-locked? l))
        ((equal? key "tint") (tj-color (layer-tint l)))
        ((equal? key "properties") (tj-props (layer-properties l)))
        ((equal? key "cells") (tj-cells tm l))
        ((equal? key "color") (tj-color (layer-color l)))
        ((equal? key "draworder") (layer-draw-order l))
        ((equal? key "image") (let ((i (layer-image l))) (and i (image-source i))))
        ((equal? key "repeat") (list (layer-repeat-x? l) (layer-repeat-y? l)))
        (else (list 'unknown-key key))))

(define (tj-map-field tm key)
  (cond ((equal? key "orientation") (symbol->string (tilemap-orientation tm)))
        ((equal? key "renderorder") (symbol->string (tilemap-render-order tm)))
        ((equal? key "tilewidth") (tilemap-tile-width tm))
        ((equal? key "tileheight") (tilemap-tile-height tm))
        ((equal? key "infinite") (tilemap-infinite? tm))
        ((equal? key "hexsidelength") (tilemap-hex-side-length tm))
        ((equal? key "staggeraxis") (let ((a (tilemap-stagger-axis tm))) (and a (symbol->string a))))
        ((equal? key "staggerindex") (let ((a (tilemap-stagger-index tm))) (and a (symbol->string a))))
        ((equal? key "parallaxoriginx") (tilemap-parallax-origin-x tm))
        ((equal? key "parallaxoriginy") (tilemap-parallax-origin-y tm))
        ((equal? key "width") (tilemap-width tm))
        ((equal? key "height") (tilemap-height tm))
        ((equal? key "backgroundcolor") (tj-color (tilemap-background-color tm)))
        (else (list 'unknown-key key))))

(define (tj-tileset-field ts key expected)
  (cond ((equal? key "firstgid") (tileset-first-gid ts))
        ((equal? key "source") (tileset-source ts))
        ((equal? key "name") (tileset-name ts))
        ((equal? key "tilewidth") (tileset-tile-width ts))
        ((equal? key "tileheight") (tileset-tile-height ts))
        ((equal? key "spacing") (tileset-spacing ts))
        ((equal? key "margin") (tileset-margin ts))
        ((equal? key "tilecount") (tileset-tile-count ts))
        ((equal? key "columns") (tileset-columns ts))
        ((equal? key "image") (image-source (tileset-image ts)))
        ((equal? key "properties") (tj-props (tileset-properties ts)))
        ;; a tile's collision shapes: the keys Tiled wrote for each
        ((equal? key "tiles")
         (map (lambda (t e)
                (list (list "id" (tile-id t)) (list "type" (tile-class t))
                      (list "properties" (tj-props (tile-properties t)))
                      (list "animation" (map (lambda (f) (list (car f) (cdr f)))
                                             (tile-animation t)))
                      (list "shapes"
                            (let ((shapes (cadr (assoc "shapes" e))))
                              (if (= (length shapes) (length (tile-shapes t)))
                                  (map (lambda (eo o)
                                         (map (lambda (kv) (list (car kv) (tj-object-field o (car kv) (cadr kv))))
                                              eo))
                                       shapes (tile-shapes t))
                                  (list 'shape-count (length (tile-shapes t))))))))
              (tileset-tiles ts)
              ;; one entry per tile of ours, so that a missing one shows
              (let pad ((e expected) (k (length (tileset-tiles ts))))
                (cond ((<= k 0) '())
                      ((null? e) (cons '(("shapes" ())) (pad '() (- k 1))))
                      (else (cons (car e) (pad (cdr e) (- k 1))))))))
        (else (list 'unknown-key key))))

;; Numbers equal by value (Tiled writes 2 where the loader read "2.0").
(define (tj-same? a b)
  (cond ((and (number? a) (number? b)) (= a b))
        ((and (pair? a) (pair? b)) (and (tj-same? (car a) (car b)) (tj-same? (cdr a) (cdr b))))
        (else (equal? a b))))

;; Every difference between Tiled's export and our reading of the .tmx, as
;; (where key tiled ours).
(define (tj-differences tm expected)
  (let ((diffs '()))
    (define (check where key tiled ours)
      ;; Tiled numbers layers and objects the file gives no id
      (unless (or (tj-same? tiled ours)
                  (and (equal? key "id") (memv ours '(#f 0))))
        (set! diffs (cons (list where key tiled ours) diffs))))
    (for-each (lambda (kv) (check "map" (car kv) (cadr kv) (tj-map-field tm (car kv))))
              (cdr (assq 'map (cdr expected))))
    (let ((tiled (cadr (assq 'properties (cdr expected))))
          (ours (tj-props (tilemap-properties tm))))
      (for-each (lambda (p)
                  (check "map properties" (car p) (cdr p)
                         (let ((o (assoc (car p) ours))) (and o (cdr o)))))
                tiled)
      (check "map properties" "names" (map car tiled) (map car ours)))
    (let ((tilesets (cdr (assq 'tilesets (cdr expected)))))
      (check "tilesets" "count" (length tilesets) (length (tilemap-tilesets tm)))
      (for-each (lambda (ts ours)
                  (for-each (lambda (kv)
                              (check (sprintf "tileset ~a" (tileset-first-gid ours)) (car kv)
                                     (cadr kv) (tj-tileset-field ours (car kv) (cadr kv))))
                            ts))
                tilesets (tilemap-tilesets tm)))
    (let ((layers (cdr (assq 'layers (cdr expected))))
          (ours (tilemap-all-layers tm)))
      (check "layers" "count" (length layers) (length ours))
      (for-each
       (lambda (l our)
         (let ((where (sprintf "layer ~s" (layer-name our))))
           (for-each
            (lambda (kv)
              (if (equal? (car kv) "objects")
                  (begin
                    (check where "object count" (length (cadr kv)) (length (layer-objects our)))
                    (for-each
                     (lambda (o our-o)
                       (for-each (lambda (okv)
                                   (check (sprintf "~a object ~a" where (object-id our-o)) (car okv)
                                          (cadr okv) (tj-object-field our-o (car okv) (cadr okv))))
                                 o))
                     (cadr kv) (layer-objects our)))
                  (check where (car kv) (cadr kv) (tj-layer-field tm our (car kv)))))
            l)))
       layers ours))
    (reverse diffs)))

;;; ------------------------------------------------------------------
;;; A whole tilemap as plain data, for comparing two loads

(define (tj-image i) (and i (list (image-source i) (image-width i) (image-height i) (image-trans i))))
(define (tj-sorted p) (tj-sorted-props p))
(define (tj-object o)
  (list (cons 'id (object-id o)) (object-name o) (object-class o) (object-x o) (object-y o)
        (object-width o) (object-height o) (object-rotation o) (object-cell o)
        (object-visible? o) (object-shape o) (object-points o) (object-text o)
        (tj-sorted (object-properties o)) (object-template o)))
(define (tj-tile t)
  (list (tile-id t) (tile-class t) (tile-probability t) (tj-sorted (tile-properties t))
        (tj-image (tile-image t)) (tile-x t) (tile-y t) (tile-width t) (tile-height t)
        (tile-animation t) (map tj-object (tile-shapes t))))
(define (tj-tileset ts)
  (list (tileset-first-gid ts) (tileset-name ts) (tileset-class ts) (tileset-source ts)
        (tileset-tile-width ts) (tileset-tile-height ts) (tileset-spacing ts)
        (tileset-margin ts) (tileset-tile-count ts) (tileset-columns ts)
        (tj-image (tileset-image ts)) (tileset-offset-x ts) (tileset-offset-y ts)
        (tileset-object-alignment ts) (tileset-grid ts) (tj-sorted (tileset-properties ts))
        (map tj-tile (tileset-tiles ts))))
(define (tj-layer tm l)
  (list (layer-kind l) (cons 'id (layer-id l)) (layer-name l) (layer-class l)
        (and (layer-data l)
             (if (tilemap-infinite? tm)
                 (tj-cells tm l)
                 (list (layer-width l) (layer-height l) (u32vector->list (layer-data l)))))
        (layer-visible? l) (layer-opacity l) (layer-tint l) (layer-offset-x l)
        (layer-offset-y l) (layer-parallax-x l) (layer-parallax-y l) (layer-locked? l)
        (tj-sorted (layer-properties l)) (map tj-object (layer-objects l))
        (layer-draw-order l) (layer-color l) (tj-image (layer-image l))
        (layer-repeat-x? l) (layer-repeat-y? l) (map (lambda (c) (tj-layer tm c)) (layer-children l))))
;; Everything but the file's own name and the Tiled version that wrote it.
;; An infinite map's extent is the union of its chunks, and Tiled cuts a
;; map into chunks of its own when it saves: its cells (and solid cells)
;; are compared where Tiled shows them, not by index.
(define (tj-tilemap tm)
  (let ((inf? (tilemap-infinite? tm)))
    (list (if inf? 'infinite (list (tilemap-width tm) (tilemap-height tm)
                                   (tilemap-origin-col tm) (tilemap-origin-row tm)))
          (tilemap-tile-width tm) (tilemap-tile-height tm)
          (list (tilemap-class tm) (tilemap-orientation tm) (tilemap-render-order tm)
                (tilemap-infinite? tm) (tilemap-hex-side-length tm) (tilemap-stagger-axis tm)
                (tilemap-stagger-index tm) (tilemap-parallax-origin-x tm)
                (tilemap-parallax-origin-y tm) (tilemap-background-color tm))
          (tj-sorted (tilemap-properties tm))
          (map tj-tileset (tilemap-tilesets tm))
          (map (lambda (l) (tj-layer tm l)) (tilemap-layer-tree tm))
          (map layer-name (tilemap-layers tm))
          (if inf?
              (tj-solid-cells tm)
              (u8vector->list (tilemap-solid-grid tm))))))

(define (tj-solid-cells tm)
  (let ((c0 (tilemap-origin-col tm)) (r0 (tilemap-origin-row tm)))
    (filter (lambda (x) x)
            (map (lambda (i)
                   (let ((c (+ c0 (remainder i (tilemap-width tm))))
                         (r (+ r0 (quotient i (tilemap-width tm)))))
                     (and (tilemap-solid? tm c r) (list c r))))
                 (iota (* (tilemap-width tm) (tilemap-height tm)))))))

;; Where two data differ: a list of (path a b), at most 20.
(define (tj-diff a b)
  (let ((out '()))
    (let walk ((a a) (b b) (path '()))
      (cond ((>= (length out) 20))
            ;; Tiled numbers the layers and objects a .tmx gives no id
            ((and (pair? a) (eq? (car a) 'id) (memv (cdr a) '(#f 0)) (pair? b) (eq? (car b) 'id)))
            ((and (pair? a) (pair? b) (list? a) (list? b) (= (length a) (length b)))
             (for-each (lambda (x y i) (walk x y (cons i path))) a b (iota (length a))))
            ((tj-same? a b))
            (else (set! out (cons (list (reverse path) a b) out)))))
    (reverse out)))

;;; ------------------------------------------------------------------
;;; What Tiled 1.8 cannot say about maps/features.tmx (written for Tiled
;;; 1.10): (where key tiled ours) in 1, tree paths in 2.

(define tj-known-differences
  '(("maps/features.tmx"
     ("map properties" "unset" (string "") (color ()))
     ("map properties" "waves" (string "") (list (1 "two" #t)))
     ;; Tiled 1.8 drops a layer's locked and an image layer's repeatx when
     ;; it exports with --embed-tilesets --detach-templates (its plain
     ;; export keeps them: the second group below compares that one)
     ("layer \"ground\"" "locked" #f #t)
     ("layer \"things\" object 3" "type" "" "Marker")
     ("layer \"sky\"" "repeat" (#f #f) (#t #f)))))
;; (A tileset of Tiled 0.x without tilecount, columns or image size, as in
;; perspective_walls, reads them from the image's header, as Tiled does.)

(test-group "Tiled's JSON export says what our TMX loader reads"
  (test "every map has an export" (length tj-maps) (length tj-expectations))
  (when (equal? tj-dir tj-fresh)
    (test "the committed exports say what a fresh export says"
          (map cdr tj-expectations) (map cdr (tj-expected tj-committed))))
  (for-each
   (lambda (map expected)
     (let ((tm (load-tilemap map)))
       (test (sprintf "~a: every field as Tiled's export (~a)" map tj-dir)
             (let ((k (assoc map tj-known-differences))) (if k (cdr k) '()))
             (tj-differences tm expected))))
   tj-maps tj-expectations))

;; Tree paths (see tj-diff) where a .tmj Tiled 1.8 wrote differs from the
;; .tmx it read: what that version does not know (the class attribute, list
;; properties, class member types).
(define tj-known-tree-differences
  '(("maps/features.tmx"
     ((3 0) "Level" "")                 ; the map's class (Tiled 1.9)
     ((4 7 2) "Spawn" "")               ; a class property's type name: not in 1.8's JSON
     ((4 7 3 0) ("x" . 4) ("where" class "" (("label" . "inner")))) ; its members: order and
     ((4 7 3 1) ("where" class "Point" (("label" . "inner"))) ("x" . 4)) ; types not in JSON
     ((4 10) ("unset" color) ("unset" . ""))               ; 1.8 saves an unset colour as ""
     ((4 11) ("waves" list 1 "two" #t) ("waves" . ""))     ; list properties (Tiled 1.11)
     ((6 0 3) "Terrain" "")             ; a layer's class (Tiled 1.9)
     ((6 1 20 1 20 0 14 2 2) "Marker" "")))) ; an object's class attribute (Tiled 1.9)
;; (1.8 writes no image layer's image size; both loaders read it from the
;; image's header.)

(test-group "a .tmj loads into the same tilemap as its .tmx"
  (for-each
   (lambda (map)
     (let* ((json (tj-export-of tj-dir map))
            (a (tj-tilemap (load-tilemap map)))
            (b (tj-tilemap (load-tilemap json))))
       (test (sprintf "~a and ~a" map json)
             (let ((k (assoc map tj-known-tree-differences))) (if k (cdr k) '()))
             (tj-diff a b))))
   tj-maps))

;;; ------------------------------------------------------------------
;;; Hand-written JSON (maps/json/): what Tiled 1.8 cannot export (classes,
;;; list properties, capsules, image layer sizes, typed properties without
;;; a value), a .tsj tileset named by a .tmx and a .tmj, a .tj template.

(test-group "hand-written .tmj, .tsj and .tj"
  (let ((x (load-tilemap "maps/json/level.tmx"))
        (j (load-tilemap "maps/json/level.tmj")))
    (test "level.tmj is level.tmx, every field" '() (tj-diff (tj-tilemap x) (tj-tilemap j)))
    (test "the .tsj tileset is the .tsx one but for its source"
          (cddddr (tj-tileset (load-tileset "maps/tilesets/terrain.tsx")))
          (cddddr (car (map tj-tileset (tilemap-tilesets j)))))
    (test "a .tmx map reads its .tsj tileset" "maps/json/terrain.tsj"
          (tileset-source (car (tilemap-tilesets x))))
    (test "typed properties without a value, class and list properties"
          '(("count" . 0) ("speed" . 0.0) ("on" . #f) ("tint" color) ("target" object 0)
            ("song" file "") ("spawn" class "Spawn" (("x" . 4) ("label" . "here")))
            ("waves" list 1 "two"))
          (tilemap-properties j))
    (test "zstd cells, a flip and a gid past the last tile" '(1 0 0 2 2147483651 0 5 9)
          (u32vector->list (layer-data (car (tilemap-layers j)))))
    (let ((objs (tilemap-objects j)))
      (test "the shapes: capsule, a template's tile, polygon, text" '(capsule tile polygon text)
            (map object-shape objs))
      (test "the template's object, its gid and properties" '("enemy" "Enemy" 7 (("hp" . 3) ("speed" . 1.5)))
            (let ((o (cadr objs))) (list (object-name o) (object-class o) (object-gid o) (object-properties o))))
      (test "text with an escaped quote" "Hi \"there\"" (cdr (assq 'text (object-text (cadddr objs)))))
      (test "the capsule as an entity: its shape and box, the group's offset added" '(capsule 6 3 20 8)
            (let ((e (car (tilemap-objects->entities j))))
              (map (lambda (k) (cdr (assq k e))) '(#:shape #:x #:y #:width #:height)))))
    (test "a .tsj loads on its own" '(8 4 (("material" . "grass")))
          (let ((ts (load-tileset "maps/json/terrain.tsj")))
            (list (tileset-tile-count ts) (tileset-columns ts) (tileset-properties ts))))))

;;; ------------------------------------------------------------------
;;; Bad JSON: each error names the file and says what is wrong.

(define tj-tmp (create-temporary-directory))
(define (tj-write name text)
  (let ((p (make-pathname tj-tmp name)))
    (with-output-to-file p (lambda () (display text)))
    p))
(tj-write "img.png" "checked for existence only")
(tj-write "ok.tsj" "{\"type\":\"tileset\",\"name\":\"t\",\"tilewidth\":8,\"tileheight\":8,\"tilecount\":4,\"columns\":2,\"image\":\"img.png\",\"imagewidth\":16,\"imageheight\":16}")

;; A 2 x 1 map; layers and tilesets as JSON text.
(define (tj-map #!key (layers "[{\"type\":\"tilelayer\",\"name\":\"L\",\"width\":2,\"height\":1,\"data\":[1,2]}]")
                (tilesets "[{\"firstgid\":1,\"source\":\"ok.tsj\"}]") (more ""))
  (string-append "{\"type\":\"map\",\"orientation\":\"orthogonal\",\"width\":2,\"height\":1,"
                 "\"tilewidth\":8,\"tileheight\":8," more "\"tilesets\":" tilesets ",\"layers\":" layers "}"))

(define ((tj-says path . fragments) exn)
  (let ((text (error-text exn)))
    (and (substring-index path text)
         (let loop ((f fragments))
           (or (null? f) (and (substring-index (car f) text) (loop (cdr f))))))))

(define (tj-layer-text extra) (string-append "[{\"type\":\"tilelayer\",\"name\":\"L\",\"width\":2,\"height\":1," extra "}]"))
(define (tj-objects-text objs) (string-append "[{\"type\":\"objectgroup\",\"name\":\"o\",\"objects\":[" objs "]}]"))

(test-group "bad JSON maps, tilesets and templates name the file and the problem"
  (test "the base map loads" 2 (tilemap-tile-at (load-tilemap (tj-write "ok.tmj" (tj-map))) 1 0))
  (for-each
   (lambda (c)
     ;; the error names the file at fault: the map, or the one in (map . file)
     (let* ((name (if (pair? (car c)) (caar c) (car c)))
            (p (tj-write name (cadr c)))
            (at-fault (if (pair? (car c)) (make-pathname tj-tmp (cdar c)) p)))
       (test-error (sprintf "~a: ~a" name (caddr c))
                   (apply tj-says at-fault (cddr c))
                   (load-tilemap p))))
   (list
    (list "trunc.tmj" "{\"type\":\"map\",\n \"width\": [1," "malformed JSON" "line 2, column 14")
    (list "array.tmj" "[1,2]" "holds an array, expected a JSON object")
    (list "kind.tmj" "{\"type\":\"tileset\"}" "of type \"tileset\", expected \"map\"")
    (list "width.tmj" (tj-map more: "\"renderorder\":3,") "\"renderorder\" is 3" "a string")
    (list "wstr.tmj" (string-append "{\"width\":\"2\"," (substring (tj-map) 1 (string-length (tj-map))))
          "map: \"width\" is \"2\" (a string), expected a number")
    (list "ltype.tmj" (tj-map layers: "[{\"type\":\"tiles\",\"name\":\"L\"}]") "layer \"L\"" "unknown layer type \"tiles\"")
    (list "notype.tmj" (tj-map layers: "[{\"name\":\"L\"}]") "layer \"L\"" "no \"type\"")
    (list "nodata.tmj" (tj-map layers: (tj-layer-text "\"x\":0")) "layer \"L\"" "no \"data\"")
    (list "short.tmj" (tj-map layers: (tj-layer-text "\"data\":[1]")) "layer \"L\"" "1 cells, expected 2")
    (list "neg.tmj" (tj-map layers: (tj-layer-text "\"data\":[1,-1]")) "\"data[1]\" is -1" "0 to 4294967295")
    (list "big.tmj" (tj-map layers: (tj-layer-text "\"data\":[1,4294967296]")) "\"data[1]\" is 4294967296")
    (list "frac.tmj" (tj-map layers: (tj-layer-text "\"data\":[1,1.5]")) "\"data[1]\" is 1.5")
    (list "b64arr.tmj" (tj-map layers: (tj-layer-text "\"encoding\":\"base64\",\"data\":[1,2]"))
          "a base64 string")
    (list "b64bad.tmj" (tj-map layers: (tj-layer-text "\"encoding\":\"base64\",\"data\":\"@@@\""))
          "bad base64")
    (list "enc.tmj" (tj-map layers: (tj-layer-text "\"encoding\":\"hex\",\"data\":\"00\"")) "unsupported encoding \"hex\"")
    (list "comp.tmj" (tj-map layers: (tj-layer-text "\"compression\":\"zlib\",\"data\":[1,2]")) "needs base64")
    (list "lzma.tmj" (tj-map layers: (tj-layer-text "\"encoding\":\"base64\",\"compression\":\"lzma\",\"data\":\"AAAA\""))
          "compression" "lzma")
    (list "gid.tmj" (tj-map tilesets: "[{\"firstgid\":2,\"source\":\"ok.tsj\"}]") "gid 1, below the first gid")
    (list "notsj.tmj" (tj-map tilesets: "[{\"firstgid\":1,\"source\":\"none.tsj\"}]") "none.tsj" "not found")
    (list '("badtsj.tmj" . "trunc.tmj") (tj-map tilesets: "[{\"firstgid\":1,\"source\":\"trunc.tmj\"}]") "trunc.tmj" "malformed JSON")
    (list "tsobj.tmj" (tj-map tilesets: "[3]") "\"tilesets[0]\" is 3" "an object")
    (list "oldtiles.tmj" (tj-map tilesets: "[{\"firstgid\":1,\"name\":\"old\",\"tilewidth\":8,\"tileheight\":8,\"tiles\":{\"0\":{}}}]")
          "tileset \"old\"" "\"tiles\" is an object, expected an array")
    (list "poly.tmj" (tj-map layers: (tj-objects-text "{\"id\":1,\"polygon\":[{\"x\":1}]}"))
          "object 1" "polygon[0] has no y")
    (list "polyobj.tmj" (tj-map layers: (tj-objects-text "{\"id\":1,\"polygon\":3}"))
          "object 1" "\"polygon\" is 3" "an array")
    (list "ellipse.tmj" (tj-map layers: (tj-objects-text "{\"id\":1,\"ellipse\":1}"))
          "object 1" "\"ellipse\" is 1" "true or false")
    (list "prop.tmj" (tj-map more: "\"properties\":[{\"name\":\"n\",\"type\":\"int\",\"value\":\"5\"}],")
          "property \"n\"" "\"value\" is \"5\" (a string), expected a number")
    (list "propint.tmj" (tj-map more: "\"properties\":[{\"name\":\"n\",\"type\":\"int\",\"value\":1.5}],")
          "property \"n\"" "not an integer")
    (list "propbool.tmj" (tj-map more: "\"properties\":[{\"name\":\"n\",\"type\":\"bool\",\"value\":\"true\"}],")
          "property \"n\"" "true or false")
    (list "proptype.tmj" (tj-map more: "\"properties\":[{\"name\":\"n\",\"type\":\"vector\",\"value\":1}],")
          "unknown property type \"vector\"")
    (list "propname.tmj" (tj-map more: "\"properties\":[{\"type\":\"int\",\"value\":1}],")
          "a property has no name")
    (list "notj.tmj" (tj-map layers: (tj-objects-text "{\"id\":1,\"template\":\"none.tj\"}")) "none.tj" "not found")
    (list '("tjtype.tmj" . "ok.tsj") (tj-map layers: (tj-objects-text "{\"id\":1,\"template\":\"ok.tsj\"}"))
          "ok.tsj" "of type \"tileset\", expected \"template\"")
    (list "deep.tmj" (string-append (make-string 2000 #\[) (make-string 2000 #\])) "nested more than 1000")
    (list "xmlroot.tmj" "<map/>" "malformed JSON" "line 1, column 1"))))

(test-group "a .tmx naming a bad .tsj names the .tsj"
  (let* ((bad (tj-write "bad.tsj" "{\"type\":\"tileset\",\"name\":\"t\",\"tilewidth\":\"8\"}"))
         (p (tj-write "m.tmx" "<?xml version=\"1.0\"?><map orientation=\"orthogonal\" width=\"1\" height=\"1\" tilewidth=\"8\" tileheight=\"8\"><tileset firstgid=\"1\" source=\"bad.tsj\"/><layer name=\"L\" width=\"1\" height=\"1\"><data encoding=\"csv\">0</data></layer></map>")))
    (test-error "\"tilewidth\" is \"8\" (a string)" (tj-says bad "tileset \"t\"" "\"tilewidth\" is \"8\" (a string)")
                (load-tilemap p))))
