;;; (downstroke json): the strict JSON reader under Tiled's JSON formats.
;;; Values as RFC 8259 defines them, and every kind of malformed text
;;; refused with its line and column.

(import scheme (chicken base) (chicken string) (chicken format) (chicken condition)
        (chicken random) (chicken bitwise)
        (only (downstroke util) iota)
        (downstroke test) (downstroke json))

;; A JSON value as plain lists: objects as (obj (key . value) ...), arrays
;; as (arr value ...).
(define (js-plain v)
  (cond ((json-object? v)
         (cons 'obj (map (lambda (m) (cons (car m) (js-plain (cdr m)))) (json-object-members v))))
        ((vector? v) (cons 'arr (map js-plain (vector->list v))))
        (else v)))

(define (js text) (js-plain (json-parse-string text)))

(define (js-error text)
  (handle-exceptions exn
      (list (and (json-condition? exn) 'json) (error-text exn))
    (json-parse-string text "t.json")
    'no-error))

(test-group "json: values"
  (test "literals" '(arr #t #f null) (js "[true, false, null]"))
  (test "integers are exact, the rest flonums" '(arr 0 -12 123456789012345678901234567890 1.5 -0.25 100.0 0.001 2.0)
        (js "[0, -12, 123456789012345678901234567890, 1.5, -0.25, 1e2, 1E-3, 2.0]"))
  (test "a number keeps every digit" 0.30000000000000004 (json-parse-string "0.30000000000000004"))
  (test "objects keep their members in order" '(obj ("b" . 1) ("a" obj ("c" arr)))
        (js " {\"b\" : 1 ,\n \"a\":{\"c\":[]}} "))
  (test "json-ref: a member, and the default" '(1 #f gone)
        (let ((o (json-parse-string "{\"a\":1}")))
          (list (json-ref o "a") (json-ref o "b") (json-ref o "b" 'gone))))
  (test "escapes" "q\"b\\s/\b\f\n\r\t" (json-parse-string "\"q\\\"b\\\\s\\/\\b\\f\\n\\r\\t\""))
  (test "\\u escapes are written as UTF-8, surrogate pairs joined"
        "\xc3\xa9\xe2\x82\xac\xf0\x9f\x98\x80"
        (json-parse-string "\"\\u00e9\\u20AC\\ud83d\\ude00\""))
  (test "UTF-8 in the text passes through" "h\xc3\xa9" (json-parse-string "\"h\xc3\xa9\""))
  (test "a byte order mark is skipped" 1 (json-parse-string "\xef\xbb\xbf 1"))
  (test "an empty array and object" '(arr (arr) (obj)) (js "[[],{}]"))
  ;; arrays are gathered in blocks of 1024: every length around a block edge
  (for-each
   (lambda (n)
     (let ((l (iota n)))
       (test (sprintf "an array of ~a elements, in order" n) l
             (vector->list (json-parse-string
                            (string-append "[" (string-intersperse (map number->string l) ",") "]"))))))
   '(1 1023 1024 1025 2047 2048 2049 5000)))

;; Whether the double d is the one nearest the decimal text, by exact
;; arithmetic: no double lies nearer. Its neighbours are an ulp away, or
;; half of one below a power of two; an exact tie is allowed here (the
;; ties are tested apart, with known doubles).
(define (nearest-double? text d)
  (let* ((v (abs (string->number (string-append "#e" text))))
         (r (abs (inexact->exact d)))
         (ulp (if (zero? r)
                  (expt 2 -1074)
                  (max (expt 2 -1074)
                       (expt 2 (- (integer-length (numerator r)) (integer-length (denominator r)) 52)))))
         (power-of-two? (and (positive? r) (= 1 (numerator (/ r (expt 2 (- (integer-length (numerator r)) (integer-length (denominator r)))))))))
         (below (if (and power-of-two? (> ulp (expt 2 -1074))) (/ ulp 2) ulp)))
    (and (eq? (negative? (string->number text)) (or (negative? d) (eqv? d -0.0)))
         (<= (abs (- v r)) (/ (if (< v r) below ulp) 2)))))

(define (digits-of-length k)
  (let ((s (make-string k)))
    (do ((i 0 (+ i 1))) ((= i k) s)
      (string-set! s i (integer->char (+ 48 (pseudo-random-integer 10)))))))

(test-group "json: numbers are the nearest double, however many digits"
  ;; each is a case that rounding twice, or rounding a bignum, gets wrong
  (for-each
   (lambda (text)
     (test-assert text (nearest-double? text (json-parse-string text))))
   '("1.00000000000000011102230246251565404236316680908203126" ; just above a halfway point
     "2.4703282292062328e-324"                                 ; just above half the least double
     "2.2250738585072011e-308" "4202200663.409e10" "42022006634090000000.0"
     "9007199254740993.0" "1e23" "8.5e-1" "-123.456e-5" "1.7976931348623157e308"))
  (test "a halfway point goes to the even double" 1.0
        (json-parse-string "1.00000000000000011102230246251565404236316680908203125"))
  (test "and the next halfway point up to the next" 1.0000000000000004
        (json-parse-string "1.00000000000000033306690738754696212708950042724609375"))
  (test "the least double, written out" 5e-324 (json-parse-string "4.9406564584124654e-324"))
  (test-assert "the check itself sees a double one ulp off"
               (not (nearest-double? "0.1" 0.10000000000000002)))
  (test "-0.0 keeps its sign" "-0.0" (number->string (json-parse-string "-0.0")))
  (test "beyond the least double is 0.0" 0.0 (json-parse-string "1e-400"))
  (test "an exponent longer than the text is 0.0 below" 0.0 (json-parse-string "7e-99999999999999999999"))
  (test-assert "and out of range above"
               (substring-index "out of range" (cadr (js-error "7e99999999999999999999"))))
  (let ((wrong
         (let loop ((i 0) (wrong '()))
           (if (= i 2000)
               wrong
               (let* ((int (let ((d (digits-of-length (+ 1 (pseudo-random-integer 25)))))
                             (if (char=? (string-ref d 0) #\0) "0" d)))
                      (frac (digits-of-length (+ 1 (pseudo-random-integer (if (zero? (modulo i 8)) 1500 30)))))
                      (text (sprintf "~a.~ae~a" int frac (- (pseudo-random-integer 620) 350))))
                 (loop (+ i 1)
                       (if (nearest-double? text (json-parse-string text)) wrong (cons text wrong))))))))
    (test "2000 random decimals of up to 1500 digits, each the nearest double" '() wrong))
  (test "two million digits, read in time linear in them" 100000.0
        (json-parse-string (string-append "1." (make-string 2000000 #\0) "1e5")))
  (test "integers of 10 to 18 digits are exact (beyond a 31-bit fixnum too)"
        '(1073741824 -999999999999999999 123456789012345678)
        (vector->list (json-parse-string "[1073741824, -999999999999999999, 123456789012345678]")))
  (test-assert "an integer longer than json-max-integer-digits is an error naming it"
               (let ((r (js-error (make-string 2000000 #\7))))
                 (and (eq? (car r) 'json) (substring-index "json-max-integer-digits" (cadr r))
                      (substring-index "2000000 digits" (cadr r)))))
  (test "a game may raise json-max-integer-digits" (string->number (make-string 1500 #\3))
        (parameterize ((json-max-integer-digits 2000))
          (json-parse-string (make-string 1500 #\3)))))

(test-group "json: strings are UTF-8 as RFC 3629 defines it"
  (test "every length of sequence, and the edges of the ranges"
        "\x7f\xc2\x80\xdf\xbf\xe0\xa0\x80\xed\x9f\xbf\xee\x80\x80\xf0\x90\x80\x80\xf4\x8f\xbf\xbf"
        (json-parse-string "\"\x7f\xc2\x80\xdf\xbf\xe0\xa0\x80\xed\x9f\xbf\xee\x80\x80\xf0\x90\x80\x80\xf4\x8f\xbf\xbf\""))
  (test "after an escape too" "\n\xc3\xa9\xf0\x9f\x98\x80" (json-parse-string "\"\\n\xc3\xa9\xf0\x9f\x98\x80\""))
  (for-each
   (lambda (c)
     (let ((r (js-error (string-append "[\"ok\", \"" (car c) "\"]"))))
       (test-assert (sprintf "~a is refused: ~a" (cadr c) (cadr r))
                    (and (eq? (car r) 'json) (substring-index "not UTF-8" (cadr r))
                         ;; the column of the first bad byte (after "\n" in the last case)
                         (substring-index (sprintf "line 1, column ~a" (if (null? (cddr c)) 9 (caddr c)))
                                          (cadr r))))))
   '(("\xff\xfe" "FF FE")
     ("\xc0\xaf" "the overlong C0 AF")
     ("\xe0\x80\xaf" "the overlong E0 80 AF")
     ("\xed\xa0\x80" "the surrogate ED A0 80")
     ("\xf4\x90\x80\x80" "F4 90 80 80, beyond U+10FFFF")
     ("\xf5\x80\x80\x80" "F5, never a lead byte")
     ("\x80" "a continuation byte alone")
     ("\xc3" "a sequence cut by the closing quote")
     ("\xe2\x82 " "a sequence cut by a space")
     ("\\n\xed\xa0\x80" "a surrogate after an escape" 11))))

(test-group "json: malformed text names the line and column"
  (for-each
   (lambda (c)
     (let ((r (js-error (car c))))
       (test-assert (sprintf "~s: ~a" (car c) (cadr r))
                    (and (eq? (car r) 'json)
                         (substring-index "t.json: line " (cadr r))
                         (substring-index (cadr c) (cadr r))))))
   '(("" "line 1, column 1: unexpected end")
     ("[1,]" "line 1, column 4: unexpected #\\]")
     ("[1 2]" "line 1, column 4: expected , or ]")
     ("{\"a\":1,}" "line 1, column 8: expected a key")
     ("{a:1}" "expected a key")
     ("{\"a\" 1}" "expected : after the key \"a\"")
     ("[01]" "may not start with 0")
     ("[1.]" "a digit must follow the decimal point")
     ("[1e]" "the exponent needs a digit")
     ("[-]" "a number needs a digit")
     ("[+1]" "unexpected #\\+")
     ("1e400" "out of range")
     ("\"abc" "the string never ends")
     ("\"a\nb\"" "a control character (code 10)")
     ("\"\\x\"" "unknown escape")
     ("\"\\u12\"" "four hex digits")
     ("\"\\ud800\"" "a lone surrogate")
     ("\"\\udc00x\"" "a lone surrogate")
     ("[1] 2" "after the value")
     ("tru" "unexpected #\\t")
     ("[1,\n  nul]" "line 2, column 3")
     ("// c\n1" "unexpected #\\/")
     ("{\"a\":[1,2" "the array never ends")
     ("'a'" "unexpected #\\'"))))

(test-group "json: nesting is limited"
  (test "1000 levels are read" 1000
        (let loop ((v (json-parse-string (string-append (make-string 999 #\[) "[]" (make-string 999 #\]))))
                   (d 1))
          (if (= 0 (vector-length v)) d (loop (vector-ref v 0) (+ d 1)))))
  (test-assert "1001 are an error naming json-max-depth"
               (substring-index "json-max-depth"
                                (cadr (js-error (string-append (make-string 1001 #\[) (make-string 1001 #\]))))))
  (test "the limit is a parameter" 3
        (parameterize ((json-max-depth 3)) (vector-length (json-parse-string "[[[1]], 2, 3]")))))
