(import scheme (chicken base) (downstroke entity) (downstroke scene)
        (downstroke engine))

;; Every hook says when it runs; the scene's engine update is a procedure
;; here so that it can speak too (normally it is the default pipeline).
(define (say game what) (print "frame " (game-frame game) ": " what))

(define game
  (make-game
   title: "Order" width: 320 height: 240
   preload: (lambda (game) (print "preload:"))
   create: (lambda (game)
             (print "create:")
             (game-scene-set! game
               (make-sprite-scene engine-update: (lambda (game dt) (say game "engine update")))))
   update: (lambda (game dt) (say game (string-append "update:, dt " (number->string dt))))
   render: (lambda (game) (say game "render:"))))

(print (game-run! game frames: 2 headless?: #t) " frames")
