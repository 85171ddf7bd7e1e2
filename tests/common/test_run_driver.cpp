// The standalone time loop (common/app/run_driver.h): a stable step that collapses stops the run as a numerical
// failure (exit code 3) naming the floor, with the snapshots written before it kept; it used to spin forever.
#include <gtest/gtest.h>

#include "common/app/run_driver.h"

namespace cosim::app {
namespace {

// A model whose stable step halves at every step after `healthy` steps (a tangling element).
struct Collapsing {
  double t = 0, dt0 = 1e-3;
  long n = 0, healthy = 20;
  double stable_dt() const { return n < healthy ? dt0 : dt0 * std::pow(0.5, static_cast<double>(n - healthy)); }
  void advance(double dt) {
    t += dt;
    ++n;
  }
  double time() const { return t; }
  long steps() const { return n; }
  std::string limiting_step() const { return "element 7"; }
};

TEST(RunDriver, ACollapsingStepStopsTheRunAsANumericalFailure) {
  Collapsing sim;
  DriveOptions o;
  o.output_times = {0.01, 0.02, 1.0};
  o.t_end = 1.0;
  o.max_steps = 1000000;
  o.quiet = true;
  int snapshots = 0;
  const DriveResult r = drive(sim, o, [&] { ++snapshots; });
  std::printf("%s after %ld steps, %d snapshots\n", r.error.c_str(), sim.steps(), snapshots);
  EXPECT_EQ(r.code, 3);
  EXPECT_EQ(r.status, "failed");
  EXPECT_NE(r.error.find("below the floor 1e-09 s (1e-6 of the first step); element 7"), std::string::npos) << r.error;
  EXPECT_LT(sim.steps(), 60);  // 20 healthy steps, then 20 halvings to reach 1e-6 of the first
  EXPECT_EQ(snapshots, 3);     // t = 0, 0.01 and 0.02 were written before the collapse
  o.dt_min = 1e-5;             // a scene's own floor
  Collapsing again;
  EXPECT_NE(drive(again, o, [] {}).error.find("below the floor 1e-05 s (numerics.dt_min)"), std::string::npos);
}

}  // namespace
}  // namespace cosim::app
