/* seamquad tests: a shared mpz model (mesh, its published map's soup and
 * its cones), loaded by the quantize tests. Header-only, for cmocka tests. */
#ifndef SQ_TEST_MODEL_H
#define SQ_TEST_MODEL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sq_cones.h"
#include "sq_io.h"
#include "sq_mesh.h"

#ifndef SQ_SHARED_DIR
#define SQ_SHARED_DIR "../shared"
#endif

typedef struct model {
    sq_soup soup;      /* the OBJ as read, vt included */
    sq_mesh mesh;
    int32_t *valence;  /* from *_Th_hat */
} model;

/* ../shared/data/mpz/NAME.obj and NAME_Th_hat */
static void load(const char *name, model *md)
{
    char path[512];
    sq_error err;
    memset(md, 0, sizeof *md);
    snprintf(path, sizeof path, "%s/data/mpz/%s.obj", SQ_SHARED_DIR, name);
    if (sq_read_mesh(path, &md->soup, &err)) fail_msg("%s", err.msg);
    if (sq_mesh_from_soup(&md->soup, 0, &md->mesh, &err)) fail_msg("%s", err.msg);
    md->valence = malloc(md->mesh.nv * sizeof *md->valence);
    assert_non_null(md->valence);
    snprintf(path, sizeof path, "%s/data/mpz/%s_Th_hat", SQ_SHARED_DIR, name);
    if (sq_cones_read(path, md->mesh.nv, md->valence, NULL, &err)) fail_msg("%s", err.msg);
}

static void unload(model *md)
{
    sq_soup_free(&md->soup);
    sq_mesh_free(&md->mesh);
    free(md->valence);
}

#endif
