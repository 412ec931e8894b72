;;; (downstroke groups): the members of a group placed where its origin is (sync-groups).
;;;
;;; docs/physics.org, "Groups".

(module (downstroke groups)
  (sync-groups)

  (import scheme (chicken base) (chicken fixnum) (chicken foreign)
          (downstroke entity) (downstroke body)
          (only (downstroke util) make-hash-table hash-table-exists? hash-table-set!
                hash-table-ref/default hash-table-count))

  (foreign-declare "#include \"physics/body.h\"")

  ;; The first entity with #:group-origin? and a #:group-id is its group's
  ;; origin; every other entity with that #:group-id is placed at the
  ;; origin's position plus its #:group-local-x / #:group-local-y. Ids are
  ;; compared with equal?. The origins are found in one pass and kept by id
  ;; in a hash table, so a frame costs two passes over the entities however
  ;; many groups there are.
  (define (sync-groups entities)
    (let ((origins (make-hash-table equal?)))
      (for-each (lambda (e)
                  (let ((id (and (entity-ref e #:group-origin? #f) (entity-ref e #:group-id #f))))
                    (when (and id (not (hash-table-exists? origins id)))
                      (hash-table-set! origins id e))))
                entities)
      (if (fx= 0 (hash-table-count origins))
          entities
          (map (lambda (e)
                 (let* ((id (entity-ref e #:group-id #f))
                        (o (and id (hash-table-ref/default origins id #f))))
                   (if (and o (not (eq? o e)))
                       (entity-set
                        (entity-set e #:x (+ (num o #:x) (num e #:group-local-x)))
                        #:y (+ (num o #:y) (num e #:group-local-y)))
                       e)))
               entities))))
)
