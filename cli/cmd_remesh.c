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
#include "sq_subdiv.h"

static void help(FILE *f)
{
    fprintf(f,
            "usage: seamquad remesh MESH -o QUADS.obj [--cones FILE] [--map MAP.obj]\n"
            "                       [--quads N | --edge-length L]\n"
            "                       [--smooth on|off] [--step OUT.step] [--iges OUT.igs]\n"
            "                       [--limit OUT.obj [--level K]] [--iterations N]\n"
            "                       [--param auto|always|never] [--seed S]\n"
            "                       [--keep DIR] [--picture VIEW.svg] [--json] [--quiet]\n"
            "\n"
            "Turns the closed triangle mesh MESH (OBJ, OFF or PLY) into a closed, pure-quad\n"
            "mesh whose irregular vertices are exactly the cones, every vertex on MESH.\n"
            "\n"
            "Stages, each checked before the next starts:\n"
            "  cones     the file given, or the singularities of a smooth cross field\n"
            "            (as `seamquad cones` computes them)\n"
            "  map       a seamless map on MESH itself: the seam rotations of a smooth\n"
            "            cross field with these cones, the map closest to the field,\n"
            "            untangled (Garanzha et al. 2021) and checked exactly; where it\n"
            "            is not valid (a triangle left flipped, an angle sum off by a\n"
            "            turn), param builds the map instead\n"
            "  param     the seamless map built combinatorially (Zhou, Tu, Zorin and\n"
            "            Campen 2020): exact seams, every triangle positive, exactly\n"
            "            the cones, whatever the mesh; valid, but distorted and refined\n"
            "  optimize  the map's distortion lowered with the seam rotations kept and the\n"
            "            translations free (symmetric Dirichlet, projected Newton with\n"
            "            progressive references; `seamquad optimize`)\n"
            "  quantize  the integer-grid map at the size asked (`seamquad quantize`)\n"
            "  extract   the quad mesh of its integer grid; quads folded over the\n"
            "            surface are relaxed, and any left fail the run\n"
            "  smooth    first, where the unsmoothed quads pass through each other,\n"
            "            verify's repair on them (below); then the vertices moved on\n"
            "            MESH toward right angles and even edges, then some held on\n"
            "            MESH's sharp points where the quads would cut them off\n"
            "            (`seamquad smooth`); no step folds a quad; where\n"
            "            the smoothed quads turn over, or fail verify even after its\n"
            "            repair, the vertices involved go back to their unsmoothed\n"
            "            places (all of them if that is not enough)\n"
            "  verify    the quads, each split along its shorter diagonal, must not\n"
            "            intersect each other where the input does not intersect\n"
            "            itself (CGAL's exact test); where they do, the vertices of\n"
            "            the quads involved are relaxed on MESH (cones too, no quad\n"
            "            folded) for up to 20 rounds; a pair left (or a quad left\n"
            "            folded at extract) refuses the layout, and quantize to\n"
            "            verify run again from the same map: at a quarter above the\n"
            "            fewest quads the cones allow where the layout had those,\n"
            "            else with the arcs' lengths on the surface instead of in\n"
            "            the map as targets, then both 3%% above the size asked;\n"
            "            after four, where quads passed through each other, the map\n"
            "            is optimized again drawn 2, 4, 8, ... 64 times larger around\n"
            "            them (smaller quads there, as many in all) and laid out at\n"
            "            the size asked; ten layouts refused fail the run\n"
            "  export    with --step, --iges or --limit: the quads' Catmull-Clark\n"
            "            surface (OpenSubdiv) as B-spline patches or a limit mesh, as\n"
            "            `seamquad subdiv` writes them\n"
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
            "The map on MESH itself has the field's rotations by construction.\n"
            "\n"
            "options:\n"
            "  -o QUADS.obj         the quad mesh\n"
            "  --cones FILE         the cones (Th_hat angles or a `VERTEX VALENCE` list);\n"
            "                       default: from a smooth cross field\n"
            "  --map MAP.obj        start from this seamless map of MESH instead of param's\n"
            "                       (an OBJ with f v/vt corners, e.g. another tool's, as\n"
            "                       `seamquad quantize --map` takes it: made exact or\n"
            "                       refused); its cones are the run's (with --cones they\n"
            "                       must agree); optimize runs on it whole\n"
            "  --quads N            about N quads (default 5000; 1 <= N <= 1e8); below the\n"
            "                       fewest the cones' layout allows, that fewest\n"
            "                       (a quarter more where that layout is refused)\n"
            "  --edge-length L      quad edges of about L on the surface instead\n"
            "  --smooth on|off      the smoothing stage (default on)\n"
            "  --step OUT.step      the subdivision surface as STEP AP214 B-spline patches\n"
            "  --iges OUT.igs       the same as IGES 5.3 (entity 128 per patch)\n"
            "  --limit OUT.obj      the limit surface as a quad mesh with normals\n"
            "  --level K            its grid per quad, 2^K x 2^K (0..8, default 3)\n"
            "  --iterations N       optimizer iterations at most (default 600; it stops\n"
            "                       sooner where the map converges, most maps after 20\n"
            "                       to 170; fewer cost quality where they cut it short,\n"
            "                       about 0.2 s per iteration per 30K map faces)\n"
            "  --param MODE         auto (default): param's map where the map on MESH itself\n"
            "                       is not valid, or where its quads fail a later stage\n"
            "                       (the stages then run again: on a large mesh param's\n"
            "                       refined map takes minutes to optimize); always:\n"
            "                       param's map only; never: the map on MESH only (a\n"
            "                       failure is final, and quick)\n"
            "  --seed S             param's cut-graph seed (default 1; 4 attempts)\n"
            "  --keep DIR           also write every intermediate into DIR: cones.txt,\n"
            "                       map.obj (the map before optimize; not with --map),\n"
            "                       optimized.obj, igm.obj\n"
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
            "      --quads 5000 -o eight.quads.obj --step eight.step\n");
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
        if (k > 0 && !maps[k]->mesh.nv) { /* param's map, when the run started from one given */
            path[k][0] = 0;
            continue;
        }
        st = k == 0 ? sq_cones_from_field_write(path[k], nv, R->valence, 1, err)
                    : sq_map_write_obj(path[k], maps[k], err);
    }
    if (st)
        for (int j = 0; j < k - 1; j++)
            if (path[j][0]) remove(path[j]);
    return st;
}

/* The export stage: the quads' Catmull-Clark surface, computed whole
 * before any file is written. */
typedef struct surface {
    sq_mesh mesh;        /* the quads as a halfedge mesh             */
    sq_subdiv S;
    sq_limit_mesh lm;    /* with --limit                             */
    double seconds;
} surface;

static sq_status build_surface(const sq_quad_mesh *Q, int level, surface *out, sq_error *err)
{
    double t0 = sq_now();
    sq_soup soup;
    memset(&soup, 0, sizeof soup);
    soup.nv = Q->nv;
    soup.pos = Q->pos;
    soup.nf = Q->nq;
    soup.face_idx = Q->quad;
    soup.face_off = malloc(((size_t)Q->nq + 1) * sizeof *soup.face_off);
    if (!soup.face_off) return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (export)");
    for (uint32_t f = 0; f <= Q->nq; f++) soup.face_off[f] = 4 * f;
    sq_status st = sq_mesh_from_soup(&soup, SQ_MESH_ALLOW_POLYGONS, &out->mesh, err);
    free(soup.face_off);
    if (!st) st = sq_subdiv_build(&out->mesh, SQ_SUBDIV_DEFAULT_ISOLATION, &out->S, err);
    if (!st && level >= 0) st = sq_subdiv_limit_mesh(&out->S, &out->mesh, level, &out->lm, err);
    out->seconds = sq_now() - t0;
    return st;
}

static void surface_free(surface *s)
{
    sq_limit_mesh_free(&s->lm);
    sq_subdiv_free(&s->S);
    sq_mesh_free(&s->mesh);
}

static void print_text(const char *mesh_path, const char *out_path, const sq_mesh *m,
                       const sq_remesh_result *R, const sq_remesh_stats *s, const surface *surf)
{
    printf("mesh          %s: %u vertices, %u faces, genus %lld\n", mesh_path, m->nv, m->nf,
           (long long)sq_mesh_genus(m));
    printf("cones         %u (%s)\n", s->cones, s->cones_from_field ? "from a smooth cross field" : "given");
    if (s->from_map)
        printf("map           given: %u faces\n", s->optimize.faces_before);
    else if (s->map_from_rotations)
        printf("map           on the mesh, from the field's rotations: %u seam edges, %u triangles\n"
               "              untangled in %u iterations, %.2f s\n",
               s->rotations.seam_edges, s->rotations.flipped_start, s->rotations.iterations, s->t_rotations);
    else {
        if (s->t_rotations > 0)
            printf("map           on the mesh: not valid (%s), %.2f s\n", s->rotations.why, s->t_rotations);
        printf("param         %u faces (%u added vertices), attempt %u, %.2f s\n", s->param.faces_out,
               s->param.steiner, s->param.attempts, s->t_param);
    }
    printf("optimize      mean conformal ratio %.4g -> %.4g, %u iterations (%u with progressive\n"
           "              references), %.2f s: %s\n",
           s->optimize.conformal_before, s->optimize.conformal_after, s->optimize.iterations,
           s->optimize.reference_iterations, s->t_optimize, s->optimize.why);
    if (!s->from_map && !s->map_from_rotations)
        printf("simplify      %u rounds (%u with the translations fixed) removed %u added vertices:\n"
               "              %u -> %u faces\n",
               s->optimize.rounds, s->optimize.fixed_rounds, s->optimize.removed, s->optimize.faces_before,
               s->optimize.faces_after);
    printf("quantize      %.0f quads", s->quantize.quads);
    if (s->quantize.min_quads > 0 && s->quantize.quads > 0 && s->quantize.min_quads >= s->quantize.quads)
        printf(" (the fewest this layout allows)");
    printf(", T-mesh of %u rectangles, %.2f s\n", s->quantize.faces, s->t_quantize);
    if (s->layouts > 1)
        printf("              layout %u of those tried (targets in the %s%s); the last refused: %s\n",
               s->layouts, s->layout_targets == SQ_TARGETS_MAP ? "map" : "surface",
               s->magnified ? ", the map magnified where quads intersected" : "", s->layout_why);
    printf("extract       %u quads, %u vertices, %u irregular; %u folded quads relaxed; %.2f s\n",
           R->quads.nq, R->quads.nv, s->extract.irregular, s->untangle.folded_before, s->t_extract);
    if (s->smoothed) {
        printf("smooth        mean |angle-90| %.2f -> %.2f degrees, min angle %.1f -> %.1f, %d iterations,\n"
               "              %u vertices pinned on sharp points, %.2f s\n",
               s->smooth.before.angle_mean_dev_deg, s->smooth.after.angle_mean_dev_deg,
               s->smooth.before.angle_min_deg, s->smooth.after.angle_min_deg, s->smooth.iterations,
               s->smooth.pinned, s->t_smooth);
        if (s->smooth_kept)
            printf("              %u vertices kept unsmoothed around quads smoothing turned over\n"
                   "              or made intersect\n",
                   s->smooth_kept);
    } else if (s->smooth_reverted)
        printf("smooth        not kept (%s), %.2f s\n", s->smooth_why, s->t_smooth);
    else
        printf("smooth        off\n");
    printf("verified      pure quads, closed, manifold, the irregular vertices exactly the cones,\n"
           "              every vertex on the surface, no quad folded; %llu intersecting triangle\n"
           "              pairs (CGAL, each quad split along its shorter diagonal), %.2f s\n",
           (unsigned long long)s->self_intersections, s->t_verify);
    if (s->repaired_unsmoothed)
        printf("repaired      %llu intersecting pairs of the unsmoothed quads removed before smoothing\n",
               (unsigned long long)s->repaired_unsmoothed);
    if (s->repaired)
        printf("repaired      %llu intersecting pairs removed by relaxing their quads on the surface\n"
               "              (%u rounds)\n",
               (unsigned long long)s->repaired, s->repair_rounds);
    if (surf->S.np)
        printf("export        %u B-spline patches of the Catmull-Clark surface, %.2f s\n", surf->S.np,
               surf->seconds);
    printf("time          total %.2f s\n", s->t_total + surf->seconds);
    printf("wrote         %s\n", out_path);
}

static void print_json(sq_status st, const char *mesh_path, const char *out_path, const sq_mesh *m,
                       const sq_remesh_result *R, const sq_remesh_stats *s, const surface *surf,
                       const char *stage, const char *msg)
{
    printf("{\n  \"ok\": %s,\n  \"mesh\": ", st == SQ_OK ? "true" : "false");
    sq_json_string(stdout, mesh_path);
    printf(",\n  \"output\": ");
    sq_json_string(stdout, out_path);
    if (m->nv)
        printf(",\n  \"mesh_vertices\": %u, \"mesh_faces\": %u, \"genus\": %lld", m->nv, m->nf,
               (long long)sq_mesh_genus(m));
    printf(",\n  \"cones\": %u, \"cones_from_field\": %s, \"from_map\": %s", s->cones,
           s->cones_from_field ? "true" : "false", s->from_map ? "true" : "false");
    printf(",\n  \"map_on_mesh\": {\"tried\": %s, \"valid\": %s, \"seam_edges\": %u, \"flipped\": %u, "
           "\"untangle_iterations\": %u, \"flipped_after\": %u, \"seconds\": %.6f, \"why\": ",
           s->t_rotations > 0 ? "true" : "false", s->map_from_rotations ? "true" : "false",
           s->rotations.seam_edges, s->rotations.flipped_start, s->rotations.iterations,
           s->rotations.flipped_after, s->t_rotations);
    sq_json_string(stdout, s->rotations.why);
    printf("}");
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
    printf(",\n  \"quantize\": {\"quads\": %.0f, \"min_quads\": %.0f, \"tmesh_faces\": %u, \"layouts\": %u, "
           "\"magnified\": %u, \"targets\": \"%s\", \"layout_refused\": ",
           s->quantize.quads, s->quantize.min_quads, s->quantize.faces, s->layouts, s->magnified,
           s->layout_targets == SQ_TARGETS_MAP ? "map" : "surface");
    sq_json_string(stdout, s->layout_why);
    printf(", \"seconds\": %.6f}", s->t_quantize);
    printf(",\n  \"extract\": {\"quads\": %u, \"vertices\": %u, \"irregular\": %u, \"folded_before\": %u, "
           "\"folded_after\": %u, \"seconds\": %.6f}",
           R->quads.nq, R->quads.nv, s->extract.irregular, s->untangle.folded_before,
           s->untangle.folded_after, s->t_extract);
    printf(",\n  \"smooth\": {\"smoothed\": %s, \"reverted\": %s, \"angle_mean_dev_before\": ",
           s->smoothed ? "true" : "false", s->smooth_reverted ? "true" : "false");
    sq_json_double(stdout, s->smooth.before.angle_mean_dev_deg);
    printf(", \"angle_mean_dev_after\": ");
    sq_json_double(stdout, s->smooth.after.angle_mean_dev_deg);
    printf(", \"iterations\": %d, \"pinned\": %u, \"kept_unsmoothed\": %u, \"why\": ", s->smooth.iterations,
           s->smooth.pinned, s->smooth_kept);
    sq_json_string(stdout, s->smooth_why);
    printf(", \"seconds\": %.6f}", s->t_smooth);
    if (surf->S.np) printf(",\n  \"export\": {\"patches\": %u, \"seconds\": %.6f}", surf->S.np, surf->seconds);
    printf(",\n  \"verify\": {\"self_intersections\": %llu, \"input_self_intersections\": %lld, "
           "\"repaired_unsmoothed\": %llu, \"repaired\": %llu, \"repair_rounds\": %u, \"seconds\": %.6f}",
           (unsigned long long)s->self_intersections, (long long)s->input_self_intersections,
           (unsigned long long)s->repaired_unsmoothed, (unsigned long long)s->repaired, s->repair_rounds,
           s->t_verify);
    printf(",\n  \"time_s\": {\"cones\": %.6f, \"map_on_mesh\": %.6f, \"param\": %.6f, \"optimize\": %.6f, "
           "\"quantize\": %.6f, \"extract\": %.6f, \"smooth\": %.6f, \"verify\": %.6f, "
           "\"export\": %.6f, \"total\": %.6f}",
           s->t_cones, s->t_rotations, s->t_param, s->t_optimize, s->t_quantize, s->t_extract, s->t_smooth, s->t_verify,
           surf->seconds, s->t_total + surf->seconds);
    if (st != SQ_OK) {
        printf(",\n  ");
        sq_json_error(st, stage, msg);
    }
    printf("\n}\n");
}

int sq_cmd_remesh(int argc, char **argv)
{
    const char *mesh_path = NULL, *out_path = NULL, *cones_path = NULL, *keep_dir = NULL, *picture = NULL;
    const char *map_path = NULL;
    const char *step_path = NULL, *iges_path = NULL, *limit_path = NULL;
    int json = 0, quiet = 0, level = -1;
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
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output") || !strcmp(a, "--cones") || !strcmp(a, "--map") ||
                   !strcmp(a, "--quads") || !strcmp(a, "--edge-length") || !strcmp(a, "--iterations") ||
                   !strcmp(a, "--seed") || !strcmp(a, "--keep") || !strcmp(a, "--picture") ||
                   !strcmp(a, "--param") ||
                   !strcmp(a, "--smooth") || !strcmp(a, "--step") || !strcmp(a, "--iges") ||
                   !strcmp(a, "--limit") || !strcmp(a, "--level")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "seamquad remesh: %s needs a value\n", a);
                return SQ_EXIT_USAGE;
            }
            const char *v = argv[++i];
            double x = 0;
            if (!strcmp(a, "--cones")) cones_path = v;
            else if (!strcmp(a, "--map")) map_path = v;
            else if (!strcmp(a, "--keep")) keep_dir = v;
            else if (!strcmp(a, "--picture")) picture = v;
            else if (!strcmp(a, "--step")) step_path = v;
            else if (!strcmp(a, "--iges")) iges_path = v;
            else if (!strcmp(a, "--limit")) limit_path = v;
            else if (!strcmp(a, "--smooth")) {
                if (strcmp(v, "on") && strcmp(v, "off")) {
                    fprintf(stderr, "seamquad remesh: --smooth takes on or off, got '%s'\n", v);
                    return SQ_EXIT_USAGE;
                }
                opt.no_smoothing = !strcmp(v, "off");
            } else if (!strcmp(a, "--level")) {
                if (!sq_cli_number_option("remesh", a, v, &x) || x < 0 || x > 8 || x != floor(x)) {
                    fprintf(stderr, "seamquad remesh: --level needs an integer from 0 to 8, got '%s'\n", v);
                    return SQ_EXIT_USAGE;
                }
                level = (int)x;
            }
            else if (!strcmp(a, "--quads")) {
                if (!sq_cli_number_option("remesh", a, v, &opt.quads)) return SQ_EXIT_USAGE;
                have_quads = 1;
            } else if (!strcmp(a, "--edge-length")) {
                if (!sq_cli_number_option("remesh", a, v, &opt.edge_length)) return SQ_EXIT_USAGE;
                have_len = 1;
            } else if (!strcmp(a, "--iterations")) {
                if (!sq_cli_number_option("remesh", a, v, &x) || x < 1 || x > 100000 || x != floor(x)) {
                    fprintf(stderr, "seamquad remesh: --iterations needs a count from 1 to 100000, got '%s'\n", v);
                    return SQ_EXIT_USAGE;
                }
                opt.optimize_iterations = (uint32_t)x;
            } else if (!strcmp(a, "--param")) {
                if (strcmp(v, "auto") && strcmp(v, "always") && strcmp(v, "never")) {
                    fprintf(stderr, "seamquad remesh: --param takes auto, always or never, got '%s'\n", v);
                    return SQ_EXIT_USAGE;
                }
                opt.param = !strcmp(v, "always") ? SQ_REMESH_PARAM_ALWAYS
                            : !strcmp(v, "never") ? SQ_REMESH_PARAM_NEVER : SQ_REMESH_PARAM_AUTO;
            } else if (!strcmp(a, "--seed")) {
                if (!sq_cli_number_option("remesh", a, v, &x) || x < 1 || x > 1e15 || x != floor(x)) {
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
    if (level >= 0 && !limit_path) {
        fprintf(stderr, "seamquad remesh: --level sets the grid of --limit; give --limit OUT.obj\n");
        return SQ_EXIT_USAGE;
    }
    if (limit_path && level < 0) level = 3;
    const char *obj_outs[2] = {out_path, limit_path};
    for (int k = 0; k < 2; k++)
        if (obj_outs[k] && sq_format_from_path(obj_outs[k]) != SQ_FORMAT_OBJ) {
            fprintf(stderr, "seamquad remesh: the output '%s' must be an .obj file\n", obj_outs[k]);
            return SQ_EXIT_USAGE;
        }
    enum { NOUTS = 5 };
    const char *outs[NOUTS] = {out_path, picture, step_path, iges_path, limit_path};
    for (int k = 0; k < NOUTS; k++) {
        if (!outs[k]) continue;
        if (!strcmp(outs[k], mesh_path) || (cones_path && !strcmp(outs[k], cones_path)) ||
            (map_path && !strcmp(outs[k], map_path))) {
            fprintf(stderr, "seamquad remesh: the output '%s' would overwrite an input\n", outs[k]);
            return SQ_EXIT_USAGE;
        }
        for (int j = 0; j < k; j++)
            if (outs[j] && !strcmp(outs[j], outs[k])) {
                fprintf(stderr, "seamquad remesh: '%s' is given for two outputs\n", outs[k]);
                return SQ_EXIT_USAGE;
            }
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
    surface surf;
    memset(&surf, 0, sizeof surf);
    sq_status st = SQ_OK;
    for (int k = 0; k < NOUTS && !st; k++)
        if (outs[k]) st = sq_cli_probe_output(outs[k], &err);
    if (!st && keep_dir) {
        struct stat sb;
        if (stat(keep_dir, &sb) != 0 && mkdir(keep_dir, 0777) != 0)
            st = sq_error_set(&err, SQ_ERR_IO, "%s: cannot create the directory: %s", keep_dir, strerror(errno));
        else if (stat(keep_dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
            st = sq_error_set(&err, SQ_ERR_IO, "%s: not a directory", keep_dir);
        else {
            char probe[4096];
            snprintf(probe, sizeof probe, "%s/igm.obj", keep_dir);
            st = sq_cli_probe_output(probe, &err);
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
    sq_map start;
    memset(&start, 0, sizeof start);
    if (!st && map_path) {
        stage = "map";
        st = sq_map_read(map_path, &mesh, valence, 1e-9, 0, &start, NULL, &err);
        if (st) sq_cli_name_file(&err, map_path);
        opt.map = &start;
    }
    if (!st) {
        st = sq_remesh(&mesh, valence, &opt, &R, &s, &err);
        if (st) stage = s.stage ? s.stage : "remesh";
    }
    if (!st && (step_path || iges_path || limit_path)) {
        stage = "export";
        if (opt.progress) progress(&ps, "export", 1);
        st = build_surface(&R.quads, limit_path ? level : -1, &surf, &err);
    }
    if (!st) {
        /* every output, or none: what was written is removed on a failure */
        stage = "write";
        int written = 0;
        for (; written < NOUTS && !st; written++) {
            const char *path = outs[written];
            if (!path) continue;
            if (written == 0) {
                st = sq_quad_mesh_write_obj(path, &R.quads, &err);
            } else if (written == 1) {
                char title[256];
                snprintf(title, sizeof title, "%s: %u quads, %u irregular vertices (the cones)", mesh_path,
                         R.quads.nq, s.extract.irregular);
                st = sq_quad_svg_write(path, R.quads.nv, R.quads.pos, R.quads.nq, R.quads.quad, title, &err);
            } else if (written == 2) {
                st = sq_cad_write_step(path, mesh_path, surf.S.np, surf.S.cv, surf.S.bbox_diag, &err);
            } else if (written == 3) {
                st = sq_cad_write_iges(path, mesh_path, surf.S.np, surf.S.cv, surf.S.bbox_diag, &err);
            } else {
                st = sq_limit_mesh_write_obj(path, &surf.lm, &err);
            }
        }
        if (!st && keep_dir) {
            st = write_keep(keep_dir, mesh.nv, &R, &err);
            written = NOUTS + 1;
        }
        if (st)
            for (int k = 0; k < written - 1 && k < NOUTS; k++)
                if (outs[k] && !sq_is_special_file(outs[k])) remove(outs[k]);
    }
    if (json) print_json(st, mesh_path, out_path, &mesh, &R, &s, &surf, stage, err.msg);
    else if (!st && !quiet) print_text(mesh_path, out_path, &mesh, &R, &s, &surf);
    if (st) fprintf(stderr, "seamquad remesh: error (%s): %s\n", stage, err.msg);
    free(valence);
    sq_map_free(&start);
    surface_free(&surf);
    sq_remesh_result_free(&R);
    sq_mesh_free(&mesh);
    sq_soup_free(&soup);
    if (st == SQ_ERR_ARGUMENT) return SQ_EXIT_INVALID_INPUT;
    return sq_exit_code(st);
}
