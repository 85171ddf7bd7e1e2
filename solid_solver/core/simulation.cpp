#include "solid_solver/core/simulation.h"

#include <Eigen/Dense>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "solid_solver/ale/rezone.h"
#include "solid_solver/core/robin_step.h"
#include "solid_solver/forces/element_kernel.h"
#include "solid_solver/mesh/element_faces.h"

namespace cosim::solid {

Mesh build_mesh(const SolidScene& s) {
  if (s.file_mesh) {
    for (std::size_t b = 0; b < s.blocks.size(); ++b)
      if (s.file_mesh->block_range[b][0] == s.file_mesh->block_range[b][1])
        throw std::runtime_error(fmt::format("block '{}' has no elements in {}", s.blocks[b].name, s.mesh_file));
    return *s.file_mesh;
  }
  Mesh m = make_box_mesh(s.dim, s.cells, s.lower, s.upper);
  m.block_names.clear();
  for (const auto& b : s.blocks) m.block_names.push_back(b.name);
  for (int e = 0; e < m.num_elements; ++e) {
    const auto c = element_centroid(m, m.x0, e);
    for (const auto& r : s.regions) {
      if (!r.contains(c, s.dim)) continue;
      for (std::size_t b = 0; b < s.blocks.size(); ++b)
        if (s.blocks[b].name == r.block) m.element_block[e] = static_cast<int>(b);
    }
  }
  finalize_mesh(m);
  for (std::size_t b = 0; b < s.blocks.size(); ++b)
    if (m.block_range[b][0] == m.block_range[b][1])
      throw std::runtime_error(
          fmt::format("block '{}' has no elements (no element centroid lies in its regions)", s.blocks[b].name));
  return m;
}

Simulation::Simulation(const SolidScene& scene) : scene_(scene), mesh_(build_mesh(scene)) { setup(); }

Simulation::Simulation(const SolidScene& scene, Mesh mesh) : scene_(scene), mesh_(std::move(mesh)) {
  if (mesh_.node_corner_offset.empty()) finalize_mesh(mesh_);
  if (mesh_.block_names.size() != scene_.blocks.size())
    throw std::runtime_error("mesh and scene disagree on the number of blocks");
  setup();
}

void Simulation::setup() {
  const int D = mesh_.dim, N = mesh_.npe, nn = mesh_.num_nodes, ne = mesh_.num_elements;
  st_.x = mesh_.x0;
  st_.v.assign(static_cast<std::size_t>(nn) * D, 0.0);
  st_.vbar.assign(st_.v.size(), 0.0);
  st_.mass.assign(nn, 0.0);
  st_.fext.assign(st_.v.size(), 0.0);
  st_.bc_mask.assign(nn, 0);
  st_.bc_value.assign(st_.v.size(), 0.0);
  st_.bc_ramp.assign(nn, 0.0);
  st_.emass.assign(ne, 0.0);
  st_.vol.assign(ne, 0.0);
  st_.ie.assign(ne, 0.0);
  st_.p.assign(ne, 0.0);
  st_.q.assign(ne, 0.0);
  st_.c.assign(ne, 0.0);
  st_.s.assign(static_cast<std::size_t>(ne) * 6, 0.0);
  st_.eps_p.assign(ne, 0.0);
  st_.w_p.assign(ne, 0.0);
  st_.fc.assign(static_cast<std::size_t>(ne) * N * D, 0.0);

  // Element mass, energy, deviator; nodal mass (lumped: M/npe per corner) and velocity
  // v0 + omega x (x - x_cm) of the block (x_cm: the block's centre of mass).
  std::vector<double> vsum(st_.v.size(), 0.0), msum(nn, 0.0);
  for (std::size_t b = 0; b < scene_.blocks.size(); ++b) {
    const BlockSpec& bs = scene_.blocks[b];
    const double rho = bs.material.density;
    const double e0 = bs.has_pressure ? bs.material.energy_from_pressure(rho, bs.pressure) : bs.energy;
    double cm[3] = {0, 0, 0}, mb = 0.0;
    for (int z = mesh_.block_range[b][0]; z < mesh_.block_range[b][1]; ++z) {
      double x[8][3] = {};
      const int* cn = &mesh_.conn[static_cast<std::size_t>(z) * N];
      double V;
      if (D == 2) {
        double x2[4][2], B2[4][2];
        for (int a = 0; a < 4; ++a)
          for (int d = 0; d < 2; ++d) x2[a][d] = st_.x[static_cast<std::size_t>(cn[a]) * 2 + d];
        V = element_b_matrix(x2, B2);
      } else {
        double B3[8][3];
        for (int a = 0; a < 8; ++a)
          for (int d = 0; d < 3; ++d) x[a][d] = st_.x[static_cast<std::size_t>(cn[a]) * 3 + d];
        V = element_b_matrix(x, B3);
      }
      const auto c = element_centroid(mesh_, st_.x, z);
      if (!(V > 0.0))
        throw std::runtime_error(
            fmt::format("element {} of block '{}' near ({:.6g}, {:.6g}, {:.6g}) is inverted or "
                        "degenerate (volume {:.6g})",
                        z, bs.name, c[0], c[1], c[2], V));
      st_.vol[z] = V;
      st_.emass[z] = rho * V;
      st_.ie[z] = e0 * rho * V;
      for (int k = 0; k < 6; ++k) st_.s[static_cast<std::size_t>(z) * 6 + k] = bs.deviator[k];
      mb += rho * V;
      for (int d = 0; d < D; ++d) cm[d] += rho * V * c[d];
    }
    for (int d = 0; d < D; ++d) cm[d] /= mb;
    const double* w = bs.angular_velocity.data();
    for (int z = mesh_.block_range[b][0]; z < mesh_.block_range[b][1]; ++z) {
      const int* cn = &mesh_.conn[static_cast<std::size_t>(z) * N];
      const double mc = st_.emass[z] / N;
      for (int a = 0; a < N; ++a) {
        double r[3] = {0, 0, 0};
        for (int d = 0; d < D; ++d) r[d] = st_.x[static_cast<std::size_t>(cn[a]) * D + d] - cm[d];
        const double wxr[3] = {w[1] * r[2] - w[2] * r[1], w[2] * r[0] - w[0] * r[2], w[0] * r[1] - w[1] * r[0]};
        msum[cn[a]] += mc;
        for (int d = 0; d < D; ++d) vsum[static_cast<std::size_t>(cn[a]) * D + d] += mc * (bs.velocity[d] + wxr[d]);
      }
    }
  }
  for (int n = 0; n < nn; ++n) {
    st_.mass[n] = msum[n];
    for (int d = 0; d < D; ++d)
      st_.v[static_cast<std::size_t>(n) * D + d] = vsum[static_cast<std::size_t>(n) * D + d] / msum[n];
  }

  // Energy deposits.
  for (const auto& dep : scene_.deposits) {
    if (dep.is_point) {
      int best = 0;
      double bd = 1e300;
      for (int z = 0; z < ne; ++z) {
        const auto c = element_centroid(mesh_, st_.x, z);
        double d2 = 0;
        for (int d = 0; d < D; ++d) d2 += (c[d] - dep.point[d]) * (c[d] - dep.point[d]);
        if (d2 < bd) {
          bd = d2;
          best = z;
        }
      }
      st_.ie[best] += dep.energy;
    } else {
      std::vector<int> in;
      double mtot = 0;
      for (int z = 0; z < ne; ++z) {
        const auto c = element_centroid(mesh_, st_.x, z);
        bool ok = true;
        for (int d = 0; d < D; ++d) ok = ok && c[d] >= dep.lower[d] && c[d] <= dep.upper[d];
        if (ok) {
          in.push_back(z);
          mtot += st_.emass[z];
        }
      }
      if (in.empty()) throw std::runtime_error("an energy deposit box contains no element centroid");
      for (int z : in) st_.ie[z] += dep.energy * st_.emass[z] / mtot;
    }
  }

  // Boundary conditions.
  for (const auto& bc : scene_.boundaries) {
    if (bc.kind == BcKind::Pressure || bc.kind == BcKind::NonReflecting) {
      auto it = mesh_.face_sets.find(bc.set);
      if (it == mesh_.face_sets.end()) throw std::runtime_error("no face set '" + bc.set + "' in the mesh");
      loads_.push_back({&it->second, bc.pressure, bc.ramp, bc.kind == BcKind::NonReflecting});
      for (const auto& f : it->second)
        for (int q = 0; q < mesh_.face_nodes(); ++q) st_.bc_mask[f.nodes[q]] |= kBcLoaded;
      continue;
    }
    std::vector<int> box_nodes;
    if (bc.node_box) {
      for (int n = 0; n < mesh_.num_nodes; ++n) {
        bool in = true;
        for (int d = 0; d < D; ++d) {
          const double xd = mesh_.x0[static_cast<std::size_t>(n) * D + d];
          const double tol = 1e-9 * (1.0 + std::abs(bc.upper[d] - bc.lower[d]));
          in = in && xd >= bc.lower[d] - tol && xd <= bc.upper[d] + tol;
        }
        if (in) box_nodes.push_back(n);
      }
      if (box_nodes.empty()) throw std::runtime_error("a boundary node box holds no node of the mesh");
    }
    auto it = bc.node_box ? mesh_.node_sets.end() : mesh_.node_sets.find(bc.set);
    if (!bc.node_box && it == mesh_.node_sets.end())
      throw std::runtime_error("no node set '" + bc.set + "' in the mesh");
    const std::vector<int>& nodes = bc.node_box ? box_nodes : it->second;
    int axis = -1;
    if (bc.kind == BcKind::Symmetry) {
      const auto fs = mesh_.face_sets.find(bc.set);
      if (fs != mesh_.face_sets.end()) axis = face_set_axis(mesh_, st_.x, fs->second);
      if (axis < 0)
        throw std::runtime_error(
            fmt::format("symmetry set '{}' is not one plane normal to x, y or z (only "
                        "axis-aligned symmetry planes are supported)",
                        bc.set));
    }
    for (int n : nodes) {
      for (int d = 0; d < D; ++d) {
        bool on = false;
        double val = 0.0;
        if (bc.kind == BcKind::Fixed) on = true;
        else if (bc.kind == BcKind::Symmetry) on = d == axis;  // box sides are axis-aligned planes
        else if (bc.component[d]) {
          on = true;
          val = bc.velocity[d];
        }
        if (on) {
          st_.bc_mask[n] |= static_cast<std::uint8_t>(1u << d);
          st_.bc_value[static_cast<std::size_t>(n) * D + d] = val;
        }
      }
      if (bc.kind == BcKind::Velocity) st_.bc_ramp[n] = bc.ramp;
    }
  }
  for (int n = 0; n < nn; ++n)
    if (st_.bc_mask[n] & kBcLoaded) loaded_nodes_.push_back(n);
  apply_boundary_conditions();

  // Rigid blocks: one rigid body each; their elements are skipped by the element pass (no stress, EOS,
  // viscosity or hourglass work), their energy stays constant.
  std::vector<int> rigid_owner(nn, -1);
  for (std::size_t b = 0; b < scene_.blocks.size(); ++b) {
    if (!scene_.blocks[b].rigid) continue;
    rigid_.push_back(make_rigid_body(mesh_, static_cast<int>(b), st_, rigid_owner));
    for (int z = mesh_.block_range[b][0]; z < mesh_.block_range[b][1]; ++z) rigid_ie_ += st_.ie[z];
  }

  // ALE gas blocks: the relaxed nodes and the faces they exchange through.
  if (!scene_.ale.blocks.empty()) {
    std::vector<char> relaxed(scene_.blocks.size(), 0);
    for (std::size_t b = 0; b < scene_.blocks.size(); ++b)
      for (const auto& name : scene_.ale.blocks) relaxed[b] |= scene_.blocks[b].name == name;
    ale_ = std::make_unique<AleMesh>(make_ale_mesh(mesh_, relaxed));
    ale_disp_.assign(st_.x.size(), 0.0);
  }

  // Initial element pass: stress, EOS, viscosity, corner forces and the stable step at t = 0.
  element_update(0.0);
  ke_ = 0.0;
  for (int n = 0; n < nn; ++n)
    for (int d = 0; d < D; ++d) {
      const double vv = st_.v[static_cast<std::size_t>(n) * D + d];
      ke_ += 0.5 * st_.mass[n] * vv * vv;
    }
}

void Simulation::apply_boundary_conditions() {
  const int D = mesh_.dim;
  for (int n = 0; n < mesh_.num_nodes; ++n) {
    const std::uint8_t m = st_.bc_mask[n];
    if (!(m & 7)) continue;
    const double r = st_.bc_ramp[n] > 0 ? std::min(1.0, t_ / st_.bc_ramp[n]) : 1.0;
    for (int d = 0; d < D; ++d)
      if (m & (1u << d))
        st_.v[static_cast<std::size_t>(n) * D + d] = r * st_.bc_value[static_cast<std::size_t>(n) * D + d];
  }
}

void Simulation::nodal_update(double dt) {
  if (!iface_.empty()) apply_interface_velocities();
  if (!loads_.empty() || !face_p_.empty()) apply_pressure_loads();
  // The nodes updated here: all of them, or with rank links the nodes this rank owns.
  const int* own = links_ ? links_->part().owned_nodes.data() : nullptr;
  const int nn = links_ ? static_cast<int>(links_->part().owned_nodes.size()) : mesh_.num_nodes;
  const int* off = mesh_.node_corner_offset.data();
  const int* corners = mesh_.node_corners.data();
  const double* fc = st_.fc.data();
  double* x = st_.x.data();
  double* v = st_.v.data();
  double* vb = st_.vbar.data();
  const double* mass = st_.mass.data();
  const double* fext = st_.fext.data();
  const std::uint8_t* mask = st_.bc_mask.data();
  const double* bval = st_.bc_value.data();
  const double* bramp = st_.bc_ramp.data();
  const double th = t_ + 0.5 * dt;
  double ke = 0.0, wb = 0.0;
  // One flat loop per dimension (D known at compile time).
  auto pass = [&](auto dim) {
    constexpr int D = decltype(dim)::value;
#pragma omp parallel for schedule(static) reduction(+ : ke, wb) if (nn > 4096)
    for (int i = 0; i < nn; ++i) {
      const int n = own ? own[i] : i;
      // The corners of a node lie in up to 2^D element rows far apart in memory, more streams than the
      // hardware prefetcher follows: ask for those of a node a few ahead.
      constexpr int ahead = 8;
      if (i + ahead < nn) {
        const int na = own ? own[i + ahead] : i + ahead;
        for (int k = off[na]; k < off[na + 1]; ++k)
          __builtin_prefetch(fc + static_cast<std::ptrdiff_t>(corners[k]) * D);
      }
      double F[3] = {0, 0, 0};
      for (int k = off[n]; k < off[n + 1]; ++k) {
        const double* f = fc + static_cast<std::ptrdiff_t>(corners[k]) * D;  // corner c = z N + a
        for (int d = 0; d < D; ++d) F[d] += f[d];
      }
      const std::uint8_t m = mask[n];
      if (m & kBcRigid) continue;  // moved with its rigid body below
      const double im = 1.0 / mass[n];
      const std::ptrdiff_t o = static_cast<std::ptrdiff_t>(n) * D;
      double vn[3], e_old = 0.0, e_new = 0.0, fw = 0.0;
      for (int d = 0; d < D; ++d) {
        const double Ft = (m & kBcLoaded) ? F[d] + fext[o + d] : F[d];
        vn[d] = v[o + d] + dt * Ft * im;
        if (m & (1u << d)) vn[d] = (bramp[n] > 0 ? std::min(1.0, th / bramp[n]) : 1.0) * bval[o + d];
      }
      if (m & kBcImpedance)  // the fluid's Robin condition, implicitly (robin_step.h)
        robin_step(D, mass[n], dt, m & 7u, &robin_K_[9 * robin_slot_[n]], &robin_b_[3 * robin_slot_[n]], v + o, vn);
      for (int d = 0; d < D; ++d) {
        const double vbar = 0.5 * (v[o + d] + vn[d]);
        e_old += v[o + d] * v[o + d];
        e_new += vn[d] * vn[d];
        fw += F[d] * vbar;
        vb[o + d] = vbar;
        v[o + d] = vn[d];
        x[o + d] += dt * vn[d];
      }
      ke += 0.5 * mass[n] * e_new;
      if (m) wb += 0.5 * mass[n] * (e_new - e_old) - dt * fw;
    }
  };
  if (mesh_.dim == 2) pass(std::integral_constant<int, 2>{});
  else pass(std::integral_constant<int, 3>{});
  advance_rigid_bodies(dt, th, ke, wb);
  ke_ = ke;
  wb_ += wb;
  if (links_) {  // the ghost nodes' new positions and velocities from their owners
    double* arrays[3] = {st_.x.data(), st_.v.data(), st_.vbar.data()};
    links_->exchange_ghost_nodes(arrays, mesh_.dim);
  }
}

// Rigid bodies: on several ranks, each node's force comes from its owner (every corner force of an owned node is
// computed there), then every rank moves the whole body alike, summing the forces in the body's node order; the
// body's kinetic energy and work are counted on rank 0.
void Simulation::advance_rigid_bodies(double dt, double t_half, double& ke, double& wb) {
  if (!links_) {
    for (auto& rb : rigid_) advance_rigid_body(rb, mesh_, st_, dt, t_half, ke, wb);
    return;
  }
  const RankPart& part = links_->part();
  double ke_rb = 0.0, wb_rb = 0.0;
  std::vector<int> owner;
  for (auto& rb : rigid_) {
    rigid_f_.resize(3 * rb.nodes.size());
    rigid_node_forces(rb, mesh_, st_, part.node_owner.data(), part.rank, rigid_f_.data());
    owner.resize(rb.nodes.size());
    for (std::size_t i = 0; i < rb.nodes.size(); ++i) owner[i] = part.node_owner[rb.nodes[i]];
    links_->gather_owned(rigid_f_, 3, owner, true);
    advance_rigid_body(rb, mesh_, st_, rigid_f_.data(), dt, t_half, ke_rb, wb_rb);
  }
  if (part.rank == 0) {
    ke += ke_rb;
    wb += wb_rb;
  }
}

void Simulation::element_update(double dt) {
  const int D = mesh_.dim;
  ElementPassArgs A{mesh_.conn.data(),
                    st_.x.data(),
                    st_.v.data(),
                    st_.vbar.data(),
                    st_.emass.data(),
                    st_.vol.data(),
                    st_.ie.data(),
                    st_.p.data(),
                    st_.q.data(),
                    st_.c.data(),
                    st_.s.data(),
                    st_.eps_p.data(),
                    st_.w_p.data(),
                    st_.fc.data(),
                    dt,
                    scene_.numerics.q_quadratic * scene_.numerics.q_quadratic,
                    scene_.numerics.q_linear,
                    scene_.numerics.hourglass,
                    0.0,
                    Strength{}};
  // R: the elements this rank owns (all on one rank); halo: those it computes for its nodes only (their energy is
  // counted and their failures reported by their owners).
  ElementPassResult R, halo;
  R.ie_sum = !links_ || links_->part().rank == 0 ? rigid_ie_ : 0.0;
  const auto pass = [&](std::size_t b, int lo, int hi, ElementPassResult& out) {
    const MaterialModel& mat = scene_.blocks[b].material;
    A.p_min = mat.p_min;
    A.strength = mat.strength;
    const bool str = mat.strength.enabled;
    auto run = [&](const auto& eos) {
      using E = std::decay_t<decltype(eos)>;
      if (D == 2) {
        if (str) element_pass<2, E, true>(A, eos, lo, hi, out);
        else element_pass<2, E, false>(A, eos, lo, hi, out);
      } else {
        if (str) element_pass<3, E, true>(A, eos, lo, hi, out);
        else element_pass<3, E, false>(A, eos, lo, hi, out);
      }
    };
    switch (mat.eos) {
      case EosKind::IdealGas: run(mat.ideal); break;
      case EosKind::LinearElastic: run(mat.linear); break;
      case EosKind::MieGruneisen: run(mat.mg); break;
    }
  };
  if (!links_) {
    for (std::size_t b = 0; b < scene_.blocks.size(); ++b)
      if (!scene_.blocks[b].rigid)  // the skip path: no stress, EOS, viscosity or hourglass work
        pass(b, mesh_.block_range[b][0], mesh_.block_range[b][1], R);
  } else {
    for (const RankPart::Run& r : links_->part().runs) {
      const auto b = static_cast<std::size_t>(mesh_.element_block[r.begin]);
      if (!scene_.blocks[b].rigid) pass(b, r.begin, r.end, r.role == kElementOwned ? R : halo);
    }
    R.dt_min = std::min(R.dt_min, halo.dt_min);
  }
  if (R.bad >= 0) {
    const int z = R.bad;
    const auto c = element_centroid(mesh_, st_.x, z);
    const auto& bn = mesh_.block_names[mesh_.element_block[z]];
    if (R.bad_kind == 1)
      throw StateError(
          fmt::format("element {} of block '{}' inverted at t = {:.9g} (step {}), centroid ({:.6g}, "
                      "{:.6g}, {:.6g}), previous volume {:.6g}, pressure {:.6g} Pa",
                      z, bn, t_ + dt, steps_ + 1, c[0], c[1], c[2], st_.vol[z], st_.p[z]));
    throw StateError(
        fmt::format("element {} of block '{}' has a non-finite state at t = {:.9g} (step {}), centroid "
                    "({:.6g}, {:.6g}, {:.6g}), energy {:.6g} J, pressure {:.6g} Pa",
                    z, bn, t_ + dt, steps_ + 1, c[0], c[1], c[2], st_.ie[z], st_.p[z]));
  }
  ie_sum_ = R.ie_sum;
  dt_elem_ = links_ ? links_->min_over_ranks(R.dt_min) : R.dt_min;
}

void Simulation::set_rank_links(RankLinks* links) {
  if (links && links->part().ranks > 1 && ale_)
    throw std::invalid_argument(
        "ALE blocks (solid.ale.blocks) run on one rank only: start solid_solver without mpirun (or with -np 1)");
  links_ = links;
  if (!links_ || links_->part().rank == 0) return;
  ie_sum_ = ke_ = wb_ = 0.0;  // rank 0 holds the totals so far
}

void Simulation::gather_state() {
  if (!links_) return;
  const RankPart& part = links_->part();
  const int D = mesh_.dim, N = mesh_.npe;
  for (std::vector<double>* a : {&st_.x, &st_.v, &st_.vbar, &st_.fext})
    links_->gather_owned(*a, D, part.node_owner, false);
  for (std::vector<double>* a : {&st_.vol, &st_.ie, &st_.p, &st_.q, &st_.c, &st_.eps_p, &st_.w_p})
    links_->gather_owned(*a, 1, part.element_part, false);
  links_->gather_owned(st_.s, 6, part.element_part, false);
  links_->gather_owned(st_.fc, N * D, part.element_part, false);
  // The energy sums too: rank 0 takes the totals, the others start again from zero (their sum is unchanged), so
  // that a checkpoint of rank 0's state holds the run's totals.
  double e[3] = {ie_sum_, ke_, wb_};
  links_->sum_over_ranks(e);
  if (part.rank == 0) {
    ie_sum_ = e[0];
    ke_ = e[1];
    wb_ = e[2];
  } else {
    ie_sum_ = ke_ = wb_ = 0.0;
  }
}

void Simulation::advance(double dt) {
  nodal_update(dt);
  element_update(dt);
  if (ale_ && (steps_ + 1) % scene_.ale.every == 0) ale_step();
  t_ += dt;
  last_dt_ = dt;
  ++steps_;
}

double Simulation::stable_dt() const {
  double dt = scene_.numerics.cfl * dt_elem_;
  if (steps_ == 0) {
    if (scene_.numerics.dt_initial > 0) dt = std::min(dt, scene_.numerics.dt_initial);
  } else {
    dt = std::min(dt, scene_.numerics.dt_growth * last_dt_);
  }
  return dt;
}

std::string Simulation::limiting_step() const {
  const int D = mesh_.dim;
  int worst = -1;
  double worst_dt = 1e300;
  for (int z = 0; z < mesh_.num_elements; ++z) {
    if (scene_.blocks[mesh_.element_block[z]].rigid) continue;
    if (links_ && links_->part().element_role[z] != kElementOwned) continue;  // another rank's
    const double L = D == 3 ? std::cbrt(std::max(st_.vol[z], 0.0)) : std::sqrt(std::max(st_.vol[z], 0.0));
    const double rho = st_.emass[z] / std::max(st_.vol[z], 1e-300);
    const double w = st_.c[z] + std::sqrt(std::max(st_.q[z], 0.0) / rho);
    const double dt = w > 0 ? L / w : 1e300;
    if (dt < worst_dt) {
      worst_dt = dt;
      worst = z;
    }
  }
  if (worst < 0) return "";
  const int z = worst;
  const auto c = element_centroid(mesh_, st_.x, z);
  return fmt::format(
      "element {} of block '{}' at ({:.6g}, {:.6g}, {:.6g}): size {:.4g} m, sound speed {:.4g} m/s, density "
      "{:.6g} kg/m^3, pressure {:.6g} Pa, viscosity {:.6g} Pa",
      z, mesh_.block_names[mesh_.element_block[z]], c[0], c[1], c[2],
      D == 3 ? std::cbrt(std::max(st_.vol[z], 0.0)) : std::sqrt(std::max(st_.vol[z], 0.0)), st_.c[z],
      st_.emass[z] / std::max(st_.vol[z], 1e-300), st_.p[z], st_.q[z]);
}

EnergyBudget Simulation::energy() const { return {ie_sum_, ke_, wb_, ale_total_.energy}; }

// ALE: rezone the relaxed nodes, remap the state onto the new mesh, and recompute the element state and corner
// forces there (an element update without a time step); the kinetic energy is that of the remapped velocities.
void Simulation::ale_step() {
  ale_x_lag_ = st_.x;
  rezone(mesh_, *ale_, scene_.ale.sweeps, ale_disp_, st_.x);
  const RemapFlux f = remap(mesh_, *ale_, ale_x_lag_, st_);
  ale_total_.mass += f.mass;
  ale_total_.energy += f.energy;
  for (int d = 0; d < 3; ++d) ale_total_.momentum[d] += f.momentum[d];
  ale_total_.kinetic_to_internal += f.kinetic_to_internal;
  element_update(0.0);
  const int D = mesh_.dim;
  ke_ = 0.0;
  for (int n = 0; n < mesh_.num_nodes; ++n)
    for (int d = 0; d < D; ++d)
      ke_ +=
          0.5 * st_.mass[n] * st_.v[static_cast<std::size_t>(n) * D + d] * st_.v[static_cast<std::size_t>(n) * D + d];
}

double Simulation::bytes_per_element() const {
  const double ne = mesh_.num_elements, nn = mesh_.num_nodes, D = mesh_.dim, N = mesh_.npe;
  const double node_bytes = nn * (8.0 * (5 * D + 2) + 1 + 4);  // x v vbar fext bc_value, mass, ramp, mask, offset
  const double elem_bytes = ne * (8.0 * (8 + 6 + N * D) + 4.0 * N + 4.0 + 4.0 * N);  // + conn, block, corners
  return (node_bytes + elem_bytes) / ne;
}

}  // namespace cosim::solid
