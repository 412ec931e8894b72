;;; The README's minimal game is run as written, and must print what its
;;; "; prints" comment says, so the example cannot go stale.

(import scheme (chicken base) (chicken io) (chicken port) (chicken string)
        (downstroke test))

;; The lines of the first scheme block after the heading `heading`.
(define (org-block file heading)
  (let* ((lines (with-input-from-file file read-lines))
         (after-heading (member heading lines))
         (start (let loop ((ls after-heading))
                  (if (substring-index "#+begin_src scheme" (car ls)) (cdr ls) (loop (cdr ls))))))
    (let loop ((ls start) (out '()))
      (if (substring-index "#+end_src" (car ls))
          (reverse out)
          (loop (cdr ls) (cons (car ls) out))))))

(define (promised-output lines)
  (let loop ((ls lines))
    (cond ((null? ls) #f)
          ((substring-index "; prints " (car ls))
           => (lambda (i) (substring (car ls) (+ i (string-length "; prints ")))))
          (else (loop (cdr ls))))))

(test-group "README: a minimal game"
  (let* ((lines (org-block "../README.org" "* A minimal game"))
         (program (string-intersperse lines "\n"))
         (printed (with-output-to-string
                    (lambda ()
                      (with-input-from-string program
                        (lambda ()
                          (let loop ((form (read)))
                            (unless (eof-object? form)
                              (eval form)
                              (loop (read))))))))))
    (test-assert "the example promises an output" (promised-output lines))
    (test "it prints what it promises" (string-append (promised-output lines) "\n") printed)))
