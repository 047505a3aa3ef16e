// seamquad: LEMON adapter (C++17). Copies the network of sq_mcf.h into a
// lemon::SmartDigraph, runs lemon::NetworkSimplex, CapacityScaling or
// CostScaling and copies the flows back.
// It checks the description (indices, bounds, supply sum) and translates
// LEMON's outcome; what the network means is decided by the C caller.
#include "sq_mcf.h"

#include <lemon/capacity_scaling.h>
#include <lemon/cost_scaling.h>
#include <lemon/network_simplex.h>
#include <lemon/smart_graph.h>

#include <cstdint>
#include <cstdlib>
#include <new>
#include <type_traits>
#include <vector>

namespace {

using Graph = lemon::SmartDigraph;

sq_mcf_status check(const sq_mcf_problem *p)
{
    if (!p || (p->n_arcs && (!p->tail || !p->head || !p->cost)))
        return SQ_MCF_BAD_INPUT;
    if (p->method != SQ_MCF_NETWORK_SIMPLEX && p->method != SQ_MCF_CAPACITY_SCALING &&
        p->method != SQ_MCF_COST_SCALING)
        return SQ_MCF_BAD_INPUT;
    if (p->n_nodes > static_cast<uint32_t>(INT32_MAX) || p->n_arcs > static_cast<uint32_t>(INT32_MAX))
        return SQ_MCF_BAD_INPUT;
    for (uint32_t a = 0; a < p->n_arcs; a++) {
        if (p->tail[a] >= p->n_nodes || p->head[a] >= p->n_nodes) return SQ_MCF_BAD_INPUT;
        int64_t lo = p->lower ? p->lower[a] : 0;
        int64_t up = p->upper ? p->upper[a] : SQ_MCF_INF;
        if (lo > up) return SQ_MCF_BAD_INPUT;
    }
    if (p->supply) {
        int64_t sum = 0;
        for (uint32_t n = 0; n < p->n_nodes; n++) {
            if (__builtin_add_overflow(sum, p->supply[n], &sum)) return SQ_MCF_BAD_INPUT;
        }
        if (sum != 0) return SQ_MCF_BAD_INPUT;
    }
    return SQ_MCF_OPTIMAL;
}

// The three algorithms share this interface (maps in, run(), flow()).
template <class Algo>
sq_mcf_status run(Algo &&algo, const sq_mcf_problem *p, const std::vector<Graph::Arc> &arcs,
                  const Graph::ArcMap<int64_t> &cost, const Graph::ArcMap<int64_t> &lower,
                  const Graph::ArcMap<int64_t> &upper, const Graph::NodeMap<int64_t> &supply, int64_t *flow,
                  int64_t *total_cost)
{
    using A = typename std::decay<Algo>::type;
    algo.costMap(cost).upperMap(upper).supplyMap(supply);
    if (p->lower) algo.lowerMap(lower);
    switch (algo.run()) {
    case A::OPTIMAL: break;
    case A::INFEASIBLE: return SQ_MCF_INFEASIBLE;
    case A::UNBOUNDED: return SQ_MCF_UNBOUNDED;
    }
    for (uint32_t a = 0; a < p->n_arcs; a++) flow[a] = algo.flow(arcs[a]);
    if (total_cost) *total_cost = algo.totalCost();
    return SQ_MCF_OPTIMAL;
}

sq_mcf_status solve(const sq_mcf_problem *p, int64_t *flow, int64_t *total_cost)
{
    if (p->n_nodes == 0) {  // LEMON refuses an empty graph; so is nothing to do
        if (total_cost) *total_cost = 0;
        return SQ_MCF_OPTIMAL;
    }
    Graph g;
    g.reserveNode(static_cast<int>(p->n_nodes));
    g.reserveArc(static_cast<int>(p->n_arcs));
    std::vector<Graph::Node> nodes(p->n_nodes);
    for (uint32_t n = 0; n < p->n_nodes; n++) nodes[n] = g.addNode();
    std::vector<Graph::Arc> arcs(p->n_arcs);
    for (uint32_t a = 0; a < p->n_arcs; a++) arcs[a] = g.addArc(nodes[p->tail[a]], nodes[p->head[a]]);

    Graph::ArcMap<int64_t> cost(g), lower(g, 0), upper(g);
    Graph::NodeMap<int64_t> supply(g, 0);
    for (uint32_t a = 0; a < p->n_arcs; a++) {
        cost[arcs[a]] = p->cost[a];
        if (p->lower) lower[arcs[a]] = p->lower[a];
        // SQ_MCF_INF is INT64_MAX, which is LEMON's INF for int64_t.
        upper[arcs[a]] = p->upper ? p->upper[a] : SQ_MCF_INF;
    }
    if (p->supply)
        for (uint32_t n = 0; n < p->n_nodes; n++) supply[nodes[n]] = p->supply[n];

    switch (p->method) {
    case SQ_MCF_NETWORK_SIMPLEX:
        return run(lemon::NetworkSimplex<Graph, int64_t, int64_t>(g), p, arcs, cost, lower, upper, supply, flow,
                   total_cost);
    case SQ_MCF_CAPACITY_SCALING:
        return run(lemon::CapacityScaling<Graph, int64_t, int64_t>(g), p, arcs, cost, lower, upper, supply, flow,
                   total_cost);
    case SQ_MCF_COST_SCALING:
        return run(lemon::CostScaling<Graph, int64_t, int64_t>(g), p, arcs, cost, lower, upper, supply, flow,
                   total_cost);
    }
    return SQ_MCF_BAD_INPUT;
}

}  // namespace

extern "C" sq_mcf_status sq_mcf_solve(const sq_mcf_problem *p, int64_t *flow, int64_t *total_cost)
{
    sq_mcf_status s = check(p);
    if (s != SQ_MCF_OPTIMAL) return s;
    if (p->n_arcs && !flow) return SQ_MCF_BAD_INPUT;
    try {
        return solve(p, flow, total_cost);
    } catch (const std::bad_alloc &) {
        return SQ_MCF_NOMEM;
    }
}

extern "C" const char *sq_mcf_status_name(sq_mcf_status s)
{
    switch (s) {
    case SQ_MCF_OPTIMAL: return "optimal";
    case SQ_MCF_INFEASIBLE: return "infeasible";
    case SQ_MCF_UNBOUNDED: return "unbounded";
    case SQ_MCF_BAD_INPUT: return "bad input";
    case SQ_MCF_NOMEM: return "out of memory";
    }
    return "unknown";
}
