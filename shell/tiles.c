/* The cells of one orthogonal tile layer drawn in one call (sdl2.scm's
   render-tile-cells!, called by mapdraw.scm): the same copies, in the same
   order and at the same pixels, as mapdraw.scm's per-cell walk, without
   a trip through Scheme for each cell.

   table: DS_TILE_FIELDS ints per gid g from index g * DS_TILE_FIELDS:
   texture (1 + an index into the textures set with ds_tiles_texture, 0 for
   none), source x y w h, and the tileset's tile offset x y. A cell is
   drawn with its bottom-left corner at (col * tw + ox + fx, (row + 1) * th
   + oy + fy): fx and fy are the layer camera's floor(-lx), floor(-ly).

   Pass 0 draws nothing and marks in `used` each texture a visible cell
   needs (the caller sets the layer's modulation on those first); pass 1
   draws. With batch on (an accelerated renderer), runs of unturned cells
   of one texture go to SDL as one SDL_RenderGeometry call, two triangles a
   cell split along the same diagonal as SDL's own copy; a diagonally
   flipped cell (a quarter turn) is SDL_RenderCopyEx as before, after the
   run so far. Every index is checked: no input reads outside the arrays. */

#define DS_TILE_FIELDS 8
#define DS_MAX_TILE_TEXTURES 64
/* The most quads a run sends at once: each run costs the driver a draw
   call and gl-batch.c's first quad through SDL, so a crowd of a few
   thousand sprites is one run; 16-bit indices reach 16,384 quads. */
#define DS_BATCH_QUADS 4096

static SDL_Texture *ds_tile_textures[DS_MAX_TILE_TEXTURES];
static SDL_Vertex ds_batch_verts[DS_BATCH_QUADS * 4];
static int ds_batch_indices[DS_BATCH_QUADS * 6];
static int ds_batch_indices_ready = 0;

static void ds_tiles_texture(int i, SDL_Texture *t) {
  if (i >= 0 && i < DS_MAX_TILE_TEXTURES) ds_tile_textures[i] = t;
}

#include "shell/gl-batch.c"

static long long ds_floor_half(long long v) { return v >= 0 ? v / 2 : -((-v + 1) / 2); }

/* n quads of texture t whose vertices are all written, colours too: by
   OpenGL itself where gl-batch.c can, else by SDL. */
static int ds_batch_send(SDL_Renderer *r, SDL_Texture *t, int n) {
  int i;
  if (n == 0 || !t) return 0;
  if (!ds_batch_indices_ready) {
    for (i = 0; i < DS_BATCH_QUADS; i++) {
      /* SDL's copy on opengl: the triangles TL TR BL and TR BL BR of
         corners TL TR BL BR, each in SDL's order (a turned quad's pixels
         follow the order, sdl2.scm's ds_q_copy_turned) */
      ds_batch_indices[i * 6 + 0] = i * 4 + 0;
      ds_batch_indices[i * 6 + 1] = i * 4 + 1;
      ds_batch_indices[i * 6 + 2] = i * 4 + 2;
      ds_batch_indices[i * 6 + 3] = i * 4 + 1;
      ds_batch_indices[i * 6 + 4] = i * 4 + 2;
      ds_batch_indices[i * 6 + 5] = i * 4 + 3;
    }
    ds_batch_indices_ready = 1;
  }
  i = ds_gl_send(r, t, ds_batch_verts, ds_batch_indices, n);
  if (i != 0) return i < 0 ? i : 0;
  return SDL_RenderGeometry(r, t, ds_batch_verts, n * 4, ds_batch_indices, n * 6);
}

/* The pending run: n quads of texture t, each vertex coloured with the
   texture's modulation (what SDL's own copy would use). */
static int ds_batch_flush(SDL_Renderer *r, SDL_Texture *t, int n) {
  Uint8 cr = 255, cg = 255, cb = 255, ca = 255;
  int i;
  if (n == 0 || !t) return 0;
  SDL_GetTextureColorMod(t, &cr, &cg, &cb);
  SDL_GetTextureAlphaMod(t, &ca);
  for (i = 0; i < n * 4; i++) {
    ds_batch_verts[i].color.r = cr; ds_batch_verts[i].color.g = cg;
    ds_batch_verts[i].color.b = cb; ds_batch_verts[i].color.a = ca;
  }
  return ds_batch_send(r, t, n);
}

/* Quad q: source sx sy sw sh of a tex_w x tex_h texture over the
   destination dx dy dw dh. A flip swaps the corners' places, not their
   texture coordinates, as SDL's own flipped copy does: the quad's
   diagonal then runs as SDL's, and a stretched copy samples the same
   texels. */
static inline void ds_batch_quad_to(int q, int tex_w, int tex_h, int sx, int sy, int sw, int sh,
                             int dx, int dy, int dw, int dh, int h, int v) {
  SDL_Vertex *p = &ds_batch_verts[q * 4];
  float x0 = (float)dx, y0 = (float)dy, x1 = (float)(dx + dw), y1 = (float)(dy + dh);
  float u0 = (float)sx / tex_w, u1 = (float)(sx + sw) / tex_w;
  float v0 = (float)sy / tex_h, v1 = (float)(sy + sh) / tex_h;
  float t;
  if (h) { t = x0; x0 = x1; x1 = t; }
  if (v) { t = y0; y0 = y1; y1 = t; }
  p[0].position.x = x0; p[0].position.y = y0; p[0].tex_coord.x = u0; p[0].tex_coord.y = v0;
  p[1].position.x = x1; p[1].position.y = y0; p[1].tex_coord.x = u1; p[1].tex_coord.y = v0;
  p[2].position.x = x0; p[2].position.y = y1; p[2].tex_coord.x = u0; p[2].tex_coord.y = v1;
  p[3].position.x = x1; p[3].position.y = y1; p[3].tex_coord.x = u1; p[3].tex_coord.y = v1;
}

static void ds_batch_quad(int q, int tex_w, int tex_h, int sx, int sy, int sw, int sh,
                          int dx, int dy, int h, int v) {
  ds_batch_quad_to(q, tex_w, tex_h, sx, sy, sw, sh, dx, dy, sw, sh, h, v);
}

/* One unturned cell as mapdraw.scm's cell walk copies it. */
static int ds_tile_copy(SDL_Renderer *r, SDL_Texture *t, int sx, int sy, int sw, int sh,
                        int dx, int dy, int h, int v) {
  SDL_Rect src = { sx, sy, sw, sh }, dst = { dx, dy, sw, sh };
  if (h || v)
    return SDL_RenderCopyEx(r, t, &src, &dst, 0.0, NULL,
                            (SDL_RendererFlip)((h ? SDL_FLIP_HORIZONTAL : 0) | (v ? SDL_FLIP_VERTICAL : 0)));
  return SDL_RenderCopy(r, t, &src, &dst);
}

/* order: 0 right-down, 1 left-down, 2 right-up, 3 left-up. Answers 0, or
   SDL's negative status of a failed call. */
static int ds_tile_cells(SDL_Renderer *r, int ntex, const Uint32 *data, int data_len,
                         int width, int height, int col0, int row0,
                         int c0, int c1, int r0, int r1, int order,
                         const int *table, int table_len, int tw, int th,
                         int fx, int fy, int vw, int vh, int pass, int batch,
                         unsigned char *used) {
  int left_first = order == 1 || order == 3, up = order == 2 || order == 3;
  int row, col, status = 0, pending = 0, tex_w = 1, tex_h = 1;
  SDL_Texture *run = NULL;
  if (ntex < 0 || ntex > DS_MAX_TILE_TEXTURES || width <= 0 || height <= 0
      || (long long)width * height > data_len) return 0;
  if (c0 < col0) c0 = col0;
  if (c1 > col0 + width - 1) c1 = col0 + width - 1;
  if (r0 < row0) r0 = row0;
  if (r1 > row0 + height - 1) r1 = row0 + height - 1;
  for (row = up ? r1 : r0; up ? row >= r0 : row <= r1; row += up ? -1 : 1) {
    for (col = left_first ? c1 : c0; left_first ? col >= c0 : col <= c1; col += left_first ? -1 : 1) {
      Uint32 cell = data[(long long)(row - row0) * width + (col - col0)];
      Uint32 gid = cell & 0x0FFFFFFFu;
      const int *e;
      int ti, sx, sy, sw, sh, d, h, v, w, hh;
      long long left, bottom;
      if (gid == 0 || (long long)gid * DS_TILE_FIELDS + DS_TILE_FIELDS > table_len) continue;
      e = &table[gid * DS_TILE_FIELDS];
      ti = e[0] - 1;
      if (ti < 0 || ti >= ntex || !ds_tile_textures[ti]) continue;
      sx = e[1]; sy = e[2]; sw = e[3]; sh = e[4];
      if (sw <= 0 || sh <= 0) continue;
      h = (cell & 0x80000000u) != 0; v = (cell & 0x40000000u) != 0; d = (cell & 0x20000000u) != 0;
      left = (long long)col * tw + e[5] + fx;
      bottom = (long long)(row + 1) * th + e[6] + fy;
      w = d ? sh : sw; hh = d ? sw : sh;
      if (!(left < vw && left + w > 0 && bottom - hh < vh && bottom > 0)) continue;
      if (pass == 0) { used[ti] = 1; continue; }
      if (d) {
        SDL_Rect src = { sx, sy, sw, sh }, dst;
        int flip = (v ? SDL_FLIP_HORIZONTAL : 0) | (h ? 0 : SDL_FLIP_VERTICAL);
        if (batch && pending) { status = ds_batch_flush(r, run, pending); pending = 0; if (status < 0) return status; }
        dst.x = (int)(left + ds_floor_half(sh - sw));
        dst.y = (int)(bottom + ds_floor_half(-(long long)(sw + sh)));
        dst.w = sw; dst.h = sh;
        status = SDL_RenderCopyEx(r, ds_tile_textures[ti], &src, &dst, 90.0, NULL, (SDL_RendererFlip)flip);
      } else if (batch) {
        if (run != ds_tile_textures[ti]) {
          status = ds_batch_flush(r, run, pending); pending = 0;
          if (status < 0) return status;
          run = ds_tile_textures[ti];
          if (SDL_QueryTexture(run, NULL, NULL, &tex_w, &tex_h) < 0 || tex_w <= 0 || tex_h <= 0) return -1;
        }
        if (sx >= 0 && sy >= 0 && sx + sw <= tex_w && sy + sh <= tex_h) {
          if (pending == DS_BATCH_QUADS) {
            status = ds_batch_flush(r, run, pending); pending = 0;
            if (status < 0) return status;
          }
          ds_batch_quad(pending++, tex_w, tex_h, sx, sy, sw, sh, (int)left, (int)(bottom - sh), h, v);
        } else {
          /* a source beyond the texture: SDL's copy cuts it (and the
             destination with it), which texture coordinates would not */
          status = ds_batch_flush(r, run, pending); pending = 0;
          if (status < 0) return status;
          status = ds_tile_copy(r, ds_tile_textures[ti], sx, sy, sw, sh, (int)left, (int)(bottom - sh), h, v);
        }
      } else {
        status = ds_tile_copy(r, ds_tile_textures[ti], sx, sy, sw, sh, (int)left, (int)(bottom - sh), h, v);
      }
      if (status < 0) return status;
    }
  }
  if (batch && pending) status = ds_batch_flush(r, run, pending);
  return status < 0 ? status : 0;
}
