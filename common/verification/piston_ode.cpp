#include "common/verification/piston_ode.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cosim::verification {

PistonEquilibrium piston_equilibrium(const PistonOde& p) {
  const double kl = p.p_left * std::pow(p.v_left, p.gamma), kr = p.p_right * std::pow(p.v_right, p.gamma);
  const double r = std::pow(kl / kr, 1.0 / p.gamma);  // VL*/VR*
  const double vt = p.v_left + p.v_right;
  PistonEquilibrium e;
  e.v_left = vt * r / (1.0 + r);
  e.v_right = vt - e.v_left;
  e.pressure = kl / std::pow(e.v_left, p.gamma);
  e.x_eq = (e.v_left - p.v_left) / p.area;
  e.omega =
      std::sqrt(p.gamma * p.area * p.area * e.pressure * (1.0 / e.v_left + 1.0 / e.v_right) / (p.mass + p.extra_mass));
  return e;
}

double piston_acceleration(const PistonOde& p, double x) {
  const double vl = p.v_left + p.area * x, vr = p.v_right - p.area * x;
  if (!(vl > 0.0 && vr > 0.0)) throw std::domain_error("piston ODE: a chamber volume reached zero");
  const double pl = p.p_left * std::pow(p.v_left / vl, p.gamma);
  const double pr = p.p_right * std::pow(p.v_right / vr, p.gamma);
  return p.area * (pl - pr) / (p.mass + p.extra_mass);
}

PistonTrajectory integrate_piston(const PistonOde& p, double t_end, double dt) {
  PistonTrajectory tr;
  tr.dt = dt;
  const long n = static_cast<long>(std::ceil(t_end / dt));
  tr.x.reserve(n + 1);
  tr.v.reserve(n + 1);
  double x = 0.0, v = 0.0;
  tr.x.push_back(x);
  tr.v.push_back(v);
  for (long i = 0; i < n; ++i) {  // classical RK4 on (x, v)
    const double a1 = piston_acceleration(p, x);
    const double a2 = piston_acceleration(p, x + 0.5 * dt * v);
    const double a3 = piston_acceleration(p, x + 0.5 * dt * (v + 0.5 * dt * a1));
    const double a4 = piston_acceleration(p, x + dt * (v + 0.5 * dt * a2));
    x += dt * (v + dt * (a1 + a2 + a3) / 6.0);
    v += dt * (a1 + 2.0 * a2 + 2.0 * a3 + a4) / 6.0;
    tr.x.push_back(x);
    tr.v.push_back(v);
  }
  return tr;
}

double PistonTrajectory::x_at(double t) const {
  const double s = t / dt;
  const long last = static_cast<long>(x.size()) - 1;
  long i = std::clamp(static_cast<long>(std::floor(s)), 0L, std::max(0L, last - 1));
  if (last < 1) return x.empty() ? 0.0 : x[0];
  const double u = std::clamp(s - static_cast<double>(i), 0.0, 1.0);
  // Cubic Hermite basis on [t_i, t_i + dt] with slopes v.
  const double h00 = (1 + 2 * u) * (1 - u) * (1 - u), h10 = u * (1 - u) * (1 - u);
  const double h01 = u * u * (3 - 2 * u), h11 = u * u * (u - 1);
  return h00 * x[i] + h10 * dt * v[i] + h01 * x[i + 1] + h11 * dt * v[i + 1];
}

double PistonTrajectory::x_min() const { return *std::min_element(x.begin(), x.end()); }
double PistonTrajectory::x_max() const { return *std::max_element(x.begin(), x.end()); }

double PistonTrajectory::period() const {
  // Maxima: v changes sign from + to -; the crossing time by linear interpolation of v.
  std::vector<double> tmax;
  for (std::size_t i = 1; i < v.size(); ++i)
    if (v[i - 1] > 0.0 && v[i] <= 0.0) tmax.push_back(dt * (i - 1 + v[i - 1] / (v[i - 1] - v[i])));
  if (tmax.size() < 2) return 0.0;
  return (tmax.back() - tmax.front()) / static_cast<double>(tmax.size() - 1);
}

}  // namespace cosim::verification
