;;; (downstroke input): actions, their configuration, and the per-frame
;;; input state with pressed / held / released edges and the pointer.
;;;
;;; Actions are any symbols a configuration names. input-actions are
;;; Downstroke 1.0's nine (up down left right a b start select quit), the
;;; default for actions:; the default configuration also binds the
;;; engine's debug-overlay (f3) and fullscreen (f11).
;;;
;;; A configuration maps sources to actions:
;;;   actions: the actions declared; the configuration's actions are these
;;;            and then each other action a binding names, once, in order.
;;;   keys:    alist (KEY . ACTION), KEY a key symbol of (downstroke sdl2)
;;;            (a..z, left, return, escape ...). Several keys may share an
;;;            action; the action is held while any of them is down.
;;;   buttons: alist (BUTTON . ACTION), BUTTON an SDL game-controller button
;;;            name as a symbol (a b x y back guide start left-stick
;;;            right-stick left-shoulder right-shoulder dpad-up dpad-down
;;;            dpad-left dpad-right).
;;;   mouse:   alist (BUTTON . ACTION), BUTTON one of mouse-buttons.
;;;   axes:    list of (AXIS SIGN ACTION [THRESHOLD]): AXIS an SDL
;;;            game-controller axis (left-x left-y right-x right-y
;;;            trigger-left trigger-right), SIGN + or -; the action is held
;;;            while the axis value is past the threshold (default: the
;;;            dead zone) on that side.
;;;   dead-zone: axis magnitude (of SDL's -32768..32767) below which an
;;;            axis counts as centred.
;;; A name it does not know, or an action that is not a symbol, is an error
;;; naming it. Asking a state about an action its configuration lacks
;;; (input-held? / input-pressed? / input-released?) is an error naming the
;;; action and the configuration's actions.
;;;
;;; Rebinding: input-pressed-sources lists the sources that went down in a
;;; frame as (key K) (button B) (mouse M) (axis A SIGN); input-config-bind
;;; makes a configuration with one of them bound; input-config->list is a
;;; configuration as make-input-config's arguments (data, to save). A state
;;; updated under another configuration than its own takes the held set
;;; the new bindings give, with no edge.
;;;
;;; Events are lists: (quit), (key-down KEY REPEAT?), (key-up KEY REPEAT?),
;;; (other TYPE) as (downstroke sdl2)'s poll-event! returns them, plus the
;;; game-controller forms
;;;   (controller-button-down BUTTON) (controller-button-up BUTTON)
;;;   (controller-axis AXIS VALUE) (controller-added INDEX)
;;;   (controller-removed INSTANCE-ID)
;;; and the mouse forms (mouse-motion X Y), (mouse-button-down BUTTON X Y),
;;; (mouse-button-up BUTTON X Y), X and Y in logical pixels,
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
;;; entry's frame only (not held); (mouse X Y) puts the pointer there from
;;; that frame on. (scripted-input script [config]) checks the actions
;;; against the configuration (default *default-input-config*) and returns a
;;; procedure (frame previous-state) -> state.
;;;
;;; Recording. (input-record recording frame state) returns the recording
;;; with that frame added: an entry is added only when the held set changes,
;;; the pointer moved or a tap (pressed and released, not held before or
;;; after) happened, and
;;; (recording->script recording) turns it into a script that scripted-input
;;; replays frame for frame: the same held sets, the same pressed / released
;;; edges. (Not reproduced: a release and re-press inside one frame, which
;;; replays as plain holding.)

(module (downstroke input)
  (input-actions *default-input-config* mouse-buttons
   make-input-config input-config? input-config-actions input-config-keys input-config-buttons
   input-config-mouse input-config-axes input-config-dead-zone
   input-config->list input-config-bind
   make-input-state input-state? input-update input-state-config input-state-actions
   input-action? input-held? input-pressed? input-released? input-quit?
   input-held-actions input-pressed-actions input-released-actions
   input-mouse-x input-mouse-y input-mouse-position input-pressed-sources
   scripted-input script-held-at script-mouse-at
   make-recording input-record recording->script
   input-poll-events! input-open-controllers! input-close-controllers!
   push-controller-button-event! push-controller-axis-event!
   push-mouse-motion-event! push-mouse-button-event!
   controller-buttons controller-axes
   ;; for sibling modules only: the engine's replay of recorded input
   input-from-held)

  (import (downstroke keywords))
  (import scheme (chicken base) (chicken format) (chicken foreign) (chicken port)
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

/* The window a pushed mouse event belongs to: the one with the mouse
   focus, else the first that exists (SDL numbers windows from 1), so
   that SDL's renderer maps its position to logical pixels as it does for
   a real pointer; 0 with no window (headless). */
static Uint32 downstroke_mouse_window(void) {
  SDL_Window *w = SDL_GetMouseFocus();
  Uint32 id;
  if (w) return SDL_GetWindowID(w);
  for (id = 1; id < 256; id++) if (SDL_GetWindowFromID(id)) return id;
  return 0;
}

static int downstroke_push_mmotion(int x, int y) {
  SDL_Event e;
  SDL_zero(e);
  e.type = SDL_MOUSEMOTION;
  e.motion.timestamp = SDL_GetTicks();
  e.motion.windowID = downstroke_mouse_window();
  e.motion.x = x;
  e.motion.y = y;
  return SDL_PushEvent(&e);
}

static int downstroke_push_mbutton(int down, int button, int x, int y) {
  SDL_Event e;
  SDL_zero(e);
  e.type = down ? SDL_MOUSEBUTTONDOWN : SDL_MOUSEBUTTONUP;
  e.button.timestamp = SDL_GetTicks();
  e.button.windowID = downstroke_mouse_window();
  e.button.button = (Uint8)button;
  e.button.state = down ? SDL_PRESSED : SDL_RELEASED;
  e.button.clicks = 1;
  e.button.x = x;
  e.button.y = y;
  return SDL_PushEvent(&e);
}

EOF
)

  ;; Downstroke 1.0's actions: the default configuration has these, plus
  ;; the engine's two toggles (debug-overlay on f3, fullscreen on f11).
  (define input-actions '(up down left right a b start select quit))

  ;; SDL's mouse buttons, in its numbering (SDL_BUTTON_LEFT is 1).
  (define mouse-buttons '(left middle right x1 x2))

  (define-record-type input-config
    (%make-input-config actions keys buttons mouse axes dead-zone)
    input-config?
    (actions input-config-actions)
    (keys input-config-keys)
    (buttons input-config-buttons)
    (mouse input-config-mouse)
    (axes input-config-axes)
    (dead-zone input-config-dead-zone))

  (define default-keys
    '((up . up) (down . down) (left . left) (right . right)
      (w . up) (s . down) (a . left) (d . right)
      (j . a) (z . a) (k . b) (x . b)
      (return . start) (escape . quit)
      (f3 . debug-overlay) (f11 . fullscreen)))

  ;; SDL's standard game-controller layout.
  (define default-buttons
    '((a . a) (b . b) (start . start) (back . select)
      (dpad-up . up) (dpad-down . down) (dpad-left . left) (dpad-right . right)))

  (define default-axes
    '((left-x - left) (left-x + right) (left-y - up) (left-y + down)))

  (define default-dead-zone 8000)

  ;; Actions are any symbols; a binding naming something else is refused.
  (define (check-action-name a binding)
    (unless (symbol? a)
      (error 'make-input-config (sprintf "an action is a symbol, got ~s in the binding ~s" a binding)))
    a)

  ;; A misspelt key, button or axis would never match: it is an error.
  (define (check-source what name known #!optional (hint (sprintf "one of ~s" known)))
    (unless (memq name known)
      (error 'make-input-config (sprintf "unknown ~a ~s: ~a" what name hint)))
    name)

  (define (check-pairs what alist known hint)
    (unless (list? alist) (error 'make-input-config (sprintf "~a: must be a list of (~a . ACTION)" what what) alist))
    (for-each (lambda (p)
                (unless (pair? p)
                  (error 'make-input-config (sprintf "a ~a binding is (~a . ACTION), got ~s" what
                                                     (string-upcase what) p)))
                (check-source what (car p) known hint)
                (check-action-name (cdr p) p))
              alist))

  (define (string-upcase s) (list->string (map char-upcase (string->list s))))

  ;; The actions: those declared, then those the bindings add, each once.
  (define (config-actions declared keys buttons mouse axes)
    (let loop ((new (append (map cdr keys) (map cdr buttons) (map cdr mouse) (map caddr axes)))
               (acc (reverse declared)))
      (cond ((null? new) (reverse acc))
            ((memq (car new) acc) (loop (cdr new) acc))
            (else (loop (cdr new) (cons (car new) acc))))))

  (define (dedupe xs)
    (let loop ((xs xs) (acc '()))
      (cond ((null? xs) (reverse acc))
            ((memq (car xs) acc) (loop (cdr xs) acc))
            (else (loop (cdr xs) (cons (car xs) acc))))))

  (define/keywords (make-input-config #!key (actions input-actions) (keys default-keys)
                                      (buttons default-buttons) (mouse '())
                                      (axes default-axes) (dead-zone default-dead-zone))
    (unless (list? actions) (error 'make-input-config "actions: must be a list of symbols" actions))
    (for-each (lambda (a)
                (unless (symbol? a) (error 'make-input-config (sprintf "actions: ~s is not a symbol" a))))
              actions)
    (check-pairs "key" keys (key-symbols) "(key-symbols) lists the names")
    (check-pairs "button" buttons controller-buttons (sprintf "one of ~s" controller-buttons))
    (check-pairs "mouse" mouse mouse-buttons (sprintf "one of ~s" mouse-buttons))
    (unless (list? axes) (error 'make-input-config "axes: must be a list of (AXIS + | - ACTION [THRESHOLD])" axes))
    (for-each (lambda (ax)
                (unless (and (list? ax) (<= 3 (length ax) 4) (memq (cadr ax) '(+ -)))
                  (error 'make-input-config
                         (sprintf "an axis binding is (AXIS + | - ACTION [THRESHOLD]), got ~s" ax)))
                (check-source "axis" (car ax) controller-axes)
                (check-action-name (caddr ax) ax)
                (when (= 4 (length ax))
                  (let ((t (cadddr ax)))
                    (unless (and (real? t) (<= 0 t 32767))
                      (error 'make-input-config
                             (sprintf "the threshold of the axis binding ~s must be a number from 0 to 32767" ax))))))
              axes)
    (unless (and (real? dead-zone) (>= dead-zone 0))
      (error 'make-input-config "dead-zone: must be a non-negative number" dead-zone))
    (warn-misspelt-actions actions (append keys buttons mouse (map (lambda (ax) (cons (car ax) (caddr ax))) axes)))
    (%make-input-config (config-actions (dedupe actions) keys buttons mouse axes)
                        keys buttons mouse axes dead-zone))

  ;; A binding adds its action to the configuration, so a misspelt one
  ;; (jmup for jump) makes a new action no code asks for, and the key does
  ;; nothing. An action that is not declared and is one slip from one that
  ;; is gets a warning naming the binding and the fix.
  (define (warn-misspelt-actions declared bindings)
    (for-each
     (lambda (b)
       (let ((a (cdr b)))
         (unless (memq a declared)
           (let ((near (let loop ((ds declared))
                         (cond ((null? ds) #f)
                               ((one-slip? (symbol->string a) (symbol->string (car ds))) (car ds))
                               (else (loop (cdr ds)))))))
             (when near
               (with-output-to-port (current-error-port)
                 (lambda ()
                   (print (sprintf "downstroke: warning: make-input-config: ~s is bound to the action ~s, which actions: does not declare; did you mean ~s? (declare ~s in actions: if it is meant)"
                                   (car b) a near a)))))))))
     bindings))

  (define *default-input-config* (make-input-config))

  ;; The configuration as make-input-config's arguments: readable data, so
  ;; a rebinding screen can save it, and (apply make-input-config list)
  ;; makes it again.
  (define (input-config->list c)
    (list actions: (input-config-actions c) keys: (input-config-keys c)
          buttons: (input-config-buttons c) mouse: (input-config-mouse c)
          axes: (input-config-axes c) dead-zone: (input-config-dead-zone c)))

  ;;; Rebinding. A source is written as input-pressed-sources answers it:
  ;;; (key K) (button B) (mouse M) (axis A SIGN).

  (define (check-bind-source who src)
    (unless (and (list? src) (pair? src)
                 (case (car src)
                   ((key) (and (= 2 (length src)) (memq (cadr src) (key-symbols))))
                   ((button) (and (= 2 (length src)) (memq (cadr src) controller-buttons)))
                   ((mouse) (and (= 2 (length src)) (memq (cadr src) mouse-buttons)))
                   ((axis) (and (= 3 (length src)) (memq (cadr src) controller-axes)
                                (memq (caddr src) '(+ -))))
                   (else #f)))
      (error who (sprintf "unknown source ~s: a source is (key K), (button B), (mouse M) or (axis A + | -)"
                          src))))

  (define (remove-if drop? xs)
    (cond ((null? xs) '())
          ((drop? (car xs)) (remove-if drop? (cdr xs)))
          (else (cons (car xs) (remove-if drop? (cdr xs))))))

  ;; A new configuration in which `source` holds `action` (and nothing
  ;; else it held before); with replace?: #t, the default, the action's
  ;; other sources of the same kind (its other keys, say) are let go.
  (define/keywords (input-config-bind config action source #!key (replace? #t))
    (check-bind-source 'input-config-bind source)
    (check-action-name action source)
    (let* ((kind (car source)) (name (cadr source))
           (pairs (lambda (alist)
                    (append (remove-if (lambda (p) (or (eq? (car p) name)
                                                       (and replace? (eq? (cdr p) action))))
                                       alist)
                            (list (cons name action)))))
           (keep (lambda (field kind2) (if (eq? kind kind2) (pairs (field config)) (field config)))))
      (make-input-config
       actions: (input-config-actions config)
       keys: (keep input-config-keys 'key)
       buttons: (keep input-config-buttons 'button)
       mouse: (keep input-config-mouse 'mouse)
       axes: (if (eq? kind 'axis)
                 (append (remove-if (lambda (b) (or (and (eq? (car b) name) (eq? (cadr b) (caddr source)))
                                                    (and replace? (eq? (caddr b) action))))
                                    (input-config-axes config))
                         (list (list name (caddr source) action)))
                 (input-config-axes config))
       dead-zone: (input-config-dead-zone config))))

  ;;; The state of one frame.
  ;;; sources: the sources down now, as (key . K) (button . B) (mouse . M)
  ;;; and (axis A . VALUE) for an axis off its centre; new: the sources
  ;;; that went down in the frame, newest first, as input-pressed-sources
  ;;; gives them; mouse-x, mouse-y: the pointer in logical screen pixels.
  (define-record-type input-state
    (%make-input-state config held pressed released sources quit? mouse-x mouse-y new)
    input-state?
    (config input-state-config)
    (held input-held-actions)
    (pressed input-pressed-actions)
    (released input-released-actions)
    (sources input-sources)
    (quit? input-quit?)
    (mouse-x input-mouse-x)
    (mouse-y input-mouse-y)
    (new input-new-sources))

  (define (make-input-state #!optional (config #f))
    (let ((config (or config *default-input-config*)))
      (unless (input-config? config)
        (error 'make-input-state "not an input configuration (make-input-config makes one)" config))
      (%make-input-state config '() '() '() '() #f 0 0 '())))

  (define (input-state-actions s) (input-config-actions (input-state-config s)))
  (define (input-action? s action) (and (memq action (input-state-actions s)) #t))

  (define (known-action who s action)
    (unless (memq action (input-state-actions s))
      (error who (sprintf "unknown action ~s (actions: ~s)" action (input-state-actions s)))))

  (define (input-held? s action)
    (known-action 'input-held? s action)
    (and (memq action (input-held-actions s)) #t))
  (define (input-pressed? s action)
    (known-action 'input-pressed? s action)
    (and (memq action (input-pressed-actions s)) #t))
  (define (input-released? s action)
    (known-action 'input-released? s action)
    (and (memq action (input-released-actions s)) #t))

  (define (input-mouse-position s) (values (input-mouse-x s) (input-mouse-y s)))

  ;; The sources pressed in the frame, oldest first: what a rebinding
  ;; screen waits for ("press a key for jump").
  (define (input-pressed-sources s) (reverse (input-new-sources s)))

  ;; Sets are lists kept in the order of the configuration's actions, so
  ;; equal? compares them.
  (define (action-set actions pred)
    (let loop ((as actions))
      (cond ((null? as) '())
            ((pred (car as)) (cons (car as) (loop (cdr as))))
            (else (loop (cdr as))))))

  (define (lookup name alist)
    (cond ((null? alist) '())
          ((eq? (car (car alist)) name) (cons (cdr (car alist)) (lookup name (cdr alist))))
          (else (lookup name (cdr alist)))))

  (define (axis-threshold b dz) (if (null? (cdddr b)) dz (cadddr b)))
  (define (axis-past? b v dz)
    (let ((t (axis-threshold b dz))) (if (eq? (cadr b) '+) (> v t) (< v (- t)))))

  ;; The actions one source holds now.
  (define (source-actions config src)
    (case (car src)
      ((key) (lookup (cdr src) (input-config-keys config)))
      ((button) (lookup (cdr src) (input-config-buttons config)))
      ((mouse) (lookup (cdr src) (input-config-mouse config)))
      ((axis) (let ((a (cadr src)) (v (cddr src)) (dz (input-config-dead-zone config)))
                (let loop ((bs (input-config-axes config)))
                  (cond ((null? bs) '())
                        ((and (eq? (car (car bs)) a) (axis-past? (car bs) v dz))
                         (cons (caddr (car bs)) (loop (cdr bs))))
                        (else (loop (cdr bs)))))))
      (else '())))

  (define (held-from-sources config sources)
    (let ((acts (let loop ((ss sources))
                  (if (null? ss) '() (append (source-actions config (car ss)) (loop (cdr ss)))))))
      (action-set (input-config-actions config) (lambda (a) (memq a acts)))))

  (define (remove-source src sources)
    (cond ((null? sources) '())
          ((equal? (car sources) src) (cdr sources))
          (else (cons (car sources) (remove-source src (cdr sources))))))

  (define (add-source src sources)
    (if (member src sources) sources (cons src sources)))

  (define (axis-value axis sources)
    (cond ((null? sources) 0)
          ((and (eq? (car (car sources)) 'axis) (eq? (cadr (car sources)) axis)) (cddr (car sources)))
          (else (axis-value axis (cdr sources)))))

  (define (without-axis axis sources)
    (remove-if (lambda (s) (and (eq? (car s) 'axis) (eq? (cadr s) axis))) sources))

  (define (input-update state config events)
    (let* ((actions (input-config-actions config))
           ;; a configuration replaced since the last frame: the held set
           ;; is what the new bindings hold, with no edge for the change
           (start-held (if (eq? config (input-state-config state))
                           (input-held-actions state)
                           (held-from-sources config (input-sources state))))
           (dz (input-config-dead-zone config)))
      (let loop ((evs events)
                 (sources (input-sources state))
                 (held start-held)
                 (pressed '()) (released '()) (quit? #f)
                 (mx (input-mouse-x state)) (my (input-mouse-y state)) (new '()))
        (if (null? evs)
            (%make-input-state config held
                               (action-set actions (lambda (a) (memq a pressed)))
                               (action-set actions (lambda (a) (memq a released)))
                               sources quit? mx my new)
            (let* ((ev (car evs))
                   ;; a source SDL could not name (unknown) holds nothing
                   (down (lambda (src form)
                           (if (or (eq? (cdr src) 'unknown) (member src sources))
                               (values sources new)
                               (values (cons src sources) (cons form new))))))
              (receive (sources2 new2 mx2 my2)
                  (case (car ev)
                    ((key-down)
                     (receive (s n) (down (cons 'key (cadr ev)) (list 'key (cadr ev)))
                       (values s n mx my)))
                    ((key-up) (values (remove-source (cons 'key (cadr ev)) sources) new mx my))
                    ((controller-button-down)
                     (receive (s n) (down (cons 'button (cadr ev)) (list 'button (cadr ev)))
                       (values s n mx my)))
                    ((controller-button-up)
                     (values (remove-source (cons 'button (cadr ev)) sources) new mx my))
                    ((mouse-button-down)
                     (receive (s n) (down (cons 'mouse (cadr ev)) (list 'mouse (cadr ev)))
                       (values s n (caddr ev) (cadddr ev))))
                    ((mouse-button-up)
                     (values (remove-source (cons 'mouse (cadr ev)) sources) new (caddr ev) (cadddr ev)))
                    ((mouse-motion) (values sources new (cadr ev) (caddr ev)))
                    ((controller-axis)
                     (let* ((axis (cadr ev)) (v (caddr ev))
                            (was (axis-value axis sources))
                            (s (without-axis axis sources))
                            (s (if (= v 0) s (cons (cons 'axis (cons axis v)) s))))
                       (values s
                               (cond ((and (> v dz) (<= was dz)) (cons (list 'axis axis '+) new))
                                     ((and (< v (- dz)) (>= was (- dz))) (cons (list 'axis axis '-) new))
                                     (else new))
                               mx my)))
                    (else (values sources new mx my)))
                (let ((held2 (if (eq? sources2 sources) held (held-from-sources config sources2))))
                  (loop (cdr evs) sources2 held2
                        (if (eq? held2 held) pressed
                            (append (action-set actions (lambda (a) (and (memq a held2) (not (memq a held)))))
                                    pressed))
                        (if (eq? held2 held) released
                            (append (action-set actions (lambda (a) (and (memq a held) (not (memq a held2)))))
                                    released))
                        (or quit? (eq? (car ev) 'quit))
                        mx2 my2 new2))))))))

  ;; The state for a frame whose held set is `held` (and whose taps are
  ;; pressed and released within it), following `prev`; the pointer at
  ;; `mouse` (x . y), or where it was. No sources: this is how scripts
  ;; drive the game.
  (define (input-from-held prev held #!optional (taps '()) (mouse #f) (config #f))
    (let* ((config (or config (input-state-config prev)))
           (actions (input-config-actions config))
           (was (input-held-actions prev))
           (check (lambda (a)
                    (unless (memq a actions)
                      (error 'input-from-held (sprintf "unknown action ~s (actions: ~s)" a actions))))))
      (for-each check held)
      (for-each check taps)
      (let ((tap? (lambda (a) (and (memq a taps) (not (memq a was)) (not (memq a held))))))
        (%make-input-state
         config
         (action-set actions (lambda (a) (memq a held)))
         (action-set actions (lambda (a) (or (and (memq a held) (not (memq a was))) (tap? a))))
         (action-set actions (lambda (a) (or (and (memq a was) (not (memq a held))) (tap? a))))
         '() #f
         (if mouse (car mouse) (input-mouse-x prev))
         (if mouse (cdr mouse) (input-mouse-y prev))
         '()))))

  (define (tap-element? x) (and (pair? x) (eq? (car x) 'tap) (pair? (cdr x)) (null? (cddr x))))
  (define (mouse-element? x)
    (and (pair? x) (eq? (car x) 'mouse) (list? x) (= 3 (length x)) (real? (cadr x)) (real? (caddr x))))

  (define (check-script script config)
    (unless (list? script) (error 'scripted-input "a script is a list of (frame . actions)" script))
    (let ((actions (input-config-actions config)))
      (let loop ((s script) (last -1))
        (unless (null? s)
          (let ((e (car s)))
            (unless (and (pair? e) (exact-integer? (car e)) (list? (cdr e)))
              (error 'scripted-input "a script entry is (frame . actions)" e))
            (unless (> (car e) last)
              (error 'scripted-input "script frames must increase" (car e)))
            (for-each (lambda (x)
                        (unless (mouse-element? x)
                          (let ((a (if (tap-element? x) (cadr x) x)))
                            (unless (memq a actions)
                              (error 'scripted-input
                                     (sprintf "unknown action ~s in the script entry ~s (actions: ~s)"
                                              a e actions))))))
                      (cdr e))
            (loop (cdr s) (car e)))))))

  ;; The entry in force at `frame`: the last one whose frame is at or
  ;; before it, found from `entry` (one such entry for an earlier frame, or
  ;; #f) and `rest` (the entries after it). Returns it and the entries
  ;; after it.
  (define (entry-at rest entry frame)
    (if (or (null? rest) (> (car (car rest)) frame))
        (values entry rest)
        (entry-at (cdr rest) (car rest) frame)))

  ;; (values held taps) of the entry in force at `frame` (#f: none).
  (define (entry-held entry frame)
    (if entry
        (let ((acts (cdr entry)))
          (values (let held ((xs acts))
                    (cond ((null? xs) '())
                          ((or (tap-element? (car xs)) (mouse-element? (car xs))) (held (cdr xs)))
                          (else (cons (car xs) (held (cdr xs))))))
                  (if (= (car entry) frame)
                      (let taps ((xs acts))
                        (cond ((null? xs) '())
                              ((tap-element? (car xs)) (cons (cadr (car xs)) (taps (cdr xs))))
                              (else (taps (cdr xs)))))
                      '())))
        (values '() '())))

  ;; The pointer position the entry in force sets if it is for exactly
  ;; `frame`, as (x . y), or #f.
  (define (entry-mouse entry frame)
    (and entry (= (car entry) frame)
         (let find ((xs (cdr entry)))
           (cond ((null? xs) #f)
                 ((mouse-element? (car xs)) (cons (cadr (car xs)) (caddr (car xs))))
                 (else (find (cdr xs)))))))

  ;; (values held taps) of `script` at `frame`.
  (define (script-held-at script frame)
    (let-values (((entry rest) (entry-at script #f frame)))
      (entry-held entry frame)))

  ;; The pointer position an entry for exactly `frame` sets, as (x . y), or #f.
  (define (script-mouse-at script frame)
    (let loop ((s script))
      (cond ((or (null? s) (> (car (car s)) frame)) #f)
            ((= (car (car s)) frame) (entry-mouse (car s) frame))
            (else (loop (cdr s))))))

  ;; The procedure keeps its place in the script: frames asked in
  ;; increasing order (as a game runs) cost one step along the script in
  ;; all, and a frame earlier than the last one asked starts again from
  ;; the script's start.
  (define (scripted-input script #!optional (config #f))
    (check-script script (or config *default-input-config*))
    ;; the last frame asked, the entry in force then and the entries after it
    (let ((asked -1) (entry #f) (rest script))
      (lambda (frame prev #!optional (config #f))
        (let-values (((e r) (if (and (exact-integer? frame) (>= frame asked))
                                (entry-at rest entry frame)
                                (entry-at script #f frame))))
          (when (exact-integer? frame)
            (set! asked frame)
            (set! entry e)
            (set! rest r))
          (receive (held taps) (entry-held e frame)
            (input-from-held prev held taps (entry-mouse e frame) config))))))

  ;; A recording: the script entries so far, newest first, the held set
  ;; of the last frame recorded and the pointer's position then.
  (define (make-recording) (list '() '() (cons 0 0)))

  (define (input-record rec frame state)
    (let* ((held (input-held-actions state))
           (was (cadr rec))
           (mouse (cons (input-mouse-x state) (input-mouse-y state)))
           (moved? (not (equal? mouse (caddr rec))))
           (taps (action-set (input-state-actions state)
                             (lambda (a) (and (memq a (input-pressed-actions state))
                                              (memq a (input-released-actions state))
                                              (not (memq a held))
                                              (not (memq a was)))))))
      (if (and (equal? held was) (null? taps) (not moved?))
          rec
          (list (cons (cons frame (append held (map (lambda (a) (list 'tap a)) taps)
                                          (if moved? (list (list 'mouse (car mouse) (cdr mouse))) '())))
                      (car rec))
                held mouse))))

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
    (void))

  (define (check-int who what v)
    (unless (and (exact-integer? v) (<= -1000000 v 1000000))
      (error who (sprintf "~a must be an integer (pixels), got ~s" what v))))

  ;; (push-mouse-motion-event! x y), in window pixels: SDL maps them to
  ;; logical pixels for a window's renderer; headless they are logical.
  (define (push-mouse-motion-event! x y)
    (check-int 'push-mouse-motion-event! "x" x)
    (check-int 'push-mouse-motion-event! "y" y)
    (unless (sdl-initialized?) (error 'push-mouse-motion-event! "SDL is not initialized (init!)"))
    (when (< ((foreign-lambda int "downstroke_push_mmotion" int int) x y) 1)
      (error 'push-mouse-motion-event! "SDL_PushEvent failed or filtered"))
    (void))

  ;; (push-mouse-button-event! 'down 'left x y) or 'up.
  (define (push-mouse-button-event! dir button x y)
    (unless (memq button mouse-buttons)
      (error 'push-mouse-button-event! (sprintf "unknown mouse button ~s: one of ~s" button mouse-buttons)))
    (check-int 'push-mouse-button-event! "x" x)
    (check-int 'push-mouse-button-event! "y" y)
    (unless (sdl-initialized?) (error 'push-mouse-button-event! "SDL is not initialized (init!)"))
    (let ((down (case dir ((down) 1) ((up) 0)
                      (else (error 'push-mouse-button-event! "dir must be down or up" dir)))))
      (when (< ((foreign-lambda int "downstroke_push_mbutton" int int int int)
                down (+ 1 (index-of button mouse-buttons 'push-mouse-button-event!)) x y)
               1)
        (error 'push-mouse-button-event! "SDL_PushEvent failed or filtered"))
      (void))))
