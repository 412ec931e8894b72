(import (downstroke test) (downstroke assets)
        scheme (chicken base) (chicken string))

;;; Helpers (prefixed as- because every suite is loaded into one toplevel).

(define (as-says? . parts)
  (lambda (exn)
    (let ((text (error-text exn)))
      (let loop ((parts parts))
        (or (null? parts)
            (and (substring-index (car parts) text) (loop (cdr parts))))))))

(test-group "assets"
  (let ((a (make-asset-registry)))
    (test-assert "a registry" (asset-registry? a))
    (test "empty" '() (asset-keys a))
    (asset-set! a 'player-sheet 'texture-1)
    (asset-set! a "font" '(font 12))
    (asset-set! a 'jump 42)
    (test "symbol key" 'texture-1 (asset-ref a 'player-sheet))
    (test "string key (equal?)" '(font 12) (asset-ref a (string-append "fo" "nt")))
    (test "keys in insertion order" '(player-sheet "font" jump) (asset-keys a))
    (asset-set! a 'player-sheet 'texture-2)
    (test "replaced" 'texture-2 (asset-ref a 'player-sheet))
    (test "replacing keeps the key's place" '(player-sheet "font" jump) (asset-keys a))
    (test "default for a missing key" 'none (asset-ref a 'ghost 'none))
    (test "#f as a default" #f (asset-ref a 'ghost #f))
    (test "a stored #f is returned, not the default"
          #f (begin (asset-set! a 'off #f) (asset-ref a 'off 'dflt)))
    (test-error "missing key without default names it" (as-says? "ghost")
                (asset-ref a 'ghost))
    (test-assert "exists" (asset-exists? a 'jump))
    (asset-remove! a 'jump)
    (test "removed" #f (asset-exists? a 'jump))
    (test "removed from keys" '(player-sheet "font" off) (asset-keys a))
    (asset-remove! a 'jump)
    (test "removing twice is harmless" '(player-sheet "font" off) (asset-keys a)))

  (test-group "registries are independent"
    (let ((a (make-asset-registry)) (b (make-asset-registry)))
      (asset-set! a 'k 1)
      (test "b does not see a's key" 'no (asset-ref b 'k 'no))))

  (test-group "many keys"
    (let ((a (make-asset-registry)))
      (do ((i 0 (+ i 1))) ((= i 1000))
        (asset-set! a (string->symbol (conc "tile-" i)) i))
      (test "1000 keys" 1000 (length (asset-keys a)))
      (test "lookup after growth" 777 (asset-ref a 'tile-777))))

  (test-group "errors"
    (test-error "not a registry" (as-says? "asset registry") (asset-ref '() 'k))
    (test-error "asset-set! on a non-registry" (as-says? "asset registry")
                (asset-set! 'x 'k 1))))

;; Under csi (as the suites run) the program's directory is the current
;; one; a compiled game's is its binary's, which the guide's shipping
;; example checks by running a static build from another directory.
(test-group "assets: program-relative-path"
  (import (chicken process-context))
  (test "under csi, relative to the current directory"
        (string-append (current-directory) "/levels/one.tmx")
        (program-relative-path "levels/one.tmx"))
  (test "an absolute path is kept" "/srv/one.tmx" (program-relative-path "/srv/one.tmx"))
  (test "program-directory is the current directory under csi"
        (current-directory) (program-directory))
  (test-error "not a string" (as-says? "the path must be a string")
              (program-relative-path 'levels)))
