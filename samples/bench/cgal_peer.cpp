#include "cgal_peer.h"

#ifdef TETPROBE_BENCH_CGAL

#include "bench_timing.h"
#include "core/half.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <utility>
#include <vector>

namespace bench {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<uint32_t, Kernel>;
using Tds = CGAL::Triangulation_data_structure_3<VertexBase, CGAL::Delaunay_triangulation_cell_base_3<Kernel>>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;
using Point = Kernel::Point_3;
using Cell = Delaunay::Cell_handle;

double det3(const Point& a, const Point& b, const Point& c, const Point& d) {
    const double ax = a.x() - d.x(), ay = a.y() - d.y(), az = a.z() - d.z();
    const double bx = b.x() - d.x(), by = b.y() - d.y(), bz = b.z() - d.z();
    const double cx = c.x() - d.x(), cy = c.y() - d.y(), cz = c.z() - d.z();
    return ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx);
}

}  // namespace

struct CgalPeer::Impl {
    Delaunay triangulation;
    const uint16_t* sh = nullptr;
    size_t sh_stride = 0;

    // Locate with hint, weights in double (ratios of signed volumes). False in an infinite cell.
    bool locate(const float* position, Cell* hint, float w[4]) const {
        const Point p(position[0], position[1], position[2]);
        const Cell c = triangulation.locate(p, *hint);
        *hint = c;
        if (triangulation.is_infinite(c)) return false;
        const Point& a = c->vertex(0)->point();
        const Point& b = c->vertex(1)->point();
        const Point& d = c->vertex(2)->point();
        const Point& e = c->vertex(3)->point();
        const double volume = det3(a, b, d, e);
        w[0] = float(det3(p, b, d, e) / volume);
        w[1] = float(det3(a, p, d, e) / volume);
        w[2] = float(det3(a, b, p, e) / volume);
        w[3] = float(det3(a, b, d, p) / volume);
        return true;
    }

    // Locate, weights, blend. False in an infinite cell.
    bool query(const float* position, Cell* hint, float out[27]) const {
        float w[4];
        if (!locate(position, hint, w)) return false;
        const Cell c = *hint;
        const uint16_t* s[4] = {sh + sh_stride * c->vertex(0)->info(), sh + sh_stride * c->vertex(1)->info(),
                                sh + sh_stride * c->vertex(2)->info(), sh + sh_stride * c->vertex(3)->info()};
        tetprobe::blend_sh_halves(s, w, out);
        return true;
    }
};

bool cgal_peer_available() { return true; }

CgalPeer::CgalPeer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CgalPeer::~CgalPeer() = default;

std::unique_ptr<CgalPeer> CgalPeer::build(const float* positions, const uint32_t* probe_of, size_t count,
                                          const uint16_t* sh, size_t sh_stride) {
    std::vector<std::pair<Point, uint32_t>> points;
    points.reserve(count);
    for (size_t i = 0; i < count; ++i)
        points.emplace_back(Point(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]), probe_of[i]);
    auto impl = std::make_unique<Impl>();
    impl->triangulation.insert(points.begin(), points.end());
    impl->sh = sh;
    impl->sh_stride = sh_stride;
    return std::unique_ptr<CgalPeer>(new CgalPeer(std::move(impl)));
}

double CgalPeer::run(const ObjectPaths& paths, float* sink, size_t* outside) const {
    std::vector<Cell> start(paths.objects);
    float out[27];
    for (size_t o = 0; o < paths.objects; ++o) impl_->query(paths.at(o, 0), &start[o], out);
    size_t infinite = 0;
    float acc = 0;
    const Clock::time_point t0 = Clock::now();
    for (size_t o = 0; o < paths.objects; ++o) {
        Cell hint = start[o];
        for (size_t f = 1; f < paths.frames; ++f) {
            infinite += impl_->query(paths.at(o, f), &hint, out) ? 0 : 1;
            acc += out[0];
        }
    }
    const double seconds = seconds_since(t0);
    *sink += acc;
    if (outside) *outside = infinite;
    return seconds;
}

double CgalPeer::locate_paths(const ObjectPaths& paths, float* sink) const {
    std::vector<Cell> start(paths.objects);
    float w[4], acc = 0;
    for (size_t o = 0; o < paths.objects; ++o) impl_->locate(paths.at(o, 0), &start[o], w);
    const Clock::time_point t0 = Clock::now();
    for (size_t o = 0; o < paths.objects; ++o) {
        Cell hint = start[o];
        for (size_t f = 1; f < paths.frames; ++f) {
            impl_->locate(paths.at(o, f), &hint, w);
            acc += w[0];
        }
    }
    const double seconds = seconds_since(t0);
    *sink += acc;
    return seconds;
}

double CgalPeer::locate_points(const float* points, size_t count, bool carry_hint, float* sink) const {
    float w[4], acc = 0;
    Cell hint;
    const Clock::time_point t0 = Clock::now();
    for (size_t i = 0; i < count; ++i) {
        if (!carry_hint) hint = Cell();
        impl_->locate(points + 3 * i, &hint, w);
        acc += w[0];
    }
    const double seconds = seconds_since(t0);
    *sink += acc;
    return seconds;
}

}  // namespace bench

#else  // without CGAL: the peer is skipped

namespace bench {

struct CgalPeer::Impl {};

bool cgal_peer_available() { return false; }

CgalPeer::CgalPeer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CgalPeer::~CgalPeer() = default;

std::unique_ptr<CgalPeer> CgalPeer::build(const float*, const uint32_t*, size_t, const uint16_t*, size_t) {
    return nullptr;
}

double CgalPeer::run(const ObjectPaths&, float*, size_t*) const { return 0.0; }
double CgalPeer::locate_paths(const ObjectPaths&, float*) const { return 0.0; }
double CgalPeer::locate_points(const float*, size_t, bool, float*) const { return 0.0; }

}  // namespace bench

#endif
