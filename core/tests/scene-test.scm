;;; (downstroke scene): construction, updates, entity helpers, camera.

(import scheme (chicken base) (downstroke test) (downstroke entity)
        (downstroke scene) (downstroke tilemap))

;; Bad entities are made here on purpose; their warnings would only be noise.
(scene-checks #f)

(define (ent . plist) (plist->entity plist))

(test-group "make-scene and update-scene"
  (let ((s (make-scene entities: (list (list #:type 'a #:x 1) (ent #:type 'b)))))
    (test "plist entities are stored as alists" '((#:type . a) (#:x . 1)) (car (scene-entities s)))
    (test "defaults" '(#f #f #f #f camera-target)
          (list (scene-tilemap s) (scene-background s) (scene-engine-update s)
                (scene-tileset s) (scene-camera-target s)))
    (test "camera at 0,0" '(0 0) (list (camera-x (scene-camera s)) (camera-y (scene-camera s))))
    (let ((s2 (update-scene s background: '(1 2 3) engine-update: 'none)))
      (test "update-scene replaces what it is given" '((1 2 3) none)
            (list (scene-background s2) (scene-engine-update s2)))
      (test-assert "and keeps the rest" (eq? (scene-entities s) (scene-entities s2)))
      (test "the original is unchanged" #f (scene-background s)))
    (test "update-scene can set a field to #f" #f
          (scene-camera-target (update-scene s camera-target: #f))))
  (test-error "a bad engine-update" (make-scene engine-update: 'fast))
  (test-error "entities must be a list" (make-scene entities: 5))
  (test "make-sprite-scene has no tilemap" #f
        (scene-tilemap (make-sprite-scene entities: (list (ent #:x 1))))))

(test-group "scene entity helpers"
  (let ((s (make-scene entities: (list (ent #:type 'a #:tags '(enemy) #:solid? #t)
                                       (ent #:type 'b #:tags '(player))
                                       (ent #:type 'c #:tags '(enemy))))))
    (test "scene-find-tagged" 'a (entity-type (scene-find-tagged s 'enemy)))
    (test "scene-find-tagged none" #f (scene-find-tagged s 'boss))
    (test "scene-find-all-tagged" '(a c) (map entity-type (scene-find-all-tagged s 'enemy)))
    (test "scene-add-entity appends" '(a b c d)
          (map entity-type (scene-entities (scene-add-entity s (list #:type 'd)))))
    (test "scene-remove-entities by predicate" '(b)
          (map entity-type (scene-entities (scene-remove-entities s (lambda (e) (entity-has-tag? e 'enemy))))))
    (test "scene-map-entities gives proc the scene" '(3 3 3)
          (map (lambda (e) (entity-ref e #:n))
               (scene-entities (scene-map-entities
                                s (lambda (sc e) (entity-set e #:n (length (scene-entities sc))))))))
    (test "scene-transform-entities" '(c b a)
          (map entity-type (scene-entities (scene-transform-entities s reverse))))
    (test "scene-solid-entities" '(a) (map entity-type (scene-solid-entities s)))
    (test "solid entities follow the entity list" '()
          (scene-solid-entities (scene-transform-entities s cdr)))))

(test-group "camera follow"
  (define (repeat n x) (if (= n 0) '() (cons x (repeat (- n 1) x))))
  (let* ((tm (list->tilemap (repeat 30 (repeat 40 0))))
         (player (lambda (x y) (ent #:x x #:y y #:width 16 #:height 16 #:tags '(camera-target)))))
    (define (cam s) (let ((c (scene-camera s))) (list (camera-x c) (camera-y c))))
    (test "centres on the tagged entity" '(168 128)
          (cam (scene-follow-camera (make-scene tilemap: tm entities: (list (player 320 240))) 320 240)))
    (test "clamped at the map's top-left" '(0 0)
          (cam (scene-follow-camera (make-scene tilemap: tm entities: (list (player 10 10))) 320 240)))
    (test "clamped at the map's bottom-right" '(320 240)
          (cam (scene-follow-camera (make-scene tilemap: tm entities: (list (player 630 470))) 320 240)))
    (test "without a map it is not clamped" '(-142 -102)
          (cam (scene-follow-camera (make-scene entities: (list (player 10 10))) 320 240)))
    (test "odd sizes give exact halves" '(-315/2 0)
          (cam (scene-follow-camera (make-scene entities: (list (ent #:x 0 #:y 0 #:width 5 #:height 0
                                                                     #:tags '(camera-target))))
                                    320 0)))
    (let ((s (make-scene tilemap: tm camera-target: #f entities: (list (player 320 240)))))
      (test-assert "camera-target #f: the camera stays" (eq? s (scene-follow-camera s 320 240))))
    (let ((s (make-scene tilemap: tm camera-target: 'hero
                         entities: (list (player 320 240) (ent #:x 100 #:y 100 #:width 0 #:height 0 #:tags '(hero))))))
      (test "camera-target names the tag to follow" '(0 0) (cam (scene-follow-camera s 320 240))))))

(test-group "scene-map-entities shares what it does not change"
  (let* ((es (map (lambda (i) (ent #:id i #:x i)) '(0 1 2 3 4 5)))
         (s (make-scene entities: es))
         (seen '())
         (out (scene-entities
               (scene-map-entities s (lambda (sc e)
                                       (set! seen (cons (entity-ref e #:id) seen))
                                       (if (= (entity-ref e #:id) 2) (entity-set e #:x 20) e))))))
    (test "proc sees the entities in order" '(0 1 2 3 4 5) (reverse seen))
    (test "the changed entity is new" '(0 1 20 3 4 5) (map (lambda (e) (entity-ref e #:x)) out))
    (test "the entities before it are the same objects" #t (and (eq? (car out) (car es)) (eq? (cadr out) (cadr es))))
    (test "the list after it is shared" #t (eq? (cdddr out) (cdddr es)))
    (test "nothing changed: the same scene" #t (eq? s (scene-map-entities s (lambda (sc e) e))))
    ;; changes apart from each other: the unchanged ones between are copied
    ;; into the new list, the original list keeps its own
    (let* ((ids '(0 3 4))
           (out2 (scene-entities
                  (scene-map-entities s (lambda (sc e)
                                          (if (memv (entity-ref e #:id) ids) (entity-set e #:x 'new) e))))))
      (test "changes at 0, 3 and 4: each result in place" '(new 1 2 new new 5)
            (map (lambda (e) (entity-ref e #:x)) out2))
      (test "the unchanged ones between are the same objects" #t
            (and (eq? (list-ref out2 1) (list-ref es 1)) (eq? (list-ref out2 2) (list-ref es 2))))
      (test "the list after the last change is shared" #t (eq? (list-tail out2 5) (list-tail es 5)))
      (test "the original list is untouched" '(0 1 2 3 4 5) (map (lambda (e) (entity-ref e #:x)) es))
      (test "the last one changed: nothing shared, six long" '(0 1 2 3 4 last)
            (map (lambda (e) (entity-ref e #:x))
                 (scene-entities (scene-map-entities s (lambda (sc e)
                                                         (if (= (entity-ref e #:id) 5) (entity-set e #:x 'last) e)))))))
    (test "a long list (100,000) maps without trouble" 100000
          (length (scene-entities (scene-map-entities
                                   (make-scene entities: (let loop ((i 0) (out '()))
                                                           (if (= i 100000) out (loop (+ i 1) (cons (ent #:x i) out)))))
                                   (lambda (sc e) (entity-set e #:x 0))))))))

(test-group "camera-follow takes a plist target too"
  (let ((cam-a (camera-follow (make-camera) (list #:x 100 #:y 80 #:width 20 #:height 20) 100 100 #f))
        (cam-b (camera-follow (make-camera) (ent #:x 100 #:y 80 #:width 20 #:height 20) 100 100 #f)))
    (test "the same camera" (list (camera-x cam-b) (camera-y cam-b)) (list (camera-x cam-a) (camera-y cam-a)))
    (test "centred on the target" '(60 40) (list (camera-x cam-a) (camera-y cam-a)))))
