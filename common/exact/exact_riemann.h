// Exact Riemann solver for the 1D Euler equations with ideal / stiffened-gas EOS.
//
// Each side K of the initial discontinuity has its own material (gamma_K, pinf_K) with
//   p = (gamma - 1) rho e - gamma pinf,   c^2 = gamma (p + pinf) / rho   (docs/methods.md §7.2).
// For a stiffened gas the shock Hugoniot and the isentropes are those of an ideal gas written in
// the shifted pressure P = p + pinf, so Toro's ch. 4 solver applies side by side with p -> p +
// pinf_K (docs/methods.md §8.1). Vacuum generation (Toro 4.6) is supported for ideal gases only.
#pragma once

#include <vector>

namespace cosim::exact {

// Stiffened gas p = (gamma - 1) rho e - gamma pinf; ideal gas: pinf = 0.
struct Material {
  double gamma = 1.4;
  double pinf = 0.0;
};

struct Primitive {
  double rho, u, p;
};

// Star region: pressure and velocity are continuous across the contact, the densities are not.
// vacuum = true: the two rarefactions do not meet (Toro 4.6); then p = rho_left = rho_right = 0
// and u is the mid-point of the two vacuum fronts (the "contact" used to split the sides).
struct Star {
  double p, u, rho_left, rho_right;
  bool vacuum;
};

// Star state of the Riemann problem (left state with material mL, right state with mR).
// Safeguarded Newton iteration on f_L(p) + f_R(p) + (uR - uL) = 0 (Toro eq. 4.5, with p -> p +
// pinf_K inside f_K), started from the PVRS / two-rarefaction / two-shock guess (Toro
// section 4.3.1). Relative tolerance 1e-13 on p* + min(pinf_L, pinf_R), the distance to cavitation.
// Throws std::runtime_error for invalid input (rho <= 0, p + pinf <= 0, gamma <= 1, pinf < 0,
// non-finite values) or if a vacuum / cavitation is generated with pinf > 0 on either side.
Star solve_star(const Primitive& L, const Material& mL, const Primitive& R, const Material& mR);

class RiemannSolution {
 public:
  RiemannSolution(const Primitive& L, const Material& mL, const Primitive& R, const Material& mR);

  const Star& star() const { return star_; }

  // State at similarity coordinate xi = (x - x0)/t. side = -1 if the point is in the left
  // material (xi <= contact), +1 in the right material. In a vacuum region rho = p = 0 and
  // u = xi (continuous with the fans' vacuum fronts).
  struct Sample {
    double rho, u, p;
    int side;
  };
  Sample sample(double xi) const;

  // Wave speeds: left wave head/tail (equal for a shock), contact, right wave tail/head.
  // In the vacuum case left_tail/right_tail are the vacuum fronts (Toro section 4.6).
  double left_head() const { return left_head_; }
  double left_tail() const { return left_tail_; }
  double contact() const { return star_.u; }
  double right_tail() const { return right_tail_; }
  double right_head() const { return right_head_; }

  const Primitive& left_state() const { return L_; }
  const Primitive& right_state() const { return R_; }
  const Material& left_material() const { return mL_; }
  const Material& right_material() const { return mR_; }

 private:
  Sample left_fan(double xi) const;
  Sample right_fan(double xi) const;

  Primitive L_, R_;
  Material mL_, mR_;
  Star star_;
  double cL_, cR_;
  bool left_shock_, right_shock_;
  double left_head_, left_tail_, right_tail_, right_head_;
};

// Sample the solution on N cell centres of [x_lo, x_hi] at time t with the discontinuity at x0
// (e.g. for L1 errors of numerical solutions). Outputs are resized to N. t = 0 gives the initial
// data (x <= x0 left); t < 0 or N < 0 throws std::invalid_argument.
void sample_on_cells(const RiemannSolution& s, double x_lo, double x_hi, int N, double x0, double t,
                     std::vector<double>& rho, std::vector<double>& u, std::vector<double>& p);

}  // namespace cosim::exact
