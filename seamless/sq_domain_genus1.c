/* seamquad: the genus-1 domain. Not built yet: reported as unsupported. */
#include "sq_domain_internal.h"

sq_status sq_domain_build_genus1(const uint32_t *irr, uint32_t n, const sq_domain_options *opt,
                                 sq_domain *D, sq_error *err)
{
    (void)irr, (void)n, (void)opt, (void)D;
    return sq_error_set(err, SQ_ERR_ARGUMENT,
                        "genus 1 needs several pieces (seed 6.2, 6.5), which this version does "
                        "not build yet; genus >= 2 is supported");
}
