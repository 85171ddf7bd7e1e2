// Exact Riemann solver, ideal and stiffened gas (Toro ch. 4; docs/methods.md §7.2 and §8.1).
#include "common/exact/exact_riemann.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace cosim::exact {
namespace {

constexpr double kTol = 1e-13;  // relative tolerance on q = p - p_min (distance to cavitation)
constexpr int kMaxIter = 500;

// One side K of the problem in shifted-pressure form P = p + pinf_K (docs/methods.md §8.1). The star
// pressure is iterated as q = p* - p_min >= 0 with p_min = -min(pinf_L, pinf_R), the pressure at
// which the softer side cavitates, so that P*_K = q + shift_K keeps full relative precision there.
struct Side {
  double rho, u, p, g, pinf;
  double P;      // p_K + pinf_K
  double c;      // sound speed, c^2 = g P / rho (docs/methods.md §7.2)
  double A;      // Toro eq. 4.8: A_K = 2 / ((g + 1) rho_K)
  double B;      // Toro eq. 4.8: B_K = (g - 1)/(g + 1) P_K
  double shift;  // P*_K = q + shift, shift = pinf_K + p_min >= 0
};

// Star state together with the shifted star pressures and the wave types.
struct StarFull {
  Star star;
  double Ps_l, Ps_r;  // p* + pinf_L, p* + pinf_R (accurate even next to cavitation)
  bool shock_l, shock_r;
};

void check_input(const Primitive& s, const Material& m, const char* name) {
  const std::string who = std::string("exact Riemann solver: ") + name + " state ";
  if (!std::isfinite(s.rho) || !std::isfinite(s.u) || !std::isfinite(s.p) || !std::isfinite(m.gamma) ||
      !std::isfinite(m.pinf)) {
    throw std::runtime_error(who + "has non-finite values");
  }
  if (!(m.gamma > 1.0)) throw std::runtime_error(who + "needs gamma > 1");
  if (!(m.pinf >= 0.0)) throw std::runtime_error(who + "needs pinf >= 0");
  if (!(s.rho > 0.0)) throw std::runtime_error(who + "needs rho > 0");
  if (!(s.p + m.pinf > 0.0)) throw std::runtime_error(who + "needs p + pinf > 0");
}

Side make_side(const Primitive& s, const Material& m, double pinf_min) {
  Side k{};
  k.rho = s.rho;
  k.u = s.u;
  k.p = s.p;
  k.g = m.gamma;
  k.pinf = m.pinf;
  k.P = s.p + m.pinf;
  k.c = std::sqrt(m.gamma * k.P / s.rho);
  k.A = 2.0 / ((m.gamma + 1.0) * s.rho);
  k.B = (m.gamma - 1.0) / (m.gamma + 1.0) * k.P;
  k.shift = m.pinf - pinf_min;
  return k;
}

// f_K and its derivative at P = p + pinf_K (Toro eqs. 4.6-4.7 and 4.37, p -> p + pinf_K).
void pressure_function(const Side& k, double P, double& f, double& df) {
  if (P > k.P) {  // shock
    const double w = std::sqrt(k.A / (P + k.B));
    f = (P - k.P) * w;
    df = w * (1.0 - 0.5 * (P - k.P) / (P + k.B));
  } else {  // rarefaction
    const double r = P / k.P;
    const double z = (k.g - 1.0) / (2.0 * k.g);
    f = 2.0 * k.c / (k.g - 1.0) * (std::pow(r, z) - 1.0);
    df = (r > 0.0) ? std::pow(r, -(k.g + 1.0) / (2.0 * k.g)) / (k.rho * k.c) : std::numeric_limits<double>::infinity();
  }
}

// F(q) = f_L + f_R + (u_R - u_L), Toro eq. 4.5, as a function of q = p - p_min.
double pressure_residual(const Side& l, const Side& r, double q, double* dF = nullptr) {
  double fl = 0.0, dfl = 0.0, fr = 0.0, dfr = 0.0;
  pressure_function(l, q + l.shift, fl, dfl);
  pressure_function(r, q + r.shift, fr, dfr);
  if (dF) *dF = dfl + dfr;
  return fl + fr + (r.u - l.u);
}

// Initial guess for q (Toro section 4.3.1, generalised to two materials).
double initial_guess(const Side& l, const Side& r, double p_min) {
  const double du = r.u - l.u;
  // Acoustic (PVRS-type) estimate with the two impedances rho_K c_K (Toro section 9.3).
  const double zl = l.rho * l.c, zr = r.rho * r.c;
  const double p_pv = (zr * l.p + zl * r.p - zl * zr * du) / (zl + zr);
  double q = p_pv - p_min;
  if (p_pv < std::min(l.p, r.p)) {
    if (l.g == r.g && l.pinf == r.pinf) {
      // Two-rarefaction approximation (Toro section 4.3.1; exact if both waves are rarefactions).
      const double z = (l.g - 1.0) / (2.0 * l.g);
      const double num = l.c + r.c - 0.5 * (l.g - 1.0) * du;
      const double den = l.c / std::pow(l.P, z) + r.c / std::pow(r.P, z);
      q = (num > 0.0) ? std::pow(num / den, 1.0 / z) - l.shift : 0.0;
    }
  } else if (p_pv > std::max(l.p, r.p)) {
    // Two-shock approximation (Toro section 4.3.1).
    const double gl = std::sqrt(l.A / (p_pv + l.pinf + l.B));
    const double gr = std::sqrt(r.A / (p_pv + r.pinf + r.B));
    q = (gl * l.p + gr * r.p - du) / (gl + gr) - p_min;
  }
  return q;
}

StarFull solve_full(const Primitive& L, const Material& mL, const Primitive& R, const Material& mR) {
  check_input(L, mL, "left");
  check_input(R, mR, "right");
  const double pinf_min = std::min(mL.pinf, mR.pinf);
  const double p_min = -pinf_min;  // lowest admissible star pressure (zero density on one side)
  const Side l = make_side(L, mL, pinf_min), r = make_side(R, mR, pinf_min);

  StarFull out{};
  if (pressure_residual(l, r, 0.0) >= 0.0) {
    // Pressure positivity condition violated: vacuum is generated (Toro eq. 4.40, section 4.6).
    if (l.pinf > 0.0 || r.pinf > 0.0) {
      throw std::runtime_error("exact Riemann solver: vacuum/cavitation with pinf > 0 is not supported");
    }
    const double sl = l.u + 2.0 * l.c / (l.g - 1.0);  // left vacuum front (Toro section 4.6)
    const double sr = r.u - 2.0 * r.c / (r.g - 1.0);  // right vacuum front (Toro section 4.6)
    out.star = Star{0.0, 0.5 * (sl + sr), 0.0, 0.0, true};
    return out;
  }

  // F is increasing and concave (Toro section 4.3.1) and F(0) < 0: bracket the root in [lo, hi].
  double lo = 0.0;
  double hi = std::max(L.p, R.p) - p_min;  // > 0 since p_K + pinf_K > 0
  while (pressure_residual(l, r, hi) < 0.0) {
    lo = hi;
    hi *= 4.0;
  }

  // Newton iteration (Toro eq. 4.44), safeguarded by bisection.
  double q = initial_guess(l, r, p_min);
  if (!(q > lo && q < hi)) q = 0.5 * (lo + hi);
  for (int it = 0; it < kMaxIter; ++it) {
    double dF = 0.0;
    const double F = pressure_residual(l, r, q, &dF);
    if (F == 0.0) break;
    if (F < 0.0) {
      lo = q;
    } else {
      hi = q;
    }
    double q_new = q - F / dF;
    if (!(q_new > lo && q_new < hi)) {
      // Bisection, geometric when the bracket spans decades: near cavitation with gamma -> 1 the
      // root can lie many decades below the initial bracket.
      if (lo == 0.0) {
        q_new = 1e-3 * hi;
      } else if (hi > 4.0 * lo) {
        q_new = std::sqrt(lo) * std::sqrt(hi);
      } else {
        q_new = 0.5 * (lo + hi);
      }
    }
    const double change = std::abs(q_new - q);
    q = q_new;
    if (change <= kTol * q || hi - lo <= kTol * q) break;
  }

  out.Ps_l = q + l.shift;
  out.Ps_r = q + r.shift;
  out.shock_l = out.Ps_l > l.P;
  out.shock_r = out.Ps_r > r.P;
  double fl = 0.0, fr = 0.0, d = 0.0;
  pressure_function(l, out.Ps_l, fl, d);
  pressure_function(r, out.Ps_r, fr, d);
  auto star_density = [](const Side& k, double Ps, bool shock) {
    const double ratio = Ps / k.P;
    if (shock) {  // Toro eq. 4.50
      const double mu = (k.g - 1.0) / (k.g + 1.0);
      return k.rho * (ratio + mu) / (mu * ratio + 1.0);
    }
    return k.rho * std::pow(ratio, 1.0 / k.g);  // isentrope, Toro eq. 4.53
  };
  out.star.p = q + p_min;
  out.star.u = 0.5 * (l.u + r.u) + 0.5 * (fr - fl);  // Toro eq. 4.9
  out.star.rho_left = star_density(l, out.Ps_l, out.shock_l);
  out.star.rho_right = star_density(r, out.Ps_r, out.shock_r);
  out.star.vacuum = false;
  return out;
}

}  // namespace

Star solve_star(const Primitive& L, const Material& mL, const Primitive& R, const Material& mR) {
  return solve_full(L, mL, R, mR).star;
}

RiemannSolution::RiemannSolution(const Primitive& L, const Material& mL, const Primitive& R, const Material& mR)
    : L_(L), R_(R), mL_(mL), mR_(mR) {
  const StarFull full = solve_full(L, mL, R, mR);
  star_ = full.star;
  const double gl = mL.gamma, gr = mR.gamma;
  const double PL = L.p + mL.pinf, PR = R.p + mR.pinf;
  cL_ = std::sqrt(gl * PL / L.rho);
  cR_ = std::sqrt(gr * PR / R.rho);

  if (star_.vacuum) {
    left_shock_ = right_shock_ = false;
    left_head_ = L.u - cL_;
    left_tail_ = L.u + 2.0 * cL_ / (gl - 1.0);   // vacuum front (Toro section 4.6)
    right_tail_ = R.u - 2.0 * cR_ / (gr - 1.0);  // vacuum front (Toro section 4.6)
    right_head_ = R.u + cR_;
    return;
  }

  left_shock_ = full.shock_l;
  if (left_shock_) {  // Toro eq. 4.52
    left_head_ = left_tail_ = L.u - cL_ * std::sqrt((gl + 1.0) / (2.0 * gl) * full.Ps_l / PL + (gl - 1.0) / (2.0 * gl));
  } else {  // Toro eqs. 4.54-4.55 (head, tail)
    left_head_ = L.u - cL_;
    left_tail_ = star_.u - cL_ * std::pow(full.Ps_l / PL, (gl - 1.0) / (2.0 * gl));
  }
  right_shock_ = full.shock_r;
  if (right_shock_) {  // Toro eq. 4.59
    right_head_ = right_tail_ =
        R.u + cR_ * std::sqrt((gr + 1.0) / (2.0 * gr) * full.Ps_r / PR + (gr - 1.0) / (2.0 * gr));
  } else {  // Toro eqs. 4.61-4.62 (head, tail)
    right_head_ = R.u + cR_;
    right_tail_ = star_.u + cR_ * std::pow(full.Ps_r / PR, (gr - 1.0) / (2.0 * gr));
  }
}

// Inside the left fan, Toro eq. 4.56 with p -> p + pinf.
RiemannSolution::Sample RiemannSolution::left_fan(double xi) const {
  const double g = mL_.gamma;
  const double c = std::max(2.0 / (g + 1.0) * (cL_ + 0.5 * (g - 1.0) * (L_.u - xi)), 0.0);
  const double u = 2.0 / (g + 1.0) * (cL_ + 0.5 * (g - 1.0) * L_.u + xi);
  const double ratio = c / cL_;
  const double rho = L_.rho * std::pow(ratio, 2.0 / (g - 1.0));
  const double p = (L_.p + mL_.pinf) * std::pow(ratio, 2.0 * g / (g - 1.0)) - mL_.pinf;
  return {rho, u, p, -1};
}

// Inside the right fan, Toro eq. 4.63 with p -> p + pinf.
RiemannSolution::Sample RiemannSolution::right_fan(double xi) const {
  const double g = mR_.gamma;
  const double c = std::max(2.0 / (g + 1.0) * (cR_ - 0.5 * (g - 1.0) * (R_.u - xi)), 0.0);
  const double u = 2.0 / (g + 1.0) * (-cR_ + 0.5 * (g - 1.0) * R_.u + xi);
  const double ratio = c / cR_;
  const double rho = R_.rho * std::pow(ratio, 2.0 / (g - 1.0));
  const double p = (R_.p + mR_.pinf) * std::pow(ratio, 2.0 * g / (g - 1.0)) - mR_.pinf;
  return {rho, u, p, +1};
}

RiemannSolution::Sample RiemannSolution::sample(double xi) const {
  if (star_.vacuum) {  // Toro 4.6, vacuum generated between the two fans
    if (xi <= left_head_) return {L_.rho, L_.u, L_.p, -1};
    if (xi < left_tail_) return left_fan(xi);
    if (xi <= right_tail_) return {0.0, xi, 0.0, xi <= star_.u ? -1 : +1};
    if (xi < right_head_) return right_fan(xi);
    return {R_.rho, R_.u, R_.p, +1};
  }
  if (xi <= star_.u) {  // left of the contact
    if (xi <= left_head_) return {L_.rho, L_.u, L_.p, -1};
    if (xi >= left_tail_) return {star_.rho_left, star_.u, star_.p, -1};
    return left_fan(xi);  // only reached for a rarefaction (head < tail)
  }
  if (xi >= right_head_) return {R_.rho, R_.u, R_.p, +1};
  if (xi <= right_tail_) return {star_.rho_right, star_.u, star_.p, +1};
  return right_fan(xi);
}

void sample_on_cells(const RiemannSolution& s, double x_lo, double x_hi, int N, double x0, double t,
                     std::vector<double>& rho, std::vector<double>& u, std::vector<double>& p) {
  if (N < 0) throw std::invalid_argument("sample_on_cells: N < 0");
  if (!(t >= 0.0)) throw std::invalid_argument("sample_on_cells: t < 0");
  const auto n = static_cast<std::size_t>(N);
  rho.resize(n);
  u.resize(n);
  p.resize(n);
  const double dx = (x_hi - x_lo) / static_cast<double>(N > 0 ? N : 1);
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    const double x = x_lo + (static_cast<double>(i) + 0.5) * dx;
    double xi = 0.0;
    if (t > 0.0) {
      xi = (x - x0) / t;
    } else {
      xi = (x <= x0) ? -inf : inf;  // initial data
    }
    const RiemannSolution::Sample q = s.sample(xi);
    rho[i] = q.rho;
    u[i] = q.u;
    p[i] = q.p;
  }
}

}  // namespace cosim::exact
