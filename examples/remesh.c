/* A quad mesh from a closed triangle mesh through libseamquad's public API:
 * what `seamquad remesh MESH -o QUADS.obj --quads N` does, in 70 lines.
 *
 *   remesh MESH QUADS.obj [N]
 *
 * Reads MESH (OBJ, OFF or PLY), takes its cones from a smooth cross field,
 * asks for about N quads (default 1000), writes the quads as OBJ and prints
 * one line per stage. Built against an installed seamquad, by CMake
 * (examples/CMakeLists.txt: find_package(seamquad)) or by hand:
 *
 *   cc remesh.c $(pkg-config --cflags --libs seamquad) -o remesh
 *
 * Memory: every array the library returns belongs to a struct with its own
 * _free function; nothing is global, nothing is printed by the library. */
#include <stdio.h>
#include <stdlib.h>

#include <seamquad/sq_io.h>
#include <seamquad/sq_mesh.h>
#include <seamquad/sq_remesh.h>
#include <seamquad/sq_version.h>

/* The library calls this as it goes: the stage and the fraction done. */
static void progress(void *user, const char *stage, double fraction)
{
    (void)user;
    fprintf(stderr, "  [%3.0f%%] %s\n", 100 * fraction, stage);
}

int main(int argc, char **argv)
{
    if (argc < 3 || argc > 4) {
        fprintf(stderr, "usage: %s MESH QUADS.obj [N]\n", argv[0]);
        return 2;
    }
    sq_error err = {0};
    sq_soup soup = {0};
    sq_mesh mesh = {0};
    sq_remesh_result result = {0};
    sq_remesh_stats stats = {0};
    sq_remesh_options opt = {0}; /* zeros are the defaults */
    opt.quads = argc == 4 ? atof(argv[3]) : 1000;
    opt.progress = progress;

    printf("libseamquad %s\n", sq_version());
    /* The reader keeps file and line of every element, so that the mesh
     * check can say where a problem is. */
    sq_status st = sq_read_mesh(argv[1], &soup, &err);
    if (!st) st = sq_mesh_from_soup(&soup, 0, &mesh, &err);
    /* valence NULL: cones from the cross field. */
    if (!st) st = sq_remesh(&mesh, NULL, &opt, &result, &stats, &err);
    if (!st) st = sq_quad_mesh_write_obj(argv[2], &result.quads, &err);
    if (st) {
        /* On failure stats.stage names the stage that failed. */
        fprintf(stderr, "remesh: %s%s%s\n", stats.stage ? stats.stage : "",
                stats.stage ? ": " : "", err.msg);
    } else {
        printf("%u faces in, %u cones, %u quads out (%u vertices), %.2f s\n", mesh.nf,
               stats.cones, result.quads.nq, result.quads.nv, stats.t_total);
    }
    sq_remesh_result_free(&result);
    sq_mesh_free(&mesh);
    sq_soup_free(&soup);
    return st ? 1 : 0;
}
