/* The extract stage: the quad mesh of an integer-grid map (sq_extract.h).
 * This file runs the steps in order; each step is in its own file. */
#include <stdlib.h>
#include <string.h>

#include "sq_clock.h"
#include "sq_extract_internal.h"

void sq_quad_mesh_free(sq_quad_mesh *q)
{
    if (!q) return;
    free(q->pos);
    free(q->quad);
    free(q->valence);
    free(q->kind);
    free(q->elem);
    free(q->uv);
    free(q->loc_face);
    free(q->loc_bary);
    memset(q, 0, sizeof *q);
}

sq_status sq_extract(const sq_map *M, sq_quad_mesh *out, sq_extract_stats *stats, sq_error *err)
{
    sq_extract_stats st_local;
    if (!stats) stats = &st_local;
    memset(stats, 0, sizeof *stats);
    if (!M || !out) return sq_error_set(err, SQ_ERR_ARGUMENT, "sq_extract: no map or no output");
    memset(out, 0, sizeof *out);
    double t0 = sq_now();
    sq_status st = sq_map_check(M, SQ_MAP_REQUIRE_INTEGER, err);
    if (st) return st;
    double tc = sq_now();
    stats->t_check = tc - t0;

    sq_grid G;
    st = sq_grid_build(M, &G, err);
    if (st) return st;
    stats->vertex_points = G.nvert;
    stats->edge_points = G.nedge;
    stats->face_points = G.nface;
    double t1 = sq_now();
    stats->t_points = t1 - tc;

    uint32_t *to = malloc((size_t)(G.nslot ? G.nslot : 1) * sizeof *to);
    if (!to) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory (grid edges)");
        goto done;
    }
    for (uint32_t s = 0; s < G.nslot; s++) {
        uint32_t steps = 0;
        if ((st = sq_grid_trace(M, &G, s, &to[s], &steps, err))) goto done;
        stats->trace_steps += steps;
        if (steps > stats->max_trace_steps) stats->max_trace_steps = steps;
    }
    double t2 = sq_now();
    stats->t_trace = t2 - t1;

    if ((st = sq_grid_quads(M, &G, to, out, stats, err))) goto done;
    double t3 = sq_now();
    stats->t_quads = t3 - t2;

    if ((st = sq_grid_positions(M, &G, out, err))) goto done;
    double t4 = sq_now();
    stats->t_positions = t4 - t3;
    stats->t_total = t4 - t0;
done:
    free(to);
    sq_grid_free(&G);
    if (st) sq_quad_mesh_free(out);
    return st;
}
