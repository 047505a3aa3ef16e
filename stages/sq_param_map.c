/* seamquad: param's result as an exact sq_map (sq_param_optimize.h; stage
 * 3 of remesh).
 *
 * The soup is param's own arrays (sq_param_soup: positions, triangles, UV
 * corners), read without copying; sq_map_from_soup with SQ_MAP_REQUIRE_EXACT checks that
 * every seam is exact as param promises (nothing is snapped), that the
 * first vertices are the input's and that the angle sums are the cones. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_param_optimize.h"

sq_status sq_param_map(const sq_param *P, const sq_mesh *m, const int32_t *valence, sq_map *out,
                       sq_error *err)
{
    memset(out, 0, sizeof *out);
    if (!P || !m || !P->nf) return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_param_map: no map");
    sq_soup s;
    sq_status st = sq_param_soup(P, &s, err);
    if (st) return st;
    st = sq_map_from_soup(&s, m, valence, 0, SQ_MAP_REQUIRE_EXACT, out, NULL, err);
    free(s.face_off);
    return st;
}
