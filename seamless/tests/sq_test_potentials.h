/* seamquad tests: potentials of a per-halfedge quantity over a face
 * spanning tree, for checking what a quantity sums to around every closed
 * loop of faces (include after cmocka.h). */
#ifndef SQ_TEST_POTENTIALS_H
#define SQ_TEST_POTENTIALS_H

#include <stdint.h>
#include <stdlib.h>

#include "sq_mesh.h"

/* phi (nf) over a breadth-first face tree from face 0: phi[0] = 0 and
 * phi[g] = phi[f] + d[h] for the tree edge h of face f whose twin lies in
 * g. Around every closed loop of faces, d sums to an integer iff every
 * halfedge h (face f, twin's face g) has phi[f] + d[h] - phi[g] in Z
 * (the tree's fundamental loops generate them all). Fails the test when a
 * face is not reached (the mesh is not connected). */
static inline void sq_test_face_potentials(const sq_mesh *m, const double *d, double *phi)
{
    uint32_t *queue = malloc((size_t)m->nf * sizeof *queue);
    uint8_t *seen = calloc(m->nf, 1);
    assert_true(queue && seen);
    uint32_t qh = 0, qt = 0;
    queue[qt++] = 0, seen[0] = 1, phi[0] = 0.0;
    while (qh < qt) {
        const uint32_t f = queue[qh++], h0 = m->f_he[f];
        uint32_t h = h0;
        do {
            const uint32_t g = m->he_face[m->he_twin[h]];
            if (!seen[g]) seen[g] = 1, phi[g] = phi[f] + d[h], queue[qt++] = g;
            h = m->he_next[h];
        } while (h != h0);
    }
    assert_int_equal(qt, m->nf);
    free(queue), free(seen);
}

#endif
