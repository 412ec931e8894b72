;;; (downstroke run-options): what a run of a game is asked for, on its
;;; command line or by game-run!'s keywords, and the watching it asks for:
;;; screenshots at chosen frames and entity keys traced frame by frame.
;;;
;;; The command line (game-run! reads it unless given command-line: #f):
;;;   --headless            no window (a software renderer on a surface)
;;;   --frames N            stop after N frames (300 when --headless is
;;;                         given without it: a headless run never ends)
;;;   --script FILE         an input script read from FILE (one datum)
;;;   --screenshot FILE     the last frame, as a PNG
;;;   --screenshot-at N FILE   frame N as a PNG (any number of these)
;;;   --trace SPEC          trace entity keys every frame (any number):
;;;                         SPEC is WHO:KEY,KEY,... with WHO a type, tag or
;;;                         name of the entities traced, or * for all
;;;   --trace-file FILE     the trace goes to FILE instead of stdout
;;;   --profile             every 60 frames, the mean time per frame of the
;;;                         engine update, update: and drawing over those
;;;                         60 frames (game-frame-profile), one line on
;;;                         stdout: "profile: frames A-B engine E ms
;;;                         update U ms render R ms"
;;; Other arguments are the game's own and are left alone. An option
;;; without its value, or a value that is not one, is an error naming it.
;;;
;;; Frames are numbered as scripts number them: frame 0 is the first.
;;; A screenshot of frame N is the picture drawn after frame N ran.
;;; An input script entry may hold (screenshot "FILE") among its actions:
;;; a screenshot of that frame. An entry holding nothing else is taken
;;; out of the script, so it changes nothing the input does.

(module (downstroke run-options)
  (command-line-run-options parse-trace-spec trace-line script-screenshots
   ;; for sibling modules only: what game-run! does with them
   run-option check-screenshots
   make-watch watch? watch-frame-run! watch-frame-drawn! watch-end!
   save-screenshot! capture-pixels)

  (import scheme (chicken base) (chicken format) (chicken string) (chicken keyword)
          (chicken file) (chicken pathname) (chicken condition) (chicken port) (chicken io)
          (downstroke entity) (downstroke scene) (downstroke sdl2))

  ;;; ------------------------------------------------------------------
  ;;; The command line, as an alist of what it asks.

  (define (option-error option why)
    (error 'game-run! (sprintf "command line: ~a ~a" option why)))

  (define (frame-number option s)
    (let ((n (and s (string->number s))))
      (unless (and n (exact-integer? n) (>= n 0))
        (option-error option (sprintf "needs a frame count (an integer >= 0), got ~s" s)))
      n))

  (define (needs-value option rest)
    (when (or (null? rest) (and (>= (string-length (car rest)) 2)
                                (string=? "--" (substring (car rest) 0 2))))
      (option-error option "needs a value"))
    (car rest))

  ;; args: strings. Answers ((option . value) ...), the repeatable options
  ;; (screenshot-at, trace) once per use, in order.
  (define (command-line-run-options args)
    (let loop ((as args) (out '()))
      (if (null? as)
          (reverse out)
          (let ((a (car as)) (rest (cdr as)))
            (cond
             ((string=? a "--headless") (loop rest (cons (cons 'headless #t) out)))
             ((string=? a "--frames")
              (loop (cdr rest) (cons (cons 'frames (frame-number a (needs-value a rest))) out)))
             ((string=? a "--script")
              (loop (cdr rest) (cons (cons 'script (needs-value a rest)) out)))
             ((string=? a "--screenshot")
              (loop (cdr rest) (cons (cons 'screenshot (needs-value a rest)) out)))
             ((string=? a "--screenshot-at")
              (let* ((n (frame-number a (needs-value a rest)))
                     (file (needs-value a (cdr rest))))
                (loop (cddr rest) (cons (cons 'screenshot-at (cons n file)) out))))
             ((string=? a "--trace")
              (loop (cdr rest) (cons (cons 'trace (parse-trace-spec (needs-value a rest))) out)))
             ((string=? a "--trace-file")
              (loop (cdr rest) (cons (cons 'trace-file (needs-value a rest)) out)))
             ((string=? a "--profile") (loop rest (cons (cons 'profile #t) out)))
             (else (loop rest out)))))))

  ;; The value of a single option, or default.
  (define (run-option options name #!optional default)
    (let ((p (assq name options))) (if p (cdr p) default)))

  ;;; ------------------------------------------------------------------
  ;;; Screenshots: ((frame . file) ...)

  (define (screenshot-command? x)
    (and (pair? x) (eq? (car x) 'screenshot)))

  ;; (values script shots): the script without its (screenshot FILE)
  ;; elements, and those screenshots as (frame . FILE).
  (define (script-screenshots script)
    (if (not (list? script))
        (values script '())
        (let loop ((es script) (kept '()) (shots '()))
          (if (null? es)
              (values (reverse kept) (reverse shots))
              (let ((e (car es)))
                (if (and (pair? e) (list? (cdr e)) (let any ((xs (cdr e)))
                                                     (and (pair? xs) (or (screenshot-command? (car xs))
                                                                         (any (cdr xs))))))
                    (let* ((commands (filter-list screenshot-command? (cdr e)))
                           (actions (filter-list (lambda (x) (not (screenshot-command? x))) (cdr e))))
                      (for-each (lambda (c)
                                  (unless (and (= 2 (length c)) (string? (cadr c)) (> (string-length (cadr c)) 0))
                                    (error 'game-run! (sprintf "input script: ~s in the entry ~s: a screenshot command is (screenshot \"FILE.png\")" c e))))
                                commands)
                      (loop (cdr es)
                            (if (null? actions) kept (cons (cons (car e) actions) kept))
                            (append (reverse (map (lambda (c) (cons (car e) (cadr c))) commands)) shots)))
                    (loop (cdr es) (cons e kept) shots)))))))

  (define (filter-list keep? l)
    (cond ((null? l) '()) ((keep? (car l)) (cons (car l) (filter-list keep? (cdr l))))
          (else (filter-list keep? (cdr l)))))

  (define (check-screenshots shots)
    (unless (list? shots)
      (error 'game-run! "screenshots: must be a list of (FRAME . \"FILE.png\")" shots))
    (for-each (lambda (s)
                (unless (and (pair? s) (exact-integer? (car s)) (>= (car s) 0)
                             (string? (cdr s)) (> (string-length (cdr s)) 0))
                  (error 'game-run! (sprintf "screenshots: ~s is not (FRAME . \"FILE.png\") with FRAME an integer >= 0" s))))
              shots)
    shots)

  ;; The screenshot's pixels, read before a present: (u8vector w h).
  (define (capture-pixels renderer)
    (receive (buf w h) (render-read-pixels renderer) (list buf w h)))

  ;; Saves the frame as a PNG: the surface of a headless run, else the
  ;; pixels captured (or read now). Missing directories are made.
  (define (save-screenshot! path renderer surface captured)
    (handle-exceptions exn
        (error 'game-run!
               (sprintf "screenshot: cannot save ~s: ~a" path
                        ((condition-property-accessor 'exn 'message "unknown error") exn)))
      (let ((dir (pathname-directory path)))
        (when (and dir (not (directory-exists? dir)))
          (create-directory dir #t)))
      (if surface
          (img-save-png! surface path)
          (let* ((c (or captured (capture-pixels renderer)))
                 (s (rgba-pixels->surface! (car c) (cadr c) (caddr c))))
            (dynamic-wind
             void
             (lambda () (img-save-png! s path))
             (lambda () (free-surface! s)))))))

  ;;; ------------------------------------------------------------------
  ;;; Traces: ((who key ...) ...), who a symbol (type or tag), a string
  ;;; (#:name), an integer (#:object-id) or #t (every entity).

  (define (parse-trace-spec spec)
    (let ((colon (substring-index ":" spec)))
      (unless (and colon (> colon 0) (< (+ colon 1) (string-length spec)))
        (option-error "--trace" (sprintf "~s is not WHO:KEY,KEY,... (e.g. player:x,y,vy or *:x)" spec)))
      (let ((who (substring spec 0 colon))
            (keys (string-split (substring spec (+ colon 1)) ",")))
        (cons (if (string=? who "*") #t (string->symbol who))
              (map (lambda (k) (string->keyword (if (and (> (string-length k) 2) (string=? "#:" (substring k 0 2)))
                                                    (substring k 2)
                                                    k)))
                   keys)))))

  (define (check-trace trace)
    (unless (and (list? trace)
                 (let ok ((t trace))
                   (or (null? t)
                       (and (pair? (car t)) (list? (cdar t)) (pair? (cdar t))
                            (let ((who (caar t)))
                              (or (eq? who #t) (symbol? who) (string? who) (exact-integer? who)))
                            (let keys ((ks (cdar t))) (or (null? ks) (and (keyword? (car ks)) (keys (cdr ks)))))
                            (ok (cdr t))))))
      (error 'game-run! (sprintf "trace: must be a list of (WHO #:key ...), WHO a type or tag symbol, a name string, an object id or #t; got ~s" trace)))
    trace)

  (define (traced? who e)
    (cond ((eq? who #t) #t)
          ((symbol? who) (or (eq? who (entity-ref e #:type #f)) (entity-has-tag? e who)))
          ((string? who) (equal? who (entity-ref e #:name #f)))
          (else (eqv? who (entity-ref e #:object-id #f)))))

  ;; "frame 12 player: #:x 32 #:y 190 #:vy 1/2", a key the entity lacks
  ;; shown as -, or #f when `keys` is empty.
  (define (trace-line frame e keys)
    (sprintf "frame ~a ~a:~a" frame (entity-label e)
             (apply string-append
                    (map (lambda (k)
                           (let ((p (assq k e)))
                             (if p (sprintf " ~s ~s" k (cdr p)) (sprintf " ~s -" k))))
                         keys))))

  ;; The keys traced for e: those of every spec that selects it, each once.
  (define (traced-keys trace e)
    (let loop ((t trace) (keys '()))
      (if (null? t)
          (reverse keys)
          (loop (cdr t)
                (if (traced? (caar t) e)
                    (foldl (lambda (acc k) (if (memq k acc) acc (cons k acc))) keys (cdar t))
                    keys)))))

  ;;; ------------------------------------------------------------------
  ;;; A watch: what a run does after each frame runs and is drawn.

  (define-record-type watch
    (%make-watch shots trace port close-port? profile)
    watch?
    (shots watch-shots watch-shots-set!)      ; pending, sorted by frame
    (trace watch-trace)
    (port watch-port)
    (close-port? watch-close-port?)
    (profile watch-profile))                  ; #f, or a thunk: game-frame-profile

  ;; #f when there is nothing to watch, so a plain run pays nothing.
  ;; profile: #f, or a thunk answering the means of the last 60 frames
  ;; (the engine's game-frame-profile of the game run), for --profile.
  (define (make-watch shots trace trace-file #!optional (profile #f))
    (let ((shots (sort-shots (check-screenshots shots)))
          (trace (check-trace trace)))
      (and (or (pair? shots) (pair? trace) profile)
           (%make-watch shots trace
                        (if trace-file
                            (handle-exceptions exn
                                (error 'game-run! (sprintf "trace file: cannot open ~s: ~a" trace-file
                                                           ((condition-property-accessor 'exn 'message "") exn)))
                              (open-output-file trace-file))
                            (current-output-port))
                        (and trace-file #t)
                        profile))))

  (define (sort-shots shots)
    (foldr (lambda (s sorted)
             (let insert ((l sorted))
               (cond ((null? l) (list s))
                     ((<= (car s) (caar l)) (cons s l))
                     (else (cons (car l) (insert (cdr l)))))))
           '() shots))

  ;; After frame `frame` ran (update: and the camera included).
  (define (watch-frame-run! w scene frame)
    (when w
      (when (and scene (pair? (watch-trace w)))
        (for-each (lambda (e)
                    (let ((keys (traced-keys (watch-trace w) e)))
                      (when (pair? keys)
                        (write-line (trace-line frame e keys) (watch-port w)))))
                  (scene-entities scene)))
      (when (and (watch-profile w) (= (modulo frame profile-frames) (- profile-frames 1)))
        (print (profile-line frame ((watch-profile w)))))))

  ;; The frames --profile takes its means over: those the engine's frame
  ;; profile remembers.
  (define profile-frames 60)

  ;; The --profile line after frame `frame`, from a game-frame-profile
  ;; alist; its render mean counts frames run but not (yet) drawn as 0.
  (define (profile-line frame means)
    (define (ms part) (/ (round (* 1000 (exact->inexact (cdr (assq part means))))) 1000))
    (sprintf "profile: frames ~a-~a engine ~a ms update ~a ms render ~a ms"
             (+ 1 (- frame profile-frames)) frame (ms 'engine) (ms 'update) (ms 'render)))

  ;; After frame `frame` was drawn, before the present: the screenshots
  ;; due (at this frame or, when a window skipped drawing it, before).
  (define (watch-frame-drawn! w frame renderer surface)
    (when w
      (let loop ()
        (let ((shots (watch-shots w)))
          (when (and (pair? shots) (<= (caar shots) frame))
            (watch-shots-set! w (cdr shots))
            (save-screenshot! (cdar shots) renderer surface #f)
            (loop))))))

  ;; At the end of the run: the trace file closed; a screenshot of a
  ;; frame never drawn is said (a warning, the run itself went well).
  (define (watch-end! w frames-run)
    (when w
      (when (watch-close-port? w) (close-output-port (watch-port w)))
      (for-each (lambda (s)
                  (with-output-to-port (current-error-port)
                    (lambda ()
                      (print (sprintf "downstroke: warning: no screenshot ~s: frame ~a was not drawn (the run drew ~a frames)"
                                      (cdr s) (car s) frames-run)))))
                (watch-shots w))
      (watch-shots-set! w '()))))
