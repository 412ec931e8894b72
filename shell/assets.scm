;;; (downstroke assets): a registry of loaded things (textures, fonts,
;;; sounds, tilemaps, prefabs ...) by key.
;;;
;;;   (define a (make-asset-registry))
;;;   (asset-set! a 'player-sheet texture)
;;;   (asset-ref a 'player-sheet)          -> texture
;;;   (asset-ref a 'missing #f)            -> #f
;;;   (asset-ref a 'missing)               -> error naming 'missing
;;;
;;; Keys are compared with equal? (symbols and strings both work). The
;;; registry only holds values: it never frees them; whoever loaded a
;;; resource frees it. asset-keys answers the keys in the order they were
;;; first set.
;;;
;;; Where a game's files are: (program-relative-path "levels/one.tmx") is
;;; the path beside the running program when it is compiled (a shipped
;;; binary finds its levels wherever it is started from), and relative to
;;; the current directory under csi, where a game is developed.

(module (downstroke assets)
  (make-asset-registry asset-registry? asset-set! asset-ref asset-keys
   asset-exists? asset-remove!
   program-directory program-relative-path)

  (import scheme (chicken base) (chicken format) (chicken pathname)
          (chicken platform) (chicken process-context)
          (only (downstroke util) make-hash-table hash-table-ref
                hash-table-set! hash-table-exists? hash-table-delete!))

  (define-record-type asset-registry
    (%make-asset-registry table keys)
    asset-registry?
    (table registry-table)
    ;; newest first
    (keys registry-keys registry-keys-set!))

  (define (make-asset-registry)
    (%make-asset-registry (make-hash-table equal?) '()))

  (define (check who r)
    (unless (asset-registry? r)
      (error who "not an asset registry" r)))

  (define (asset-set! r key value)
    (check 'asset-set! r)
    (unless (hash-table-exists? (registry-table r) key)
      (registry-keys-set! r (cons key (registry-keys r))))
    (hash-table-set! (registry-table r) key value)
    (void))

  (define none (list 'none))

  (define (asset-ref r key #!optional (default none))
    (check 'asset-ref r)
    (hash-table-ref (registry-table r) key
                    (lambda ()
                      (if (eq? default none)
                          (error 'asset-ref
                                 (sprintf "no asset named ~s (known: ~s)" key (asset-keys r))
                                 key)
                          default))))

  (define (asset-exists? r key)
    (check 'asset-exists? r)
    (hash-table-exists? (registry-table r) key))

  (define (asset-remove! r key)
    (check 'asset-remove! r)
    (when (hash-table-exists? (registry-table r) key)
      (hash-table-delete! (registry-table r) key)
      (registry-keys-set! r (let loop ((ks (registry-keys r)) (acc '()))
                              (cond ((null? ks) (reverse acc))
                                    ((equal? (car ks) key) (append (reverse acc) (cdr ks)))
                                    (else (loop (cdr ks) (cons (car ks) acc)))))))
    (void))

  (define (asset-keys r)
    (check 'asset-keys r)
    (reverse (registry-keys r)))

  ;; A compiled program's own directory (CHICKEN reads it from the system,
  ;; /proc/self/exe on Linux); csi's would be /usr/bin, so under csi the
  ;; current directory stands for the game's.
  (define (program-directory)
    (let ((exe (and (not (feature? #:csi)) (executable-pathname))))
      (if exe
          (or (pathname-directory exe) (current-directory))
          (current-directory))))

  (define (program-relative-path path)
    (unless (string? path)
      (error 'program-relative-path "the path must be a string" path))
    (if (absolute-pathname? path)
        path
        (make-pathname (program-directory) path))))
