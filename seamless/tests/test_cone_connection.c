/* The smooth cross field's rotations as a connection (sq_cone_connection.h)
 * and the cut graph steered to them (sq_cut_graph_steer), on the real
 * meshes and cone files of ../shared/data and on random cone sets:
 *  - the connection: antisymmetric; around every vertex exactly its cone's
 *    index (4 - valence) quarter turns; around every closed loop of faces
 *    an integer (checked independently: a face tree, then every edge);
 *    Gauss-Bonnet violations refused;
 *  - steering: where the hole chain of mpz/holes3, genus3, cup, sculpt and
 *    block disagrees with the field's rotations (mismatch > 0), the steered
 *    graph has mismatch 0, passes sq_cut_graph_check and an independent
 *    disk check, keeps its pattern's genus, size and rank, and no cone
 *    lies on it; on random cone sets the mismatch never grows and every
 *    steered graph passes the checks.
 * (That maps built on a steered graph have the field's rotations is
 * checked on param's maps in stages/tests/test_rotations.c.) */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_clock.h"
#include "sq_cone_connection.h"
#include "sq_cut_graph.h"
#include "sq_mesh.h"
#include "sq_pattern.h"
#include "sq_test_cut.h"
#include "sq_test_mesh.h"
#include "sq_test_potentials.h"
#include "sq_test_random.h"

/* Every closed loop of faces has an integer total turn: the largest
 * distance from an integer of phi[f] + turn[h] - phi[g] over the
 * halfedges, phi the face-tree potentials (sq_test_potentials.h). */
static double loop_integrality(const sq_mesh *m, const double *turn)
{
    double *phi = malloc((size_t)m->nf * sizeof *phi);
    assert_non_null(phi);
    sq_test_face_potentials(m, turn, phi);
    double worst = 0.0;
    for (uint32_t h = 0; h < m->nh; ++h) {
        const double d = phi[m->he_face[h]] + turn[h] - phi[m->he_face[m->he_twin[h]]];
        const double r = fabs(d - nearbyint(d));
        if (r > worst) worst = r;
    }
    free(phi);
    return worst;
}

static void check_connection(const sq_mesh *m, const int32_t *val, const char *what)
{
    double *turn = malloc((size_t)m->nh * sizeof *turn);
    assert_non_null(turn);
    sq_error err;
    sq_cone_connection_stats st;
    if (sq_cone_connection(m, val, turn, &st, &err)) fail_msg("%s: %s", what, err.msg);
    assert_int_equal(st.genus, (uint32_t)sq_mesh_genus(m));
    for (uint32_t h = 0; h < m->nh; ++h) assert_true(turn[h] == -turn[m->he_twin[h]]);
    for (uint32_t v = 0; v < m->nv; ++v) { /* the loop around v: he_prev of each outgoing */
        double s = 0.0;
        const uint32_t h0 = m->v_he[v];
        uint32_t h = h0;
        do {
            uint32_t p = h;
            while (m->he_next[p] != h) p = m->he_next[p];
            s += turn[p];
            h = m->he_next[m->he_twin[h]];
        } while (h != h0);
        const double want = 4 - val[v];
        const double k = (s - want) / 4.0;
        if (fabs(k - nearbyint(k)) > 1e-8)
            fail_msg("%s: vertex %u turns %.12g quarter turns, its cone %g", what, v, s, want);
    }
    const double r = loop_integrality(m, turn);
    if (r > 1e-8) fail_msg("%s: a loop of faces turns %g from an integer", what, r);
    free(turn);
}

static void test_connection_shared(void **state)
{
    (void)state;
    static const char *models[] = {"eight", "holes3", "genus3", "knot1", "fandisk", "helmet"};
    for (size_t i = 0; i < sizeof models / sizeof *models; ++i) {
        char mesh[128], cones[128];
        snprintf(mesh, sizeof mesh, "mpz/%s.obj", models[i]);
        snprintf(cones, sizeof cones, "mpz/%s_Th_hat", models[i]);
        sq_mesh m;
        sq_test_load_mesh(&m, mesh);
        int32_t *val = sq_test_load_valence(cones, m.nv);
        check_connection(&m, val, models[i]);
        free(val);
        sq_mesh_free(&m);
    }
}

/* Random admissible cone sets on meshes of genus 0 to 3. */
static void test_connection_random(void **state)
{
    (void)state;
    static const char *meshes[] = {"mpz/fandisk.obj", "mpz/knot1.obj", "mpz/eight.obj", "mpz/holes3.obj"};
    rng_state = 0x5eed0c0ull;
    const uint32_t rounds = long_mode() ? 200 : 8;
    for (size_t i = 0; i < sizeof meshes / sizeof *meshes; ++i) {
        sq_mesh m;
        sq_test_load_mesh(&m, meshes[i]);
        const int64_t chi = sq_mesh_euler(&m);
        int32_t *val = malloc((size_t)m.nv * sizeof *val);
        assert_non_null(val);
        for (uint32_t r = 0; r < rounds; ++r) {
            /* 4 chi quarter turns spread as valence-3 / valence-5 cones,
             * plus cancelling pairs */
            for (uint32_t v = 0; v < m.nv; ++v) val[v] = 4;
            int64_t need = 4 * chi;
            uint32_t pairs = rnd(6);
            while (need != 0 || pairs) {
                const uint32_t v = rnd(m.nv);
                if (val[v] != 4) continue;
                if (need > 0) val[v] = 3, --need;
                else if (need < 0) val[v] = 5, ++need;
                else {
                    const uint32_t u = rnd(m.nv);
                    if (u == v || val[u] != 4) continue;
                    val[v] = 3, val[u] = 5, --pairs;
                }
            }
            char what[160];
            snprintf(what, sizeof what, "%s, random cones %u", meshes[i], r);
            check_connection(&m, val, what);
        }
        free(val);
        sq_mesh_free(&m);
    }
}

static void test_connection_refuses_gauss_bonnet(void **state)
{
    (void)state;
    sq_mesh m;
    sq_test_load_mesh(&m, "mpz/eight.obj");
    int32_t *val = malloc((size_t)m.nv * sizeof *val);
    double *turn = malloc((size_t)m.nh * sizeof *turn);
    assert_true(val && turn);
    for (uint32_t v = 0; v < m.nv; ++v) val[v] = 4; /* genus 2 needs -8 */
    sq_error err;
    assert_int_equal(sq_cone_connection(&m, val, turn, NULL, &err), SQ_ERR_ARGUMENT);
    assert_non_null(strstr(err.msg, "Gauss-Bonnet"));
    free(val), free(turn);
    sq_mesh_free(&m);
}

/* The steered graph: every check of an unsteered one, same pattern size,
 * genus and rank, no cone on it, mismatch as reported. */
static void check_steered(const sq_mesh *m, const int32_t *val, const double *turn,
                          const sq_cut_graph *G0, const sq_cut_graph *G, const sq_cut_steer_stats *ss,
                          const char *what)
{
    sq_error err;
    uint8_t *cone = calloc(m->nv, 1);
    assert_non_null(cone);
    for (uint32_t v = 0; v < m->nv; ++v) cone[v] = val[v] != 4;
    if (sq_cut_graph_check(m, cone, G, &err)) fail_msg("%s: steered graph: %s", what, err.msg);
    for (uint32_t h = 0; h < m->nh; ++h)
        if (G->he_cut[h] && cone[m->he_vert[h]]) fail_msg("%s: cone %u on the cut", what, m->he_vert[h]);
    uint32_t loops = 0;
    const int64_t chi = cut_soup_euler(m, G->he_cut, &loops);
    if (chi != 1 || loops != 1) fail_msg("%s: the cut surface has chi %lld, %u boundary loops", what, (long long)chi, loops);
    sq_pattern_info i0, i1;
    assert_int_equal(sq_pattern_validate(&G0->pattern, &i0, &err), SQ_OK);
    assert_int_equal(sq_pattern_validate(&G->pattern, &i1, &err), SQ_OK);
    assert_int_equal(G->pattern.k, G0->pattern.k);
    assert_int_equal(i1.genus, i0.genus);
    assert_int_equal(i1.rank, i0.rank);
    uint32_t norm = 0, wrong = 0;
    assert_int_equal(sq_cut_graph_rotation_mismatch(m, G, turn, &norm, &wrong, &err), SQ_OK);
    assert_int_equal(norm, ss->norm_after);
    assert_int_equal(wrong, ss->wrong_loops_after);
    assert_true(ss->norm_after <= ss->norm_before);
    assert_true(norm > 0 || wrong == 0);
    free(cone);
}

static void steer_model(const char *name, uint32_t *before, uint32_t *after)
{
    char mesh[128], cones[128];
    snprintf(mesh, sizeof mesh, "mpz/%s.obj", name);
    snprintf(cones, sizeof cones, "mpz/%s_Th_hat", name);
    sq_mesh m;
    sq_test_load_mesh(&m, mesh);
    int32_t *val = sq_test_load_valence(cones, m.nv);
    uint8_t *cone = calloc(m.nv, 1);
    double *turn = malloc((size_t)m.nh * sizeof *turn);
    assert_true(cone && turn);
    for (uint32_t v = 0; v < m.nv; ++v) cone[v] = val[v] != 4;
    sq_error err;
    if (sq_cone_connection(&m, val, turn, NULL, &err)) fail_msg("%s: %s", name, err.msg);
    sq_cut_options o;
    sq_cut_options_default(&o);
    o.seed = 1;
    sq_cut_graph G0, G;
    sq_cut_graph_init(&G0), sq_cut_graph_init(&G);
    if (sq_cut_graph_build(&m, cone, &o, &G0, NULL, &err)) fail_msg("%s: %s", name, err.msg);
    if (sq_cut_graph_build(&m, cone, &o, &G, NULL, &err)) fail_msg("%s: %s", name, err.msg);
    sq_cut_steer_stats ss;
    const double t0 = sq_now();
    if (sq_cut_graph_steer(&m, val, turn, &G, &ss, &err)) fail_msg("%s: steer: %s", name, err.msg);
    const double seconds = sq_now() - t0;
    uint32_t norm0 = 0;
    assert_int_equal(sq_cut_graph_rotation_mismatch(&m, &G0, turn, &norm0, NULL, &err), SQ_OK);
    assert_int_equal(norm0, ss.norm_before);
    check_steered(&m, val, turn, &G0, &G, &ss, name);
    print_message("%-8s mismatch %u -> %u, %u reroutes, cut length %.4g -> %.4g, %.2f s\n", name, ss.norm_before,
                  ss.norm_after, ss.reroutes, ss.length_before, ss.length_after, seconds);
    *before = ss.norm_before, *after = ss.norm_after;
    sq_cut_graph_free(&G0), sq_cut_graph_free(&G);
    free(val), free(cone), free(turn);
    sq_mesh_free(&m);
}

static void test_steer_shared(void **state)
{
    (void)state;
    static const char *models[] = {"holes3", "genus3", "cup", "sculpt", "block"};
    for (size_t i = 0; i < sizeof models / sizeof *models; ++i) {
        uint32_t before, after;
        steer_model(models[i], &before, &after);
        if (before == 0) fail_msg("%s: the hole chain already had the field's rotations", models[i]);
        if (after != 0) fail_msg("%s: mismatch %u left after steering", models[i], after);
    }
    uint32_t before, after; /* already right: nothing moves */
    steer_model("eight", &before, &after);
    assert_int_equal(before, 0);
    assert_int_equal(after, 0);
}

static void test_steer_random(void **state)
{
    (void)state;
    static const char *meshes[] = {"mpz/eight.obj", "mpz/holes3.obj"};
    rng_state = 0x57ee2ull;
    const uint32_t rounds = long_mode() ? 60 : 3;
    uint32_t zero = 0, total = 0;
    for (size_t i = 0; i < sizeof meshes / sizeof *meshes; ++i) {
        sq_mesh m;
        sq_test_load_mesh(&m, meshes[i]);
        const uint32_t g = (uint32_t)sq_mesh_genus(&m);
        int32_t *val = malloc((size_t)m.nv * sizeof *val);
        int32_t list[64];
        uint8_t *cone = calloc(m.nv, 1);
        double *turn = malloc((size_t)m.nh * sizeof *turn);
        assert_true(val && cone && turn);
        for (uint32_t r = 0; r < rounds; ++r) {
            const uint32_t n = random_cones(g, list, 64);
            for (uint32_t v = 0; v < m.nv; ++v) val[v] = 4;
            for (uint32_t c = 0; c < n;) {
                const uint32_t v = rnd(m.nv);
                if (val[v] == 4) val[v] = list[c++];
            }
            for (uint32_t v = 0; v < m.nv; ++v) cone[v] = val[v] != 4;
            sq_error err;
            if (sq_cone_connection(&m, val, turn, NULL, &err)) fail_msg("%s: %s", meshes[i], err.msg);
            sq_cut_options o;
            sq_cut_options_default(&o);
            o.seed = 1 + r;
            sq_cut_graph G0, G;
            sq_cut_graph_init(&G0), sq_cut_graph_init(&G);
            if (sq_cut_graph_build(&m, cone, &o, &G0, NULL, &err) ||
                sq_cut_graph_build(&m, cone, &o, &G, NULL, &err)) {
                /* cones walling a route off: the cut graph's own limit */
                sq_cut_graph_free(&G0), sq_cut_graph_free(&G);
                continue;
            }
            sq_cut_steer_stats ss;
            if (sq_cut_graph_steer(&m, val, turn, &G, &ss, &err)) fail_msg("%s: steer: %s", meshes[i], err.msg);
            char what[160];
            snprintf(what, sizeof what, "%s, random cones %u", meshes[i], r);
            check_steered(&m, val, turn, &G0, &G, &ss, what);
            zero += ss.norm_after == 0, ++total;
            sq_cut_graph_free(&G0), sq_cut_graph_free(&G);
        }
        free(val), free(cone), free(turn);
        sq_mesh_free(&m);
    }
    print_message("random cone sets: %u of %u steered to the field's rotations\n", zero, total);
    assert_true(total > 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_connection_shared),
        cmocka_unit_test(test_connection_random),
        cmocka_unit_test(test_connection_refuses_gauss_bonnet),
        cmocka_unit_test(test_steer_shared),
        cmocka_unit_test(test_steer_random),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
