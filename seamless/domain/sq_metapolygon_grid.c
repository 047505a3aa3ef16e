/* seamquad: regular grids of 4-gons glued onto a metapolygon boundary
 * (seed 5.1, Def. 5.4 steps 2 and 3; seed 6.1 padding), cell by cell.
 *
 * Grid coordinates: cell (r, c), 0 <= r < rows, 0 <= c < cols; grid point
 * (r, c) is a vertex. Row 0 lies on the boundary path being covered, rows
 * grow away from the metapolygon. Every cell is one 4-gon glued with
 * sq_metapolygon_glue_polygon along 1, 2 or 3 consecutive boundary edges:
 *   along 2 edges (1 new vertex): the notch (r+1,c) -> (r,c) -> (r,c+1);
 *   along 1 edge (2 new vertices): the first cell of a row of a one-sided
 *     grid;
 *   along 3 edges (no new vertex): the last cell of a row of a three-sided
 *     grid, (r+1,c) -> (r,c) -> (r,c+1) -> (r+1,c+1).
 * Filling row by row, cell by cell, every cell finds its notch on the
 * boundary left by the previous cells. */
#include "sq_metapolygon.h"

#include <assert.h>

/* Def. 5.4 step 2 (sides = 3), step 3 (sides = 2); seed 6.1 (sides = 1). */
sq_status sq_metapolygon_glue_grid(sq_metapolygon *P, uint32_t h, uint32_t rows,
                                   uint32_t cols, uint32_t sides, sq_error *err)
{
    if (rows == 0 || cols == 0) return SQ_OK;
    if (sides < 1 || sides > 3)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "a grid is glued with 1, 2 or 3 sides, not %u",
                            sides);
    if (h >= P->nh || P->he_face[h] != SQ_NONE)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "grid anchor %u is not a boundary halfedge", h);
    uint64_t covered = sides == 1 ? cols
                     : sides == 2 ? (uint64_t)rows + cols
                                  : 2ull * rows + cols;
    if (covered >= P->nbnd)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "a %ux%u grid on %u sides covers %llu of only %u boundary edges",
                            rows, cols, sides, (unsigned long long)covered, P->nbnd);
    uint64_t cells = (uint64_t)rows * cols;
    uint64_t new_v = sides == 1 ? (uint64_t)rows * (cols + 1ull)
                   : sides == 2 ? cells
                                : (uint64_t)rows * (cols - 1ull);
    /* each cell adds at most 3 edges (6 halfedges) */
    sq_status st = sq_metapolygon_reserve(P, new_v, cells, 6 * cells, err);
    if (st != SQ_OK) return st;

    uint32_t row_start = h; /* boundary halfedge where row r's first cell glues */
    for (uint32_t r = 0; r < rows; r++) {
        uint32_t next_start = SQ_NONE;
        /* two and three sides: row r+1 starts at the edge before row r's,
         * on the original boundary (untouched so far) */
        if (sides >= 2 && r + 1 < rows) next_start = sq_metapolygon_boundary_prev(P, row_start);
        uint32_t cur = row_start;
        for (uint32_t c = 0; c < cols; c++) {
            uint32_t first = SQ_NONE, last = SQ_NONE;
            if (sides == 1 && c == 0) {
                st = sq_metapolygon_glue_polygon(P, cur, 1, 2, NULL, &first, &last, err);
                /* new boundary (r,0) -> (r+1,0) -> (r+1,1) -> (r,1): the
                 * middle edge carries row r+1 */
                if (st == SQ_OK) next_start = P->he_next[first];
            } else if (sides == 3 && c + 1 == cols) {
                st = sq_metapolygon_glue_polygon(P, cur, 3, 0, NULL, &first, &last, err);
            } else {
                st = sq_metapolygon_glue_polygon(P, cur, 2, 1, NULL, &first, &last, err);
            }
            if (st != SQ_OK) return st;
            cur = last; /* enters grid point (r, c+1): the next cell's notch */
        }
        row_start = next_start;
    }
    return SQ_OK;
}

/* A regular meta-4-gon (Def. 5.1 with no irregular face). */
sq_status sq_metapolygon_make_grid(sq_metapolygon *P, uint32_t rows, uint32_t cols,
                                   sq_error *err)
{
    if (rows == 0 || cols == 0)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "grid size %ux%u: both must be positive", rows,
                            cols);
    if (P->nf != 0)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "make_grid needs an empty metapolygon");
    sq_status st = sq_metapolygon_add_polygon(P, 4, NULL, err);
    /* a strip of cols quads: cols-1 layers on one edge of the first quad */
    if (st == SQ_OK) st = sq_metapolygon_glue_grid(P, P->bnd_he, cols - 1, 1, 1, err);
    if (st == SQ_OK && rows > 1) {
        /* rows-1 layers on a long side of the strip */
        uint32_t he[4], dist[4];
        if (sq_metapolygon_nonflat(P, 4, NULL, he, dist) != 4) {
            sq_metapolygon_free(P);
            return sq_error_set(err, SQ_ERR_INTERNAL, "a strip of quads is not a meta-4-gon");
        }
        uint32_t s = 0;
        while (s < 4 && dist[s] != cols) s++;
        assert(s < 4);
        st = sq_metapolygon_glue_grid(P, he[s], rows - 1, cols, 1, err);
    }
    if (st != SQ_OK) sq_metapolygon_free(P);
    return st;
}
