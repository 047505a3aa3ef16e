/* seamquad: the whole pipeline, a closed triangle mesh in, a quad mesh out
 * (docs/remesh.md).
 *
 * Stages, each checked before the next starts:
 *  1. cones: the caller's, or a smooth cross field's singularities made
 *     admissible (sq_cones_from_field);
 *  2. param: the seamless map of the seed (sq_param_build): exact seams,
 *     every UV triangle positive, exactly the cones;
 *  3. map: that map as an exact sq_map of a refinement of the input
 *     (sq_param_map);
 *  4. optimize: its distortion lowered with its rotations kept and its
 *     translations free (sq_optimize_map, progressive references), in
 *     rounds each followed by param's simplification, which removes far
 *     more added vertices from the optimized map (sq_param_optimize);
 *  5. quantize: the integer-grid map at the requested size, with its own
 *     optimization step (sq_quantize);
 *  6. extract: the quad mesh (sq_extract), folded quads relaxed on the
 *     surface (sq_extract_untangle); a quad still folded or turned over
 *     fails the run;
 *  7. smooth (unless no_smoothing): the quads' vertices moved on the input
 *     surface toward right angles and even edges (sq_smooth_quads: Ceres,
 *     no step folds a quad); where it turns quads over, or makes them
 *     intersect where the unsmoothed quads do not (and the verify stage's
 *     repair cannot undo it), the vertices involved and rings around them
 *     go back to their unsmoothed places; all of them when that fails;
 *  8. verify: the quad surface (each quad split along its shorter
 *     diagonal) must not intersect itself where the input does not
 *     (CGAL's exact test, sq_cgal_adapter.h; where it does, the quads
 *     involved are relaxed on the surface first, sq_remesh_repair.c), and
 *     no quad may be folded or turned over on the surface,
 *     have an edge shorter than 1e-12 of the diagonal or an area below
 *     1e-12 of its square (sq_quad_mesh_check_shapes); else the run fails.
 *
 * Guarantees of a successful result: a closed, manifold, pure-quad mesh of
 * the input's genus whose irregular vertices are exactly the cones (a cone
 * of valence k is a vertex of k quads), every vertex on the input surface,
 * no quad folded (the referee's test: a quad is folded when in both of its
 * triangulations the two triangles' normals differ by more than 90
 * degrees), none turned over (every corner facing away from the surface),
 * and, where the input does not intersect itself, no two of the
 * quads' triangles intersecting. On failure nothing is returned, the error
 * names the stage (sq_remesh_stats.stage) and the cause.
 *
 * The library never prints or exits. */
#ifndef SQ_REMESH_H
#define SQ_REMESH_H

#include <stdint.h>

#include "sq_cross_field.h"
#include "sq_error.h"
#include "sq_extract.h"
#include "sq_map.h"
#include "sq_map_from_rotations.h"
#include "sq_mesh.h"
#include "sq_optimize.h"
#include "sq_param.h"
#include "sq_param_optimize.h"
#include "sq_quantize.h"
#include "sq_smooth.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SQ_REMESH_QUADS 5000.0
/* The optimizer's budget: it stops sooner where it converges. Measured at
 * 5K quads: the 11 models of the remesh bench that pass converge after 24
 * to 168 iterations (the same outputs with 200 or 600); fandisk from its
 * cones (param's map at 1.3e88) converges after 414 and passes, refused
 * after 200; helmet and femur, refused either way, spend 10 s and 1 s
 * more at 600. */
#define SQ_REMESH_ITERATIONS SQ_PARAM_OPTIMIZE_ITERATIONS
/* On maps of SQ_REMESH_STEP5_CAP_FACES faces or more, quantize's step 5
 * (the integer-grid map's distortion, sq_quantize.h) stops after
 * SQ_REMESH_STEP5_ITERATIONS Newton steps (quantize's own default: 20):
 * each step is a sparse Cholesky of the map split along the T-mesh, most
 * of the gain comes in the first ones, and smoothing follows. cid/elephant
 * (49,918 faces) at 5K quads: 12 -> 6 steps, 9.0 s in all instead of 10.2,
 * 4.08 degrees instead of 4.31. With the cap on every map, the 15 mpz cone
 * files at 1K and 5K and 15 other models at 1K and 5K stayed valid, the
 * same quads where step 5 converged sooner, but the smoothed figures of
 * some coarse layouts moved by several degrees either way (fertility_tri
 * at 1K 7.9 -> 16.5, pinion 20.9 -> 10.8): below the bound the cheaper
 * steps are kept whole. */
#define SQ_REMESH_STEP5_CAP_FACES 40000u
#define SQ_REMESH_STEP5_ITERATIONS 6u
/* Layouts tried from one map (stages 5 to 8) before the magnified ones:
 * the size asked, then three others (sq_remesh.c, next_layout). */
#define SQ_REMESH_LAYOUTS 4u
/* Then up to this many layouts from the map magnified around the quads
 * that passed through each other (sq_remesh_magnify.c), each at the size
 * asked, the magnification doubled each time (2 to 64). */
#define SQ_REMESH_MAGNIFIED 6u

enum { SQ_REMESH_PARAM_AUTO = 0, SQ_REMESH_PARAM_ALWAYS = 1, SQ_REMESH_PARAM_NEVER = 2 };

typedef struct sq_remesh_options {
    double quads;                  /* about this many quads; 0 with          */
                                   /* edge_length 0: SQ_REMESH_QUADS         */
    double edge_length;            /* or quad edges of about this length     */
    uint32_t optimize_iterations;  /* stage 4 (0: SQ_REMESH_ITERATIONS)      */
    uint64_t seed;                 /* param's cut-graph seed (0: 1)          */
    uint32_t attempts;             /* param's attempts (0: 4)                */
    int keep_maps;                 /* 1: the result keeps the three maps     */
    int no_smoothing;              /* 1: skip stage 7                        */
    int param;                     /* stage 2: SQ_REMESH_PARAM_AUTO (0):     */
                                   /* param's map where the map on the mesh  */
                                   /* fails or its quads do; _ALWAYS: param's */
                                   /* only; _NEVER: the map on the mesh only */
    sq_map *map;                   /* NULL, or a seamless map of the mesh to */
                                   /* start from (sq_map_read: exact): its   */
                                   /* cones are the run's, stages 1 and 2    */
                                   /* are skipped and stage 4 optimizes it   */
                                   /* whole (no simplification rounds).      */
                                   /* sq_remesh takes it over: freed and     */
                                   /* zeroed, whatever the outcome           */
    /* progress (may be NULL): the stage and the fraction of the whole run */
    void (*progress)(void *user, const char *stage, double fraction);
    void *user;
} sq_remesh_options;

typedef struct sq_remesh_stats {
    const char *stage;             /* the stage running, or that failed      */
    int cones_from_field;          /* 1: stage 1 computed the cones          */
    int from_map;                  /* 1: started from the caller's map       */
    uint32_t cones;                /* vertices of valence != 4               */
    sq_cones_from_field_stats field;
    sq_rotation_map_report rotations; /* stage 2's map on the mesh itself   */
    int map_from_rotations;        /* 1: it was valid and used (no param)    */
    sq_param_stats param;
    sq_param_optimize_report optimize;
    sq_quantize_stats quantize;
    sq_extract_stats extract;
    sq_untangle_stats untangle;
    sq_smooth_stats smooth;        /* stage 7 (quality before and after; the */
                                   /* latter of the quads returned)          */
    int smoothed;                  /* 1: the quads returned are smoothed     */
    int smooth_reverted;           /* 1: smoothed, but the unsmoothed quads  */
                                   /* were returned (smooth_why says why)    */
    char smooth_why[160];
    uint32_t smooth_kept;          /* vertices left unsmoothed: around quads  */
                                   /* that smoothing turned over or made     */
                                   /* intersect                              */
    uint64_t self_intersections;   /* intersecting pairs of the quads'       */
                                   /* triangles (each quad split along its   */
                                   /* shorter diagonal; CGAL)                */
    int64_t input_self_intersections; /* the input's, when the quads have    */
                                   /* some (-1: not computed)                */
    double t_verify;               /* the self-intersection tests and the    */
                                   /* repairs (before smoothing too)         */
    uint64_t repaired_unsmoothed;  /* pairs of the unsmoothed quads the      */
                                   /* repair removed before smoothing        */
    uint64_t repaired;             /* intersecting pairs the repair removed  */
    uint32_t repair_rounds;        /* its rounds (0: nothing to repair)      */
    uint32_t layouts;              /* layouts tried (stages 5 to 8; 1: the   */
                                   /* first passed)                          */
    char layout_why[200];          /* why the last refused one was refused   */
    int layout_targets;            /* the arcs' targets of the one returned  */
                                   /* (SQ_TARGETS_MAP or _SURFACE)           */
    uint32_t magnified;            /* of the layouts, those from the map     */
                                   /* magnified where quads intersected      */
    double t_rotations;            /* stage 2's map on the mesh (tried)      */
    double t_cones, t_param, t_optimize, t_quantize, t_extract, t_smooth, t_total; /* stage 3 in t_optimize */
} sq_remesh_stats;

typedef struct sq_remesh_result {
    sq_quad_mesh quads;            /* when smoothed, pos is the smoothed     */
                                   /* position and uv, loc_face, loc_bary    */
                                   /* still those of the integer grid point  */
    int32_t *valence;              /* nv of the input: the cones used        */
    /* with keep_maps: param's map, the optimized map, the integer-grid map */
    sq_map map, optimized, igm;
} sq_remesh_result;

/* Runs the pipeline on the closed, connected triangle mesh m (as
 * sq_mesh_from_soup builds it). valence: nv cones (4 = regular), or NULL
 * for cones from the cross field. out is overwritten; on failure it is left
 * empty. stats (may be NULL) get per-stage figures and times. */
sq_status sq_remesh(const sq_mesh *m, const int32_t *valence, const sq_remesh_options *opt,
                    sq_remesh_result *out, sq_remesh_stats *stats, sq_error *err);

void sq_remesh_result_free(sq_remesh_result *r);

#ifdef __cplusplus
}
#endif
#endif
