;;; The browser's save data surviving a reload (tools/web-test.py): each
;;; start prints how many starts this browser's storage has seen, then
;;; counts this one with game-save!.
(import scheme (chicken base) (downstroke engine))

(define game (make-game title: "Saves" org: "downstroke-tests" app: "web-save"))

(let ((seen (game-load game 'starts 0)))
  (print "web-save: starts before this one: " seen)
  (game-save! game 'starts (+ seen 1))
  (print "web-save: saved " (+ seen 1)))
