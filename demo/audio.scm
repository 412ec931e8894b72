;;; Audio: music and sound effects, with what is playing on screen.
;;;   bin/demo-audio     1 (or z) jump, 2 (or x) coin, 3 (or c) boom,
;;;                      m (or return) music on / off, escape quits
;;; The sounds are WAV files made by tools/make-assets.scm; music.wav is a
;;; 4 s loop. With no audio device (or no sound files) the demo runs
;;; silent and says why.
(import scheme (chicken base) (chicken format) (chicken condition)
        (downstroke entity) (downstroke scene) (downstroke engine)
        (downstroke input) (downstroke sound) (downstroke text))
(include-relative "common.scm")

;; The keys 1 2 3 and m are bound to actions of their own choosing here:
;; a scripted run (--script) presses the actions, a player the keys.
(define keys
  '((n-1 . a) (z . a) (j . a) (n-2 . b) (x . b) (k . b) (n-3 . select) (c . select)
    (m . start) (return . start) (escape . quit)))

;; (action effect key colour): one card per effect.
(define effects
  '((a jump "1" (90 200 120)) (b coin "2" (250 200 70)) (select boom "3" (240 100 80))))

(define lit-frames 30)                  ; a card stays lit this long after a play
(define no-device #f)                   ; why there is no sound, or #f
(define music-on #f)                    ; what the player asked for
(define played '())                     ; effects that got a channel, newest first

(define (card i e)
  (list #:type 'card #:tags '(card) #:action (car e) #:effect (cadr e) #:key (caddr e) #:lit-colour (cadddr e)
        #:x (+ 40 (* i 195)) #:y 262 #:width 170 #:height 104 #:plays 0 #:lit 0
        #:color '(46 50 76)))

;; Twenty-four equaliser bars; they dance while the music plays.
(define (numbers n) (if (= n 0) '() (append (numbers (- n 1)) (list (- n 1)))))   ; 0 .. n-1
(define (bar i) (list #:type 'bar #:index i #:x (+ 40 (* i 24)) #:y 226 #:width 18 #:height 4
                      #:color '(70 74 100)))

(define (bar-height i frame)
  (let ((wave (* (abs (sin (+ (* frame 0.11) (* i 0.73)))) (abs (sin (+ (* frame 0.037) (* i 0.29)))))))
    (+ 6 (inexact->exact (round (* 46 wave))))))

;; Plays the card's effect when its action is pressed; lights it a while.
(define (press input card)
  (if (input-pressed? input (entity-ref card #:action))
      (let ((name (entity-ref card #:effect)))
        (when (and (not no-device) (play-sound name)) (set! played (cons name played)))
        (entity-set (entity-set card #:plays (+ 1 (entity-ref card #:plays))) #:lit lit-frames))
      (entity-set card #:lit (max 0 (- (entity-ref card #:lit) 1)))))

(define (show-card card)
  (entity-set card #:color (if (> (entity-ref card #:lit) 0) (entity-ref card #:lit-colour) '(46 50 76))))

(define (toggle-music!)
  (set! music-on (not music-on))
  (unless no-device (if music-on (play-music! volume: 0.5) (stop-music!))))

(define font-dir "/usr/share/fonts/truetype/dejavu/")
(define big #f) (define small #f) (define tiny #f)

(define game
  (make-game
   title: "Downstroke audio" width: 640 height: 480
   input-config: (make-input-config keys: keys)
   create: (lambda (game)
             (set! big (open-font (string-append font-dir "DejaVuSans-Bold.ttf") 26))
             (set! small (open-font (string-append font-dir "DejaVuSans.ttf") 15))
             (set! tiny (open-font (string-append font-dir "DejaVuSans.ttf") 11))
             (condition-case
                 (begin (init-audio!)
                        (load-sounds! '((jump . "demo/assets/jump.wav") (coin . "demo/assets/coin.wav")
                                        (boom . "demo/assets/boom.wav")))
                        (load-music! "demo/assets/music.wav"))
               (e (exn) (set! no-device ((condition-property-accessor 'exn 'message) e))))
             (toggle-music!)                ; music on from the start
             (game-scene-set! game (make-sprite-scene
                                    background: '(24 26 42)
                                    entities: (append (map card '(0 1 2) effects)
                                                      (map bar (numbers 24))))))
   update: (lambda (game dt)
             (let ((input (game-input game)) (frame (game-frame game)))
               (when (input-pressed? input 'start) (toggle-music!))
               (game-scene-set!
                game
                (scene-map-entities (game-scene game)
                  (lambda (scene e)
                    (if (eq? (entity-type e) 'card)
                        (show-card (press input e))
                        (let ((h (if music-on (bar-height (entity-ref e #:index) frame) 4)))
                          (entity-set (entity-set (entity-set e #:height h) #:y (- 230 h))
                                      #:color (if music-on '(110 190 255) '(70 74 100))))))))))
   render: (lambda (game)
             (let ((r (game-renderer game)) (grey '(150 156 190)))
               (draw-text! r big "Audio" 40 20)
               (draw-text! r small "music and effects through (downstroke sound)" 40 56 color: grey)
               (if no-device
                   (begin (draw-text! r small "No sound: the demo runs silent" 40 84 color: '(250 170 80))
                          (draw-text! r tiny no-device 40 104 color: grey))
                   (draw-text! r small "Audio device open" 40 84 color: '(120 220 140)))
               (draw-text! r big (cond ((not music-on) "Music: stopped")
                                       (no-device "Music: on (silent)")
                                       (else "Music: playing"))
                           40 126 color: (if music-on '(120 220 140) grey))
               (draw-text! r small "music.wav, a 4 second loop" 330 134 color: grey)
               (for-each (lambda (c)
                           (let ((x (entity-ref c #:x)) (on (> (entity-ref c #:lit) 0)))
                             (draw-text! r big (entity-ref c #:key) (+ x 14) 272
                                         color: (if on '(24 26 42) '(255 255 255)))
                             (draw-text! r big (symbol->string (entity-ref c #:effect)) (+ x 50) 272
                                         color: (if on '(24 26 42) (entity-ref c #:lit-colour)))
                             (draw-text! r small (case (entity-ref c #:plays)
                                                   ((0) "not played yet") ((1) "played once")
                                                   (else (sprintf "played ~a times" (entity-ref c #:plays))))
                                         (+ x 14) 334 color: (if on '(24 26 42) grey))))
                         (scene-find-all-tagged (game-scene game) 'card))
               (draw-text! r small "1 2 3 (or z x c): play an effect    m (or return): music on/off" 40 400)
               (draw-text! r small "escape: quit" 40 424 color: grey)))))

(demo-run! game)

;; The state the mixer reports at the end, for the tests.
(printf "audio: device open ~a, music playing ~a, effects played ~s~%"
        (audio-open?) (music-playing?) (reverse played))
(shutdown-audio!)
(close-font! big)
(close-font! small)
(close-font! tiny)
