/* seamquad: the OpenSubdiv adapter (stages/adapter_opensubdiv.cpp), a thin
 * extern "C" wrapper around OpenSubdiv 3.5's Far API (Debian libosd-dev).
 *
 * It only hands out what OpenSubdiv computes: the Catmull-Clark patches of a
 * closed quad mesh (adaptive refinement with B-spline end caps, so every
 * patch is a regular 4x4 uniform bicubic B-spline), limit-surface
 * evaluations on those patches, and uniform refinement. Every algorithm built
 * on top (limit mesh, CAD export, gap report) lives in C (sq_subdiv*.c).
 *
 * Parameters: each base face f (a quad with corners c0 c1 c2 c3 in the
 * input's order) has the parameter square [0,1]^2 with c0 at (0,0), c1 at
 * (1,0), c2 at (1,1), c3 at (0,1). A patch covers the sub-square
 * [u0,u1] x [v0,v1] of one base face; its control points cv[4*j + i]
 * (i along u, j along v, xyz interleaved) define a uniform bicubic B-spline
 * over the knots -3 .. 4 in each direction whose domain [0,1]^2 maps
 * linearly onto that sub-square. */
#ifndef SQ_OSD_ADAPTER_H
#define SQ_OSD_ADAPTER_H

#include <stdint.h>

#include "sq_error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sq_osd sq_osd;

/* Builds the surface of a closed pure-quad mesh (validate it first with
 * sq_mesh_from_soup). `isolation` (1..10) is the adaptive isolation level of
 * extraordinary vertices: the B-spline end caps around them, which
 * approximate the exact limit surface, shrink by 2 per level. */
sq_status sq_osd_create(uint32_t nv, const double *pos, uint32_t nf, const uint32_t *face_off,
                        const uint32_t *face_idx, int isolation, sq_osd **out, sq_error *err);
void sq_osd_free(sq_osd *o);

uint32_t sq_osd_patch_count(const sq_osd *o);

/* Patch p: its 16 control points, base face and domain {u0, v0, u1, v1} in
 * the face's parameter square. */
void sq_osd_patch(const sq_osd *o, uint32_t p, double cv[48], uint32_t *face, double dom[4]);

/* Limit position P and derivatives Pu, Pv (with respect to the base face's
 * parameters) at (u, v) of base face `face`. With patch == UINT32_MAX the
 * patch is found by OpenSubdiv's patch map; otherwise patch `patch` (which
 * must cover (u, v) up to rounding) is evaluated. Pu, Pv may be NULL. */
void sq_osd_eval(const sq_osd *o, uint32_t face, uint32_t patch, double u, double v, double P[3],
                 double Pu[3], double Pv[3]);

/* `levels` uniform Catmull-Clark steps of a closed polygon mesh; the result
 * is a quad mesh in malloc'ed arrays (free them with free()). */
sq_status sq_osd_refine_uniform(uint32_t nv, const double *pos, uint32_t nf,
                                const uint32_t *face_off, const uint32_t *face_idx,
                                int levels, uint32_t *out_nv, double **out_pos, uint32_t *out_nf,
                                uint32_t **out_face_off, uint32_t **out_face_idx, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
