/* The C boundary between `quadra report textures` and a texture-system peer
 * module that it loads with dlopen only when that report runs
 * (quadra_oiio_peer.so, tools/peer/oiio_peer.cpp). Plain C types only: no
 * C++ class, container or exception of either side crosses it, so the
 * module's library (OpenImageIO and its ~250 shared libraries) stays out of
 * the quadra binary and out of every other command's start-up, and the two
 * sides need not agree on anything but this header. */
#pragma once

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Bumped whenever the table below changes; quadra refuses a module built
 * against another version instead of calling through a mismatched table. */
#define QUADRA_TEXTURE_PEER_ABI 1

/* The one symbol a module exports: a function returning its table. */
#define QUADRA_TEXTURE_PEER_ENTRY "quadra_texture_peer"

/* One texture prepared by the peer (opaque to quadra). */
typedef struct QuadraPeerTexture QuadraPeerTexture;

/* The filters a lookup can ask for: bilinear within a level, trilinear
 * between levels, or the peer's anisotropic filter (up to maxAniso probes). */
enum { QUADRA_PEER_TRILINEAR = 0, QUADRA_PEER_ANISOTROPIC = 1 };

typedef struct QuadraTexturePeer {
  int abi;             /* QUADRA_TEXTURE_PEER_ABI of the module's build */
  const char* name;    /* the library compared, e.g. "OpenImageIO" */
  const char* version; /* its version, e.g. "2.4.7" */
  /* A texture from width x height linear float RGBA texels (4 floats each,
   * rows top to bottom), repeat-wrapped, for lookups with up to maxAniso
   * probes. scratchFile: where the peer may write its own texture file; it
   * is removed again by destroy. Returns NULL on failure, with a one-line
   * message in error (errorSize bytes, NUL-terminated). */
  QuadraPeerTexture* (*create)(int width, int height, const float* rgba, const char* scratchFile,
                               int maxAniso, char* error, size_t errorSize);
  /* count lookups, one per footprint: (u, v) in normalized texture units and
   * the Jacobian (du/dx, dv/dx, du/dy, dv/dy) per pixel; rgba receives 4
   * linear floats per lookup, in order. mode: QUADRA_PEER_TRILINEAR or
   * QUADRA_PEER_ANISOTROPIC. */
  void (*lookup)(const QuadraPeerTexture* texture, int mode, size_t count, const float* u,
                 const float* v, const float* dudx, const float* dvdx, const float* dudy,
                 const float* dvdy, float* rgba);
  void (*destroy)(QuadraPeerTexture* texture);
} QuadraTexturePeer;

/* The type of QUADRA_TEXTURE_PEER_ENTRY. */
typedef const QuadraTexturePeer* (*QuadraTexturePeerEntry)(void);

#ifdef __cplusplus
}
#endif
