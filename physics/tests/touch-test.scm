;;; Contacts per side (docs/physics.org, "Contacts"): what a body that
;;; asks (#:contacts? #t) touches after each frame, since when, and which
;;; tiles and entities; and from which side two overlapping boxes met.

(import scheme (chicken base) (downstroke test) (downstroke entity) (downstroke scene)
        (downstroke tilemap) (downstroke pipeline) (downstroke physics) (downstroke overlap))

(define (tc-ent . plist) (plist->entity plist))

;; 16 px tiles: a floor in row 4 (y 64), a wall in column 5 (x 80); tile 3
;; (one floor cell) has the kind ice
(define tc-map
  (list->tilemap '((0 0 0 0 0 1)
                   (0 0 0 0 0 1)
                   (0 0 0 0 0 1)
                   (0 0 0 0 0 1)
                   (1 1 3 1 1 1))
                 kinds: '((3 . ice))))

(define (tc-frames scene n pipeline)
  (let loop ((s scene) (k 0) (out '()))
    (if (= k n)
        (reverse out)
        (let ((s (pipeline s 16)))
          (loop s (+ k 1) (cons (car (scene-entities s)) out))))))

(test-group "contacts: tiles"
  (define standing (tc-ent #:type 'p #:x 24 #:y 52 #:width 12 #:height 12 #:gravity? #t #:contacts? #t))
  (for-each
   (lambda (pipeline)
     (let ((fs (tc-frames (make-scene tilemap: tc-map entities: (list standing)) 3 pipeline)))
       (test "on the floor: touching, for 1, 2, 3 frames; began only in the first"
             '((#t 1 #t) (#t 2 #f) (#t 3 #f))
             (map (lambda (e) (list (entity-touching? e 'floor) (entity-touch-frames e 'floor)
                                    (entity-touch-began? e 'floor)))
                  fs))
       (test "its floor tiles: solid, and ice (the kind of tile 3)" '(solid ice)
             (entity-touch-tiles (car fs) 'floor))
       (test "nothing on the other sides" '(#f #f #f)
             (map (lambda (side) (entity-touching? (car fs) side)) '(ceiling left right)))))
   (list engine-pipeline contract-pipeline))
  (let ((e (car (tc-frames (make-scene tilemap: tc-map
                                       entities: (list (tc-ent #:x 60 #:y 20 #:width 12 #:height 12 #:vx 10
                                                               #:contacts? #t)))
                           1 engine-pipeline))))
    (test "walking into the wall: the right side touches it, from this frame" '(68 #t #t (solid))
          (list (entity-ref e #:x) (entity-touching? e 'right) (entity-touch-began? e 'right)
                (entity-touch-tiles e 'right))))
  (test "in the air: no contact, and the key holds ()" '()
        (entity-ref (car (tc-frames (make-scene tilemap: tc-map
                                                entities: (list (tc-ent #:x 8 #:y 0 #:width 12 #:height 12
                                                                        #:contacts? #t)))
                                    1 engine-pipeline))
                    #:contacts))
  (test "an entity that does not ask gets no #:contacts" #f
        (assq #:contacts (car (tc-frames (make-scene tilemap: tc-map
                                                     entities: (list (tc-ent #:x 8 #:y 52 #:width 12 #:height 12
                                                                             #:gravity? #t)))
                                         2 engine-pipeline)))))

;; A foot exactly on a slope's line touches that slope cell with its
;; floor (docs/physics.org, "Contacts" and "Slopes"). 16 px tiles: the
;; floor in row 3 (y 48), a 45 degree slope (tile 3, 0 -> 16) in column
;; 2, a flat top in row 2 (y 32) from column 3.
(define (tc-slope-walk kinds x vx n pipeline mode)
  (let ((tm (list->tilemap '((0 0 0 0 0 0) (0 0 0 0 0 0) (0 0 3 1 1 1) (1 1 1 1 1 1))
                           slopes: '((3 0 16)) kinds: kinds)))
    (let loop ((s (make-scene tilemap: tm collision-mode: mode
                              entities: (list (tc-ent #:type 'w #:x x #:y (if (> vx 0) 32 16) #:width 16 #:height 16
                                                      #:vx vx #:gravity? #t #:contacts? #t))))
               (k 0) (out '()))
      (if (= k n)
          (reverse out)
          (let* ((s (pipeline s 16)) (e (car (scene-entities s))))
            (loop (scene-map-entities s (lambda (s e) (entity-set e #:vx vx))) (+ k 1)
                  (cons (list (entity-ref e #:x) (entity-ref e #:y)
                              (entity-touch-frames e 'floor) (entity-touch-tiles e 'floor))
                        out)))))))

(test-group "contacts: a foot on a slope"
  (for-each
   (lambda (mode)
     (for-each
      (lambda (pipeline name)
        (test (sprintf "up the slope (~a, ~a): the floor never lets go, the slope named where the foot is on it" name mode)
              '((20 32 5 (solid)) (24 32 6 (solid slope)) (28 28 7 (slope)) (32 24 8 (slope))
                (36 20 9 (slope)) (40 16 10 (solid)) (44 16 11 (solid)))
              (list-tail (tc-slope-walk '() 0 4 11 pipeline mode) 4))
        (test (sprintf "down it again (~a, ~a), the slope's kind when it has one" name mode)
              '((40 16 1 (solid)) (36 20 2 (ramp)) (32 24 3 (ramp)) (28 28 4 (ramp)) (24 32 5 (solid ramp))
                (20 32 6 (solid)))
              (tc-slope-walk '((3 . ramp)) 44 -4 6 pipeline mode)))
      (list engine-pipeline contract-pipeline) '("engine" "readable steps")))
   '(swept discrete))
  (test "a foot 1 px above the line touches nothing" '()
        (let* ((tm (list->tilemap '((0 0 0) (0 3 0)) slopes: '((3 0 16))))
               (b (tc-ent #:x 16 #:y 7 #:width 16 #:height 16 #:contacts? #t)))
          (entity-ref (detect-contacts (make-scene tilemap: tm entities: (list b)) b 16) #:contacts))))

(test-group "contacts: entities"
  (define (lift) (tc-ent #:type 'platform #:id 'lift #:x 0 #:y 100 #:width 48 #:height 8
                         #:solid? #t #:immovable? #t #:vx 1))
  (define (rider) (tc-ent #:type 'rider #:x 10 #:y 86 #:width 12 #:height 12
                          #:solid? #t #:gravity? #t #:contacts? #t))
  (define (crate x) (tc-ent #:type 'crate #:x x #:y 88 #:width 8 #:height 12 #:solid? #t #:immovable? #t))
  (let ((fs (tc-frames (make-scene entities: (list (rider) (lift) (crate 24))) 4 engine-pipeline)))
    (test "the rider lands in frame 2: its floor is the lift (named by #:id)" '(#f (lift) (lift) (lift))
          (map (lambda (e) (and (entity-touching? e 'floor) (entity-touch-entities e 'floor))) fs))
    (test "the lift carries it into the crate: its right side touches the crate (named by #:type)"
          '(crate)
          (entity-touch-entities (list-ref fs 3) 'right)))
  (test "the readable steps give the same contacts"
        (map (lambda (e) (entity-ref e #:contacts))
             (tc-frames (make-scene entities: (list (rider) (lift) (crate 24))) 4 engine-pipeline))
        (map (lambda (e) (entity-ref e #:contacts))
             (tc-frames (make-scene entities: (list (rider) (lift) (crate 24))) 4 contract-pipeline))))

(test-group "entity-overlap-side: from which side a met b"
  (define enemy (tc-ent #:type 'enemy #:x 20 #:y 50 #:width 16 #:height 16 #:vx -1))
  (test "falling onto it: above (a stomp), even 10 px deep" 'above
        (entity-overlap-side (tc-ent #:x 14 #:y 44 #:width 12 #:height 16 #:vy 10) enemy))
  (test "walking into its left side: left" 'left
        (entity-overlap-side (tc-ent #:x 10 #:y 52 #:width 12 #:height 12 #:vx 2) enemy))
  (test "jumping into it from below: below" 'below
        (entity-overlap-side (tc-ent #:x 22 #:y 62 #:width 12 #:height 12 #:vy -8) enemy))
  (test "already overlapping on both axes: the shallower axis decides" 'right
        (entity-overlap-side (tc-ent #:x 33 #:y 52 #:width 12 #:height 12) enemy))
  (test "boxes that do not overlap: #f" #f
        (entity-overlap-side (tc-ent #:x 36 #:y 52 #:width 12 #:height 12) enemy)))
