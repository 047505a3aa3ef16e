/* seamquad: a picture of a quad mesh as SVG (sq_quad_svg.c). */
#ifndef SQ_QUAD_SVG_H
#define SQ_QUAD_SVG_H

#include <stdint.h>

#include "sq_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Writes an orthographic, shaded view of the quad mesh (pos: 3 nv, quad:
 * 4 nq vertex indices, counterclockwise seen from outside) to path,
 * atomically: quads facing the viewer, far ones first; irregular vertices
 * marked (red: valence below 4, blue: above). title (may be NULL) is
 * written above the picture. */
sq_status sq_quad_svg_write(const char *path, uint32_t nv, const double *pos, uint32_t nq,
                            const uint32_t *quad, const char *title, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
