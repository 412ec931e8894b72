;;; (downstroke game): the game record, made by make-game, and its named
;;; states. Building a game makes no SDL call; (downstroke engine) runs it
;;; and (downstroke level) loads scenes into it. Games import all three
;;; through (downstroke engine).

(module (downstroke game)
  (make-game game?
   game-title game-width game-height game-scale game-frame-delay
   game-input-config game-debug? game-headless?
   game-preload-hook game-create-hook game-update-hook game-render-hook
   game-scene game-scene-set! game-input game-input-set!
   game-renderer game-renderer-set! game-window game-window-set!
   game-frame game-asset game-asset-set!
   game-recording game-surface game-textures
   game-add-state! game-state-set! game-current-state game-states
   ;; for the engine and the level loader, not for games
   game-frame-set! game-surface-set! game-recording-set! game-textures-set!
   active-update-hook active-render-hook)

  (import (downstroke keywords))
  (import scheme (chicken base) (chicken format) (downstroke assets))

  (define-record-type game
    (%make-game title width height scale frame-delay input-config
                preload create update render debug? headless?
                scene input renderer window frame assets
                surface states current-state recording textures)
    game?
    (title game-title)
    (width game-width)
    (height game-height)
    (scale game-scale)
    (frame-delay game-frame-delay)
    (input-config game-input-config)
    (preload game-preload-hook)
    (create game-create-hook)
    (update game-update-hook)
    (render game-render-hook)
    (debug? game-debug?)
    (headless? game-headless?)
    (scene game-scene game-scene-set!)
    (input game-input game-input-set!)
    (renderer game-renderer game-renderer-set!)
    (window game-window game-window-set!)
    (frame game-frame game-frame-set!)
    (assets game-assets)
    (surface game-surface game-surface-set!)
    (states game-states game-states-set!)
    (current-state game-current-state game-current-state-set!)
    (recording game-recording game-recording-set!)
    (textures game-textures game-textures-set!))

  (define (check what ok? value)
    (unless (ok? value)
      (error 'make-game (sprintf "~a: bad value ~s" what value)))
    value)

  (define (positive-integer? v) (and (exact-integer? v) (positive? v)))
  (define (hook? v) (or (not v) (procedure? v)))

  ;; width x height is the logical resolution the game draws at; the window
  ;; is `scale` times larger on each axis. input-config #f stands for the
  ;; input module's default configuration.
  (define/keywords (make-game #!key (title "Downstroke Game") (width 640) (height 480)
                     (scale 1) (frame-delay 16) (input-config #f)
                     (preload #f) (create #f) (update #f) (render #f)
                     (debug? #f) (headless? #f))
    (%make-game (check "title:" string? title)
                (check "width:" positive-integer? width)
                (check "height:" positive-integer? height)
                (check "scale:" positive-integer? scale)
                (check "frame-delay:" positive-integer? frame-delay)
                input-config
                (check "preload:" hook? preload)
                (check "create:" hook? create)
                (check "update:" hook? update)
                (check "render:" hook? render)
                debug? headless?
                #f #f #f #f 0 (make-asset-registry) #f '() #f #f '()))

  ;; The game's assets live in an asset registry: (game-asset game key
  ;; [default]) is asset-ref on it, so a missing key without a default is an
  ;; error naming the key.
  (define (game-asset game key . default)
    (apply asset-ref (game-assets game) key default))

  (define (game-asset-set! game key value)
    (asset-set! (game-assets game) key value))

  ;;; ------------------------------------------------------------------
  ;;; Named game states (title, play, pause ...).
  ;;;
  ;;; (game-add-state! game name #!key update render enter) registers a
  ;;; state (adding a name again replaces it). (game-state-set! game name)
  ;;; makes it the active state and calls its enter: hook as (enter game);
  ;;; (game-state-set! game #f) goes back to the game's own hooks. While a
  ;;; state is active its update: (game dt) and render: (game) hooks are
  ;;; used INSTEAD of the game's update: and render: (a state without one
  ;;; runs none); the scene's engine update and the camera follow still run.

  (define-record-type game-state
    (make-game-state update render enter)
    game-state?
    (update game-state-update)
    (render game-state-render)
    (enter game-state-enter))

  (define/keywords (game-add-state! game name #!key (update #f) (render #f) (enter #f))
    (for-each (lambda (what h)
                (unless (hook? h)
                  (error 'game-add-state! (sprintf "~a must be a procedure or #f" what) h)))
              '("update:" "render:" "enter:") (list update render enter))
    (game-states-set! game (cons (cons name (make-game-state update render enter))
                                 (let loop ((ss (game-states game)))
                                   (cond ((null? ss) '())
                                         ((equal? (caar ss) name) (cdr ss))
                                         (else (cons (car ss) (loop (cdr ss))))))))
    (void))

  (define (game-state-set! game name)
    (if (not name)
        (game-current-state-set! game #f)
        (let ((p (assoc name (game-states game))))
          (unless p (error 'game-state-set! (sprintf "no game state named ~s" name)))
          (game-current-state-set! game name)
          (let ((enter (game-state-enter (cdr p))))
            (when enter (enter game)))))
    (void))

  (define (active-state game)
    (let ((name (game-current-state game)))
      (and name (let ((p (assoc name (game-states game)))) (and p (cdr p))))))

  (define (active-update-hook game)
    (let ((st (active-state game)))
      (if st (game-state-update st) (game-update-hook game))))

  (define (active-render-hook game)
    (let ((st (active-state game)))
      (if st (game-state-render st) (game-render-hook game)))))
