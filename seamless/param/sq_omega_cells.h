/* seamquad: Omega cut into rectangles by straight chords (seed 8, interior
 * map; seamless-notes 5, "compatible triangulation", with rectangles for
 * triangles).
 *
 * Omega_c (sq_omega.h) is a disk of unit squares laid out with integer
 * corners; every interior vertex is regular, so grid lines run straight
 * through it. From every boundary vertex whose sector spans 3 or more
 * quads (a reflex corner: 270 degrees or more, e.g. at cone copies and at
 * turns of the cone tree) chords are shot along interior grid edges until
 * they reach the boundary of Omega_c or an earlier chord. Afterwards every
 * cell (a connected set of quads not separated by the boundary or a chord)
 * is a rectangle: a flat disk whose boundary turns left exactly four times,
 * hence an embedded axis-aligned rectangle even where Omega overlaps
 * itself.
 *
 * The surface stage (sq_param_interior.c) replays the chords, in this order, as paths
 * on the cut surface and maps every surface cell onto its rectangle (Tutte,
 * convex target). For that replay a chord names its two ends by the
 * halfedge that bounds the end's sector on its clockwise side, at the
 * moment the chord is added (see sq_omega_chord).
 *
 * Chords are few (docs/omega.md section 6): a sector of q >= 3 quads gets
 * floor((q - 1) / 2) chords, minus those that a chord arriving from another
 * reflex corner already provides; sectors are recomputed from the current
 * chord set after every chord, so cells = chords + 1.
 *
 * Conventions are those of sq_metapolygon / sq_omega: faces are
 * counterclockwise; boundary halfedges run clockwise; a "face halfedge" is
 * one with a face on its left. The sector of a face halfedge h leaving
 * vertex v is the fan of faces around v from face(h) counterclockwise up to
 * (not across) the next boundary or chord edge.
 */
#ifndef SQ_OMEGA_CELLS_H
#define SQ_OMEGA_CELLS_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_omega.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sq_omega_chord {
    uint32_t len;         /* unit edges, >= 1                                */
    uint32_t he_off;      /* the chord's halfedges of O->cut are             */
                          /* cells.chord_he[he_off .. he_off + len - 1],     */
                          /* face halfedges directed from start to end       */
    /* Start: O->cut vertex he_vert[first chord halfedge], a boundary
     * vertex of Omega_c, or (a chord that splits a long cell, see
     * sq_omega_cells_build) a vertex of an earlier chord. start_sector: the face halfedge of
     * O->cut leaving the start vertex that bounds, on its clockwise side,
     * the sector the chord leaves through at the moment it is added (the
     * chord's first halfedge is reached from it counterclockwise before any
     * other boundary or chord edge). Its edge is either a boundary edge of
     * Omega_c (then it is the twin of the boundary halfedge ENTERING the
     * vertex: boundary halfedges run clockwise, so the face halfedge
     * leaving v along a boundary edge is the twin of the incoming one) or
     * an earlier chord through the vertex: the first halfedge of an earlier
     * chord starting there, or the twin of the last halfedge of an earlier
     * chord ending there. Chords from one vertex are not necessarily added
     * in counterclockwise order (a chord that serves two reflex corners
     * goes first), which is why the sector is named at the moment of
     * adding: replaying the chords in order, the named sector always
     * exists and the chord is the only one inside it. */
    uint32_t start_sector;
    /* End: the head of the last chord halfedge; either a boundary vertex of
     * Omega_c or a vertex on an earlier chord (inside Omega_c: a
     * T-junction). The chord stops at the first such vertex. end_sector:
     * likewise the face halfedge leaving the end vertex that bounds, on its
     * clockwise side, the sector the chord arrives in (before the chord
     * splits it; the twin of the chord's last halfedge is reached from it
     * counterclockwise before any other boundary or chord edge): the twin
     * of the boundary halfedge entering the end vertex, or a halfedge of an
     * earlier chord leaving the end vertex (in either direction along that
     * chord). */
    uint32_t end_sector;
} sq_omega_chord;

typedef struct sq_omega_cells {
    uint32_t nchords;
    sq_omega_chord *chord;  /* nchords, in the order they were added         */
    uint32_t *chord_he;     /* sum of len: halfedges of O->cut               */
    uint8_t *he_chord;      /* O->cut.nh: 1 where the halfedge's edge lies   */
                            /* on a chord                                    */
    uint32_t ncells;
    uint32_t *f_cell;       /* O->cut.nf: the cell of each face              */
    int64_t *cell_box;      /* 4 ncells: xmin, ymin, xmax, ymax              */
} sq_omega_cells;

void sq_omega_cells_init(sq_omega_cells *C);
void sq_omega_cells_free(sq_omega_cells *C);

/* Shoots the chords and labels the cells (C replaced; must be initialized).
 * max_side > 0: then every cell wider or taller than max_side is halved
 * across its longer dimension, repeatedly (chords that start on a side of
 * the cell: a boundary vertex or a vertex of an earlier chord), so that
 * every cell is at most max_side x max_side; 0: only the chords the
 * reflex corners need. face_limit (NULL: none; else O->cut.nf entries):
 * likewise per quad, a cell is halved while it is wider or taller than
 * the smallest limit of its quads (0 counts as 1).
 * Verifies before returning (SQ_ERR_INTERNAL naming the first violation):
 * every cell is a rectangle exactly filled by its quads (quads = area of
 * cell_box, every quad's layout inside the box, the box's boundary made of
 * boundary or chord edges); every chord is straight (one direction),
 * runs through interior edges only, and every vertex strictly inside a
 * chord is an interior vertex of Omega_c; no sector of a vertex spans more
 * than two quads between consecutive boundary or chord edges; the sector
 * names; cells = connected pieces between chords
 * (sq_omega_cells_verify, sq_omega_cells_internal.h, has the full list).
 * SQ_ERR_ARGUMENT if a face of O is not a quad or the boundary loop is
 * broken (O not built by sq_omega_build). */
sq_status sq_omega_cells_build(const sq_omega *O, uint32_t max_side, const uint32_t *face_limit,
                               sq_omega_cells *C, sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
