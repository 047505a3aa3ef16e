/* seamquad: untangling a seamless map in the basis of its seamless maps
 * (sq_map_untangle.c; a step of sq_map_from_rotations, not a public
 * header). */
#ifndef SQ_MAP_UNTANGLE_H
#define SQ_MAP_UNTANGLE_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_optimize_internal.h"
#include "sq_uv_basis.h"

typedef struct sq_untangle_result {
    uint32_t flipped_before, flipped_after; /* triangles with det J <= 0     */
    uint32_t iterations, rounds;            /* Newton steps, values of eps   */
    double eps;                             /* the last regularization       */
} sq_untangle_result;

/* Moves the unknowns z (the map c + P z of basis B on mesh m; F: nf
 * surface triangles, area 0 for those left out) until every triangle has
 * a positive Jacobian determinant in doubles, or max_iterations Newton
 * steps are spent. S: the Newton system of m and B from sq_zsys_init,
 * its values overwritten (a caller that solved with it before passes it
 * on, and its symbolic factorization is reused), or NULL to build one. */
sq_status sq_map_untangle(const sq_mesh *m, const sq_uv_basis *B, const sq_sd_face *F, sq_zsys *S, double *z,
                          uint32_t max_iterations, sq_untangle_result *res, sq_error *err);

#endif
