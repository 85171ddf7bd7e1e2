// The per-pass clocks of a time step: they change no result, they account for the step's time, and each pass is
// charged where (and only where) the scene does that work.
#include <gtest/gtest.h>

#include <chrono>

#include "fluid_test_utils.h"

namespace cosim::fluid::test {
namespace {

FluidScene scene(const char* file, int cells) {
  FluidScene s = load_fluid_scene(std::string(COSIM_SOURCE_DIR) + "/" + file,
                                  {fmt::format("fluid.mesh.cells=[{},{}]", cells, cells)});
  s.threads = 1;  // thread-seconds are then wall seconds
  return s;
}

struct Timed {
  PassTimes times;
  double wall = 0;
  std::vector<PhaseTotals> totals;
  std::vector<double> rho;
};

Timed run(const FluidScene& s, bool profile, int steps) {
  auto sim = make_simulation(s);
  sim->set_pass_profiling(profile);
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) sim->advance(sim->stable_dt());
  Timed r{sim->pass_times(), std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
          sim->totals(), sim->phase_fields(0).rho};
  return r;
}

double sum(const PassTimes& t) {
  double s = 0;
  for (double x : t.seconds) s += x;
  return s;
}

TEST(PassProfile, ClocksChangeNoResultAndAccountForTheStep) {
  const FluidScene s = scene("bench/fluid/riemann_2d.yaml", 200);
  const Timed off = run(s, false, 20), on = run(s, true, 20);
  EXPECT_EQ(off.rho, on.rho);  // bit for bit
  EXPECT_EQ(sum(off.times), 0.0);
  for (int p = 0; p < kPassCount; ++p) EXPECT_GE(on.times.seconds[p], 0.0) << kPassNames[p];
  // One thread: the passes cover the step but for the serial glue between them, and never more than the wall.
  std::printf("[ measured ] passes %.4f s of a %.4f s step loop\n", sum(on.times), on.wall);
  EXPECT_LE(sum(on.times), on.wall * 1.0001);
  EXPECT_GE(sum(on.times), 0.8 * on.wall);
  for (Pass p : {Pass::Primitives, Pass::WaveRate, Pass::Reconstruction, Pass::Fluxes, Pass::Apply, Pass::Update})
    EXPECT_GT(on.times[p], 0.0) << kPassNames[static_cast<int>(p)];
  EXPECT_EQ(on.times[Pass::Relaxation], 0.0);  // a single phase relaxes nothing
  EXPECT_EQ(on.times[Pass::Exchange], 0.0);
}

TEST(PassProfile, TwoPhaseRelaxationAndExchangeAreCharged) {
  const FluidScene s = scene("bench/fluid/two_phase_2d.yaml", 64);
  ASSERT_EQ(s.num_phases(), 2);
  const Timed off = run(s, false, 5), on = run(s, true, 5);
  EXPECT_EQ(off.rho, on.rho);
  EXPECT_GT(on.times[Pass::Relaxation], 0.0);
  EXPECT_GT(on.times[Pass::Exchange], 0.0);
  EXPECT_LE(sum(on.times), on.wall * 1.0001);
}

}  // namespace
}  // namespace cosim::fluid::test
