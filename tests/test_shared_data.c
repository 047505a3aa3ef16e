/* Every mesh of ../shared/data loads, and its counts and genus match
 * MANIFEST.tsv; every cone file of a closed mesh has the manifest's cone count
 * and passes Gauss-Bonnet; the open meshes are rejected naming a boundary
 * edge; mpz/twirl's valence-1 cone is rejected by name. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sq_cones.h"
#include "sq_io.h"
#include "sq_mesh.h"

#define DATA SQ_SHARED_DIR "/data/"

typedef struct manifest_row {
    char file[256], closed[16], cones[256];
    long nv, nf, genus, ncones;
} manifest_row;

/* Splits a tab-separated line into at most n fields (in place). */
static int split_tabs(char *line, char **field, int n)
{
    int k = 0;
    field[k++] = line;
    for (char *p = line; *p && k < n; p++) {
        if (*p == '\t') {
            *p = '\0';
            field[k++] = p + 1;
        }
    }
    return k;
}

static int read_manifest(manifest_row **rows_out)
{
    FILE *f = fopen(DATA "MANIFEST.tsv", "r");
    if (!f) fail_msg("cannot open %s", DATA "MANIFEST.tsv");
    static char line[8192];
    manifest_row *rows = NULL;
    int n = 0;
    if (!fgets(line, sizeof line, f)) fail_msg("empty manifest");
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = '\0';
        char *fld[12];
        if (split_tabs(line, fld, 12) < 11) continue;
        rows = realloc(rows, (size_t)(n + 1) * sizeof *rows);
        manifest_row *r = &rows[n++];
        snprintf(r->file, sizeof r->file, "%s", fld[0]);
        r->nv = atol(fld[5]);
        r->nf = atol(fld[6]);
        snprintf(r->closed, sizeof r->closed, "%s", fld[7]);
        r->genus = atol(fld[8]);
        snprintf(r->cones, sizeof r->cones, "%s", fld[9]);
        r->ncones = strcmp(fld[10], "-") ? atol(fld[10]) : -1;
    }
    fclose(f);
    *rows_out = rows;
    return n;
}

static int all_quads(const sq_soup *s)
{
    for (uint32_t f = 0; f < s->nf; f++)
        if (s->face_off[f + 1] - s->face_off[f] != 4) return 0;
    return 1;
}

static void check_row(const manifest_row *r, int *n_closed, int *n_cones)
{
    char path[600], cpath[1024];
    snprintf(path, sizeof path, DATA "%s", r->file);
    sq_soup soup;
    sq_error err;
    if (sq_read_mesh(path, &soup, &err)) fail_msg("%s: %s", r->file, err.msg);
    if ((long)soup.nv != r->nv || (long)soup.nf != r->nf)
        fail_msg("%s: read %u vertices %u faces, manifest says %ld %ld", r->file, soup.nv, soup.nf,
                 r->nv, r->nf);
    unsigned flags = all_quads(&soup) ? SQ_MESH_ALLOW_POLYGONS : 0;
    sq_mesh mesh;
    sq_status st = sq_mesh_from_soup(&soup, flags, &mesh, &err);
    if (strcmp(r->closed, "yes")) {
        /* open meshes must be rejected, naming a boundary edge and its line */
        if (st != SQ_ERR_BOUNDARY || !strstr(err.msg, "boundary edge") || !strstr(err.msg, ".obj:"))
            fail_msg("%s: open mesh not rejected as open: %s", r->file, err.msg);
        if (r->ncones >= 0) {
            /* the cone file is still well-formed with one angle per vertex */
            char dir[600];
            snprintf(dir, sizeof dir, "%s", path);
            *strrchr(dir, '/') = '\0';
            snprintf(cpath, sizeof cpath, "%s/%s", dir, r->cones);
            int32_t *val = malloc(soup.nv * sizeof *val);
            if (sq_cones_read(cpath, soup.nv, val, NULL, &err)) fail_msg("%s: %s", r->cones, err.msg);
            free(val);
        }
        sq_soup_free(&soup);
        return;
    }
    if (st) fail_msg("%s: %s", r->file, err.msg);
    (*n_closed)++;
    if (sq_mesh_genus(&mesh) != r->genus)
        fail_msg("%s: genus %lld, manifest says %ld", r->file, (long long)sq_mesh_genus(&mesh),
                 r->genus);
    if (r->ncones >= 0) {
        char dir[600];
        snprintf(dir, sizeof dir, "%s", path);
        *strrchr(dir, '/') = '\0';
        snprintf(cpath, sizeof cpath, "%s/%s", dir, r->cones);
        int32_t *val = malloc(mesh.nv * sizeof *val);
        sq_cone_format fmt;
        if (sq_cones_read(cpath, mesh.nv, val, &fmt, &err)) fail_msg("%s: %s", r->cones, err.msg);
        assert_int_equal(fmt, SQ_CONES_TH_HAT);
        uint32_t nc = sq_cones_histogram(mesh.nv, val, NULL, 0);
        if ((long)nc != r->ncones)
            fail_msg("%s: %u cones, manifest says %ld", r->cones, nc, r->ncones);
        if (sq_cones_check_gauss_bonnet(mesh.nv, val, sq_mesh_euler(&mesh), &err))
            fail_msg("%s: %s", r->cones, err.msg);
        st = sq_cones_check_realizable(mesh.nv, val, sq_mesh_genus(&mesh), &err);
        if (strstr(r->file, "twirl")) {
            if (st != SQ_ERR_UNREALIZABLE || !strstr(err.msg, "valence 1"))
                fail_msg("%s: the valence-1 cone must be rejected: %s", r->file, err.msg);
        } else if (st) {
            fail_msg("%s: %s", r->cones, err.msg);
        }
        (*n_cones)++;
        free(val);
    }
    sq_mesh_free(&mesh);
    sq_soup_free(&soup);
}

static void test_manifest(void **state)
{
    (void)state;
    manifest_row *rows;
    int n = read_manifest(&rows), n_closed = 0, n_cones = 0, want_cones = 0;
    assert_true(n >= 30);
    for (int i = 0; i < n; i++) {
        check_row(&rows[i], &n_closed, &n_cones);
        want_cones += !strcmp(rows[i].closed, "yes") && rows[i].ncones >= 0;
    }
    print_message("%d meshes read, %d closed and valid, %d cone files checked\n", n, n_closed,
                  n_cones);
    assert_int_equal(n_closed, n - 2); /* cid/fertility_tri and cid/aircraft are open */
    assert_int_equal(n_cones, want_cones);
    assert_true(n_cones >= 17); /* all of mpz/ and cid/elephant */
    free(rows);
}

static void test_elephant(void **state)
{
    (void)state;
    sq_soup soup;
    sq_mesh mesh;
    sq_error err;
    assert_int_equal(sq_read_mesh(DATA "cid/elephant.obj", &soup, &err), SQ_OK);
    assert_int_equal(sq_mesh_from_soup(&soup, 0, &mesh, &err), SQ_OK);
    assert_int_equal(sq_mesh_genus(&mesh), 3);
    int32_t *val = malloc(mesh.nv * sizeof *val);
    assert_int_equal(sq_cones_read(DATA "cid/elephant_Th_hat", mesh.nv, val, NULL, &err), SQ_OK);
    uint32_t hist[16];
    assert_int_equal(sq_cones_histogram(mesh.nv, val, hist, 16), 118);
    assert_int_equal(hist[3], 54);
    assert_int_equal(hist[5], 59);
    assert_int_equal(hist[6], 4);
    assert_int_equal(hist[7], 1);
    assert_int_equal(sq_cones_check_realizable(mesh.nv, val, 3, &err), SQ_OK);
    /* every vertex has valence >= 3 in a closed triangle mesh */
    for (uint32_t v = 0; v < mesh.nv; v++) assert_true(sq_mesh_vertex_valence(&mesh, v) >= 3);
    free(val);
    sq_mesh_free(&mesh);
    sq_soup_free(&soup);
}

static void test_wrong_cone_count(void **state)
{
    (void)state;
    /* elephant's cones against helmet's mesh: a wrong-length Th_hat */
    sq_error err;
    int32_t *val = malloc(818 * sizeof *val);
    assert_int_equal(sq_cones_read(DATA "cid/elephant_Th_hat", 818, val, NULL, &err),
                     SQ_ERR_CONE_COUNT);
    assert_non_null(strstr(err.msg, "24955 angles for a mesh with 818 vertices"));
    free(val);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_manifest),
        cmocka_unit_test(test_elephant),
        cmocka_unit_test(test_wrong_cone_count),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
