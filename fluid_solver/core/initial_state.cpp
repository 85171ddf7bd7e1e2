#include "fluid_solver/core/initial_state.h"

namespace cosim::fluid {

MixtureValue profile_value(const FluidScene& scene, const std::array<double, 3>& x, const std::array<double, 3>& dx) {
  const Profile& pr = scene.profile;
  const int dim = scene.dim;
  PhaseValue v;
  v.alpha = 1.0;
  if (pr.kind == Profile::Kind::DensityWave) {
    // Cell average of rho0 (1 + A sin(2 pi sum_d k_d (x_d - lo_d) / L_d)): the sine at the centre
    // times the product of sinc(pi k_d dx_d / L_d).
    double phase = 0, damp = 1;
    for (int d = 0; d < dim; ++d) {
      const double L = scene.upper[d] - scene.lower[d];
      const double w = 2.0 * std::numbers::pi * pr.wave_number[d] / L;
      phase += w * (x[d] - scene.lower[d]);
      const double h = 0.5 * w * dx[d];
      if (h != 0.0) damp *= std::sin(h) / h;
    }
    v.rho = pr.rho0 * (1.0 + pr.amplitude * std::sin(phase) * damp);
    v.velocity = pr.velocity;
    v.p = pr.p0;
  } else {
    // Gresho vortex (Liska & Wendroff 2003), scaled: speed U at r = 0.2 R, background Mach number
    // M = U / c0, p0 = rho U^2 / (gamma M^2).
    const double gamma = scene.phases[0].eos.gamma;
    const double R = pr.radius_scale, U = pr.speed, rho = pr.rho0;
    const double dx0 = x[0] - pr.center[0], dy0 = x[1] - pr.center[1];
    const double r = std::sqrt(dx0 * dx0 + dy0 * dy0) / R;
    double uphi, dp;  // u_phi / U and (p - p0) / (rho U^2) for U = 1 at r = 0.2
    if (r < 0.2) {
      uphi = 5.0 * r;
      dp = 12.5 * r * r;
    } else if (r < 0.4) {
      uphi = 2.0 - 5.0 * r;
      dp = 12.5 * r * r + 4.0 - 20.0 * r + 4.0 * std::log(5.0 * r);
    } else {
      uphi = 0.0;
      dp = -2.0 + 4.0 * std::log(2.0);
    }
    const double p0 = rho * U * U / (gamma * pr.mach * pr.mach);
    const double rr = std::max(r * R, 1e-300);
    v.rho = rho;
    v.velocity = {-U * uphi * dy0 / rr, U * uphi * dx0 / rr, 0.0};
    if (r == 0.0) v.velocity = {0, 0, 0};
    v.p = p0 + rho * U * U * dp;
  }
  return {v};
}

}  // namespace cosim::fluid
