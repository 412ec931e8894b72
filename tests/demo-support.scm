;;; What the demo suites share (included, not a suite): run a demo as a
;;; user would, from the repository root, and read the lines it prints.

(import (chicken base) (chicken io) (chicken process))

;; The lines `command` prints on stdout (stderr dropped: SDL's audio chatter).
(define (demo-output command)
  (with-input-from-pipe (string-append "cd .. && " command " 2>/dev/null") read-lines))

(define (last-line lines) (if (null? lines) "" (car (reverse lines))))
