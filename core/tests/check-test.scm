;;; The scene check: misspelt keys, zero-size bodies, values of the wrong
;;; type, each named with its entity.

(import scheme (chicken base) (chicken port) (chicken string)
        (downstroke test) (downstroke entity) (downstroke scene) (downstroke check))

(define (ck . plist) (plist->entity plist))

(define (ck-problems . plist) (entity-problems (plist->entity plist)))

(test-group "check: keys one edit away from one Downstroke reads"
  (test "#:gravity for #:gravity?"
        '("entity player: key #:gravity is not one Downstroke reads (did you mean #:gravity?)")
        (ck-problems #:type 'player #:x 0 #:y 0 #:width 8 #:height 8 #:gravity #t))
  (test "#:widht for #:width (and so no width: a zero-size body)"
        '("entity box: key #:widht is not one Downstroke reads (did you mean #:width)"
          "entity box: no #:width: the collision steps treat it as zero-size")
        (ck-problems #:type 'box #:x 0 #:y 0 #:widht 8 #:height 8 #:solid? #t))
  (test "a key of the game's own, far from any, is fine" '()
        (ck-problems #:type 'coin #:x 0 #:y 0 #:value 10 #:sparkle 3))
  (test "a near key is fine when the real one is there too" '()
        (ck-problems #:type 'x #:x 0 #:vx 1 #:vz 2)))

(test-group "check: bodies the collision steps see as zero-size"
  (test "a solid entity without a size"
        '("entity wall: no #:width or #:height: the collision steps treat it as zero-size")
        (ck-problems #:type 'wall #:x 0 #:y 0 #:solid? #t))
  (test "a gravity entity without a height"
        '("entity hero: no #:height: the collision steps treat it as zero-size")
        (ck-problems #:type 'hero #:x 0 #:y 0 #:width 8 #:gravity? #t))
  (test "a decoration without a size is fine" '() (ck-problems #:type 'cloud #:x 0 #:y 0))
  (test "a negative size" '("entity slab: a negative size (-8 x 4)")
        (ck-problems #:type 'slab #:width -8 #:height 4)))

(test-group "check: values of the wrong type"
  (test "a position given as a string" '("entity e: #:x is \"10\", not a finite number")
        (ck-problems #:type 'e #:x "10"))
  (test "a NaN velocity" '("entity e: #:vy is +nan.0, not a finite number")
        (ck-problems #:type 'e #:vy +nan.0))
  (test "#:skip-pipelines as a string"
        '("entity e: #:skip-pipelines is \"gravity\", not a list of step symbols")
        (ck-problems #:type 'e #:skip-pipelines "gravity"))
  (test-assert "#:skip-pipelines naming no step"
               (substring-index "names gravty, which is no step"
                                (car (ck-problems #:type 'e #:skip-pipelines '(gravty)))))
  (test "an unknown collision mode" '("entity e: #:collision-mode is fast, not discrete or swept")
        (ck-problems #:type 'e #:collision-mode 'fast))
  (test "tags that are not a list" '("entity e: #:tags is player, not a list")
        (ck-problems #:type 'e #:tags 'player))
  (test "a correct platformer player has no problems" '()
        (ck-problems #:type 'player #:tags '(player) #:x 0 #:y 0 #:width 16 #:height 16
                     #:vx 0 #:vy 0 #:gravity? #t #:solid? #t #:skip-pipelines '(animation)
                     #:collision-mode 'swept)))

(define (said thunk)
  (call-with-output-string
   (lambda (port) (parameterize ((current-error-port port)) (thunk)))))

(test-group "check: a whole scene, by hand and in debug mode"
  (let ((s (make-scene entities: (list (ck #:type 'a #:x 0 #:gravity #t)
                                       (ck #:type 'b #:x 0)
                                       (ck #:type 'c #:y "top")))))
    (test "scene-problems: every entity's, in order"
          '("entity a: key #:gravity is not one Downstroke reads (did you mean #:gravity?)"
            "entity c: #:y is \"top\", not a finite number")
          (scene-problems s)))
  (test "checks off (scene-checks #f, a release build): make-scene says nothing" ""
        (said (lambda () (parameterize ((scene-checks #f))
                           (make-scene entities: (list (ck #:type 'quiet #:gravityy #t #:gravty #t)))))))
  (test "checks on: make-scene says each problem on the error port"
        "downstroke: entity loud: key #:solid is not one Downstroke reads (did you mean #:solid?)\n"
        (said (lambda () (parameterize ((scene-checks #t))
                           (make-scene entities: (list (ck #:type 'loud #:solid #t)))))))
  (test "and only once: the same problem again is not repeated" ""
        (said (lambda () (parameterize ((scene-checks #t))
                           (update-scene (make-scene) entities: (list (ck #:type 'loud #:solid #t))))))))

(test-group "check: on by default, when a scene is made or an entity added"
  (test "make-scene says a misspelt key with no parameter set"
        "downstroke: entity player: key #:widht is not one Downstroke reads (did you mean #:width)\n"
        (said (lambda () (make-scene entities: (list (ck #:type 'player #:x 0 #:widht 16 #:height 16))))))
  (test "a solid lift without #:width is said when it is added"
        "downstroke: entity lift (object 7): no #:width: the collision steps treat it as zero-size\n"
        (said (lambda () (scene-add-entity (make-scene) (ck #:type 'lift #:object-id 7 #:solid? #t #:height 8)))))
  (test "update-scene, called every frame by games, checks nothing by default" ""
        (said (lambda () (update-scene (make-scene) entities: (list (ck #:type 'per-frame #:solid #t))))))
  (test "'always (a debug game) checks update-scene's entities too"
        "downstroke: entity debugged: key #:solid is not one Downstroke reads (did you mean #:solid?)\n"
        (said (lambda () (parameterize ((scene-checks 'always))
                           (update-scene (make-scene) entities: (list (ck #:type 'debugged #:solid #t)))))))
  (test-error "scene-checks takes #t, #f or 'always" (scene-checks 'sometimes)))
