;;; Riders are carried by what their platform did this frame
;;; (docs/physics.org, "Solid entities"): its velocity, its tween, or nothing.

(import scheme (chicken base) (downstroke test) (downstroke entity)
        (downstroke scene) (downstroke tween) (downstroke pipeline))

(define (rd-ent . plist) (plist->entity plist))

(define (rd-run scene frames pipeline)
  (if (= frames 0) scene (rd-run (pipeline scene 16) (- frames 1) pipeline)))

(define (rd-find scene type)
  (let loop ((es (scene-entities scene)))
    (cond ((null? es) #f)
          ((eq? (entity-ref (car es) #:type) type) (car es))
          (else (loop (cdr es))))))

(define (rd-both name scene frames check)
  (for-each (lambda (p)
              (check (string-append name " (" (car p) ")") (rd-run scene frames (cdr p))))
            (list (cons "engine-pipeline" engine-pipeline) (cons "contract-pipeline" contract-pipeline))))

(test-group "carrying: a platform's displacement, not its #:vx"
  ;; the issue's scene: the platform skips velocity-x, so its vx moves nothing
  (rd-both "a platform that skips velocity-x with vx -5 carries nothing"
           (make-scene entities: (list (rd-ent #:type 'platform #:x 0 #:y 40 #:width 40 #:height 8 #:vx -5
                                               #:solid? #t #:immovable? #t #:skip-pipelines '(velocity-x))
                                       (rd-ent #:type 'rider #:x 10 #:y 30 #:width 10 #:height 10 #:vy 1
                                               #:solid? #t)))
           1
           (lambda (name s)
             (test name '(0 10 30) (list (entity-ref (rd-find s 'platform) #:x)
                                         (entity-ref (rd-find s 'rider) #:x)
                                         (entity-ref (rd-find s 'rider) #:y)))))
  (rd-both "a platform moving by its vx carries its rider by the same 2 px a frame"
           (make-scene entities: (list (rd-ent #:type 'platform #:x 0 #:y 40 #:width 40 #:height 8 #:vx 2
                                               #:solid? #t #:immovable? #t)
                                       (rd-ent #:type 'rider #:x 10 #:y 30 #:width 10 #:height 10
                                               #:gravity? #t #:solid? #t)))
           30
           (lambda (name s)
             (test name '(60 70 30 #t) (list (entity-ref (rd-find s 'platform) #:x)
                                             (entity-ref (rd-find s 'rider) #:x)
                                             (entity-ref (rd-find s 'rider) #:y)
                                             (entity-ref (rd-find s 'rider) #:on-ground?)))))
  ;; a tweened platform: a tween moves it, the velocity steps are skipped
  (let* ((platform (rd-ent #:type 'platform #:x 0 #:y 40 #:width 40 #:height 8
                           #:solid? #t #:immovable? #t
                           #:skip-pipelines '(acceleration gravity velocity-x velocity-y)))
         (platform (entity-set platform #:tween
                               (make-tween platform props: '((#:x . 32)) duration: 512))))
    (rd-both "a tweened platform (32 px in 32 frames of 16 ms) carries its rider 32 px"
             (make-scene entities: (list platform
                                         (rd-ent #:type 'rider #:x 10 #:y 30 #:width 10 #:height 10
                                                 #:gravity? #t #:solid? #t)))
             40
             (lambda (name s)
               (test name '(32 42 30) (list (entity-ref (rd-find s 'platform) #:x)
                                            (entity-ref (rd-find s 'rider) #:x)
                                            (entity-ref (rd-find s 'rider) #:y)))))))

;; A lift: immovable, moved by its #:vy, turned round by the test.
(define (rd-lift-scene vy)
  (make-scene entities: (list (rd-ent #:type 'lift #:x 0 #:y 100 #:width 40 #:height 8 #:vy vy
                                      #:solid? #t #:immovable? #t)
                              (rd-ent #:type 'rider #:x 10 #:y 90 #:width 10 #:height 10
                                      #:gravity? #t #:solid? #t))))

(test-group "lifts keep their rider on top, up and down"
  (for-each
   (lambda (speed)
     (for-each
      (lambda (dir)
        (let loop ((f 0) (s (rd-lift-scene (* dir speed))) (off-top 0) (airborne 0))
          (if (= f 40)
              (begin
                (test (sprintf "lift at ~a px/frame ~a: the rider's bottom is on its top every frame"
                               speed (if (> dir 0) "down" "up"))
                      0 off-top)
                ;; up, the rider sinks 1 + speed px before the push; ground
                ;; detection (before the push) sees it only within 5 px
                (when (or (> dir 0) (<= (+ speed 1) 5))
                  (test (sprintf "lift at ~a px/frame ~a: the rider stays on the ground after landing"
                                 speed (if (> dir 0) "down" "up"))
                        0 airborne)))
              (let* ((s (engine-pipeline s 16))
                     (lift (rd-find s 'lift)) (rider (rd-find s 'rider)))
                (loop (+ f 1) s
                      (if (= (+ (entity-ref rider #:y) 10) (entity-ref lift #:y)) off-top (+ off-top 1))
                      ;; ground detection runs before the entity step: from the second frame on
                      (if (or (< f 1) (entity-ref rider #:on-ground?)) airborne (+ airborne 1)))))))
      '(1 -1)))
   '(1 2 4 6)))
