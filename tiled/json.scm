;;; (downstroke json): a small strict JSON reader (RFC 8259), pure Scheme.
;;; CHICKEN has none in core and the loader of Tiled's JSON formats needs
;;; one that never crashes and names where the input is wrong.
;;;
;;; Values: an object is a `json-object` record (its members an alist of
;;; (key-string . value) in document order; a key written twice keeps its
;;; first value for json-ref), an array a vector, a string a string (UTF-8;
;;; \u escapes are encoded, surrogate pairs joined, a lone surrogate is an
;;; error), a number an exact integer when written without a fraction or an
;;; exponent and a flonum otherwise, true/false #t/#f, null the symbol null.
;;;
;;; Numbers: a flonum is the double nearest the decimal written (correctly
;;; rounded, however many digits); one too large for a double is an error,
;;; one too small is 0.0. An integer may have at most
;;; json-max-integer-digits digits (RFC 8259 lets a reader limit numbers):
;;; CHICKEN converts a long integer in time quadratic in its digits, and no
;;; Tiled value needs more than ten.
;;;
;;; Strict: nothing but JSON is accepted (no comments, no trailing commas,
;;; no single quotes, no leading zeros, no raw control characters in
;;; strings, no byte sequence that is not UTF-8 as RFC 3629 defines it
;;; (overlong forms, surrogates and bytes F5-FF included), nothing after the
;;; value but whitespace); a UTF-8 byte order mark at the start is skipped.
;;; Nesting deeper than json-max-depth is an error. Time is linear in the
;;; input: arrays and objects are built by consing and one reverse, never
;;; with apply, and a number costs at most a bounded amount beyond reading
;;; its digits.
;;;
;;; Errors are conditions of kinds exn and json (property `file`), whose
;;; message is "SOURCE: line L, column C: what is wrong" (without "SOURCE: "
;;; when the source is #f).
(module (downstroke json)
  (json-parse-string json-read-file json-object? json-object-members
   json-ref json-null? json-max-depth json-max-integer-digits json-condition?
   json-type-name)

  (import scheme (chicken base) (chicken fixnum) (chicken format)
          (chicken condition) (chicken io) (chicken port) (chicken bitwise)
          (chicken flonum))

  (define-record-type json-object
    (make-json-object members)
    json-object?
    (members json-object-members))

  (define (json-null? x) (eq? x 'null))

  ;; The value of key in object, or default (#f) when absent.
  (define (json-ref obj key #!optional default)
    (let ((p (assoc key (json-object-members obj))))
      (if p (cdr p) default)))

  ;; How a value is called in an error message.
  (define (json-type-name v)
    (cond ((json-object? v) "an object")
          ((vector? v) "an array")
          ((string? v) "a string")
          ((boolean? v) "a boolean")
          ((eq? v 'null) "null")
          ((exact-integer? v) "an integer")
          ((number? v) "a number")
          (else "a value")))

  (define json-max-depth (make-parameter 1000))
  (define json-max-integer-digits (make-parameter 1000))

  ;; Significant digits kept when a decimal becomes a double. A value
  ;; halfway between two doubles has at most 767 significant digits, so
  ;; the digits beyond 800 only matter by being zero or not: one more
  ;; digit 1 stands for any that are not, and the rounding is unchanged.
  (define kept-digits 800)

  ;; 10^0 .. 10^22, each exact as a double: a mantissa below 2^53 times or
  ;; divided by one of them is rounded once, so correctly.
  (define exact-powers-of-ten
    (let ((v (make-vector 23)))
      (do ((k 0 (fx+ k 1)) (p 1.0 (fp* p 10.0))) ((fx= k 23) v)
        (vector-set! v k p))))

  ;; The double nearest p/q (positive exact integers), ties to even.
  ;; CHICKEN's exact->inexact rounds a bignum wrongly at times (it gives
  ;; 42022006634090004480 for 42022006634090000000, whose nearest double is
  ;; 42022006634089996288), so the rounding is done here: u is the unit of
  ;; the last of the 53 bits kept (never below 2^-1074, the least
  ;; subnormal's), Q the bits, R/D what is left over.
  (define (nearest-flonum p q)
    (define (divide u)
      (if (>= u 0)
          (let ((d (arithmetic-shift q u))) (values (quotient p d) (remainder p d) d))
          (let ((n (arithmetic-shift p (- u)))) (values (quotient n q) (remainder n q) q))))
    (let* ((u1 (- (integer-length p) (integer-length q) 53))  ; p/q / 2^u1 is in [2^52, 2^54)
           (u (max -1074 (receive (bits left over) (divide u1)
                           (if (>= bits (expt 2 53)) (+ u1 1) u1)))))
      (receive (bits left over) (divide u)
        (let ((m (if (or (> (* 2 left) over) (and (= (* 2 left) over) (odd? bits))) (+ bits 1) bits)))
          (* (exact->inexact m) (expt 2.0 u))))))

  ;; The continuation bytes allowed after each lead byte of a UTF-8
  ;; sequence (RFC 3629, section 4): lead from, lead to, second byte from,
  ;; second byte to, sequence length; every later byte is 80-BF.
  (define utf8-forms
    '((#xC2 #xDF #x80 #xBF 2) (#xE0 #xE0 #xA0 #xBF 3) (#xE1 #xEC #x80 #xBF 3)
      (#xED #xED #x80 #x9F 3) (#xEE #xEF #x80 #xBF 3) (#xF0 #xF0 #x90 #xBF 4)
      (#xF1 #xF3 #x80 #xBF 4) (#xF4 #xF4 #x80 #x8F 4)))

  (define json-condition? (condition-predicate 'json))

  ;; Line and column (both from 1) of index i of s.
  (define (position s i)
    (let loop ((k 0) (line 1) (col 1))
      (cond ((or (fx>= k i) (fx>= k (string-length s))) (values line col))
            ((char=? (string-ref s k) #\newline) (loop (fx+ k 1) (fx+ line 1) 1))
            (else (loop (fx+ k 1) line (fx+ col 1))))))

  (define (json-parse-string s #!optional (source "JSON text"))
    (define n (string-length s))
    (define max-depth (json-max-depth))
    (define (fail i fmt . args)
      (receive (line col) (position s i)
        (abort (make-composite-condition
                (make-property-condition
                 'exn 'location 'json-parse-string
                 'message (sprintf "~aline ~a, column ~a: ~a"
                                   (if source (string-append source ": ") "")
                                   line col (apply sprintf fmt args))
                 'arguments '())
                (make-property-condition 'json 'file source)))))
    (define (describe i)
      (if (fx>= i n) "the end of the input" (sprintf "~s" (string-ref s i))))
    (define (skip-ws i)
      (if (and (fx< i n)
               (let ((c (string-ref s i)))
                 (or (char=? c #\space) (char=? c #\newline)
                     (char=? c #\return) (char=? c #\tab))))
          (skip-ws (fx+ i 1))
          i))
    (define (expect-word i word value)
      (let ((m (string-length word)))
        (if (and (fx<= (fx+ i m) n) (string=? (substring s i (fx+ i m)) word))
            (values value (fx+ i m))
            (fail i "unexpected ~a (expected a value)" (describe i)))))
    (define (digit? i)
      (and (fx< i n) (let ((c (string-ref s i))) (and (char>=? c #\0) (char<=? c #\9)))))
    (define (digits i) (if (digit? i) (digits (fx+ i 1)) i))
    (define (number i)
      (let* ((a (if (and (fx< i n) (char=? (string-ref s i) #\-)) (fx+ i 1) i))
             (b (cond ((not (digit? a)) (fail a "a number needs a digit here, found ~a" (describe a)))
                      ((char=? (string-ref s a) #\0)
                       (when (digit? (fx+ a 1)) (fail a "a number may not start with 0"))
                       (fx+ a 1))
                      (else (digits a))))
             (c (if (and (fx< b n) (char=? (string-ref s b) #\.))
                    (if (digit? (fx+ b 1)) (digits (fx+ b 1))
                        (fail (fx+ b 1) "a digit must follow the decimal point"))
                    b))
             (d (if (and (fx< c n) (memv (string-ref s c) '(#\e #\E)))
                    (let ((e (if (and (fx< (fx+ c 1) n) (memv (string-ref s (fx+ c 1)) '(#\+ #\-)))
                                 (fx+ c 2) (fx+ c 1))))
                      (if (digit? e) (digits e) (fail e "the exponent needs a digit")))
                    c))
             (v (cond ((and (fx= b d) (fx< (fx- b a) 10))
                       ;; an integer below 10^9, a fixnum even where fixnums
                       ;; have 31 bits: no substring, no string->number (most
                       ;; of a map's cells)
                       (let loop ((k a) (v 0))
                         (if (fx= k b)
                             (if (fx= a i) v (fx- 0 v))
                             (loop (fx+ k 1) (fx+ (fx* v 10) (fx- (char->integer (string-ref s k)) 48))))))
                      ((fx= b d)
                       (when (fx> (fx- b a) (json-max-integer-digits))
                         (fail i "an integer of ~a digits (json-max-integer-digits is ~a)"
                               (fx- b a) (json-max-integer-digits)))
                       (string->number (substring s i d)))
                      (else (decimal->flonum (fx> a i) a b c d)))))
        (unless (and v (or (exact? v) (finite? v)))
          (fail i "the number ~a is out of range"
                (if (fx> (fx- d i) 40) (string-append (substring s i (fx+ i 40)) "...") (substring s i d))))
        (values v d)))
    ;; The double nearest the decimal whose integer digits are s[a, b),
    ;; fraction digits s[b+1, c) (none when c = b) and exponent s[c+1, d)
    ;; (none when d = c); +inf.0 when it is too large for a double.
    (define (decimal->flonum negative? a b c d)
      (let* ((int-count (fx- b a))
             (frac-count (if (fx> c b) (fx- c (fx+ b 1)) 0))
             (count (fx+ int-count frac-count))
             (digit-at (lambda (k)                 ; k-th digit of both parts
                         (string-ref s (if (fx< k int-count) (fx+ a k) (fx+ (fx+ b 1) (fx- k int-count))))))
             (first (let skip ((k 0))
                      (if (and (fx< k count) (char=? (digit-at k) #\0)) (skip (fx+ k 1)) k)))
             (significant (fx- count first))
             (kept (fxmin significant kept-digits))
             (sticky? (let any ((k (fx+ first kept)))
                        (and (fx< k count) (or (not (char=? (digit-at k) #\0)) (any (fx+ k 1))))))
             ;; the exponent, or tiny or huge when it is larger than the text
             ;; is long: then no count of digits brings it near a double
             (exponent (if (fx= d c) 0
                           (let* ((sign-at (fx+ c 1))
                                  (minus? (char=? (string-ref s sign-at) #\-))
                                  (from (if (memv (string-ref s sign-at) '(#\+ #\-)) (fx+ sign-at 1) sign-at)))
                             (let loop ((k from) (e 0))
                               (cond ((fx= k d) (if minus? (fx- 0 e) e))
                                     ((fx> e (fx+ n 400)) (if minus? 'tiny 'huge))
                                     (else (loop (fx+ k 1) (fx+ (fx* e 10) (fx- (char->integer (string-ref s k)) 48)))))))))
             (magnitude
              (cond ((fx= significant 0) 0.0)
                    ((eq? exponent 'tiny) 0.0)
                    ((eq? exponent 'huge) +inf.0)
                    (else
                     ;; the value is M * 10^x, M the kept digits (and the sticky 1)
                     (let ((x (- (+ exponent significant) frac-count kept (if sticky? 1 0)))
                           (top (- (+ exponent significant) frac-count)))   ; value < 10^top
                       (cond ((> top 310) +inf.0)
                             ((< top -330) 0.0)
                             ((and (fx<= kept 15) (not sticky?) (<= -22 x 22))
                              (let ((m (let loop ((k first) (m 0.0))
                                         (if (fx= k (fx+ first kept)) m
                                             (loop (fx+ k 1) (fp+ (fp* m 10.0) (exact->inexact (fx- (char->integer (digit-at k)) 48))))))))
                                (if (>= x 0)
                                    (fp* m (vector-ref exact-powers-of-ten x))
                                    (fp/ m (vector-ref exact-powers-of-ten (- x))))))
                             (else
                              (let ((digits (make-string (if sticky? (fx+ kept 1) kept) #\1)))
                                (do ((k 0 (fx+ k 1))) ((fx= k kept))
                                  (string-set! digits k (digit-at (fx+ first k))))
                                (if (>= x 0)
                                    (nearest-flonum (* (string->number digits) (expt 10 x)) 1)
                                    (nearest-flonum (string->number digits) (expt 10 (- x))))))))))))
        (if negative? (fpneg magnitude) magnitude)))
    (define (hex4 i)
      (let loop ((k 0) (v 0))
        (if (fx= k 4)
            v
            (let* ((j (fx+ i k))
                   (c (if (fx< j n) (string-ref s j) #\x))
                   (d (cond ((char-numeric? c) (fx- (char->integer c) 48))
                            ((memv c '(#\a #\b #\c #\d #\e #\f)) (fx- (char->integer c) 87))
                            ((memv c '(#\A #\B #\C #\D #\E #\F)) (fx- (char->integer c) 55))
                            (else (fail j "\\u needs four hex digits")))))
              (loop (fx+ k 1) (fx+ (fx* v 16) d))))))
    (define (put-utf8 code out)
      (define (byte b) (write-char (integer->char b) out))
      (cond ((fx< code #x80) (byte code))
            ((fx< code #x800)
             (byte (fxior #xC0 (fxshr code 6))) (byte (fxior #x80 (fxand code #x3F))))
            ((fx< code #x10000)
             (byte (fxior #xE0 (fxshr code 12)))
             (byte (fxior #x80 (fxand (fxshr code 6) #x3F)))
             (byte (fxior #x80 (fxand code #x3F))))
            (else
             (byte (fxior #xF0 (fxshr code 18)))
             (byte (fxior #x80 (fxand (fxshr code 12) #x3F)))
             (byte (fxior #x80 (fxand (fxshr code 6) #x3F)))
             (byte (fxior #x80 (fxand code #x3F))))))
    ;; The index just after the UTF-8 sequence whose lead byte is at j (80
    ;; or above); anything that is not a whole well-formed sequence is an
    ;; error.
    (define (utf8-end j)
      (define (byte k) (if (fx< k n) (char->integer (string-ref s k)) -1))
      (define (in? x from to) (and (fx>= x from) (fx<= x to)))
      (let* ((lead (byte j))
             (form (let find ((fs utf8-forms))
                     (cond ((null? fs) #f)
                           ((in? lead (car (car fs)) (cadr (car fs))) (car fs))
                           (else (find (cdr fs))))))
             (end (and form (fx+ j (list-ref form 4)))))
        (let check ((k (fx+ j 1)))
          (cond ((not form) (fail j "the byte ~x is not UTF-8 (strings must be UTF-8)" lead))
                ((fx= k end) end)
                ((in? (byte k) (if (fx= k (fx+ j 1)) (caddr form) #x80)
                      (if (fx= k (fx+ j 1)) (cadddr form) #xBF))
                 (check (fx+ k 1)))
                (else (fail j "the bytes from ~x are not UTF-8 (strings must be UTF-8)" lead))))))
    ;; i is just after the opening quote.
    (define (str i)
      ;; fast path: no escape before the closing quote
      (let scan ((j i))
        (cond ((fx>= j n) (fail (fx- i 1) "the string never ends"))
              ((char=? (string-ref s j) #\") (values (substring s i j) (fx+ j 1)))
              ((char=? (string-ref s j) #\\) (escaped i))
              ((fx< (char->integer (string-ref s j)) 32)
               (fail j "a control character (code ~a) inside a string must be escaped"
                     (char->integer (string-ref s j))))
              ((fx>= (char->integer (string-ref s j)) 128) (scan (utf8-end j)))
              (else (scan (fx+ j 1))))))
    (define (escaped i)
      (let ((out (open-output-string)))
        (let loop ((j i))
          (when (fx>= j n) (fail (fx- i 1) "the string never ends"))
          (let ((c (string-ref s j)))
            (cond ((char=? c #\") (values (get-output-string out) (fx+ j 1)))
                  ((fx< (char->integer c) 32)
                   (fail j "a control character (code ~a) inside a string must be escaped"
                         (char->integer c)))
                  ((char=? c #\\)
                   (when (fx>= (fx+ j 1) n) (fail j "the string never ends"))
                   (let ((e (string-ref s (fx+ j 1))))
                     (case e
                       ((#\") (write-char #\" out) (loop (fx+ j 2)))
                       ((#\\) (write-char #\\ out) (loop (fx+ j 2)))
                       ((#\/) (write-char #\/ out) (loop (fx+ j 2)))
                       ((#\b) (write-char #\backspace out) (loop (fx+ j 2)))
                       ((#\f) (write-char (integer->char 12) out) (loop (fx+ j 2)))
                       ((#\n) (write-char #\newline out) (loop (fx+ j 2)))
                       ((#\r) (write-char #\return out) (loop (fx+ j 2)))
                       ((#\t) (write-char #\tab out) (loop (fx+ j 2)))
                       ((#\u)
                        (let ((u (hex4 (fx+ j 2))))
                          (cond ((and (fx>= u #xD800) (fx< u #xDC00))
                                 (let ((k (fx+ j 6)))
                                   (unless (and (fx< (fx+ k 1) n) (char=? (string-ref s k) #\\)
                                                (char=? (string-ref s (fx+ k 1)) #\u))
                                     (fail j "a lone surrogate \\u~a" (substring s (fx+ j 2) (fx+ j 6))))
                                   (let ((lo (hex4 (fx+ k 2))))
                                     (unless (and (fx>= lo #xDC00) (fx< lo #xE000))
                                       (fail j "a lone surrogate \\u~a" (substring s (fx+ j 2) (fx+ j 6))))
                                     (put-utf8 (fx+ #x10000 (fxior (fxshl (fx- u #xD800) 10)
                                                                    (fx- lo #xDC00)))
                                               out)
                                     (loop (fx+ k 6)))))
                                ((and (fx>= u #xDC00) (fx< u #xE000))
                                 (fail j "a lone surrogate \\u~a" (substring s (fx+ j 2) (fx+ j 6))))
                                (else (put-utf8 u out) (loop (fx+ j 6))))))
                       (else (fail j "unknown escape \\~a" e)))))
                  ((fx>= (char->integer c) 128)
                   (let ((end (utf8-end j)))
                     (do ((k j (fx+ k 1))) ((fx= k end)) (write-char (string-ref s k) out))
                     (loop end)))
                  (else (write-char c out) (loop (fx+ j 1))))))))
    (define (value i depth)
      (let ((i (skip-ws i)))
        (if (fx>= i n)
            (fail i "unexpected end of the input (expected a value)")
            (let ((c (string-ref s i)))
              (cond ((char=? c #\{) (object (fx+ i 1) (fx+ depth 1) i))
                    ((char=? c #\[) (array (fx+ i 1) (fx+ depth 1) i))
                    ((char=? c #\") (str (fx+ i 1)))
                    ((or (char=? c #\-) (and (char>=? c #\0) (char<=? c #\9))) (number i))
                    ((char=? c #\t) (expect-word i "true" #t))
                    ((char=? c #\f) (expect-word i "false" #f))
                    ((char=? c #\n) (expect-word i "null" 'null))
                    (else (fail i "unexpected ~a (expected a value)" (describe i))))))))
    (define (check-depth depth start)
      (when (fx> depth max-depth)
        (fail start "nested more than ~a deep (json-max-depth)" max-depth)))
    (define (array i depth start)
      (check-depth depth start)
      (let ((i (skip-ws i)))
        (if (and (fx< i n) (char=? (string-ref s i) #\]))
            (values (vector) (fx+ i 1))
            ;; elements go into blocks of 1024 (full blocks kept in a
            ;; list, newest first), then into one vector: a word per
            ;; element instead of a pair's three
            (let loop ((i i) (block (make-vector 1024)) (k 0) (full '()) (count 0))
              (receive (v j) (value i depth)
                (vector-set! block k v)
                (let ((j (skip-ws j)) (k (fx+ k 1)) (count (fx+ count 1)))
                  (cond ((fx>= j n) (fail start "the array never ends"))
                        ((char=? (string-ref s j) #\,)
                         (if (fx= k 1024)
                             (loop (fx+ j 1) (make-vector 1024) 0 (cons block full) count)
                             (loop (fx+ j 1) block k full count)))
                        ((char=? (string-ref s j) #\])
                         (let ((vec (make-vector count)))
                           ;; the last block holds k, the full ones 1024 each
                           (let fill ((b block) (m k) (end count) (rest full))
                             (let ((from (fx- end m)))
                               (do ((x 0 (fx+ x 1))) ((fx= x m))
                                 (vector-set! vec (fx+ from x) (vector-ref b x)))
                               (unless (null? rest)
                                 (fill (car rest) 1024 from (cdr rest)))))
                           (values vec (fx+ j 1))))
                        (else (fail j "expected , or ] in an array, found ~a" (describe j))))))))))
    (define (object i depth start)
      (check-depth depth start)
      (let ((i (skip-ws i)))
        (if (and (fx< i n) (char=? (string-ref s i) #\}))
            (values (make-json-object '()) (fx+ i 1))
            (let loop ((i i) (acc '()))
              (let ((i (skip-ws i)))
                (unless (and (fx< i n) (char=? (string-ref s i) #\"))
                  (fail i "expected a key (a string) in an object, found ~a" (describe i)))
                (receive (key j) (str (fx+ i 1))
                  (let ((j (skip-ws j)))
                    (unless (and (fx< j n) (char=? (string-ref s j) #\:))
                      (fail j "expected : after the key ~s, found ~a" key (describe j)))
                    (receive (v k) (value (fx+ j 1) depth)
                      (let ((k (skip-ws k)) (acc (cons (cons key v) acc)))
                        (cond ((fx>= k n) (fail start "the object never ends"))
                              ((char=? (string-ref s k) #\,) (loop (fx+ k 1) acc))
                              ((char=? (string-ref s k) #\})
                               (values (make-json-object (reverse acc)) (fx+ k 1)))
                              (else (fail k "expected , or } in an object, found ~a"
                                          (describe k)))))))))))))
    (let* ((start (if (and (fx>= n 3) (string=? (substring s 0 3) "\xef\xbb\xbf")) 3 0)))
      (receive (v i) (value start 0)
        (let ((i (skip-ws i)))
          (unless (fx= i n)
            (fail i "unexpected ~a after the value" (describe i)))
          v))))

  ;; The value in a file; errors name the file.
  (define (json-read-file path)
    (let ((text (with-input-from-file path (lambda () (read-string #f)))))
      (json-parse-string (if (string? text) text "") path))))
