;;; (downstroke tilemap), mutation test: thousands of damaged maps (and
;;; damaged external tilesets and templates), in TMX and in Tiled's JSON
;;; formats (.tmj, .tsj, .tj). Each must either load or raise
;;; an error whose message names the damaged file's path and says more than
;;; that. Deterministic: a fixed-seed generator picks every mutation.

(import scheme (chicken base) (chicken format) (chicken string) (chicken file)
        (chicken process) (chicken pathname) (chicken io) (chicken time)
        (chicken condition) (chicken process-context)
        (downstroke test) (downstroke tilemap))

;; How many mutants per base file (DOWNSTROKE_FUZZ_N overrides).
(define fuzz-tmx-per-file
  (let ((n (get-environment-variable "DOWNSTROKE_FUZZ_N")))
    (or (and n (string->number n)) 400)))

;; A 31-bit linear congruential generator (Park-Miller), fixed seed.
(define fuzz-tmx-seed 20240611)
(define (fuzz-tmx-random n)
  (set! fuzz-tmx-seed (modulo (* fuzz-tmx-seed 48271) 2147483647))
  (modulo fuzz-tmx-seed n))

(define (fuzz-tmx-read path) (with-input-from-file path (lambda () (read-string #f))))

(define fuzz-tmx-values
  '("" "-1" "0" "abc" "99999999999" "1e400" "+nan.0" "-inf.0" "#x10" "1.5" "zstd" "gzip"
    "csv" "base64" "lzma" "../../nowhere.png" "hexagonal" "1" "4294967297" " " "&amp;" "true"))

;; One mutation of text.
(define (fuzz-tmx-mutate text)
  (let* ((n (string-length text))
         (pos (fuzz-tmx-random (max n 1)))
         (kind (fuzz-tmx-random 7)))
    (case kind
      ((0) (substring text 0 pos))                         ; truncation
      ((1) (string-append (substring text 0 pos)           ; byte flip
                          (string (integer->char (+ 1 (fuzz-tmx-random 126))))
                          (substring text (min n (+ pos 1)) n)))
      ((2) (let ((digit (let loop ((i pos) (k 0))          ; change one digit
                          (cond ((>= k n) #f)
                                ((char-numeric? (string-ref text (modulo i n))) (modulo i n))
                                (else (loop (+ i 1) (+ k 1)))))))
             (if digit
                 (string-append (substring text 0 digit)
                                (number->string (fuzz-tmx-random 10))
                                (substring text (+ digit 1) n))
                 text)))
      ((3 4) (if (json-text? text)
                 (fuzz-json-value text pos)
                 (fuzz-xml-attribute text pos)))
      ((5) (let ((end (min n (+ pos 1 (fuzz-tmx-random 40)))))  ; deletion
             (string-append (substring text 0 pos) (substring text end n))))
      (else (let ((end (min n (+ pos 1 (fuzz-tmx-random 40)))))  ; duplication
              (string-append (substring text 0 end) (substring text pos n)))))))

(define (json-text? text) (and (> (string-length text) 0) (char=? (string-ref text 0) #\{)))

(define fuzz-json-values
  '("\"\"" "-1" "0" "\"abc\"" "99999999999" "1e400" "true" "false" "null" "[]" "{}" "1.5"
    "\"zstd\"" "\"base64\"" "\"csv\"" "4294967297" "\"../../nowhere.png\"" "[1,2" "\"#zz\""
    "[{\"x\":1}]" "\"tilelayer\"" "\"group\"" "-0.0" "1e308"))

;; A JSON member's value after pos replaced by another JSON token.
(define (fuzz-json-value text pos)
  (let* ((n (string-length text))
         (q (substring-index "\":" text pos)))
    (if q
        (let loop ((end (+ q 2)) (depth 0) (in-string? #f))
          (if (>= end n)
              (substring text 0 pos)
              (let ((c (string-ref text end)))
                (cond (in-string? (loop (+ end (if (char=? c #\\) 2 1)) depth (not (char=? c #\"))))
                      ((char=? c #\") (loop (+ end 1) depth #t))
                      ((memv c '(#\[ #\{)) (loop (+ end 1) (+ depth 1) #f))
                      ((and (memv c '(#\] #\})) (> depth 0)) (loop (+ end 1) (- depth 1) #f))
                      ((and (= depth 0) (memv c '(#\, #\] #\})))
                       (string-append (substring text 0 (+ q 2))
                                      (list-ref fuzz-json-values (fuzz-tmx-random (length fuzz-json-values)))
                                      (substring text end n)))
                      (else (loop (+ end 1) depth #f))))))
        (substring text 0 pos))))

(define (fuzz-xml-attribute text pos)
  (let ((n (string-length text)))
    (let ((q (substring-index "=\"" text pos)))    ; bad attribute value
               (if q
                   (let ((end (substring-index "\"" text (+ q 2))))
                     (if end
                         (string-append (substring text 0 (+ q 2))
                                        (list-ref fuzz-tmx-values
                                                  (fuzz-tmx-random (length fuzz-tmx-values)))
                                        (substring text end n))
                         text))
                   (substring text 0 pos)))))

(define fuzz-tmx-dir (create-temporary-directory))
(system (sprintf "cp -R maps/tilesets maps/images maps/templates maps/json '~a'/" fuzz-tmx-dir))

;; Damage `file` (relative to maps/) in the copy, load `map`, and restore.
;; Returns #t when the outcome is acceptable, else a description.
(define (fuzz-tmx-one map file text)
  (let* ((target (make-pathname fuzz-tmx-dir file))
         (map-path (make-pathname fuzz-tmx-dir map))
         (damaged (fuzz-tmx-mutate text)))
    (with-output-to-file target (lambda () (display damaged)))
    (let ((outcome
           (call/cc
            (lambda (k)
              (with-exception-handler
               (lambda (exn) (k (cons 'error exn)))
               (lambda () (cons 'ok (load-tilemap map-path))))))))
      (when (eq? (car outcome) 'error) (set! fuzz-tmx-errors (+ fuzz-tmx-errors 1)))
      (cond ((and (eq? (car outcome) 'ok) (tilemap? (cdr outcome))) #t)
            ((eq? (car outcome) 'ok) (sprintf "returned ~s" (cdr outcome)))
            ((not (condition? (cdr outcome))) (sprintf "raised a non-condition ~s" (cdr outcome)))
            (else
             (let ((msg (error-text (cdr outcome))))
               (if (and (substring-index fuzz-tmx-dir msg)
                        (> (string-length msg) (+ (string-length target) 8)))
                   #t
                   (sprintf "~a: unhelpful error ~s" file msg))))))))

(define fuzz-tmx-errors 0)

(define (fuzz-tmx-run map file)
  (let* ((source (fuzz-tmx-read (make-pathname "maps" file)))
         (pristine (make-pathname fuzz-tmx-dir file))
         (errors-before fuzz-tmx-errors) (problems '()))
    ;; the other files of the map stay intact
    (unless (equal? map file)
      (with-output-to-file (make-pathname fuzz-tmx-dir map)
        (lambda () (display (fuzz-tmx-read (make-pathname "maps" map))))))
    (do ((i 0 (+ i 1))) ((= i fuzz-tmx-per-file))
      (let ((r (fuzz-tmx-one map file source)))
        (unless (eq? r #t) (set! problems (cons r problems)))))
    (with-output-to-file pristine (lambda () (display source)))
    (test-assert (sprintf "some mutants of ~a are rejected, some load" file)
                 (< 0 (- fuzz-tmx-errors errors-before) fuzz-tmx-per-file))
    (test (sprintf "~a mutants of ~a (loading ~a): all load or name the file and the problem"
                   fuzz-tmx-per-file file map)
          '() (let ((p (reverse problems))) (if (> (length p) 3) (fuzz-tmx-head p 3) p)))))

(define (fuzz-tmx-head l k) (if (or (zero? k) (null? l)) '() (cons (car l) (fuzz-tmx-head (cdr l) (- k 1)))))

(test-group "mutated maps"
  (parameterize ((tilemap-max-cells 100000))
    (begin
      (for-each (lambda (f) (fuzz-tmx-run f f))
                '("enc-csv.tmx" "enc-xml.tmx" "enc-base64.tmx" "enc-zlib.tmx" "enc-gzip.tmx"
                  "enc-zstd.tmx" "infinite.tmx" "features.tmx"
                  ;; the hostile shapes, small: groups 12 deep with offsets,
                  ;; a 60-point polygon, 48 chunks in two layers
                  "hostile-nested.tmx" "hostile-chunks.tmx"))
      (fuzz-tmx-run "features.tmx" "tilesets/terrain.tsx")
      (fuzz-tmx-run "features.tmx" "templates/enemy.tx")
      ;; Tiled's JSON formats: a map (zstd cells, every shape, class and
      ;; list properties), its .tsj tileset and .tj template, and a .tmx
      ;; whose tileset is that .tsj
      (fuzz-tmx-run "json/level.tmj" "json/level.tmj")
      (fuzz-tmx-run "json/level.tmj" "json/terrain.tsj")
      (fuzz-tmx-run "json/level.tmj" "json/enemy.tj")
      (fuzz-tmx-run "json/level.tmx" "json/terrain.tsj"))))
