#include "solid_solver/mesh/element_faces.h"

#include <algorithm>

namespace cosim::solid {

std::array<int, 4> face_key(int dim, const std::array<int, 4>& nodes) {
  std::array<int, 4> k = nodes;
  if (dim == 2) k[2] = k[3] = -1;
  std::sort(k.begin(), k.end());
  return k;
}

std::vector<FaceRef> all_element_faces(const Mesh& m) {
  const int nf = faces_per_element(m.dim);
  std::vector<FaceRef> faces;
  faces.reserve(static_cast<std::size_t>(m.num_elements) * nf);
  for (int e = 0; e < m.num_elements; ++e)
    for (int f = 0; f < nf; ++f) faces.push_back({face_key(m.dim, element_face_nodes(m, e, f)), e, f});
  std::sort(faces.begin(), faces.end(),
            [](const FaceRef& a, const FaceRef& b) { return a.key != b.key ? a.key < b.key : a.element < b.element; });
  return faces;
}

std::vector<BoundaryFace> exterior_faces(const Mesh& m) {
  const auto faces = all_element_faces(m);
  std::vector<BoundaryFace> out;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j - i == 1) out.push_back({element_face_nodes(m, faces[i].element, faces[i].local), faces[i].element});
    i = j;
  }
  std::sort(out.begin(), out.end(), [&](const BoundaryFace& a, const BoundaryFace& b) {
    return a.element != b.element ? a.element < b.element : a.nodes < b.nodes;
  });
  return out;
}

int face_set_axis(const Mesh& m, const std::vector<double>& x, const std::vector<BoundaryFace>& faces, double tol) {
  if (faces.empty()) return -1;
  int axis = -1;
  double plane = 0.0, extent = 0.0;
  bool have_plane = false;
  for (const auto& f : faces) {
    double an[3];
    face_area_vector(m.dim, x.data(), f.nodes, an);
    const double a = std::sqrt(an[0] * an[0] + an[1] * an[1] + an[2] * an[2]);
    if (!(a > 0.0)) return -1;
    int ax = 0;
    for (int d = 1; d < m.dim; ++d)
      if (std::abs(an[d]) > std::abs(an[ax])) ax = d;
    if (axis < 0) axis = ax;
    if (ax != axis || std::abs(an[ax]) < (1.0 - tol) * a) return -1;
    for (int q = 0; q < m.face_nodes(); ++q) {
      const double c = x[static_cast<std::size_t>(f.nodes[q]) * m.dim + axis];
      if (!have_plane) plane = c;
      have_plane = true;
      extent = std::max(extent, std::sqrt(a));
      if (std::abs(c - plane) > tol * 1e3 * extent) return -1;  // all nodes on one plane
    }
  }
  return axis;
}

}  // namespace cosim::solid
