(import scheme (chicken base) (downstroke util))

(define scores (make-hash-table))
(for-each (lambda (p) (hash-table-update!/default scores (car p) (lambda (s) (+ s (cdr p))) 0))
          '((ann . 3) (bob . 5) (ann . 4)))
(print (filter odd? (iota 10)) " " (hash-table-ref/default scores 'ann 0)
       " " (list-max (hash-table-values scores)))
