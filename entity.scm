;;; (downstroke entity): entities as keyword alists.
;;;
;;; An entity is an alist keyed by CHICKEN keywords:
;;;   ((#:type . player) (#:x . 100) (#:y . 50) ...)
;;; Every operation returns a new entity and never changes its argument.
;;; `entity-set` replaces a key's pair in a copy of the list up to that pair
;;; and shares the rest, so an entity never grows by shadowing pairs, however
;;; many frames it lives.

(module (downstroke entity)
  (entity-ref entity-set entity-update entity-remove
   make-entity plist->entity entity->plist as-entity entity?
   entity-type entity-tags entity-has-tag? entity-label
   entity-skips-pipeline? define-pipeline
   entity-number check-entity-number)

  (import scheme (chicken base) (chicken keyword) (chicken format))

  (define (entity-ref e key #!optional (default #f))
    (let ((p (assq key e)))
      (if p (cdr p) default)))

  ;; Copy the pairs before `key`, replace its pair, share the tail.
  ;; A key not present yet is added at the front.
  (define (entity-set e key value)
    (let loop ((rest e) (before '()))
      (cond ((null? rest) (cons (cons key value) e))
            ((eq? (caar rest) key)
             (let rebuild ((before before) (out (cons (cons key value) (cdr rest))))
               (if (null? before)
                   out
                   (rebuild (cdr before) (cons (car before) out)))))
            (else (loop (cdr rest) (cons (car rest) before))))))

  (define (entity-update e key proc #!optional (default #f))
    (entity-set e key (proc (entity-ref e key default))))

  (define (entity-remove e key)
    (let loop ((rest e) (before '()))
      (cond ((null? rest) e)
            ((eq? (caar rest) key)
             (let rebuild ((before before) (out (cdr rest)))
               (if (null? before)
                   out
                   (rebuild (cdr before) (cons (car before) out)))))
            (else (loop (cdr rest) (cons (car rest) before))))))

  (define (make-entity x y w h)
    (list (cons #:x x) (cons #:y y) (cons #:width w) (cons #:height h)
          (cons #:vx 0) (cons #:vy 0)))

  ;; Users write entities as plists, the way the physics contract shows them.
  (define (plist->entity plist)
    (let loop ((rest plist) (out '()))
      (cond ((null? rest) (reverse out))
            ((not (keyword? (car rest)))
             (error 'plist->entity "entity plist: expected a keyword, got" (car rest)))
            ((null? (cdr rest))
             (error 'plist->entity "entity plist: key has no value" (car rest)))
            ((assq (car rest) out)
             (error 'plist->entity "entity plist: key given twice" (car rest)))
            (else (loop (cddr rest) (cons (cons (car rest) (cadr rest)) out))))))

  (define (entity->plist e)
    (let loop ((rest e) (out '()))
      (if (null? rest)
          (reverse out)
          (loop (cdr rest) (cons (cdar rest) (cons (caar rest) out))))))

  (define (entity? x)
    (and (list? x)
         (let loop ((x x))
           (or (null? x)
               (and (pair? (car x)) (keyword? (caar x)) (loop (cdr x)))))))

  ;; Accept either form: a plist starts with a keyword, an alist with a pair.
  ;; Only the first element is looked at: scenes call this on every entity
  ;; they are given, every frame.
  (define (as-entity x)
    (cond ((null? x) x)
          ((and (pair? x) (pair? (car x))) x)
          ((and (pair? x) (keyword? (car x))) (plist->entity x))
          (else (error 'as-entity "not an entity (plist or keyword alist)" x))))

  (define (entity-type e) (entity-ref e #:type #f))
  (define (entity-tags e) (entity-ref e #:tags '()))
  (define (entity-has-tag? e tag) (and (memq tag (entity-tags e)) #t))

  ;; How errors name an entity: its type, and its id or name when it has one.
  (define (entity-label e)
    (let ((type (entity-ref e #:type #f))
          (id (or (entity-ref e #:id #f) (entity-ref e #:name #f))))
      (cond ((and type id) (sprintf "~a ~s" type id))
            (type (sprintf "~a" type))
            (id (sprintf "~s" id))
            (else "(untyped)"))))

  (define (entity-skips-pipeline? e step)
    (let ((skips (entity-ref e #:skip-pipelines #f)))
      (and skips (memq step skips) #t)))

  ;; A step of the per-frame pipeline. It returns the entity unchanged when
  ;; the guard is false or the entity lists skip-symbol in #:skip-pipelines.
  (define-syntax define-pipeline
    (syntax-rules ()
      ((_ (name skip) (scene entity dt) guard: check body0 body ...)
       (define (name scene entity dt)
         (if (and check (not (entity-skips-pipeline? entity 'skip)))
             (let () body0 body ...)
             entity)))
      ((_ (name skip) (scene entity dt) body0 body ...)
       (define (name scene entity dt)
         (if (entity-skips-pipeline? entity 'skip)
             entity
             (let () body0 body ...))))))

  ;; Physics reads positions, sizes and velocities through this: NaN, an
  ;; infinity or a non-number is an error naming the entity and the key,
  ;; raised before anything is written, so no step is half-applied.
  (define (check-entity-number e key v)
    (if (and (real? v) (finite? v))
        v
        (error 'downstroke
               (sprintf "entity ~a: ~s is ~s, not a finite real number"
                        (entity-label e) key v))))

  (define (entity-number e key #!optional (default 0))
    (let ((v (entity-ref e key default)))
      (if (fixnum? v) v (check-entity-number e key v)))))
