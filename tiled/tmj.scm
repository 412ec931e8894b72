;;; (downstroke tmj): Tiled's JSON formats (.tmj maps, .tsj tilesets, .tj
;;; templates; .json for any of them) read into the element tree the TMX
;;; reader walks, so both formats go through the same code and give the
;;; same tilemap value for the same map.
;;;
;;; The tree is SXML as (downstroke xml) makes it: (tag (@ (attr value)
;;; ...) child ...), with three liberties the TMX reader accepts: an
;;; attribute value may be a number (JSON numbers are never turned into
;;; text and back, which would lose digits), a polygon's points may be a
;;; list of (x . y) pairs, and a layer's or chunk's <data> may hold its
;;; cells as one u32vector instead of text.
;;;
;;; Every JSON value is type-checked here, before the TMX reader sees it:
;;; a key holding the wrong kind of value is an error naming the file, what
;;; was being read and the key. Keys Tiled writes that the TMX reader has no
;;; use for (wangsets, nextobjectid, ...) are ignored, as their TMX
;;; elements are.
;;;
;;; What JSON cannot say: a class property's members carry no types in
;;; Tiled's JSON (Tiled takes them from the project's custom types), so a
;;; member is read as the JSON value says: a string, a bool, an int (an
;;; integer), a float (another number) or a class (an object, of type "").
(module (downstroke tmj)
  (json-file? json-root)

  (import scheme (chicken base) (chicken fixnum) (chicken format)
          (chicken pathname) (chicken condition) (chicken io) srfi-4
          (downstroke json)
          (only (downstroke util) filter append-map))

  ;; Whether path holds JSON: by its extension, else by its first
  ;; non-blank character being {.
  (define (json-file? path)
    (let ((ext (pathname-extension path)))
      (if (member ext '("tmj" "tsj" "tj" "json"))
          #t
          (and (not (member ext '("tmx" "tsx" "tx")))
               (handle-exceptions exn #f
                 (with-input-from-file path
                   (lambda ()
                     (let loop ((k 0))
                       (let ((c (read-char)))
                         (cond ((eof-object? c) #f)
                               ((memv c '(#\space #\tab #\newline #\return)) (if (< k 4096) (loop (+ k 1)) #f))
                               (else (char=? c #\{))))))))))))

  ;; The root element (map, tileset or template) of a JSON file, as the TMX
  ;; reader's read-root gives it. fail is the TMX reader's error procedure:
  ;; (fail file format-string arg ...).
  (define (json-root path tag fail)
    (let* ((text (with-input-from-file path (lambda () (read-string #f))))
           (doc (handle-exceptions exn
                    (if (json-condition? exn)
                        (fail path "malformed JSON: ~a"
                              ((condition-property-accessor 'exn 'message "") exn))
                        (abort exn))
                  (json-parse-string (if (string? text) text "") #f))))
      (unless (json-object? doc)
        (fail path "the file holds ~a, expected a JSON object (a Tiled ~a)"
              (json-type-name doc) tag))
      (let ((type (json-ref doc "type" 'absent)))
        (unless (or (eq? type 'absent) (equal? type (symbol->string tag)))
          (fail path "the file is of type ~s, expected ~s" type (symbol->string tag))))
      (let ((r (reader path fail)))
        (case tag
          ((map) (r 'map doc))
          ((tileset) (r 'tileset doc))
          ((template) (r 'template doc))))))

  ;; The element builders for one file. (r kind json) builds an element.
  (define (reader path fail)
    ;; what: the place being read, for messages
    (define (bad what key v expected)
      (fail path "~a: ~s is ~a, expected ~a" what key
            (cond ((string? v) (sprintf "~s (a string)" v))
                  ((or (json-object? v) (vector? v)) (json-type-name v))
                  ((boolean? v) (if v "true" "false"))
                  (else (sprintf "~a" v)))
            expected))
    (define (get obj key) (json-ref obj key 'null))
    (define (present? v) (not (eq? v 'null)))
    ;; Checked access to one key: the value, or #f when absent or null; a
    ;; value that is not `ok?` is an error saying what was `expected`.
    (define (typed-at what obj key ok? expected)
      (let ((v (get obj key)))
        (cond ((not (present? v)) #f)
              ((ok? v) v)
              (else (bad what key v expected)))))
    (define (number-at what obj key) (typed-at what obj key number? "a number"))
    (define (string-at what obj key) (typed-at what obj key string? "a string"))
    (define (object-at what obj key) (typed-at what obj key json-object? "an object"))
    (define (array-at what obj key) (typed-at what obj key vector? "an array"))
    ;; (a JSON false is a value here, so it cannot be typed-at's answer)
    (define (bool-at what obj key)
      (let ((v (get obj key)))
        (cond ((not (present? v)) #f)
              ((boolean? v) (if v "true" "false"))
              (else (bad what key v "true or false")))))
    (define (objects-of what obj key)
      (let ((v (array-at what obj key)))
        (if v
            (let loop ((i (fx- (vector-length v) 1)) (acc '()))
              (if (fx< i 0)
                  acc
                  (let ((e (vector-ref v i)))
                    (unless (json-object? e)
                      (bad what (sprintf "~a[~a]" key i) e "an object"))
                    (loop (fx- i 1) (cons e acc)))))
            '())))
    ;; (@ ...) from a spec of (key attribute kind): kind number, string,
    ;; bool, or version (a string or, before Tiled 1.6, a number).
    (define (attrs what obj spec)
      (cons '@
            (let loop ((spec spec) (acc '()))
              (if (null? spec)
                  (reverse acc)
                  (let* ((key (car (car spec)))
                         (attr (cadr (car spec)))
                         (v (case (caddr (car spec))
                              ((number) (number-at what obj key))
                              ((string) (string-at what obj key))
                              ((bool) (bool-at what obj key))
                              ((version) (let ((v (get obj key)))
                                           (cond ((not (present? v)) #f)
                                                 ((string? v) v)
                                                 ((number? v) (number->string v))
                                                 (else (bad what key v "a string"))))))))
                    (loop (cdr spec) (if v (cons (list attr v) acc) acc)))))))
    (define (name-of obj) (let ((v (get obj "name"))) (if (string? v) v "")))

    ;; Properties: [{name, type, value, propertytype}, ...]
    (define (properties what obj)
      (let ((ps (objects-of what obj "properties")))
        (if (null? ps)
            '()
            (list (cons 'properties (map (lambda (p) (property what p)) ps))))))
    (define (property what p)
      (let* ((name (or (string-at what p "name")
                       (fail path "~a: a property has no name" what)))
             (pwhat (sprintf "~a, property ~s" what name))
             (type (or (string-at pwhat p "type") "string"))
             (ptype (string-at pwhat p "propertytype"))
             (head (append (list (list 'name name) (list 'type type))
                           (if ptype (list (list 'propertytype ptype)) '()))))
        (typed-value pwhat 'property head type (get p "value"))))
    ;; An element (tag (@ head... (value v))) for a value of a Tiled type;
    ;; a missing value is left out (the TMX reader's default for the type).
    (define (typed-value what tag head type v)
      (define (plain expected ok?)
        (cond ((not (present? v)) (list tag (cons '@ head)))
              ((ok? v) (list tag (cons '@ (append head (list (list 'value v))))))
              (else (bad what "value" v expected))))
      (cond ((member type '("string" "color" "file")) (plain "a string" string?))
            ((member type '("int" "float" "object")) (plain "a number" number?))
            ((equal? type "bool")
             (cond ((not (present? v)) (list tag (cons '@ head)))
                   ((boolean? v) (list tag (cons '@ (append head (list (list 'value (if v "true" "false")))))))
                   (else (bad what "value" v "true or false"))))
            ((equal? type "class")
             (cond ((not (present? v)) (list tag (cons '@ head)))
                   ((json-object? v)
                    (list tag (cons '@ head) (cons 'properties (class-members what v))))
                   (else (bad what "value" v "an object"))))
            ((equal? type "list")
             (cond ((not (present? v)) (list tag (cons '@ head)))
                   ((vector? v)
                    (cons tag (cons (cons '@ head)
                                    (let loop ((i (fx- (vector-length v) 1)) (acc '()))
                                      (if (fx< i 0)
                                          acc
                                          (loop (fx- i 1) (cons (list-item what i (vector-ref v i)) acc)))))))
                   (else (bad what "value" v "an array"))))
            ;; the TMX reader names the unknown type
            (else (list tag (cons '@ head)))))
    (define (list-item what i item)
      (let ((iwhat (sprintf "~a, item ~a" what i)))
        (unless (json-object? item) (bad what (sprintf "value[~a]" i) item "an object"))
        (let ((type (or (string-at iwhat item "type") "string"))
              (ptype (string-at iwhat item "propertytype")))
          (typed-value iwhat 'item (append (list (list 'type type))
                                           (if ptype (list (list 'propertytype ptype)) '()))
                       type (get item "value")))))
    (define (class-members what obj)
      (map (lambda (m)
             (let* ((name (car m)) (v (cdr m))
                    (type (cond ((string? v) "string") ((boolean? v) "bool")
                                ((exact-integer? v) "int") ((number? v) "float")
                                ((json-object? v) "class")
                                (else (bad what name v "a string, number, bool or object")))))
               (typed-value (sprintf "~a, member ~s" what name) 'property
                            (append (list (list 'name name) (list 'type type))
                                    (if (equal? type "class") (list (list 'propertytype "")) '()))
                            type v)))
           (json-object-members obj)))

    ;; An <image> from the keys image, imagewidth, imageheight, transparentcolor.
    (define (image what obj)
      (let ((src (string-at what obj "image")))
        (if (and src (not (string=? src "")))
            (list (list 'image (attrs what obj '(("image" source string) ("imagewidth" width number)
                                                 ("imageheight" height number)
                                                 ("transparentcolor" trans string)))))
            '())))

    ;; Tilesets
    (define (tileset obj)
      (let ((what (sprintf "tileset ~s" (name-of obj))))
        (if (present? (get obj "source"))
            (list 'tileset (attrs what obj '(("firstgid" firstgid number) ("source" source string))))
            (append
             (list 'tileset
                   (attrs what obj '(("firstgid" firstgid number) ("name" name string)
                                     ("class" class string)
                                     ("tilewidth" tilewidth number) ("tileheight" tileheight number)
                                     ("spacing" spacing number) ("margin" margin number)
                                     ("tilecount" tilecount number) ("columns" columns number)
                                     ("objectalignment" objectalignment string))))
             (image what obj)
             (let ((o (object-at what obj "tileoffset")))
               (if o (list (list 'tileoffset (attrs what o '(("x" x number) ("y" y number))))) '()))
             (let ((g (object-at what obj "grid")))
               (if g (list (list 'grid (attrs what g '(("orientation" orientation string)
                                                       ("width" width number) ("height" height number)))))
                   '()))
             (properties what obj)
             (map (lambda (t) (tile what t)) (objects-of what obj "tiles"))))))
    (define (tile what obj)
      (let ((twhat (sprintf "~a, tile ~a" what (get obj "id"))))
        (append
         (list 'tile (attrs twhat obj '(("id" id number) ("type" type string) ("class" class string)
                                        ("probability" probability number)
                                        ("x" x number) ("y" y number)
                                        ("width" width number) ("height" height number))))
         (properties twhat obj)
         (image twhat obj)
         (let ((frames (objects-of twhat obj "animation")))
           (if (null? frames)
               '()
               (list (cons 'animation
                           (map (lambda (f)
                                  (list 'frame (attrs twhat f '(("tileid" tileid number)
                                                                ("duration" duration number)))))
                                frames)))))
         (let ((og (object-at twhat obj "objectgroup")))
           (if og
               (list (cons 'objectgroup
                           (cons (attrs twhat og '(("draworder" draworder string)))
                                 (map (lambda (o) (object twhat o)) (objects-of twhat og "objects")))))
               '())))))

    ;; Objects
    (define (points what obj key)
      (let ((v (array-at what obj key)))
        (let loop ((i (fx- (vector-length v) 1)) (acc '()))
          (if (fx< i 0)
              acc
              (let ((p (vector-ref v i))
                    (pwhat (sprintf "~a, ~a[~a]" what key i)))
                (unless (json-object? p) (bad what (sprintf "~a[~a]" key i) p "an object {x, y}"))
                (let ((x (or (number-at pwhat p "x") (fail path "~a has no x" pwhat)))
                      (y (or (number-at pwhat p "y") (fail path "~a has no y" pwhat))))
                  (loop (fx- i 1) (cons (cons x y) acc))))))))
    (define (object what obj)
      (let* ((owhat (sprintf "~a, object ~a" what (get obj "id")))
             (flag (lambda (key) (equal? (bool-at owhat obj key) "true")))
             (shape
              (cond ((flag "ellipse") (list (list 'ellipse)))
                    ((flag "point") (list (list 'point)))
                    ((flag "capsule") (list (list 'capsule)))
                    ((present? (get obj "polygon"))
                     (list (list 'polygon (list '@ (list 'points (points owhat obj "polygon"))))))
                    ((present? (get obj "polyline"))
                     (list (list 'polyline (list '@ (list 'points (points owhat obj "polyline"))))))
                    ((object-at owhat obj "text")
                     => (lambda (t)
                          (list (list 'text
                                      (attrs owhat t '(("fontfamily" fontfamily string)
                                                       ("pixelsize" pixelsize number)
                                                       ("wrap" wrap bool) ("color" color string)
                                                       ("bold" bold bool) ("italic" italic bool)
                                                       ("underline" underline bool)
                                                       ("strikeout" strikeout bool)
                                                       ("kerning" kerning bool)
                                                       ("halign" halign string)
                                                       ("valign" valign string)))
                                      (or (string-at owhat t "text") "")))))
                    (else '()))))
        (append
         (list 'object
               (attrs owhat obj '(("id" id number) ("name" name string) ("type" type string)
                                  ("class" class string) ("x" x number) ("y" y number)
                                  ("width" width number) ("height" height number)
                                  ("rotation" rotation number) ("gid" gid number)
                                  ("visible" visible bool) ("template" template string))))
         (properties owhat obj)
         shape)))

    ;; Layers
    (define common-layer-attrs
      '(("id" id number) ("name" name string) ("class" class string)
        ("opacity" opacity number) ("visible" visible bool) ("tintcolor" tintcolor string)
        ("offsetx" offsetx number) ("offsety" offsety number)
        ("parallaxx" parallaxx number) ("parallaxy" parallaxy number) ("locked" locked bool)))
    ;; Cells of a JSON array, checked: each a tile id with its flags.
    (define (cells what v)
      (let* ((n (vector-length v)) (out (make-u32vector n 0)))
        (do ((i 0 (fx+ i 1))) ((fx= i n) out)
          (let ((c (vector-ref v i)))
            (unless (and (exact-integer? c) (<= 0 c 4294967295))
              (bad what (sprintf "data[~a]" i) c "a cell (an integer from 0 to 4294967295)"))
            (u32vector-set! out i c)))))
    ;; The content of a <data> or <chunk> from obj's "data".
    (define (data-content what obj encoding)
      (let ((d (get obj "data")))
        (cond ((equal? encoding "base64")
               (if (string? d) (list d) (bad what "data" d "a base64 string (the encoding is base64)")))
              ((vector? d) (list (cells what d)))
              ((not (present? d)) (fail path "~a: the layer has no \"data\"" what))
              (else (bad what "data" d "an array of cells")))))
    (define (tile-layer what obj)
      (let* ((encoding (or (string-at what obj "encoding") "csv"))
             (compression (string-at what obj "compression"))
             (data-attrs (cons '@ (append (if (equal? encoding "base64") '((encoding "base64")) '())
                                          (if (and compression (not (string=? compression "")))
                                              (list (list 'compression compression))
                                              '())))))
        (unless (member encoding '("csv" "base64"))
          (fail path "~a: unsupported encoding ~s (expected csv or base64)" what encoding))
        (when (and compression (not (string=? compression "")) (not (equal? encoding "base64")))
          (fail path "~a: compression ~a needs base64 encoding, not ~a" what compression encoding))
        (append
         (list 'layer (attrs what obj (append common-layer-attrs
                                              '(("width" width number) ("height" height number)))))
         (properties what obj)
         (list
          (cons 'data
                (cons data-attrs
                      (if (present? (get obj "chunks"))
                          (map (lambda (ch)
                                 (let ((cwhat (sprintf "~a, chunk at (~a, ~a)" what (get ch "x") (get ch "y"))))
                                   (cons 'chunk
                                         (cons (attrs cwhat ch '(("x" x number) ("y" y number)
                                                                 ("width" width number)
                                                                 ("height" height number)))
                                               (data-content cwhat ch encoding)))))
                               (objects-of what obj "chunks"))
                          (data-content what obj encoding))))))))
    (define (layer obj)
      (let* ((type (get obj "type"))
             (what (sprintf "layer ~s" (name-of obj))))
        (cond ((equal? type "tilelayer") (tile-layer what obj))
              ((equal? type "objectgroup")
               (append (list 'objectgroup
                             (attrs what obj (append common-layer-attrs
                                                     '(("color" color string)
                                                       ("draworder" draworder string)))))
                       (properties what obj)
                       (map (lambda (o) (object what o)) (objects-of what obj "objects"))))
              ((equal? type "imagelayer")
               (append (list 'imagelayer
                             (attrs what obj (append common-layer-attrs
                                                     '(("repeatx" repeatx bool) ("repeaty" repeaty bool)))))
                       (properties what obj)
                       (image what obj)))
              ((equal? type "group")
               (append (list 'group (attrs what obj common-layer-attrs))
                       (properties what obj)
                       (map layer (objects-of what obj "layers"))))
              ((present? type)
               (fail path "~a: unknown layer type ~s (expected tilelayer, objectgroup, imagelayer or group)"
                     what type))
              (else (fail path "~a: the layer has no \"type\"" what)))))

    (lambda (kind doc)
      (case kind
        ((map)
         (append
          (list 'map (attrs "map" doc '(("version" version version) ("tiledversion" tiledversion string)
                                        ("class" class string) ("orientation" orientation string)
                                        ("renderorder" renderorder string)
                                        ("width" width number) ("height" height number)
                                        ("tilewidth" tilewidth number) ("tileheight" tileheight number)
                                        ("infinite" infinite bool)
                                        ("hexsidelength" hexsidelength number)
                                        ("staggeraxis" staggeraxis string)
                                        ("staggerindex" staggerindex string)
                                        ("parallaxoriginx" parallaxoriginx number)
                                        ("parallaxoriginy" parallaxoriginy number)
                                        ("backgroundcolor" backgroundcolor string))))
          (properties "map" doc)
          (map tileset (objects-of "map" doc "tilesets"))
          (map layer (objects-of "map" doc "layers"))))
        ((tileset) (tileset doc))
        ((template)
         (append (list 'template)
                 (let ((ts (object-at "template" doc "tileset")))
                   (if ts (list (tileset ts)) '()))
                 (let ((o (object-at "template" doc "object")))
                   (if o (list (object "template" o)) '()))))))))
