/* seamquad: the seamless maps near a given one, as an affine function of
 * free unknowns (the reduced basis the optimizer works in).
 *
 * Every corner coordinate of a map (he_uv[k], k = 2h + axis: the u or v of
 * halfedge h's origin corner in its face's chart) is written as
 *
 *     he_uv[k] = c[k] + sum over j in row_off[k] .. row_off[k+1]-1 of
 *                val[j] * z[col[j]]
 *
 * so that every z gives a map whose transitions have the input map's
 * rotations: seamless by construction, with no constraint left to enforce.
 * z0 reproduces the input map (up to the rounding of the sums; callers
 * snap and check the result exactly, sq_map_from_soup).
 *
 * Two bases:
 *  - sq_uv_basis_fixed_transitions: rotations and translations both kept
 *    (an integer-grid map stays one): one unknown point per vertex that is
 *    not a cone, in the chart of its first corner; its other corners follow
 *    by the transitions around it; cones stay where they are.
 *  - sq_uv_basis_free_translations: rotations kept, translations free (the
 *    optimizer's setting before quantization, issue 24); the gauge (a global
 *    translation) is fixed by pinning one vertex.
 *
 * Cost: O(halfedges) entries for the first; the second adds a dense
 * elimination over the seam graph's nodes. */
#ifndef SQ_UV_BASIS_H
#define SQ_UV_BASIS_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_map.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sq_uv_basis {
    uint32_t nz;        /* free real unknowns                                 */
    uint32_t ncoord;    /* 2 nh: one row per corner coordinate                */
    uint32_t *row_off;  /* ncoord + 1                                         */
    uint32_t *col;      /* row_off[ncoord]: unknown index                     */
    double *val;        /* row_off[ncoord]: coefficient                       */
    double *c;          /* ncoord: constant part                              */
    double *z0;         /* nz: the unknowns of the input map                  */
} sq_uv_basis;

/* Rotations and translations of M kept; cones fixed. M must pass
 * sq_map_check. */
sq_status sq_uv_basis_fixed_transitions(const sq_map *M, sq_uv_basis *out, sq_error *err);

/* Rotations of M kept; translations free; one vertex pinned. M must pass
 * sq_map_check. */
sq_status sq_uv_basis_free_translations(const sq_map *M, sq_uv_basis *out, sq_error *err);

/* The same space for a map that need not be valid yet (not checked): the
 * seams are seam[h] (nh; set on both halfedges of every seam edge), the
 * rotations he_rot (constant along every chain of seam edges between
 * nodes); he_uv and he_t give only z0 and the pinned values (zeros are
 * fine). For a map built from rotations alone (sq_map_untangle.h). */
sq_status sq_uv_basis_free_translations_seams(const sq_map *M, const uint8_t *seam, sq_uv_basis *out,
                                              sq_error *err);

/* he_uv = c + P z (2 nh doubles, caller-allocated). */
void sq_uv_basis_eval(const sq_uv_basis *B, const double *z, double *he_uv);

void sq_uv_basis_free(sq_uv_basis *B);

#ifdef __cplusplus
}
#endif
#endif
