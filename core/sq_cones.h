/* seamquad: prescribed cones.
 *
 * A cone of angle k*pi/2 at a vertex becomes an irregular quad vertex of
 * valence k; k = 4 is a regular vertex. Two file formats (docs/cones.md):
 *   - Th_hat: one angle in radians per vertex, one per line, vertex order;
 *   - cone list: `VERTEX VALENCE` per line, 0-based vertex index, only the
 *     cones (vertices not listed have valence 4); `#` starts a comment.
 * Rule that tells them apart: a file whose data lines all hold exactly one
 * number is a Th_hat file; one whose data lines all hold exactly two integers
 * is a cone list; anything else is an error naming the first line that fits
 * neither. */
#ifndef SQ_CONES_H
#define SQ_CONES_H

#include <stddef.h>
#include <stdint.h>

#include "sq_error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sq_cone_format {
    SQ_CONES_TH_HAT = 1,
    SQ_CONES_LIST = 2
} sq_cone_format;

/* Parses a cone file for a mesh with nv vertices into valence[nv]
 * (caller-owned). Th_hat angles are rounded to the nearest k*pi/2; a value
 * off by more than 1e-6 is an error naming the line. */
sq_status sq_cones_parse(const char *data, size_t size, const char *name, uint32_t nv,
                         int32_t *valence, sq_cone_format *format, sq_error *err);
sq_status sq_cones_read(const char *path, uint32_t nv, int32_t *valence,
                        sq_cone_format *format, sq_error *err);

/* Histogram: hist[k] = number of vertices of valence k, for k < nhist;
 * returns the number of vertices with valence != 4 (cones). Valences >=
 * nhist are counted in hist[nhist-1]. */
uint32_t sq_cones_histogram(uint32_t nv, const int32_t *valence, uint32_t *hist, uint32_t nhist);

/* Gauss-Bonnet: sum over vertices of (4 - k) must equal 4 * chi. */
sq_status sq_cones_check_gauss_bonnet(uint32_t nv, const int32_t *valence, int64_t euler,
                                      sq_error *err);

/* Everything the construction needs beyond Gauss-Bonnet: no valence below 2
 * (valence 1 is outside the seed's construction, seed Def. 5.4 needs i > 1),
 * and not the torus with exactly one valence-3 and one valence-5 cone (no
 * quad mesh exists, Jucovic-Trenkler 1973). Also checks Gauss-Bonnet. */
sq_status sq_cones_check_realizable(uint32_t nv, const int32_t *valence, int64_t genus,
                                    sq_error *err);

/* Same checks on a bare multiset of valences (no vertices), for the domain
 * construction. */
sq_status sq_valences_check_realizable(uint32_t n, const int32_t *valences, int64_t genus,
                                       sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
