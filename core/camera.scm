;;; (downstroke camera): where the view looks, as a pure function of the
;;; camera and its target.
;;;
;;; A camera is its top-left corner in world pixels (camera-x, camera-y:
;;; what the renderer subtracts) and how it follows:
;;;   deadzone:    (w . h), a box centred in the view inside which the
;;;                target moves without moving the camera; #f: none (the
;;;                camera centres the target).
;;;   follow-rate: the part of the way to its goal the camera goes each
;;;                frame: 1 snaps (the default), 1/8 glides.
;;;   bounds:      'map keeps the view inside the scene's map (the default),
;;;                (x y w h) inside that rectangle, #f anywhere. A region
;;;                smaller than the view pins the camera to its left or top.
;;;   zoom:        world pixels are drawn zoom times larger (2 shows a
;;;                quarter of the world), from 1/64 to 64; the view in
;;;                world pixels is the screen's view divided by the zoom.
;;; Every number given is finite (checked here, naming the keyword), and a
;;; target whose numbers would carry the view past the largest flonum is
;;; an error naming it.
;;; camera-shake starts a shake of a given amplitude (px) that decays by a
;;; factor each frame. The camera keeps its exact position (to 1/16 px, so
;;; that gliding exact numbers do not grow without end) and draws from a
;;; whole pixel whenever it glides or shakes, so a resting target never
;;; jitters by a pixel; the default camera (rate 1, no shake) keeps the
;;; exact centre, as Downstroke 1.0 did.

(module (downstroke camera)
  (make-camera camera? camera-x camera-y camera-deadzone camera-follow-rate
   camera-bounds camera-zoom camera-shake camera-shaking? camera-follow)

  (import scheme (chicken base) (chicken format) (chicken fixnum)
          (downstroke keywords) (downstroke entity) (downstroke map)
          (only (downstroke numbers) finite-real? check-finite lerp))

  (define-record-type camera
    (%make-camera x y exact-x exact-y deadzone rate bounds zoom shake decay seed)
    camera?
    (x camera-x) (y camera-y)                  ; drawn from here
    (exact-x camera-exact-x) (exact-y camera-exact-y)
    (deadzone camera-deadzone) (rate camera-follow-rate)
    (bounds camera-bounds) (zoom camera-zoom)
    (shake camera-shake-amplitude) (decay camera-shake-decay) (seed camera-seed))

  ;; Every number a camera is given is finite (an infinity or a NaN would
  ;; only fail later, in a frame); errors name the procedure and keyword.
  (define (check-positive who key v)
    (unless (and (finite-real? v) (positive? v))
      (error (sprintf "~a: ~a ~s must be a positive finite number" who key v))))

  (define (all-finite? l) (or (null? l) (and (finite-real? (car l)) (all-finite? (cdr l)))))

  ;; The zoom's range, that of make-game's scale: SDL's scale is a float
  ;; (a zoom of 1e300 is +inf.0 there), and a view zoomed out 1e-300
  ;; times would hold more tiles and image repeats than any frame draws.
  (define zoom-min 1/64)
  (define zoom-max 64)

  (define (check-settings who x y deadzone rate bounds zoom)
    (check-finite who "x:" x)
    (check-finite who "y:" y)
    (unless (or (not deadzone)
                (and (pair? deadzone) (finite-real? (car deadzone)) (finite-real? (cdr deadzone))
                     (>= (car deadzone) 0) (>= (cdr deadzone) 0)))
      (error (sprintf "~a: deadzone: ~s must be #f or (width . height), both finite and >= 0" who deadzone)))
    (unless (and (real? rate) (> rate 0) (<= rate 1))
      (error (sprintf "~a: follow-rate: ~s must be a number above 0 and at most 1" who rate)))
    (unless (or (not bounds) (eq? bounds 'map)
                (and (list? bounds) (= (length bounds) 4) (all-finite? bounds)
                     (>= (caddr bounds) 0) (>= (cadddr bounds) 0)))
      (error (sprintf "~a: bounds: ~s must be 'map, #f or (x y width height) of finite numbers" who bounds)))
    (check-positive who "zoom:" zoom)
    (unless (<= zoom-min zoom zoom-max)
      (error (sprintf "~a: zoom: ~s must be from ~a to ~a" who zoom zoom-min zoom-max))))

  (define/keywords (make-camera #!key (x 0) (y 0) (deadzone #f) (follow-rate 1) (bounds 'map)
                                (zoom 1))
    (check-settings 'make-camera x y deadzone follow-rate bounds zoom)
    (%make-camera x y x y deadzone follow-rate bounds zoom 0 0 1))

  (define (with-position c x y ex ey shake seed)
    (%make-camera x y ex ey (camera-deadzone c) (camera-follow-rate c) (camera-bounds c)
                  (camera-zoom c) shake (camera-shake-decay c) seed))

  ;; A shake of `amplitude` px (the larger of it and the one going on),
  ;; shrinking by `decay` each frame until it is under half a pixel.
  (define/keywords (camera-shake c amplitude #!key (decay 9/10))
    (unless (camera? c) (error (sprintf "camera-shake: ~s is not a camera" c)))
    (check-positive 'camera-shake "amplitude" amplitude)
    (unless (and (real? decay) (>= decay 0) (< decay 1))
      (error (sprintf "camera-shake: decay: ~s must be at least 0 and below 1" decay)))
    (%make-camera (camera-x c) (camera-y c) (camera-exact-x c) (camera-exact-y c)
                  (camera-deadzone c) (camera-follow-rate c) (camera-bounds c) (camera-zoom c)
                  (max amplitude (camera-shake-amplitude c)) decay (camera-seed c)))

  (define (camera-shaking? c) (positive? (camera-shake-amplitude c)))

  ;; The shake's offsets come from the spec's generator, seeded by the
  ;; camera, so that a replay shakes the same way: a number in [-1, 1].
  (define (next-seed s) (modulo (+ (* 1103515245 s) 12345) 2147483648))
  (define (unit s) (- (/ (modulo s 2049) 1024) 1))

  ;; To 1/16 px: exact numbers keep a bounded denominator.
  (define (sixteenth v)
    (if (exact? v) (/ (round (* v 16)) 16) v))

  (define (whole v) (let ((r (round v))) (if (exact? r) r (inexact->exact r))))

  ;; The goal on one axis: `centre` is the target's centre, `pos` the
  ;; camera's exact position, `view` the view's size in world pixels,
  ;; `dead` the deadzone's size on that axis (#f: none).
  (define (goal centre pos view dead)
    (if dead
        (let ((lo (+ pos (/ (- view dead) 2))) (hi (+ pos (/ (+ view dead) 2))))
          (cond ((< centre lo) (- centre (/ (- view dead) 2)))
                ((> centre hi) (- centre (/ (+ view dead) 2)))
                (else pos)))
        (- centre (/ view 2))))

  (define (clamp pos view lo extent)
    (if extent (max lo (min pos (- (+ lo extent) view))) pos))

  ;; The camera after one frame of following `target` (an entity or a
  ;; plist) with a view of view-w x view-h screen pixels, inside the map
  ;; `tilemap` (or #f) when its bounds are 'map. An infinite map's edges
  ;; are those of its chunks, negative ones included.
  ;; A target of #f keeps the camera where it is (a shake still plays out).
  (define (camera-follow c target view-w view-h tilemap)
    (let* ((target (and target (as-entity target)))
           (zoom (camera-zoom c))
           (vw (/ view-w zoom)) (vh (/ view-h zoom))
           (cx (if target
                   (+ (entity-number target #:x) (/ (entity-number target #:width) 2))
                   (+ (camera-exact-x c) (/ vw 2))))
           (cy (if target
                   (+ (entity-number target #:y) (/ (entity-number target #:height) 2))
                   (+ (camera-exact-y c) (/ vh 2))))
           (dead (and target (camera-deadzone c)))
           (rate (camera-follow-rate c))
           (bounds (camera-bounds c))
           (region (cond ((and (eq? bounds 'map) tilemap
                               (not (eq? (tilemap-orientation tilemap) 'orthogonal)))
                          ;; the picture Tiled draws of the map
                          (receive (w h) (tilemap-screen-size tilemap) (list 0 0 w h)))
                         ((and (eq? bounds 'map) tilemap)
                          (list (* (tilemap-origin-col tilemap) (tilemap-tile-width tilemap))
                                (* (tilemap-origin-row tilemap) (tilemap-tile-height tilemap))
                                (tilemap-pixel-width tilemap) (tilemap-pixel-height tilemap)))
                         ((pair? bounds) bounds)
                         (else #f)))
           (axis (lambda (centre pos view dead lo extent)
                   (let* ((g (clamp (goal centre pos view dead) view lo extent))
                          (next (if (= rate 1) g (sixteenth (lerp pos g rate)))))
                     ;; within half a pixel of a goal it will not reach: there
                     (if (< (abs (- g next)) 1/2) g next))))
           ;; a target near the largest flonum can put the view past it
           (settled (lambda (axis v)
                      (if (finite-real? v)
                          v
                          (error (sprintf "camera-follow: following ~a, the camera's ~a would be ~s"
                                          (if target (sprintf "entity ~a" (entity-label target)) "no target")
                                          axis v)))))
           (ex (settled "x" (axis cx (camera-exact-x c) vw (and dead (car dead))
                                  (if region (car region) 0) (and region (caddr region)))))
           (ey (settled "y" (axis cy (camera-exact-y c) vh (and dead (cdr dead))
                                  (if region (cadr region) 0) (and region (cadddr region)))))
           (amplitude (camera-shake-amplitude c)))
      (if (and (= rate 1) (zero? amplitude))
          (with-position c ex ey ex ey 0 (camera-seed c))
          (let* ((s1 (next-seed (camera-seed c))) (s2 (next-seed s1))
                 (ox (* amplitude (unit s1))) (oy (* amplitude (unit s2)))
                 (left (* amplitude (camera-shake-decay c))))
            (with-position c (whole (settled "x" (+ ex ox))) (whole (settled "y" (+ ey oy))) ex ey
                           (if (< left 1/2) 0 left) s2))))))
