;;; Writes the Makefile's view of the build graph from downstroke.egg, the
;;; one place that states it: the modules in the egg's order, each one's
;;; source file (SOURCE_name), the C files it includes, the modules it depends on, and its
;;; csc and link options. The Makefile includes what this prints
;;; (build/graph.mk) and remakes it when the .egg changes.
;;;   csi -q -s tools/egg-graph.scm downstroke.egg > build/graph.mk

(import scheme (chicken base) (chicken process-context) (chicken string) (chicken format))

(define (property component key)
  (let ((p (assq key (cddr component)))) (if p (cdr p) '())))

(define (module-name symbol)          ; downstroke.physics -> "physics"
  (let ((s (symbol->string symbol)))
    (substring s (string-length "downstroke.") (string-length s))))

;; The library's modules: every extension but the static builds' linker
;; scripts (downstroke.X-libraries, which have no modules).
(define (library-modules egg)
  (let loop ((cs (cdr (assq 'components egg))) (out '()))
    (cond ((null? cs) (reverse out))
          ((and (eq? (caar cs) 'extension) (not (assq 'linkage (cddr (car cs)))))
           (loop (cdr cs) (cons (car cs) out)))
          (else (loop (cdr cs) out)))))

(define (words strings) (string-intersperse strings " "))

(define (write-graph egg)
  (let ((modules (library-modules egg)))
    (print "# Written by tools/egg-graph.scm from downstroke.egg; edit the .egg, not this.")
    (print "MODULES := " (words (map (lambda (c) (module-name (cadr c))) modules)))
    (for-each
     (lambda (c)
       (let ((name (module-name (cadr c))))
         (print "SOURCE_" name " := " (words (property c 'source)))
         (print "FLAGS_" name " := " (words (append (property c 'csc-options) (property c 'link-options))))
         (print "$(BUILD)/downstroke." name ".so: "
                (words (append (property c 'source)
                               (property c 'source-dependencies)
                               (map (lambda (d) (sprintf "$(BUILD)/downstroke.~a.so" (module-name d)))
                                    (property c 'component-dependencies)))))))
     modules)))

(write-graph (with-input-from-file (car (command-line-arguments)) read))
