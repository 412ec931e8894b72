;;; (downstroke game): the game record, made by make-game, and its named
;;; states. Building a game makes no SDL call; (downstroke engine) runs it
;;; and (downstroke level) loads scenes into it. Games import all three
;;; through (downstroke engine).

(module (downstroke game)
  (make-game game?
   game-title game-width game-height game-scale game-frame-delay
   game-input-config game-debug? game-debug-set! game-headless?
   game-resizable? game-org game-app
   game-preload-hook game-create-hook game-update-hook game-render-hook
   game-scene game-scene-set! game-input game-input-set!
   game-renderer game-renderer-set! game-window game-window-set!
   game-frame game-asset game-asset-set!
   game-recording game-surface game-textures
   game-add-state! game-state-set! game-current-state game-states
   ;; for sibling modules only: the engine and the level loader
   game-frame-set! game-surface-set! game-recording-set! game-textures-set!
   active-update-hook active-render-hook game-profile %game-input-config-set! game-draw-clock
   game-fullscreen-flag game-fullscreen-flag-set!)

  (import (downstroke keywords))
  (import scheme (chicken base) (chicken format) (chicken condition) (chicken string)
          (downstroke assets))

  (define-record-type game
    (%make-game title width height scale frame-delay input-config
                preload create update render debug? headless?
                resizable? fullscreen org app
                scene input renderer window frame assets
                surface states current-state recording textures profile draw-clock)
    game?
    (title game-title)
    (width game-width)
    (height game-height)
    (scale game-scale)
    (frame-delay game-frame-delay)
    (input-config game-input-config %game-input-config-set!)
    (preload game-preload-hook)
    (create game-create-hook)
    (update game-update-hook)
    (render game-render-hook)
    (debug? game-debug? %game-debug-set!)
    (headless? game-headless?)
    (resizable? game-resizable?)
    ;; wanted fullscreen (the engine applies it to the window)
    (fullscreen game-fullscreen-flag game-fullscreen-flag-set!)
    ;; the names SDL_GetPrefPath files the game's save data under
    (org game-org)
    (app game-app)
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
    (textures game-textures game-textures-set!)
    ;; the last frames' times (downstroke engine's game-frame-profile)
    (profile game-profile)
    ;; frames drawn per second: #(start-ms draws-since-start last-rate)
    (draw-clock game-draw-clock))

  (define (check what ok? value)
    (unless (ok? value)
      (error 'make-game (sprintf "~a: bad value ~s" what value)))
    value)

  (define (positive-integer? v) (and (exact-integer? v) (positive? v)))
  (define (positive-scale? v) (and (real? v) (finite? v) (positive? v) (<= v 64)))
  (define (name-string? v) (and (string? v) (> (string-length v) 0)
                                (not (substring-index "/" v)) (not (member v '("." "..")))))
  (define (hook? v) (or (not v) (procedure? v)))

  ;; How many arguments a procedure takes, as (min . max) with max #f for
  ;; any number, read from CHICKEN's procedure-information, e.g.
  ;; (? game dt) or (named a . rest); #f when CHICKEN does not know (code
  ;; compiled with -d0).
  (define (procedure-arity proc)
    (let ((info (procedure-information proc)))
      (and (pair? info)
           (let count ((args (cdr info)) (n 0))
             (cond ((null? args) (cons n n))
                   ((symbol? args) (cons n #f))          ; a dotted rest
                   ((memq (car args) '(#!optional #!rest #!key)) (cons n #f))
                   (else (count (cdr args) (+ n 1))))))))

  ;; A hook is called with `n` arguments, shown as `call`: one that cannot
  ;; take them is an error now, naming the hook, not at its first call.
  (define (check-hook who what proc n call)
    (when proc
      (unless (procedure? proc)
        (error (sprintf "~a: ~a must be a procedure or #f, got ~s" who what proc)))
      (let ((arity (procedure-arity proc)))
        (when (and arity (or (< n (car arity)) (and (cdr arity) (> n (cdr arity)))))
          (error (sprintf "~a: ~a hook ~s takes ~a; it is called as ~a"
                              who what (procedure-information proc)
                              (cond ((not (cdr arity)) (sprintf "at least ~a arguments" (car arity)))
                                    ((= 1 (car arity)) "1 argument")
                                    (else (sprintf "~a arguments" (car arity))))
                              call)))))
    (if (and proc (not (procedure-arity proc)))
        (arity-reporting what proc call)
        proc))

  ;; A hook whose arity CHICKEN cannot tell (compiled with -d0) is checked
  ;; when it is called instead: a call with the wrong number of arguments
  ;; is reported naming the hook. An arity error raised inside the hook,
  ;; by a call of some other procedure, passes through as it was.
  (define (arity-reporting what proc call)
    (lambda args
      (condition-case (apply proc args)
        (e (exn arity)
           (if (memq proc ((condition-property-accessor 'exn 'arguments '()) e))
               (error (sprintf "~a hook ~s cannot take ~a; it is called as ~a"
                               what proc
                               (if (= 1 (length args)) "1 argument" (sprintf "~a arguments" (length args)))
                               call))
               (signal e))))))

  ;; width x height is the logical resolution the game draws at; the window
  ;; is `scale` times larger on each axis (any positive number: 1.5 makes a
  ;; 960x720 window of a 640x480 game, rounded to whole pixels).
  ;; input-config #f stands for the input module's default configuration.
  ;; resizable?: the player may resize the window; fullscreen?: start
  ;; fullscreen (at the desktop's resolution). Either way the logical
  ;; resolution stays and is letterboxed. org: and app: name the
  ;; directory of the game's save data (app: defaults to the title).
  (define/keywords (make-game #!key (title "Downstroke Game") (width 640) (height 480)
                     (scale 1) (frame-delay 16) (input-config #f)
                     (preload #f) (create #f) (update #f) (render #f)
                     (debug? #f) (headless? #f) (resizable? #f) (fullscreen? #f)
                     (org "downstroke") (app #f))
    (%make-game (check "title:" string? title)
                (check "width:" positive-integer? width)
                (check "height:" positive-integer? height)
                (check "scale:" positive-scale? scale)
                (check "frame-delay:" positive-integer? frame-delay)
                input-config
                (check-hook 'make-game "preload:" preload 1 "(preload game)")
                (check-hook 'make-game "create:" create 1 "(create game)")
                (check-hook 'make-game "update:" update 2 "(update game dt)")
                (check-hook 'make-game "render:" render 1 "(render game)")
                (and debug? #t) (and headless? #t) (and resizable? #t) (and fullscreen? #t)
                (check "org:" name-string? org)
                (if app (check "app:" name-string? app) (title->app title))
                #f #f #f #f 0 (make-asset-registry) #f '() #f #f '()
                (make-vector (* 3 profile-frames) 0)
                (vector #f 0 0)))

  ;; How many frames the profile remembers: three times per frame (engine
  ;; update, update:, drawing), in ms, frame f at slots 3 (f mod n) ...
  (define profile-frames 60)

  ;; The title as a directory name: no slash, never empty nor . or ..
  (define (title->app title)
    (let ((s (list->string (map (lambda (c) (if (char=? c #\/) #\- c)) (string->list title)))))
      (if (name-string? s) s "downstroke-game")))

  (define (game-debug-set! game on?) (%game-debug-set! game (and on? #t)))

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
    (check-hook 'game-add-state! "update:" update 2 "(update game dt)")
    (check-hook 'game-add-state! "render:" render 1 "(render game)")
    (check-hook 'game-add-state! "enter:" enter 1 "(enter game)")
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
