/* seamquad: writing computed cones (sq_cross_field.h). Both formats are the
 * ones sq_cones_read accepts (core/sq_cones.h, docs/cones.md). */
#include "sq_cross_field.h"

#include <stdio.h>

#include "sq_cones.h"
#include "sq_io.h"

sq_status sq_cones_from_field_write(const char *path, uint32_t nv, const int32_t *valence,
                                    int list, sq_error *err)
{
    if (!path || !valence)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "cone writer: NULL argument");
    const double half_pi = 1.57079632679489661923;
    sq_atomic_file af;
    sq_status st = sq_atomic_open(&af, path, err);
    if (st) return st;
    FILE *fp = af.fp;
    int bad = 0;
    if (list) {
        uint32_t n = 0;
        for (uint32_t v = 0; v < nv; v++) n += valence[v] != 4;
        bad |= fprintf(fp, "# seamquad cones: %u cones on %u vertices (VERTEX VALENCE, 0-based)\n",
                       n, nv) < 0;
        for (uint32_t v = 0; v < nv && !bad; v++)
            if (valence[v] != 4) bad |= fprintf(fp, "%u %d\n", v, (int)valence[v]) < 0;
    } else {
        for (uint32_t v = 0; v < nv && !bad; v++)
            bad |= fprintf(fp, "%.17g\n", (double)valence[v] * half_pi) < 0;
    }
    if (bad || ferror(fp)) {
        sq_atomic_abort(&af);
        return sq_error_set(err, SQ_ERR_IO, "%s: write failed", path);
    }
    return sq_atomic_commit(&af, err);
}
