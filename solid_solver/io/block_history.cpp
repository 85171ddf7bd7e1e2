#include "solid_solver/io/block_history.h"

#include "common/checkpoint/output_resume.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "solid_solver/materials/strength.h"

namespace cosim::solid {

std::vector<BlockTotals> block_totals(const Simulation& sim) {
  const Mesh& m = sim.mesh();
  const State& st = sim.state();
  const int D = m.dim, N = m.npe;
  std::vector<BlockTotals> out(m.block_names.size());
  for (std::size_t b = 0; b < out.size(); ++b) {
    BlockTotals& t = out[b];
    for (int z = m.block_range[b][0]; z < m.block_range[b][1]; ++z) {
      const double mc = st.emass[z] / N;
      t.mass += st.emass[z];
      t.internal += st.ie[z];
      t.plastic_work += st.w_p[z];
      t.max_von_mises = std::max(t.max_von_mises, von_mises(&st.s[static_cast<std::size_t>(z) * 6]));
      t.max_plastic_strain = std::max(t.max_plastic_strain, st.eps_p[z]);
      for (int a = 0; a < N; ++a) {
        const double* v = &st.v[static_cast<std::size_t>(m.conn[static_cast<std::size_t>(z) * N + a]) * D];
        for (int d = 0; d < D; ++d) {
          t.momentum[d] += mc * v[d];
          t.kinetic += 0.5 * mc * v[d] * v[d];
        }
      }
    }
  }
  return out;
}

BlockHistory::BlockHistory(const std::filesystem::path& dir, const checkpoint::PartReader* resume) {
  const std::filesystem::path file = dir / "block_history.csv";
  if (resume) {
    out_ = checkpoint::resume_log(*resume, "block_history", file);
    last_step_ = resume->integer("block_history.last_step");
  } else {
    out_ = io::LineLog(file,
                       "time,step,block,mass,velocity_x,velocity_y,velocity_z,kinetic_energy,internal_energy,"
                       "plastic_work,max_von_mises,max_plastic_strain\n");
  }
}

void BlockHistory::save(checkpoint::PartWriter& w) const {
  checkpoint::put_log(w, "block_history", out_);
  w.put_integer("block_history.last_step", last_step_);
}

void BlockHistory::record(const Simulation& sim) {
  if (sim.steps() == last_step_) return;
  last_step_ = sim.steps();
  const auto totals = block_totals(sim);
  std::string rows;
  for (std::size_t b = 0; b < totals.size(); ++b) {
    const BlockTotals& t = totals[b];
    const double im = t.mass > 0 ? 1.0 / t.mass : 0.0;
    rows +=
        fmt::format("{:.12g},{},{},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g}\n",
                    sim.time(), sim.steps(), sim.mesh().block_names[b], t.mass, t.momentum[0] * im, t.momentum[1] * im,
                    t.momentum[2] * im, t.kinetic, t.internal, t.plastic_work, t.max_von_mises, t.max_plastic_strain);
  }
  out_.append(rows);  // the record's rows whole, or none of them
}

}  // namespace cosim::solid
