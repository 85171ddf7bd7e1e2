// Closed surfaces of the scene shapes (box, circle / sphere, polygon, extruded step), each
// with a rigid velocity. Orientation: outward normals (see surface.h).
#pragma once

#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

#include "fluid_solver/embedded/surface.h"

namespace cosim::fluid::embedded {

using Point2 = std::array<double, 2>;

// Rotates the vertices by `deg` degrees about the z axis through `pivot`; velocities stay lab-frame.
inline void rotate_z(Surface& s, const Vec3& pivot, double deg) {
  if (deg == 0) return;
  const double a = deg * std::numbers::pi / 180, c = std::cos(a), sn = std::sin(a);
  for (std::size_t i = 0; i < s.vertices.size(); ++i) {
    const Vec3 r = s.vertices[i] - pivot;
    s.vertices[i] = pivot + Vec3{c * r[0] - sn * r[1], sn * r[0] + c * r[1], r[2]};
    // velocities stay as given: a scene's body velocity is in the lab frame
  }
}

inline double signed_area(const std::vector<Point2>& p) {
  double a = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const auto& u = p[k];
    const auto& v = p[(k + 1) % p.size()];
    a += 0.5 * (u[0] * v[1] - v[0] * u[1]);
  }
  return a;
}

// 1D: the interval [a, b] as two oriented points.
inline Surface make_interval(double a, double b, double velocity = 0) {
  if (!(b > a)) throw std::runtime_error("embedded shape: interval needs a < b");
  Surface s;
  s.dim = 1;
  add_vertex(s, {a, 0, 0}, {velocity, 0, 0});
  add_vertex(s, {b, 0, 0}, {velocity, 0, 0});
  s.faces = {{0, -1, -1}, {1, 1, -1}};
  return s;
}

// 2D polygon from its vertices (either orientation; stored counter-clockwise), rotated by
// rotation_deg about its vertex mean.
inline Surface make_polygon(std::vector<Point2> v, const Vec3& velocity = {0, 0, 0}, double rotation_deg = 0) {
  if (v.size() < 3) throw std::runtime_error("embedded shape: a polygon needs at least 3 vertices");
  if (signed_area(v) < 0) std::reverse(v.begin(), v.end());
  Surface s;
  s.dim = 2;
  Vec3 mean{0, 0, 0};
  for (const auto& p : v) {
    add_vertex(s, {p[0], p[1], 0}, velocity);
    mean = mean + (1.0 / static_cast<double>(v.size())) * Vec3{p[0], p[1], 0};
  }
  const int n = static_cast<int>(v.size());
  for (int k = 0; k < n; ++k) s.faces.push_back({k, (k + 1) % n, -1});
  rotate_z(s, mean, rotation_deg);
  return s;
}

// 2D circle as a regular polygon with `segments` edges, vertices at angles phase + 2 pi k / segments.
inline Surface make_circle(const Vec3& center, double radius, int segments, const Vec3& velocity = {0, 0, 0},
                           double phase = 0) {
  if (segments < 3 || !(radius > 0))
    throw std::runtime_error("embedded shape: circle needs radius > 0 and >= 3 segments");
  std::vector<Point2> v;
  for (int k = 0; k < segments; ++k) {
    const double a = phase + 2 * std::numbers::pi * k / segments;
    v.push_back({center[0] + radius * std::cos(a), center[1] + radius * std::sin(a)});
  }
  return make_polygon(v, velocity);
}

namespace detail {
// Ear clipping of a simple counter-clockwise polygon (O(n^3), for small profiles): triangles (CCW).
inline std::vector<std::array<int, 3>> triangulate(const std::vector<Point2>& p) {
  std::vector<int> idx(p.size());
  for (std::size_t k = 0; k < p.size(); ++k) idx[k] = static_cast<int>(k);
  auto cross2 = [&](int a, int b, int c) {
    const auto& A = p[static_cast<std::size_t>(a)];
    const auto& B = p[static_cast<std::size_t>(b)];
    const auto& Cc = p[static_cast<std::size_t>(c)];
    return (B[0] - A[0]) * (Cc[1] - A[1]) - (B[1] - A[1]) * (Cc[0] - A[0]);
  };
  std::vector<std::array<int, 3>> tris;
  while (idx.size() > 3) {
    bool found = false;
    const std::size_t m = idx.size();
    for (std::size_t k = 0; k < m && !found; ++k) {
      const int a = idx[(k + m - 1) % m], b = idx[k], c = idx[(k + 1) % m];
      if (cross2(a, b, c) <= 0) continue;  // reflex or flat
      bool empty = true;
      for (int q : idx)
        if (q != a && q != b && q != c && cross2(a, b, q) >= 0 && cross2(b, c, q) >= 0 && cross2(c, a, q) >= 0)
          empty = false;
      if (!empty) continue;
      tris.push_back({a, b, c});
      idx.erase(idx.begin() + static_cast<std::ptrdiff_t>(k));
      found = true;
    }
    if (!found) throw std::runtime_error("embedded shape: the profile polygon is not simple");
  }
  tris.push_back({idx[0], idx[1], idx[2]});
  return tris;
}
}  // namespace detail

// 3D prism: a simple 2D profile (x, y) extruded over z in [z0, z1].
inline Surface make_extrusion(std::vector<Point2> profile, double z0, double z1, const Vec3& velocity = {0, 0, 0}) {
  if (profile.size() < 3 || !(z1 > z0))
    throw std::runtime_error("embedded shape: extrusion needs >= 3 profile points and z1 > z0");
  if (signed_area(profile) < 0) std::reverse(profile.begin(), profile.end());
  Surface s;
  s.dim = 3;
  const int n = static_cast<int>(profile.size());
  for (const auto& p : profile) add_vertex(s, {p[0], p[1], z0}, velocity);
  for (const auto& p : profile) add_vertex(s, {p[0], p[1], z1}, velocity);
  for (int k = 0; k < n; ++k)
    add_quad(s, k, (k + 1) % n, n + (k + 1) % n, n + k);  // sides, normal to the right of the edge
  for (const auto& t : detail::triangulate(profile)) {
    s.faces.push_back({n + t[0], n + t[1], n + t[2]});  // top cap, +z
    s.faces.push_back({t[0], t[2], t[1]});              // bottom cap, -z
  }
  return s;
}

// Box [lo, hi] (2D rectangle or 3D box), rotated by rotation_deg about z through its centre.
inline Surface make_box(int dim, const Vec3& lo, const Vec3& hi, const Vec3& velocity = {0, 0, 0},
                        double rotation_deg = 0) {
  const std::vector<Point2> rect{{lo[0], lo[1]}, {hi[0], lo[1]}, {hi[0], hi[1]}, {lo[0], hi[1]}};
  Surface s;
  if (dim == 1) return make_interval(lo[0], hi[0], velocity[0]);
  if (dim == 2) s = make_polygon(rect, velocity);
  else if (dim == 3) s = make_extrusion(rect, lo[2], hi[2], velocity);
  else throw std::runtime_error("embedded shape: dim must be 1, 2 or 3");
  rotate_z(s, 0.5 * (lo + hi), rotation_deg);
  return s;
}

// The boundary of a structured solid mesh of the box [lo, hi] with n[d] cells along d, as a solid solver sends it
// (many coplanar faces): 2D segments, counter-clockwise; 3D quads (two triangles each), counter-clockwise seen
// from outside. Rotated by rotation_deg about z through the box centre.
inline Surface make_subdivided_box(int dim, const Vec3& lo, const Vec3& hi, const std::array<int, 3>& n,
                                   double rotation_deg = 0) {
  if (dim < 2 || dim > 3 || n[0] < 1 || n[1] < 1 || (dim == 3 && n[2] < 1))
    throw std::runtime_error("embedded shape: subdivided box needs dim 2 or 3 and at least one cell per direction");
  Surface s;
  s.dim = dim;
  std::map<std::array<int, 3>, int> id;
  auto vertex = [&](int i, int j, int k) {
    const auto [it, fresh] = id.try_emplace({i, j, k}, static_cast<int>(s.vertices.size()));
    if (fresh) {
      Vec3 x{0, 0, 0};
      const int ijk[3] = {i, j, k};
      for (std::size_t d = 0; d < static_cast<std::size_t>(dim); ++d) x[d] = lo[d] + (hi[d] - lo[d]) * ijk[d] / n[d];
      add_vertex(s, x);
    }
    return it->second;
  };
  if (dim == 2) {  // counter-clockwise
    for (int i = 0; i < n[0]; ++i) s.faces.push_back({vertex(i, 0, 0), vertex(i + 1, 0, 0), -1});
    for (int j = 0; j < n[1]; ++j) s.faces.push_back({vertex(n[0], j, 0), vertex(n[0], j + 1, 0), -1});
    for (int i = n[0]; i > 0; --i) s.faces.push_back({vertex(i, n[1], 0), vertex(i - 1, n[1], 0), -1});
    for (int j = n[1]; j > 0; --j) s.faces.push_back({vertex(0, j, 0), vertex(0, j - 1, 0), -1});
  } else {  // quads counter-clockwise seen from outside
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k) {
        add_quad(s, vertex(n[0], j, k), vertex(n[0], j + 1, k), vertex(n[0], j + 1, k + 1), vertex(n[0], j, k + 1));
        add_quad(s, vertex(0, j, k), vertex(0, j, k + 1), vertex(0, j + 1, k + 1), vertex(0, j + 1, k));
      }
    for (int i = 0; i < n[0]; ++i)
      for (int k = 0; k < n[2]; ++k) {
        add_quad(s, vertex(i, n[1], k), vertex(i, n[1], k + 1), vertex(i + 1, n[1], k + 1), vertex(i + 1, n[1], k));
        add_quad(s, vertex(i, 0, k), vertex(i + 1, 0, k), vertex(i + 1, 0, k + 1), vertex(i, 0, k + 1));
      }
    for (int i = 0; i < n[0]; ++i)
      for (int j = 0; j < n[1]; ++j) {
        add_quad(s, vertex(i, j, n[2]), vertex(i + 1, j, n[2]), vertex(i + 1, j + 1, n[2]), vertex(i, j + 1, n[2]));
        add_quad(s, vertex(i, j, 0), vertex(i, j + 1, 0), vertex(i + 1, j + 1, 0), vertex(i + 1, j, 0));
      }
  }
  rotate_z(s, 0.5 * (lo + hi), rotation_deg);
  return s;
}

// Forward-facing step (paper 9.1): the block [lo, hi]; in 2D a rectangle, in 3D the rectangle
// profile extruded over [lo_z, hi_z]. Let it reach below the domain floor: the part outside the
// padded grid is clipped away, so the floor under it needs no surface.
inline Surface make_step(int dim, const Vec3& lo, const Vec3& hi, const Vec3& velocity = {0, 0, 0}) {
  return make_box(dim, lo, hi, velocity);
}

// 3D icosphere: the icosahedron subdivided `refinement` times (faces 20 * 4^refinement), vertices
// projected onto the sphere.
inline Surface make_sphere(const Vec3& center, double radius, int refinement, const Vec3& velocity = {0, 0, 0}) {
  if (refinement < 0 || refinement > 8 || !(radius > 0))
    throw std::runtime_error("embedded shape: sphere needs radius > 0 and refinement in [0, 8]");
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> v;  // icosahedron: cyclic permutations of (0, +-1, +-g), edge length 2
  for (int s1 : {-1, 1})
    for (int s2 : {-1, 1}) {
      v.push_back({0, 1.0 * s1, g * s2});
      v.push_back({1.0 * s1, g * s2, 0});
      v.push_back({g * s2, 0, 1.0 * s1});
    }
  std::vector<std::array<int, 3>> f;
  const int nv = static_cast<int>(v.size());
  auto is_edge = [&](int a, int b) {
    return std::abs(norm(v[static_cast<std::size_t>(a)] - v[static_cast<std::size_t>(b)]) - 2.0) < 1e-9;
  };
  for (int a = 0; a < nv; ++a)
    for (int b = a + 1; b < nv; ++b)
      for (int c = b + 1; c < nv; ++c)
        if (is_edge(a, b) && is_edge(b, c) && is_edge(a, c)) {
          const Vec3& A = v[static_cast<std::size_t>(a)];
          const bool outward =
              dot(cross(v[static_cast<std::size_t>(b)] - A, v[static_cast<std::size_t>(c)] - A), A) > 0;
          f.push_back(outward ? std::array<int, 3>{a, b, c} : std::array<int, 3>{a, c, b});
        }
  for (auto& x : v) x = normalized(x);
  for (int r = 0; r < refinement; ++r) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(normalized(v[static_cast<std::size_t>(a)] + v[static_cast<std::size_t>(b)]));
      return mid[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& t : f) {
      const int ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({ab, t[1], bc});
      next.push_back({ca, bc, t[2]});
      next.push_back({ab, bc, ca});
    }
    f.swap(next);
  }
  Surface s;
  s.dim = 3;
  for (const auto& x : v) add_vertex(s, center + radius * x, velocity);
  s.faces = f;
  return s;
}

}  // namespace cosim::fluid::embedded
