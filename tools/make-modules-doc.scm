;;; Writes docs/modules.org: every module of the library, what it is for
;;; (the first line of its file) and every name it exports, in the order of
;;; its export list. tests/layout-test.scm checks that the file is what
;;; this would write, so the list never goes stale; after changing an
;;; export list, run from the repository root:
;;;   csi -q -s tools/make-modules-doc.scm --write

(import scheme (chicken base) (chicken io) (chicken string) (chicken sort) (chicken port)
        (chicken file) (chicken pathname) (chicken process-context) (chicken format))

;; The names a module exports only for its sibling modules: those after the
;; comment ";; for sibling modules only" in its export list, which the
;; source puts last.
(define md-marker ";; for sibling modules only")

(define (md-sibling-only file)
  (let* ((text (with-input-from-file file read-string))
         (start (substring-index "(module " text))
         (imports (and start (substring-index "(import" text start)))
         (marker (and start (substring-index md-marker text start))))
    (if (and marker imports (< marker imports))
        (let* ((after (substring text marker imports))
               (lines (cdr (string-split after "\n" #t)))
               (code (string-intersperse
                      (map (lambda (l) (let ((i (substring-index ";" l))) (if i (substring l 0 i) l)))
                           lines)
                      "\n")))
          (with-input-from-string (string-append "(" code) read))
        '())))

;; The (module NAME (EXPORT ...) ...) form of a file, or #f.
(define (md-module-form file)
  (with-input-from-file file
    (lambda ()
      (let loop ()
        (let ((x (read)))
          (cond ((eof-object? x) #f)
                ((and (pair? x) (eq? (car x) 'module)) x)
                (else (loop))))))))

;; The first sentence of the file's head comment, without
;; ";;; (downstroke NAME): ", capitalised.
(define (md-summary file)
  (let* ((head (let loop ((ls (with-input-from-file file read-lines)) (out '()))
                 (if (and (pair? ls) (>= (string-length (car ls)) 4)
                          (string=? ";;; " (substring (car ls) 0 4)))
                     (loop (cdr ls) (cons (substring (car ls) 4) out))
                     (string-intersperse (reverse out) " "))))
         (i (substring-index "): " head))
         (text (if i (substring head (+ i 3)) head))
         (end (substring-index ". " text))
         (sentence (if end (substring text 0 (+ end 1)) text)))
    (if (string=? sentence "")
        sentence
        (string-append (string (char-upcase (string-ref sentence 0))) (substring sentence 1)))))

;; Re-exported modules, for a module whose body is (reexport M ...).
(define (md-reexports form)
  (let loop ((body (cdddr form)))
    (cond ((null? body) '())
          ((and (pair? (car body)) (eq? (caar body) 'reexport))
           ;; (except M name ...) re-exports M without those names
           (map (lambda (spec) (if (memq (car spec) '(except only)) (cadr spec) spec))
                (cdar body)))
          (else (loop (cdr body))))))

(define (md-name m) (sprintf "(~a)" (string-intersperse (map ->string m) " ")))

;; Names as =name=, several to a line.
(define (md-names names)
  (let loop ((ns names) (line "") (out '()))
    (if (null? ns)
        (reverse (if (string=? line "") out (cons line out)))
        (let* ((w (sprintf "=~a=" (car ns)))
               (next (if (string=? line "") w (string-append line " " w))))
          (if (> (string-length next) 76)
              (loop (cdr ns) w (cons line out))
              (loop (cdr ns) next out))))))

(define (md-text root)
  (let* ((files (map (lambda (source) (make-pathname root source)) (md-egg-sources root)))
         (modules (let loop ((fs files) (out '()))
                    (if (null? fs) (reverse out)
                        (let ((form (md-module-form (car fs))))
                          (loop (cdr fs) (if form (cons (cons (car fs) form) out) out)))))))
    (string-intersperse
     (append
      (list "#+TITLE: Modules and their exports"
            ""
            "Every module of the library, in the order of downstroke.egg (its layers,"
            "lowest first: base, core, physics, tiled, shell), with its file, what it"
            "is for and every name it exports, in the order of its export list. Games"
            "import the modules the other documents name. A few names are exported"
            "only because a sibling module needs them (CHICKEN has no narrower"
            "export): the source puts them last in its export list, after the comment"
            "=;; for sibling modules only=, they are listed apart below, and the"
            "modules games import for them ((downstroke engine), (downstroke"
            "tilemap)) do not pass them on. This file is written by"
            "=tools/make-modules-doc.scm= and checked by =tests/layout-test.scm=."
            "")
      (append-map*
       (lambda (entry)
         (let* ((file (md-relative root (car entry)))
                (form (cdr entry))
                (siblings (md-sibling-only (car entry)))
                (exports (md-without (caddr form) siblings))
                (re (md-reexports form)))
           (append
            (list (sprintf "* ~a, =~a=" (md-name (cadr form)) file)
                  (md-summary (car entry)))
            (if (null? re) '()
                (list (sprintf "Re-exports ~a."
                               (string-intersperse (map md-name re) ", "))))
            (if (null? exports) '() (cons "" (md-names (map ->string exports))))
            (if (null? siblings) '()
                (cons "" (cons "For sibling modules only, not for games:"
                               (md-names (map ->string siblings)))))
            (list ""))))
       modules))
     "\n")))

;; The source files of the .egg's modules, in its order (the static builds'
;; linker scripts aside).
(define (md-egg-sources root)
  (let ((egg (with-input-from-file (make-pathname root "downstroke.egg") read)))
    (let loop ((cs (cdr (assq 'components egg))) (out '()))
      (cond ((null? cs) (reverse out))
            ((assq 'linkage (cddar cs)) (loop (cdr cs) out))
            (else (loop (cdr cs) (cons (cadr (assq 'source (cddar cs))) out)))))))

(define (md-relative root file)
  (let ((prefix (string-append root "/")))
    (if (and (> (string-length file) (string-length prefix))
             (string=? prefix (substring file 0 (string-length prefix))))
        (substring file (string-length prefix))
        file)))

(define (md-without names drop)
  (let loop ((ns names) (out '()))
    (cond ((null? ns) (reverse out))
          ((memq (car ns) drop) (loop (cdr ns) out))
          (else (loop (cdr ns) (cons (car ns) out))))))

(define (append-map* f ls) (if (null? ls) '() (append (f (car ls)) (append-map* f (cdr ls)))))

(when (member "--write" (command-line-arguments))
  (with-output-to-file "docs/modules.org" (lambda () (display (md-text ".")))))
