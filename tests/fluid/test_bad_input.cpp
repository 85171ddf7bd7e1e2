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

// An initial region that covers no cell is refused, naming the key: upper below lower; and a box, sphere or half-space
// that holds no cell centre at this resolution (outside the domain, or smaller than a cell between two centres), with
// the region, the domain and the cell size (it used to run a uniform tube with exit 0). A region that reaches past
// the domain, or holds one centre, is fine.
TEST(SceneValidation, InitialRegionThatCoversNoCellIsRefused) {
  const auto with_region = [](const std::string& region) {
    return std::string(kGood) + "    regions:\n      - " + region +
           "\n        state: {rho: 0.125, velocity: [0.0], p: 0.1}\n";
  };
  const std::string inverted = error_of(with_region("box: {lower: [0.7], upper: [0.2]}"));
  EXPECT_NE(inverted.find("<scene>:9: fluid.initial.regions.0.box.upper: expected upper >= lower in every direction"),
            std::string::npos)
      << inverted;
  const std::string outside = error_of(with_region("box: {lower: [2.0], upper: [3.0]}"));
  EXPECT_NE(outside.find("<scene>:9: fluid.initial.regions.0.box: expected a region that contains the centre of at "
                         "least one cell, but the box from [2] to [3] covers no cell (domain from [0] to [1], cells "
                         "of [0.02] m)"),
            std::string::npos)
      << outside;
  // cell centres at 0.01, 0.03, ...: a box between two of them
  const std::string thin = error_of(with_region("box: {lower: [0.011], upper: [0.029]}"));
  EXPECT_NE(thin.find("the box from [0.011] to [0.029] covers no cell"), std::string::npos) << thin;
  const std::string sphere = error_of(with_region("sphere: {center: [1.5], radius: 0.4}"));
  EXPECT_NE(sphere.find("fluid.initial.regions.0.sphere: expected a region that contains the centre of at least one "
                        "cell, but the sphere of radius 0.4 at [1.5] covers no cell"),
            std::string::npos)
      << sphere;
  const std::string half = error_of(with_region("half_space: {point: [0.995], normal: [1.0]}"));
  EXPECT_NE(half.find("the half-space through [0.995] with normal [1] covers no cell"), std::string::npos) << half;
  const std::string no_normal = error_of(with_region("half_space: {point: [0.5], normal: [0.0]}"));
  EXPECT_NE(no_normal.find("fluid.initial.regions.0.half_space.normal: expected a normal that is not zero"),
            std::string::npos)
      << no_normal;
  for (const char* fine : {"box: {lower: [0.5], upper: [2.0]}", "box: {lower: [0.009], upper: [0.011]}",
                           "box: {lower: [0.01], upper: [0.01]}", "sphere: {center: [1.2], radius: 0.215}",
                           "half_space: {point: [0.985], normal: [1.0]}", "half_space: {point: [2.0], normal: [-1.0]}"})
    EXPECT_EQ(error_of(with_region(fine)), "") << fine;
  // 2D, 10 x 10 cells, centres at 0.05 + 0.1 k: a circle between four centres, and one that reaches the nearest
  const std::string two_d = R"(fluid:
  mesh: {cells: [10, 10], lower: [0.0, 0.0], upper: [1.0, 1.0]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: 0.01}
  initial:
    state: {rho: 1.0, velocity: [0.0, 0.0], p: 1.0}
    regions:
      - sphere: {center: [0.1, 0.1], radius: 0.07}
        state: {rho: 0.125, velocity: [0.0, 0.0], p: 0.1}
)";
  const std::string circle = error_of(two_d);
  EXPECT_NE(circle.find("the sphere of radius 0.07 at [0.1, 0.1] covers no cell (domain from [0, 0] to [1, 1], "
                        "cells of [0.1, 0.1] m)"),
            std::string::npos)
      << circle;
  EXPECT_EQ(error_of(replace(two_d, "radius: 0.07", "radius: 0.071")), "");
}

// Phase names are identifiers (they name the output fields, NAME_density): an empty name, a leading digit, a space or
// a control byte is refused, naming the key and the value with its non-printable bytes escaped; two phases differ.
TEST(SceneValidation, PhaseNamesAreIdentifiers) {
  for (const auto& [yaml, shown] : std::vector<std::pair<std::string, std::string>>{
           {"''", "''"}, {"1gas", "'1gas'"}, {"'my gas'", "'my gas'"}, {"\"gas\\x1b[31m\"", "'gas\\x1b[31m'"}}) {
    const std::string e = error_of(replace(kGood, "name: gas", "name: " + yaml));
    EXPECT_NE(e.find("<scene>:4: fluid.phases.0.name: expected a phase name of ASCII letters, digits and '_' that does "
                     "not start with a digit (it names the output fields: NAME_density), got " +
                     shown),
              std::string::npos)
        << yaml << ": " << e;
    EXPECT_EQ(e.find('\x1b'), std::string::npos) << e;
  }
  EXPECT_EQ(error_of(replace(kGood, "name: gas", "name: _Gas_2")), "");
  const std::string twice = error_of(R"(fluid:
  mesh: {cells: [20], lower: [0.0], upper: [1.0]}
  phases: [{name: air, material: air}, {name: air, material: air}]
  time: {end: 0.01}
  initial:
    state: {p: 1.0e5, T: 300, velocity: [0.0], alpha: [0.5, 0.5]}
)");
  EXPECT_NE(twice.find("fluid.phases.1.name: expected a name that differs from the first phase's, got 'air' twice"),
            std::string::npos)
      << twice;
}

// Boundary values are checked at load, naming the key, the value and the range (they used to pass and fail later as a
// numerical failure, exit 3): pressures in (0, 1e13] Pa (a stiffened gas at p = -1 Pa included, though p + pinf > 0),
// densities in (0, 1e5] kg/m^3, temperatures in (0, 1e9] K and the density they give, speeds, per-phase values.
// Initial states get the same magnitudes (a pressure may be negative there, with p + pinf > 0).
TEST(SceneValidation, BoundaryValuesAreCheckedAtLoad) {
  const std::string inflow = replace(kGood, "  time:", R"(  boundaries:
    x_lower: {type: inflow, state: {rho: 1.0, velocity: [1.0], p: 1.0}}
  time:)");
  EXPECT_EQ(error_of(inflow), "");
  const auto boundary_error = [&](const std::string& state) {
    return error_of(replace(inflow, "state: {rho: 1.0, velocity: [1.0], p: 1.0}", "state: " + state));
  };
  struct Case {
    std::string state, expected;
  };
  for (const Case& c : std::vector<Case>{
           {"{rho: 1.0, velocity: [1.0], p: 1.0e300}",
            "<scene>:6: fluid.boundaries.x_lower.state.p: expected a boundary pressure in (0, 1e13] Pa, got '1.0e300'"},
           {"{rho: 1.0, velocity: [1.0], p: -1.0e300}",
            "fluid.boundaries.x_lower.state.p: expected a boundary pressure in (0, 1e13] Pa, got '-1.0e300'"},
           {"{rho: 1.0, velocity: [1.0], p: 0}",
            "fluid.boundaries.x_lower.state.p: expected a boundary pressure in (0, 1e13] Pa, got '0'"},
           {"{rho: 0, velocity: [1.0], p: 1.0}",
            "fluid.boundaries.x_lower.state.rho: expected a density in (0, 1e5] kg/m^3, got '0'"},
           {"{rho: 1.0e300, velocity: [1.0], p: 1.0}",
            "fluid.boundaries.x_lower.state.rho: expected a density in (0, 1e5] kg/m^3, got '1.0e300'"},
           {"{T: -3, velocity: [1.0], p: 1.0}",
            "fluid.boundaries.x_lower.state.T: expected a temperature in (0, 1e9] K, got '-3'"},
           {"{T: 1.0e300, velocity: [1.0], p: 1.0}",
            "fluid.boundaries.x_lower.state.T: expected a temperature in (0, 1e9] K, got '1.0e300'"},
           {"{T: 1.0e-30, velocity: [1.0], p: 1.0}",
            "fluid.boundaries.x_lower.state.T: expected a temperature that gives phase 'gas' a density in (0, 1e5] "
            "kg/m^3, but T = 1e-30 K at p = 1 Pa"},
           {"{rho: 1.0, velocity: [.inf], p: 1.0}", "fluid.boundaries.x_lower.state.velocity"},
           {"{rho: 1.0, velocity: [1.0e6], p: 1.0}",
            "fluid.boundaries.x_lower.state.velocity: expected entries that are speeds of at most 1e5 m/s"},
           {"{rho: 1.0, velocity: [1.0], p: .nan}", "fluid.boundaries.x_lower.state.p"}}) {
    const std::string e = boundary_error(c.state);
    EXPECT_NE(e.find(c.expected), std::string::npos) << c.state << ": " << e;
  }
  // water in tension: admissible (p + pinf > 0), but not as a boundary's reservoir; in the initial state it is
  const std::string water = replace(
      replace(replace(inflow, "{name: gas, eos: {type: ideal_gas, gamma: 1.4}}", "{name: water, material: water}"),
              "state: {rho: 1.0, velocity: [0.0], p: 1.0}", "state: {rho: 1000.0, velocity: [0.0], p: -1.0}"),
      "state: {rho: 1.0, velocity: [1.0], p: 1.0}", "state: {rho: 1000.0, velocity: [1.0], p: -1.0}");
  const std::string tension = error_of(water);
  EXPECT_NE(tension.find("fluid.boundaries.x_lower.state.p: expected a boundary pressure in (0, 1e13] Pa, got '-1.0'"),
            std::string::npos)
      << tension;
  EXPECT_EQ(error_of(replace(water, "velocity: [1.0], p: -1.0", "velocity: [1.0], p: 1.0e5")), "");
  // two phases: a per-phase value
  const std::string two = R"(fluid:
  mesh: {cells: [20], lower: [0.0], upper: [1.0]}
  phases: [{name: air, material: air}, {name: water, eos: {type: stiffened_gas, gamma: 4.4, pinf: 6.0e8, cv: 4186}}]
  time: {end: 0.01}
  boundaries:
    x_lower: {type: inflow, state: {p: 1.0e5, rho: 1.2, velocity: [0.0], alpha: [0.5, 0.5], phases: [{}, {p: -5}]}}
  initial:
    state: {p: 1.0e5, rho: 1.2, velocity: [0.0], alpha: [0.5, 0.5], phases: [{}, {rho: 1000}]}
)";
  const std::string per_phase = error_of(two);
  EXPECT_NE(per_phase.find("<scene>:6: fluid.boundaries.x_lower.state.phases.1.p: expected a boundary pressure in "
                           "(0, 1e13] Pa, got '-5'"),
            std::string::npos)
      << per_phase;
  EXPECT_EQ(error_of(replace(two, "{p: -5}", "{p: 5}")), "");
  // initial states: the same magnitudes
  const std::string huge = error_of(replace(kGood, "p: 1.0}", "p: 1.0e300}"));
  EXPECT_NE(huge.find("fluid.initial.state.p: expected a pressure of at most 1e13 Pa in magnitude, got '1.0e300'"),
            std::string::npos)
      << huge;
}

// The solver refuses such a scene with exit code 2 and writes nothing.
TEST(FluidSolverExecutable, RegionCoveringNoCellAndAbsurdBoundaryExitTwo) {
  const auto out = cosim::test::scratch_path("bad_region_out");
  std::string err;
  const std::string region = std::string(kGood) +
                             "    regions:\n      - box: {lower: [2.0], upper: [3.0]}\n"
                             "        state: {rho: 0.125, velocity: [0.0], p: 0.1}\n";
  EXPECT_EQ(run_solver(region, out, err), 2) << err;
  EXPECT_NE(err.find("scene.yaml:9: fluid.initial.regions.0.box: expected a region that contains the centre of at "
                     "least one cell"),
            std::string::npos)
      << err;
  EXPECT_FALSE(std::filesystem::exists(out / "summary.json"));
  const std::string boundary = replace(kGood, "  time:", R"(  boundaries:
    x_lower: {type: inflow, state: {rho: 1.0, velocity: [1.0], p: -1.0e300}}
  time:)");
  EXPECT_EQ(run_solver(boundary, out, err), 2) << err;
  EXPECT_NE(err.find("fluid.boundaries.x_lower.state.p: expected a boundary pressure in (0, 1e13] Pa"),
            std::string::npos)
      << err;
  EXPECT_FALSE(std::filesystem::exists(out / "summary.json"));
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace cosim::fluid::test
