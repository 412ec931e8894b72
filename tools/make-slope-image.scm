;;; The picture of docs/physics.org's "Slopes", drawn headless by the library.
;;;   SDL_VIDEODRIVER=dummy CHICKEN_REPOSITORY_PATH=$PWD/build:$(env -u CHICKEN_INSTALL_REPOSITORY chicken-install -repository) \
;;;     csi -q -s tools/make-slope-image.scm
;;; run from the top of the source tree, after tools/make-assets.scm. It
;;; writes docs/images/physics-slopes.png: the platformer demo's hill
;;; (demo/levels/platformer.tmx: up 45 degrees, a flat top, down a 22.5
;;; degree pair), and a 16 x 16 body walking over it at 2 px/frame under
;;; the default pipeline, drawn every 4th frame, with a white dot on its
;;; foot (the middle of its bottom edge), which the slope's line holds.

(import scheme (chicken base) (chicken file) (chicken process-context)
        (downstroke entity) (downstroke scene) (downstroke tilemap) (downstroke camera)
        (downstroke pipeline) (downstroke engine))

(define out (string-append (current-directory) "/docs/images/physics-slopes.png"))
(define level "demo/levels/platformer.tmx")

;; The walk: from x 736 on the floor (y 192) to past the hill, 2 px a frame.
(define walk
  (let ((tm (load-tilemap level)))
    (let loop ((s (make-scene tilemap: tm entities: (list (list #:x 736 #:y 192 #:width 16 #:height 16
                                                                #:vx 2 #:gravity? #t))))
               (k 0) (out '()))
      (if (= k 64)
          (reverse out)
          (let* ((s (engine-pipeline s 16)) (e (car (scene-entities s))))
            (loop (scene-map-entities s (lambda (s e) (entity-set e #:vx 2))) (+ k 1)
                  (if (= 0 (modulo k 4)) (cons (cons (entity-ref e #:x) (entity-ref e #:y)) out) out)))))))

(define bodies
  (append
   (map (lambda (p) (list #:x (car p) #:y (cdr p) #:width 16 #:height 16 #:color '(230 80 60) #:alpha 90))
        walk)
   (map (lambda (p) (list #:x (+ (car p) 7) #:y (+ (cdr p) 15) #:width 2 #:height 2 #:color '(255 255 255)))
        walk)))

(define game
  (make-game title: "slopes" width: 176 height: 80 scale: 4 headless?: #t
             create: (lambda (game)
                       (game-load-scene! game level engine-update: 'none entities: bodies
                                         camera: (make-camera x: 728 y: 144 bounds: #f)))))

(game-run! game frames: 1 screenshot: out)
(print "wrote " out)
