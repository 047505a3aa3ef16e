/* seamquad: pieces of the domain construction shared by sq_domain*.c. */
#ifndef SQ_DOMAIN_INTERNAL_H
#define SQ_DOMAIN_INTERNAL_H

#include "sq_domain.h"

/* Genus 0 (seed 6.5) and genus 1 (seed 6.2, several pieces) builders.
 * Called by sq_domain_build after the realizability check, with D
 * initialized, D->genus set, and the irregular valences (every entry != 4,
 * each >= 2) in irr[0..n-1]. They fill every field of D that
 * sq_domain_verify, sq_domain_glue and the outputs use (see sq_domain.h),
 * and leave D freed on failure is NOT required: the caller frees D. */
sq_status sq_domain_build_genus0(const uint32_t *irr, uint32_t n, const sq_domain_options *opt,
                                 sq_domain *D, sq_error *err);
sq_status sq_domain_build_genus1(const uint32_t *irr, uint32_t n, const sq_domain_options *opt,
                                 sq_domain *D, sq_error *err);

/* The construction order of n valences (seed 5.2; sq_domain.c): with
 * keep, val itself, checked admissible (seed 9.2: the caller's order);
 * else an admissible order of them. out: n entries. */
sq_status sq_domain_order(const uint32_t *val, uint32_t n, int keep, uint32_t *out, sq_error *err);

/* 1 if gluing all identified sides of D gives a simple closed quad mesh
 * (sq_domain.c). */
int sq_domain_glued_is_simple(const sq_domain *D);

#endif
