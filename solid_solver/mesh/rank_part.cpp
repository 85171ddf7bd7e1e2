#include "solid_solver/mesh/rank_part.h"

#include <algorithm>
#include <map>

namespace cosim::solid {

RankPart make_rank_part(const Mesh& m, const MeshPartition& p, int rank) {
  RankPart r;
  r.rank = rank;
  r.ranks = p.parts;
  const int N = m.npe;
  r.element_part = p.element_part;
  r.node_owner = p.node_owner;
  for (int& o : r.node_owner)
    if (o >= p.parts) o = 0;  // a node of no element: nobody reads it
  for (int n = 0; n < m.num_nodes; ++n)
    if (r.node_owner[n] == rank) r.owned_nodes.push_back(n);
  // The ranks that compute an element: its owner and the owners of its nodes. For each such rank s, the nodes of the
  // element owned elsewhere are ghosts of s: received here (s = rank) or sent from here (owned here).
  r.element_role.assign(static_cast<std::size_t>(m.num_elements), kElementAbsent);
  std::map<int, std::vector<int>> send, recv;
  std::vector<int> computing;
  for (int e = 0; e < m.num_elements; ++e) {
    const int* cn = &m.conn[static_cast<std::size_t>(e) * N];
    computing.assign(1, r.element_part[e]);
    for (int a = 0; a < N; ++a) computing.push_back(r.node_owner[cn[a]]);
    std::sort(computing.begin(), computing.end());
    computing.erase(std::unique(computing.begin(), computing.end()), computing.end());
    for (const int s : computing) {
      if (s == rank) r.element_role[e] = r.element_part[e] == rank ? kElementOwned : kElementHalo;
      for (int a = 0; a < N; ++a) {
        const int o = r.node_owner[cn[a]];
        if (o == s) continue;
        if (s == rank) recv[o].push_back(cn[a]);
        else if (o == rank) send[s].push_back(cn[a]);
      }
    }
  }
  std::vector<int> ranks;
  for (const auto& [s, list] : send) ranks.push_back(s);
  for (const auto& [s, list] : recv) ranks.push_back(s);
  std::sort(ranks.begin(), ranks.end());
  ranks.erase(std::unique(ranks.begin(), ranks.end()), ranks.end());
  for (const int s : ranks) {
    auto tidy = [](std::vector<int> v) {
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());
      return v;
    };
    r.ghosts.neighbours.push_back(s);
    r.ghosts.send.push_back(tidy(send[s]));
    r.ghosts.recv.push_back(tidy(recv[s]));
  }
  // Runs within each block.
  for (const auto& br : m.block_range)
    for (int e = br[0]; e < br[1];) {
      const char role = r.element_role[e];
      int f = e + 1;
      while (f < br[1] && r.element_role[f] == role) ++f;
      if (role != kElementAbsent) r.runs.push_back({e, f, role});
      e = f;
    }
  for (const char role : r.element_role) {
    r.owned_elements += role == kElementOwned;
    r.halo_elements += role == kElementHalo;
  }
  return r;
}

RankPart whole_mesh_part(const Mesh& m) {
  RankPart r;
  r.node_owner.assign(static_cast<std::size_t>(m.num_nodes), 0);
  r.element_part.assign(static_cast<std::size_t>(m.num_elements), 0);
  r.owned_nodes.resize(static_cast<std::size_t>(m.num_nodes));
  for (int n = 0; n < m.num_nodes; ++n) r.owned_nodes[n] = n;
  r.element_role.assign(static_cast<std::size_t>(m.num_elements), kElementOwned);
  for (const auto& br : m.block_range)
    if (br[1] > br[0]) r.runs.push_back({br[0], br[1], kElementOwned});
  r.owned_elements = m.num_elements;
  return r;
}

}  // namespace cosim::solid
