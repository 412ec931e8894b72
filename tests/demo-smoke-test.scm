;;; The demos run headless as a user would start them (bin/demo-NAME) and
;;; end where their input says. Screenshots are checked to exist.

(import scheme (chicken base) (chicken io) (chicken process) (chicken file)
        (chicken file posix) (chicken string) (downstroke test))
(include-relative "demo-support.scm")

(test-group "demo: getting-started"
  (with-output-to-file "/tmp/ds-gs-script.scm" (lambda () (write '((0 right) (10)))))
  (test "ten frames of the right arrow move the square 30 px"
        "getting-started: square at 180 110"
        (last-line (demo-output "bin/demo-getting-started --headless --frames 30 --script /tmp/ds-gs-script.scm"))))

(test-group "demo: platformer"
  (when (file-exists? "/tmp/ds-platformer.png") (delete-file "/tmp/ds-platformer.png"))
  (let ((line (last-line (demo-output "bin/demo-platformer --headless --frames 120 --screenshot /tmp/ds-platformer.png"))))
    (test-assert "the player stands on the ground after 120 frames"
                 (substring-index "on-ground #t" line))
    (test-assert "a screenshot was saved"
                 (and (file-exists? "/tmp/ds-platformer.png")
                      (> (file-size "/tmp/ds-platformer.png") 1000)))))
