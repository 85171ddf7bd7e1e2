#include "solid_solver/ale/ale_mesh.h"

#include <algorithm>

#include "solid_solver/mesh/element_faces.h"

namespace cosim::solid {

namespace {
// Element edges as local node pairs: quad sides; hex edges (VTK order).
constexpr int kQuadEdges[4][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
constexpr int kHexEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                  {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
}  // namespace

AleMesh make_ale_mesh(const Mesh& m, const std::vector<char>& relaxed_block) {
  AleMesh a;
  const int ne = m.num_elements, nn = m.num_nodes, N = m.npe;
  a.relaxed_element.assign(ne, 0);
  a.relaxed_node.assign(nn, 1);
  a.exterior_node.assign(nn, 0);
  for (int e = 0; e < ne; ++e) {
    a.relaxed_element[e] = relaxed_block[m.element_block[e]];
    if (!a.relaxed_element[e])
      for (int k = 0; k < N; ++k) a.relaxed_node[m.conn[static_cast<std::size_t>(e) * N + k]] = 0;
  }
  // Faces: matched pairs of the sorted face list are interior, single ones exterior.
  const std::vector<FaceRef> f = all_element_faces(m);
  const int k = m.face_nodes();
  for (std::size_t i = 0; i < f.size();) {
    const bool pair = i + 1 < f.size() && f[i + 1].key == f[i].key;
    if (pair) {
      if (a.relaxed_element[f[i].element] && a.relaxed_element[f[i + 1].element])
        a.faces.push_back({f[i].element, f[i].local, f[i + 1].element});
      i += 2;
    } else {
      if (a.relaxed_element[f[i].element]) a.faces.push_back({f[i].element, f[i].local, -1});
      const auto nodes = element_face_nodes(m, f[i].element, f[i].local);
      for (int q = 0; q < k; ++q) a.exterior_node[nodes[q]] = 1;
      i += 1;
    }
  }
  for (int n = 0; n < nn; ++n) a.exterior_node[n] = a.exterior_node[n] && a.relaxed_node[n];
  // Edge neighbours (each edge once per element; duplicates removed per node).
  std::vector<std::vector<int>> nb(nn);
  const int ned = m.dim == 2 ? 4 : 12;
  for (int e = 0; e < ne; ++e)
    for (int j = 0; j < ned; ++j) {
      const int* c = &m.conn[static_cast<std::size_t>(e) * N];
      const int p = c[m.dim == 2 ? kQuadEdges[j][0] : kHexEdges[j][0]];
      const int q = c[m.dim == 2 ? kQuadEdges[j][1] : kHexEdges[j][1]];
      nb[p].push_back(q);
      nb[q].push_back(p);
    }
  a.neighbour_offset.assign(nn + 1, 0);
  for (int n = 0; n < nn; ++n) {
    std::sort(nb[n].begin(), nb[n].end());
    nb[n].erase(std::unique(nb[n].begin(), nb[n].end()), nb[n].end());
    a.neighbour_offset[n + 1] = a.neighbour_offset[n] + static_cast<int>(nb[n].size());
    a.neighbours.insert(a.neighbours.end(), nb[n].begin(), nb[n].end());
  }
  return a;
}

}  // namespace cosim::solid
