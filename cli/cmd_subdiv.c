/* seamquad subdiv: Catmull-Clark limit surface of a closed quad mesh and its
 * export as bicubic B-spline patches for CAD (stages/sq_subdiv.h,
 * docs/subdiv.md). */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli_common.h"
#include "sq_io.h"
#include "sq_mesh.h"
#include "sq_subdiv.h"


static void help(FILE *f)
{
    fprintf(f,
            "usage: seamquad subdiv QUADS [--step OUT.step] [--iges OUT.igs]\n"
            "                       [--limit OUT.obj [--level N]] [--isolation L]\n"
            "                       [--refine K] [--seam-samples S] [--json]\n"
            "\n"
            "Builds the Catmull-Clark subdivision surface of a closed pure-quad mesh\n"
            "(OBJ, OFF or PLY) with OpenSubdiv and exports it:\n"
            "  - as bicubic B-spline patches for CAD: OpenSubdiv refines adaptively around\n"
            "    extraordinary vertices (valence != 4) and closes them with B-spline end\n"
            "    caps, so every patch is one uniform bicubic B-spline (4x4 control\n"
            "    points). Away from extraordinary vertices the patches ARE the limit\n"
            "    surface (C2 across borders); the end caps, 2^-L of a quad wide, are a\n"
            "    close approximation that interpolates the limit point at the vertex\n"
            "    (C0 with their neighbours, small normal jumps: see the report);\n"
            "  - as the limit surface sampled on a 2^N x 2^N grid per quad, positions and\n"
            "    normals evaluated on the surface, as a watertight OBJ with normals.\n"
            "The report gives the patch count, the gap between neighbouring patches\n"
            "(max distance of their shared border curves: ~1e-16 relative) and the\n"
            "jump of the normal across patch borders (max and mean, in degrees).\n"
            "\n"
            "options:\n"
            "  --step OUT.step   STEP AP214: one ADVANCED_FACE per patch (B-spline surface\n"
            "                    bounded by its four boundary curves) in an open shell\n"
            "  --iges OUT.igs    IGES 5.3: one entity 128 (B-spline surface, weights 1)\n"
            "                    per patch\n"
            "  --limit OUT.obj   the limit surface as a quad mesh with normals (vn)\n"
            "  --level N         grid 2^N x 2^N per quad for --limit (0..8, default 3)\n"
            "  --isolation L     adaptive isolation level of extraordinary vertices\n"
            "                    (1..10, default %d): higher = smaller end caps, more\n"
            "                    patches (about 3 x valence more per vertex and level)\n"
            "  --refine K        first apply K uniform Catmull-Clark steps (0..4; the\n"
            "                    surface is the same, the patches 4^K times more)\n"
            "  --seam-samples S  points per patch side for the seam report (default 8)\n"
            "  --json            print a machine-readable report on stdout\n"
            "  -h, --help        this help\n"
            "Files are written atomically: on failure no output file is left. Units are\n"
            "the mesh's; the CAD files declare millimetres.\n"
            "\n"
            "exit code 0 on success; 1 when the mesh cannot be processed (not closed,\n"
            "not pure quads, ...) or an output cannot be written; 2 for a wrong command\n"
            "line; 3 for an internal failure.\n"
            "\n"
            "example:\n"
            "  seamquad subdiv ../shared/data/quads/bunny_quadriflow5k.obj \\\n"
            "      --step bunny.step --iges bunny.igs --limit bunny_limit.obj --level 2\n",
            SQ_SUBDIV_DEFAULT_ISOLATION);
}

typedef struct subdiv_run {
    const char *mesh_path, *step_path, *iges_path, *limit_path;
    int level, isolation, refine;
    uint32_t seam_samples;
    uint32_t nv, nf, irregular, max_valence;
    int64_t genus;
    uint32_t np, limit_nv, limit_nq;
    double diag;
    sq_subdiv_seams seams;
    double t_read, t_refine, t_build, t_seams, t_limit, t_step, t_iges;
    long long step_bytes, iges_bytes, limit_bytes;
    int done;
    sq_error err;
    const char *err_stage;
} subdiv_run;

static long long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long long)st.st_size : -1;
}

static void run(subdiv_run *r)
{
    sq_soup soup = {0}, refined = {0};
    sq_mesh mesh = {0};
    sq_subdiv s = {0};
    sq_limit_mesh lm = {0};
    double t0 = sq_now();
    r->err_stage = "read";
    if (sq_read_mesh(r->mesh_path, &soup, &r->err)) goto done;
    r->err_stage = "validate";
    if (sq_mesh_from_soup(&soup, SQ_MESH_ALLOW_POLYGONS, &mesh, &r->err)) goto done;
    for (uint32_t f = 0; f < soup.nf; f++)
        if (soup.face_off[f + 1] - soup.face_off[f] != 4) {
            char where[512];
            sq_error_set(&r->err, SQ_ERR_POLYGON,
                         "%s: face %u has %u corners: Catmull-Clark export needs a pure-quad "
                         "mesh (run seamquad extract first)",
                         sq_soup_where_face(&soup, f, where, sizeof where), f,
                         soup.face_off[f + 1] - soup.face_off[f]);
            goto done;
        }
    r->t_read = sq_now() - t0;
    if (r->refine > 0) {
        r->err_stage = "refine";
        t0 = sq_now();
        if (sq_subdiv_refine(&soup, r->refine, &refined, &r->err)) goto done;
        sq_mesh_free(&mesh);
        if (sq_mesh_from_soup(&refined, SQ_MESH_ALLOW_POLYGONS, &mesh, &r->err)) goto done;
        r->t_refine = sq_now() - t0;
    }
    r->nv = mesh.nv;
    r->nf = mesh.nf;
    r->genus = sq_mesh_genus(&mesh);
    for (uint32_t v = 0; v < mesh.nv; v++) {
        uint32_t k = sq_mesh_vertex_valence(&mesh, v);
        if (k != 4) r->irregular++;
        if (k > r->max_valence) r->max_valence = k;
    }
    r->err_stage = "patches";
    t0 = sq_now();
    if (sq_subdiv_build(&mesh, r->isolation, &s, &r->err)) goto done;
    r->t_build = sq_now() - t0;
    r->np = s.np;
    r->diag = s.bbox_diag;
    r->err_stage = "seams";
    t0 = sq_now();
    if (sq_subdiv_seam_report(&s, &mesh, r->seam_samples, &r->seams, &r->err)) goto done;
    r->t_seams = sq_now() - t0;
    if (r->limit_path) {
        r->err_stage = "limit";
        t0 = sq_now();
        if (sq_subdiv_limit_mesh(&s, &mesh, r->level, &lm, &r->err)) goto done;
        if (sq_limit_mesh_write_obj(r->limit_path, &lm, &r->err)) goto done;
        r->t_limit = sq_now() - t0;
        r->limit_nv = lm.nv;
        r->limit_nq = lm.nq;
        r->limit_bytes = file_size(r->limit_path);
    }
    if (r->step_path) {
        r->err_stage = "step";
        t0 = sq_now();
        if (sq_cad_write_step(r->step_path, r->mesh_path, s.np, s.cv, s.bbox_diag, &r->err))
            goto done;
        r->t_step = sq_now() - t0;
        r->step_bytes = file_size(r->step_path);
    }
    if (r->iges_path) {
        r->err_stage = "iges";
        t0 = sq_now();
        if (sq_cad_write_iges(r->iges_path, r->mesh_path, s.np, s.cv, s.bbox_diag, &r->err))
            goto done;
        r->t_iges = sq_now() - t0;
        r->iges_bytes = file_size(r->iges_path);
    }
    r->done = 1;
done:
    sq_limit_mesh_free(&lm);
    sq_subdiv_free(&s);
    sq_mesh_free(&mesh);
    sq_soup_free(&refined);
    sq_soup_free(&soup);
}

static void print_text(const subdiv_run *r)
{
    const sq_subdiv_seams *g = &r->seams;
    printf("mesh       %s: %u vertices, %u quads, genus %lld, %u extraordinary vertices "
           "(max valence %u)%s\n",
           r->mesh_path, r->nv, r->nf, (long long)r->genus, r->irregular, r->max_valence,
           r->refine ? " after refinement" : "");
    if (r->refine) printf("refine     %d uniform Catmull-Clark step(s)\n", r->refine);
    printf("patches    %u bicubic B-spline patches (isolation level %d, B-spline end caps)\n",
           r->np, r->isolation);
    printf("seams      %llu border points: gap max %.3g (%.3g of the bbox diagonal %.6g)\n",
           (unsigned long long)g->points, g->max_gap, g->max_gap_rel, r->diag);
    printf("normals    jump across borders: max %.4g deg, mean %.4g deg; away from end caps "
           "max %.3g deg\n",
           g->max_normal_deg, g->mean_normal_deg, g->max_normal_regular_deg);
    if (r->limit_path)
        printf("limit      %s: %u vertices, %u quads (level %d), %lld bytes\n", r->limit_path,
               r->limit_nv, r->limit_nq, r->level, r->limit_bytes);
    if (r->step_path) printf("step       %s: %lld bytes\n", r->step_path, r->step_bytes);
    if (r->iges_path) printf("iges       %s: %lld bytes\n", r->iges_path, r->iges_bytes);
    printf("time       read %.1f ms, refine %.1f ms, patches %.1f ms, seams %.1f ms, limit %.1f "
           "ms, step %.1f ms, iges %.1f ms\n",
           1e3 * r->t_read, 1e3 * r->t_refine, 1e3 * r->t_build, 1e3 * r->t_seams,
           1e3 * r->t_limit, 1e3 * r->t_step, 1e3 * r->t_iges);
}

static void json_out(int *first, const char *key, const char *path, long long bytes, int written)
{
    printf("%s\"%s\": {\"path\": ", *first ? "" : ", ", key);
    *first = 0;
    sq_json_string(stdout, path);
    printf(", \"written\": %s, \"bytes\": %lld}", written ? "true" : "false", written ? bytes : 0);
}

static void print_json(const subdiv_run *r)
{
    const sq_subdiv_seams *g = &r->seams;
    printf("{\n  \"ok\": %s,\n  \"mesh\": {\"path\": ", r->done ? "true" : "false");
    sq_json_string(stdout, r->mesh_path);
    if (r->nf)
        printf(", \"vertices\": %u, \"faces\": %u, \"genus\": %lld, \"extraordinary\": %u, "
               "\"max_valence\": %u, \"refine\": %d",
               r->nv, r->nf, (long long)r->genus, r->irregular, r->max_valence, r->refine);
    printf("},\n  \"options\": {\"isolation\": %d, \"level\": %d, \"seam_samples\": %u}",
           r->isolation, r->level, r->seam_samples);
    printf(",\n  \"outputs\": {");
    int first = 1;
    if (r->step_path) json_out(&first, "step", r->step_path, r->step_bytes, r->done);
    if (r->iges_path) json_out(&first, "iges", r->iges_path, r->iges_bytes, r->done);
    if (r->limit_path) json_out(&first, "limit", r->limit_path, r->limit_bytes, r->done);
    printf("}");
    if (r->done) {
        printf(",\n  \"patches\": %u, \"bbox_diagonal\": %.17g", r->np, r->diag);
        if (r->limit_path)
            printf(",\n  \"limit\": {\"vertices\": %u, \"quads\": %u, \"level\": %d}", r->limit_nv,
                   r->limit_nq, r->level);
        printf(",\n  \"seams\": {\"points\": %llu, \"max_gap\": %.17g, \"max_gap_rel\": %.17g, "
               "\"normal_jump_max_deg\": %.17g, \"normal_jump_mean_deg\": %.17g, "
               "\"normal_jump_max_regular_deg\": %.17g}",
               (unsigned long long)g->points, g->max_gap, g->max_gap_rel, g->max_normal_deg,
               g->mean_normal_deg, g->max_normal_regular_deg);
        printf(",\n  \"time_ms\": {\"read\": %.3f, \"refine\": %.3f, \"patches\": %.3f, \"seams\": "
               "%.3f, \"limit\": %.3f, \"step\": %.3f, \"iges\": %.3f}",
               1e3 * r->t_read, 1e3 * r->t_refine, 1e3 * r->t_build, 1e3 * r->t_seams,
               1e3 * r->t_limit, 1e3 * r->t_step, 1e3 * r->t_iges);
    } else {
        printf(",\n  ");
        sq_json_error(r->err.code, r->err_stage, r->err.msg);
    }
    printf("\n}\n");
}

static int usage_error(const char *fmt, const char *arg)
{
    fprintf(stderr, "seamquad subdiv: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, " (see seamquad subdiv --help)\n");
    return SQ_EXIT_USAGE;
}

static int parse_int(const char *v, long lo, long hi, int *out)
{
    char *end;
    errno = 0;
    long x = strtol(v, &end, 10);
    if (end == v || *end || errno || x < lo || x > hi) return 0;
    *out = (int)x;
    return 1;
}

int sq_cmd_subdiv(int argc, char **argv)
{
    subdiv_run r;
    memset(&r, 0, sizeof r);
    r.level = 3;
    r.isolation = SQ_SUBDIV_DEFAULT_ISOLATION;
    r.seam_samples = 8;
    int json = 0, level_given = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char **path = NULL;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            help(stdout);
            return SQ_EXIT_OK;
        } else if (!strcmp(a, "--json")) {
            json = 1;
            continue;
        } else if (!strcmp(a, "--step")) {
            path = &r.step_path;
        } else if (!strcmp(a, "--iges")) {
            path = &r.iges_path;
        } else if (!strcmp(a, "--limit")) {
            path = &r.limit_path;
        } else if (!strcmp(a, "--level") || !strcmp(a, "--isolation") || !strcmp(a, "--refine") ||
                   !strcmp(a, "--seam-samples")) {
            if (i + 1 >= argc) return usage_error("%s needs a number", a);
            const char *v = argv[++i];
            int x;
            if (!strcmp(a, "--level")) {
                if (!parse_int(v, 0, 8, &x)) return usage_error("--level takes 0..8, not '%s'", v);
                r.level = x;
                level_given = 1;
            } else if (!strcmp(a, "--isolation")) {
                if (!parse_int(v, 1, 10, &x))
                    return usage_error("--isolation takes 1..10, not '%s'", v);
                r.isolation = x;
            } else if (!strcmp(a, "--refine")) {
                if (!parse_int(v, 0, 4, &x)) return usage_error("--refine takes 0..4, not '%s'", v);
                r.refine = x;
            } else {
                if (!parse_int(v, 1, 1000, &x))
                    return usage_error("--seam-samples takes 1..1000, not '%s'", v);
                r.seam_samples = (uint32_t)x;
            }
            continue;
        } else if (a[0] == '-' && a[1]) {
            return usage_error("unknown option '%s'", a);
        } else if (!r.mesh_path) {
            r.mesh_path = a;
            continue;
        } else {
            return usage_error("more than one mesh given (second: '%s')", a);
        }
        if (i + 1 >= argc) return usage_error("%s needs a file name", a);
        if (*path) return usage_error("%s given twice", a);
        *path = argv[++i];
        if (!**path) return usage_error("empty file name after %s", a);
    }
    if (!r.mesh_path) {
        help(stderr);
        return SQ_EXIT_USAGE;
    }
    if (level_given && !r.limit_path) return usage_error("--level needs --limit OUT.obj%s", "");
    run(&r);
    if (json) print_json(&r);
    else if (r.done) print_text(&r);
    if (!r.done) {
        fprintf(stderr, "seamquad subdiv: error: %s\n", r.err.msg);
        return sq_exit_code(r.err.code);
    }
    return SQ_EXIT_OK;
}
