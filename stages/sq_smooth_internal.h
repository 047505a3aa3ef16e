/* seamquad: internals of the quad smoother shared by sq_smooth*.c. */
#ifndef SQ_SMOOTH_INTERNAL_H
#define SQ_SMOOTH_INTERNAL_H

#include <stdint.h>

#include "sq_smooth.h"

#define SQ_SMOOTH_MAX_RES 13 /* 4 angle + 4 length + 1 barrier + 4 untangling */

typedef struct sq_smooth_ctx {
    uint32_t nv, nq;
    const uint32_t *quads;   /* 4*nq                                           */
    const double *base;      /* 3*nv: vertex positions on the surface          */
    const double *frame;     /* 9*nv: tangent t1, tangent t2, normal n          */
    const double *h;         /* nv: local length scale (mean incident edge)     */
    const double *ref_normal;/* 3*nq: surface normal for the untangling terms   */
    const unsigned char *untangle; /* nq: 1 = the quad gets untangling terms    */
    const double *threshold; /* nq: feasible iff fold margin >= threshold       */
    const double *target;    /* 4*nq: target angle of each corner (radians); NULL: pi/2 */
    const double *ideal_log; /* 4*nq: log ideal length of each edge, zero mean; NULL: 0 */
    const uint32_t *con_quad;/* constraint block -> quad                        */
    double wa, wl, wu, wb;
    double damping;          /* weight of the per-vertex damping residuals      */
    long fold_rejections;    /* counted by the feasibility callback             */
    const double *base_angle;/* 4*nq or NULL: each corner's angle at `base`; a  */
                             /* corner's angle is then taken on the branch      */
                             /* within pi of it (continuous during a solve)     */
} sq_smooth_ctx;

/* Per-corner target angles and per-edge ideal log lengths of every quad
 * (docs/smooth.md, "Targets"): corner k of quad q aims at 2 pi / valence of
 * its vertex; the ideal edge lengths are those of the planar quad whose
 * angles are these targets scaled to sum 2 pi, closest to equal lengths.
 * target, ideal_log: 4*nq each. */
void sq_smooth_targets(uint32_t nv, uint32_t nq, const uint32_t *quads, double *target, double *ideal_log);

/* The four corner angles of quad x[0..3] measured around the normal n,
 * in [0, 2 pi): corner k turns from its edge to x[k+1] to its edge to
 * x[k-1] (a reflex corner is above pi). */
void sq_smooth_corner_angles(const double *const x[4], const double n[3], double theta[4]);

/* Number of residuals of quad q (9, or 13 with untangling terms). */
uint32_t sq_smooth_residual_count(const sq_smooth_ctx *c, uint32_t q);

/* Residuals of quad q at corner positions x[0..3] (3D). 0 when undefined
 * (a zero-length edge). */
int sq_smooth_quad_residuals(const sq_smooth_ctx *c, uint32_t q, const double *const x[4], double *r);

/* Sum of squared residuals of all quads at positions pos (3*nv). */
double sq_smooth_energy(const sq_smooth_ctx *c, const double *pos);

/* Fidelity pins (docs/smooth.md, "Fidelity"): the surface vertices i
 * (snv, spos) whose distance to the quad surface (each quad split along
 * its shorter diagonal, as the referee does) exceeds both theta * h[v] and
 * half the largest such distance, v being the nearest corner of the quad
 * triangle nearest to i: the pairs (pin_v, pin_s), room for snv each. */
sq_status sq_smooth_find_pins(uint32_t snv, const double *spos, uint32_t nv, const double *pos, uint32_t nq,
                              const uint32_t *quads, const double *h, double theta, uint32_t *pin_v,
                              uint32_t *pin_s, uint32_t *npin, sq_error *err);

/* Callbacks for sq_nlls_solve: residual blocks 0..nq-1 are the quads;
 * blocks nq..nq+nv-1 (when damping > 0) are damping * (a, b) of vertex
 * r - nq (a damped, shorter step on a retry). Parameter block i is vertex
 * i's tangent offset (a, b): position base + h (a t1 + b t2). The residual
 * callback (sq_nlls_residual_fn) gives the angle and length residuals'
 * derivatives analytically, the barrier's and untangling's (nonzero only
 * near a fold) by central differences. */
int sq_smooth_residual_cb(void *user, uint32_t q, const double *const *param, double *r, double **jac);
int sq_smooth_feasible_cb(void *user, uint32_t con, const double *const *param);

#endif
