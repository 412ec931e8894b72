;;; (downstroke contacts): bodies against bodies: ground detection, solid entities pushed apart, riders carried, one-way entities.
;;;
;;; docs/physics.org, "Standing on things" (detect-on-solid) and "Solid
;;; entities" (record-frame-start, resolve-entity-collisions).

(module (downstroke contacts)
  (detect-on-solid record-frame-start resolve-entity-collisions
   aabb-overlap? entity-solid-support-below? resolve-pair push-apart
   ;; for sibling modules only: push-apart without contacts.c, and
   ;; contacts.c's whole push, for tests
   push-apart/scheme push-apart/c push-keys)

  (import scheme (chicken base) (chicken fixnum) (chicken foreign) (chicken blob)
          (downstroke entity) (downstroke scene) (downstroke broadphase)
          (downstroke body) (downstroke tuning) (downstroke tile-collisions))

  (foreign-declare "#include \"physics/body.h\"")
  (foreign-declare "#include \"physics/contacts.c\"")

  ;;; Standing on things

  ;; Entity ground: a solid entity other than the mover that overlaps it
  ;; horizontally, whose top is within the contact tolerance of the mover's
  ;; bottom, while the mover's |vy| is within *entity-ground-vy-max*.
  ;; "Other" means not the same object (eq?), as the pipeline passes them.
  (define (entity-solid-support-below? entity solids)
    (entity-ground? entity solids (num entity #:x) (num entity #:width)
                    (+ (num entity #:y) (num entity #:height)) (num entity #:vy)))

  (define (entity-ground? entity solids x w bottom vy)
    (and (pair? solids)
         (<= (abs vy) *entity-ground-vy-max*)
         (if (at-least? solids index-from)
             ;; many solids: only those whose top is near the feet
             (let* ((si (support-index solids))
                    (v (car si))
                    (index (cdr si))
                    (tol *entity-ground-contact-tolerance*)
                    (count (box-index-gather! index x (- bottom tol) w (* 2 tol))))
               (if (fx< count 0)
                   (let loop ((ks (box-index-near index x (- bottom tol) w (* 2 tol))))
                     (and (pair? ks)
                          (or (supports? (vector-ref v (car ks)) entity x w bottom vy)
                              (loop (cdr ks)))))
                   (supported-among? (box-index-buffer index) count v entity x w bottom vy tol)))
             (let loop ((solids solids))
               (and (pair? solids)
                    (or (supports? (car solids) entity x w bottom vy)
                        (loop (cdr solids))))))))

  ;; Whether one of the candidates buf[0..count) (indices into the vector
  ;; of solids v) supports the entity: supports? for each in turn, the
  ;; common cases judged in C (contacts.c, ds_ground_scan), which hands
  ;; back a candidate it cannot judge (and all of them, for a mover whose
  ;; numbers it does not take). C judges fixnums and flonums only, with
  ;; exactly supports?'s answer; everything else is supports?'s.
  (define ground-keys (vector #:solid? #:one-way? #:x #:width #:y))
  (define (supported-among? buf count v entity x w bottom vy tol)
    (let scan ((from 0))
      (let ((r (##core#inline "ds_ground_scan" buf from count v entity x w bottom tol ground-keys)))
        (cond ((eq? r -2) #t)
              ((eq? r -1) #f)
              ((eq? r -3)
               (let loop ((i from))
                 (and (fx< i count)
                      (or (supports? (vector-ref v (vector-ref buf i)) entity x w bottom vy)
                          (loop (fx+ i 1))))))
              (else (or (supports? (vector-ref v (vector-ref buf r)) entity x w bottom vy)
                        (scan (fx+ r 1))))))))

  (define (supports? s entity x w bottom vy)
    (and (not (eq? s entity))
         (entity-ref s #:solid? #f)
         (< x (+ (num s #:x) (num s #:width)))
         (< (num s #:x) (+ x w))
         (<= (abs (- (num s #:y) bottom))
             *entity-ground-contact-tolerance*)
         ;; a one-way platform holds no one rising through it,
         ;; dropping through it or climbing through it
         (or (not (entity-ref s #:one-way? #f))
             (and (>= vy 0) (not (passes-one-way-entities? entity))))))

  ;; Whether one-way entities let this body through: it has
  ;; #:drop-through?, or it is climbing a ladder (docs/physics.org,
  ;; "Ladders"), as one-way tiles do.
  (define (passes-one-way-entities? e)
    (or (entity-ref e #:drop-through? #f) (climbing? e)))

  ;; From this many solid entities on, ground detection asks a spatial
  ;; hash of their tops (broadphase.scm) instead of walking them all for
  ;; every body: the same answer, without the cost growing with the square
  ;; of the crowd. The hash of a frame's solid list is kept while the
  ;; scene's cached list is the same object.
  (define index-from 48)

  (define (at-least? ls n)
    (let loop ((ls ls) (n n)) (or (fx= n 0) (and (pair? ls) (loop (cdr ls) (fx- n 1))))))

  (define last-support (cons #f #f))     ; (solids . (vector . index))

  (define (support-index solids)
    (if (eq? (car last-support) solids)
        (cdr last-support)
        (let* ((v (list->vector solids))
               ;; each solid as its top edge
               (index (make-box-index (vector-length v)
                                      (lambda (k)
                                        (let ((s (vector-ref v k)))
                                          (values (num s #:x) (num s #:y) (num s #:width) 0)))))
               (entry (cons v index)))
          (set! last-support (cons solids entry))
          entry)))

  ;; Ground detection (docs/physics.org, Standing on things), reading the
  ;; entity in one walk.
  (define (detect-on-solid scene entity dt)
    (entity-let entity ((gp #:gravity?) (skipp #:skip-pipelines) (known #:on-ground?)
                        (xp #:x) (yp #:y) (wp #:width) (hp #:height) (vyp #:vy))
      (if (and gp (cdr gp)
               (not (and skipp (cdr skipp) (memq 'on-solid (cdr skipp)))))
          (let* ((read (lambda (p key) (read-number entity p key)))
                 (tm (scene-tilemap scene))
                 (ground? (or (and tm (tile-ground? tm (read xp #:x) (read yp #:y)
                                                    (read wp #:width) (read hp #:height)
                                                    (entity-ref entity #:drop-through? #f)))
                              (entity-ground? entity (scene-solid-entities scene)
                                              (read xp #:x) (read wp #:width)
                                              (+ (read yp #:y) (read hp #:height))
                                              (read vyp #:vy)))))
            (if (and known (eq? (cdr known) ground?))
                entity
                (entity-set entity #:on-ground? ground?)))
          entity)))

  ;;; Entity against entity

  ;; floor(p) for an exact p, inline: a rational n/d (d > 1, in lowest
  ;; terms) is never an integer, so its floor is n quotient d, less one
  ;; below zero.
  (define-inline (integer-part p)
    (if (ratnum? p)
        (let ((q (quotient (numerator p) (denominator p))))
          (if (negative? (numerator p)) (- q 1) q))
        p))

  ;; Whether the spans [p1, p1+s1) and [p2, p2+s2) certainly do not meet,
  ;; judged by floor(p1) and floor(p2) when both are exact and both sizes
  ;; integers: p1 >= floor(p1) >= floor(p2) + 1 + s2 > p2 + s2. #f means
  ;; "not certain", and the exact comparison decides.
  (define-inline (apart-on-axis? p1 s1 p2 s2)
    (and (exact? p1) (exact? p2) (exact-integer? s1) (exact-integer? s2)
         (not (and (fixnum? p1) (fixnum? p2)))   ; integers compare fast anyway
         (let ((f1 (integer-part p1)) (f2 (integer-part p2)))
           (or (>= f1 (+ f2 1 s2)) (>= f2 (+ f1 1 s1))))))

  ;; Strict overlap: rectangles that only share an edge do not overlap.
  ;; Boxes of fixnums and flonums are compared in C (contacts.c), with
  ;; exactly the answer of the comparisons below: these make a flonum for
  ;; each sum of a flonum, four new objects in the nursery a pair.
  ;; Exact rationals (bodies pushed apart by halves) make each comparison
  ;; a multiplication of big integers, so boxes at least a pixel apart
  ;; are told apart first by the integer parts of their coordinates.
  ;; Inline for the pair pass; aabb-overlap? is the same as a procedure.
  (define-inline (boxes-overlap? x1 y1 w1 h1 x2 y2 w2 h2)
    (let ((fast (##core#inline "ds_boxes_overlap" x1 y1 w1 h1 x2 y2 w2 h2)))
      (if (eq? fast -1)
          (exact-boxes-overlap? x1 y1 w1 h1 x2 y2 w2 h2)
          (eq? fast 1))))

  ;; The comparisons in Scheme, for any numbers.
  (define-inline (exact-boxes-overlap? x1 y1 w1 h1 x2 y2 w2 h2)
    (and (not (apart-on-axis? x1 w1 x2 w2))
         (not (apart-on-axis? y1 h1 y2 h2))
         (< x1 (+ x2 w2)) (< x2 (+ x1 w1))
         (< y1 (+ y2 h2)) (< y2 (+ y1 h1))))

  (define (aabb-overlap? x1 y1 w1 h1 x2 y2 w2 h2)
    (boxes-overlap? x1 y1 w1 h1 x2 y2 w2 h2))

  (define (overlap-1d p1 s1 p2 s2)
    (- (min (+ p1 s1) (+ p2 s2)) (max p1 p2)))

  (define (axis-keys axis)
    (if (eq? axis 'x) (values #:x #:width #:vx) (values #:y #:height #:vy)))

  ;; Whether `a` goes to the negative side of `b` on the axis: its centre is
  ;; smaller; with equal centres the later entity of the pair does.
  (define (goes-negative? a b axis a-is-later?)
    (let-values (((pos size vel) (axis-keys axis)))
      (let ((ca (+ (* 2 (num a pos)) (num a size)))
            (cb (+ (* 2 (num b pos)) (num b size))))
        (or (< ca cb) (and (= ca cb) a-is-later?)))))

  ;; Move `e` by `delta` on the axis and set that axis's velocity: one
  ;; new version of the body.
  (define (shift e axis delta velocity)
    (let-values (((pos size vel) (axis-keys axis)))
      (entity-set* e pos (+ (num e pos) delta) vel velocity)))

  ;; The axis of least penetration; a tie goes to y.
  (define (shallow-axis a b)
    (let ((ox (overlap-1d (num a #:x) (num a #:width) (num b #:x) (num b #:width)))
          (oy (overlap-1d (num a #:y) (num a #:height) (num b #:y) (num b #:height))))
      (if (< ox oy) (values 'x ox) (values 'y oy))))

  (define (overlap-on a b axis)
    (let-values (((pos size vel) (axis-keys axis)))
      (overlap-1d (num a pos) (num a size) (num b pos) (num b size))))

  ;; Two movable bodies: each moves half the overlap away from the other
  ;; along the shallow axis, with velocity -1 / +1 on that axis.
  ;; a is the earlier entity of the pair.
  (define (push-apart/scheme a b)
    (let-values (((axis depth) (shallow-axis a b)))
      (push-by a b axis depth (goes-negative? a b axis #f))))

  (define (push-by a b axis depth a-negative?)
    (let ((half (/ depth 2)))
      (if a-negative?
          (values (shift a axis (- half) -1) (shift b axis half 1))
          (values (shift a axis half 1) (shift b axis (- half) -1)))))

  ;; The same, made in C for the common bodies (contacts.c, ds_push_pair:
  ;; both new versions in one pass, no generic arithmetic); a pair it
  ;; leaves has the axis and the side decided in C for boxes of fixnums
  ;; and flonums (ds_push_sides: no flonum made), and the push's numbers
  ;; made here as above. A crowd pushes more pairs per body the denser it
  ;; is (docs/performance.org, "S5: the pushes and the pair test in C").
  (define (push-apart a b)
    (let ((pushed (push-apart/c a b push-keys)))
      (cond ((pair? pushed) (values (car pushed) (cdr pushed)))
            ((eq? pushed -1) (push-apart/scheme a b))     ; a rational or a bignum
            (else (push-apart/sides a b)))))

  (define (push-apart/sides a b)
    (let ((sides (##core#inline "ds_push_sides" a b box-keys)))
      (if (eq? sides -1)
          (push-apart/scheme a b)
          (let ((axis (if (fx< sides 2) 'x 'y)))
            (push-by a b axis (overlap-on a b axis) (fx= 0 (fxand sides 1)))))))

  ;; (push-apart/c a b keys): the two pushed bodies as a pair, #f for a
  ;; pair the C leaves, -1 for one whose numbers only the Scheme takes.
  (define push-apart/c
    ((foreign-primitive scheme-object ()
       "C_word *a = C_alloc(2);"
       "a[0] = C_CLOSURE_TYPE | 1; a[1] = (C_word)ds_push_pair;"
       "C_return((C_word)a);")))

  (define push-keys (vector #:x #:y #:width #:height #:vx #:vy))

  ;; Where a body was at the start of the frame's engine update, as
  ;; #:frame-start (x . y), a key the library owns: the pipeline's first
  ;; step writes it on every immovable body, so that the entity step knows
  ;; what the body did this frame, whatever moved it (its velocity, a
  ;; tween, a tile snap, the game); and, in a scene that holds a one-way
  ;; entity, on every other solid body too, so that a landing on a one-way
  ;; platform is judged from where the body was before this frame's move
  ;; (land-on-one-way). Other scenes pay nothing for the second.
  (define-pipeline (record-frame-start frame-start) (scene entity dt)
    guard: (or (entity-ref entity #:immovable? #f)
               (and (entity-ref entity #:solid? #f) (one-way-scene? scene)))
    (let ((x (num entity #:x)) (y (num entity #:y))
          (old (entity-ref entity #:frame-start #f)))
      (if (and (pair? old) (eqv? (car old) x) (eqv? (cdr old) y))
          entity
          (entity-set entity #:frame-start (cons x y)))))

  ;; Whether the scene holds a one-way entity (#:one-way? true), asked for
  ;; every solid body by record-frame-start: the answer for the last
  ;; scene asked about is kept, so a frame walks its list once.
  (define last-one-way (cons #f #f))     ; (scene . answer)
  (define (one-way-scene? scene)
    (if (eq? (car last-one-way) scene)
        (cdr last-one-way)
        (let ((answer (let loop ((es (scene-entities scene)))
                        (and (pair? es)
                             (or (and (entity-ref (car es) #:one-way? #f) #t)
                                 (loop (cdr es)))))))
          (set! last-one-way (cons scene answer))
          answer)))

  ;; How far a body moved since record-frame-start: 0 and 0 without a
  ;; record (a body that did not move, or a pipeline without that step).
  (define (frame-displacement e)
    (let ((start (entity-ref e #:frame-start #f)))
      (if (pair? start)
          (values (- (num e #:x) (car start)) (- (num e #:y) (cdr start)))
          (values 0 0))))

  ;; A movable body against an immovable one: the mover alone moves the full
  ;; overlap, and its velocity on that axis becomes 0. A mover falling onto
  ;; it (vy > 0) while its centre is above the immovable's is separated
  ;; vertically (a landing), so a rider is never shoved sideways off a
  ;; platform's edge. A mover that is not falling (a walker on the floor, a
  ;; top-down body) meets it on the shallow axis like any other contact.
  ;; A mover pushed up off an immovable body rests on it, and is carried by
  ;; that body's displacement on x this frame: a moving platform takes its
  ;; rider along, and one that did not move carries nothing.
  (define (push-off mover fixed mover-is-later?)
    (let-values (((axis depth)
                  (if (and (> (num mover #:vy) 0)
                           (< (+ (* 2 (num mover #:y)) (num mover #:height))
                              (+ (* 2 (num fixed #:y)) (num fixed #:height))))
                      (values 'y (overlap-on mover fixed 'y))
                      (shallow-axis mover fixed))))
      (let* ((up? (goes-negative? mover fixed axis mover-is-later?))
             (moved (shift mover axis (if up? (- depth) depth) 0)))
        (if (and up? (eq? axis 'y))
            (carry moved fixed)
            moved))))

  (define (carry rider platform)
    (let-values (((dx dy) (frame-displacement platform)))
      (if (zero? dx)
          rider
          (entity-set rider #:x (+ (num rider #:x) dx)))))

  ;; A lift going down: `fixed` moved down by dy > 0 this frame, so its top
  ;; swept from y - dy to y. A mover not rising, overlapping it on x, whose
  ;; bottom that top swept past (or reached) stood on it: it goes down with
  ;; it, its bottom on the lift's top and its #:vy 0, and is carried on x.
  ;; (Falling 1 px a frame, it would otherwise be left behind by any lift
  ;; faster than that.)
  ;; A mover with #:drop-through?, or climbing, is not held by a one-way
  ;; lift: it falls (climbs) on.
  (define (ride-down mover fixed dy)
    (let ((top (num fixed #:y))
          (bottom (+ (num mover #:y) (num mover #:height))))
      (if (and (>= (num mover #:vy) 0)
               (not (and (entity-ref fixed #:one-way? #f) (passes-one-way-entities? mover)))
               (<= (- top dy) bottom top)
               (< (num mover #:x) (+ (num fixed #:x) (num fixed #:width)))
               (< (num fixed #:x) (+ (num mover #:x) (num mover #:width))))
          (carry (entity-set* mover #:y (- top (num mover #:height)) #:vy 0) fixed)
          mover)))

  (define (collides? e)
    (and (entity-ref e #:solid? #f)
         (not (entity-skips-pipeline? e 'entity-collisions))))

  ;; One pair, a before b in the entity list. Returns both, unchanged (eq?)
  ;; when they do not interact.
  (define (resolve-pair a b)
    (if (and (collides? a) (collides? b))
        (resolve-colliding-pair a b)
        (values a b)))

  ;; (entity-ref e key #f), inline: no call on the pair pass's path.
  (define-inline (flag e key)
    (let ((p (assq key e))) (and p (cdr p))))

  ;; A one-way entity (#:one-way?) is a jump-through platform, never
  ;; pushed: it stops only a mover falling onto it (vy > 0) whose bottom,
  ;; before this frame's move, was at or above the platform's top at the
  ;; start of the frame. "Before this frame's move" is the mover's
  ;; #:frame-start, where it was when the frame began, before its tween,
  ;; its velocity and any push; a mover without one (a pipeline that
  ;; leaves record-frame-start out) is judged from y - vy. The platform's
  ;; top is its own #:frame-start, else where it is. The mover's bottom
  ;; is put on the platform's top, #:vy 0, and it is carried like any
  ;; rider; from below and from the side it passes through, and so does
  ;; a mover with #:drop-through? or one climbing a ladder.
  (define (land-on-one-way mover platform)
    (let* ((vy (num mover #:vy))
           (start (flag platform #:frame-start))
           (top (if (pair? start) (cdr start) (num platform #:y)))
           (own (flag mover #:frame-start))
           (was (if (pair? own) (cdr own) (- (num mover #:y) vy))))
      (if (and (> vy 0)
               (not (passes-one-way-entities? mover))
               (<= (+ was (num mover #:height)) top))
          (carry (entity-set* mover #:y (- (num platform #:y) (num mover #:height)) #:vy 0) platform)
          mover)))

  ;; resolve-pair for two entities known to collide (solid, not skipping):
  ;; the pass below checks that once per entity, not once per pair.
  ;; The C test of the two boxes (contacts.c) answers only for numbers
  ;; that are fixnums or finite flonums, which let-numbers would let
  ;; through: the numbers are checked (a call each, and an error naming
  ;; the entity and the key for a bad one, as let-numbers raises it) only
  ;; when it does not answer.
  (define (resolve-colliding-pair a b)
    (define-syntax box-number
      (syntax-rules () ((_ e key) (let ((p (assq key e))) (if p (cdr p) 0)))))
    (define-syntax plain?
      (syntax-rules () ((_ v ...) (eq? (fxand* (plain-number-bit v) ...) 1))))
    (let ((ax (box-number a #:x)) (ay (box-number a #:y))
          (aw (box-number a #:width)) (ah (box-number a #:height))
          (bx (box-number b #:x)) (by (box-number b #:y))
          (bw (box-number b #:width)) (bh (box-number b #:height)))
      (let ((fast (##core#inline "ds_boxes_overlap" ax ay aw ah bx by bw bh)))
        (cond ((eq? fast 1) (collide a b))
              ((eq? fast 0) (values a b))
              ((not (plain? ax ay aw ah))
               (reject-numbers a (list #:x #:y #:width #:height) (list ax ay aw ah)))
              ((not (plain? bx by bw bh))
               (reject-numbers b (list #:x #:y #:width #:height) (list bx by bw bh)))
              ((exact-boxes-overlap? ax ay aw ah bx by bw bh) (collide a b))
              (else (values a b))))))

  ;; Two colliding entities whose boxes overlap.
  (define (collide a b)
    (let ((a-fixed (flag a #:immovable?))
          (b-fixed (flag b #:immovable?)))
      (cond ((flag a #:one-way?) (if (or b-fixed (flag b #:one-way?)) (values a b) (values a (land-on-one-way b a))))
            ((flag b #:one-way?) (if a-fixed (values a b) (values (land-on-one-way a b) b)))
            ((and a-fixed b-fixed) (values a b))
            (a-fixed (values a (push-off b a #t)))
            (b-fixed (values (push-off a b #f) b))
            (else (push-apart a b)))))

  ;; All pairs i < j in list order; each pair sees the positions left by the
  ;; pairs before it. Only entities that collide take part, so a scene with
  ;; fewer than two of them costs one scan and returns the list itself.
  ;; `method`: 'all-pairs visits every pair, as docs/physics.org describes;
  ;; 'spatial-hash visits only pairs that can overlap at their turn (see
  ;; broadphase.scm), with exactly the same result; 'auto (the default)
  ;; takes the hash from `spatial-hash-threshold` colliding entities on.
  (define spatial-hash-threshold 32)

  ;; resolve-colliding-pair where a or b may be a lift going down (da, db:
  ;; how far it went, or #f).
  (define (resolve-pair-with-lifts a b da db)
    (let-values (((a1 b1) (resolve-colliding-pair a b)))
      (cond ((not (and (eq? a1 a) (eq? b1 b))) (values a1 b1))
            ((and db (not (flag a #:immovable?))) (values (ride-down a b db) b))
            ((and da (not (flag b #:immovable?))) (values a (ride-down b a da)))
            (else (values a b)))))

  ;; How far an immovable body went down this frame, or #f.
  (define (descent e)
    (and (flag e #:frame-start)
         (flag e #:immovable?)
         (let-values (((dx dy) (frame-displacement e)))
           (and (positive? dy) dy))))

  (define box-keys (vector #:x #:y #:width #:height))

  (define (resolve-entity-collisions entities #!optional (method 'auto))
    (let* ((all (list->vector entities))
           (idx (let loop ((i (- (vector-length all) 1)) (out '()))
                  (cond ((< i 0) (list->vector out))
                        ((collides? (vector-ref all i)) (loop (- i 1) (cons i out)))
                        (else (loop (- i 1) out)))))
           (n (vector-length idx))
           ;; lifts going down, by collider; #f when there is none
           (drops (let ((v (make-vector n #f)))
                    (let loop ((p 0) (any? #f))
                      (if (fx= p n)
                          (and any? v)
                          (let ((dy (descent (vector-ref all (vector-ref idx p)))))
                            (vector-set! v p dy)
                            (loop (fx+ p 1) (or any? dy))))))))
      ;; Without lifts going down, each collider's box as
      ;; resolve-colliding-pair reads it, kept in C (contacts.c,
      ;; ds_keep_box) and read again only when a visit gives the body a
      ;; new version.
      (define boxes (and (not drops) (fx>= n 2) (take-kept-boxes n)))
      ;; true when the pair moved. Without lifts going down, a pair whose
      ;; boxes (fixnums and flonums) do not overlap is left at once, by
      ;; the test resolve-colliding-pair starts with, on the kept boxes
      ;; (contacts.c, ds_kept_apart): most pairs the hash offers are such,
      ;; and each would otherwise be a call returning two values.
      ;; A pair whose kept boxes overlap goes to collide at once.
      (define (visit! p q)
        (let ((kept (if boxes (##core#inline "ds_kept_apart" boxes p q) 0)))
          (and (not (eq? kept 1))
               (let* ((i (vector-ref idx p)) (j (vector-ref idx q)))
                 (visit-pair! i j (vector-ref all i) (vector-ref all j) p q (eq? kept 2))))))
      (define (visit-pair! i j a0 b0 p q overlap?)
        (let-values (((a b) (cond (drops (resolve-pair-with-lifts a0 b0 (vector-ref drops p) (vector-ref drops q)))
                                  (overlap? (collide a0 b0))
                                  (else (resolve-colliding-pair a0 b0)))))
          (and (not (and (eq? a a0) (eq? b b0)))
               (begin (vector-set! all i a)
                      (vector-set! all j b)
                      (when boxes
                        (##core#inline "ds_keep_box" boxes p a box-keys)
                        (##core#inline "ds_keep_box" boxes q b box-keys))
                      #t))))
      ;; A lift going down is filed with the space its top swept, so that
      ;; the spatial hash visits the riders it left above it.
      (define (box p)
        (let ((e (vector-ref all (vector-ref idx p))))
          (let-numbers e ((x #:x) (y #:y) (w #:width) (h #:height))
            (let ((dy (and drops (vector-ref drops p))))
              (if dy
                  (values x (- y dy) w (+ h dy))
                  (values x y w h))))))
      (if (< n 2)
          entities
          (begin
            (when boxes
              (do ((p 0 (fx+ p 1))) ((fx= p n))
                (##core#inline "ds_keep_box" boxes p (vector-ref all (vector-ref idx p)) box-keys)))
            (case (if (eq? method 'auto)
                      (if (< n spatial-hash-threshold) 'all-pairs 'spatial-hash)
                      method)
              ((all-pairs)
               (do ((p 0 (fx+ p 1))) ((fx= p n))
                 (do ((q (fx+ p 1) (fx+ q 1))) ((fx= q n))
                   (visit! p q))))
              ((spatial-hash) (visit-pairs-in-order n box visit!))
              (else (error 'resolve-entity-collisions
                           "method must be 'auto, 'all-pairs or 'spatial-hash" method)))
            (when boxes (set! spare-boxes boxes))
            (vector->list all)))))

  ;; The blob of kept boxes (contacts.c, ds_kept_boxes: 5 doubles a
  ;; collider) of the last pass, used again by the next: a crowd's pass
  ;; would otherwise leave one in the heap every frame. A pass takes it
  ;; and gives it back when done, so two passes never share one.
  (define spare-boxes #f)
  (define (take-kept-boxes n)
    (let ((bytes (* 8 (+ 1 (* 5 n))))        ; no fixnum limit assumed
          (b spare-boxes))
      (set! spare-boxes #f)
      (if (and b (>= (blob-size b) bytes)) b (make-blob bytes))))

)
