// Simulation::save_state / restore_state: the solid's evolving state for checkpoints (every State array, the
// clocks, the energy sums, the ALE displacement and the rigid bodies' motion), so that a restored solid continues
// bit for bit. What the coupler's last InterfaceStates set (face pressures, impedances, interface velocities) is
// not stored here: the coupled runner keeps those states in its part and sets them again after the restore.
#include <fmt/format.h>

#include "solid_solver/core/simulation.h"

namespace cosim::solid {

namespace {
using checkpoint::PartReader;
using checkpoint::PartWriter;

// The State arrays by name, the same list for writing and reading.
template <class S, class F>
void for_each_array(S& st, F&& f) {
  f("x", st.x);
  f("v", st.v);
  f("vbar", st.vbar);
  f("mass", st.mass);
  f("fext", st.fext);
  f("bc_value", st.bc_value);
  f("bc_ramp", st.bc_ramp);
  f("emass", st.emass);
  f("vol", st.vol);
  f("ie", st.ie);
  f("p", st.p);
  f("q", st.q);
  f("c", st.c);
  f("s", st.s);
  f("eps_p", st.eps_p);
  f("w_p", st.w_p);
  f("fc", st.fc);
}
}  // namespace

void Simulation::save_state(PartWriter& w) const {
  for_each_array(st_, [&](const char* name, const std::vector<double>& v) { w.put(std::string("solid.") + name, v); });
  w.put("solid.bc_mask", st_.bc_mask);
  w.put_scalar("solid.time", t_);
  w.put_scalar("solid.last_dt", last_dt_);
  w.put_scalar("solid.dt_elem", dt_elem_);
  w.put_integer("solid.steps", steps_);
  w.put_scalar("solid.ie_sum", ie_sum_);
  w.put_scalar("solid.ke", ke_);
  w.put_scalar("solid.wb", wb_);
  w.put("solid.ale_disp", ale_disp_);
  const double ale[6] = {ale_total_.mass,        ale_total_.energy,      ale_total_.momentum[0],
                         ale_total_.momentum[1], ale_total_.momentum[2], ale_total_.kinetic_to_internal};
  w.put("solid.ale_total", std::span<const double>(ale, 6));
  std::vector<double> rigid;  // per body: Q (9), X, V, L (3 each)
  for (const RigidBody& rb : rigid_) {
    for (const auto& row : rb.Q) rigid.insert(rigid.end(), row, row + 3);
    rigid.insert(rigid.end(), rb.X, rb.X + 3);
    rigid.insert(rigid.end(), rb.V, rb.V + 3);
    rigid.insert(rigid.end(), rb.L, rb.L + 3);
  }
  w.put("solid.rigid", rigid);
}

void Simulation::restore_state(const PartReader& r) {
  for_each_array(
      st_, [&](const char* name, std::vector<double>& v) { v = r.doubles(std::string("solid.") + name, v.size()); });
  st_.bc_mask = r.bytes("solid.bc_mask", st_.bc_mask.size());
  t_ = r.scalar("solid.time");
  last_dt_ = r.scalar("solid.last_dt");
  dt_elem_ = r.scalar("solid.dt_elem");
  steps_ = r.integer("solid.steps");
  ie_sum_ = r.scalar("solid.ie_sum");
  ke_ = r.scalar("solid.ke");
  wb_ = r.scalar("solid.wb");
  ale_disp_ = r.doubles("solid.ale_disp", ale_disp_.size());
  const std::vector<double> ale = r.doubles("solid.ale_total", 6);
  ale_total_.mass = ale[0];
  ale_total_.energy = ale[1];
  for (int d = 0; d < 3; ++d) ale_total_.momentum[d] = ale[2 + d];
  ale_total_.kinetic_to_internal = ale[5];
  const std::vector<double> rigid = r.doubles("solid.rigid", 18 * rigid_.size());
  const double* q = rigid.data();
  for (RigidBody& rb : rigid_) {
    for (auto& row : rb.Q)
      for (double& x : row) x = *q++;
    for (double* a : {rb.X, rb.V, rb.L})
      for (int d = 0; d < 3; ++d) a[d] = *q++;
  }
  loaded_nodes_.clear();  // as set_face_pressures leaves it, from the restored masks
  for (int n = 0; n < mesh_.num_nodes; ++n)
    if (st_.bc_mask[n] & kBcLoaded) loaded_nodes_.push_back(n);
  iface_.clear();
}

}  // namespace cosim::solid
