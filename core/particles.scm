;;; (downstroke particles): particle emitters as pure data. No SDL: the
;;; renderer draws what is here, the pipeline steps it.
;;;
;;; An emitter is a value held by an entity under #:emitter; the entity's
;;; box (#:x #:y #:width #:height, size 0 for a point) is where particles
;;; are born. Each step (one per logical frame, like physics: dt is
;;; ignored)
;;;   1. ages every particle by one frame and drops those whose age reached
;;;      their lifetime; the others move: vy += gravity, then x += vx,
;;;      y += vy;
;;;   2. emits `rate` new particles (a fraction carries over to the next
;;;      frame: rate 1/4 is one every fourth frame) while emitting, plus
;;;      any pending burst, never more than max-particles alive at once.
;;; A new particle is born at a random point of the box with age 0, a
;;; lifetime (whole frames) drawn from `lifetime`, a speed (px/frame)
;;; from `speed` and a direction from `angle`: degrees clockwise from
;;; +x, y pointing down as on the screen, so 90 is down and -90 up.
;;; Ranges are a number or a list (low high); integers for lifetimes.
;;;
;;; Colour over life: a particle of age a and lifetime L has the colour
;;; color + (end-color - color) * a / L, each component (r g b a) rounded
;;; towards color (integer quotient), so a particle is born exactly
;;; `color` and fades towards end-color.
;;;
;;; Positions and velocities are flonums, computed in the same order every
;;; step, so they too are the same on every run.
;;;
;;; Randomness comes from the emitter's own generator (Park and Miller's
;;; minimal standard, s' = 16807 s mod (2^31 - 1)), seeded by `seed:`,
;;; and is part of the value: the same emitter stepped the same way gives
;;; the same particles, bit for bit, every run.
;;;
;;; Particles are drawn by the renderer (docs/rendering.org, "Particles"):
;;; a filled size-w x size-h rectangle centred on the particle, or with
;;; tile-id a tile of the entity's sprite sheet (its #:tileset or the
;;; scene's), centred likewise, colour- and alpha-modulated.

(module (downstroke particles)
  (make-emitter emitter? emitter-step emitter-burst emitter-start emitter-stop
   emitter-particles emitter-count emitter-emitting? emitter-done? emitter-seed
   emitter-rate emitter-size emitter-tile-id emitter-color emitter-end-color
   particle? particle-x particle-y particle-vx particle-vy particle-age particle-life
   particle-color emitter-for-each step-particles random-next)

  (import (downstroke keywords) (only (downstroke numbers) finite-real? lerp))
  (import scheme (chicken base) (chicken format) (chicken flonum) (chicken fixnum) srfi-4
          (downstroke entity))

  (define-record-type particle
    (make-particle x y vx vy age life)
    particle?
    (x particle-x) (y particle-y) (vx particle-vx) (vy particle-vy)
    (age particle-age) (life particle-life))

  ;; The configuration and the state: the particles, packed six flonums
  ;; each (x y vx vy age life), oldest first, in an f64vector that a step
  ;; replaces (never changes: an emitter is a value), `count` of them; the
  ;; generator's state, the fraction of a particle carried over, and the
  ;; burst still to emit. Packed, ten thousand particles are one object
  ;; for the garbage collector instead of ten thousand.
  (define-record-type emitter
    (%make-emitter rate lifetime speed angle gravity color end-color size tile-id
                   max-particles emitting? data count seed carry pending)
    emitter?
    (rate emitter-rate) (lifetime emitter-lifetime) (speed emitter-speed)
    (angle emitter-angle) (gravity emitter-gravity) (color emitter-color)
    (end-color emitter-end-color) (size emitter-size) (tile-id emitter-tile-id)
    (max-particles emitter-max-particles) (emitting? emitter-emitting?)
    (data emitter-data) (count emitter-count) (seed emitter-seed)
    (carry emitter-carry) (pending emitter-pending))

  (define-record-printer (emitter e out)
    (fprintf out "#<emitter ~a particles>" (emitter-count e)))

  (define (with-state e emitting? data count seed carry pending)
    (%make-emitter (emitter-rate e) (emitter-lifetime e) (emitter-speed e) (emitter-angle e)
                   (emitter-gravity e) (emitter-color e) (emitter-end-color e) (emitter-size e)
                   (emitter-tile-id e) (emitter-max-particles e)
                   emitting? data count seed carry pending))

  ;; The particles as records, oldest first (for a game or a test to look
  ;; at; the renderer reads the packed form with emitter-for-each).
  (define (emitter-particles e)
    (let ((d (emitter-data e)))
      (let loop ((i (fx- (emitter-count e) 1)) (out '()))
        (if (fx< i 0)
            out
            (let ((k (fx* 6 i)))
              (loop (fx- i 1)
                    (cons (make-particle (f64vector-ref d k) (f64vector-ref d (fx+ k 1))
                                         (f64vector-ref d (fx+ k 2)) (f64vector-ref d (fx+ k 3))
                                         (inexact->exact (f64vector-ref d (fx+ k 4)))
                                         (inexact->exact (f64vector-ref d (fx+ k 5))))
                          out)))))))

  ;; (proc x y r g b a) for each particle, oldest first: its place and its
  ;; colour by age (particle-color).
  (define (emitter-for-each e proc)
    (let ((d (emitter-data e)) (n (emitter-count e))
          (c0 (emitter-color e)) (c1 (emitter-end-color e)))
      (do ((i 0 (fx+ i 1))) ((fx= i n))
        (let ((k (fx* 6 i)))
          (if (eq? c0 c1)
              (proc (f64vector-ref d k) (f64vector-ref d (fx+ k 1))
                    (car c0) (cadr c0) (caddr c0) (cadddr c0))
              (let ((a (inexact->exact (f64vector-ref d (fx+ k 4))))
                    (l (inexact->exact (f64vector-ref d (fx+ k 5)))))
                (define (at from to) (fx+ from (fx/ (fx* (fx- to from) a) l)))
                (proc (f64vector-ref d k) (f64vector-ref d (fx+ k 1))
                      (at (car c0) (car c1)) (at (cadr c0) (cadr c1))
                      (at (caddr c0) (caddr c1)) (at (cadddr c0) (cadddr c1)))))))))

  ;;; Checking the configuration: each error names make-emitter and the key.

  (define (bad key v what) (error 'make-emitter (sprintf "~a is ~s, ~a" key v what)))

  ;; A range: a number, or (low high) with low <= high -> (low . high).
  (define (range key v integer?)
    (let ((ok? (lambda (x) (and (finite-real? x) (or (not integer?) (exact-integer? x))))))
      (cond ((ok? v) (cons v v))
            ((and (list? v) (= (length v) 2) (ok? (car v)) (ok? (cadr v)) (<= (car v) (cadr v)))
             (cons (car v) (cadr v)))
            (else (bad key v (if integer?
                                 "not an integer or a list (low high) of integers, low <= high"
                                 "not a number or a list (low high) of numbers, low <= high"))))))

  ;; At most this many particles per emitter: 48 MB of flonums.
  (define particle-limit 1000000)

  (define (byte? x) (and (exact-integer? x) (<= 0 x 255)))

  (define (colour key c)
    (cond ((and (list? c) (= (length c) 3) (byte? (car c)) (byte? (cadr c)) (byte? (caddr c)))
           (append c '(255)))
          ((and (list? c) (= (length c) 4) (byte? (car c)) (byte? (cadr c)) (byte? (caddr c))
                (byte? (cadddr c)))
           c)
          (else (bad key c "not a colour (r g b [a]) of integers 0-255"))))

  (define/keywords (make-emitter #!key (rate 0) (burst 0) (lifetime 30) (speed 1) (angle '(0 360))
                        (gravity 0) (color '(255 255 255)) (end-color #f) (size '(2 2))
                        (tile-id #f) (max-particles 1000) (seed 1) (emitting? #t))
    (unless (and (real? rate) (exact? rate) (>= rate 0))
      (bad "rate:" rate "not an exact number of particles per frame (0 or more; 1/4 is one every 4 frames)"))
    (unless (and (exact-integer? burst) (>= burst 0)) (bad "burst:" burst "not a whole number, 0 or more"))
    (let ((life (range "lifetime:" lifetime #t)))
      (unless (>= (car life) 1) (bad "lifetime:" lifetime "not at least 1 frame"))
      (unless (finite-real? gravity) (bad "gravity:" gravity "not a finite number"))
      (unless (and (list? size) (= (length size) 2) (exact-integer? (car size)) (exact-integer? (cadr size))
                   (>= (car size) 1) (>= (cadr size) 1))
        (bad "size:" size "not a list (w h) of whole numbers of pixels, each at least 1"))
      (unless (or (not tile-id) (and (exact-integer? tile-id) (>= tile-id 0)))
        (bad "tile-id:" tile-id "not #f or a tile id"))
      (unless (and (exact-integer? max-particles) (<= 0 max-particles particle-limit))
        (bad "max-particles:" max-particles
             (sprintf "not a whole number from 0 to ~a (an emitter's particles are one vector)"
                      particle-limit)))
      (unless (and (exact-integer? seed) (<= 1 seed 2147483646))
        (bad "seed:" seed "not an integer from 1 to 2147483646"))
      (let ((c0 (colour "color:" color)))
        (%make-emitter rate life (range "speed:" speed #f) (range "angle:" angle #f)
                       gravity c0 (if end-color (colour "end-color:" end-color) c0)
                       size tile-id max-particles (and emitting? #t)
                       (make-f64vector 0) 0 seed 0 burst))))

  ;;; The generator: Park and Miller's minimal standard. The state is a
  ;;; fixnum from 1 to 2^31 - 2; 16807 times it fits a fixnum.

  (define modulus 2147483647)
  (define (random-next s) (modulo (* s 16807) modulus))

  ;; A value of the range (lo . hi) from the state s: (values v s').
  ;; Integers (lifetimes) uniformly from lo to hi; other numbers the
  ;; point a flonum of [0, 1] of the way from lo to hi (lerp: a range
  ;; from -1e308 to 1e308 is wider than any flonum, not its points). A
  ;; range of one value draws nothing, so a fixed speed or angle stays exact.
  (define (draw-int r s)
    (if (= (car r) (cdr r))
        (values (car r) s)
        (let ((s (random-next s)))
          (values (+ (car r) (modulo s (+ 1 (- (cdr r) (car r))))) s))))

  (define (draw-real r s)
    (if (= (car r) (cdr r))
        (values (car r) s)
        (let ((s (random-next s)))
          (values (lerp (car r) (cdr r) (/ (- s 1) (- modulus 2.))) s))))

  ;; Sine and cosine of degrees, exact at the multiples of 90, so that a
  ;; straight-down fountain has vx exactly 0.
  (define pi (* 4 (atan 1)))
  (define (sine d)
    (if (and (integer? d) (zero? (modulo d 90)))
        (case (modulo (inexact->exact d) 360) ((0 180) 0) ((90) 1) (else -1))
        (sin (/ (* d pi) 180))))
  (define (cosine d) (sine (+ d 90)))

  ;; One new particle in the box x y w h, written at index k of d:
  ;; answers the generator's new state.
  (define (spawn! d k e x y w h s)
    (receive (px s) (if (zero? w) (values x s) (draw-real (cons x (+ x w)) s))
      (receive (py s) (if (zero? h) (values y s) (draw-real (cons y (+ y h)) s))
        (receive (life s) (draw-int (emitter-lifetime e) s)
          (receive (speed s) (draw-real (emitter-speed e) s)
            (receive (angle s) (draw-real (emitter-angle e) s)
              (f64vector-set! d k (exact->inexact px))
              (f64vector-set! d (fx+ k 1) (exact->inexact py))
              (f64vector-set! d (fx+ k 2) (exact->inexact (* speed (cosine angle))))
              (f64vector-set! d (fx+ k 3) (exact->inexact (* speed (sine angle))))
              (f64vector-set! d (fx+ k 4) 0.)
              (f64vector-set! d (fx+ k 5) (exact->inexact life))
              s))))))

  ;; One frame of the emitter, whose box is x y w h: see the head of the file.
  (define (emitter-step e x y w h)
    (let* ((g (exact->inexact (emitter-gravity e)))
           (old (emitter-data e))
           (n (emitter-count e))
           ;; 2. emit: the rate's whole part now, its fraction carried
           (due (+ (emitter-carry e) (if (emitter-emitting? e) (emitter-rate e) 0)))
           (whole (floor due))
           (wanted (+ whole (emitter-pending e)))
           (d (make-f64vector (fx* 6 (fx+ n (min wanted (emitter-max-particles e)))))))
      ;; 1. age, drop, move, packing the survivors at the front
      (let ((live (let loop ((i 0) (j 0))
                    (if (fx= i n)
                        j
                        (let* ((k (fx* 6 i))
                               (age (fp+ (f64vector-ref old (fx+ k 4)) 1.))
                               (life (f64vector-ref old (fx+ k 5))))
                          (if (fp>= age life)
                              (loop (fx+ i 1) j)
                              (let ((m (fx* 6 j))
                                    (vx (f64vector-ref old (fx+ k 2)))
                                    (vy (fp+ (f64vector-ref old (fx+ k 3)) g)))
                                (f64vector-set! d m (fp+ (f64vector-ref old k) vx))
                                (f64vector-set! d (fx+ m 1) (fp+ (f64vector-ref old (fx+ k 1)) vy))
                                (f64vector-set! d (fx+ m 2) vx)
                                (f64vector-set! d (fx+ m 3) vy)
                                (f64vector-set! d (fx+ m 4) age)
                                (f64vector-set! d (fx+ m 5) life)
                                (loop (fx+ i 1) (fx+ j 1)))))))))
        (let* ((spawned (max 0 (min wanted (- (emitter-max-particles e) live))))
               (total (fx+ live spawned)))
          (let loop ((i 0) (s (emitter-seed e)))
            (if (fx= i spawned)
                (with-state e (emitter-emitting? e)
                            (if (fx= (fx* 6 total) (f64vector-length d)) d (subf64vector d 0 (fx* 6 total)))
                            total s (- due whole) 0)
                (loop (fx+ i 1) (spawn! d (fx* 6 (fx+ live i)) e x y w h s))))))))

  ;; n more particles at the next step (an explosion), whether emitting or not.
  (define (emitter-burst e n)
    (unless (and (exact-integer? n) (>= n 0))
      (error 'emitter-burst (sprintf "the count is ~s, not a whole number" n)))
    (with-state e (emitter-emitting? e) (emitter-data e) (emitter-count e)
                (emitter-seed e) (emitter-carry e) (+ (emitter-pending e) n)))

  (define (emitter-start e)
    (with-state e #t (emitter-data e) (emitter-count e) (emitter-seed e) (emitter-carry e)
                (emitter-pending e)))
  (define (emitter-stop e)
    (with-state e #f (emitter-data e) (emitter-count e) (emitter-seed e) 0
                (emitter-pending e)))

  ;; Nothing alive and nothing more to come: the entity may go.
  (define (emitter-done? e)
    (and (zero? (emitter-count e)) (zero? (emitter-pending e))
         (or (not (emitter-emitting? e)) (zero? (emitter-rate e)))))

  ;; The colour (r g b a) of a particle of this emitter, by its age.
  (define (particle-color e p)
    (let ((c0 (emitter-color e)) (c1 (emitter-end-color e)))
      (if (eq? c0 c1)
          c0
          (let ((a (particle-age p)) (l (particle-life p)))
            (map (lambda (from to) (+ from (quotient (* (- to from) a) l))) c0 c1)))))

  ;; The pipeline step (skip symbol particles): an entity's #:emitter one
  ;; frame on, born in the entity's box.
  (define-pipeline (step-particles particles) (scene entity dt)
    guard: (entity-ref entity #:emitter #f)
    (let ((e (entity-ref entity #:emitter)))
      (unless (emitter? e)
        (error 'step-particles (sprintf "entity ~a: #:emitter is ~s, not an emitter (make-emitter)"
                                        (entity-label entity) e)))
      (entity-set entity #:emitter
                  (emitter-step e (entity-number entity #:x) (entity-number entity #:y)
                                (entity-number entity #:width) (entity-number entity #:height))))))
