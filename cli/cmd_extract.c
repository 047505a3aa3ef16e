/* seamquad extract: the closed pure-quad mesh of an integer-grid map
 * (extract/sq_extract.h, docs/extract.md). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "sq_extract.h"
#include "sq_io.h"
#include "sq_map.h"
#include "sq_mesh.h"

#define MAX_VALENCE_HIST 64

static void help(FILE *f)
{
    fprintf(f,
            "usage: seamquad extract MESH IGM.obj -o QUADS.obj [--cones FILE]\n"
            "                        [--json] [--quiet]\n"
            "\n"
            "Extracts the quad mesh of an integer-grid map (IGM) of the closed triangle\n"
            "mesh MESH.\n"
            "\n"
            "An integer-grid map gives every corner of every triangle a UV point, in a\n"
            "chart of its own triangle, such that:\n"
            "  - every UV triangle is positively oriented (the map is locally injective);\n"
            "  - across every edge the two charts differ by a rotation by a multiple of\n"
            "    90 degrees plus an INTEGER translation, exactly in floating point;\n"
            "  - every cone (a vertex whose UV angle sum is k*pi/2 with k != 4) lies on\n"
            "    an integer point.\n"
            "The integer grid lines of the charts then join across the seams into a net\n"
            "of quadrilaterals covering the surface. `seamquad param` writes such maps\n"
            "(at unit-square scale: one quad per unit of UV area); multiplying every vt\n"
            "by an integer k gives another one with k*k times the quads.\n"
            "\n"
            "IGM.obj is an OBJ with `f v/vt` corners. Its first vertices must be those\n"
            "of MESH, in order and at the same positions (a refinement, as param writes\n"
            "it; its added vertices lie on MESH, and may form 3D slivers). It is checked\n"
            "exactly before anything else, with no tolerance and no snapping.\n"
            "\n"
            "Steps: (1) the integer points of the map, each once: at mesh vertices,\n"
            "strictly inside edges, strictly inside faces; (2) from each point, each\n"
            "grid direction (4, or k at a cone of valence k) is traced as the unit\n"
            "segment to the next point, across triangles and seams; (3) the quads: each\n"
            "directed grid edge has one quad on its left, found by turning left at its\n"
            "end, four times; (4) each point's position by barycentric interpolation in\n"
            "the triangle (or edge, or vertex) holding it. Every decision is an exact\n"
            "orientation test on the stored doubles. (5) Where a quad is folded in 3D\n"
            "or turned over (every corner facing away from the surface), as where the\n"
            "map is distorted at the scale of one quad, the vertices of such quads\n"
            "other than cones move towards their neighbours' mean (or other targets),\n"
            "projected back onto MESH, each move kept only if it helps; the summary\n"
            "counts the bad quads before and after. (6) Every quad is judged as\n"
            "check_quad.py judges it: none folded, no edge of length <= 1e-12 of the\n"
            "bounding-box diagonal, no area <= 1e-12 of its square; and none turned\n"
            "over; one such quad and nothing is written (exit 1, the counts and the\n"
            "first quad named).\n"
            "\n"
            "Guarantees of QUADS.obj (written only when all hold):\n"
            "  - only quads; closed, manifold, consistently oriented (as MESH), one\n"
            "    component, the Euler characteristic of MESH;\n"
            "  - its irregular vertices are exactly the cones, a cone of valence k a\n"
            "    vertex of valence k; every other vertex has valence 4;\n"
            "  - every vertex lies on MESH (a convex combination of one triangle's\n"
            "    corners); no quad repeats a vertex, no two edges join the same points;\n"
            "  - the number of quads equals the UV area of the map;\n"
            "  - no quad folded or turned over, none with a zero-length edge or zero\n"
            "    area (step 6).\n"
            "The shapes are the map's: where it is strongly distorted, quads spanning\n"
            "bent regions fold in 3D that step 5 may not unfold (param's maps, see\n"
            "docs/extract.md); `seamquad optimize` lowers a map's distortion first.\n"
            "\n"
            "options:\n"
            "  -o QUADS.obj  the quad mesh (v and f lines; vertices at mesh vertices\n"
            "                first, then inside edges, then inside faces)\n"
            "  --cones FILE  the cones the map must have (Th_hat or cone list, see check\n"
            "                --help): every vertex of MESH must have the UV angle sum of\n"
            "                its valence, so the quad mesh's irregular vertices are these\n"
            "                cones; without it, the cones are whatever the map's angle\n"
            "                sums say\n"
            "  --json        machine-readable statistics on stdout: grid points by kind,\n"
            "                quads, edges, irregular vertices, valences, time per step\n"
            "  --quiet       no summary on stdout (errors still on stderr)\n"
            "  -h, --help    this help\n"
            "\n"
            "exit codes: 0 success; 1 the input cannot be processed (a broken mesh, a\n"
            "map that is not an integer-grid map of MESH, a map too coarse for a quad\n"
            "mesh: the message names the file, face, vertex or grid point) or the output\n"
            "cannot be written; 2 wrong command line; 3 internal failure (a bug: an\n"
            "inconsistent trace; or out of memory). On any error nothing is written.\n"
            "\n"
            "example:\n"
            "  seamquad param ../shared/data/mpz/eight.obj \\\n"
            "      --cones ../shared/data/mpz/eight_Th_hat -o eight.igm.obj\n"
            "  seamquad extract ../shared/data/mpz/eight.obj eight.igm.obj -o eight.quads.obj\n"
            "  python3 ../shared/tools/check_quad.py ../shared/data/mpz/eight.obj \\\n"
            "      eight.quads.obj --cones ../shared/data/mpz/eight_Th_hat\n");
}

typedef struct report {
    const char *mesh_path, *map_path, *out_path, *cones_path;
    uint32_t nv, nf, map_nv, map_nf;
    int64_t genus;
    sq_map_report map;
    sq_extract_stats st;
    sq_untangle_stats un;
    sq_quad_shapes shapes;
    int shapes_checked;
    double t_untangle;
    uint32_t hist[MAX_VALENCE_HIST]; /* quad mesh valences */
    double t_read, t_map, t_write, t_total;
    int done;
} report;

static void print_hist(const uint32_t *hist, int json)
{
    int first = 1;
    for (uint32_t k = 0; k < MAX_VALENCE_HIST; k++) {
        if (!hist[k]) continue;
        const char *ge = k == MAX_VALENCE_HIST - 1 ? ">=" : "";
        if (json) printf("%s\"%s%u\": %u", first ? "" : ", ", ge, k, hist[k]);
        else printf(" %s%u:%u", ge, k, hist[k]);
        first = 0;
    }
}

static void print_text(const report *r)
{
    const sq_extract_stats *s = &r->st;
    printf("mesh          %s: %u vertices, %u faces, genus %lld\n", r->mesh_path, r->nv, r->nf,
           (long long)r->genus);
    printf("map           %s: %u vertices, %u faces, %u seam edges, %u cones\n", r->map_path,
           r->map_nv, r->map_nf, r->map.seam_edges, r->map.cones);
    printf("grid points   %u: %u at mesh vertices, %u inside edges, %u inside faces\n",
           s->vertex_points + s->edge_points + s->face_points, s->vertex_points, s->edge_points,
           s->face_points);
    printf("quads         %u quads, %u edges, %u irregular vertices (valence:count", s->quads,
           s->edges, s->irregular);
    print_hist(r->hist, 0);
    printf(")\n");
    printf("traced        %llu faces, edges and vertices crossed (longest edge: %u)\n",
           (unsigned long long)s->trace_steps, s->max_trace_steps);
    printf("untangled     %u folded or turned quads before, %u after (%u moves in %u rounds, %.3f s)\n",
           r->un.folded_before, r->un.folded_after, r->un.moves, r->un.rounds, r->t_untangle);
    printf("verified      closed, manifold, oriented, Euler characteristic of the mesh; the\n"
           "              irregular vertices are the cones; quads = UV area\n");
    printf("time          read %.3f s, map %.3f s, extract %.3f s (check %.3f, points %.3f, "
           "trace %.3f, quads %.3f, positions %.3f), write %.3f s; total %.3f s\n",
           r->t_read, r->t_map, s->t_total, s->t_check, s->t_points, s->t_trace, s->t_quads,
           s->t_positions, r->t_write, r->t_total);
    printf("wrote         %s\n", r->out_path);
}

static void print_json(const report *r, sq_status st, const char *stage, const char *msg)
{
    const sq_extract_stats *s = &r->st;
    sq_json_open_map_report(st, r->mesh_path, r->map_path, r->out_path);
    if (r->cones_path) {
        printf(",\n  \"cones_file\": ");
        sq_json_string(stdout, r->cones_path);
    }
    if (r->nv) printf(",\n  \"mesh_vertices\": %u, \"mesh_faces\": %u, \"genus\": %lld", r->nv, r->nf, (long long)r->genus);
    if (r->map_nv)
        printf(",\n  \"map_vertices\": %u, \"map_faces\": %u, \"seam_edges\": %u, \"cones\": %u",
               r->map_nv, r->map_nf, r->map.seam_edges, r->map.cones);
    if (r->done) {
        printf(",\n  \"grid_points\": {\"vertex\": %u, \"edge\": %u, \"face\": %u, \"total\": %u}",
               s->vertex_points, s->edge_points, s->face_points,
               s->vertex_points + s->edge_points + s->face_points);
        printf(",\n  \"quads\": %u, \"edges\": %u, \"irregular\": %u, \"valences\": {", s->quads,
               s->edges, s->irregular);
        print_hist(r->hist, 1);
        printf("},\n  \"trace_steps\": %llu, \"max_trace_steps\": %u", (unsigned long long)s->trace_steps,
               s->max_trace_steps);
        printf(",\n  \"folded_before\": %u, \"folded_after\": %u, \"untangle_moves\": %u, "
               "\"untangle_rounds\": %u, \"untangle_s\": %.6f",
               r->un.folded_before, r->un.folded_after, r->un.moves, r->un.rounds, r->t_untangle);
    }
    if (r->shapes_checked)
        printf(",\n  \"degenerate\": {\"short_edge\": %u, \"tiny\": %u, \"folded\": %u, \"turned\": %u}",
               r->shapes.short_edge, r->shapes.tiny, r->shapes.folded, r->shapes.turned);
    printf(",\n  \"time_s\": {\"read\": %.6f, \"map\": %.6f, \"check\": %.6f, \"points\": %.6f, "
           "\"trace\": %.6f, \"quads\": %.6f, \"positions\": %.6f, \"extract\": %.6f, "
           "\"write\": %.6f, \"total\": %.6f}",
           r->t_read, r->t_map, s->t_check, s->t_points, s->t_trace, s->t_quads, s->t_positions,
           s->t_total, r->t_write, r->t_total);
    if (st != SQ_OK) {
        printf(",\n  ");
        sq_json_error(st, stage, msg);
    }
    printf("\n}\n");
}

int sq_cmd_extract(int argc, char **argv)
{
    report r;
    memset(&r, 0, sizeof r);
    int json = 0, quiet = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            help(stdout);
            return SQ_EXIT_OK;
        } else if (!strcmp(a, "--json")) {
            json = 1;
        } else if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
            quiet = 1;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output") || !strcmp(a, "--cones")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "seamquad extract: %s needs a file\n", a);
                return SQ_EXIT_USAGE;
            }
            if (!strcmp(a, "--cones")) r.cones_path = argv[++i];
            else r.out_path = argv[++i];
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "seamquad extract: unknown option '%s' (see seamquad extract --help)\n", a);
            return SQ_EXIT_USAGE;
        } else if (!r.mesh_path) {
            r.mesh_path = a;
        } else if (!r.map_path) {
            r.map_path = a;
        } else {
            fprintf(stderr, "seamquad extract: unexpected argument '%s' (MESH and IGM.obj only)\n", a);
            return SQ_EXIT_USAGE;
        }
    }
    if (!r.mesh_path || !r.map_path || !r.out_path) {
        fprintf(stderr, "seamquad extract: give MESH, IGM.obj and -o QUADS.obj (see seamquad "
                        "extract --help)\n");
        return SQ_EXIT_USAGE;
    }
    if (sq_format_from_path(r.out_path) != SQ_FORMAT_OBJ) {
        fprintf(stderr, "seamquad extract: the output '%s' must be an .obj file\n", r.out_path);
        return SQ_EXIT_USAGE;
    }
    if (!strcmp(r.out_path, r.mesh_path) || !strcmp(r.out_path, r.map_path) ||
        (r.cones_path && !strcmp(r.out_path, r.cones_path))) {
        fprintf(stderr, "seamquad extract: the output '%s' would overwrite an input\n", r.out_path);
        return SQ_EXIT_USAGE;
    }

    sq_error err;
    sq_error_clear(&err);
    sq_soup soup;
    memset(&soup, 0, sizeof soup);
    sq_mesh mesh;
    memset(&mesh, 0, sizeof mesh);
    sq_map M;
    memset(&M, 0, sizeof M);
    sq_quad_mesh Q;
    memset(&Q, 0, sizeof Q);
    int32_t *valence = NULL;
    const char *stage = "read";
    double t0 = sq_now();
    sq_status st = sq_read_mesh(r.mesh_path, &soup, &err);
    if (!st) st = sq_mesh_from_soup(&soup, 0, &mesh, &err);
    if (!st) {
        r.nv = mesh.nv, r.nf = mesh.nf, r.genus = sq_mesh_genus(&mesh);
        double t1 = sq_now();
        if (r.cones_path) {
            stage = "cones";
            valence = malloc((size_t)mesh.nv * sizeof *valence);
            if (!valence) st = sq_error_set(&err, SQ_ERR_NOMEM, "out of memory");
            else st = sq_cli_read_cones(r.cones_path, &mesh, valence, &err);
            t1 = sq_now();
        }
        r.t_read = t1 - t0;
    }
    if (!st) {
        double t1 = sq_now();
        stage = "map";
        /* slivers whose 3D corners are collinear are accepted in the map
         * (quantization's refinement makes them); its UV triangles are not */
        st = sq_map_read(r.map_path, &mesh, valence, 1e-9,
                         SQ_MAP_REQUIRE_EXACT | SQ_MAP_REQUIRE_INTEGER | SQ_MAP_ALLOW_FLAT_3D, &M,
                         &r.map, &err);
        r.t_map = sq_now() - t1;
        if (st) sq_cli_name_file(&err, r.map_path);
    }
    if (!st) {
        r.map_nv = M.mesh.nv, r.map_nf = M.mesh.nf;
        stage = "extract";
        st = sq_extract(&M, &Q, &r.st, &err);
        if (st) sq_cli_name_file(&err, r.map_path);
    }
    if (!st) {
        stage = "untangle";
        double t1 = sq_now();
        st = sq_extract_untangle(&M, &Q, &r.un, &err);
        r.t_untangle = sq_now() - t1;
    }
    if (!st) { /* no quad the referee would reject: nothing written */
        stage = "shapes";
        st = sq_quad_mesh_check_shapes(&Q, &M.mesh, Q.loc_face, Q.loc_bary, sq_bbox_diagonal(M.mesh.nv, M.mesh.pos), &r.shapes,
                                       &err);
        r.shapes_checked = 1;
    }
    if (!st) {
        r.done = 1;
        for (uint32_t p = 0; p < Q.nv; p++) {
            int32_t k = Q.valence[p];
            r.hist[k < 0 ? 0 : k >= MAX_VALENCE_HIST ? MAX_VALENCE_HIST - 1 : k]++;
        }
        stage = "write";
        double t1 = sq_now();
        st = sq_quad_mesh_write_obj(r.out_path, &Q, &err);
        r.t_write = sq_now() - t1;
    }
    r.t_total = sq_now() - t0;
    if (json) print_json(&r, st, stage, err.msg);
    else if (!st && !quiet) print_text(&r);
    if (st) fprintf(stderr, "seamquad extract: error (%s): %s\n", stage, err.msg);
    free(valence);
    sq_quad_mesh_free(&Q);
    sq_map_free(&M);
    sq_mesh_free(&mesh);
    sq_soup_free(&soup);
    /* a map that is not an integer-grid map of MESH is refused by the
     * library as a bad argument: for the command line it is bad input */
    if (st == SQ_ERR_ARGUMENT) return SQ_EXIT_INVALID_INPUT;
    return sq_exit_code(st);
}
