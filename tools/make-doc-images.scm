;;; Pictures for the documents, drawn headless by the library itself.
;;;   SDL_VIDEODRIVER=dummy CHICKEN_REPOSITORY_PATH=$PWD/build:$(env -u CHICKEN_INSTALL_REPOSITORY chicken-install -repository) \
;;;     csi -q -s tools/make-doc-images.scm
;;; run from the top of the source tree. It writes
;;;   docs/images/rendering-debug-overlay.png   (docs/rendering.org)
;;; a small level drawn with the debug overlay: a body resting on the floor,
;;; a slow mover, and a fast one in the discrete collision mode (in red).

(import scheme (chicken base) (chicken file) (chicken process-context)
        (chicken string)
        (downstroke sdl2) (downstroke scene) (downstroke engine))

(define out (string-append (current-directory) "/docs/images/rendering-debug-overlay.png"))

;; The map and its one-tile sheet live in a temporary directory.
(define work (create-temporary-directory))
(define (in-work name) (string-append work "/" name))

(define cols 20)
(define rows 12)

(define (brick-sheet! path)
  (init!)
  (let* ((s (create-rgba-surface! 8 8))
         (r (create-software-renderer! s)))
    (render-draw-color-set! r 120 72 48)
    (render-clear! r)
    (render-draw-color-set! r 150 96 64)
    (render-fill-rect! r (make-rect 1 1 6 2))
    (render-fill-rect! r (make-rect 1 5 6 2))
    (img-save-png! s path)
    (free-surface! s))
  (quit!))

;; Walls on the left and right, a floor, and a ledge.
(define (cell col row)
  (if (or (= row (- rows 1)) (= col 0) (= col (- cols 1))
          (and (= row 7) (<= 4 col 8)))
      1 0))

(define (write-level! path)
  (with-output-to-file path
    (lambda ()
      (print "<?xml version=\"1.0\" encoding=\"UTF-8\"?>")
      (print "<map version=\"1.10\" orientation=\"orthogonal\" width=\"" cols "\" height=\"" rows
             "\" tilewidth=\"8\" tileheight=\"8\">")
      (print " <tileset firstgid=\"1\" name=\"bricks\" tilewidth=\"8\" tileheight=\"8\""
             " tilecount=\"1\" columns=\"1\">")
      (print "  <image source=\"bricks.png\" width=\"8\" height=\"8\"/>")
      (print " </tileset>")
      (print " <layer name=\"walls\" width=\"" cols "\" height=\"" rows "\">")
      (print "  <data encoding=\"csv\">")
      (let loop ((row 0) (lines '()))
        (if (= row rows)
            (print (string-intersperse (reverse lines) ",\n"))
            (loop (+ row 1)
                  (cons (string-intersperse
                         (let c ((col 0)) (if (= col cols) '() (cons (->string (cell col row)) (c (+ col 1)))))
                         ",")
                        lines))))
      (print "  </data>")
      (print " </layer>")
      (print "</map>"))))

(brick-sheet! (in-work "bricks.png"))
(write-level! (in-work "level.tmx"))

(define bodies
  (list (list #:x 44 #:y 44 #:width 8 #:height 12 #:color '(230 200 60))   ; on the ledge
        (list #:x 100 #:y 62 #:width 10 #:height 10 #:vx 3 #:vy -2
              #:color '(90 170 230))                                      ; a slow mover
        (list #:x 20 #:y 70 #:width 6 #:height 6 #:vx 15 #:vy 0
              #:color '(220 90 90))))                                     ; too fast for discrete

(define game
  (make-game title: "overlay" width: (* cols 8) height: (* rows 8) scale: 3
             headless?: #t debug?: #t
             create: (lambda (game)
                       (game-load-scene! game (in-work "level.tmx")
                                         background: '(24 28 40) engine-update: 'none
                                         entities: bodies)
                       (game-scene-set! game (update-scene (game-scene game)
                                                           collision-mode: 'discrete)))))

(game-run! game frames: 1 screenshot: out)
(delete-directory work #t)
(print "wrote " out)
