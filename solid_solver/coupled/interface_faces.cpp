#include "solid_solver/coupled/interface_faces.h"

#include <unordered_map>

namespace cosim::solid {

InterfaceFaceMap make_interface_face_map(const BoundaryFaces& bf) {
  InterfaceFaceMap m;
  std::unordered_map<int, std::uint32_t> index;
  m.face_vertex.reserve(bf.nodes.size());
  for (int node : bf.nodes) {
    auto [it, fresh] = index.try_emplace(node, static_cast<std::uint32_t>(m.vertex_node.size()));
    if (fresh) m.vertex_node.push_back(node);
    m.face_vertex.push_back(it->second);
  }
  return m;
}

coupling::Faces interface_faces(const BoundaryFaces& bf, const InterfaceFaceMap& map, const State& st) {
  coupling::Faces f;
  f.dim = bf.dim;
  f.count = bf.count;
  f.centre = bf.centre;
  f.normal = bf.normal;
  f.area = bf.area;
  f.velocity = bf.velocity;
  f.normal_stress = bf.normal_stress;
  f.impedance = bf.impedance;
  f.nodes_per_face = bf.nodes_per_face;
  f.face_vertex = map.face_vertex;
  const int D = bf.dim;
  f.vertex_position.resize(map.vertex_node.size() * static_cast<std::size_t>(D));
  for (std::size_t v = 0; v < map.vertex_node.size(); ++v)
    for (int d = 0; d < D; ++d)
      f.vertex_position[v * D + d] = st.x[static_cast<std::size_t>(map.vertex_node[v]) * D + d];
  return f;
}

}  // namespace cosim::solid
