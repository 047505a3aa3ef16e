/* seamquad: tests of Q triangulated with local room (sq_qtri.h; seed 9.4):
 * on real meshes with their cone files, the surface tree of seed 9.4
 * (radial order of the guidance disk, Algorithm 1's domain) is copied into
 * Q triangulated, and the copy must be the same plane tree: the same
 * cyclic order of paths at every node, every path ending at the copy of
 * its surface end, the root inside the matching side of Q; the flat
 * vectors of every face close (they sum to zero) and are dyadic; Q's
 * boundary is cut exactly once per side edge. SQ_LONG_TESTS adds
 * cid/elephant and more cut-graph seeds. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_test_mesh.h"
#include "sq_test_random.h"

#include "sq_cut_graph.h"
#include "sq_domain.h"
#include "sq_guide.h"
#include "sq_metapolygon.h"
#include "sq_omega.h"
#include "sq_pattern.h"
#include "sq_predicates.h"
#include "sq_qtri.h"

/* The cone of Q standing for each step: the irregular vertex inside the
 * step's irregular face of the metapolygon (as sq_param does). */
static void step_q_vertices(const sq_domain *D, uint32_t *qv)
{
    const sq_metapolygon *Q = &D->quads, *M = &D->meta;
    uint32_t *mstep = malloc(M->nf * sizeof *mstep), j = 0;
    uint8_t *qbnd = calloc(Q->nv, 1);
    for (uint32_t f = 0; f < M->nf; f++) mstep[f] = M->f_valence[f] != 4 ? j++ : SQ_NONE;
    for (uint32_t h = 0; h < Q->nh; h++)
        if (Q->he_face[h] == SQ_NONE) qbnd[Q->he_vert[h]] = 1;
    for (uint32_t s = 0; s < D->ncones; s++) qv[s] = SQ_NONE;
    for (uint32_t v = 0; v < Q->nv; v++) {
        if (Q->v_nface[v] == 4 || qbnd[v]) continue;
        uint32_t f = Q->he_face[Q->v_he[v]];
        assert_true(f < D->nf_unpadded);
        uint32_t s = mstep[D->f_meta_face[f]];
        assert_true(s < D->ncones);
        assert_int_equal(qv[s], SQ_NONE);
        qv[s] = v;
    }
    for (uint32_t s = 0; s < D->ncones; s++) assert_int_not_equal(qv[s], SQ_NONE);
    free(mstep), free(qbnd);
}

/* (step, direction) of the tree edge x-w: direction 1 when w is x's next */
static uint64_t edge_key(const uint32_t *next, const uint32_t *step, uint32_t x, uint32_t w)
{
    if (next[x] == w) return (uint64_t)step[x] << 1 | 1;
    return (uint64_t)step[w] << 1;
}

/* the tree edges around x in counterclockwise order, as keys */
static uint32_t mesh_ring(const sq_mesh *m, const uint32_t *next, const uint32_t *step, uint32_t x, uint64_t *out)
{
    uint32_t n = 0, h0 = m->v_he[x], h = h0;
    do {
        uint32_t w = m->he_vert[m->he_next[h]];
        if (next[x] == w || next[w] == x) out[n++] = edge_key(next, step, x, w);
        h = m->he_twin[m->he_next[m->he_next[h]]]; /* counterclockwise */
    } while (h != h0);
    return n;
}

static uint32_t qtri_ring(const sq_qtri *T, uint32_t x, uint64_t *out)
{
    const sq_tsurf *S = &T->S;
    uint32_t n = 0, h0 = S->v_he[x], h = h0;
    do {
        uint32_t w = sq_ts_head(S, h);
        if (T->tree_next[x] == w || T->tree_next[w] == x) {
            assert_int_equal(S->kind[h], SQ_TS_SEAM);
            assert_int_equal(S->label[h], SQ_NONE);
            out[n++] = edge_key(T->tree_next, T->tree_step, x, w);
        }
        h = sq_ts_ccw(S, h);
    } while (h != h0);
    return n;
}

static int same_cycle(const uint64_t *a, const uint64_t *b, uint32_t n)
{
    for (uint32_t r = 0; r < (n ? n : 1); r++) {
        uint32_t i = 0;
        while (i < n && a[i] == b[(i + r) % n]) i++;
        if (i == n) return 1;
    }
    return 0;
}

/* the worst triangle of O by 4 sqrt(3) area / (sum of squared edges) */
static double worst_quality(const sq_omega *O)
{
    double worst = 1;
    for (uint32_t f = 0; f < O->cut.nf; f++) {
        uint32_t h = O->cut.f_he[f];
        double q[3][2], s = 0;
        for (int i = 0; i < 3; i++, h = O->cut.he_next[h])
            q[i][0] = (double)O->xy[2 * O->cut.he_vert[h]], q[i][1] = (double)O->xy[2 * O->cut.he_vert[h] + 1];
        for (int i = 0; i < 3; i++) {
            double dx = q[(i + 1) % 3][0] - q[i][0], dy = q[(i + 1) % 3][1] - q[i][1];
            s += dx * dx + dy * dy;
        }
        double a2 = (q[1][0] - q[0][0]) * (q[2][1] - q[0][1]) - (q[1][1] - q[0][1]) * (q[2][0] - q[0][0]);
        double qual = 2 * sqrt(3.0) * a2 / s;
        if (qual < worst) worst = qual;
    }
    return worst;
}

/* T's flat vectors: every face closes exactly, dyadic, twins of equal
 * length; Omega laid out exactly, every cut edge a turn by k x 90 degrees
 * and an integer translation, the same along every label between nodes.
 * Returns the cut halfedges. */
static uint32_t check_layout(const char *name, uint64_t seed, sq_qtri *T, uint32_t n)
{
    const sq_tsurf *S = &T->S;
    sq_error err = {0};
    /* every face's flat vectors close, exactly, and are dyadic */
    for (uint32_t f = 0; f < S->nf; f++) {
        uint32_t h = S->f_he[f];
        double sx = 0, sy = 0;
        for (int i = 0; i < 3; i++, h = S->next[h]) {
            double x = S->hvec[2 * h], y = S->hvec[2 * h + 1];
            assert_true(ldexp(x, 60) == nearbyint(ldexp(x, 60)));
            assert_true(ldexp(y, 60) == nearbyint(ldexp(y, 60)));
            sx += x, sy += y;
            /* twins are the same segment: equal lengths */
            double tx = S->hvec[2 * S->twin[h]], ty = S->hvec[2 * S->twin[h] + 1];
            assert_true(x * x + y * y == tx * tx + ty * ty);
        }
        assert_true(sx == 0 && sy == 0);
    }
    /* Omega: the cut disk laid out exactly; across every cut edge a
     * turn by a multiple of 90 degrees and an integer translation, the
     * same along every tree segment and every side (but the root's) */
    double *cxy = malloc(2 * S->nh * sizeof *cxy);
    if (sq_qtri_layout(T, cxy, &err)) fail_msg("%s seed %llu: %s", name, (unsigned long long)seed, err.msg);
    uint32_t ncut = 0, changes = 0;
    for (uint32_t h = 0; h < S->nh; h++) {
        if (!S->kind[h]) continue;
        uint8_t rot, rot2;
        double t[2], t2[2];
        assert_true(sq_qtri_transition(T, cxy, h, &rot, t));
        assert_true(t[0] == nearbyint(t[0]) && t[1] == nearbyint(t[1]));
        ncut++;
        /* the next cut edge along the same label, where the vertex
         * between is no node */
        uint32_t b = sq_ts_head(S, h), g = sq_tsurf_next_boundary(S, h);
        if (S->label[g] != S->label[h]) continue;
        int node = S->valence[b] != 4 || b == T->root;
        for (uint32_t j = 1; j < n; j++) node |= T->att[j] == b;
        if (node) continue;
        assert_true(sq_qtri_transition(T, cxy, g, &rot2, t2));
        if (rot2 != rot || t2[0] != t[0] || t2[1] != t[1]) changes++;
    }
    /* (the root, where its side's transition changes, is a node, and
     * a side's two ends are corners, where the label changes) */
    assert_int_equal(changes, 0);
    free(cxy);
    return ncut;
}

/* Omega as an sq_omega, then coarsened (sq_omega_coarsen). */
static void check_omega(const char *name, uint64_t seed, sq_qtri *T, sq_domain *D, uint32_t k, uint32_t n,
                        uint32_t ncut)
{
    const sq_tsurf *S = &T->S;
    sq_error err = {0};
    /* Omega as an sq_omega: a disk of T's faces, every label one
     * transition, the root splitting its side */
    sq_omega O;
    sq_omega_init(&O);
    uint32_t nseg = 0, *sf = NULL, *stt = NULL;
    if (sq_qtri_omega(T, D, &O, &nseg, &sf, &stt, &err))
        fail_msg("%s seed %llu: %s", name, (unsigned long long)seed, err.msg);
    assert_int_equal(O.cut.nf, S->nf);
    assert_int_equal(O.cut.nbnd, ncut);
    assert_int_equal(O.nlabels, k + 2 * nseg + 2);
    assert_true(nseg >= n - 1);
    for (uint32_t s2 = 0; s2 < nseg; s2++) assert_true(sf[s2] != stt[s2]);
    free(sf), free(stt);
    /* coarser: fewer inner vertices, the same boundary and labels,
     * every triangle positive (exact) */
    const uint32_t nb0 = O.cut.nbnd, nf0 = O.cut.nf;
    uint32_t *lab0 = malloc(nb0 * sizeof *lab0);
    for (uint32_t i = 0, b = O.cut.bnd_he; i < nb0; i++, b = O.cut.he_next[b]) lab0[i] = O.he_label[b];
    uint32_t removed = 0;
    const double q0 = worst_quality(&O);
    assert_int_equal(sq_omega_coarsen(&O, &removed, &err), SQ_OK);
    /* no sliver made: the worst shape is no worse than before */
    assert_true(worst_quality(&O) >= q0);
    assert_int_equal(sq_metapolygon_validate(&O.cut, 0, &err), SQ_OK);
    assert_int_equal(O.cut.nbnd, nb0);
    assert_true(O.cut.nf < nf0 && removed > 0);
    for (uint32_t i = 0, b = O.cut.bnd_he; i < nb0; i++, b = O.cut.he_next[b]) {
        assert_int_equal(O.he_label[b], lab0[i]);
        assert_int_equal(O.he_partner[O.he_partner[b]], b);
    }
    for (uint32_t f = 0; f < O.cut.nf; f++) {
        uint32_t h = O.cut.f_he[f];
        double q[3][2];
        for (int i = 0; i < 3; i++, h = O.cut.he_next[h])
            q[i][0] = (double)O.xy[2 * O.cut.he_vert[h]], q[i][1] = (double)O.xy[2 * O.cut.he_vert[h] + 1];
        assert_true(sq_orient2d(q[0], q[1], q[2]) > 0);
    }
    free(lab0);
    sq_omega_free(&O);
}

static void run_model(const char *name, uint64_t seed)
{
    char path[256];
    sq_mesh m;
    snprintf(path, sizeof path, "%s.obj", name);
    sq_test_load_mesh(&m, path);
    snprintf(path, sizeof path, "%s_Th_hat", name);
    int32_t *val = sq_test_load_valence(path, m.nv);
    uint8_t *cone = calloc(m.nv, 1);
    uint32_t n = 0;
    for (uint32_t v = 0; v < m.nv; v++)
        if (val[v] != 4) cone[v] = 1, n++;
    sq_cut_graph G;
    sq_cut_graph_init(&G);
    sq_cut_options copt;
    sq_cut_options_default(&copt);
    copt.seed = seed;
    sq_error err = {0};
    if (sq_cut_graph_build(&m, cone, &copt, &G, NULL, &err)) {
        print_message("%s seed %llu: no cut graph (%s)\n", name, (unsigned long long)seed, err.msg);
        sq_cut_graph_free(&G);
        free(cone), free(val);
        sq_mesh_free(&m);
        return;
    }
    sq_pattern pcw;
    sq_pattern_init(&pcw);
    assert_int_equal(sq_pattern_reversed(&G.pattern, &pcw, &err), SQ_OK);
    /* seed 9.2: cones by distance from the disk centre */
    uint32_t k = G.pattern.k;
    double *vxy = malloc(2 * m.nv * sizeof *vxy), *ang = malloc(k * sizeof *ang);
    assert_int_equal(sq_guide_surface_disk(&m, &G, vxy, ang, &err), SQ_OK);
    uint32_t *cv = malloc(n * sizeof *cv), *order = malloc(n * sizeof *order), *scone = malloc(n * sizeof *scone);
    int32_t *cval = malloc(n * sizeof *cval), *sval = malloc(n * sizeof *sval);
    double *cxy = malloc(2 * n * sizeof *cxy), *sxy = malloc(2 * n * sizeof *sxy);
    for (uint32_t v = 0, i = 0; v < m.nv; v++)
        if (cone[v]) cv[i] = v, cval[i] = val[v], cxy[2 * i] = vxy[2 * v], cxy[2 * i + 1] = vxy[2 * v + 1], i++;
    assert_int_equal(sq_guide_cone_order(n, cval, cxy, order, &err), SQ_OK);
    for (uint32_t i = 0; i < n; i++) {
        scone[i] = cv[order[i]], sval[i] = cval[order[i]];
        sxy[2 * i] = cxy[2 * order[i]], sxy[2 * i + 1] = cxy[2 * order[i] + 1];
    }
    /* Algorithm 1's domain */
    sq_guide_glue glue;
    memset(&glue, 0, sizeof glue);
    glue.c = sxy;
    sq_build_options bopt;
    memset(&bopt, 0, sizeof bopt);
    bopt.chooser = sq_guide_glue_chooser;
    bopt.chooser_user = &glue;
    sq_domain_options dopt;
    memset(&dopt, 0, sizeof dopt);
    dopt.offset = SQ_NONE;
    dopt.pattern = &pcw;
    dopt.build = &bopt;
    dopt.keep_order = 1;
    sq_domain D;
    if (sq_domain_build((uint32_t)sq_mesh_genus(&m), sval, n, &dopt, &D, &err)) fail_msg("%s: %s", name, err.msg);
    uint32_t r = 0;
    assert_int_equal(sq_cut_graph_domain_offset(&G, &D.pattern, &r, &err), SQ_OK);
    uint32_t *qv = malloc(n * sizeof *qv);
    step_q_vertices(&D, qv);
    double *qxy = malloc(2 * D.quads.nv * sizeof *qxy);
    assert_int_equal(sq_guide_metapolygon_layout(&D.quads, sxy, n, qv, qxy, &err), SQ_OK);
    /* the surface tree and its root path */
    uint32_t *att = malloc(n * sizeof *att), *av = malloc(n * sizeof *av), *nx = malloc(m.nv * sizeof *nx);
    double *frac = malloc(n * sizeof *frac);
    uint8_t *side = malloc(n);
    assert_int_equal(sq_guide_surface_tree(&m, &G, n, scone, att, frac, side, av, nx, &err), SQ_OK);
    uint32_t rs = 0;
    double far = -1;
    for (uint32_t j = 0; j < n; j++)
        if (hypot(sxy[2 * j], sxy[2 * j + 1]) > far) far = hypot(sxy[2 * j], sxy[2 * j + 1]), rs = j;
    sq_guide_root root = {rs, SQ_NONE, SQ_NONE, SQ_NONE};
    assert_int_equal(sq_guide_surface_root(&m, &G, n, scone, nx, nx, &root, &err), SQ_OK);
    int complete = root.vertex != SQ_NONE;
    for (uint32_t j = 1; j < n; j++) complete &= att[j] != SQ_NONE;
    if (!complete) {
        print_message("%s seed %llu: the surface tree is incomplete\n", name, (unsigned long long)seed);
    } else {
        sq_qtri T;
        sq_qtri_init(&T);
        if (sq_qtri_build(&D, qxy, &T, &err)) fail_msg("%s seed %llu: %s", name, (unsigned long long)seed, err.msg);
        const uint32_t nv0 = T.S.nv;
        /* Q's side i <-> the cut graph's side k - 1 - (i + r) % k (as in sq_param) */
        uint32_t qside = (2 * k - 1 - root.side - r % k) % k;
        sq_status st = sq_qtri_replicate(&T, &D, &m, &G, n, scone, qv, nx, av, &root, qside, &err);
        if (st) fail_msg("%s seed %llu: %s", name, (unsigned long long)seed, err.msg);
        const sq_tsurf *S = &T.S;
        /* surface path steps, as the copy names them */
        uint32_t *sstep = malloc(m.nv * sizeof *sstep);
        for (uint32_t v = 0; v < m.nv; v++) sstep[v] = SQ_NONE;
        sstep[scone[0]] = 0;
        for (uint32_t j = 1; j < n; j++)
            for (uint32_t x = scone[j]; x != av[j]; x = nx[x]) sstep[x] = j;
        for (uint32_t x = root.vertex; x != scone[rs]; x = nx[x]) sstep[x] = n;
        /* the same plane tree: every node's ring of paths, cyclically */
        uint64_t a[64], b[64];
        uint32_t nodes = 0;
        for (uint32_t j = 0; j < n; j++) {
            uint32_t x = scone[j], y = T.cone[j];
            uint32_t na = mesh_ring(&m, nx, sstep, x, a), nb = qtri_ring(&T, y, b);
            assert_int_equal(na, nb);
            assert_true(same_cycle(a, b, na));
            nodes++;
            if (j == 0) continue;
            x = av[j], y = T.att[j];
            assert_int_not_equal(y, SQ_NONE);
            na = mesh_ring(&m, nx, sstep, x, a), nb = qtri_ring(&T, y, b);
            assert_int_equal(na, nb);
            assert_true(same_cycle(a, b, na));
            nodes++;
        }
        /* tree vertices: off Q's boundary but the root, regular but the cones */
        uint32_t ntree = 0;
        for (uint32_t v = 0; v < S->nv; v++) {
            if (T.tree_step[v] == SQ_NONE) continue;
            ntree++;
            uint32_t nb_cut = 0, h0 = S->v_he[v], h = h0;
            do {
                if (S->kind[h] && S->label[h] != SQ_NONE) nb_cut++;
                h = sq_ts_ccw(S, h);
            } while (h != h0);
            if (v == T.root) assert_true(nb_cut == 2);
            else assert_int_equal(nb_cut, 0);
            if (S->valence[v] != 4) {
                uint32_t j = 0;
                while (j < n && T.cone[j] != v) j++;
                assert_true(j < n);
            }
        }
        assert_int_equal(T.tree_step[T.root], n);
        assert_true(T.root_side < k && T.root_side == qside);
        assert_int_equal(S->label[T.root_he], T.root_side);
        const uint32_t ncut = check_layout(name, seed, &T, n);
        check_omega(name, seed, &T, &D, k, n, ncut);
        print_message("%s seed %llu: %u cones, %u nodes, tree %u vertices, Q triangulated %u -> %u vertices "
                      "(%llu Steiner), %u cut halfedges, Omega laid out\n",
                      name, (unsigned long long)seed, n, nodes, ntree, nv0, S->nv, (unsigned long long)T.splits, ncut);
        free(sstep);
        sq_qtri_free(&T);
    }
    free(att), free(av), free(nx), free(frac), free(side), free(qv), free(qxy);
    sq_domain_free(&D);
    sq_guide_glue_free(&glue);
    free(vxy), free(ang), free(cv), free(order), free(scone), free(cval), free(sval), free(cxy), free(sxy);
    sq_pattern_free(&pcw);
    sq_cut_graph_free(&G);
    free(cone), free(val);
    sq_mesh_free(&m);
}

static void test_replicate(void **state)
{
    (void)state;
    static const char *models[] = {"mpz/eight", "mpz/helmet", "mpz/holes3", "mpz/genus3", "mpz/block"};
    for (uint32_t i = 0; i < sizeof models / sizeof *models; i++) run_model(models[i], 1);
    if (!long_mode()) return;
    for (uint64_t s = 1; s <= 3; s++) run_model("cid/elephant", s);
    for (uint32_t i = 0; i < sizeof models / sizeof *models; i++)
        for (uint64_t s = 2; s <= 4; s++) run_model(models[i], s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_replicate)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
