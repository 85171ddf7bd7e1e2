// The solid's interface faces as they arrive from the coupler (coupling::Faces: the solid's exterior
// boundary at t^{n+1}, proto InterfaceFaces) turned into the embedded boundary's Surface (paper
// section 8, step 2: "the exterior boundary of the foreground mesh").
#pragma once

#include <string>
#include <vector>

#include "common/coupling/types.h"
#include "fluid_solver/embedded/surface.h"

namespace cosim::fluid::interface {

struct InterfaceSurface {
  embedded::Surface surface;
  std::vector<int> source_face;  // the coupler face of each Surface face (3D quads become two triangles)
};

// Builds the Surface of `faces` for a fluid grid of dimension `dim` (1, 2 or 3; the faces must have the same
// dimension and carry vertex data: points, segments, triangles or quads). Vertex velocities are the area-weighted means
// of the adjacent faces' velocities (exact for rigid motion). The vertices are moved back by `back_dt` times their
// velocity: the solid has already advanced to t^{n+1}, the fluid state is at t^n, and the body is placed where it was
// at t^n (the same explicit placement as prescribed motion). Face orientation follows the faces' outward normals.
// Throws std::invalid_argument naming the field for malformed data.
InterfaceSurface surface_from_faces(const coupling::Faces& faces, int dim, double back_dt);

// The faces of a Surface as a solid would send them (centre, outward normal, measure, mean vertex velocity;
// no vertex data): what sample_interface() reads, e.g. to sample next to the scene's own bodies.
coupling::Faces faces_of_surface(const embedded::Surface& s);

}  // namespace cosim::fluid::interface
