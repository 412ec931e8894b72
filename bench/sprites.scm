;;; Sprite and particle benchmark (docs/performance.org, "Sprites and
;;; particles"). Prints, each the median of RUNS runs (default 5):
;;;   1. ms per frame of render-scene! drawing 2,000 sprite entities
;;;      (16 x 16 tiles) into a 320 x 240 software renderer: plain
;;;      entities (#:x #:y #:tile-id), the same with #:z, and with
;;;      #:angle, #:scale and #:tint;
;;;   2. particles stepped per ms: one emitter holding 10,000 living
;;;      particles (emitter-step, gravity on, lifetimes long enough that
;;;      none dies), and the same through engine-pipeline;
;;;   3. particles drawn per ms: the same 10,000 as 2 x 2 boxes.
;;;
;;;   SDL_VIDEODRIVER=dummy CHICKEN_REPOSITORY_PATH=build:$(env -u CHICKEN_INSTALL_REPOSITORY chicken-install -repository) \
;;;     csi -q -s bench/sprites.scm [RUNS]
;;;
;;; Part 1 runs against any build: pointed at a build from before sprites
;;; had their keys, it measures what plain entities cost then (the other
;;; lines need the new keys and are skipped when the build lacks them).

(import scheme (chicken base) (chicken format) (chicken file) (chicken time)
        (chicken sort) (chicken process-context) (chicken condition)
        (downstroke sdl2) (downstroke tilemap) (downstroke scene)
        (downstroke renderer) (downstroke pipeline))

(unless (get-environment-variable "SDL_VIDEODRIVER")
  (set-environment-variable! "SDL_VIDEODRIVER" "dummy"))

(define runs (let ((args (command-line-arguments)))
               (or (and (pair? args) (string->number (car args))) 5)))

(define (median xs)
  (let ((s (sort xs <)) (n (length xs)))
    (if (odd? n) (list-ref s (quotient n 2))
        (/ (+ (list-ref s (- (quotient n 2) 1)) (list-ref s (quotient n 2))) 2))))

(define (round3 x) (/ (round (* 1000 x)) 1000.))

;; The median over `runs` of (thunk) -> ms per unit, after one warm-up.
(define (measure thunk)
  (thunk)
  (median (let loop ((i 0)) (if (= i runs) '() (cons (thunk) (loop (+ i 1)))))))

(init! '(video))
(define dir (create-temporary-directory))
(define png (string-append dir "/sheet.png"))
(let* ((s (create-rgba-surface! 64 16)) (r (create-software-renderer! s)))
  (do ((i 0 (+ i 1))) ((= i 4))
    (render-draw-color-set! r (* 60 i) 200 (- 255 (* 60 i)))
    (render-fill-rect! r (make-rect (* 16 i) 0 16 16)))
  (img-save-png! s png)
  (free-surface! s))

(define surface (create-rgba-surface! 320 240))
(define r (create-software-renderer! surface))
(define sheet (make-sheet-tileset png tile-width: 16 tile-height: 16 columns: 4))
(define tex (img-load-texture! r png))

;; 2,000 entities spread over the view, `extra` a plist added to each.
(define (crowd extra)
  (let loop ((i 0) (out '()))
    (if (= i 2000)
        out
        (loop (+ i 1)
              (cons (append (list #:type 'sprite #:x (modulo (* i 37) 304) #:y (modulo (* i 23) 224)
                                  #:width 16 #:height 16 #:vx 0 #:vy 0 #:tile-id (+ 1 (modulo i 4)))
                            (extra i))
                    out)))))

(define frames (string->number (or (get-environment-variable "SPRITES_FRAMES") "100")))
(define (frame-ms scene)
  (lambda ()
    (let ((t0 (current-milliseconds)))
      (do ((i 0 (+ i 1))) ((= i frames))
        (render-scene! r scene))
      (/ (- (current-milliseconds) t0) (exact->inexact frames)))))

(define (sprite-scene extra)
  (make-sprite-scene tileset: sheet tileset-texture: tex background: '(0 0 0)
                     entities: (crowd extra)))

(printf "sprites, 2,000 entities, 320x240 software: plain ~a ms/frame~%"
        (round3 (measure (frame-ms (sprite-scene (lambda (i) '()))))))

;; The rest needs the sprite keys and (downstroke particles).
(define new-keys?
  (handle-exceptions e #f (eval '(import (downstroke particles))) #t))

(when (and new-keys? (not (get-environment-variable "SPRITES_PLAIN_ONLY")))
  (printf "sprites, 2,000 entities: with #:z ~a ms/frame~%"
          (round3 (measure (frame-ms (sprite-scene (lambda (i) (list #:z (modulo i 3))))))))
  (printf "sprites, 2,000 entities: with #:angle #:scale #:tint ~a ms/frame~%"
          (round3 (measure (frame-ms (sprite-scene (lambda (i) (list #:angle (modulo i 360) #:scale 1.5
                                                                     #:tint '(255 128 128))))))))
  (eval
   '(begin
      (import (downstroke particles) (downstroke entity))
      (define count 10000)
      ;; 10,000 living particles: a burst that lives longer than the run
      (define full
        (emitter-step (emitter-burst (make-emitter speed: '(1 3) angle: '(0 360) gravity: 1/10
                                                   lifetime: 100000 max-particles: count color: '(255 200 80))
                                     count)
                      160 120 0 0))
      (define steps 50)
      (define (step-rate)
        (let ((t0 (current-milliseconds)))
          (let loop ((i 0) (e full))
            (if (< i steps) (loop (+ i 1) (emitter-step e 160 120 0 0))
                (unless (= (emitter-count e) count) (error "particles died"))))
          (/ (* count steps) (max 1 (- (current-milliseconds) t0)))))
      (define scene (make-sprite-scene entities: (list (list #:x 160 #:y 120 #:emitter full))))
      (define (pipeline-rate)
        (let ((t0 (current-milliseconds)))
          (let loop ((i 0) (s scene)) (when (< i steps) (loop (+ i 1) (engine-pipeline s 16))))
          (/ (* count steps) (max 1 (- (current-milliseconds) t0)))))
      (define (draw-rate)
        (let ((t0 (current-milliseconds)))
          (do ((i 0 (+ i 1))) ((= i 10)) (render-scene! r scene))
          (/ (* count 10) (max 1 (- (current-milliseconds) t0)))))
      (printf "particles stepped: ~a per ms (emitter-step), ~a per ms (engine-pipeline)~%"
              (round (measure step-rate)) (round (measure pipeline-rate)))
      (printf "particles drawn (2 x 2 boxes, software): ~a per ms~%" (round (measure draw-rate))))
   (interaction-environment)))

(destroy-texture! tex)
(free-surface! surface)
(delete-directory dir #t)
(quit!)
