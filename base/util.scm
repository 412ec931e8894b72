;;; (downstroke util): list and hash-table utilities.
;;;
;;; A stand-in for the parts of SRFI 1 (lists) and SRFI 69 (hash tables) the
;;; library needs. CHICKEN 5 core has only foldl/foldr and no usable hash
;;; table, and the srfi-1 / srfi-69 eggs cannot be installed here. Names and
;;; argument orders follow the SRFIs, so callers can later import the eggs
;;; instead without changes.
;;;
;;; Every list procedure is iterative (accumulate, then reverse) so that long
;;; lists never grow the stack.
;;;
;;; Hash tables are a vector of buckets (lists of (key . value) entries) that
;;; doubles when the load factor passes 3/4. Keys are hashed by our own
;;; functions below. Objects that cannot be hashed by value for a given
;;; equality (records, procedures, and, for eq?/eqv? tables, any mutable
;;; object such as a pair, string or vector) all hash to one fixed value: they
;;; share a bucket that is scanned with the table's equality. That stays
;;; correct, but lookups for such keys are linear in their number.

(module (downstroke util)
  (;; SRFI 1
   filter remove partition any every find find-tail count iota take drop
   take-while drop-while last append-map filter-map delete delete-duplicates
   list-index fold reduce append-reverse
   ;; for lists as long as the input: CHICKEN 5.3's apply does not return
   ;; with about 32,000 arguments, so (apply max l) is not an option
   list-min list-max string-concatenate
   ;; SRFI 69
   make-hash-table hash-table? hash-table-ref hash-table-ref/default
   hash-table-set! hash-table-delete! hash-table-exists? hash-table-update!
   hash-table-update!/default hash-table-count hash-table-keys
   hash-table-values hash-table-walk hash-table-fold hash-table->alist
   alist->hash-table hash-table-copy)

  (import scheme (chicken base) (chicken fixnum) (chicken keyword)
          (only srfi-4 f64vector f64vector->blob/shared
                blob->u16vector/shared u16vector-ref))

  ;;; ------------------------------------------------------------------
  ;;; Lists

  ;; With several lists, SRFI 1 procedures stop at the shortest. These two
  ;; helpers give the heads and the tails of all lists, or #f when one ran out.
  (define (%any-null? lists)
    (let loop ((ls lists))
      (cond ((null? ls) #f)
            ((null? (car ls)) #t)
            (else (loop (cdr ls))))))

  (define (%cars lists)
    (let loop ((ls lists) (acc '()))
      (if (null? ls) (reverse acc) (loop (cdr ls) (cons (caar ls) acc)))))

  (define (%cdrs lists)
    (let loop ((ls lists) (acc '()))
      (if (null? ls) (reverse acc) (loop (cdr ls) (cons (cdar ls) acc)))))

  (define (filter pred lst)
    (let loop ((l lst) (acc '()))
      (cond ((null? l) (reverse acc))
            ((pred (car l)) (loop (cdr l) (cons (car l) acc)))
            (else (loop (cdr l) acc)))))

  (define (remove pred lst)
    (filter (lambda (x) (not (pred x))) lst))

  (define (partition pred lst)
    (let loop ((l lst) (in '()) (out '()))
      (cond ((null? l) (values (reverse in) (reverse out)))
            ((pred (car l)) (loop (cdr l) (cons (car l) in) out))
            (else (loop (cdr l) in (cons (car l) out))))))

  ;; any returns the true value of pred; the last call is a tail call, as
  ;; SRFI 1 requires.
  (define (any pred lst . more)
    (if (null? more)
        (and (pair? lst)
             (let loop ((l lst))
               (if (null? (cdr l))
                   (pred (car l))
                   (or (pred (car l)) (loop (cdr l))))))
        (let loop ((ls (cons lst more)))
          (and (not (%any-null? ls))
               (let ((tails (%cdrs ls)))
                 (if (%any-null? tails)
                     (apply pred (%cars ls))
                     (or (apply pred (%cars ls)) (loop tails))))))))

  ;; every returns #t for empty input, else the value of the last call.
  (define (every pred lst . more)
    (if (null? more)
        (or (null? lst)
            (let loop ((l lst))
              (if (null? (cdr l))
                  (pred (car l))
                  (and (pred (car l)) (loop (cdr l))))))
        (let loop ((ls (cons lst more)))
          (or (%any-null? ls)
              (let ((tails (%cdrs ls)))
                (if (%any-null? tails)
                    (apply pred (%cars ls))
                    (and (apply pred (%cars ls)) (loop tails))))))))

  (define (find-tail pred lst)
    (let loop ((l lst))
      (cond ((null? l) #f)
            ((pred (car l)) l)
            (else (loop (cdr l))))))

  (define (find pred lst)
    (let ((tail (find-tail pred lst)))
      (and tail (car tail))))

  (define (count pred lst . more)
    (if (null? more)
        (let loop ((l lst) (n 0))
          (if (null? l) n (loop (cdr l) (if (pred (car l)) (+ n 1) n))))
        (let loop ((ls (cons lst more)) (n 0))
          (if (%any-null? ls)
              n
              (loop (%cdrs ls) (if (apply pred (%cars ls)) (+ n 1) n))))))

  ;; Each element is start + i*step (not a running sum), so inexact steps
  ;; do not accumulate rounding error.
  (define (iota n #!optional (start 0) (step 1))
    (unless (and (integer? n) (exact? n) (>= n 0))
      (error 'iota "count must be a non-negative exact integer" n))
    (let loop ((i (- n 1)) (acc '()))
      (if (< i 0)
          acc
          (loop (- i 1) (cons (+ start (* i step)) acc)))))

  (define (take lst k)
    (let loop ((l lst) (k k) (acc '()))
      (cond ((zero? k) (reverse acc))
            ((pair? l) (loop (cdr l) (- k 1) (cons (car l) acc)))
            (else (error 'take "list too short" lst)))))

  (define (drop lst k)
    (let loop ((l lst) (k k))
      (cond ((zero? k) l)
            ((pair? l) (loop (cdr l) (- k 1)))
            (else (error 'drop "list too short" lst)))))

  (define (take-while pred lst)
    (let loop ((l lst) (acc '()))
      (if (and (pair? l) (pred (car l)))
          (loop (cdr l) (cons (car l) acc))
          (reverse acc))))

  (define (drop-while pred lst)
    (let loop ((l lst))
      (if (and (pair? l) (pred (car l)))
          (loop (cdr l))
          l)))

  (define (last lst)
    (unless (pair? lst) (error 'last "empty list" lst))
    (let loop ((l lst))
      (if (pair? (cdr l)) (loop (cdr l)) (car l))))

  (define (append-reverse rev-head tail)
    (let loop ((l rev-head) (acc tail))
      (if (null? l) acc (loop (cdr l) (cons (car l) acc)))))

  (define (append-map f lst . more)
    (let loop ((ls (cons lst more)) (acc '()))
      (if (%any-null? ls)
          (reverse acc)
          (loop (%cdrs ls) (append-reverse (apply f (%cars ls)) acc)))))

  (define (filter-map f lst . more)
    (let loop ((ls (cons lst more)) (acc '()))
      (if (%any-null? ls)
          (reverse acc)
          (let ((v (apply f (%cars ls))))
            (loop (%cdrs ls) (if v (cons v acc) acc))))))

  ;; SRFI 1 calls (= x element), x first.
  (define (delete x lst #!optional (= equal?))
    (filter (lambda (y) (not (= x y))) lst))

  (define (list-index pred lst . more)
    (let loop ((ls (cons lst more)) (i 0))
      (cond ((%any-null? ls) #f)
            ((apply pred (%cars ls)) i)
            (else (loop (%cdrs ls) (+ i 1))))))

  (define (fold kons knil lst . more)
    (if (null? more)
        (let loop ((l lst) (acc knil))
          (if (null? l) acc (loop (cdr l) (kons (car l) acc))))
        (let loop ((ls (cons lst more)) (acc knil))
          (if (%any-null? ls)
              acc
              (loop (%cdrs ls) (apply kons (append (%cars ls) (list acc))))))))

  (define (reduce f ridentity lst)
    (if (null? lst) ridentity (fold f (car lst) (cdr lst))))

  ;; The least and greatest number of a non-empty list, in one walk.
  (define (list-min lst)
    (when (null? lst) (error 'list-min "empty list"))
    (foldl min (car lst) (cdr lst)))

  (define (list-max lst)
    (when (null? lst) (error 'list-max "empty list"))
    (foldl max (car lst) (cdr lst)))

  ;; The strings of a list joined, in one copy of each.
  (define (string-concatenate strings)
    (let* ((total (foldl (lambda (n s) (+ n (string-length s))) 0 strings))
           (out (make-string total)))
      (let loop ((ss strings) (at 0))
        (if (null? ss)
            out
            (let ((n (string-length (car ss))))
              (let copy ((i 0))
                (when (< i n)
                  (string-set! out (+ at i) (string-ref (car ss) i))
                  (copy (+ i 1))))
              (loop (cdr ss) (+ at n)))))))

  ;;; ------------------------------------------------------------------
  ;;; Hashing

  ;; Hash values stay below 2^28 so mixing arithmetic never leaves the
  ;; fixnum range, even on 32-bit builds.
  (define hash-mask #xFFFFFFF)

  ;; h * c mod 2^28 for h < 2^28 and odd c < 2^14, done in two halves so
  ;; no intermediate product exceeds 2^28.
  (define (mul28 h c)
    (fxand (fx+ (fx* (fxand h #x3FFF) c)
                (fxshl (fxand (fx* (fxshr h 14) c) #x3FFF) 14))
           hash-mask))

  ;; Fold x into h (xor, then multiply: FNV-1a style).
  (define (mix h x)
    (let ((v (mul28 (fxxor h (fxand x hash-mask)) 9719)))
      (fxxor v (fxshr v 15))))

  ;; Spread the bits so a power-of-two bucket count uses all of them.
  (define (scramble h)
    (let* ((h (fxxor h (fxshr h 14)))
           (h (mul28 h 12829))
           (h (fxxor h (fxshr h 13)))
           (h (mul28 h 10271)))
      (fxxor h (fxshr h 15))))

  (define (string-hash* s salt)
    (let ((n (string-length s)))
      (let loop ((i 0) (h (fx+ salt n)))
        (if (fx= i n)
            h
            (loop (fx+ i 1) (mix h (char->integer (string-ref s i))))))))

  ;; Exact integers of any size: fold the value in 24-bit chunks. A fixnum
  ;; folds its bits from 28 and 56 up; the second shift is two of 28, since
  ;; a shift by 56 is undefined where fixnums are 31 bits wide (wasm32).
  (define (integer-hash n)
    (if (fixnum? n)
        (fxand (fxxor n (let ((high (fxshr n 28))) (fxxor high (fxshr high 28)))) hash-mask)
        (let loop ((m (abs n)) (h (if (negative? n) 7 3)))
          (if (zero? m)
              h
              (loop (quotient m 16777216)
                    (mix h (remainder m 16777216)))))))

  ;; A flonum is hashed by its IEEE bits. eqv? (and so equal?) tells 0.0 from
  ;; -0.0, whose bits differ; all NaNs share one hash, since NaN bit patterns
  ;; vary and NaN keys can never be found by value anyway. The bits are read
  ;; as four 16-bit words, each a fixnum on every platform (a 32-bit word may
  ;; not be one where fixnums are 31 bits wide).
  (define (flonum-hash x)
    (if (not (= x x))
        17
        (let ((words (blob->u16vector/shared
                      (f64vector->blob/shared (f64vector x)))))
          (mix (mix (mix (mix 11 (u16vector-ref words 0)) (u16vector-ref words 1))
                    (u16vector-ref words 2))
               (u16vector-ref words 3)))))

  (define (number-hash x)
    (cond ((fixnum? x) (integer-hash x))
          ((flonum? x) (flonum-hash x))
          ((exact-integer? x) (integer-hash x))
          ((and (exact? x) (rational? x))
           (mix (integer-hash (numerator x)) (integer-hash (denominator x))))
          ((not (real? x))        ; complex
           (mix (number-hash (real-part x)) (number-hash (imag-part x))))
          (else 19)))

  ;; Hash of a value that eqv? compares by value: numbers, characters,
  ;; symbols, keywords, booleans and the empty list. Anything else gets #f.
  (define (atom-hash x)
    (cond ((number? x) (number-hash x))
          ((symbol? x) (string-hash* (symbol->string x) 101))
          ((keyword? x) (string-hash* (keyword->string x) 211))
          ((char? x) (mix 23 (char->integer x)))
          ((eq? x #t) 29)
          ((eq? x #f) 31)
          ((null? x) 37)
          (else #f)))

  ;; Objects with no value hash (records, procedures, ports...) share this.
  (define shared-hash 41)

  (define (eqv-hash x)
    (or (atom-hash x) shared-hash))

  ;; equal? looks inside pairs, vectors and strings. Depth and breadth are
  ;; bounded so long or cyclic-looking structures cost a fixed amount; equal
  ;; structures still agree on the part that is looked at.
  (define (equal-hash x)
    (let walk ((x x) (depth 4))
      (cond ((atom-hash x))
            ((string? x) (string-hash* x 307))
            ((fx= depth 0) 43)
            ((pair? x)
             (let loop ((l x) (i 0) (h 47))
               (cond ((fx= i 8) h)
                     ((pair? l)
                      (loop (cdr l) (fx+ i 1) (mix h (walk (car l) (fx- depth 1)))))
                     ((null? l) h)
                     (else (mix h (walk l (fx- depth 1)))))))
            ((vector? x)
             (let ((n (vector-length x)))
               (let loop ((i 0) (h (mix 53 n)))
                 (if (or (fx= i n) (fx= i 8))
                     h
                     (loop (fx+ i 1)
                           (mix h (walk (vector-ref x i) (fx- depth 1))))))))
            (else shared-hash))))

  (define (string=-hash s)
    (string-hash* s 307))

  ;;; ------------------------------------------------------------------
  ;;; Hash tables

  (define-record-type hash-table
    (%make-hash-table equiv hash buckets size)
    hash-table?
    (equiv ht-equiv)
    (hash ht-hash)
    (buckets ht-buckets set-ht-buckets!)
    (size ht-size set-ht-size!))

  (define initial-buckets 16)

  ;; The hash for a known equality. eq? uses the eqv? hash: equal by eq?
  ;; implies equal by eqv?, so equal keys always share a hash.
  (define (hash-for equiv)
    (cond ((eq? equiv equal?) equal-hash)
          ((eq? equiv eqv?) eqv-hash)
          ((eq? equiv eq?) eqv-hash)
          ((eq? equiv string=?) string=-hash)
          (else #f)))

  ;; (make-hash-table [equality [hash]]). A custom equality needs its hash.
  (define (make-hash-table #!optional (equiv equal?) hash #!rest _)
    (let ((hash (or hash (hash-for equiv)
                    (error 'make-hash-table
                           "no hash function for this equality; pass one"
                           equiv))))
      (%make-hash-table equiv hash (make-vector initial-buckets '()) 0)))

  (define (check-table who t)
    (unless (hash-table? t) (error who "not a hash table" t)))

  (define (bucket-index t key)
    (fxand (scramble ((ht-hash t) key))
           (fx- (vector-length (ht-buckets t)) 1)))

  ;; The (key . value) entry for key, or #f.
  (define (lookup t key)
    (let ((equiv (ht-equiv t)))
      (let loop ((b (vector-ref (ht-buckets t) (bucket-index t key))))
        (cond ((null? b) #f)
              ((equiv key (caar b)) (car b))
              (else (loop (cdr b)))))))

  ;; Double the bucket vector; entries are moved, not copied.
  (define (grow! t)
    (let* ((old (ht-buckets t))
           (new (make-vector (fx* 2 (vector-length old)) '())))
      (set-ht-buckets! t new)
      (let loop ((i 0))
        (when (fx< i (vector-length old))
          (let move ((b (vector-ref old i)))
            (unless (null? b)
              (let ((j (bucket-index t (caar b))))
                (vector-set! new j (cons (car b) (vector-ref new j))))
              (move (cdr b))))
          (loop (fx+ i 1))))))

  (define (insert! t key value)
    (let ((i (bucket-index t key))
          (buckets (ht-buckets t)))
      (vector-set! buckets i (cons (cons key value) (vector-ref buckets i)))
      (set-ht-size! t (fx+ (ht-size t) 1))
      ;; load factor 3/4
      (when (fx> (fx* 4 (ht-size t)) (fx* 3 (vector-length buckets)))
        (grow! t))))

  (define (hash-table-ref t key #!optional missing found)
    (check-table 'hash-table-ref t)
    (let ((e (lookup t key)))
      (cond ((and e found) (found (cdr e)))
            (e (cdr e))
            (missing (missing))
            (else (error 'hash-table-ref "key not found" key)))))

  (define (hash-table-ref/default t key default)
    (check-table 'hash-table-ref/default t)
    (let ((e (lookup t key)))
      (if e (cdr e) default)))

  (define (hash-table-set! t key value)
    (check-table 'hash-table-set! t)
    (let ((e (lookup t key)))
      (if e (set-cdr! e value) (insert! t key value))))

  (define (hash-table-delete! t key)
    (check-table 'hash-table-delete! t)
    (let* ((buckets (ht-buckets t))
           (i (bucket-index t key))
           (equiv (ht-equiv t)))
      (let loop ((b (vector-ref buckets i)) (kept '()))
        (cond ((null? b) (void))
              ((equiv key (caar b))
               (vector-set! buckets i (append-reverse kept (cdr b)))
               (set-ht-size! t (fx- (ht-size t) 1)))
              (else (loop (cdr b) (cons (car b) kept)))))))

  (define (hash-table-exists? t key)
    (check-table 'hash-table-exists? t)
    (and (lookup t key) #t))

  (define (hash-table-update! t key proc #!optional missing)
    (check-table 'hash-table-update! t)
    (let ((e (lookup t key)))
      (cond (e (set-cdr! e (proc (cdr e))))
            (missing (insert! t key (proc (missing))))
            (else (error 'hash-table-update! "key not found" key)))))

  (define (hash-table-update!/default t key proc default)
    (check-table 'hash-table-update!/default t)
    (let ((e (lookup t key)))
      (if e
          (set-cdr! e (proc (cdr e)))
          (insert! t key (proc default)))))

  (define (hash-table-count t)
    (check-table 'hash-table-count t)
    (ht-size t))

  ;; (kons key value acc) over every entry, in bucket order.
  (define (hash-table-fold t kons knil)
    (check-table 'hash-table-fold t)
    (let ((buckets (ht-buckets t)))
      (let loop ((i 0) (acc knil))
        (if (fx= i (vector-length buckets))
            acc
            (loop (fx+ i 1)
                  (let inner ((b (vector-ref buckets i)) (acc acc))
                    (if (null? b)
                        acc
                        (inner (cdr b) (kons (caar b) (cdar b) acc)))))))))

  (define (hash-table-walk t proc)
    (hash-table-fold t (lambda (k v acc) (proc k v)) (void))
    (void))

  (define (hash-table-keys t)
    (hash-table-fold t (lambda (k v acc) (cons k acc)) '()))

  (define (hash-table-values t)
    (hash-table-fold t (lambda (k v acc) (cons v acc)) '()))

  (define (hash-table->alist t)
    (hash-table-fold t (lambda (k v acc) (cons (cons k v) acc)) '()))

  ;; As SRFI 69 says, the first association of a repeated key wins.
  (define (alist->hash-table alist #!optional (equiv equal?) hash #!rest _)
    (let ((t (make-hash-table equiv hash)))
      (for-each (lambda (p)
                  (unless (lookup t (car p)) (insert! t (car p) (cdr p))))
                alist)
      t))

  ;; The optional mutable? argument of SRFI 69 is accepted; copies are
  ;; always mutable.
  (define (hash-table-copy t #!optional mutable?)
    (check-table 'hash-table-copy t)
    (let* ((old (ht-buckets t))
           (new (make-vector (vector-length old) '())))
      (let loop ((i 0))
        (when (fx< i (vector-length old))
          (vector-set! new i (map (lambda (e) (cons (car e) (cdr e)))
                                  (vector-ref old i)))
          (loop (fx+ i 1))))
      (%make-hash-table (ht-equiv t) (ht-hash t) new (ht-size t))))

  ;; delete-duplicates keeps first occurrences in order. For the standard
  ;; equalities a table of seen elements makes it linear; any other = is
  ;; checked against every kept element, called as (= earlier later).
  (define (delete-duplicates lst #!optional (= equal?))
    (if (hash-for =)
        (let ((seen (make-hash-table =)))
          (let loop ((l lst) (acc '()))
            (cond ((null? l) (reverse acc))
                  ((lookup seen (car l)) (loop (cdr l) acc))
                  (else (insert! seen (car l) #t)
                        (loop (cdr l) (cons (car l) acc))))))
        (let loop ((l lst) (acc '()))
          (cond ((null? l) (reverse acc))
                ((any (lambda (kept) (= kept (car l))) acc) (loop (cdr l) acc))
                (else (loop (cdr l) (cons (car l) acc)))))))
  )
