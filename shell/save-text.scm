;;; (downstroke save-text): the text of save data, written and read by
;;; this module alone, so that reading a save never reaches CHICKEN's
;;; reader (its #, constructors, #e numbers, #!eof, reader extensions a
;;; game or library added). Pure Scheme, no C.
;;;
;;; The syntax is what datum->save-text writes, and save-text->datum
;;; accepts that and nothing else:
;;;   - #t #f; () (a b) (a . b) (the dot only before a tail that is not a
;;;     list) and #(a b), items separated by spaces;
;;;   - exact integers -?D+ and fractions -?D+/D+ in lowest terms;
;;;     flonums as number->string writes them with 15 significant digits,
;;;     or 17 when 15 do not read back the same, +inf.0 and -inf.0 (no NaN,
;;;     no complex numbers); at most (save-data-max-digits) digits, 10,000
;;;     by default, so that one number costs a bounded time to convert
;;;     (CHICKEN's string->number is quadratic in the digits) and reading
;;;     is linear in the size of the text;
;;;   - characters #\c for printable ASCII, #\NAME for the names of
;;;     char-names, #\xHEX for every other;
;;;   - strings "..." with the escapes \" \\ \a \b \t \n \v \f \r, and
;;;     \xHH; for the other control bytes; other bytes as they are;
;;;   - symbols bare when plain-symbol? says so, else |...| with the
;;;     string escapes (\| for |); keywords #: and the same.
;;; Whitespace and ; comments may stand between items. Each atom must be
;;; the very text the writer gives its value (so 1.50, 2/4, |abc|, #\x41
;;; and "\x41;" are refused) and must end at whitespace, a ; or a ).
;;; Both sides count objects (pairs, atoms, (), vectors) the same way
;;; against (save-data-max-nodes), so whatever is written reads back.

(module (downstroke save-text)
  (datum->save-text save-text->datum data-problem save-data-max-nodes save-data-max-digits
   save-text-error? save-text-error-message)

  (import scheme (chicken base) (chicken format) (chicken condition) (chicken port)
          (chicken keyword) (chicken flonum) (chicken blob) (chicken io)
          (only (chicken bitwise) integer-length)
          (only (chicken memory representation) record-instance? record-instance-type))

  (define save-data-max-nodes (make-parameter 100000))
  (define save-data-max-digits (make-parameter 10000))

  ;; What is wrong with a value or a text, as a sentence for the caller
  ;; to put in its own error (the caller knows the name and the file).
  (define (text-error fmt . args)
    (signal (make-property-condition 'save-text 'message (apply sprintf fmt args))))
  (define (save-text-error? c) (and (condition? c) ((condition-predicate 'save-text) c)))
  (define save-text-error-message (condition-property-accessor 'save-text 'message))

  ;;; What may be written.

  ;; The kind of the first object in v that is not data, as a phrase, or
  ;; #f when all of it is; counts objects against the bound.
  (define (data-problem v)
    (let ((budget (save-data-max-nodes)))
      (call/cc
       (lambda (return)
         (let walk ((v v))
           (set! budget (- budget 1))
           (when (< budget 0)
             (return (sprintf "more than ~a objects (or a circular list)" (save-data-max-nodes))))
           (cond ((or (boolean? v) (char? v) (string? v) (symbol? v) (keyword? v) (null? v)) #f)
                 ((number? v) (number-problem v))
                 ((pair? v) (or (walk (car v)) (walk (cdr v))))
                 ((vector? v) (let loop ((i 0))
                                (and (< i (vector-length v))
                                     (or (walk (vector-ref v i)) (loop (+ i 1))))))
                 (else (return (kind-of v)))))))))

  (define (number-problem v)
    (cond ((not (real? v)) "a complex number")
          ((not (= v v)) "a NaN number")
          ((and (exact? v) (or (surely-too-long? (numerator v)) (surely-too-long? (denominator v))))
           (sprintf "a number of more than ~a digits (save-data-max-digits)" (save-data-max-digits)))
          (else #f)))

  ;; More than D decimal digits, seen from the bits alone (no conversion,
  ;; which for a huge number is the very cost the bound avoids): n has at
  ;; least 2^(bits-1), and 3.33 bits per digit exceeds log2(10).
  (define (surely-too-long? n)
    (> (integer-length (abs n)) (+ 1 (quotient (* 333 (save-data-max-digits)) 100))))

  (define (kind-of v)
    (cond ((procedure? v) "a procedure")
          ((eof-object? v) "the end-of-file object")
          ((port? v) "a port")
          ((condition? v) "a condition")
          ((record-instance? v) (sprintf "a record (~a)" (record-instance-type v)))
          ((blob? v) "a blob")
          (else (sprintf "a ~a" (let ((s (with-output-to-string (lambda () (write v)))))
                                  (if (> (string-length s) 40) (string-append (substring s 0 40) "...") s))))))

  ;;; The text of each kind of atom: the writer uses these, and the
  ;;; reader accepts an atom only when they give back its very text.

  (define (digit? c) (and (char<=? #\0 c) (char<=? c #\9)))

  ;; The decimal digits of a number's text, those of an exponent aside.
  (define (digit-count s)
    (let loop ((i 0) (k 0))
      (cond ((or (= i (string-length s)) (char=? (string-ref s i) #\e)) k)
            ((digit? (string-ref s i)) (loop (+ i 1) (+ k 1)))
            (else (loop (+ i 1) k)))))

  (define (check-digits! s)
    (let ((d (digit-count s)))
      (when (> d (save-data-max-digits))
        (text-error "a number of ~a digits, over save-data-max-digits (~a)" d (save-data-max-digits)))))

  ;; 15 significant digits, as CHICKEN prints by default, or 17 (always
  ;; enough) when 15 do not read back the same. flonum-print-precision is
  ;; a global setting, not a parameter, and a game may have changed it.
  (define (flonum-text x)
    (let ((s (flonum-digits x 15)))
      (if (eqv? x (string->number s)) s (flonum-digits x 17))))

  (define (flonum-digits x precision)
    (let ((old (flonum-print-precision)))
      (dynamic-wind (lambda () (flonum-print-precision precision))
                    (lambda () (number->string x))
                    (lambda () (flonum-print-precision old)))))

  (define (number-text v)
    (let ((s (if (flonum? v) (flonum-text v) (number->string v))))
      (check-digits! s)
      s))

  ;; The names CHICKEN's own writer gives these characters.
  (define char-names
    '((0 . "null") (7 . "alarm") (8 . "backspace") (9 . "tab") (10 . "newline") (11 . "vtab")
      (12 . "page") (13 . "return") (27 . "escape") (32 . "space") (127 . "delete")))

  (define (char-text c)
    (let ((n (char->integer c)))
      (cond ((assv n char-names) => (lambda (p) (string-append "#\\" (cdr p))))
            ((< 32 n 127) (string #\# #\\ c))
            (else (string-append "#\\x" (number->string n 16))))))

  (define string-escapes
    '((7 . #\a) (8 . #\b) (9 . #\t) (10 . #\n) (11 . #\v) (12 . #\f) (13 . #\r)))
  (define string-unescapes (map (lambda (p) (cons (cdr p) (car p))) string-escapes))

  ;; s between two q's (" or |), escaped.
  (define (write-escaped s q out)
    (write-char q out)
    (let ((n (string-length s)))
      (do ((i 0 (+ i 1))) ((= i n))
        (let* ((c (string-ref s i)) (k (char->integer c)))
          (cond ((or (char=? c q) (char=? c #\\)) (write-char #\\ out) (write-char c out))
                ((assv k string-escapes) => (lambda (p) (write-char #\\ out) (write-char (cdr p) out)))
                ((or (< k 32) (= k 127))
                 (write-string (if (< k 16) "\\x0" "\\x") #f out)
                 (write-string (number->string k 16) #f out)
                 (write-char #\; out))
                (else (write-char c out))))))
    (write-char q out))

  (define (escaped-text s q) (call-with-output-string (lambda (out) (write-escaped s q out))))

  (define (symbol-start? c)
    (or (and (char<=? #\a c) (char<=? c #\z)) (and (char<=? #\A c) (char<=? c #\Z))
        (memv c '(#\! #\$ #\% #\& #\* #\/ #\< #\= #\> #\? #\^ #\_ #\~))
        (char>=? c #\x80)))
  (define (symbol-part? c) (or (symbol-start? c) (digit? c) (memv c '(#\+ #\- #\. #\@))))

  ;; A symbol written without bars: no digit, sign or dot first (never a
  ;; number), no : (never a keyword), no # ' ` , or delimiter anywhere.
  (define (plain-symbol? s)
    (or (member s '("+" "-" "..."))
        (and (> (string-length s) 0)
             (symbol-start? (string-ref s 0))
             (let loop ((i 1))
               (or (= i (string-length s))
                   (and (symbol-part? (string-ref s i)) (loop (+ i 1))))))))

  (define (symbol-name-text s) (if (plain-symbol? s) s (escaped-text s #\|)))

  ;;; Writing.

  ;; The text of v, which data-problem found to be data.
  (define (datum->save-text v)
    (call-with-output-string (lambda (out) (write-datum v out))))

  (define (write-datum v out)
    (cond ((eq? v #t) (write-string "#t" #f out))
          ((eq? v #f) (write-string "#f" #f out))
          ((number? v) (write-string (number-text v) #f out))
          ((char? v) (write-string (char-text v) #f out))
          ((string? v) (write-escaped v #\" out))
          ((keyword? v) (write-string "#:" #f out) (write-string (symbol-name-text (keyword->string v)) #f out))
          ((symbol? v) (write-string (symbol-name-text (symbol->string v)) #f out))
          ((null? v) (write-string "()" #f out))
          ((pair? v)
           (write-char #\( out)
           (write-datum (car v) out)
           (let loop ((tail (cdr v)))
             (cond ((pair? tail) (write-char #\space out) (write-datum (car tail) out) (loop (cdr tail)))
                   ((null? tail) (write-char #\) out))
                   (else (write-string " . " #f out) (write-datum tail out) (write-char #\) out)))))
          ((vector? v)
           (write-string "#(" #f out)
           (do ((i 0 (+ i 1))) ((= i (vector-length v)))
             (when (> i 0) (write-char #\space out))
             (write-datum (vector-ref v i) out))
           (write-char #\) out))
          (else (text-error "it holds ~a, which is not data" (kind-of v)))))

  ;;; Reading.

  (define (white? c) (memv c '(#\space #\tab #\newline #\return)))
  (define (delimiter? c) (or (white? c) (memv c '(#\( #\) #\" #\; #\|))))

  ;; -?D+, -?D+/D+, -?D+(.D+)?(e[+-]?D{1,3})? with a fraction or an
  ;; exponent, +inf.0, -inf.0: the only texts string->number is given.
  (define (number-shape? s)
    (let ((n (string-length s)))
      (define (digits-end j) (if (and (< j n) (digit? (string-ref s j))) (digits-end (+ j 1)) j))
      (define (exponent? j)                 ; s from j is e[+-]?D{1,3} to its end
        (and (< j n) (char=? (string-ref s j) #\e)
             (let* ((d (if (and (< (+ j 1) n) (memv (string-ref s (+ j 1)) '(#\+ #\-))) (+ j 2) (+ j 1)))
                    (e (digits-end d)))
               (and (< d e) (<= e (+ d 3)) (= e n)))))
      (or (member s '("+inf.0" "-inf.0"))
          (let* ((a (if (and (> n 0) (char=? (string-ref s 0) #\-)) 1 0))
                 (b (digits-end a)))
            (and (> b a)
                 (or (= b n)
                     (and (char=? (string-ref s b) #\/)
                          (let ((c (digits-end (+ b 1)))) (and (> c (+ b 1)) (= c n))))
                     (and (char=? (string-ref s b) #\.)
                          (let ((c (digits-end (+ b 1))))
                            (and (> c (+ b 1)) (or (= c n) (exponent? c)))))
                     (exponent? b)))))))

  ;; The one datum of text; anything else is a save-text error saying
  ;; what and on which line.
  (define (save-text->datum text)
    (let ((n (string-length text)) (i 0) (budget (save-data-max-nodes)))

      (define (line-of j)
        (let loop ((k 0) (line 1))
          (if (>= k j) line (loop (+ k 1) (if (char=? (string-ref text k) #\newline) (+ line 1) line)))))
      (define (bad at fmt . args) (text-error "~a (line ~a)" (apply sprintf fmt args) (line-of at)))
      (define (excerpt s) (if (> (string-length s) 40) (string-append (substring s 0 40) "...") s))
      (define (count! at)
        (set! budget (- budget 1))
        (when (< budget 0) (bad at "more than ~a objects (save-data-max-nodes)" (save-data-max-nodes))))

      (define (skip-space!)
        (when (< i n)
          (let ((c (string-ref text i)))
            (cond ((white? c) (set! i (+ i 1)) (skip-space!))
                  ((char=? c #\;)
                   (let loop () (when (and (< i n) (not (char=? (string-ref text i) #\newline)))
                                  (set! i (+ i 1)) (loop)))
                   (skip-space!))))))

      ;; the end of the run of non-delimiters from j
      (define (run-end j) (if (and (< j n) (not (delimiter? (string-ref text j)))) (run-end (+ j 1)) j))

      ;; after an atom: whitespace, a comment, a ) or the end
      (define (atom-ends! at)
        (when (and (< i n) (not (white? (string-ref text i))) (not (memv (string-ref text i) '(#\; #\)))))
          (bad at "~s runs into ~s: items are separated by spaces"
               (excerpt (substring text at i)) (string (string-ref text i)))))

      ;; the index after the q closing the text opened at j, or #f
      (define (closing j q)
        (let loop ((k (+ j 1)))
          (cond ((>= k n) #f)
                ((char=? (string-ref text k) #\\) (loop (+ k 2)))
                ((char=? (string-ref text k) q) (+ k 1))
                (else (loop (+ k 1))))))

      ;; the string between q's from j to end, escapes undone, or #f; the
      ;; callers compare its written text with the source, which refuses
      ;; what the writer does not write
      (define (unescape j end)
        (call/cc
         (lambda (return)
           (call-with-output-string
            (lambda (out)
              (let loop ((k (+ j 1)))
                (when (< k (- end 1))
                  (let ((c (string-ref text k)))
                    (if (not (char=? c #\\))
                        (begin (write-char c out) (loop (+ k 1)))
                        (let ((e (string-ref text (+ k 1))))
                          (cond ((memv e '(#\" #\\ #\|)) (write-char e out) (loop (+ k 2)))
                                ((assv e string-unescapes)
                                 => (lambda (p) (write-char (integer->char (cdr p)) out) (loop (+ k 2))))
                                ((and (char=? e #\x) (< (+ k 4) (- end 1)) (char=? (string-ref text (+ k 4)) #\;))
                                 (let ((v (string->number (substring text (+ k 2) (+ k 4)) 16)))
                                   (unless (and (exact-integer? v) (<= 0 v 255)) (return #f))
                                   (write-char (integer->char v) out)
                                   (loop (+ k 5))))
                                (else (return #f)))))))))))))

      ;; a "string" or |symbol name| at j: its value and the index after it
      (define (delimited j q what)
        (let ((end (closing j q)))
          (unless end (bad j "~a that is never closed (the text ends first)" what))
          (let ((s (unescape j end)))
            (unless (and s (string=? (escaped-text s q) (substring text j end)))
              (bad j "~a ~s is not written as save data writes it" what (excerpt (substring text j end))))
            (values s end))))

      ;; the name of a symbol or keyword at j: its string and the index after it
      (define (symbol-name j)
        (receive (s end) (if (and (< j n) (char=? (string-ref text j) #\|))
                             (delimited j #\| "a |symbol|")
                             (let ((end (run-end j))) (values (substring text j end) end)))
          (unless (string=? (symbol-name-text s) (substring text j end))
            (bad j "the symbol ~s is not written as save data writes it (~a)"
                 (excerpt (substring text j end)) (excerpt (symbol-name-text s))))
          (values s end)))

      (define (char-at j)               ; j at the #
        (when (>= (+ j 2) n) (bad j "#\\ with no character after it"))
        (let* ((c (string-ref text (+ j 2)))
               (end (if (delimiter? c) (+ j 3) (run-end (+ j 2))))
               (name (substring text (+ j 2) end))
               (ch (cond ((= 1 (string-length name)) c)
                         ((find-name name char-names) => integer->char)
                         ((and (char=? c #\x) (<= 2 (string-length name) 7)
                               (string->number (substring name 1) 16))
                          => (lambda (k) (and (exact-integer? k) (<= 0 k #x10FFFF) (integer->char k))))
                         (else #f))))
          (unless (and ch (string=? (char-text ch) (substring text j end)))
            (bad j "~s is not a character as save data writes it" (excerpt (substring text j end))))
          (values ch end)))

      (define (number-at j end)
        (let ((s (substring text j end)))
          (unless (number-shape? s) (bad j "unknown text ~s: not a number, symbol or other save data" (excerpt s)))
          (let ((d (digit-count s)))
            (when (> d (save-data-max-digits))
              (bad j "a number of ~a digits, over save-data-max-digits (~a)" d (save-data-max-digits))))
          (let ((v (condition-case (string->number s) (e () #f))))
            (unless (and v (string=? (number-text v) s))
              (bad j "the number ~s is not written as save data writes it" (excerpt s)))
            v)))

      ;; The next token: (values kind value at), kind one of open vector
      ;; close dot atom end.
      (define (next)
        (skip-space!)
        (let ((at i))
          (define (atom! v end) (set! i end) (atom-ends! at) (values 'atom v at))
          (if (>= i n)
              (values 'end #f at)
              (let ((c (string-ref text i)))
                (cond ((char=? c #\() (set! i (+ i 1)) (values 'open #f at))
                      ((char=? c #\)) (set! i (+ i 1)) (values 'close #f at))
                      ((char=? c #\") (receive (s end) (delimited i #\" "a string") (atom! s end)))
                      ((char=? c #\|) (receive (s end) (symbol-name i) (atom! (string->symbol s) end)))
                      ((char=? c #\#)
                       (let ((d (and (< (+ i 1) n) (string-ref text (+ i 1)))))
                         (cond ((eqv? d #\() (set! i (+ i 2)) (values 'vector #f at))
                               ((eqv? d #\\) (receive (ch end) (char-at i) (atom! ch end)))
                               ((eqv? d #\:) (receive (s end) (symbol-name (+ i 2)) (atom! (string->keyword s) end)))
                               ((memv d '(#\t #\f))
                                (let ((s (substring text i (run-end i))))
                                  (unless (member s '("#t" "#f"))
                                    (bad at "unknown text ~s: save data's booleans are #t and #f" (excerpt s)))
                                  (atom! (eqv? d #\t) (+ i 2))))
                               ((not d) (bad at "a lone # at the end"))
                               (else (bad at "the syntax #~a: save data has only #t #f #\\ #( and #:" d)))))
                      (else
                       (let* ((end (run-end i)) (s (substring text i end)))
                         (cond ((string=? s ".") (set! i end) (atom-ends! at) (values 'dot #f at))
                               ((plain-symbol? s) (atom! (string->symbol s) end))
                               ((or (digit? c) (memv c '(#\+ #\- #\.))) (atom! (number-at i end) end))
                               (else (bad at "unknown text ~s: not a number, symbol or other save data"
                                          (excerpt s)))))))))))

      ;; a list is counted as its pairs and its (), by read-list
      (define (datum kind value at)
        (unless (eq? kind 'open) (count! at))
        (case kind
          ((atom) value)
          ((open) (read-list at))
          ((vector) (list->vector (read-vector at)))
          ((close) (bad at "a ) with no ( before it"))
          ((dot) (bad at "a . that is not before a list's last item"))
          (else (bad at "the text ends where a value should be"))))

      (define (read-list start)
        (let loop ((items '()))
          (receive (kind value at) (next)
            (case kind
              ((close) (count! at) (reverse items))           ; the () that ends it
              ((end) (bad start "a list that is never closed (the text ends first)"))
              ((dot)
               (when (null? items) (bad at "a . with nothing before it"))
               (receive (k v a) (next)
                 (when (memq k '(open close end dot))
                   (bad a "after a . save data has one item, and not a list"))
                 (let ((tail (datum k v a)))
                   (receive (k2 v2 a2) (next)
                     (unless (eq? k2 'close) (bad a2 "more than one item after a ."))
                     (let rev ((items items) (out tail))
                       (if (null? items) out (rev (cdr items) (cons (car items) out))))))))
              (else (count! at) (loop (cons (datum kind value at) items)))))))

      (define (read-vector start)
        (let loop ((items '()))
          (receive (kind value at) (next)
            (case kind
              ((close) (reverse items))
              ((end) (bad start "a vector that is never closed (the text ends first)"))
              ((dot) (bad at "a . inside a vector"))
              (else (loop (cons (datum kind value at) items)))))))

      (receive (kind value at) (next)
        (when (eq? kind 'end) (text-error "it holds no value (empty or truncated)"))
        (let ((v (datum kind value at)))
          (receive (kind value at) (next)
            (unless (eq? kind 'end)
              (bad at (if (eq? kind 'close) "a ) with no ( before it" "it holds more than one value")))
            v)))))

  (define (find-name name alist)
    (cond ((null? alist) #f)
          ((string=? name (cdar alist)) (caar alist))
          (else (find-name name (cdr alist))))))
