/* Property tests of the editable triangle surface (sq_tsurf.h) on real
 * meshes of ../shared/data: random edge splits, cuts, region boundaries,
 * sectors, opening of sectors and vertices, and blocking-edge splits (the
 * routes: test_tsurf_route.c).
 * Every operation is followed by an independent check of the whole
 * structure (check_tsurf). Seeded; SQ_LONG_TESTS=1 runs many more rounds. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_io.h"
#include "sq_mesh.h"
#include "sq_test_mesh.h"
#include "sq_test_random.h"
#include "sq_tsurf.h"
#include "sq_test_tsurf.h"

/* ---- 1. random splits ----------------------------------------------------- */

/* forig: every face of S lies in the input face of m it names, oriented
 * like it, and the faces of each input face add up to its area. */
static void check_forig(const sq_mesh *pm, const sq_tsurf *pS)
{
    const sq_mesh m = *pm;
    const sq_tsurf S = *pS;
    double *farea = calloc(m.nf, sizeof *farea);
    assert_non_null(farea);
    for (uint32_t f = 0; f < S.nf; f++) {
        uint32_t F = S.forig[f], e = m.f_he[F];
        assert_true(F < m.nf);
        const double *q[3];
        for (int i = 0; i < 3; i++, e = m.he_next[e]) q[i] = m.pos + 3 * (size_t)m.he_vert[e];
        double n[3], u[3] = {q[1][0] - q[0][0], q[1][1] - q[0][1], q[1][2] - q[0][2]},
                     w[3] = {q[2][0] - q[0][0], q[2][1] - q[0][1], q[2][2] - q[0][2]};
        n[0] = u[1] * w[2] - u[2] * w[1], n[1] = u[2] * w[0] - u[0] * w[2], n[2] = u[0] * w[1] - u[1] * w[0];
        double nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        uint32_t h = S.f_he[f];
        const double *p[3];
        for (int i = 0; i < 3; i++, h = S.next[h]) p[i] = S.pos + 3 * (size_t)S.vert[h];
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++) {
                /* on the inner side of input edge k (relative to its area) */
                const double *a = q[k], *b = q[(k + 1) % 3];
                double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, ap[3] = {p[i][0] - a[0], p[i][1] - a[1], p[i][2] - a[2]};
                double cx = ab[1] * ap[2] - ab[2] * ap[1], cy = ab[2] * ap[0] - ab[0] * ap[2], cz = ab[0] * ap[1] - ab[1] * ap[0];
                assert_true((cx * n[0] + cy * n[1] + cz * n[2]) / nn >= -1e-9 * nn);
            }
        double g1[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]},
               g2[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
        double t[3] = {g1[1] * g2[2] - g1[2] * g2[1], g1[2] * g2[0] - g1[0] * g2[2], g1[0] * g2[1] - g1[1] * g2[0]};
        assert_true(t[0] * n[0] + t[1] * n[1] + t[2] * n[2] > 0);
        farea[F] += 0.5 * sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    }
    for (uint32_t F = 0; F < m.nf; F++) {
        uint32_t e = m.f_he[F];
        const double *q0 = m.pos + 3 * (size_t)m.he_vert[e], *q1 = m.pos + 3 * (size_t)m.he_vert[m.he_next[e]],
                     *q2 = m.pos + 3 * (size_t)m.he_vert[m.he_next[m.he_next[e]]];
        double u[3] = {q1[0] - q0[0], q1[1] - q0[1], q1[2] - q0[2]}, w[3] = {q2[0] - q0[0], q2[1] - q0[1], q2[2] - q0[2]};
        double cx = u[1] * w[2] - u[2] * w[1], cy = u[2] * w[0] - u[0] * w[2], cz = u[0] * w[1] - u[1] * w[0];
        double a = 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
        assert_true(fabs(farea[F] - a) <= 1e-9 * a);
    }
    free(farea);
}

static void split_run(const char *rel, uint32_t nsplit)
{
    sq_mesh m;
    sq_tsurf S;
    sq_error err;
    sq_test_load_mesh(&m, rel);
    sq_tsurf_init(&S);
    uint32_t *he_map = malloc(m.nh * sizeof *he_map);
    assert_non_null(he_map);
    assert_int_equal(sq_tsurf_from_mesh(&m, NULL, &S, he_map, &err), SQ_OK);
    int64_t euler = sq_mesh_euler(&m);
    double area0 = total_area(&S);
    assert_true(area0 > 0);
    check_tsurf(&S, euler, area0);
    /* he_map and face order */
    for (uint32_t h = 0; h < m.nh; h++) {
        uint32_t g = he_map[h];
        assert_true(g < S.nh);
        assert_int_equal(S.vert[g], m.he_vert[h]);
        assert_int_equal(sq_ts_head(&S, g), m.he_vert[m.he_next[h]]);
        assert_int_equal(S.face[g], m.he_face[h]);
        assert_int_equal(S.twin[g], he_map[m.he_twin[h]]);
    }
    for (uint32_t f = 0; f < m.nf; f++) assert_int_equal(he_map[m.f_he[f]], 3 * f);
    for (uint32_t v = 0; v < S.nv; v++) assert_int_equal(S.valence[v], 4);

    /* cut ~6% of the edges, labelled by their original halfedges */
    uint32_t nh0 = S.nh;
    uint8_t *okind = calloc(nh0, 1);
    double *olen = malloc(nh0 * sizeof *olen), *clen = calloc(nh0, sizeof *clen);
    assert_true(okind && olen && clen);
    for (uint32_t h = 0; h < nh0; h++) {
        if (rnd(33) || S.kind[h]) continue;
        uint8_t k = rnd(2) ? SQ_TS_SEAM : SQ_TS_CHORD;
        sq_tsurf_cut_edge(&S, h, k, h, S.twin[h]);
        okind[h] = okind[S.twin[h]] = k;
    }
    /* re-cutting keeps v_ncut (cut_edge on a cut edge only relabels) */
    for (uint32_t h = 0; h < nh0; h++)
        if (okind[h] && rnd(10) == 0) sq_tsurf_cut_edge(&S, h, okind[h], h, S.twin[h]);
    check_tsurf(&S, euler, area0);
    snap s0;
    snap_take(&s0, &S);
    for (uint32_t h = 0; h < nh0; h++) {
        double off;
        (void)off;
        const double *a = S.pos + 3 * s0.vert[h], *b = S.pos + 3 * s0.head[h];
        olen[h] = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    }

    for (uint32_t it = 0; it < nsplit; it++) {
        /* bias towards cut edges, so that cut state is split often */
        uint32_t h = rnd(S.nh);
        if (rnd(3) == 0)
            for (uint32_t k = 0; k < 20 && !S.kind[h]; k++) h = rnd(S.nh);
        double t = 0.05 + 0.9 * urand();
        uint32_t g = S.twin[h], a = S.vert[h], b = sq_ts_head(&S, h), c = S.vert[sq_ts_prev(&S, h)],
                 d = S.vert[sq_ts_prev(&S, g)];
        uint8_t kh = S.kind[h];
        uint32_t lh = S.label[h], lg = S.label[g], nv = S.nv, ncut_a = S.v_ncut[a], ncut_b = S.v_ncut[b];
        double pa[3], pb[3];
        memcpy(pa, S.pos + 3 * a, sizeof pa);
        memcpy(pb, S.pos + 3 * b, sizeof pb);
        uint32_t mv = sq_tsurf_split_edge(&S, h, t);
        assert_int_equal(mv, nv);
        assert_int_equal(S.nv, nv + 1);
        for (int i = 0; i < 3; i++) assert_true(fabs(S.pos[3 * mv + i] - ((1 - t) * pa[i] + t * pb[i])) <= 1e-12 * (1 + fabs(pa[i]) + fabs(pb[i])));
        /* h keeps its origin and direction; the two halves and their state */
        assert_int_equal(S.vert[h], a);
        assert_int_equal(sq_ts_head(&S, h), mv);
        assert_int_equal(S.vert[g], b);
        assert_int_equal(sq_ts_head(&S, g), mv);
        uint32_t h2 = sq_ts_find(&S, mv, b), g2 = S.twin[h];
        assert_int_equal(S.twin[h2], g);
        assert_int_equal(sq_ts_head(&S, g2), a);
        assert_int_equal(S.kind[h2], kh);
        assert_int_equal(S.kind[g2], kh);
        assert_int_equal(S.label[h2], lh);
        assert_int_equal(S.label[g2], lg);
        assert_int_equal(S.v_ncut[mv], kh ? 2u : 0u);
        assert_int_equal(S.v_ncut[a], ncut_a);
        assert_int_equal(S.v_ncut[b], ncut_b);
        assert_int_equal(S.valence[mv], 4);
        /* the new vertex sees a, b, c, d and nothing else */
        assert_int_not_equal(sq_ts_find(&S, mv, c), SQ_NONE);
        assert_int_not_equal(sq_ts_find(&S, mv, d), SQ_NONE);
        assert_int_equal(sq_ts_find(&S, a, b), SQ_NONE);
        uint32_t deg = 0, x = S.v_he[mv];
        do deg++, x = sq_ts_ccw(&S, x);
        while (x != S.v_he[mv]);
        assert_int_equal(deg, 4);
        if (it % 97 == 0) check_tsurf(&S, euler, area0);
    }
    check_tsurf(&S, euler, area0);
    check_since(&S, &s0, 0);
    /* cut pieces: on the segment of their label, same direction, same kind,
     * and together exactly the original edge */
    for (uint32_t x = 0; x < S.nh; x++) {
        if (!S.kind[x]) continue;
        uint32_t L = S.label[x];
        assert_true(L < nh0);
        assert_int_equal(okind[L], S.kind[x]);
        const double *a = s0.pos + 3 * s0.vert[L], *b = s0.pos + 3 * s0.head[L];
        double o1, o2, s1 = seg_param(a, b, S.pos + 3 * S.vert[x], &o1),
                       s2 = seg_param(a, b, S.pos + 3 * sq_ts_head(&S, x), &o2);
        assert_true(o1 < 1e-9 && o2 < 1e-9);
        assert_true(s1 > -1e-12 && s2 < 1 + 1e-12 && s2 > s1);
        clen[L] += (s2 - s1) * olen[L];
    }
    for (uint32_t h = 0; h < nh0; h++) {
        if (okind[h]) assert_true(fabs(clen[h] - olen[h]) <= 1e-9 * olen[h]);
        else assert_true(clen[h] == 0);
    }
    /* twin labels: a cut piece labelled L has a twin labelled twin0(L) */
    for (uint32_t x = 0; x < S.nh; x++) {
        if (!S.kind[x]) continue;
        uint32_t L = S.label[x], Lt = S.label[S.twin[x]];
        assert_true(Lt < nh0);
        assert_int_equal(s0.vert[Lt], s0.head[L]);
        assert_int_equal(s0.head[Lt], s0.vert[L]);
    }
    check_forig(&m, &S);
    snap_free(&s0);
    free(okind), free(olen), free(clen), free(he_map);
    sq_tsurf_free(&S);
    sq_mesh_free(&m);
}

static void test_split_random(void **state)
{
    (void)state;
    rng_state = 0x75A1;
    int L = long_mode();
    split_run("mpz/knot1.obj", L ? 20000 : 1500);
    split_run("mpz/eight.obj", L ? 30000 : 2500);
    if (L) split_run("libigl/bunny.off", 30000);
}

/* sq_tsurf_copy: a deep copy, equal array by array (forig too), that then changes
 * independently of its source (the refinement rounds of sq_param restore
 * the surface from one). */
static void assert_tsurf_equal(const sq_tsurf *a, const sq_tsurf *b)
{
    assert_true(a->nv == b->nv && a->nf == b->nf && a->nh == b->nh && a->nv_input == b->nv_input);
    assert_memory_equal(a->pos, b->pos, 3 * (size_t)a->nv * sizeof *a->pos);
    assert_memory_equal(a->v_he, b->v_he, a->nv * sizeof *a->v_he);
    assert_memory_equal(a->v_ncut, b->v_ncut, a->nv * sizeof *a->v_ncut);
    assert_memory_equal(a->valence, b->valence, a->nv * sizeof *a->valence);
    assert_memory_equal(a->f_he, b->f_he, a->nf * sizeof *a->f_he);
    assert_memory_equal(a->forig, b->forig, a->nf * sizeof *a->forig);
    assert_memory_equal(a->vert, b->vert, a->nh * sizeof *a->vert);
    assert_memory_equal(a->next, b->next, a->nh * sizeof *a->next);
    assert_memory_equal(a->face, b->face, a->nh * sizeof *a->face);
    assert_memory_equal(a->twin, b->twin, a->nh * sizeof *a->twin);
    assert_memory_equal(a->kind, b->kind, a->nh * sizeof *a->kind);
    assert_memory_equal(a->label, b->label, a->nh * sizeof *a->label);
}

static void test_copy(void **state)
{
    (void)state;
    rng_state = 0xC0B1;
    sq_mesh m;
    sq_tsurf S, A, B;
    sq_error err;
    sq_test_load_mesh(&m, "mpz/knot1.obj");
    sq_tsurf_init(&S), sq_tsurf_init(&A), sq_tsurf_init(&B);
    assert_int_equal(sq_tsurf_from_mesh(&m, NULL, &S, NULL, &err), SQ_OK);
    for (uint32_t i = 0; i < 300; i++) {
        uint32_t h = rnd(S.nh);
        if (rnd(2)) sq_tsurf_cut_edge(&S, h, SQ_TS_SEAM, h, S.twin[h]);
        else assert_int_not_equal(sq_tsurf_split_edge(&S, h, 0.5), SQ_NONE);
    }
    double area = total_area(&S);
    assert_int_equal(sq_tsurf_copy(&A, &S), 0);
    assert_tsurf_equal(&A, &S);
    assert_int_equal(sq_tsurf_copy(&B, &S), 0);
    /* the copy grows and cuts on its own; the source stays as it was */
    for (uint32_t i = 0; i < 300; i++) {
        uint32_t h = rnd(A.nh);
        if (rnd(2)) sq_tsurf_cut_edge(&A, h, SQ_TS_CHORD, h, A.twin[h]);
        else assert_int_not_equal(sq_tsurf_split_edge(&A, h, 0.25), SQ_NONE);
    }
    assert_true(A.nv > S.nv);
    check_tsurf(&A, sq_mesh_euler(&m), area);
    assert_tsurf_equal(&B, &S);
    /* copying over a used surface replaces it */
    assert_int_equal(sq_tsurf_copy(&A, &S), 0);
    assert_tsurf_equal(&A, &S);
    sq_tsurf_free(&S), sq_tsurf_free(&A), sq_tsurf_free(&B);
    sq_mesh_free(&m);
}

static void test_from_mesh_rejects_polygons(void **state)
{
    (void)state;
    /* a closed quad mesh (cube) must be refused, not copied */
    static const char cube[] = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                               "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    sq_soup soup;
    sq_mesh m;
    sq_tsurf S;
    sq_error err;
    memset(&soup, 0, sizeof soup);
    assert_int_equal(sq_parse_obj(cube, sizeof cube - 1, "cube.obj", &soup, &err), SQ_OK);
    assert_int_equal(sq_mesh_from_soup(&soup, SQ_MESH_ALLOW_POLYGONS, &m, &err), SQ_OK);
    sq_tsurf_init(&S);
    assert_int_equal(sq_tsurf_from_mesh(&m, NULL, &S, NULL, &err), SQ_ERR_ARGUMENT);
    sq_tsurf_free(&S);
    sq_mesh_free(&m);
    sq_soup_free(&soup);
}

/* ---- 2. region boundaries and sectors ------------------------------------ */


static void boundary_run(const char *rel, uint32_t trials)
{
    sq_mesh m;
    sq_tsurf S;
    sq_error err;
    sq_test_load_mesh(&m, rel);
    sq_tsurf_init(&S);
    int64_t euler = sq_mesh_euler(&m);
    for (uint32_t tr = 0; tr < trials; tr++) {
        assert_int_equal(sq_tsurf_from_mesh(&m, NULL, &S, NULL, &err), SQ_OK);
        double area0 = total_area(&S);
        /* a face-connected patch grown from a random face */
        uint32_t want = 3 + rnd(120);
        uint8_t *in = calloc(S.nf, 1);
        uint32_t *q = malloc(S.nf * sizeof *q), nq = 0;
        assert_true(in && q);
        q[nq++] = rnd(S.nf), in[q[0]] = 1;
        for (uint32_t i = 0; i < nq && nq < want; i++) {
            uint32_t h = S.f_he[q[i]];
            for (int k = 0; k < 3 && nq < want; k++, h = S.next[h]) {
                uint32_t f = S.face[S.twin[h]];
                if (!in[f] && rnd(4)) in[f] = 1, q[nq++] = f;
            }
        }
        uint32_t nbd = 0;
        for (uint32_t h = 0; h < S.nh; h++)
            if (in[S.face[h]] && !in[S.face[S.twin[h]]]) {
                sq_tsurf_cut_edge(&S, h, SQ_TS_SEAM, 1, 2);
                nbd++;
            }
        check_tsurf(&S, euler, area0);
        uint32_t *reg = malloc(S.cap_f * sizeof *reg);
        assert_non_null(reg);
        /* the patch is one region; its complement may fall into several */
        uint32_t nr = regions(&S, reg);
        assert_true(nr >= 2);
        uint32_t rin = reg[q[0]];
        for (uint32_t f = 0; f < S.nf; f++) assert_int_equal(reg[f] == rin, in[f]);
        check_boundary(&S, reg);
        /* the loops around the patch hold exactly its boundary edges */
        uint32_t around = 0;
        for (uint32_t h = 0; h < S.nh; h++) around += S.kind[h] && reg[S.face[h]] == rin;
        assert_int_equal(around, nbd);
        /* splits (of cut edges, too) keep all of it; the loops grow */
        uint32_t nsp = 20 + rnd(60), cut_splits = 0;
        for (uint32_t i = 0; i < nsp; i++) {
            uint32_t h = rnd(S.nh);
            if (rnd(2))
                for (uint32_t k = 0; k < 40 && !S.kind[h]; k++) h = rnd(S.nh);
            cut_splits += S.kind[h] != 0;
            assert_int_not_equal(sq_tsurf_split_edge(&S, h, 0.05 + 0.9 * urand()), SQ_NONE);
        }
        check_tsurf(&S, euler, area0);
        reg = realloc(reg, S.nf * sizeof *reg);
        assert_int_equal(regions(&S, reg), nr);
        check_boundary(&S, reg);
        around = 0;
        for (uint32_t h = 0; h < S.nh; h++) around += S.kind[h] && reg[S.face[h]] == reg[q[0]];
        assert_int_equal(around, nbd + cut_splits);
        free(reg), free(in), free(q);
    }
    sq_tsurf_free(&S);
    sq_mesh_free(&m);
}

static void test_boundary_loops(void **state)
{
    (void)state;
    rng_state = 0xB0B;
    int L = long_mode();
    boundary_run("mpz/knot1.obj", L ? 300 : 20);
    boundary_run("mpz/eight.obj", L ? 300 : 15);
}

/* ---- 4. opening sectors and vertices --------------------------------------- */

static void test_open(void **state)
{
    (void)state;
    rng_state = 0x0BE7;
    int trials = long_mode() ? 200 : 10;
    for (int tr = 0; tr < trials; tr++) {
        walled W;
        walled_make(&W, tr % 2 ? "libigl/bumpy.off" : "libigl/decimated-knight.off");
        sq_tsurf *S = &W.S;
        /* sectors of random cut vertices (every face at c is one) */
        for (int k = 0; k < 30; k++) {
            uint32_t s;
            if (k < 4) {
                s = S->v_he[W.c];
                for (uint32_t j = rnd(8); j; j--) s = sq_ts_ccw(S, s);
            } else {
                do s = rnd(S->nh);
                while (!S->kind[s]);
            }
            /* a one-face sector whose opposite edge is cut cannot open */
            if (S->kind[sq_ts_ccw(S, s)] && S->kind[S->next[s]]) continue;
            snap sn;
            snap_take(&sn, S);
            uint32_t nv0 = S->nv;
            int64_t n = sq_tsurf_open_sector(S, s);
            assert_true(n >= 0);
            assert_int_equal((int64_t)(S->nv - nv0), n);
            check_since(S, &sn, 1);
            snap_free(&sn);
            check_tsurf(S, W.euler, W.area0);
            /* every edge strictly inside the sector now leads off the cut
             * and to no cone, and there is one */
            uint32_t g = sq_ts_ccw(S, s), inner = 0;
            while (!S->kind[g]) {
                uint32_t w = sq_ts_head(S, g);
                if (blocked_v(S, w)) fail_msg("open_sector(%u): inner neighbour %u still blocked", s, w);
                inner++;
                g = sq_ts_ccw(S, g);
            }
            assert_true(inner >= 1);
            assert_int_equal(sq_tsurf_open_sector(S, s), 0);
        }
        /* vertices off the cut next to the wall */
        for (int k = 0; k < 20; k++) {
            uint32_t v;
            do v = rnd(S->nv);
            while (blocked_v(S, v));
            snap sn;
            snap_take(&sn, S);
            uint32_t nv0 = S->nv;
            int64_t n = sq_tsurf_open_vertex(S, v);
            assert_true(n >= 0);
            assert_int_equal((int64_t)(S->nv - nv0), n);
            check_since(S, &sn, 1);
            snap_free(&sn);
            check_tsurf(S, W.euler, W.area0);
            uint32_t h0 = S->v_he[v], h = h0;
            do {
                if (blocked_v(S, sq_ts_head(S, h)))
                    fail_msg("open_vertex(%u): neighbour %u still blocked", v, sq_ts_head(S, h));
                h = sq_ts_ccw(S, h);
            } while (h != h0);
        }
        walled_free(&W);
    }
}

/* ---- 5. blocking edges ------------------------------------------------------ */

static uint32_t count_blocking(const sq_tsurf *S, int cones)
{
    uint32_t n = 0;
    for (uint32_t h = 0; h < S->nh; h++) {
        if (S->kind[h] || S->vert[h] > sq_ts_head(S, h)) continue;
        uint32_t a = S->vert[h], b = sq_ts_head(S, h);
        int ca = S->v_ncut[a] > 0, cb = S->v_ncut[b] > 0;
        int ka = !ca && S->valence[a] != 4, kb = !cb && S->valence[b] != 4;
        if ((ca && cb) || (cones && ((ka && (kb || cb)) || (kb && ca)))) n++;
    }
    return n;
}

static void test_split_blocking(void **state)
{
    (void)state;
    rng_state = 0xB10C;
    int trials = long_mode() ? 200 : 12;
    uint32_t *reg = NULL;
    for (int tr = 0; tr < trials; tr++) {
        walled W;
        walled_make(&W, tr % 2 ? "mpz/eight.obj" : "libigl/decimated-knight.off");
        sq_tsurf *S = &W.S;
        /* more cut edges and cones at random */
        for (uint32_t k = 0; k < S->nh / 40; k++) {
            uint32_t h = rnd(S->nh);
            if (!S->kind[h]) sq_tsurf_cut_edge(S, h, rnd(2) ? SQ_TS_SEAM : SQ_TS_CHORD, 5, 6);
        }
        for (uint32_t k = 0; k < S->nv / 30; k++) S->valence[rnd(S->nv)] = 3 + (int32_t)rnd(2) * 2;
        check_tsurf(S, W.euler, W.area0);
        int cones = tr % 3 != 0;
        reg = realloc(reg, S->nf * sizeof *reg);
        uint32_t nr = regions(S, reg);
        uint32_t before = count_blocking(S, cones);
        assert_true(before > 0);
        snap sn;
        snap_take(&sn, S);
        uint32_t nv0 = S->nv;
        int64_t n = sq_tsurf_split_blocking(S, cones);
        assert_int_equal((int64_t)before, n);
        assert_int_equal((int64_t)(S->nv - nv0), n);
        check_since(S, &sn, 1);
        snap_free(&sn);
        check_tsurf(S, W.euler, W.area0);
        assert_int_equal(count_blocking(S, cones), 0);
        assert_int_equal(count_blocking(S, 0), 0);
        reg = realloc(reg, S->nf * sizeof *reg);
        assert_int_equal(regions(S, reg), nr);
        assert_int_equal(sq_tsurf_split_blocking(S, cones), 0);
        walled_free(&W);
    }
    free(reg);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_from_mesh_rejects_polygons),
        cmocka_unit_test(test_split_random),
        cmocka_unit_test(test_copy),
        cmocka_unit_test(test_boundary_loops),
        cmocka_unit_test(test_open),
        cmocka_unit_test(test_split_blocking),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
