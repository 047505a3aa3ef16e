/* seamquad: the quad disk Q laid out in the unit disk with its corners at
 * the angles of the corresponding surface corners (seed 9.2: the domain's
 * layout is compared with the surface's); uniform Tutte weights
 * (sq_disk_layout_tutte_fixed). */
#include <math.h>

#include "sq_disk_layout.h"
#include "sq_guide.h"

sq_status sq_guide_domain_disk(const sq_domain *D, const double *corner_angle, double *q_xy,
                               sq_error *err)
{
    const sq_metapolygon *Q = &D->quads;
    const uint32_t k = D->k;
    /* boundary: side i from corner i, clockwise, evenly spaced */
    for (uint32_t i = 0; i < k; i++) {
        double a0 = corner_angle[i], a1 = corner_angle[(i + 1) % k];
        double span = fmod(a0 - a1 + 4 * SQ_GUIDE_PI, 2 * SQ_GUIDE_PI);
        if (!(span > 0)) span = 2 * SQ_GUIDE_PI;
        uint32_t len = D->side_len[i], h = Q->v_he[D->corner_vert[i]];
        for (uint32_t t = 0; t < len; t++, h = Q->he_next[h]) {
            if (Q->he_face[h] != SQ_NONE)
                return sq_error_set(err, SQ_ERR_INTERNAL, "guidance: side %u of Q leaves the boundary", i);
            uint32_t v = Q->he_vert[h];
            double a = a0 - span * (double)t / (double)len;
            q_xy[2 * v] = cos(a), q_xy[2 * v + 1] = sin(a);
        }
        if (Q->he_vert[h] != D->corner_vert[(i + 1) % k])
            return sq_error_set(err, SQ_ERR_INTERNAL, "guidance: side %u of Q does not end at a corner", i);
    }
    return sq_disk_layout_tutte_fixed(Q, q_xy, err);
}
