;;; (downstroke engine) game-run!: the headless shell on real SDL (dummy
;;; video driver, software renderer on a surface): frame counts, hook
;;; order, scripted and recorded input, cleanup after errors, quitting,
;;; game states.

(import scheme (chicken base) (chicken string) (chicken file) (chicken time) (chicken port) (chicken io) (chicken condition) srfi-4 (only (downstroke util) take)
        (downstroke test) (downstroke sdl2) (downstroke entity) (downstroke scene)
        (downstroke input) (downstroke engine)
        (only (downstroke tilemap) make-sheet-tileset))
(include-relative "pixels.scm")

;; Earlier suites may leave SDL initialised, and game-run! leaves an SDL it
;; did not open initialised; start from a shut-down SDL so each run below
;; opens and closes its own.
(when (sdl-initialized?) (quit!))

;; A scene with one player square; engine update 'none, so only the hooks move it.
(define (run-player-scene)
  (make-sprite-scene
   entities: (list (plist->entity (list #:type 'player #:x 10 #:y 10 #:width 4 #:height 4
                                        #:color '(0 255 0))))
   background: '(255 0 0) engine-update: 'none camera-target: #f))

(define (run-player g) (car (scene-entities (game-scene g))))

;; update: moves the player one pixel per frame along the held directions.
(define (run-move-player g dt)
  (let* ((in (game-input g))
         (dx (+ (if (input-held? in 'right) 1 0) (if (input-held? in 'left) -1 0)))
         (dy (+ (if (input-held? in 'down) 1 0) (if (input-held? in 'up) -1 0)))
         (jump (if (input-pressed? in 'a) 100 0))
         (p (run-player g)))
    (game-scene-set! g (update-scene (game-scene g)
                                     entities: (list (entity-set (entity-set p #:x (+ (entity-ref p #:x) dx))
                                                                 #:y (+ (entity-ref p #:y) dy (- jump))))))))

(define (run-game . args)
  (apply make-game headless?: #t width: 32 height: 24 args))

(test-group "game-run!: frames"
  (let* ((calls 0)
         (g (run-game update: (lambda (g dt) (set! calls (+ calls 1)))))
         (ran (game-run! g frames: 10)))
    (test "update: runs exactly 10 times" 10 calls)
    (test "game-frame advances to 10" 10 (game-frame g))
    (test "the number of frames run" 10 ran)
    (test-assert "SDL is shut down after the run" (not (sdl-initialized?)))
    (test "the renderer is reset" #f (game-renderer g))
    (test-assert "the last input state is kept" (input-state? (game-input g))))
  (let* ((seen #f)
         (g (run-game scale: 2 title: "t"
                      create: (lambda (g) (set! seen (list (renderer? (game-renderer g))
                                                          (game-window g)
                                                          (receive (w h) (surface-size (game-surface g)) (list w h))
                                                          (receive (w h) (render-logical-size (game-renderer g))
                                                            (list w h))))))))
    (game-run! g frames: 0)
    (test "headless: software renderer on a width*scale surface, no window, logical size"
          '(#t #f (64 48) (32 24)) seen))
  (let* ((dts '())
         (g (run-game frame-delay: 20 update: (lambda (g dt) (set! dts (cons dt dts))))))
    (game-run! g frames: 3)
    (test "dt is the frame delay" '(20 20 20) dts)))

(test-group "game-run!: hook order and drawing"
  (let* ((order '())
         (pixels '())
         (g (run-game
             preload: (lambda (g) (set! order (cons 'preload order)))
             create: (lambda (g) (set! order (cons 'create order))
                       (game-scene-set! g (run-player-scene)))
             update: (lambda (g dt) (set! order (cons 'update order)))
             render: (lambda (g)
                       (set! order (cons 'render order))
                       (let ((r (game-renderer g)))
                         ;; the scene is already drawn: background and the square
                         (set! pixels (list (renderer-pixel r 0 0) (renderer-pixel r 11 11)))
                         (render-draw-color-set! r 0 0 255)
                         (render-fill-rect! r (make-rect 0 0 2 2))
                         (set! pixels (append pixels (list (renderer-pixel r 0 0)))))))))
    (game-run! g frames: 2)
    (test "preload, create, then update before render each frame"
          '(preload create update render update render) (reverse order))
    (test "render: runs after the scene draw and draws on top"
          '((255 0 0 255) (0 255 0 255) (0 0 255 255)) pixels)))

(test-group "game-run!: scripted input"
  (let ((g (run-game create: (lambda (g) (game-scene-set! g (run-player-scene)))
                     update: run-move-player)))
    (game-run! g frames: 10 input-script: '((2 right) (5 right down) (7) (8 (tap a))))
    ;; right on frames 2..6 (5), down on 5..6 (2), a tap on frame 8 (-100)
    (test "the player moved as scripted" '(15 -88)
          (list (entity-ref (run-player g) #:x) (entity-ref (run-player g) #:y)))))

(test-group "game-run!: record and replay"
  (let* ((pushes '((1 key-down right) (3 key-down s) (4 key-up right) (5 key-down j)
                   (5 key-up j) (7 key-up s) (8 key-down left)))
         (pusher (lambda (g dt)
                   (for-each (lambda (p)
                               (when (= (car p) (game-frame g)) (push-key-event! (cadr p) (caddr p))))
                             pushes)))
         (g1 (run-game create: (lambda (g) (game-scene-set! g (run-player-scene)))
                       update: (lambda (g dt) (run-move-player g dt) (pusher g dt))))
         (rec (game-run! g1 frames: 12 record: #t))
         (g2 (run-game create: (lambda (g) (game-scene-set! g (run-player-scene)))
                       update: run-move-player)))
    (test "the recording is a script of the changes"
          '((2 right) (4 down right) (5 down) (6 down (tap a)) (8) (9 left)) rec)
    (test "kept on the game too" rec (game-recording g1))
    (game-run! g2 frames: 12 input-script: rec)
    (test-assert "the live run moved" (not (equal? (run-player g1) (car (scene-entities (run-player-scene))))))
    (test "the replay ends in an equal scene" (scene-entities (game-scene g1))
          (scene-entities (game-scene g2)))
    (test "at the same frame" (game-frame g1) (game-frame g2)))
  ;; a run ended by escape: the replay quits at the same frame
  (let* ((mk (lambda (update)
               (run-game create: (lambda (g) (game-scene-set! g (run-player-scene)))
                         update: update)))
         (g1 (mk (lambda (g dt)
                   (run-move-player g dt)
                   (case (game-frame g)
                     ((0) (push-key-event! 'key-down 'd))
                     ((4) (push-key-event! 'key-down 'escape))))))
         (rec (game-run! g1 frames: 50 record: #t))
         (g2 (mk run-move-player)))
    (test "the recording ends with the quit" '((1 right) (5 right quit)) rec)
    (test "the replay quits at the same frame" (game-frame g1) (game-run! g2 frames: 50 input-script: rec))
    (test "to the same scene" (scene-entities (game-scene g1)) (scene-entities (game-scene g2)))))

(test-group "game-run!: errors free every resource"
  (let* ((r #f) (s #f)
         (g (run-game create: (lambda (g) (set! r (game-renderer g)) (set! s (game-surface g)))
                      update: (lambda (g dt) (when (= (game-frame g) 3) (error 'run-test "boom in update"))))))
    (test-error "the hook's error reaches the caller"
                (lambda (exn) (substring-index "boom" (error-text exn)))
                (game-run! g frames: 10))
    (test "the frames before the error ran" 3 (game-frame g))
    (test-assert "the renderer is destroyed" (not (renderer-alive? r)))
    (test-assert "the surface is freed" (not (surface-alive? s)))
    (test-assert "SDL is shut down" (not (sdl-initialized?)))
    (test "game-renderer is reset" #f (game-renderer g))
    (test-error "an error in render: too"
                (game-run! (run-game render: (lambda (g) (error 'run-test "boom in render")))
                           frames: 5))
    (test-assert "SDL is shut down again" (not (sdl-initialized?)))
    (let ((g2 (run-game)))
      (test "SDL is usable by the next run" 5 (game-run! g2 frames: 5))))
  (test-error "create: raising still cleans up"
              (game-run! (run-game create: (lambda (g) (error 'run-test "boom in create"))) frames: 1))
  (test-assert "... SDL shut down" (not (sdl-initialized?)))
  (test-error "frames: must be a count" (game-run! (run-game) frames: -1)))

(test-group "game-run!: quitting"
  (let ((g (run-game)))
    (test "the quit action in a script ends the loop" 4
          (game-run! g frames: 100 input-script: '((4 quit))))
    (test "no update for the quitting frame" 4 (game-frame g)))
  (let ((g (run-game update: (lambda (g dt) (when (= (game-frame g) 2) (push-key-event! 'key-down 'escape))))))
    (test "escape ends the loop" 3 (game-run! g frames: 100)))
  (let ((g (run-game update: (lambda (g dt) (when (= (game-frame g) 1) (push-quit-event!))))))
    (test "a (quit) event (window closed) ends the loop" 2 (game-run! g frames: 100)))
  (let ((g (run-game update: (lambda (g dt) (when (= (game-frame g) 1) (push-quit-event!))))))
    (test "a (quit) event ends a scripted run too" 2
          (game-run! g frames: 100 input-script: '((0 right)))))
  (let ((g (run-game update: (lambda (g dt) (when (= (game-frame g) 1) (push-quit-event!))))))
    (test "a run closed by a (quit) event records it as the quit action" '((2 quit))
          (game-run! g frames: 100 record: #t))))

(test-group "game-run!: the timed loop"
  ;; no frames: -> real time, fixed steps of frame-delay ms, until quit
  (let* ((t0 #f) (t1 #f)
         (g (run-game frame-delay: 10
                      create: (lambda (g) (set! t0 (get-ticks)))
                      update: (lambda (g dt) (set! t1 (get-ticks))))))
    (test "runs frames until the scripted quit" 5 (game-run! g input-script: '((5 quit))))
    (test-assert "at the fixed rate (about 10 ms a frame, not as fast as possible)"
                 (>= (- t1 t0) 30)))
  (let ()
    ;; a 200 ms frame is 40 frames late; at most 4 catch-up frames follow
    (let* ((after '())
           (g (run-game frame-delay: 5
                        update: (lambda (g dt)
                                  (set! after (cons (get-ticks) after))
                                  (when (= (game-frame g) 1) (delay! 200))))))
      (game-run! g input-script: '((12 quit)))
      (let ((ts (reverse after)))
        (test-assert "a slow frame does not start a spiral of catch-up frames"
                     ;; frames 2..5 catch up at once; frame 6 onwards waits for real time again
                     (>= (- (list-ref ts 11) (list-ref ts 2)) 20))))))

(test-group "game-run!: named game states"
  (let* ((log '())
         (g (run-game update: (lambda (g dt) (set! log (cons 'game log)))
                      render: (lambda (g) (set! log (cons 'game-render log))))))
    (game-add-state! g 'title
                     update: (lambda (g dt)
                               (set! log (cons 'title log))
                               (when (= (game-frame g) 1) (game-state-set! g 'play)))
                     enter: (lambda (g) (set! log (cons 'enter-title log))))
    (game-add-state! g 'play
                     update: (lambda (g dt) (set! log (cons 'play log)))
                     render: (lambda (g) (set! log (cons 'play-render log)))
                     enter: (lambda (g) (set! log (cons 'enter-play log))))
    (game-state-set! g 'title)
    (test "the current state" 'title (game-current-state g))
    (game-run! g frames: 3)
    (test "a state's hooks replace the game's; enter: runs on the switch"
          '(enter-title title title enter-play play-render play play-render) (reverse log))
    (game-state-set! g #f)
    (set! log '())
    (game-step! g)
    (test "#f goes back to the game's hooks" '(game) log)
    (test-error "an unknown state" (game-state-set! g 'nope))))

(test-group "game-run!: game-load-scene!"
  (let* ((dir (create-temporary-directory))
         (path (lambda (n) (string-append dir "/" n)))
         ;; a 2-tile tileset: gid 1 red, gid 2 blue (8x8 each)
         (write-files!
          (lambda (g)
            (write-tiles-png! (path "t.png") 8 '((255 0 0) (0 0 255)))
            (write-csv-tmx! (path "m.tmx") "t.png" 8 2 1
                            '((0 0 0 0) (0 1 0 0) (0 0 0 2)))))
         (pixels '())
         (first-textures #f)
         (after-reload #f)
         (g (run-game
             preload: write-files!
             create: (lambda (g)
                       (game-load-scene! g (path "m.tmx") background: '(0 255 0) camera-target: #f
                                         entities: (list (plist->entity (list #:x 0 #:y 0 #:tile-id 2))))
                       (set! first-textures (game-textures g)))
             update: (lambda (g dt)
                       (when (= (game-frame g) 1)
                         (game-load-scene! g (path "m.tmx") camera-target: #f)
                         (set! after-reload (list (texture-alive? (cdar first-textures))
                                                  (texture-alive? (cdar (game-textures g)))))))
             render: (lambda (g)
                       (let ((r (game-renderer g)))
                         (set! pixels (cons (map (lambda (xy) (renderer-pixel r (car xy) (cadr xy)))
                                                 '((3 3) (9 9) (25 17) (20 3)))
                                            pixels)))))))
    (game-run! g frames: 3)
    (test "the map's tiles and the sprite are drawn from the loaded textures"
          '((0 0 255 255) (255 0 0 255) (0 0 255 255) (0 255 0 255))
          (car (reverse pixels)))
    (test "after reloading: no sprite, default background"
          '((0 0 0 255) (255 0 0 255) (0 0 255 255) (0 0 0 255))
          (car pixels))
    (test "reloading destroyed the first scene's textures, the new ones live" '(#f #t) after-reload)
    (test-assert "and they are dead after the run" (not (texture-alive? (cdar first-textures))))
    (test "the textures are released at the end" '() (game-textures g))
    (test-error "game-load-scene! needs a running game"
                (lambda (exn) (substring-index "renderer" (error-text exn)))
                (game-load-scene! (run-game) (path "m.tmx")))))

(test-group "game-run!: game-load-tilesets!"
  ;; A sprite scene from a sheet made in code: no map anywhere. Sprites
  ;; gid 1 (red) and 2 (blue) draw from the texture game-load-tilesets!
  ;; loaded; a second call for the same image loads nothing more.
  (let* ((dir (create-temporary-directory))
         (png (string-append dir "/s.png"))
         (seen #f) (pixels #f) (textures-in-run #f)
         (g (run-game
             preload: (lambda (g) (write-tiles-png! png 8 '((255 0 0) (0 0 255))))
             create: (lambda (g)
                       (let* ((sheet (make-sheet-tileset png tile-width: 8 tile-height: 8 columns: 2))
                              (back (game-load-tilesets! g (list sheet)))
                              (once (length (game-textures g))))
                         (game-load-tilesets! g (list sheet))
                         (set! seen (list (eq? (car back) sheet) once (length (game-textures g))
                                          (texture-alive? (cdar (game-textures g)))))
                         (set! textures-in-run (game-textures g))
                         (game-scene-set! g (make-sprite-scene
                                             tileset: sheet background: '(0 255 0) camera-target: #f
                                             entities: (list (plist->entity (list #:x 0 #:y 0 #:tile-id 1))
                                                             (plist->entity (list #:x 10 #:y 0 #:tile-id 2)))))))
             render: (lambda (g)
                       (let ((r (game-renderer g)))
                         (set! pixels (map (lambda (xy) (renderer-pixel r (car xy) (cadr xy)))
                                           '((3 3) (13 3) (20 3)))))))))
    (game-run! g frames: 1)
    (test "it returns the tilesets; one texture, loaded once" '(#t 1 1 #t) seen)
    (test "the sprites are drawn from it, with no map and no tileset-texture:"
          '((255 0 0 255) (0 0 255 255) (0 255 0 255)) pixels)
    (test-assert "the game frees it at the end of the run" (not (texture-alive? (cdar textures-in-run))))
    (test "and forgets it" '() (game-textures g))
    (test-error "it needs a running game"
                (lambda (exn) (substring-index "renderer" (error-text exn)))
                (game-load-tilesets! (run-game) '()))
    (test-error "it takes a list of tilesets"
                (lambda (exn) (substring-index "tilesets" (error-text exn)))
                (game-load-tilesets! (run-game) (list png)))
    (let* ((missing #f)
           (g (run-game preload: (lambda (g) (write-tiles-png! png 8 '((255 0 0) (0 0 255))))
                        create: (lambda (g)
                                  (let ((sheet (make-sheet-tileset png tile-width: 8 tile-height: 8 columns: 2)))
                                    (delete-file png)
                                    (set! missing
                                      (handle-exceptions exn (list (substring-index "s.png" (error-text exn))
                                                                   (game-textures g))
                                        (game-load-tilesets! g (list sheet)))))))))
      (game-run! g frames: 0)
      (test-assert "an image that fails to load is an error naming it, and nothing is added"
                   (and (car missing) (null? (cadr missing)))))))

(test-group "game-run!: headless? and screenshot"
  (let* ((dir (create-temporary-directory))
         (shot (string-append dir "/a/b/shot.png"))
         (seen #f)
         (g (make-game headless?: #f width: 32 height: 24 scale: 2
                       create: (lambda (g)
                                 (set! seen (list (game-window g) (surface? (game-surface g))))
                                 (game-scene-set! g (run-player-scene))))))
    (test "headless?: #t overrides the game's #f" 3 (game-run! g frames: 3 headless?: #t screenshot: shot))
    (test "headless: no window, a surface" '(#f #t) seen)
    (test-assert "the screenshot exists, its directories created" (file-exists? shot))
    (let ((s (img-load-surface! shot)))
      (receive (px w h) (surface-pixels s)
        (let ((at (lambda (x y) (rgba-at px w x y))))
          (test "the screenshot is the output size" '(64 48) (list w h))
          (test "background colour at a free pixel" '(255 0 0 255) (at 2 40))
          (test "the entity's colour where it is (x 10..14, scale 2)" '(0 255 0 255) (at 22 22))
          (test "the entity's edge" '((0 255 0 255) (255 0 0 255)) (list (at 27 27) (at 28 28)))))
      (free-surface! s))
    (test-assert "SDL is shut down after a screenshot run" (not (sdl-initialized?))))
  ;; the windowed path, on whatever video driver is present (dummy in the tests)
  (let* ((dir (create-temporary-directory))
         (shot (string-append dir "/w.png"))
         (seen #f)
         (g (make-game headless?: #t width: 32 height: 24
                       create: (lambda (g)
                                 (set! seen (list (window? (game-window g)) (game-surface g)))
                                 (game-scene-set! g (run-player-scene))))))
    (game-run! g frames: 2 headless?: #f screenshot: shot)
    (test "headless?: #f overrides the game's #t: a window, no surface" '(#t #f) seen)
    (let ((s (img-load-surface! shot)))
      (receive (px w h) (surface-pixels s)
        (let ((at (lambda (x y) (take (rgba-at px w x y) 3))))
          (test "windowed screenshot: size, background, entity"
                '((32 24) (255 0 0) (0 255 0))
                (list (list w h) (at 1 1) (at 11 11)))))
      (free-surface! s))
    (test-assert "no window left" (not (sdl-initialized?))))
  (let* ((dir (create-temporary-directory))
         (blocker (string-append dir "/file")))
    (with-output-to-file blocker (lambda () (display "x")))
    (test-error "a screenshot that cannot be saved is an error naming the path"
                (lambda (exn) (substring-index (string-append blocker "/x.png") (error-text exn)))
                (game-run! (run-game) frames: 1 screenshot: (string-append blocker "/x.png")))
    (test-assert "and the run still shut down" (not (sdl-initialized?)))
    (test-error "screenshot: must be a path"
                (game-run! (run-game) frames: 1 screenshot: 'x))))

;; Busy until the millisecond clock has moved on by `ms`: at least ms - 1
;; milliseconds of real time.
(define (run-busy ms)
  (let ((end (+ (current-milliseconds) ms)))
    (let loop () (when (< (current-milliseconds) end) (loop)))))

(test-group "game-run!: the frame profile"
  (let ((g (run-game update: (lambda (g dt) (run-busy 3))
                     render: (lambda (g) (run-busy 2)))))
    (game-run! g frames: 12)
    (let ((p (game-frame-profile g)))
      (test "it remembers the 12 frames run" 12 (cdr (assq 'frames p)))
      (test-assert "update: took its 2 ms or more a frame" (>= (cdr (assq 'update p)) 2))
      (test-assert "drawing (with the render: hook's 1 ms or more) took 1 ms or more" (>= (cdr (assq 'render p)) 1))
      (test-assert "the engine update, with nothing to do, took less than update:"
                   (< (cdr (assq 'engine p)) (cdr (assq 'update p))))))
  (let ((g (run-game)))
    (game-run! g frames: 100)
    (test "at most the last 60 frames are kept" 60 (cdr (assq 'frames (game-frame-profile g)))))
  ;; --profile: a line every 60 frames, its means those of the frames it names
  (let* ((g (run-game update: (lambda (g dt) (run-busy 3))))
         (lines (string-split (with-output-to-string
                                (lambda () (game-run! g command-line: '("--frames" "130" "--profile"))))
                              "\n"))
         (update-ms (lambda (line) (string->number (cadr (member "update" (string-split line " ")))))))
    (test "--profile: one line after frame 59 and one after frame 119, none for the 10 frames after"
          '(("profile:" "frames" "0-59" "engine") ("profile:" "frames" "60-119" "engine"))
          (map (lambda (l) (take (string-split l " ") 4)) lines))
    ;; run-busy counts whole milliseconds: asked for 3 it spins more than 2
    (test-assert "each gives update:'s mean, 2 ms or more a frame"
                 (and (= 2 (length lines)) (>= (update-ms (car lines)) 2) (>= (update-ms (cadr lines)) 2))))
  (test "without --profile nothing is printed" ""
        (with-output-to-string (lambda () (game-run! (run-game) command-line: '("--frames" "70")))))
  (test "a game that has run no frame has a profile of zeros"
        '((engine . 0) (update . 0) (render . 0) (frames . 0) (fps . 0))
        (game-frame-profile (run-game)))
  ;; the overlay's bars: blue for update:, which takes a whole frame budget
  ;; here, so its bar spans half the view (16 of 32 px) at y 3
  (let* ((shot "/tmp/downstroke-profile-shot.png")
         (g (run-game debug?: #t frame-delay: 10 update: (lambda (g dt) (run-busy 12)))))
    (game-debug-corner-set! g 'top-left)
    (game-run! g frames: 3 screenshot: shot)
    (test "debug?: the update: bar is drawn along the top, as long as its share of the budget"
          '((60 140 255 255) (60 140 255 255))
          (list (png-pixel shot 0 3) (png-pixel shot 15 3)))
    (delete-file* shot))
  ;; by default the readout sits at the bottom right, clear of a HUD at
  ;; the top left: the bars grow leftwards from the right edge
  (let* ((shot "/tmp/downstroke-profile-corner.png")
         (g (run-game debug?: #t frame-delay: 10 update: (lambda (g dt) (run-busy 12))
                      render: (lambda (g) (let ((r (game-renderer g)))
                                            (render-draw-color-set! r 10 20 30)
                                            (render-fill-rect! r (make-rect 0 0 16 8)))))))
    (game-run! g frames: 3 screenshot: shot)
    (test "the default corner: the update: bar along the bottom right (y 24 - 9 + 3)"
          '((60 140 255 255) (60 140 255 255))
          (list (png-pixel shot 31 18) (png-pixel shot 16 18)))
    (test "the HUD at the top left is not covered" '((10 20 30 255) (10 20 30 255))
          (list (png-pixel shot 0 0) (png-pixel shot 15 3)))
    (test-error "a corner that is none is an error" (game-debug-corner-set! g 'middle))
    (delete-file* shot)))

;; The debug overlay toggled by its action (f3 by default) while the game
;; runs, with its readout of frames per second and frame time; a scale of
;; 1.5 makes a 96x72 output.
(test-group "game-run!: the overlay toggled at run time; a non-integer scale"
  (let* ((dir (create-temporary-directory))
         (log '())
         (run (lambda (frames shot)
                (let ((g (make-game headless?: #t width: 64 height: 48 scale: 1.5
                                    update: (lambda (g dt)
                                              (set! log (cons (game-debug? g) log))
                                              (case (game-frame g)
                                                ((0 3) (push-key-event! 'key-down 'f3))
                                                ((1 4) (push-key-event! 'key-up 'f3)))))))
                  (game-debug-corner-set! g 'top-left)
                  (set! log '())
                  (game-run! g frames: frames screenshot: shot)
                  (reverse log))))
         (white? (lambda (p) (equal? (take p 3) '(255 255 255)))))
    (test "f3 turns the overlay on, and again off" '(#f #t #t #t #f #f) (run 6 (string-append dir "/off.png")))
    (test "a 64x48 game at scale 1.5 is 96x72" '(96 72) (png-size (string-append dir "/off.png")))
    (test "off: no readout" 0 (png-count (string-append dir "/off.png") white?))
    (run 3 (string-append dir "/on.png"))
    ;; the first glyph is the rate, 0 in the first second: a 3x5 "0" in
    ;; window pixels from (2, 16), under the bars (9 logical rows, 13.5)
    (let ((at (lambda (x y) (white? (png-pixel (string-append dir "/on.png") x y)))))
      (test "on: the readout's first digit, a 0 (ring, hollow centre)" '(#t #t #t #t #f #f)
            (list (at 2 16) (at 4 16) (at 2 20) (at 4 20) (at 3 18) (at 1 16))))
    (test-assert "the profile has the rate" (assq 'fps (game-frame-profile (make-game))))))

(test-group "game: the pointer in world pixels, through the camera"
  (let ((g (make-game width: 64 height: 48)))
    (game-input-set! g (input-update (make-input-state) *default-input-config* '((mouse-motion 10 6))))
    (test "no scene: the screen position" '(10 6) (receive (x y) (game-mouse-world-position g) (list x y)))
    (game-scene-set! g (make-sprite-scene camera: (make-camera x: 100 y: 40)))
    (test "logical (10, 6) with the camera at (100, 40)" '(110 46)
          (receive (x y) (game-mouse-world-position g) (list x y)))
    (game-scene-set! g (make-sprite-scene camera: (make-camera x: 100 y: 40 zoom: 2)))
    (test "zoom 2: half as far from the camera's corner" '(105 43)
          (receive (x y) (game-mouse-world-position g) (list x y)))
    (test "the screen position stays" '(10 6) (receive (x y) (game-mouse-position g) (list x y)))))

;;; ------------------------------------------------------------------
;;; A game's own headless runs: the demos' command line, screenshots at
;;; several frames, traced keys, errors naming the step.

;; A game whose every drawn frame is one colour, red 10 x (frames run), so
;; a screenshot says which frame it is: frame N (from 0) is drawn red
;; 10 (N + 1).
(define (frame-coloured-game . args)
  (apply run-game render: (lambda (g)
                            (let ((r (game-renderer g)))
                              (render-draw-color-set! r (* 10 (game-frame g)) 0 0)
                              (render-fill-rect! r (make-rect 0 0 32 24))))
         args))

(define (shot-red path) (car (png-pixel path 5 5)))

(test-group "game-run!: the command line of every game"
  (let ((dir (create-temporary-directory)))
    (define (in name) (string-append dir "/" name))
    (test "--frames and --screenshot-at, twice: one run, two pictures" 5
          (game-run! (frame-coloured-game) command-line: (list "--headless" "--frames" "5"
                                                                "--screenshot-at" "1" (in "one.png")
                                                                "--screenshot-at" "3" (in "three.png"))))
    (test "frame 1 and frame 3, each as it was drawn" '(20 40)
          (list (shot-red (in "one.png")) (shot-red (in "three.png"))))
    (test "--screenshot: the last frame" 30
          (begin (game-run! (frame-coloured-game) command-line: (list "--frames" "3" "--screenshot" (in "last.png")))
                 (shot-red (in "last.png"))))
    (test "a keyword wins over the command line" 2
          (game-run! (frame-coloured-game) frames: 2 command-line: '("--frames" "5")))
    (test "the game's own arguments are left alone" 1
          (game-run! (frame-coloured-game) command-line: '("--level" "3" "--frames" "1" "extra")))
    (test "--headless without --frames runs 300 frames (it would never end)" 300
          (game-run! (run-game) command-line: '("--headless")))
    (with-output-to-file (in "script.scm") (lambda () (write '((0 right) (2 right (tap a))))))
    (let* ((held '())
           (g (run-game update: (lambda (g dt) (set! held (cons (input-held? (game-input g) 'right) held))))))
      (game-run! g command-line: (list "--frames" "3" "--script" (in "script.scm")))
      (test "--script FILE drives the input" '(#t #t #t) (reverse held)))
    (test-error "--frames without a number is an error naming it"
                (lambda (e) (substring-index "--frames" ((condition-property-accessor 'exn 'message "") e)))
                (game-run! (run-game) command-line: '("--frames" "many")))
    (test-error "--screenshot-at without its file" (game-run! (run-game) command-line: '("--screenshot-at" "2")))
    (test-error "--script of a file that is not there names it"
                (lambda (e) (substring-index "nowhere.scm" ((condition-property-accessor 'exn 'message "") e)))
                (game-run! (run-game) command-line: '("--frames" "1" "--script" "nowhere.scm")))
    (delete-directory dir #t)))

(test-group "game-run!: screenshots at frames and from a script"
  (let ((dir (create-temporary-directory)))
    (define (in name) (string-append dir "/" name))
    (game-run! (frame-coloured-game) frames: 6 command-line: #f
               screenshots: `((4 . ,(in "four.png")) (0 . ,(in "zero.png"))))
    (test "screenshots: ((frame . file) ...), in any order" '(10 50)
          (list (shot-red (in "zero.png")) (shot-red (in "four.png"))))
    (let* ((held '())
           (g (frame-coloured-game update: (lambda (g dt) (set! held (cons (input-held? (game-input g) 'right) held))))))
      (game-run! g frames: 4 command-line: #f
                 input-script: `((0 right) (2 (screenshot ,(in "script.png")))))
      (test "(screenshot FILE) in a script entry: that frame's picture" 30 (shot-red (in "script.png")))
      (test "an entry holding only the command changes nothing the input does" '(#t #t #t #t) (reverse held)))
    (game-run! (frame-coloured-game) frames: 3 command-line: #f
               input-script: `((1 right (screenshot ,(in "with-action.png")))))
    (test "beside actions, in the same entry" 20 (shot-red (in "with-action.png")))
    (test "a frame the run never drew: no file, and a warning naming it"
          '(#f #t)
          (let ((said (call-with-output-string
                       (lambda (port)
                         (parameterize ((current-error-port port))
                           (game-run! (run-game) frames: 2 command-line: #f screenshots: `((9 . ,(in "nine.png")))))))))
            (list (file-exists? (in "nine.png"))
                  (and (substring-index "frame 9 was not drawn" said) (substring-index "nine.png" said) #t))))
    (test-error "screenshots: must be (frame . file)" (game-run! (run-game) frames: 1 command-line: #f screenshots: '((-1 . "x.png"))))
    (test-error "a screenshot command needs its file"
                (game-run! (run-game) frames: 1 command-line: #f input-script: '((0 (screenshot)))))
    (delete-directory dir #t)))

(test-group "game-run!: traced keys"
  (let* ((walker (lambda () (list #:type 'player #:name "p1" #:x 0 #:vx 1 #:width 4 #:height 4)))
         (game (lambda () (run-game create: (lambda (g) (game-scene-set! g (make-sprite-scene
                                                                              entities: (list (walker) (list #:type 'coin #:x 9)))))))))
    (test "trace: ((who key ...)): a line per frame per entity traced, after the frame ran"
          '("frame 0 player \"p1\": #:x 1 #:vx 1" "frame 1 player \"p1\": #:x 2 #:vx 1" "frame 2 player \"p1\": #:x 3 #:vx 1")
          (string-split (with-output-to-string
                          (lambda () (game-run! (game) frames: 3 command-line: #f trace: '((player #:x #:vx)))))
                        "\n"))
    (test "by name, with a key an entity lacks shown as -"
          '("frame 0 player \"p1\": #:hp -")
          (string-split (with-output-to-string
                          (lambda () (game-run! (game) frames: 1 command-line: #f trace: '(("p1" #:hp)))))
                        "\n"))
    (let ((file (string-append (create-temporary-directory) "/trace.txt")))
      (game-run! (game) command-line: (list "--frames" "2" "--trace" "*:x" "--trace-file" file))
      (test "--trace *:x --trace-file FILE: every entity, into the file"
            '("frame 0 player \"p1\": #:x 1" "frame 0 coin: #:x 9" "frame 1 player \"p1\": #:x 2" "frame 1 coin: #:x 9")
            (with-input-from-file file read-lines)))
    (test-error "--trace without KEYs is an error" (game-run! (game) command-line: '("--trace" "player")))
    (test-error "trace: of a bad shape" (game-run! (game) frames: 1 command-line: #f trace: '((player x))))))

(test-group "game-run!: an error of the engine update names the frame, the step and the entity"
  (let* ((slimes (list (list #:type 'slime #:object-id 3 #:x 0 #:vx 1)
                       (list #:type 'slime #:object-id 4 #:x 10 #:vx 1)))
         (g (run-game create: (lambda (g) (game-scene-set! g (make-sprite-scene entities: slimes)))
                      update: (lambda (g dt)
                                ;; the second slime's speed becomes NaN at frame 2
                                (when (= (game-frame g) 2)
                                  (game-scene-set! g (update-scene (game-scene g)
                                                                   entities: (map (lambda (e) (if (eqv? 4 (entity-ref e #:object-id))
                                                                                                  (entity-set e #:vx (/ 0. 0.))
                                                                                                  e))
                                                                                  (scene-entities (game-scene g)))))))))
         (caught (handle-exceptions e e (game-run! g frames: 5 command-line: #f) #f)))
    (test-assert "the message: frame, step, which slime (its Tiled object), the key"
                 (let ((m ((condition-property-accessor 'exn 'message "") caught)))
                   (and (substring-index "frame 3, engine update, step velocity-x: entity slime (object 4): #:vx is +nan.0" m) #t)))
    (test "the step is the condition's (pipeline step) property" 'velocity-x
          ((condition-property-accessor 'pipeline 'step #f) caught))))
