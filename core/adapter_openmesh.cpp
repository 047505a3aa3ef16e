// seamquad: OpenMesh adapter (C++17), behind core/sq_openmesh_adapter.h.
//
// Thin wrapper only: OpenMesh reads the file, this file copies what OpenMesh
// holds into malloc'ed flat arrays. No geometry or combinatorics happens
// here. Every C++ exception is caught before it can reach the C caller.

// OpenMesh's VectorT default constructor leaves its elements uninitialized
// by design; GCC's -Wmaybe-uninitialized flags its property arrays when
// they are instantiated for Vec3d. The warning is about OpenMesh's headers,
// not this file; it is silenced for this translation unit only.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include "sq_openmesh_adapter.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <new>

namespace {

// Polygon mesh with double coordinates: the mesh keeps every bit a reader
// hands it. Texture coordinates are doubles too, for the same reason.
struct SqOmTraits : public OpenMesh::DefaultTraits {
    typedef OpenMesh::Vec3d Point;
    typedef OpenMesh::Vec3d Normal;
    typedef OpenMesh::Vec2d TexCoord2D;
};

typedef OpenMesh::PolyMesh_ArrayKernelT<SqOmTraits> SqOmMesh;

// The adapter must not depend on sq_core (it is linked after it), so it
// fills the public sq_error struct itself.
sq_status om_fail(sq_error *err, sq_status code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

sq_status om_fail(sq_error *err, sq_status code, const char *fmt, ...)
{
    if (err) {
        err->code = code;
        va_list ap;
        va_start(ap, fmt);
        std::vsnprintf(err->msg, sizeof err->msg, fmt, ap);
        va_end(ap);
    }
    return code;
}

template <typename T>
T *om_alloc(size_t n)
{
    // calloc so that the C side frees with free(); at least one element so
    // that a successful allocation is never NULL.
    return static_cast<T *>(std::calloc(n ? n : 1, sizeof(T)));
}

sq_status om_copy(const SqOmMesh &mesh, bool with_uv, const char *path,
                  sq_om_mesh *out, sq_error *err)
{
    const size_t nv = mesh.n_vertices();
    const size_t nf = mesh.n_faces();
    const size_t nh = mesh.n_halfedges();
    const size_t lim = std::numeric_limits<uint32_t>::max() - 1;
    if (nv > lim || nf > lim || nh > lim)
        return om_fail(err, SQ_ERR_ARGUMENT, "%s: OpenMesh read more elements than 32-bit indices hold", path);

    // Corners: each face halfedge is one corner, so nh bounds their count.
    out->pos = om_alloc<double>(3 * nv);
    out->vert_fixed = om_alloc<uint8_t>(nv);
    out->face_off = om_alloc<uint32_t>(nf + 1);
    out->face_idx = om_alloc<uint32_t>(nh);
    out->face_fixed = om_alloc<uint8_t>(nf);
    if (with_uv) out->corner_uv = om_alloc<double>(2 * nh);
    if (!out->pos || !out->vert_fixed || !out->face_off || !out->face_idx || !out->face_fixed ||
        (with_uv && !out->corner_uv))
        return om_fail(err, SQ_ERR_NOMEM, "%s: out of memory copying OpenMesh's mesh", path);

    for (SqOmMesh::VertexHandle vh : mesh.vertices()) {
        const size_t v = static_cast<size_t>(vh.idx());
        const SqOmMesh::Point &p = mesh.point(vh);
        out->pos[3 * v + 0] = p[0];
        out->pos[3 * v + 1] = p[1];
        out->pos[3 * v + 2] = p[2];
        if (mesh.status(vh).fixed_nonmanifold()) {
            out->vert_fixed[v] = 1;
            out->n_vert_fixed++;
        }
    }

    // A corner is the target vertex of a face halfedge: that is where
    // OpenMesh's importer stores the corner's texture coordinate, and the
    // order in which its face-vertex circulator lists the corners.
    uint32_t c = 0;
    for (SqOmMesh::FaceHandle fh : mesh.faces()) {
        const size_t f = static_cast<size_t>(fh.idx());
        out->face_off[f] = c;
        for (SqOmMesh::HalfedgeHandle hh : mesh.fh_range(fh)) {
            if (c >= nh)
                return om_fail(err, SQ_ERR_INTERNAL, "%s: OpenMesh's faces have more corners than halfedges", path);
            out->face_idx[c] = static_cast<uint32_t>(mesh.to_vertex_handle(hh).idx());
            if (with_uv) {
                const SqOmMesh::TexCoord2D &t = mesh.texcoord2D(hh);
                out->corner_uv[2 * c + 0] = t[0];
                out->corner_uv[2 * c + 1] = t[1];
            }
            c++;
        }
        if (mesh.status(fh).fixed_nonmanifold()) {
            out->face_fixed[f] = 1;
            out->n_face_fixed++;
        }
    }
    out->face_off[nf] = c;
    out->nv = static_cast<uint32_t>(nv);
    out->nf = static_cast<uint32_t>(nf);
    return SQ_OK;
}

sq_status om_read(const char *path, unsigned flags, sq_om_mesh *out, sq_error *err)
{
    SqOmMesh mesh;
    // With status attributes present, OpenMesh's importer records the
    // vertices and faces it had to duplicate ("fixed non-manifold").
    mesh.request_vertex_status();
    mesh.request_face_status();
    mesh.request_edge_status();

    OpenMesh::IO::Options opt;
    const bool with_uv = (flags & SQ_OM_READ_TEXCOORDS) != 0;
    if (with_uv) {
        mesh.request_vertex_texcoords2D();
        mesh.request_halfedge_texcoords2D();
        opt += OpenMesh::IO::Options::VertexTexCoord;
        opt += OpenMesh::IO::Options::FaceTexCoord;
    }

    if (!OpenMesh::IO::read_mesh(mesh, std::string(path), opt))
        return om_fail(err, SQ_ERR_IO, "%s: OpenMesh::IO::read_mesh failed (see OpenMesh's messages on stderr)", path);

    // Only report UVs when the reader says the file had them.
    const bool got_uv = with_uv && opt.face_has_texcoord();
    return om_copy(mesh, got_uv, path, out, err);
}

} // namespace

extern "C" void sq_om_mesh_free(sq_om_mesh *m)
{
    if (!m) return;
    std::free(m->pos);
    std::free(m->face_off);
    std::free(m->face_idx);
    std::free(m->vert_fixed);
    std::free(m->face_fixed);
    std::free(m->corner_uv);
    std::memset(m, 0, sizeof *m);
}

extern "C" sq_status sq_openmesh_read(const char *path, unsigned flags, sq_om_mesh *out, sq_error *err)
{
    if (err) {
        err->code = SQ_OK;
        err->msg[0] = '\0';
    }
    if (!out) return om_fail(err, SQ_ERR_ARGUMENT, "sq_openmesh_read: out is NULL");
    std::memset(out, 0, sizeof *out);
    if (!path) return om_fail(err, SQ_ERR_ARGUMENT, "sq_openmesh_read: path is NULL");

    sq_status st;
    try {
        st = om_read(path, flags, out, err);
    } catch (const std::bad_alloc &) {
        st = om_fail(err, SQ_ERR_NOMEM, "%s: out of memory in OpenMesh", path);
    } catch (const std::exception &e) {
        st = om_fail(err, SQ_ERR_INTERNAL, "%s: OpenMesh threw: %s", path, e.what());
    } catch (...) {
        st = om_fail(err, SQ_ERR_INTERNAL, "%s: OpenMesh threw an unknown exception", path);
    }
    if (st != SQ_OK) sq_om_mesh_free(out);
    return st;
}
