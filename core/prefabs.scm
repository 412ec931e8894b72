;;; (downstroke prefabs): entity templates read from a data file.
;;;
;;; The file holds one form, read with CHICKEN's reader and never
;;; evaluated:
;;;
;;;   ((mixins
;;;     (solid   #:solid? #t #:immovable? #t)
;;;     (enemy   #:tags (enemy) #:hp 3))
;;;    (prefabs
;;;     (goblin  enemy animated #:width 16 #:height 16
;;;              #:animations ((#:name walk #:frames (28 29) #:duration 10)))
;;;     (crate   solid #:width 16 #:height 16 #:tile-id 7)))
;;;
;;; A mixin is a name and a plist. A prefab is a name, the names of the
;;; mixins it uses, then its own plist. Either section may be left out;
;;; names are symbols and must be unique within their section.
;;;
;;; (instantiate-prefab prefabs name overrides: ...) builds the entity
;;; alist, each layer replacing the keys of the ones before it:
;;;   1. #:type, set to the prefab's name;
;;;   2. the mixins, in the order the prefab lists them;
;;;   3. the prefab's own keys;
;;;   4. the overrides (a plist or a keyword alist).
;;; Keys keep the position where they first appeared. Afterwards an
;;; #:anim-name of #f (what the `animated` mixin sets) becomes the name of
;;; the entity's first animation, when it has #:animations.
;;;
;;; Nested plists become alists as they are read: a value that is a plist
;;; becomes an alist, and a value that is a list of plists becomes a list of
;;; alists, at any depth. So #:animations above becomes
;;;   (((#:name . walk) (#:frames . (28 29)) (#:duration . 10)))
;;; which is what (downstroke animation) reads. Other lists, such as
;;; #:frames or #:tags, are kept as they are.
;;;
;;; engine-mixins are available to every file (a file's mixin of the same
;;; name replaces one of them):
;;;   animated   #:anim-name #f  #:anim-frame 0  #:anim-tick 0
;;;
;;; Errors name the file and the entry: a file that is missing or does not
;;; parse, a malformed section or entry, a prefab using an unknown mixin
;;; (all raised by load-prefabs), and an unknown prefab (raised by
;;; instantiate-prefab).

(module (downstroke prefabs)
  (load-prefabs parse-prefabs prefabs? prefabs-source prefab-names mixin-names
   instantiate-prefab engine-mixins nested-plists->alists)

  (import (downstroke keywords))
  (import scheme (chicken base) (chicken format) (chicken keyword)
          (chicken condition) (chicken file) (chicken io)
          (only (downstroke entity) as-entity)
          (only (downstroke util) make-hash-table hash-table-ref/default
                hash-table-set! hash-table-exists? every))

  (define engine-mixins
    (list (cons 'animated
                (list (cons #:anim-name #f) (cons #:anim-frame 0)
                      (cons #:anim-tick 0)))))

  ;; source: the file name (or a label for data given directly).
  (define-record-type prefabs
    (%make-prefabs source mixins mixin-order table order)
    prefabs?
    (source prefabs-source)
    (mixins prefabs-mixins)         ; name -> alist
    (mixin-order prefabs-mixin-order)
    (table prefabs-table)           ; name -> (mixin-names . alist)
    (order prefabs-order))

  (define (prefab-names p) (prefabs-order p))
  (define (mixin-names p) (prefabs-mixin-order p))

  ;;; ------------------------------------------------------------------
  ;;; Nested plists

  (define (plist? x)
    (and (pair? x)
         (let loop ((x x))
           (or (null? x)
               (and (pair? x) (keyword? (car x)) (pair? (cdr x))
                    (loop (cddr x)))))))

  (define (nested-plists->alists v)
    (cond ((plist? v)
           (let loop ((x v) (out '()))
             (if (null? x)
                 (reverse out)
                 (loop (cddr x)
                       (cons (cons (car x) (nested-plists->alists (cadr x))) out)))))
          ((and (pair? v) (list? v) (every plist? v))
           (map nested-plists->alists v))
          (else v)))

  ;;; ------------------------------------------------------------------
  ;;; Parsing

  (define (fail who source fmt . args)
    (error who (sprintf "~a: ~a" source (apply sprintf fmt args))))

  ;; A plist of one entry -> alist, checked. what: "mixin foo" etc.
  (define (entry-plist who source what plist)
    (let loop ((x plist) (out '()))
      (cond ((null? x) (reverse out))
            ((not (pair? x))
             (fail who source "~a: malformed entry (not a proper list)" what))
            ((not (keyword? (car x)))
             (fail who source "~a: malformed entry: expected a keyword, got ~s" what (car x)))
            ((not (pair? (cdr x)))
             (fail who source "~a: malformed entry: key ~s has no value" what (car x)))
            ((assq (car x) out)
             (fail who source "~a: malformed entry: key ~s given twice" what (car x)))
            (else
             (loop (cddr x)
                   (cons (cons (car x) (nested-plists->alists (cadr x))) out))))))

  (define (entry-name who source section entry)
    (unless (and (pair? entry) (list? entry))
      (fail who source "~a: malformed entry ~s (expected (name ...))" section entry))
    (unless (symbol? (car entry))
      (fail who source "~a: malformed entry: the name must be a symbol, got ~s"
            section (car entry)))
    (car entry))

  ;; data: the form the file holds.
  (define/keywords (parse-prefabs data #!key (source "<prefab data>") (who 'parse-prefabs))
    (let ((mixins (make-hash-table equal?))
          (table (make-hash-table equal?))
          (mixin-order '())
          (order '())
          (seen '()))
      (for-each (lambda (m) (hash-table-set! mixins (car m) (cdr m))) engine-mixins)
      (unless (list? data)
        (fail who source "malformed file: expected ((mixins ...) (prefabs ...)), got ~s" data))
      (for-each
       (lambda (section)
         (unless (and (pair? section) (list? section) (memq (car section) '(mixins prefabs)))
           (fail who source "malformed section ~s (expected (mixins ...) or (prefabs ...))"
                 (if (pair? section) (car section) section)))
         (when (memq (car section) seen)
           (fail who source "malformed file: section ~a given twice" (car section)))
         (set! seen (cons (car section) seen)))
       data)
      ;; Mixins first, so prefabs may use mixins whichever section comes first.
      (let ((section (assq 'mixins data)))
        (when section
          (for-each
           (lambda (entry)
             (let* ((name (entry-name who source "mixins" entry))
                    (what (sprintf "mixin ~a" name)))
               (when (memq name mixin-order)
                 (fail who source "~a: malformed entry: defined twice" what))
               (hash-table-set! mixins name (entry-plist who source what (cdr entry)))
               (set! mixin-order (cons name mixin-order))))
           (cdr section))))
      (let ((section (assq 'prefabs data)))
        (when section
          (for-each
           (lambda (entry)
             (let* ((name (entry-name who source "prefabs" entry))
                    (what (sprintf "prefab ~a" name)))
               (when (memq name order)
                 (fail who source "~a: malformed entry: defined twice" what))
               (let loop ((x (cdr entry)) (used '()))
                 (cond ((or (null? x) (keyword? (car x)))
                        (hash-table-set! table name
                                         (cons (reverse used)
                                               (entry-plist who source what x))))
                       ((symbol? (car x))
                        (unless (hash-table-exists? mixins (car x))
                          (fail who source "~a: unknown mixin ~a (known: ~s)"
                                what (car x)
                                (append (reverse mixin-order)
                                        (filter-out (map car engine-mixins) mixin-order))))
                        (loop (cdr x) (cons (car x) used)))
                       (else
                        (fail who source
                              "~a: malformed entry: expected a mixin name or a keyword, got ~s"
                              what (car x)))))
               (set! order (cons name order))))
           (cdr section))))
      (%make-prefabs source mixins (reverse mixin-order) table (reverse order))))

  (define (filter-out names exclude)
    (let loop ((n names) (out '()))
      (cond ((null? n) (reverse out))
            ((memq (car n) exclude) (loop (cdr n) out))
            (else (loop (cdr n) (cons (car n) out))))))

  (define (load-prefabs path)
    (unless (string? path)
      (error 'load-prefabs "the prefab file must be a string" path))
    (unless (and (file-exists? path) (not (directory-exists? path)))
      (fail 'load-prefabs path "cannot open the prefab file (no such file)"))
    (let ((data
           (handle-exceptions exn
               (fail 'load-prefabs path "does not parse: ~a"
                     (if (condition? exn)
                         ((condition-property-accessor 'exn 'message "") exn)
                         exn))
             (call-with-input-file path
               (lambda (port)
                 (let ((form (read port)))
                   (when (eof-object? form)
                     (error 'read "the file is empty"))
                   (unless (eof-object? (read port))
                     (error 'read "more than one form (expected ((mixins ...) (prefabs ...)))"))
                   form))))))
      (parse-prefabs data source: path who: 'load-prefabs)))

  ;;; ------------------------------------------------------------------
  ;;; Instantiation

  ;; Later layers replace values; a key keeps its first position.
  (define (merge acc alist)
    (let loop ((rest alist) (acc acc))
      (if (null? rest)
          acc
          (let ((key (caar rest)) (value (cdar rest)))
            (loop (cdr rest)
                  (if (assq key acc)
                      (map (lambda (p) (if (eq? (car p) key) (cons key value) p)) acc)
                      (append acc (list (cons key value)))))))))

  (define (override-alist prefabs name overrides)
    (cond ((null? overrides) '())
          ((and (pair? overrides) (keyword? (car overrides)))
           (entry-plist 'instantiate-prefab (prefabs-source prefabs)
                        (sprintf "prefab ~a: overrides" name) overrides))
          ((and (list? overrides)
                (every (lambda (p) (and (pair? p) (keyword? (car p)))) overrides))
           overrides)
          (else
           (fail 'instantiate-prefab (prefabs-source prefabs)
                 "prefab ~a: overrides must be a plist or a keyword alist, got ~s"
                 name overrides))))

  (define (resolve-anim-name e)
    (let ((p (assq #:anim-name e))
          (anims (let ((a (assq #:animations e))) (and a (cdr a)))))
      (if (and p (not (cdr p)) (pair? anims) (pair? (car anims)))
          (let ((first-name (let ((n (assq #:name (as-entity (car anims)))))
                              (and n (cdr n)))))
            (merge e (list (cons #:anim-name first-name))))
          e)))

  (define/keywords (instantiate-prefab prefabs name #!key (overrides '()))
    (unless (prefabs? prefabs)
      (error 'instantiate-prefab "not a prefab collection (see load-prefabs)" prefabs))
    (let ((entry (hash-table-ref/default (prefabs-table prefabs) name #f)))
      (unless entry
        (fail 'instantiate-prefab (prefabs-source prefabs)
              "no prefab named ~s (known: ~s)" name (prefab-names prefabs)))
      (let* ((e (list (cons #:type name)))
             (e (let loop ((ms (car entry)) (e e))
                  (if (null? ms)
                      e
                      (loop (cdr ms)
                            (merge e (hash-table-ref/default (prefabs-mixins prefabs)
                                                             (car ms) '()))))))
             (e (merge e (cdr entry)))
             (e (merge e (override-alist prefabs name overrides))))
        (resolve-anim-name e)))))
