/* seamquad: the flat seamless parameter domain Omega (seed 3, Fig. 2 c-d;
 * seed 7, "Compatible Cutting").
 *
 * The padded quad disk Q of sq_domain is a cone manifold D (seed Fig. 2 c):
 * flat except at its interior vertices of valence != 4, the cones. Seed 7:
 * "In the quad mesh Q, we compute a discrete (edge-based) spanning tree of
 * all singularities and one arbitrary flat boundary vertex, within the set
 * of non-boundary edges" ... "Using the unit square metric, the cut quad
 * mesh Q can be laid out isometrically in the plane, yielding the seamless
 * parameter domain Omega" (seed Fig. 2 d).
 *
 * Three steps, each a function here, each checked exactly in integers:
 *
 * 1. sq_cone_tree: the spanning tree T of the cones and a root on Q's
 *    boundary (sq_cone_tree_shortest builds one by shortest paths, seed
 *    9.4; sq_cone_tree_from_edges accepts any tree, e.g. one the surface
 *    stage chose), with its rotation system (seed 7: the tree must be
 *    compatible with the surface cut "as an embedded graph").
 * 2. sq_omega_build, cut: Q cut along T into the disk Omega_c (every tree
 *    vertex split into one copy per sector between consecutive tree edges),
 *    stored as an sq_metapolygon with Q's faces in Q's face order.
 * 3. sq_omega_build, layout: every quad a unit square with integer corners,
 *    placed by a breadth-first walk across uncut edges; then the seamless
 *    transitions (seed 3, 8; seamless-notes 5): the two copies of every
 *    point of Omega_c's boundary differ by a rotation by a multiple of 90
 *    degrees plus an integer translation, one per side pair of Q and one
 *    per segment of T (the side holding the root splits in two there).
 *
 * sq_omega_verify re-checks everything independently of how it was built.
 *
 * Omega is an immersed, in general only weakly self-overlapping polygon
 * (seed Fig. 2 caption): the layout is locally injective, not injective.
 *
 * The library never prints or exits; fallible functions return an sq_status
 * and fill the caller's sq_error (which may be NULL). */
#ifndef SQ_OMEGA_H
#define SQ_OMEGA_H

#include <stdint.h>

#include "sq_domain.h"
#include "sq_error.h"
#include "sq_metapolygon.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the cone tree (sq_omega_tree.c) ----------------------------------- */

/* Kinds of tree vertices (bit flags in sq_cone_tree.node). A vertex with
 * any flag is a node: segments run from node to node. */
enum {
    SQ_TREE_ROOT = 1u << 0,   /* the root, on Q's boundary                  */
    SQ_TREE_CONE = 1u << 1,   /* an interior vertex of Q of valence != 4    */
    SQ_TREE_BRANCH = 1u << 2, /* tree degree >= 3 (a regular branch vertex) */
    SQ_TREE_LEAF = 1u << 3    /* tree degree 1, not the root                */
};

typedef struct sq_cone_tree {
    uint32_t root;     /* vertex of Q on its boundary                        */
    uint32_t nedges;   /* edges of T                                        */
    uint32_t *he;      /* nedges: a halfedge of Q per edge, oriented away   */
                       /* from the root (he_vert = the end nearer the root); */
                       /* parents before children (depth-first order)       */
    uint32_t nverts;   /* nedges + 1                                        */
    uint32_t *vert;    /* nverts: vertices of Q, vert[0] = root             */
    uint8_t *node;     /* nverts: SQ_TREE_* flags, 0 for a degree-2 regular */
                       /* vertex inside a segment                          */
    uint32_t *rot_off; /* nverts + 1: CSR offsets into rot_he               */
    uint32_t *rot_he;  /* 2 nedges: the rotation system. For vert[i], its   */
                       /* outgoing tree halfedges of Q in counterclockwise  */
                       /* order, starting with the edge towards the root    */
                       /* for an interior vertex; for the root, in the      */
                       /* counterclockwise order of its fan of faces (from  */
                       /* the edge of its incoming boundary halfedge to the */
                       /* edge of its outgoing one)                         */
    uint32_t nseg;     /* segments: maximal paths between nodes             */
    uint32_t *seg_off; /* nseg + 1: CSR offsets into seg_he                 */
    uint32_t *seg_he;  /* nedges: the halfedges of each segment, in order,  */
                       /* oriented away from the root                       */
} sq_cone_tree;

void sq_cone_tree_init(sq_cone_tree *T);
void sq_cone_tree_free(sq_cone_tree *T);

/* T from an explicit edge list: `he` holds n halfedges of Q (either
 * halfedge of each edge). Checks (SQ_ERR_ARGUMENT naming the edge or
 * vertex): every edge is interior to Q (faces on both sides) and appears
 * once; root is a vertex on Q's boundary; every other tree vertex is
 * interior (a tree touching the boundary twice would cut Q apart); the
 * edges form one tree containing the root and every cone of Q. Extra
 * non-cone leaves are accepted (they become nodes). Then orients the
 * edges, computes the rotation system, the nodes and the segments. T is
 * replaced (it must be initialized). */
sq_status sq_cone_tree_from_edges(const sq_metapolygon *Q, uint32_t root, const uint32_t *he,
                                  uint32_t n, sq_cone_tree *T, sq_error *err);

/* Seed 7 / 9.4: a tree of shortest paths over interior edges, through
 * interior vertices only. Starting with T = {root}, repeatedly the cone
 * nearest to T (breadth-first distance in edges; ties: lowest vertex
 * index) is joined to T by a shortest path (in the spirit of seed 9.4,
 * where each further singularity is joined "by the shortest possible
 * path ... to any of these"). root: a boundary vertex of Q, or SQ_NONE for
 * the default: the flat boundary vertex (two faces) nearest to a cone, ties
 * to the first in boundary order from Q->bnd_he; if Q has no flat boundary
 * vertex with an interior neighbour (the genus-0 slit), any non-corner
 * boundary vertex with one. SQ_ERR_INTERNAL if a cone cannot be reached
 * through interior vertices (seed 7 argues it always can). */
sq_status sq_cone_tree_shortest(const sq_metapolygon *Q, uint32_t root, sq_cone_tree *T,
                                sq_error *err);

/* ---- Omega (sq_omega.c, sq_omega_cut.c, sq_omega_layout.c) ------------- */

typedef struct sq_omega {
    /* Omega_c: Q cut along T, a disk. Faces are Q's faces, same indices.
     * Halfedges: first the face halfedges, face by face in Q's face order,
     * each face starting at Q->f_he[f] (so for quads face f owns halfedges
     * 4f .. 4f+3 and he_vert[4f+i] is its i-th corner); then the boundary
     * halfedges (one loop, clockwise: the disk lies to its right).
     * cut.bnd_he is the copy of Q's boundary halfedge leaving corner 0. */
    sq_metapolygon cut;
    uint32_t *v_qvert;   /* cut.nv: the vertex of Q each vertex copies      */
    uint32_t *he_qhe;    /* cut.nh: the halfedge of Q each halfedge copies  */
                         /* (for a boundary halfedge of the cut: the twin   */
                         /* in Q of its interior twin's copy)              */
    uint32_t k;          /* sides of Q                                     */
    uint32_t nlabels;    /* k + 2 T.nseg, + 2 if the root splits a side    */
    uint32_t *he_label;  /* cut.nh: SQ_NONE inside; for a boundary         */
                         /* halfedge its label: the pieces of Omega_c's     */
                         /* boundary with one transition each (below)       */
    uint32_t *label_side;/* nlabels: the side of Q a label lies on, SQ_NONE */
                         /* for the tree. Labels: i < k: side i of Q;       */
                         /* k + 2s: the left side of tree segment s (its    */
                         /* faces lie left of the segment's halfedges),     */
                         /* k + 2s + 1: its right side. When the root lies  */
                         /* inside side r (root_pos > 0), the tree's two    */
                         /* sides are spliced in there and the part of r    */
                         /* after the root is displaced by the holonomy     */
                         /* around the tree: it gets label k + 2 T.nseg, and */
                         /* the part of partner[r] glued to it label        */
                         /* k + 2 T.nseg + 1                                */
    /* layout: exact integer positions, every face a unit square,
     * counterclockwise (sq_metapolygon convention) */
    int64_t *xy;         /* 2 cut.nv                                       */
    uint8_t *f_dir;      /* cut.nf: direction of the face's first edge,    */
                         /* 0..3 = +x, +y, -x, -y                           */
    /* seamless transitions, one per label l: a point x on the boundary
     * with label l and its other copy y (label partner[l]) satisfy
     * y = R^rot[l] x + (tx[l], ty[l]), R the rotation by +90 degrees */
    uint32_t *label_partner; /* nlabels                                    */
    uint8_t *label_rot;      /* nlabels: 0..3                              */
    int64_t *label_t;        /* 2 nlabels: tx, ty                          */
    uint32_t *he_partner;    /* cut.nh: SQ_NONE inside; for a boundary      */
                             /* halfedge, the other copy of its edge, which */
                             /* runs the opposite way (its tail is the copy */
                             /* of this one's head)                         */
    uint32_t root_side;      /* T's root is vertex root_pos (0 <= root_pos  */
    uint32_t root_pos;       /* < side_len) of side root_side of Q, counted */
                             /* from the side's first corner                */
    int64_t xmin, ymin, xmax, ymax; /* bounding box of the layout          */
    int xy_shift;            /* xy, label_t and the box are in units of     */
                             /* 2^-xy_shift: 0 for Q's unit squares; > 0    */
                             /* for Omega from Q triangulated with midpoint */
                             /* splits (sq_qtri_omega: faces are triangles, */
                             /* f_dir is NULL, v_qvert and he_qhe name the  */
                             /* triangulated Q's vertices and halfedges)    */
} sq_omega;

void sq_omega_init(sq_omega *O);
void sq_omega_free(sq_omega *O);

/* Step 2 alone (sq_omega_cut.c): fills cut, v_qvert, he_qhe, k, nlabels,
 * he_label, label_side, he_partner, label_partner, root_side, root_pos, and
 * checks that the cut is a disk. O must be initialized (it is freed first). */
sq_status sq_omega_cut(const sq_domain *D, const sq_cone_tree *T, sq_omega *O, sq_error *err);

/* Step 3 alone (sq_omega_layout.c), after sq_omega_cut: fills xy, f_dir,
 * the bounding box and the transitions (label_rot, label_t), checking the
 * closing condition at every vertex and every transition on every edge. */
sq_status sq_omega_layout(const sq_domain *D, sq_omega *O, sq_error *err);

/* Cuts D's quad disk Q along T (built for D->quads) and lays the result out
 * (seed 7). Every step checks its invariant as it goes: the cut is a disk
 * (sq_metapolygon_validate), every quad gets the same corner positions from
 * every neighbour, every boundary label (side pieces, tree segment sides)
 * has one exact transition. SQ_ERR_INTERNAL names the first violation. O is replaced (it
 * must be initialized). */
sq_status sq_omega_build(const sq_domain *D, const sq_cone_tree *T, sq_omega *O,
                         sq_error *err);

/* Angles of Omega, in units of 90 degrees (exact). angle (cut.nv entries,
 * caller-owned): the number of quad corners at each vertex of Omega_c.
 * point_angle (D->quads.nv entries, optional): for each vertex of Q, the
 * total angle of its glued point (its class after gluing Q's sides) over
 * every copy in Omega_c; 4 at a regular point, the valence at a cone. */
sq_status sq_omega_angles(const sq_domain *D, const sq_omega *O, uint32_t *angle,
                          uint32_t *point_angle, sq_error *err);

/* Independent check of O against D and T, all in exact integers:
 * - Omega_c is a disk (Euler characteristic 1, one boundary loop, valid
 *   halfedges), with Q's faces, nv = Q.nv + T.nedges and
 *   nbnd = Q.nbnd + 2 T.nedges, and v_qvert / he_qhe consistent with Q;
 * - every face is a counterclockwise axis-aligned unit square, and every
 *   interior vertex has four quads (so the layout is an immersion);
 * - at every boundary vertex the turn of the boundary polygon agrees with
 *   its number of quad corners (mod 4);
 * - every label's transition maps every vertex of every boundary edge with
 *   that label onto its other copy (reversing the edge), and the faces on
 *   the two copies lie on opposite sides; transitions of partner labels
 *   are inverse;
 * - every cone appears on the boundary only, with copies whose angles add
 *   up to its valence; every other glued point (in particular each corner
 *   class, a branch point of the cut graph) has 360 degrees.
 * SQ_ERR_INTERNAL names the first violation. */
sq_status sq_omega_verify(const sq_domain *D, const sq_cone_tree *T, const sq_omega *O,
                          sq_error *err);

/* Its picture: sq_omega_write_svg (sq_seamless_svg.h). */

#ifdef __cplusplus
}
#endif
#endif
