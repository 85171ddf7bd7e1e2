#include "fluid_solver/io/fluid_output.h"

#include <fmt/format.h>

#include "common/io/atomic_file.h"

namespace cosim::fluid {

void write_snapshot(io::SnapshotSeries& series, const FluidSimulation& sim) {
  write_snapshot(series, sim, sim.interface_segments_csv());
}

SnapshotFields::SnapshotFields(const FluidSimulation& sim) {
  const FluidScene& s = sim.scene();
  const int np = s.num_phases();
  for (int k = 0; k < np; ++k) ph.push_back(sim.phase_fields(k));
  for (int k = 0; k < np; ++k) {
    const std::string& n = s.phases[k].name;
    if (np > 1) views.push_back({n + "_alpha", ph[k].alpha.data(), 1, io::Center::Cell});
    views.push_back({n + "_density", ph[k].rho.data(), 1, io::Center::Cell});
    views.push_back({n + "_velocity", ph[k].velocity.data(), 3, io::Center::Cell});
    views.push_back({n + "_pressure", ph[k].p.data(), 1, io::Center::Cell});
    views.push_back({n + "_temperature", ph[k].T.data(), 1, io::Center::Cell});
    if (!ph[k].theta.empty()) views.push_back({n + "_granular_temperature", ph[k].theta.data(), 1, io::Center::Cell});
  }
  if (np > 1) {
    const std::size_t n = ph[0].rho.size();
    mrho.assign(n, 0.0);
    mvel.assign(3 * n, 0.0);
    mp.assign(n, 0.0);
    for (std::size_t c = 0; c < n; ++c) {
      for (int k = 0; k < np; ++k) {
        const double m = ph[k].alpha[c] * ph[k].rho[c];
        mrho[c] += m;
        for (int d = 0; d < 3; ++d) mvel[3 * c + d] += m * ph[k].velocity[3 * c + d];
        mp[c] += ph[k].alpha[c] * ph[k].p[c];
      }
      for (int d = 0; d < 3; ++d) mvel[3 * c + d] /= mrho[c];
    }
    views.push_back({"mixture_density", mrho.data(), 1, io::Center::Cell});
    views.push_back({"mixture_velocity", mvel.data(), 3, io::Center::Cell});
    views.push_back({"mixture_pressure", mp.data(), 1, io::Center::Cell});
  }
  if (sim.embedded().active) {  // cell categories of paper Table 1 (0 fluid .. 4 solid), for inspection
    kind = sim.embedded_categories();
    views.push_back({"embedded_category", kind.data(), 1, io::Center::Cell});
  }
}

std::size_t SnapshotFields::values_per_cell() const {
  std::size_t n = 0;
  for (const io::FieldView& v : views) n += static_cast<std::size_t>(v.ncomp);
  return n;
}

std::size_t snapshot_values_per_cell(const FluidScene& s) {
  const bool embedded_active = s.coupled || !s.embedded.bodies.empty();
  const std::size_t np = static_cast<std::size_t>(s.num_phases());
  const bool granular = np == 2 && s.exchange.dispersed && s.exchange.granular.enabled;
  const std::size_t per_phase = (np > 1 ? 1 : 0) + 1 + 3 + 1 + 1;  // alpha, density, velocity, pressure, T
  return np * per_phase + (granular ? 1 : 0) + (np > 1 ? 1 + 3 + 1 : 0) + (embedded_active ? 1 : 0);
}

io::UniformGrid snapshot_grid(const FluidScene& s) {
  io::UniformGrid g{s.dim, s.cells, s.lower, {1, 1, 1}};
  for (int d = 0; d < s.dim; ++d) g.spacing[d] = (s.upper[d] - s.lower[d]) / s.cells[d];
  return g;
}

void write_snapshot(io::SnapshotSeries& series, const FluidSimulation& sim, const std::string& segments) {
  const FluidScene& s = sim.scene();
  const SnapshotFields fields(sim);
  const io::UniformGrid g = snapshot_grid(s);
  const std::size_t index = series.count();
  const std::filesystem::path h5 = series.write(sim.time(), sim.steps(), g, fields.views);
  if (index == 0) io::remove_numbered_files(h5.parent_path(), "fluid_interface_", ".csv");  // an earlier run's
  if (!segments.empty())  // the embedded interface of this snapshot (ParaView: CSV reader + Table To Points)
    io::write_file_atomically(h5.parent_path() / fmt::format("fluid_interface_{:06d}.csv", index), segments);
}

nlohmann::json totals_json(const FluidScene& scene, const std::vector<PhaseTotals>& totals) {
  nlohmann::json arr = nlohmann::json::array();
  for (std::size_t k = 0; k < totals.size(); ++k) {
    const auto& t = totals[k];
    arr.push_back({{"phase", scene.phases[k].name},
                   {"mass", t.mass},
                   {"momentum", {t.momentum[0], t.momentum[1], t.momentum[2]}},
                   {"energy", t.energy}});
  }
  return arr;
}

}  // namespace cosim::fluid
