;;; The camera: deadzone, gliding, bounds, shake and zoom, as pure
;;; functions of the camera and its target.

(import scheme (chicken base) (chicken condition) (chicken format)
        (downstroke test) (downstroke entity) (downstroke map) (downstroke camera))

(define (cm-target x y) (plist->entity (list #:x x #:y y #:width 16 #:height 16)))
(define (cm-xy c) (list (camera-x c) (camera-y c)))

;; Follow `targets` (one per frame) from camera c; every camera on the way.
(define (cm-run c targets view-w view-h tm)
  (if (null? targets)
      '()
      (let ((next (camera-follow c (car targets) view-w view-h tm)))
        (cons next (cm-run next (cdr targets) view-w view-h tm)))))

(define (cm-take ls n) (if (= n 0) '() (cons (car ls) (cm-take (cdr ls) (- n 1)))))
(define (cm-repeat n x) (if (= n 0) '() (cons x (cm-repeat (- n 1) x))))

(define (cm-message thunk)
  (condition-case (begin (thunk) "no error")
    (e (exn) ((condition-property-accessor 'exn 'message) e))))

(test-group "camera: deadzone"
  ;; view 320x240, deadzone 64x32 centred: x from cam+128 to cam+192
  (let* ((c (make-camera x: 0 y: 0 deadzone: '(64 . 32)))
         (inside (camera-follow c (cm-target 142 106) 320 240 #f)))  ; centre (150, 114)
    (test "a target inside the deadzone moves nothing" '(0 0) (cm-xy inside))
    (test "leaving it on the right: its centre is kept on the zone's right edge" '(8 0)
          (cm-xy (camera-follow c (cm-target 192 106) 320 240 #f)))           ; centre 200 = 8 + 192
    (test "leaving it on the left" '(-28 0)
          (cm-xy (camera-follow c (cm-target 92 106) 320 240 #f)))            ; centre 100 = -28 + 128
    (test "leaving it below" '(0 12) (cm-xy (camera-follow c (cm-target 142 140) 320 240 #f))))
  ;; stairs: the target bobs 4 px up and down every frame while walking
  (let* ((cams (cm-run (make-camera x: 0 y: 0 deadzone: '(0 . 32))
                       (let loop ((f 0)) (if (= f 60) '() (cons (cm-target (+ 150 f) (+ 100 (* 4 (modulo f 2)))) (loop (+ f 1)))))
                       320 240 #f)))
    (test "on stairs a tall deadzone keeps the camera's y still" '(0)
          (let loop ((cs cams) (ys '()))
            (if (null? cs) ys (loop (cdr cs) (if (member (camera-y (car cs)) ys) ys (cons (camera-y (car cs)) ys))))))
    (test "while x follows the walk" (+ 150 59 8 -160) (camera-x (list-ref cams 59)))))

(test-group "camera: gliding"
  (let* ((cams (cm-run (make-camera follow-rate: 1/2) (cm-repeat 40 (cm-target 252 112)) 320 240 #f))
         (xs (map camera-x cams)))
    ;; the goal is x 100 (centre 260 - 160), y 0
    (test "half the way each frame, drawn from whole pixels" '(50 75 88 94 97 98 99 100)
          (cm-take xs 8))
    (test-assert "every drawn position is a whole pixel" (let loop ((cs cams)) (or (null? cs) (and (exact-integer? (camera-x (car cs))) (loop (cdr cs))))))
    (test "a resting target: the camera arrives exactly and stays (no jitter)" (cm-repeat 30 100)
          (list-tail xs 10)))
  (let* ((cams (cm-run (make-camera follow-rate: 1/10)
                       (let loop ((f 0)) (if (= f 2000) '() (cons (cm-target (+ 252 (* f 3/7)) 112) (loop (+ f 1)))))
                       320 240 #f))
         (last (list-ref cams 1999)))
    (test-assert "a long glide after a moving target keeps exact numbers small (1/16 px)"
                 (<= (denominator (camera-x last)) 16))
    (test-assert "and trails it by a bounded amount"
                 (< (abs (- (camera-x last) (- (+ 260 (* 1999 3/7)) 160))) 10))))

(test-group "camera: bounds"
  ;; an isometric map of 40 x 30 cells of 32 x 16 is drawn (40 + 30) * 16
  ;; by (40 + 30) * 8 = 1120 x 560 pixels: 'map keeps the view in that
  (let* ((ortho (list->tilemap (cm-repeat 30 (cm-repeat 40 0)) tile-width: 32 tile-height: 16))
         (iso (make-tilemap 40 30 32 16 (tilemap-layers ortho)
                            info: '((orientation . isometric)))))
    (test "'map on an isometric map: the picture Tiled draws of it" '(800 320)
          (cm-xy (camera-follow (make-camera) (cm-target 2000 2000) 320 240 iso)))
    (test "'map on an orthogonal map of the same cells: its pixel size" '(960 240)
          (cm-xy (camera-follow (make-camera) (cm-target 2000 2000) 320 240 ortho))))
  (let ((tm (list->tilemap (cm-repeat 30 (cm-repeat 40 0)))))   ; 640 x 480 px
    (test "'map (the default) keeps the view in the map" '(320 240)
          (cm-xy (camera-follow (make-camera) (cm-target 630 470) 320 240 tm)))
    (test "#f lets it go anywhere" '(478 358)
          (cm-xy (camera-follow (make-camera bounds: #f) (cm-target 630 470) 320 240 tm)))
    (test "a rectangle (x y w h) keeps the view in it" '(100 50)
          (cm-xy (camera-follow (make-camera bounds: '(100 50 400 300)) (cm-target 10 10) 320 240 tm)))
    (test "and at its far corner" '(180 110)
          (cm-xy (camera-follow (make-camera bounds: '(100 50 400 300)) (cm-target 630 470) 320 240 tm)))
    (test "a rectangle smaller than the view pins it to its top-left" '(100 50)
          (cm-xy (camera-follow (make-camera bounds: '(100 50 100 100)) (cm-target 630 470) 320 240 tm)))))

(test-group "camera: shake"
  (let* ((c (camera-shake (make-camera x: 100 y: 100) 8 decay: 1/2))
         (cams (cm-run c (cm-repeat 12 (cm-target 252 212)) 320 240 #f))
         (offsets (map (lambda (k) (list (- (camera-x k) 100) (- (camera-y k) 100))) cams)))
    (test-assert "it shakes: the first frame is off its place" (not (equal? (car offsets) '(0 0))))
    (test-assert "never by more than the amplitude"
                 (let loop ((os offsets)) (or (null? os) (and (<= (abs (caar os)) 8) (<= (abs (cadar os)) 8) (loop (cdr os))))))
    (test "amplitude 8 halving: shaking for 4 frames, then still at its place"
          '((#t #t #t #t #f #f) (0 0))
          (list (map camera-shaking? (cm-take cams 6)) (list-ref offsets 11)))
    (test "the same shake twice is the same (a replay shakes alike)" (map cm-xy cams)
          (map cm-xy (cm-run c (cm-repeat 12 (cm-target 252 212)) 320 240 #f))))
  (let* ((c (camera-shake (make-camera x: 40 y: 30 bounds: #f) 5 decay: 1/2))
         (cams (cm-run c (cm-repeat 8 #f) 320 240 #f)))
    (test "without a target the camera stays and the shake plays out" '((40 30) #f)
          (list (cm-xy (list-ref cams 7)) (camera-shaking? (list-ref cams 7))))
    (test-assert "having shaken on the way" (not (equal? (cm-xy (car cams)) '(40 30)))))
  (test "a stronger shake replaces a weaker one, a weaker one does not"
        '(#t #t)
        (let ((c (camera-shake (make-camera) 3)))
          (list (camera-shaking? (camera-shake c 6)) (camera-shaking? (camera-shake c 1))))))

(test-group "camera: zoom"
  (test "zoom 2: the view is 160 x 120 world pixels, centred on the target" '(120 140)
        (cm-xy (camera-follow (make-camera zoom: 2) (cm-target 192 192) 320 240 #f)))
  (test "zoom 1/2: 640 x 480 world pixels" '(-120 -40)
        (cm-xy (camera-follow (make-camera zoom: 1/2) (cm-target 192 192) 320 240 #f))))

(test-group "camera: settings are checked"
  (test "zoom: 0" "make-camera: zoom: 0 must be a positive finite number"
        (cm-message (lambda () (make-camera zoom: 0))))
  (test "follow-rate: 2" "make-camera: follow-rate: 2 must be a number above 0 and at most 1"
        (cm-message (lambda () (make-camera follow-rate: 2))))
  (test "a deadzone that is not a pair" "make-camera: deadzone: 64 must be #f or (width . height), both finite and >= 0"
        (cm-message (lambda () (make-camera deadzone: 64))))
  (test "bounds of three numbers" "make-camera: bounds: (1 2 3) must be 'map, #f or (x y width height) of finite numbers"
        (cm-message (lambda () (make-camera bounds: '(1 2 3)))))
  (test "a misspelt keyword" "make-camera: unknown keyword deadzon: (did you mean deadzone:?)"
        (cm-message (lambda () (make-camera deadzon: '(1 . 1))))))
