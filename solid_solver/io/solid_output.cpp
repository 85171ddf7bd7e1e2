#include "solid_solver/io/solid_output.h"

#include <vector>

#include "solid_solver/materials/strength.h"

namespace cosim::solid {

void write_snapshot(io::SnapshotSeries& series, const Simulation& sim) {
  const Mesh& m = sim.mesh();
  const State& st = sim.state();
  const int ne = m.num_elements;
  std::vector<std::int64_t> conn(m.conn.begin(), m.conn.end());
  std::vector<double> rho(ne), e(ne), sig(static_cast<std::size_t>(ne) * 6), vm(ne), blk(ne);
  for (int z = 0; z < ne; ++z) {
    rho[z] = st.emass[z] / st.vol[z];
    e[z] = st.ie[z] / st.emass[z];
    const double* s = &st.s[static_cast<std::size_t>(z) * 6];
    const double pq = st.p[z] + st.q[z];
    double* o = &sig[static_cast<std::size_t>(z) * 6];  // writer order: xx, xy, xz, yy, yz, zz
    o[0] = s[0] - pq;
    o[1] = s[3];
    o[2] = s[5];
    o[3] = s[1] - pq;
    o[4] = s[4];
    o[5] = s[2] - pq;
    vm[z] = von_mises(s);
    blk[z] = m.element_block[z];
  }
  io::UnstructuredGrid g{m.dim, st.x.data(), m.num_nodes, conn.data(), ne, m.npe};
  std::vector<io::FieldView> f = {
      {"velocity", st.v.data(), m.dim, io::Center::Node},
      {"density", rho.data(), 1, io::Center::Cell},
      {"pressure", st.p.data(), 1, io::Center::Cell},
      {"viscosity", st.q.data(), 1, io::Center::Cell},
      {"energy", e.data(), 1, io::Center::Cell},
      {"sound_speed", st.c.data(), 1, io::Center::Cell},
      {"stress", sig.data(), 6, io::Center::Cell},
      {"von_mises", vm.data(), 1, io::Center::Cell},
      {"plastic_strain", st.eps_p.data(), 1, io::Center::Cell},
      {"block", blk.data(), 1, io::Center::Cell},
  };
  series.write(sim.time(), sim.steps(), g, f);
}

nlohmann::json energy_json(const EnergyBudget& e) {
  return {{"internal", e.internal},
          {"kinetic", e.kinetic},
          {"total", e.total()},
          {"boundary_work", e.boundary_work},
          {"ale_inflow", e.ale_inflow}};
}

}  // namespace cosim::solid
