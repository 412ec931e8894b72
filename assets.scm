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

(module (downstroke assets)
  (make-asset-registry asset-registry? asset-set! asset-ref asset-keys
   asset-exists? asset-remove!)

  (import scheme (chicken base) (chicken format)
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
    (reverse (registry-keys r))))
