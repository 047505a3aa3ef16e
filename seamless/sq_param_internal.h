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

/* Whether Algorithm 1 builds Q and the surface tree applies (seed 9.2):
 * guidance on, or auto for genus >= 2. */
int sq_param_uses_algorithm1(int guidance, int genus);

/* One attempt of sq_param_build at opt->seed (sq_param.c): cut graph,
 * domain, cuts, maps and their refinement rounds. cancel (may be NULL):
 * when another thread sets it, the attempt stops at its next Steiner
 * budget check or round with SQ_ERR_SOLVER (its result is then unused). */
sq_status sq_param_build_once(const sq_mesh *m, const int32_t *valence, const sq_param_options *opt,
                              const _Atomic int *cancel, sq_param *out, sq_param_stats *stats,
                              sq_error *err);

/* Steiner vertices an attempt may add (sq_param_options.max_steiner, or
 * 9 per input vertex + 100000). */
uint64_t sq_param_steiner_budget(const sq_param_options *opt, uint32_t nv_input);

/* The colour of a cone of valence k in the pictures (sq_param_io.c). */
const char *sq_param_valence_colour(int32_t k);

/* The distortion statistics of P into stats (sym_dirichlet_*,
 * conformal_*; sq_param.c). */
void sq_param_distortion(const sq_param *P, sq_param_stats *stats);

#endif
