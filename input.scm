;;; (downstroke input): actions, their configuration, and the per-frame
;;; input state with pressed / held / released edges.
;;;
;;; Actions are the symbols  up down left right a b start select quit.
;;;
;;; A configuration maps sources to actions:
;;;   keys:    alist (KEY . ACTION), KEY a key symbol of (downstroke sdl2)
;;;            (a..z, left, return, escape ...). Several keys may share an
;;;            action; the action is held while any of them is down.
;;;   buttons: alist (BUTTON . ACTION), BUTTON an SDL game-controller button
;;;            name as a symbol (a b x y back guide start left-stick
;;;            right-stick left-shoulder right-shoulder dpad-up dpad-down
;;;            dpad-left dpad-right).
;;;   axes:    list of (AXIS SIGN ACTION): AXIS an SDL game-controller axis
;;;            (left-x left-y right-x right-y trigger-left trigger-right),
;;;            SIGN + or -; the action is held while the axis value is past
;;;            the dead zone on that side.
;;;   dead-zone: axis magnitude (of SDL's -32768..32767) below which an
;;;            axis counts as centred.
;;;
;;; Events are lists: (quit), (key-down KEY REPEAT?), (key-up KEY REPEAT?),
;;; (other TYPE) as (downstroke sdl2)'s poll-event! returns them, plus the
;;; game-controller forms
;;;   (controller-button-down BUTTON) (controller-button-up BUTTON)
;;;   (controller-axis AXIS VALUE) (controller-added INDEX)
;;;   (controller-removed INSTANCE-ID)
;;; which (input-poll-events!) also reads from SDL (it is poll-events! plus
;;; controller events; the game loop uses it). (input-open-controllers!)
;;; starts SDL's game-controller subsystem, and controllers are opened as
;;; SDL reports them (controller-added); (input-close-controllers!) closes
;;; every opened one, once. push-controller-button-event! and
;;; push-controller-axis-event! queue synthetic controller events (tests).
;;;
;;; The input state is immutable. (input-update state config events) folds
;;; one frame's events into a new state; it is pure, so it runs without SDL.
;;;
;;; Edges, exactly once per frame. An action is held while one of its
;;; sources is down. Following the events of one frame in order:
;;;   input-pressed?  is #t when the action went from not held to held at
;;;                   some point in the frame (at most once, however many
;;;                   key-down and repeat events arrived);
;;;   input-released? is #t when it went from held to not held at some point;
;;;   input-held?     is its state after the last event of the frame.
;;; Key-repeat events never make an edge (the key is already down). So a
;;; key pressed and released within one frame gives pressed? #t,
;;; released? #t and held? #f: the tap is seen once and never lost. A key
;;; released and pressed again within one frame gives all three #t.
;;; A (quit) event (the window closing) sets input-quit? for that frame.
;;;
;;; Scripted input. A script is a list of (FRAME . ACTIONS) entries in
;;; increasing FRAME order; frames are numbered from 0 (the game-frame value
;;; while the frame runs). The actions of an entry are held from its frame
;;; until the next entry's frame; before the first entry nothing is held.
;;; An element (tap ACTION) of ACTIONS is pressed and released within that
;;; entry's frame only (not held). (scripted-input script) returns a
;;; procedure (frame previous-state) -> state.
;;;
;;; Recording. (input-record recording frame state) returns the recording
;;; with that frame added: an entry is added only when the held set changes
;;; or a tap (pressed and released, not held before or after) happened, and
;;; (recording->script recording) turns it into a script that scripted-input
;;; replays frame for frame: the same held sets, the same pressed / released
;;; edges. (Not reproduced: a release and re-press inside one frame, which
;;; replays as plain holding.)

(module (downstroke input)
  (input-actions *default-input-config*
   make-input-config input-config? input-config-keys input-config-buttons
   input-config-axes input-config-dead-zone
   make-input-state input-state? input-update
   input-held? input-pressed? input-released? input-quit?
   input-held-actions input-pressed-actions input-released-actions
   scripted-input script-held-at
   make-recording input-record recording->script
   input-poll-events! input-open-controllers! input-close-controllers!
   push-controller-button-event! push-controller-axis-event!
   controller-buttons controller-axes
   ;; for sibling modules only: the engine's replay of recorded input
   input-from-held)

  (import (downstroke keywords))
  (import scheme (chicken base) (chicken format) (chicken foreign)
          (only (downstroke sdl2) keycode->key key-symbols sdl-initialized? poll-events!
                controller-buttons controller-axes))

  (foreign-declare #<<EOF
#include <SDL.h>

static int downstroke_push_cbutton(int down, int button) {
  SDL_Event e;
  SDL_zero(e);
  e.type = down ? SDL_CONTROLLERBUTTONDOWN : SDL_CONTROLLERBUTTONUP;
  e.cbutton.timestamp = SDL_GetTicks();
  e.cbutton.which = 0;
  e.cbutton.button = (Uint8)button;
  e.cbutton.state = down ? SDL_PRESSED : SDL_RELEASED;
  return SDL_PushEvent(&e);
}

static int downstroke_push_caxis(int axis, int value) {
  SDL_Event e;
  SDL_zero(e);
  e.type = SDL_CONTROLLERAXISMOTION;
  e.caxis.timestamp = SDL_GetTicks();
  e.caxis.which = 0;
  e.caxis.axis = (Uint8)axis;
  e.caxis.value = (Sint16)value;
  return SDL_PushEvent(&e);
}

EOF
)

  (define input-actions '(up down left right a b start select quit))

  (define-record-type input-config
    (%make-input-config keys buttons axes dead-zone)
    input-config?
    (keys input-config-keys)
    (buttons input-config-buttons)
    (axes input-config-axes)
    (dead-zone input-config-dead-zone))

  (define default-keys
    '((up . up) (down . down) (left . left) (right . right)
      (w . up) (s . down) (a . left) (d . right)
      (j . a) (z . a) (k . b) (x . b)
      (return . start) (escape . quit)))

  ;; SDL's standard game-controller layout.
  (define default-buttons
    '((a . a) (b . b) (start . start) (back . select)
      (dpad-up . up) (dpad-down . down) (dpad-left . left) (dpad-right . right)))

  (define default-axes
    '((left-x - left) (left-x + right) (left-y - up) (left-y + down)))

  (define default-dead-zone 8000)

  (define (check-action who a)
    (unless (memq a input-actions)
      (error who (sprintf "unknown action ~s (actions: ~s)" a input-actions)))
    a)

  ;; A misspelt key, button or axis would never match: it is an error.
  (define (check-source what name known #!optional (hint (sprintf "one of ~s" known)))
    (unless (memq name known)
      (error 'make-input-config (sprintf "unknown ~a ~s: ~a" what name hint)))
    name)

  (define/keywords (make-input-config #!key (keys default-keys) (buttons default-buttons)
                             (axes default-axes) (dead-zone default-dead-zone))
    (for-each (lambda (p)
                (unless (pair? p) (error 'make-input-config "a key binding is (KEY . ACTION)" p))
                (check-source "key" (car p) (key-symbols) "(key-symbols) lists the names")
                (check-action 'make-input-config (cdr p)))
              keys)
    (for-each (lambda (p)
                (unless (pair? p) (error 'make-input-config "a button binding is (BUTTON . ACTION)" p))
                (check-source "button" (car p) controller-buttons)
                (check-action 'make-input-config (cdr p)))
              buttons)
    (for-each (lambda (ax)
                (unless (and (list? ax) (= (length ax) 3) (memq (cadr ax) '(+ -)))
                  (error 'make-input-config "an axis binding is (AXIS + | - ACTION)" ax))
                (check-source "axis" (car ax) controller-axes)
                (check-action 'make-input-config (caddr ax)))
              axes)
    (unless (and (real? dead-zone) (>= dead-zone 0))
      (error 'make-input-config "dead-zone: must be a non-negative number" dead-zone))
    (%make-input-config keys buttons axes dead-zone))

  (define *default-input-config* (make-input-config))

  ;; sources: the sources down now, as (key . K) (button . B) (axis A . SIGN).
  (define-record-type input-state
    (%make-input-state held pressed released sources quit?)
    input-state?
    (held input-held-actions)
    (pressed input-pressed-actions)
    (released input-released-actions)
    (sources input-sources)
    (quit? input-quit?))

  (define (make-input-state) (%make-input-state '() '() '() '() #f))

  (define (input-held? s action) (and (memq action (input-held-actions s)) #t))
  (define (input-pressed? s action) (and (memq action (input-pressed-actions s)) #t))
  (define (input-released? s action) (and (memq action (input-released-actions s)) #t))

  ;; Sets are lists kept in the order of input-actions, so equal? compares them.
  (define (action-set pred) (let loop ((as input-actions))
                              (cond ((null? as) '())
                                    ((pred (car as)) (cons (car as) (loop (cdr as))))
                                    (else (loop (cdr as))))))

  (define (source-action config src)
    (case (car src)
      ((key) (let ((p (assq (cdr src) (input-config-keys config)))) (and p (cdr p))))
      ((button) (let ((p (assq (cdr src) (input-config-buttons config)))) (and p (cdr p))))
      (else #f)))

  (define (held-from-sources config sources)
    (let ((acts (let loop ((ss sources))
                  (cond ((null? ss) '())
                        ((eq? (car (car ss)) 'axis)
                         (let* ((axis (cadr (car ss))) (sign (cddr (car ss))))
                           (let find ((bs (input-config-axes config)))
                             (cond ((null? bs) (loop (cdr ss)))
                                   ((and (eq? (car (car bs)) axis) (eq? (cadr (car bs)) sign))
                                    (cons (caddr (car bs)) (find (cdr bs))))
                                   (else (find (cdr bs)))))))
                        (else (let ((a (source-action config (car ss))))
                                (if a (cons a (loop (cdr ss))) (loop (cdr ss)))))))))
      (action-set (lambda (a) (memq a acts)))))

  (define (remove-source src sources)
    (cond ((null? sources) '())
          ((equal? (car sources) src) (cdr sources))
          (else (cons (car sources) (remove-source src (cdr sources))))))

  (define (add-source src sources)
    (if (member src sources) sources (cons src sources)))

  ;; Sources after one event.
  (define (apply-event config sources ev)
    (case (car ev)
      ((key-down) (add-source (cons 'key (cadr ev)) sources))
      ((key-up) (remove-source (cons 'key (cadr ev)) sources))
      ((controller-button-down) (add-source (cons 'button (cadr ev)) sources))
      ((controller-button-up) (remove-source (cons 'button (cadr ev)) sources))
      ((controller-axis)
       (let* ((axis (cadr ev)) (v (caddr ev))
              (dz (input-config-dead-zone config))
              (s (remove-source (cons 'axis (cons axis '-))
                                (remove-source (cons 'axis (cons axis '+)) sources))))
         (cond ((> v dz) (cons (cons 'axis (cons axis '+)) s))
               ((< v (- dz)) (cons (cons 'axis (cons axis '-)) s))
               (else s))))
      (else sources)))

  (define (input-update state config events)
    (let loop ((evs events)
               (sources (input-sources state))
               (held (input-held-actions state))
               (pressed '()) (released '()) (quit? #f))
      (if (null? evs)
          (%make-input-state held
                             (action-set (lambda (a) (memq a pressed)))
                             (action-set (lambda (a) (memq a released)))
                             sources quit?)
          (let* ((ev (car evs))
                 (sources2 (apply-event config sources ev))
                 (held2 (if (eq? sources2 sources) held (held-from-sources config sources2))))
            (loop (cdr evs) sources2 held2
                  (append (action-set (lambda (a) (and (memq a held2) (not (memq a held)))))
                          pressed)
                  (append (action-set (lambda (a) (and (memq a held) (not (memq a held2)))))
                          released)
                  (or quit? (eq? (car ev) 'quit)))))))

  ;; The state for a frame whose held set is `held` (and whose taps are
  ;; pressed and released within it), following `prev`. No sources: this
  ;; is how scripts drive the game.
  (define (input-from-held prev held #!optional (taps '()))
    (let ((was (input-held-actions prev)))
      (for-each (lambda (a) (check-action 'input-from-held a)) held)
      (for-each (lambda (a) (check-action 'input-from-held a)) taps)
      (let ((tap? (lambda (a) (and (memq a taps) (not (memq a was)) (not (memq a held))))))
        (%make-input-state
         (action-set (lambda (a) (memq a held)))
         (action-set (lambda (a) (or (and (memq a held) (not (memq a was))) (tap? a))))
         (action-set (lambda (a) (or (and (memq a was) (not (memq a held))) (tap? a))))
         '() #f))))

  (define (tap-element? x) (and (pair? x) (eq? (car x) 'tap) (pair? (cdr x))))

  (define (check-script script)
    (unless (list? script) (error 'scripted-input "a script is a list of (frame . actions)" script))
    (let loop ((s script) (last -1))
      (unless (null? s)
        (let ((e (car s)))
          (unless (and (pair? e) (exact-integer? (car e)) (list? (cdr e)))
            (error 'scripted-input "a script entry is (frame . actions)" e))
          (unless (> (car e) last)
            (error 'scripted-input "script frames must increase" (car e)))
          (for-each (lambda (x) (check-action 'scripted-input (if (tap-element? x) (cadr x) x)))
                    (cdr e))
          (loop (cdr s) (car e))))))

  ;; (values held taps) of `script` at `frame`.
  (define (script-held-at script frame)
    (let loop ((s script) (entry #f))
      (if (or (null? s) (> (car (car s)) frame))
          (if entry
              (let ((acts (cdr entry)))
                (values (let held ((xs acts))
                          (cond ((null? xs) '())
                                ((tap-element? (car xs)) (held (cdr xs)))
                                (else (cons (car xs) (held (cdr xs))))))
                        (if (= (car entry) frame)
                            (let taps ((xs acts))
                              (cond ((null? xs) '())
                                    ((tap-element? (car xs)) (cons (cadr (car xs)) (taps (cdr xs))))
                                    (else (taps (cdr xs)))))
                            '())))
              (values '() '()))
          (loop (cdr s) (car s)))))

  (define (scripted-input script)
    (check-script script)
    (lambda (frame prev)
      (receive (held taps) (script-held-at script frame)
        (input-from-held prev held taps))))

  ;; A recording: the script entries so far, newest first, and the held
  ;; set of the last frame recorded.
  (define (make-recording) (cons '() '()))

  (define (input-record rec frame state)
    (let* ((held (input-held-actions state))
           (taps (action-set (lambda (a) (and (input-pressed? state a)
                                              (input-released? state a)
                                              (not (memq a held))
                                              (not (memq a (cdr rec))))))))
      (if (and (equal? held (cdr rec)) (null? taps))
          rec
          (cons (cons (cons frame (append held (map (lambda (a) (list 'tap a)) taps)))
                      (car rec))
                held))))

  (define (recording->script rec) (reverse (car rec)))
  ;;; ------------------------------------------------------------------
  ;;; Reading SDL: keys, quit and game controllers.


  (define (index-of x xs who)
    (let loop ((ys xs) (i 0))
      (cond ((null? ys) (error who "unknown controller button or axis" x))
            ((eq? (car ys) x) i)
            (else (loop (cdr ys) (+ i 1))))))

  ;; Opened controllers: native pointers, closed once by input-close-controllers!.
  (define open-controllers '())

  (define (open-controller! index)
    (let ((p ((foreign-lambda c-pointer "SDL_GameControllerOpen" int) index)))
      (when p (set! open-controllers (cons p open-controllers)))))

  ;; Every pending SDL event, oldest first, as (downstroke sdl2)'s
  ;; poll-events! reads them; a controller that SDL reports as added is
  ;; opened here, so its buttons and axes reach the game.
  (define (input-poll-events!)
    (unless (sdl-initialized?) (error 'input-poll-events! "SDL is not initialized (init!)"))
    (let ((events (poll-events!)))
      (for-each (lambda (e) (when (eq? (car e) 'controller-added) (open-controller! (cadr e))))
                events)
      events))

  ;; Starts the game-controller subsystem; #f (and no error) when SDL cannot.
  (define (input-open-controllers!)
    (= 0 ((foreign-lambda int "SDL_InitSubSystem" unsigned-int)
          (foreign-value "SDL_INIT_GAMECONTROLLER" unsigned-int))))

  (define (input-close-controllers!)
    (let ((cs open-controllers))
      (set! open-controllers '())
      (when (sdl-initialized?)
        (for-each (foreign-lambda void "SDL_GameControllerClose" c-pointer) cs)))
    (void))

  ;; (push-controller-button-event! 'down 'a) or 'up.
  (define (push-controller-button-event! dir button)
    (index-of button controller-buttons 'push-controller-button-event!)
    (unless (sdl-initialized?) (error 'push-controller-button-event! "SDL is not initialized (init!)"))
    (let ((down (case dir ((down) 1) ((up) 0)
                      (else (error 'push-controller-button-event! "dir must be down or up" dir)))))
      (when (< ((foreign-lambda int "downstroke_push_cbutton" int int)
                down (index-of button controller-buttons 'push-controller-button-event!))
               1)
        (error 'push-controller-button-event! "SDL_PushEvent failed or filtered"))
      (void)))

  ;; (push-controller-axis-event! 'left-x value), value in -32768..32767.
  (define (push-controller-axis-event! axis value)
    (index-of axis controller-axes 'push-controller-axis-event!)
    (unless (sdl-initialized?) (error 'push-controller-axis-event! "SDL is not initialized (init!)"))
    (when (< ((foreign-lambda int "downstroke_push_caxis" int int)
              (index-of axis controller-axes 'push-controller-axis-event!)
              (max -32768 (min 32767 value)))
             1)
      (error 'push-controller-axis-event! "SDL_PushEvent failed or filtered"))
    (void)))
