#include "solid_solver/mesh/partition.h"

#include <fmt/format.h>
#include <metis.h>

#include <algorithm>
#include <stdexcept>

#include "solid_solver/mesh/element_faces.h"

namespace cosim::solid {

std::vector<int> MeshPartition::elements_per_part() const {
  std::vector<int> n(static_cast<std::size_t>(parts), 0);
  for (const int p : element_part) ++n[static_cast<std::size_t>(p)];
  return n;
}

MeshPartition partition_elements(const Mesh& m, int parts) {
  if (parts < 1) throw std::invalid_argument(fmt::format("{} parts: at least 1 expected", parts));
  if (parts > m.num_elements)
    throw std::invalid_argument(
        fmt::format("{} parts of a mesh of {} elements: at least one element per part", parts, m.num_elements));
  MeshPartition p;
  p.parts = parts;
  p.element_part.assign(static_cast<std::size_t>(m.num_elements), 0);
  if (parts > 1) {
    idx_t ne = m.num_elements, nn = m.num_nodes, ncommon = m.dim == 2 ? 2 : 4, nparts = parts, objval = 0;
    std::vector<idx_t> eptr(static_cast<std::size_t>(ne) + 1), eind(m.conn.begin(), m.conn.end());
    for (idx_t e = 0; e <= ne; ++e) eptr[static_cast<std::size_t>(e)] = e * m.npe;
    std::vector<idx_t> epart(static_cast<std::size_t>(ne)), npart(static_cast<std::size_t>(nn));
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_NUMBERING] = 0;
    options[METIS_OPTION_SEED] = 1;  // the same parts on every rank and every run
    options[METIS_OPTION_CONTIG] = 1;  // each part one connected piece of the mesh
    const int status = METIS_PartMeshDual(&ne, &nn, eptr.data(), eind.data(), nullptr, nullptr, &ncommon, &nparts,
                                          nullptr, options, &objval, epart.data(), npart.data());
    if (status != METIS_OK)
      throw std::runtime_error(fmt::format("METIS could not split {} elements into {} parts (status {})", ne, parts,
                                           status));
    std::copy(epart.begin(), epart.end(), p.element_part.begin());
  }
  // Owners and shared nodes from the elements' parts.
  p.node_owner.assign(static_cast<std::size_t>(m.num_nodes), parts);
  std::vector<std::vector<int>> parts_of_node(static_cast<std::size_t>(m.num_nodes));
  for (int e = 0; e < m.num_elements; ++e) {
    const int part = p.element_part[static_cast<std::size_t>(e)];
    for (int k = 0; k < m.npe; ++k) {
      const auto n = static_cast<std::size_t>(m.conn[static_cast<std::size_t>(e) * m.npe + k]);
      p.node_owner[n] = std::min(p.node_owner[n], part);
      auto& list = parts_of_node[n];
      if (std::find(list.begin(), list.end(), part) == list.end()) list.push_back(part);
    }
  }
  p.shared_nodes.assign(static_cast<std::size_t>(parts), {});
  for (int n = 0; n < m.num_nodes; ++n) {
    const auto& list = parts_of_node[static_cast<std::size_t>(n)];
    if (list.size() > 1)
      for (const int part : list) p.shared_nodes[static_cast<std::size_t>(part)].push_back(n);
  }
  const std::vector<FaceRef> faces = all_element_faces(m);
  for (std::size_t i = 0; i + 1 < faces.size(); ++i)
    if (faces[i].key == faces[i + 1].key &&
        p.element_part[static_cast<std::size_t>(faces[i].element)] !=
            p.element_part[static_cast<std::size_t>(faces[i + 1].element)])
      ++p.cut_faces;
  return p;
}

}  // namespace cosim::solid
