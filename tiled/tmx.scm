;;; (downstroke tmx): Tiled's TMX maps, TSX tilesets and TX templates, read
;;; into (downstroke map)'s records with expat (xml.scm) and zlib/zstd
;;; (decode.scm).
;;;
;;; The loader. `(load-tilemap path)` reads a TMX file with its external
;;; tilesets (.tsx), templates (.tx) and checks that every image they name
;;; exists (images are not decoded). Any of these files may be in Tiled's
;;; JSON format instead (.tmj, .tsj, .tj, or JSON content under another
;;; name): (downstroke tmj) turns it into the tree an XML file gives. It never crashes the process: every
;;; problem is raised as an error whose message starts with the file it is in
;;; and says what is wrong; the condition also has the kind `tmx` with the
;;; property `file`.
;;;
(module (downstroke tmx)
  (load-tilemap tilemap-max-cells tilemap-max-depth load-tileset)

  (import (downstroke keywords) (only (downstroke media-header) file-problem image-file-size))
  (import scheme (chicken base) (chicken fixnum) (chicken format)
          (chicken bitwise) (chicken pathname) (chicken condition)
          (chicken string) (chicken file) (chicken port) srfi-4
          (downstroke xml) (downstroke decode) (downstroke map) (downstroke tmj)
          (only (downstroke util) filter append-map any list-min list-max string-concatenate take drop
                make-hash-table hash-table-ref/default hash-table-set!
                hash-table-exists?))
  ;;; ------------------------------------------------------------------
  ;;; Loading: errors

  ;; The largest number of cells a layer (or the union of an infinite map's
  ;; chunks) may have: 2^26, a 8192 x 8192 map. Larger is an error, never an
  ;; attempt to allocate.
  (define tilemap-max-cells (make-parameter (* 8192 8192)))

  ;; How deep groups may nest (a group in a group is depth 2). Tiled sets
  ;; no limit; maps made by hand rarely pass 5.
  (define tilemap-max-depth (make-parameter 100))

  ;; The procedure a loading error is reported from.
  (define loader (make-parameter 'load-tilemap))

  (define (tmx-error file fmt . args)
    (let ((msg (string-append file ": " (apply sprintf fmt args))))
      (abort (make-composite-condition
              (make-property-condition 'exn 'location (loader)
                                       'message msg 'arguments '())
              (make-property-condition 'tmx 'file file)))))

  (define tmx-condition? (condition-predicate 'tmx))

  (define (condition-message exn)
    (if (condition? exn)
        (let ((msg ((condition-property-accessor 'exn 'message #f) exn))
              (args ((condition-property-accessor 'exn 'arguments '()) exn)))
          (if (string? msg)
              (string-concatenate
               (cons msg (map (lambda (a) (sprintf " ~s" a))
                              (if (list? args) args '()))))
              (sprintf "~s" exn)))
        (sprintf "~s" exn)))

  ;; Runs thunk; any error that is not already ours becomes one that names
  ;; file and what was being done.
  (define (with-tmx-context file what thunk)
    (handle-exceptions exn
        (if (tmx-condition? exn)
            (abort exn)
            (tmx-error file "~a: ~a" what (condition-message exn)))
      (thunk)))

  ;;; ------------------------------------------------------------------
  ;;; Loading: SXML access and attribute parsing

  (define (element? x) (and (pair? x) (symbol? (car x)) (not (eq? (car x) '@))
                            (not (eq? (car x) '*PI*)) (not (eq? (car x) '*COMMENT*))))

  (define (x-attrs node)
    (let ((rest (cdr node)))
      (if (and (pair? rest) (pair? (car rest)) (eq? (caar rest) '@)) (cdar rest) '())))

  (define (x-attr node name)
    (let ((p (assq name (x-attrs node))))
      (and p (pair? (cdr p)) (cadr p))))

  (define (x-children node #!optional tag)
    (filter (lambda (c) (and (element? c) (or (not tag) (eq? (car c) tag))))
            (cdr node)))

  (define (x-child node tag)
    (let loop ((cs (cdr node)))
      (cond ((null? cs) #f)
            ((and (element? (car cs)) (eq? (caar cs) tag)) (car cs))
            (else (loop (cdr cs))))))

  (define (x-text node)
    (string-concatenate (filter string? (cdr node))))

  ;; Each attribute reader takes ctx: (file . "what is being read").
  (define (ctx-file ctx) (car ctx))
  ;; What is being read: a string, or a chain (what-before . part) that
  ;; sub-ctx makes and that is written out only when an error names it,
  ;; so nested groups cost memory in proportion to their depth, not to
  ;; its square.
  (define (ctx-what ctx)
    (let loop ((w (cdr ctx)) (parts '()) (n 1))
      (if (string? w)
          (string-concatenate (intersperse (abridge (cons w parts) n) ", "))
          (loop (car w) (cons (cdr w) parts) (+ n 1)))))

  ;; The first three parts and the last four of a long path, so that an
  ;; error 20,000 groups deep stays a line.
  (define (abridge parts n)
    (if (<= n 8)
        parts
        (append (take parts 3)
                (list (sprintf "... ~a more groups ..." (- n 7)))
                (drop parts (- n 4)))))

  (define (sub-ctx ctx what) (cons (car ctx) (cons (cdr ctx) what)))

  (define (bad-attr ctx node name expected)
    (tmx-error (ctx-file ctx) "~a: attribute ~a=~s of <~a> is not ~a"
               (ctx-what ctx) name (x-attr node name) (car node) expected))

  (define (attr-string node name default)
    (or (x-attr node name) default))

  ;; A number from an attribute's text, or as a JSON file gave it.
  (define (parse-real s)
    (let ((n (cond ((string? s) (string->number s)) ((number? s) s) (else #f))))
      (and n (real? n) (not (nan? n)) (finite? n) n)))

  (define (attr-number ctx node name default)
    (let ((s (x-attr node name)))
      (cond ((not s) default)
            ((parse-real s) => values)
            (else (bad-attr ctx node name "a number")))))

  (define (attr-int ctx node name default #!optional (min -inf.0))
    (let ((s (x-attr node name)))
      (if (not s)
          default
          (let ((n (parse-real s)))
            (if (and n (exact-integer? n) (>= n min)
                     (< (abs n) 4294967296))
                n
                (bad-attr ctx node name
                          (if (> min 0) "a positive integer"
                              (if (= min 0) "a non-negative integer" "an integer"))))))))

  (define (attr-bool ctx node name default)
    (let ((s (x-attr node name)))
      (cond ((not s) default)
            ((member s '("1" "true")) #t)
            ((member s '("0" "false")) #f)
            (else (bad-attr ctx node name "0, 1, true or false")))))

  (define (attr-choice ctx node name choices default)
    (let ((s (x-attr node name)))
      (cond ((not s) default)
            ((assoc s choices) => cdr)
            (else (tmx-error (ctx-file ctx) "~a: unsupported ~a ~s of <~a> (expected one of ~a)"
                             (ctx-what ctx) name s (car node)
                             (string-intersperse (map car choices) ", "))))))

  (define (hex-digit c)
    (let ((i (char->integer c)))
      (cond ((and (>= i 48) (<= i 57)) (- i 48))
            ((and (>= i 97) (<= i 102)) (- i 87))
            ((and (>= i 65) (<= i 70)) (- i 55))
            (else #f))))

  ;; "#AARRGGBB", "#RRGGBB" (the # optional) -> (color R G B A); "" -> #f.
  (define (parse-color s)
    (let* ((s (if (and (> (string-length s) 0) (char=? (string-ref s 0) #\#))
                  (substring s 1 (string-length s))
                  s))
           (n (string-length s))
           (byte (lambda (i)
                   (let ((a (hex-digit (string-ref s i)))
                         (b (hex-digit (string-ref s (+ i 1)))))
                     (and a b (+ (* 16 a) b))))))
      (cond ((= n 6)
             (let ((r (byte 0)) (g (byte 2)) (b (byte 4)))
               (and r g b (list 'color r g b 255))))
            ((= n 8)
             (let ((a (byte 0)) (r (byte 2)) (g (byte 4)) (b (byte 6)))
               (and a r g b (list 'color r g b a))))
            (else #f))))

  (define (attr-color ctx node name)
    (let ((s (x-attr node name)))
      (and s (not (string=? s ""))
           (or (parse-color s) (bad-attr ctx node name "a colour (#AARRGGBB or #RRGGBB)")))))

  ;;; ------------------------------------------------------------------
  ;;; Loading: files

  (define (resolve-path relative-to path)
    (if (absolute-pathname? path)
        (normalize-pathname path)
        (normalize-pathname (make-pathname (pathname-directory relative-to) path))))

  ;; Why a path cannot be read as a file, or #f ((downstroke media-header)).
  (define unreadable-file file-problem)

  (define (regular-file? path) (not (unreadable-file path)))

  (define (check-exists ctx path what)
    (let ((why (unreadable-file path)))
      (when why
        (tmx-error (ctx-file ctx) "~a: ~a file ~s ~a" (ctx-what ctx) what path why))))

  ;; The root element of an XML file, which must be a <tag>; a JSON file's
  ;; object turned into the same tree.
  (define (read-root ctx path tag)
    (if (json-file? path)
        (json-root path tag tmx-error)
        (read-xml-root path tag)))

  (define (read-xml-root path tag)
    (let ((tree (handle-exceptions exn
                    (tmx-error path "malformed XML: ~a" (condition-message exn))
                  (xml-parse-file path))))
      (let ((root (and (pair? tree) (let loop ((cs (cdr tree)))
                                      (cond ((null? cs) #f)
                                            ((element? (car cs)) (car cs))
                                            (else (loop (cdr cs))))))))
        (unless (and root (eq? (car root) tag))
          (tmx-error path "the root element is ~a, expected <~a>"
                     (if root (sprintf "<~a>" (car root)) "missing") tag))
        root)))

  ;;; ------------------------------------------------------------------
  ;;; Loading: properties

  (define (parse-properties ctx node)
    (let ((props (and node (x-child node 'properties))))
      (if props
          (map (lambda (p) (parse-property ctx p)) (x-children props 'property))
          '())))

  (define (parse-property ctx p)
    (let* ((name (or (x-attr p 'name)
                     (tmx-error (ctx-file ctx) "~a: a <property> has no name" (ctx-what ctx))))
           (pctx (sub-ctx ctx (sprintf "property ~s" name))))
      (cons name (property-value pctx p))))

  (define (property-value ctx p)
    (let* ((type (attr-string p 'type "string"))
           (value (or (x-attr p 'value) (x-text p)))
           (fail (lambda (expected)
                   (tmx-error (ctx-file ctx) "~a: value ~s is not ~a" (ctx-what ctx) value expected))))
      ;; A typed property written without a value (or with value="")
      ;; reads as the type's empty value: int 0, float 0.0, bool #f,
      ;; object (object 0); string, file and color are "", (file "") and
      ;; (color) (unset) below.
      (cond ((string=? type "string") value)
            ((and (equal? value "") (member type '("int" "float" "bool" "object")))
             (cond ((string=? type "int") 0)
                   ((string=? type "float") 0.0)
                   ((string=? type "bool") #f)
                   (else (list 'object 0))))
            ((string=? type "int")
             (let ((n (parse-real value)))
               (if (and n (exact-integer? n)) n (fail "an integer"))))
            ((string=? type "float")
             (let ((n (parse-real value)))
               (if n (exact->inexact n) (fail "a number"))))
            ((string=? type "bool")
             (cond ((string=? value "true") #t)
                   ((string=? value "false") #f)
                   (else (fail "true or false"))))
            ((string=? type "color")
             (if (string=? value "")
                 '(color)
                 (or (parse-color value) (fail "a colour"))))
            ((string=? type "file")
             (list 'file (if (string=? value "") "" (resolve-path (ctx-file ctx) value))))
            ((string=? type "object")
             (let ((n (parse-real value)))
               (if (and n (exact-integer? n) (>= n 0)) (list 'object n) (fail "an object id"))))
            ((string=? type "class")
             (list 'class (attr-string p 'propertytype "") (parse-properties ctx p)))
            ((string=? type "list")
             (cons 'list
                   (map (lambda (item) (property-value ctx item))
                        (append (x-children p 'item)
                                (let ((ps (x-child p 'properties)))
                                  (if ps (x-children ps 'property) '()))))))
            (else (tmx-error (ctx-file ctx) "~a: unknown property type ~s" (ctx-what ctx) type)))))

  ;;; ------------------------------------------------------------------
  ;;; Loading: images and tilesets

  (define (parse-image ctx node)
    (let ((source (x-attr node 'source)))
      (when (and source (string=? source ""))
        (tmx-error (ctx-file ctx) "~a: <image> has an empty source" (ctx-what ctx)))
      (let ((path (and source (resolve-path (ctx-file ctx) source))))
        (when path (check-exists ctx path "image"))
        (unless (or path (x-child node 'data))
          (tmx-error (ctx-file ctx) "~a: <image> has neither a source nor data" (ctx-what ctx)))
        ;; width and height are optional: Tiled then reads the image's
        ;; own size, which the header of a PNG, JPEG, GIF, BMP, QOI or WebP
        ;; gives (another format stays #f and the renderer counts columns
        ;; from the loaded texture)
        (let* ((w (attr-int ctx node 'width #f 0))
               (h (attr-int ctx node 'height #f 0))
               (size (and path (not (and w h)) (image-file-size path))))
          (make-image path
                      (or w (and size (car size)))
                      (or h (and size (cadr size)))
                      (attr-color ctx node 'trans))))))

  (define (parse-animation ctx node)
    (let ((anim (x-child node 'animation)))
      (if anim
          (map (lambda (f)
                 (cons (attr-int ctx f 'tileid 0 0) (attr-int ctx f 'duration 0 0)))
               (x-children anim 'frame))
          '())))

  ;; Collision shapes of a tile: the objects of its <objectgroup>.
  (define (parse-tile ctx node gid-of)
    (let* ((id (or (attr-int ctx node 'id #f 0)
                   (tmx-error (ctx-file ctx) "~a: a <tile> has no id" (ctx-what ctx))))
           (tctx (sub-ctx ctx (sprintf "tile ~a" id)))
           (img (x-child node 'image))
           (og (x-child node 'objectgroup)))
      (make-tile id
                 (or (x-attr node 'class) (x-attr node 'type) "")
                 (attr-number tctx node 'probability 1)
                 (parse-properties tctx node)
                 (and img (parse-image tctx img))
                 (attr-int tctx node 'x 0 0) (attr-int tctx node 'y 0 0)
                 (attr-int tctx node 'width #f 0) (attr-int tctx node 'height #f 0)
                 (parse-animation tctx node)
                 (if og
                     (map (lambda (o) (parse-object tctx o gid-of '() #f))
                          (x-children og 'object))
                     '()))))

  ;; A tileset element (embedded in a map, or the root of a .tsx file).
  ;; file is the file holding the element; source the .tsx path or #f.
  (define (parse-tileset file node first-gid source)
    (let* ((name (attr-string node 'name ""))
           (ctx (cons file (sprintf "tileset ~s" name)))
           (tw (attr-int ctx node 'tilewidth #f 1))
           (th (attr-int ctx node 'tileheight #f 1))
           (spacing (attr-int ctx node 'spacing 0 0))
           (margin (attr-int ctx node 'margin 0 0))
           (img-node (x-child node 'image))
           (img (and img-node (parse-image ctx img-node)))
           (offset (x-child node 'tileoffset))
           (grid (x-child node 'grid))
           (table (make-hash-table eqv?))
           (ids '()))
      (unless (and tw th)
        (tmx-error file "~a: tilewidth and tileheight are required" (ctx-what ctx)))
      (for-each
       (lambda (t)
         (let ((tile (parse-tile ctx t #f)))
           (unless (hash-table-exists? table (tile-id tile))
             (set! ids (cons (tile-id tile) ids)))
           (hash-table-set! table (tile-id tile) tile)))
       (x-children node 'tile))
      (hash-table-set! table 'order (reverse ids))
      (let* ((columns (or (attr-int ctx node 'columns #f 0)
                          (and img (image-width img)
                               (max 0 (quotient (+ (- (image-width img) (* 2 margin)) spacing)
                                                (+ tw spacing))))))
             (rows (and img (image-height img)
                        (max 0 (quotient (+ (- (image-height img) (* 2 margin)) spacing)
                                         (+ th spacing)))))
             (count (or (attr-int ctx node 'tilecount #f 0)
                        (and img columns rows (* columns rows)))))
        (make-tileset first-gid name (or (x-attr node 'class) "") source tw th spacing margin
                      count columns img
                      (if offset (attr-number ctx offset 'x 0) 0)
                      (if offset (attr-number ctx offset 'y 0) 0)
                      (attr-choice ctx node 'objectalignment
                                   '(("unspecified" . unspecified) ("topleft" . top-left)
                                     ("top" . top) ("topright" . top-right) ("left" . left)
                                     ("center" . center) ("right" . right)
                                     ("bottomleft" . bottom-left) ("bottom" . bottom)
                                     ("bottomright" . bottom-right))
                                   'unspecified)
                      (and grid (list (attr-string grid 'orientation "orthogonal")
                                      (attr-int ctx grid 'width #f 0)
                                      (attr-int ctx grid 'height #f 0)))
                      (parse-properties ctx node)
                      table))))

  ;; A <tileset> child of a map or template: embedded, or naming a .tsx.
  ;; External tilesets are read once per load (cache: path -> root element).
  (define (load-tileset-ref st file node)
    (let* ((ctx (cons file "tileset"))
           (first-gid (or (attr-int ctx node 'firstgid #f 1)
                          (tmx-error file "a <tileset> has no firstgid")))
           (source (x-attr node 'source)))
      (if source
          (let ((path (resolve-path file source)))
            (check-exists ctx path "tileset")
            (let ((root (or (hash-table-ref/default (state-tsx st) path #f)
                            (let ((r (read-root ctx path 'tileset)))
                              (hash-table-set! (state-tsx st) path r)
                              r))))
              (with-tmx-context path "tileset"
                (lambda () (parse-tileset path root first-gid path)))))
          (parse-tileset file node first-gid #f))))

  ;;; ------------------------------------------------------------------
  ;;; Loading: objects and templates

  ;; Per-load state: caches and the map's tileset list (templates may add
  ;; tilesets the map does not list).
  (define-record-type load-state
    (make-state tsx templates tilesets stack)
    load-state?
    (tsx state-tsx)
    (templates state-templates)
    (tilesets state-tilesets state-tilesets-set!)
    (stack state-stack state-stack-set!))

  ;; "x,y x,y ..." as TMX writes it; a JSON file's points are already pairs.
  (define (parse-points ctx s)
    (if (pair? s)
        s
        (parse-points-text ctx s)))

  (define (parse-points-text ctx s)
    (let ((pairs (string-split s " \t\n\r")))
      (map (lambda (p)
             (let* ((xy (string-split p "," #t))
                    (x (and (= (length xy) 2) (parse-real (car xy))))
                    (y (and x (parse-real (cadr xy)))))
               (unless (and x y)
                 (tmx-error (ctx-file ctx) "~a: bad point ~s in points ~s" (ctx-what ctx) p s))
               (cons x y)))
           pairs)))

  (define (parse-text ctx node)
    (list (cons 'text (x-text node))
          (cons 'font-family (attr-string node 'fontfamily "sans-serif"))
          (cons 'pixel-size (attr-int ctx node 'pixelsize 16 0))
          (cons 'wrap? (attr-bool ctx node 'wrap #f))
          (cons 'color (or (attr-color ctx node 'color) '(color 0 0 0 255)))
          (cons 'bold? (attr-bool ctx node 'bold #f))
          (cons 'italic? (attr-bool ctx node 'italic #f))
          (cons 'underline? (attr-bool ctx node 'underline #f))
          (cons 'strikeout? (attr-bool ctx node 'strikeout #f))
          (cons 'kerning? (attr-bool ctx node 'kerning #t))
          (cons 'halign (attr-choice ctx node 'halign
                                     '(("left" . left) ("center" . center)
                                       ("right" . right) ("justify" . justify)) 'left))
          (cons 'valign (attr-choice ctx node 'valign
                                     '(("top" . top) ("center" . center)
                                       ("bottom" . bottom)) 'top))))

  ;; Properties of base overridden (by name) by those of the instance.
  (define (merge-properties base own)
    (append (filter (lambda (p) (not (assoc (car p) own))) base) own))

  ;; An <object>. gid-of maps a raw gid written in this file to the map's
  ;; gid space (templates have their own tilesets), or is #f (tile collision
  ;; shapes, which never name tiles). base is the template's object or #f.
  (define (parse-object ctx node gid-of stack st)
    (let* ((id (attr-int ctx node 'id 0 0))
           (octx (sub-ctx ctx (sprintf "object ~a" id)))
           (tpl (x-attr node 'template))
           (base (and tpl st (load-template st (ctx-file octx) octx tpl stack)))
           (inherit (lambda (get default) (if base (get base) default)))
           (raw-gid (attr-int octx node 'gid #f 0))
           (cell (cond (raw-gid (if gid-of (gid-of octx raw-gid) raw-gid))
                       (else (inherit object-cell 0))))
           (shape-node (any (lambda (tag) (x-child node tag))
                            '(ellipse point polygon polyline text capsule)))
           (shape (cond (shape-node (car shape-node))
                        (raw-gid (if (zero? (cell-gid cell)) 'rectangle 'tile))
                        (base (object-shape base))
                        (else 'rectangle))))
      (make-map-object
       id
       (attr-string node 'name (inherit object-name ""))
       (or (x-attr node 'class) (x-attr node 'type) (inherit object-class ""))
       (attr-number octx node 'x (inherit object-x 0))
       (attr-number octx node 'y (inherit object-y 0))
       (attr-number octx node 'width (inherit object-width 0))
       (attr-number octx node 'height (inherit object-height 0))
       (attr-number octx node 'rotation (inherit object-rotation 0))
       cell
       (attr-bool octx node 'visible (inherit object-visible? #t))
       (if (and (eq? shape 'tile) (zero? (cell-gid cell))) 'rectangle shape)
       (cond ((and shape-node (memq shape '(polygon polyline)))
              (parse-points octx (or (x-attr shape-node 'points)
                                     (tmx-error (ctx-file octx) "~a: <~a> has no points"
                                                (ctx-what octx) shape))))
             (shape-node '())
             (else (inherit object-points '())))
       (cond ((and shape-node (eq? shape 'text)) (parse-text octx shape-node))
             (shape-node #f)
             (else (inherit object-text #f)))
       (merge-properties (inherit object-properties '()) (parse-properties octx node))
       (if tpl (resolve-path (ctx-file octx) tpl) #f))))

  ;; Find the map's copy of a tileset (same .tsx), adding it after the last
  ;; gid when the map does not list it. Returns its first gid.
  (define (map-first-gid-for st ts)
    (let ((same (and (tileset-source ts)
                     (let loop ((l (state-tilesets st)))
                       (cond ((null? l) #f)
                             ((equal? (tileset-source (car l)) (tileset-source ts)) (car l))
                             (else (loop (cdr l))))))))
      (if same
          (tileset-first-gid same)
          (let* ((next (fold-max-gid (state-tilesets st)))
                 (copy (make-tileset next (tileset-name ts) (tileset-class ts)
                                     (tileset-source ts) (tileset-tile-width ts)
                                     (tileset-tile-height ts) (tileset-spacing ts)
                                     (tileset-margin ts) (tileset-tile-count ts)
                                     (tileset-columns ts) (tileset-image ts)
                                     (tileset-offset-x ts) (tileset-offset-y ts)
                                     (tileset-object-alignment ts) (tileset-grid ts)
                                     (tileset-properties ts) (tileset-tile-table ts))))
            (state-tilesets-set! st (append (state-tilesets st) (list copy)))
            next))))

  ;; One past the highest gid any tileset can hold.
  (define (fold-max-gid tilesets)
    (let loop ((l tilesets) (m 1))
      (if (null? l)
          m
          (let* ((ts (car l))
                 (n (or (tileset-tile-count ts) 0))
                 (ids (tileset-tile-ids ts))
                 (top (+ (tileset-first-gid ts)
                         (max n (if (null? ids) 0 (+ 1 (list-max ids)))))))
            (loop (cdr l) (max m top))))))

  (define (load-template st file ctx tpl stack)
    (let ((path (resolve-path file tpl)))
      (when (member path stack)
        (tmx-error (ctx-file ctx) "~a: template cycle: ~a"
                   (ctx-what ctx) (string-intersperse (reverse (cons path stack)) " -> ")))
      (or (hash-table-ref/default (state-templates st) path #f)
          (begin
            (check-exists ctx path "template")
            (let* ((root (read-root ctx path 'template))
                   (tctx (cons path "template"))
                   (ts-node (x-child root 'tileset))
                   (ts (and ts-node (load-tileset-ref st path ts-node)))
                   (obj-node (or (x-child root 'object)
                                 (tmx-error path "the template has no <object>")))
                   (gid-of
                    (lambda (octx raw)
                      (let ((g (cell-gid raw)))
                        (cond ((zero? g) raw)
                              ((not ts)
                               (tmx-error path "~a: gid ~a but the template has no tileset"
                                          (ctx-what octx) g))
                              ((< g (tileset-first-gid ts))
                               (tmx-error path "~a: gid ~a is below the first gid of the template's tileset ~s"
                                          (ctx-what octx) g (tileset-name ts)))
                              (else
                               (let ((first (map-first-gid-for st ts)))
                                 (bitwise-ior (bitwise-and raw (bitwise-not gid-mask))
                                              (+ first (- g (tileset-first-gid ts)))))))))))
              (let ((obj (with-tmx-context path "template"
                           (lambda ()
                             (parse-object tctx obj-node gid-of (cons path stack) st)))))
                (hash-table-set! (state-templates st) path obj)
                obj))))))

  ;;; ------------------------------------------------------------------
  ;;; Loading: layer data

  (define (whitespace? c)
    (or (char=? c #\space) (char=? c #\newline) (char=? c #\return) (char=? c #\tab)))

  (define (strip-whitespace s)
    (let* ((n (string-length s))
           (keep (let loop ((i 0) (k 0))
                   (if (fx= i n) k
                       (loop (fx+ i 1) (if (whitespace? (string-ref s i)) k (fx+ k 1)))))))
      (if (fx= keep n)
          s
          (let ((out (make-string keep)))
            (let loop ((i 0) (k 0))
              (if (fx= i n)
                  out
                  (let ((c (string-ref s i)))
                    (if (whitespace? c)
                        (loop (fx+ i 1) k)
                        (begin (string-set! out k c) (loop (fx+ i 1) (fx+ k 1)))))))))))

  ;; CSV cells: unsigned decimal numbers separated by commas, whitespace
  ;; anywhere between them; one trailing comma is tolerated.
  (define (parse-csv ctx s count)
    (let* ((n (string-length s))
           (commas (let loop ((i 0) (k 0))
                     (if (fx= i n) k
                         (loop (fx+ i 1) (if (char=? (string-ref s i) #\,) (fx+ k 1) k)))))
           (trailing? (let loop ((i (fx- n 1)))
                        (and (fx>= i 0)
                             (let ((c (string-ref s i)))
                               (if (whitespace? c) (loop (fx- i 1)) (char=? c #\,))))))
           (blank? (let loop ((i 0))
                     (or (fx= i n) (and (whitespace? (string-ref s i)) (loop (fx+ i 1))))))
           (cells (cond (blank? 0) (trailing? commas) (else (fx+ commas 1)))))
      (unless (fx= cells count)
        (tmx-error (ctx-file ctx) "~a: csv data has ~a cells, expected ~a"
                   (ctx-what ctx) cells count))
      (let ((out (make-u32vector count 0)))
        (let loop ((i 0) (cell 0) (value 0) (digits 0))
          (define (finish-cell)
            (when (fx= digits 0)
              (tmx-error (ctx-file ctx) "~a: csv cell ~a is empty" (ctx-what ctx) cell))
            (when (fx>= cell count)
              (tmx-error (ctx-file ctx) "~a: csv data has more than ~a cells" (ctx-what ctx) count))
            (u32vector-set! out cell value))
          (if (fx= i n)
              (cond ((fx> digits 0)
                     (finish-cell)
                     (unless (fx= (fx+ cell 1) count)
                       (tmx-error (ctx-file ctx) "~a: csv data has ~a cells, expected ~a"
                                  (ctx-what ctx) (fx+ cell 1) count)))
                    ((not (fx= cell count))
                     (tmx-error (ctx-file ctx) "~a: csv data has ~a cells, expected ~a"
                                (ctx-what ctx) cell count)))
              (let ((c (string-ref s i)))
                (cond ((char-numeric? c)
                       ;; below 10^9 a cell is a fixnum on every platform;
                       ;; past it (flip flags) generic arithmetic, since a
                       ;; 32-bit word is no fixnum where fixnums are 31 bits
                       (let* ((d (fx- (char->integer c) 48))
                              (v (if (fx< value 100000000)
                                     (fx+ (fx* value 10) d)
                                     (+ (* value 10) d))))
                         (when (and (fx>= value 100000000) (> v 4294967295))
                           (tmx-error (ctx-file ctx) "~a: csv cell ~a is larger than 32 bits"
                                      (ctx-what ctx) cell))
                         (loop (fx+ i 1) cell v (fx+ digits 1))))
                      ((char=? c #\,)
                       (finish-cell)
                       (loop (fx+ i 1) (fx+ cell 1) 0 0))
                      ((whitespace? c)
                       (if (and (fx> digits 0)
                                (let skip ((j i))
                                  (and (fx< j n)
                                       (let ((d (string-ref s j)))
                                         (if (whitespace? d) (skip (fx+ j 1)) (char-numeric? d))))))
                           (tmx-error (ctx-file ctx) "~a: csv cell ~a: two numbers without a comma"
                                      (ctx-what ctx) cell)
                           (loop (fx+ i 1) cell value digits)))
                      (else
                       (tmx-error (ctx-file ctx) "~a: unexpected character ~s in csv data"
                                  (ctx-what ctx) c))))))
        out)))

  (define (parse-base64 ctx s compression count)
    (let* ((bytes (* 4 count))
           (raw (handle-exceptions exn
                    (tmx-error (ctx-file ctx) "~a: bad base64 data: ~a"
                               (ctx-what ctx) (condition-message exn))
                  (base64-decode (strip-whitespace s))))
           (plain (handle-exceptions exn
                      (if (tmx-condition? exn)
                          (abort exn)
                          (tmx-error (ctx-file ctx) "~a: bad ~a data: ~a"
                                     (ctx-what ctx) compression (condition-message exn)))
                    (case compression
                      ((none) raw)
                      ((zlib) (zlib-inflate raw max-size: (+ bytes 4)))
                      ((gzip) (gzip-inflate raw max-size: (+ bytes 4)))
                      ((zstd) (zstd-decompress raw max-size: (+ bytes 4)))))))
      (unless (= (u8vector-length plain) bytes)
        (tmx-error (ctx-file ctx) "~a: data has ~a bytes~a, expected ~a (~a cells)"
                   (ctx-what ctx) (u8vector-length plain)
                   (if (eq? compression 'none) "" (sprintf " after ~a decompression" compression))
                   bytes count))
      (u8vector->u32vector-le plain)))

  (define (parse-xml-tiles ctx node count)
    (let ((tiles (x-children node 'tile)))
      (unless (= (length tiles) count)
        (tmx-error (ctx-file ctx) "~a: data has ~a <tile> elements, expected ~a"
                   (ctx-what ctx) (length tiles) count))
      (let ((out (make-u32vector count 0)))
        (let loop ((ts tiles) (i 0))
          (unless (null? ts)
            (u32vector-set! out i (attr-int ctx (car ts) 'gid 0 0))
            (loop (cdr ts) (+ i 1))))
        out)))

  (define (check-cells ctx count)
    (when (> count (tilemap-max-cells))
      (tmx-error (ctx-file ctx) "~a: ~a cells is more than the limit of ~a (tilemap-max-cells)"
                 (ctx-what ctx) count (tilemap-max-cells))))

  ;; The limit is on the whole map: its tile layers together.
  (define (check-map-cells file count layers)
    (when (> count (tilemap-max-cells))
      (tmx-error file "~a cells in ~a tile layer~a: more than the limit of ~a (tilemap-max-cells)"
                 count layers (if (= layers 1) "" "s") (tilemap-max-cells))))

  ;; What an infinite map's chunks hold, from their width and height, before
  ;; any is decoded.
  (define (declared-chunk-cells ctx tile-nodes)
    (foldl (lambda (sum node)
             (let ((data (x-child node 'data)))
               (if (not data)
                   sum
                   (foldl (lambda (sum ch)
                            (+ sum (* (or (attr-int ctx ch 'width #f 0) 0)
                                      (or (attr-int ctx ch 'height #f 0) 0))))
                          sum (x-children data 'chunk)))))
           0 tile-nodes))

  ;; The cells of a <data> or <chunk>, w x h of them.
  (define (decode-cells ctx node encoding compression w h)
    (let ((count (* w h)))
      (check-cells ctx count)
      (cond ((json-cells node)
             => (lambda (v)
                  (unless (= (u32vector-length v) count)
                    (tmx-error (ctx-file ctx) "~a: data has ~a cells, expected ~a"
                               (ctx-what ctx) (u32vector-length v) count))
                  v))
            (else
             (case encoding
               ((xml) (parse-xml-tiles ctx node count))
               ((csv) (parse-csv ctx (x-text node) count))
               ((base64) (parse-base64 ctx (x-text node) compression count)))))))

  ;; A JSON file's cells, already decoded by (downstroke tmj), or #f.
  (define (json-cells node)
    (let loop ((cs (cdr node)))
      (cond ((null? cs) #f)
            ((u32vector? (car cs)) (car cs))
            (else (loop (cdr cs))))))

  (define (data-format ctx data)
    (let ((encoding (attr-choice ctx data 'encoding
                                 '(("csv" . csv) ("base64" . base64) ("" . xml)) 'xml))
          (compression (attr-choice ctx data 'compression
                                    '(("zlib" . zlib) ("gzip" . gzip) ("zstd" . zstd)
                                      ("" . none)) 'none)))
      (when (and (not (eq? compression 'none)) (not (eq? encoding 'base64)))
        (tmx-error (ctx-file ctx) "~a: compression ~a needs base64 encoding, not ~a"
                   (ctx-what ctx) compression encoding))
      (values encoding compression)))

  ;;; ------------------------------------------------------------------
  ;;; Loading: layers

  ;; What a layer inherits from its enclosing groups.
  (define-record-type inherited
    (make-inherited offset-x offset-y parallax-x parallax-y opacity visible?)
    inherited?
    (offset-x in-offset-x) (offset-y in-offset-y)
    (parallax-x in-parallax-x) (parallax-y in-parallax-y)
    (opacity in-opacity) (visible? in-visible?))

  (define top-level (make-inherited 0 0 1 1 1 #t))

  ;; Parses the layers under node; tile layers' data is kept as the raw
  ;; element for a second pass (infinite maps need every chunk first).
  ;; Returns a list of (layer-node . inherited) for every layer, in document
  ;; order, and builds records later.
  ;; Every layer and group under node, as (element . inherited), in
  ;; document order (a group before what it holds).
  (define (collect-layers ctx node inh)
    (let walk ((ctx ctx) (node node) (inh inh) (depth 1) (out '()) (k reverse))
      (let each ((children (x-children node)) (out out))
        (if (null? children)
            (k out)
            (let ((child (car children)))
              (case (car child)
                ((layer objectgroup imagelayer)
                 (each (cdr children) (cons (cons child inh) out)))
                ((group)
                 (let ((gctx (sub-ctx ctx (sprintf "group ~s" (attr-string child 'name "")))))
                   (when (> depth (tilemap-max-depth))
                     (tmx-error (ctx-file ctx) "~a: groups nest more than ~a deep (tilemap-max-depth)"
                                (ctx-what gctx) (tilemap-max-depth)))
                   (walk gctx child (compose-inherited gctx child inh) (+ depth 1)
                         (cons (cons child inh) out)
                         (lambda (out) (each (cdr children) out)))))
                (else (each (cdr children) out))))))))

  ;; Tiled still reads an image layer's old x and y attributes as its
  ;; offset when it has neither offsetx nor offsety.
  (define (legacy-offset ctx node axis)
    (if (and (eq? (car node) 'imagelayer) (not (x-attr node 'offsetx)) (not (x-attr node 'offsety)))
        (attr-number ctx node axis 0)
        0))

  ;; A layer's own offsets and parallax factors folded into its groups':
  ;; each is a finite number, but a sum or product of them may not be
  ;; (a group and its layer both offset by 1e308), and the map would then
  ;; fail in its first frame: an error naming the file and the layer.
  (define (compose-inherited ctx node inh)
    (define (fold attr own combine how inherited)
      (let ((v (combine inherited own)))
        (if (finite? v)
            v
            (tmx-error (ctx-file ctx) "~a: ~a ~s ~a its groups' ~s is ~s, not a finite number"
                       (ctx-what ctx) attr own how inherited v))))
    (make-inherited (fold 'offsetx (attr-number ctx node 'offsetx (legacy-offset ctx node 'x))
                          + "added to" (in-offset-x inh))
                    (fold 'offsety (attr-number ctx node 'offsety (legacy-offset ctx node 'y))
                          + "added to" (in-offset-y inh))
                    (fold 'parallaxx (attr-number ctx node 'parallaxx 1) * "times" (in-parallax-x inh))
                    (fold 'parallaxy (attr-number ctx node 'parallaxy 1) * "times" (in-parallax-y inh))
                    (* (in-opacity inh) (attr-number ctx node 'opacity 1))
                    (and (in-visible? inh) (attr-bool ctx node 'visible #t))))

  (define (layer-ctx file node)
    (cons file (sprintf "~a ~s"
                        (case (car node)
                          ((layer) "layer") ((objectgroup) "object layer")
                          ((imagelayer) "image layer") (else "group"))
                        (attr-string node 'name ""))))

  ;; A layer record from its element; data is the tile layer's cells or #f;
  ;; children the group's already built children.
  (define (build-layer file node inh data w h st children)
    (let* ((ctx (layer-ctx file node))
           (eff (compose-inherited ctx node inh))
           (kind (case (car node)
                   ((layer) 'tile) ((objectgroup) 'object)
                   ((imagelayer) 'image) (else 'group)))
           (img (and (eq? kind 'image) (x-child node 'image))))
      (%make-layer kind
                   (attr-int ctx node 'id #f 0)
                   (attr-string node 'name "")
                   (attr-string node 'class "")
                   (and (eq? kind 'tile) w) (and (eq? kind 'tile) h)
                   data
                   (in-visible? eff) (in-opacity eff)
                   (attr-color ctx node 'tintcolor)
                   (in-offset-x eff) (in-offset-y eff)
                   (in-parallax-x eff) (in-parallax-y eff)
                   (attr-bool ctx node 'locked #f)
                   (parse-properties ctx node)
                   (if (eq? kind 'object)
                       (map (lambda (o) (parse-object ctx o map-gid '() st))
                            (x-children node 'object))
                       '())
                   (and (eq? kind 'object)
                        (attr-choice ctx node 'draworder
                                     '(("topdown" . topdown) ("index" . index)) 'topdown))
                   (and (eq? kind 'object) (attr-color ctx node 'color))
                   (and img (parse-image ctx img))
                   (attr-bool ctx node 'repeatx #f)
                   (attr-bool ctx node 'repeaty #f)
                   children)))

  ;; Gids written in the map itself are already in the map's gid space.
  (define (map-gid ctx raw) raw)

  ;; Rebuild the nested tree from the flat (node . inherited) list, in one
  ;; pass from the end: a layer's record goes on a stack, and a group takes
  ;; its direct children off the top of it (the entries after a group are
  ;; its contents, already built). `cells-of` is called for the tile layers
  ;; from the last to the first. Returns the top level's layers and every
  ;; layer, both in document order.
  (define (build-tree file entries cells-of st)
    (let loop ((es (reverse entries)) (stack '()) (all '()))
      (if (null? es)
          (values stack all)
          (let* ((node (caar es))
                 (inh (cdar es))
                 (group? (eq? (car node) 'group)))
            (let-values (((children rest)
                          (if group?
                              (split-at* stack (count-layer-children node))
                              (values '() stack))))
              (let* ((cells (and (eq? (car node) 'layer) (cells-of node)))
                     (layer (build-layer file node inh
                                         (and cells (car cells))
                                         (and cells (cadr cells)) (and cells (caddr cells))
                                         st children)))
                (loop (cdr es) (cons layer rest) (cons layer all))))))))

  (define (count-layer-children node)
    (let loop ((cs (cdr node)) (n 0))
      (cond ((null? cs) n)
            ((and (element? (car cs)) (memq (caar cs) '(layer objectgroup imagelayer group)))
             (loop (cdr cs) (+ n 1)))
            (else (loop (cdr cs) n)))))

  ;; The first n items of xs and the rest.
  (define (split-at* xs n)
    (let loop ((xs xs) (n n) (taken '()))
      (if (or (zero? n) (null? xs))
          (values (reverse taken) xs)
          (loop (cdr xs) (- n 1) (cons (car xs) taken)))))

  ;;; ------------------------------------------------------------------
  ;;; Loading: the map

  ;; A predicate: whether gid g belongs to some tileset (the one with the
  ;; largest first gid not above g). A gid past the last tile of that
  ;; tileset belongs to it too: Tiled loads such a map, keeps the gid when it
  ;; saves, and draws nothing there (tilemap-tileset-for answers #f for it).
  ;; Only a gid below every first gid, which Tiled refuses ("Invalid
  ;; tile"), is an error.
  (define (gid-covered-by tilesets)
    (let ((sorted (sort-tilesets tilesets)))
      (lambda (g)
        (and (pair? sorted) (<= (tileset-first-gid (car sorted)) g)))))

  (define (check-gids file layers tilesets)
    ;; cells checked with a one-entry memo
    (let ((covered? (gid-covered-by tilesets)))
      (for-each
       (lambda (entry)
         (let* ((layer (car entry))
                (data (layer-data layer))
                (w (layer-width layer))
                (n (u32vector-length data)))
           (let loop ((i 0) (last-ok 0))
             (when (fx< i n)
               (let ((g (cell-gid (u32vector-ref data i))))
                 (cond ((or (fx= g 0) (fx= g last-ok)) (loop (fx+ i 1) last-ok))
                       ((covered? g) (loop (fx+ i 1) g))
                       (else
                        (tmx-error file "layer ~s: cell (~a, ~a) has gid ~a, below the first gid of every tileset"
                                   (layer-name layer) (+ (cadr entry) (remainder i w))
                                   (+ (cddr entry) (quotient i w)) g))))))))
       layers)))

  (define (sort-tilesets tilesets)
    ;; insertion sort: maps have few tilesets
    (let loop ((l tilesets) (out '()))
      (if (null? l)
          out
          (loop (cdr l)
                (let ins ((o out))
                  (cond ((null? o) (list (car l)))
                        ((< (tileset-first-gid (car l)) (tileset-first-gid (car o)))
                         (cons (car l) o))
                        (else (cons (car o) (ins (cdr o))))))))))

  (define (check-object-gids file layers tilesets)
    (let ((covered? (gid-covered-by tilesets)))
      (for-each
       (lambda (layer)
         (for-each
          (lambda (o)
            (let ((g (object-gid o)))
              (unless (or (zero? g) (covered? g))
                (tmx-error file "object layer ~s: object ~a has gid ~a, below the first gid of every tileset"
                           (layer-name layer) (object-id o) g))))
          (layer-objects layer)))
       layers)))

;; The layer properties the collision grid reads (core/map.scm): one
  ;; that is not a bool would be read as "collides" and a misspelt one
  ;; not read at all, so the decoration collides with no word said. A
  ;; wrong type is an error; a name one slip from one of them a warning
  ;; (a game may have a property of its own of that name).
  (define grid-layer-properties '("collides" "one-way" "ladder"))

  (define (check-layer-properties path layer)
    (for-each
     (lambda (p)
       (let ((name (car p)))
         (cond ((member name grid-layer-properties)
                (unless (boolean? (cdr p))
                  (tmx-error path "layer ~s: property ~a is ~s, of type ~a, not a bool; in Tiled give it the type bool (type=\"bool\")"
                             (layer-name layer) name (cdr p) (property-type (cdr p)))))
               ((near-grid-property name)
                => (lambda (known)
                     (warn-map path "layer ~s: property ~s is not one Downstroke reads; did you mean ~s (a bool)?"
                               (layer-name layer) name known))))))
     (layer-properties layer)))

  (define (near-grid-property name)
    (let loop ((ks grid-layer-properties))
      (cond ((null? ks) #f)
            ((one-slip? name (car ks)) (car ks))
            (else (loop (cdr ks))))))

  ;; A mistake worth a word that does not stop the load, on the error port.
  (define (warn-map path fmt . args)
    (with-output-to-port (current-error-port)
      (lambda () (print "downstroke: warning: " path ": " (apply sprintf fmt args)))))

  (define (read-tilemap path)
    (let* ((root (read-root (cons path "map") path 'map))
           (ctx (cons path "map"))
           (orientation (attr-choice ctx root 'orientation
                                     '(("orthogonal" . orthogonal) ("isometric" . isometric)
                                       ("staggered" . staggered) ("hexagonal" . hexagonal))
                                     #f))
           (infinite? (attr-bool ctx root 'infinite #f))
           (map-w (attr-int ctx root 'width #f 0))
           (map-h (attr-int ctx root 'height #f 0))
           (tw (attr-int ctx root 'tilewidth #f 1))
           (th (attr-int ctx root 'tileheight #f 1))
           (st (make-state (make-hash-table equal?) (make-hash-table equal?) '() '())))
      (unless orientation (tmx-error path "the map has no orientation"))
      (unless (and tw th) (tmx-error path "the map needs tilewidth and tileheight"))
      (unless (or infinite? (and map-w map-h))
        (tmx-error path "the map needs width and height"))
      (when (and (not infinite?) (> (* map-w map-h) (tilemap-max-cells)))
        (tmx-error path "the map is ~ax~a: more than the limit of ~a cells (tilemap-max-cells)"
                   map-w map-h (tilemap-max-cells)))
      ;; Tilesets, in document order.
      (state-tilesets-set! st (map (lambda (t) (load-tileset-ref st path t))
                                   (x-children root 'tileset)))
      (let* ((entries (collect-layers ctx root top-level))
             (tile-nodes (filter (lambda (n) (eq? (car n) 'layer)) (map car entries)))
             ;; every tile layer holds the map's cells: the limit is on them all
             (_ (unless infinite?
                  (check-map-cells path (* map-w map-h (length tile-nodes)) (length tile-nodes))))
             (_ (when infinite? (check-map-cells path (declared-chunk-cells ctx tile-nodes) (length tile-nodes))))
             ;; node -> decoded data: finite: (u32vector); infinite: chunks
             (decoded
              (map (lambda (node)
                     (let* ((lctx (layer-ctx path node))
                            (data (or (x-child node 'data)
                                      (tmx-error path "~a: the layer has no <data>" (ctx-what lctx)))))
                       (let-values (((encoding compression) (data-format lctx data)))
                         (cons node
                               (if infinite?
                                   (map (lambda (ch)
                                          (let* ((cx (or (attr-int lctx ch 'x #f) 0))
                                                 (cy (or (attr-int lctx ch 'y #f) 0))
                                                 (cw (or (attr-int lctx ch 'width #f 0) 0))
                                                 (chh (or (attr-int lctx ch 'height #f 0) 0))
                                                 (cctx (sub-ctx lctx (sprintf "chunk at (~a, ~a)" cx cy))))
                                            (list cx cy cw chh
                                                  (decode-cells cctx ch encoding compression cw chh))))
                                        (x-children data 'chunk))
                                   (begin
                                     (let ((lw (attr-int lctx node 'width map-w 0))
                                           (lh (attr-int lctx node 'height map-h 0)))
                                       (unless (and (= lw map-w) (= lh map-h))
                                         (tmx-error path "~a: the layer is ~ax~a, the map is ~ax~a"
                                                    (ctx-what lctx) lw lh map-w map-h)))
                                     (decode-cells lctx data encoding compression map-w map-h)))))))
                   tile-nodes))
             (chunks (if infinite? (append-map cdr decoded) '()))
             (x0 (if (null? chunks) 0 (list-min (map car chunks))))
             (y0 (if (null? chunks) 0 (list-min (map cadr chunks))))
             (x1 (if (null? chunks) 0 (list-max (map (lambda (c) (+ (car c) (caddr c))) chunks))))
             (y1 (if (null? chunks) 0 (list-max (map (lambda (c) (+ (cadr c) (cadddr c))) chunks))))
             (w (if infinite? (- x1 x0) map-w))
             (h (if infinite? (- y1 y0) map-h)))
        (when infinite?
          (check-cells (cons path "the union of the chunks") (* w h))
          (check-map-cells path (* w h (length tile-nodes)) (length tile-nodes)))
        (let*-values
            (((pending) (reverse decoded))   ; build-tree asks from the last
             ((cells-of)
                (lambda (node)
                  (let ((d (if (and (pair? pending) (eq? (caar pending) node))
                               (let ((d (cdar pending))) (set! pending (cdr pending)) d)
                               (error 'read-tilemap "tile layers out of order"))))
                    (if infinite?
                        (let ((out (make-u32vector (* w h) 0)))
                          (for-each
                           (lambda (c)
                             (let ((cx (- (car c) x0)) (cy (- (cadr c) y0))
                                   (cw (caddr c)) (chh (cadddr c)) (v (list-ref c 4)))
                               (do ((r 0 (fx+ r 1))) ((fx= r chh))
                                 (do ((k 0 (fx+ k 1))) ((fx= k cw))
                                   (u32vector-set! out (fx+ (fx* (fx+ cy r) w) (fx+ cx k))
                                                   (u32vector-ref v (fx+ (fx* r cw) k)))))))
                           d)
                          (list out w h))
                        (list d w h)))))
             ((tree all) (build-tree path entries cells-of st))
             ((tile-layers) (filter (lambda (l) (eq? (layer-kind l) 'tile)) all))
             ((tilesets) (sort-tilesets (state-tilesets st))))
          (check-gids path (map (lambda (l) (cons l (cons x0 y0))) tile-layers) tilesets)
          (check-object-gids path (filter (lambda (l) (eq? (layer-kind l) 'object)) all) tilesets)
          (for-each (cut check-layer-properties path <>) tile-layers)
          (make-tilemap w h tw th tile-layers
                        properties: (parse-properties ctx root)
                        origin-col: x0 origin-row: y0
                        tilesets: tilesets
                        layer-tree: tree
                        info: (list (cons 'source path)
                                    (cons 'version (x-attr root 'version))
                                    (cons 'tiled-version (x-attr root 'tiledversion))
                                    (cons 'class (attr-string root 'class ""))
                                    (cons 'orientation orientation)
                                    (cons 'render-order
                                          (attr-choice ctx root 'renderorder
                                                       '(("right-down" . right-down)
                                                         ("right-up" . right-up)
                                                         ("left-down" . left-down)
                                                         ("left-up" . left-up))
                                                       'right-down))
                                    (cons 'infinite? infinite?)
                                    (cons 'hex-side-length (attr-int ctx root 'hexsidelength #f 0))
                                    (cons 'stagger-axis (attr-choice ctx root 'staggeraxis
                                                                     '(("x" . x) ("y" . y)) #f))
                                    (cons 'stagger-index (attr-choice ctx root 'staggerindex
                                                                      '(("odd" . odd) ("even" . even)) #f))
                                    (cons 'parallax-origin-x (attr-number ctx root 'parallaxoriginx 0))
                                    (cons 'parallax-origin-y (attr-number ctx root 'parallaxoriginy 0))
                                    (cons 'background-color (attr-color ctx root 'backgroundcolor))))))))

  ;; Load a TMX map. Every failure is an error naming the file and the problem.
  (define (load-tilemap path)
    (unless (string? path)
      (error 'load-tilemap "the path must be a string" path))
    (with-tmx-context path "cannot load the map"
      (lambda ()
        (let ((why (unreadable-file path)))
          (cond ((equal? why "not found") (tmx-error path "no such file"))
                (why (tmx-error path "the map ~a" why))))
        (read-tilemap path))))

  ;; A .tsx file on its own: the sprites of a scene without a map
  ;; (make-sprite-scene tileset:). Its gids start at first-gid, as in a map
  ;; that listed the file there, so 1 is its first tile by default. Errors
  ;; are the loader's: they name the file and what is wrong.
  (define/keywords (load-tileset path #!key (first-gid 1))
    (unless (string? path)
      (error 'load-tileset "the path must be a string" path))
    (check-integer 'load-tileset "" "first-gid:" first-gid 1)
    (parameterize ((loader 'load-tileset))
      (with-tmx-context path "cannot load the tileset"
        (lambda ()
          (let ((why (unreadable-file path)))
            (cond ((equal? why "not found") (tmx-error path "no such file"))
                  (why (tmx-error path "the tileset ~a" why))))
          (let ((path (normalize-pathname path)))
            (parse-tileset path (read-root (cons path "tileset") path 'tileset)
                           first-gid path)))))))
