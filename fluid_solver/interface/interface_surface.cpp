#include "fluid_solver/interface/interface_surface.h"
#include <limits>

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace cosim::fluid::interface {

using embedded::Vec3;
using embedded::operator-;
using embedded::operator*;

namespace {
void check_size(const char* field, std::size_t got, std::size_t want) {
  if (got != want)
    throw std::invalid_argument(fmt::format("InterfaceFaces.{}: {} values, expected {}", field, got, want));
}
}  // namespace

InterfaceSurface surface_from_faces(const coupling::Faces& f, int dim, double back_dt) {
  if (dim < 1 || dim > 3) throw std::invalid_argument(fmt::format("a {}D fluid grid cannot take faces", dim));
  if (f.dim != dim)
    throw std::invalid_argument(fmt::format("InterfaceFaces.dim = {} but the fluid grid is {}D", f.dim, dim));
  const int npf = f.nodes_per_face;
  if ((dim == 1 && npf != 1) || (dim == 2 && npf != 2) || (dim == 3 && npf != 3 && npf != 4))
    throw std::invalid_argument(fmt::format("InterfaceFaces.nodes_per_face = {}, expected {}", npf,
                                            dim == 1   ? "1 (points)"
                                            : dim == 2 ? "2 (segments)"
                                                       : "3 or 4 (triangles or quads)"));
  const auto n = static_cast<std::size_t>(f.count), d = static_cast<std::size_t>(dim);
  check_size("centre", f.centre.size(), n * d);
  check_size("normal", f.normal.size(), n * d);
  check_size("velocity", f.velocity.size(), n * d);
  check_size("area", f.area.size(), n);
  check_size("face_vertex", f.face_vertex.size(), n * static_cast<std::size_t>(npf));
  if (f.vertex_position.size() % d != 0)
    throw std::invalid_argument(fmt::format("InterfaceFaces.vertex_position: {} values, not a multiple of dim = {}",
                                            f.vertex_position.size(), dim));
  const std::size_t nv = f.vertex_position.size() / d;
  for (std::size_t i = 0; i < f.face_vertex.size(); ++i)
    if (f.face_vertex[i] >= nv)
      throw std::invalid_argument(
          fmt::format("InterfaceFaces.face_vertex[{}] = {} but there are {} vertices", i, f.face_vertex[i], nv));
  for (double x : f.vertex_position)
    if (!std::isfinite(x)) throw std::invalid_argument("InterfaceFaces.vertex_position: not finite");
  for (double x : f.velocity)
    if (!std::isfinite(x)) throw std::invalid_argument("InterfaceFaces.velocity: not finite");

  // Vertex velocities: area-weighted mean of the adjacent faces' velocities.
  std::vector<Vec3> vel(nv, Vec3{0, 0, 0});
  std::vector<double> weight(nv, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double w = std::max(f.area[i], 1e-300);
    for (int q = 0; q < npf; ++q) {
      const std::size_t v = f.face_vertex[i * npf + q];
      for (std::size_t c = 0; c < d; ++c) vel[v][c] += w * f.velocity[i * d + c];
      weight[v] += w;
    }
  }
  InterfaceSurface out;
  embedded::Surface& s = out.surface;
  s.dim = dim;
  s.vertices.resize(nv);
  s.velocities.resize(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    Vec3 x{0, 0, 0};
    for (std::size_t c = 0; c < d; ++c) x[c] = f.vertex_position[v * d + c];
    const Vec3 u = weight[v] > 0 ? (1.0 / weight[v]) * vel[v] : Vec3{0, 0, 0};
    s.vertices[v] = x - back_dt * u;
    s.velocities[v] = u;
  }
  // Faces, oriented by the outward normal the solid sent.
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 nrm{0, 0, 0};
    for (std::size_t c = 0; c < d; ++c) nrm[c] = f.normal[i * d + c];
    std::array<int, 4> q{-1, -1, -1, -1};
    for (int k = 0; k < npf; ++k) q[k] = static_cast<int>(f.face_vertex[i * npf + k]);
    if (dim == 1) {  // a point with outward normal sign(n_x) e_x
      s.faces.push_back({q[0], nrm[0] >= 0 ? 1 : -1, -1});
      out.source_face.push_back(static_cast<int>(i));
      continue;
    }
    if (dim == 2) {
      s.faces.push_back({q[0], q[1], -1});
      if (embedded::dot(embedded::face_normal(s, static_cast<int>(s.faces.size()) - 1), nrm) < 0)
        s.faces.back() = {q[1], q[0], -1};
      out.source_face.push_back(static_cast<int>(i));
      continue;
    }
    const Vec3& a = s.vertices[q[0]];
    // The quad's normal from its diagonals (robust for slightly warped quads).
    const Vec3 qn = npf == 4 ? embedded::cross(s.vertices[q[2]] - a, s.vertices[q[3]] - s.vertices[q[1]])
                             : embedded::cross(s.vertices[q[1]] - a, s.vertices[q[2]] - a);
    if (embedded::dot(qn, nrm) < 0) {
      if (npf == 4) q = {q[0], q[3], q[2], q[1]};
      else std::swap(q[1], q[2]);
    }
    s.faces.push_back({q[0], q[1], q[2]});
    out.source_face.push_back(static_cast<int>(i));
    if (npf == 4) {
      s.faces.push_back({q[0], q[2], q[3]});
      out.source_face.push_back(static_cast<int>(i));
    }
  }
  return out;
}

coupling::Faces faces_of_surface(const embedded::Surface& s) {
  coupling::Faces f;
  const int dim = s.dim;
  f.dim = dim;
  f.count = static_cast<int>(s.faces.size());
  const int nv = dim == 3 ? 3 : dim == 2 ? 2 : 1;  // vertices of a face (1D: the point)
  for (int i = 0; i < f.count; ++i) {
    const auto& q = s.faces[static_cast<std::size_t>(i)];
    double measure = 0;
    const Vec3 n = embedded::face_normal(s, i, &measure);
    Vec3 c{0, 0, 0}, v{0, 0, 0};
    for (int k = 0; k < nv; ++k)
      for (int d = 0; d < 3; ++d) {
        c[d] += s.vertices[q[k]][d];
        v[d] += s.velocities[q[k]][d];
      }
    for (int d = 0; d < dim; ++d) {
      f.centre.push_back(c[d] / nv);
      f.normal.push_back(n[d]);
      f.velocity.push_back(v[d] / nv);
    }
    f.area.push_back(measure);
    f.normal_stress.push_back(0.0);
    f.impedance.push_back(std::numeric_limits<double>::infinity());
  }
  return f;
}

}  // namespace cosim::fluid::interface
