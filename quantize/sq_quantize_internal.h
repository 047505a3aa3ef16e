/* seamquad: the T-mesh layout of a split map, shared by the quantization
 * steps (sq_quantize_layout.c, sq_quantize_embed.c). Not a public header. */
#ifndef SQ_QUANTIZE_INTERNAL_H
#define SQ_QUANTIZE_INTERNAL_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_map.h"
#include "sq_map_split.h"

/* The T-mesh read off a split map: faces are the components of the split
 * triangles across edges off the chords (each an axis-aligned rectangle of
 * the map), arcs the chains of chord edges between nodes (cones, vertices
 * on three or more chord edges, face corners). */
typedef struct sq_qlayout {
    uint32_t np;          /* faces (patches)                                   */
    uint32_t *tri_patch;  /* nt: the patch of each split triangle              */
    uint8_t *tri_rot;     /* nt: X_t, the split triangle's chart (its mesh     */
    double *tri_shift;    /* 2 nt: face's) to the patch's local frame:        */
                          /* p -> R^rot p + shift, the patch [0,W] x [0,H]     */
                          /* with its bottom along +u from (0, 0)              */
    double *W, *H;        /* np                                               */
    uint32_t *corner_he;  /* 4 np: the first boundary halfedge of each side    */
                          /* (side 0 starts at the lower-left corner)          */
    uint8_t *v_node;      /* nv (split): 1 at nodes                            */
    uint32_t na;          /* arcs                                              */
    uint32_t *he_arc;     /* nh (split): the arc of a chord halfedge, or       */
                          /* UINT32_MAX                                        */
    uint8_t *he_fwd;      /* nh: 1 where the halfedge runs along its arc       */
    uint32_t *he_pos;     /* nh: index of the halfedge's origin along its arc  */
                          /* (0 at the arc's first node), forward direction    */
    uint32_t *arc_nv;     /* na: vertices along the arc including both nodes   */
    uint32_t *arc_end;    /* 2 na: its first and last node (split vertices)    */
    double *arc_len;      /* na: parametric length                             */
    double *arc_len3d;    /* na: length on the surface                         */
    double *arc_dist;     /* the parametric distance of each arc vertex from   */
    uint32_t *arc_off;    /* its first node: arc_dist[arc_off[a] + i]          */
    uint32_t *side_off;   /* 4 np + 1: side s of patch p is side_arc[...]      */
    uint32_t *side_arc;
    uint8_t *side_rev;    /* 1 where the side runs the arc backwards           */
} sq_qlayout;

/* The layout of S (split from M along chords). Refused (SQ_ERR_INTERNAL,
 * naming the patch) where a component is not a rectangle with 4 convex
 * corners, or its charts do not agree. */
sq_status sq_qlayout_build(const sq_map *M, const sq_split *S, sq_qlayout *L, sq_error *err);
void sq_qlayout_free(sq_qlayout *L);

/* The split triangles of each patch, in order: those of patch p are
 * list[off[p] .. off[p + 1]) (off: np + 1 entries, list: nt; the caller
 * allocates both). */
void sq_qlayout_patch_triangles(const sq_split *S, const sq_qlayout *L, uint32_t *off, uint32_t *list);

/* The boundary halfedge of a patch that follows h (a chord halfedge with
 * the patch on its left): around h's end, inside the patch. */
uint32_t sq_qlayout_next_boundary(const sq_split *S, uint32_t h);

/* The integer-grid map: every patch re-embedded onto its integer rectangle
 * for the arc lengths `length` (na), assembled and checked exactly
 * (sq_map_from_soup with SQ_MAP_REQUIRE_EXACT | SQ_MAP_REQUIRE_INTEGER).
 * *fallback receives the patches that needed a fallback (sq_patch_embed:
 * not the surface's mean-value map). failed (np, or NULL): where given,
 * a patch that sq_patch_embed cannot place is marked 1 and the others are
 * still tried; SQ_ERR_SOLVER then names the first. */
sq_status sq_qlayout_embed(const sq_map *M, const sq_split *S, const sq_qlayout *L,
                           const int64_t *length, sq_map *igm, uint32_t *fallback, uint8_t *failed,
                           sq_error *err);

/* Refinement for the patches marked in failed (np): chords (appended to
 * *chords, *n of them, *cap allocated) that cut each such patch along the
 * sweep's kink lines (sq_patch_embed.h: the lines u = c through the nodes
 * on its bottom and top sides, v = c through those on its left and right)
 * and, for grid > 1, along the lines dividing it into grid x grid equal
 * cells. Each chord is refinement only (an empty extent: it lies on no
 * arc), in the chart of every mesh face of the patch that the line
 * crosses; a line within 1e-9 of the patch's size of a line the face is
 * already cut along is that line. */
sq_status sq_qlayout_refine_chords(const sq_split *S, const sq_qlayout *L, const uint8_t *failed,
                                   uint32_t grid, sq_chord **chords, uint32_t *n, uint32_t *cap,
                                   sq_error *err);

#endif
