;;; (downstroke input): action edges over synthetic event lists (pure), the
;;; configuration, scripts and recordings, and real SDL key events pushed
;;; into a short headless game-run!.

(import scheme (chicken base) (chicken string)
        (downstroke test) (downstroke input) (downstroke sdl2) (downstroke engine))

(include-relative "../../tests/bounded-support.scm")

(define in-cfg *default-input-config*)

;; The state after feeding frames of events in turn, starting empty.
(define (in-run frames)
  (let loop ((s (make-input-state)) (fs frames))
    (if (null? fs) s (loop (input-update s in-cfg (car fs)) (cdr fs)))))

(define (in-edges s action)
  (list (input-pressed? s action) (input-held? s action) (input-released? s action)))

(test-group "input: configuration"
  (test "the actions" '(up down left right a b start select quit) input-actions)
  (test "arrows and WASD" '(up down left right up down left right)
        (map (lambda (k) (cdr (assq k (input-config-keys in-cfg))))
             '(up down left right w s a d)))
  (test "j z -> a, k x -> b, return -> start, escape -> quit" '(a a b b start quit)
        (map (lambda (k) (cdr (assq k (input-config-keys in-cfg)))) '(j z k x return escape)))
  (test-assert "controller buttons are data" (assq 'dpad-left (input-config-buttons in-cfg)))
  (test-assert "a dead zone" (> (input-config-dead-zone in-cfg) 0))
  (test "a new action named by a binding joins the actions, after the declared ones"
        '(up down left right a b start select quit jump debug-overlay fullscreen)
        (input-config-actions (make-input-config keys: (cons '(space . jump) (input-config-keys in-cfg)))))
  (test "the default configuration's actions: 1.0's nine and the engine's two toggles"
        '(up down left right a b start select quit debug-overlay fullscreen)
        (input-config-actions in-cfg))
  (test "f3 and f11 toggle the overlay and fullscreen" '(debug-overlay fullscreen)
        (map (lambda (k) (cdr (assq k (input-config-keys in-cfg)))) '(f3 f11)))
  (test-error "an action that is not a symbol is refused, named with its binding"
              (lambda (exn) (substring-index "\"jump\" in the binding (space . \"jump\")" (error-text exn)))
              (make-input-config keys: '((space . "jump"))))
  (test-error "a misspelt key is refused, named"
              (lambda (exn) (substring-index "unknown key spacebar" (error-text exn)))
              (make-input-config keys: '((spacebar . a))))
  (test-error "a misspelt controller button is refused, named"
              (lambda (exn) (substring-index "unknown button turbo" (error-text exn)))
              (make-input-config buttons: '((turbo . a))))
  (test-error "a misspelt axis is refused, named"
              (lambda (exn) (substring-index "unknown axis wheel" (error-text exn)))
              (make-input-config axes: '((wheel + right))))
  (let ((c (make-input-config keys: '((space . a)))))
    (test "a custom key" '(#t #t #f)
          (in-edges (input-update (make-input-state) c '((key-down space #f))) 'a))
    (test "keys not in the config do nothing" '(#f #f #f)
          (in-edges (input-update (make-input-state) c '((key-down j #f))) 'a))))

(test-group "input: edges over event lists"
  (test "nothing happens with no events" '(#f #f #f) (in-edges (in-run '(())) 'left))
  (test "a key down: pressed and held" '(#t #t #f) (in-edges (in-run '(((key-down left #f)))) 'left))
  (test "held the next frame, not pressed again" '(#f #t #f)
        (in-edges (in-run '(((key-down left #f)) ())) 'left))
  (test "key repeat never re-presses" '(#f #t #f)
        (in-edges (in-run '(((key-down left #f)) ((key-down left #t) (key-down left #t)))) 'left))
  (test "down and repeats in one frame: pressed once" '(left)
        (input-pressed-actions (in-run '(((key-down left #f) (key-down left #t) (key-down left #t))))))
  (test "key up: released, not held" '(#f #f #t)
        (in-edges (in-run '(((key-down left #f)) ((key-up left #f)))) 'left))
  (test "released only that frame" '(#f #f #f)
        (in-edges (in-run '(((key-down left #f)) ((key-up left #f)) ())) 'left))
  (test "down and up within one frame: pressed and released, not held" '(#t #f #t)
        (in-edges (in-run '(((key-down j #f) (key-up j #f)))) 'a))
  (test "up and down again within one frame: all three" '(#t #t #t)
        (in-edges (in-run '(((key-down j #f)) ((key-up j #f) (key-down j #f)))) 'a))
  (test "two keys of one action: releasing one keeps it held" '(#f #t #f)
        (in-edges (in-run '(((key-down left #f) (key-down a #f)) ((key-up a #f)))) 'left))
  (test "... and releasing the other releases it" '(#f #f #t)
        (in-edges (in-run '(((key-down left #f) (key-down a #f)) ((key-up a #f)) ((key-up left #f))))
                  'left))
  (test "pressing a second key of a held action is no edge" '(#f #t #f)
        (in-edges (in-run '(((key-down left #f)) ((key-down a #f)))) 'left))
  (test "a key up with nothing down is nothing" '(#f #f #f)
        (in-edges (in-run '(((key-up left #f)))) 'left))
  (test "several actions at once" '(up right a)
        (input-held-actions (in-run '(((key-down j #f) (key-down d #f) (key-down up #f))))))
  (test-assert "the (quit) event" (input-quit? (in-run '(((other 512) (quit))))))
  (test-assert "quit is for that frame only" (not (input-quit? (in-run '(((quit)) ())))))
  (test "escape is the quit action" '(#t #t #f) (in-edges (in-run '(((key-down escape #f)))) 'quit))
  (test "other events are ignored" '() (input-held-actions (in-run '(((other 1024) (key-up unknown #f))))))
  (let* ((s0 (make-input-state))
         (s1 (input-update s0 in-cfg '((key-down left #f)))))
    (test "the old state is unchanged (immutable)" '(#f #f #f) (in-edges s0 'left))
    (test-assert "the new state" (input-held? s1 'left))))

(test-group "input: controller events (data forms)"
  (test "a button" '(#t #t #f)
        (in-edges (in-run '(((controller-button-down dpad-left)))) 'left))
  (test "a button up" '(#f #f #t)
        (in-edges (in-run '(((controller-button-down a)) ((controller-button-up a)))) 'a))
  (test "an axis inside the dead zone is centred" '()
        (input-held-actions (in-run '(((controller-axis left-x 5000))))))
  (test "an axis past the dead zone" '(#t #t #f)
        (in-edges (in-run '(((controller-axis left-x 20000)))) 'right))
  (test "an axis moved across: released one side, pressed the other" '((#f #f #t) (#t #t #f))
        (let ((s (in-run '(((controller-axis left-x 20000)) ((controller-axis left-x -20000))))))
          (list (in-edges s 'right) (in-edges s 'left))))
  (test "back to centre" '(#f #f #t)
        (in-edges (in-run '(((controller-axis left-y -30000)) ((controller-axis left-y 100)))) 'up)))

(test-group "input: scripts and recordings"
  (let* ((script '((2 right) (4 right a) (6) (8 (tap b))))
         (proc (scripted-input script))
         (states (let loop ((f 0) (s (make-input-state)) (out '()))
                   (if (= f 10)
                       (reverse out)
                       (let ((n (proc f s))) (loop (+ f 1) n (cons n out)))))))
    (test "held per frame" '(() () (right) (right) (right a) (right a) () () () ())
          (map input-held-actions states))
    (test "pressed per frame" '(() () (right) () (a) () () () (b) ())
          (map input-pressed-actions states))
    (test "released per frame" '(() () () () () () (right a) () (b) ())
          (map input-released-actions states))
    (let ((rec (let loop ((f 0) (ss states) (r (make-recording)))
                 (if (null? ss) r (loop (+ f 1) (cdr ss) (input-record r f (car ss)))))))
      (test "a recording of a scripted run is the script" script (recording->script rec))))
  (test-error "frames must increase" (scripted-input '((3 left) (1 right))))
  (test-error "an unknown action in a script" (scripted-input '((0 jump))))
  ;; a recording of event-driven states replays to the same edges
  (let* ((frames '(((key-down left #f)) ((key-down left #t)) ((key-down j #f) (key-up j #f))
                   () ((key-up left #f) (key-down x #f)) ((key-up x #f)) ()))
         (live (let loop ((s (make-input-state)) (fs frames) (out '()))
                 (if (null? fs) (reverse out)
                     (let ((n (input-update s in-cfg (car fs)))) (loop n (cdr fs) (cons n out))))))
         (rec (let loop ((f 0) (ss live) (r (make-recording)))
                (if (null? ss) r (loop (+ f 1) (cdr ss) (input-record r f (car ss))))))
         (proc (scripted-input (recording->script rec)))
         (replay (let loop ((f 0) (s (make-input-state)) (out '()))
                   (if (= f (length frames)) (reverse out)
                       (let ((n (proc f s))) (loop (+ f 1) n (cons n out))))))
         (edges (lambda (ss) (map (lambda (s) (list (input-held-actions s) (input-pressed-actions s)
                                                    (input-released-actions s)))
                                  ss))))
    (test "a recording replays the same edges frame by frame" (edges live) (edges replay))))

;; scripted-input keeps its place in the script; the states it gives are
;; those of the readable definitions, which look each frame up from the
;; script's start, whatever order the frames are asked in.
(test-group "input: a script's place is kept, with the same states"
  (define seed 99)
  (define (rnd n) (set! seed (modulo (+ (* 1103515245 seed) 12345) 2147483648)) (modulo (quotient seed 16) n))
  (define (pick . xs) (list-ref xs (rnd (length xs))))
  (define (some-script)
    (let loop ((f (rnd 3)) (k (rnd 12)) (out '()))
      (if (= k 0) (reverse out)
          (loop (+ f 1 (rnd 4)) (- k 1)
                (cons (cons f (append (if (< (rnd 3) 2) (list (pick 'left 'right 'a)) '())
                                      (if (< (rnd 3) 1) (list (list 'tap (pick 'a 'b 'left))) '())
                                      (if (< (rnd 4) 1) (list (list 'mouse (rnd 300) (rnd 200))) '())))
                      out)))))
  ;; mostly forward, as a game runs; sometimes a skip, a repeat or a step back
  (define (some-frames)
    (let loop ((f 0) (k 40) (out '()))
      (if (= k 0) (reverse out)
          (let ((next (case (rnd 10) ((0) (max 0 (- f (rnd 20)))) ((1) f) ((2) (+ f (rnd 15))) (else (+ f 1)))))
            (loop next (- k 1) (cons f out))))))
  (define (state-of s) (list (input-held-actions s) (input-pressed-actions s) (input-released-actions s)
                             (input-mouse-x s) (input-mouse-y s)))
  (let loop ((k 0) (differ 0) (backwards 0))
    (if (= k 500)
        (begin (test-assert (sprintf "~a of 500 runs stepped back" backwards) (> backwards 300))
               (test "every state is the same" 0 differ))
        (let* ((script (some-script)) (frames (some-frames))
               (proc (scripted-input script))
               (same? (let run ((fs frames) (a (make-input-state)) (b (make-input-state)))
                        (or (null? fs)
                            (let* ((f (car fs))
                                   (a (proc f a))
                                   (b (receive (held taps) (script-held-at script f)
                                        (input-from-held b held taps (script-mouse-at script f)))))
                              (and (equal? (state-of a) (state-of b)) (run (cdr fs) a b)))))))
          (loop (+ k 1) (if same? differ (+ differ 1))
                (if (let back ((fs frames)) (and (pair? fs) (pair? (cdr fs)) (or (< (cadr fs) (car fs)) (back (cdr fs)))))
                    (+ backwards 1) backwards))))))

;; Replaying costs one step along the script in all: a script of 60,000
;; entries over 120,000 frames, within a limit of 20 s of CPU time
;; (looking each frame up from the start took about four minutes).
(test-group "input: the cost of a long replay"
  (define e 60000)
  (define results
    (bounded-run
     20
     `((import scheme (chicken base) (downstroke input))
       ;; entry k at frame 2k: left or right in turn, a tap of a every
       ;; third, the pointer at (k, 2k) every fifth
       (define script (let loop ((k (- ,e 1)) (out '()))
                        (if (< k 0) out
                            (loop (- k 1)
                                  (cons (cons (* 2 k) (append (list (if (even? k) 'left 'right))
                                                              (if (= 0 (modulo k 3)) '((tap a)) '())
                                                              (if (= 0 (modulo k 5)) (list (list 'mouse k (* 2 k))) '())))
                                        out)))))
       (define proc (scripted-input script))
       (let loop ((f 0) (s (make-input-state)) (left 0) (a 0))
         (if (= f ,(* 2 e))
             (begin (write (list "left held, a pressed, pointer" (list left a (input-mouse-x s) (input-mouse-y s))))
                    (newline))
             (let ((n (proc f s)))
               (loop (+ f 1) n (if (input-held? n 'left) (+ left 1) left) (if (input-pressed? n 'a) (+ a 1) a))))))))
  ;; left is held in the two frames of each even entry; a is pressed once
  ;; for each entry k divisible by 3; the last pointer entry is the last k
  ;; divisible by 5
  (test "the replay's states" (list (* 2 (quotient (+ e 1) 2)) (quotient (+ e 2) 3)
                                    (* 5 (quotient (- e 1) 5)) (* 10 (quotient (- e 1) 5)))
        (bounded-result results "left held, a pressed, pointer")))

;; Real SDL key events, pushed from the update hook and seen by the next
;; frame's input state.
(test-group "input: pushed SDL key events through game-run!"
  (let* ((log '())
         (pushes `((0 (key-down left) (key-down-repeat left))
                   (1 (key-down-repeat left))
                   (2 (key-up left))
                   (3 (key-down j) (key-up j))
                   (5 (key-down escape))))
         (g (make-game
             headless?: #t width: 32 height: 24
             update: (lambda (g dt)
                       (let ((in (game-input g)))
                         (set! log (cons (list (game-frame g)
                                               (input-pressed? in 'left) (input-held? in 'left)
                                               (input-released? in 'left)
                                               (input-pressed? in 'a) (input-held? in 'a)
                                               (input-released? in 'a))
                                         log)))
                       (let ((p (assv (game-frame g) pushes)))
                         (when p
                           (for-each (lambda (ev)
                                       (case (car ev)
                                         ((key-down-repeat) (push-key-event! 'key-down (cadr ev) repeat?: #t))
                                         (else (push-key-event! (car ev) (cadr ev)))))
                                     (cdr p)))))))
         (ran (game-run! g frames: 20)))
    (test "frame 0: nothing" '(0 #f #f #f #f #f #f) (list-ref (reverse log) 0))
    (test "frame 1: left pressed and held (the repeat adds nothing)" '(1 #t #t #f #f #f #f)
          (list-ref (reverse log) 1))
    (test "frame 2: a repeat event: held, no edge" '(2 #f #t #f #f #f #f) (list-ref (reverse log) 2))
    (test "frame 3: released" '(3 #f #f #t #f #f #f) (list-ref (reverse log) 3))
    (test "frame 4: j down and up in one frame: a pressed and released, not held"
          '(4 #f #f #f #t #f #t) (list-ref (reverse log) 4))
    (test "frame 5: all quiet again" '(5 #f #f #f #f #f #f) (list-ref (reverse log) 5))
    (test "escape (quit) pushed in frame 5 ends the run before frame 6's update" 6 ran)
    (test "game-frame" 6 (game-frame g))))

(test-group "input: pushed SDL controller events through game-run!"
  (let* ((log '())
         (pushes `((0 ,(lambda () (push-controller-button-event! 'down 'dpad-right)))
                   (1 ,(lambda () (push-controller-button-event! 'up 'dpad-right)
                              (push-controller-axis-event! 'left-y 3000)))
                   (2 ,(lambda () (push-controller-axis-event! 'left-y -25000)))
                   (3 ,(lambda () (push-controller-axis-event! 'left-y 0)
                              (push-controller-button-event! 'down 'a)
                              (push-controller-button-event! 'up 'a)))))
         (g (make-game
             headless?: #t width: 32 height: 24
             update: (lambda (g dt)
                       (let ((in (game-input g)))
                         (set! log (cons (list (input-pressed-actions in) (input-held-actions in)
                                               (input-released-actions in))
                                         log)))
                       (let ((p (assv (game-frame g) pushes)))
                         (when p ((cadr p))))))))
    (game-run! g frames: 6)
    (test "per frame (pressed held released): button, dead zone, axis, tap"
          '((() () ())
            ((right) (right) ())
            (() () (right))
            ((up) (up) ())
            ((a) () (up a))
            (() () ()))
          (reverse log)))
  (test-error "an unknown button is named"
              (lambda (exn) (substring-index "turbo" (error-text exn)))
              (push-controller-button-event! 'down 'turbo))
  (test-error "an unknown axis is named"
              (lambda (exn) (substring-index "wheel" (error-text exn)))
              (push-controller-axis-event! 'wheel 0)))

;;; Actions a game names, mouse, axes with thresholds, rebinding.

(define my-cfg
  (make-input-config actions: '(jump fire pause)
                     keys: '((space . jump) (lctrl . fire) (p . pause) (escape . quit))
                     buttons: '((a . jump) (x . fire))
                     mouse: '((left . fire) (right . jump))
                     axes: '((trigger-right + fire 20000) (left-x - walk-left) (left-x + walk-right))))

(define (my-run frames #!optional (cfg my-cfg))
  (let loop ((s (make-input-state cfg)) (fs frames))
    (if (null? fs) s (loop (input-update s cfg (car fs)) (cdr fs)))))

(test-group "input: actions a game names"
  (test "the actions: declared, then those the bindings add" '(jump fire pause quit walk-left walk-right)
        (input-config-actions my-cfg))
  (test "a key holds a named action" '(#t #t #f) (in-edges (my-run '(((key-down space #f)))) 'jump))
  (test "a controller button and a key share one" '(#f #t #f)
        (in-edges (my-run '(((key-down space #f)) ((controller-button-down a)) ((key-up space #f)))) 'jump))
  (test-error "asking for an action the configuration lacks is an error naming it and the actions"
              (lambda (exn) (and (substring-index "unknown action left" (error-text exn))
                                 (substring-index "(jump fire pause quit walk-left walk-right)" (error-text exn))))
              (input-held? (my-run '(())) 'left))
  (test-error "... for input-pressed? too" (lambda (exn) (substring-index "unknown action jmup" (error-text exn)))
              (input-pressed? (my-run '(())) 'jmup))
  (test-error "... and input-released?" (lambda (exn) (substring-index "unknown action jmup" (error-text exn)))
              (input-released? (my-run '(())) 'jmup))
  (test-error "the default configuration names its eleven actions"
              (lambda (exn) (substring-index "(up down left right a b start select quit debug-overlay fullscreen)"
                                             (error-text exn)))
              (input-held? (make-input-state) 'jump))
  (test "input-action? asks without an error" '(#t #f) (list (input-action? (make-input-state my-cfg) 'fire)
                                                            (input-action? (make-input-state my-cfg) 'left)))
  (test-error "an unknown key name in a configuration is named"
              (lambda (exn) (substring-index "unknown key spce" (error-text exn)))
              (make-input-config keys: '((space . jump) (spce . fire))))
  (test-error "an unknown mouse button is named"
              (lambda (exn) (substring-index "unknown mouse wheel" (error-text exn)))
              (make-input-config mouse: '((wheel . fire))))
  (test-error "a bad axis threshold is refused, naming the binding"
              (lambda (exn) (substring-index "(left-x + right 40000)" (error-text exn)))
              (make-input-config axes: '((left-x + right 40000)))))

(test-group "input: mouse"
  (let ((s (my-run '(((mouse-motion 10 20))
                     ((mouse-button-down left 30 40))
                     ((mouse-motion 31 41) (mouse-button-up left 32 42) (mouse-button-down right 33 43))))))
    (test "the last position of the frame, in logical pixels" '(33 43)
          (receive (x y) (input-mouse-position s) (list x y)))
    (test "the left button (fire) released, the right (jump) pressed" '((#f #f #t) (#t #t #f))
          (list (in-edges s 'fire) (in-edges s 'jump))))
  (test "the pointer starts at (0, 0)" '(0 0)
        (list (input-mouse-x (make-input-state)) (input-mouse-y (make-input-state))))
  (test "motion alone is no edge" '(() ())
        (let ((s (my-run '(((mouse-motion 5 5)) ((mouse-motion 6 6))))))
          (list (input-pressed-actions s) (input-held-actions s)))))

(test-group "input: axes with a threshold"
  (test "a trigger below its own threshold holds nothing" '()
        (input-held-actions (my-run '(((controller-axis trigger-right 15000))))))
  (test "past it, fire" '(fire) (input-held-actions (my-run '(((controller-axis trigger-right 25000))))))
  (test "a binding without a threshold uses the dead zone (8000)" '(() (walk-left))
        (list (input-held-actions (my-run '(((controller-axis left-x -7000)))))
              (input-held-actions (my-run '(((controller-axis left-x -9000))))))))

(test-group "input: waiting for the next source (rebinding)"
  (test "the sources pressed in a frame, oldest first, in binding form"
        '((key q) (mouse middle) (button y) (axis right-y -))
        (input-pressed-sources
         (input-update (make-input-state) in-cfg
                       '((key-down q #f) (key-down q #t) (mouse-button-down middle 1 1)
                         (controller-button-down y) (controller-axis right-y -20000)))))
  (test "unknown buttons SDL could not name are not sources" '()
        (input-pressed-sources (input-update (make-input-state) in-cfg
                                             '((mouse-button-down unknown 1 1) (controller-button-down unknown)))))
  (test "a key already down, an unknown key and a small axis move are not new" '()
        (let ((s (input-update (make-input-state) in-cfg '((key-down q #f)))))
          (input-pressed-sources (input-update s in-cfg '((key-down q #t) (key-down unknown #f)
                                                            (controller-axis left-x 3000))))))
  (let* ((c (input-config-bind my-cfg 'jump '(key w)))
         (c2 (input-config-bind my-cfg 'jump '(key w) replace?: #f))
         (c3 (input-config-bind my-cfg 'dash '(key lctrl))))
    (test "bind: the new key holds the action, its old keys do not" '((w . jump) #f)
          (list (assq 'w (input-config-keys c)) (assq 'space (input-config-keys c))))
    (test "bind: other kinds of source keep the action" '(a . jump) (assq 'a (input-config-buttons c)))
    (test "bind with replace?: #f keeps the old keys" '((space . jump) (w . jump))
          (list (assq 'space (input-config-keys c2)) (assq 'w (input-config-keys c2))))
    (test "bind: a key taken from another action leaves it; a new action joins" '((lctrl . dash) dash)
          (list (assq 'lctrl (input-config-keys c3)) (car (reverse (input-config-actions c3)))))
    (test "bind an axis side" '(right-y + fire)
          (car (reverse (input-config-axes (input-config-bind my-cfg 'fire '(axis right-y +)))))))
  (test-error "bind: an unknown source is named"
              (lambda (exn) (substring-index "(key spacebar)" (error-text exn)))
              (input-config-bind my-cfg 'jump '(key spacebar)))
  (test "a configuration as data makes the same configuration"
        (input-config->list my-cfg)
        (input-config->list (apply make-input-config (input-config->list my-cfg))))
  (let* ((s (input-update (make-input-state in-cfg) in-cfg '((key-down space #f))))
         (c (input-config-bind in-cfg 'a '(key space)))
         (s2 (input-update s c '())))
    (test "a configuration replaced while a key is down: held at once, with no edge" '(#f #t #f)
          (in-edges s2 'a))))

(test-group "input: scripts and recordings with named actions and the mouse"
  (let* ((frames '(((key-down space #f) (mouse-motion 4 5)) ()
                   ((mouse-motion 7 8) (mouse-button-down left 7 8))
                   ((mouse-button-up left 7 8) (key-up space #f)) ((mouse-motion 1 2))))
         (live (let loop ((s (make-input-state my-cfg)) (fs frames) (out '()))
                 (if (null? fs) (reverse out)
                     (let ((n (input-update s my-cfg (car fs)))) (loop n (cdr fs) (cons n out))))))
         (rec (let loop ((f 0) (ss live) (r (make-recording)))
                (if (null? ss) r (loop (+ f 1) (cdr ss) (input-record r f (car ss))))))
         (script (recording->script rec))
         (proc (scripted-input script my-cfg))
         (replay (let loop ((f 0) (s (make-input-state my-cfg)) (out '()))
                   (if (= f (length frames)) (reverse out)
                       (let ((n (proc f s))) (loop (+ f 1) n (cons n out))))))
         (view (lambda (ss) (map (lambda (s) (list (input-held-actions s) (input-pressed-actions s)
                                                   (input-released-actions s)
                                                   (input-mouse-x s) (input-mouse-y s)))
                                 ss))))
    (test "the recording" '((0 jump (mouse 4 5)) (2 jump fire (mouse 7 8)) (3) (4 (mouse 1 2))) script)
    (test "replayed: the same actions and pointer frame by frame" (view live) (view replay)))
  (test-error "a script's unknown action is named, with the configuration's actions"
              (lambda (exn) (substring-index "unknown action left" (error-text exn)))
              (scripted-input '((0 left)) my-cfg)))

;; Real SDL mouse events (headless: their coordinates are logical pixels)
;; and a configuration replaced mid-run, through game-run!.
(test-group "input: mouse events and rebinding through game-run!"
  (let* ((log '())
         (g (make-game
             headless?: #t width: 32 height: 24 input-config: my-cfg
             update: (lambda (g dt)
                       (let ((in (game-input g)) (f (game-frame g)))
                         (set! log (cons (list f (input-mouse-x in) (input-mouse-y in)
                                               (input-held-actions in) (input-pressed-sources in))
                                         log))
                         (case f
                           ((0) (push-mouse-motion-event! 10 12))
                           ((1) (push-mouse-button-event! 'down 'left 11 13))
                           ((2) (push-mouse-button-event! 'up 'left 11 13) (push-key-event! 'key-down 'q))
                           ;; a rebinding screen: the key pressed becomes fire's
                           ((3) (let ((src (input-pressed-sources in)))
                                  (game-input-config-set! g (input-config-bind (game-input-config g) 'fire (car src)))))
                           ((4) (push-key-event! 'key-up 'q))
                           ((5) (push-key-event! 'key-down 'q))))))))
    (game-run! g frames: 7)
    (test "per frame: pointer, held actions, sources pressed"
          '((0 0 0 () ()) (1 10 12 () ()) (2 11 13 (fire) ((mouse left))) (3 11 13 () ((key q)))
            (4 11 13 (fire) ()) (5 11 13 () ()) (6 11 13 (fire) ((key q))))
          (reverse log)))
  (test-error "an unknown mouse button is named"
              (lambda (exn) (substring-index "wheel" (error-text exn)))
              (push-mouse-button-event! 'down 'wheel 0 0))
  (test-error "game-input-config-set! refuses what is not a configuration"
              (lambda (exn) (substring-index "not an input configuration" (error-text exn)))
              (game-input-config-set! (make-game) '((space . a)))))

;; A run played with pushed key and mouse events, recorded, and replayed:
;; the same named actions and pointer, frame by frame.
(test-group "input: record and replay through game-run! with named actions and the mouse"
  (define (run player . args)
    (let* ((log '())
           (g (make-game headless?: #t width: 32 height: 24 input-config: my-cfg
                         update: (lambda (g dt)
                                   (let ((in (game-input g)))
                                     (receive (x y) (game-mouse-position g)
                                       (set! log (cons (list (game-frame g) x y (input-held-actions in)
                                                             (input-pressed-actions in))
                                                       log))))
                                   (player (game-frame g)))))
           (result (apply game-run! g frames: 12 args)))
      (values (reverse log) result)))
  (define (player f)
    (case f
      ((0) (push-mouse-motion-event! 3 4))
      ((1) (push-mouse-button-event! 'down 'left 5 6) (push-key-event! 'key-down 'space))
      ((2) (push-mouse-button-event! 'up 'left 7 8))
      ((4) (push-key-event! 'key-up 'space) (push-key-event! 'key-down 'p) (push-key-event! 'key-up 'p))
      ((6) (push-mouse-motion-event! 20 1))
      ((8) (push-key-event! 'key-down 'escape))))
  (receive (live recording) (run player record: #t)
    (receive (replayed frames) (run (lambda (f) (void)) input-script: recording)
      (test "the live run quit at frame 9" 9 (length live))
      (test "the recording" '((1 (mouse 3 4)) (2 jump fire (mouse 5 6)) (3 jump (mouse 7 8)) (5 (tap pause))
                              (7 (mouse 20 1)) (9 quit))
            recording)
      (test "the replay: the same frames, actions and pointer" live replayed)
      (test "and it stops where the live run did" 9 frames))))

;; A binding adds its action, so a misspelt one would make a key do nothing
;; with no word said.
(test-group "make-input-config: a key bound to a misspelt action is said"
  (import (chicken port))
  (define (said thunk)
    (call-with-output-string (lambda (port) (parameterize ((current-error-port port)) (thunk)))))
  (test "jmup for jump: a warning naming the key, the action and the fix"
        "downstroke: warning: make-input-config: z is bound to the action jmup, which actions: does not declare; did you mean jump? (declare jmup in actions: if it is meant)\n"
        (said (lambda () (make-input-config actions: '(left right jump) keys: '((left . left) (z . jmup))))))
  (test "a swap of two letters too (lfet)"
        #t (and (substring-index "did you mean left?" (said (lambda () (make-input-config actions: '(left right) keys: '((a . lfet)))))) #t))
  (test "an action of its own, far from every declared one, is said nothing of" ""
        (said (lambda () (make-input-config actions: '(left right) keys: '((x . fire))))))
  (test "a declared action is said nothing of" ""
        (said (lambda () (make-input-config actions: '(jump) keys: '((z . jump))))))
  (test "the misspelt action still exists (the warning changes nothing else)"
        #t (and (memq 'jmup (input-config-actions
                            (parameterize ((current-error-port (open-output-string)))
                              (make-input-config actions: '(jump) keys: '((z . jmup))))))
                #t)))
