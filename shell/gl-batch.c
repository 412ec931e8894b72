/* A run of quads of one texture drawn by OpenGL itself (tiles.c's
   ds_batch_send, included by it), on SDL's "opengl" renderer: SDL 2.26
   sends a quad of SDL_RenderGeometry as six vertices, each copied into
   its command queue; here a quad is its four vertices, read where the
   batch already holds them, and six 16-bit indices.

   The first quad of the run still goes through SDL_RenderGeometry, and
   the queue is flushed: SDL has then set everything the run is drawn
   with (its shader for the texture, the blend mode, the texture bound,
   the viewport and its projection, the clip rectangle). The rest is
   drawn with that state and the same numbers SDL would send (positions
   and texture coordinates unchanged, which is what SDL does at a render
   scale of 1 and a texture it did not pad), then the client arrays are
   put back as they were and the texture unbound through SDL, so SDL's
   record of its state stays true. Anything else (a scale, a padded
   texture, a buffer object bound, another renderer, the browser's
   OpenGL ES build) leaves the run to SDL. shell/tests/gl-batch-test.scm
   compares the two ways pixel for pixel (docs/performance.org, "Sprites
   drawn with four vertices"). */

static int ds_gl_allowed = 1;        /* sdl2.scm's render-gl-batching? */
static double ds_gl_quads = 0;       /* quads drawn here since the start */

static void ds_gl_allow(int on) { ds_gl_allowed = on; }

#if defined(__EMSCRIPTEN__)

static int ds_gl_send(SDL_Renderer *r, SDL_Texture *t, SDL_Vertex *v, const int *indices, int n) {
  (void)r; (void)t; (void)v; (void)indices; (void)n;
  return 0;
}

#else

#include <SDL_opengl.h>

typedef void (APIENTRY *ds_gl_state_fn)(GLenum);
typedef GLboolean (APIENTRY *ds_gl_is_enabled_fn)(GLenum);
typedef void (APIENTRY *ds_gl_pointer_fn)(GLint, GLenum, GLsizei, const void *);
typedef void (APIENTRY *ds_gl_draw_range_elements_fn)(GLenum, GLuint, GLuint, GLsizei, GLenum, const void *);
typedef void (APIENTRY *ds_gl_get_integerv_fn)(GLenum, GLint *);

static struct {
  int loaded;                        /* 0 not tried, 1 every function found, -1 not */
  ds_gl_state_fn enable_client, disable_client;
  ds_gl_is_enabled_fn is_enabled;
  ds_gl_pointer_fn vertex_pointer, color_pointer, tex_coord_pointer;
  ds_gl_draw_range_elements_fn draw_range_elements;
  ds_gl_get_integerv_fn get_integerv;
} ds_gl;

static Uint16 ds_gl_indices[DS_BATCH_QUADS * 6];

/* The functions, from the OpenGL library SDL's renderer loaded. */
static int ds_gl_load(void) {
  int i;
  if (ds_gl.loaded) return ds_gl.loaded > 0;
  ds_gl.enable_client = (ds_gl_state_fn)SDL_GL_GetProcAddress("glEnableClientState");
  ds_gl.disable_client = (ds_gl_state_fn)SDL_GL_GetProcAddress("glDisableClientState");
  ds_gl.is_enabled = (ds_gl_is_enabled_fn)SDL_GL_GetProcAddress("glIsEnabled");
  ds_gl.vertex_pointer = (ds_gl_pointer_fn)SDL_GL_GetProcAddress("glVertexPointer");
  ds_gl.color_pointer = (ds_gl_pointer_fn)SDL_GL_GetProcAddress("glColorPointer");
  ds_gl.tex_coord_pointer = (ds_gl_pointer_fn)SDL_GL_GetProcAddress("glTexCoordPointer");
  ds_gl.draw_range_elements = (ds_gl_draw_range_elements_fn)SDL_GL_GetProcAddress("glDrawRangeElements");
  ds_gl.get_integerv = (ds_gl_get_integerv_fn)SDL_GL_GetProcAddress("glGetIntegerv");
  ds_gl.loaded = (ds_gl.enable_client && ds_gl.disable_client && ds_gl.is_enabled && ds_gl.vertex_pointer
                  && ds_gl.color_pointer && ds_gl.tex_coord_pointer && ds_gl.draw_range_elements
                  && ds_gl.get_integerv) ? 1 : -1;
  /* the corners of quad q are vertices 4q .. 4q + 3, split as SDL's copy
     (tiles.c's ds_batch_indices) */
  for (i = 0; i < DS_BATCH_QUADS; i++) {
    ds_gl_indices[i * 6 + 0] = (Uint16)(i * 4 + 0);
    ds_gl_indices[i * 6 + 1] = (Uint16)(i * 4 + 1);
    ds_gl_indices[i * 6 + 2] = (Uint16)(i * 4 + 2);
    ds_gl_indices[i * 6 + 3] = (Uint16)(i * 4 + 1);
    ds_gl_indices[i * 6 + 4] = (Uint16)(i * 4 + 2);
    ds_gl_indices[i * 6 + 5] = (Uint16)(i * 4 + 3);
  }
  return ds_gl.loaded > 0;
}

static int ds_gl_renderer(SDL_Renderer *r) {
  SDL_RendererInfo info;
  float sx = 0, sy = 0;
  if (SDL_GetRendererInfo(r, &info) < 0 || !info.name || SDL_strcmp(info.name, "opengl") != 0) return 0;
  SDL_RenderGetScale(r, &sx, &sy);
  return sx == 1.0f && sy == 1.0f;
}

/* Quads 1 .. n - 1 of the n at v (quad 0 sent by the caller through SDL,
   whose queue is then flushed here): 1 drawn, 0 left to SDL, or SDL's
   negative status. */
static int ds_gl_draw_rest(SDL_Renderer *r, SDL_Texture *t, SDL_Vertex *v, int n) {
  float tw = 0, th = 0;
  GLint array_buffer = 1, element_buffer = 1;
  GLboolean had_vertex, had_color, had_tex;
  (void)r;
  if (SDL_GL_BindTexture(t, &tw, &th) < 0) return 0;
  ds_gl.get_integerv(GL_ARRAY_BUFFER_BINDING, &array_buffer);
  ds_gl.get_integerv(GL_ELEMENT_ARRAY_BUFFER_BINDING, &element_buffer);
  if (tw != 1.0f || th != 1.0f || array_buffer != 0 || element_buffer != 0) {
    SDL_GL_UnbindTexture(t);
    return 0;
  }
  had_vertex = ds_gl.is_enabled(GL_VERTEX_ARRAY);
  had_color = ds_gl.is_enabled(GL_COLOR_ARRAY);
  had_tex = ds_gl.is_enabled(GL_TEXTURE_COORD_ARRAY);
  if (!had_vertex) ds_gl.enable_client(GL_VERTEX_ARRAY);
  if (!had_color) ds_gl.enable_client(GL_COLOR_ARRAY);
  if (!had_tex) ds_gl.enable_client(GL_TEXTURE_COORD_ARRAY);
  ds_gl.vertex_pointer(2, GL_FLOAT, sizeof(SDL_Vertex), &v[0].position);
  ds_gl.color_pointer(4, GL_UNSIGNED_BYTE, sizeof(SDL_Vertex), &v[0].color);
  ds_gl.tex_coord_pointer(2, GL_FLOAT, sizeof(SDL_Vertex), &v[0].tex_coord);
  /* the range of the vertices used (those of quads 1 .. n - 1), so the
     driver need not scan the indices for it */
  ds_gl.draw_range_elements(GL_TRIANGLES, 4, (GLuint)(n * 4 - 1), (n - 1) * 6, GL_UNSIGNED_SHORT,
                            ds_gl_indices + 6);
  if (!had_vertex) ds_gl.disable_client(GL_VERTEX_ARRAY);
  if (!had_color) ds_gl.disable_client(GL_COLOR_ARRAY);
  if (!had_tex) ds_gl.disable_client(GL_TEXTURE_COORD_ARRAY);
  SDL_GL_UnbindTexture(t);
  ds_gl_quads += n - 1;
  return 1;
}

/* The n quads at v (n <= DS_BATCH_QUADS; indices: SDL's, as
   ds_batch_send passes them): 1 when every quad was drawn, SDL's
   negative status, or 0 when none was and SDL is to draw them all. */
static int ds_gl_send(SDL_Renderer *r, SDL_Texture *t, SDL_Vertex *v, const int *indices, int n) {
  int st;
  if (!ds_gl_allowed || n < 2 || n > DS_BATCH_QUADS || !ds_gl_renderer(r) || !ds_gl_load()) return 0;
  st = SDL_RenderGeometry(r, t, v, 4, indices, 6);
  if (st < 0) return st;
  if (SDL_RenderFlush(r) < 0 || (st = ds_gl_draw_rest(r, t, v, n)) == 0)
    /* SDL draws the rest after all: indices 0 .. are quad 1's from v + 4 */
    st = SDL_RenderGeometry(r, t, v + 4, (n - 1) * 4, indices, (n - 1) * 6);
  return st < 0 ? st : 1;
}

#endif
