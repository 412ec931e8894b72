;;; (downstroke media-header): what an image or a WAV file says about
;;; itself in its first bytes, read before SDL_image or SDL_mixer decode
;;; it, so that a small hostile file cannot ask for gigabytes or hand
;;; SDL_mixer a header it divides by. Pure Scheme: it reads bytes, and
;;; loads no C library.

(module (downstroke media-header)
  (file-problem image-file-size wav-file-problem)

  (import scheme (chicken base) (chicken io) (chicken format) (chicken bitwise)
          (only (chicken file) file-exists?) (only (chicken file posix) regular-file?))

  ;; Why a path cannot be read as a file, or #f when it can: it must name
  ;; a regular file. A directory, a FIFO or /dev/stdin would block a loader
  ;; (or feed it for ever: /dev/zero); a NUL byte cannot reach the system
  ;; at all. The one rule for maps, images, sounds and fonts.
  (define (file-problem path)
    (cond ((let loop ((i 0))
             (and (< i (string-length path))
                  (or (char=? (string-ref path i) #\x0) (loop (+ i 1)))))
           "has a NUL byte in its name")
          ((not (file-exists? path)) "not found")
          ((not (regular-file? path)) "is not a regular file (a directory, device or pipe)")
          (else #f)))

  ;; The first n bytes of a file, as a string (shorter at its end).
  (define (file-head path n)
    (call-with-input-file path (lambda (in) (let ((s (read-string n in))) (if (eof-object? s) "" s)))
      #:binary))

  (define (byte s i) (if (< i (string-length s)) (char->integer (string-ref s i)) 0))
  (define (u16be s i) (+ (* 256 (byte s i)) (byte s (+ i 1))))
  (define (u16le s i) (+ (byte s i) (* 256 (byte s (+ i 1)))))
  (define (u24le s i) (+ (u16le s i) (* 65536 (byte s (+ i 2)))))
  (define (u32be s i) (+ (* 65536 (u16be s i)) (u16be s (+ i 2))))
  (define (u32le s i) (+ (u16le s i) (* 65536 (u16le s (+ i 2)))))
  (define (s32le s i) (let ((v (u32le s i))) (if (>= v 2147483648) (- v 4294967296) v)))
  (define (part s from to) (if (<= to (string-length s)) (substring s from to) ""))
  (define png-magic (list->string (map integer->char '(#x89 80 78 71 13 10 26 10))))
  (define jpeg-magic (list->string (map integer->char '(#xff #xd8))))
  (define (starts? s prefix)
    (and (>= (string-length s) (string-length prefix))
         (string=? (substring s 0 (string-length prefix)) prefix)))

  ;; An image file's width and height as its header gives them (PNG, GIF,
  ;; BMP, QOI, WebP, JPEG), or #f for a format this does not read.
  (define (image-file-size path)
    (let ((h (file-head path 64)))
      (cond ((starts? h png-magic) (list (u32be h 16) (u32be h 20)))
            ((or (starts? h "GIF87a") (starts? h "GIF89a")) (list (u16le h 6) (u16le h 8)))
            ((starts? h "BM") (list (abs (s32le h 18)) (abs (s32le h 22))))
            ((starts? h "qoif") (list (u32be h 4) (u32be h 8)))
            ((and (starts? h "RIFF") (string=? (part h 8 12) "WEBP")) (webp-size h))
            ((starts? h jpeg-magic) (jpeg-size path))
            (else #f))))

  (define (webp-size h)
    (let ((kind (part h 12 16)))
      (cond ((string=? kind "VP8 ") (list (bitwise-and (u16le h 26) #x3fff) (bitwise-and (u16le h 28) #x3fff)))
            ((string=? kind "VP8L")
             (let ((bits (u32le h 21)))
               (list (+ 1 (bitwise-and bits #x3fff)) (+ 1 (bitwise-and (arithmetic-shift bits -14) #x3fff)))))
            ((string=? kind "VP8X") (list (+ 1 (u24le h 24)) (+ 1 (u24le h 27))))
            (else #f))))

  ;; A JPEG's size is in its first start-of-frame segment, after any
  ;; number of others: walk the segments, reading only their lengths.
  (define (jpeg-size path)
    (call-with-input-file path
      (lambda (in)
        (read-string 2 in)
        (let loop ()
          (let ((m (read-string 4 in)))
            (cond ((or (eof-object? m) (< (string-length m) 4) (not (= (byte m 0) #xff))) #f)
                  ((memv (byte m 1) '(#xc0 #xc1 #xc2 #xc3 #xc5 #xc6 #xc7 #xc9 #xca #xcb #xcd #xce #xcf))
                   (let ((f (read-string 5 in)))
                     (and (string? f) (= (string-length f) 5) (list (u16be f 3) (u16be f 1)))))
                  ((< (u16be m 2) 2) #f)
                  (else (let ((skip (read-string (- (u16be m 2) 2) in)))
                          (and (string? skip) (loop))))))))
      #:binary))

  ;; Why SDL_mixer should not be given this WAV file, or #f: a RIFF WAVE
  ;; whose format chunk says 0 channels, 0 samples a second, 0 bytes a
  ;; block or 0 bits a sample (SDL divides by these; 0 channels once ended
  ;; a game with a floating-point exception). Other files are not judged.
  (define (wav-file-problem path)
    (let ((h (file-head path 4096)))
      (and (starts? h "RIFF")
           (string=? (part h 8 12) "WAVE")
           (let loop ((i 12))
             (cond ((> (+ i 8) (string-length h)) "a WAVE file without a format chunk in its first 4 KB")
                   ((string=? (part h i (+ i 4)) "fmt ")
                    (let ((channels (u16le h (+ i 10))) (rate (u32le h (+ i 12)))
                          (align (u16le h (+ i 20))) (bits (u16le h (+ i 22))))
                      (cond ((< (u32le h (+ i 4)) 16) "its format chunk is shorter than 16 bytes")
                            ((zero? channels) "its format chunk says 0 channels")
                            ((zero? rate) "its format chunk says 0 samples a second")
                            ((zero? align) "its format chunk says 0 bytes a block")
                            ((zero? bits) "its format chunk says 0 bits a sample")
                            (else #f))))
                   (else (loop (+ i 8 (u32le h (+ i 4)) (if (odd? (u32le h (+ i 4))) 1 0))))))))))
