// Interface segments (paper section 6, Fig. 2): every face clipped to the background cells it
// crosses, with centre, outward normal, area and the face velocity at the centre. 2D segments are
// clipped parametrically (Liang & Barsky, ACM TOG 3 (1984) 1), 3D triangles as polygons against the
// six planes of the cell box (Sutherland & Hodgman, CACM 17 (1974) 32). Candidate cells come from
// the slab search of lattice.h: O(cut cells) box tests per face.
#pragma once

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "fluid_solver/embedded/domain_wall_faces.h"
#include "fluid_solver/embedded/lattice.h"
#include "fluid_solver/embedded/surface.h"

namespace cosim::fluid::embedded {

struct InterfaceSegment {
  std::size_t cell = 0;                  // padded index of the owning cell (Grid::index)
  std::array<int, 3> ijk{0, 0, 0};       // interior-numbered cell (negative / >= n in the ghost layers)
  int face = -1;                         // source face of the Surface
  Vec3 center{0, 0, 0};                  // centroid of the piece
  Vec3 normal{0, 0, 0};                  // unit, solid -> fluid
  Vec3 velocity{0, 0, 0};                // face velocity interpolated at the centre
  double area = 0;                       // length (2D), area (3D), 1 (1D)
  int first_point = 0, point_count = 0;  // the piece's polygon in EmbeddedGeometry::segment_points
};

namespace detail {

// Sutherland-Hodgman: keeps the part of the convex polygon `in` with sign*(x_d - plane) <= tol. Points within
// tol of the plane count as on it: a face that lies in a cell face up to round-off (a moving body's wall that
// arrives on a grid line) is kept whole by both neighbours, and owns_piece() gives it to one.
inline void clip_against(std::vector<Vec3>& in, std::vector<Vec3>& out, std::size_t d, double plane, double sign,
                         double tol) {
  const std::size_t m = in.size();
  bool cut = false;  // a point beyond the plane: else the polygon stays as it is
  for (std::size_t k = 0; k < m; ++k) cut = cut || sign * (in[k][d] - plane) > tol;
  if (!cut) return;
  out.clear();
  for (std::size_t k = 0; k < m; ++k) {
    const Vec3& p = in[k];
    const Vec3& q = in[(k + 1) % m];
    const double fp = sign * (p[d] - plane), fq = sign * (q[d] - plane);
    if (fp <= tol) out.push_back(p);
    if ((fp < -tol && fq > tol) || (fp > tol && fq < -tol)) {
      Vec3 x = p + (fp / (fp - fq)) * (q - p);
      x[d] = plane;  // exactly on the plane
      out.push_back(x);
    }
  }
  std::swap(in, out);
}

// Barycentric weights of a point x in the plane of triangle (a,b,c).
inline std::array<double, 3> barycentric(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = cross(b - a, c - a);
  const double inv = 1.0 / dot(n, n);
  const double wb = dot(cross(x - a, c - a), n) * inv;
  const double wc = dot(cross(b - a, x - a), n) * inv;
  return {1 - wb - wc, wb, wc};
}

// A piece lying in a face plane of the cell box belongs to the cell on its solid side (the side
// opposite to the normal), so that each piece has exactly one owner and that owner is cut.
inline bool owns_piece(const std::vector<Vec3>& pts, const Vec3& lo, const Vec3& hi, const Vec3& n, int dim,
                       const Vec3& tol) {
  for (std::size_t d = 0; d < static_cast<std::size_t>(dim); ++d) {
    bool on_lo = true, on_hi = true;
    for (const auto& p : pts) {
      on_lo = on_lo && std::abs(p[d] - lo[d]) <= tol[d];
      on_hi = on_hi && std::abs(p[d] - hi[d]) <= tol[d];
    }
    if (on_lo && !(n[d] < 0)) return false;
    if (on_hi && !(n[d] > 0)) return false;
  }
  return true;
}

}  // namespace detail

// The pieces of face f in the cells it crosses (clip_surface), appended to segments and points.
template <int DIM>
void clip_face(const Surface& s, const SurfaceTopology& topo, std::size_t f, const Lattice<DIM>& centres,
               const Lattice<DIM>& nodes, const Vec3& half, const Vec3& tol, double hmin, double min_measure,
               const DomainWallFaces* walls, std::vector<Vec3>& poly, std::vector<Vec3>& scratch,
               std::vector<InterfaceSegment>& segments, std::vector<Vec3>& points, std::size_t& tests) {
  if (walls && walls->skips(f)) return;
  const auto& fc = s.faces[f];
  const Vec3& n = topo.face_normal[f];
  const int nid = DIM == 1 ? 1 : DIM;
  Vec3 lo = s.vertices[static_cast<std::size_t>(fc[0])], hi = lo;
  for (int k = 1; k < nid; ++k)
    for (std::size_t d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], s.vertices[static_cast<std::size_t>(fc[static_cast<std::size_t>(k)])][d]);
      hi[d] = std::max(hi[d], s.vertices[static_cast<std::size_t>(fc[static_cast<std::size_t>(k)])][d]);
    }
  const Vec3& a = s.vertices[static_cast<std::size_t>(fc[0])];
  // A cell box meets the face's plane iff |n.(x_c - a)| <= sum_d |n_d| dx_d / 2.
  double r = 0;
  for (std::size_t d = 0; d < static_cast<std::size_t>(DIM); ++d) r += std::abs(n[d]) * half[d];
  r += 1e-12 * hmin;
  // In 3D only the cells over the triangle's own footprint, not over its whole bounding box (lattice.h).
  std::array<Vec3, 3> tri{};
  if constexpr (DIM == 3)
    for (std::size_t k = 0; k < 3; ++k) tri[k] = s.vertices[static_cast<std::size_t>(fc[k])];
  for_each_in_slab(
      centres, lo, hi, half, n, dot(n, a), r,
      [&](int I, int J, int K) {
        ++tests;
        const Vec3 blo = nodes.point(I, J, K), bhi = nodes.point(I + 1, DIM > 1 ? J + 1 : J, DIM > 2 ? K + 1 : K);
        Vec3 c{0, 0, 0};
        double measure = 0;
        std::array<double, 3> bary{1, 0, 0};
        if constexpr (DIM == 1) {
          if (a[0] < blo[0] - tol[0] || a[0] > bhi[0] + tol[0]) return;
          poly.assign(1, a);
          c = a;
          measure = 1;
        } else if constexpr (DIM == 2) {
          const Vec3& b = s.vertices[static_cast<std::size_t>(fc[1])];
          const Vec3 delta = b - a;
          double t0 = 0, t1 = 1;
          for (std::size_t d = 0; d < 2; ++d) {
            // Along a grid line up to round-off (a moving wall that arrives on it): in both cells, owns_piece()
            // decides; otherwise the piece would fall between them and the cut cell would be lost.
            if (std::abs(delta[d]) <= tol[d]) {
              if (std::max(a[d], b[d]) < blo[d] - tol[d] || std::min(a[d], b[d]) > bhi[d] + tol[d]) return;
              continue;
            }
            double ta = (blo[d] - a[d]) / delta[d], tb = (bhi[d] - a[d]) / delta[d];
            if (ta > tb) std::swap(ta, tb);
            t0 = std::max(t0, ta);
            t1 = std::min(t1, tb);
          }
          if (!(t1 > t0)) return;
          measure = (t1 - t0) * topo.face_measure[f];
          poly = {a + t0 * delta, a + t1 * delta};
          c = 0.5 * (poly[0] + poly[1]);
          const double tm = 0.5 * (t0 + t1);
          bary = {1 - tm, tm, 0};
        } else {
          poly = {a, s.vertices[static_cast<std::size_t>(fc[1])], s.vertices[static_cast<std::size_t>(fc[2])]};
          for (std::size_t d = 0; d < 3 && poly.size() >= 3; ++d) {
            detail::clip_against(poly, scratch, d, blo[d], -1.0, tol[d]);
            if (poly.size() >= 3) detail::clip_against(poly, scratch, d, bhi[d], 1.0, tol[d]);
          }
          if (poly.size() < 3) return;
          // area-weighted centroid of the fan triangles
          Vec3 acc{0, 0, 0};
          for (std::size_t k = 1; k + 1 < poly.size(); ++k) {
            const double ak = 0.5 * dot(cross(poly[k] - poly[0], poly[k + 1] - poly[0]), n);
            measure += ak;
            acc = acc + (ak / 3.0) * (poly[0] + poly[k] + poly[k + 1]);
          }
          if (!(measure > 0)) return;
          c = (1.0 / measure) * acc;
          bary = detail::barycentric(c, a, s.vertices[static_cast<std::size_t>(fc[1])],
                                     s.vertices[static_cast<std::size_t>(fc[2])]);
        }
        if (measure <= min_measure) return;
        if (!detail::owns_piece(poly, blo, bhi, n, DIM, tol)) return;
        InterfaceSegment seg;
        seg.cell = centres.index(I, J, K);
        seg.ijk = {I - Grid<DIM>::offset(0), J - Grid<DIM>::offset(1), K - Grid<DIM>::offset(2)};
        seg.face = static_cast<int>(f);
        seg.center = c;
        seg.normal = n;
        seg.area = measure;
        seg.velocity = face_velocity(s, static_cast<int>(f), bary);
        seg.first_point = static_cast<int>(points.size());
        seg.point_count = static_cast<int>(poly.size());
        points.insert(points.end(), poly.begin(), poly.end());
        segments.push_back(seg);
      },
      DIM == 3 ? &tri : nullptr);
}

// Clips all faces of s to the cells of the padded grid. Pieces outside the padded grid are dropped, and so
// are the faces on the domain wall (`walls`, geometry.h: domain_wall_faces). `tests` counts the clip tests.
template <int DIM>
void clip_surface(const Grid<DIM>& g, const Surface& s, const SurfaceTopology& topo,
                  std::vector<InterfaceSegment>& segments, std::vector<Vec3>& points, std::size_t& tests,
                  const DomainWallFaces* walls = nullptr) {
  segments.clear();
  points.clear();
  const Lattice<DIM> centres = centre_lattice(g), nodes = node_lattice(g);
  double hmin = g.dx[0];
  Vec3 half{0, 0, 0}, tol{0, 0, 0};
  for (std::size_t d = 0; d < static_cast<std::size_t>(DIM); ++d) {
    half[d] = 0.5 * g.dx[d] * (1 + 1e-9);
    tol[d] = 1e-10 * g.dx[d];
    hmin = std::min(hmin, g.dx[d]);
  }
  const double min_measure = DIM == 3 ? 1e-12 * hmin * hmin : 1e-12 * hmin;
  // Threads take contiguous ranges of faces and their pieces are joined in thread order: the same list, in the
  // same order, as one thread gives. The first range goes straight into the output, the others into buffers
  // that keep their capacity from cycle to cycle.
  const std::size_t nfaces = s.faces.size();
  const int nthreads = nfaces < 256 ? 1 : omp_get_max_threads();
  std::vector<std::vector<InterfaceSegment>*> seg_t(static_cast<std::size_t>(nthreads));
  std::vector<std::vector<Vec3>*> pts_t(static_cast<std::size_t>(nthreads));
  std::vector<std::size_t> tests_t(static_cast<std::size_t>(nthreads), 0);
#pragma omp parallel num_threads(nthreads)
  {
    static thread_local std::vector<InterfaceSegment> own_segments;
    static thread_local std::vector<Vec3> own_points;
    const std::size_t t = static_cast<std::size_t>(omp_get_thread_num()), nt = static_cast<std::size_t>(nthreads);
    std::vector<InterfaceSegment>& segs = t == 0 ? segments : own_segments;
    std::vector<Vec3>& pts = t == 0 ? points : own_points;
    segs.clear();
    pts.clear();
    seg_t[t] = &segs;
    pts_t[t] = &pts;
    std::vector<Vec3> poly, scratch;
    for (std::size_t f = nfaces * t / nt; f < nfaces * (t + 1) / nt; ++f)
      clip_face(s, topo, f, centres, nodes, half, tol, hmin, min_measure, walls, poly, scratch, segs, pts, tests_t[t]);
  }
  for (std::size_t t = 0; t < seg_t.size(); ++t) {
    tests += tests_t[t];
    if (t == 0) continue;
    const int offset = static_cast<int>(points.size());
    for (InterfaceSegment seg : *seg_t[t]) {
      seg.first_point += offset;
      segments.push_back(seg);
    }
    points.insert(points.end(), pts_t[t]->begin(), pts_t[t]->end());
  }
  // Sorted by owning cell (then face): the pieces of one cell are contiguous.
  std::stable_sort(segments.begin(), segments.end(),
                   [](const InterfaceSegment& x, const InterfaceSegment& y) { return x.cell < y.cell; });
}

}  // namespace cosim::fluid::embedded
