;;; One-way (jump-through) platforms: tiles and entities. A body lands on
;;; one only falling, from at or above its top; it passes through from
;;; below and from the side, and drops through on purpose with
;;; #:drop-through?.

(import scheme (chicken base) (chicken format) (chicken file) (chicken io) (chicken condition) (chicken string)
        (downstroke test) (downstroke entity) (downstroke scene) (downstroke tilemap)
        (downstroke pipeline) (only (downstroke physics) detect-on-solid))

(define (ow-ent . plist) (plist->entity plist))

;; 16 px tiles, 8 wide and 8 tall; row 4 (y 64 to 80) holds one-way tile 2
;; in columns 2-5; row 7 is solid floor.
(define ow-map
  (list->tilemap '((0 0 0 0 0 0 0 0)
                   (0 0 0 0 0 0 0 0)
                   (0 0 0 0 0 0 0 0)
                   (0 0 0 0 0 0 0 0)
                   (0 0 2 2 2 2 0 0)
                   (0 0 0 0 0 0 0 0)
                   (0 0 0 0 0 0 0 0)
                   (1 1 1 1 1 1 1 1))
                 one-way: '(2)))

(define (ow-run scene frames)
  (if (= frames 0) scene (ow-run (engine-pipeline scene 16) (- frames 1))))

(define (ow-body scene) (car (scene-entities scene)))

(define (ow-scene body . more)
  (make-scene tilemap: ow-map entities: (cons body more)
              collision-mode: (entity-ref body #:mode 'discrete)))

(define (ow-at e) (list (entity-ref e #:x) (entity-ref e #:y) (entity-ref e #:vy)))

(test-group "one-way tiles"
  (test "the map knows which cells are one-way, and they are not solid" '(#t #f #f #t)
        (list (tilemap-one-way? ow-map 2 4) (tilemap-solid? ow-map 2 4)
              (tilemap-one-way? ow-map 0 7) (tilemap-solid? ow-map 0 7)))
  (for-each
   (lambda (mode)
     (let ((body (lambda more (apply ow-ent #:mode mode #:collision-mode mode #:x 40 #:width 12 #:height 12 more))))
       (test (sprintf "~a: a body falling onto it from above lands on its top" mode)
             '(40 52 0 #t)
             (let ((e (ow-body (ow-run (ow-scene (body #:y 20 #:gravity? #t)) 40))))
               (append (ow-at e) (list (entity-ref e #:on-ground?)))))
       (test (sprintf "~a: a body jumping from below passes up through it" mode) #t
             ;; from the floor (y 100) a jump of 10 rises 45 px: its feet clear row 4's top
             (let loop ((s (ow-scene (body #:y 100 #:gravity? #t #:ay -12))) (f 0) (above? #f))
               (if (= f 14)
                   above?
                   (let* ((s (engine-pipeline s 16)) (e (ow-body s)))
                     (loop s (+ f 1) (or above? (< (+ (entity-ref e #:y) 12) 64)))))))
       (test (sprintf "~a: the jumper then lands on it from above" mode) '(52 #t)
             (let ((e (ow-body (ow-run (ow-scene (body #:y 100 #:gravity? #t #:ay -12)) 40))))
               (list (entity-ref e #:y) (entity-ref e #:on-ground?))))
       (test (sprintf "~a: a body moving sideways passes through it" mode) '(120 66)
             (let ((e (ow-body (ow-run (ow-scene (ow-ent #:mode mode #:collision-mode mode #:x 0 #:y 66
                                                         #:width 12 #:height 12 #:vx 8))
                                       15))))
               (list (entity-ref e #:x) (entity-ref e #:y))))
       (test (sprintf "~a: a body whose feet were below its top falls on through" mode) '(100 0)
             ;; bottom at 70 at the start: inside the platform row
             (let ((e (ow-body (ow-run (ow-scene (body #:y 58 #:gravity? #t)) 30))))
               (list (entity-ref e #:y) (entity-ref e #:vy))))
       (test (sprintf "~a: #:drop-through? falls through from on top" mode) '(100 #t)
             (let ((e (ow-body (ow-run (ow-scene (body #:y 52 #:gravity? #t #:drop-through? #t)) 30))))
               (list (entity-ref e #:y) (entity-ref e #:on-ground?))))
       (test (sprintf "~a: standing on it and then dropping: not on the ground the frame it drops" mode) #f
             (let* ((s (ow-run (ow-scene (body #:y 52 #:gravity? #t)) 3))
                    (s (update-scene s entities: (list (entity-set (ow-body s) #:drop-through? #t)))))
               (entity-ref (ow-body (engine-pipeline s 16)) #:on-ground?)))))
   '(discrete swept))
  (let ((e (ow-body (engine-pipeline (ow-scene (ow-ent #:x 40 #:y 52 #:width 12 #:height 12 #:gravity? #t
                                                       #:skip-pipelines '(velocity-y)))
                                     16))))
    (test "a body that skips velocity-y is not stopped by it (it did not fall)" '(52 1) (list (entity-ref e #:y) (entity-ref e #:vy)))))

;; Falling from row 0 onto the platform at speed v for one frame at a time:
;; does it stop on the top (y 52) or pass it?
(define (ow-fall mode v)
  (let loop ((s (ow-scene (ow-ent #:mode mode #:collision-mode mode #:x 40 #:y 0 #:width 12 #:height 12 #:vy v)))
             (f 0))
    (let* ((e (ow-body s)) (y (entity-ref e #:y)))
      (cond ((= y 52) 'landed)
            ((> y 52) 'passed)
            ((= f 200) 'stuck)
            (else (loop (engine-pipeline s 16) (+ f 1)))))))

(test-group "one-way tiles at speed"
  (test "swept: a falling body lands on a one-way top at every speed"
        '(landed landed landed landed landed landed landed)
        (map (lambda (v) (ow-fall 'swept v)) '(1 7 16 27 28 29 1000)))
  ;; discrete sees only the cells covered after the move: a body of 12 px
  ;; on 16 px tiles is safe below 28 px/frame, as against a wall
  (test "discrete: it lands below 12 + 16 = 28 px/frame"
        '(landed landed landed landed)
        (map (lambda (v) (ow-fall 'discrete v)) '(1 7 16 27)))
  (test-assert "discrete: and at 1000 px/frame it passes"
               (eq? 'passed (ow-fall 'discrete 1000))))

;; Tiled's ways of saying it: a tile property in the tileset, or a layer
;; property.
(define (ow-tmx path layer-props tile-props)
  (with-output-to-file path
    (lambda ()
      (print "<?xml version=\"1.0\" encoding=\"UTF-8\"?>")
      (print "<map version=\"1.8\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"4\" height=\"2\" tilewidth=\"16\" tileheight=\"16\" infinite=\"0\" nextlayerid=\"3\" nextobjectid=\"1\">")
      (print " <tileset firstgid=\"1\" name=\"t\" tilewidth=\"16\" tileheight=\"16\" tilecount=\"2\" columns=\"2\">")
      (print "  <image source=\"../docs/images/demo-getting-started.png\" width=\"320\" height=\"240\"/>")
      (print tile-props)
      (print " </tileset>")
      (print " <layer id=\"1\" name=\"ground\" width=\"4\" height=\"2\">")
      (print layer-props)
      (print "  <data encoding=\"csv\">1,2,1,2,0,0,0,0</data>")
      (print " </layer>")
      (print "</map>"))))

(test-group "one-way in Tiled: a tile property or a layer property"
  ;; written beside the tests, so that the tileset's image (a PNG of the
  ;; docs) is found
  (let ((path (sprintf "oneway-~a.tmx" (current-process-id))))
    (ow-tmx path "" "  <tile id=\"1\"><properties><property name=\"one-way\" type=\"bool\" value=\"true\"/></properties></tile>")
    (let ((tm (load-tilemap path)))
      (test "tile 2 of the tileset is one-way, tile 1 solid" '((#t #f) (#f #t))
            (list (list (tilemap-one-way? tm 1 0) (tilemap-solid? tm 1 0))
                  (list (tilemap-one-way? tm 0 0) (tilemap-solid? tm 0 0)))))
    (ow-tmx path "  <properties><property name=\"one-way\" type=\"bool\" value=\"true\"/></properties>" "")
    (let ((tm (load-tilemap path)))
      (test "a layer with one-way set: every tile of it" '(#t #t #f)
            (list (tilemap-one-way? tm 0 0) (tilemap-one-way? tm 1 0) (tilemap-solid? tm 0 0))))
    (ow-tmx path "  <properties><property name=\"one-way\" type=\"string\" value=\"true\"/></properties>" "")
    (test-error "only a bool property counts: the string \"true\" is an error naming the layer and the fix"
                (lambda (e) (let ((m ((condition-property-accessor 'exn 'message "") e)))
                              (and (substring-index "layer \"ground\": property one-way is \"true\", of type string, not a bool" m)
                                   (substring-index "type=\"bool\"" m))))
                (load-tilemap path))
    (delete-file* path)))

(test-group "one-way entities"
  (define (platform . more)
    (apply ow-ent #:type 'platform #:x 0 #:y 100 #:width 64 #:height 8
           #:solid? #t #:immovable? #t #:one-way? #t more))
  (define (body . more)
    (apply ow-ent #:type 'body #:x 20 #:width 12 #:height 12 #:solid? #t #:gravity? #t more))
  (define (run es frames) (scene-entities (ow-run (make-scene entities: es) frames)))
  (define (the type es) (let loop ((es es)) (if (eq? (entity-ref (car es) #:type) type) (car es) (loop (cdr es)))))
  (test "a body falling onto it lands on its top and stands" '(88 #t)
        (let ((b (the 'body (run (list (platform) (body #:y 40)) 40))))
          (list (entity-ref b #:y) (entity-ref b #:on-ground?))))
  (test "a body jumping from below passes up through it and lands on top" '(88 #t)
        (let ((b (the 'body (run (list (platform) (body #:y 120 #:vy -14)) 60))))
          (list (entity-ref b #:y) (entity-ref b #:on-ground?))))
  (test "while rising through it the body is not on the ground" #f
        (let ((b (the 'body (run (list (platform) (body #:y 105 #:vy -3)) 1))))
          (entity-ref b #:on-ground?)))
  (test "a body walking into its side passes through" '(80 102)
        (let ((b (the 'body (run (list (platform) (ow-ent #:type 'body #:x 0 #:y 102 #:width 12 #:height 12
                                                           #:solid? #t #:vx 4)) 20))))
          (list (entity-ref b #:x) (entity-ref b #:y))))
  (test "#:drop-through? falls through" #t
        (let ((b (the 'body (run (list (platform) (body #:y 88 #:drop-through? #t)) 20))))
          (> (entity-ref b #:y) 108)))
  ;; the body lands in the second frame and rides the other 19: 20 + 2 * 19
  (test "a moving one-way platform carries its rider" '(40 58 88)
        (let* ((es (run (list (platform #:vx 2) (body #:y 86)) 20)))
          (list (entity-ref (the 'platform es) #:x) (entity-ref (the 'body es) #:x) (entity-ref (the 'body es) #:y)))))

;; docs/physics.org, "One-way platforms": a body with #:drop-through? is
;; not held by a one-way lift either, and a landing is judged from where
;; the body was when the frame began (its #:frame-start), whatever moved
;; it since: its velocity, a push, or nothing.
(test-group "one-way entities: dropping through a lift, and where the frame began"
  (define (ledge . more)
    (apply ow-ent #:type 'ledge #:x 0 #:y 100 #:width 48 #:height 8
           #:solid? #t #:immovable? #t #:one-way? #t more))
  (define (the type es) (let loop ((es es)) (if (eq? (entity-ref (car es) #:type) type) (car es) (loop (cdr es)))))
  ;; each frame's (y vy) of the entity of that type
  (define (frames es type n)
    (let loop ((s (make-scene entities: es)) (k 0) (out '()))
      (if (= k n)
          (reverse out)
          (let ((s (engine-pipeline s 16)))
            (loop s (+ k 1) (cons (let ((e (the type (scene-entities s))))
                                    (list (entity-ref e #:y) (entity-ref e #:vy)))
                                  out))))))
  (test "a drop-through rider falls through a lift going down (it is not carried)"
        '((89 1) (91 2) (94 3))
        (frames (list (ledge #:vy 3)
                      (ow-ent #:type 'rider #:x 10 #:y 88 #:width 12 #:height 12
                              #:gravity? #t #:solid? #t #:drop-through? #t))
                'rider 3))
  (test "without #:drop-through? the lift carries it down" '((91 0) (94 0) (97 0))
        (frames (list (ledge #:vy 3)
                      (ow-ent #:type 'rider #:x 10 #:y 88 #:width 12 #:height 12 #:gravity? #t #:solid? #t))
                'rider 3))
  (test "a body pushed into the ledge from above lands on it (its bottom was at 98)"
        '((94 0) (94 0))
        (frames (list (ow-ent #:type 'a #:x 10 #:y 80 #:width 12 #:height 16 #:solid? #t)
                      (ow-ent #:type 'b #:x 10 #:y 92 #:width 12 #:height 6 #:vy 3 #:solid? #t)
                      (ledge))
                'b 2))
  (test "a body that did not move, sunk into the ledge, stays where it is" '((95 10))
        (frames (list (ow-ent #:type 'b #:x 10 #:y 95 #:width 12 #:height 12 #:vy 10 #:solid? #t
                              #:skip-pipelines '(velocity-y))
                      (ledge))
                'b 1))
  (test "a body that came from below the top is not lifted onto it" '((97 4))
        (frames (list (ow-ent #:type 'b #:x 10 #:y 93 #:width 12 #:height 12 #:vy 4 #:solid? #t)
                      (ledge))
                'b 1))
  (test "#:frame-start is written on solid bodies only in a scene with a one-way entity" '((10 . 92) #f)
        (list (entity-ref (the 'b (scene-entities
                                   (engine-pipeline
                                    (make-scene entities: (list (ow-ent #:type 'b #:x 10 #:y 92 #:width 12 #:height 6
                                                                        #:vy 3 #:solid? #t)
                                                                (ledge)))
                                    16)))
                          #:frame-start)
              (entity-ref (the 'b (scene-entities
                                   (engine-pipeline
                                    (make-scene entities: (list (ow-ent #:type 'b #:x 10 #:y 92 #:width 12 #:height 6
                                                                        #:vy 3 #:solid? #t)
                                                                (ow-ent #:type 'ledge #:x 0 #:y 100 #:width 48 #:height 8
                                                                        #:solid? #t #:immovable? #t)))
                                    16)))
                          #:frame-start)))
  (test "the readable steps say the same" '((94 0) (94 0))
        (let loop ((s (make-scene entities: (list (ow-ent #:type 'a #:x 10 #:y 80 #:width 12 #:height 16 #:solid? #t)
                                                  (ow-ent #:type 'b #:x 10 #:y 92 #:width 12 #:height 6 #:vy 3 #:solid? #t)
                                                  (ledge))))
                   (k 0) (out '()))
          (if (= k 2)
              (reverse out)
              (let ((s (contract-pipeline s 16)))
                (loop s (+ k 1) (cons (let ((e (the 'b (scene-entities s)))) (list (entity-ref e #:y) (entity-ref e #:vy)))
                                      out)))))))

;; docs/physics.org, "Standing on things" and "One-way platforms": the
;; readings settled there.
(test-group "one-way: ground and landing, precisely"
  (define ledge (ow-ent #:type 'ledge #:x 0 #:y 100 #:width 48 #:height 8
                        #:solid? #t #:immovable? #t #:one-way? #t))
  (define (grounded? body . more)
    (entity-ref (detect-on-solid (make-scene tilemap: (and (pair? more) (car more)) entities: (list ledge body))
                                 body 16)
                #:on-ground?))
  (define (feet y vy) (ow-ent #:type 'b #:x 10 #:y y #:width 12 #:height 12 #:vy vy #:gravity? #t #:solid? #t))
  (test "a one-way entity: a body 2 px above it, not rising, is on the ground" #t (grounded? (feet 86 0)))
  (test "a one-way entity: the same body rising is not" #f (grounded? (feet 86 -1)))
  (test "a one-way entity: a rider 5 px inside it, not rising, is on the ground" #t (grounded? (feet 93 0)))
  (test "a one-way tile: a body on its top, rising, is on the ground (tiles ask no velocity)" #t
        (entity-ref (detect-on-solid (make-scene tilemap: ow-map entities: '())
                                     (ow-ent #:x 40 #:y 52 #:width 12 #:height 12 #:vy -1 #:gravity? #t) 16)
                    #:on-ground?))
  (test "landing puts the bottom on the top: y is exactly top - height, vy 0" '(88 0)
        (let ((b (car (scene-entities
                       (engine-pipeline (make-scene entities: (list (ow-ent #:type 'b #:x 10 #:y 87.3 #:width 12 #:height 12
                                                                            #:vy 2.9 #:solid? #t)
                                                                    ledge))
                                        16)))))
          (list (entity-ref b #:y) (entity-ref b #:vy)))))
