// The closed boundary of the embedded bodies (paper section 6: "the exterior boundary of the
// foreground mesh"): vertices with velocities and oriented faces, plus the per-cycle topology
// (face normals and the angle-weighted pseudo-normals used to sign the distance).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "fluid_solver/embedded/vec.h"

namespace cosim::fluid::embedded {

// faces[f] by dimension (outward = from the solid into the fluid):
//   dim 3: triangle (v0, v1, v2), counter-clockwise seen from the fluid (normal (v1-v0)x(v2-v0));
//   dim 2: segment (v0, v1, -1), the body on its left (a counter-clockwise polygon; normal (t_y, -t_x));
//   dim 1: point (v, s, -1) with outward normal s * e_x, s = +1 or -1.
// Components beyond `dim` of the vertices must be 0. Several bodies may share one Surface.
struct Surface {
  int dim = 2;
  std::vector<Vec3> vertices;
  std::vector<Vec3> velocities;  // one per vertex [m/s]
  std::vector<std::array<int, 3>> faces;
};

inline int add_vertex(Surface& s, const Vec3& x, const Vec3& v = {0, 0, 0}) {
  s.vertices.push_back(x);
  s.velocities.push_back(v);
  return static_cast<int>(s.vertices.size()) - 1;
}
// A planar quad (counter-clockwise seen from the fluid) as two triangles.
inline void add_quad(Surface& s, int a, int b, int c, int d) {
  s.faces.push_back({a, b, c});
  s.faces.push_back({a, c, d});
}
// Appends `src` (same dim) to `dst`: several bodies in one surface.
inline void append(Surface& dst, const Surface& src) {
  if (dst.vertices.empty()) dst.dim = src.dim;
  if (dst.dim != src.dim) throw std::runtime_error("embedded surface: cannot append a surface of another dimension");
  const int off = static_cast<int>(dst.vertices.size());
  dst.vertices.insert(dst.vertices.end(), src.vertices.begin(), src.vertices.end());
  dst.velocities.insert(dst.velocities.end(), src.velocities.begin(), src.velocities.end());
  for (auto f : src.faces) {
    f[0] += off;
    if (src.dim >= 2) f[1] += off;
    if (src.dim == 3) f[2] += off;
    dst.faces.push_back(f);
  }
}

inline void set_rigid_velocity(Surface& s, const Vec3& v) { s.velocities.assign(s.vertices.size(), v); }
// Moves every vertex by dt times its velocity (explicit, one cycle).
inline void move_surface(Surface& s, double dt) {
  for (std::size_t i = 0; i < s.vertices.size(); ++i) s.vertices[i] = s.vertices[i] + dt * s.velocities[i];
}

// Unit outward normal and measure (area / length / 1) of face f.
inline Vec3 face_normal(const Surface& s, int f, double* measure = nullptr) {
  const auto& fc = s.faces[static_cast<std::size_t>(f)];
  Vec3 n{0, 0, 0};
  double m = 1;
  if (s.dim == 1) {
    n = {fc[1] > 0 ? 1.0 : -1.0, 0, 0};
  } else if (s.dim == 2) {
    const Vec3 t = s.vertices[static_cast<std::size_t>(fc[1])] - s.vertices[static_cast<std::size_t>(fc[0])];
    m = norm(t);
    n = normalized(Vec3{t[1], -t[0], 0});
  } else {
    const Vec3& a = s.vertices[static_cast<std::size_t>(fc[0])];
    const Vec3 c =
        cross(s.vertices[static_cast<std::size_t>(fc[1])] - a, s.vertices[static_cast<std::size_t>(fc[2])] - a);
    m = 0.5 * norm(c);
    n = normalized(c);
  }
  if (measure) *measure = m;
  return n;
}

// Total boundary measure (perimeter in 2D, area in 3D, point count in 1D).
inline double surface_measure(const Surface& s) {
  double total = 0, m = 0;
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    face_normal(s, static_cast<int>(f), &m);
    total += m;
  }
  return total;
}

// Enclosed volume (area in 2D, length in 1D) by the divergence theorem, V = (1/dim) sum x_f.n_f A_f.
inline double enclosed_volume(const Surface& s) {
  double v = 0;
  for (const auto& f : s.faces) {
    const Vec3& a = s.vertices[static_cast<std::size_t>(f[0])];
    if (s.dim == 1) v += (f[1] > 0 ? 1.0 : -1.0) * a[0];
    else if (s.dim == 2) v += 0.5 * cross(a, s.vertices[static_cast<std::size_t>(f[1])])[2];
    else
      v += dot(a, cross(s.vertices[static_cast<std::size_t>(f[1])], s.vertices[static_cast<std::size_t>(f[2])])) / 6.0;
  }
  return v;
}

// Generalised winding number of p (1 inside, 0 outside): 2D angle sum, 3D solid angles of the
// triangles (Van Oosterom & Strackee, IEEE Trans. Biomed. Eng. 30 (1983) 125), 1D signed crossings.
// O(faces): used once per cycle to seed the inside/outside sign of rows outside the band.
inline double winding_number(const Surface& s, const Vec3& p) {
  double w = 0;
  for (const auto& f : s.faces) {
    const Vec3 a = s.vertices[static_cast<std::size_t>(f[0])] - p;
    if (s.dim == 1) {
      if (a[0] > 0) w += f[1] > 0 ? 1.0 : -1.0;
    } else if (s.dim == 2) {
      const Vec3 b = s.vertices[static_cast<std::size_t>(f[1])] - p;
      w += std::atan2(cross(a, b)[2], dot(a, b)) / (2 * std::numbers::pi);
    } else {
      const Vec3 b = s.vertices[static_cast<std::size_t>(f[1])] - p;
      const Vec3 c = s.vertices[static_cast<std::size_t>(f[2])] - p;
      const double la = norm(a), lb = norm(b), lc = norm(c);
      const double num = dot(a, cross(b, c));
      const double den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
      w += 2 * std::atan2(num, den) / (4 * std::numbers::pi);
    }
  }
  return w;
}

// Closest-feature codes of a face (edge k joins local vertices k and k+1 mod 3).
enum class Feature : std::uint8_t { Vertex0, Vertex1, Vertex2, Edge01, Edge12, Edge20, Interior };

// Per-cycle normals of a closed surface. Pseudo-normals sign the distance robustly at edges and
// vertices: face normal, edge = sum of the two face normals, vertex = angle-weighted sum
// (Baerentzen & Aanaes, IEEE TVCG 11 (2005) 243). In 2D the vertex normal is the sum of its two
// segment normals.
struct SurfaceTopology {
  std::vector<Vec3> face_normal;
  std::vector<double> face_measure;
  std::vector<Vec3> vertex_normal;
  std::vector<Vec3> edge_normal;               // 3D only
  std::vector<std::array<int, 3>> face_edges;  // 3D only: edge ids of (01, 12, 20)
  int dim = 0;
  std::vector<std::array<int, 3>> faces;  // the connectivity checked and numbered (update_topology reuses it)
};

namespace detail {
[[noreturn]] inline void topology_fail(const std::string& why) { throw std::runtime_error("embedded surface: " + why); }

// What holds for the vertex positions of every cycle: the dimension, a velocity per vertex, no components beyond
// the dimension.
inline void check_vertices(const Surface& s) {
  if (s.dim < 1 || s.dim > 3) topology_fail("dim must be 1, 2 or 3");
  if (s.velocities.size() != s.vertices.size()) topology_fail("one velocity per vertex is required");
  for (const auto& x : s.vertices)
    for (int d = s.dim; d < 3; ++d)
      if (x[static_cast<std::size_t>(d)] != 0)
        topology_fail("vertex components beyond the surface dimension must be 0");
}

// The normals for the vertex positions of now, on t's connectivity (its edge ids in 3D), each sum taken over the
// faces in their order: face normals and measures; vertex normals: the face's (1D), the sum of the two segments'
// (2D), angle-weighted (3D); edge normals: the sum of the two faces' (3D).
inline void compute_normals(const Surface& s, SurfaceTopology& t) {
  const std::size_t nf = s.faces.size();
  t.face_normal.resize(nf);
  t.face_measure.resize(nf);
  t.vertex_normal.assign(s.vertices.size(), Vec3{0, 0, 0});
  for (std::size_t f = 0; f < nf; ++f) {
    t.face_normal[f] = face_normal(s, static_cast<int>(f), &t.face_measure[f]);
    if (!(t.face_measure[f] > 0)) topology_fail("face " + std::to_string(f) + " is degenerate (zero length/area)");
  }
  if (s.dim == 1) {
    for (std::size_t f = 0; f < nf; ++f) t.vertex_normal[static_cast<std::size_t>(s.faces[f][0])] = t.face_normal[f];
    return;
  }
  if (s.dim == 2) {
    for (std::size_t f = 0; f < nf; ++f) {
      const auto a = static_cast<std::size_t>(s.faces[f][0]), b = static_cast<std::size_t>(s.faces[f][1]);
      t.vertex_normal[a] = t.vertex_normal[a] + t.face_normal[f];
      t.vertex_normal[b] = t.vertex_normal[b] + t.face_normal[f];
    }
    return;
  }
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& fc = s.faces[f];
    for (int k = 0; k < 3; ++k) {
      const int u = fc[static_cast<std::size_t>(k)], v = fc[static_cast<std::size_t>((k + 1) % 3)];
      const Vec3& x = s.vertices[static_cast<std::size_t>(u)];
      const Vec3 e1 = s.vertices[static_cast<std::size_t>(v)] - x;
      const Vec3 e2 = s.vertices[static_cast<std::size_t>(fc[static_cast<std::size_t>((k + 2) % 3)])] - x;
      const double angle = std::atan2(norm(cross(e1, e2)), dot(e1, e2));
      t.vertex_normal[static_cast<std::size_t>(u)] =
          t.vertex_normal[static_cast<std::size_t>(u)] + angle * t.face_normal[f];
    }
  }
  t.edge_normal.assign(t.edge_normal.size(), Vec3{0, 0, 0});
  for (std::size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      Vec3& en = t.edge_normal[static_cast<std::size_t>(t.face_edges[f][static_cast<std::size_t>(k)])];
      en = en + t.face_normal[f];
    }
}
}  // namespace detail

// Checks that the surface is closed and consistently oriented (throws std::runtime_error
// otherwise) and computes its normals. O(faces).
inline SurfaceTopology build_topology(const Surface& s) {
  using detail::topology_fail;
  detail::check_vertices(s);
  const int nv = static_cast<int>(s.vertices.size());
  SurfaceTopology t;
  t.dim = s.dim;
  t.faces = s.faces;
  const std::size_t nf = s.faces.size();
  const int nid = s.dim == 1 ? 1 : s.dim;
  for (std::size_t f = 0; f < nf; ++f) {
    for (int k = 0; k < nid; ++k)
      if (s.faces[f][static_cast<std::size_t>(k)] < 0 || s.faces[f][static_cast<std::size_t>(k)] >= nv)
        topology_fail("face " + std::to_string(f) + " has a vertex id out of range");
    if (s.dim == 1 && std::abs(s.faces[f][1]) != 1)
      topology_fail("1D face " + std::to_string(f) + " needs an orientation of +1 or -1");
  }
  if (s.dim == 1) {  // sorted points must alternate -x, +x (a union of disjoint intervals)
    std::vector<std::size_t> order(nf);
    for (std::size_t f = 0; f < nf; ++f) order[f] = f;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return s.vertices[static_cast<std::size_t>(s.faces[a][0])][0] <
             s.vertices[static_cast<std::size_t>(s.faces[b][0])][0];
    });
    for (std::size_t k = 0; k < nf; ++k)
      if (s.faces[order[k]][1] != (k % 2 == 0 ? -1 : 1))
        topology_fail("1D faces must alternate -x/+x along x (closed intervals)");
  } else if (s.dim == 2) {  // every vertex starts exactly one segment and ends exactly one
    std::vector<int> starts(s.vertices.size(), 0), ends(s.vertices.size(), 0);
    for (std::size_t f = 0; f < nf; ++f) {
      ++starts[static_cast<std::size_t>(s.faces[f][0])];
      ++ends[static_cast<std::size_t>(s.faces[f][1])];
    }
    for (std::size_t v = 0; v < s.vertices.size(); ++v)
      if (starts[v] != ends[v] || starts[v] > 1)
        topology_fail("the polygon is not closed and consistently oriented at vertex " + std::to_string(v));
  } else {  // 3D: every directed edge (u,v) once and its reverse (v,u) once
    std::unordered_map<std::uint64_t, int> directed;
    directed.reserve(3 * nf);
    auto key = [](int u, int v) {
      return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(u)) << 32) | static_cast<std::uint32_t>(v);
    };
    for (std::size_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const int u = s.faces[f][static_cast<std::size_t>(k)], v = s.faces[f][static_cast<std::size_t>((k + 1) % 3)];
        if (!directed.emplace(key(u, v), static_cast<int>(f)).second)
          topology_fail("edge (" + std::to_string(u) + "," + std::to_string(v) +
                        ") is used twice in the same direction (non-manifold or inconsistent orientation)");
      }
    std::unordered_map<std::uint64_t, int> edge_id;
    edge_id.reserve(3 * nf / 2 + 1);
    t.face_edges.resize(nf);
    int edges = 0;
    for (std::size_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const int u = s.faces[f][static_cast<std::size_t>(k)], v = s.faces[f][static_cast<std::size_t>((k + 1) % 3)];
        if (directed.find(key(v, u)) == directed.end())
          topology_fail("the surface is not closed: edge (" + std::to_string(u) + "," + std::to_string(v) +
                        ") has one face only");
        const auto it = edge_id.emplace(key(std::min(u, v), std::max(u, v)), edges).first;
        if (it->second == edges) ++edges;
        t.face_edges[f][static_cast<std::size_t>(k)] = it->second;
      }
    t.edge_normal.resize(static_cast<std::size_t>(edges));
  }
  detail::compute_normals(s, t);
  return t;
}

// `t` for this cycle's surface: a surface with the faces `t` was built for (a body that moves and deforms) keeps
// its checked connectivity and gets new normals only, the same values build_topology gives; any other is built anew.
inline void update_topology(const Surface& s, SurfaceTopology& t) {
  if (t.dim != s.dim || t.vertex_normal.size() != s.vertices.size() || t.faces != s.faces) {
    t = build_topology(s);
    return;
  }
  detail::check_vertices(s);
  detail::compute_normals(s, t);
}

// Pseudo-normal (not normalised) of the closest feature of face f.
inline Vec3 pseudo_normal(const Surface& s, const SurfaceTopology& t, int f, Feature feat) {
  const auto& fc = s.faces[static_cast<std::size_t>(f)];
  switch (feat) {
    case Feature::Vertex0: return t.vertex_normal[static_cast<std::size_t>(fc[0])];
    case Feature::Vertex1: return t.vertex_normal[static_cast<std::size_t>(fc[1])];
    case Feature::Vertex2: return t.vertex_normal[static_cast<std::size_t>(fc[2])];
    case Feature::Edge01: return t.edge_normal[static_cast<std::size_t>(t.face_edges[static_cast<std::size_t>(f)][0])];
    case Feature::Edge12: return t.edge_normal[static_cast<std::size_t>(t.face_edges[static_cast<std::size_t>(f)][1])];
    case Feature::Edge20: return t.edge_normal[static_cast<std::size_t>(t.face_edges[static_cast<std::size_t>(f)][2])];
    default: return t.face_normal[static_cast<std::size_t>(f)];
  }
}

// Velocity at a point of face f given its barycentric weights (linear interpolation of the
// vertex velocities).
inline Vec3 face_velocity(const Surface& s, int f, const std::array<double, 3>& bary) {
  const auto& fc = s.faces[static_cast<std::size_t>(f)];
  const int nid = s.dim == 1 ? 1 : s.dim;
  Vec3 v{0, 0, 0};
  for (int k = 0; k < nid; ++k)
    v = v + bary[static_cast<std::size_t>(k)] * s.velocities[static_cast<std::size_t>(fc[static_cast<std::size_t>(k)])];
  return v;
}

}  // namespace cosim::fluid::embedded
