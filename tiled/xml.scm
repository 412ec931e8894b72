;;; (downstroke xml): XML documents as SXML-shaped trees, parsed by expat.
;;;
;;;   (xml-parse-string "<map version=\"1.10\"><layer name=\"a\"/></map>")
;;;   => (*TOP* (map (@ (version "1.10")) (layer (@ (name "a")))))
;;;
;;; Shape of the tree:
;;;   - the whole document is (*TOP* root-element);
;;;   - an element is (name (@ (attr "value") ...) child ...), where name and
;;;     attr are symbols spelled exactly as in the document (no namespace
;;;     processing, so `xml:space` stays `xml:space`); the (@ ...) list comes
;;;     second and only when the element has attributes, in document order;
;;;   - text is a string; adjacent character data (including CDATA sections
;;;     and entity/character references) is merged into one string, and
;;;     whitespace-only text is kept. Comments and processing instructions
;;;     are dropped.
;;; Output strings are UTF-8 whatever the document's declared encoding.
;;;
;;; How it works: expat's callbacks run in C and append to a flat event
;;; buffer (no calls from C back into Scheme); after each chunk of input the
;;; buffer is copied out and folded into the tree on the Scheme side. Input is
;;; fed in chunks, so large files never sit in memory twice.
;;;
;;; Safety: external entities and external DTDs are never loaded (a reference
;;; to an external entity is an error, as is a reference to an entity whose
;;; declaration could only be in an unread external DTD); internal entity
;;; expansion is bounded by expat's billion-laughs protection, switched on
;;; early here (at 1 MiB of output instead of expat's 8 MiB).
;;;
;;; Errors are conditions of kinds `exn` and `xml-error`; the message reads
;;;   SOURCE:LINE:COLUMN: XML parse error: REASON
;;; with a 1-based line and column (expat's column plus one). The `xml-error`
;;; part holds the properties source, line, column and reason. A file that
;;; cannot be opened or read raises a condition of kinds `exn`, `i/o`, `file`
;;; and `xml-error` whose message names the path and the system's reason.

(module (downstroke xml)
  (xml-parse-string xml-parse-file xml-error?
   sxml-attr sxml-attrs sxml-children sxml-child sxml-text)

  (import scheme (chicken base) (chicken foreign) (chicken condition)
          (chicken fixnum) (chicken format) (chicken string))

  (foreign-declare #<<EOF
#include <expat.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Event buffer format, all integers 32-bit little-endian:
     'S' name-len name attr-count { key-len key value-len value } ...
     'E'
     'T' text-len text                                                    */
typedef struct {
  XML_Parser parser;
  unsigned char *ev;
  size_t len, cap;
  size_t text_hdr;     /* offset of the length field of the open text event */
  int text_open;       /* last event in the buffer is text that may grow */
  int failed;          /* a handler stopped the parser; reason in detail */
  char detail[512];
  char reason[768];    /* the full reason, after an error */
  unsigned long line, column;
  FILE *fp;
  int io_errno;
} dsx_state;

static void dsx_fail(dsx_state *st, const char *what)
{
  if (!st->failed) {
    st->failed = 1;
    snprintf(st->detail, sizeof st->detail, "%s", what);
    XML_StopParser(st->parser, XML_FALSE);
  }
}

static int dsx_reserve(dsx_state *st, size_t need)
{
  size_t cap;
  unsigned char *p;
  if (need > SIZE_MAX / 2 - st->len) { dsx_fail(st, "out of memory"); return 0; }
  if (st->len + need <= st->cap) return 1;
  cap = st->cap ? st->cap : 65536;
  while (cap < st->len + need) cap *= 2;
  p = (unsigned char *)realloc(st->ev, cap);
  if (!p) { dsx_fail(st, "out of memory"); return 0; }
  st->ev = p;
  st->cap = cap;
  return 1;
}

static void dsx_put_u32(unsigned char *p, size_t v)
{
  p[0] = (unsigned char)(v & 0xff);
  p[1] = (unsigned char)((v >> 8) & 0xff);
  p[2] = (unsigned char)((v >> 16) & 0xff);
  p[3] = (unsigned char)((v >> 24) & 0xff);
}

static void dsx_put_str(dsx_state *st, const char *s, size_t n)
{
  dsx_put_u32(st->ev + st->len, n);
  memcpy(st->ev + st->len + 4, s, n);
  st->len += 4 + n;
}

static void XMLCALL dsx_on_start(void *ud, const XML_Char *name, const XML_Char **atts)
{
  dsx_state *st = (dsx_state *)ud;
  size_t need, n, i, l;
  if (st->failed) return;
  st->text_open = 0;
  l = strlen(name);
  if (l > 0x7fffffff) { dsx_fail(st, "name too long"); return; }
  need = 1 + 4 + l + 4;
  for (n = 0; atts[n]; n += 2) {
    size_t kl = strlen(atts[n]), vl = strlen(atts[n + 1]);
    if (kl > 0x7fffffff || vl > 0x7fffffff || need > SIZE_MAX / 4) {
      dsx_fail(st, "attribute too long");
      return;
    }
    need += 8 + kl + vl;
  }
  if (!dsx_reserve(st, need)) return;
  st->ev[st->len++] = 'S';
  dsx_put_str(st, name, l);
  dsx_put_u32(st->ev + st->len, n / 2);
  st->len += 4;
  for (i = 0; i < n; i++) dsx_put_str(st, atts[i], strlen(atts[i]));
}

static void XMLCALL dsx_on_end(void *ud, const XML_Char *name)
{
  dsx_state *st = (dsx_state *)ud;
  (void)name;
  if (st->failed) return;
  st->text_open = 0;
  if (!dsx_reserve(st, 1)) return;
  st->ev[st->len++] = 'E';
}

static void XMLCALL dsx_on_text(void *ud, const XML_Char *s, int len)
{
  dsx_state *st = (dsx_state *)ud;
  if (st->failed || len <= 0) return;
  if (st->text_open) {
    unsigned char *h = st->ev + st->text_hdr;
    size_t cur = (size_t)h[0] | ((size_t)h[1] << 8) | ((size_t)h[2] << 16) | ((size_t)h[3] << 24);
    if (cur + (size_t)len <= 0x7fffffff) {
      if (!dsx_reserve(st, (size_t)len)) return;
      h = st->ev + st->text_hdr;       /* the buffer may have moved */
      dsx_put_u32(h, cur + (size_t)len);
      memcpy(st->ev + st->len, s, (size_t)len);
      st->len += (size_t)len;
      return;
    }
  }
  if (!dsx_reserve(st, 5 + (size_t)len)) return;
  st->ev[st->len++] = 'T';
  st->text_hdr = st->len;
  dsx_put_str(st, s, (size_t)len);
  st->text_open = 1;
}

static int XMLCALL dsx_on_external_entity(XML_Parser p, const XML_Char *context,
                                          const XML_Char *base, const XML_Char *system_id,
                                          const XML_Char *public_id)
{
  dsx_state *st = (dsx_state *)XML_GetUserData(p);
  char buf[400];
  (void)context; (void)base; (void)public_id;
  snprintf(buf, sizeof buf, "external entity refused (SYSTEM \"%.300s\")",
           system_id ? system_id : "");
  if (!st->failed) {
    st->failed = 1;
    snprintf(st->detail, sizeof st->detail, "%s", buf);
  }
  return XML_STATUS_ERROR;
}

static void XMLCALL dsx_on_skipped_entity(void *ud, const XML_Char *name, int is_param)
{
  dsx_state *st = (dsx_state *)ud;
  char buf[400];
  if (is_param) return;   /* parameter entities in the DTD: nothing is lost */
  snprintf(buf, sizeof buf,
           "entity \"%.300s\" is not declared in the document (external DTDs are not read)",
           name);
  dsx_fail(st, buf);
}

static dsx_state *dsx_new(void)
{
  dsx_state *st = (dsx_state *)calloc(1, sizeof *st);
  if (!st) return NULL;
  st->parser = XML_ParserCreate(NULL);
  if (!st->parser) { free(st); return NULL; }
  XML_SetUserData(st->parser, st);
  XML_SetElementHandler(st->parser, dsx_on_start, dsx_on_end);
  XML_SetCharacterDataHandler(st->parser, dsx_on_text);
  XML_SetExternalEntityRefHandler(st->parser, dsx_on_external_entity);
  XML_SetSkippedEntityHandler(st->parser, dsx_on_skipped_entity);
  XML_SetParamEntityParsing(st->parser, XML_PARAM_ENTITY_PARSING_NEVER);
#ifdef XML_DTD
  XML_SetBillionLaughsAttackProtectionActivationThreshold(st->parser, 1024ULL * 1024ULL);
  XML_SetBillionLaughsAttackProtectionMaximumAmplification(st->parser, 100.0f);
#endif
  return st;
}

static void dsx_free(dsx_state *st)
{
  if (!st) return;
  if (st->parser) XML_ParserFree(st->parser);
  if (st->fp) fclose(st->fp);
  free(st->ev);
  free(st);
}

/* After XML_Parse* failed: remember where and why. */
static void dsx_note_error(dsx_state *st)
{
  enum XML_Error code = XML_GetErrorCode(st->parser);
  const XML_LChar *msg = XML_ErrorString(code);
  st->line = (unsigned long)XML_GetCurrentLineNumber(st->parser);
  st->column = (unsigned long)XML_GetCurrentColumnNumber(st->parser) + 1;
  if (st->failed)
    snprintf(st->reason, sizeof st->reason, "%s", st->detail);
  else
    snprintf(st->reason, sizeof st->reason, "%s", msg ? msg : "unknown error");
}

/* Parses len bytes at data+offset. 0 = fine so far, -1 = parse error. */
static int dsx_parse_bytes(dsx_state *st, const char *data, size_t offset, size_t len, int final)
{
  if (XML_Parse(st->parser, data + offset, (int)len, final) != XML_STATUS_OK) {
    dsx_note_error(st);
    return -1;
  }
  return 0;
}

/* 0 on success, otherwise errno. */
static int dsx_open(dsx_state *st, const char *path)
{
  errno = 0;
  st->fp = fopen(path, "rb");
  if (!st->fp) return errno ? errno : EIO;
  return 0;
}

/* Reads and parses one chunk. 0 = more to come, 1 = document complete,
   -1 = parse error, -2 = read error (errno in io_errno). */
static int dsx_parse_file_chunk(dsx_state *st)
{
  const int chunk = 256 * 1024;
  size_t n;
  int final;
  void *buf = XML_GetBuffer(st->parser, chunk);
  if (!buf) { dsx_note_error(st); return -1; }
  errno = 0;
  n = fread(buf, 1, (size_t)chunk, st->fp);
  if (ferror(st->fp)) { st->io_errno = errno ? errno : EIO; return -2; }
  final = (n < (size_t)chunk) && feof(st->fp);
  if (XML_ParseBuffer(st->parser, (int)n, final) != XML_STATUS_OK) {
    dsx_note_error(st);
    return -1;
  }
  return final ? 1 : 0;
}

static size_t dsx_events_length(dsx_state *st) { return st->len; }

static void dsx_take_events(dsx_state *st, char *dest)
{
  if (st->len && dest) memcpy(dest, st->ev, st->len);
  st->len = 0;
  st->text_open = 0;
}

static const char *dsx_reason(dsx_state *st) { return st->reason; }
static unsigned long dsx_line(dsx_state *st) { return st->line; }
static unsigned long dsx_column(dsx_state *st) { return st->column; }
static int dsx_io_errno(dsx_state *st) { return st->io_errno; }
static const char *dsx_strerror(int e) { return strerror(e); }
EOF
)

  (define %new (foreign-lambda c-pointer "dsx_new"))
  (define %free (foreign-lambda void "dsx_free" c-pointer))
  (define %parse-bytes
    (foreign-lambda int "dsx_parse_bytes" c-pointer scheme-pointer size_t size_t bool))
  (define %open (foreign-lambda int "dsx_open" c-pointer c-string))
  (define %parse-file-chunk (foreign-lambda int "dsx_parse_file_chunk" c-pointer))
  (define %events-length (foreign-lambda size_t "dsx_events_length" c-pointer))
  (define %take-events (foreign-lambda void "dsx_take_events" c-pointer scheme-pointer))
  (define %reason (foreign-lambda c-string "dsx_reason" c-pointer))
  (define %line (foreign-lambda unsigned-long "dsx_line" c-pointer))
  (define %column (foreign-lambda unsigned-long "dsx_column" c-pointer))
  (define %io-errno (foreign-lambda int "dsx_io_errno" c-pointer))
  (define %strerror (foreign-lambda c-string "dsx_strerror" int))

  ;; ---- conditions -------------------------------------------------------

  (define xml-error? (condition-predicate 'xml-error))

  (define (parse-error who source st)
    (let ((line (%line st)) (column (%column st)) (reason (%reason st)))
      (abort
       (make-composite-condition
        (make-property-condition
         'exn 'location who
         'message (sprintf "~a:~a:~a: XML parse error: ~a" source line column reason)
         'arguments '())
        (make-property-condition
         'xml-error 'source source 'line line 'column column 'reason reason)))))

  (define (file-error who path what errno)
    (let ((reason (sprintf "~a: ~a" what (%strerror errno))))
      (abort
       (make-composite-condition
        (make-property-condition
         'exn 'location who
         'message (sprintf "~a: ~a ~s: ~a" who what path (%strerror errno))
         'arguments '())
        (make-property-condition 'i/o)
        (make-property-condition 'file)
        (make-property-condition
         'xml-error 'source path 'line #f 'column #f 'reason reason)))))

  ;; ---- building the tree from events ------------------------------------

  ;; An open element: #(name attrs children-reversed texts-reversed).
  (define (make-frame name attrs) (vector name attrs '() '()))

  (define (flush-text! frame)
    (let ((texts (vector-ref frame 3)))
      (unless (null? texts)
        (vector-set! frame 2
                     (cons (if (null? (cdr texts))
                               (car texts)
                               (string-intersperse (reverse texts) ""))
                           (vector-ref frame 2)))
        (vector-set! frame 3 '()))))

  (define (frame->node frame)
    (flush-text! frame)
    (let ((children (reverse (vector-ref frame 2)))
          (attrs (vector-ref frame 1)))
      (cons (vector-ref frame 0)
            (if (null? attrs) children (cons (cons '@ attrs) children)))))

  ;; The builder is a one-element list holding the stack of open frames,
  ;; innermost first; the outermost is *TOP*.
  (define (make-builder) (list (list (make-frame '*TOP* '()))))

  (define (builder-finish builder)
    (let ((stack (car builder)))
      ;; expat reports a document whose root is unclosed as an error, so
      ;; only *TOP* is left here.
      (let loop ((stack stack))
        (if (null? (cdr stack)) (frame->node (car stack)) (loop (cdr stack))))))

  (define (u32-at s i)
    (fx+ (char->integer (string-ref s i))
         (fx+ (fxshl (char->integer (string-ref s (fx+ i 1))) 8)
              (fx+ (fxshl (char->integer (string-ref s (fx+ i 2))) 16)
                   (fxshl (char->integer (string-ref s (fx+ i 3))) 24)))))

  ;; Folds one buffer of events into the builder.
  (define (feed-events! builder ev)
    (let ((end (string-length ev)))
      (let loop ((i 0) (stack (car builder)))
        (if (fx>= i end)
            (set-car! builder stack)
            (case (string-ref ev i)
              ((#\S)
               (let* ((nl (u32-at ev (fx+ i 1)))
                      (name (string->symbol (substring ev (fx+ i 5) (fx+ i (fx+ 5 nl)))))
                      (j (fx+ i (fx+ 5 nl)))
                      (count (u32-at ev j)))
                 (let attrs ((k 0) (j (fx+ j 4)) (acc '()))
                   (if (fx< k count)
                       (let* ((kl (u32-at ev j))
                              (key (string->symbol (substring ev (fx+ j 4) (fx+ j (fx+ 4 kl)))))
                              (j (fx+ j (fx+ 4 kl)))
                              (vl (u32-at ev j))
                              (val (substring ev (fx+ j 4) (fx+ j (fx+ 4 vl)))))
                         (attrs (fx+ k 1) (fx+ j (fx+ 4 vl)) (cons (list key val) acc)))
                       (begin
                         (flush-text! (car stack))
                         (loop j (cons (make-frame name (reverse acc)) stack)))))))
              ((#\E)
               (let ((node (frame->node (car stack)))
                     (parent (cadr stack)))
                 (flush-text! parent)
                 (vector-set! parent 2 (cons node (vector-ref parent 2)))
                 (loop (fx+ i 1) (cdr stack))))
              ((#\T)
               (let* ((n (u32-at ev (fx+ i 1)))
                      (text (substring ev (fx+ i 5) (fx+ i (fx+ 5 n))))
                      (frame (car stack)))
                 (vector-set! frame 3 (cons text (vector-ref frame 3)))
                 (loop (fx+ i (fx+ 5 n)) stack)))
              (else (error 'xml "internal error: bad event buffer" i)))))))

  (define (drain! st builder)
    (let ((n (%events-length st)))
      (unless (zero? n)
        (let ((ev (make-string n)))
          (%take-events st ev)
          (feed-events! builder ev)))))

  (define (call-with-parser who proc)
    (let ((st #f))
      (dynamic-wind
          (lambda () (set! st (%new)))
          (lambda ()
            (unless st (error who "cannot create an XML parser (out of memory)"))
            (proc st))
          (lambda () (when st (%free st) (set! st #f))))))

  ;; ---- entry points -----------------------------------------------------

  (define string-chunk (* 1024 1024))

  (define (xml-parse-string str #!optional (source "string"))
    (unless (string? str)
      (error 'xml-parse-string "not a string" str))
    (call-with-parser
     'xml-parse-string
     (lambda (st)
       (let ((builder (make-builder))
             (len (string-length str)))
         (let loop ((offset 0))
           (let* ((n (min string-chunk (- len offset)))
                  (final (= (+ offset n) len)))
             (unless (zero? (%parse-bytes st str offset n final))
               (parse-error 'xml-parse-string source st))
             (drain! st builder)
             (if final
                 (builder-finish builder)
                 (loop (+ offset n)))))))))

  (define (xml-parse-file path)
    (unless (string? path)
      (error 'xml-parse-file "path is not a string" path))
    (when (substring-index (string (integer->char 0)) path)
      (error 'xml-parse-file "path contains a NUL byte" path))
    (call-with-parser
     'xml-parse-file
     (lambda (st)
       (let ((e (%open st path)))
         (unless (zero? e) (file-error 'xml-parse-file path "cannot open" e)))
       (let ((builder (make-builder)))
         (let loop ()
           (let ((rc (%parse-file-chunk st)))
             (case rc
               ((0) (drain! st builder) (loop))
               ((1) (drain! st builder) (builder-finish builder))
               ((-1) (parse-error 'xml-parse-file path st))
               (else (file-error 'xml-parse-file path "cannot read" (%io-errno st))))))))))

  ;; ---- helpers for consumers --------------------------------------------

  (define (->symbol x) (if (string? x) (string->symbol x) x))

  (define (element? x) (and (pair? x) (symbol? (car x)) (not (eq? (car x) '@))))

  ;; The (@ ...) list's entries, or '().
  (define (sxml-attrs node)
    (if (and (pair? node) (pair? (cdr node)) (pair? (cadr node)) (eq? (car (cadr node)) '@))
        (cdr (cadr node))
        '()))

  (define (sxml-attr node name #!optional (default #f))
    (let ((entry (assq (->symbol name) (sxml-attrs node))))
      (if (and entry (pair? (cdr entry))) (cadr entry) default)))

  (define (content node) (if (pair? node) (cdr node) '()))

  (define (sxml-children node #!optional tag)
    (let ((tag (and tag (->symbol tag))))
      (let loop ((xs (content node)) (acc '()))
        (cond ((null? xs) (reverse acc))
              ((and (element? (car xs)) (or (not tag) (eq? (caar xs) tag)))
               (loop (cdr xs) (cons (car xs) acc)))
              (else (loop (cdr xs) acc))))))

  (define (sxml-child node tag)
    (let ((tag (->symbol tag)))
      (let loop ((xs (content node)))
        (cond ((null? xs) #f)
              ((and (element? (car xs)) (eq? (caar xs) tag)) (car xs))
              (else (loop (cdr xs)))))))

  (define (sxml-text node)
    (let ((texts (let loop ((xs (content node)) (acc '()))
                   (cond ((null? xs) (reverse acc))
                         ((string? (car xs)) (loop (cdr xs) (cons (car xs) acc)))
                         (else (loop (cdr xs) acc))))))
      (cond ((null? texts) "")
            ((null? (cdr texts)) (car texts))
            (else (string-intersperse texts "")))))
)
