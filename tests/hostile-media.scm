;;; Run by hostile-test.scm in a child process, in a bounded address space
;;; and under a time limit: each of the issue's memory cases (a small file
;;; that asks for gigabytes) must be a prompt error here. Before the
;;; limits, each took 1.3 to 3.7 GB; a regression now ends this child
;;; (out of memory) and the parent's test fails, not the machine.
;;; Each case prints (name message).

(import scheme (chicken base) (chicken format) (chicken file) (chicken condition)
        (chicken pathname) (chicken process-context) (chicken process-context posix) srfi-4
        (downstroke sdl2) (downstroke sound) (downstroke text))

(define hm-dir (make-pathname (or (get-environment-variable "TMPDIR") "/tmp")
                              (sprintf "downstroke-hostile-media-~a" (current-process-id))))
(create-directory hm-dir #t)

(define (hm-case name thunk)
  (write (list name (handle-exceptions e ((condition-property-accessor 'exn 'message "?") e)
                      (thunk) "no error")))
  (newline))

;; A PNG signature and header that claim 20000 x 20000, and nothing else.
(define huge-png (make-pathname hm-dir "huge.png"))
(call-with-output-file huge-png
  (lambda (port)
    (write-u8vector (u8vector #x89 80 78 71 13 10 26 10 0 0 0 13 73 72 68 82
                              0 0 #x4e #x20 0 0 #x4e #x20 8 6 0 0 0 0 0 0 0)
                    port))
  #:binary)

(init!)
(define surface (create-rgba-surface! 16 16))
(define renderer (create-software-renderer! surface))
(hm-case "a 33-byte PNG of 20000 x 20000, as a texture" (lambda () (img-load-texture! renderer huge-png)))
(hm-case "the same PNG as a surface" (lambda () (img-load-surface! huge-png)))
(init-audio!)
(hm-case "load-sounds! of /dev/zero" (lambda () (load-sounds! '((z . "/dev/zero")))))
(hm-case "load-music! of /dev/zero" (lambda () (load-music! "/dev/zero")))
(shutdown-audio!)
(define font-path "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf")
(hm-case "a font of 2^32 points" (lambda () (open-font font-path 4294967296)))
(let ((font (open-font font-path 10)))
  (hm-case "a 1 MB string to draw-text!"
           (lambda () (draw-text! renderer font (make-string (* 1024 1024) #\a) 0 0))))
(define nul-path (string-append "le" (string #\x0) "vel.png"))
(hm-case "an image path with a NUL byte" (lambda () (img-load-texture! renderer nul-path)))
(init-audio!)
(hm-case "a sound path with a NUL byte" (lambda () (load-sounds! `((a . ,nul-path)))))
(shutdown-audio!)
(hm-case "a font path with a NUL byte" (lambda () (open-font nul-path 10)))
(hm-case "a font that is a device" (lambda () (open-font "/dev/zero" 10)))
(delete-directory hm-dir #t)
