/* seamquad: the cut graph on the surface (seed 7, seed 9.1), genus >= 1.
 *
 * Cuts a closed genus-g mesh along mesh edges into one topological disk
 * with 8g-4 sides, avoiding every cone vertex. The graph has 4g-2 branches
 * and 2g-1 branch points, each of degree 4 (seed 6, "Assume we cut ...";
 * seed 7, "the employed cut graph having branch points of degree 4").
 *
 * Two stages (docs/cut_graph.md):
 *  1. sq_cut_loops_find: g pairwise vertex-disjoint, simple, cone-free loops
 *     whose complement is connected (a sphere with 2g holes), picked
 *     greedily by length among tree-cotree candidates from sampled base
 *     points (seed 9.1, after Erickson-Whittlesey).
 *  2. sq_cut_chain: 2g-1 shortest paths that chain the holes as
 *     L1+, L2+, L2-, ..., Lg+, Lg-, L1- (seamless-notes 6, the variant),
 *     then the boundary word of the cut disk as an sq_pattern plus the mesh
 *     halfedges of every side.
 * sq_cut_graph_build runs both and tries rotation/flip choices until the
 * pattern passes the rank test of seamless-notes 7 (genus >= 2).
 *
 * Sides of a loop: loop L is a closed sequence of halfedges; its + side is
 * the side of the faces of those halfedges (left of the loop direction),
 * its - side the side of their twins.
 *
 * Cones: `cone` has one entry per vertex, nonzero for a cone (valence !=
 * 4); NULL means no cones. No cone vertex lies on the cut. Where cones
 * block every route (a vertex walled in by cones, or a ring of adjacent
 * cones around a handle) the mesh needs an edge split (Steiner vertex,
 * seed 9.1); that is not implemented: the functions fail with
 * SQ_ERR_ARGUMENT, a message naming the edge or vertex, and
 * failure = SQ_CUT_FAIL_NEEDS_SPLIT in the stats.
 *
 * The library never prints or exits. Arrays are owned by the structs and
 * released by the matching _free. */
#ifndef SQ_CUT_GRAPH_H
#define SQ_CUT_GRAPH_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_mesh.h"
#include "sq_pattern.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sq_cut_failure {
    SQ_CUT_FAIL_NONE = 0,
    SQ_CUT_FAIL_NEEDS_SPLIT, /* cones block a loop or path: split an edge */
    SQ_CUT_FAIL_NO_LOOP,     /* no further non-separating loop was found   */
    SQ_CUT_FAIL_NO_PATH,     /* a chain path has no cone- and cut-free route */
    SQ_CUT_FAIL_CHECK        /* a result failed its own verification (bug)   */
} sq_cut_failure;

typedef struct sq_cut_options {
    uint32_t base_points; /* tree-cotree base points per round (default 8)  */
    uint64_t seed;        /* splitmix64 seed for sampling base points       */
    /* Rotation order at the branch points a_i, b_i (i = 2..g, in chain
     * order). The path arriving at a_i (on the + side of L_i) splits that
     * side's sector in two; bit 2(i-2) says in which one the next path
     * leaves: 0 = between the loop edge to the previous loop vertex and
     * the arriving path, 1 = between the arriving path and the loop edge
     * to the next loop vertex. Bit 2(i-2)+1 likewise at b_i on the - side:
     * 0 = between the edge to the next loop vertex and the arriving path,
     * 1 = between the arriving path and the edge to the previous one
     * (previous/next along the loop's orientation after `flip`). Each
     * choice gives a different rotation system, hence pattern. */
    uint64_t rotation;
    uint64_t flip;        /* bit i: reverse the orientation of loop i       */
    /* sq_cut_graph_build: number of (rotation, flip) choices tried until
     * the rank test passes, starting from (rotation, flip) above; default
     * 64. 1 tries only the given choice. */
    uint32_t max_tries;
} sq_cut_options;

void sq_cut_options_default(sq_cut_options *opt);

typedef struct sq_cut_stats {
    sq_cut_failure failure;
    uint32_t where[2];    /* vertices of the offending edge (or vertex, -) */
    uint32_t rounds;      /* tree-cotree rounds                            */
    uint32_t candidates;  /* candidate loops examined                      */
} sq_cut_stats;

typedef struct sq_cut_loops {
    uint32_t genus;
    uint32_t nloops;      /* = genus on success                            */
    uint32_t *loop_off;   /* nloops + 1                                     */
    uint32_t *loop_he;    /* loop i: halfedges loop_off[i] .. loop_off[i+1]-1,
                           * head to tail, closed                           */
    double *loop_len;     /* nloops: Euclidean lengths                      */
} sq_cut_loops;

void sq_cut_loops_init(sq_cut_loops *L);
void sq_cut_loops_free(sq_cut_loops *L);

/* Stage 1 (seed 9.1). stats optional. */
sq_status sq_cut_loops_find(const sq_mesh *m, const uint8_t *cone, const sq_cut_options *opt,
                            sq_cut_loops *out, sq_cut_stats *stats, sq_error *err);

/* Verifies loops: each closed and simple, cone-free, pairwise vertex-
 * disjoint, and cutting along all of them leaves one connected surface with
 * the same Euler characteristic and 2 * nloops boundary loops (so genus
 * g - nloops). */
sq_status sq_cut_loops_check(const sq_mesh *m, const uint8_t *cone, const sq_cut_loops *L,
                             sq_error *err);

typedef struct sq_cut_graph {
    uint32_t genus;
    uint8_t *he_cut;        /* nh: 1 where the halfedge's edge is cut       */
    uint32_t ncut_edges;
    uint32_t npoints;       /* branch points (2g - 1)                       */
    uint32_t *point_vertex; /* npoints                                      */
    uint32_t nbranches;     /* 4g - 2                                       */
    double length;          /* total Euclidean length of the cut            */
    /* Boundary word of the cut disk, walked with the disk on the left. */
    sq_pattern pattern;     /* k = 8g - 4 sides; side i: corner i -> i+1    */
    uint32_t *side_off;     /* k + 1                                        */
    uint32_t *side_he;      /* 2 * ncut_edges mesh halfedges, side by side  */
    uint32_t *corner_vertex;/* k: branch vertex at corner i                 */
    uint32_t rank;          /* sq_pattern_rank (2 passes the rank test)     */
    uint64_t rotation, flip;/* choices that built this graph                */
    uint32_t tries;         /* choices tried by sq_cut_graph_build          */
} sq_cut_graph;

void sq_cut_graph_init(sq_cut_graph *G);
void sq_cut_graph_free(sq_cut_graph *G);

/* Stage 2: the hole chain (seamless-notes 6, variant) for given loops and
 * choices, then the boundary word (sq_cut_boundary_word) and the checks of
 * sq_cut_graph_check. For genus 1 this is the two-loop graph a b a^-1 b^-1
 * (rank 0: genus 1 needs pieces or slides later, seamless-notes 7). */
sq_status sq_cut_chain(const sq_mesh *m, const uint8_t *cone, const sq_cut_loops *L,
                       uint64_t rotation, uint64_t flip, sq_cut_graph *out,
                       sq_cut_stats *stats, sq_error *err);

/* Both stages; tries up to opt->max_tries choices until rank == 2 (genus
 * >= 2); keeps the first graph that passes, else the last one built. */
sq_status sq_cut_graph_build(const sq_mesh *m, const uint8_t *cone, const sq_cut_options *opt,
                             sq_cut_graph *out, sq_cut_stats *stats, sq_error *err);

/* From G->he_cut alone: branch points, branches, the boundary walk, the
 * sides and their partners, corner vertices, the pattern and its rank.
 * Fails unless the boundary is one loop split into sides that pair up as
 * reverses of each other. */
sq_status sq_cut_boundary_word(const sq_mesh *m, sq_cut_graph *G, sq_error *err);

/* Verifies G: no cone on the cut; every branch point of degree 4, other
 * cut vertices of degree 2; 2g-1 branch points and 4g-2 branches; the cut
 * surface (vertices duplicated along the cut) is one disk: Euler
 * characteristic 1, one boundary loop; the pattern is valid with genus g
 * and corner classes of 4 corners at one branch vertex each. Genus 0 and
 * 1 also accept the graphs of sq_cut_graph_build_low_genus: two degree-1
 * points and one branch (genus 0, k = 2; pairing and Euler characteristic
 * only, see sq_cut_graph.c), two degree-3 points and three branches
 * (genus 1, k = 6); classes then have as many corners as the degree. */
sq_status sq_cut_graph_check(const sq_mesh *m, const uint8_t *cone, const sq_cut_graph *G,
                             sq_error *err);

/* Cut graphs for every genus, with the genus 0 and 1 graphs matching the
 * domain Q of sq_domain_build (seed 6.5, seed 6.2, seed 7 "Low Genus
 * Special Cases"; docs/cut_graph.md "Genus 0 and 1"):
 *  - genus 0: one shortest path of at least 2 edges between two non-cone
 *    vertices through non-cone vertices (Dijkstra, Euclidean lengths), from
 *    the first suitable vertex in index order (opt->seed 1) or from a
 *    vertex spread over the index range by the seed; its ends are degree-1
 *    branch points; k = 2, partner {1, 0} (Q: the sphere cut along one
 *    edge);
 *  - genus 1 with cones (some cone[v] != 0): the theta graph, a shortest
 *    cone-free non-separating loop L (sq_cut_loops_find) and a shortest
 *    cone-free path P from the + side of L to the - side with ends x != y
 *    on L (interior vertices off L and off cones); x, y have degree 3,
 *    three branches, k = 6, word a b c a^-1 b^-1 c^-1 (partner i + 3 mod
 *    6), the first corner of each class marked straight in
 *    pattern.straight (Q's genus-1 pattern: partner {3, 4, 5, 0, 1, 2},
 *    one straight corner per class);
 *  - genus 1 without cones, genus >= 2: sq_cut_graph_build (two-loop graph
 *    a b a^-1 b^-1, resp. the hole chain).
 * Every field of out is filled; out->tries = 1 for genus 0 and 1 with
 * cones. Cones walling a path off: SQ_ERR_ARGUMENT, stats->failure =
 * SQ_CUT_FAIL_NEEDS_SPLIT, stats->where a cone-cone edge (SQ_NONE if none).
 * A negative genus (not a closed connected orientable surface):
 * SQ_ERR_ARGUMENT. stats optional. */
sq_status sq_cut_graph_build_low_genus(const sq_mesh *m, const uint8_t *cone,
                                       const sq_cut_options *opt, sq_cut_graph *out,
                                       sq_cut_stats *stats, sq_error *err);

/* Seam rotations (docs/holonomy.md). turn: a connection in quarter turns
 * per halfedge (sq_cone_connection.h) for the cones `valence`.
 *
 * sq_cut_graph_rotation_mismatch: how far every map built on G (the seed's
 * domain, right-angled corners) is from the connection's rotations: norm =
 * sum over the non-tree branches of a spanning tree of the branch graph of
 * the Z4 distance from 0 of the rotation each must gain; wrong_loops = side
 * pairs whose boundary loop rotates differently. 0 and 0: the maps have
 * the connection's rotations around every loop.
 *
 * sq_cut_graph_steer: reroutes branches of G across cones (same corners,
 * same pattern) until the mismatch is 0 or no reroute lowers it; G is
 * replaced by the steered graph (checked by sq_cut_graph_check), its
 * corners possibly renumbered (stats->corner_shift) with their straight
 * marks kept. The domain's corner angles are taken from G->pattern: for
 * genus 1 (theta graph) the caller marks the corners the domain makes
 * straight. Genus 0 is left unchanged; where the mismatch cannot be
 * computed (corner angles that do not fit the graph, or no memory), G is
 * left unchanged and both norms are UINT32_MAX. stats optional. */
typedef struct sq_cut_steer_stats {
    uint32_t norm_before, norm_after;
    uint32_t wrong_loops_before, wrong_loops_after;
    uint32_t reroutes;
    double length_before, length_after; /* Euclidean length of the cut */
    uint32_t corner_shift;  /* the steered word's corner (i + corner_shift) */
                            /* mod k is the input word's corner i          */
} sq_cut_steer_stats;

sq_status sq_cut_graph_rotation_mismatch(const sq_mesh *m, const sq_cut_graph *G,
                                         const double *turn, uint32_t *norm, uint32_t *wrong_loops,
                                         sq_error *err);
sq_status sq_cut_graph_steer(const sq_mesh *m, const int32_t *valence, const double *turn,
                             sq_cut_graph *G, sq_cut_steer_stats *stats, sq_error *err);

/* Side correspondence between the cut graph and the domain Q.
 *
 * Orientation: G->pattern is read with the cut disk on the LEFT
 * (counterclockwise); Q's sides in sq_domain follow Q's boundary halfedges,
 * with the disk on the RIGHT (clockwise). Read clockwise, the surface's word
 * is sq_pattern_reversed(&G->pattern): clockwise side j = counterclockwise
 * side k-1-j traversed backward, clockwise corner j = counterclockwise
 * corner (k-j) mod k.
 *
 * Finds r in 0..k-1 such that Q side j corresponds to clockwise surface
 * side (j + r) mod k (= G side (2k - 1 - j - r) mod k, walked backward;
 * Q corner j = clockwise corner (j + r) mod k = G corner (2k - j - r) mod
 * k) with exactly Q's pairing: cw.partner[(j + r) % k] == (q_pattern->
 * partner[j] + r) % k for all j. Straight corners do not constrain the
 * match (on the surface any corner may take any angle); among matching r
 * the smallest one that also maps straight flags onto straight flags is
 * returned if there is one, else the smallest matching r. For genus >= 2
 * with q_pattern = sq_pattern_reversed(&G->pattern) (what the domain was
 * built with), r = 0. SQ_ERR_ARGUMENT if the side counts differ or no r
 * matches. */
sq_status sq_cut_graph_domain_offset(const sq_cut_graph *G, const sq_pattern *q_pattern,
                                     uint32_t *offset, sq_error *err);

/* 1 if shift r pairs the sides as Q does: cw.partner[(j + r) % k] ==
 * (q.partner[j] + r) % k for every j (cw: the surface's word read
 * clockwise, sq_pattern_reversed; both with k = q->k sides). The test of
 * sq_cut_graph_domain_offset, for callers that choose r themselves. */
int sq_cut_graph_shift_pairs(const sq_pattern *cw, const sq_pattern *q, uint32_t r);

#ifdef __cplusplus
}
#endif
#endif
