/* seamquad: the seam rotations a smooth cross field with exactly the given
 * cones has around every loop of the surface.
 *
 * A seamless map with cones C has, around any closed loop that avoids the
 * cones, a rotation by k x 90 degrees (its holonomy). Around a cone it is
 * fixed by the cone's angle; around the 2g handle loops it is a choice,
 * and it decides how good the map can be: a map whose handle rotations
 * disagree with those of a smooth cross field having these cones is
 * distorted whatever optimizer follows (docs/holonomy.md). This file
 * computes the smooth field's rotations as a connection: a transport angle
 * across every edge, in quarter turns, whose sum over any closed loop of
 * faces is an integer, the loop's rotation.
 *
 * Method (a trivial connection, after Crane, Desbrun and Schroeder 2010,
 * "Trivial Connections on Discrete Surfaces"): the Levi-Civita transport
 * rho across each edge (unfolding the two faces), plus the smallest
 * correction a (norm sum w_e a_e^2, w_e = |e|^2 / (area f + area g)) such
 * that the total rotation around every vertex is its prescribed cone angle
 * defect (4 - valence) quarter turns exactly, and around each of 2g
 * tree-cotree generator loops an integer number of quarter turns; the
 * integers are those of the closest lattice point in the correction's
 * norm (enumerated exactly up to genus 5, by coordinate descent beyond).
 * Cost: one sparse Cholesky of the vertex Laplacian and one of the face
 * Laplacian (2g right-hand sides).
 *
 * The library never prints or exits. */
#ifndef SQ_CONE_CONNECTION_H
#define SQ_CONE_CONNECTION_H

#include <stdint.h>

#include "sq_error.h"
#include "sq_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sq_cone_connection_stats {
    uint32_t genus;
    double energy;          /* sum w_e a_e^2 of the correction              */
    double max_residual;    /* largest distance of a vertex or generator    */
                            /* loop's total from its integer, quarter turns */
    int exact_lattice;      /* 1: the generators' integers were enumerated  */
} sq_cone_connection_stats;

/* turn[h] (caller-owned, m->nh entries): the transport from face(h) to
 * face(twin(h)) across h's edge, in quarter turns; turn[twin(h)] =
 * -turn[h]. For a closed loop of faces crossing halfedges h_1..h_n (each
 * from its face into its twin's), sum turn[h_i] is within 1e-6 of an
 * integer: the rotation of the field (and of any seamless map with the
 * same handle rotations) around it, counterclockwise positive; around a
 * vertex v (crossing he_prev of each outgoing halfedge) it is
 * 4 - valence[v]. valence: nv entries, satisfying Gauss-Bonnet (sum of
 * 4 - valence = 4 chi); SQ_ERR_ARGUMENT otherwise. stats may be NULL. */
sq_status sq_cone_connection(const sq_mesh *m, const int32_t *valence, double *turn,
                             sq_cone_connection_stats *stats, sq_error *err);

/* Sum of turn over the crossed halfedges, rounded to the nearest integer
 * and reduced to 0..3. */
uint32_t sq_cone_connection_rotation(const double *turn, const uint32_t *crossed, uint32_t n);

#ifdef __cplusplus
}
#endif

#endif
