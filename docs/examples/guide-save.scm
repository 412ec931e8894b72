(import scheme (chicken base) (chicken condition) (chicken file)
        (chicken process-context) (downstroke engine) (downstroke save)
        (downstroke input))

;; where SDL looks on Linux; a real game leaves XDG_DATA_HOME alone
(define home (create-temporary-directory))
(set-environment-variable! "XDG_DATA_HOME" home)

(define game (make-game title: "Sky Jump" org: "acme"))
(print (substring (game-save-directory game) (string-length home)))

(print "best before: " (game-load game 'best 0))
(game-save! game 'best 4200)
(game-save! game 'settings `((volume . 0.8) (keys . ,(input-config->list *default-input-config*))))
(print "best after: " (game-load game 'best 0))
(print "volume: " (cdr (assq 'volume (game-load game 'settings))))

(define (message-of thunk)
  (handle-exceptions e ((condition-property-accessor 'exn 'message) e) (thunk)))
(print (message-of (lambda () (game-save! game 'best (lambda () 4200)))))
(with-output-to-file (string-append (game-save-directory game) "best.scm")
  (lambda () (display "(4200")))
(print "corrupt, with a default: " (game-load game 'best 0))
(delete-directory home #t)
