// Closest point of a face to a query point, with the closest feature (vertex / edge / interior,
// which selects the pseudo-normal that signs the distance) and barycentric weights (which
// interpolate the wall velocity). Triangle: Voronoi-region classification of the point against
// the vertices and edges, Ericson, "Real-Time Collision Detection" (2005) section 5.1.5.
#pragma once

#include "fluid_solver/embedded/surface.h"

namespace cosim::fluid::embedded {

struct ClosestPoint {
  Vec3 point{0, 0, 0};
  std::array<double, 3> bary{0, 0, 0};  // weights of the face's vertices
  Feature feature = Feature::Interior;
  double d2 = 0;  // squared distance
};

inline ClosestPoint closest_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  ClosestPoint r;
  const Vec3 ab = b - a;
  const double t = dot(p - a, ab) / dot(ab, ab);
  if (t <= 0) {
    r.point = a, r.bary = {1, 0, 0}, r.feature = Feature::Vertex0;
  } else if (t >= 1) {
    r.point = b, r.bary = {0, 1, 0}, r.feature = Feature::Vertex1;
  } else {
    r.point = a + t * ab, r.bary = {1 - t, t, 0}, r.feature = Feature::Interior;
  }
  const Vec3 d = p - r.point;
  r.d2 = dot(d, d);
  return r;
}

inline ClosestPoint closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  ClosestPoint r;
  auto finish = [&](const Vec3& q, double wa, double wb, double wc, Feature f) {
    r.point = q, r.bary = {wa, wb, wc}, r.feature = f;
    const Vec3 d = p - q;
    r.d2 = dot(d, d);
    return r;
  };
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return finish(a, 1, 0, 0, Feature::Vertex0);
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return finish(b, 0, 1, 0, Feature::Vertex1);
  const double vc = d1 * d4 - d3 * d2;  // signed area weight of c
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return finish(a + v * ab, 1 - v, v, 0, Feature::Edge01);
  }
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return finish(c, 0, 0, 1, Feature::Vertex2);
  const double vb = d5 * d2 - d1 * d6;  // weight of b
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return finish(a + w * ac, 1 - w, 0, w, Feature::Edge20);
  }
  const double va = d3 * d6 - d5 * d4;  // weight of a
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return finish(b + w * (c - b), 0, 1 - w, w, Feature::Edge12);
  }
  const double inv = 1.0 / (va + vb + vc);
  const double v = vb * inv, w = vc * inv;
  return finish(a + v * ab + w * ac, 1 - v - w, v, w, Feature::Interior);
}

// Closest point of face f of s to p (only the first s.dim components of p matter).
inline ClosestPoint closest_on_face(const Surface& s, int f, const Vec3& p) {
  const auto& fc = s.faces[static_cast<std::size_t>(f)];
  const Vec3& a = s.vertices[static_cast<std::size_t>(fc[0])];
  if (s.dim == 1) {
    ClosestPoint r;
    r.point = a, r.bary = {1, 0, 0}, r.feature = Feature::Vertex0;
    r.d2 = (p[0] - a[0]) * (p[0] - a[0]);
    return r;
  }
  if (s.dim == 2) return closest_on_segment(p, a, s.vertices[static_cast<std::size_t>(fc[1])]);
  return closest_on_triangle(p, a, s.vertices[static_cast<std::size_t>(fc[1])],
                             s.vertices[static_cast<std::size_t>(fc[2])]);
}

}  // namespace cosim::fluid::embedded
