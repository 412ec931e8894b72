;;; The window pictures of docs/rendering.org, taken from a real window:
;;;   xvfb-run -a -s '-screen 0 640x480x24' env -u SDL_VIDEODRIVER \
;;;     CHICKEN_REPOSITORY_PATH=$PWD/build:$(env -u CHICKEN_INSTALL_REPOSITORY chicken-install -repository) \
;;;     csi -q -s tools/make-window-images.scm
;;; run from the top of the source tree. It writes
;;;   docs/images/window-letterbox.png
;;; a 160x90 (16:9) game in a resizable window the player made 400x300
;;; (4:3): the game is drawn 2.5 times larger, centred, with black bars
;;; above and below; the debug overlay is on, its readout in the corner.

(import scheme (chicken base) (chicken process-context)
        (downstroke sdl2) (downstroke scene) (downstroke engine))

(define out (string-append (current-directory) "/docs/images/window-letterbox.png"))

(define (block x y w h color) (list #:x x #:y y #:width w #:height h #:color color))

(define game
  (make-game
   title: "letterbox" width: 160 height: 90 scale: 2 resizable?: #t debug?: #t
   create: (lambda (g)
             (game-scene-set!
              g (make-sprite-scene
                 background: '(90 160 230)
                 entities: (list (block 0 74 160 16 '(70 140 60))      ; the ground
                                 (block 24 50 32 8 '(150 100 60))     ; a ledge
                                 (block 104 42 40 8 '(150 100 60))
                                 (block 36 34 10 16 '(240 200 40))    ; the player
                                 (block 120 62 12 12 '(200 60 60)))))) ; a crate
   update: (lambda (g dt)
             (when (= (game-frame g) 1) (window-size-set! (game-window g) 400 300)))))

(game-run! game headless?: #f frames: 80 screenshot: out)
(print "wrote " out)
