/* The benchmark scenes S1, S2 and S5 of docs/performance.org ("The
   scenes") in plain C, doubles for positions: what the same work costs without
   Scheme, to read bench/scenes.scm's figures against ("Against a plain C
   implementation" in docs/performance.org). It prints the same checksum
   lines as bench/scenes.scm; equal checksums are what make it the same
   scene (tests/bench-reference-test.scm compares them). Only the rules
   these scenes use are here: no slopes, one-way tiles, immovable bodies
   or tweens. Besides the times it prints the scenes' work per body-frame
   (pairs tested, pushes, escapes), which is the scene's, not the
   program's. Built by the Makefile as build/bench-reference:
     bench-reference [--runs R] [--csv FILE] [--quick] [--n N] [--mode M]
                     [--warm-up W] [--frames F] [S1 S2 S5]
   S1 runs its two tile modes, discrete and swept (docs/physics.org,
   "Collision modes"); S2 and S5 run with flonum positions, bench/scenes.scm's
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
   line's near side. Returns 0 when nothing stops it. rows: lines are rows.
   start: where this frame's motion on the axis started, pos - v unless
   the escape moved it. */
static int tile_stop(long v, double pos, double size, double across, double across_size,
                     int swept, double start, int rows, double *stop) {
  int forward = v > 0;
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

/* Tile ground: a solid cell in the row one pixel below the feet, under
   either lower corner. */
static int tile_ground(const body *b, double w, double h) {
  long row = (long)span_first(b->y + h + 1.0);
  long c0 = (long)span_first(b->x), c1 = (long)span_last(b->x, w);
  if (c1 < c0) c1 = c0;
  return solid_at(c0, row) || solid_at(c1, row);
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
  if (b->vx != 0 && tile_stop(b->vx, b->x, w, b->y, h, swept, b->x - (double)b->vx, 0, &stop)) {
    b->x = stop; b->vx = 0;
  }
  b->y += (double)b->vy;
  if (b->vy != 0 && tile_stop(b->vy, b->y, h, b->x, w, swept, b->y - (double)b->vy, 1, &stop)) {
    b->y = stop; b->vy = 0;
  }
  b->on_ground = tile_ground(b, w, h);
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
#define GRID 256
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
/* Re-files body k in the cells of s when they changed; 1 when they did. */
static int refresh(long k, span s) {
  span o = spans[k];
  if (s.x0 == o.x0 && s.y0 == o.y0 && s.x1 == o.x1 && s.y1 == o.y1) return 0;
  unfile(k, o);
  file(k, s);
  spans[k] = s;
  return 1;
}

/* The queue of row p: bodies after `after` in p's cells not yet queued
   in this row, kept descending, so that the next is the last. */
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
          queue[j] = q;
        }
      }
    }
}

/* Every pair p < q in list order, each seeing the positions the pairs
   before it left, visiting only the pairs that share a cell when their
   turn comes: the others do not overlap, and visiting them does nothing.
   visit(p, q) pushes the pair apart if it overlaps (1 when it did);
   cells(k) are body k's cells now. */
static long pairs_tested, pushes;      /* the scene's work, counted */
static void visit_pairs(int (*visit)(long, long), span (*cells)(long)) {
  for (long k = 0; k < count; k++) stamp[k] = -1;
  for (long p = 0; p < count; p++) {
    queued = 0;
    gather(p, p);
    while (queued > 0) {
      long q = queue[--queued];
      pairs_tested++;
      if (!visit(p, q)) continue;
      pushes++;
      refresh(q, cells(q));
      if (refresh(p, cells(p))) gather(p, q);      /* p reached new cells */
    }
  }
}

static void clear_grid(void) {
  for (int cy = 0; cy < GRID; cy++)
    for (int cx = 0; cx < GRID; cx++) grid[cy][cx].n = 0;
}

/* S2's bodies, 8 x 8 */
static span s2_cells(long k) { return span_of(&bodies[k], 8, 8); }
static int s2_visit(long p, long q) {
  if (!overlap(&bodies[p], &bodies[q], 8, 8)) return 0;
  push_apart(&bodies[p], &bodies[q], 8, 8);
  return 1;
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
  clear_grid();
  for (long k = 0; k < n; k++) { spans[k] = s2_cells(k); file(k, spans[k]); }
}

static void clamp_axis(double *p, long *v) {
  if (*p < 0.0) { *p = 0.0; *v = -*v; }
  else if (*p > 2040.0) { *p = 2040.0; *v = -*v; }
}

static void s2_frame(void) {
  for (long k = 0; k < count; k++) {
    bodies[k].x += (double)bodies[k].vx;
    bodies[k].y += (double)bodies[k].vy;
    refresh(k, s2_cells(k));
  }
  visit_pairs(s2_visit, s2_cells);
  for (long k = 0; k < count; k++) {
    clamp_axis(&bodies[k].x, &bodies[k].vx);
    clamp_axis(&bodies[k].y, &bodies[k].vy);
    refresh(k, s2_cells(k));
  }
}

/* ---- S5: S1's map and movers, every one solid, flonum positions */

/* bench-scenes' S5 --mode flonum starts every position as a flonum, but
   a tile stop puts a body on a whole pixel, an exact integer, and a push
   between two bodies exact on that axis moves each by an exact half, so
   some coordinates are exact rationals of denominator 2^e, and a dense
   crowd pushes a few of them to denominators of 2^100 and more. So a
   position here is of either kind, and each operation takes the kinds as
   Scheme's generic arithmetic does: exact with exact stays exact; with a
   flonum, the exact one is rounded to a double and the operation is one
   IEEE operation; comparisons are exact. An exact value is kept in the
   double d while a double holds it exactly (nearly always: the fast
   path, plain double arithmetic), else in the binary128 q, 113 bits
   (beyond those it rounds, where Scheme does not: the checksums say
   whether that ever mattered). */
typedef struct { int kind; double d; __float128 q; } num;   /* kind: */
enum { FLONUM, EXACT, EXACT_WIDE };

static num num_int(long v) { num r = { EXACT, (double)v, 0 }; return r; }
static num num_flo(double d) { num r = { FLONUM, d, 0 }; return r; }
static __float128 wide(num a) { return a.kind == EXACT_WIDE ? a.q : (__float128)a.d; }
static double num_double(num a) { return a.kind == EXACT_WIDE ? (double)a.q : a.d; }
/* an exact value, in a double when one holds it */
static num exact_of(__float128 q) {
  double d = (double)q;
  num r = { EXACT, d, 0 };
  if ((__float128)d != q) { r.kind = EXACT_WIDE; r.q = q; }
  return r;
}
static num add(num a, num b) {
  if (a.kind == FLONUM || b.kind == FLONUM) return num_flo(num_double(a) + num_double(b));
  if (a.kind == EXACT && b.kind == EXACT) {
    double s = a.d + b.d, bb = s - a.d;         /* the sum's rounding error, exactly */
    if ((a.d - (s - bb)) + (b.d - bb) == 0) { num r = { EXACT, s, 0 }; return r; }
  }
  return exact_of(wide(a) + wide(b));
}
static num neg(num a) { a.d = -a.d; a.q = -a.q; return a; }
static num sub(num a, num b) { return add(a, neg(b)); }
static num addi(num a, long v) { return add(a, num_int(v)); }
static num half(num a) { a.d /= 2; a.q /= 2; return a; }
static num twice(num a) { a.d *= 2; a.q *= 2; return a; }
/* -1, 0 or 1, exactly */
static int cmp(num a, num b) {
  if (a.kind != EXACT_WIDE && b.kind != EXACT_WIDE) return a.d < b.d ? -1 : a.d > b.d;
  __float128 x = wide(a), y = wide(b);
  return x < y ? -1 : x > y;
}
static int lt(num a, num b) { return cmp(a, b) < 0; }
static num absn(num a) { return cmp(a, num_int(0)) < 0 ? neg(a) : a; }
/* Scheme's min and max: the one the comparison picks (the first of
   equals), made a flonum when either is one */
static num inexact_if(num r, num a, num b) {
  return a.kind != FLONUM && b.kind != FLONUM ? r : num_flo(num_double(r));
}
static num minn(num a, num b) { return inexact_if(lt(b, a) ? b : a, a, b); }
static num maxn(num a, num b) { return inexact_if(cmp(b, a) > 0 ? b : a, a, b); }
/* same kind, same value */
static int eqv(num a, num b) { return (a.kind == FLONUM) == (b.kind == FLONUM) && cmp(a, b) == 0; }
/* floor(a / T) and ceil(a / T) */
static long floor_wide(__float128 q) { long t = (long)q; return (__float128)t > q ? t - 1 : t; }
static long floor_cell(num a) {
  return a.kind == EXACT_WIDE ? floor_wide(a.q / TILE) : (long)floor(a.d / TILE);
}
static long ceil_cell(num a) {
  return a.kind == EXACT_WIDE ? -floor_wide(-a.q / TILE) : (long)ceil(a.d / TILE);
}

/* A squared distance, for the escape's comparisons: exact (the square of
   an exact offset, kept in a 113-bit binary128, exact up to 56
   significant bits an offset, rounded past that) or a double. */
typedef struct { int exact; __float128 q; double d; } dist;
static dist square(num a) {
  dist r = { a.kind != FLONUM, 0, 0 };
  if (a.kind == FLONUM) r.d = a.d * a.d;
  else r.q = wide(a) * wide(a);
  return r;
}
static dist dist_add(dist a, dist b) {
  dist r;
  if (a.exact && b.exact) { r.exact = 1; r.q = a.q + b.q; r.d = 0; }
  else { r.exact = 0; r.d = (a.exact ? (double)a.q : a.d) + (b.exact ? (double)b.q : b.d); r.q = 0; }
  return r;
}
static int dist_lt(dist a, dist b) {
  return (a.exact ? a.q : (__float128)a.d) < (b.exact ? b.q : (__float128)b.d);
}
/* the least whole s with s * s >= ceil(v) */
static long sqrt_ceiling(dist v) {
  long r = v.exact ? (long)v.q + ((__float128)(long)v.q < v.q) : (long)ceil(v.d);
  long s = (long)sqrt((double)r);
  while (s > 0 && s * s > r) s--;
  while ((s + 1) * (s + 1) <= r) s++;
  return s * s == r ? s : s + 1;
}

static long last_cell(num p, long size) { return ceil_cell(addi(p, size)) - 1; }

static num *px, *py;          /* S5's positions; the rest is in bodies[] */

static int box_solid_n(num x, num y, long w, long h) {
  long c0 = floor_cell(x), c1 = last_cell(x, w), r0 = floor_cell(y), r1 = last_cell(y, h);
  for (long r = r0; r <= r1; r++)
    for (long c = c0; c <= c1; c++)
      if (solid_at(c, r)) return 1;
  return 0;
}

/* tile_stop on numbers of either kind */
static int tile_stop_n(long v, num pos, long size, num across, long across_size, num start, int rows,
                       long *stop) {
  int forward = v > 0;
  long l0 = floor_cell(pos), l1 = last_cell(pos, size);
  long lo = floor_cell(across), hi = last_cell(across, across_size);
  long limit = rows ? MAP_H - 1 : MAP_W - 1, cells = rows ? MAP_W - 1 : MAP_H - 1;
  long from = forward ? l0 : l1, to = forward ? l1 : l0;
  long s = forward ? floor_cell(addi(start, size)) : ceil_cell(start) - 1;   /* swept */
  if (forward ? s < from : s > from) from = s;
  if (lo < 0) lo = 0;
  if (hi > cells) hi = cells;
  if (forward) { if (from < 0) from = 0; if (to > limit) to = limit; }
  else { if (from > limit) from = limit; if (to < 0) to = 0; }
  if (lo > hi || (forward ? from > to : from < to)) return 0;
  for (long line = from;; line += forward ? 1 : -1) {
    for (long cell = lo; cell <= hi; cell++)
      if (rows ? solid[line][cell] : solid[cell][line]) {
        *stop = forward ? line * TILE - size : (line + 1) * TILE;
        return 1;
      }
    if (line == to) return 0;
  }
}

/* The escape (docs/physics.org, "A body that starts a frame inside solid
   tiles"): the nearest place where the box covers no solid cell, each
   coordinate unchanged or flush with a tile edge. First the four
   straight moves, up, down, left, right, each past the solid lines in
   its way until the box is free: the shortest, of equals the first in
   that order. Then moves on both axes made of candidates within its
   length: x candidates by |dx| (the negative one first), for each the
   first free y candidate by |dy| (the upward one first), kept only when
   strictly nearer. Offsets are edge - pos, as bench-scenes makes them. */

/* The solid line runner i (0 up, 1 down, 2 left, 3 right) must pass
   next: the one nearest the side it moves away from; -1 when the box is
   free. */
static long blocking_line(int i, num x, num y, long w, long h) {
  int vertical = i < 2, up = i == 0 || i == 2;
  num pos = vertical ? y : x, across = vertical ? x : y;
  long size = vertical ? h : w, across_size = vertical ? w : h;
  long l0 = floor_cell(pos), l1 = last_cell(pos, size);
  long c0 = floor_cell(across), c1 = last_cell(across, across_size);
  long limit = vertical ? MAP_H - 1 : MAP_W - 1, cells = vertical ? MAP_W - 1 : MAP_H - 1;
  if (c0 < 0) c0 = 0;
  if (c1 > cells) c1 = cells;
  if (l0 < 0) l0 = 0;
  if (l1 > limit) l1 = limit;
  if (c0 > c1 || l0 > l1) return -1;
  for (long line = up ? l1 : l0; up ? line >= l0 : line <= l1; line += up ? -1 : 1)
    for (long c = c0; c <= c1; c++)
      if (vertical ? solid[line][c] : solid[c][line]) return line;
  return -1;
}

static long runner_place(int i, long line, long w, long h) {
  return i == 0 ? line * TILE - h : i == 2 ? line * TILE - w : (line + 1) * TILE;
}

static int by_distance(const void *a, const void *b) {
  num x = *(const num *)a, y = *(const num *)b;
  int c = cmp(absn(x), absn(y));
  return c ? c : cmp(x, y);
}
/* The offsets within reach that put [pos, pos + size) flush with a tile
   edge, and 0; by |offset|, the negative first. */
static num *offsets_x, *offsets_y;
static long offsets_room;
static int candidates(num pos, long size, long reach, num **out) {
  long need = 2 * (2 * reach + size) / TILE + 8;
  if (need > offsets_room) {
    offsets_room = 2 * need;
    offsets_x = realloc(offsets_x, offsets_room * sizeof *offsets_x);
    offsets_y = realloc(offsets_y, offsets_room * sizeof *offsets_y);
    if (!offsets_x || !offsets_y) { fprintf(stderr, "bench-reference: out of memory\n"); exit(1); }
  }
  num *o = *out, r = num_int(reach), limit = addi(addi(pos, size), reach);
  int n = 0;
  o[n++] = num_int(0);
  for (long k = floor_cell(addi(pos, -reach)); cmp(num_int(k * TILE), limit) <= 0; k++) {
    num near = sub(num_int(k * TILE), pos), far = sub(num_int(k * TILE - size), pos);
    if (cmp(absn(near), r) <= 0) o[n++] = near;
    if (cmp(absn(far), r) <= 0) o[n++] = far;
  }
  qsort(o, n, sizeof *o, by_distance);
  return n;
}

/* The way out (*dx, *dy) of the box at (x, y); 0 when it is free. */
static int way_out(num x, num y, long w, long h, num *dx, num *dy) {
  if (!box_solid_n(x, y, w, h)) return 0;
  num at[4] = { y, y, x, x };
  dist far = { 1, 0, 0 };
  int best = -1;
  for (int i = 0; i < 4; i++) {
    long line;
    while ((line = blocking_line(i, i < 2 ? x : at[i], i < 2 ? at[i] : y, w, h)) >= 0)
      at[i] = num_int(runner_place(i, line, w, h));
    dist gone = square(sub(at[i], i < 2 ? y : x));
    if (best < 0 || dist_lt(gone, far)) { far = gone; best = i; }
  }
  *dx = best < 2 ? num_int(0) : sub(at[best], x);
  *dy = best < 2 ? sub(at[best], y) : num_int(0);
  dist bound = dist_add(square(*dx), square(*dy));
  long reach = sqrt_ceiling(bound);
  int nx = candidates(x, w, reach, &offsets_x), ny = candidates(y, h, reach, &offsets_y);
  for (int i = 0; i < nx && dist_lt(square(offsets_x[i]), bound); i++) {
    dist limit = bound, sx = square(offsets_x[i]);
    for (int j = 0; j < ny; j++) {
      if (!dist_lt(dist_add(sx, square(offsets_y[j])), limit)) break;
      if (!box_solid_n(add(x, offsets_x[i]), add(y, offsets_y[j]), w, h)) {
        *dx = offsets_x[i];
        *dy = offsets_y[j];
        bound = dist_add(square(*dx), square(*dy));
        break;
      }
    }
  }
  return 1;
}

/* Where the escape puts the box at (*x, *y): moved by the way out, then
   each flonum coordinate it moved stepped on to the next double in the
   direction of its move until the box covers no solid cell (a rounded
   move can leave it 1e-15 px inside), at most 8 times. 0: it was free. */
static int escape_place(num *x, num *y, long w, long h) {
  num dx, dy;
  if (!way_out(*x, *y, w, h, &dx, &dy)) return 0;
  num nx = add(*x, dx), ny = add(*y, dy);
  int step_x = !eqv(dx, num_int(0)) && nx.kind == FLONUM, step_y = !eqv(dy, num_int(0)) && ny.kind == FLONUM;
  for (int tries = 0; tries < 8 && box_solid_n(nx, ny, w, h); tries++) {
    if (step_x) nx.d = nextafter(nx.d, cmp(dx, num_int(0)) < 0 ? -INFINITY : INFINITY);
    if (step_y) ny.d = nextafter(ny.d, cmp(dy, num_int(0)) < 0 ? -INFINITY : INFINITY);
  }
  *x = nx;
  *y = ny;
  return 1;
}

/* S1's motion for a solid body in swept mode, where a push may have left
   it inside solid tiles: a body that moves leaves them first, from where
   its frame started, (x - vx, y); the x sweep starts where the escape put
   that start, the body as far from it as before. */
static long escapes;
static void solid_motion(long k, long w, long h) {
  body *b = &bodies[k];
  long stop;
  b->vy += b->ay;
  b->ay = 0;
  b->vy += 1;
  px[k] = addi(px[k], b->vx);
  num sx = addi(px[k], -b->vx);
  if (b->vx != 0 || b->vy != 0) {
    num nx = sx, ny = py[k];
    if (escape_place(&nx, &ny, w, h)) {
      escapes++;
      if (!eqv(nx, sx)) px[k] = addi(nx, b->vx);
      py[k] = ny;
      sx = nx;
    }
  }
  if (b->vx != 0 && tile_stop_n(b->vx, px[k], w, py[k], h, sx, 0, &stop)) { px[k] = num_int(stop); b->vx = 0; }
  py[k] = addi(py[k], b->vy);
  if (b->vy != 0 && tile_stop_n(b->vy, py[k], h, px[k], w, addi(py[k], -b->vy), 1, &stop)) {
    py[k] = num_int(stop);
    b->vy = 0;
  }
}

/* The grid holds each body in the cells of its box widened by a pixel,
   so that the rounding of an exact coordinate to a double never leaves
   out a cell it covers. */
static span s5_cells(long k) {
  double x = num_double(px[k]), y = num_double(py[k]);
  span s = { clamp_cell(x - 1), clamp_cell(y - 1), clamp_cell(x + 13), clamp_cell(y + 13) };
  return s;
}

static int tile_ground_n(long k, long w, long h) {
  num bottom = addi(py[k], h);
  long row = floor_cell(addi(bottom, 1)), c0 = floor_cell(px[k]), c1 = last_cell(px[k], w);
  if (c1 < c0) c1 = c0;
  return solid_at(c0, row) || solid_at(c1, row);
}

/* Entity ground (docs/physics.org, "Standing on things"): another solid
   body overlapping this one horizontally whose top is within 5 px of its
   bottom, while |vy| <= 12; its top lies in the cells of rows bottom - 5
   to bottom + 5 (a pixel more each way, for rounding). */
static long ground_tested;
static int entity_ground(long k, long w, long h) {
  if (labs(bodies[k].vy) > 12) return 0;
  num bottom = addi(py[k], h);
  double x = num_double(px[k]), yb = num_double(bottom);
  int x0 = clamp_cell(x - 1), x1 = clamp_cell(x + w + 1), y0 = clamp_cell(yb - 6), y1 = clamp_cell(yb + 6);
  for (int cy = y0; cy <= y1; cy++)
    for (int cx = x0; cx <= x1; cx++) {
      cell_list *c = &grid[cy][cx];
      for (int i = 0; i < c->n; i++) {
        long s = c->at[i];
        ground_tested++;
        if (s != k && lt(px[k], addi(px[s], w)) && lt(px[s], addi(px[k], w)) &&
            cmp(absn(sub(py[s], bottom)), num_int(5)) <= 0)
          return 1;
      }
    }
  return 0;
}

/* Two movable solid bodies of 12 x 12 (docs/physics.org, "Solid
   entities"), in Scheme's order of operations. */
static int s5_visit(long p, long q) {
  const long size = 12;
  if (!(lt(px[p], addi(px[q], size)) && lt(px[q], addi(px[p], size)) &&
        lt(py[p], addi(py[q], size)) && lt(py[q], addi(py[p], size))))
    return 0;
  num ox = sub(minn(addi(px[p], size), addi(px[q], size)), maxn(px[p], px[q]));
  num oy = sub(minn(addi(py[p], size), addi(py[q], size)), maxn(py[p], py[q]));
  int on_x = lt(ox, oy);
  num d = half(on_x ? ox : oy);
  num *a = on_x ? &px[p] : &py[p], *b = on_x ? &px[q] : &py[q];
  long *va = on_x ? &bodies[p].vx : &bodies[p].vy, *vb = on_x ? &bodies[q].vx : &bodies[q].vy;
  if (lt(addi(twice(*a), size), addi(twice(*b), size))) {
    *a = add(*a, neg(d)); *va = -1; *b = add(*b, d); *vb = 1;
  } else {
    *a = add(*a, d); *va = 1; *b = add(*b, neg(d)); *vb = -1;
  }
  return 1;
}

static void s5_scene(long n) {
  s1_scene(n);
  for (long k = 0; k < n; k++) { px[k] = num_flo(bodies[k].x); py[k] = num_flo(bodies[k].y); }
  clear_grid();
  for (long k = 0; k < n; k++) { spans[k] = s5_cells(k); file(k, spans[k]); }
  escapes = 0;
}

/* motion, then ground (tiles or a body below), then the pairs, then S1's logic */
static void s5_frame(long f) {
  for (long k = 0; k < count; k++) { solid_motion(k, 12, 12); refresh(k, s5_cells(k)); }
  for (long k = 0; k < count; k++)
    bodies[k].on_ground = tile_ground_n(k, 12, 12) || entity_ground(k, 12, 12);
  visit_pairs(s5_visit, s5_cells);
  s1_logic(f);
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
      if (f == warm) { start = now_ms(); pairs_tested = pushes = 0; }
      s2_frame();
    }
    times[r] = now_ms() - start;
    if (r == 0) {
      double body_frames = (double)n * timed;
      printf("  work per body-frame: %.2f pairs tested, %.3f pushed apart\n",
             pairs_tested / body_frames, pushes / body_frames);
      char x[40], y[40];
      flonum_string(sum_x(), x, sizeof x);
      flonum_string(sum_y(), y, sizeof y);
      printf("checksum S2 flonum n=%ld sum-x=%s sum-y=%s\n", n, x, y);
    }
  }
  report("S2", "flonum", n, timed, median(times, runs) / timed);
}

/* A sum as bench-scenes writes it: exact while every term is (a whole
   number, or n/d), else a flonum, each term added in list order. */
static void int128_string(__int128 v, char *out) {
  char digits[48];
  int i = 0, minus = v < 0;
  unsigned __int128 u = minus ? -(unsigned __int128)v : (unsigned __int128)v;
  do { digits[i++] = '0' + (int)(u % 10); u /= 10; } while (u);
  if (minus) *out++ = '-';
  while (i) *out++ = digits[--i];
  *out = '\0';
}
static void sum_string(num *ps, char *out, size_t size) {
  num s = num_int(0);
  for (long k = 0; k < count; k++) s = add(s, ps[k]);
  if (s.kind == FLONUM) { flonum_string(s.d, out, size); return; }
  __float128 q = wide(s), d = 1;
  while ((__float128)(__int128)(q * d) != q * d) d *= 2;
  char nd[48], dd[48];
  int128_string((__int128)(q * d), nd);
  int128_string((__int128)d, dd);
  snprintf(out, size, d > 1 ? "%s/%s" : "%s", nd, dd);
}

static void run_s5(long n) {
  int warm = warm_up >= 0 ? warm_up : 10, timed = frames >= 0 ? frames : 60;
  double times[101];
  for (int r = 0; r < runs; r++) {
    double start = 0;
    s5_scene(n);
    for (long f = 0; f < warm + timed; f++) {
      if (f == warm) { start = now_ms(); pairs_tested = pushes = escapes = ground_tested = 0; }
      s5_frame(f);
    }
    times[r] = now_ms() - start;
    if (r == 0) {
      double body_frames = (double)n * timed;
      printf("  work per body-frame: %.2f pairs tested, %.3f pushed apart, %.4f escapes, "
             "%.2f bodies tested for ground\n", pairs_tested / body_frames, pushes / body_frames,
             escapes / body_frames, ground_tested / body_frames);
      char x[64], y[64];
      sum_string(px, x, sizeof x);
      sum_string(py, y, sizeof y);
      printf("checksum S5 flonum n=%ld sum-x=%s sum-y=%s on-ground=%ld\n", n, x, y, on_ground());
    }
  }
  report("S5", "flonum", n, timed, median(times, runs) / timed);
}

static void usage(void) {
  fprintf(stderr, "usage: bench-reference [--runs R] [--csv FILE] [--quick] [--n N] [--mode M] "
                  "[--warm-up W] [--frames F] [S1 S2 S5]\n");
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
  int s1 = 0, s2 = 0, s5 = 0, named = 0;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (strcmp(a, "S1") == 0) { s1 = 1; named = 1; }
    else if (strcmp(a, "S2") == 0) { s2 = 1; named = 1; }
    else if (strcmp(a, "S5") == 0) { s5 = 1; named = 1; }
    /* bench-scenes' other scenes and --quick: make bench passes the same
       BENCH_ARGS to both programs */
    else if (strcmp(a, "steps") == 0 || (a[0] == 'S' && a[1] >= '3' && a[1] <= '7' && a[1] != '5' && !a[2])) named = 1;
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
  if (!named) s1 = s2 = s5 = 1;
  long largest = only_n ? only_n : 16000;
  bodies = malloc(largest * sizeof *bodies);
  spans = malloc(largest * sizeof *spans);
  stamp = malloc(largest * sizeof *stamp);
  queue = malloc(largest * sizeof *queue);
  px = malloc(largest * sizeof *px);
  py = malloc(largest * sizeof *py);
  if (!bodies || !spans || !stamp || !queue || !px || !py) { fprintf(stderr, "bench-reference: out of memory\n"); return 1; }
  /* the sizes of bench-scenes; --n keeps one of them */
  long s1_sizes[] = { 100, 1000, 10000, 16000 }, s2_sizes[] = { 100, 1000, 5000 };
  if (s1 && (wanted_mode("discrete") || wanted_mode("swept")))
    for (int i = 0; i < (quick ? 2 : 4); i++)
      if (!only_n || only_n == s1_sizes[i]) run_s1(only_n ? only_n : s1_sizes[i]);
  if (s2 && wanted_mode("flonum"))
    for (int i = 0; i < (quick ? 1 : 3); i++)
      if (!only_n || only_n == s2_sizes[i]) run_s2(only_n ? only_n : s2_sizes[i]);
  long s5_sizes[] = { 1000, 4000, 16000 };
  if (s5 && wanted_mode("flonum"))
    for (int i = 0; i < (quick ? 1 : 3); i++)
      if (!only_n || only_n == s5_sizes[i]) run_s5(only_n ? only_n : s5_sizes[i]);
  FILE *out = fopen(csv_file, "w");
  if (!out) { fprintf(stderr, "bench-reference: cannot write the CSV file \"%s\"\n", csv_file); return 1; }
  fprintf(out, "scene,mode,n,speed,frames,ms_per_frame,us_per_entity_frame,tunnel_pct,wrong_pct\n%s", csv);
  fclose(out);
  printf("wrote %s\n", csv_file);
  return 0;
}
