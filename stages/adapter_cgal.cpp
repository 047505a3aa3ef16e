// seamquad: CGAL adapter (sq_cgal_adapter.h). Thin: the mesh handed over as
// a CGAL Surface_mesh, Polygon Mesh Processing's self_intersections run on
// it, the pairs counted. No algorithm of ours lives here.
#include "sq_cgal_adapter.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <exception>
#include <iterator>
#include <new>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Face = Mesh::Face_index;

// An output iterator that counts the pairs and keeps the first cap of them.
struct pair_counter {
    using iterator_category = std::output_iterator_tag;
    using value_type = void;
    using difference_type = std::ptrdiff_t;
    using pointer = void;
    using reference = void;
    uint64_t *n;
    uint32_t *list;
    uint32_t cap;
    pair_counter &operator*() { return *this; }
    pair_counter &operator++() { return *this; }
    pair_counter operator++(int) { return *this; }
    pair_counter &operator=(const std::pair<Face, Face> &p)
    {
        if (list && *n < cap) list[2 * *n] = uint32_t(p.first), list[2 * *n + 1] = uint32_t(p.second);
        ++*n;
        return *this;
    }
};

} // namespace

extern "C" sq_status sq_cgal_self_intersections(uint32_t nv, const double *pos, uint32_t nt, const uint32_t *tri,
                                                 uint64_t *pairs, uint32_t *list, uint32_t cap, sq_error *err)
{
    *pairs = 0;
    try {
        Mesh m;
        std::vector<Mesh::Vertex_index> v(nv);
        for (uint32_t i = 0; i < nv; i++) v[i] = m.add_vertex(Kernel::Point_3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]));
        for (uint32_t f = 0; f < nt; f++) {
            Face added = m.add_face(v[tri[3 * f]], v[tri[3 * f + 1]], v[tri[3 * f + 2]]);
            if (added == Mesh::null_face())
                return sq_error_set(err, SQ_ERR_ARGUMENT, "self-intersection test: triangle %u does not fit the mesh "
                                    "(not an oriented manifold)", f);
            // faces are numbered in the order they are added
        }
        uint64_t n = 0;
        CGAL::Polygon_mesh_processing::self_intersections(m, pair_counter{&n, list, cap});
        *pairs = n;
        return SQ_OK;
    } catch (const std::bad_alloc &) {
        return sq_error_set(err, SQ_ERR_NOMEM, "out of memory (self-intersection test, %u triangles)", nt);
    } catch (const std::exception &e) {
        return sq_error_set(err, SQ_ERR_INTERNAL, "self-intersection test: CGAL: %s", e.what());
    }
}
