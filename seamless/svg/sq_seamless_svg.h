/* seamquad: the pictures of the seamless stage, every one an SVG file
 * written atomically (no partial file on error): the domain (seed Fig. 3,
 * 8), Omega (Fig. 1, 11), a parametrization's UV layout, its cut on the
 * surface, and the diagnosis of a map that failed its orientation check. */
#ifndef SQ_SEAMLESS_SVG_H
#define SQ_SEAMLESS_SVG_H

#include "sq_error.h"
#include "sq_mesh.h"
#include "sq_param.h"

#ifdef __cplusplus
extern "C" {
#endif

struct sq_domain;
struct sq_cone_tree;
struct sq_omega;

/* The metapolygon and the padded domain side by side
 * (sq_domain_svg.c). qxy: the Tutte layout of D->quads (2 per vertex,
 * boundary starting at corner 0, as sq_disk_layout_tutte gives it), or
 * NULL to compute it. */
sq_status sq_domain_write_svg(const struct sq_domain *D, const double *qxy, const char *path,
                              sq_error *err);

/* Omega (sq_omega_svg.c): quads light, the boundary polygon with Q's
 * sides in one colour per identified pair and both sides of the tree
 * highlighted, cone copies (by valence), branch points (copies of Q's
 * corners) and the root's copies marked. */
sq_status sq_omega_write_svg(const struct sq_domain *D, const struct sq_cone_tree *T,
                             const struct sq_omega *O, const char *path, sq_error *err);

/* The UV layout of P (sq_param_svg.c): triangles (thin), seams in one
 * colour per seam curve, cone points by valence. */
sq_status sq_param_write_svg(const char *path, const sq_param *P, sq_error *err);

/* The cut on the surface (sq_param_cut_svg.c): the input mesh m in three
 * orthographic views (front, side, from (1, 1, 1)), shaded and drawn back
 * to front, with P's seams (the cut graph and the cone tree: he_cut 1)
 * where they are visible, cones by valence and the seams' branch points. */
sq_status sq_param_write_cut_svg(const char *path, const sq_mesh *m, const sq_param *P, sq_error *err);

/* The given cells (from sq_param_bad_cells; sq_param_cells_svg.c), each
 * twice: on the surface (projected on its best-fitting plane) and in UV;
 * bad triangles red, cut edges black, chords blue. */
sq_status sq_param_write_cells_svg(const char *path, const sq_param *P, const sq_param_cell *cells,
                                   uint32_t ncells, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
