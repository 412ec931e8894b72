;;; (downstroke entity): keyword alists, plists, tags, skips, define-pipeline.

(import scheme (chicken base) (chicken string) (chicken condition) (chicken keyword)
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

;; entity-ref, entity-set and entity-set* are C (core/entity.c); the Scheme
;; definitions are the rule. On random entities, well formed or not, both
;; must answer the same (equal?, and eq? to the argument alike, sharing
;; the same tail) or raise the same error at the same place.
(define entity-rand-state 20261203)
(define (entity-rand n)
  (set! entity-rand-state (modulo (+ (* 1103515245 entity-rand-state) 12345) 2147483648))
  (modulo (quotient entity-rand-state 65536) n))
(define entity-test-keys (vector #:x #:y #:vx #:vy #:type #:tags))
(define entity-test-values (vector 0 1 -7 1/2 2.5 #f '() 'player (list 1 2) "s"))
(define (random-key) (vector-ref entity-test-keys (entity-rand (vector-length entity-test-keys))))
(define (random-value) (vector-ref entity-test-values (entity-rand (vector-length entity-test-values))))

;; An alist of up to 7 pairs, keys possibly repeated; one in four is
;; malformed somewhere (a plist, an improper tail, a non-pair element, not
;; a list at all).
(define (random-entity)
  (let ((pairs (let make ((i (entity-rand 8)) (out '()))
                 (if (= i 0) out (make (- i 1) (cons (cons (random-key) (random-value)) out))))))
    (case (entity-rand 12)
      ((0) (entity->plist pairs))
      ((1) (if (pair? pairs) (append pairs 5) 5))
      ((2) (append pairs (list 'oops) pairs))
      ((3) (vector-ref (vector #f "entity" 42 (list #:x)) (entity-rand 4)))
      (else pairs))))

;; What a call does: (value v eq shared), eq whether v is e itself and
;; shared the pairs of the longest tail of e that v shares (eq?), or
;; (error location message).
(define (outcome thunk e)
  (handle-exceptions exn
      (list 'error ((condition-property-accessor 'exn 'location #f) exn) (error-text exn))
    (let ((v (thunk)))
      (list 'value v (eq? v e) (shared-pairs e v)))))
(define (shared-pairs e v)
  (let loop ((t e))
    (cond ((not (pair? t)) -1)
          ((let tail? ((v v)) (and (pair? v) (or (eq? v t) (tail? (cdr v)))))
           (let count ((t t) (n 0)) (if (pair? t) (count (cdr t) (+ n 1)) n)))
          (else (loop (cdr t))))))
;; The value e holds for key (so that a setting can be the value held),
;; 0 when e cannot be read.
(define (held-value e key) (handle-exceptions exn 0 (entity-ref/scheme e key 0)))
;; (k1 v1 ...) of n settings of one key, f giving each value
(define (settings key n) (let make ((i 0)) (if (= i n) '() (cons key (cons i (make (+ i 1)))))))

(test-group "entity-ref, entity-set and entity-set* in C against their Scheme definitions"
  (let loop ((k 0) (refs 0) (sets 0) (set*s 0))
    (if (= k 4000)
        (begin
          (test "entity-ref, with and without a default, 4000 random entities" 0 refs)
          (test "entity-set, 4000 random entities" 0 sets)
          (test "entity-set* with 0 to 4 settings, 4000 random entities" 0 set*s))
        (let* ((e (random-entity))
               (key (random-key))
               (value (if (= 0 (entity-rand 3)) (held-value e key) (random-value)))
               (kvs (let make ((i (entity-rand 5)))
                      (if (= i 0) '()
                          (cons (random-key) (cons (if (= 0 (entity-rand 3)) (held-value e key) (random-value))
                                                   (make (- i 1)))))))
               (same? (lambda (fast slow) (equal? (outcome fast e) (outcome slow e)))))
          (loop (+ k 1)
                (+ refs (if (and (same? (lambda () (entity-ref e key)) (lambda () (entity-ref/scheme e key)))
                                 (same? (lambda () (entity-ref e key 'none)) (lambda () (entity-ref/scheme e key 'none))))
                            0 1))
                (+ sets (if (same? (lambda () (entity-set e key value)) (lambda () (entity-set/scheme e key value))) 0 1))
                (+ set*s (if (same? (lambda () (apply entity-set* e kvs)) (lambda () (apply entity-set*/scheme e kvs)))
                             0 1))))))
  (let ((e (list (cons #:a 1) (cons #:b 2) (cons #:c 3))))
    (test-assert "entity-set* to the values held gives the entity itself" (eq? e (entity-set* e #:b 2 #:a 1)))
    (test-assert "entity-set* copies only up to the last pair it changes"
                 (eq? (cdr e) (cdr (entity-set* e #:a 10 #:c 3))))
    (test "entity-set* sets a key twice: the last setting counts, once"
          '((#:d . 3) (#:a . 1) (#:b . 5) (#:c . 3)) (entity-set* e #:d 1 #:b 5 #:d 3))
    (test "entity-set* on an entity holding a key twice: its Scheme definition's answer"
          (entity-set*/scheme (cons (cons #:b 0) e) #:b 7 #:a 2)
          (entity-set* (cons (cons #:b 0) e) #:b 7 #:a 2))
    (test "entity-set* with more settings than C takes (17)"
          (apply entity-set*/scheme e (settings #:a 17))
          (apply entity-set* e (settings #:a 17)))
    (test-error "entity-set with a missing value, as its Scheme definition" (entity-set e #:a))
    (test-error "entity-set* with a key and no value" (entity-set* e #:a 1 #:b))
    (test "entity-ref with a fourth argument, as its Scheme definition"
          (entity-ref/scheme e #:z 1 2) (entity-ref e #:z 1 2)))
  ;; Copies longer than C allocates at once (1,024 pairs in front of the
  ;; key), and many copies in a row, which fill the nursery: C asks the
  ;; collector for room and starts again.
  (let* ((long (let make ((i 0) (out (list (cons #:x 0))))
                 (if (= i 1500) out (make (+ i 1) (cons (cons (string->keyword (number->string i)) i) out)))))
         (mid (list-tail long 700)))
    (test "entity-set behind 1,500 pairs" (entity-set/scheme long #:x 1) (entity-set long #:x 1))
    (test "entity-set* behind 1,500 pairs" (entity-set*/scheme long #:x 1 #:y 2) (entity-set* long #:x 1 #:y 2))
    (test "20,000 copies of 800 pairs, each the Scheme's" 0
          (let loop ((i 0) (bad 0))
            (if (= i 20000)
                bad
                (loop (+ i 1)
                      (if (equal? (entity-set mid #:x i) (entity-set/scheme mid #:x i))
                          (if (equal? (entity-set* mid #:x i #:vx i) (entity-set*/scheme mid #:x i #:vx i)) bad (+ bad 1))
                          (+ bad 1))))))))
