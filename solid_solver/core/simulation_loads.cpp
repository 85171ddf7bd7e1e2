// Loads on the solid from its boundaries and from the coupler: scene pressure and non-reflecting faces,
// per-face interface pressures, and the interface normal velocities of wetted faces (Simulation members;
// the time step itself is in simulation.cpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "solid_solver/core/simulation.h"
#include "solid_solver/mesh/element_faces.h"

namespace cosim::solid {

// Pressure p on a face: force -p A n (A n: mesh/element_faces.h), split equally over its nodes (exact for
// planar faces).
void Simulation::apply_pressure_loads() {
  const int D = mesh_.dim;
  for (int n : loaded_nodes_)
    for (int d = 0; d < D; ++d) st_.fext[static_cast<std::size_t>(n) * D + d] = 0.0;
  const double* x = st_.x.data();
  const int k = mesh_.face_nodes();
  for (const auto& L : loads_) {
    const double p0 = L.pressure * (L.ramp > 0 ? std::min(1.0, t_ / L.ramp) : 1.0);
    for (const auto& f : *L.faces) {
      double an[3];
      face_area_vector(D, x, f.nodes, an);
      double p = p0;
      if (L.absorbing) p += absorbing_pressure(f, an);
      for (int q = 0; q < k; ++q)
        for (int d = 0; d < D; ++d) st_.fext[static_cast<std::size_t>(f.nodes[q]) * D + d] -= p / k * an[d];
    }
  }
  // Pressures from outside (the coupler), per exterior face.
  for (std::size_t i = 0; i < face_p_.size(); ++i) {
    std::array<int, 4> fn{-1, -1, -1, -1};
    for (int q = 0; q < k; ++q) fn[q] = faces_.nodes[i * k + q];
    double an[3];
    face_area_vector(D, x, fn, an);
    const double w = face_p_[i] / k;
    for (int q = 0; q < k; ++q)
      for (int d = 0; d < D; ++d) st_.fext[static_cast<std::size_t>(fn[q]) * D + d] -= w * an[d];
  }
}

// rho c (v . n) of a non-reflecting face: the face's mean velocity (v^{n-1/2}) along its unit outward normal,
// times the impedance of the element behind it.
double Simulation::absorbing_pressure(const BoundaryFace& f, const double* an) const {
  const int D = mesh_.dim, k = mesh_.face_nodes();
  double vn = 0, a2 = 0;
  for (int d = 0; d < D; ++d) {
    double vd = 0;
    for (int q = 0; q < k; ++q) vd += st_.v[static_cast<std::size_t>(f.nodes[q]) * D + d] / k;
    vn += vd * an[d];
    a2 += an[d] * an[d];
  }
  const int e = f.element;
  return a2 > 0 ? st_.emass[e] / st_.vol[e] * st_.c[e] * vn / std::sqrt(a2) : 0.0;
}

const BoundaryFaces& Simulation::boundary_faces() {
  if (!faces_built_) {
    faces_ = make_boundary_faces(mesh_);
    faces_built_ = true;
  }
  std::vector<char> rigid(scene_.blocks.size(), 0);
  for (std::size_t b = 0; b < scene_.blocks.size(); ++b) rigid[b] = scene_.blocks[b].rigid ? 1 : 0;
  update_boundary_faces(faces_, st_, rigid);
  return faces_;
}

void Simulation::set_face_pressures(const std::vector<double>& p) {
  if (!faces_built_) boundary_faces();
  if (!p.empty() && static_cast<int>(p.size()) != faces_.count)
    throw std::invalid_argument(
        fmt::format("set_face_pressures: {} values for {} exterior faces", p.size(), faces_.count));
  face_p_ = p;
  if (p.empty())  // the loads of the scene (if any) are rebuilt every cycle
    for (int n : loaded_nodes_)
      for (int d = 0; d < mesh_.dim; ++d) st_.fext[static_cast<std::size_t>(n) * mesh_.dim + d] = 0.0;
  // Mark the face nodes as loaded (their fext is rebuilt every cycle and enters the boundary work).
  for (int n : faces_.nodes) st_.bc_mask[n] |= kBcLoaded;
  loaded_nodes_.clear();
  for (int n = 0; n < mesh_.num_nodes; ++n)
    if (st_.bc_mask[n] & kBcLoaded) loaded_nodes_.push_back(n);
}

void Simulation::set_face_normal_velocities(const std::vector<double>& u, const std::vector<char>& wetted) {
  if (!faces_built_) boundary_faces();
  if (u.size() != static_cast<std::size_t>(faces_.count) || wetted.size() != u.size())
    throw std::invalid_argument(
        fmt::format("set_face_normal_velocities: {} velocities and {} flags for {} exterior "
                    "faces",
                    u.size(), wetted.size(), faces_.count));
  const int D = mesh_.dim, k = faces_.nodes_per_face;
  // Per node, the area-weighted normal equations of "v . n_f = u_f on every wetted face f":
  // N = sum A n n^T, c = sum A u n.
  std::vector<Eigen::Matrix3d> N(mesh_.num_nodes, Eigen::Matrix3d::Zero());
  std::vector<Eigen::Vector3d> c(mesh_.num_nodes, Eigen::Vector3d::Zero());
  std::vector<char> touched(mesh_.num_nodes, 0);
  for (int f = 0; f < faces_.count; ++f) {
    if (!wetted[f]) continue;
    Eigen::Vector3d nf = Eigen::Vector3d::Zero();
    for (int d = 0; d < D; ++d) nf[d] = faces_.normal[static_cast<std::size_t>(f) * D + d];
    const double A = faces_.area[f];
    for (int q = 0; q < k; ++q) {
      const int n = faces_.nodes[static_cast<std::size_t>(f) * k + q];
      N[n] += A * nf * nf.transpose();
      c[n] += A * u[f] * nf;
      touched[n] = 1;
    }
  }
  iface_.clear();
  const RankPart* part = links_ ? &links_->part() : nullptr;  // on several ranks, each sets the nodes it owns
  for (int n = 0; n < mesh_.num_nodes; ++n) {
    if (!touched[n] || (st_.bc_mask[n] & kBcRigid)) continue;
    if (part && part->node_owner[n] != part->rank) continue;
    // Pseudo-inverse over the directions the faces constrain (eigenvalues above 5% of the largest: faces
    // that are nearly parallel constrain one direction, not two). A node of one flat face gets u along n;
    // a corner gets the velocity that meets every face's condition; tangential directions stay free.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(N[n]);
    const double top = es.eigenvalues().maxCoeff();
    Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
    for (int i = 0; i < 3; ++i)
      if (es.eigenvalues()[i] > 0.05 * top)
        P += es.eigenvectors().col(i) * es.eigenvectors().col(i).transpose() / es.eigenvalues()[i];
    iface_.push_back({n, N[n], c[n], P});
  }
}

void Simulation::set_face_impedances(const std::vector<double>& z) {
  if (!faces_built_) boundary_faces();
  for (int n = 0; n < mesh_.num_nodes; ++n) st_.bc_mask[n] &= static_cast<std::uint8_t>(~kBcImpedance);
  for (auto& rb : rigid_) {
    for (auto& row : rb.added_K) row[0] = row[1] = row[2] = 0.0;
    rb.added_b[0] = rb.added_b[1] = rb.added_b[2] = 0.0;
    rb.added_torque[0] = rb.added_torque[1] = rb.added_torque[2] = 0.0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) rb.added_C[i][j] = rb.added_Krot[i][j] = 0.0;
  }
  robin_K_.clear();
  robin_b_.clear();
  if (z.empty()) return;
  if (static_cast<int>(z.size()) != faces_.count)
    throw std::invalid_argument(
        fmt::format("set_face_impedances: {} values for {} exterior faces", z.size(), faces_.count));
  const int D = mesh_.dim, k = faces_.nodes_per_face;
  robin_slot_.assign(mesh_.num_nodes, -1);
  for (int f = 0; f < faces_.count; ++f) {
    if (!(z[f] > 0.0)) continue;
    double nf[3] = {0, 0, 0}, v_sent = 0.0;
    for (int d = 0; d < D; ++d) {
      nf[d] = faces_.normal[static_cast<std::size_t>(f) * D + d];
      v_sent += faces_.velocity[static_cast<std::size_t>(f) * D + d] * nf[d];
    }
    const double w = faces_.area[f] / k * z[f];
    for (int q = 0; q < k; ++q) {
      const int n = faces_.nodes[static_cast<std::size_t>(f) * k + q];
      if (robin_slot_[n] < 0) {
        robin_slot_[n] = static_cast<int>(robin_b_.size() / 3);
        robin_K_.resize(robin_K_.size() + 9, 0.0);
        robin_b_.resize(robin_b_.size() + 3, 0.0);
        st_.bc_mask[n] |= kBcImpedance;
      }
      double* K = &robin_K_[9 * static_cast<std::size_t>(robin_slot_[n])];
      double* b = &robin_b_[3 * static_cast<std::size_t>(robin_slot_[n])];
      for (int i = 0; i < D; ++i) {
        b[i] += w * v_sent * nf[i];
        for (int j = 0; j < D; ++j) K[3 * i + j] += w * nf[i] * nf[j];
      }
    }
  }
  // Rigid blocks: the sums over their nodes act on the translation and, with their arms, on the rotation.
  for (auto& rb : rigid_)
    for (int n : rb.nodes) {
      if (robin_slot_[n] < 0) continue;
      const double* K = &robin_K_[9 * static_cast<std::size_t>(robin_slot_[n])];
      const double* b = &robin_b_[3 * static_cast<std::size_t>(robin_slot_[n])];
      for (int i = 0; i < 3; ++i) {
        rb.added_b[i] += b[i];
        for (int j = 0; j < 3; ++j) rb.added_K[i][j] += K[3 * i + j];
      }
      double r[3] = {0, 0, 0};
      for (int d = 0; d < D; ++d) r[d] = st_.x[static_cast<std::size_t>(n) * D + d] - rb.X[d];
      rb.added_torque[0] += r[1] * b[2] - r[2] * b[1];
      rb.added_torque[1] += r[2] * b[0] - r[0] * b[2];
      rb.added_torque[2] += r[0] * b[1] - r[1] * b[0];
      // [r]x K and [r]x K [r]x^T ([r]x v = r x v).
      const double X[3][3] = {{0, -r[2], r[1]}, {r[2], 0, -r[0]}, {-r[1], r[0], 0}};
      double XK[3][3] = {};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          for (int q = 0; q < 3; ++q) XK[i][j] += X[i][q] * K[3 * q + j];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          rb.added_C[i][j] += XK[i][j];
          for (int q = 0; q < 3; ++q) rb.added_Krot[i][j] += XK[i][q] * X[j][q];
        }
    }
}

void Simulation::share_boundary_state() {
  if (!links_ || links_->part().ranks == 1) return;
  const RankPart& part = links_->part();
  if (!faces_built_) {
    faces_ = make_boundary_faces(mesh_);
    faces_built_ = true;
  }
  if (shared_nodes_.empty() && faces_.count > 0) {
    std::vector<char> on_node(mesh_.num_nodes, 0), on_element(mesh_.num_elements, 0);
    for (int n : faces_.nodes) on_node[n] = 1;
    for (int z : faces_.element) on_element[z] = 1;
    for (int n = 0; n < mesh_.num_nodes; ++n)
      if (on_node[n]) shared_nodes_.push_back(n), shared_node_owner_.push_back(part.node_owner[n]);
    for (int z = 0; z < mesh_.num_elements; ++z)
      if (on_element[z]) shared_elements_.push_back(z), shared_element_owner_.push_back(part.element_part[z]);
  }
  const int D = mesh_.dim;
  // Nodes: x and v (2 D values each).
  shared_buf_.resize(shared_nodes_.size() * 2 * D);
  for (std::size_t i = 0; i < shared_nodes_.size(); ++i)
    for (int d = 0; d < D; ++d) {
      const std::size_t o = static_cast<std::size_t>(shared_nodes_[i]) * D + d;
      shared_buf_[i * 2 * D + d] = st_.x[o];
      shared_buf_[i * 2 * D + D + d] = st_.v[o];
    }
  links_->gather_owned(shared_buf_, 2 * D, shared_node_owner_, true);
  for (std::size_t i = 0; i < shared_nodes_.size(); ++i)
    for (int d = 0; d < D; ++d) {
      const std::size_t o = static_cast<std::size_t>(shared_nodes_[i]) * D + d;
      st_.x[o] = shared_buf_[i * 2 * D + d];
      st_.v[o] = shared_buf_[i * 2 * D + D + d];
    }
  // Elements: vol, p, q, c and the 6 deviatoric stresses (10 values each).
  constexpr int E = 10;
  shared_buf_.resize(shared_elements_.size() * E);
  for (std::size_t i = 0; i < shared_elements_.size(); ++i) {
    const auto z = static_cast<std::size_t>(shared_elements_[i]);
    double* b = &shared_buf_[i * E];
    b[0] = st_.vol[z], b[1] = st_.p[z], b[2] = st_.q[z], b[3] = st_.c[z];
    for (int k = 0; k < 6; ++k) b[4 + k] = st_.s[z * 6 + k];
  }
  links_->gather_owned(shared_buf_, E, shared_element_owner_, true);
  for (std::size_t i = 0; i < shared_elements_.size(); ++i) {
    const auto z = static_cast<std::size_t>(shared_elements_[i]);
    const double* b = &shared_buf_[i * E];
    st_.vol[z] = b[0], st_.p[z] = b[1], st_.q[z] = b[2], st_.c[z] = b[3];
    for (int k = 0; k < 6; ++k) st_.s[z * 6 + k] = b[4 + k];
  }
}

void Simulation::apply_interface_velocities() {
  const int D = mesh_.dim;
  double wb = 0;
  for (const InterfaceNode& in : iface_) {
    double* v = &st_.v[static_cast<std::size_t>(in.node) * D];
    Eigen::Vector3d vv = Eigen::Vector3d::Zero();
    for (int d = 0; d < D; ++d) vv[d] = v[d];
    const Eigen::Vector3d dv = in.pinv * (in.c - in.N * vv);  // least-squares correction in the constrained directions
    double e_old = 0, e_new = 0;
    for (int d = 0; d < D; ++d) {
      e_old += v[d] * v[d];
      if (!(st_.bc_mask[in.node] & (1u << d))) v[d] += dv[d];
      e_new += v[d] * v[d];
    }
    wb += 0.5 * st_.mass[in.node] * (e_new - e_old);
  }
  wb_ += wb;
  ke_ += wb;
  iface_.clear();
}

}  // namespace cosim::solid
