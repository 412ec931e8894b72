(import scheme (chicken base) (chicken condition) (downstroke engine)
        (downstroke assets))

(define game (make-game))
(game-asset-set! game 'score 0)
(game-asset-set! game "level" "demo/levels/platformer.tmx")
(print (game-asset game 'score) " " (game-asset game "level") " " (game-asset game 'lives 3))

;; a missing key without a default is an error that lists the known keys
(handle-exceptions exn
    (print ((condition-property-accessor 'exn 'message) exn))
  (game-asset game 'lives))

;; the registry on its own, as (downstroke assets) provides it
(define registry (make-asset-registry))
(asset-set! registry 'tiles "a texture")
(asset-set! registry 'font "a font")
(print (asset-keys registry) " " (asset-exists? registry 'music))
