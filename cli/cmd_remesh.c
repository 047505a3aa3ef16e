/* seamquad remesh: the whole pipeline, a closed triangle mesh in, a quad
 * mesh out (stages/sq_remesh.h, docs/remesh.md). */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli_common.h"
#include "sq_io.h"
#include "sq_mesh.h"
#include "sq_quad_svg.h"
#include "sq_remesh.h"

static void help(FILE *f)
{
    fprintf(f,
            "usage: seamquad remesh MESH -o QUADS.obj [--cones FILE] [--quads N | --edge-length L]\n"
            "                       [--iterations N] [--seed S] [--keep DIR] [--picture VIEW.svg]\n"
            "                       [--json] [--quiet]\n"
            "\n"
            "Turns the closed triangle mesh MESH (OBJ, OFF or PLY) into a closed, pure-quad\n"
            "mesh whose irregular vertices are exactly the cones, every vertex on MESH.\n"
            "\n"
            "Stages, each checked before the next starts:\n"
            "  cones     the file given, or the singularities of a smooth cross field\n"
            "            (as `seamquad cones` computes them)\n"
            "  param     the seamless map built combinatorially (Zhou, Tu, Zorin and\n"
            "            Campen 2020): exact seams, every triangle positive, exactly\n"
            "            the cones; valid, but distorted\n"
            "  optimize  its distortion lowered with the seam rotations kept and the\n"
            "            translations free (symmetric Dirichlet, projected Newton with\n"
            "            progressive references; `seamquad optimize`)\n"
            "  quantize  the integer-grid map at the size asked (`seamquad quantize`)\n"
            "  extract   the quad mesh of its integer grid; quads folded over the\n"
            "            surface are relaxed, and any left fail the run\n"
            "  verify    the quads, each split along its shorter diagonal, must not\n"
            "            intersect each other where the input does not intersect\n"
            "            itself (CGAL's exact test); if they do, the run fails\n"
            "\n"
            "Guarantees of QUADS.obj (written only when all hold): only quads, closed,\n"
            "manifold, MESH's genus, the irregular vertices exactly the cones (a cone\n"
            "of angle k*90 degrees is a vertex of k quads), every vertex on MESH, no\n"
            "quad folded over the surface, no quad through another (where MESH does\n"
            "not intersect itself).\n"
            "\n"
            "The quality follows the map: where param's seam rotations around the\n"
            "handles disagree with a smooth cross field (docs/remesh.md lists the\n"
            "models), no optimizer reaches a low distortion and the quads are skewed.\n"
            "\n"
            "options:\n"
            "  -o QUADS.obj         the quad mesh\n"
            "  --cones FILE         the cones (Th_hat angles or a `VERTEX VALENCE` list);\n"
            "                       default: from a smooth cross field\n"
            "  --quads N            about N quads (default 5000; 1 <= N <= 1e8); below the\n"
            "                       fewest the cones' layout allows, that fewest\n"
            "  --edge-length L      quad edges of about L on the surface instead\n"
            "  --iterations N       optimizer iterations at most (default 200; it stops\n"
            "                       sooner where the map converges; more lower the\n"
            "                       distortion further, at about 0.2 s per iteration\n"
            "                       per 30K map faces)\n"
            "  --seed S             param's cut-graph seed (default 1; 4 attempts)\n"
            "  --keep DIR           also write every intermediate into DIR: cones.txt,\n"
            "                       map.obj (param's), optimized.obj, igm.obj\n"
            "  --picture VIEW.svg   a shaded view of the quads (irregular vertices red\n"
            "                       below valence 4, blue above)\n"
            "  --json               statistics on stdout: per stage sizes, quality, times\n"
            "  --quiet              no progress on stderr, no summary on stdout\n"
            "  -h, --help           this help\n"
            "\n"
            "exit codes: 0 success; 1 the input cannot be processed (the message names\n"
            "the file and element) or an output cannot be written (found before the work\n"
            "starts); 2 wrong command line; 3 a stage failed (named, with the cause) or\n"
            "an internal failure. On any error nothing is written.\n"
            "\n"
            "example:\n"
            "  seamquad remesh ../shared/data/mpz/eight.obj --cones ../shared/data/mpz/eight_Th_hat \\\n"
            "      --quads 5000 -o eight.quads.obj\n");
}

typedef struct progress_state {
    const char *stage;
    double last, t0;
} progress_state;

static void progress(void *user, const char *stage, double fraction)
{
    progress_state *ps = user;
    int new_stage = !ps->stage || strcmp(ps->stage, stage);
    if (!new_stage && fraction < ps->last + 0.05) return;
    ps->stage = stage;
    ps->last = fraction;
    fprintf(stderr, "[%3.0f%%] %-9s %7.1f s\n", 100 * fraction, stage, sq_now() - ps->t0);
}

static int number_option(const char *opt, const char *val, double *out)
{
    char *end = NULL;
    double x = strtod(val, &end);
    if (!end || *end || end == val || !isfinite(x)) {
        fprintf(stderr, "seamquad remesh: %s needs a number, got '%s'\n", opt, val);
        return 0;
    }
    *out = x;
    return 1;
}

/* An output that cannot be written is found before the work starts: a
 * temporary file is created beside it and removed. */
static sq_status probe_output(const char *path, sq_error *err)
{
    sq_atomic_file af;
    sq_status st = sq_atomic_open(&af, path, err);
    if (!st) sq_atomic_abort(&af);
    return st;
}

/* The intermediates into dir; on failure none is left. */
static sq_status write_keep(const char *dir, uint32_t nv, const sq_remesh_result *R, sq_error *err)
{
    static const char *const names[4] = {"cones.txt", "map.obj", "optimized.obj", "igm.obj"};
    const sq_map *maps[4] = {NULL, &R->map, &R->optimized, &R->igm};
    char path[4][4096];
    sq_status st = SQ_OK;
    int k = 0;
    for (; k < 4 && !st; k++) {
        snprintf(path[k], sizeof path[k], "%s/%s", dir, names[k]);
        st = k == 0 ? sq_cones_from_field_write(path[k], nv, R->valence, 1, err)
                    : sq_map_write_obj(path[k], maps[k], err);
    }
    if (st)
        for (int j = 0; j < k - 1; j++) remove(path[j]);
    return st;
}

static void print_text(const char *mesh_path, const char *out_path, const sq_mesh *m,
                       const sq_remesh_result *R, const sq_remesh_stats *s)
{
    printf("mesh          %s: %u vertices, %u faces, genus %lld\n", mesh_path, m->nv, m->nf,
           (long long)sq_mesh_genus(m));
    printf("cones         %u (%s)\n", s->cones, s->cones_from_field ? "from a smooth cross field" : "given");
    printf("param         %u faces (%u added vertices), attempt %u, %.2f s\n", s->param.faces_out,
           s->param.steiner, s->param.attempts, s->t_param);
    printf("optimize      mean conformal ratio %.4g -> %.4g, %u iterations (%u with progressive\n"
           "              references), %.2f s: %s\n",
           s->optimize.conformal_before, s->optimize.conformal_after, s->optimize.iterations,
           s->optimize.reference_iterations, s->t_optimize, s->optimize.why);
    printf("simplify      %u rounds (%u with the translations fixed) removed %u added vertices:\n"
           "              %u -> %u faces\n",
           s->optimize.rounds, s->optimize.fixed_rounds, s->optimize.removed, s->optimize.faces_before,
           s->optimize.faces_after);
    printf("quantize      %.0f quads", s->quantize.quads);
    if (s->quantize.min_quads > 0 && s->quantize.quads > 0 && s->quantize.min_quads >= s->quantize.quads)
        printf(" (the fewest this layout allows)");
    printf(", T-mesh of %u rectangles, %.2f s\n", s->quantize.faces, s->t_quantize);
    printf("extract       %u quads, %u vertices, %u irregular; %u folded quads relaxed; %.2f s\n",
           R->quads.nq, R->quads.nv, s->extract.irregular, s->untangle.folded_before, s->t_extract);
    printf("verified      pure quads, closed, manifold, the irregular vertices exactly the cones,\n"
           "              every vertex on the surface, no quad folded; %llu intersecting triangle\n"
           "              pairs (CGAL, each quad split along its shorter diagonal), %.2f s\n",
           (unsigned long long)s->self_intersections, s->t_verify);
    printf("time          total %.2f s\n", s->t_total);
    printf("wrote         %s\n", out_path);
}

static void print_json(sq_status st, const char *mesh_path, const char *out_path, const sq_mesh *m,
                       const sq_remesh_result *R, const sq_remesh_stats *s, const char *stage,
                       const char *msg)
{
    printf("{\n  \"ok\": %s,\n  \"mesh\": ", st == SQ_OK ? "true" : "false");
    sq_json_string(stdout, mesh_path);
    printf(",\n  \"output\": ");
    sq_json_string(stdout, out_path);
    if (m->nv)
        printf(",\n  \"mesh_vertices\": %u, \"mesh_faces\": %u, \"genus\": %lld", m->nv, m->nf,
               (long long)sq_mesh_genus(m));
    printf(",\n  \"cones\": %u, \"cones_from_field\": %s", s->cones, s->cones_from_field ? "true" : "false");
    printf(",\n  \"param\": {\"faces\": %u, \"steiner\": %u, \"attempts\": %u, \"seconds\": %.6f}",
           s->param.faces_out, s->param.steiner, s->param.attempts, s->t_param);
    printf(",\n  \"optimize\": {\"iterations\": %u, \"reference_iterations\": %u, \"rounds\": %u, "
           "\"fixed_rounds\": %u, \"removed\": %u, \"faces_before\": %u, \"faces_after\": %u, "
           "\"conformal_before\": ",
           s->optimize.iterations, s->optimize.reference_iterations, s->optimize.rounds,
           s->optimize.fixed_rounds, s->optimize.removed, s->optimize.faces_before, s->optimize.faces_after);
    sq_json_double(stdout, s->optimize.conformal_before);
    printf(", \"conformal_after\": ");
    sq_json_double(stdout, s->optimize.conformal_after);
    printf(", \"seconds\": %.6f, \"stopped\": ", s->t_optimize);
    sq_json_string(stdout, s->optimize.why);
    printf("}");
    printf(",\n  \"quantize\": {\"quads\": %.0f, \"min_quads\": %.0f, \"tmesh_faces\": %u, \"seconds\": %.6f}",
           s->quantize.quads, s->quantize.min_quads, s->quantize.faces, s->t_quantize);
    printf(",\n  \"extract\": {\"quads\": %u, \"vertices\": %u, \"irregular\": %u, \"folded_before\": %u, "
           "\"folded_after\": %u, \"seconds\": %.6f}",
           R->quads.nq, R->quads.nv, s->extract.irregular, s->untangle.folded_before,
           s->untangle.folded_after, s->t_extract);
    printf(",\n  \"verify\": {\"self_intersections\": %llu, \"input_self_intersections\": %lld, \"seconds\": %.6f}",
           (unsigned long long)s->self_intersections, (long long)s->input_self_intersections, s->t_verify);
    printf(",\n  \"time_s\": {\"cones\": %.6f, \"param\": %.6f, \"optimize\": %.6f, "
           "\"quantize\": %.6f, \"extract\": %.6f, \"verify\": %.6f, \"total\": %.6f}",
           s->t_cones, s->t_param, s->t_optimize, s->t_quantize, s->t_extract, s->t_verify, s->t_total);
    if (st != SQ_OK) {
        printf(",\n  ");
        sq_json_error(st, stage, msg);
    }
    printf("\n}\n");
}

int sq_cmd_remesh(int argc, char **argv)
{
    const char *mesh_path = NULL, *out_path = NULL, *cones_path = NULL, *keep_dir = NULL, *picture = NULL;
    int json = 0, quiet = 0;
    sq_remesh_options opt;
    memset(&opt, 0, sizeof opt);
    int have_quads = 0, have_len = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            help(stdout);
            return SQ_EXIT_OK;
        } else if (!strcmp(a, "--json")) {
            json = 1;
        } else if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
            quiet = 1;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output") || !strcmp(a, "--cones") ||
                   !strcmp(a, "--quads") || !strcmp(a, "--edge-length") || !strcmp(a, "--iterations") ||
                   !strcmp(a, "--seed") || !strcmp(a, "--keep") || !strcmp(a, "--picture")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "seamquad remesh: %s needs a value\n", a);
                return SQ_EXIT_USAGE;
            }
            const char *v = argv[++i];
            double x = 0;
            if (!strcmp(a, "--cones")) cones_path = v;
            else if (!strcmp(a, "--keep")) keep_dir = v;
            else if (!strcmp(a, "--picture")) picture = v;
            else if (!strcmp(a, "--quads")) {
                if (!number_option(a, v, &opt.quads)) return SQ_EXIT_USAGE;
                have_quads = 1;
            } else if (!strcmp(a, "--edge-length")) {
                if (!number_option(a, v, &opt.edge_length)) return SQ_EXIT_USAGE;
                have_len = 1;
            } else if (!strcmp(a, "--iterations")) {
                if (!number_option(a, v, &x) || x < 1 || x > 100000 || x != floor(x)) {
                    fprintf(stderr, "seamquad remesh: --iterations needs a count from 1 to 100000, got '%s'\n", v);
                    return SQ_EXIT_USAGE;
                }
                opt.optimize_iterations = (uint32_t)x;
            } else if (!strcmp(a, "--seed")) {
                if (!number_option(a, v, &x) || x < 1 || x > 1e15 || x != floor(x)) {
                    fprintf(stderr, "seamquad remesh: --seed needs a positive integer, got '%s'\n", v);
                    return SQ_EXIT_USAGE;
                }
                opt.seed = (uint64_t)x;
            } else out_path = v;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "seamquad remesh: unknown option '%s' (see seamquad remesh --help)\n", a);
            return SQ_EXIT_USAGE;
        } else if (!mesh_path) {
            mesh_path = a;
        } else {
            fprintf(stderr, "seamquad remesh: unexpected argument '%s' (one MESH)\n", a);
            return SQ_EXIT_USAGE;
        }
    }
    if (!mesh_path || !out_path) {
        fprintf(stderr, "seamquad remesh: give MESH and -o QUADS.obj (see seamquad remesh --help)\n");
        return SQ_EXIT_USAGE;
    }
    if (have_quads && have_len) {
        fprintf(stderr, "seamquad remesh: give --quads or --edge-length, not both\n");
        return SQ_EXIT_USAGE;
    }
    if (have_quads && !(opt.quads >= 1 && opt.quads <= 1e8)) {
        fprintf(stderr, "seamquad remesh: --quads %g: the quad count must be between 1 and 1e8\n", opt.quads);
        return SQ_EXIT_USAGE;
    }
    if (have_len && !(opt.edge_length > 0)) {
        fprintf(stderr, "seamquad remesh: --edge-length %g: the edge length must be positive\n",
                opt.edge_length);
        return SQ_EXIT_USAGE;
    }
    if (sq_format_from_path(out_path) != SQ_FORMAT_OBJ) {
        fprintf(stderr, "seamquad remesh: the output '%s' must be an .obj file\n", out_path);
        return SQ_EXIT_USAGE;
    }
    const char *outs[2] = {out_path, picture};
    for (int k = 0; k < 2; k++)
        if (outs[k] && (!strcmp(outs[k], mesh_path) || (cones_path && !strcmp(outs[k], cones_path)))) {
            fprintf(stderr, "seamquad remesh: the output '%s' would overwrite an input\n", outs[k]);
            return SQ_EXIT_USAGE;
        }
    opt.keep_maps = keep_dir != NULL;
    progress_state ps = {NULL, 0, sq_now()};
    if (!quiet && !json) {
        opt.progress = progress;
        opt.user = &ps;
    }

    sq_error err;
    sq_error_clear(&err);
    sq_soup soup;
    memset(&soup, 0, sizeof soup);
    sq_mesh mesh;
    memset(&mesh, 0, sizeof mesh);
    sq_remesh_result R;
    memset(&R, 0, sizeof R);
    sq_remesh_stats s;
    memset(&s, 0, sizeof s);
    int32_t *valence = NULL;
    const char *stage = "output";
    sq_status st = probe_output(out_path, &err);
    if (!st && picture) st = probe_output(picture, &err);
    if (!st && keep_dir) {
        struct stat sb;
        if (stat(keep_dir, &sb) != 0 && mkdir(keep_dir, 0777) != 0)
            st = sq_error_set(&err, SQ_ERR_IO, "%s: cannot create the directory: %s", keep_dir, strerror(errno));
        else if (stat(keep_dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
            st = sq_error_set(&err, SQ_ERR_IO, "%s: not a directory", keep_dir);
        else {
            char probe[4096];
            snprintf(probe, sizeof probe, "%s/igm.obj", keep_dir);
            st = probe_output(probe, &err);
        }
    }
    if (!st) {
        stage = "read";
        st = sq_read_mesh(mesh_path, &soup, &err);
        if (!st) st = sq_mesh_from_soup(&soup, 0, &mesh, &err);
    }
    if (!st && cones_path) {
        stage = "cones";
        valence = malloc((size_t)mesh.nv * sizeof *valence);
        if (!valence) st = sq_error_set(&err, SQ_ERR_NOMEM, "out of memory");
        else st = sq_cli_read_cones(cones_path, &mesh, valence, &err);
    }
    if (!st) {
        st = sq_remesh(&mesh, valence, &opt, &R, &s, &err);
        if (st) stage = s.stage ? s.stage : "remesh";
    }
    if (!st) {
        stage = "write";
        st = sq_cli_write_quads(out_path, &R.quads, &err);
        if (!st && picture) {
            char title[256];
            snprintf(title, sizeof title, "%s: %u quads, %u irregular vertices (the cones)", mesh_path, R.quads.nq,
                     s.extract.irregular);
            st = sq_quad_svg_write(picture, R.quads.nv, R.quads.pos, R.quads.nq, R.quads.quad, title, &err);
            if (st) remove(out_path);
        }
        if (!st && keep_dir) {
            st = write_keep(keep_dir, mesh.nv, &R, &err);
            if (st) {
                remove(out_path);
                if (picture) remove(picture);
            }
        }
    }
    if (json) print_json(st, mesh_path, out_path, &mesh, &R, &s, stage, err.msg);
    else if (!st && !quiet) print_text(mesh_path, out_path, &mesh, &R, &s);
    if (st) fprintf(stderr, "seamquad remesh: error (%s): %s\n", stage, err.msg);
    free(valence);
    sq_remesh_result_free(&R);
    sq_mesh_free(&mesh);
    sq_soup_free(&soup);
    if (st == SQ_ERR_ARGUMENT) return SQ_EXIT_INVALID_INPUT;
    return sq_exit_code(st);
}
