/* seamquad: Q triangulated, with room made locally (seed 9.4, "Cone Cuts").
 *
 * Seed 9.4: "On the quad mesh Q these paths are replicated as discrete
 * geodesic paths using Dijkstra's algorithm, constrained to the proper
 * sectors. To prevent paths from blocking subsequent paths, we introduce
 * Steiner vertices in Q through edge splits where necessary, cf. [SAPH04].
 * To simplify implementation, Q can be triangulated (splitting each quad
 * into two right triangles)."
 *
 * sq_qtri is that triangulated Q, closed by gluing Q's sides in pairs (so
 * that Q's boundary is a cut, as the cut graph is on the surface), as an
 * editable sq_tsurf whose halfedges carry exact flat vectors (hvec, each in
 * its face's quad frame: quad f is the unit square with corner i of
 * Q->f_he[f] at (0,0), (1,0), (1,1), (0,1)). Every Steiner vertex is the
 * midpoint of an edge, so every position in Omega stays a dyadic rational.
 *
 * sq_qtri_replicate copies a surface cone tree (seed 9.4 on the surface,
 * sq_guide_surface_tree and sq_guide_surface_root) into it as the same
 * plane tree: step by step, each path leaves the copy of the node (or of
 * the segment) its surface path ended at, in the copy of the sector it
 * arrived in, and runs through faces to its cone (sq_tsurf_route_faces:
 * every crossed edge is split at its midpoint, so a path never touches an
 * earlier one and always exists: a tree does not separate a disk). Unlike
 * a copy in Q's quad grid, it cannot fail for lack of room, and it refines
 * Q only along the paths.
 *
 * The library never prints or exits. */
#ifndef SQ_QTRI_H
#define SQ_QTRI_H

#include <stdint.h>

#include "sq_cut_graph.h"
#include "sq_domain.h"
#include "sq_error.h"
#include "sq_guide.h"
#include "sq_mesh.h"
#include "sq_omega.h"
#include "sq_tsurf.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sq_qtri {
    sq_tsurf S;          /* Q's quads as triangle pairs (quad f: faces 2f, */
                         /* 2f + 1; forig = that index), Q's sides glued;  */
                         /* cut: Q's boundary (label: the side of Q whose  */
                         /* face the halfedge lies in) and the tree        */
                         /* (label SQ_NONE); valence: quads at the vertex  */
    uint32_t nq;         /* Q->nv                                          */
    uint32_t *closed_of; /* nq: the vertex of S each vertex of Q is glued to */
    uint32_t *tree_next; /* S.cap_v: along each tree path towards its end  */
                         /* (the vertex it joined; the root path: towards  */
                         /* its cone); SQ_NONE off the tree and at cone 0  */
    uint32_t *tree_step; /* S.cap_v: the step whose path holds the vertex  */
                         /* (cone j: j; the root path: n); SQ_NONE off it  */
    uint32_t cap_v;      /* entries of tree_next and tree_step             */
    uint32_t n;          /* cones (steps)                                  */
    uint32_t *cone;      /* n: the vertex of S of each step's cone         */
    uint32_t *att;       /* n: the vertex of S each path ends at (SQ_NONE  */
                         /* for step 0)                                    */
    uint32_t root;       /* the root, on Q's boundary (SQ_NONE: none yet)  */
    uint32_t root_side;  /* the side of Q it lies inside                   */
    uint32_t root_he;    /* the cut halfedge leaving it along that side,   */
                         /* the side's faces to its left                   */
    uint32_t root_pos;   /* its index on that side (sq_domain_side_vertices) */
    uint64_t splits;     /* Steiner vertices made by the tree              */
    uint64_t max_faces;  /* the replication fails (SQ_ERR_SOLVER) once S   */
                         /* has more faces (a memory limit; 0: none)       */
} sq_qtri;

void sq_qtri_init(sq_qtri *T);
void sq_qtri_free(sq_qtri *T);

/* Q of D triangulated and glued. xy (2 per vertex of Q, may be NULL):
 * positions used only for path lengths (e.g. Q laid out in the unit disk
 * by sq_guide_metapolygon_layout); a glued vertex takes its lowest-index
 * copy's. SQ_ERR_INTERNAL when the glued Q is not a simple closed mesh. */
sq_status sq_qtri_build(const sq_domain *D, const double *xy, sq_qtri *T, sq_error *err);

/* The surface tree of seed 9.4 copied into T as the same plane tree.
 * m, G: the surface and its cut graph; cone[0..n): the surface cones in
 * step order; qcone[0..n): the vertex of Q standing for each (any cone of
 * Q, as Q's own labelling of the steps); tree_next (m->nv): the surface
 * tree of sq_guide_surface_tree with the root path attached
 * (sq_guide_surface_root with path_next = tree_next); att_vertex (n): where
 * each surface path ends; root: the surface root (step, side, vertex,
 * index); q_root_side: the side of Q standing for root->side. The root of
 * T is the inner vertex of that side at about the same fraction of its
 * length. SQ_ERR_SOLVER when the surface tree is incomplete (a cone it did
 * not join); SQ_ERR_INTERNAL on a broken invariant. */
sq_status sq_qtri_replicate(sq_qtri *T, const sq_domain *D, const sq_mesh *m, const sq_cut_graph *G,
                            uint32_t n, const uint32_t *cone, const uint32_t *qcone,
                            const uint32_t *tree_next, const uint32_t *att_vertex,
                            const sq_guide_root *root, uint32_t q_root_side, sq_error *err);

/* Omega's layout from T (seed 7: "the cut quad mesh Q can be laid out
 * isometrically in the plane"): S cut along its cut edges (Q's boundary
 * and the tree) is a disk, laid out face by face across uncut edges, each
 * face by its flat vectors turned by a multiple of 90 degrees, with face
 * 0's frame the plane's. corner_xy (2
 * S.nh, caller-owned): the position of each halfedge's origin in its face.
 * Every position is a dyadic rational, exact in doubles. Checked: the two
 * faces of every uncut edge agree on its ends, bit for bit; every face is
 * reached and positively oriented (exact predicate). SQ_ERR_INTERNAL names
 * the first violation. */
sq_status sq_qtri_layout(const sq_qtri *T, double *corner_xy, sq_error *err);

/* The transition across the cut edge of halfedge h (corner_xy from
 * sq_qtri_layout): the motion y = R^rot x + t taking h's face's copy of the
 * edge to its twin's copy; 0 if it is not a rotation by a multiple of 90
 * degrees plus a translation, exactly. */
int sq_qtri_transition(const sq_qtri *T, const double *corner_xy, uint32_t h, uint8_t *rot, double t[2]);

/* Omega from T (after sq_qtri_replicate) as an sq_omega (seed 7): S cut
 * along Q's boundary and the tree, laid out by sq_qtri_layout, with the
 * labels of sq_omega (Q's sides, then per tree segment s its left side
 * k + 2s and its right side k + 2s + 1, walked away from the root, then the
 * part of the root's side after the root and its partner), their exact
 * transitions, and xy_shift > 0 where the midpoints need it. The
 * segments are numbered here: seg_from[s], seg_to[s] (vertices of S, nodes
 * of the tree, seg_from nearer the root; arrays of *nseg entries,
 * malloc'd, the caller frees them). O is replaced (it must be
 * initialized). */
sq_status sq_qtri_omega(const sq_qtri *T, const sq_domain *D, sq_omega *O, uint32_t *nseg, uint32_t **seg_from,
                        uint32_t **seg_to, sq_error *err);

/* A coarser triangulation of an Omega of triangles (sq_qtri_omega): inner
 * vertices collapsed into a neighbour (nearest first) wherever the link
 * condition holds, every remaining triangle stays positively oriented
 * (exact predicate on the stored positions) and their worst shape gets no
 * worse (no slivers, which cost the overlay crossings); the boundary, its labels and
 * every position kept. Any triangulation of Omega serves the overlay
 * (seed 10: "any coarse tessellation ... is sufficient"). *removed: the
 * vertices removed. */
sq_status sq_omega_coarsen(sq_omega *O, uint32_t *removed, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
