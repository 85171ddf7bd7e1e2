// Interface conditions (coupler/interface_conditions.h; paper eqs. 17-22, docs/methods.md §4.1).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "coupler/interface_conditions.h"
#include "coupler/pressure_predictor.h"

using namespace cosim::coupler;
using cosim::coupling::Faces;
using cosim::coupling::FluidSamples;
using cosim::coupling::Mode;

namespace {
// One 1D face at x = 0 with outward normal nx (+1 or -1), solid velocity vx along x.
Faces face(double nx, double vx, double sigma_s, double z_s) {
  Faces f;
  f.dim = 2;
  f.count = 1;
  f.centre = {0, 0};
  f.normal = {nx, 0};
  f.area = {2.0};
  f.velocity = {vx, 0};
  f.normal_stress = {sigma_s};
  f.impedance = {z_s};
  return f;
}
FluidSamples samples(std::vector<double> alpha, std::vector<double> un, std::vector<double> p, std::vector<double> z) {
  FluidSamples s;
  s.count = 1;
  s.phases = static_cast<int>(alpha.size());
  s.alpha = alpha;
  s.rho.assign(alpha.size(), 1.0);
  s.normal_velocity = un;
  s.pressure = p;
  s.impedance = z;
  s.wetted = {1};
  return s;
}
}  // namespace

TEST(InterfaceConditions, HeavySolidGivesTheFluidTheWallVelocity) {
  for (Mode m : {Mode::Impedance, Mode::Characteristic}) {
    const auto st = interface_point(m, /*v_s*/ 2.0, /*sigma_s*/ -5e5, /*z_s*/ 1e12, /*v_f*/ -1.0, /*p_f*/ 1e5, 400.0);
    EXPECT_NEAR(st.velocity, 2.0, 1e-6);
    if (m == Mode::Impedance) EXPECT_NEAR(st.pressure, 1e5, 1e-3);    // eq. 21: the fluid pressure
    else EXPECT_NEAR(st.pressure, 1e5 + 400.0 * (2.0 - -1.0), 1e-3);  // + z_f (v_s - v_f): the wall pushes
  }
  const double inf = std::numeric_limits<double>::infinity();
  const auto rigid = interface_point(Mode::Impedance, 2.0, 0.0, inf, -1.0, 1e5, 400.0);
  EXPECT_EQ(rigid.velocity, 2.0);
  EXPECT_EQ(rigid.pressure, 1e5);
}

TEST(InterfaceConditions, LightSolidSeesTheFluidTraction) {
  // z_s << z_f: the pressure the solid gets tends to its own -sigma_s ... in eq. 21 the weight of p_f is w_s -> 0
  const auto st = interface_point(Mode::Impedance, 2.0, -3e5, 1e-6, -1.0, 1e5, 1e6);
  EXPECT_NEAR(st.pressure, 3e5, 1e-3);
  EXPECT_NEAR(st.velocity, -1.0, 1e-9);  // the fluid keeps its velocity
  // Standard conditions ignore impedances: fluid gets v_s, solid gets p_f.
  const auto std_st = interface_point(Mode::Standard, 2.0, -3e5, 1e-6, -1.0, 1e5, 1e6);
  EXPECT_EQ(std_st.velocity, 2.0);
  EXPECT_EQ(std_st.pressure, 1e5);
}

TEST(InterfaceConditions, WeightsFollowEqs21And22) {
  // z_s = 3 z_f: w_s = 3/4, w_f = 1/4.
  const auto st = interface_point(Mode::Impedance, 4.0, -2e5, 300.0, 0.0, 1e5, 100.0);
  EXPECT_DOUBLE_EQ(st.velocity, 0.25 * 0.0 + 0.75 * 4.0);
  EXPECT_DOUBLE_EQ(st.pressure, 0.75 * 1e5 + 0.25 * 2e5);
}

TEST(InterfaceConditions, CharacteristicIsTheAcousticRiemannSolution) {
  // Solid (left, state v_s, p_s, z_s) and fluid (right): u* = (z_s v_s + z_f v_f + p_s - p_f)/(z_s+z_f),
  // p* = (z_f p_s + z_s p_f + z_s z_f (v_s - v_f))/(z_s+z_f) (docs/methods.md §4.1).
  const double vs = 3.0, ps = 2e5, zs = 500.0, vf = -1.0, pf = 1e5, zf = 200.0;
  const auto st = interface_point(Mode::Characteristic, vs, -ps, zs, vf, pf, zf);
  EXPECT_NEAR(st.velocity, (zs * vs + zf * vf + ps - pf) / (zs + zf), 1e-9);
  EXPECT_NEAR(st.pressure, (zf * ps + zs * pf + zs * zf * (vs - vf)) / (zs + zf), 1e-6);
}

TEST(InterfaceConditions, SymmetricInSolidAndFluidWhenImpedancesSwap) {
  // Swapping the two sides (states and impedances) flips the normal: velocities along it change sign, and the
  // interface state is the same (velocity along the new normal = minus the old one).
  for (Mode m : {Mode::Impedance, Mode::Characteristic}) {
    const auto a = interface_point(m, 1.0, -3e5, 700.0, -2.0, 1e5, 300.0);
    const auto b = interface_point(m, 2.0, -1e5, 300.0, -1.0, 3e5, 700.0);
    EXPECT_NEAR(a.velocity, -b.velocity, 1e-12) << cosim::coupling::mode_name(m);
    EXPECT_NEAR(a.pressure, b.pressure, 1e-6) << cosim::coupling::mode_name(m);
  }
}

TEST(InterfaceConditions, OrientationMirroredFacesGiveMirroredStates) {
  // Solid moving at +1 m/s into fluid on its right (normal +x) vs. the mirror image (fluid on the left,
  // normal -x, solid moving at -1 m/s): same pressure, same velocity along the normal.
  for (Mode m : {Mode::Impedance, Mode::Characteristic, Mode::Standard}) {
    const auto right = interface_conditions(face(+1, +1.0, -1e5, 1000.0), samples({1}, {0.5}, {1e5}, {400}), m);
    const auto left = interface_conditions(face(-1, -1.0, -1e5, 1000.0), samples({1}, {0.5}, {1e5}, {400}), m);
    EXPECT_DOUBLE_EQ(right.pressure[0], left.pressure[0]);
    EXPECT_DOUBLE_EQ(right.normal_velocity[0], left.normal_velocity[0]);
  }
  // A solid moving into the fluid compresses it: p_I > p_f (characteristic), and pulls less when receding.
  const auto in =
      interface_conditions(face(-1, -1.0, -1e5, 1000.0), samples({1}, {0.0}, {1e5}, {400}), Mode::Characteristic);
  const auto out =
      interface_conditions(face(-1, +1.0, -1e5, 1000.0), samples({1}, {0.0}, {1e5}, {400}), Mode::Characteristic);
  EXPECT_GT(in.pressure[0], 1e5);
  EXPECT_LT(out.pressure[0], 1e5);
  EXPECT_DOUBLE_EQ(in.normal_velocity[0], (400 * 0.0 + 1000 * 1.0) / 1400.0);  // velocity projected on the normal
}

TEST(InterfaceConditions, PerPhaseWeightingAndVolumeAverage) {
  // Two phases with different impedances see different interface states; the solid gets sum alpha p_I.
  const auto st = interface_conditions(
      face(1, 0.0, -1e5, 1000.0), samples({0.25, 0.75}, {1.0, 1.0}, {2e5, 2e5}, {1000.0, 3000.0}), Mode::Impedance);
  ASSERT_EQ(st.pressure.size(), 2u);
  EXPECT_DOUBLE_EQ(st.pressure[0], 0.5 * 2e5 + 0.5 * 1e5);    // w_s = 1/2
  EXPECT_DOUBLE_EQ(st.pressure[1], 0.25 * 2e5 + 0.75 * 1e5);  // w_s = 1/4
  EXPECT_DOUBLE_EQ(st.normal_velocity[0], 0.5);
  EXPECT_DOUBLE_EQ(st.normal_velocity[1], 0.75);
  EXPECT_DOUBLE_EQ(st.face_pressure[0], 0.25 * st.pressure[0] + 0.75 * st.pressure[1]);
  EXPECT_DOUBLE_EQ(st.face_normal_velocity[0], 0.25 * 0.5 + 0.75 * 0.75);
}

TEST(InterfaceConditions, UnwettedFacesGetNoLoadAndCountsMustMatch) {
  auto s = samples({1}, {0.0}, {1e5}, {400});
  s.wetted = {0};
  const auto st = interface_conditions(face(1, 3.0, -2e5, 1000.0), s, Mode::Impedance);
  EXPECT_EQ(st.face_pressure[0], 0.0);
  EXPECT_EQ(st.normal_velocity[0], 3.0);
  s.count = 2;
  EXPECT_THROW(interface_conditions(face(1, 0, 0, 1), s, Mode::Impedance), std::invalid_argument);
}

// Robin (methods §4.4): the fluid gets the wall's velocity and the pressure along its incoming characteristic
// p_f - z_f (v_f - v_s), whatever the solid's impedance (its own step takes the rest); the solid gets the
// alpha-weighted fluid impedance with it, so that face_pressure + Z (v - v_s) is the alpha-weighted sum of the
// phases' characteristics at any wall velocity v. Unwetted faces: no load, no impedance.
TEST(InterfaceConditions, RobinGivesTheFluidsCharacteristicAndImpedance) {
  for (double z_s : {1e-6, 1000.0, std::numeric_limits<double>::infinity()}) {
    const auto pt = interface_point(Mode::Robin, 2.0, -3e5, z_s, -1.0, 1e5, 400.0);
    EXPECT_EQ(pt.velocity, 2.0);
    EXPECT_DOUBLE_EQ(pt.pressure, 1e5 + 400.0 * (2.0 + 1.0));
  }
  const auto st = interface_conditions(face(1, 0.5, -1e5, 1000.0),
                                       samples({0.25, 0.75}, {1.0, -2.0}, {2e5, 3e5}, {1000.0, 3000.0}), Mode::Robin);
  ASSERT_EQ(st.face_impedance.size(), 1u);
  EXPECT_DOUBLE_EQ(st.face_impedance[0], 0.25 * 1000.0 + 0.75 * 3000.0);
  for (double v : {-3.0, 0.5, 7.0}) {
    const double phases = 0.25 * (2e5 + 1000.0 * (v - 1.0)) + 0.75 * (3e5 + 3000.0 * (v + 2.0));
    EXPECT_NEAR(st.face_pressure[0] + st.face_impedance[0] * (v - 0.5), phases, 1e-9 * phases) << v;
  }
  EXPECT_EQ(st.face_normal_velocity[0], 0.5);
  auto dry = samples({1}, {0.0}, {1e5}, {400});
  dry.wetted = {0};
  const auto u = interface_conditions(face(1, 3.0, -2e5, 1000.0), dry, Mode::Robin);
  EXPECT_EQ(u.face_pressure[0], 0.0);
  EXPECT_EQ(u.face_impedance[0], 0.0);
}

// In Robin mode the predictor extrapolates the normal velocities with the pressures (the characteristic
// p - z u at t^{n+1}); by default it leaves them alone.
TEST(PressurePredictor, RobinModeExtrapolatesTheVelocityToo) {
  for (bool with_velocity : {false, true}) {
    PressurePredictor pp(with_velocity);
    FluidSamples a = samples({1}, {1.0}, {1e5}, {400}), b = samples({1}, {2.0}, {1.1e5}, {400});
    pp.apply(a, 0.0, 0.1);
    pp.apply(b, 0.1, 0.05);
    EXPECT_DOUBLE_EQ(b.pressure[0], 1.15e5);
    EXPECT_DOUBLE_EQ(b.normal_velocity[0], with_velocity ? 2.5 : 2.0);
  }
}

// The coupler's pressure predictor (coupler/pressure_predictor.h): pressures linear in time reach t + dt
// exactly; a face not wetted in both samples, a non-positive extrapolation and the first sample stay as they
// are; a second sample at the same time (cycles 0 and 1) is no history.
TEST(PressurePredictor, LinearInTimeIsExtrapolatedExactly) {
  PressurePredictor pp;
  const auto samples = [](double p0, double p1, char w1) {
    FluidSamples s;
    s.count = 2;
    s.phases = 1;
    s.pressure = {p0, p1};
    s.wetted = {1, w1};
    return s;
  };
  auto s = samples(1e5, 2e5, 1);
  pp.apply(s, 0.0, 0.0);  // cycle 0: first sample, no change
  EXPECT_EQ(s.pressure, (std::vector<double>{1e5, 2e5}));
  s = samples(1e5, 2e5, 1);
  pp.apply(s, 0.0, 1e-3);  // cycle 1: the same time again, no history yet
  EXPECT_EQ(s.pressure, (std::vector<double>{1e5, 2e5}));
  // t = 1e-3: p0 rises by 100 Pa per ms, p1 falls by 250 Pa per ms (face 1 now dry), next step 2e-3.
  s = samples(1e5 + 100, 2e5 - 250, 0);
  pp.apply(s, 1e-3, 2e-3);
  EXPECT_NEAR(s.pressure[0], 1e5 + 300, 1e-9);  // p(t + dt) of the linear history
  EXPECT_EQ(s.pressure[1], 2e5 - 250);          // not wetted now: as sampled
  // A collapse that would extrapolate below zero keeps the sample.
  s = samples(10.0, 2e5 - 500, 1);
  pp.apply(s, 2e-3, 1e-3);
  EXPECT_EQ(s.pressure[0], 10.0);
  EXPECT_EQ(s.pressure[1], 2e5 - 500);  // was not wetted in the previous sample
}
