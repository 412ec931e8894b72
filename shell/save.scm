;;; (downstroke save): a small Scheme value (settings, a high score, the
;;; key bindings) kept in a file under a name, in a given directory.
;;;
;;; (save-data-write! dir name value) stores value as dir/NAME.scm;
;;; (save-data-read dir name [default]) reads it back. NAME is a symbol or
;;; a string of letters, digits, - and _ (at most 64), so a name is never a
;;; path. The engine's game-save! and game-load put the directory where
;;; SDL keeps an application's per-user files (SDL_GetPrefPath); this
;;; module itself knows nothing of SDL.
;;;
;;; Only data is stored, in the text (downstroke save-text) writes and
;;; alone reads: booleans, real numbers (not NaN, at most
;;; save-data-max-digits digits), characters, strings, symbols, keywords,
;;; the empty list, pairs and vectors of those, at most save-data-max-size
;;; bytes and save-data-max-nodes objects (which also stops a circular
;;; list). Anything else is an error naming the name and what was found.
;;;
;;; Writing never leaves a half-written file, and a failed write is an
;;; error that leaves the old value: the text goes to a temporary file
;;; NAME.scm.tmp.PID.RANDOM in the same directory, created afresh
;;; (O_CREAT|O_EXCL|O_NOFOLLOW, mode 0600, so a planted file or symbolic
;;; link is never opened and two writers never share one), written whole
;;; (a short write, a full disk, a file-size limit are errors), flushed to
;;; the disk (fsync) and closed, and only then renamed over NAME.scm
;;; (rename is atomic and replaces a link rather than following it); then
;;; the directory is synced. Each failing system call's errno is read at
;;; once and named in the error. A crash leaves the old value or the new
;;; one, and perhaps a temporary file, which a later write of the name
;;; removes once the process that made it is gone.
;;;
;;; Reading never evaluates anything and never blocks: the file is opened
;;; with O_NOFOLLOW|O_NONBLOCK, must be a regular file (not a link, FIFO,
;;; device or directory) of at most save-data-max-size bytes, and its text
;;; must be exactly one datum of the writer's syntax. A missing file gives
;;; the default, or an error without one; a corrupt one (not a regular
;;; file, unreadable syntax, truncated, too large) and a directory name the
;;; system cannot take (a NUL byte, longer than PATH_MAX) give the default
;;; when one is given, else an error naming the file and what is wrong.
;;; Every error of this module has the condition kind save-data
;;; (save-data-error?).

(module (downstroke save)
  (save-data-write! save-data-read save-data-exists? save-data-delete!
   save-data-path save-data-error? save-data-max-size save-data-max-nodes
   save-data-max-digits
   ;; for sibling modules only (and the tests): a procedure called as
   ;; (hook stage path) while writing: stage 'create with the temporary
   ;; file's path just before it is created, 'partial when half the bytes
   ;; are in it; the tests plant a link there, or end the process
   save-data-write-hook)

  (import scheme (chicken base) (chicken format) (chicken condition) (chicken foreign)
          (chicken string) (chicken blob) (chicken random)
          (only (chicken file) directory)
          (only (chicken process-context posix) current-process-id)
          (downstroke save-text))

  (foreign-declare #<<EOF
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <string.h>
#include <unistd.h>
#include <sys/stat.h>
#include <sys/types.h>
#ifndef O_CLOEXEC
#define O_CLOEXEC 0
#endif
#ifndef PATH_MAX
#define PATH_MAX 4096
#endif
/* Each returns at once what the system said: a descriptor or a count,
   or minus errno, so no later call can overwrite the reason. */
static int ds_create(const char *path)
{ int fd = open(path, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_NOCTTY | O_CLOEXEC, 0600);
  return fd < 0 ? -errno : fd; }
static int ds_open_read(const char *path)
{ int fd = open(path, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  return fd < 0 ? -errno : fd; }
/* All of buf[start, end), however many calls write needs: 0 or minus errno. */
static int ds_write_all(int fd, const char *buf, int start, int end)
{ while (start < end) {
    ssize_t n = write(fd, buf + start, (size_t)(end - start));
    if (n < 0) { if (errno == EINTR) continue; return -errno; }
    if (n == 0) return -EIO;
    start += (int)n; }
  return 0; }
static int ds_read(int fd, char *buf, int start, int count)
{ for (;;) { ssize_t n = read(fd, buf + start, (size_t)count);
    if (n < 0 && errno == EINTR) continue;
    return n < 0 ? -errno : (int)n; } }
static int ds_fsync(int fd) { return fsync(fd) == 0 ? 0 : -errno; }
/* After a successful fsync an interrupted close has nothing left to lose. */
static int ds_close(int fd) { return close(fd) == 0 || errno == EINTR ? 0 : -errno; }
static int ds_rename(const char *from, const char *to) { return rename(from, to) == 0 ? 0 : -errno; }
static int ds_unlink(const char *path) { return unlink(path) == 0 ? 0 : -errno; }
/* 0 a regular file, 1 a directory, 2 a symbolic link, 3 anything else, or minus errno. */
static int ds_kind(struct stat *st)
{ return S_ISREG(st->st_mode) ? 0 : S_ISDIR(st->st_mode) ? 1 : S_ISLNK(st->st_mode) ? 2 : 3; }
static int ds_fd_kind(int fd) { struct stat st; return fstat(fd, &st) ? -errno : ds_kind(&st); }
static int ds_path_kind(const char *path) { struct stat st; return lstat(path, &st) ? -errno : ds_kind(&st); }
static int ds_dir_kind(const char *path) { struct stat st; return stat(path, &st) ? -errno : ds_kind(&st); }
static double ds_fd_size(int fd) { struct stat st; return fstat(fd, &st) ? -1.0 : (double)st.st_size; }
static int ds_process_gone(int pid) { return pid > 0 && kill((pid_t)pid, 0) != 0 && errno == ESRCH; }
static void ds_sync_dir(const char *path)
{ int fd = open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd >= 0) { fsync(fd); close(fd); } }
EOF
)

  (define save-data-max-size (make-parameter (* 1024 1024)))
  (define save-data-write-hook (make-parameter #f))

  (define c-create (foreign-lambda int "ds_create" nonnull-c-string))
  (define c-open-read (foreign-lambda int "ds_open_read" nonnull-c-string))
  (define c-write-all (foreign-lambda int "ds_write_all" int scheme-pointer int int))
  (define c-read (foreign-lambda int "ds_read" int scheme-pointer int int))
  (define c-fsync (foreign-lambda int "ds_fsync" int))
  (define c-close (foreign-lambda int "ds_close" int))
  (define c-rename (foreign-lambda int "ds_rename" nonnull-c-string nonnull-c-string))
  (define c-unlink (foreign-lambda int "ds_unlink" nonnull-c-string))
  (define c-fd-kind (foreign-lambda int "ds_fd_kind" int))
  (define c-path-kind (foreign-lambda int "ds_path_kind" nonnull-c-string))
  (define c-dir-kind (foreign-lambda int "ds_dir_kind" nonnull-c-string))
  (define c-fd-size (foreign-lambda double "ds_fd_size" int))
  (define c-process-gone? (foreign-lambda bool "ds_process_gone" int))
  (define c-sync-dir (foreign-lambda void "ds_sync_dir" nonnull-c-string))
  (define c-strerror (foreign-lambda c-string "strerror" int))
  (define path-max (foreign-value "PATH_MAX" int))
  (define errno/noent (foreign-value "ENOENT" int))
  (define errno/notdir (foreign-value "ENOTDIR" int))
  (define errno/exist (foreign-value "EEXIST" int))
  (define errno/loop (foreign-value "ELOOP" int))
  (define errno/nametoolong (foreign-value "ENAMETOOLONG" int))

  ;; The system's sentence for a minus-errno result.
  (define (reason r) (c-strerror (- r)))

  (define (fail who fmt . args)
    (signal (make-composite-condition
             (make-property-condition 'exn 'location who 'message (apply sprintf fmt args)
                                      'arguments '())
             (make-property-condition 'save-data))))

  (define (save-data-error? c) (and (condition? c) ((condition-predicate 'save-data) c)))

  ;;; Names and paths.

  (define (name-char? c)
    (or (char-alphabetic? c) (char-numeric? c) (memv c '(#\- #\_))))

  (define (name-string who name)
    (let ((s (cond ((symbol? name) (symbol->string name))
                   ((string? name) name)
                   (else (fail who "the name ~s must be a symbol or a string" name)))))
      (unless (and (< 0 (string-length s) 65)
                   (let loop ((i 0))
                     (or (= i (string-length s))
                         (and (char<? (string-ref s i) #\x80) (name-char? (string-ref s i))
                              (loop (+ i 1))))))
        (fail who "the name ~s must be 1 to 64 letters, digits, - or _" name))
      s))

  (define (check-dir who dir)
    (unless (and (string? dir) (> (string-length dir) 0))
      (fail who "the directory must be a non-empty string, got ~s" dir)))

  ;; A path in a message: whole, unless it is very long (a hostile name
  ;; over PATH_MAX); then its start and its end, where the file's own name is.
  (define (shown s)
    (let ((n (string-length s)))
      (if (> n 160)
          (string-append (substring s 0 60) "..." (substring s (- n 80) n))
          s)))

  ;; Why the system cannot be handed this path, or #f.
  (define (path-problem path)
    (cond ((substring-index (string #\nul) path) "the directory's name has a NUL byte")
          ((>= (string-length path) path-max)
           (sprintf "the path would be ~a bytes, over the system's PATH_MAX (~a)"
                    (string-length path) path-max))
          (else #f)))

  (define (save-data-path dir name)
    (check-dir 'save-data-path dir)
    (string-append dir (if (char=? #\/ (string-ref dir (- (string-length dir) 1))) "" "/")
                   (name-string 'save-data-path name) ".scm"))

  ;; The longest temporary name beside a path: .tmp, a pid, 16 hex digits.
  (define temp-suffix-room 40)

  (define (temp-path path)
    (let ((r (random-bytes (make-blob 8))))
      (sprintf "~a.tmp.~a.~a" path (current-process-id)
               (apply string-append
                      (map (lambda (c) (let ((s (number->string (char->integer c) 16)))
                                         (if (< (string-length s) 2) (string-append "0" s) s)))
                           (string->list (blob->string r)))))))

  ;;; Writing.

  ;; The file's text: a comment saying what it is, the value, a newline.
  (define (file-text who n value)
    (let ((kind (data-problem value)))
      (when kind
        (fail who "cannot save ~s: the value holds ~a; only data (numbers, strings, symbols, lists, vectors ...) is saved"
              n kind)))
    (let ((text (condition-case (string-append ";; downstroke save data " n "\n" (datum->save-text value) "\n")
                  (e (save-text) (fail who "cannot save ~s: the value holds ~a" n (save-text-error-message e))))))
      (when (> (string-length text) (save-data-max-size))
        (fail who "cannot save ~s: ~a bytes written out, over save-data-max-size (~a)"
              n (string-length text) (save-data-max-size)))
      ;; what is written must read back the same
      (let ((back (condition-case (save-text->datum text)
                    (e (save-text) (fail who "cannot save ~s: ~a" n (save-text-error-message e))))))
        (unless (equal? back value)
          (fail who "cannot save ~s: the value does not read back the same" n)))
      text))

  ;; A fresh temporary file beside path: (values fd temp). A name that is
  ;; taken (by another writer, a crash, a planted link) is passed over.
  (define (create-temp who n path)
    (let retry ((tries 0))
      (let ((tmp (temp-path path)))
        (let ((hook (save-data-write-hook))) (when hook (hook 'create tmp)))
        (let ((fd (c-create tmp)))
          (cond ((>= fd 0) (values fd tmp))
                ((and (= fd (- errno/exist)) (< tries 15)) (retry (+ tries 1)))
                (else (fail who "cannot save ~s: cannot create ~s: ~a" n tmp (reason fd))))))))

  (define (save-data-write! dir name value)
    (let* ((who 'save-data-write!)
           (n (name-string who name))
           (path (save-data-path dir name))
           (text (file-text who n value)))
      (let ((bad (path-problem (string-append path (make-string temp-suffix-room #\x)))))
        (when bad (fail who "cannot save ~s in ~s: ~a" n (shown dir) bad)))
      (let ((k (c-dir-kind dir)))
        (unless (= k 1)
          (fail who "cannot save ~s: no directory ~s (~a)" n dir
                (cond ((< k 0) (reason k)) (else "it is not a directory")))))
      (receive (fd tmp) (create-temp who n path)
        ;; an error from here on removes the temporary file; the old value stays
        (define (give-up fmt . args)
          (when fd (c-close fd))
          (c-unlink tmp)
          (apply fail who (string-append "cannot save ~s: " fmt) n args))
        (define (step! r what)
          (when (< r 0) (give-up "~a ~s: ~a" what tmp (reason r))))
        (let ((half (quotient (string-length text) 2)))
          (step! (c-write-all fd text 0 half) "writing")
          (let ((hook (save-data-write-hook))) (when hook (hook 'partial tmp)))
          (step! (c-write-all fd text half (string-length text)) "writing")
          (step! (c-fsync fd) "flushing (fsync)")
          (let ((r (c-close fd)))
            (set! fd #f)
            (step! r "closing"))
          (let ((r (c-rename tmp path)))
            (when (< r 0) (give-up "renaming ~s to ~s: ~a" tmp path (reason r))))
          ;; best effort: some file systems refuse to sync a directory
          (c-sync-dir dir)
          (remove-stale-temps! dir (string-append n ".scm.tmp."))
          (void)))))

  ;; Temporary files of this name left by processes that are gone (a
  ;; crash mid-write); those of a live writer stay.
  (define (remove-stale-temps! dir prefix)
    (for-each
     (lambda (entry)
       (when (and (> (string-length entry) (string-length prefix))
                  (string=? prefix (substring entry 0 (string-length prefix))))
         (let* ((rest (substring entry (string-length prefix)))
                (dot (substring-index "." rest))
                (digits (and dot (< 0 dot 10) (substring rest 0 dot)))
                (pid (and digits (every-digit? digits) (string->number digits))))
           (when (and (exact-integer? pid) (not (= pid (current-process-id))) (c-process-gone? pid))
             (c-unlink (string-append dir "/" entry))))))
     (condition-case (directory dir #t) (e () '()))))

  (define (every-digit? s)
    (let loop ((i 0))
      (or (= i (string-length s)) (and (char-numeric? (string-ref s i)) (loop (+ i 1))))))

  ;;; Reading.

  (define no-default (list 'no-default))

  ;; The file's text, or (values #f what-is-wrong kind) with kind one of
  ;; missing, corrupt (the default stands in), error (it does not).
  (define (file-text-of path limit)
    (let ((fd (c-open-read path)))
      (cond ((< fd 0)
             (cond ((memv (- fd) (list errno/noent errno/notdir)) (values #f "no file" 'missing))
                   ((= (- fd) errno/loop) (values #f "it is a symbolic link, which is not followed" 'corrupt))
                   ((= (- fd) errno/nametoolong) (values #f (reason fd) 'corrupt))
                   (else (values #f (reason fd) 'error))))
            (else
             (let ((kind (c-fd-kind fd)) (size (c-fd-size fd)))
               (define (done . results) (c-close fd) (apply values results))
               (cond ((< kind 0) (done #f (reason kind) 'error))
                     ((= kind 1) (done #f "it is a directory" 'corrupt))
                     ((not (= kind 0)) (done #f "it is not a regular file (a FIFO, device or socket)" 'corrupt))
                     ((> size limit)
                      (done #f (sprintf "~a bytes, over save-data-max-size (~a)" (inexact->exact size) limit)
                            'corrupt))
                     (else
                      ;; room for one byte more than fstat said, which
                      ;; tells a file that grows while it is read
                      (let* ((room (+ (inexact->exact size) 1)) (buf (make-string room)))
                        (let loop ((got 0))
                          (let ((r (if (= got room) 0 (c-read fd buf got (- room got)))))
                            (cond ((< r 0) (done #f (reason r) 'error))
                                  ((> r 0) (loop (+ got r)))
                                  ((= got room) (done #f "it grew while it was read" 'corrupt))
                                  (else (done (substring buf 0 got) #f #f)))))))))))))

  (define (save-data-read dir name #!optional (default no-default))
    (check-dir 'save-data-read dir)
    (let* ((who 'save-data-read)
           (n (name-string who name))
           (path (save-data-path dir name))
           (corrupt (lambda (what)
                      (if (eq? default no-default)
                          (fail who "the save data ~s (~s) is corrupt: ~a" n (shown path) what)
                          default)))
           (bad (path-problem path)))
      (if bad
          (if (eq? default no-default)
              (fail who "cannot read the save data ~s in ~s: ~a" n (shown dir) bad)
              default)
          (receive (text what kind) (file-text-of path (save-data-max-size))
            (case kind
              ((missing) (if (eq? default no-default)
                             (fail who "no save data ~s (no file ~s)" n path)
                             default))
              ((corrupt) (corrupt what))
              ((error) (fail who "cannot read the save data ~s (~s): ~a" n path what))
              (else
               (if (string=? text "")
                   (corrupt "the file is empty")
                   (condition-case (save-text->datum text)
                     (e (save-text) (corrupt (save-text-error-message e)))))))))))

  ;; #t when a regular file (not a link) holds the name; a directory the
  ;; system cannot take holds nothing.
  (define (save-data-exists? dir name)
    (let ((path (save-data-path dir name)))
      (and (not (path-problem path)) (= 0 (c-path-kind path)))))

  (define (save-data-delete! dir name)
    (let ((path (save-data-path dir name)))
      (let ((bad (path-problem path)))
        (when bad (fail 'save-data-delete! "cannot delete the save data in ~s: ~a" (shown dir) bad)))
      (let ((r (c-unlink path)))
        (unless (or (= r 0) (= r (- errno/noent)))
          (fail 'save-data-delete! "cannot delete the save data ~s: ~a" path (reason r))))
      (void))))
