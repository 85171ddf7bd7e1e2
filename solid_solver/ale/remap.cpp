#include "solid_solver/ale/remap.h"

#include <algorithm>
#include <cmath>

#include "solid_solver/kinematics/element_geometry.h"
#include "solid_solver/mesh/element_faces.h"

namespace cosim::solid {

double element_volume(const Mesh& m, const std::vector<double>& x, int e) {
  const int* c = &m.conn[static_cast<std::size_t>(e) * m.npe];
  if (m.dim == 2) {
    double p[4][2], B[4][2];
    for (int k = 0; k < 4; ++k)
      for (int d = 0; d < 2; ++d) p[k][d] = x[2 * static_cast<std::size_t>(c[k]) + d];
    return element_b_matrix(p, B);
  }
  double p[8][3], B[8][3];
  for (int k = 0; k < 8; ++k)
    for (int d = 0; d < 3; ++d) p[k][d] = x[3 * static_cast<std::size_t>(c[k]) + d];
  return element_b_matrix(p, B);
}

double swept_volume(int dim, const std::array<int, 4>& f, const std::vector<double>& xo,
                    const std::vector<double>& xn) {
  if (dim == 2) {
    // Quadrilateral a, a', b', b: counter-clockwise when the edge a-b moves outward (to its right).
    const int a = f[0], b = f[1];
    double x[4][2] = {
        {xo[2 * a], xo[2 * a + 1]}, {xn[2 * a], xn[2 * a + 1]}, {xn[2 * b], xn[2 * b + 1]}, {xo[2 * b], xo[2 * b + 1]}};
    double B[4][2];
    return element_b_matrix(x, B);
  }
  // Hexahedron with the old face as its bottom and the new as its top: the face's nodes run counter-clockwise
  // seen from outside the element, which is how VTK's bottom face is seen from the top.
  double x[8][3];
  for (int q = 0; q < 4; ++q)
    for (int d = 0; d < 3; ++d) {
      x[q][d] = xo[3 * static_cast<std::size_t>(f[q]) + d];
      x[q + 4][d] = xn[3 * static_cast<std::size_t>(f[q]) + d];
    }
  double B[8][3];
  return element_b_matrix(x, B);
}

RemapFlux remap(const Mesh& m, const AleMesh& a, const std::vector<double>& xo, State& st) {
  const int D = m.dim, N = m.npe, ne = m.num_elements, nn = m.num_nodes;
  RemapFlux out;
  // Donor densities of the relaxed elements: mass, internal energy, momentum and kinetic energy per volume
  // (element-mean velocity), on the Lagrangian mesh.
  std::vector<double> rho(ne, 0.0), rie(ne, 0.0), vbar(static_cast<std::size_t>(ne) * 3, 0.0);
  for (int e = 0; e < ne; ++e) {
    if (!a.relaxed_element[e]) continue;
    rho[e] = st.emass[e] / st.vol[e];
    rie[e] = st.ie[e] / st.vol[e];
    for (int k = 0; k < N; ++k)
      for (int d = 0; d < D; ++d)
        vbar[3 * static_cast<std::size_t>(e) + d] += st.v[static_cast<std::size_t>(m.conn[e * N + k]) * D + d] / N;
  }
  // Element changes: mass, internal energy, momentum, kinetic energy carried in.
  std::vector<double> dm(ne, 0.0), die(ne, 0.0), dp(static_cast<std::size_t>(ne) * 3, 0.0), dk(ne, 0.0);
  auto exchange = [&](int to, int donor, double mass, double sign) {
    const double* v = &vbar[3 * static_cast<std::size_t>(donor)];
    double v2 = 0;
    for (int d = 0; d < D; ++d) v2 += v[d] * v[d];
    dm[to] += sign * mass;
    die[to] += sign * mass * rie[donor] / rho[donor];
    dk[to] += sign * 0.5 * mass * v2;
    for (int d = 0; d < D; ++d) dp[3 * static_cast<std::size_t>(to) + d] += sign * mass * v[d];
  };
  for (const AleFace& f : a.faces) {
    const double dv = swept_volume(D, element_face_nodes(m, f.a, f.local), xo, st.x);
    if (dv == 0.0) continue;
    if (f.b < 0) {  // the exterior: the element's own state goes out (dv < 0) or comes in (dv > 0)
      const double mass = rho[f.a] * dv;
      exchange(f.a, f.a, mass, 1.0);
      out.mass += mass;
      const double* v = &vbar[3 * static_cast<std::size_t>(f.a)];
      double v2 = 0;
      for (int d = 0; d < D; ++d) v2 += v[d] * v[d], out.momentum[d] += mass * v[d];
      out.energy += mass * (rie[f.a] / rho[f.a] + 0.5 * v2);
      continue;
    }
    const int donor = dv > 0 ? f.b : f.a;  // a gains volume from b's side: b's state comes in
    const double mass = rho[donor] * dv;
    exchange(f.a, donor, mass, 1.0);
    exchange(f.b, donor, mass, -1.0);
  }
  // Nodes: old masses and momenta, plus a 1/N share of their elements' changes.
  std::vector<double> dmn(nn, 0.0), dpn(static_cast<std::size_t>(nn) * 3, 0.0), dkn(nn, 0.0);
  for (int e = 0; e < ne; ++e) {
    if (!a.relaxed_element[e]) continue;
    for (int k = 0; k < N; ++k) {
      const int n = m.conn[e * N + k];
      dmn[n] += dm[e] / N;
      dkn[n] += dk[e] / N;
      for (int d = 0; d < D; ++d)
        dpn[3 * static_cast<std::size_t>(n) + d] += dp[3 * static_cast<std::size_t>(e) + d] / N;
    }
    st.emass[e] += dm[e];
    st.ie[e] += die[e];
  }
  // New velocities; the kinetic energy lost to the averaging, per node, goes to its elements by corner mass.
  std::vector<double> loss(nn, 0.0);
  for (int n = 0; n < nn; ++n) {
    if (dmn[n] == 0.0 && dpn[3 * static_cast<std::size_t>(n)] == 0.0 &&
        dpn[3 * static_cast<std::size_t>(n) + 1] == 0.0 && dpn[3 * static_cast<std::size_t>(n) + 2] == 0.0)
      continue;
    double* v = &st.v[static_cast<std::size_t>(n) * D];
    const double m_old = st.mass[n], m_new = m_old + dmn[n];
    double k_old = 0, k_new = 0;
    for (int d = 0; d < D; ++d) {
      k_old += 0.5 * m_old * v[d] * v[d];
      v[d] = (m_old * v[d] + dpn[3 * static_cast<std::size_t>(n) + d]) / m_new;
      k_new += 0.5 * m_new * v[d] * v[d];
    }
    st.mass[n] = m_new;
    // Only a loss is returned as heat: a gain (possible where the donor velocities differ widely) would take
    // internal energy that may not be there.
    loss[n] = std::max(0.0, k_old + dkn[n] - k_new);
  }
  std::vector<double> relaxed_mass(nn, 0.0);  // the node's corner masses in relaxed elements
  for (int e = 0; e < ne; ++e)
    if (a.relaxed_element[e])
      for (int k = 0; k < N; ++k) relaxed_mass[m.conn[e * N + k]] += st.emass[e] / N;
  for (int e = 0; e < ne; ++e) {
    if (!a.relaxed_element[e]) continue;
    for (int k = 0; k < N; ++k) {
      const int n = m.conn[e * N + k];
      if (loss[n] == 0.0) continue;
      const double share = loss[n] * (st.emass[e] / N) / relaxed_mass[n];
      st.ie[e] += share;
      out.kinetic_to_internal += share;
    }
  }
  // Volumes of the new mesh.
  for (int e = 0; e < ne; ++e)
    if (a.relaxed_element[e]) st.vol[e] = element_volume(m, st.x, e);
  return out;
}

}  // namespace cosim::solid
