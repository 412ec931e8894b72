;;; Empty on purpose: the source of the downstroke.X-libraries components,
;;; whose static object tools/egg-csc replaces with a linker script naming
;;; the C libraries downstroke.X links (see that file).
