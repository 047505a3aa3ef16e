/* seamquad: seamless parametrization of a closed surface (seed 7, 8, 9):
 * the surface cut graph, the combinatorial domain for its side pattern, the
 * flat domain Omega, the compatible cone tree on the surface, the boundary
 * map by normalized arc length, and a bijective interior map.
 *
 * Pipeline (sq_param_build):
 *  1. cut graph of M (seed 7, 9.1; sq_cut_graph.h): a disk M^c whose side
 *     pattern is handed to the domain construction;
 *  2. domain Q for that pattern and the cone valences (sq_domain.h); with
 *     guidance (seed 9.2, genus >= 1; sq_guide.h) its cones are ordered and
 *     glued after a disk layout of M^c, and its corners matched to M^c's at
 *     similar angles, so that each cone of Q stands for one surface cone;
 *  3. cone tree in Q and the flat domain Omega (sq_omega.h); guided, the
 *     tree is first chosen on M^c by shortest paths in radial order and
 *     replicated in Q (seed 9.4; sq_guide_surface_tree);
 *  4. the same tree on M^c, path by path in the tree's rotation order (the
 *     surface tree's own paths where they fit), with Steiner vertices by
 *     edge splits where paths would block each other (seed 7, [SAPH04]);
 *  5. boundary map by normalized arc length between corresponding corners
 *     (seed 8), seam UVs snapped to a dyadic grid so that every transition
 *     is exact in floating point (seamless-notes 5);
 *  6. Omega cut into rectangles by chords (sq_omega_cells.h), the chords
 *     replayed as paths on the surface, and every surface cell mapped onto
 *     its rectangle by a Tutte embedding (convex target: bijective);
 *  7. exact checks: every UV triangle positively oriented (exact predicate
 *     on the stored doubles), every seam transition exact.
 *
 * The output mesh keeps the input's vertices first, in order, with their
 * coordinates; added (Steiner) vertices lie on edges or inside faces of the
 * input.
 *
 * The library never prints or exits. */
#ifndef SQ_PARAM_H
#define SQ_PARAM_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_mesh.h"
#include "sq_soup.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sq_param_options {
    uint64_t seed; /* seeds the cut graph's sampling (default 1) */
    /* Optional progress report: stage name and the fraction of the whole
     * run done (0..1). Called a handful of times per stage. */
    void (*progress)(void *ctx, const char *stage, double fraction);
    void *progress_ctx;
    /* Diagnostics only: return the map even when some UV triangles are not
     * positively oriented (sq_param_verify then rejects it). Default 0. */
    int allow_flips;
    /* Geometric guidance (seed 9.2), SQ_GUIDE_*: which surface cone each
     * cone of Q stands for and how Q is built. Default SQ_GUIDE_AUTO. */
    int guidance;
    /* Attempts before giving up (default 1; 0 counts as 1): attempt a uses
     * the cut-graph seed  seed + a. Only failures of the map itself
     * (SQ_ERR_SOLVER: a flipped or degenerate UV triangle, the Steiner
     * budget) are retried; the result is the first map that passes every
     * exact check. */
    uint32_t attempts;
    /* The cone tree (genus >= 1), SQ_TREE_* below. Default SQ_TREE_AUTO. */
    int tree;
    /* Refinement rounds per attempt (step 7c): when some triangles are bad
     * after the interior map, the cells of Omega holding them are halved
     * and the cells and the map redone on the same cut, tree and boundary
     * map, up to this many times.
     * Default SQ_PARAM_REFINE (sq_param_options_default); 0: none. */
    uint32_t refine;
    /* Steiner vertices allowed before an attempt gives up (SQ_ERR_SOLVER);
     * 0: 9 per input vertex + 100000. */
    uint64_t max_steiner;
    /* Crossings of surface and domain edges the overlay (step 7') may make
     * before it gives up (SQ_ERR_SOLVER); 0: the Steiner budget above (with
     * tree qtri: SQ_QTRI_PER_FACE (400) per input face, at most
     * 10,000,000, at least the Steiner budget). The overlay stops at its
     * sample where that expects more than 5/4 of it (sq_overlay.h). */
    uint64_t max_crossings;
    /* Attempts run at once, each in its own thread (default 1; 0 counts
     * as 1). The result is the same as with 1: the lowest attempt that
     * passes (later ones are cancelled, earlier ones awaited); memory grows
     * with the attempts running. With 2 or more, the overlay's walk and the
     * simplification use two threads as well (the same result too). */
    uint32_t threads;
    /* The interior map (steps 6-7), SQ_INTERIOR_*: Omega cut into
     * rectangles by chords replayed on the surface, each cell mapped by
     * Tutte (with refinement rounds); or the overlay of the two disk maps
     * (sq_overlay.h; step 7'); or both (auto, the default): the cells, and
     * when they pass, the overlay on the same cuts, whose map replaces
     * theirs if it passes too (far less distorted; docs/param.md). */
    int interior;
    /* SQ_SIMPLIFY_ON (default): the map that passed is simplified
     * (sq_param_simplify: added vertices off the seams removed where every
     * check still holds); SQ_SIMPLIFY_OFF: the map as built. */
    int simplify;
    /* SQ_FANS_ON (default): in the overlay (step 7'), the fans of thin
     * triangles along the cut (an input edge on the cut split at Omega's
     * boundary points, every piece joined to the opposite vertex) are
     * replaced by graded triangulations of the same polygons before the
     * disk map (sq_param_grade_fans): far fewer crossings (cid/elephant
     * 30%, mpz/elk 29%), the same guarantees. SQ_FANS_OFF: the fans as
     * they are. */
    int fans;
    /* Tree qtri (genus >= 1): Algorithm 1's ties broken
     * another way (sq_guide_glue.variant), up to `variants` domains per
     * attempt while the overlay's sample expects more than variant_gate
     * crossings per input face; where none is under it, the one expecting
     * the fewest (docs/param.md, "Domain variants"). 0: SQ_VARIANTS and
     * SQ_VARIANT_PER_FACE; variants 1: the first domain only. Not with
     * max_crossings given. */
    uint32_t variants;
    uint32_t variant_gate;
    /* Memory an attempt may plan for (bytes; 0: SQ_PARAM_MAX_MEMORY) in
     * the steps whose size the input does not bound: the domain Q may have
     * max_memory / SQ_BYTES_PER_DOMAIN_QUAD quads, Q triangulated by tree
     * qtri's paths max_memory / SQ_BYTES_PER_QTRI_FACE triangles, Omega
     * triangulated for the overlay max_memory / SQ_BYTES_PER_DISK_TRIANGLE
     * (checked before its disk map is factored), the overlay (step 7')
     * max_memory / SQ_BYTES_PER_CROSSING crossings (its sample refuses a
     * walk that would not fit before the walk's arrays grow); beyond, the
     * attempt fails (SQ_ERR_SOLVER) with a message naming the limit, and
     * the next attempt runs. With threads >= 2 two attempts may run at
     * once, each within the limit. */
    uint64_t max_memory;
} sq_param_options;

/* 2 GiB, and the cost per item of the steps it bounds, measured on the
 * largest runs and rounded up: a run whose overlay makes N crossings peaks
 * at about 260 N bytes (cid/elephant: 804 MB at 3.09 million), and each
 * of the walk's two ranges may reach the budget alone, hence 500; tree
 * qtri's Q triangulated into F triangles, about 400 F (vmas/neptune with
 * its field's cones: 7.6 GB at 19.9 million); Omega's disk map of T
 * triangles and a domain of N quads: vmas/neptune passed 5.7 GB at 17.1
 * million triangles from about 4.3 million quads, still factoring, so
 * 450 per triangle and 2,000 per quad (the shared models' domains have at
 * most 72,000 quads; cid/elephant's Omega disk map has 84,672 triangles) */
#define SQ_PARAM_MAX_MEMORY (2ull << 30)
#define SQ_BYTES_PER_CROSSING 500u
#define SQ_BYTES_PER_QTRI_FACE 400u
#define SQ_BYTES_PER_DISK_TRIANGLE 450u
#define SQ_BYTES_PER_DOMAIN_QUAD 2000u

/* SQ_INTERIOR_OVERLAY triangulates Omega in its unit squares, and where
 * that fails in its chords' rectangles (docs/param.md). */
enum { SQ_INTERIOR_AUTO = 0, SQ_INTERIOR_CELLS = 1, SQ_INTERIOR_OVERLAY = 2 };
enum { SQ_SIMPLIFY_ON = 0, SQ_SIMPLIFY_OFF = 1 };
enum { SQ_FANS_ON = 0, SQ_FANS_OFF = 1 };
/* SQ_TREE_AUTO: tree qtri's attempts (at most SQ_QTRI_ATTEMPTS), then the
 * surface tree's (sq_param_attempts.c) */
#define SQ_QTRI_ATTEMPTS 4
#define SQ_QTRI_PER_FACE 400u
#define SQ_QTRI_MAX_CROSSINGS 10000000u
/* tree qtri: domains per attempt (Algorithm 1's ties broken otherwise)
 * while the overlay's sample expects more than SQ_VARIANT_PER_FACE
 * crossings per input face (sq_param_build_once; docs/param.md) */
#define SQ_VARIANTS 4u
#define SQ_VARIANT_PER_FACE 100u

#define SQ_PARAM_REFINE 8

/* Cone tree modes (sq_param_options.tree; genus >= 1):
 *  SQ_TREE_AUTO (default): where the other choices are at their defaults,
 *    tree qtri's attempts (at most SQ_QTRI_ATTEMPTS), then the surface
 *    tree's; the lowest that passes is the result (stats.fallback: the
 *    surface tree's). On the shared models qtri passes on every one of
 *    genus >= 1 (at its first attempt for genus >= 2, within 3 for genus
 *    1), with a mean conformal ratio as low as the surface tree's or far
 *    lower (helmet 29.5 against 419, rocker_arm 735 against 2e8;
 *    bench/bench_param_modes.sh). Otherwise, and for genus 0, as
 *    SQ_TREE_SURFACE.
 *  SQ_TREE_SURFACE: with guidance, the surface tree (seed 9.4) replicated
 *    in Q's quad grid, Q's own shortest tree where it cannot be; the
 *    interior map by cells or overlay (sq_param_options.interior).
 *  SQ_TREE_QTRI: seed 9.4 as the seed does it: the surface tree copied
 *    into Q triangulated, room made by edge splits along the paths only
 *    (sq_qtri.h), Omega laid out from it (triangles, dyadic positions) and
 *    the interior map by overlay (the cells need Q's quads); genus 1 with
 *    guidance (SQ_GUIDE_AUTO means on here). The same plane tree on both
 *    sides always (a tree does not separate a disk); the attempt fails
 *    where the surface tree leaves a cone unjoined. */
enum { SQ_TREE_AUTO = 0, SQ_TREE_SURFACE = 1, SQ_TREE_QTRI = 2 };

/* Guidance modes (sq_param_options.guidance):
 *  SQ_GUIDE_AUTO: SQ_GUIDE_ON for genus >= 2, SQ_GUIDE_OFF below (where
 *    only the cone matching of SQ_GUIDE_ON exists, and it measured worse).
 *  SQ_GUIDE_OFF: Q as seed 5.3 builds it (fewest quads); the cone tree
 *    takes the nearest free surface cone of the right valence.
 *  SQ_GUIDE_ON: the cut surface is laid out in the unit disk (sq_guide.h).
 *    Genus >= 2: the cones are taken by distance from the disk centre and
 *    glued where the growing metapolygon's layout is closest to them (seed
 *    9.2, Algorithm 1), so each cone of Q stands for its own surface cone;
 *    of the cyclic correspondences of Q's corners with the cut graph's, the
 *    one whose corners lie at the most similar angles is used. Genus 1
 *    (two pieces, seed 6.2): the meta-2-gon takes a valence-2 cone or two
 *    valence-3 cones near the circle, the meta-6-gon the others by
 *    Algorithm 1; of its 6 gluings to the meta-2-gon and the cyclic
 *    correspondences, the pair whose corners fit best. Genus 0: Q as for
 *    OFF, laid out in the disk too, each cone of Q matched to the nearest
 *    surface cone of its valence. */
enum { SQ_GUIDE_AUTO = 0, SQ_GUIDE_OFF = 1, SQ_GUIDE_ON = 2 };

void sq_param_options_default(sq_param_options *opt);

typedef struct sq_param_stats {
    uint32_t genus, ncones;
    uint32_t verts_in, faces_in;
    uint32_t verts_out, faces_out, steiner; /* steiner = verts_out - verts_in */
    uint32_t nuv;                           /* distinct UV points            */
    uint32_t cut_edges;                     /* edges of the surface cut graph */
    /* seam rotations (docs/holonomy.md): the cut graph's mismatch with a
     * smooth cross field having these cones, before and after steering
     * (sq_cut_graph_steer; 0: every map on it has the field's rotations
     * around the handles; UINT32_MAX: not computed), and the branches
     * rerouted */
    uint32_t rot_mismatch_before, rot_mismatch_after, rot_reroutes;
    uint64_t quads_unpadded, quads_added;   /* the domain Q                   */
    uint32_t tree_edges, tree_segments;     /* cone tree in Q                 */
    uint32_t chords, cells;                 /* rectangles of Omega            */
    uint32_t seam_edges;                    /* output edges with two UV copies */
    /* distortion of the final map (per triangle, area-weighted mean and
     * max): symmetric Dirichlet energy after the best global scale, and the
     * conformal ratio sigma1/sigma2 */
    double sym_dirichlet_mean, sym_dirichlet_max;
    double conformal_mean, conformal_max;
    uint32_t attempts;                      /* attempts made (1 = first)      */
    uint32_t rounds;                        /* refinement rounds of the last  */
                                            /* attempt (0 = none needed)      */
    uint32_t cells_refined;                 /* cells halved, all rounds       */
    uint64_t seed_used;                     /* cut-graph seed of the result   */
    int guided;                             /* 1: seed 9.2 guidance was used  */
    int surface_tree;                       /* 1: the seed 9.4 surface tree   */
    int overlay;                            /* 1: interior map by overlay     */
    int tree_qtri;                          /* 1: SQ_TREE_QTRI: Omega from Q  */
                                            /* triangulated (triangles)       */
    uint32_t qtri_verts;                    /* its vertices, with the tree's  */
    uint32_t qtri_steiner;                  /* Steiner vertices among them    */
    uint64_t crossings;                     /* the overlay's (step 7')        */
    uint64_t crossings_expected;            /* by its sample (sq_overlay.h)   */
    int gated;                              /* 1: the attempt gave its domain */
                                            /* up on crossings_expected (the  */
                                            /* domain variants' gate)         */
    uint32_t domain_variant;                /* tree qtri: Algorithm 1's tie   */
                                            /* order of the result's domain   */
                                            /* (0: the first)                 */
    uint32_t wall_splits;                   /* tree qtri: input edges split   */
                                            /* at their midpoints where the   */
                                            /* cut walled a cone in (0: none) */
    uint32_t cone_splits;                   /* input edges between two cones  */
                                            /* split at their midpoints so    */
                                            /* that the cut graph's loops and */
                                            /* paths pass between them (seed  */
                                            /* 9.1; 0: none needed)           */
    int cut_needs_split;                    /* 1: the cut graph failed for    */
                                            /* want of an edge split (a ring  */
                                            /* of adjacent cones, a narrow    */
                                            /* passage)                       */
    uint32_t fan_vertices;                  /* overlay: added by the graded   */
                                            /* fans (sq_param_grade_fans)     */
    double refinement_max_dist;             /* the largest distance of an     */
                                            /* added vertex from its input    */
                                            /* face over the diagonal         */
                                            /* (sq_param_verify_refinement)   */
    int fallback;                           /* 1: SQ_TREE_AUTO's fallback, the */
                                            /* surface tree, made the map     */
    /* seconds per step (of the last attempt; t_total covers all) */
    double t_cut, t_domain, t_omega, t_tree, t_boundary, t_cells, t_tutte, t_check, t_total;
    double t_overlay; /* step 7' (after the cells by default; kept or not) */
    /* sq_param_simplify on the result (SQ_SIMPLIFY_ON): added vertices it
     * removed, the faces before it, its time (within t_total) */
    uint32_t simplified, faces_unsimplified;
    double t_simplify;
} sq_param_stats;

/* The result: a triangle mesh (input vertices first) with UVs per corner.
 * Arrays are owned by the struct (sq_param_free). */
typedef struct sq_param {
    uint32_t nv, nf, nuv;
    uint32_t nv_input;  /* the first nv_input vertices are the input's     */
    double *pos;        /* 3 nv                                            */
    uint32_t *tri;      /* 3 nf, counterclockwise as in the input          */
    uint32_t *tri_uv;   /* 3 nf: UV index of each corner                   */
    double *uv;         /* 2 nuv                                           */
    uint32_t *tri_in;   /* nf: the input face holding the triangle (NULL  */
                        /* where unknown)                                  */
    uint8_t *he_seam;   /* 3 nf: 1 where the edge from corner i to i+1 of  */
                        /* a face is a seam (its two sides have different   */
                        /* UVs)                                            */
    uint8_t *he_cut;    /* 3 nf: the edge from corner i to i+1 of a face is */
                        /* 0 inside a cell, 1 on the cut (cut graph and    */
                        /* cone tree), 2 on a chord (a cell side inside    */
                        /* Omega); for diagnosis (sq_param_cells)          */
    int32_t *valence;   /* nv_input: the prescribed valences (4 = regular) */
    uint32_t *he_twin;  /* 3 nf or NULL: the corner across each edge, kept */
                        /* from the construction for sq_param_simplify     */
                        /* (which derives it where NULL, and frees it)     */
    /* The combinatorial domain, its cone tree and Omega, kept for
     * pictures (sq_domain_write_svg, sq_omega_write_svg; sq_domain.h and
     * sq_omega.h declare them); tree is NULL with tree qtri. */
    struct sq_domain *domain;
    struct sq_cone_tree *tree;
    struct sq_omega *omega;
} sq_param;

void sq_param_init(sq_param *P);
void sq_param_free(sq_param *P);

/* Builds the parametrization of the closed, connected triangle mesh m for
 * the per-vertex valences (valence[v] = 4 for a regular vertex; a cone of
 * angle k*pi/2 has valence k). The cone set must pass sq_cones_check_*:
 * SQ_ERR_UNREALIZABLE (valence 1, the torus {3,5}) and Gauss-Bonnet
 * violations are reported before any work. stats and opt may be NULL. */
sq_status sq_param_build(const sq_mesh *m, const int32_t *valence, const sq_param_options *opt,
                         sq_param *out, sq_param_stats *stats, sq_error *err);

enum {
    /* sq_param_verify: transitions must be exact with integer translations
     * and cone points must have integer UVs (an integer grid map) */
    SQ_PARAM_VERIFY_INTEGER = 1u << 0
};

/* Independent check of P (for tests and the CLI): every UV triangle has
 * positive orientation by the exact predicate; across every edge the two
 * UV copies are related by a rotation by a multiple of 90 degrees plus a
 * translation (exactly, and integer with SQ_PARAM_VERIFY_INTEGER), one
 * transition per seam curve; UV angle sums are valence * pi/2 at input
 * vertices and 2 pi at added ones (1e-9 relative). SQ_ERR_INTERNAL names
 * the first violation (face, vertex, edge; 0-based). Also checked: indices
 * in range, finite UVs, the triangles form a closed oriented manifold, each
 * UV point is used by one vertex only, he_seam (when not NULL) matches the
 * UV indices. valence may be NULL (no cones). A seam curve is a maximal
 * chain of seam edges through non-cone vertices with two seam edges, as in
 * shared/tools/check_param.py; exactness is decided without tolerance
 * (sq_param_io.c explains how). */
sq_status sq_param_verify(const sq_param *P, unsigned flags, sq_error *err);

/* The 3D side: P's mesh is a refinement of m, the mesh it was built from.
 * Its first nv_input vertices are m's, bit for bit; every triangle f lies
 * in its input face tri_in[f] (input vertices among its corners must be
 * that face's corners; added vertices within 1e-12 of the input's
 * bounding-box diagonal of it) and faces the same way (unless its 3D area
 * is below 1e-12 of the squared diagonal). SQ_ERR_INTERNAL names the first
 * violation (face, vertex, input face; 0-based). max_dist (may be NULL)
 * gets the largest distance of an added vertex from its input face,
 * relative to the diagonal. */
sq_status sq_param_verify_refinement(const sq_param *P, const sq_mesh *m, double *max_dist,
                                     sq_error *err);

/* Removes added vertices of P that lie off its seams, by half-edge
 * collapses that keep every property sq_param_verify and the referee
 * check: UV triangles positively oriented (exact predicate), angle sums,
 * seams and cones untouched (seam vertices do not move), every triangle
 * inside one input triangle of m (P->tri_in) and positively oriented
 * there, a closed manifold; and no new triangle more distorted (conformal
 * ratio) than the worst of the triangles it replaces. Input vertices keep
 * their indices; faces, added vertices and UVs keep their order.
 * sq_param_simplify.c explains the rules. m is the input mesh of P;
 * *removed (may be NULL) receives the vertices removed. */
sq_status sq_param_simplify(const sq_mesh *m, sq_param *P, uint32_t *removed, sq_error *err);

/* The same in `threads` threads (2 used at most: the input's faces in two
 * halves, each simplified on its own, then the vertices between them);
 * the result does not depend on threads. */
sq_status sq_param_simplify_threads(const sq_mesh *m, sq_param *P, uint32_t threads, uint32_t *removed,
                                    sq_error *err);

/* P's triangles as a soup that views P's arrays (positions, triangles, UV
 * points and corners; nothing copied) with its own face offsets, which the
 * caller frees (free(s->face_off)). SQ_ERR_NOMEM only. */
sq_status sq_param_soup(const sq_param *P, sq_soup *s, sq_error *err);

/* Writes P as OBJ (v, vt, f a/ta b/tb c/tc), atomically (no partial file on
 * error). Its pictures: sq_seamless_svg.h. */
sq_status sq_param_write_obj(const char *path, const sq_param *P, sq_error *err);

/* Diagnosis of a map that failed its orientation check (built with
 * sq_param_options.allow_flips; sq_param_cells.c): the cells of Omega on
 * the surface (faces joined across edges with he_cut 0), those holding
 * bad UV triangles (not positively oriented, exact predicate), worst
 * first. Per cell: its rectangle in UV and the surface (3D) length of its
 * boundary on each side of the rectangle: a surface cell whose sides
 * differ wildly from the rectangle's, or that runs along one side twice,
 * is what Tutte's map squeezes (docs/param.md, "Pictures and
 * diagnosis"). */
typedef struct sq_param_cell {
    uint32_t faces, bad;         /* triangles, of them not positive      */
    uint32_t first_bad;          /* a bad face                           */
    double umin, vmin, umax, vmax; /* the rectangle                      */
    double side_len[4];          /* 3D length on u = umin, v = vmin,     */
                                 /* u = umax, v = vmax                   */
    double other_len;            /* 3D length on no side (should be 0)   */
    uint32_t runs;               /* maximal runs of one side along the   */
                                 /* boundary (4 for a rectangle traced   */
                                 /* once; more when a side folds)        */
} sq_param_cell;

/* Fills up to max cells with bad triangles (worst first) into cells; *n
 * receives how many cells have bad triangles (may exceed max). Needs
 * P->he_cut. */
sq_status sq_param_bad_cells(const sq_param *P, sq_param_cell *cells, uint32_t max, uint32_t *n,
                             sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
