/* seamquad: integer arc lengths of a T-mesh by min-cost flows on the double
 * cover of its bi-directed constraint graph (docs/quantize_lengths.md).
 *
 * The constraint graph: face f has a u-node 2f (sides 0 and 2) and a v-node
 * 2f+1 (sides 1 and 3). An arc's occurrence on side 0 or 3 is an end of sign
 * +1 at that node, on side 2 or 1 an end of sign -1, and the constraints say
 * that at every node the signed sum of the lengths of its ends is 0.
 *
 * The double cover: node x becomes x+ (2x) and x- (2x+1). An end of sign +1
 * at x enters x+ and leaves x-, one of sign -1 enters x- and leaves x+. Arc a
 * with first end (u, su) and second end (v, sv) becomes the two ordinary
 * arcs e1 = out(u) -> in(v) and e2 = out(v) -> in(u), and L_a = f(e1) +
 * f(e2). For any circulation f on the cover, the signed sum at x equals
 * (inflow - outflow at x+) - (inflow - outflow at x-) = 0, so every integral
 * circulation gives exact integer lengths.
 *
 * Costs: c_a(L) = W_a |L - t_a| interpolated linearly between the integers
 * (equal to the true cost at every integer L), with nondecreasing unit
 * slopes sigma_a(j) = c_a(j+1) - c_a(j). Two ways of putting it on the two
 * copies of an arc:
 *
 *  - the relaxation: both copies cost c_a(F) on their flows F, and
 *    L_a = (F(e1) + F(e2)) / 2. The symmetric lift F(e1) = F(e2) = L of any real solution
 *    costs 2 c_a(L) at integers and c_a(L) + c_a(L+1) at L + 1/2, and by
 *    convexity no cover flow with the same L costs less, so the cover's
 *    optimum is the relaxation's optimum over real lengths, reached at a
 *    half-integral point: a lower bound for every integer solution, and the
 *    answer where it is integral;
 *  - the split: e1 gets the steps j = 2x (x >= ceil(m/2)) and e2 the steps
 *    j = 2y+1 (y >= floor(m/2)); their merged slopes are exactly sigma_a(m),
 *    sigma_a(m+1), ..., so the cheapest split of L >= m costs c_a(L) -
 *    c_a(m) and f(e1) + f(e2) >= m always. That cheapest split is
 *    f(e1) = ceil(L/2), f(e2) = floor(L/2); it is a circulation when the
 *    arcs of odd L are oriented (first -> second) so that every node has as
 *    many of them in as out. The rounds orient the arcs that way around the
 *    current solution and solve again: a solve costs at most its start (the
 *    start's lift is feasible), which is how the method gets past the parity
 *    obstacles of bi-directed flows.
 *
 * A convex cost on a cover arc is a bundle of parallel network arcs: the
 * steps of slope -W (with the arc's lower bound), at most one fractional
 * step, and an uncapacitated arc of slope +W. */
#include "sq_tmesh_lengths.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sq_mcf.h"

/* Integer cost of one unit of deviation for the largest weight: the costs
 * resolve weights and fractional targets to 2^-20 (about 1e-6). */
#define COST_UNIT 1048576.0

typedef struct model {
    const sq_tmesh_sides *T;
    uint32_t n_nodes;            /* bi-directed nodes: 2 n_faces */
    uint32_t *end_node;          /* 2 n_arcs: node of end e of arc a at [2a+e] */
    int8_t *end_sign;            /* 2 n_arcs: +1 or -1 */
    uint32_t *adj_off, *adj;     /* per node, its ends (2a+e), CSR */
    int64_t *W;                  /* n_arcs: integer weights */
    /* network scratch: at most 6 network arcs per T-mesh arc */
    uint32_t *tail, *head;
    int64_t *lower, *upper, *cost, *flow;
    uint32_t *owner;             /* network arc -> T-mesh arc */
    uint8_t *first;              /* n_arcs: end that is the "first" end */
    uint8_t *used;               /* n_arcs: scratch of the orientation */
    uint32_t *ptr, *rem;         /* n_nodes: scratch of the orientation */
    uint32_t net_arcs;           /* network arcs of the last build */
} model;

static void model_free(model *M)
{
    free(M->end_node);
    free(M->end_sign);
    free(M->adj_off);
    free(M->adj);
    free(M->W);
    free(M->tail);
    free(M->head);
    free(M->lower);
    free(M->upper);
    free(M->cost);
    free(M->flow);
    free(M->owner);
    free(M->first);
    free(M->used);
    free(M->ptr);
    free(M->rem);
}

static const char *const side_name[4] = {"bottom", "right", "top", "left"};

/* Checks T's structure, targets and weights and fills the arcs' ends. */
static sq_status model_init(model *M, const sq_tmesh_sides *T, sq_error *err)
{
    memset(M, 0, sizeof *M);
    M->T = T;
    if (!T) return sq_error_set(err, SQ_ERR_ARGUMENT, "T-mesh lengths: no T-mesh given");
    if (T->n_faces == 0 || T->n_arcs == 0)
        return sq_error_set(err, SQ_ERR_EMPTY, "T-mesh lengths: %u faces and %u arcs (need both)",
                            T->n_faces, T->n_arcs);
    if (T->n_faces > (UINT32_MAX - 1) / 8 || T->n_arcs > (UINT32_MAX - 1) / 8)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "T-mesh lengths: too large (%u faces, %u arcs)",
                            T->n_faces, T->n_arcs);
    if (!T->side_off || !T->side_arc || !T->target)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "T-mesh lengths: side_off, side_arc or target is NULL");
    if (T->min_length < 1 || (double)T->min_length > SQ_TMESH_MAX_LENGTH)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "T-mesh lengths: min_length %lld is not in 1 .. %.0f",
                            (long long)T->min_length, SQ_TMESH_MAX_LENGTH);
    uint32_t nf = T->n_faces, na = T->n_arcs;
    for (uint32_t a = 0; T->min_arc && a < na; a++)
        if ((double)T->min_arc[a] > SQ_TMESH_MAX_LENGTH)
            return sq_error_set(err, SQ_ERR_ARGUMENT, "T-mesh lengths: arc %u's minimum %lld is above %.0f", a,
                                (long long)T->min_arc[a], SQ_TMESH_MAX_LENGTH);
    if (T->side_off[0] != 0)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "T-mesh lengths: side_off[0] is %u, not 0", T->side_off[0]);
    for (uint32_t fs = 0; fs < 4 * nf; fs++) {
        if (T->side_off[fs + 1] <= T->side_off[fs])
            return sq_error_set(err, SQ_ERR_ARGUMENT, "T-mesh lengths: %s side %u of face %u has no arc",
                                side_name[fs & 3], fs & 3, fs / 4);
        if (T->side_off[fs + 1] > 2 * na)
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "T-mesh lengths: side %u of face %u ends at %u, past the 2 n_arcs = %u"
                                " arc occurrences", fs & 3, fs / 4, T->side_off[fs + 1], 2 * na);
    }
    if (T->side_off[4 * nf] != 2 * na)
        return sq_error_set(err, SQ_ERR_ARGUMENT,
                            "T-mesh lengths: the sides hold %u arc occurrences, not 2 n_arcs = %u",
                            T->side_off[4 * nf], 2 * na);
    for (uint32_t a = 0; a < na; a++) {
        double t = T->target[a];
        if (!isfinite(t) || t <= 0.0 || t > SQ_TMESH_MAX_LENGTH)
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "T-mesh lengths: arc %u has target %g (need finite, > 0, <= %.0f)", a, t,
                                SQ_TMESH_MAX_LENGTH);
        if (T->weight && (!isfinite(T->weight[a]) || T->weight[a] < 0.0))
            return sq_error_set(err, SQ_ERR_ARGUMENT, "T-mesh lengths: arc %u has weight %g (need finite, >= 0)",
                                a, T->weight[a]);
    }

    M->n_nodes = 2 * nf;
    M->end_node = malloc(2 * (size_t)na * sizeof *M->end_node);
    M->end_sign = malloc(2 * (size_t)na * sizeof *M->end_sign);
    uint32_t *face_side = malloc(2 * (size_t)na * sizeof *face_side);
    if (!M->end_node || !M->end_sign || !face_side) {
        free(face_side);
        return sq_error_set(err, SQ_ERR_NOMEM, "T-mesh lengths: out of memory (%u arcs)", na);
    }
    memset(M->end_sign, 0, 2 * (size_t)na);
    for (uint32_t fs = 0; fs < 4 * nf; fs++) {
        uint32_t f = fs / 4, s = fs & 3;
        for (uint32_t i = T->side_off[fs]; i < T->side_off[fs + 1]; i++) {
            uint32_t a = T->side_arc[i];
            if (a >= na) {
                free(face_side);
                return sq_error_set(err, SQ_ERR_INDEX, "T-mesh lengths: side %u of face %u names arc %u (of %u)",
                                    s, f, a, na);
            }
            uint32_t e = M->end_sign[2 * a] ? 1 : 0;
            if (e == 1 && M->end_sign[2 * a + 1]) {
                uint32_t f0 = face_side[2 * a] / 4, s0 = face_side[2 * a] & 3;
                uint32_t f1 = face_side[2 * a + 1] / 4, s1 = face_side[2 * a + 1] & 3;
                free(face_side);
                return sq_error_set(err, SQ_ERR_ARGUMENT,
                                    "T-mesh lengths: arc %u lies on more than two sides (side %u of face %u,"
                                    " side %u of face %u and side %u of face %u)", a, s0, f0, s1, f1, s, f);
            }
            M->end_node[2 * a + e] = 2 * f + (s & 1);
            M->end_sign[2 * a + e] = (s == 0 || s == 3) ? 1 : -1;
            face_side[2 * a + e] = fs;
        }
    }
    for (uint32_t a = 0; a < na; a++) {
        if (!M->end_sign[2 * a + 1]) {
            /* unreachable after the checks above (2 n_arcs occurrences, none
             * thrice), kept so a broken check cannot read an unset end */
            uint32_t fs = face_side[2 * a];
            int none = !M->end_sign[2 * a];
            free(face_side);
            if (none) return sq_error_set(err, SQ_ERR_ARGUMENT, "T-mesh lengths: arc %u lies on no side", a);
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "T-mesh lengths: arc %u lies on one side only (side %u of face %u)", a, fs & 3,
                                fs / 4);
        }
        if (face_side[2 * a] == face_side[2 * a + 1]) {
            uint32_t fs = face_side[2 * a];
            free(face_side);
            return sq_error_set(err, SQ_ERR_ARGUMENT,
                                "T-mesh lengths: arc %u lies twice on side %u of face %u, which forces"
                                " its length to 0", a, fs & 3, fs / 4);
        }
    }
    free(face_side);

    /* adjacency of the nodes (for the orientations) */
    M->adj_off = calloc((size_t)M->n_nodes + 1, sizeof *M->adj_off);
    M->adj = malloc(2 * (size_t)na * sizeof *M->adj);
    M->W = malloc((size_t)na * sizeof *M->W);
    size_t cap = 6 * (size_t)na;
    M->tail = malloc(cap * sizeof *M->tail);
    M->head = malloc(cap * sizeof *M->head);
    M->lower = malloc(cap * sizeof *M->lower);
    M->upper = malloc(cap * sizeof *M->upper);
    M->cost = malloc(cap * sizeof *M->cost);
    M->flow = malloc(cap * sizeof *M->flow);
    M->owner = malloc(cap * sizeof *M->owner);
    M->first = malloc(na);
    M->used = malloc(na);
    M->ptr = malloc((size_t)M->n_nodes * sizeof *M->ptr);
    M->rem = malloc((size_t)M->n_nodes * sizeof *M->rem);
    if (!M->adj_off || !M->adj || !M->W || !M->tail || !M->head || !M->lower || !M->upper || !M->cost ||
        !M->flow || !M->owner || !M->first || !M->used || !M->ptr || !M->rem)
        return sq_error_set(err, SQ_ERR_NOMEM, "T-mesh lengths: out of memory (%u arcs)", na);
    for (uint32_t i = 0; i < 2 * na; i++) M->adj_off[M->end_node[i] + 1]++;
    for (uint32_t x = 0; x < M->n_nodes; x++) M->adj_off[x + 1] += M->adj_off[x];
    memcpy(M->ptr, M->adj_off, (size_t)M->n_nodes * sizeof *M->ptr);
    for (uint32_t i = 0; i < 2 * na; i++) M->adj[M->ptr[M->end_node[i]]++] = i;

    /* integer weights: the largest weight costs COST_UNIT per unit */
    double wmax = 0.0;
    for (uint32_t a = 0; a < na; a++) wmax = fmax(wmax, T->weight ? T->weight[a] : 1.0);
    for (uint32_t a = 0; a < na; a++) {
        double w = T->weight ? T->weight[a] : 1.0;
        M->W[a] = wmax > 0.0 ? (int64_t)llround(w / wmax * COST_UNIT) : (int64_t)COST_UNIT;
    }
    return SQ_OK;
}

/* ---- orientation -------------------------------------------------------- */

/* Orients the arcs with sel[a] == want (sel NULL: all arcs) by walking
 * trails: first from the nodes of odd degree among them, then closed trails
 * from any node. Each trail leaves a node as often as it enters it except at
 * its two ends, so afterwards every node has |in - out| <= 1 among these
 * arcs, and in == out when all their degrees are even. first[a] is the end
 * the trail leaves by. */
static void orient(model *M, const uint8_t *sel, uint8_t want)
{
    uint32_t na = M->T->n_arcs;
    for (uint32_t a = 0; a < na; a++) M->used[a] = sel && sel[a] != want;
    memcpy(M->ptr, M->adj_off, (size_t)M->n_nodes * sizeof *M->ptr);
    for (uint32_t x = 0; x < M->n_nodes; x++) {
        uint32_t r = 0;
        for (uint32_t i = M->adj_off[x]; i < M->adj_off[x + 1]; i++) r += !M->used[M->adj[i] / 2];
        M->rem[x] = r;
    }
    for (int pass = 0; pass < 2; pass++) {
        for (uint32_t start = 0; start < M->n_nodes; start++) {
            while (M->rem[start] && (pass == 1 || (M->rem[start] & 1))) {
                uint32_t x = start;
                for (;;) {
                    uint32_t *p = &M->ptr[x];
                    while (*p < M->adj_off[x + 1] && M->used[M->adj[*p] / 2]) (*p)++;
                    if (*p == M->adj_off[x + 1]) break;
                    uint32_t end = M->adj[*p], a = end / 2;
                    M->used[a] = 1;
                    M->first[a] = (uint8_t)(end & 1);
                    uint32_t y = M->end_node[end ^ 1];
                    M->rem[x]--;
                    M->rem[y]--;
                    x = y;
                }
            }
        }
    }
}

/* ---- the network -------------------------------------------------------- */

/* The convex cost of one cover arc on flows F >= lo: n_neg unit steps of
 * slope -W, then (when has_frac) one step of slope frac, then slope +W. */
typedef struct piecewise {
    int64_t lo, n_neg, frac;
    int has_frac;
} piecewise;

static void add_net_arc(model *M, uint32_t a, uint32_t tail, uint32_t head, int64_t lo, int64_t up, int64_t c)
{
    uint32_t k = M->net_arcs++;
    M->tail[k] = tail;
    M->head[k] = head;
    M->lower[k] = lo;
    M->upper[k] = up;
    M->cost[k] = c;
    M->owner[k] = a;
}

static void add_cover_arc(model *M, uint32_t a, uint32_t tail, uint32_t head, piecewise h)
{
    int64_t W = M->W[a];
    if (h.lo + h.n_neg > 0) add_net_arc(M, a, tail, head, h.lo, h.lo + h.n_neg, -W);
    if (h.has_frac) add_net_arc(M, a, tail, head, 0, 1, h.frac);
    add_net_arc(M, a, tail, head, 0, SQ_MCF_INF, W);
}

static uint32_t cover_in(uint32_t x, int s) { return s > 0 ? 2 * x : 2 * x + 1; }
static uint32_t cover_out(uint32_t x, int s) { return s > 0 ? 2 * x + 1 : 2 * x; }

/* The cover arc of L-steps j = 2x + parity (x >= lo): slope -W for
 * j + 1 <= t, +W for j >= t, and W (2j + 1 - 2t) for the step j = floor(t)
 * when t is not an integer. */
static piecewise split_cost(int64_t W, double t, int64_t lo, int parity)
{
    piecewise h = {lo, 0, 0, 0};
    int64_t xmax = (int64_t)floor((t - 1.0 - parity) / 2.0);  /* last x with 2x+parity+1 <= t */
    h.n_neg = xmax >= lo ? xmax - lo + 1 : 0;
    double k = floor(t);
    if (k != t && ((int64_t)k - parity) % 2 == 0 && ((int64_t)k - parity) / 2 >= lo) {
        h.has_frac = 1;
        h.frac = (int64_t)llround((double)W * (2.0 * k + 1.0 - 2.0 * t));
    }
    return h;
}

/* The cover arc of the relaxation: cost W |F - t| interpolated at the
 * integers on flows F >= lo, where L = (F1 + F2) / 2. The lift F1 = F2 = L
 * of an integer L costs 2 c(L), and F1 + F2 = 2L + 1 costs c(L) + c(L+1):
 * twice the interpolated cost of L + 1/2. */
static piecewise relaxed_cost(int64_t W, double t, int64_t lo)
{
    piecewise h = {lo, 0, 0, 0};
    double k = floor(t);
    h.n_neg = (int64_t)k > lo ? (int64_t)k - lo : 0;
    if (k != t && (int64_t)k >= lo) {
        h.has_frac = 1;
        h.frac = (int64_t)llround((double)W * (2.0 * k + 1.0 - 2.0 * t));
    }
    return h;
}

/* The smallest length allowed on arc a. */
static int64_t arc_min(const sq_tmesh_sides *T, uint32_t a)
{
    int64_t m = T->min_length;
    if (T->min_arc && T->min_arc[a] > m) m = T->min_arc[a];
    return m;
}

/* Builds the cover network for targets t with the current orientation and
 * solves it. Split costs of the integer problem: L[a] = f(e1) + f(e2).
 * relaxed: the relaxation's costs, and Lr[a] = (f(e1) + f(e2)) / 2. */
static sq_status solve_cover(model *M, const double *t, int relaxed, int64_t *L, double *Lr, sq_error *err)
{
    const sq_tmesh_sides *T = M->T;
    M->net_arcs = 0;
    for (uint32_t a = 0; a < T->n_arcs; a++) {
        int64_t m = arc_min(T, a);
        uint32_t i = M->first[a], j = i ^ 1;
        uint32_t u = M->end_node[2 * a + i], v = M->end_node[2 * a + j];
        int su = M->end_sign[2 * a + i], sv = M->end_sign[2 * a + j];
        piecewise h1, h2;
        if (relaxed) {
            h1 = relaxed_cost(M->W[a], t[a], m);
            h2 = h1;
        } else {
            h1 = split_cost(M->W[a], t[a], (m + 1) / 2, 0);
            h2 = split_cost(M->W[a], t[a], m / 2, 1);
        }
        add_cover_arc(M, a, cover_out(u, su), cover_in(v, sv), h1);
        add_cover_arc(M, a, cover_out(v, sv), cover_in(u, su), h2);
    }
    sq_mcf_problem P = {
        .method = SQ_MCF_CAPACITY_SCALING,
        .n_nodes = 2 * M->n_nodes,
        .n_arcs = M->net_arcs,
        .supply = NULL,
        .tail = M->tail,
        .head = M->head,
        .lower = M->lower,
        .upper = M->upper,
        .cost = M->cost,
    };
    sq_mcf_status st = sq_mcf_solve(&P, M->flow, NULL);
    if (st == SQ_MCF_INFEASIBLE)
        return sq_error_set(err, SQ_ERR_UNREALIZABLE,
                            "T-mesh lengths: no lengths >= %lld satisfy the T-mesh's %u faces' constraints",
                            (long long)T->min_length, T->n_faces);
    if (st == SQ_MCF_NOMEM)
        return sq_error_set(err, SQ_ERR_NOMEM, "T-mesh lengths: out of memory in the min-cost flow (%u arcs)",
                            M->net_arcs);
    if (st != SQ_MCF_OPTIMAL)
        return sq_error_set(err, SQ_ERR_INTERNAL, "T-mesh lengths: the min-cost flow returned '%s'",
                            sq_mcf_status_name(st));
    if (L) memset(L, 0, (size_t)T->n_arcs * sizeof *L);
    if (Lr) memset(Lr, 0, (size_t)T->n_arcs * sizeof *Lr);
    for (uint32_t k = 0; k < M->net_arcs; k++) {
        if (L) L[M->owner[k]] += M->flow[k];
        if (Lr) Lr[M->owner[k]] += (double)M->flow[k];
    }
    if (Lr)
        for (uint32_t a = 0; a < T->n_arcs; a++) Lr[a] /= 2.0;
    return SQ_OK;
}

/* ---- evaluation --------------------------------------------------------- */

/* The integer model's cost of length L on arc a: sum of the slopes of the
 * steps m .. L-1 (what the cover's cheapest split of L costs). */
static double model_cost(int64_t W, double t, int64_t m, int64_t L)
{
    double ct = ceil(t), k = floor(t);
    double last_neg = k - 1.0;  /* steps j with j + 1 <= t have slope -W */
    double n_neg = fmax(0.0, fmin((double)L - 1.0, last_neg) - (double)m + 1.0);
    double n_pos = fmax(0.0, (double)L - 1.0 - fmax((double)m, ct) + 1.0);
    double c = (double)W * (n_pos - n_neg);
    if (k != t && k >= (double)m && k <= (double)L - 1.0) c += (double)llround((double)W * (2.0 * k + 1.0 - 2.0 * t));
    return c;
}

static double total_model_cost(const model *M, const double *t, const int64_t *L)
{
    double c = 0.0;
    for (uint32_t a = 0; a < M->T->n_arcs; a++) c += model_cost(M->W[a], t[a], arc_min(M->T, a), L[a]);
    return c;
}

static double real_cost(const sq_tmesh_sides *T, const double *t, const int64_t *L, const double *Lr)
{
    double c = 0.0;
    for (uint32_t a = 0; a < T->n_arcs; a++) {
        double w = T->weight ? T->weight[a] : 1.0;
        c += w * fabs((L ? (double)L[a] : Lr[a]) - t[a]);
    }
    return c;
}

static int64_t side_sum(const sq_tmesh_sides *T, uint32_t f, uint32_t s, const int64_t *L)
{
    int64_t sum = 0;
    for (uint32_t i = T->side_off[4 * f + s]; i < T->side_off[4 * f + s + 1]; i++) sum += L[T->side_arc[i]];
    return sum;
}

/* 0 when L meets every constraint; otherwise 1 with *bad_face (or
 * *bad_arc when an arc is below min_length, *bad_face = UINT32_MAX). */
static int violates(const sq_tmesh_sides *T, const int64_t *L, uint32_t *bad_face, uint32_t *bad_arc)
{
    for (uint32_t a = 0; a < T->n_arcs; a++)
        if (L[a] < arc_min(T, a)) {
            *bad_face = UINT32_MAX;
            *bad_arc = a;
            return 1;
        }
    for (uint32_t f = 0; f < T->n_faces; f++)
        if (side_sum(T, f, 0, L) != side_sum(T, f, 2, L) || side_sum(T, f, 1, L) != side_sum(T, f, 3, L)) {
            *bad_face = f;
            return 1;
        }
    return 0;
}

static double quad_count(const sq_tmesh_sides *T, const int64_t *L)
{
    double q = 0.0;
    for (uint32_t f = 0; f < T->n_faces; f++) q += (double)side_sum(T, f, 0, L) * (double)side_sum(T, f, 1, L);
    return q;
}

/* ---- the solver --------------------------------------------------------- */

/* c_a interpolated linearly between the integers (real weights). */
static double interpolated_cost(double w, double t, double L)
{
    double k = floor(L), c0 = w * fabs(k - t);
    return L == k ? c0 : c0 + (L - k) * (w * fabs(k + 1.0 - t) - c0);
}

/* Lengths for targets t (validated like T->target):
 *  1. the relaxation (relaxed_cost), whose cover optimum is exactly the
 *     optimum over real lengths of the costs interpolated between the
 *     integers, at a half-integral point L*. Its cost is a lower bound for every integer
 *     solution; where L* is integral it is the answer, and optimal;
 *  2. otherwise the arcs are oriented around the parity of L* rounded
 *     down, and the split costs are solved;
 *  3. rounds orient the arcs of odd length as closed trails (their degrees
 *     are even at every node, since the signed sum of the lengths there is
 *     0) and the others as balanced trails, and solve again, until the model
 *     cost stops falling; unless that reached the bound, 2. and 3. again
 *     from L* rounded up, and the cheaper of the two is kept;
 *  4. plain rounding replaces the result where it is valid and cheaper. */
static sq_status solve_lengths(model *M, const double *t, int64_t *length, sq_tmesh_lengths_stats *st,
                               sq_error *err)
{
    const sq_tmesh_sides *T = M->T;
    uint32_t na = T->n_arcs;
    int64_t *next = calloc(na, sizeof *next), *cur = calloc(na, sizeof *cur);
    uint8_t *odd = malloc(na);
    double *half = malloc((size_t)na * sizeof *half);
    if (!next || !cur || !odd || !half) {
        free(next);
        free(cur);
        free(odd);
        free(half);
        return sq_error_set(err, SQ_ERR_NOMEM, "T-mesh lengths: out of memory (%u arcs)", na);
    }
    uint32_t solves = 0, improvements = 0, half_arcs = 0;
    double bound = 0.0;
    /* 1. the relaxation (no orientation: both copies cost the same) */
    memset(M->first, 0, na);
    sq_status s = solve_cover(M, t, 1, NULL, half, err);
    solves++;
    if (s == SQ_OK) {
        for (uint32_t a = 0; a < na; a++) {
            double w = T->weight ? T->weight[a] : 1.0;
            bound += interpolated_cost(w, t[a], half[a]);
            half_arcs += floor(half[a]) != half[a];
            length[a] = (int64_t)half[a];  /* the answer when no arc is half */
        }
    }
    /* 2. and 3., from the parity of L* rounded down, then up */
    double best = INFINITY;
    for (int start = 0; s == SQ_OK && half_arcs && start < 2; start++) {
        for (uint32_t a = 0; a < na; a++) odd[a] = (uint8_t)((int64_t)(start ? ceil(half[a]) : floor(half[a])) & 1);
        orient(M, odd, 1);
        orient(M, odd, 0);
        s = solve_cover(M, t, 0, cur, NULL, err);
        solves++;
        double cost = s == SQ_OK ? total_model_cost(M, t, cur) : 0.0;
        for (uint32_t round = 0; s == SQ_OK && round < SQ_TMESH_MAX_ROUNDS; round++) {
            for (uint32_t a = 0; a < na; a++) odd[a] = (uint8_t)(cur[a] & 1);
            orient(M, odd, 1);
            orient(M, odd, 0);
            s = solve_cover(M, t, 0, next, NULL, err);
            solves++;
            if (s != SQ_OK) break;
            double c = total_model_cost(M, t, next);
            if (!(c < cost)) break;
            cost = c;
            improvements++;
            memcpy(cur, next, (size_t)na * sizeof *next);
        }
        if (s == SQ_OK && cost < best) {
            best = cost;
            memcpy(length, cur, (size_t)na * sizeof *cur);
        }
        /* at the bound: optimal, no second start needed */
        if (s == SQ_OK && real_cost(T, t, length, NULL) <= bound + 1e-9 * (1.0 + bound)) break;
    }
    /* 4. plain rounding */
    uint32_t bad_face = 0, bad_arc = 0;
    for (uint32_t a = 0; a < na; a++) {
        int64_t v = (int64_t)llround(t[a]);
        next[a] = v < arc_min(T, a) ? arc_min(T, a) : v;
    }
    int rounding_feasible = !violates(T, next, &bad_face, &bad_arc);
    double rounding_cost = real_cost(T, t, next, NULL);
    if (s == SQ_OK && rounding_feasible && rounding_cost < real_cost(T, t, length, NULL))
        memcpy(length, next, (size_t)na * sizeof *next);
    free(next);
    free(cur);
    free(odd);
    free(half);
    if (s != SQ_OK) return s;

    if (violates(T, length, &bad_face, &bad_arc)) {
        if (bad_face == UINT32_MAX)
            return sq_error_set(err, SQ_ERR_INTERNAL, "T-mesh lengths: arc %u got length %lld < its minimum %lld",
                                bad_arc, (long long)length[bad_arc], (long long)arc_min(T, bad_arc));
        return sq_error_set(err, SQ_ERR_INTERNAL,
                            "T-mesh lengths: face %u's opposite sides differ (%lld/%lld, %lld/%lld)", bad_face,
                            (long long)side_sum(T, bad_face, 0, length), (long long)side_sum(T, bad_face, 2, length),
                            (long long)side_sum(T, bad_face, 1, length), (long long)side_sum(T, bad_face, 3, length));
    }
    if (st) {
        st->cost = real_cost(T, t, length, NULL);
        st->lower_bound = bound;
        st->half_arcs = half_arcs;
        st->quads = quad_count(T, length);
        st->solves += solves;
        st->improvements += improvements;
        st->network_nodes = 2 * M->n_nodes;
        st->network_arcs = M->net_arcs;
        st->rounding_cost = rounding_cost;
        st->rounding_feasible = rounding_feasible;
    }
    return SQ_OK;
}

sq_status sq_tmesh_lengths(const sq_tmesh_sides *T, int64_t *length, sq_tmesh_lengths_stats *stats, sq_error *err)
{
    if (stats) memset(stats, 0, sizeof *stats);
    if (!length) return sq_error_set(err, SQ_ERR_ARGUMENT, "T-mesh lengths: no output array");
    model M;
    sq_status s = model_init(&M, T, err);
    if (s == SQ_OK) s = solve_lengths(&M, T->target, length, stats, err);
    model_free(&M);
    if (s == SQ_OK) sq_error_clear(err);
    return s;
}

/* ---- a target quad count ------------------------------------------------ */

/* See sq_tmesh_lengths_for_quads: the spread of the second search's
 * per-arc factors, and the factor's u in [-1, 1] from the arc's index (a
 * multiplicative hash: fixed, so the result is reproducible). */
#define JITTER 0.04

static double jitter(uint32_t a)
{
    uint32_t h = (a + 1) * 2654435761u;
    h ^= h >> 15;
    h *= 2246822519u;
    h ^= h >> 13;
    return (double)h / 2147483647.5 - 1.0;
}

sq_status sq_tmesh_lengths_for_quads(const sq_tmesh_sides *T, double n_quads, int64_t *length,
                                     sq_tmesh_lengths_stats *stats, sq_error *err)
{
    sq_tmesh_lengths_stats local;
    if (!stats) stats = &local;
    memset(stats, 0, sizeof *stats);
    if (!length) return sq_error_set(err, SQ_ERR_ARGUMENT, "T-mesh lengths: no output array");
    if (!isfinite(n_quads) || n_quads < 1.0)
        return sq_error_set(err, SQ_ERR_ARGUMENT, "T-mesh lengths: quad count %g is not finite and >= 1", n_quads);
    model M;
    sq_status s = model_init(&M, T, err);
    uint32_t na = T ? T->n_arcs : 0;
    double *t = NULL;
    int64_t *trial = NULL;
    if (s == SQ_OK) {
        t = malloc((size_t)na * sizeof *t);
        trial = malloc((size_t)na * sizeof *trial);
        if (!t || !trial) s = sq_error_set(err, SQ_ERR_NOMEM, "T-mesh lengths: out of memory (%u arcs)", na);
    }
    /* the fewest quads: every target far below min_length (all slopes +W) */
    sq_tmesh_lengths_stats sub;
    if (s == SQ_OK) {
        for (uint32_t a = 0; a < na; a++) t[a] = 1e-6;
        memset(&sub, 0, sizeof sub);
        s = solve_lengths(&M, t, length, &sub, err);
        /* reported against the caller's targets; no bound or rounding */
        *stats = sub;
        stats->min_quads = sub.quads;
        stats->cost = real_cost(T, T->target, length, NULL);
        stats->lower_bound = 0.0;
        stats->half_arcs = 0;
        stats->rounding_cost = 0.0;
        stats->rounding_feasible = 0;
        stats->target_scale = 0.0;
    }
    if (s == SQ_OK && n_quads > stats->min_quads) {
        /* the targets' own area, a first guess of how the count scales */
        double area = 0.0;
        for (uint32_t f = 0; f < T->n_faces; f++) {
            double s0 = 0.0, s1 = 0.0;
            for (uint32_t i = T->side_off[4 * f]; i < T->side_off[4 * f + 1]; i++) s0 += T->target[T->side_arc[i]];
            for (uint32_t i = T->side_off[4 * f + 1]; i < T->side_off[4 * f + 2]; i++)
                s1 += T->target[T->side_arc[i]];
            area += s0 * s1;
        }
        double scale0 = sqrt(n_quads / area), best_err = fabs(stats->quads - n_quads);
        double tmax = 0.0;
        for (uint32_t a = 0; a < na; a++) tmax = fmax(tmax, T->target[a]);
        /* The count jumps with the rounding: once a scale below and one
         * above the request are known, bisect between them. Where many
         * arcs have the same target (a symmetric layout: the cube's), they
         * all round together and the count jumps past the request at one
         * scale; a second search then gives every arc its own factor
         * 1 + JITTER u (u in [-1, 1], fixed by the arc's index), which
         * spreads their thresholds so that the count rises in small steps. */
        for (int pass = 0; pass < 2 && s == SQ_OK && best_err > 0.05 * n_quads; pass++) {
            double scale = scale0, below = 0.0, above = 0.0;
            for (int iter = 0; iter < 16; iter++) {
                if (scale * tmax * (1 + JITTER) > SQ_TMESH_MAX_LENGTH) scale = SQ_TMESH_MAX_LENGTH / (tmax * (1 + JITTER));
                for (uint32_t a = 0; a < na; a++) t[a] = T->target[a] * scale * (pass ? 1.0 + JITTER * jitter(a) : 1.0);
                memset(&sub, 0, sizeof sub);
                s = solve_lengths(&M, t, trial, &sub, err);
                stats->solves += sub.solves;
                if (s != SQ_OK) break;
                double e = fabs(sub.quads - n_quads);
                if (e < best_err) {
                    best_err = e;
                    memcpy(length, trial, (size_t)na * sizeof *trial);
                    uint32_t solves = stats->solves;
                    double min_quads = stats->min_quads;
                    *stats = sub;
                    stats->solves = solves;
                    stats->min_quads = min_quads;
                    stats->target_scale = scale;
                }
                if (e <= 0.05 * n_quads || sub.quads <= 0.0) break;
                if (sub.quads < n_quads) below = scale;
                else above = scale;
                if (below > 0.0 && above > 0.0) scale = sqrt(below * above);
                else scale *= sqrt(n_quads / sub.quads);
            }
        }
    }
    free(t);
    free(trial);
    model_free(&M);
    if (s == SQ_OK) sq_error_clear(err);
    return s;
}
