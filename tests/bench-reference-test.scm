;;; bench/reference/scenes.c, S1, S2 and S5 in plain C, against bench/scenes.scm:
;;; for the same arguments both print the same checksum lines, so the C
;;; figures docs/performance.org compares with are the same scenes
;;; ("Against a plain C implementation"). A change to either side's rules
;;; shows here. Small crowds and few frames: a few seconds, no times.
;;; `make check` builds both programs in build/; run on its own, or where
;;; they are missing or older than their source, the suite builds them.

(import scheme (chicken base) (chicken io) (chicken process) (chicken format)
        (chicken string) (chicken file) (chicken file posix) (chicken pathname)
        (downstroke test))

(define root (normalize-pathname (make-pathname (current-directory) "..")))
(define (from-root . parts) (string-intersperse (cons root parts) "/"))
(define work (create-temporary-directory))

;; build/NAME when it is newer than its source, else a copy built here
;; by `command` (a format string given the source and the output).
(define (program name source command)
  (let ((built (from-root "build" name)) (src (from-root source)))
    (if (and (file-exists? built) (>= (file-modification-time built) (file-modification-time src)))
        built
        (let ((out (make-pathname work name)))
          (system (sprintf command (qs src) (qs out)))
          (and (file-exists? out) out)))))

(define scenes
  (program "bench-scenes" "bench/scenes.scm"
           (string-append "cd " (qs work) " && csc -O2 -d0 ~a -o ~a >/dev/null")))
(define reference (program "bench-reference" "bench/reference/scenes.c" "cc -O2 ~a -o ~a -lm"))

;; The checksum lines a program prints for these arguments, in order.
(define (checksums program args)
  (if program
      (let ((lines (with-input-from-pipe
                    (sprintf "cd ~a && ~a --runs 1 --csv ~a ~a" (qs root) (qs program)
                             (qs (make-pathname work (sprintf "~a.csv" (pathname-file program)))) args)
                    read-lines)))
        (let keep ((ls lines) (out '()))
          (cond ((null? ls) (reverse out))
                ((substring=? (car ls) "checksum ") (keep (cdr ls) (cons (car ls) out)))
                (else (keep (cdr ls) out)))))
      '()))

(test-group "both programs are built"
  (test-assert "bench-scenes" scenes)
  (test-assert "bench-reference" reference))

;; args, and how many checksum lines they make (one per scene instance)
(define cases
  '(("S1 --n 100" 2)                               ; the scene as defined, both modes
    ("S1 --n 1000 --warm-up 60 --frames 70" 2)     ; a jump at frame 60 on the ground
    ("S2 --n 100 --mode flonum" 1)
    ("S2 --n 1000 --mode flonum --warm-up 10 --frames 50" 1)    ; sums not whole
    ("S5 --n 1000 --mode flonum" 1)
    ;; by frame 48 pushes have made exact coordinates no double holds
    ("S5 --n 4000 --mode flonum --warm-up 0 --frames 50" 1)))

(for-each
 (lambda (c)
   (let ((args (car c)) (lines (cadr c)))
     (test-group args
       (let ((lisp (checksums scenes args)) (c (checksums reference args)))
         (test (sprintf "bench-scenes prints ~a checksum lines" lines) lines (length lisp))
         (test "bench-reference prints the same ones" lisp c)))))
 cases)

(system (sprintf "rm -rf ~a" (qs work)))
(test-exit)
