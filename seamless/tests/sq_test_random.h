/* seamquad tests: seeded randomness and random admissible cone sets shared
 * by the property tests of seamless/ (include after cmocka.h). */
#ifndef SQ_TEST_RANDOM_H
#define SQ_TEST_RANDOM_H

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static uint64_t rng_state;

static inline uint64_t rng(void) /* splitmix64 */
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static inline uint32_t rnd(uint32_t n) { return (uint32_t)(rng() % n); }

/* SQ_LONG_TESTS=1 (anything but empty or 0) selects the long mode. */
static inline int long_mode(void)
{
    const char *s = getenv("SQ_LONG_TESTS");
    return s && *s && strcmp(s, "0");
}

/* A random multiset of valences (2..8, sometimes 22) with total excess
 * 8g - 8 (genus g >= 1), plus some cancelling 3/5 pairs. */
static inline uint32_t random_cones(uint32_t genus, int32_t *v, uint32_t cap)
{
    int64_t target = 8 * (int64_t)genus - 8, excess = 0;
    uint32_t n = 0;
    uint32_t pairs = rnd(4);
    for (uint32_t p = 0; p < pairs && n + 2 <= cap; p++) {
        v[n++] = 3;
        v[n++] = 5;
    }
    while (excess != target && n < cap) {
        int32_t k;
        if (excess < target) {
            int64_t room = target - excess;
            if (room >= 18 && rnd(20) == 0) k = 22;
            else k = 5 + (int32_t)rnd(room >= 4 ? 4 : (uint32_t)room);
        } else {
            k = (excess - target >= 2 && rnd(3) == 0) ? 2 : 3;
        }
        v[n++] = k;
        excess += k - 4;
    }
    assert_true(excess == target);
    return n;
}

#endif
