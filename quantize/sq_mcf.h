/* seamquad: minimum-cost flow (LEMON's network simplex and scaling
 * algorithms behind a C interface; the only C++ of quantize/ is its adapter, adapter_lemon.cpp).
 *
 * A plain capacitated min-cost flow on a directed multigraph:
 *
 *   minimize  sum_a cost[a] * flow[a]
 *   subject to  lower[a] <= flow[a] <= upper[a]                 (every arc)
 *               sum_{a out of n} flow[a] - sum_{a into n} flow[a] = supply[n]
 *
 * Every datum is an integer, so an optimal flow returned is integral (all
 * three algorithms only add and subtract integer amounts along paths and
 * cycles). The caller builds
 * the network; the adapter only copies it into LEMON and the flows back, so
 * no modelling happens there (see docs/quantize_lengths.md).
 *
 * Limits: the supplies must sum to 0; |cost| * (total flow) and the node
 * count * max |cost| must fit in int64 (the caller keeps costs below 2^31
 * and flows below 2^31). Self-loops and parallel arcs are allowed. */
#ifndef SQ_MCF_H
#define SQ_MCF_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* An upper bound meaning "no capacity limit". */
#define SQ_MCF_INF INT64_MAX

typedef enum sq_mcf_status {
    SQ_MCF_OPTIMAL = 0,   /* flow[] is an optimal integral flow            */
    SQ_MCF_INFEASIBLE,    /* no flow meets the bounds and supplies         */
    SQ_MCF_UNBOUNDED,     /* a negative-cost cycle of unlimited capacity   */
                          /* (scaling methods: see sq_mcf_method)          */
    SQ_MCF_BAD_INPUT,     /* node index out of range, lower > upper,       */
                          /* supplies not summing to 0, NULL arrays,       */
                          /* unknown method                                */
    SQ_MCF_NOMEM          /* allocation failed                             */
} sq_mcf_status;

/* LEMON's algorithms; all return an optimal flow, their speed differs. */
typedef enum sq_mcf_method {
    SQ_MCF_NETWORK_SIMPLEX = 0,  /* primal network simplex, block search     */
    SQ_MCF_CAPACITY_SCALING,     /* successive shortest paths with capacity */
                                 /* scaling: far fewer steps than the       */
                                 /* simplex on mesh-like networks (the      */
                                 /* double cover of a T-mesh: 40x faster)   */
    SQ_MCF_COST_SCALING          /* push-relabel with cost scaling          */
} sq_mcf_method;
/* The two scaling methods report SQ_MCF_UNBOUNDED for any arc of negative
 * cost and infinite upper bound, even where the optimum is finite (LEMON
 * saturates such arcs first); give negative-cost arcs finite bounds. */

typedef struct sq_mcf_problem {
    uint32_t n_nodes, n_arcs;
    int method;                /* an sq_mcf_method (0: network simplex)       */
    const int64_t *supply;     /* n_nodes, or NULL for a circulation (all 0)  */
    const uint32_t *tail;      /* n_arcs: arc a goes from tail[a] ...         */
    const uint32_t *head;      /* n_arcs: ... to head[a]                      */
    const int64_t *lower;      /* n_arcs, or NULL for all 0                   */
    const int64_t *upper;      /* n_arcs, or NULL for all SQ_MCF_INF          */
    const int64_t *cost;       /* n_arcs: cost per unit of flow               */
} sq_mcf_problem;

/* Solves p. On SQ_MCF_OPTIMAL fills flow[0 .. n_arcs-1] (caller-owned) and,
 * when total_cost is not NULL, *total_cost = sum cost * flow; otherwise
 * flow and *total_cost are left unchanged. */
sq_mcf_status sq_mcf_solve(const sq_mcf_problem *p, int64_t *flow, int64_t *total_cost);

/* Short name of a status ("optimal", "infeasible", ...). */
const char *sq_mcf_status_name(sq_mcf_status s);

#ifdef __cplusplus
}
#endif
#endif
