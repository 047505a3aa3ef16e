/* The quad mesh as an OBJ file (sq_extract.h). */
#include <stdlib.h>

#include "sq_extract.h"
#include "sq_io.h"

sq_status sq_quad_mesh_write_obj(const char *path, const sq_quad_mesh *Q, sq_error *err)
{
    uint32_t *off = malloc(((size_t)Q->nq + 1) * sizeof *off);
    if (!off) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
    for (uint32_t f = 0; f <= Q->nq; f++) off[f] = 4 * f;
    sq_status st = sq_write_obj(path, Q->nv, Q->pos, Q->nq, off, Q->quad, 0, NULL, NULL, err);
    free(off);
    return st;
}
