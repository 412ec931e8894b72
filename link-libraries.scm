;;; Stands for the C libraries the egg links: tools/egg-csc replaces its
;;; static object with a linker script naming them (see that file).
(module (downstroke link-libraries) ())
