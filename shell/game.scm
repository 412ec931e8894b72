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
   game-state-push! game-state-pop! game-state-stack game-transition!
   make-transition transition? game-transitioning? game-scene-time
   ;; for sibling modules only: the engine and the level loader
   game-frame-set! game-surface-set! game-recording-set! game-textures-set!
   active-update-hook active-render-hook game-profile %game-input-config-set! game-draw-clock
   game-fullscreen-flag game-fullscreen-flag-set!
   begin-frame! run-update-hooks! end-frame! abandon-frame! scene-drawn? run-render-hooks!
   draw-transition!)

  (import (downstroke keywords))
  (import scheme (chicken base) (chicken format) (chicken condition) (chicken string)
          (downstroke assets))

  (define-record-type game
    (%make-game title width height scale frame-delay input-config
                preload create update render debug? headless?
                resizable? fullscreen org app
                scene input renderer window frame assets
                surface states state-stack recording textures profile draw-clock
                requests in-frame? transition scene-time)
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
    ;; the states' names, top first; a #f at the bottom stands for the
    ;; game's own hooks under a state pushed over them
    (state-stack game-state-stack* game-state-stack-set!)
    (recording game-recording game-recording-set!)
    (textures game-textures game-textures-set!)
    ;; the last frames' times (downstroke engine's game-frame-profile)
    (profile game-profile)
    ;; frames drawn per second: #(start-ms draws-since-start last-rate)
    (draw-clock game-draw-clock)
    ;; state changes asked for and not yet made, oldest first
    (requests game-requests game-requests-set!)
    ;; #t while a frame's hooks run: requests then wait for its end
    (in-frame? game-in-frame? game-in-frame-set!)
    ;; the transition playing: #(request transition phase ms), or #f
    (transition game-transition game-transition-set!)
    ;; ms the scene has run (frames not frozen), the map animations' clock
    (scene-time game-scene-time game-scene-time-set!))

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
                #f #f #f #f 0 (make-asset-registry) #f '() '() #f '()
                (make-vector (* 3 profile-frames) 0)
                (vector #f 0 0)
                '() #f #f 0))

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
  ;;; Named game states (title, play, pause ...), a stack of them, and
  ;;; transitions: docs/scenes.org, "Game states".
  ;;;
  ;;; (game-add-state! game name #!key update render enter leave resume
  ;;; update-below? draw-below?) registers a state (adding a name again
  ;;; replaces it). The states form a stack; the top one's update: (game
  ;;; dt) and render: (game) hooks are used INSTEAD of the game's own (a
  ;;; state without one runs none). A state pushed over another freezes it:
  ;;; the one below, and the scene (its engine update, timers, camera),
  ;;; stop, unless the upper state says update-below?: #t; they are still
  ;;; drawn, under it, unless it says draw-below?: #f.
  ;;;
  ;;; A change asked for while a frame runs (in update:, a callback) is
  ;;; made when the frame's update: hooks are done, before the camera
  ;;; follows and the frame is drawn (asked for in render:, once the
  ;;; render: hooks have drawn); changes are made in the order they
  ;;; were asked for. Asked for between frames (create:, the REPL) a change
  ;;; is made at once. A change with a transition plays its first half,
  ;;; the game frozen, makes the change (and those its hooks ask for),
  ;;; then plays its second half while the new state runs; changes asked
  ;;; for meanwhile wait for its end.

  (define-record-type game-state
    (make-game-state update render enter leave resume update-below? draw-below?)
    game-state?
    (update game-state-update)
    (render game-state-render)
    (enter game-state-enter)
    (leave game-state-leave)
    (resume game-state-resume)
    (update-below? game-state-update-below?)
    (draw-below? game-state-draw-below?))

  (define/keywords (game-add-state! game name #!key (update #f) (render #f) (enter #f)
                     (leave #f) (resume #f) (update-below? #f) (draw-below? #t))
    (unless name (error 'game-add-state! "a state's name cannot be #f (#f stands for the game's own hooks)"))
    (let ((st (make-game-state
               (check-hook 'game-add-state! "update:" update 2 "(update game dt)")
               (check-hook 'game-add-state! "render:" render 1 "(render game)")
               (check-hook 'game-add-state! "enter:" enter 1 "(enter game)")
               (check-hook 'game-add-state! "leave:" leave 1 "(leave game)")
               (check-hook 'game-add-state! "resume:" resume 1 "(resume game)")
               (and update-below? #t) (and draw-below? #t))))
      (game-states-set! game (cons (cons name st)
                                   (let loop ((ss (game-states game)))
                                     (cond ((null? ss) '())
                                           ((equal? (caar ss) name) (cdr ss))
                                           (else (cons (car ss) (loop (cdr ss)))))))))
    (void))

  (define (state-named who game name)
    (let ((p (assoc name (game-states game))))
      (unless p
        (error who (sprintf "no game state named ~s (the game has ~s; add one with game-add-state!)"
                            name (map car (game-states game)))))
      (cdr p)))

  ;; The name of the state on top, #f when the game's own hooks run.
  (define (game-current-state game)
    (let ((stack (game-state-stack* game))) (and (pair? stack) (car stack))))

  ;; The states' names, top first (a #f last: pushed over the game's hooks).
  (define (game-state-stack game) (game-state-stack* game))

  ;;; Transitions: out ms of the first half, in ms of the second, and
  ;;; (draw game amount) drawing the cover over the frame, amount from 0
  ;;; (none) to 1 (all covered). The engine's make-fade is one.

  (define-record-type transition
    (%make-transition out in draw)
    transition?
    (out transition-out)
    (in transition-in)
    (draw transition-draw))

  (define/keywords (make-transition #!key (out 250) (in 250) (draw #f))
    (define (check-ms what v)
      (unless (and (real? v) (finite? v) (>= v 0))
        (error 'make-transition (sprintf "~a must be a finite number of ms >= 0, got ~s" what v))))
    (check-ms "out:" out)
    (check-ms "in:" in)
    (%make-transition out in (check-hook 'make-transition "draw:" draw 2 "(draw game amount)")))

  (define (check-transition who t)
    (unless (or (not t) (transition? t))
      (error who (sprintf "transition: must be a transition (make-fade, make-transition) or #f, got ~s" t))))

  ;; A request: (kind name transition), kind set, push, pop or call (name
  ;; then being a procedure of the game).
  (define (request! game kind name transition)
    (game-requests-set! game (append (game-requests game) (list (list kind name transition))))
    (unless (game-in-frame? game) (carry-out-requests! game)))

  (define/keywords (game-state-set! game name #!key (transition #f))
    (when name (state-named 'game-state-set! game name))
    (check-transition 'game-state-set! transition)
    (request! game 'set name transition)
    (void))

  (define/keywords (game-state-push! game name #!key (transition #f))
    (state-named 'game-state-push! game name)
    (check-transition 'game-state-push! transition)
    (request! game 'push name transition)
    (void))

  (define/keywords (game-state-pop! game #!key (transition #f))
    (check-transition 'game-state-pop! transition)
    (request! game 'pop #f transition)
    (void))

  ;; (proc game) at the transition's midpoint, when the screen is covered:
  ;; a change of scene (game-scene-set!, game-load-scene!) or anything else.
  (define/keywords (game-transition! game proc #!key (transition #f))
    (unless (procedure? proc)
      (error 'game-transition! (sprintf "expected a procedure (lambda (game) ...), got ~s" proc)))
    (check-transition 'game-transition! transition)
    (request! game 'call proc transition)
    (void))

  (define (game-transitioning? game) (and (game-transition game) #t))

  (define (call-hook proc game) (when proc (proc game)))

  (define (named-state game name)
    (let ((p (and name (assoc name (game-states game))))) (and p (cdr p))))

  ;; The change itself: leave: of each state left, top first, then enter:
  ;; (set, push) or resume: (pop) of the state on top.
  (define (make-change! game kind name)
    (let ((stack (game-state-stack* game)))
      (case kind
        ((set)
         (for-each (lambda (n) (let ((st (named-state game n))) (when st (call-hook (game-state-leave st) game))))
                   stack)
         (game-state-stack-set! game (if name (list name) '()))
         (when name (call-hook (game-state-enter (named-state game name)) game)))
        ((push)
         (game-state-stack-set! game (cons name (if (null? stack) '(#f) stack)))
         (call-hook (game-state-enter (state-named 'game-state-push! game name)) game))
        ((pop)
         (unless (and (pair? stack) (car stack))
           (error 'game-state-pop! "no state to pop: the game's own hooks are running"))
         (let ((st (named-state game (car stack))))
           (when st (call-hook (game-state-leave st) game)))
         (let ((rest (if (equal? (cdr stack) '(#f)) '() (cdr stack))))
           (game-state-stack-set! game rest)
           (let ((st (and (pair? rest) (named-state game (car rest)))))
             (when st (call-hook (game-state-resume st) game)))))
        ((call) (name game)))))

  ;; The requests waiting, in order, until one starts a transition (the
  ;; rest then wait for its end). Requests their hooks make join the queue.
  (define (carry-out-requests! game)
    (when (and (pair? (game-requests game)) (not (game-transition game)))
      (carry-out-queue! game)))

  (define (carry-out-queue! game)
    (let ((was (game-in-frame? game)))
      (dynamic-wind
       (lambda () (game-in-frame-set! game #t))
       (lambda ()
         (let loop ((n 0))
           (let ((q (game-requests game)))
             (when (and (pair? q) (not (game-transition game)))
               (when (> n 1000)
                 (error 'game-state-set! "state changes keep asking for more (1000 in one frame): an enter: or leave: hook asks for a change each time"))
               (game-requests-set! game (cdr q))
               (let ((r (car q)))
                 (if (caddr r)
                     (game-transition-set! game (vector r (caddr r) 'out 0))
                     (make-change! game (car r) (cadr r))))
               (loop (+ n 1))))))
       (lambda () (game-in-frame-set! game was)))))

  ;; The transition's clock: its first half ends with the change, its
  ;; second with the requests that waited.
  (define (advance-transition! game dt)
    (let ((tr (game-transition game)))
      (when tr
        (let ((time (+ (vector-ref tr 3) dt))
              (t (vector-ref tr 1)))
          (cond ((eq? (vector-ref tr 2) 'out)
                 (if (>= time (transition-out t))
                     (begin (vector-set! tr 2 'in)
                            (vector-set! tr 3 0)
                            (midpoint! game tr))
                     (vector-set! tr 3 time)))
                ((>= time (transition-in t)) (game-transition-set! game #f))
                (else (vector-set! tr 3 time)))))))

  ;; The change, under the full cover; the changes its own hooks (or
  ;; game-transition!'s procedure) ask for are made now too, those that
  ;; waited for the transition after its second half.
  (define (midpoint! game tr)
    (let ((waiting (game-requests game))
          (r (vector-ref tr 0)))
      (game-requests-set! game '())
      (game-transition-set! game #f)
      (let ((was (game-in-frame? game)))
        (dynamic-wind
         (lambda () (game-in-frame-set! game #t))
         (lambda () (make-change! game (car r) (cadr r)))
         (lambda () (game-in-frame-set! game was))))
      (carry-out-requests! game)
      ;; the second half plays, unless those started a transition of their own
      (unless (game-transition game) (game-transition-set! game tr))
      (game-requests-set! game (append (game-requests game) waiting))))

  ;;; The layers of the stack, top first: a state record, or 'game for
  ;;; the game's own hooks.
  (define (layers game)
    (let ((stack (game-state-stack* game)))
      (if (null? stack)
          '(game)
          (map (lambda (n) (if n (or (named-state game n) 'none) 'game)) stack))))

  (define (layer-update l game)
    (cond ((eq? l 'game) (game-update-hook game)) ((eq? l 'none) #f) (else (game-state-update l))))
  (define (layer-render l game)
    (cond ((eq? l 'game) (game-render-hook game)) ((eq? l 'none) #f) (else (game-state-render l))))

  ;; The layers from the top down while each lets the one below run
  ;; (below?: update-below? or draw-below?), and whether the bottom one,
  ;; whose scene it is, is among them.
  (define (reached game below?)
    (if (null? (game-state-stack* game))
        (values '(game) #t)             ; no state: the game's own hooks
        (reached-through (layers game) below?)))

  (define (reached-through layers below?)
    (let loop ((ls layers) (out '()))
      (cond ((null? (cdr ls)) (values (cons (car ls) out) #t))
            ((and (game-state? (car ls)) (below? (car ls))) (loop (cdr ls) (cons (car ls) out)))
            (else (values (cons (car ls) out) #f)))))

  (define (out-half? game)
    (let ((tr (game-transition game))) (and tr (eq? (vector-ref tr 2) 'out))))

  ;;; What the engine calls, in this order, each frame.

  ;; Starts a frame: #t when the scene runs in it (nothing frozen).
  (define (begin-frame! game)
    (game-in-frame-set! game #t)
    (and (not (out-half? game))
         (receive (ls bottom?) (reached game game-state-update-below?) bottom?)))

  ;; The update: hooks of the layers that run, bottom first.
  (define (run-update-hooks! game dt)
    (unless (out-half? game)
      (receive (ls bottom?) (reached game game-state-update-below?)
        (for-each (lambda (l) (let ((h (layer-update l game))) (when h (h game dt)))) ls))))

  ;; Ends the frame's hooks: the transition's clock moves on by dt, then
  ;; the changes asked for are made. ran?: the scene ran this frame.
  (define (end-frame! game dt ran?)
    (when ran? (game-scene-time-set! game (+ (game-scene-time game) dt)))
    (game-in-frame-set! game #f)
    (advance-transition! game dt)
    (carry-out-requests! game))

  ;; A frame a hook's error ended: the changes it asked for wait (for the
  ;; next frame's end, or one asked for between frames, as from the REPL).
  (define (abandon-frame! game) (game-in-frame-set! game #f))

  ;; Whether the scene is drawn under the states' render: hooks.
  (define (scene-drawn? game)
    (receive (ls bottom?) (reached game game-state-draw-below?) bottom?))

  ;; The render: hooks of the layers drawn, bottom first; the changes
  ;; they ask for are made once they have drawn.
  (define (run-render-hooks! game)
    (receive (ls bottom?) (reached game game-state-draw-below?)
      (dynamic-wind
       (lambda () (game-in-frame-set! game #t))
       (lambda () (for-each (lambda (l) (let ((h (layer-render l game))) (when h (h game)))) ls))
       (lambda () (game-in-frame-set! game #f))))
    (carry-out-requests! game))

  ;; The transition's cover, when one plays.
  (define (draw-transition! game)
    (let ((tr (game-transition game)))
      (when tr
        (let* ((t (vector-ref tr 1))
               (time (vector-ref tr 3))
               (amount (if (eq? (vector-ref tr 2) 'out)
                           (if (zero? (transition-out t)) 1 (min 1 (/ time (transition-out t))))
                           (if (zero? (transition-in t)) 0 (max 0 (- 1 (/ time (transition-in t))))))))
          (when (transition-draw t) ((transition-draw t) game amount))))))

  (define (active-state game) (named-state game (game-current-state game)))

  (define (active-update-hook game)
    (let ((st (active-state game)))
      (if st (game-state-update st) (game-update-hook game))))

  (define (active-render-hook game)
    (let ((st (active-state game)))
      (if st (game-state-render st) (game-render-hook game)))))
