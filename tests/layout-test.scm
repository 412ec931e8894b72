;;; The library's layout: the pure core loads no C library, and the two
;;; statements of the build graph (downstroke.egg for chicken-install, the
;;; Makefile for make) agree with each other and with the modules' own
;;; imports, so neither can go stale.

(import scheme (chicken base) (chicken io) (chicken string) (chicken file)
        (chicken pathname) (chicken process) (chicken sort) (chicken format)
        (downstroke test))

(define (filter-map* f ls)
  (if (null? ls) '() (let ((v (f (car ls)))) (if v (cons v (filter-map* f (cdr ls))) (filter-map* f (cdr ls))))))
(define (filter-words ok? ls)
  (cond ((null? ls) '()) ((ok? (car ls)) (cons (car ls) (filter-words ok? (cdr ls)))) (else (filter-words ok? (cdr ls)))))
(define (find* ok? ls) (cond ((null? ls) #f) ((ok? (car ls)) (car ls)) (else (find* ok? (cdr ls)))))
(define (ly-make-deps name)
  (let ((l (find* (lambda (l) (string-prefix? (sprintf "$(BUILD)/downstroke.~a.so:" name) l)) ly-make-lines)))
    (if l
        (sort (map (lambda (w) (substring w 20 (- (string-length w) 3)))
                   (filter-words (lambda (w) (string-prefix? "$(BUILD)/downstroke." w)) (cdr (string-split l))))
              string<?)
        '())))
(define (delete* x ls) (cond ((null? ls) '()) ((equal? x (car ls)) (delete* x (cdr ls))) (else (cons (car ls) (delete* x (cdr ls))))))

;; A file's text without its ; comments (no module name sits in a string).
(define (ly-code file)
  (string-intersperse
   (map (lambda (line) (let ((i (substring-index ";" line))) (if i (substring line 0 i) line)))
        (with-input-from-file file read-lines))
   "\n"))

;; The (downstroke NAME) modules a source file imports, as sorted strings.
(define (ly-imports file)
  (let loop ((text (ly-code file)) (out '()))
    (let ((i (substring-index "(downstroke " text)))
      (if (not i)
          (sort (ly-dedupe out) string<?)
          (let* ((rest (substring text (+ i 12)))
                 (end (let scan ((j 0))
                        (if (memv (string-ref rest j) '(#\) #\space #\newline)) j (scan (+ j 1)))))
                 (name (substring rest 0 end)))
            (loop rest (cons name out)))))))

(define (ly-dedupe ls)
  (cond ((null? ls) '())
        ((member (car ls) (cdr ls)) (ly-dedupe (cdr ls)))
        (else (cons (car ls) (ly-dedupe (cdr ls))))))

(define (ly-strip-prefix s) (if (string-prefix? "downstroke." s) (substring s 11) s))
(define (string-prefix? p s) (and (>= (string-length s) (string-length p))
                                  (string=? p (substring s 0 (string-length p)))))
(define (string-suffix? p s) (and (>= (string-length s) (string-length p))
                                  (string=? p (substring s (- (string-length s) (string-length p))))))

;; The .egg's library modules (the -libraries linker-script companions
;; aside), each with its sorted component-dependencies.
(define ly-egg
  (let ((egg (with-input-from-file "../downstroke.egg" read)))
    (filter-map*
     (lambda (c)
       (let ((name (ly-strip-prefix (symbol->string (cadr c)))))
         (and (eq? (car c) 'extension) (not (string-suffix? "-libraries" name))
              (cons name (sort (map (lambda (d) (ly-strip-prefix (symbol->string d)))
                                    (cond ((assq 'component-dependencies (cddr c)) => cdr)
                                          (else '())))
                               string<?)))))
     (cdr (assq 'components egg)))))


;; The Makefile's MODULES and its "$(BUILD)/downstroke.X.so: deps" lines.
(define ly-make-lines (with-input-from-file "../Makefile" read-lines))
(define ly-make-modules
  (let ((l (find* (lambda (l) (string-prefix? "MODULES :=" l)) ly-make-lines)))
    (sort (cddr (string-split l)) string<?)))

(test-group "layout: one build graph"
  (test "the Makefile builds the .egg's modules" (sort (map car ly-egg) string<?) ly-make-modules)
  (for-each
   (lambda (m)
     (let ((imports (delete* (car m) (ly-imports (string-append "../" (car m) ".scm")))))
       (test (sprintf "~a: the .egg's dependencies are its imports" (car m)) imports (cdr m))
       (test (sprintf "~a: the Makefile's dependencies are its imports" (car m)) imports
             (ly-make-deps (car m)))))
   ly-egg))


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
                  (append (glob "../*.scm") (glob "../*.c") (glob "../*.h")))))
    (test "only sdl2.scm calls SDL_PollEvent" '("../sdl2.scm") readers)))

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
         (cases '((engine game level input) (tilemap map objects)))
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
          (let ((names (md-sibling-only (sprintf "../~a.scm" m))))   ; the doc tool's reading
            (test-assert (sprintf "~a.scm marks some names for its siblings" m) (pair? names))
            (for-each (lambda (n)
                        (test (sprintf "(downstroke ~a) does not offer ~a's ~a" (car c) m n) #f
                              (exported? (car c) n)))
                      names)))
        (cdr c)))
     cases)
    (test-assert "and the check can see a name that is offered"
                 (exported? 'tilemap 'make-tilemap))))
