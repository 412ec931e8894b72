;;; (downstroke entity): entities as keyword alists.
;;;
;;; An entity is an alist keyed by CHICKEN keywords:
;;;   ((#:type . player) (#:x . 100) (#:y . 50) ...)
;;; Every operation returns an entity and never changes its argument (an
;;; operation that changes nothing may return the argument itself).
;;; `entity-set` replaces a key's pair in a copy of the list up to that pair
;;; and shares the rest, so an entity never grows by shadowing pairs, however
;;; many frames it lives.

(module (downstroke entity)
  (entity-ref entity-set entity-set* entity-update entity-remove entity-let
   make-entity plist->entity entity->plist as-entity entity?
   entity-type entity-tags entity-has-tag? entity-label
   entity-skips-pipeline? define-pipeline
   entity-number check-entity-number
   entity-ref/scheme entity-set/scheme entity-set*/scheme)

  (import scheme (chicken base) (chicken keyword) (chicken format) (chicken fixnum) (chicken foreign))

  ;; entity-ref, entity-set and entity-set* are C procedures (entity.c)
  ;; that hand what they do not take to these definitions, the rules they
  ;; follow (docs/entities.org).
  (define (entity-ref/scheme e key #!optional (default #f))
    (if (plist-shaped? e)
        (not-an-alist 'entity-ref e key)
        (let ((p (assq key e)))
          (if p (cdr p) default))))

  ;; Entities written as plists, the way docs/entities.org shows them, must be
  ;; converted before they are read or written (make-scene, update-scene and
  ;; scene-add-entity do it). Only the first element is looked at, so this
  ;; costs one test per call; without it the user would see assq's bare
  ;; "bad argument type".
  (define (plist-shaped? e) (and (pair? e) (not (pair? (car e)))))

  (define (not-an-alist who e key)
    (let ((type (and (keyword? (car e)) (get-keyword #:type e (lambda () #f)))))
      (error who
             (sprintf "~akey ~s: ~s is ~a, not an entity (a keyword alist); convert it with plist->entity"
                      (if type (sprintf "entity ~a, " type) "")
                      key e
                      (if (keyword? (car e)) "a plist" "a list of non-pairs")))))

  ;; Copy the pairs before `key`, replace its pair, share the tail.
  ;; A key not present yet is added at the front (and nothing is copied);
  ;; a key that holds this very value already gives e itself, so a game
  ;; that sets a key every frame allocates only when the value changes.
  (define (entity-set/scheme e key value)
    (when (plist-shaped? e) (not-an-alist 'entity-set e key))
    (let find ((rest e) (n 0))
      (cond ((null? rest) (cons (cons key value) e))
            ((eq? (caar rest) key)
             (if (eq? (cdar rest) value)
                 e
                 (let copy ((e e) (n n))
                   (if (fx= n 0)
                       (cons (cons key value) (cdr e))
                       (cons (car e) (copy (cdr e) (fx- n 1)))))))
            (else (find (cdr rest) (fx+ n 1))))))

  ;; e with its first n+1 pairs copied, the ones whose key is in the plist
  ;; `kvs` holding their new value (a new pair only when the value is not
  ;; the one held); the rest of e is shared.
  (define (copy-replacing e n kvs)
    (if (fx< n 0)
        e
        (let ((p (car e)))
          (cons (let ((kv (last-setting (car p) kvs)))
                  (if (and kv (not (eq? (cadr kv) (cdr p)))) (cons (car p) (cadr kv)) p))
                (copy-replacing (cdr e) (fx- n 1) kvs)))))

  ;; The tail of the plist kvs at the last setting of key, or #f.
  (define (last-setting key kvs)
    (let loop ((kvs kvs) (found #f))
      (cond ((null? kvs) found)
            ((eq? (car kvs) key) (loop (cddr kvs) kvs))
            (else (loop (cddr kvs) found)))))

  ;; (entity-set* e k1 v1 k2 v2 ...) is (entity-set (entity-set e k1 v1) k2 v2)
  ;; ..., with one walk and one copy: present keys are replaced where they
  ;; are, absent ones go in front, the last one set first; the copy goes
  ;; up to the last pair whose value changes (none: e itself).
  (define (entity-set*/scheme e . kvs)
    (when (plist-shaped? e) (not-an-alist 'entity-set* e (if (pair? kvs) (car kvs) #f)))
    (let find ((rest e) (n 0) (last -1) (found 0))
      (if (pair? rest)
          (let ((kv (last-setting (caar rest) kvs)))
            (if kv
                (find (cdr rest) (fx+ n 1) (if (eq? (cadr kv) (cdar rest)) last n) (fx+ found 1))
                (find (cdr rest) (fx+ n 1) last found)))
          (let ((copy (copy-replacing e last kvs)))
            (if (fx= found (distinct-keys kvs))
                copy
                (let add ((ks kvs) (out copy))
                  (cond ((null? ks) out)
                        ((or (assq (car ks) e) (assq (car ks) out)) (add (cddr ks) out))
                        (else (add (cddr ks)
                                   (cons (cons (car ks) (cadr (last-setting (car ks) kvs)))
                                         out))))))))))

  (foreign-declare "#include \"core/entity.c\"")

  ;; A C procedure of entity.c: a closure of its code and the Scheme
  ;; definition it hands the rest to.
  (define-syntax define-c-entity-procedure
    (syntax-rules ()
      ((_ name code scheme)
       (define name
         ((foreign-primitive scheme-object ((scheme-object proc))
            "C_word *a = C_alloc(3);"
            "a[0] = C_CLOSURE_TYPE | 2; a[1] = (C_word)" code "; a[2] = proc;"
            "C_return((C_word)a);")
          scheme)))))

  (define-c-entity-procedure entity-ref "ds_entity_ref" entity-ref/scheme)
  (define-c-entity-procedure entity-set "ds_entity_set" entity-set/scheme)
  (define-c-entity-procedure entity-set* "ds_entity_set_star" entity-set*/scheme)

  ;; How many different keys the plist kvs sets.
  (define (distinct-keys kvs)
    (let loop ((ks kvs) (n 0))
      (cond ((null? ks) n)
            ((eq? (last-setting (car ks) kvs) ks) (loop (cddr ks) (fx+ n 1)))
            (else (loop (cddr ks) n)))))

  ;; (entity-let e ((var key) ...) body ...) binds each var to e's pair for
  ;; key, or #f when e has no such key: one walk of e for all of them. The
  ;; walk carries the pairs found as loop arguments, so nothing is boxed.
  (define-syntax entity-let
    (syntax-rules ()
      ((_ e ((var key) ...) body0 body ...)
       (%entity-let (walk rest p k) e (var ...) () ((var key) ...) () (body0 body ...)))))

  ;; Builds one cond clause per key: (eq? k key) passes p in that key's place.
  (define-syntax %entity-let
    (syntax-rules ()
      ((_ (walk rest p k) e (var ...) done () (clause ...) (body ...))
       (let walk ((rest e) (var #f) ...)
         (if (pair? rest)
             (let* ((p (car rest)) (k (car p)))
               (cond clause ... (else (walk (cdr rest) var ...))))
             (let () body ...))))
      ((_ (walk rest p k) e vars (done ...) ((v key) (rv rk) ...) (clause ...) bodies)
       (%entity-let (walk rest p k) e vars (done ... v) ((rv rk) ...)
                    (clause ... ((eq? k key) (walk (cdr rest) done ... (or v p) rv ...)))
                    bodies))))

  (define (entity-update e key proc #!optional (default #f))
    (when (plist-shaped? e) (not-an-alist 'entity-update e key))
    (entity-set e key (proc (entity-ref e key default))))

  (define (entity-remove e key)
    (when (plist-shaped? e) (not-an-alist 'entity-remove e key))
    (let find ((rest e) (n 0))
      (cond ((null? rest) e)
            ((eq? (caar rest) key)
             (let copy ((e e) (n n))
               (if (fx= n 0) (cdr e) (cons (car e) (copy (cdr e) (fx- n 1))))))
            (else (find (cdr rest) (fx+ n 1))))))

  (define (make-entity x y w h)
    (list (cons #:x x) (cons #:y y) (cons #:width w) (cons #:height h)
          (cons #:vx 0) (cons #:vy 0)))

  ;; Users write entities as plists, the way docs/entities.org shows them.
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
  ;; "slime", "slime \"boss\"", "slime (object 12)": its type, its #:id
  ;; or #:name, and the Tiled object it came from, so that an error names
  ;; which of five slimes, and where to find it in the map.
  (define (entity-label e)
    (let* ((type (entity-ref e #:type #f))
           (id (or (entity-ref e #:id #f) (entity-ref e #:name #f)))
           (object (entity-ref e #:object-id #f))
           (base (cond ((and type id) (sprintf "~a ~s" type id))
                       (type (sprintf "~a" type))
                       (id (sprintf "~s" id))
                       (else "(untyped)"))))
      (if object (sprintf "~a (object ~a)" base object) base)))

  (define (entity-skips-pipeline? e step)
    (let ((skips (entity-ref e #:skip-pipelines #f)))
      (cond ((pair? skips) (and (memq step skips) #t))
            ((or (not skips) (null? skips)) #f)
            (else (error 'downstroke
                         (sprintf "entity ~a: #:skip-pipelines is ~s, expected a list of step symbols such as (gravity)"
                                  (entity-label e) skips))))))

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
    (if (and (real? v) (or (exact? v) (finite? v)))   ; exact numbers are finite
        v
        (error 'downstroke
               (sprintf "entity ~a: ~s is ~s, not a finite real number"
                        (entity-label e) key v))))

  (define (entity-number e key #!optional (default 0))
    (let ((v (entity-ref e key default)))
      (if (fixnum? v) v (check-entity-number e key v)))))
