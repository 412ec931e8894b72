;;; (downstroke engine): what a game imports to run: the frame loop
;;; (game-start!, game-step!, game-run!) and the engine update, plus, under
;;; the same name, the game record of (downstroke game), the level loader
;;; of (downstroke level) and the pipelines of (downstroke pipeline).
;;;
;;; `make-game` only builds a record: no SDL call is made until the game
;;; shell opens a window, so the pipeline and the hooks run in csi with no
;;; display. One logical frame is
;;;   input -> the scene's engine update -> update: -> camera follow -> render
;;; and `game-step!` runs the middle three, the part that needs no device.

(module (downstroke engine)
  (make-game game?
   game-title game-width game-height game-scale game-frame-delay
   game-input-config game-input-config-set! game-debug? game-debug-set! game-headless?
   game-resizable? game-fullscreen? game-fullscreen-set! game-toggle-fullscreen!
   game-mouse-position game-mouse-world-position game-org game-app
   game-save-directory game-save! game-load
   game-preload-hook game-create-hook game-update-hook game-render-hook
   game-scene game-scene-set! game-input game-input-set!
   game-renderer game-renderer-set! game-window game-window-set!
   game-frame game-asset game-asset-set!
   ;; from (downstroke pipeline) and (downstroke level), for games
   engine-pipeline contract-pipeline
   default-engine-update run-engine-update!
   game-start! game-step!
   game-run! game-recording game-surface game-load-scene! game-load-tilesets! game-textures
   load-tilemap-textures!
   game-add-state! game-state-set! game-current-state game-states
   game-state-push! game-state-pop! game-state-stack game-transition!
   make-transition transition? make-fade game-transitioning? game-scene-time
   game-frame-profile game-paused? game-resume! game-quit!
   game-debug-corner game-debug-corner-set!)

  (import (downstroke keywords))
  (import scheme (chicken base) (chicken format) (chicken process-context) (chicken fixnum)
          (chicken foreign) (chicken condition) (chicken file) (chicken pathname) (chicken port)
          (downstroke game) (downstroke level) (downstroke pipeline)
          (downstroke scene) (downstroke sdl2) (downstroke renderer) (downstroke input)
          (downstroke repl) (downstroke camera) (downstroke save) (downstroke run-options)
          (only (downstroke timer) step-scene-timers)
          (only (chicken platform) return-to-host))

  ;;; ------------------------------------------------------------------
  ;;; Input, window and pointer settings a game changes while it runs.

  ;; Replacing the input configuration (a rebinding screen): the next
  ;; frame's input uses it; #f means *default-input-config*.
  (define (game-input-config-set! game config)
    (unless (or (not config) (input-config? config))
      (error 'game-input-config-set! "not an input configuration (make-input-config makes one)" config))
    (%game-input-config-set! game config))

  (define (current-config game)
    (let ((c (game-input-config game)))
      (cond ((not c) *default-input-config*)
            ((input-config? c) c)
            (else (error 'game-run! "input-config: not an input configuration (make-input-config makes one)" c)))))

  (define (game-fullscreen? game) (game-fullscreen-flag game))

  ;; Fullscreen at the desktop's resolution, the game letterboxed in it;
  ;; before the run (or headless) it only sets what the window starts as.
  (define (game-fullscreen-set! game on?)
    (let ((w (game-window game)))
      (when w
        (cond ((and on? (not (window-fullscreen? w)))
               (receive (ww wh) (window-size w)
                 (set! windowed-sizes (cons (list game ww wh) (remove-game-entry game windowed-sizes))))
               (window-fullscreen-set! w #t))
              ((and (not on?) (window-fullscreen? w))
               (window-fullscreen-set! w #f)
               ;; back to the size it had (SDL does not always restore it,
               ;; e.g. with no window manager)
               (let ((old (assq game windowed-sizes)))
                 (when old (window-size-set! w (cadr old) (caddr old))))))))
    (game-fullscreen-flag-set! game (and on? #t)))

  ;; (game width height) of each game's window before it went fullscreen.
  (define windowed-sizes '())
  (define (remove-game-entry game entries)
    (cond ((null? entries) '())
          ((eq? (car (car entries)) game) (cdr entries))
          (else (cons (car entries) (remove-game-entry game (cdr entries))))))

  (define (game-toggle-fullscreen! game)
    (game-fullscreen-set! game (not (game-fullscreen? game))))

  ;; The pointer in logical screen pixels (SDL maps the window's pixels
  ;; through the scale and the letterbox), (values x y).
  (define (game-mouse-position game)
    (let ((in (game-input game)))
      (if in (input-mouse-position in) (values 0 0))))

  ;; The pointer in world pixels: through the scene's camera (its
  ;; position and zoom), as the renderer draws the world.
  (define (game-mouse-world-position game)
    (receive (x y) (game-mouse-position game)
      (let* ((scene (game-scene game))
             (cam (and scene (scene-camera scene))))
        (if cam
            (values (+ (camera-x cam) (/ x (camera-zoom cam)))
                    (+ (camera-y cam) (/ y (camera-zoom cam))))
            (values x y)))))

  ;;; Save data: (downstroke save) in the directory SDL gives the game's
  ;;; org: and app: (SDL_GetPrefPath, created when missing).

  (define (game-save-directory game) (pref-path (game-org game) (game-app game)))

  (define (game-save! game name value)
    (save-data-write! (game-save-directory game) name value)
    (web-storage-sync!))

  (define (game-load game name #!optional (default no-default))
    (if (eq? default no-default)
        (save-data-read (game-save-directory game) name)
        (save-data-read (game-save-directory game) name default)))

  (define no-default (list 'no-default))

  (define (default-engine-update game dt)
    (let ((scene (game-scene game)))
      (when scene
        (game-scene-set! game (handle-exceptions exn (raise-naming-step game scene dt exn)
                                (engine-pipeline scene dt))))))

  ;; An error of the engine's fused pipeline, raised again naming the
  ;; frame and the step that raised it (the steps are run again one at a
  ;; time on the scene the frame started with, which costs nothing on a
  ;; frame that goes well). The condition keeps its kinds; the step is
  ;; its property (pipeline step).
  (define (raise-naming-step game scene dt exn)
    (receive (step _) (pipeline-failing-step scene dt)
      (if (and step ((condition-predicate 'exn) exn))
          (abort (make-composite-condition
                  (make-property-condition
                   'exn 'location 'engine-update
                   'message (sprintf "frame ~a, engine update, step ~a: ~a" (game-frame game) step
                                     ((condition-property-accessor 'exn 'message "") exn))
                   'arguments ((condition-property-accessor 'exn 'arguments '()) exn))
                  (make-property-condition 'pipeline 'step step)
                  exn))
          (abort exn))))

  ;; The scene's engine-update field: #f runs the default pipeline, a
  ;; procedure runs instead of it as (proc game dt), 'none runs nothing.
  ;; The scene's timers run first, whichever it is.
  (define (run-engine-update! game dt)
    (run-scene-timers! game dt)
    (let ((scene (game-scene game)))
      (when scene
        (let ((eu (scene-engine-update scene)))
          (cond ((not eu) (default-engine-update game dt))
                ((procedure? eu) (eu game dt))
                ((eq? eu 'none))
                (else (error 'run-engine-update!
                             "scene engine-update must be #f, a procedure or 'none" eu)))))))

  (define (run-scene-timers! game dt)
    (let ((scene (game-scene game)))
      (when (and scene (pair? (scene-timers scene)))
        (game-scene-set! game (step-scene-timers scene dt)))))

  ;; What a game does once before its first frame.
  (define (game-start! game)
    (let ((preload (game-preload-hook game))
          (create (game-create-hook game)))
      (when preload (preload game))
      (when create (create game))))

  ;; One logical frame without devices: engine update, update:, the
  ;; state changes asked for, camera follow. dt defaults to the game's
  ;; frame delay (ms). While a state is pushed over the scene (or a
  ;; transition's first half plays) the scene is frozen: no engine update,
  ;; no camera follow (game.scm, "Named game states").
  (define (game-step! game #!optional (dt (game-frame-delay game)))
    (let ((runs? (begin-frame! game))
          (done? #f))
      (dynamic-wind
       void
       (lambda ()
         (let* ((t0 (now-ms))
                (t1 (begin (when runs? (run-engine-update! game dt)) (now-ms))))
           (run-update-hooks! game dt)
           (profile-set! game 0 (- t1 t0))
           (profile-set! game 1 (- (now-ms) t1))
           (profile-set! game 2 0))            ; until the frame is drawn
         (set! done? #t))
       ;; an error in a hook leaves no frame open (the REPL goes on)
       (lambda () (unless done? (abandon-frame! game))))
      (end-frame! game dt runs?)
      (let ((scene (game-scene game)))
        (when (and scene runs?)
          (game-scene-set! game (scene-follow-camera scene (game-width game)
                                                     (game-height game))))))
    (game-frame-set! game (+ (game-frame game) 1)))

  ;; A transition that fades the frame to `color` (r g b) over out: ms,
  ;; then back from it over in: ms.
  (define/keywords (make-fade #!key (out 250) (in 250) (color '(0 0 0)))
    (unless (and (list? color) (= (length color) 3)
                 (let ok ((c color)) (or (null? c) (and (exact-integer? (car c)) (<= 0 (car c) 255) (ok (cdr c))))))
      (error 'make-fade (sprintf "color: expected (r g b), each 0-255, got ~s" color)))
    (make-transition out: out in: in draw: (lambda (game amount) (fade-cover! game color amount))))

  (define (fade-cover! game color amount)
    (let ((r (game-renderer game))
          (a (inexact->exact (round (* 255 amount)))))
      (when (and r (> a 0))
        (render-draw-blend-mode-set! r (if (< a 255) 'blend 'none))
        (render-draw-color-set! r (car color) (cadr color) (caddr color) a)
        (render-fill-rect! r (make-rect 0 0 (game-width game) (game-height game)))
        (render-draw-blend-mode-set! r 'none))))

  ;;; The frame profile: how long the last frames' engine update, update:
  ;;; and drawing took (ms, from a monotonic clock), for the overlay and
  ;;; for game-frame-profile.

  (foreign-declare "#include <time.h>")
  (define now-ms
    (foreign-lambda* double ()
      "struct timespec t; clock_gettime(CLOCK_MONOTONIC, &t);
       C_return(t.tv_sec * 1e3 + t.tv_nsec / 1e6);"))

  (define (profile-slot game part)
    (let ((v (game-profile game)))
      (+ (* 3 (modulo (game-frame game) (quotient (vector-length v) 3))) part)))

  (define (profile-set! game part ms)
    (vector-set! (game-profile game) (profile-slot game part) ms))

  ;; The mean time of each part over the frames remembered (at most the
  ;; last 60 run): ((engine . ms) (update . ms) (render . ms) (frames . n)
  ;; (fps . rate)), rate the frames drawn per second of real time over the
  ;; last whole second (0 in the first second).
  ;; Frames run by game-step! alone have no drawing time (0).
  (define (game-frame-profile game)
    (let* ((v (game-profile game))
           (n (min (game-frame game) (quotient (vector-length v) 3))))
      (define (mean part)
        (if (= n 0)
            0
            (let loop ((i 0) (sum 0))
              (if (= i n) (/ sum n) (loop (+ i 1) (+ sum (vector-ref v (+ (* 3 i) part))))))))
      (list (cons 'engine (mean 0)) (cons 'update (mean 1)) (cons 'render (mean 2))
            (cons 'frames n) (cons 'fps (game-fps game)))))

  ;; Frames drawn per second, counted over windows of a second of real
  ;; time: the rate of the last whole window (0 before the first ends).
  (define (count-draw! game)
    (let ((c (game-draw-clock game)) (now (now-ms)))
      (cond ((not (vector-ref c 0)) (vector-set! c 0 now) (vector-set! c 1 0))
            ((>= (- now (vector-ref c 0)) 1000)
             (vector-set! c 2 (/ (* 1000. (vector-ref c 1)) (- now (vector-ref c 0))))
             (vector-set! c 0 now)
             (vector-set! c 1 0)))
      (vector-set! c 1 (+ 1 (vector-ref c 1)))))

  (define (game-fps game) (vector-ref (game-draw-clock game) 2))

  ;; The overlay's readout, in a corner of the view the game chooses
  ;; (game-debug-corner-set!: top-left, top-right, bottom-left or
  ;; bottom-right, the default, away from the HUD games put at the top):
  ;; a bar per part, its length the part's share of the frame budget (the
  ;; frame delay) across half the view, growing from the corner's side:
  ;; green engine update, blue update:, orange drawing; a grey tick marks
  ;; the whole budget. Beside the bars, on the side away from the edge, in
  ;; white, the frames drawn per second and the mean time of a frame's
  ;; three parts.
  (define profile-colors '((0 220 0) (60 140 255) (255 160 0)))

  (define debug-corners '(top-left top-right bottom-left bottom-right))
  (define game-corners '())           ; (game . corner), for games that chose

  (define (game-debug-corner game)
    (let ((c (assq game game-corners))) (if c (cdr c) 'bottom-right)))

  (define (game-debug-corner-set! game corner)
    (unless (game? game) (error 'game-debug-corner-set! "not a game" game))
    (unless (memq corner debug-corners)
      (error 'game-debug-corner-set! (sprintf "the corner must be one of ~s, got ~s" debug-corners corner)))
    (set! game-corners (cons (cons game corner) (remove-game-entry game game-corners))))

  (define (draw-profile! game renderer)
    (let* ((p (game-frame-profile game))
           (budget (game-frame-delay game))
           (gw (game-width game))
           (gh (game-height game))
           (full (quotient gw 2))
           (corner (game-debug-corner game))
           (right? (memq corner '(top-right bottom-right)))
           (bottom? (memq corner '(bottom-left bottom-right)))
           (bars-y (if bottom? (- gh 9) 0))
           ;; a bar of length len from the corner's side
           (bar (lambda (len y) (make-rect (if right? (- gw len) 0) y len 2))))
      (render-draw-color-set! renderer 128 128 128)
      (render-fill-rect! renderer (make-rect (if right? (- gw full 1) full) bars-y 1 9))
      (let loop ((parts '(engine update render)) (colors profile-colors) (y bars-y))
        (unless (null? parts)
          (let ((len (min gw (inexact->exact (round (* full (/ (cdr (assq (car parts) p)) budget)))))))
            (apply render-draw-color-set! renderer (car colors))
            (when (> len 0) (render-fill-rect! renderer (bar len y)))
            (loop (cdr parts) (cdr colors) (+ y 3)))))
      ;; the text is drawn in window pixels (scale 1), so that it stays
      ;; sharp at any scale, 2 pixels a dot past a scale of 2
      (render-draw-color-set! renderer 255 255 255)
      (receive (sx sy) (render-scale renderer)
        (let* ((px (if (> (min sx sy) 2) 2 1))
               (text (profile-readout (cdr (assq 'fps p))
                                      (+ (cdr (assq 'engine p)) (cdr (assq 'update p))
                                         (cdr (assq 'render p)))))
               (tw (- (* 4 px (string-length text)) px))
               (bars-h (inexact->exact (ceiling (* 9 sy))))
               (x (if right? (- (inexact->exact (floor (* gw sx))) tw 2) 2))
               (y (if bottom?
                      (- (inexact->exact (floor (* gh sy))) bars-h (* 5 px) 2)
                      (+ 2 bars-h))))
          (render-scale-set! renderer 1 1)
          (draw-readout! renderer text x y px)
          (render-scale-set! renderer sx sy)))))

  ;; "60 FPS 3.2 MS": the rate rounded, the frame time to a tenth of a ms.
  (define (profile-readout fps ms)
    (let* ((tenths (inexact->exact (round (* 10 ms)))))
      (sprintf "~a FPS ~a.~a MS" (inexact->exact (round fps))
               (quotient tenths 10) (remainder tenths 10))))

  ;; A 3x5 pixel font of what the readout needs, one string per row.
  (define readout-glyphs
    '((#\0 "###" "#.#" "#.#" "#.#" "###") (#\1 ".#." "##." ".#." ".#." "###")
      (#\2 "###" "..#" "###" "#.." "###") (#\3 "###" "..#" ".##" "..#" "###")
      (#\4 "#.#" "#.#" "###" "..#" "..#") (#\5 "###" "#.." "###" "..#" "###")
      (#\6 "###" "#.." "###" "#.#" "###") (#\7 "###" "..#" ".#." ".#." ".#.")
      (#\8 "###" "#.#" "###" "#.#" "###") (#\9 "###" "#.#" "###" "..#" "###")
      (#\. "..." "..." "..." "..." ".#.") (#\F "###" "#.." "##." "#.." "#..")
      (#\P "##." "#.#" "##." "#.." "#..") (#\S ".##" "#.." ".#." "..#" "##.")
      (#\M "#.#" "###" "###" "#.#" "#.#") (#\space "..." "..." "..." "..." "...")))

  ;; Draws text of those characters from (x, y), each pixel a px-sized
  ;; square, in the current draw colour; 4 px of advance per character.
  (define (draw-readout! renderer text x y px)
    (let loop ((cs (string->list text)) (cx x))
      (unless (null? cs)
        (let ((g (assv (car cs) readout-glyphs)))
          (when g
            (let rows ((rs (cdr g)) (ry 0))
              (unless (null? rs)
                (let cols ((i 0))
                  (when (< i 3)
                    (when (char=? #\# (string-ref (car rs) i))
                      (render-fill-rect! renderer (make-rect (+ cx (* i px)) (+ y (* ry px)) px px)))
                    (cols (+ i 1))))
                (rows (cdr rs) (+ ry 1))))))
        (loop (cdr cs) (+ cx (* 4 px))))))

  ;;; ------------------------------------------------------------------
  ;;; The game shell.
  ;;;
  ;;; (game-run! game #!key frames input-script record headless? screenshot
  ;;;            repl screenshots trace trace-file (command-line #t))
  ;;;
  ;;; The command line (command-line-arguments, or command-line: a list of
  ;;; strings; #f: none) gives what a keyword does not: --headless,
  ;;; --frames N, --script FILE, --screenshot FILE, --screenshot-at N FILE,
  ;;; --trace WHO:KEY,..., --trace-file FILE ((downstroke run-options)).
  ;;; screenshots: ((frame . "file.png") ...) and the script's (screenshot
  ;;; "file.png") commands save those frames; trace: ((who #:key ...) ...)
  ;;; prints those keys after every frame.
  ;;;
  ;;; Opens SDL (unless it is already initialised, in which case it is
  ;;; left initialised at the end), then a window of (width * scale) x
  ;;; (height * scale), rounded, titled game-title (resizable when the
  ;;; game's resizable? is set, then made fullscreen when its fullscreen?
  ;;; is) with an accelerated renderer
  ;;; (software fallback), or, when the run is headless, no window: a
  ;;; software renderer drawing into an RGBA surface of that size
  ;;; (game-surface). The run is headless when game-run!'s headless?: says
  ;;; so (#t or #f, overriding everything else for this run); without it,
  ;;; when the game's headless? is set or SDL_VIDEODRIVER is "dummy". The renderer's logical size is
  ;;; width x height. Then preload: and create: run, and the loop:
  ;;;
  ;;; Fixed timestep. Real time (SDL ticks) accumulates; each loop runs as
  ;;; many logical frames of frame-delay ms as are due, at most 4; time due
  ;;; beyond that is dropped (so a slow frame never starts a spiral), and
  ;;; when none is due the loop sleeps until the next one. One logical
  ;;; frame: the events polled with input-poll-events! (only the first frame of a catch-up batch
  ;;; sees them) -> the input state (game-input), or the script's state ->
  ;;; the scene's timers and engine update -> update: (game dt) -> the
  ;;; state changes asked for -> camera follow (game-step!: no engine
  ;;; update nor camera follow while a pushed state freezes the scene);
  ;;; then, once per loop that ran a frame: render-scene! (or a black clear
  ;;; when there is no scene, or the states drawn hide it), the render:
  ;;; hooks, a transition's cover, the overlay's readout when the
  ;;; game is in debug mode, the letterbox bars (when the window's shape is
  ;;; not the game's), present. dt is always frame-delay. Each frame reads
  ;;; the game's input configuration anew (game-input-config-set!), and a
  ;;; pressed debug-overlay or fullscreen action, when the configuration
  ;;; has one, toggles the overlay or fullscreen before the engine update.
  ;;; The scene is drawn at game time frames-run * frame-delay ms
  ;;; (render-scene!'s time:), so the map's animated tiles play at the
  ;;; durations Tiled gives them and a replay draws the same frames.
  ;;; A headless run with frames: N never sleeps: it runs exactly N logical
  ;;; frames back to back, each one rendered.
  ;;;
  ;;; frames: N stops after N frames (else the loop runs until quit).
  ;;; The loop ends, before that frame's update, on a (quit) event (window
  ;;; closed) or when the `quit` action (if the configuration has one) is
  ;;; pressed or held.
  ;;; input-script: a script (see (downstroke input)) drives the actions
  ;;; instead of the keyboard; the (quit) event still ends the run.
  ;;; record: #t records the per-frame actions; game-run! then returns the
  ;;; recording as a script (also kept in game-recording), and replaying it
  ;;; with input-script: gives the same frames.
  ;;;
  ;;; A recording ends with the quit action on the frame the run quit (by
  ;;; the action or the (quit) event), so its replay stops there too.
  ;;;
  ;;; screenshot: "path.png" saves the last drawn frame as a PNG, at the
  ;;; output size (width * scale x height * scale), when the loop has ended
  ;;; normally, just before the shutdown (a run that ends in an error saves
  ;;; nothing). Headless, that is the software renderer's surface;
  ;;; windowed, the renderer's pixels read back (before the present, on the
  ;;; frame known to be the last, i.e. every drawn frame when frames: is not
  ;;; given, as the back buffer is undefined after a present) copied into a
  ;;; new RGBA surface. A run that drew no frame saves the cleared target.
  ;;; Missing directories of the path are created; an error creating them
  ;;; or saving is an error of game-run! naming the path (the cleanup still
  ;;; runs).
  ;;;
  ;;; At the end, however the loop ends (an error in a hook included: the
  ;;; error reaches game-run!'s caller unchanged, and the cleanup runs as
  ;;; it unwinds, through dynamic-wind), the renderer, the window or surface
  ;;; and SDL itself (when game-run! initialised it) are freed exactly once,
  ;;; and game-renderer, game-window and game-surface are reset to #f.
  ;;; game-input keeps the last input state. Returns the recording, or the
  ;;; number of frames run when not recording.
  ;;;
  ;;; Game controllers: the game-controller subsystem is started, each
  ;;; controller SDL reports is opened (and closed at the end), and its
  ;;; buttons and axes drive actions through the input config.

  (define max-catch-up 4)

  ;; A window side: the logical size times the scale, in whole pixels.
  (define (scaled n scale) (max 1 (inexact->exact (round (* n scale)))))

  (define (headless-run? game)
    (or (game-headless? game)
        (equal? (get-environment-variable "SDL_VIDEODRIVER") "dummy")))

  ;;; Pausing and quitting from outside the hooks (the REPL, mostly).
  ;;; With a REPL on, an error in a hook pauses the game instead of ending
  ;;; game-run!: frames stop (the window and the REPL stay live) until
  ;;; (game-resume! game). (game-quit! game) ends the run after the frame
  ;;; it is called in.
  (define paused-games '())
  (define quitting-games '())
  (define (game-paused? game) (and (memq game paused-games) #t))
  (define (game-resume! game)
    (set! paused-games (remove-game game paused-games)))
  (define (game-quit! game)
    (unless (memq game quitting-games) (set! quitting-games (cons game quitting-games))))
  (define (remove-game game games)
    (cond ((null? games) '())
          ((eq? (car games) game) (cdr games))
          (else (cons (car games) (remove-game game (cdr games))))))

  ;; Runs thunk; with a REPL, an error pauses the game and is told there
  ;; (and is not raised); without one it is raised as usual.
  (define (guarded repl what thunk)
    (if repl
        (condition-case (thunk)
          (e ()
             (set! paused-games (cons (car repl) paused-games))
             (repl-say! (cdr repl)
                        (sprintf "downstroke: ~a raised an error; the game is paused until (game-resume! game):\n~a"
                                 what (call-with-output-string (lambda (p) (print-error-message e p)))))))
        (thunk)))

  ;; One logical frame. Returns #t when the game should quit instead.
  (define (run-frame! game script events rec-box #!optional repl watch)
    (let* ((config (current-config game))
           (prev (game-input game))
           (from-events (input-update (if script (make-input-state config) prev) config events))
           (state (if script (script (game-frame game) prev config) from-events))
           (action? (lambda (a) (and (input-action? state a) (input-pressed? state a)))))
      (game-input-set! game state)
      ;; the engine's own actions, when the configuration has them
      (when (action? 'debug-overlay) (game-debug-set! game (not (game-debug? game))))
      (when (action? 'fullscreen) (game-toggle-fullscreen! game))
      (if (or (input-quit? from-events)
              (and (input-action? state 'quit)
                   (or (input-pressed? state 'quit) (input-held? state 'quit))))
          (begin
            ;; recorded as the quit action, so the replay stops here too
            (when rec-box
              (set-car! rec-box (input-record (car rec-box) (game-frame game)
                                              (if (input-action? state 'quit)
                                                  (input-from-held prev (cons 'quit (input-held-actions state)))
                                                  state))))
            #t)
          (cond ((memq game quitting-games)
                 (set! quitting-games (remove-game game quitting-games))
                 #t)
                ((game-paused? game) #f)
                (else
                 (when rec-box
                   (set-car! rec-box (input-record (car rec-box) (game-frame game) state)))
                 (guarded repl "a hook or the engine update" (lambda () (game-step! game)))
                 (watch-frame-run! watch (game-scene game) (- (game-frame game) 1))
                 #f)))))

  ;; shot-box: #f, or a one-element list that receives the frame's pixels
  ;; (read before the present) for a windowed screenshot.
  (define (render-frame! game renderer #!optional (shot-box #f) (watch #f))
    (let ((scene (game-scene game))
          (t0 (now-ms)))
      (if (and scene (scene-drawn? game))
          (render-scene! renderer scene textures: (game-textures game)
                         debug?: (game-debug? game)
                         ;; game time: animated map tiles follow the frames
                         ;; the scene ran (they stop while it is frozen)
                         time: (game-scene-time game))
          (begin (render-draw-color-set! renderer 0 0 0)
                 (render-clear! renderer)))
      (run-render-hooks! game)
      (draw-transition! game)
      ;; the frame just drawn is game-frame - 1
      (vector-set! (game-profile game)
                   (+ (* 3 (modulo (- (game-frame game) 1) (quotient (vector-length (game-profile game)) 3))) 2)
                   (- (now-ms) t0))
      (count-draw! game)
      (when (game-debug? game) (draw-profile! game renderer))
      (render-letterbox! renderer (game-width game) (game-height game))
      (when shot-box (set-car! shot-box (capture-pixels renderer)))
      (watch-frame-drawn! watch (- (game-frame game) 1) renderer (game-surface game))
      (render-present! renderer)))

  ;; Returns the number of frames run.
  ;; repl: #f, or (game . repl), served once per pass of the loop.
  (define (run-loop! game renderer script frames fast? rec-box shot-box repl watch)
    (let ((fd (game-frame-delay game)))
      (define (draw! shot)
        (guarded repl "the render: hook or drawing" (lambda () (render-frame! game renderer shot watch))))
      ;; One pass of the real-time loop at `now` (ms), `acc` ms being due
      ;; since `last`: the frames due run, then one draw when any ran.
      ;; Returns the frames run in all, the ms still due, and whether the
      ;; run has ended (frames: reached, or quit).
      (define (pass done acc last now)
        (let* ((acc (+ acc (- now last)))
               (due (quotient acc fd))
               (n (min due max-catch-up (if frames (- frames done) due)))
               (acc (if (> due max-catch-up) (remainder acc fd) (- acc (* n fd)))))
          (if (= n 0)
              (values done acc #f)
              (let batch ((i 0) (events (input-poll-events!)))
                (cond ((= i n)
                       (draw! (and shot-box
                                   (or (not frames) (>= (+ done n) frames))
                                   shot-box))
                       (values (+ done n) acc (and frames (>= (+ done n) frames) #t)))
                      ((run-frame! game script events rec-box repl watch) (values (+ done i) acc #t))
                      (else (batch (+ i 1) '())))))))
      (cond ((and frames (>= 0 frames)) 0)
            ((and (not fast?) (web-build?))
             ;; the browser calls one pass per animation frame
             (let ((done 0) (acc 0) (last (get-ticks)))
               (web-main-loop!
                (lambda ()
                  (when repl (repl-poll! (cdr repl)))
                  (let ((now (get-ticks)))
                    (receive (d a end?) (pass done acc last now)
                      (set! done d) (set! acc a) (set! last now)
                      (and end? done)))))))
            (else
             (let loop ((done 0) (acc 0) (last (get-ticks)))
               (when repl (repl-poll! (cdr repl)))
               (cond ((and frames (>= done frames)) done)
                     (fast?
                      (if (run-frame! game script (input-poll-events!) rec-box repl watch)
                          done
                          (begin (draw! #f)
                                 (loop (+ done 1) 0 last))))
                     (else
                      (let ((now (get-ticks)))
                        (receive (d a end?) (pass done acc last now)
                          (cond (end? d)
                                ((= d done) (delay! (max 1 (- fd a))) (loop d a now))
                                (else (loop d a now))))))))))))

  ;;; The browser build (make web, which compiles with the feature
  ;;; downstroke-web): a page must get its thread back after every pass of
  ;;; the loop, so game-run! hands the browser one pass to call on each
  ;;; animation frame (emscripten_set_main_loop) and returns to the page.
  ;;; When a pass ends the run (a pass returns the frames run instead of
  ;;; #f) the loop is cancelled and game-run! goes on from where it left,
  ;;; through the continuation kept for it, so what follows game-run! in
  ;;; the game runs as it does natively. The save directory lies in the
  ;;; browser's storage (IndexedDB), written back after each game-save!.
  ;;; docs/guide.org, "Shipping to the web".
  (cond-expand
    (downstroke-web
     (foreign-declare "#include <emscripten.h>")
     (define (web-build?) #t)
     (define web-pass void)
     (define-external (downstroke_web_frame) void (web-pass))
     (define (web-main-loop! pass)
       (call/cc
        (lambda (k)
          (set! web-pass
            (lambda ()
              (let ((ran (pass)))
                (when ran
                  (set! web-pass void)
                  ((foreign-lambda* void () "emscripten_cancel_main_loop();"))
                  (k ran)))))
          ((foreign-lambda* void () "emscripten_set_main_loop(downstroke_web_frame, 0, 0);"))
          (return-to-host))))
     (define (web-storage-sync!)
       ((foreign-lambda* void ()
          "EM_ASM(FS.syncfs(false, function (e) {
             if (e) console.error('downstroke: saving to the browser storage failed', e); }));"))))
    (else
     (define (web-build?) #f)
     (define (web-main-loop! pass) (void))
     (define (web-storage-sync!) (void))))

  (define unset (list 'unset))

  ;; repl: #f; 'stdin; a TCP port number (0: any free one); or a list of
  ;; such. The port and its secret's file are printed when the REPL opens;
  ;; its limits are the (downstroke repl) parameters of the moment.
  (define (check-repl-option who repl)
    (for-each (lambda (p)
                (unless (or (eq? p 'stdin) (and (exact-integer? p) (<= 0 p 65535)))
                  (error (sprintf "~a: repl: ~s must be #f, 'stdin, a TCP port number or a list of those"
                                  who repl))))
              (if (list? repl) repl (list repl))))

  (define (repl-options who repl)
    (check-repl-option who repl)
    (let ((parts (if (list? repl) repl (list repl))))
      (values (memq 'stdin parts)
              (let find ((ps parts)) (cond ((null? ps) #f) ((exact-integer? (car ps)) (car ps))
                                           (else (find (cdr ps))))))))

  ;; What the command line asks, under game-run!'s keywords: a keyword
  ;; given wins. (values frames input-script headless? screenshot
  ;; screenshots trace trace-file profile?), each `unset` when neither
  ;; says (profile?, the command line's alone, is #t or #f).
  (define (run-request command-line frames input-script headless? screenshot screenshots trace trace-file)
    (let* ((opts (cond ((eq? command-line #t) (command-line-run-options (command-line-arguments)))
                       ((not command-line) '())
                       ((and (list? command-line) (every-string? command-line))
                        (command-line-run-options command-line))
                       (else (error 'game-run! "command-line: must be #t, #f or a list of strings" command-line))))
           (asked (lambda (given name) (if (eq? given unset) (run-option opts name unset) given)))
           (headless (asked headless? 'headless))
           (frames (cond ((not (eq? frames unset)) frames)
                         ((assq 'frames opts) => cdr)
                         ;; --headless alone would never end
                         ((assq 'headless opts) 300)
                         (else #f)))
           (script (cond ((not (eq? input-script unset)) input-script)
                         ((assq 'script opts) => (lambda (p) (read-script-file (cdr p))))
                         (else #f))))
      (values frames script headless (let ((s (asked screenshot 'screenshot))) (if (eq? s unset) #f s))
              (append screenshots (let loop ((os opts))
                                    (cond ((null? os) '())
                                          ((eq? (caar os) 'screenshot-at) (cons (cdar os) (loop (cdr os))))
                                          (else (loop (cdr os))))))
              (append trace (let loop ((os opts))
                              (cond ((null? os) '())
                                    ((eq? (caar os) 'trace) (cons (cdar os) (loop (cdr os))))
                                    (else (loop (cdr os))))))
              (let ((f (asked trace-file 'trace-file))) (if (eq? f unset) #f f))
              (run-option opts 'profile #f))))

  (define (every-string? l) (or (null? l) (and (string? (car l)) (every-string? (cdr l)))))

  (define (read-script-file path)
    (unless (file-exists? path)
      (error 'game-run! (sprintf "--script: no file ~s" path)))
    (handle-exceptions exn
        (error 'game-run! (sprintf "--script: ~s is not one readable datum: ~a" path
                                   ((condition-property-accessor 'exn 'message "") exn)))
      (with-input-from-file path read)))

  (define/keywords (game-run! game #!key (frames unset) (input-script unset) (record #f)
                     (headless? unset) (screenshot unset) (repl #f)
                     (screenshots '()) (trace '()) (trace-file unset) (command-line #t))
    (receive (frames input-script headless? screenshot screenshots trace trace-file profile?)
        (run-request command-line frames input-script headless? screenshot screenshots trace trace-file)
      (receive (input-script script-shots) (script-screenshots input-script)
        (run-game! game frames input-script record headless? screenshot repl
                   (append screenshots script-shots) trace trace-file profile?))))

  (define (run-game! game frames input-script record headless? screenshot repl screenshots trace trace-file
                     profile?)
    (unless (or (not frames) (and (exact-integer? frames) (>= frames 0)))
      (error 'game-run! "frames: must be a non-negative integer or #f" frames))
    (unless (or (not screenshot) (and (string? screenshot) (> (string-length screenshot) 0)))
      (error 'game-run! "screenshot: must be a file path (a string) or #f" screenshot))
    (let* ((config (current-config game))
           (script (and input-script (scripted-input input-script config)))
           (watch (make-watch screenshots trace trace-file
                              (and profile? (lambda () (game-frame-profile game)))))
           (headless (if (eq? headless? unset) (headless-run? game) (and headless? #t)))
           (shot-box (and screenshot (not headless) (list #f)))
           (owns-sdl (not (sdl-initialized?)))
           (w (scaled (game-width game) (game-scale game)))
           (h (scaled (game-height game) (game-scale game)))
           (rec-box (and record (list (make-recording))))
           (window #f) (surface #f) (renderer #f)
           (served #f)                  ; (game . repl) while a REPL runs
           (ran 0))
      (when repl (check-repl-option 'game-run! repl))
      ;; a debug game has its scenes' entities checked at every update-scene
      (parameterize ((scene-checks (if (game-debug? game) 'always (scene-checks))))
      (dynamic-wind
       void
       (lambda ()
         (when owns-sdl (init! '(video events timer)))
         (input-open-controllers!)
         (if headless
             (begin (set! surface (create-rgba-surface! w h))
                    (set! renderer (create-software-renderer! surface)))
             (begin (set! window (create-window! (game-title game) 'centered 'centered w h
                                                 (if (game-resizable? game) '(shown resizable) '(shown))))
                    (set! renderer (create-renderer! window))
                    (game-window-set! game window)
                    ;; made fullscreen once it exists, so that leaving
                    ;; fullscreen gives back the window's own size
                    (when (game-fullscreen? game) (game-fullscreen-set! game #t))))
         (render-set-logical-size! renderer (game-width game) (game-height game))
         (game-window-set! game window)
         (game-surface-set! game surface)
         (game-renderer-set! game renderer)
         (game-input-set! game (make-input-state config))
         ;; the frame rate is counted from this run's first frame
         (let ((c (game-draw-clock game))) (vector-set! c 0 #f) (vector-set! c 1 0) (vector-set! c 2 0))
         (when repl
           (let-values (((stdin? port) (repl-options 'game-run! repl)))
             (set! served (cons game (make-repl port: port stdin?: stdin?)))
             (when port
               ;; the secret's file, and the command that sends it
               (let ((port (repl-port (cdr served))))
                 (print "downstroke: repl on 127.0.0.1 port " port ", for this user only (secret in "
                        (repl-secret-file (cdr served)) ")")
                 (print "downstroke: connect with: csi -q -R downstroke.repl -e '(repl-connect " port ")'"))
               (flush-output))))
         (game-start! game)
         (set! ran (run-loop! game renderer script frames
                              (and frames headless) rec-box shot-box served watch))
         (when screenshot
           (save-screenshot! screenshot renderer surface (and shot-box (car shot-box)))))
       (lambda ()
         (watch-end! watch ran)
         (when served (repl-close! (cdr served)) (game-resume! game) (set! served #f))
         (when rec-box (game-recording-set! game (recording->script (car rec-box))))
         (free-textures! game)
         (input-close-controllers!)
         (game-renderer-set! game #f)
         (game-window-set! game #f)
         (game-surface-set! game #f)
         (let ((r renderer) (wi window) (s surface))
           (set! renderer #f) (set! window #f) (set! surface #f)
           (when r (destroy-renderer! r))
           (when wi (destroy-window! wi))
           (when s (free-surface! s)))
         (when (and owns-sdl (sdl-initialized?)) (quit!)))))
      (if record (game-recording game) ran))))
