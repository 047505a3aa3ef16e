/* seamquad: param's map optimized and simplified in rounds
 * (sq_param_optimize.h; `param --optimize on`, stage 4 of remesh).
 *
 * param's maps carry 3 to 39 times the input's faces: the added vertices
 * its cuts and overlay needed, most of which its own simplification could
 * not remove while the map was distorted (a collapse must not make any
 * triangle more distorted than the worst it replaces). Once the optimizer
 * has lowered the distortion, far more of them can go. So the budget of
 * iterations is spent in rounds: ROUND_ITERATIONS iterations
 * (sq_optimize_map, rotations kept, translations free), the optimized UVs
 * written back into param's result, sq_param_simplify (every check of the
 * map kept: exact orientation, seams and cones untouched, every triangle
 * inside one input triangle), the map rebuilt exactly; until the budget
 * is spent, or the optimizer converges with nothing left to remove. A
 * simplification costs little next to an iteration, a round's restart
 * one symbolic factorization. Measured (bench/bench_optimize.sh, rows
 * "param --optimize on"): genus3's map, 97,510 faces at mean conformal
 * ratio 206, ends at 13,698 faces and 1.28 after 127 iterations in 31 s;
 * optimize on the whole map stands at 13.1 after 100 iterations in 114 s.
 *
 * A round keeps the optimizer's last iterate even where the surface energy
 * rose on the way (progressive references can do that over a few
 * iterations; keep_last), and where the free translations' snapped result
 * fails the exact check (triangles far below the grid: param's rectangles'
 * maps) the round is run with the translations fixed. Every map handed on
 * passes sq_map_check; the simplification never makes a triangle more
 * distorted than the worst it replaces. */
#include <string.h>

#include "sq_param_optimize.h"

#define ROUND_ITERATIONS 5u

/* the map's corner UVs back into P (face f's corner c is halfedge 3f + c
 * of the map built from P; corners sharing a UV index share the value) */
static void uv_to_param(const sq_map *M, sq_param *P)
{
    for (uint32_t f = 0; f < P->nf; f++)
        for (int c = 0; c < 3; c++) {
            uint32_t h = 3 * f + (uint32_t)c, u = P->tri_uv[3 * f + c];
            P->uv[2 * u] = M->he_uv[2 * (size_t)h];
            P->uv[2 * u + 1] = M->he_uv[2 * (size_t)h + 1];
        }
}

sq_status sq_param_optimize(const sq_mesh *m, const int32_t *valence, sq_param *P,
                            const sq_optimize_options *base, uint32_t budget, sq_map *M,
                            sq_param_optimize_report *rep, sq_error *err)
{
    memset(rep, 0, sizeof *rep);
    memset(M, 0, sizeof *M);
    sq_status st = sq_param_map(P, m, valence, M, err);
    if (st) return st;
    rep->conformal_before = sq_map_conformal_mean(M);
    rep->faces_before = M->mesh.nf;
    while (rep->iterations < budget) {
        sq_optimize_options o = *base;
        o.progress_base = base->progress_base + rep->iterations;
        uint32_t left = budget - rep->iterations;
        o.max_iterations = left > ROUND_ITERATIONS ? ROUND_ITERATIONS : left;
        o.keep_last = 1; /* a round may raise the surface energy on the way */
        sq_optimize_report r;
        /* a round whose snapped result (free translations) fails the exact
         * check is run with the translations fixed */
        if ((st = sq_optimize_map_free_or_fixed(M, &o, &r, err))) return st;
        rep->fixed_rounds += r.fixed_rounds;
        rep->iterations += r.iterations;
        rep->reference_iterations += r.reference_iterations;
        memcpy(rep->why, r.why, sizeof rep->why);
        uint32_t removed = 0;
        uv_to_param(M, P);
        if ((st = sq_param_simplify(m, P, &removed, err))) return st;
        rep->rounds++;
        rep->removed += removed;
        if (removed > 0) {
            sq_map_free(M);
            if ((st = sq_param_map(P, m, valence, M, err))) return st;
        } else if (r.iterations < o.max_iterations) {
            break; /* converged (or stalled) and nothing left to remove */
        }
    }
    rep->faces_after = M->mesh.nf;
    rep->conformal_after = sq_map_conformal_mean(M);
    return SQ_OK;
}
