(import (downstroke entity) (downstroke physics))

(define box (entity-set (make-entity 0 0 16 16) #:vx 5))
(write (apply-velocity-x #f box 16))
(newline)
