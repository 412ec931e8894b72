;;; (downstroke decode): the byte codecs a Tiled map's layer data may use.
;;;
;;;   base64-decode  string -> u8vector     base64-encode  u8vector -> string
;;;   zlib-inflate   u8vector -> u8vector   zlib-deflate   u8vector -> u8vector
;;;   gzip-inflate   u8vector -> u8vector   gzip-deflate   u8vector -> u8vector
;;;   zstd-decompress u8vector -> u8vector  zstd-compress  u8vector -> u8vector
;;;   u8vector->u32vector-le  u8vector -> u32vector (little-endian words)
;;;
;;; The decompressors take #!key (max-size default-max-size): output longer
;;; than max-size bytes is refused (a decompression bomb), and #f lifts the
;;; bound. The compressors take #!key (level ...) and exist so tests and tools
;;; can build fixtures.
;;;
;;; Every failure is a condition of kinds `exn` and `decode-error` whose
;;; message starts with the procedure's name, e.g.
;;;   "zlib-inflate: corrupt input: incorrect header check"
;;;   "gzip-inflate: truncated input (the stream ends early)"
;;;   "zstd-decompress: output exceeds max-size (1024 bytes)"
;;;   "base64-decode: invalid character #\% (byte 37) at position 12"
;;; The `decode-error` part carries the property `problem`, a symbol:
;;; invalid-character, data-after-padding, bad-length, corrupt, truncated,
;;; trailing-data, too-large, out-of-memory, bad-argument.
;;;
;;; All work happens in C in one call per operation (no callbacks), into
;;; malloc'd memory that is copied into the result vector and freed.

(module (downstroke decode)
  (base64-decode base64-encode
   zlib-inflate gzip-inflate zstd-decompress
   zlib-deflate gzip-deflate zstd-compress
   u8vector->u32vector-le
   default-max-size decode-error?)

  (import (downstroke keywords))
  (import scheme (chicken base) (chicken foreign) (chicken condition)
          (chicken format) srfi-4)

  (foreign-declare #<<EOF
#include <zlib.h>
#include <zstd.h>
#include <zstd_errors.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Result of one operation: malloc'd bytes, or an error. */
typedef struct {
  unsigned char *data;
  size_t len, cap;
  int problem;          /* 0 = none, see dsd_problem_names in Scheme */
  char msg[256];
} dsd_out;

enum { DSD_OK = 0, DSD_CORRUPT = 1, DSD_TRUNCATED = 2, DSD_TRAILING = 3,
       DSD_TOO_LARGE = 4, DSD_NOMEM = 5, DSD_BAD_ARG = 6 };

static dsd_out *dsd_new(void) { return (dsd_out *)calloc(1, sizeof(dsd_out)); }

static void dsd_free(dsd_out *o) { if (o) { free(o->data); free(o); } }

static int dsd_fail(dsd_out *o, int problem, const char *fmt, const char *detail)
{
  o->problem = problem;
  snprintf(o->msg, sizeof o->msg, fmt, detail ? detail : "");
  return problem;
}

/* Makes room for more output. limit is the largest allowed output; the
   buffer grows to at most limit + 1 bytes so that overflow is noticed. */
static int dsd_grow(dsd_out *o, size_t limit)
{
  size_t cap;
  unsigned char *p;
  if (o->cap > limit) return 0;
  cap = o->cap < 65536 ? 65536 : (o->cap > SIZE_MAX / 4 ? SIZE_MAX / 2 : o->cap * 2);
  if (cap > limit + 1) cap = limit + 1;
  if (cap <= o->cap) return 0;
  p = (unsigned char *)realloc(o->data, cap);
  if (!p) return -1;
  o->data = p;
  o->cap = cap;
  return 1;
}

static int dsd_reserve_exact(dsd_out *o, size_t cap)
{
  unsigned char *p = (unsigned char *)malloc(cap ? cap : 1);
  if (!p) return 0;
  free(o->data);
  o->data = p;
  o->cap = cap;
  o->len = 0;
  return 1;
}

static size_t dsd_limit(size_t max_size, int bounded)
{
  size_t cap = SIZE_MAX / 2;
  return (bounded && max_size < cap) ? max_size : cap;
}

/* ---- zlib / gzip ----------------------------------------------------- */

/* zlib takes at most UINT_MAX bytes a call: give it the next slice of the
   input once it has used the last one. */
static void dsd_feed(z_stream *zs, const unsigned char *in, size_t inlen, size_t *fed)
{
  if (zs->avail_in == 0 && *fed < inlen) {
    size_t chunk = inlen - *fed;
    if (chunk > (1u << 30)) chunk = 1u << 30;
    zs->next_in = (Bytef *)(in + *fed);
    zs->avail_in = (uInt)chunk;
    *fed += chunk;
  }
}

/* Point zlib's output at the free room of o; returns that room's size. */
static size_t dsd_point_out(z_stream *zs, dsd_out *o)
{
  size_t room = o->cap - o->len;
  if (room > UINT_MAX) room = UINT_MAX;
  zs->next_out = o->data + o->len;
  zs->avail_out = (uInt)room;
  return room;
}

static int dsd_inflate(dsd_out *o, const unsigned char *in, size_t inlen,
                       int gzip, size_t max_size, int bounded)
{
  z_stream zs;
  size_t fed = 0, limit = dsd_limit(max_size, bounded);
  size_t guess;
  int rc;
  char limtxt[64];

  if (inlen == 0) return dsd_fail(o, DSD_TRUNCATED, "empty input%s", NULL);
  memset(&zs, 0, sizeof zs);
  rc = inflateInit2(&zs, gzip ? 15 + 16 : 15);
  if (rc != Z_OK)
    return dsd_fail(o, rc == Z_MEM_ERROR ? DSD_NOMEM : DSD_CORRUPT,
                    "cannot start zlib: %s", zs.msg ? zs.msg : "inflateInit2 failed");
  guess = inlen < SIZE_MAX / 8 ? inlen * 4 : inlen;
  if (guess < 65536) guess = 65536;
  if (guess > limit + 1) guess = limit + 1;
  if (!dsd_reserve_exact(o, guess)) {
    inflateEnd(&zs);
    return dsd_fail(o, DSD_NOMEM, "out of memory%s", NULL);
  }
  for (;;) {
    size_t before;
    dsd_feed(&zs, in, inlen, &fed);
    if (o->len == o->cap) {
      int g = dsd_grow(o, limit);
      if (g < 0) { inflateEnd(&zs); return dsd_fail(o, DSD_NOMEM, "out of memory%s", NULL); }
      if (g == 0) break;  /* over the limit; reported below */
    }
    before = dsd_point_out(&zs, o);
    rc = inflate(&zs, Z_NO_FLUSH);
    o->len += before - zs.avail_out;
    if (o->len > limit) break;
    if (rc == Z_STREAM_END) {
      size_t left = zs.avail_in + (inlen - fed);
      if (left == 0) { inflateEnd(&zs); return DSD_OK; }
      if (!gzip) {
        inflateEnd(&zs);
        snprintf(limtxt, sizeof limtxt, "%zu", left);
        return dsd_fail(o, DSD_TRAILING, "%s bytes of trailing data after the end of the stream", limtxt);
      }
      /* gzip: another member follows (as `gzip -d` allows). */
      if (inflateReset(&zs) != Z_OK) {
        inflateEnd(&zs);
        return dsd_fail(o, DSD_CORRUPT, "corrupt input: %s", "cannot reset the stream");
      }
      continue;
    }
    if (rc == Z_OK) continue;
    if (rc == Z_BUF_ERROR) {
      if (zs.avail_out == 0) continue;  /* needs more room */
      if (zs.avail_in == 0 && fed == inlen) {
        inflateEnd(&zs);
        return dsd_fail(o, DSD_TRUNCATED, "truncated input (the stream ends early)%s", NULL);
      }
      inflateEnd(&zs);
      return dsd_fail(o, DSD_CORRUPT, "corrupt input: %s", "no progress");
    }
    inflateEnd(&zs);
    if (rc == Z_MEM_ERROR) return dsd_fail(o, DSD_NOMEM, "out of memory%s", NULL);
    if (rc == Z_NEED_DICT)
      return dsd_fail(o, DSD_CORRUPT, "corrupt input: %s", "the stream needs a preset dictionary");
    return dsd_fail(o, DSD_CORRUPT, "corrupt input: %s", zs.msg ? zs.msg : "invalid data");
  }
  inflateEnd(&zs);
  snprintf(limtxt, sizeof limtxt, "%zu", limit);
  return dsd_fail(o, DSD_TOO_LARGE, "output exceeds max-size (%s bytes)", limtxt);
}

static int dsd_deflate(dsd_out *o, const unsigned char *in, size_t inlen, int gzip, int level)
{
  z_stream zs;
  size_t fed = 0;
  int rc;
  memset(&zs, 0, sizeof zs);
  rc = deflateInit2(&zs, level, Z_DEFLATED, gzip ? 15 + 16 : 15, 8, Z_DEFAULT_STRATEGY);
  if (rc != Z_OK)
    return dsd_fail(o, rc == Z_MEM_ERROR ? DSD_NOMEM : DSD_BAD_ARG,
                    "cannot start zlib: %s", zs.msg ? zs.msg : "bad compression level");
  if (!dsd_reserve_exact(o, (size_t)deflateBound(&zs, (uLong)inlen) + 64)) {
    deflateEnd(&zs);
    return dsd_fail(o, DSD_NOMEM, "out of memory%s", NULL);
  }
  for (;;) {
    size_t before;
    int flush;
    dsd_feed(&zs, in, inlen, &fed);
    flush = (fed == inlen) ? Z_FINISH : Z_NO_FLUSH;
    if (o->len == o->cap && dsd_grow(o, SIZE_MAX / 2) <= 0) {
      deflateEnd(&zs);
      return dsd_fail(o, DSD_NOMEM, "out of memory%s", NULL);
    }
    before = dsd_point_out(&zs, o);
    rc = deflate(&zs, flush);
    o->len += before - zs.avail_out;
    if (rc == Z_STREAM_END) break;
    if (rc != Z_OK && rc != Z_BUF_ERROR) {
      deflateEnd(&zs);
      return dsd_fail(o, DSD_CORRUPT, "compression failed: %s", zs.msg ? zs.msg : "deflate error");
    }
  }
  deflateEnd(&zs);
  return DSD_OK;
}

/* ---- zstd ------------------------------------------------------------ */

static int dsd_zstd_decompress(dsd_out *o, const unsigned char *in, size_t inlen,
                               size_t max_size, int bounded)
{
  ZSTD_DCtx *d;
  ZSTD_inBuffer ib;
  size_t limit = dsd_limit(max_size, bounded), guess, ret = 1;
  unsigned long long fcs;
  char limtxt[64];

  if (inlen == 0) return dsd_fail(o, DSD_TRUNCATED, "empty input%s", NULL);
  fcs = ZSTD_getFrameContentSize(in, inlen);
  if (fcs == ZSTD_CONTENTSIZE_ERROR) {
    if (inlen < 4) return dsd_fail(o, DSD_TRUNCATED, "truncated input (the stream ends early)%s", NULL);
    /* let the decoder name the problem below */
    guess = 65536;
  } else if (fcs == ZSTD_CONTENTSIZE_UNKNOWN) {
    guess = inlen < SIZE_MAX / 8 ? inlen * 4 : inlen;
  } else if (fcs > (unsigned long long)limit) {
    snprintf(limtxt, sizeof limtxt, "%zu", limit);
    return dsd_fail(o, DSD_TOO_LARGE, "output exceeds max-size (%s bytes)", limtxt);
  } else {
    guess = (size_t)fcs + 1;   /* +1: a following frame shows up at once */
  }
  if (guess < 4096) guess = 4096;
  if (guess > limit + 1) guess = limit + 1;
  if (!dsd_reserve_exact(o, guess)) return dsd_fail(o, DSD_NOMEM, "out of memory%s", NULL);
  d = ZSTD_createDCtx();
  if (!d) return dsd_fail(o, DSD_NOMEM, "out of memory%s", NULL);
  ib.src = in;
  ib.size = inlen;
  ib.pos = 0;
  for (;;) {
    ZSTD_outBuffer ob;
    if (o->len == o->cap) {
      int g = dsd_grow(o, limit);
      if (g < 0) { ZSTD_freeDCtx(d); return dsd_fail(o, DSD_NOMEM, "out of memory%s", NULL); }
      if (g == 0) break;
    }
    ob.dst = o->data + o->len;
    ob.size = o->cap - o->len;
    ob.pos = 0;
    ret = ZSTD_decompressStream(d, &ob, &ib);
    if (ZSTD_isError(ret)) {
      ZSTD_ErrorCode code = ZSTD_getErrorCode(ret);
      ZSTD_freeDCtx(d);
      if (code == ZSTD_error_memory_allocation)
        return dsd_fail(o, DSD_NOMEM, "out of memory%s", NULL);
      return dsd_fail(o, DSD_CORRUPT, "corrupt input: %s", ZSTD_getErrorName(ret));
    }
    o->len += ob.pos;
    if (o->len > limit) break;
    if (ib.pos == ib.size && ob.pos < ob.size) {
      /* all input used and everything decodable flushed */
      ZSTD_freeDCtx(d);
      if (ret != 0)
        return dsd_fail(o, DSD_TRUNCATED, "truncated input (the stream ends early)%s", NULL);
      return DSD_OK;
    }
  }
  ZSTD_freeDCtx(d);
  snprintf(limtxt, sizeof limtxt, "%zu", limit);
  return dsd_fail(o, DSD_TOO_LARGE, "output exceeds max-size (%s bytes)", limtxt);
}

static int dsd_zstd_compress(dsd_out *o, const unsigned char *in, size_t inlen, int level)
{
  ZSTD_CCtx *c;
  size_t r;
  if (level < ZSTD_minCLevel() || level > ZSTD_maxCLevel())
    return dsd_fail(o, DSD_BAD_ARG, "bad compression level%s", NULL);
  if (!dsd_reserve_exact(o, ZSTD_compressBound(inlen))) return dsd_fail(o, DSD_NOMEM, "out of memory%s", NULL);
  c = ZSTD_createCCtx();
  if (!c) return dsd_fail(o, DSD_NOMEM, "out of memory%s", NULL);
  ZSTD_CCtx_setParameter(c, ZSTD_c_compressionLevel, level);
  ZSTD_CCtx_setParameter(c, ZSTD_c_checksumFlag, 1);
  r = ZSTD_compress2(c, o->data, o->cap, in, inlen);
  ZSTD_freeCCtx(c);
  if (ZSTD_isError(r)) return dsd_fail(o, DSD_CORRUPT, "compression failed: %s", ZSTD_getErrorName(r));
  o->len = r;
  return DSD_OK;
}

/* ---- base64 (RFC 4648, standard alphabet) ---------------------------- */

static int dsd_b64_value(unsigned char c)
{
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

static int dsd_b64_space(unsigned char c)
{
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

/* Checks the text. info[0] = problem (0 ok, 1 invalid character,
   2 data after padding, 3 bad length), info[1] = position (or decoded
   length when ok), info[2] = number of base64 characters seen. */
static void dsd_b64_scan(const unsigned char *s, size_t len, int64_t *info)
{
  size_t i, count = 0, pad = 0, first_pad = 0, r;
  for (i = 0; i < len; i++) {
    unsigned char c = s[i];
    if (dsd_b64_space(c)) continue;
    if (c == '=') {
      if (pad == 0) first_pad = i;
      pad++;
      continue;
    }
    if (dsd_b64_value(c) < 0) { info[0] = 1; info[1] = (int64_t)i; info[2] = (int64_t)count; return; }
    if (pad) { info[0] = 2; info[1] = (int64_t)i; info[2] = (int64_t)count; return; }
    count++;
  }
  r = count % 4;
  info[2] = (int64_t)(count + pad);
  if (r == 1 || (pad && (pad > 2 || (count + pad) % 4 != 0))) {
    info[0] = 3;
    info[1] = (int64_t)(pad ? first_pad : len);
    return;
  }
  info[0] = 0;
  info[1] = (int64_t)(count / 4 * 3 + (r == 2 ? 1 : r == 3 ? 2 : 0));
}

/* Decodes text already accepted by dsd_b64_scan into out. */
static void dsd_b64_decode(const unsigned char *s, size_t len, unsigned char *out)
{
  size_t i, o = 0;
  unsigned long acc = 0;
  int bits = 0;
  for (i = 0; i < len; i++) {
    int v = dsd_b64_value(s[i]);
    if (v < 0) continue;      /* whitespace or padding */
    acc = ((acc << 6) | (unsigned long)v) & 0xffffff;
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out[o++] = (unsigned char)((acc >> bits) & 0xff);
    }
  }
}

static void dsd_b64_encode(const unsigned char *in, size_t len, char *out)
{
  static const char abc[] =
    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  size_t i = 0, o = 0;
  for (; i + 3 <= len; i += 3) {
    unsigned long v = ((unsigned long)in[i] << 16) | ((unsigned long)in[i + 1] << 8) | in[i + 2];
    out[o++] = abc[(v >> 18) & 63];
    out[o++] = abc[(v >> 12) & 63];
    out[o++] = abc[(v >> 6) & 63];
    out[o++] = abc[v & 63];
  }
  if (len - i == 1) {
    unsigned long v = (unsigned long)in[i] << 16;
    out[o++] = abc[(v >> 18) & 63];
    out[o++] = abc[(v >> 12) & 63];
    out[o++] = '=';
    out[o++] = '=';
  } else if (len - i == 2) {
    unsigned long v = ((unsigned long)in[i] << 16) | ((unsigned long)in[i + 1] << 8);
    out[o++] = abc[(v >> 18) & 63];
    out[o++] = abc[(v >> 12) & 63];
    out[o++] = abc[(v >> 6) & 63];
    out[o++] = '=';
  }
}

/* ---- little-endian words --------------------------------------------- */

static void dsd_u32le(const unsigned char *in, size_t words, uint32_t *out)
{
  size_t i;
  for (i = 0; i < words; i++, in += 4)
    out[i] = (uint32_t)in[0] | ((uint32_t)in[1] << 8) | ((uint32_t)in[2] << 16) | ((uint32_t)in[3] << 24);
}

/* ---- results --------------------------------------------------------- */

static size_t dsd_len(dsd_out *o) { return o->len; }
static int dsd_problem(dsd_out *o) { return o->problem; }
static const char *dsd_msg(dsd_out *o) { return o->msg; }
static void dsd_copy(dsd_out *o, unsigned char *dest) { if (o->len && dest) memcpy(dest, o->data, o->len); }
EOF
)

  (define %new (foreign-lambda c-pointer "dsd_new"))
  (define %free (foreign-lambda void "dsd_free" c-pointer))
  (define %len (foreign-lambda size_t "dsd_len" c-pointer))
  (define %problem (foreign-lambda int "dsd_problem" c-pointer))
  (define %msg (foreign-lambda c-string "dsd_msg" c-pointer))
  (define %copy (foreign-lambda void "dsd_copy" c-pointer u8vector))
  (define %inflate
    (foreign-lambda int "dsd_inflate" c-pointer u8vector size_t bool size_t bool))
  (define %deflate (foreign-lambda int "dsd_deflate" c-pointer u8vector size_t bool int))
  (define %zstd-decompress
    (foreign-lambda int "dsd_zstd_decompress" c-pointer u8vector size_t size_t bool))
  (define %zstd-compress (foreign-lambda int "dsd_zstd_compress" c-pointer u8vector size_t int))
  (define %b64-scan (foreign-lambda void "dsd_b64_scan" scheme-pointer size_t s64vector))
  (define %b64-decode (foreign-lambda void "dsd_b64_decode" scheme-pointer size_t u8vector))
  (define %b64-encode (foreign-lambda void "dsd_b64_encode" u8vector size_t scheme-pointer))
  (define %u32le (foreign-lambda void "dsd_u32le" u8vector size_t u32vector))

  ;; ---- conditions -------------------------------------------------------

  (define decode-error? (condition-predicate 'decode-error))

  (define problem-names
    '#(ok corrupt truncated trailing-data too-large out-of-memory bad-argument))

  (define (fail who problem message . args)
    (abort
     (make-composite-condition
      (make-property-condition
       'exn 'location who
       'message (string-append (symbol->string who) ": " message)
       'arguments args)
      (make-property-condition 'decode-error 'problem problem))))

  (define default-max-size (* 256 1024 1024))

  (define (check-u8vector who v)
    (unless (u8vector? v) (fail who 'bad-argument "not a u8vector" v)))

  (define (check-max-size who max-size)
    (unless (or (not max-size)
                (and (exact-integer? max-size) (>= max-size 0)))
      (fail who 'bad-argument "max-size must be #f or a non-negative exact integer" max-size)))

  ;; Runs (proc out) for a fresh C result; returns its bytes as a u8vector
  ;; or raises its error. The C side is freed whatever happens.
  (define (run-codec who proc)
    (let ((out #f))
      (dynamic-wind
          (lambda () (set! out (%new)))
          (lambda ()
            (unless out (fail who 'out-of-memory "out of memory"))
            (let ((rc (proc out)))
              (if (zero? rc)
                  (let ((v (make-u8vector (%len out))))
                    (%copy out v)
                    v)
                  (fail who (vector-ref problem-names rc) (%msg out)))))
          (lambda () (when out (%free out) (set! out #f))))))

  ;; max-size as the C side wants it: a size_t and whether it applies.
  (define (bound max-size) (if max-size (min max-size (* 1024 1024 1024 1024 1024)) 0))

  ;; ---- decompression ----------------------------------------------------

  (define (inflate-with who gzip? data max-size)
    (check-u8vector who data)
    (check-max-size who max-size)
    (run-codec who (lambda (out)
                     (%inflate out data (u8vector-length data) gzip?
                               (bound max-size) (and max-size #t)))))

  (define/keywords (zlib-inflate data #!key (max-size default-max-size))
    (inflate-with 'zlib-inflate #f data max-size))

  (define/keywords (gzip-inflate data #!key (max-size default-max-size))
    (inflate-with 'gzip-inflate #t data max-size))

  (define/keywords (zstd-decompress data #!key (max-size default-max-size))
    (check-u8vector 'zstd-decompress data)
    (check-max-size 'zstd-decompress max-size)
    (run-codec 'zstd-decompress
               (lambda (out)
                 (%zstd-decompress out data (u8vector-length data)
                                   (bound max-size) (and max-size #t)))))

  ;; ---- compression ------------------------------------------------------

  (define (check-level who level lo hi)
    (unless (and (fixnum? level) (<= lo level hi))
      (fail who 'bad-argument (sprintf "level must be an integer from ~a to ~a" lo hi) level)))

  (define/keywords (zlib-deflate data #!key (level 6))
    (check-u8vector 'zlib-deflate data)
    (check-level 'zlib-deflate level 0 9)
    (run-codec 'zlib-deflate
               (lambda (out) (%deflate out data (u8vector-length data) #f level))))

  (define/keywords (gzip-deflate data #!key (level 6))
    (check-u8vector 'gzip-deflate data)
    (check-level 'gzip-deflate level 0 9)
    (run-codec 'gzip-deflate
               (lambda (out) (%deflate out data (u8vector-length data) #t level))))

  ;; Frames carry their content size and a checksum, so corruption is caught.
  (define/keywords (zstd-compress data #!key (level 3))
    (check-u8vector 'zstd-compress data)
    (check-level 'zstd-compress level -131072 22)
    (run-codec 'zstd-compress
               (lambda (out) (%zstd-compress out data (u8vector-length data) level))))

  ;; ---- base64 -----------------------------------------------------------

  (define (describe-byte s pos)
    (let* ((c (string-ref s pos)) (n (char->integer c)))
      (if (and (> n 32) (< n 127))
          (sprintf "~s (byte ~a)" c n)
          (sprintf "byte ~a" n))))

  (define (base64-decode text)
    (unless (string? text) (fail 'base64-decode 'bad-argument "not a string" text))
    (let ((info (make-s64vector 3 0))
          (len (string-length text)))
      (%b64-scan text len info)
      (let ((problem (s64vector-ref info 0))
            (pos (s64vector-ref info 1))
            (count (s64vector-ref info 2)))
        (case problem
          ((0) (let ((v (make-u8vector pos)))
                 (%b64-decode text len v)
                 v))
          ((1) (fail 'base64-decode 'invalid-character
                     (sprintf "invalid character ~a at position ~a"
                              (describe-byte text pos) pos)))
          ((2) (fail 'base64-decode 'data-after-padding
                     (sprintf "data after padding: ~a at position ~a"
                              (describe-byte text pos) pos)))
          (else (fail 'base64-decode 'bad-length
                      (sprintf "bad length: ~a base64 characters (with padding) at position ~a; ~a"
                               count pos
                               "padded input must be a multiple of 4, unpadded must not leave 1 over")))))))

  (define (base64-encode data)
    (check-u8vector 'base64-encode data)
    (let* ((n (u8vector-length data))
           (s (make-string (* 4 (quotient (+ n 2) 3)))))
      (%b64-encode data n s)
      s))

  ;; ---- words ------------------------------------------------------------

  (define (u8vector->u32vector-le data)
    (check-u8vector 'u8vector->u32vector-le data)
    (let ((n (u8vector-length data)))
      (unless (zero? (remainder n 4))
        (fail 'u8vector->u32vector-le 'bad-length
              (sprintf "length ~a is not a multiple of 4" n)))
      (let ((words (make-u32vector (quotient n 4))))
        (%u32le data (quotient n 4) words)
        words)))
)
