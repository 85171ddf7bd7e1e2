// The scene's embedded bodies (core/scene.h, EmbeddedBody) as one closed Surface.
#pragma once

#include "fluid_solver/core/scene.h"
#include "fluid_solver/embedded/shapes.h"

namespace cosim::fluid::embedded {

// One body: box / step (rotation about z in 2D), circle (`segments` edges), sphere (icosphere,
// `segments` = refinement level), polygon (2D vertices, rotated about their mean).
inline Surface surface_of(const EmbeddedBody& b, int dim) {
  switch (b.shape) {
    case EmbeddedBody::Shape::Box: return make_box(dim, b.lower, b.upper, b.velocity, b.rotation_deg);
    case EmbeddedBody::Shape::Step: return make_step(dim, b.lower, b.upper, b.velocity);
    case EmbeddedBody::Shape::Circle: return make_circle(b.center, b.radius, b.segments, b.velocity);
    case EmbeddedBody::Shape::Sphere: return make_sphere(b.center, b.radius, b.segments, b.velocity);
    case EmbeddedBody::Shape::Polygon: {
      std::vector<Point2> v(b.vertices.begin(), b.vertices.end());
      return make_polygon(v, b.velocity, b.rotation_deg);
    }
  }
  throw std::runtime_error("embedded shape: unknown body shape");
}

// All bodies of a scene in one surface (their faces keep the order of the bodies).
inline Surface surface_of(const EmbeddedSettings& e, int dim) {
  Surface s;
  s.dim = dim;
  for (const auto& b : e.bodies) append(s, surface_of(b, dim));
  return s;
}

}  // namespace cosim::fluid::embedded
