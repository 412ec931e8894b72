;;; (downstroke json): the strict JSON reader under Tiled's JSON formats.
;;; Values as RFC 8259 defines them, and every kind of malformed text
;;; refused with its line and column.

(import scheme (chicken base) (chicken string) (chicken format) (chicken condition)
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
