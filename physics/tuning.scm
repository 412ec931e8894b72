;;; (downstroke tuning): the physics constants a game may tune, and tune-physics!.
;;;
;;; They live in one module so that tune-physics! sets them where they are
;;; defined; every rule that reads them imports them from here.

(module (downstroke tuning)
  (*gravity* *jump-force* *entity-ground-contact-tolerance* *entity-ground-vy-max*
   *climb-speed* tune-physics!)

  (import scheme (chicken base) (chicken format) (downstroke keywords))

  ;;; Constants

  ;; Added to #:vy of gravity entities every frame (px/frame^2).
  (define *gravity* 1)
  ;; A jump is #:ay = (- *jump-force*): the first frame of a jump moves up
  ;; 9 px (10 - gravity), and the body rises 45 px, almost three 16 px tiles,
  ;; in 9 frames.
  (define *jump-force* 10)
  ;; A solid entity whose top is within this many px of a mover's bottom
  ;; supports it (px).
  (define *entity-ground-contact-tolerance* 5)
  ;; A mover falling or rising faster than this (px/frame) is not supported
  ;; by an entity: it would only be passing through the contact band.
  (define *entity-ground-vy-max* 12)
  ;; How fast a climber without its own #:climb-speed climbs a ladder
  ;; (px/frame): a 16 px tile in 8 frames.
  (define *climb-speed* 2)

  ;; The supported way to change the constants above (a set! of an
  ;; imported binding works, with a compiler warning): each keyword given
  ;; sets one, after all are checked, so a bad one changes nothing.
  (define/keywords (tune-physics! #!key (gravity *gravity*) (jump-force *jump-force*)
                                  (ground-contact-tolerance *entity-ground-contact-tolerance*)
                                  (ground-vy-max *entity-ground-vy-max*)
                                  (climb-speed *climb-speed*))
    (define (check key v ok? what)
      (unless (and (real? v) (or (exact? v) (finite? v)) (ok? v))
        (error (sprintf "tune-physics!: ~a ~s must be ~a" key v what))))
    (check "gravity:" gravity (lambda (v) #t) "a finite number")
    (check "jump-force:" jump-force (lambda (v) #t) "a finite number")
    (check "ground-contact-tolerance:" ground-contact-tolerance (lambda (v) (>= v 0)) "a finite number >= 0")
    (check "ground-vy-max:" ground-vy-max (lambda (v) (>= v 0)) "a finite number >= 0")
    (check "climb-speed:" climb-speed (lambda (v) (>= v 0)) "a finite number >= 0")
    (set! *gravity* gravity)
    (set! *jump-force* jump-force)
    (set! *entity-ground-contact-tolerance* ground-contact-tolerance)
    (set! *entity-ground-vy-max* ground-vy-max)
    (set! *climb-speed* climb-speed))
)
