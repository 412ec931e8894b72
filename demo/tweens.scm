;;; Tweens: every easing of (downstroke tween), side by side.
;;;   bin/demo-tweens        watch; escape quits
;;; One row per family (linear, quad, cubic ... bounce), one lane per form
;;; (-in, -out, -in-out). Each box is an entity whose #:tween moves its #:x
;;; from the left tick to the right one and back, forever: the engine's
;;; step-tweens does all the moving, this file only sets the tweens up.
;;; Back and elastic overshoot their ticks: that is their shape.
(import scheme (chicken base) (chicken format) (chicken string)
        (downstroke entity) (downstroke scene) (downstroke engine)
        (downstroke tween) (downstroke text))
(include-relative "common.scm")

(define duration 1000)                  ; ms from one tick to the other
(define travel 110)                     ; px between the ticks
(define lane-width 208)
(define start-offset 44)                ; the left tick, from the lane's left
(define row-height 38)
(define (row-top row) (+ 62 (* row row-height)))
(define (lane-left lane) (+ 8 (* lane lane-width)))

;; The families in *ease-table*'s order, each with its colour.
(define families
  '((quad (250 110 110)) (cubic (250 160 80)) (quart (240 210 80))
    (quint (170 220 90)) (sine (90 210 140)) (expo (80 200 220))
    (circ (100 150 250)) (back (160 120 250)) (elastic (220 110 230))
    (bounce (250 130 180))))

;; Every lane: (name row lane colour), linear alone on the first row.
(define lanes
  (cons '(linear 0 0 (230 230 240))
        (let loop ((fs families) (row 1))
          (if (null? fs)
              '()
              (let ((family (caar fs)) (colour (cadar fs)))
                (append (map (lambda (form lane)
                               (list (string->symbol (conc family form)) row lane colour))
                             '("-in" "-out" "-in-out") '(0 1 2))
                        (loop (cdr fs) (+ row 1))))))))

(define (rect x y w h colour)
  (list #:type 'decor #:x x #:y y #:width w #:height h #:color colour))

;; A lane's track: a line between two ticks, under its box.
(define (track row lane)
  (let ((x0 (+ (lane-left lane) start-offset)) (y (+ (row-top row) 24)))
    (list (rect (+ x0 6) y travel 1 '(70 74 100))
          (rect (+ x0 5) (- y 5) 1 11 '(110 116 150))
          (rect (+ x0 travel 6) (- y 5) 1 11 '(110 116 150)))))

;; The box: a 12 px square at the left tick, tweening to the right one.
(define (box name row lane colour)
  (let* ((x0 (+ (lane-left lane) start-offset))
         (e (list #:type 'box #:name name #:start x0 #:x x0 #:y (+ (row-top row) 18)
                  #:width 12 #:height 12 #:color colour)))
    (append e (list #:tween (make-tween e props: `((#:x . ,(+ x0 travel)))
                                        duration: duration ease: name
                                        repeat: -1 yoyo?: #t)))))

(define font-dir "/usr/share/fonts/truetype/dejavu/")
(define title-font #f)
(define label-font #f)

(define game
  (make-game
   title: "Downstroke tweens" width: 640 height: 480
   create: (lambda (game)
             (set! title-font (open-font (string-append font-dir "DejaVuSans-Bold.ttf") 18))
             (set! label-font (open-font (string-append font-dir "DejaVuSans.ttf") 12))
             (game-scene-set!
              game
              (make-sprite-scene
               background: '(22 24 38)
               ;; tracks first: entities are drawn in list order
               entities: (append (apply append (map (lambda (l) (track (cadr l) (caddr l))) lanes))
                                 (map (lambda (l) (apply box l)) lanes)))))
   ;; the names are text drawn over the scene every frame
   render: (lambda (game)
             (let ((r (game-renderer game)))
               (draw-text! r title-font "Tweens: every easing, there and back" 12 12)
               (draw-text! r label-font (sprintf "~a ms each way, repeat: -1, yoyo?: #t" duration)
                           12 38 color: '(150 156 190))
               (for-each (lambda (l)
                           (draw-text! r label-font (symbol->string (car l))
                                       (+ (lane-left (caddr l)) 4) (+ (row-top (cadr l)) 2)
                                       color: (cadddr l)))
                         lanes)))))

(demo-run! game)
(close-font! title-font)
(close-font! label-font)

;; Where each box is on the last frame: (name left-tick x), for the tests.
(printf "tweens: frame ~a ~s~%" (game-frame game)
        (foldr (lambda (e out)
                 (if (eq? (entity-type e) 'box)
                     (cons (list (entity-ref e #:name) (entity-ref e #:start) (entity-ref e #:x)) out)
                     out))
               '() (scene-entities (game-scene game))))
