;;; Tests for (downstroke decode): base64, zlib, gzip, zstd and LE words.
(import (downstroke test) (downstroke decode)
        scheme (chicken base) (chicken condition) (chicken string) (chicken random)
        (chicken bitwise) srfi-4)

;; A decode-error whose message contains text.
(define (dec-error-mentions text)
  (lambda (exn) (and (decode-error? exn) (substring-index text (error-text exn)) #t)))

;; A decode-error whose message is exactly text.
(define (dec-error-is text)
  (lambda (exn) (and (decode-error? exn) (string=? text (error-text exn)))))

;; A decode-error with this problem symbol.
(define (dec-problem problem)
  (lambda (exn)
    (and (decode-error? exn)
         (eq? problem ((condition-property-accessor 'decode-error 'problem) exn)))))

(define (dec-bytes str)
  (let* ((n (string-length str)) (v (make-u8vector n)))
    (do ((i 0 (+ i 1))) ((= i n) v)
      (u8vector-set! v i (char->integer (string-ref str i))))))

(define (dec-string v)
  (let* ((n (u8vector-length v)) (s (make-string n)))
    (do ((i 0 (+ i 1))) ((= i n) s)
      (string-set! s i (integer->char (u8vector-ref v i))))))

;; Deterministic pseudo-random bytes (a 31-bit LCG), so failures reproduce.
(define (dec-noise n seed)
  (let ((v (make-u8vector n)))
    (let loop ((i 0) (x seed))
      (if (= i n)
          v
          (let ((x (modulo (+ (* x 1103515245) 12345) 2147483648)))
            (u8vector-set! v i (quotient x 8388608))
            (loop (+ i 1) x))))))

;; Text-like data that compresses well.
(define (dec-text n)
  (let ((v (make-u8vector n)) (words "tile layer object map gid 0,1,2,3\n"))
    (do ((i 0 (+ i 1))) ((= i n) v)
      (u8vector-set! v i (char->integer (string-ref words (modulo (* i 7) (string-length words))))))))

(define (dec-append a b)
  (let* ((na (u8vector-length a)) (nb (u8vector-length b)) (v (make-u8vector (+ na nb))))
    (do ((i 0 (+ i 1))) ((= i na)) (u8vector-set! v i (u8vector-ref a i)))
    (do ((i 0 (+ i 1))) ((= i nb) v) (u8vector-set! v (+ na i) (u8vector-ref b i)))))

(define (dec-prefix v n) (subu8vector v 0 n))

(define (dec-flip v i)
  (let ((c (subu8vector v 0 (u8vector-length v))))
    (u8vector-set! c i (bitwise-xor (u8vector-ref c i) #xff))
    c))

;; 'ok when (thunk) returns a u8vector, 'error for a decode-error; any
;; other outcome is returned as text so the test shows it.
(define (dec-outcome thunk)
  (call/cc
   (lambda (k)
     (with-exception-handler
      (lambda (exn) (k (if (decode-error? exn) 'error (error-text exn))))
      (lambda () (if (u8vector? (thunk)) 'ok 'not-a-u8vector))))))

;; How many prefixes of v, shorter than v, decode raises a decode-error on.
(define (dec-truncations-raising decode v)
  (let loop ((i 0) (n 0))
    (if (= i (u8vector-length v))
        n
        (loop (+ i 1) (if (eq? 'error (dec-outcome (lambda () (decode (dec-prefix v i))))) (+ n 1) n)))))

;; Fixtures made independently: python3's zlib and gzip modules, and the
;; zstd 1.5.4 command-line tool reading stdin (so its frame carries no
;; content size and is decoded by streaming). The data is 16 little-endian
;; tile ids: 1..12, then 1 and 2 and 3 with Tiled's flip flags, then 0.
(define dec-fixture-ids
  (u32vector 1 2 3 4 5 6 7 8 9 10 11 12 #x80000001 #x40000002 #x20000003 0))
(define dec-fixture-raw
  "AQAAAAIAAAADAAAABAAAAAUAAAAGAAAABwAAAAgAAAAJAAAACgAAAAsAAAAMAAAAAQAAgAIAAEADAAAgAAAAAA==")
(define dec-fixture-zlib "eNoNyscNACAAgEDsdQhHcTRHl8c9SAhAVFJWUVVT19DU0laA53/9j8kHFHABNQ==")
(define dec-fixture-gzip "H4sIAAAAAAAC/w3Kxw0AIACAQOx1CEdxNEeXxz1ICEBUUlZRVVPX0NTSVoDnf/2PyQfBkUJlQAAAAA==")
(define dec-fixture-zstd "KLUv/QRoLQEAAkQID8BrDf+/v/7F7S7Z7iYyBb8ObNC+q6ejn5uXk4+Lh4NfAM2fo6k=")
;; "The quick brown fox jumps over the lazy dog.\n" 20 times (900 bytes).
(define dec-fox-line "The quick brown fox jumps over the lazy dog.\n")
(define dec-fox-zlib "eJwLyUhVKCzNTM5WSCrKL89TSMuvUMgqzS0oVsgvSy1SKAFK5yRWVSqk5KfrcYWMKh5VPKqY2ooBZvxBZA==")
(define dec-fox-gzip "H4sIAAAAAAAC/wvJSFUoLM1MzlZIKsovz1NIy69QyCrNLShWyC9LLVIoAUrnJFZVKqTkp+txhYwqHlU8qpjaigHFDdBWhAMAAA==")
(define dec-fox-zstd "KLUv/QRYtQEA1AJUaGUgcXVpY2sgYnJvd24gZm94IGp1bXBzIG92ZXIgdGhlIGxhenkgZG9nLgoBAKUKK1UGv8tYpg==")
;; Two gzip members, "abc" then "def" (python3 gzip.compress twice).
(define dec-two-members "H4sIAAAAAAACA0tMSgYAwkEkNQMAAAAfiwgAAAAAAAIDS0lNAwBh4cQMAwAAAA==")

(define (dec-fox)
  (let loop ((n 20) (acc '()))
    (if (zero? n) (string-intersperse acc "") (loop (- n 1) (cons dec-fox-line acc)))))

(test-group "decode: base64 (RFC 4648 section 10 vectors)"
  (for-each
   (lambda (pair)
     (test (string-append "decode \"" (cadr pair) "\"") (car pair)
           (dec-string (base64-decode (cadr pair))))
     (test (string-append "encode \"" (car pair) "\"") (cadr pair)
           (base64-encode (dec-bytes (car pair)))))
   '(("" "") ("f" "Zg==") ("fo" "Zm8=") ("foo" "Zm9v") ("foob" "Zm9vYg==")
     ("fooba" "Zm9vYmE=") ("foobar" "Zm9vYmFy")))
  (test "result is a u8vector" #t (u8vector? (base64-decode "Zm9v")))
  (test "empty input" (u8vector) (base64-decode ""))
  (test "whitespace only" (u8vector) (base64-decode " \n\t\r "))
  (test "ASCII whitespace anywhere is ignored" "foobar"
        (dec-string (base64-decode " Zm9v\n  YmFy\r\n\t")))
  (test "whitespace between padding" "f" (dec-string (base64-decode "Zg=\n=\n")))
  (test "unpadded input accepted (2 left over)" "foob" (dec-string (base64-decode "Zm9vYg")))
  (test "unpadded input accepted (3 left over)" "fooba" (dec-string (base64-decode "Zm9vYmE")))
  (test "all 62/63 characters" (u8vector #xfb #xff #xbf) (base64-decode "+/+/"))
  (let ((all (let ((v (make-u8vector 256)))
               (do ((i 0 (+ i 1))) ((= i 256) v) (u8vector-set! v i i)))))
    (test "every byte value round-trips" all (base64-decode (base64-encode all))))
  (let ((big (dec-noise 100003 7)))
    (test "100 KB round trip" big (base64-decode (base64-encode big))))
  (test "Tiled-style layer data, decoded to words" dec-fixture-ids
        (u8vector->u32vector-le (base64-decode (string-append "\n   " dec-fixture-raw "\n  "))))
  (test-error "invalid character named with its position"
              (dec-error-is "base64-decode: invalid character #\\! (byte 33) at position 4")
              (base64-decode "Zm9v!mFy"))
  (test-error "URL-safe alphabet is not accepted"
              (dec-error-is "base64-decode: invalid character #\\- (byte 45) at position 1")
              (base64-decode "Z-9v"))
  (test-error "non-ASCII byte" (dec-error-is "base64-decode: invalid character byte 195 at position 2")
              (base64-decode "Zm\xc3\xa9"))
  (test-error "NUL byte" (dec-error-mentions "invalid character byte 0 at position 0")
              (base64-decode (string (integer->char 0))))
  (test-error "data after padding" (dec-error-is "base64-decode: data after padding: #\\Z (byte 90) at position 4")
              (base64-decode "Zg==Zg=="))
  (test-error "one character left over" (dec-problem 'bad-length) (base64-decode "Zm9vY"))
  (test-error "bad length names count and position"
              (dec-error-mentions "bad length: 5 base64 characters (with padding) at position 5")
              (base64-decode "Zm9vY"))
  (test-error "too little padding" (dec-problem 'bad-length) (base64-decode "Zg="))
  (test-error "too much padding" (dec-problem 'bad-length) (base64-decode "Zg==="))
  (test-error "padding alone" (dec-problem 'bad-length) (base64-decode "===="))
  (test-error "padding on a full quantum" (dec-problem 'bad-length) (base64-decode "Zm9v===="))
  (test-error "not a string" (dec-problem 'bad-argument) (base64-decode (u8vector 1)))
  (test-error "encode wants a u8vector" (dec-problem 'bad-argument) (base64-encode "abc")))

(test-group "decode: known answers from independent tools"
  (test "zlib (python3 zlib)" dec-fixture-ids
        (u8vector->u32vector-le (zlib-inflate (base64-decode dec-fixture-zlib))))
  (test "gzip (python3 gzip)" dec-fixture-ids
        (u8vector->u32vector-le (gzip-inflate (base64-decode dec-fixture-gzip))))
  (test "zstd (zstd CLI, no content size in the frame)" dec-fixture-ids
        (u8vector->u32vector-le (zstd-decompress (base64-decode dec-fixture-zstd))))
  (test "zlib text" (dec-fox) (dec-string (zlib-inflate (base64-decode dec-fox-zlib))))
  (test "gzip text" (dec-fox) (dec-string (gzip-inflate (base64-decode dec-fox-gzip))))
  (test "zstd text" (dec-fox) (dec-string (zstd-decompress (base64-decode dec-fox-zstd))))
  (test "gzip with two members" "abcdef"
        (dec-string (gzip-inflate (base64-decode dec-two-members)))))

(test-group "decode: round trips"
  (for-each
   (lambda (case)
     (let ((name (car case)) (data (cadr case)))
       (test (string-append "zlib " name) data (zlib-inflate (zlib-deflate data)))
       (test (string-append "gzip " name) data (gzip-inflate (gzip-deflate data)))
       (test (string-append "zstd " name) data (zstd-decompress (zstd-compress data)))))
   (list (list "empty" (u8vector))
         (list "one byte" (u8vector 42))
         (list "small" (dec-bytes "hello, tiles"))
         (list "1 MiB text" (dec-text (* 1024 1024)))
         (list "1 MiB noise" (dec-noise (* 1024 1024) 1))
         (list "1 MiB zeros" (make-u8vector (* 1024 1024) 0))))
  (let ((data (dec-text 100000)))
    (test "zlib level 0" data (zlib-inflate (zlib-deflate data level: 0)))
    (test "zlib level 9" data (zlib-inflate (zlib-deflate data level: 9)))
    (test "gzip level 1" data (gzip-inflate (gzip-deflate data level: 1)))
    (test "zstd level 19" data (zstd-decompress (zstd-compress data level: 19)))
    (test "zstd negative level" data (zstd-decompress (zstd-compress data level: -5)))
    (test-error "bad zlib level" (dec-problem 'bad-argument) (zlib-deflate data level: 10))
    (test-error "bad zstd level" (dec-problem 'bad-argument) (zstd-compress data level: 99)))
  (test "zlib output is a zlib stream" '(#x78 #x9c)
        (let ((z (zlib-deflate (dec-bytes "x")))) (list (u8vector-ref z 0) (u8vector-ref z 1))))
  (test "gzip output has the gzip magic" '(#x1f #x8b)
        (let ((z (gzip-deflate (dec-bytes "x")))) (list (u8vector-ref z 0) (u8vector-ref z 1))))
  (test "zstd output has the zstd magic" '(#x28 #xb5 #x2f #xfd)
        (let ((z (zstd-compress (dec-bytes "x"))))
          (list (u8vector-ref z 0) (u8vector-ref z 1) (u8vector-ref z 2) (u8vector-ref z 3))))
  (test "the three formats are not interchangeable" '(error error error)
        (let ((data (dec-bytes "interchangeable?")))
          (list (dec-outcome (lambda () (zlib-inflate (gzip-deflate data))))
                (dec-outcome (lambda () (gzip-inflate (zstd-compress data))))
                (dec-outcome (lambda () (zstd-decompress (zlib-deflate data))))))))

(test-group "decode: corrupt and truncated input"
  (let ((z (base64-decode dec-fixture-zlib))
        (g (base64-decode dec-fixture-gzip))
        (s (base64-decode dec-fixture-zstd))
        (s2 (zstd-compress (dec-text 5000))))
    (test-error "zlib: bad header" (dec-error-is "zlib-inflate: corrupt input: incorrect header check")
                (zlib-inflate (dec-flip z 0)))
    (test-error "zlib: bad checksum" (dec-error-is "zlib-inflate: corrupt input: incorrect data check")
                (zlib-inflate (dec-flip z (- (u8vector-length z) 1))))
    (test-error "zlib: truncated" (dec-error-is "zlib-inflate: truncated input (the stream ends early)")
                (zlib-inflate (dec-prefix z 20)))
    (test-error "zlib: empty" (dec-error-is "zlib-inflate: empty input") (zlib-inflate (u8vector)))
    (test-error "zlib: trailing data"
                (dec-error-is "zlib-inflate: 3 bytes of trailing data after the end of the stream")
                (zlib-inflate (dec-append z (u8vector 1 2 3))))
    (test-error "zlib: garbage" (dec-problem 'corrupt) (zlib-inflate (dec-noise 1000 3)))
    (test-error "gzip: bad magic" (dec-error-mentions "gzip-inflate: corrupt input")
                (gzip-inflate (dec-flip g 0)))
    (test-error "gzip: bad CRC" (dec-error-is "gzip-inflate: corrupt input: incorrect data check")
                (gzip-inflate (dec-flip g (- (u8vector-length g) 6))))
    (test-error "gzip: bad length field" (dec-error-is "gzip-inflate: corrupt input: incorrect length check")
                (gzip-inflate (dec-flip g (- (u8vector-length g) 2))))
    (test-error "gzip: truncated" (dec-problem 'truncated) (gzip-inflate (dec-prefix g 15)))
    (test-error "gzip: given zlib data" (dec-problem 'corrupt) (gzip-inflate z))
    (test-error "gzip: garbage after a member" (dec-problem 'corrupt)
                (gzip-inflate (dec-append g (u8vector 1 2 3 4 5 6 7 8 9 10 11 12))))
    (test-error "zstd: bad magic" (dec-error-mentions "zstd-decompress: corrupt input: Unknown frame descriptor")
                (zstd-decompress (dec-flip s 0)))
    (test-error "zstd: bad checksum" (dec-error-mentions "zstd-decompress: corrupt input")
                (zstd-decompress (dec-flip s2 (- (u8vector-length s2) 1))))
    (test-error "zstd: truncated" (dec-error-is "zstd-decompress: truncated input (the stream ends early)")
                (zstd-decompress (dec-prefix s 30)))
    (test-error "zstd: empty" (dec-error-is "zstd-decompress: empty input") (zstd-decompress (u8vector)))
    (test-error "zstd: garbage" (dec-problem 'corrupt) (zstd-decompress (dec-noise 1000 3)))
    (test "zlib: every proper prefix raises" (u8vector-length z)
          (dec-truncations-raising zlib-inflate z))
    (test "gzip: every proper prefix raises" (u8vector-length g)
          (dec-truncations-raising gzip-inflate g))
    (test "zstd (CLI frame): every proper prefix raises" (u8vector-length s)
          (dec-truncations-raising zstd-decompress s))
    (test "zstd (own frame): every proper prefix raises" (u8vector-length s2)
          (dec-truncations-raising zstd-decompress s2))
    (set-pseudo-random-seed! "downstroke-decode")
    (for-each
     (lambda (codec)
       (let ((name (car codec)) (decode (cadr codec)) (data (caddr codec)))
         (test (string-append name ": 1000 random corruptions each decode or raise") 1000
               (let loop ((k 0) (good 0))
                 (if (= k 1000)
                     good
                     (let ((c (subu8vector data 0 (u8vector-length data))))
                       (do ((j (+ 1 (pseudo-random-integer 3)) (- j 1))) ((zero? j))
                         (u8vector-set! c (pseudo-random-integer (u8vector-length c))
                                        (pseudo-random-integer 256)))
                       (loop (+ k 1)
                             (if (memq (dec-outcome (lambda () (decode c))) '(ok error))
                                 (+ good 1)
                                 good))))))))
     (list (list "zlib" zlib-inflate (zlib-deflate (dec-text 3000)))
           (list "gzip" gzip-inflate (gzip-deflate (dec-text 3000)))
           (list "zstd" zstd-decompress (zstd-compress (dec-text 3000)))
           (list "zstd CLI frame" zstd-decompress s)))
    (test-error "not a u8vector" (dec-problem 'bad-argument) (zlib-inflate "abc"))))

(test-group "decode: max-size refuses decompression bombs"
  (let* ((zeros (make-u8vector (* 1024 1024) 0))
         (z (zlib-deflate zeros))
         (g (gzip-deflate zeros))
         (s (zstd-compress zeros))
         (cli (base64-decode dec-fox-zstd)))
    (test "default bound is 256 MiB" (* 256 1024 1024) default-max-size)
    (test "1 MiB of zeros is small compressed" #t (< (u8vector-length z) 2000))
    (test-error "zlib over the bound" (dec-error-is "zlib-inflate: output exceeds max-size (1000 bytes)")
                (zlib-inflate z max-size: 1000))
    (test-error "gzip over the bound" (dec-error-is "gzip-inflate: output exceeds max-size (65536 bytes)")
                (gzip-inflate g max-size: 65536))
    (test-error "zstd over the bound (size known from the frame)"
                (dec-error-is "zstd-decompress: output exceeds max-size (1048575 bytes)")
                (zstd-decompress s max-size: (- (* 1024 1024) 1)))
    (test-error "zstd over the bound (streamed frame)" (dec-problem 'too-large)
                (zstd-decompress cli max-size: 899))
    (test "zstd streamed frame at exactly the bound" 900
          (u8vector-length (zstd-decompress cli max-size: 900)))
    (test "zlib exactly at the bound" (* 1024 1024)
          (u8vector-length (zlib-inflate z max-size: (* 1024 1024))))
    (test-error "zlib one byte under" (dec-problem 'too-large)
                (zlib-inflate z max-size: (- (* 1024 1024) 1)))
    (test "gzip exactly at the bound" (* 1024 1024)
          (u8vector-length (gzip-inflate g max-size: (* 1024 1024))))
    (test "zstd exactly at the bound" (* 1024 1024)
          (u8vector-length (zstd-decompress s max-size: (* 1024 1024))))
    (test "max-size 0 allows empty output" (u8vector)
          (zlib-inflate (zlib-deflate (u8vector)) max-size: 0))
    (test-error "max-size 0 refuses one byte" (dec-problem 'too-large)
                (zstd-decompress (zstd-compress (u8vector 1)) max-size: 0))
    (test "max-size #f lifts the bound" (* 1024 1024)
          (u8vector-length (gzip-inflate g max-size: #f)))
    (test-error "bad max-size" (dec-problem 'bad-argument) (zlib-inflate z max-size: -1))
    (test-error "bad max-size type" (dec-problem 'bad-argument) (zlib-inflate z max-size: 1.5))))

(test-group "decode: u8vector->u32vector-le"
  (test "empty" (u32vector) (u8vector->u32vector-le (u8vector)))
  (test "little-endian words" (u32vector 1 #x04030201 #xffffffff #x80000000)
        (u8vector->u32vector-le (u8vector 1 0 0 0  1 2 3 4  255 255 255 255  0 0 0 128)))
  (test "result is a u32vector" #t (u32vector? (u8vector->u32vector-le (u8vector 0 0 0 0))))
  (test-error "length not a multiple of 4"
              (dec-error-is "u8vector->u32vector-le: length 5 is not a multiple of 4")
              (u8vector->u32vector-le (u8vector 1 2 3 4 5)))
  (test-error "not a u8vector" (dec-problem 'bad-argument) (u8vector->u32vector-le (u32vector 1))))
