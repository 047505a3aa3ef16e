/* seamquad: per-face frames and the discrete Levi-Civita connection between
 * neighbouring faces, shared by the cross-field files (internal header).
 *
 * Face f's frame: e1 = unit vector along its first halfedge (m->f_he[f]),
 * n = unit normal (right-hand rule over the corner order), e2 = n x e1. A
 * direction at angle a in face f, carried across the edge of halfedge h
 * (face f) into g = face(twin h) by unfolding g into f's plane, has angle
 * a + r_h in g's frame. For 4-direction fields only 4 r_h matters, and we
 * store rot[h] = 4 r_h for the halfedge of each edge with h < twin(h) and
 * rot[twin h] = -rot[h] exactly, so rot is antisymmetric bit for bit. */
#ifndef SQ_CROSS_FIELD_FRAMES_H
#define SQ_CROSS_FIELD_FRAMES_H

#include "sq_error.h"
#include "sq_mesh.h"

#define SQ_CROSS_FIELD_PI 3.14159265358979323846

typedef struct sq_cross_field_frames {
    uint32_t nf, nh;
    double *e1, *e2, *n; /* 3*nf each                                   */
    double *area;        /* nf, face area / total area (sums to 1)      */
    double total_area;   /* in the mesh's units                         */
    double *rot;         /* nh, 4 r_h as above                          */
} sq_cross_field_frames;

sq_status sq_cross_field_frames_build(const sq_mesh *m, sq_cross_field_frames *fr,
                                      sq_error *err);
void sq_cross_field_frames_free(sq_cross_field_frames *fr);

/* Previous halfedge in a triangle. */
static inline uint32_t sq_cross_field_prev(const sq_mesh *m, uint32_t h)
{
    return m->he_next[m->he_next[h]];
}

#endif
