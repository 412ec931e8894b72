;;; (downstroke check): the mistakes in a scene's entities that the
;;; pipeline would otherwise pass over in silence. Each problem is a string
;;; naming the entity:
;;;   - a key one edit away from a key the library reads (#:gravity for
;;;     #:gravity?, #:widht for #:width): the pipeline never sees it;
;;;   - a body the collision steps will treat as zero-size (a solid or
;;;     gravity entity without #:width or #:height);
;;;   - a value of the wrong type (a position that is not a number, a
;;;     #:skip-pipelines that is not a list of step symbols, an unknown
;;;     #:collision-mode, #:tags that are not a list, a #:tint that is not
;;;     (r g b), an #:emitter that is not one).
;;; Nothing here runs in the per-frame pipeline. By default (scene-checks
;;; is #t) make-scene checks the entities it is given and scene-add-entity
;;; the one it adds, and each problem is printed once on the error port;
;;; 'always checks update-scene's entities too (game-run! sets it for a
;;; debug? game, whose overlay also reports them every frame); #f, for a
;;; release build, checks nothing. scene-problems asks by hand.

(module (downstroke check)
  (entity-problems entity-list-problems scene-checks report-entity-problems!
   known-entity-keys)

  (import scheme (chicken base) (chicken format) (chicken keyword) (chicken port)
          (only (downstroke keywords) one-slip?)
          (only (downstroke particles) emitter?)
          (downstroke entity))

  ;; Every key the library's steps, renderer and loaders read or write.
  (define known-entity-keys
    '(#:type #:id #:name #:tags #:x #:y #:width #:height #:vx #:vy #:ay
      #:gravity? #:on-ground? #:solid? #:immovable? #:one-way? #:drop-through?
      #:frame-start #:x-pass-start #:skip-pipelines #:collision-mode #:tween #:contacts? #:contacts
      #:drag #:air-drag #:max-vx #:max-vy #:bounce
      #:climber? #:climb #:climb-speed #:climbing?
      #:group-id #:group-origin? #:group-local-x #:group-local-y
      #:animations #:anim-name #:anim-frame #:anim-tick #:anim-duration #:anim-finished? #:anim-event
      #:tile-id #:color #:facing
      ;; sprites and particles (renderer.scm, particles.scm)
      #:sprite-offset-x #:sprite-offset-y #:origin-x #:origin-y #:flip-x? #:flip-y?
      #:angle #:scale #:scale-x #:scale-y #:alpha #:tint #:tileset #:z #:emitter))

  (define pipeline-steps
    '(tweens frame-start climbing acceleration gravity controls velocity-x tile-collisions-x velocity-y
      tile-collisions-y on-solid entity-collisions contacts animation particles))

  (define number-keys '(#:x #:y #:width #:height #:vx #:vy #:ay
                        #:sprite-offset-x #:sprite-offset-y #:origin-x #:origin-y
                        #:angle #:scale #:scale-x #:scale-y #:alpha #:z
                        #:drag #:air-drag #:max-vx #:max-vy #:bounce #:climb #:climb-speed))

  (define (kw k) (sprintf "~s" k))

  ;; A known key one edit (or one swap of neighbours) away from k, or #f.
  (define (near-key k)
    (let ((s (keyword->string k)))
      (let loop ((ks known-entity-keys))
        (cond ((null? ks) #f)
              ((let ((known (keyword->string (car ks))))
                 (one-slip? s known))
               (car ks))
              (else (loop (cdr ks)))))))

  (define (entity-problems e)
    (let ((who (sprintf "entity ~a" (entity-label e))))
      (define (problem fmt . args) (string-append who ": " (apply sprintf fmt args)))
      (if (not (and (list? e) (let all-pairs ((ps e)) (or (null? ps) (and (pair? (car ps)) (all-pairs (cdr ps)))))))
          (list (sprintf "~s is not an entity (a keyword alist)" e))
          (append
           ;; keys the library does not know, one edit from one it does
           (let loop ((ps e) (out '()))
             (if (null? ps)
                 (reverse out)
                 (let* ((k (caar ps))
                        (near (and (keyword? k) (not (memq k known-entity-keys)) (near-key k))))
                   (loop (cdr ps)
                         (if (and near (not (assq near e)))
                             (cons (problem "key ~a is not one Downstroke reads (did you mean ~a)" (kw k) (kw near))
                                   out)
                             out)))))
           ;; numbers
           (let loop ((ks number-keys) (out '()))
             (if (null? ks)
                 (reverse out)
                 (let ((p (assq (car ks) e)))
                   (loop (cdr ks)
                         (if (and p (not (and (real? (cdr p)) (or (exact? (cdr p)) (finite? (cdr p))))))
                             (cons (problem "~a is ~s, not a finite number" (kw (car ks)) (cdr p)) out)
                             out)))))
           ;; sizes of bodies the collision steps look at
           (if (or (entity-ref e #:solid? #f) (entity-ref e #:gravity? #f))
               (let ((missing (let loop ((ks '(#:width #:height)) (out '()))
                                (cond ((null? ks) (reverse out))
                                      ((assq (car ks) e) (loop (cdr ks) out))
                                      (else (loop (cdr ks) (cons (kw (car ks)) out)))))))
                 (if (null? missing)
                     '()
                     (list (problem "no ~a: the collision steps treat it as zero-size"
                                    (if (= 2 (length missing)) "#:width or #:height" (car missing))))))
               '())
           (let ((w (entity-ref e #:width #f)) (h (entity-ref e #:height #f)))
             (if (or (and (real? w) (negative? w)) (and (real? h) (negative? h)))
                 (list (problem "a negative size (~s x ~s)" w h))
                 '()))
           ;; lists and symbols
           (let ((skips (entity-ref e #:skip-pipelines '())))
             (cond ((not (list? skips))
                    (list (problem "#:skip-pipelines is ~s, not a list of step symbols" skips)))
                   (else
                    (let loop ((ss skips) (out '()))
                      (cond ((null? ss) (reverse out))
                            ((memq (car ss) pipeline-steps) (loop (cdr ss) out))
                            (else (loop (cdr ss)
                                        (cons (problem "#:skip-pipelines names ~s, which is no step (steps: ~a)"
                                                       (car ss) pipeline-steps)
                                              out))))))))
           (let ((mode (entity-ref e #:collision-mode #f)))
             (if (and mode (not (memq mode '(discrete swept))))
                 (list (problem "#:collision-mode is ~s, not discrete or swept" mode))
                 '()))
           (let ((tags (entity-ref e #:tags '())))
             (if (list? tags) '() (list (problem "#:tags is ~s, not a list" tags))))
           ;; drawing values the renderer would refuse
           (let ((tint (entity-ref e #:tint #f)))
             (if (or (not tint) (and (list? tint) (= 3 (length tint)) (all-bytes? tint)))
                 '()
                 (list (problem "#:tint is ~s, not (r g b) of integers 0-255" tint))))
           (let ((em (entity-ref e #:emitter #f)))
             (if (or (not em) (emitter? em))
                 '()
                 (list (problem "#:emitter is ~s, not an emitter (make-emitter)" em))))))))

  (define (all-bytes? l)
    (or (null? l) (and (exact-integer? (car l)) (<= 0 (car l) 255) (all-bytes? (cdr l)))))

  ;; Every problem of every entity of a list, in order.
  (define (entity-list-problems entities)
    (let loop ((es entities) (out '()))
      (if (null? es)
          (reverse out)
          (loop (cdr es) (append (reverse (entity-problems (car es))) out)))))

  ;; #t: make-scene and scene-add-entity check the entities they are
  ;; given; 'always: update-scene too; #f: nothing is checked.
  (define scene-checks
    (make-parameter #t (lambda (v)
                         (unless (memq v '(#t #f always))
                           (error 'scene-checks "must be #t, #f or 'always" v))
                         v)))

  ;; Prints each problem not printed before (at most `remembered` kept),
  ;; on the error port, prefixed "downstroke: ". The debug overlay calls
  ;; this every frame, so a problem is said once, not sixty times a second.
  (define remembered 256)
  (define said '())

  (define (report-entity-problems! entities)
    (for-each (lambda (p)
                (unless (member p said)
                  (set! said (cons p (if (>= (length said) remembered) (list-head* said (- remembered 1)) said)))
                  (with-output-to-port (current-error-port)
                    (lambda () (print "downstroke: " p)))))
              (entity-list-problems entities)))

  (define (list-head* ls n) (if (or (= n 0) (null? ls)) '() (cons (car ls) (list-head* (cdr ls) (- n 1))))))
