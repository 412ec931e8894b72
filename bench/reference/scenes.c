/* The benchmark scenes S1 and S2 of docs/performance.org ("The scenes")
   in plain C, doubles for positions: what the same work costs without
   Scheme, to read bench/scenes.scm's figures against ("Against a plain C
   implementation" in docs/performance.org). It prints the same checksum
   lines as bench/scenes.scm; equal checksums are what make it the same
   scene (tests/bench-reference-test.scm compares them). Only the rules
   these scenes use are here: no slopes, one-way tiles, immovable bodies
   or tweens. Built by the Makefile as build/bench-reference:
     bench-reference [--runs R] [--csv FILE] [--quick] [--n N] [--mode M]
                     [--warm-up W] [--frames F] [S1 S2]
   S1 runs its two tile modes, discrete and swept (docs/physics.org,
   "Collision modes"); S2 runs with flonum positions, bench/scenes.scm's
   mode flonum (its exact modes keep rationals, which doubles are not). */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* ---- the generator and the map (docs/performance.org, "The scenes") */

static long seed;
static void reseed(void) { seed = 20261121; }
static long draw(void) {
  seed = (long)((1103515245ULL * (unsigned long long)seed + 12345ULL) % 2147483648ULL);
  return seed;
}

#define TILE 16
#define MAP_W 256
#define MAP_H 256
static unsigned char solid[MAP_H][MAP_W];

static void generate_map(void) {
  for (int j = 0; j < MAP_H; j++)
    for (int i = 0; i < MAP_W; i++) {
      long r = draw();
      solid[j][i] = i == 0 || j == 0 || i == MAP_W - 1 || j == MAP_H - 1 || r % 100 < 12;
    }
}

/* a cell outside the map is empty */
static int solid_at(long col, long row) {
  return col >= 0 && col < MAP_W && row >= 0 && row < MAP_H && solid[row][col];
}

/* ---- bodies */

typedef struct {
  double x, y;          /* positions */
  long vx, vy, ay;      /* the scenes' velocities stay integers */
  long speed;           /* S1's walking speed, turned round at walls */
  int on_ground;
} body;

static body *bodies;
static long count;

/* ---- tile rules (docs/physics.org, "Tile collisions", "Collision modes") */

/* The cells a span [p, p + size) covers: floor(p / T) to ceil((p + size) / T) - 1. */
static double span_first(double p) { return floor(p / TILE); }
static double span_last(double p, double size) { return ceil((p + size) / TILE) - 1.0; }

/* Where a body that moved by v (not 0) to pos stops on one axis, its span
   across being [across, across + across_size): the nearest solid line in
   its direction of motion among the lines it covers (swept: from the line
   its leading edge was in at start, pos - v), the stop flush with that
   line's near side. Returns 0 when nothing stops it. rows: lines are rows. */
static int tile_stop(long v, double pos, double size, double across, double across_size,
                     int swept, int rows, double *stop) {
  int forward = v > 0;
  double start = pos - (double)v;
  double l0 = span_first(pos), l1 = span_last(pos, size);
  double from = forward ? l0 : l1, to = forward ? l1 : l0;
  double lo = span_first(across), hi = span_last(across, across_size);
  long limit = rows ? MAP_H - 1 : MAP_W - 1, cells = rows ? MAP_W - 1 : MAP_H - 1;
  if (swept) {
    double s = forward ? span_first(start + size) : ceil(start / TILE) - 1.0;
    if (forward ? s < from : s > from) from = s;
  }
  if (lo < 0) lo = 0;
  if (hi > cells) hi = cells;
  if (forward) { if (from < 0) from = 0; if (to > limit) to = limit; }
  else { if (from > limit) from = limit; if (to < 0) to = 0; }
  if (lo > hi || (forward ? from > to : from < to)) return 0;
  for (long line = (long)from;; line += forward ? 1 : -1) {
    for (long cell = (long)lo; cell <= (long)hi; cell++)
      if (rows ? solid[line][cell] : solid[cell][line]) {
        *stop = forward ? (double)(line * TILE) - size : (double)((line + 1) * TILE);
        return 1;
      }
    if (line == (long)to) return 0;
  }
}

/* Whether the box covers a solid cell. */
static int box_solid(double x, double y, double w, double h) {
  long c0 = (long)span_first(x), c1 = (long)span_last(x, w);
  long r0 = (long)span_first(y), r1 = (long)span_last(y, h);
  for (long r = r0; r <= r1; r++)
    for (long c = c0; c <= c1; c++)
      if (solid_at(c, r)) return 1;
  return 0;
}

/* Steps 2 to 7 of the pipeline and tile ground (docs/physics.org, "The
   pipeline", "Standing on things") for a gravity body of w x h: S1's
   bodies are never inside solid tiles at a frame's start (no pushes), so
   the swept escape never applies; a body that is is reported, not moved. */
static long escapes_needed;
static void tile_motion(body *b, double w, double h, int swept) {
  double stop;
  b->vy += b->ay;
  b->ay = 0;
  b->vy += 1;                                   /* gravity */
  if (swept && (b->vx != 0 || b->vy != 0) && box_solid(b->x, b->y, w, h)) escapes_needed++;
  b->x += (double)b->vx;
  if (b->vx != 0 && tile_stop(b->vx, b->x, w, b->y, h, swept, 0, &stop)) { b->x = stop; b->vx = 0; }
  b->y += (double)b->vy;
  if (b->vy != 0 && tile_stop(b->vy, b->y, h, b->x, w, swept, 1, &stop)) { b->y = stop; b->vy = 0; }
  /* the row one pixel below the feet, under either lower corner */
  long row = (long)span_first(b->y + h + 1.0);
  long c0 = (long)span_first(b->x), c1 = (long)span_last(b->x, w);
  if (c1 < c0) c1 = c0;
  b->on_ground = solid_at(c0, row) || solid_at(c1, row);
}

/* ---- S1: platformer crowd */

static void s1_scene(long n) {
  reseed();
  generate_map();
  for (long k = 0; k < n;) {
    long cx = 1 + draw() % (MAP_W - 2), cy = 1 + draw() % (MAP_H - 2);
    if (solid[cy][cx]) continue;
    long s = draw() % 9 - 4;
    body b = { cx * TILE, cy * TILE, 0, 0, 0, s == 0 ? 1 : s, 0 };
    bodies[k++] = b;
  }
  count = n;
}

/* the game logic of frame f: turn round at a wall, walk, jump now and then */
static void s1_logic(long f) {
  for (long k = 0; k < count; k++) {
    body *b = &bodies[k];
    if (b->vx == 0 && f > 0) b->speed = -b->speed;
    b->vx = b->speed;
    if (b->on_ground && (f + k) % 60 == 0) b->ay = -10;
  }
}

static void s1_frame(long f, int swept) {
  for (long k = 0; k < count; k++) tile_motion(&bodies[k], 12, 12, swept);
  s1_logic(f);
}

/* ---- S2: solid crowd, pairs in list order over a grid of cells */

/* Strict overlap of two boxes of w x h. */
static int overlap(const body *a, const body *b, double w, double h) {
  return a->x < b->x + w && b->x < a->x + w && a->y < b->y + h && b->y < a->y + h;
}

/* Two movable solid bodies (docs/physics.org, "Solid entities"): half the
   overlap each, along the axis of smaller overlap (a tie goes to y); the
   one whose centre is smaller goes to the negative side, with equal
   centres the later one. Sums in the order the rules write them. */
static void push_apart(body *a, body *b, double w, double h) {
  double ox = fmin(a->x + w, b->x + w) - fmax(a->x, b->x);
  double oy = fmin(a->y + h, b->y + h) - fmax(a->y, b->y);
  int on_x = ox < oy;
  double half = (on_x ? ox : oy) / 2;
  double *pa = on_x ? &a->x : &a->y, *pb = on_x ? &b->x : &b->y;
  long *va = on_x ? &a->vx : &a->vy, *vb = on_x ? &b->vx : &b->vy;
  double size = on_x ? w : h;
  if (2 * *pa + size < 2 * *pb + size) {
    *pa += -half; *va = -1; *pb += half; *vb = 1;
  } else {
    *pa += half; *va = 1; *pb += -half; *vb = -1;
  }
}

/* The grid: square cells of CELL px over [0, GRID * CELL); a box's cells
   are clamped into it, so a box out of the arena is filed at its edge
   (two overlapping boxes still share a cell). Each cell holds the bodies
   whose cells include it, unordered. */
#define CELL 16
#define GRID 160
typedef struct { long *at; int n, cap; } cell_list;
static cell_list grid[GRID][GRID];
typedef struct { int x0, y0, x1, y1; } span;
static span *spans;
static long *stamp;

static int clamp_cell(double p) {
  double c = floor(p / CELL);
  return c < 0 ? 0 : c > GRID - 1 ? GRID - 1 : (int)c;
}
static span span_of(const body *b, double w, double h) {
  span s = { clamp_cell(b->x), clamp_cell(b->y), clamp_cell(b->x + w), clamp_cell(b->y + h) };
  return s;
}
static void file(long k, span s) {
  for (int cy = s.y0; cy <= s.y1; cy++)
    for (int cx = s.x0; cx <= s.x1; cx++) {
      cell_list *c = &grid[cy][cx];
      if (c->n == c->cap) {
        c->cap = c->cap ? 2 * c->cap : 8;
        c->at = realloc(c->at, c->cap * sizeof *c->at);
        if (!c->at) { fprintf(stderr, "bench-reference: out of memory\n"); exit(1); }
      }
      c->at[c->n++] = k;
    }
}
static void unfile(long k, span s) {
  for (int cy = s.y0; cy <= s.y1; cy++)
    for (int cx = s.x0; cx <= s.x1; cx++) {
      cell_list *c = &grid[cy][cx];
      for (int i = 0; i < c->n; i++)
        if (c->at[i] == k) { c->at[i] = c->at[--c->n]; break; }
    }
}
/* Re-files body k when its cells changed; 1 when they did. */
static int refresh(long k, double w, double h) {
  span s = span_of(&bodies[k], w, h), o = spans[k];
  if (s.x0 == o.x0 && s.y0 == o.y0 && s.x1 == o.x1 && s.y1 == o.y1) return 0;
  unfile(k, o);
  file(k, s);
  spans[k] = s;
  return 1;
}

/* The queue of row p: bodies after `after` in p's cells not yet queued
   in this row, kept ascending. */
static long *queue;
static long queued;
static void gather(long p, long after) {
  span s = spans[p];
  for (int cy = s.y0; cy <= s.y1; cy++)
    for (int cx = s.x0; cx <= s.x1; cx++) {
      cell_list *c = &grid[cy][cx];
      for (int i = 0; i < c->n; i++) {
        long q = c->at[i];
        if (q > after && stamp[q] != p) {
          long j = queued++;
          stamp[q] = p;
          while (j > 0 && queue[j - 1] < q) { queue[j] = queue[j - 1]; j--; }
          queue[j] = q;                         /* descending: the next is last */
        }
      }
    }
}

/* Every pair p < q in list order, each seeing the positions the pairs
   before it left, visiting only the pairs that share a cell when their
   turn comes: the others do not overlap, and visiting them does nothing. */
static void push_all_apart(double w, double h) {
  for (long k = 0; k < count; k++) stamp[k] = -1;
  for (long p = 0; p < count; p++) {
    queued = 0;
    gather(p, p);
    while (queued > 0) {
      long q = queue[--queued];
      if (!overlap(&bodies[p], &bodies[q], w, h)) continue;
      push_apart(&bodies[p], &bodies[q], w, h);
      refresh(q, w, h);
      if (refresh(p, w, h)) gather(p, q);      /* p reached new cells */
    }
  }
}

static void s2_scene(long n) {
  reseed();
  for (long k = 0; k < n; k++) {
    double x = (double)(draw() % 2040), y = (double)(draw() % 2040);
    long vx = draw() % 5 - 2, vy = draw() % 5 - 2;
    body b = { x, y, vx, vy, 0, 0, 0 };
    bodies[k] = b;
  }
  count = n;
  for (int cy = 0; cy < GRID; cy++)
    for (int cx = 0; cx < GRID; cx++) grid[cy][cx].n = 0;
  for (long k = 0; k < n; k++) { spans[k] = span_of(&bodies[k], 8, 8); file(k, spans[k]); }
}

static void clamp_axis(double *p, long *v) {
  if (*p < 0.0) { *p = 0.0; *v = -*v; }
  else if (*p > 2040.0) { *p = 2040.0; *v = -*v; }
}

static void s2_frame(void) {
  for (long k = 0; k < count; k++) {
    bodies[k].x += (double)bodies[k].vx;
    bodies[k].y += (double)bodies[k].vy;
    refresh(k, 8, 8);
  }
  push_all_apart(8, 8);
  for (long k = 0; k < count; k++) {
    clamp_axis(&bodies[k].x, &bodies[k].vx);
    clamp_axis(&bodies[k].y, &bodies[k].vy);
    refresh(k, 8, 8);
  }
}

/* ---- checksums, timing, reporting */

/* A flonum as CHICKEN's number->string writes it: 15 significant digits,
   ".0" after a whole number. */
static void flonum_string(double v, char *out, size_t size) {
  snprintf(out, size, "%.15g", v);
  if (!strpbrk(out, ".en")) strncat(out, ".0", size - strlen(out) - 1);
}

static double sum_x(void) { double s = 0; for (long k = 0; k < count; k++) s += bodies[k].x; return s; }
static double sum_y(void) { double s = 0; for (long k = 0; k < count; k++) s += bodies[k].y; return s; }
static long on_ground(void) { long c = 0; for (long k = 0; k < count; k++) c += bodies[k].on_ground; return c; }

static double now_ms(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec * 1000.0 + t.tv_nsec / 1e6;
}

static int compare(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}
/* the upper median, as bench/scenes.scm takes it */
static double median(double *xs, int n) {
  qsort(xs, n, sizeof *xs, compare);
  return xs[n / 2];
}

/* 4 decimals, without trailing zeros but one: bench/scenes.scm's `fixed` */
static void fixed(double v, char *out, size_t size) {
  snprintf(out, size, "%.4f", v);
  char *end = out + strlen(out) - 1;
  while (*end == '0' && end[-1] != '.') *end-- = '\0';
}

static char csv[1 << 16];
static void report(const char *scene, const char *mode, long n, long frames, double ms) {
  char a[32], b[32];
  fixed(ms, a, sizeof a);
  fixed(1000 * ms / n, b, sizeof b);
  printf("%s %s n=%ld  %s ms/frame  %s us/entity-frame\n", scene, mode, n, a, b);
  size_t used = strlen(csv);
  snprintf(csv + used, sizeof csv - used, "%s,%s,%ld,,%ld,%s,%s,,\n", scene, mode, n, frames, a, b);
}

static int warm_up = -1, frames = -1, runs = 3, quick = 0;
static long only_n = 0;
static const char *only_mode = NULL;

static int wanted_mode(const char *mode) { return !only_mode || strcmp(only_mode, mode) == 0; }

/* One run of S1 in a mode: the time of its timed frames (ms); the first
   run prints the checksum line. */
static double s1_run(long n, int swept, int checksum) {
  int warm = warm_up >= 0 ? warm_up : 60, timed = frames >= 0 ? frames : 600;
  double start = 0;
  s1_scene(n);
  for (long f = 0; f < warm + timed; f++) {
    if (f == warm) start = now_ms();
    s1_frame(f, swept);
  }
  double ms = now_ms() - start;
  if (checksum)
    printf("checksum S1 %s n=%ld sum-x=%.0f sum-y=%.0f on-ground=%ld\n",
           swept ? "swept" : "discrete", n, sum_x(), sum_y(), on_ground());
  return ms;
}

static void run_s1(long n) {
  int timed = frames >= 0 ? frames : 600;
  const char *names[2] = { "discrete", "swept" };
  double times[2][101];
  for (int r = 0; r < runs; r++)
    for (int m = 0; m < 2; m++)
      if (wanted_mode(names[m])) times[m][r] = s1_run(n, m, r == 0);
  for (int m = 0; m < 2; m++)
    if (wanted_mode(names[m])) report("S1", names[m], n, timed, median(times[m], runs) / timed);
  if (escapes_needed) {
    fprintf(stderr, "bench-reference: %ld S1 bodies started a swept frame inside solid tiles\n",
            escapes_needed);
    exit(1);
  }
}

static void run_s2(long n) {
  int warm = warm_up >= 0 ? warm_up : 60, timed = frames >= 0 ? frames : 600;
  double times[101];
  for (int r = 0; r < runs; r++) {
    double start = 0;
    s2_scene(n);
    for (long f = 0; f < warm + timed; f++) {
      if (f == warm) start = now_ms();
      s2_frame();
    }
    times[r] = now_ms() - start;
    if (r == 0) {
      char x[40], y[40];
      flonum_string(sum_x(), x, sizeof x);
      flonum_string(sum_y(), y, sizeof y);
      printf("checksum S2 flonum n=%ld sum-x=%s sum-y=%s\n", n, x, y);
    }
  }
  report("S2", "flonum", n, timed, median(times, runs) / timed);
}

static void usage(void) {
  fprintf(stderr, "usage: bench-reference [--runs R] [--csv FILE] [--quick] [--n N] [--mode M] "
                  "[--warm-up W] [--frames F] [S1 S2]\n");
  exit(2);
}

static long number(const char *flag, const char *s, long lo, long hi) {
  char *end;
  long v = strtol(s, &end, 10);
  if (*s == '\0' || *end != '\0' || v < lo || v > hi) {
    fprintf(stderr, "bench-reference: %s wants a whole number from %ld to %ld, not \"%s\"\n",
            flag, lo, hi, s);
    exit(2);
  }
  return v;
}

int main(int argc, char **argv) {
  const char *csv_file = "bench/reference/results.csv";
  int s1 = 0, s2 = 0, named = 0;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (strcmp(a, "S1") == 0) { s1 = 1; named = 1; }
    else if (strcmp(a, "S2") == 0) { s2 = 1; named = 1; }
    /* bench-scenes' other scenes and --quick: make bench passes the same
       BENCH_ARGS to both programs */
    else if (strcmp(a, "steps") == 0 || (a[0] == 'S' && a[1] >= '3' && a[1] <= '7' && !a[2])) named = 1;
    else if (strcmp(a, "--quick") == 0) quick = 1;
    else if (!v) usage();
    else if (strcmp(a, "--runs") == 0) { runs = (int)number(a, v, 1, 100); i++; }
    else if (strcmp(a, "--n") == 0) { only_n = number(a, v, 2, 1000000); i++; }
    else if (strcmp(a, "--warm-up") == 0) { warm_up = (int)number(a, v, 0, 1000000); i++; }
    else if (strcmp(a, "--frames") == 0) { frames = (int)number(a, v, 1, 1000000); i++; }
    else if (strcmp(a, "--mode") == 0) { only_mode = v; i++; }
    else if (strcmp(a, "--csv") == 0) { csv_file = v; i++; }
    else usage();
  }
  if (!named) s1 = s2 = 1;
  long largest = only_n ? only_n : 16000;
  bodies = malloc(largest * sizeof *bodies);
  spans = malloc(largest * sizeof *spans);
  stamp = malloc(largest * sizeof *stamp);
  queue = malloc(largest * sizeof *queue);
  if (!bodies || !spans || !stamp || !queue) { fprintf(stderr, "bench-reference: out of memory\n"); return 1; }
  /* the sizes of bench-scenes; --n keeps one of them */
  long s1_sizes[] = { 100, 1000, 10000, 16000 }, s2_sizes[] = { 100, 1000, 5000 };
  if (s1 && (wanted_mode("discrete") || wanted_mode("swept")))
    for (int i = 0; i < (quick ? 2 : 4); i++)
      if (!only_n || only_n == s1_sizes[i]) run_s1(only_n ? only_n : s1_sizes[i]);
  if (s2 && wanted_mode("flonum"))
    for (int i = 0; i < (quick ? 1 : 3); i++)
      if (!only_n || only_n == s2_sizes[i]) run_s2(only_n ? only_n : s2_sizes[i]);
  FILE *out = fopen(csv_file, "w");
  if (!out) { fprintf(stderr, "bench-reference: cannot write the CSV file \"%s\"\n", csv_file); return 1; }
  fprintf(out, "scene,mode,n,speed,frames,ms_per_frame,us_per_entity_frame,tunnel_pct,wrong_pct\n%s", csv);
  fclose(out);
  printf("wrote %s\n", csv_file);
  return 0;
}
