/* seamquad: private parts of the parametrization's output checks and
 * pictures (sq_param_io.c, sq_param_cells.c). */
#ifndef SQ_PARAM_INTERNAL_H
#define SQ_PARAM_INTERNAL_H

#include "sq_mesh.h"
#include "sq_param.h"

/* The halfedge mesh of P's triangles: halfedge c starts at corner c (face
 * c / 3, corner c % 3), so twin and next answer for corners. Topology
 * only: closed, manifold, oriented, connected (SQ_ERR_INTERNAL naming `who`
 * otherwise). */
sq_status sq_param_mesh(const sq_param *P, const char *who, sq_mesh *m, sq_error *err);

#endif
