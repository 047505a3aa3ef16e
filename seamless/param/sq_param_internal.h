/* seamquad: private parts of the parametrization shared by its steps, its
 * check (sq_param_io.c) and its pictures (svg/). */
#ifndef SQ_PARAM_INTERNAL_H
#define SQ_PARAM_INTERNAL_H

#include "sq_mesh.h"
#include "sq_omega.h"
#include "sq_omega_cells.h"
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
                              const _Atomic int *cancel, sq_param *out, sq_param_stats *stats, sq_error *err);

/* Steiner vertices an attempt may add (sq_param_options.max_steiner, or
 * 9 per input vertex + 100000). */
uint64_t sq_param_steiner_budget(const sq_param_options *opt, uint32_t nv_input);
/* The overlay's crossing budget of SQ_TREE_QTRI (and so of the fallback)
 * when max_crossings is 0: SQ_FALLBACK_PER_FACE per input face, at most
 * SQ_QTRI_MAX_CROSSINGS, at least the Steiner budget. */
uint64_t sq_param_crossing_budget(const sq_param_options *opt, uint32_t nv, uint32_t nf);

/* The memory an attempt may plan for (sq_param_options.max_memory, or
 * SQ_PARAM_MAX_MEMORY where 0). */
static inline uint64_t sq_param_max_memory(const sq_param_options *opt)
{
    return opt->max_memory ? opt->max_memory : SQ_PARAM_MAX_MEMORY;
}

/* Arguments and index ranges of P (sq_param_seam_curves.c); a message
 * naming `who` and the first bad element. */
sq_status sq_param_check_arrays(const sq_param *P, const char *who, sq_error *err);

static inline uint32_t sq_param_he_dst(const sq_mesh *m, uint32_t h) { return m->he_vert[m->he_next[h]]; }

/* Whether halfedge h of sq_param_mesh(P) is on a seam: its two faces give
 * its ends different UV points. */
static inline int sq_param_is_seam(const sq_mesh *m, const sq_param *P, uint32_t h)
{
    uint32_t t = m->he_twin[h];
    return P->tri_uv[h] != P->tri_uv[m->he_next[t]] || P->tri_uv[m->he_next[h]] != P->tri_uv[t];
}

static inline int sq_param_is_cone(const sq_param *P, uint32_t v)
{
    return P->valence && v < P->nv_input && P->valence[v] != 4;
}

/* The seam curves of P on m = sq_param_mesh(P) (sq_param_seam_curves.c):
 * maximal chains of seam edges through vertices with exactly two seam
 * edges that are not cones, or closed loops of such vertices. curve[h]:
 * the curve of both halfedges of every seam edge, SQ_NONE elsewhere;
 * dir[h] = 1 for the halfedge along its curve's walking direction;
 * first[i]: the first halfedge of curve i; sdeg[v]: seam edges at v. */
typedef struct sq_param_seam_curves {
    uint32_t n;
    uint32_t *curve; /* nh */
    uint8_t *dir;    /* nh */
    uint32_t *first; /* n  */
    uint32_t *sdeg;  /* nv */
} sq_param_seam_curves;

sq_status sq_param_seam_curves_find(const sq_mesh *m, const sq_param *P, sq_param_seam_curves *C, sq_error *err);
void sq_param_seam_curves_free(sq_param_seam_curves *C);
/* Whether a curve ends at v (not two seam edges, or a cone). */
int sq_param_seam_node(const sq_param_seam_curves *C, const sq_param *P, uint32_t v);
/* The other seam halfedge out of the vertex where halfedge `in` ends (it
 * has two seam edges and is not a cone), or SQ_NONE. */
uint32_t sq_param_seam_next_out(const sq_mesh *m, const sq_param_seam_curves *C, uint32_t in);

/* Whether face f's UV triangle is not positive (exact predicate). */
int sq_param_face_bad(const sq_param *P, uint32_t f);
/* Labels every face with its cell of Omega (faces joined across edges
 * with he_cut 0; m = sq_param_mesh(P)); the number of cells, or SQ_NONE
 * when out of memory (sq_param_cells.c). */
uint32_t sq_param_label_cells(const sq_param *P, const sq_mesh *m, uint32_t *cell);

/* The colour of a cone of valence k in the pictures (svg/sq_param_svg.c). */
const char *sq_param_valence_colour(int32_t k);

/* The distortion statistics of P into stats (sym_dirichlet_*,
 * conformal_*; sq_param_assemble.c). */
void sq_param_distortion(const sq_param *P, sq_param_stats *stats);

/* The next and the previous corner of corner c in its triangle (corners
 * 3 f, 3 f + 1, 3 f + 2; the edge from corner c runs to the next one). */
static inline uint32_t sq_param_corner_next(uint32_t c) { return c % 3 == 2 ? c - 2 : c + 1; }
static inline uint32_t sq_param_corner_prev(uint32_t c) { return c % 3 == 0 ? c + 2 : c - 1; }

/* ---- step 7' (the overlay; sq_param_overlay.c) -------------------------- */

/* Twins of a triangle list by vertex pairs (sorting): twin[3 f + i] is the
 * halfedge running the other way, SQ_NONE when it has none. 0; -1: out of
 * memory; -2: an edge with more than two halfedges or two in one direction
 * (sq_param_disk_tutte.c). */
int sq_param_pair_twins(uint32_t nf, const uint32_t *tri, uint32_t *twin);
/* The same, the pairing in two threads when threads > 1 (same result). */
int sq_param_pair_twins_threads(uint32_t nf, const uint32_t *tri, uint32_t *twin, uint32_t threads);

/* Tutte's map of one triangulated disk (nf triangles tri, twins twin) onto
 * the plane: its interior vertices [first, first + n) at the
 * mean-value-weighted mean of their neighbours (one UMFPACK solve), every
 * other vertex fixed at its xy. p3: a 3D position per vertex id, for the
 * weights (sq_param_disk_tutte.c). */
sq_status sq_param_disk_tutte(uint32_t nf, const uint32_t *tri, const uint32_t *twin, uint32_t first,
                              uint32_t n, const double *p3, double *xy, sq_error *err);

/* The overlay's surface disk (step 7'): every fan of at least min_run
 * triangles with one interior apex, one input face (fin) and a straight
 * base of boundary edges (twin SQ_NONE, both ends < nbl) replaced by a
 * graded triangulation of the same polygon (sq_param_fans.c). tri, fin
 * (nf), p3 (3 per vertex, nv) grow in place (the kept faces in their
 * order, then the new ones; the new vertices from nv on, inside their
 * polygons); twins are the caller's to redo. added: the new vertices. */
#define SQ_FAN_MIN_RUN 3u
sq_status sq_param_grade_fans(uint32_t nbl, uint32_t min_run, const uint32_t *twin, uint32_t *nf, uint32_t **tri,
                              uint32_t **fin, uint32_t *nv, double **p3, uint32_t *added, sq_error *err);

/* Edge splits between blocked vertices (sq_param_walls.c): m with a
 * midpoint on every edge that joins two blocked vertices and is not cut,
 * its faces split to match (two, three or four per face). Blocked: cones
 * (valence[v] != 4) and, where he_cut is given, the vertices of the cut
 * (tree qtri where the cut walls a cone in); with he_cut NULL, cones only
 * (seed 9.1: the cut graph's loops pass between adjacent cones). m2's
 * first m->nv vertices are m's; *val2 (m2->nv): the valences, 4 at the
 * midpoints; *fparent (m2->nf): m's face holding each face; *cut2
 * (m2->nh; only with he_cut and cut2): the same cut. *nsplit: the edges
 * split (0: none, and nothing allocated). The caller frees m2 and the
 * arrays. */
sq_status sq_param_split_walls(const sq_mesh *m, const int32_t *valence, const uint8_t *he_cut, sq_mesh *m2,
                               int32_t **val2, uint32_t **fparent, uint8_t **cut2, uint32_t *nsplit,
                               sq_error *err);

/* A growing list of triangles (3 n ids in t). */
typedef struct sq_param_tri_list {
    uint32_t *t;
    uint32_t n, cap;
} sq_param_tri_list;

/* Omega (O) triangulated for the overlay (sq_param_omega_tri.c): each cell
 * (C's chords' rectangles; C NULL: the unit squares of O->cut) fanned from
 * its centre, its sides split at every vertex of Omega on them and, on
 * Omega's boundary, at the surface's boundary points, with graded layers
 * where a side carries three points or more. Vertex ids: [0, nbl) the
 * surface's boundary loop (uv buv0), [nbl, na) reserved for the surface's
 * inner vertices, then Omega's inner vertices, the cells' centres, split
 * midpoints and the layers' points. wb (O->cut.nv): the id of each of
 * Omega's boundary vertices (SQ_NONE elsewhere); oseq: Omega's boundary
 * halfedges in order; bstart[i]: the id where boundary halfedge i starts.
 * Out: *nv_out ids, *uv_out their uv (2 per id; caller frees), triangles
 * appended to bt. */
sq_status sq_param_omega_triangulation(const sq_omega *O, const sq_omega_cells *C, uint32_t nbl, uint32_t na,
                                       const uint32_t *wb, const uint32_t *oseq, const uint32_t *bstart,
                                       const double *buv0, uint32_t *nv_out, double **uv_out,
                                       sq_param_tri_list *bt, sq_error *err);

#endif
