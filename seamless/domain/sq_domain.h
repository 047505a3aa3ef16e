/* seamquad: the combinatorial seamless domain (seed 4, steps 2-5; seed 6).
 *
 * From a genus and a multiset of cone valences, build the padded quad disk
 * Q whose 8g-4 sides pair up according to a side-pairing pattern with equal
 * lengths, whose corners are right angles and whose irregular vertices are
 * exactly the prescribed cones. Gluing every identified pair of sides closes
 * Q into a quad mesh of genus g in which the 2g-1 branch points are regular.
 *
 * Steps: admissible valence order (seed 5.2) -> metapolygon by repeated
 * extension (seed 5.1) -> subdivision into quads (seed 5.4) -> exact padding
 * solve over the k cyclic side correspondences, keeping the one with the
 * fewest added quads (seed 6.3, 9.3) -> padding strips glued to Q (seed
 * 6.1) -> sides, corners and the gluing map.
 *
 * Genus 0 (seed 6.5; sq_domain_genus0.c): four meta-2-gons, padded instead
 * of refined, glued into a sphere, which is cut along one edge (k = 2).
 * Genus 1 (seed 6.2; sq_domain_genus1.c): several pieces. Genus >= 2: one
 * piece without a slide, which suffices whenever the pattern passes the rank
 * test (seamless-notes 7; the canonical patterns of sq_pattern_canonical all
 * do).
 */
#ifndef SQ_DOMAIN_H
#define SQ_DOMAIN_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_metapolygon.h"
#include "sq_pattern.h"
#include "sq_soup.h"

#ifdef __cplusplus
extern "C" {
#endif

struct sq_build_options;

typedef struct sq_domain_options {
    const sq_pattern *pattern;            /* NULL: sq_pattern_canonical(genus) */
    uint32_t offset;                      /* side correspondence: pattern side */
                                          /* i = metapolygon side (i + offset) */
                                          /* mod k; SQ_NONE: best of all k      */
    const struct sq_build_options *build; /* glue-edge choices; NULL: seed 5.3 */
    int keep_order;                       /* genus >= 2 (genus 1: with       */
                                          /* g1_split): the valences' order  */
                                          /* is the construction order (must */
                                          /* be admissible; seed 9.2)        */
    uint32_t g1_split;                    /* genus 1 with keep_order: the    */
                                          /* last g1_split valences form the */
                                          /* meta-2-gon T (excess -2), the   */
                                          /* others the meta-6-gon H, each in*/
                                          /* the given order; `build` then   */
                                          /* applies to H only (seed 9.2)    */
} sq_domain_options;

typedef struct sq_domain {
    uint32_t genus;
    uint32_t ncones;
    uint32_t *order;          /* ncones: valences in construction order      */
    sq_metapolygon meta;      /* the metapolygon P                           */
    sq_metapolygon quads;     /* the padded quad disk Q (all faces 4-gons)   */
    uint32_t nf_unpadded;     /* faces 0 .. nf_unpadded-1 subdivide P        */
    uint32_t *f_meta_face;    /* nf_unpadded: the face of P each quad is in  */
    sq_pattern pattern;       /* side i of Q glues reversed to partner[i]    */
    uint32_t k;               /* sides = corners = 8g - 4                    */
    uint32_t offset;          /* pattern side i = metapolygon side i+offset  */
    uint32_t *corner_vert;    /* k: vertex of Q at corner i (side i starts)  */
    uint32_t *side_len;       /* k: final side lengths in quad edges         */
    int64_t *padding;         /* k: layers glued on side i                   */
    uint64_t refine;          /* d of seed 6.3 (1: no refinement)            */
    uint64_t quads_unpadded;  /* quads of the subdivided metapolygon         */
    uint64_t quads_added;     /* quads added by padding                      */
    uint32_t offsets_feasible;/* side correspondences with a padding         */
    int slid;                 /* 1: built with one slide (seed 6.4)          */
    uint32_t slide_length;    /* edges of the slid straight sequence         */
    int64_t slide_shift;      /* the relative shift t of the two pieces      */
    uint32_t slide_start;     /* the seam's end vertices in Q                */
    uint32_t slide_end;
    double seconds;           /* time of sq_domain_build                     */
} sq_domain;

void sq_domain_init(sq_domain *D);
void sq_domain_free(sq_domain *D);

/* Builds the domain for `ncones` valences (each >= 2; valence 4 entries are
 * ignored) on a closed surface of the given genus. Checks realizability
 * first (sq_valences_check_realizable). opt may be NULL. */
sq_status sq_domain_build(uint32_t genus, const int32_t *valences, uint32_t ncones,
                          const sq_domain_options *opt, sq_domain *D, sq_error *err);

/* Q glued along every identified pair of sides: a closed quad mesh. Its
 * vertices are the classes of Q's vertices; closed_of (Q->nv entries,
 * caller-owned, may be NULL) maps each vertex of Q to its class. out
 * receives faces and, when xy (2 per vertex of Q) is given, positions
 * (x, y, 0) of one representative; otherwise zeros. */
sq_status sq_domain_glue(const sq_domain *D, const double *xy, sq_soup *out,
                         uint32_t *closed_of, sq_error *err);

/* The vertices of side i of Q, from corner i to corner i+1 (side_len[i]+1
 * entries, caller-owned). */
void sq_domain_side_vertices(const sq_domain *D, uint32_t side, uint32_t *verts);

/* Independent check of the result, for tests and the CLI: Q is a valid quad
 * disk whose corners are exactly the k corner vertices, identified sides
 * have equal lengths, and the glued mesh is closed, manifold, oriented,
 * connected, of genus g, with vertices of valence != 4 exactly the cones.
 * SQ_ERR_INTERNAL names the first violation. */
sq_status sq_domain_verify(const sq_domain *D, const int32_t *valences, uint32_t ncones,
                           sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
