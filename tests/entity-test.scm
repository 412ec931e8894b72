(import (downstroke test) (downstroke entity))
(test-group "entity"
  (test 3 (entity-ref (make-entity 3 4 5 6) #:x)))
