#include "solid_solver/core/boundary_faces.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solid_solver/mesh/element_faces.h"

namespace cosim::solid {

BoundaryFaces make_boundary_faces(const Mesh& m) {
  BoundaryFaces bf;
  bf.dim = m.dim;
  bf.nodes_per_face = m.face_nodes();
  const auto faces = exterior_faces(m);
  bf.count = static_cast<int>(faces.size());
  const int k = bf.nodes_per_face;
  // Sets: match by the sorted node key.
  std::vector<std::pair<std::array<int, 4>, int>> keyed;
  for (const auto& [name, list] : m.face_sets) {
    const int id = static_cast<int>(bf.set_names.size());
    bf.set_names.push_back(name);
    for (const auto& f : list) keyed.push_back({face_key(m.dim, f.nodes), id});
  }
  std::sort(keyed.begin(), keyed.end());
  for (const auto& f : faces) {
    for (int q = 0; q < k; ++q) bf.nodes.push_back(f.nodes[q]);
    bf.element.push_back(f.element);
    bf.block.push_back(m.element_block[f.element]);
    const auto key = face_key(m.dim, f.nodes);
    auto it = std::lower_bound(keyed.begin(), keyed.end(), std::make_pair(key, -1));
    bf.set.push_back(it != keyed.end() && it->first == key ? it->second : -1);
  }
  const std::size_t n = static_cast<std::size_t>(bf.count);
  bf.normal.assign(n * m.dim, 0.0);
  bf.area.assign(n, 0.0);
  bf.centre.assign(n * m.dim, 0.0);
  bf.velocity.assign(n * m.dim, 0.0);
  bf.normal_stress.assign(n, 0.0);
  bf.impedance.assign(n, 0.0);
  return bf;
}

void update_boundary_faces(BoundaryFaces& bf, const State& st, const std::vector<char>& rigid) {
  const int D = bf.dim, k = bf.nodes_per_face;
  const double inf = std::numeric_limits<double>::infinity();
  for (int i = 0; i < bf.count; ++i) {
    std::array<int, 4> fn{-1, -1, -1, -1};
    for (int q = 0; q < k; ++q) fn[q] = bf.nodes[static_cast<std::size_t>(i) * k + q];
    double an[3];
    face_area_vector(D, st.x.data(), fn, an);
    const double a = std::sqrt(an[0] * an[0] + an[1] * an[1] + an[2] * an[2]);
    bf.area[i] = a;
    double n[3] = {0, 0, 0};
    for (int d = 0; d < D; ++d) n[d] = a > 0 ? an[d] / a : 0.0;
    for (int d = 0; d < D; ++d) {
      double xc = 0, vc = 0;
      for (int q = 0; q < k; ++q) {
        xc += st.x[static_cast<std::size_t>(fn[q]) * D + d];
        vc += st.v[static_cast<std::size_t>(fn[q]) * D + d];
      }
      bf.normal[static_cast<std::size_t>(i) * D + d] = n[d];
      bf.centre[static_cast<std::size_t>(i) * D + d] = xc / k;
      bf.velocity[static_cast<std::size_t>(i) * D + d] = vc / k;
    }
    const int z = bf.element[i];
    if (rigid[bf.block[i]]) {
      bf.normal_stress[i] = 0.0;
      bf.impedance[i] = inf;
      continue;
    }
    // n . s . n with s = (xx, yy, zz, xy, yz, zx), minus p + q.
    const double* s = &st.s[static_cast<std::size_t>(z) * 6];
    const double nsn = s[0] * n[0] * n[0] + s[1] * n[1] * n[1] + s[2] * n[2] * n[2] +
                       2.0 * (s[3] * n[0] * n[1] + s[4] * n[1] * n[2] + s[5] * n[2] * n[0]);
    bf.normal_stress[i] = nsn - st.p[z] - st.q[z];
    bf.impedance[i] = st.emass[z] / st.vol[z] * st.c[z];
  }
}

}  // namespace cosim::solid
