/* seamquad: Catmull-Clark subdivision surface of a closed quad mesh, its
 * limit surface as a mesh, and its export as bicubic B-spline patches for
 * CAD (STEP AP214, IGES 5.3). See docs/subdiv.md.
 *
 * OpenSubdiv (through stages/sq_osd_adapter.h) computes the patches and
 * every limit evaluation; this code builds meshes, reports and files from
 * them. */
#ifndef SQ_SUBDIV_H
#define SQ_SUBDIV_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_mesh.h"
#include "sq_soup.h"

#ifdef __cplusplus
extern "C" {
#endif

struct sq_osd;

typedef struct sq_subdiv {
    struct sq_osd *osd;   /* OpenSubdiv patch table (adapter)                 */
    uint32_t nf;          /* base quads                                       */
    uint32_t np;          /* bicubic patches                                  */
    double *cv;           /* 48*np: 16 control points per patch, cv[4*j+i]    */
                          /* (i along u, j along v), uniform knots -3..4      */
    uint32_t *patch_face; /* np: base face of each patch                      */
    double *patch_dom;    /* 4*np: {u0, v0, u1, v1} in the face's square      */
    uint32_t *face_first; /* nf+1: patches of face f are listed from         */
    uint32_t *face_patch; /* face_patch[face_first[f]] on                     */
    double bbox_diag;     /* diagonal of the control mesh's bounding box     */
    int isolation;
} sq_subdiv;

#define SQ_SUBDIV_DEFAULT_ISOLATION 6

/* Builds the surface of `mesh`, a closed pure-quad mesh (from
 * sq_mesh_from_soup with SQ_MESH_ALLOW_POLYGONS). isolation: 1..10. */
sq_status sq_subdiv_build(const sq_mesh *mesh, int isolation, sq_subdiv *out, sq_error *err);
void sq_subdiv_free(sq_subdiv *s);

/* Limit position (and, when not NULL, unit normal) at (u, v) of base face f. */
void sq_subdiv_eval(const sq_subdiv *s, uint32_t f, double u, double v, double P[3], double N[3]);

/* `levels` uniform Catmull-Clark steps of a closed polygon soup (OpenSubdiv):
 * the result is a quad soup without provenance. */
sq_status sq_subdiv_refine(const sq_soup *in, int levels, sq_soup *out, sq_error *err);

/* The limit surface sampled on a (2^level)^2 grid per base quad, evaluated
 * on the limit surface (positions and normals), as a closed watertight quad
 * mesh: vertices on base vertices and edges are shared. level: 0..8.
 * Arrays are malloc'ed: pos and nrm 3*nv, quads 4*nq. */
typedef struct sq_limit_mesh {
    uint32_t nv, nq;
    double *pos, *nrm;
    uint32_t *quads;
} sq_limit_mesh;

sq_status sq_subdiv_limit_mesh(const sq_subdiv *s, const sq_mesh *mesh, int level,
                               sq_limit_mesh *out, sq_error *err);
void sq_limit_mesh_free(sq_limit_mesh *lm);

/* OBJ with `v`, `vn` and `f a//a ...` lines, written atomically. */
sq_status sq_limit_mesh_write_obj(const char *path, const sq_limit_mesh *lm, sq_error *err);

/* Continuity across patch borders: every side of every patch is sampled at
 * `samples`+1 points; each point is evaluated on the patch and on the patch
 * across the border (in the same base face or across the base edge). */
typedef struct sq_subdiv_seams {
    uint64_t points;        /* sampled border points                          */
    double max_gap;         /* max distance between the two patches           */
    double max_gap_rel;     /* max_gap / bbox diagonal                        */
    double max_normal_deg;  /* max angle between the two patches' normals     */
    double mean_normal_deg; /* mean angle                                     */
    double max_normal_regular_deg; /* max angle where neither patch touches   */
                            /* an extraordinary vertex's end cap              */
} sq_subdiv_seams;

sq_status sq_subdiv_seam_report(const sq_subdiv *s, const sq_mesh *mesh, uint32_t samples,
                                sq_subdiv_seams *out, sq_error *err);

/* CAD export of the np patches (cv as in sq_subdiv), each its own surface.
 * STEP: AP214 file with one ADVANCED_FACE per patch (B_SPLINE_SURFACE_WITH_
 * KNOTS bounded by its four boundary B-spline curves) in an OPEN_SHELL of a
 * SHELL_BASED_SURFACE_MODEL. IGES: one untrimmed entity 128 (rational
 * B-spline surface, all weights 1) per patch. Both atomic. `name` goes into
 * the header; `scale` (bbox diagonal) sets the stated tolerance. */
sq_status sq_cad_write_step(const char *path, const char *name, uint32_t np, const double *cv,
                            double scale, sq_error *err);
sq_status sq_cad_write_iges(const char *path, const char *name, uint32_t np, const double *cv,
                            double scale, sq_error *err);

/* Real number as STEP and IGES want it: 17 significant digits, always with
 * a decimal point ("1.", "-2.5E-07"). buf: at least 32 bytes. */
const char *sq_cad_real(double x, char *buf);

#ifdef __cplusplus
}
#endif
#endif
