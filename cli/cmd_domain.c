/* seamquad domain: the combinatorial seamless domain of a cone set. */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli_common.h"
#include "sq_cones.h"
#include "sq_disk_layout.h"
#include "sq_domain.h"
#include "sq_seamless_svg.h"
#include "sq_io.h"
#include "sq_mesh.h"
#include "sq_omega.h"
#include "sq_pattern_io.h"

static void help(FILE *f)
{
    fprintf(f,
            "usage: seamquad domain --genus G --valences K,K,... -o PREFIX [options]\n"
            "       seamquad domain MESH --cones FILE -o PREFIX [options]\n"
            "\n"
            "Builds the combinatorial seamless domain of the seed paper (Zhou, Tu, Zorin,\n"
            "Campen 2020, sections 5-6) for a cone set: a quad disk Q whose 8g-4 sides\n"
            "pair up with equal lengths and right-angle corners, and whose irregular\n"
            "vertices are exactly the cones. Gluing all identified sides closes Q into a\n"
            "quad mesh of genus g whose only irregular vertices are the cones.\n"
            "\n"
            "  metapolygon (seed 5.1-5.2) -> quads (5.4) -> exact padding solve over\n"
            "  all side correspondences, fewest quads kept (6.3, 9.3) -> padding (6.1)\n"
            "\n"
            "The cones come either from --genus and --valences (a cone of angle k*pi/2\n"
            "has valence k) or from a mesh and its cone file (genus from the mesh).\n"
            "No surface geometry is used: this is the purely combinatorial stage.\n"
            "\n"
            "options:\n"
            "  --genus G         genus of the closed surface\n"
            "  --valences LIST   comma-separated cone valences (4s are ignored)\n"
            "  --cones FILE      cone file (Th_hat or cone list, see check --help)\n"
            "  --pattern FILE    side-pairing pattern (docs/domain.md); default: the\n"
            "                    canonical pattern of the genus\n"
            "  --offset N        fix the side correspondence (default: best of all)\n"
            "  --seed N          genus >= 2 without --pattern: a random valid pattern\n"
            "                    that passes the rank test, drawn from seed N, instead\n"
            "                    of the canonical one\n"
            "  -o PREFIX         writes PREFIX.quad.obj (padded disk Q, Tutte layout),\n"
            "                    PREFIX.closed.obj (Q with all sides glued),\n"
            "                    PREFIX.sides.txt (corners, sides, pairs, lengths) and\n"
            "                    PREFIX.svg (metapolygon and padded domain)\n"
            "  --no-svg          skip the picture (large domains)\n"
            "  --omega           also cut Q to the cones along a shortest cone tree and\n"
            "                    lay it out flat with exact integer coordinates (seed\n"
            "                    7): verified seams, PREFIX.omega.svg\n"
            "  --json            machine-readable statistics on stdout\n"
            "  -h, --help        this help\n"
            "\n"
            "Genus 0 (seed 6.5): four meta-2-gons padded and glued into a sphere, cut\n"
            "along one edge. Genus 1 (seed 6.2): several pieces. Genus >= 2: one\n"
            "piece; the pattern must pass the rank test (docs/padding.md).\n"
            "\n"
            "example:\n"
            "  seamquad domain --genus 3 --valences 3,3,3,3,3,3,5,7,22 -o helmet\n");
}

static int parse_valences(const char *s, int32_t **out, uint32_t *n)
{
    uint32_t cap = 16, k = 0;
    int32_t *v = malloc(cap * sizeof *v);
    if (!v) return 0;
    const char *p = s;
    if (!*p) {
        free(v);
        return 0;
    }
    while (*p) {
        char *e;
        errno = 0;
        long x = strtol(p, &e, 10);
        if (e == p || errno || x < -1000000 || x > 1000000 || (*e && *e != ',')) {
            free(v);
            return 0;
        }
        if (k == cap) {
            int32_t *t = realloc(v, (cap *= 2) * sizeof *v);
            if (!t) {
                free(v);
                return 0;
            }
            v = t;
        }
        v[k++] = (int32_t)x;
        if (*e == ',' && !e[1]) { /* trailing comma */
            free(v);
            return 0;
        }
        p = *e ? e + 1 : e;
    }
    *out = v;
    *n = k;
    return 1;
}

static char *join(const char *prefix, const char *suffix)
{
    size_t n = strlen(prefix) + strlen(suffix) + 1;
    char *s = malloc(n);
    if (s) snprintf(s, n, "%s%s", prefix, suffix);
    return s;
}

static sq_status write_sides(const sq_domain *D, const char *path, sq_error *err)
{
    sq_atomic_file af;
    sq_status st = sq_atomic_open(&af, path, err);
    if (st) return st;
    FILE *f = af.fp;
    fprintf(f, "# seamquad domain sides (docs/domain.md)\n");
    fprintf(f, "genus %u\nsides %u\noffset %u\nrefinement %llu\n", D->genus, D->k, D->offset,
            (unsigned long long)D->refine);
    fprintf(f, "# corner INDEX VERTEX [straight]   (0-based vertex of PREFIX.quad.obj; side "
               "INDEX starts at corner INDEX; 'straight': a 180-degree corner, else 90)\n");
    for (uint32_t i = 0; i < D->k; i++)
        fprintf(f, "corner %u %u%s\n", i, D->corner_vert[i],
                D->pattern.straight[i] ? " straight" : "");
    fprintf(f, "# side INDEX LENGTH PARTNER PADDING   (side INDEX runs from corner INDEX to "
               "corner INDEX+1 and is glued, reversed, to side PARTNER; LENGTH in quad edges; "
               "PADDING = layers added on it)\n");
    for (uint32_t i = 0; i < D->k; i++)
        fprintf(f, "side %u %u %u %lld\n", i, D->side_len[i], D->pattern.partner[i],
                (long long)D->padding[i]);
    return sq_atomic_commit(&af, err);
}

/* Genus 0: a point of the sphere's planar drawing (sq_disk_layout_sphere,
 * inside the unit circle) lifted onto the unit sphere by the inverse
 * stereographic projection, scaled so that the outer quad becomes a small
 * cap, mirrored so that the faces face outwards. */
static void lift_to_sphere(double x, double y, double *p)
{
    const double X = -3.0 * x, Y = 3.0 * y, d = 1 + X * X + Y * Y;
    p[0] = 2 * X / d, p[1] = 2 * Y / d, p[2] = (X * X + Y * Y - 1) / d;
}

/* Q as OBJ: flat (x, y, 0), or on the sphere for genus 0 (lift). */
static sq_status write_quads_obj(const sq_metapolygon *Q, const double *xy, int lift, const char *path,
                                 sq_error *err)
{
    double *pos = malloc(3 * (size_t)Q->nv * sizeof *pos);
    uint32_t *off = malloc(((size_t)Q->nf + 1) * sizeof *off);
    uint32_t *idx = malloc(4 * (size_t)Q->nf * sizeof *idx);
    sq_status st;
    if (!pos || !off || !idx) {
        st = sq_error_set(err, SQ_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (uint32_t v = 0; v < Q->nv; v++) {
        pos[3 * v] = xy[2 * v];
        pos[3 * v + 1] = xy[2 * v + 1];
        pos[3 * v + 2] = 0;
        if (lift) lift_to_sphere(xy[2 * v], xy[2 * v + 1], pos + 3 * v);
    }
    uint32_t c = 0;
    for (uint32_t f = 0; f < Q->nf; f++) {
        off[f] = c;
        uint32_t h0 = Q->f_he[f], h = h0;
        do {
            idx[c++] = Q->he_vert[h];
            h = Q->he_next[h];
        } while (h != h0);
    }
    off[Q->nf] = c;
    st = sq_write_obj(path, Q->nv, pos, Q->nf, off, idx, 0, NULL, NULL, err);
done:
    free(pos), free(off), free(idx);
    return st;
}

int sq_cmd_domain(int argc, char **argv)
{
    const char *mesh_path = NULL, *cones_path = NULL, *pattern_path = NULL, *prefix = NULL;
    const char *valences_arg = NULL;
    long genus = -1, offset = -1;
    unsigned long long seed = 0;
    int have_seed = 0;
    int json = 0, svg = 1, omega = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int has = i + 1 < argc;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            help(stdout);
            return SQ_EXIT_OK;
        } else if (!strcmp(a, "--json")) {
            json = 1;
        } else if (!strcmp(a, "--no-svg")) {
            svg = 0;
        } else if (!strcmp(a, "--omega")) {
            omega = 1;
        } else if (!strcmp(a, "--genus") && has) {
            char *e;
            const char *arg = argv[++i];
            errno = 0;
            genus = strtol(arg, &e, 10);
            if (e == arg || *e || errno || genus < 0 || genus > 100000) {
                fprintf(stderr, "seamquad domain: --genus needs a non-negative integer\n");
                return SQ_EXIT_USAGE;
            }
        } else if (!strcmp(a, "--offset") && has) {
            char *e;
            const char *arg = argv[++i];
            errno = 0;
            offset = strtol(arg, &e, 10);
            if (e == arg || *e || errno || offset < 0 || offset >= (long)SQ_NONE) {
                fprintf(stderr, "seamquad domain: --offset needs a non-negative integer\n");
                return SQ_EXIT_USAGE;
            }
        } else if (!strcmp(a, "--seed") && has) {
            char *e;
            const char *arg = argv[++i];
            errno = 0;
            seed = strtoull(arg, &e, 10);
            if (e == arg || *e || errno || arg[0] == '-') {
                fprintf(stderr, "seamquad domain: --seed needs a non-negative integer\n");
                return SQ_EXIT_USAGE;
            }
            have_seed = 1;
        } else if (!strcmp(a, "--valences") && has) {
            valences_arg = argv[++i];
        } else if (!strcmp(a, "--cones") && has) {
            cones_path = argv[++i];
        } else if (!strcmp(a, "--pattern") && has) {
            pattern_path = argv[++i];
        } else if (!strcmp(a, "-o") && has) {
            prefix = argv[++i];
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "seamquad domain: unknown option or missing value '%s' (see "
                            "seamquad domain --help)\n", a);
            return SQ_EXIT_USAGE;
        } else if (!mesh_path) {
            mesh_path = a;
        } else {
            fprintf(stderr, "seamquad domain: unexpected argument '%s'\n", a);
            return SQ_EXIT_USAGE;
        }
    }
    if (!prefix || (mesh_path ? (!cones_path || valences_arg || genus >= 0)
                              : (!valences_arg || genus < 0))) {
        fprintf(stderr, "seamquad domain: give --genus and --valences, or MESH and --cones, and "
                        "-o PREFIX (see seamquad domain --help)\n");
        return SQ_EXIT_USAGE;
    }

    sq_error err;
    sq_error_clear(&err);
    int32_t *val = NULL;
    uint32_t nval = 0;
    sq_pattern pat;
    sq_pattern_init(&pat);
    sq_domain D;
    sq_domain_init(&D);
    double *xy = NULL;
    char *paths[5] = {NULL, NULL, NULL, NULL, NULL};
    sq_cone_tree tree;
    sq_cone_tree_init(&tree);
    sq_omega om;
    sq_omega_init(&om);
    double t_omega = 0;
    int written = 0, rc = SQ_EXIT_OK;
    const char *stage = "input";
    double t0 = sq_now();

    if (mesh_path) {
        sq_soup soup = {0};
        sq_mesh mesh = {0};
        if (sq_read_mesh(mesh_path, &soup, &err) || sq_mesh_from_soup(&soup, 0, &mesh, &err)) {
            sq_soup_free(&soup);
            goto fail;
        }
        genus = (long)sq_mesh_genus(&mesh);
        val = malloc((size_t)mesh.nv * sizeof *val);
        if (!val) {
            sq_error_set(&err, SQ_ERR_NOMEM, "out of memory");
        } else if (sq_cli_read_cones(cones_path, &mesh, val, &err) == SQ_OK) {
            nval = 0;
            for (uint32_t v = 0; v < mesh.nv; v++)
                if (val[v] != 4) val[nval++] = val[v];
        }
        sq_mesh_free(&mesh);
        sq_soup_free(&soup);
        if (err.code) goto fail;
    } else if (!parse_valences(valences_arg, &val, &nval)) {
        fprintf(stderr, "seamquad domain: --valences needs comma-separated integers, got '%s'\n",
                valences_arg);
        return SQ_EXIT_USAGE;
    }
    if (pattern_path && sq_pattern_read(pattern_path, &pat, &err)) goto fail;
    if (!pattern_path && have_seed && genus >= 2) {
        /* draws until the pattern passes the rank test (a third of them at
         * genus 2, nearly all from genus 5 on; docs/padding.md) */
        uint64_t state = seed;
        for (int draw = 0; draw < 1000; draw++) {
            if (sq_pattern_random((uint32_t)genus, &state, &pat, &err)) goto fail;
            if (sq_pattern_rank(&pat) == 2) break;
        }
        pattern_path = "(random)"; /* use pat below */
    }

    stage = "domain";
    sq_domain_options opt = {pattern_path ? &pat : NULL,
                             offset >= 0 ? (uint32_t)offset : SQ_NONE, NULL, 0, 0};
    if (sq_domain_build((uint32_t)genus, val, nval, &opt, &D, &err)) goto fail;
    stage = "verify";
    double t1 = sq_now();
    if (sq_domain_verify(&D, val, nval, &err)) goto fail;
    double t_verify = sq_now() - t1;

    if (omega) {
        /* seed 7: cut Q to the cones, lay it out flat, verify the seams */
        stage = "omega";
        double t3 = sq_now();
        if (sq_cone_tree_shortest(&D.quads, SQ_NONE, &tree, &err) ||
            sq_omega_build(&D, &tree, &om, &err) || sq_omega_verify(&D, &tree, &om, &err))
            goto fail;
        t_omega = sq_now() - t3;
    }

    stage = "output";
    xy = malloc(2 * (size_t)D.quads.nv * sizeof *xy);
    if (!xy) {
        sq_error_set(&err, SQ_ERR_NOMEM, "out of memory");
        goto fail;
    }
    double t2 = sq_now();
    /* genus 0: Q is a sphere cut along one edge, whose disk layout would be
     * one segment: a planar drawing of the sphere instead, lifted onto it
     * in the OBJ files */
    const int sphere = D.quads.nbnd <= 2;
    if (sphere ? sq_disk_layout_sphere(&D.quads, sq_disk_layout_sphere_outer(&D.quads), xy, &err)
               : sq_disk_layout_tutte(&D.quads, D.quads.v_he[D.corner_vert[0]], xy, &err))
        goto fail;
    paths[0] = join(prefix, ".quad.obj");
    paths[1] = join(prefix, ".closed.obj");
    paths[2] = join(prefix, ".sides.txt");
    paths[3] = join(prefix, ".svg");
    paths[4] = join(prefix, ".omega.svg");
    if (!paths[0] || !paths[1] || !paths[2] || !paths[3] || !paths[4]) {
        sq_error_set(&err, SQ_ERR_NOMEM, "out of memory");
        goto fail;
    }
    if (write_quads_obj(&D.quads, xy, sphere, paths[0], &err)) goto fail;
    written = 1;
    {
        sq_soup closed;
        if (sq_domain_glue(&D, xy, &closed, NULL, &err)) goto fail;
        for (uint32_t v = 0; sphere && v < closed.nv; v++)
            lift_to_sphere(closed.pos[3 * v], closed.pos[3 * v + 1], closed.pos + 3 * v);
        sq_status st = sq_write_obj(paths[1], closed.nv, closed.pos, closed.nf, closed.face_off,
                                    closed.face_idx, 0, NULL, NULL, &err);
        sq_soup_free(&closed);
        if (st) goto fail;
    }
    written = 2;
    if (write_sides(&D, paths[2], &err)) goto fail;
    written = 3;
    if (svg && sq_domain_write_svg(&D, xy, paths[3], &err)) goto fail;
    written = svg ? 4 : 3;
    if (omega) {
        if (!svg) { /* keep paths[] dense for the listing and the cleanup */
            free(paths[3]);
            paths[3] = paths[4];
            paths[4] = NULL;
        }
        if (sq_omega_write_svg(&D, &tree, &om, paths[written], &err)) goto fail;
        written++;
    }
    double t_output = sq_now() - t2;

    if (json) {
        printf("{\n  \"ok\": true,\n  \"genus\": %u,\n  \"cones\": %u,\n  \"valences\": [", D.genus,
               D.ncones);
        for (uint32_t i = 0; i < D.ncones; i++) printf("%s%u", i ? ", " : "", D.order[i]);
        printf("],\n  \"sides\": %u,\n  \"metapolygon_faces\": %u,\n", D.k, D.meta.nf);
        printf("  \"quads_before_padding\": %llu,\n  \"quads_added_by_padding\": %llu,\n",
               (unsigned long long)D.quads_unpadded, (unsigned long long)D.quads_added);
        printf("  \"quads\": %u,\n  \"offset\": %u,\n  \"offsets_feasible\": %u,\n", D.quads.nf,
               D.offset, D.offsets_feasible);
        if (D.slid)
            printf("  \"slide\": {\"length\": %u, \"shift\": %lld, \"seam\": [%u, %u]},\n",
                   D.slide_length, (long long)D.slide_shift, D.slide_start, D.slide_end);
        else
            printf("  \"slide\": null,\n");
        printf("  \"pieces\": %u,\n  \"refinement\": %llu,\n",
               D.genus == 0 ? 4u : D.genus == 1 && D.k == 6 ? 2u : 1u,
               (unsigned long long)D.refine);
        printf("  \"padding\": [");
        for (uint32_t i = 0; i < D.k; i++) printf("%s%lld", i ? ", " : "", (long long)D.padding[i]);
        printf("],\n  \"side_lengths\": [");
        for (uint32_t i = 0; i < D.k; i++) printf("%s%u", i ? ", " : "", D.side_len[i]);
        printf("],\n  \"partner\": [");
        for (uint32_t i = 0; i < D.k; i++) printf("%s%u", i ? ", " : "", D.pattern.partner[i]);
        printf("],\n  \"time_domain_s\": %.6f,\n  \"time_verify_s\": %.6f,\n", D.seconds,
               t_verify);
        if (omega)
            printf("  \"omega\": {\"tree_edges\": %u, \"time_s\": %.6f},\n", tree.nedges,
                   t_omega);
        printf("  \"time_output_s\": %.6f,\n  \"time_total_s\": %.6f,\n  \"outputs\": [", t_output,
               sq_now() - t0);
        for (int i = 0; i < written; i++) {
            printf("%s", i ? ", " : "");
            sq_json_string(stdout, paths[i]);
        }
        printf("]\n}\n");
    } else {
        printf("genus %u, %u cones, %u sides\n", D.genus, D.ncones, D.k);
        printf("metapolygon    %u faces\n", D.meta.nf);
        printf("quads          %llu before padding + %llu padding = %u\n",
               (unsigned long long)D.quads_unpadded, (unsigned long long)D.quads_added, D.quads.nf);
        if (D.genus >= 2 && !D.slid)
            printf("correspondence offset %u (%u of %u feasible), refinement %llu\n", D.offset,
                   D.offsets_feasible, D.k, (unsigned long long)D.refine);
        if (D.slid)
            printf("slide          the pattern fails the rank test: one slide (seed 6.4) along "
                   "%u edges, shift %lld\n",
                   D.slide_length, (long long)D.slide_shift);
        printf("verified       sides pair up with equal lengths; glued mesh closed, genus %u, "
               "irregular vertices = cones\n",
               D.genus);
        if (omega)
            printf("omega          cut along a %u-edge cone tree, laid out on the integer grid; "
                   "seams verified exactly (%.1f ms)\n",
                   tree.nedges, 1e3 * t_omega);
        printf("time           domain %.1f ms, verify %.1f ms, output %.1f ms\n", 1e3 * D.seconds,
               1e3 * t_verify, 1e3 * t_output);
        for (int i = 0; i < written; i++) printf("wrote          %s\n", paths[i]);
    }
    goto done;
fail:
    /* no half-written output: remove what this run wrote */
    for (int i = 0; i < written; i++) unlink(paths[i]);
    fprintf(stderr, "seamquad domain: error (%s): %s\n", stage, err.msg);
    if (json) {
        printf("{\n  \"ok\": false,\n  ");
        sq_json_error(err.code, stage, err.msg);
        printf("\n}\n");
    }
    /* the command line was checked above: an argument error from the
     * library here is about the input's content (pattern, cones, genus) */
    rc = err.code == SQ_ERR_ARGUMENT ? SQ_EXIT_INVALID_INPUT : sq_exit_code(err.code);
done:
    for (int i = 0; i < 5; i++) free(paths[i]);
    sq_cone_tree_free(&tree);
    sq_omega_free(&om);
    free(xy);
    free(val);
    sq_pattern_free(&pat);
    sq_domain_free(&D);
    return rc;
}
