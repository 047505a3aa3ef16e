/* seamquad: side-pairing patterns (seed 6, 7; seamless-notes 1, 2, 6, 7).
 * See sq_pattern.h for the conventions. */
#include "sq_pattern.h"
#include "sq_union_find.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

#define SQ_PAT_NONE UINT32_MAX

void sq_pattern_init(sq_pattern *pat) { memset(pat, 0, sizeof *pat); }

void sq_pattern_free(sq_pattern *pat)
{
    if (!pat)
        return;
    free(pat->partner);
    free(pat->straight);
    memset(pat, 0, sizeof *pat);
}

sq_status sq_pattern_alloc(sq_pattern *pat, uint32_t k, sq_error *err)
{
    uint32_t *p = malloc((size_t)(k ? k : 1) * sizeof *p);
    uint8_t *s = calloc(k ? k : 1, 1);
    if (!p || !s) {
        free(p);
        free(s);
        return sq_error_set(err, SQ_ERR_NOMEM, "pattern: cannot allocate %u sides", k);
    }
    for (uint32_t i = 0; i < k; ++i)
        p[i] = SQ_PAT_NONE;
    sq_pattern_free(pat);
    pat->k = k;
    pat->partner = p;
    pat->straight = s;
    return SQ_OK;
}

sq_status sq_pattern_copy(sq_pattern *dst, const sq_pattern *src, sq_error *err)
{
    sq_status st = sq_pattern_alloc(dst, src->k, err);
    if (st != SQ_OK)
        return st;
    memcpy(dst->partner, src->partner, (size_t)src->k * sizeof *src->partner);
    if (src->straight)
        memcpy(dst->straight, src->straight, src->k);
    return SQ_OK;
}

sq_status sq_pattern_reversed(const sq_pattern *in, sq_pattern *out, sq_error *err)
{
    const uint32_t k = in->k;
    sq_status st = sq_pattern_alloc(out, k, err);
    if (st != SQ_OK)
        return st;
    for (uint32_t j = 0; j < k; ++j) {
        const uint32_t p = in->partner[k - 1 - j];
        out->partner[j] = p < k ? k - 1 - p : SQ_PAT_NONE;
        out->straight[j] = in->straight ? in->straight[(k - j) % k] : 0;
    }
    return SQ_OK;
}

/* ---- corner classes ---------------------------------------------------- */

/* Fills class_of (k entries) with class ids numbered by first corner;
 * parent is scratch of k entries. Returns the number of classes. */
static uint32_t classes_into(const sq_pattern *pat, uint32_t *parent, uint32_t *class_of)
{
    const uint32_t k = pat->k;
    for (uint32_t i = 0; i < k; ++i)
        parent[i] = i;
    for (uint32_t i = 0; i < k; ++i) {
        const uint32_t j = pat->partner[i];
        assert(j < k && pat->partner[j] == i);
        /* side i runs corner i -> i+1, side j runs corner j -> j+1, glued
         * reversed: the start of one is the end of the other. */
        sq_uf_union(parent, i, (j + 1) % k);
        sq_uf_union(parent, (i + 1) % k, j);
    }
    uint32_t n = 0;
    for (uint32_t i = 0; i < k; ++i) {
        const uint32_t r = sq_uf_find(parent, i);
        if (r == i)
            class_of[i] = n++;
        else
            class_of[i] = class_of[r]; /* r < i: roots are class minima */
    }
    return n;
}

uint32_t sq_pattern_corner_classes(const sq_pattern *pat, uint32_t *class_of)
{
    if (pat->k == 0)
        return 0;
    uint32_t *buf = malloc((size_t)pat->k * 2 * sizeof *buf);
    if (!buf)
        return 0;
    const uint32_t n = classes_into(pat, buf, buf + pat->k);
    if (class_of)
        memcpy(class_of, buf + pat->k, (size_t)pat->k * sizeof *buf);
    free(buf);
    return n;
}

/* ---- directions and the rank test -------------------------------------- */

uint32_t sq_pattern_side_direction(const sq_pattern *pat, uint32_t side)
{
    uint32_t t = 0;
    for (uint32_t c = 1; c <= side; ++c)
        if (!(pat->straight && pat->straight[c]))
            ++t;
    return t & 3u;
}

static const int64_t dir_x[4] = {1, 0, -1, 0};
static const int64_t dir_y[4] = {0, 1, 0, -1};

/* Fills dir (k entries) in one pass. */
static void directions(const sq_pattern *pat, uint32_t *dir)
{
    uint32_t t = 0;
    for (uint32_t i = 0; i < pat->k; ++i) {
        if (i > 0 && !(pat->straight && pat->straight[i]))
            ++t;
        dir[i] = t & 3u;
    }
}

static uint32_t rank_and_kinds(const sq_pattern *pat, sq_pattern_info *info)
{
    const uint32_t k = pat->k;
    uint32_t *dir = malloc((size_t)(k ? k : 1) * sizeof *dir);
    if (!dir)
        return 0;
    directions(pat, dir);
    int64_t ax = 0, ay = 0; /* first nonzero u_p */
    uint32_t rank = 0, tr = 0, ht = 0, qt = 0;
    for (uint32_t i = 0; i < k; ++i) {
        const uint32_t j = pat->partner[i];
        if (j < i)
            continue;
        const int64_t ux = dir_x[dir[i]] + dir_x[dir[j]];
        const int64_t uy = dir_y[dir[i]] + dir_y[dir[j]];
        const uint32_t diff = (dir[j] - dir[i]) & 3u;
        if (diff == 2)
            ++tr;
        else if (diff == 0)
            ++ht;
        else
            ++qt;
        if (ux == 0 && uy == 0)
            continue;
        if (rank == 0) {
            ax = ux;
            ay = uy;
            rank = 1;
        } else if (rank == 1 && ax * uy - ay * ux != 0) {
            rank = 2;
        }
    }
    free(dir);
    if (info) {
        info->rank = rank;
        info->translations = tr;
        info->half_turns = ht;
        info->quarter_turns = qt;
    }
    return rank;
}

uint32_t sq_pattern_rank(const sq_pattern *pat) { return rank_and_kinds(pat, NULL); }

void sq_pattern_closure(const sq_pattern *pat, const int64_t *length, int64_t *vx,
                        int64_t *vy)
{
    int64_t x = 0, y = 0;
    uint32_t t = 0;
    for (uint32_t i = 0; i < pat->k; ++i) {
        if (i > 0 && !(pat->straight && pat->straight[i]))
            ++t;
        x += length[i] * dir_x[t & 3u];
        y += length[i] * dir_y[t & 3u];
    }
    *vx = x;
    *vy = y;
}

/* ---- validation -------------------------------------------------------- */

sq_status sq_pattern_validate(const sq_pattern *pat, sq_pattern_info *info, sq_error *err)
{
    sq_pattern_info tmp;
    if (!info)
        info = &tmp;
    memset(info, 0, sizeof *info);
    const uint32_t k = pat->k;
    if (k < 2 || k % 2 != 0)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "pattern: %u sides; need an even number >= 2", k);
    if (!pat->partner)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "pattern: no partner array");
    for (uint32_t i = 0; i < k; ++i) {
        const uint32_t j = pat->partner[i];
        if (j >= k)
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "pattern: side %u has partner %u, out of range 0..%u", i, j,
                                k - 1);
        if (j == i)
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "pattern: side %u is paired with itself", i);
        if (pat->partner[j] != i)
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "pattern: side %u pairs with %u but side %u pairs with %u", i,
                                j, j, pat->partner[j]);
    }
    uint32_t *buf = malloc((size_t)k * 3 * sizeof *buf);
    if (!buf)
        return sq_error_set(err, SQ_ERR_NOMEM, "pattern: out of memory");
    uint32_t *class_of = buf + k, *angle = buf + 2 * k;
    const uint32_t V = classes_into(pat, buf, class_of);
    info->classes = V;
    rank_and_kinds(pat, info);
    /* angles in units of 90 degrees: 1 per right corner, 2 per straight */
    memset(angle, 0, (size_t)V * sizeof *angle);
    for (uint32_t c = 0; c < k; ++c)
        angle[class_of[c]] += (pat->straight && pat->straight[c]) ? 2u : 1u;
    sq_status st = SQ_OK;
    for (uint32_t v = 0; v < V && st == SQ_OK; ++v) {
        if (angle[v] != 4) {
            uint32_t first = 0, n = 0;
            for (uint32_t c = 0; c < k; ++c)
                if (class_of[c] == v) {
                    if (n == 0)
                        first = c;
                    ++n;
                }
            st = sq_error_set(err, SQ_ERR_ARGUMENT,
                              "pattern: branch point %u (corner %u and %u more) has total "
                              "angle %u x 90 degrees; a regular point needs 4 x 90 (seed 3, "
                              "condition (1))",
                              v, first, n - 1, angle[v]);
        }
    }
    free(buf);
    if (st != SQ_OK)
        return st;
    /* chi = V - k/2 + 1 = 2 - 2g */
    const int64_t twice_g = 1 + (int64_t)(k / 2) - (int64_t)V;
    if (twice_g < 0 || twice_g % 2 != 0)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "pattern: Euler characteristic V - E + F = %u - %u + 1 is odd or "
                            "above 2",
                            V, k / 2);
    info->genus = (uint32_t)(twice_g / 2);
    return SQ_OK;
}

/* ---- constructions ----------------------------------------------------- */

sq_status sq_pattern_torus(sq_pattern *pat, sq_error *err)
{
    sq_status st = sq_pattern_alloc(pat, 4, err);
    if (st != SQ_OK)
        return st;
    static const uint32_t p[4] = {2, 3, 0, 1};
    memcpy(pat->partner, p, sizeof p);
    return SQ_OK;
}

/* The handle insertions. Side a (partner q) becomes a1 a2 a3 and side q
 * becomes q3 q2 q1 (a_m glued to q_m). The new corners are X1 = a1|a2,
 * Y1 = a2|a3, Y2 = q3|q2, X2 = q2|q1; each rule lists the new sides put
 * into them, in order, with e~E and f~F paired. These are exactly the 48 of
 * the 840 placements of {e, E, f, F} into the four corners for which the
 * eight new corners form two classes of four (exhaustive search, recorded
 * in docs/padding.md). The new corners are only ever identified with each
 * other (the outer ends of a1, a3, q1, q3 are the old corners, with the old
 * identifications), so a rule that works once works on every pattern. */
static const char *const handle_rule[SQ_PATTERN_HANDLE_RULES][4] = {
    {"E", "e", "f", "F"},   {"E", "f", "e", "F"},   {"E", "F", "e", "f"},
    {"E", "e", "F", "f"},   {"EF", "ef", "", ""},   {"EF", "", "ef", ""},
    {"Ef", "eF", "", ""},   {"Ef", "", "eF", ""},   {"F", "e", "f", "E"},
    {"F", "f", "e", "E"},   {"F", "E", "f", "e"},   {"F", "f", "E", "e"},
    {"FE", "fe", "", ""},   {"FE", "", "fe", ""},   {"Fe", "fE", "", ""},
    {"Fe", "", "fE", ""},   {"e", "E", "f", "F"},   {"e", "f", "E", "F"},
    {"e", "E", "F", "f"},   {"e", "F", "E", "f"},   {"eF", "Ef", "", ""},
    {"eF", "", "Ef", ""},   {"ef", "EF", "", ""},   {"ef", "", "EF", ""},
    {"f", "F", "e", "E"},   {"f", "e", "F", "E"},   {"f", "E", "F", "e"},
    {"f", "F", "E", "e"},   {"fE", "Fe", "", ""},   {"fE", "", "Fe", ""},
    {"fe", "FE", "", ""},   {"fe", "", "FE", ""},   {"", "ef", "", "EF"},
    {"", "", "ef", "EF"},   {"", "eF", "", "Ef"},   {"", "", "eF", "Ef"},
    {"", "fe", "", "FE"},   {"", "", "fe", "FE"},   {"", "fE", "", "Fe"},
    {"", "", "fE", "Fe"},   {"", "Ef", "", "eF"},   {"", "", "Ef", "eF"},
    {"", "EF", "", "ef"},   {"", "", "EF", "ef"},   {"", "Fe", "", "fE"},
    {"", "", "Fe", "fE"},   {"", "FE", "", "fe"},   {"", "", "FE", "fe"},
};

static uint32_t new_side_code(char c)
{
    switch (c) {
    case 'e': return 0;
    case 'E': return 1;
    case 'f': return 2;
    default: assert(c == 'F'); return 3;
    }
}

sq_status sq_pattern_insert_handle(const sq_pattern *pat, uint32_t side, uint32_t rule,
                                   sq_pattern *out, sq_error *err)
{
    const uint32_t k = pat->k;
    if (out == pat)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "insert_handle: out must differ from pat");
    if (side >= k || rule >= SQ_PATTERN_HANDLE_RULES)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "insert_handle: side %u / rule %u out of range (%u sides, %u rules)",
                            side, rule, k, SQ_PATTERN_HANDLE_RULES);
    if (k > UINT32_MAX - 16)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "insert_handle: too many sides");
    for (uint32_t i = 0; pat->straight && i < k; ++i)
        if (pat->straight[i])
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "insert_handle: corner %u is straight; not supported", i);
    sq_status st = sq_pattern_validate(pat, NULL, err);
    if (st != SQ_OK)
        return st;
    const uint32_t a = side, q = pat->partner[side];
    const uint32_t k2 = k + 8;
    /* Old side i maps to position pos_old[i]; a -> a1 a2 a3 and q -> q3 q2 q1
     * occupy pos_sub[0][0..2] and pos_sub[1][0..2] (index m-1 for a_m / q_m). */
    uint32_t *pos_old = malloc((size_t)k * sizeof *pos_old);
    if (!pos_old)
        return sq_error_set(err, SQ_ERR_NOMEM, "insert_handle: out of memory");
    st = sq_pattern_alloc(out, k2, err);
    if (st != SQ_OK) {
        free(pos_old);
        return st;
    }
    uint32_t pos_sub[2][3], pos_new[4], n = 0;
    const char *const *r = handle_rule[rule];
    for (uint32_t i = 0; i < k; ++i) {
        pos_old[i] = n;
        if (i == a || i == q) {
            const int first = (i == a);
            const char *s1 = first ? r[0] : r[2]; /* X1 or Y2 */
            const char *s2 = first ? r[1] : r[3]; /* Y1 or X2 */
            uint32_t *ps = pos_sub[first ? 0 : 1];
            /* a: a1 [X1] a2 [Y1] a3;  q: q3 [Y2] q2 [X2] q1 */
            ps[first ? 0 : 2] = n++;
            for (const char *c = s1; *c; ++c)
                pos_new[new_side_code(*c)] = n++;
            ps[1] = n++;
            for (const char *c = s2; *c; ++c)
                pos_new[new_side_code(*c)] = n++;
            ps[first ? 2 : 0] = n++;
        } else {
            ++n;
        }
    }
    assert(n == k2);
    for (uint32_t i = 0; i < k; ++i)
        if (i != a && i != q)
            out->partner[pos_old[i]] = pos_old[pat->partner[i]];
    for (uint32_t m = 0; m < 3; ++m) {
        out->partner[pos_sub[0][m]] = pos_sub[1][m];
        out->partner[pos_sub[1][m]] = pos_sub[0][m];
    }
    out->partner[pos_new[0]] = pos_new[1];
    out->partner[pos_new[1]] = pos_new[0];
    out->partner[pos_new[2]] = pos_new[3];
    out->partner[pos_new[3]] = pos_new[2];
    free(pos_old);
    sq_pattern_info info;
    st = sq_pattern_validate(out, &info, err);
    if (st != SQ_OK)
        return sq_error_set(err, SQ_ERR_INTERNAL, "insert_handle: result invalid: %s",
                            err ? err->msg : "");
    return SQ_OK;
}

sq_status sq_pattern_canonical(uint32_t genus, sq_pattern *pat, sq_error *err)
{
    if (genus < 1)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "canonical pattern: genus %u; need >= 1 (genus 0 has no cut "
                            "disk pattern, seed 6.5)",
                            genus);
    if (genus > (UINT32_MAX - 8) / 8)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "canonical pattern: genus %u too large",
                            genus);
    sq_pattern tmp;
    sq_pattern_init(&tmp);
    sq_status st = sq_pattern_torus(pat, err);
    for (uint32_t g = 2; g <= genus && st == SQ_OK; ++g) {
        st = sq_pattern_insert_handle(pat, 0, g == 2 ? 4u : 0u, &tmp, err);
        if (st == SQ_OK) {
            sq_pattern swap = *pat;
            *pat = tmp;
            tmp = swap;
        }
    }
    sq_pattern_free(&tmp);
    if (st != SQ_OK)
        return st;
    sq_pattern_info info;
    st = sq_pattern_validate(pat, &info, err);
    if (st != SQ_OK)
        return st;
    if (info.genus != genus || (genus >= 2 && info.rank != 2))
        return sq_error_set(err, SQ_ERR_INTERNAL,
                            "canonical pattern: genus %u came out with genus %u, rank %u",
                            genus, info.genus, info.rank);
    return SQ_OK;
}

static uint64_t splitmix64(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

sq_status sq_pattern_random(uint32_t genus, uint64_t *state, sq_pattern *pat, sq_error *err)
{
    if (genus < 1 || genus > (UINT32_MAX - 8) / 8)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "random pattern: genus %u out of range",
                            genus);
    sq_pattern tmp;
    sq_pattern_init(&tmp);
    sq_status st = sq_pattern_torus(pat, err);
    for (uint32_t g = 2; g <= genus && st == SQ_OK; ++g) {
        const uint32_t side = (uint32_t)(splitmix64(state) % pat->k);
        const uint32_t rule = (uint32_t)(splitmix64(state) % SQ_PATTERN_HANDLE_RULES);
        st = sq_pattern_insert_handle(pat, side, rule, &tmp, err);
        if (st == SQ_OK) {
            sq_pattern swap = *pat;
            *pat = tmp;
            tmp = swap;
        }
    }
    if (st == SQ_OK) /* random cyclic relabelling: side i <- side i + r */
        st = sq_pattern_copy(&tmp, pat, err);
    if (st == SQ_OK) {
        const uint32_t k = pat->k, r = (uint32_t)(splitmix64(state) % k);
        for (uint32_t i = 0; i < k; ++i)
            pat->partner[i] = (tmp.partner[(i + r) % k] + k - r) % k;
    }
    sq_pattern_free(&tmp);
    return st;
}
