/* seamquad: smooth cross (4-direction) fields and the cones they imply.
 *
 * The field is face-based: one unit "4th-power" complex number per face,
 * u_f = exp(4 i phi_f), where phi_f is the angle of any of the field's four
 * directions in the face's own frame (see sq_cross_field_frames.h). Faces are
 * connected through their shared edge (Levi-Civita transport by unfolding),
 * so the field's singularities sit on vertices and each has an integer index
 * in quarter turns: exactly what a cone file holds (docs/cones_from_field.md).
 *
 * Method: the globally optimal direction fields of Knoppel, Crane, Pinkall
 * and Schroeder (SIGGRAPH 2013), discretized on faces:
 *   - smooth: the smallest eigenvector of the 4-symmetric connection
 *     Laplacian A (generalized problem A u = lambda M u, M = face areas),
 *     by inverse power iteration on one CHOLMOD factorization;
 *   - curvature: (A + s M) u = M q, with q the principal curvature
 *     cross of each face weighted by the face's curvature anisotropy. */
#ifndef SQ_CROSS_FIELD_H
#define SQ_CROSS_FIELD_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sq_field_align {
    SQ_FIELD_SMOOTH = 0,     /* the smoothest field, no alignment         */
    SQ_FIELD_CURVATURE = 1   /* smooth, aligned to principal directions   */
} sq_field_align;

typedef struct sq_cross_field_options {
    sq_field_align align;
    /* SQ_FIELD_SMOOTH: at most this many inverse power iterations (stops
     * earlier when the Rayleigh quotient settles). Default 40. */
    uint32_t max_iterations;
    /* SQ_FIELD_CURVATURE: the shift s >= 0 in (A + s M) u = M q, for a mesh
     * scaled to unit area. 0 gives the smoothest field that still follows
     * the curvature globally; larger s follows the local curvature more
     * closely (and makes more singularities). Default 0. */
    double alignment;
} sq_cross_field_options;

typedef struct sq_cross_field_info {
    double energy;        /* u^H A u / u^H M u of the result (unit area)  */
    uint32_t iterations;  /* inverse power iterations done (smooth only)  */
    double t_assemble, t_factor, t_solve; /* seconds                      */
} sq_cross_field_info;

void sq_cross_field_default_options(sq_cross_field_options *opt);

/* Computes the field: u[2f], u[2f+1] = real and imaginary part of u_f, unit
 * modulus (a face where the field vanishes exactly gets u_f = 1). opt and
 * info may be NULL (defaults; no report). */
sq_status sq_cross_field(const sq_mesh *m, const sq_cross_field_options *opt, double *u,
                         sq_cross_field_info *info, sq_error *err);

/* Principal curvature source for SQ_FIELD_CURVATURE: q[2f], q[2f+1] =
 * |k1 - k2| exp(4 i theta_f), theta_f a principal direction of face f in
 * its frame, from an edge-based shape operator averaged over the one-rings
 * of the face's corners (curvature in units of 1/sqrt(total area)). */
sq_status sq_cross_field_curvature(const sq_mesh *m, double *q, sq_error *err);

/* Index of the field at every vertex in quarter turns: index[v] = 4 - k for
 * a cone of valence k (index 0 = regular). Computed in exact integers from
 * per-edge period jumps; the sum is 4 * Euler characteristic by
 * construction, and is verified (SQ_ERR_INTERNAL otherwise). */
sq_status sq_cross_field_indices(const sq_mesh *m, const double *u, int32_t *index,
                                 sq_error *err);

/* ---- cones from a field (sq_cones_from_field.c) ------------------------- */

typedef struct sq_cones_from_field_options {
    sq_cross_field_options field;
    /* Opposite-sign singularities closer than this (shortest path along
     * edges, in units of the mean edge length) cancel; 0 keeps every
     * singularity of the field. Default 3 (sq_cones_from_field_cancel). */
    double cancel_radius;
} sq_cones_from_field_options;

void sq_cones_from_field_default_options(sq_cones_from_field_options *opt);

typedef struct sq_cones_from_field_stats {
    sq_cross_field_info field;
    uint32_t raw_singularities; /* vertices of nonzero index in the field   */
    uint32_t cancelled;         /* quarter turns cancelled between +/- pairs */
    uint32_t low_valence;       /* of those, vertices of valence <= 1       */
    uint32_t moved_units;       /* quarter turns moved to resolve them      */
    int torus_pair_cancelled;   /* a lone 3-5 pair on a torus was removed   */
    uint32_t cones;             /* vertices of valence != 4 in the result   */
    double t_field, t_indices, t_total; /* seconds                          */
} sq_cones_from_field_stats;

/* Cones for a mesh that has none: valence[nv] (caller-owned) gets the
 * valence k of every vertex (4 = regular) of a smooth cross field's
 * singularities, made admissible: every valence >= 2 and never the lone
 * 3-5 pair on a torus (docs/cones_from_field.md says how). The result
 * satisfies sq_cones_check_gauss_bonnet and sq_cones_check_realizable;
 * both are verified before returning. stats may be NULL. */
sq_status sq_cones_from_field(const sq_mesh *m, const sq_cones_from_field_options *opt,
                              int32_t *valence, sq_cones_from_field_stats *stats,
                              sq_error *err);

/* Cancels nearby singularities of opposite sign, in place: a vertex of
 * valence < 4 and the nearest vertex of valence > 4 within radius (mesh
 * units, shortest path along edges) move one quarter turn towards 4 each,
 * closest pairs first, until no pair is left. Gauss-Bonnet is unchanged and
 * no valence <= 1 is created. cancelled (may be NULL) gets the number of
 * quarter turns cancelled. */
sq_status sq_cones_from_field_cancel(const sq_mesh *m, int32_t *valence, double radius,
                                     uint32_t *cancelled, sq_error *err);

/* Makes a Gauss-Bonnet valence assignment admissible, in place: moves one
 * quarter turn at a time from a vertex of valence <= 1 to the nearest
 * vertex (mesh graph distance) of valence >= 3, then cancels a lone 3-5
 * pair on a torus. Gauss-Bonnet is unchanged. Used by sq_cones_from_field;
 * public for tests. moved and cancelled may be NULL. */
sq_status sq_cones_from_field_repair(const sq_mesh *m, int32_t *valence, uint32_t *moved,
                                     int *cancelled, sq_error *err);

/* Writes cones to path atomically (no file on failure): a cone list
 * (`VERTEX VALENCE` lines, 0-based, cones only, after a `#` comment line)
 * when list is nonzero, else a Th_hat file (one angle k*pi/2 per vertex,
 * radians, %.17g). */
sq_status sq_cones_from_field_write(const char *path, uint32_t nv, const int32_t *valence,
                                    int list, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
