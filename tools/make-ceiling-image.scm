;;; The picture of docs/physics.org's "Ceiling slopes", drawn headless by the library.
;;;   SDL_VIDEODRIVER=dummy CHICKEN_REPOSITORY_PATH=$PWD/build:$(env -u CHICKEN_INSTALL_REPOSITORY chicken-install -repository) \
;;;     csi -q -s tools/make-ceiling-image.scm
;;; run from the top of the source tree, after tools/make-assets.scm. It
;;; writes docs/images/physics-ceiling-slopes.png: a small level made of
;;; the platformer demo's tiles, whose ceiling slopes are its slope tiles
;;; flipped vertically (and horizontally, for the 22.5 degree pair on the
;;; left). On the right a 16 x 36 body walks into the 45 degree ceiling at
;;; 2 px/frame and stops where its head meets the line; on the left a
;;; 16 x 16 body jumps into the 22.5 degree pair and its head stops on
;;; the line. Each is drawn every 4th frame (the jump every frame), with
;;; a white dot on its head (the middle of its top edge).

(import scheme (chicken base) (chicken file) (chicken format) (chicken process-context)
        (chicken process-context posix)
        (chicken string)
        (downstroke entity) (downstroke scene) (downstroke tilemap) (downstroke camera)
        (downstroke pipeline) (downstroke engine))

(define out (string-append (current-directory) "/docs/images/physics-ceiling-slopes.png"))

;; The level beside the demo's, so that its tilesets' paths hold; removed
;; once drawn.
(define level (sprintf "demo/levels/ceiling-image-~a.tmx" (current-process-id)))

(define v #x40000000)
(define h #x80000000)

;; gids: 1 and 2 the demo's solid tiles, 28 the 45 degree slope 0 16, 29
;; and 30 the 22.5 degree pair 0 8 and 8 16.
(define rows
  (list (list 2 2 2 2 2 2 2 2 2 2 2)
        (list 2 2 (+ 30 v h) (+ 29 v h) 0 0 (+ 28 v) 2 2 2 2)
        (list 0 0 0 0 0 0 0 0 0 0 0)
        (list 0 0 0 0 0 0 0 0 0 0 0)
        (list 1 1 1 1 1 1 1 1 1 1 1)))

(with-output-to-file level
  (lambda ()
    (print "<?xml version=\"1.0\" encoding=\"UTF-8\"?>")
    (print "<map version=\"1.10\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"11\" height=\"5\" tilewidth=\"16\" tileheight=\"16\" infinite=\"0\" backgroundcolor=\"#5c94fc\" nextlayerid=\"2\" nextobjectid=\"1\">")
    (print " <tileset firstgid=\"1\" source=\"tiles.tsx\"/>")
    (print " <tileset firstgid=\"28\" source=\"slopes.tsx\"/>")
    (print " <layer id=\"1\" name=\"ground\" width=\"11\" height=\"5\">")
    (print "  <data encoding=\"csv\">"
           (string-intersperse (map (lambda (r) (string-intersperse (map number->string r) ",")) rows) ",")
           "</data>")
    (print " </layer>")
    (print "</map>")))

;; (x . y) of the first entity after each frame, every `every`th.
(define (path body frames every keep-vx)
  (let ((tm (load-tilemap level)))
    (let loop ((s (make-scene tilemap: tm entities: (list body))) (k 0) (out '()))
      (if (= k frames)
          (reverse out)
          (let* ((s (engine-pipeline s 16)) (e (car (scene-entities s))))
            (loop (scene-map-entities s (lambda (s e) (if keep-vx (entity-set e #:vx keep-vx) e))) (+ k 1)
                  (if (= 0 (modulo k every)) (cons (cons (entity-ref e #:x) (entity-ref e #:y)) out) out)))))))

(define walk (path (list #:x 68 #:y 28 #:width 16 #:height 36 #:vx 2 #:gravity? #t) 24 4 2))
(define jump (path (list #:x 36 #:y 48 #:width 16 #:height 16 #:vy -14 #:gravity? #t) 2 1 #f))

(define (drawn ps w h)
  (append
   (map (lambda (p) (list #:x (car p) #:y (cdr p) #:width w #:height h #:color '(230 80 60) #:alpha 80)) ps)
   (map (lambda (p) (list #:x (+ (car p) (- (/ w 2) 1)) #:y (cdr p) #:width 2 #:height 2 #:color '(255 255 255)))
        ps)))

(define game
  (make-game title: "ceiling slopes" width: 176 height: 80 scale: 4 headless?: #t
             create: (lambda (game)
                       (game-load-scene! game level engine-update: 'none
                                         entities: (append (drawn walk 16 36) (drawn jump 16 16))
                                         camera: (make-camera x: 0 y: 0 bounds: #f)))))

(game-run! game frames: 1 screenshot: out)
(delete-file* level)
(print "wrote " out " (walker stops at " (car (reverse walk)) ", jumper's head at " (car (reverse jump)) ")")
