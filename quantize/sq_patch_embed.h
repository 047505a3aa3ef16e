/* seamquad: a T-mesh face re-embedded onto its integer rectangle.
 *
 * Quantization gives every T-mesh face integer side lengths a x b. The
 * triangles inside the face (the mesh split along the face's boundary
 * arcs) keep their shape in the map's chart: an axis-aligned rectangle
 * [0, W] x [0, H]. This step moves them into [0, a] x [0, b] so that the
 * boundary goes where quantization put it (the vertices on the boundary
 * have prescribed new coordinates, the same for both faces of an arc) and
 * no triangle flips:
 *
 *  1. The surface's own shape, where the vertices' 3D positions are given:
 *     Tutte's map with mean-value weights from the 3D triangles (Floater
 *     2003): every free vertex a positive combination of its neighbours,
 *     boundary fixed on the convex rectangle, so a bijection for a
 *     triangulated disk whose boundary goes onto a convex polygon in order
 *     (Tutte 1963, Floater 2003), and close to conformal on the surface
 *     inside the face whatever the input map's distortion (UMFPACK).
 *  2. Else, or where rounding flips a triangle: the sweep, two monotone
 *     maps, one per axis. The bottom and top sides' boundary vertices
 *     define piecewise linear maps F_b, F_t of u onto [0, a]; the left and
 *     right sides', G_l, G_r of v onto [0, b]. A point (u, v) goes first to
 *     s = (1 - v/H) F_b(u) + (v/H) F_t(u) (for each v an increasing
 *     function of u), then to t = (1 - s/a) G_l(v) + (s/a) G_r(v) (for
 *     each s an increasing function of v). Each step is a bijection of the
 *     rectangle, so their composition is one, and it agrees with the
 *     prescribed boundary; it keeps the input map's shape. Triangles are
 *     mapped by their vertices, so a triangle much larger than the map's
 *     variation can still flip, and so can a long thin one across a kink
 *     (where an arc ends on a side) or bent by the bilinear blend.
 *  3. Where that flips too: Tutte's map with mean-value weights from the
 *     map's own shape (which reproduce an affine change exactly), then
 *     with uniform weights (CHOLMOD) if rounding still flips a triangle or
 *     the mean-value system is singular.
 * Every result is checked with the exact predicate.
 *
 * Cost: O(nv log nv) for the sweep; one sparse Cholesky of the free
 * vertices for Tutte. A patch that neither gives positive triangles is
 * refused (SQ_ERR_SOLVER) with the count: never returned folded.
 * Quantization then cuts it along the sweep's kink lines and finer grids
 * and tries again (sq_quantize_refine.c). */
#ifndef SQ_PATCH_EMBED_H
#define SQ_PATCH_EMBED_H

#include <stdint.h>

#include "sq_error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sq_patch {
    uint32_t nv, nt;
    const double *uv;     /* 2 nv: the map's coordinates, face-local, in      */
                          /* [0, W] x [0, H]; boundary vertices exactly on    */
                          /* u = 0, u = W, v = 0 or v = H                     */
    const uint32_t *tri;  /* 3 nt, counterclockwise (positive in uv)          */
    double W, H;          /* the face's size in the map                       */
    int64_t a, b;         /* its integer size                                 */
    const uint8_t *fixed; /* nv: 0 inside; on the boundary (new UV given) the */
                          /* sides the vertex lies on, SQ_PATCH_BOTTOM | ...   */
                          /* (a corner has two)                               */
    const double *pos;    /* 3 nv or NULL: the vertices on the surface (see   */
                          /* sq_patch_embed)                                  */
} sq_patch;

enum { SQ_PATCH_BOTTOM = 1, SQ_PATCH_RIGHT = 2, SQ_PATCH_TOP = 4, SQ_PATCH_LEFT = 8 };

enum { SQ_PATCH_SURFACE = 3, SQ_PATCH_SWEEP = 1, SQ_PATCH_TUTTE = 2 };

/* out_uv (2 nv): on entry the new coordinates of the fixed vertices (the
 * four corners at (0,0), (a,0), (a,b), (0,b)); on return every vertex's.
 * *method receives the step that gave it: SQ_PATCH_SURFACE, SQ_PATCH_SWEEP
 * or SQ_PATCH_TUTTE. */
sq_status sq_patch_embed(const sq_patch *P, double *out_uv, int *method, sq_error *err);

/* Step 2 alone (the fallback, mean-value weights): Tutte's map with the
 * same boundary; the caller checks the orientation. */
sq_status sq_patch_embed_tutte(const sq_patch *P, double *out_uv, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
