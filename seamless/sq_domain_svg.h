/* seamquad: SVG picture of a seamless domain (see sq_domain_svg.c). */
#ifndef SQ_DOMAIN_SVG_H
#define SQ_DOMAIN_SVG_H

#include "sq_domain.h"
#include "sq_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Writes the metapolygon and the padded domain side by side (atomic).
 * qxy: the Tutte layout of D->quads (2 per vertex, boundary starting at
 * corner 0, as sq_disk_layout_tutte gives it), or NULL to compute it. */
sq_status sq_domain_write_svg(const sq_domain *D, const double *qxy, const char *path,
                              sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
