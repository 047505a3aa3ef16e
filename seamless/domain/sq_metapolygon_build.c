/* seamquad: metapolygon with prescribed valences, seed 5.2 (Prop. 5.1):
 * Q_(0) = empty, Q_(i) = E(Q_(i-1), l_(i-1)).
 *
 * The glue edge of every step is an explicit input: an array entry, else a
 * caller's chooser (seed 9.2, Algorithm 1, lines 3-5: embed Q_(i), pick the
 * boundary edge closest to the next singularity), else the default of seed
 * 5.3 (sq_metapolygon_default_glue_edge). */
#include "sq_metapolygon.h"

#include <string.h>

#include "sq_valence_order.h"

/* Prefixes err's message with the build step, keeping its code. */
static sq_status at_step(sq_error *err, sq_status st, uint32_t step, uint32_t valence)
{
    if (err) {
        char msg[SQ_ERROR_MSG_MAX];
        memcpy(msg, err->msg, sizeof msg);
        msg[sizeof msg - 1] = '\0';
        sq_error_set(err, st, "metapolygon build, step %u (valence %u): %s", step, valence, msg);
    }
    return st;
}

sq_status sq_metapolygon_build(sq_metapolygon *P, const uint32_t *valences, uint32_t n,
                               const sq_build_options *opt, sq_build_stats *stats,
                               sq_error *err)
{
    if (stats) memset(stats, 0, sizeof *stats);
    if (P->nf != 0 || P->nv != 0)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "metapolygon build needs an empty metapolygon (Q_(0) = empty)");
    sq_status st = sq_valence_check_sequence(valences, n, NULL, err);
    if (st != SQ_OK) return st;
    if (opt && opt->glue_he && n > 0 && opt->glue_he[0] != SQ_NONE)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "glue edge %u given for step 0, where the metapolygon is empty",
                            opt->glue_he[0]);
    uint64_t q2 = 0, q3 = 0;
    for (uint32_t s = 0; s < n; s++) {
        uint32_t h = SQ_NONE;
        if (s > 0 && opt) {
            if (opt->glue_he) h = opt->glue_he[s];
            if (h == SQ_NONE && opt->chooser) {
                st = opt->chooser(opt->chooser_user, P, s, valences[s], &h, err);
                if (st != SQ_OK) return at_step(err, st, s, valences[s]);
            }
        }
        sq_extend_stats es;
        st = sq_metapolygon_extend(P, valences[s], h, &es, err);
        if (st != SQ_OK) return at_step(err, st, s, valences[s]);
        q2 += es.quads_step2;
        q3 += es.quads_step3;
    }
    if (stats) {
        stats->quads = sq_metapolygon_count_quads(P);
        stats->quads_step2 = q2;
        stats->quads_step3 = q3;
        stats->corners = sq_metapolygon_count_corners(P);
    }
    return SQ_OK;
}
