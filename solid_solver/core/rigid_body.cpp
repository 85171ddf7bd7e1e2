#include "solid_solver/core/rigid_body.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "solid_solver/core/robin_step.h"

namespace cosim::solid {

namespace {

using M3 = double[3][3];

void cross(const double* a, const double* b, double* c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

void matmul(const M3& a, const M3& b, M3& c) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
}

// Rotation by the vector w (angle t = |w| about k = w / |w|): R = 1 + sin(t) K + (1 - cos(t)) K^2 (Rodrigues).
// Returns R - 1, formed without cancellation so that (R - 1) r / dt stays accurate for tiny steps.
void rotation_minus_one(const double* w, M3& R) {
  const double t = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = 0.0;
  if (t == 0.0) return;
  const double k[3] = {w[0] / t, w[1] / t, w[2] / t};
  const M3 K = {{0, -k[2], k[1]}, {k[2], 0, -k[0]}, {-k[1], k[0], 0}};
  M3 K2;
  matmul(K, K, K2);
  const double s = std::sin(t), c1 = 2.0 * std::sin(0.5 * t) * std::sin(0.5 * t);  // 1 - cos t
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] += s * K[i][j] + c1 * K2[i][j];
}

// omega = I^{-1} L with the world inertia I = Q I0 Q^T (3D), or omega_z = L_z / I_zz (2D).
void angular_velocity(const RigidBody& rb, int dim, const M3& Q, const double* L, double* w) {
  w[0] = w[1] = w[2] = 0.0;
  if (dim == 2) {
    if (rb.I0[2][2] > 0.0) w[2] = L[2] / rb.I0[2][2];
    return;
  }
  M3 QI, I;
  matmul(Q, rb.I0, QI);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) I[i][j] = QI[i][0] * Q[j][0] + QI[i][1] * Q[j][1] + QI[i][2] * Q[j][2];
  // Cramer's rule (I is symmetric positive definite for a body with volume).
  const double c00 = I[1][1] * I[2][2] - I[1][2] * I[2][1], c01 = I[1][2] * I[2][0] - I[1][0] * I[2][2],
               c02 = I[1][0] * I[2][1] - I[1][1] * I[2][0];
  const double det = I[0][0] * c00 + I[0][1] * c01 + I[0][2] * c02;
  if (!(det > 0.0)) return;
  const double inv[3][3] = {{c00, I[0][2] * I[2][1] - I[0][1] * I[2][2], I[0][1] * I[1][2] - I[0][2] * I[1][1]},
                            {c01, I[0][0] * I[2][2] - I[0][2] * I[2][0], I[0][2] * I[1][0] - I[0][0] * I[1][2]},
                            {c02, I[0][1] * I[2][0] - I[0][0] * I[2][1], I[0][0] * I[1][1] - I[0][1] * I[1][0]}};
  for (int i = 0; i < 3; ++i) w[i] = (inv[i][0] * L[0] + inv[i][1] * L[1] + inv[i][2] * L[2]) / det;
}

}  // namespace

RigidBody make_rigid_body(const Mesh& m, int b, State& st, std::vector<int>& rigid_owner) {
  const int D = m.dim, N = m.npe;
  RigidBody rb;
  rb.block = b;
  for (int z = m.block_range[b][0]; z < m.block_range[b][1]; ++z)
    for (int a = 0; a < N; ++a) rb.nodes.push_back(m.conn[static_cast<std::size_t>(z) * N + a]);
  std::sort(rb.nodes.begin(), rb.nodes.end());
  rb.nodes.erase(std::unique(rb.nodes.begin(), rb.nodes.end()), rb.nodes.end());
  for (int n : rb.nodes) {
    if (rigid_owner[n] >= 0 && rigid_owner[n] != b)
      throw std::runtime_error(fmt::format("rigid blocks '{}' and '{}' share node {}: make them one block",
                                           m.block_names[rigid_owner[n]], m.block_names[b], n));
    rigid_owner[n] = b;
    st.bc_mask[n] |= kBcRigid;
  }
  // Mass, centre of mass, momentum.
  double P[3] = {0, 0, 0};
  for (int n : rb.nodes) {
    rb.mass += st.mass[n];
    for (int d = 0; d < D; ++d) {
      rb.X[d] += st.mass[n] * st.x[static_cast<std::size_t>(n) * D + d];
      P[d] += st.mass[n] * st.v[static_cast<std::size_t>(n) * D + d];
    }
  }
  for (int d = 0; d < D; ++d) {
    rb.X[d] /= rb.mass;
    rb.V[d] = P[d] / rb.mass;
  }
  // Body-frame positions, inertia tensor I0 = sum m (|r|^2 1 - r r^T), angular momentum sum m r x v.
  rb.r0.assign(rb.nodes.size() * 3, 0.0);
  for (std::size_t i = 0; i < rb.nodes.size(); ++i) {
    const int n = rb.nodes[i];
    double r[3] = {0, 0, 0}, v[3] = {0, 0, 0}, rxv[3];
    for (int d = 0; d < D; ++d) {
      r[d] = st.x[static_cast<std::size_t>(n) * D + d] - rb.X[d];
      v[d] = st.v[static_cast<std::size_t>(n) * D + d] - rb.V[d];
      rb.r0[3 * i + d] = r[d];
    }
    const double r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q) rb.I0[p][q] += st.mass[n] * ((p == q ? r2 : 0.0) - r[p] * r[q]);
    cross(r, v, rxv);
    for (int d = 0; d < 3; ++d) rb.L[d] += st.mass[n] * rxv[d];
  }
  if (D == 2) rb.L[0] = rb.L[1] = 0.0;
  // Prescribed velocity components of any node fix the body's translation component and its rotation.
  for (int n : rb.nodes) {
    const std::uint8_t mk = st.bc_mask[n];
    for (int d = 0; d < D; ++d) {
      if (!(mk & (1u << d))) continue;
      const double val = st.bc_value[static_cast<std::size_t>(n) * D + d];
      if (rb.fixed[d] && std::abs(val - rb.fixed_value[d]) > 1e-12 * (std::abs(val) + std::abs(rb.fixed_value[d])))
        throw std::runtime_error(
            fmt::format("rigid block '{}': its nodes have different prescribed velocities "
                        "in direction {} ({} and {} m/s)",
                        m.block_names[b], "xyz"[d], rb.fixed_value[d], val));
      rb.fixed[d] = true;
      rb.fixed_value[d] = val;
      rb.rotation_locked = true;
      rb.fixed_ramp = std::max(rb.fixed_ramp, st.bc_ramp[n]);
    }
  }
  if (rb.rotation_locked) rb.L[0] = rb.L[1] = rb.L[2] = 0.0;
  for (int d = 0; d < D; ++d)
    if (rb.fixed[d]) rb.V[d] = rb.fixed_ramp > 0 ? 0.0 : rb.fixed_value[d];
  // The node velocities become the rigid field V + omega x r.
  double w[3];
  angular_velocity(rb, D, rb.Q, rb.L, w);
  for (std::size_t i = 0; i < rb.nodes.size(); ++i) {
    double wxr[3];
    cross(w, &rb.r0[3 * i], wxr);
    for (int d = 0; d < D; ++d) st.v[static_cast<std::size_t>(rb.nodes[i]) * D + d] = rb.V[d] + wxr[d];
  }
  return rb;
}

void rigid_node_forces(const RigidBody& rb, const Mesh& m, const State& st, const int* owner, int rank, double* f) {
  const int D = m.dim;
  const int* off = m.node_corner_offset.data();
  const int* corners = m.node_corners.data();
  for (std::size_t i = 0; i < rb.nodes.size(); ++i) {
    const int n = rb.nodes[i];
    double* fi = f + 3 * i;
    fi[0] = fi[1] = fi[2] = 0.0;
    if (owner && owner[n] != rank) continue;
    for (int k = off[n]; k < off[n + 1]; ++k) {
      const int c = corners[k];
      const double* fc = st.fc.data() + static_cast<std::ptrdiff_t>(c) * D;  // corner c = z * N + a
      for (int d = 0; d < D; ++d) fi[d] += fc[d];
    }
    if (st.bc_mask[n] & kBcLoaded)
      for (int d = 0; d < D; ++d) fi[d] += st.fext[static_cast<std::size_t>(n) * D + d];
  }
}

void advance_rigid_body(RigidBody& rb, const Mesh& m, State& st, double dt, double t_half, double& ke, double& wb) {
  std::vector<double> f(3 * rb.nodes.size());
  rigid_node_forces(rb, m, st, nullptr, 0, f.data());
  advance_rigid_body(rb, m, st, f.data(), dt, t_half, ke, wb);
}

void advance_rigid_body(RigidBody& rb, const Mesh& m, State& st, const double* node_force, double dt, double t_half,
                        double& ke, double& wb) {
  const int D = m.dim;
  // Net force and torque about the centre of mass at t^n: corner forces of the neighbouring elements (those of
  // the body's own elements are zero) and external loads, summed in the body's node order.
  double F[3] = {0, 0, 0}, T[3] = {0, 0, 0};
  for (std::size_t i = 0; i < rb.nodes.size(); ++i) {
    const int n = rb.nodes[i];
    double f[3] = {node_force[3 * i], node_force[3 * i + 1], node_force[3 * i + 2]}, r[3] = {0, 0, 0}, rxf[3];
    for (int d = 0; d < D; ++d) {
      F[d] += f[d];
      r[d] = st.x[static_cast<std::size_t>(n) * D + d] - rb.X[d];
    }
    cross(r, f, rxf);
    for (int d = 0; d < 3; ++d) T[d] += rxf[d];
  }
  for (int d = 0; d < 3; ++d) T[d] += rb.added_torque[d];
  // Translation, with prescribed components (their reaction force does work R . Vbar).
  const double ramp = rb.fixed_ramp > 0 ? std::min(1.0, t_half / rb.fixed_ramp) : 1.0;
  // With the fluid's Robin condition (added_K, added_b; zero without it), as for the nodes (robin_step.h):
  // (M I + theta dt K) V' = M V + dt (F + b - (1 - theta) K V) over the free components, the prescribed ones known.
  double Vn[3] = {0, 0, 0}, Vc[3] = {0, 0, 0};
  unsigned fixed = 0;
  for (int d = 0; d < D; ++d) {
    Vn[d] = rb.fixed[d] ? ramp * rb.fixed_value[d] : rb.V[d] + dt * F[d] / rb.mass;
    if (rb.fixed[d]) fixed |= 1u << d;
  }
  const double theta = robin_step(D, rb.mass, dt, fixed, &rb.added_K[0][0], rb.added_b, rb.V, Vn);
  for (int d = 0; d < D; ++d) Vc[d] = (1.0 - theta) * rb.V[d] + theta * Vn[d];
  for (int d = 0; d < D; ++d) {
    double robin = rb.added_b[d];  // the Robin force at the step's velocity, whose work is boundary work
    for (int j = 0; j < D; ++j) robin -= rb.added_K[d][j] * Vc[j];
    wb += dt * robin * 0.5 * (rb.V[d] + Vn[d]);
    if (rb.fixed[d]) {
      const double reaction = rb.mass * (Vn[d] - rb.V[d]) / dt - F[d] - robin;
      wb += dt * reaction * 0.5 * (rb.V[d] + Vn[d]);
    }
  }
  // Rotation.
  M3 R = {};  // R - 1
  if (!rb.rotation_locked) {
    double w0[3];
    angular_velocity(rb, D, rb.Q, rb.L, w0);
    // The Robin torque -C V_c - K_rot omega_c (added_C, added_Krot; zero without it), omega_c taken as for
    // the translation: (1 + theta dt I^-1 K_rot) omega' = omega + dt I^-1 (T - C V_c - (1 - theta) K_rot omega).
    double robin_torque[3] = {rb.added_torque[0], rb.added_torque[1], rb.added_torque[2]};
    double Krot_trace = 0.0;
    for (int i = 0; i < 3; ++i) Krot_trace += rb.added_Krot[i][i];
    if (Krot_trace > 0) {
      Eigen::Matrix3d Iinv, K, C;
      for (int j = 0; j < 3; ++j) {
        const double e[3] = {j == 0 ? 1.0 : 0.0, j == 1 ? 1.0 : 0.0, j == 2 ? 1.0 : 0.0};
        double col[3];
        angular_velocity(rb, D, rb.Q, e, col);
        for (int i = 0; i < 3; ++i) {
          Iinv(i, j) = col[i];
          K(i, j) = rb.added_Krot[i][j];
          C(i, j) = rb.added_C[i][j];
        }
      }
      const Eigen::Vector3d om0(w0[0], w0[1], w0[2]), vc(Vc[0], Vc[1], Vc[2]);
      const double theta_rot = robin_theta(dt * (Iinv * K).trace());
      const Eigen::Vector3d Te = Eigen::Vector3d(T[0], T[1], T[2]) - C * vc;
      const Eigen::Matrix3d A = Eigen::Matrix3d::Identity() + theta_rot * dt * Iinv * K;
      const Eigen::Vector3d om1 = A.partialPivLu().solve(om0 + dt * Iinv * (Te - (1.0 - theta_rot) * K * om0));
      const Eigen::Vector3d rob = -C * vc - K * ((1.0 - theta_rot) * om0 + theta_rot * om1);
      for (int d = 0; d < 3; ++d) {
        T[d] += rob[d];
        robin_torque[d] += rob[d];
      }
    }
    for (int d = (D == 2 ? 2 : 0); d < 3; ++d) rb.L[d] += dt * T[d];
    double w[3];
    angular_velocity(rb, D, rb.Q, rb.L, w);
    for (int d = 0; d < 3; ++d) wb += dt * robin_torque[d] * 0.5 * (w0[d] + w[d]);  // its work
    if (D == 3) {  // predictor: inertia at the mid-step orientation
      M3 Rh, Qh;
      const double wh[3] = {0.5 * dt * w[0], 0.5 * dt * w[1], 0.5 * dt * w[2]};
      rotation_minus_one(wh, Rh);
      matmul(Rh, rb.Q, Qh);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) Qh[i][j] += rb.Q[i][j];
      angular_velocity(rb, D, Qh, rb.L, w);
    }
    const double wt[3] = {dt * w[0], dt * w[1], dt * w[2]};
    rotation_minus_one(wt, R);
  }
  // Node velocities: the chords V + (R - 1) Q r0 / dt (evaluated without cancellation), x += dt v, so that the
  // neighbouring elements see exactly the rigid motion; then Q <- R Q.
  double wload = 0.0;
  for (std::size_t i = 0; i < rb.nodes.size(); ++i) {
    const int n = rb.nodes[i];
    const double* r0 = &rb.r0[3 * i];
    double r[3];
    for (int d = 0; d < 3; ++d) r[d] = rb.Q[d][0] * r0[0] + rb.Q[d][1] * r0[1] + rb.Q[d][2] * r0[2];
    for (int d = 0; d < D; ++d) {
      const std::size_t o = static_cast<std::size_t>(n) * D + d;
      const double vn = Vn[d] + (R[d][0] * r[0] + R[d][1] * r[1] + R[d][2] * r[2]) / dt;
      const double xn = st.x[o] + dt * vn;
      const double vbar = 0.5 * (st.v[o] + vn);
      if (st.bc_mask[n] & kBcLoaded) wload += dt * st.fext[o] * vbar;
      ke += 0.5 * st.mass[n] * vn * vn;
      st.vbar[o] = vbar;
      st.v[o] = vn;
      st.x[o] = xn;
    }
  }
  wb += wload;
  M3 RQ;
  matmul(R, rb.Q, RQ);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rb.Q[i][j] += RQ[i][j];
  for (int d = 0; d < D; ++d) {
    rb.V[d] = Vn[d];
    rb.X[d] += dt * Vn[d];
  }
}

double rigid_body_kinetic_energy(const RigidBody& rb, int dim) {
  double w[3];
  angular_velocity(rb, dim, rb.Q, rb.L, w);
  double e = 0.0;
  for (int d = 0; d < dim; ++d) e += 0.5 * rb.mass * rb.V[d] * rb.V[d];
  return e + 0.5 * (rb.L[0] * w[0] + rb.L[1] * w[1] + rb.L[2] * w[2]);
}

}  // namespace cosim::solid
