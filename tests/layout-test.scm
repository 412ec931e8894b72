;;; The library's layout: the folders are its layers and imports point only
;;; down; downstroke.egg, the one statement of the build graph (the Makefile
;;; reads it through tools/egg-graph.scm), agrees with the modules' own
;;; imports; the pure core loads no C library.

(import scheme (chicken base) (chicken io) (chicken string) (chicken file)
        (chicken pathname) (chicken process) (chicken sort) (chicken format)
        (downstroke test))

(define (filter-words ok? ls)
  (cond ((null? ls) '()) ((ok? (car ls)) (cons (car ls) (filter-words ok? (cdr ls)))) (else (filter-words ok? (cdr ls)))))
(define (find* ok? ls) (cond ((null? ls) #f) ((ok? (car ls)) (car ls)) (else (find* ok? (cdr ls)))))
(define (delete* x ls) (cond ((null? ls) '()) ((equal? x (car ls)) (delete* x (cdr ls))) (else (cons (car ls) (delete* x (cdr ls))))))
(define (dedupe ls)
  (cond ((null? ls) '()) ((member (car ls) (cdr ls)) (dedupe (cdr ls))) (else (cons (car ls) (dedupe (cdr ls))))))

;; The layers, lowest first, each a folder; two folders of one rank sit side
;; by side and may not import each other.
(define layer-ranks '(("base" . 0) ("core" . 1) ("physics" . 2) ("tiled" . 2) ("shell" . 3)))

;; A file's text without its ; comments (no module name sits in a string).
(define (code-of file)
  (string-intersperse
   (map (lambda (line) (let ((i (substring-index ";" line))) (if i (substring line 0 i) line)))
        (with-input-from-file file read-lines))
   "\n"))

;; The (downstroke NAME) modules a source file names, as sorted strings.
(define (imports-of file)
  (let loop ((text (code-of file)) (out '()))
    (let ((i (substring-index "(downstroke " text)))
      (if (not i)
          (sort (dedupe out) string<?)
          (let* ((rest (substring text (+ i 12)))
                 (end (let scan ((j 0))
                        (if (memv (string-ref rest j) '(#\) #\space #\newline)) j (scan (+ j 1)))))
                 (name (substring rest 0 end)))
            (loop rest (cons name out)))))))

(define (strip-prefix s) (if (substring-index "downstroke." s) (substring s 11) s))

;; The .egg's modules (the static builds' linker scripts aside): each as
;; (name source-file sorted-dependencies).
(define egg-modules
  (let ((egg (with-input-from-file "../downstroke.egg" read)))
    (foldr (lambda (c out)
             (if (and (eq? (car c) 'extension) (not (assq 'linkage (cddr c))))
                 (cons (list (strip-prefix (symbol->string (cadr c)))
                             (string-append "../" (cadr (assq 'source (cddr c))))
                             (sort (map (lambda (d) (strip-prefix (symbol->string d)))
                                        (cond ((assq 'component-dependencies (cddr c)) => cdr) (else '())))
                                   string<?))
                       out)
                 out))
           '()
           (cdr (assq 'components egg)))))

(define (module-file name) (cadr (assoc name egg-modules)))
(define (layer-of file) (cadr (string-split file "/")))    ; "../core/map.scm" -> "core"

(test-group "layout: the .egg states the build graph"
  (test "every module file of a layer folder is in the .egg"
        (sort (apply append (map (lambda (l) (glob (sprintf "../~a/*.scm" (car l)))) layer-ranks)) string<?)
        (sort (map cadr egg-modules) string<?))
  (for-each
   (lambda (m)
     (test (sprintf "~a: the .egg's dependencies are its imports" (car m))
           (delete* (car m) (imports-of (cadr m)))
           (caddr m)))
   egg-modules))

(define (rank-of layer) (cdr (assoc layer layer-ranks)))

;; The modules of deps that a module of layer may not import: those of
;; another folder whose rank is not lower.
(define (upward-imports layer deps)
  (filter-words (lambda (d)
                  (let ((other (layer-of (module-file d))))
                    (not (or (string=? other layer) (< (rank-of other) (rank-of layer))))))
                deps))

(test-group "layout: imports point down the layers"
  (for-each
   (lambda (m)
     (test (sprintf "~a (~a/) imports only from its folder and lower layers" (car m) (layer-of (cadr m)))
           '() (upward-imports (layer-of (cadr m)) (caddr m))))
   egg-modules)
  (test "the rule sees an import upward and one sideways" '("engine" "tmx")
        (upward-imports "physics" '("entity" "broadphase" "engine" "tmx"))))

;; A child csi imports the pure modules and reads its own memory map.
(test-group "layout: the pure core loads no C library"
  (let* ((path (string-intersperse
                (map (lambda (d) (if (absolute-pathname? d) d (normalize-pathname (make-pathname (current-directory) d))))
                     (repository-path))
                ":"))
         (program "(import (downstroke entity) (downstroke physics) (downstroke scene) (downstroke tween) (downstroke animation) (downstroke map) (downstroke overlap) (downstroke camera) (downstroke check) (downstroke particles) (chicken io)) (for-each print (with-input-from-file \"/proc/self/maps\" read-lines))")
         (maps (with-input-from-pipe
                (sprintf "CHICKEN_REPOSITORY_PATH=~a csi -q -e ~a" (qs path) (qs program))
                read-lines))
         (loaded? (lambda (lib) (and (find* (lambda (l) (substring-index lib l)) maps) #t))))
    (test-assert "the child ran (its map shows libchicken)" (loaded? "libchicken"))
    (for-each (lambda (lib) (test (sprintf "~a is not loaded" lib) #f (loaded? lib)))
              '("libexpat" "libz.so" "libzstd" "libSDL2-2" "libSDL2_image" "libSDL2_mixer" "libSDL2_ttf"))))

;; SDL's event queue has one reader, (downstroke sdl2)'s poll-event!: two
;; pumps would each see only some of the events.
(test-group "layout: one SDL event pump"
  (let ((readers (filter-words
                  (lambda (file) (substring-index "SDL_PollEvent" (with-input-from-file file read-string)))
                  (apply append (map (lambda (l) (append (glob (sprintf "../~a/*.scm" (car l))) (glob (sprintf "../~a/*.c" (car l)))
                                                     (glob (sprintf "../~a/*.h" (car l)))))
                                    layer-ranks)))))
    (test "only sdl2.scm calls SDL_PollEvent" '("../shell/sdl2.scm") readers)))

;; docs/modules.org is what tools/make-modules-doc.scm writes from the
;; modules' own export lists.
(test-group "layout: docs/modules.org lists every module's exports"
  (load "../tools/make-modules-doc.scm")
  (test "docs/modules.org is current (csi -q -s tools/make-modules-doc.scm --write)"
        (md-text "..")
        (with-input-from-file "../docs/modules.org" read-string)))

;; Names exported only for sibling modules (after ";; for sibling modules
;; only" in an export list, as tools/make-modules-doc.scm reads them) are
;; not passed on by the modules games import for them.
(test-group "layout: names for sibling modules stay out of what games import"
  (let* ((path (string-intersperse
                (map (lambda (d) (if (absolute-pathname? d) d (normalize-pathname (make-pathname (current-directory) d))))
                     (repository-path))
                ":"))
         ;; each facade, and the modules whose sibling-only names it must not offer
         (cases '((engine game level input) (tilemap map objects) (physics tile-grid escape tile-collisions body)))
         (exported?
          (lambda (facade name)
            ;; `only` of a name the module does not export is only a
            ;; warning: the name must also be bound after the import
            (let ((program (sprintf "(import (only (downstroke ~a) ~a)) (print (if ~a 'yes 'no))" facade name name)))
              (equal? '("yes")
                      (with-input-from-pipe
                       (sprintf "CHICKEN_REPOSITORY_PATH=~a csi -q -e ~a 2>/dev/null" (qs path) (qs program))
                       read-lines))))))
    (for-each
     (lambda (c)
       (for-each
        (lambda (m)
          (let ((names (md-sibling-only (module-file (symbol->string m)))))   ; the doc tool's reading
            (test-assert (sprintf "~a.scm marks some names for its siblings" m) (pair? names))
            (for-each (lambda (n)
                        (test (sprintf "(downstroke ~a) does not offer ~a's ~a" (car c) m n) #f
                              (exported? (car c) n)))
                      names)))
        (cdr c)))
     cases)
    (test-assert "and the check can see a name that is offered"
                 (exported? 'tilemap 'make-tilemap))))
