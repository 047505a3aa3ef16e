/* seamquad: quantization: a seamless map becomes an integer-grid map at the
 * user's scale (docs/quantize.md).
 *
 * Steps, each its own file:
 *  0. before the rest, a call of its own (sq_quantize_prepare): the map's
 *     distortion lowered, its rotations and cones kept, its translations
 *     free (sq_optimize.h), so that quantization has a map it can follow;
 *  1. the T-mesh (sq_tmesh.h): separatrices traced from the cones, exactly;
 *  2. the map's triangles split along them (sq_map_split.h), and the
 *     T-mesh's rectangles, arcs and sides read off the split
 *     (sq_quantize_layout.c);
 *  3. integer arc lengths (sq_tmesh_lengths.h): every T-mesh face gets
 *     integer sides with equal opposite sides, close to targets scaled to
 *     the requested size;
 *  4. every face re-embedded onto its integer rectangle (sq_patch_embed.h)
 *     and the result checked exactly as an integer-grid map: rotations by
 *     k x 90 degrees plus integer translations, positive triangles, cones on
 *     integer points (sq_quantize_embed.c);
 *  5. optionally (sq_quantize_options.optimize), the integer-grid map's
 *     distortion lowered with its transitions and cones fixed
 *     (sq_optimize.h: at most 20 iterations, tolerance 1e-3, triangles far
 *     from their surface shape held): the same layout and quad count,
 *     quads closer to squares.
 *
 * Guarantees: the result passes sq_map_check with SQ_MAP_REQUIRE_INTEGER,
 * or the call fails with the reason; every arc has length >= 1, so no two
 * nodes (cones, T-junctions) of the T-mesh merge and no face collapses. */
#ifndef SQ_QUANTIZE_H
#define SQ_QUANTIZE_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_map.h"
#include "sq_map_split.h"
#include "sq_optimize.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    SQ_TARGETS_SURFACE = 0, /* arc targets from their lengths on the surface */
    SQ_TARGETS_MAP = 1      /* from their lengths in the map                 */
};

typedef struct sq_quantize_options {
    double quads;       /* requested quad count (> 0), or 0 to use:          */
    double edge_length; /* requested quad edge length on the surface (> 0)   */
    int targets;        /* SQ_TARGETS_SURFACE (default) or SQ_TARGETS_MAP     */
    int optimize;       /* 1: step 5 (sq_quantize only, not _chords)         */
    uint32_t optimize_iterations; /* step 5's Newton steps at most (0: 20)   */
} sq_quantize_options;

typedef struct sq_quantize_stats {
    uint32_t cones;
    uint32_t nodes, arcs, faces;      /* the T-mesh read off the split       */
    uint32_t split_vertices, split_triangles;
    uint32_t fallback_faces;          /* faces not placed by the surface map */
    uint32_t refined_faces;           /* faces cut further before they could */
                                      /* be embedded (summed over rounds)    */
    uint32_t refine_rounds;           /* rounds of that refinement (0-3)     */
    double quads;                     /* quads of the integer-grid map       */
    double min_quads;                 /* the fewest the T-mesh allows (for a */
                                      /* quad target; 0 otherwise)          */
    sq_optimize_report optimize;      /* step 5 (when asked)                 */
    double seconds_tmesh, seconds_split, seconds_layout, seconds_lengths, seconds_embed;
    double seconds;
} sq_quantize_stats;

/* Step 0 (sq_quantize_prepare.c). */
#define SQ_QUANTIZE_PREPARE_ITERATIONS 600u
typedef struct sq_quantize_prepare_options {
    uint32_t iterations; /* the budget of Newton steps; 0:                     */
                         /* SQ_QUANTIZE_PREPARE_ITERATIONS                     */
    /* called after every iteration (may be NULL): a progress hook */
    void (*progress)(void *user, uint32_t iteration, double energy, double step);
    void *user;
} sq_quantize_prepare_options;
typedef struct sq_quantize_prepare_report {
    double conformal_before;   /* sq_map_conformal_mean before and after     */
    double conformal_after;
    sq_optimize_report optimize; /* sq_optimize_map_free_or_fixed's report   */
} sq_quantize_prepare_report;
/* Lowers the distortion of the exact map M in place before sq_quantize
 * (sq_optimize_map_free_or_fixed; opt may be NULL: the defaults). M stays
 * exact (sq_map_check passes), with the same mesh, rotations and cones.
 * rep may be NULL. */
sq_status sq_quantize_prepare(sq_map *M, const sq_quantize_prepare_options *opt,
                              sq_quantize_prepare_report *rep, sq_error *err);
/* The integer-grid map of the exact map M (sq_map_check passes) at the
 * requested size, from its cones' separatrices. *igm is a refinement of M
 * (its first vertices are M's). stats may be NULL. */
sq_status sq_quantize(const sq_map *M, const sq_quantize_options *opt, sq_map *igm,
                      sq_quantize_stats *stats, sq_error *err);

/* The same with the T-mesh given as chords (steps 2-4 only; the chords
 * must cut M into rectangles whose corners are its cones and the chords'
 * ends). */
sq_status sq_quantize_chords(const sq_map *M, const sq_chord *chords, uint32_t n_chords,
                             const sq_quantize_options *opt, sq_map *igm, sq_quantize_stats *stats,
                             sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
