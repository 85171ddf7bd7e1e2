#include "solid_solver/ale/rezone.h"

namespace cosim::solid {

void rezone(const Mesh& m, const AleMesh& a, int sweeps, std::vector<double>& disp, std::vector<double>& x) {
  const int D = m.dim, nn = m.num_nodes;
  // Boundary values: Lagrangian nodes keep where the step put them, exterior relaxed nodes their start.
  for (int n = 0; n < nn; ++n)
    for (int d = 0; d < D; ++d) {
      const std::size_t i = static_cast<std::size_t>(n) * D + d;
      if (!a.relaxed_node[n]) disp[i] = x[i] - m.x0[i];
      else if (a.exterior_node[n]) disp[i] = 0.0;
    }
  std::vector<double> next(disp);
  for (int s = 0; s < sweeps; ++s) {
    for (int n = 0; n < nn; ++n) {
      if (!a.relaxed_node[n] || a.exterior_node[n]) continue;
      const int lo = a.neighbour_offset[n], hi = a.neighbour_offset[n + 1];
      for (int d = 0; d < D; ++d) {
        double sum = 0;
        for (int k = lo; k < hi; ++k) sum += disp[static_cast<std::size_t>(a.neighbours[k]) * D + d];
        next[static_cast<std::size_t>(n) * D + d] = sum / (hi - lo);
      }
    }
    disp.swap(next);
  }
  for (int n = 0; n < nn; ++n)
    if (a.relaxed_node[n])
      for (int d = 0; d < D; ++d) {
        const std::size_t i = static_cast<std::size_t>(n) * D + d;
        x[i] = m.x0[i] + disp[i];
      }
}

}  // namespace cosim::solid
