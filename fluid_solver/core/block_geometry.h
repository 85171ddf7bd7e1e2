// The embedded geometry of one block of a split mesh (embedded_block.h), for the scene's bodies (embedded_bodies.h)
// and a coupled run's interface (coupled/coupled_boundary.cpp): the surface cut over the block and its margin, the
// samples of the faces the block samples with the cells of other blocks they read, and the records restricted to the
// block with its far cells. Every block makes every call together; the blocks agree on a failure before each
// exchange (no block waits in one for a block that failed).
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "fluid_solver/core/block_links.h"
#include "fluid_solver/core/embedded_block.h"
#include "fluid_solver/core/grid.h"
#include "fluid_solver/core/simulation.h"
#include "fluid_solver/embedded/geometry.h"
#include "fluid_solver/interface/interface_samples.h"

namespace cosim::fluid {

template <int DIM>
class BlockGeometry {
 public:
  // Which of the faces this block samples, from the cut geometry.
  using Choice = std::function<std::vector<char>(const embedded::EmbeddedGeometry<DIM>&)>;

  BlockGeometry(const Grid<DIM>& block, const embedded::GeometryOptions& opt)
      : block_(block), g_(margin_grid(block)), opt_(opt) {
    want_block_records(g_, block_, opt_.image);
  }
  void set_links(BlockLinks* links) { links_ = links; }
  const Grid<DIM>& grid() const { return g_; }
  const embedded::EmbeddedGeometry<DIM>& geometry() const { return geo_; }
  // Which faces of the last cut this block samples.
  const std::vector<char>& sampled() const { return sampled_; }

  // Cuts `surface` over the margin grid; with `faces` (kept until the next cut), the faces `choose` picks are this
  // block's to sample: every cell their samples may read beyond the block is planned.
  void cut(const embedded::Surface& surface, const coupling::Faces* faces = nullptr, const Choice& choose = {}) {
    std::string error;
    try {
      embedded::build_geometry<DIM>(g_, surface, opt_, geo_);
      if (faces) plan_samples(*faces, choose(geo_));
    } catch (const std::exception& e) { error = e.what(); }
    agree(error);
  }

  // The samples of the faces this block samples (the others not wetted), from its cells and the other blocks'.
  coupling::FluidSamples samples(const FluidSimulation& sim, const interface::SampleOptions& opt = {}) {
    exchange_samples(sim);
    coupling::FluidSamples smp;
    std::string error;
    try {
      smp = interface::sample_faces<DIM>(
          block_, [&](const std::array<int, 3>& c) { return is_flow_cell(geo_.category[margin_index(c)]); },
          [&](const std::array<int, 3>* c, int count, CellSample* out) { sample_states(sim, c, count, out); },
          sim.scene(), faces_, &sampled_, opt);
    } catch (const std::exception& e) { error = e.what(); }
    agree(error);
    return smp;
  }

  // The records of the cut for the solver (to_embedded_state's wall speeds and pressures per surface face),
  // restricted to the block, its far cells planned.
  template <class ToState>
  EmbeddedState state(ToState&& to_state) {
    std::vector<std::array<int, 3>> far;
    EmbeddedState st;
    std::string error;
    try {
      st = restrict_to_block<DIM>(to_state(g_, geo_), g_, block_, far);
    } catch (const std::exception& e) { error = e.what(); }
    agree(error);
    // The x rows take the blocked-face path wherever the whole mesh has a blocked face along x (solver_sweep.h):
    // the same sums in the same order as on one rank, also on a block that has none.
    st.blocked_x = links_->any(!st.blocked[0].empty());
    links_->plan_far(0, far);
    return st;
  }

  // Every block's samples of the faces it samples (`mine`: those of `owned`), merged on every block: face f from the
  // block that owns it.
  coupling::FluidSamples merge_samples(const coupling::FluidSamples& mine, const std::vector<char>& owned) {
    std::string pack;
    const std::size_t np = static_cast<std::size_t>(mine.phases);
    const auto put = [&](const void* p, std::size_t n) { pack.append(static_cast<const char*>(p), n); };
    for (int f = 0; f < mine.count; ++f) {
      const std::size_t uf = static_cast<std::size_t>(f);
      if (!owned[uf]) continue;
      put(&f, sizeof f);
      put(&mine.wetted[uf], 1);
      for (const std::vector<double>* v :
           {&mine.alpha, &mine.rho, &mine.normal_velocity, &mine.pressure, &mine.impedance})
        put(v->data() + uf * np, np * sizeof(double));
    }
    coupling::FluidSamples all = mine;
    for (const std::string& part : links_->texts_of_blocks(pack)) {
      const char* p = part.data();
      const char* end = p + part.size();
      while (p < end) {
        int f = 0;
        std::memcpy(&f, p, sizeof f);
        p += sizeof f;
        const std::size_t uf = static_cast<std::size_t>(f);
        all.wetted[uf] = *p++;
        for (std::vector<double>* v : {&all.alpha, &all.rho, &all.normal_velocity, &all.pressure, &all.impedance}) {
          std::memcpy(v->data() + uf * np, p, np * sizeof(double));
          p += np * sizeof(double);
        }
      }
    }
    return all;
  }

  // The faces whose centre lies in the block's cells (a centre outside the mesh: the cell nearest to it): each face
  // has one such block.
  std::vector<char> faces_centred_here(const coupling::Faces& faces) const {
    std::vector<char> here(static_cast<std::size_t>(faces.count), 0);
    for (int f = 0; f < faces.count; ++f) {
      bool in = true;
      for (int d = 0; d < DIM && d < faces.dim; ++d) {
        const double x = faces.centre[static_cast<std::size_t>(f * faces.dim + d)];
        const int c =
            std::clamp(static_cast<int>(std::floor((x - block_.lower[d]) / block_.dx[d])), 0, block_.mesh[d] - 1);
        in = in && c >= block_.first[d] && c < block_.first[d] + block_.n[d];
      }
      here[static_cast<std::size_t>(f)] = in ? 1 : 0;
    }
    return here;
  }

 private:
  void agree(const std::string& error) {
    if (links_->any(!error.empty()))
      throw std::runtime_error(error.empty() ? "another block could not build its embedded geometry" : error);
  }

  // The padded index in the margin grid of global cell c; a cell beyond it is an error (embedded/reach.h).
  std::size_t margin_index(const std::array<int, 3>& c) const {
    std::array<int, 3> l{0, 0, 0};
    for (int d = 0; d < DIM; ++d) {
      l[d] = c[d] - g_.first[d];
      if (l[d] < -Grid<DIM>::NG || l[d] >= g_.n[d] + Grid<DIM>::NG)
        throw embedded::ReachError(fmt::format(
            "embedded geometry: a wall pressure sample reads cell {} along axis {}, beyond the cells [{}, {}) this "
            "block's geometry holds (fluid_solver/embedded/reach.h)",
            c[d], d, g_.first[d] - Grid<DIM>::NG, g_.first[d] + g_.n[d] + Grid<DIM>::NG));
    }
    return g_.index(l[0], l[1], l[2]);
  }
  bool interior(const std::array<int, 3>& c) const {
    for (int d = 0; d < DIM; ++d)
      if (c[d] < block_.first[d] || c[d] >= block_.first[d] + block_.n[d]) return false;
    return true;
  }
  static bool mesh_order(const std::array<int, 3>& a, const std::array<int, 3>& b) {
    return a[2] != b[2] ? a[2] < b[2] : a[1] != b[1] ? a[1] < b[1] : a[0] < b[0];
  }

  // The faces to sample and every cell their samples may read beyond the block's cells.
  void plan_samples(const coupling::Faces& faces, std::vector<char> sampled) {
    faces_ = faces;
    sampled_ = std::move(sampled);
    sample_far_.clear();
    std::array<std::array<int, 3>, 1 << DIM> cells{};
    std::array<double, 1 << DIM> w{};
    for (int f = 0; f < faces.count; ++f)
      if (sampled_[static_cast<std::size_t>(f)])
        interface::sample_points<DIM>(block_, faces, f, interface::SampleOptions{},
                                      [&](const std::array<double, 3>& x) {
                                        interface::sample_stencil<DIM>(block_, x, cells, w);
                                        for (const auto& c : cells)
                                          if (!interior(c)) sample_far_.push_back(c);
                                      });
    std::sort(sample_far_.begin(), sample_far_.end(), mesh_order);
    sample_far_.erase(std::unique(sample_far_.begin(), sample_far_.end()), sample_far_.end());
  }

  // The states of the sampled cells of other blocks (channel 1), and those of this block's cells they asked for.
  void exchange_samples(const FluidSimulation& sim) {
    const std::vector<std::size_t>& send = links_->plan_far(1, sample_far_);
    const int np = sim.scene().num_phases();
    std::vector<CellSample> st(static_cast<std::size_t>(np));
    std::vector<double> out(send.size() * kPerPhase * np);
    for (std::size_t i = 0; i < send.size(); ++i) {
      sim.cell_states(&send[i], 1, st.data());
      for (int k = 0; k < np; ++k) {
        const CellSample& c = st[static_cast<std::size_t>(k)];
        double* o = out.data() + (i * np + k) * kPerPhase;
        o[0] = c.alpha, o[1] = c.rho, o[2] = c.p, o[3] = c.c;
        o[4] = c.velocity[0], o[5] = c.velocity[1], o[6] = c.velocity[2], o[7] = c.granular;
      }
    }
    sample_values_.resize(sample_far_.size() * kPerPhase * np);
    links_->exchange_far(1, out.data(), sample_values_.data(), kPerPhase * np);
  }

  // States of global cells for the samples: the block's own, or those exchange_samples brought.
  void sample_states(const FluidSimulation& sim, const std::array<int, 3>* c, int count, CellSample* out) const {
    const int np = sim.scene().num_phases();
    for (int q = 0; q < count; ++q) {
      CellSample* o = out + static_cast<std::ptrdiff_t>(q) * np;
      if (interior(c[q])) {
        const std::size_t idx =
            block_.index(c[q][0] - block_.first[0], c[q][1] - block_.first[1], c[q][2] - block_.first[2]);
        sim.cell_states(&idx, 1, o);
        continue;
      }
      const auto it = std::lower_bound(sample_far_.begin(), sample_far_.end(), c[q], mesh_order);
      if (it == sample_far_.end() || *it != c[q])
        throw std::logic_error("embedded geometry: a wall pressure sample reads a cell it did not ask for");
      const double* v = sample_values_.data() + static_cast<std::size_t>(it - sample_far_.begin()) * kPerPhase * np;
      for (int k = 0; k < np; ++k, v += kPerPhase) {
        o[k].alpha = v[0], o[k].rho = v[1], o[k].p = v[2], o[k].c = v[3];
        o[k].velocity = {v[4], v[5], v[6]};
        o[k].granular = v[7];
      }
    }
  }

  static constexpr int kPerPhase = 8;  // CellSample: alpha, rho, p, c, velocity[3], granular
  Grid<DIM> block_;                    // the solver's cells
  Grid<DIM> g_;                        // the geometry's: the block and its margin (margin_grid)
  embedded::GeometryOptions opt_;
  embedded::EmbeddedGeometry<DIM> geo_;
  BlockLinks* links_ = nullptr;
  coupling::Faces faces_;                       // the faces of the last cut
  std::vector<char> sampled_;                   // and which of them
  std::vector<std::array<int, 3>> sample_far_;  // cells of other blocks their samples read (mesh order)
  std::vector<double> sample_values_;           // and their states (kPerPhase values per phase)
};

}  // namespace cosim::fluid
