;;; (downstroke keywords): keyword arguments that are checked. CHICKEN's
;;; #!key drops a keyword it does not know, so (make-game widht: 320) would
;;; quietly keep the default width. A procedure defined with
;;;   (define/keywords (make-game #!key (title "x") (width 640)) body ...)
;;; is an ordinary #!key procedure that first checks its keyword arguments:
;;; an unknown one is an error naming the procedure, the keyword and the
;;; nearest valid ones,
;;;   make-game: unknown keyword widht: (did you mean width:?)
;;; and a keyword without a value, or a value where a keyword should be,
;;; is an error too. The check is a walk over the arguments given, a few
;;; memq calls: nothing that a frame would notice.

(module (downstroke keywords)
  (define/keywords
   ;; for sibling modules only: what define/keywords expands into, and the
   ;; distance and the slip (downstroke check), the map loader and the
   ;; input configuration measure misspelt names with
   check-keywords edit-distance one-slip?)

  (import scheme (chicken base) (chicken format) (chicken keyword) (chicken string))
  (import-for-syntax (chicken keyword))

  (define-syntax define/keywords
    (er-macro-transformer
     (lambda (form rename compare)
       (let* ((head (cadr form))
              (body (cddr form))
              (name (car head))
              (formals (cdr head))
              (rest (rename 'keyword-arguments)))
         (let split ((fs formals) (before '()))
           (cond ((null? fs)
                  ;; no #!key: nothing to check
                  `(,(rename 'define) ,head ,@body))
                 ((eq? (car fs) '#!key)
                  (let ((keys (map (lambda (k) (string->keyword (symbol->string (if (pair? k) (car k) k))))
                                   (cdr fs))))
                    `(,(rename 'define) (,name ,@(reverse before) #!rest ,rest ,@fs)
                      (,(rename 'check-keywords) ',name ,rest ',keys)
                      ,@body)))
                 (else (split (cdr fs) (cons (car fs) before)))))))))

  ;; Levenshtein distance of two strings.
  (define (edit-distance a b)
    (let* ((n (string-length b))
           (row (let make ((j 0)) (if (> j n) '() (cons j (make (+ j 1)))))))
      (let loop ((i 0) (prev row))
        (if (= i (string-length a))
            (list-ref prev n)
            (loop (+ i 1)
                  (let next ((j 1) (prev prev) (out (list (+ i 1))))
                    (if (> j n)
                        (reverse out)
                        (let ((cost (if (char=? (string-ref a i) (string-ref b (- j 1))) 0 1)))
                          (next (+ j 1) (cdr prev)
                                (cons (min (+ (car out) 1) (+ (cadr prev) 1) (+ (car prev) cost))
                                      out))))))))))

  ;; Whether b is one slip of the fingers from a: one edit, or two
  ;; neighbouring characters swapped (two edits to edit-distance).
  (define (one-slip? a b)
    (or (= 1 (edit-distance a b))
        (and (= (string-length a) (string-length b))
             (let loop ((i 0))
               (cond ((>= (+ i 1) (string-length a)) #f)
                     ((char=? (string-ref a i) (string-ref b i)) (loop (+ i 1)))
                     (else (and (char=? (string-ref a i) (string-ref b (+ i 1)))
                                (char=? (string-ref a (+ i 1)) (string-ref b i))
                                (string=? (substring a (+ i 2)) (substring b (+ i 2))))))))))

  (define (kw->string k) (string-append (keyword->string k) ":"))

  ;; The valid keywords nearest to k (within two edits), as "a: or b:".
  (define (suggestion k valid)
    (let* ((s (keyword->string k))
           (scored (map (lambda (v) (cons (edit-distance s (keyword->string v)) v)) valid))
           (best (foldl (lambda (m p) (min m (car p))) 3 scored)))
      (and (<= best 2)
           (string-intersperse
            (map (lambda (p) (kw->string (cdr p)))
                 (filter-best best scored))
            " or "))))

  (define (filter-best best scored)
    (cond ((null? scored) '())
          ((= (caar scored) best) (cons (car scored) (filter-best best (cdr scored))))
          (else (filter-best best (cdr scored)))))

  (define (check-keywords who args valid)
    (let loop ((as args))
      (cond ((null? as) (void))
            ((not (keyword? (car as)))
             (error (sprintf "~a: expected a keyword, got ~s (keywords: ~a)"
                                 who (car as) (string-intersperse (map kw->string valid) " "))))
            ((null? (cdr as))
             (error (sprintf "~a: keyword ~a has no value" who (kw->string (car as)))))
            ((memq (car as) valid) (loop (cddr as)))
            (else
             (let ((near (suggestion (car as) valid)))
               (error (if near
                              (sprintf "~a: unknown keyword ~a (did you mean ~a?)"
                                       who (kw->string (car as)) near)
                              (sprintf "~a: unknown keyword ~a (keywords: ~a)"
                                       who (kw->string (car as))
                                       (string-intersperse (map kw->string valid) " "))))))))))
