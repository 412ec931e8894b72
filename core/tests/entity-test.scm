;;; (downstroke entity): keyword alists, plists, tags, skips, define-pipeline.

(import scheme (chicken base) (chicken string) (chicken condition)
        (downstroke test) (downstroke entity))

(test-group "entity access"
  (let ((e (plist->entity (list #:type 'player #:x 100 #:y 50 #:tags '(player hero)))))
    (test "plist->entity keeps order" '((#:type . player) (#:x . 100) (#:y . 50) (#:tags player hero)) e)
    (test "entity-ref" 100 (entity-ref e #:x))
    (test "entity-ref default" 'none (entity-ref e #:vx 'none))
    (test "entity-ref default is #f" #f (entity-ref e #:vx))
    (test "entity-set replaces" 7 (entity-ref (entity-set e #:y 7) #:y))
    (test "entity-set keeps the length" 4 (length (entity-set e #:y 7)))
    (test "entity-set leaves its argument alone" 50 (entity-ref e #:y))
    (test "entity-set shares the tail after the key" #t
          (eq? (cddr e) (cddr (entity-set e #:x 1))))
    (test "entity-set adds a missing key at the front" '(#:vx . 3) (car (entity-set e #:vx 3)))
    (test "entity-set to the value held already gives the entity itself" #t
          (eq? e (entity-set e #:y 50)))
    (test "entity-set to an equal but not eq? value copies" #f
          (eq? e (entity-set e #:tags (list 'player 'hero))))
    (test "entity-update" 101 (entity-ref (entity-update e #:x (lambda (x) (+ x 1))) #:x))
    (test "entity-update with default" 1 (entity-ref (entity-update e #:vx (lambda (v) (+ v 1)) 0) #:vx))
    (test "entity-remove" '(#:type #:y #:tags) (map car (entity-remove e #:x)))
    (test-assert "entity-remove of a missing key returns it" (eq? e (entity-remove e #:nope)))
    (test "entity-type" 'player (entity-type e))
    (test "entity-tags" '(player hero) (entity-tags e))
    (test-assert "entity-has-tag?" (entity-has-tag? e 'hero))
    (test-assert "entity-has-tag? absent" (not (entity-has-tag? e 'enemy)))
    (test "entity->plist round trip" (list #:type 'player #:x 100 #:y 50 #:tags '(player hero))
          (entity->plist e))))

(test-group "entity construction"
  (test "make-entity" '((#:x . 1) (#:y . 2) (#:width . 3) (#:height . 4) (#:vx . 0) (#:vy . 0))
        (make-entity 1 2 3 4))
  (test "as-entity converts a plist" '((#:x . 1)) (as-entity (list #:x 1)))
  (let ((a '((#:x . 1))))
    (test-assert "as-entity passes an alist through" (eq? a (as-entity a))))
  (test-error "a plist with a non-keyword key" (plist->entity (list 'x 1)))
  (test-error "a plist with a key and no value"
              (lambda (exn) (substring-index "#:y" (error-text exn)))
              (plist->entity (list #:x 1 #:y)))
  (test-error "a plist giving a key twice" (plist->entity (list #:x 1 #:x 2)))
  (test-error "something that is no entity" (as-entity 42))
  ;; A plist handed straight to the accessors: an error that says what it
  ;; is and what to do, naming the entity's type and the key asked for.
  (let ((p (list #:type 'player #:x 1 #:y 2)))
    (for-each
     (lambda (who call)
       (test-error (string-append who " on a plist says to convert it")
                   (lambda (exn) (let ((text (error-text exn)))
                                   (and (equal? (string->symbol who)
                                                ((condition-property-accessor 'exn 'location #f) exn))
                                        (substring-index "entity player" text)
                                        (substring-index "plist->entity" text)
                                        (substring-index "#:y" text))))
                   (call)))
     '("entity-ref" "entity-set" "entity-set*" "entity-remove" "entity-update")
     (list (lambda () (entity-ref p #:y))
           (lambda () (entity-set p #:y 3))
           (lambda () (entity-set* p #:y 3 #:x 4))
           (lambda () (entity-remove p #:y))
           (lambda () (entity-update p #:y (lambda (y) (+ y 1)))))))
  (test "an empty entity is still an entity" 'none (entity-ref '() #:x 'none)))

(test-group "entity-skips-pipeline? and define-pipeline"
  (define-pipeline (bump-x bump) (scene entity dt)
    (entity-update entity #:x (lambda (x) (+ x dt)) 0))
  (define-pipeline (guarded-bump guarded) (scene entity dt)
    guard: (entity-ref entity #:ready? #f)
    (entity-update entity #:x (lambda (x) (+ x dt)) 0))
  (let ((e (plist->entity (list #:x 1 #:skip-pipelines '(gravity bump)))))
    (test-assert "lists a step" (entity-skips-pipeline? e 'gravity))
    (test-assert "does not list a step" (not (entity-skips-pipeline? e 'velocity-x)))
    (test-assert "a skipped step returns the entity itself" (eq? e (bump-x #f e 5)))
    (test "a step runs when not skipped" 6 (entity-ref (bump-x #f (plist->entity (list #:x 1)) 5) #:x)))
  (let ((off (plist->entity (list #:x 1)))
        (on (plist->entity (list #:x 1 #:ready? #t)))
        (on-skip (plist->entity (list #:x 1 #:ready? #t #:skip-pipelines '(guarded)))))
    (test-assert "a false guard returns the entity itself" (eq? off (guarded-bump #f off 5)))
    (test "a true guard runs the body" 6 (entity-ref (guarded-bump #f on 5) #:x))
    (test-assert "guard true but skipped" (eq? on-skip (guarded-bump #f on-skip 5)))))

(test-group "entity-number"
  (let ((e (plist->entity (list #:type 'crate #:id 7 #:x 1/2 #:vx +nan.0 #:vy +inf.0 #:name "box"))))
    (test "a finite number comes back" 1/2 (entity-number e #:x))
    (test "a missing key gives the default" 0 (entity-number e #:y))
    (test-error "NaN names entity and key"
                (lambda (exn) (and (substring-index "#:vx" (error-text exn))
                                   (substring-index "crate 7" (error-text exn))))
                (entity-number e #:vx))
    (test-error "infinity names the key"
                (lambda (exn) (substring-index "#:vy" (error-text exn)))
                (entity-number e #:vy))
    (test-error "a string is no number" (entity-number e #:name))))
