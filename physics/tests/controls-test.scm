;;; Body controls (docs/physics.org, "Body controls"): #:max-vx, #:max-vy,
;;; #:drag, #:air-drag and #:bounce, opt-in keys, exact with integers; the
;;; engine's fast path and the readable steps agree.

(import scheme (chicken base) (chicken string) (chicken condition) (downstroke test) (downstroke entity) (downstroke scene)
        (downstroke tilemap) (downstroke pipeline))

(define (bc-ent . plist) (plist->entity plist))

;; 16 px tiles: a floor in row 6 (y 96), a wall in column 9 (x 144)
(define bc-map
  (list->tilemap '((0 0 0 0 0 0 0 0 0 1) (0 0 0 0 0 0 0 0 0 1) (0 0 0 0 0 0 0 0 0 1)
                   (0 0 0 0 0 0 0 0 0 1) (0 0 0 0 0 0 0 0 0 1) (0 0 0 0 0 0 0 0 0 1)
                   (1 1 1 1 1 1 1 1 1 1))))

;; The (x y vx vy) of the first entity after each of n frames.
(define (bc-run e n pipeline #!optional (tm bc-map))
  (let loop ((s (make-scene tilemap: tm entities: (list e))) (k 0) (out '()))
    (if (= k n)
        (reverse out)
        (let* ((s (pipeline s 16)) (e (car (scene-entities s))))
          (loop s (+ k 1) (cons (map (lambda (key) (entity-ref e key)) '(#:x #:y #:vx #:vy)) out))))))

(define (both name expected e n)
  (test (string-append name " (engine)") expected (bc-run e n engine-pipeline))
  (test (string-append name " (readable steps)") expected (bc-run e n contract-pipeline)))

(test-group "max velocity"
  (both "a falling body's vy stops growing at #:max-vy 3"
        '((10 11 0 1) (10 13 0 2) (10 16 0 3) (10 19 0 3))
        (bc-ent #:x 10 #:y 10 #:width 8 #:height 8 #:vx 0 #:vy 0 #:gravity? #t #:max-vy 3) 4)
  (both "#:max-vx clamps both ways" '((5 10 -5/2 0))
        (bc-ent #:x 15/2 #:y 10 #:width 8 #:height 8 #:vx -9 #:vy 0 #:max-vx 5/2) 1))

(test-group "drag"
  (both "#:drag on the ground takes 2 px/frame off vx each frame, down to 0"
        '((15 88 5 0) (18 88 3 0) (19 88 1 0) (19 88 0 0))
        (bc-ent #:x 10 #:y 88 #:width 8 #:height 8 #:vx 7 #:vy 0 #:gravity? #t #:on-ground? #t #:drag 2) 4)
  (both "in the air #:air-drag applies instead (here none: vx stays)"
        '((17 11 7 1))
        (bc-ent #:x 10 #:y 10 #:width 8 #:height 8 #:vx 7 #:vy 0 #:gravity? #t #:drag 2) 1)
  (both "#:air-drag 1/2 going left" '((7/2 11 -13/2 1))
        (bc-ent #:x 10 #:y 10 #:width 8 #:height 8 #:vx -7 #:vy 0 #:gravity? #t #:air-drag 1/2) 1))

(test-group "bounce"
  (both "falling onto the floor at 8 px/frame with #:bounce 1/2: leaves it at -4"
        '((10 88 0 -4) (10 85 0 -3))
        (bc-ent #:x 10 #:y 83 #:width 8 #:height 8 #:vx 0 #:vy 7 #:gravity? #t #:bounce 1/2) 2)
  (both "against the wall at 6 px/frame with #:bounce 1: back at -6"
        '((136 10 -6 0) (130 10 -6 0))
        (bc-ent #:x 133 #:y 10 #:width 8 #:height 8 #:vx 6 #:vy 0 #:bounce 1) 2)
  (both "resting on the floor it settles: gravity's 1 px/frame does not bounce"
        '((10 88 0 0) (10 88 0 0))
        (bc-ent #:x 10 #:y 88 #:width 8 #:height 8 #:vx 0 #:vy 0 #:gravity? #t #:bounce 1/2) 2))

(test-group "no controls, no change"
  (test "a body without them moves as before" '((17 11 7 1))
        (bc-run (bc-ent #:x 10 #:y 10 #:width 8 #:height 8 #:vx 7 #:vy 0 #:gravity? #t) 1 engine-pipeline))
  (test "a bad value is an error naming the key" #t
        (handle-exceptions exn
          (and (substring-index "max-vx" ((condition-property-accessor 'exn 'message "") exn)) #t)
          (bc-run (bc-ent #:x 10 #:y 10 #:width 8 #:height 8 #:vx 7 #:max-vx +nan.0) 1 engine-pipeline)
          #f)))
