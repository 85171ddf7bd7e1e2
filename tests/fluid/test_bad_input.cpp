// Bad scene input: clear "file:line: key: expected ..." messages, non-zero exit, no output written.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "fluid_solver/core/memory_estimate.h"
#include "fluid_solver/core/scene.h"
#include "fluid_solver/core/simulation.h"
#include "tests/support/scratch_dir.h"

namespace cosim::fluid::test {
namespace {

const char* kGood = R"(name: good
fluid:
  mesh: {cells: [50], lower: [0.0], upper: [1.0]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: 0.01, cfl: 0.4}
  initial:
    state: {rho: 1.0, velocity: [0.0], p: 1.0}
)";

std::string error_of(const std::string& text, const std::vector<std::string>& sets = {}) {
  try {
    parse_fluid_scene(text, sets);
  } catch (const config::ConfigError& e) { return e.what(); }
  return "";
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  s.replace(s.find(from), from.size(), to);
  return s;
}

// A condensed library material far from its reference density is refused, naming the key, the density the state
// implies and the reference, unless the phase says it is meant; by temperature, metals get their true density.
TEST(SceneValidation, CondensedPhaseFarFromItsReferenceDensityIsRefused) {
  const std::string two_phase = R"(name: w
fluid:
  mesh: {cells: [20], lower: [0.0], upper: [1.0]}
  phases: [{name: air, material: air}, {name: drops, material: water}]
  time: {end: 0.01}
  initial:
    state: {p: 1.0e5, T: 300, velocity: [0.0], alpha: [0.9, 0.1]}
)";
  // water's stiffened gas with its true heat capacity: 1e5 Pa and 300 K would be 140.5 kg/m^3
  const std::string e = error_of(two_phase);
  EXPECT_NE(e.find("<scene>:7: fluid.initial.state.T: expected a state of phase 'drops' (material water) within 10% "
                   "of its reference density 1000 kg/m^3, but T = 300 K at p = 100000 Pa gives rho = 140.5 kg/m^3 "
                   "(0.141 times the reference); give rho instead of T"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("allow_off_reference_density: true"), std::string::npos) << e;
  // given by its density it is fine; a density 35x too high is refused the same way, unless allowed
  const std::string by_rho = replace(two_phase, "T: 300, velocity", "rho: 1.2, velocity");
  EXPECT_EQ(error_of(replace(by_rho, "alpha: [0.9, 0.1]}", "alpha: [0.9, 0.1], phases: [{}, {rho: 1000}]}")), "");
  const std::string dense = replace(by_rho, "alpha: [0.9, 0.1]}", "alpha: [0.9, 0.1], phases: [{}, {rho: 35000}]}");
  EXPECT_NE(error_of(dense).find("fluid.initial.state.rho: expected a state of phase 'drops' (material water) within "
                                 "10% of its reference density 1000 kg/m^3, but rho = 3.5e+04 kg/m^3 is (35 times"),
            std::string::npos)
      << error_of(dense);
  EXPECT_EQ(error_of(replace(dense, "material: water}", "material: water, allow_off_reference_density: true}")), "");
  // tungsten by temperature: its density (the scene is accepted), cold and hot
  FluidScene s = parse_fluid_scene(replace(two_phase, "material: water", "material: tungsten"));
  EXPECT_NEAR(s.background[1].rho, 19221, 10);
  s = parse_fluid_scene(replace(replace(two_phase, "material: water", "material: tungsten"), "T: 300", "T: 3000"));
  EXPECT_NEAR(s.background[1].rho, 17924, 10);
}

TEST(SceneValidation, GoodSceneParses) { EXPECT_EQ(error_of(kGood), ""); }

TEST(SceneValidation, TypoSuggestsClosestKey) {
  std::string e = error_of(replace(kGood, "cfl: 0.4", "clf: 0.4"));
  EXPECT_NE(e.find("<scene>:5: fluid.time.clf: unknown key (did you mean 'cfl'?)"), std::string::npos) << e;
}

// A required key that is missing while the section has a key close to it: the typo is named.
TEST(SceneValidation, MissingKeyNamesTheTypoThatTookItsPlace) {
  const std::string e = error_of(replace(kGood, "cells: [50]", "cell: [50]"));
  EXPECT_NE(e.find("<scene>:3: fluid.mesh.cells: expected a list of 1 to 3 numbers, but the key is missing (did "
                   "you mean 'cell', given at line 3?)"),
            std::string::npos)
      << e;
  const std::string e2 = error_of(replace(kGood, "  time: {end: 0.01, cfl: 0.4}", "  tiem: {end: 0.01, cfl: 0.4}"));
  EXPECT_NE(e2.find("fluid.time: expected a section, but the key is missing (did you mean 'tiem', given at line 5?)"),
            std::string::npos)
      << e2;
}

TEST(SceneValidation, NegativeCflIsRejected) {
  std::string e = error_of(replace(kGood, "cfl: 0.4", "cfl: -0.4"));
  EXPECT_NE(e.find("<scene>:5: fluid.time.cfl: expected a number in (0, 1], got '-0.4'"), std::string::npos) << e;
}

TEST(SceneValidation, WrongTypeMissingKeyAndBadChoice) {
  EXPECT_NE(error_of(replace(kGood, "end: 0.01", "end: soon")).find("fluid.time.end: expected a number, got 'soon'"),
            std::string::npos);
  EXPECT_NE(error_of(replace(kGood, "end: 0.01, ", ""))
                .find("fluid.time.end: expected a value (a number), but the key is missing"),
            std::string::npos);
  std::string e = error_of(kGood, {"fluid.numerics.flux=aufz"});
  EXPECT_NE(e.find("--set fluid.numerics.flux: fluid.numerics.flux: expected one of aufs | hllc | rusanov (did you "
                   "mean 'aufs'?)"),
            std::string::npos)
      << e;
  EXPECT_NE(error_of(replace(kGood, "cells: [50]", "cells: [50, 0]")).find("fluid.mesh.cells"), std::string::npos);
  EXPECT_NE(error_of(replace(kGood, "p: 1.0}", "p: -1.0}")).find("p + pinf > 0"), std::string::npos);
  EXPECT_NE(error_of(replace(kGood, "fluid:", "fluidd:")).find("unknown key (did you mean 'fluid'?)"),
            std::string::npos);
}

TEST(SceneValidation, MalformedYamlNamesLine) {
  std::string e = error_of(replace(kGood, "cfl: 0.4}", "cfl: 0.4"));
  EXPECT_NE(e.find("<scene>:"), std::string::npos) << e;
  EXPECT_NE(e.find("YAML syntax error"), std::string::npos) << e;
}

TEST(SceneValidation, OverridesApply) {
  FluidScene s = parse_fluid_scene(kGood, {"fluid.time.cfl=0.2", "fluid.mesh.cells=[80]", "fluid.numerics.flux=hllc"});
  EXPECT_EQ(s.cfl, 0.2);
  EXPECT_EQ(s.cells[0], 80);
  EXPECT_EQ(s.flux, FluxKind::HLLC);
  EXPECT_NE(error_of(kGood, {"fluid.time.cfl"}).find("expected key.path=value"), std::string::npos);
}

// Runs the real executable; returns the exit code and fills stderr.
int run_solver(const std::string& scene_text, const std::filesystem::path& out, std::string& err) {
  const auto dir = cosim::test::scratch_path("bad_input");
  std::filesystem::create_directories(dir);
  const auto scene = dir / "scene.yaml";
  std::ofstream(scene) << scene_text;
  const std::string cmd = std::string(COSIM_BINARY_DIR) + "/bin/fluid_solver " + scene.string() + " --quiet --out " +
                          out.string() + " 2>" + (dir / "err.txt").string();
  const int status = std::system(cmd.c_str());
  std::ifstream in(dir / "err.txt");
  err.assign(std::istreambuf_iterator<char>(in), {});
  return WEXITSTATUS(status);
}

TEST(FluidSolverExecutable, BadInputExitsNonZeroWithMessage) {
  const auto out = cosim::test::scratch_path("bad_out");
  std::string err;
  EXPECT_EQ(run_solver(replace(kGood, "cfl: 0.4", "cfl: -1"), out, err), 2);
  EXPECT_NE(err.find("scene.yaml:5: fluid.time.cfl: expected a number in (0, 1], got '-1'"), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists(out / "summary.json"));
  EXPECT_EQ(run_solver(replace(kGood, "cfl: 0.4", "cfll: 0.4"), out, err), 2);
  EXPECT_NE(err.find("did you mean 'cfl'?"), std::string::npos) << err;
  EXPECT_EQ(run_solver("fluid: [1, 2", out, err), 2);
  EXPECT_NE(err.find("YAML syntax error"), std::string::npos) << err;
  EXPECT_EQ(run_solver(kGood, out, err), 0) << err;
  EXPECT_TRUE(std::filesystem::exists(out / "summary.json"));
  {  // a 1D run has one row of cells: one thread, and waiting threads sleep (the user set no policy)
    std::ifstream in(out / "summary.json");
    const std::string summary((std::istreambuf_iterator<char>(in)), {});
    EXPECT_NE(summary.find("\"threads\": 1,"), std::string::npos) << summary;
    if (!std::getenv("OMP_WAIT_POLICY")) {
      EXPECT_NE(summary.find("\"omp_wait_policy\": \"PASSIVE\""), std::string::npos) << summary;
    }
  }
  EXPECT_TRUE(std::filesystem::exists(out / "fluid.xmf"));
  std::filesystem::remove_all(out);
}

// A state that cannot stay admissible (water pulled apart at +-2 km/s cavitates: p + pinf < 0,
// which a single-phase stiffened gas cannot represent) stops the run with a diagnostic naming the
// cell and the time, exit code 3, and the snapshots written before stay complete.
TEST(FluidSolverExecutable, InadmissibleStateStopsWithDiagnostic) {
  const std::string scene = R"(name: blowup
fluid:
  mesh: {cells: [100], lower: [0.0], upper: [1.0]}
  phases: [{name: water, material: water}]
  time: {end: 1.0e-4}
  initial:
    state: {rho: 1000.0, velocity: [-2000.0], p: 1.0e5}
    regions:
      - half_space: {point: [0.5], normal: [1.0]}
        state: {rho: 1000.0, velocity: [2000.0], p: 1.0e5}
  output: {interval: 1.0e-6}
)";
  const auto out = cosim::test::scratch_path("blowup");
  std::string err;
  const int code = run_solver(scene, out, err);
  EXPECT_EQ(code, 3) << err;
  EXPECT_NE(err.find("inadmissible state in cell (i="), std::string::npos) << err;
  EXPECT_NE(err.find("at t="), std::string::npos) << err;
  EXPECT_TRUE(std::filesystem::exists(out / "fluid_000000.h5"));
  for (const auto& f : std::filesystem::directory_iterator(out)) EXPECT_NE(f.path().extension(), ".tmp");
  std::filesystem::remove_all(out);
}

// Numbers that make no physical sense are refused at load time, naming the key: a speed of 1e300 m/s (it used to
// pass and fail later as p = -nan), and nan or inf anywhere a number is read.
TEST(SceneValidation, AbsurdAndNonFiniteNumbersAreRefusedAtLoad) {
  const std::string fast = error_of(replace(kGood, "velocity: [0.0]", "velocity: [-1.0e300]"));
  EXPECT_NE(fast.find("fluid.initial.state.velocity"), std::string::npos) << fast;
  EXPECT_NE(fast.find("speeds of at most 1e5 m/s"), std::string::npos) << fast;
  for (const char* bad : {"nan", ".nan", "inf", "-.inf"}) {
    const std::string e = error_of(replace(kGood, "rho: 1.0", std::string("rho: ") + bad));
    EXPECT_NE(e.find("fluid.initial.state.rho"), std::string::npos) << bad << ": " << e;
  }
  EXPECT_EQ(error_of(replace(kGood, "velocity: [0.0]", "velocity: [3.0e4]")), "");  // fast, but physical
}

// A mesh whose state cannot fit in the machine's memory is refused when the scene is read, before anything is
// allocated, naming the key, the memory it needs and what the machine has; the estimate is the solver's own
// allocation (within the row buffers, a few percent at a small size).
TEST(SceneValidation, AMeshTooLargeForTheMachineIsRefusedBeforeAnythingIsAllocated) {
  const std::string big =
      error_of(replace(replace(replace(kGood, "cells: [50]", "cells: [100000, 100000, 100000]"),
                               "lower: [0.0], upper: [1.0]", "lower: [0.0, 0.0, 0.0], upper: [1.0, 1.0, 1.0]"),
                       "velocity: [0.0]", "velocity: [0.0, 0.0, 0.0]"));
  EXPECT_NE(big.find("fluid.mesh.cells"), std::string::npos) << big;
  EXPECT_NE(big.find("1e+15 cells need about"), std::string::npos) << big;
  EXPECT_NE(big.find("available"), std::string::npos) << big;

  const FluidScene s = parse_fluid_scene(R"(
fluid:
  mesh: {cells: [24, 20, 16], lower: [0, 0, 0], upper: [1, 1, 1]}
  phases: [{name: air, material: air}, {name: tungsten, material: tungsten}]
  exchange: {velocity_relaxation: none, dispersed: true}
  time: {end: 1.0e-3}
  initial:
    state: {p: 1.0e5, T: 300, velocity: [0.0, 0.0, 0.0], alpha: [0.99, 0.01]}
)");
  const double estimate = static_cast<double>(estimated_state_bytes(s));
  const double actual = static_cast<double>(make_simulation(s)->state_bytes());
  std::printf("state of a 24 x 20 x 16 dispersed scene: estimated %.0f bytes, allocated %.0f\n", estimate, actual);
  EXPECT_GT(estimate, 0.85 * actual);
  EXPECT_LE(estimate, actual);
}

}  // namespace
}  // namespace cosim::fluid::test
