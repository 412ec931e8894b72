(import scheme (chicken base) (chicken condition) (downstroke engine) (downstroke scene))

(define (message thunk)
  (handle-exceptions e ((condition-property-accessor 'exn 'message) e) (thunk)))

(print (message (lambda () (make-game widht: 320))))
(print (message (lambda () (make-scene entites: '()))))
(print (message (lambda () (make-camera colour: 1))))
