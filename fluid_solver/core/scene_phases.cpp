// The fluid scene's phases (name, material, equation of state) and mixture states (scene_readers.h).
#include <fmt/format.h>

#include <cmath>

#include "common/eos/materials.h"
#include "fluid_solver/core/scene_readers.h"

namespace cosim::fluid::scene_readers {

using config::Node;

namespace {

eos::StiffenedGas read_eos(Node& n, const std::string& phase_name, std::string& material) {
  material = n.get<std::string>("material", "custom");
  eos::StiffenedGas sg;
  if (material != "custom") {
    const auto* m = eos::find_material(material);
    if (!m) {
      auto names = eos::material_names();
      names.push_back("custom");
      n.fail("material", config::one_of(names)(material));
    }
    sg = m->sg;
  }
  auto e = n.optional_child("eos");
  if (e) {
    std::string type = e->get<std::string>("type", "stiffened_gas", config::one_of({"ideal_gas", "stiffened_gas"}));
    sg.gamma = e->get<double>("gamma", sg.gamma, config::in_open_closed(1.0, 100.0));
    if (type == "stiffened_gas") sg.pinf = e->get<double>("pinf", sg.pinf, config::non_negative());
    else sg.pinf = 0.0;
    sg.q = e->get<double>("q", sg.q);
    sg.cv = e->get<double>("cv", sg.cv, config::positive());
    e->finish();
    sg.a0 = 0.0;
    if (const eos::Material* m = eos::find_material(material); m && m->mg) {  // refit the metal's temperature
      const auto fit =
          eos::with_reference_temperature(sg, m->reference_density, m->reference_pressure, m->reference_temperature);
      if (fit.a0 > 0.0) sg = fit;
    }
  } else if (material == "custom") {
    n.fail("eos", "an eos section (type, gamma, pinf, cv) for phase '" + phase_name + "' without a material");
  }
  return sg;
}

// A condensed library material (a metal, water) far from its reference density makes no physical sense at the
// pressures a scene starts from: refused with the value and its source unless the phase allows it.
void check_reference_density(const Node& n, const Phase& ph, const PhaseValue& v, std::optional<double> T) {
  const double ref = ph.reference_density;
  if (!(ref > 0.0) || ph.allow_off_reference_density || std::abs(v.rho / ref - 1.0) <= 0.1) return;
  const std::string given = T ? fmt::format("T = {:g} K at p = {:g} Pa gives rho = {:.4g} kg/m^3", *T, v.p, v.rho)
                              : fmt::format("rho = {:.4g} kg/m^3 is", v.rho);
  n.fail(T ? "T" : "rho",
         fmt::format("a state of phase '{}' (material {}) within 10% of its reference density {:g} kg/m^3, but {} "
                     "({:.3g} times the reference){}; set allow_off_reference_density: true in the phase if that "
                     "is meant",
                     ph.name, ph.material, ref, given, v.rho / ref, T ? "; give rho instead of T" : ""));
}

// Physical ranges of a state's values: beyond them a number is a typo or a unit slip, and fails later as a numerical
// failure (exit 3) instead of a scene error.
constexpr double kMaxPressure = 1e13;    // [Pa], 10 TPa
constexpr double kMaxDensity = 1e5;      // [kg/m^3], four times the densest element
constexpr double kMaxTemperature = 1e9;  // [K]

// A pressure of at most kMaxPressure in magnitude (p + pinf > 0 is checked with the phase); > 0 at an inflow
// boundary, whose ghost cells feed the state in every step: a liquid in tension there cavitates, which a stiffened
// gas cannot represent.
config::Check<double> pressure_range(bool boundary) {
  return [boundary](const double& v) {
    if (boundary ? v > 0.0 && v <= kMaxPressure : std::abs(v) <= kMaxPressure) return std::string();
    return std::string(boundary ? "a boundary pressure in (0, 1e13] Pa" : "a pressure of at most 1e13 Pa in magnitude");
  };
}
config::Check<double> density_range() {
  return [](const double& v) {
    return v > 0.0 && v <= kMaxDensity ? std::string() : std::string("a density in (0, 1e5] kg/m^3");
  };
}
config::Check<double> temperature_range() {
  return [](const double& v) {
    return v > 0.0 && v <= kMaxTemperature ? std::string() : std::string("a temperature in (0, 1e9] K");
  };
}

// [A-Za-z_][A-Za-z0-9_]*, in ASCII whatever the locale.
bool is_identifier(const std::string& s) {
  const auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  if (s.empty() || !letter(s[0])) return false;
  for (char c : s)
    if (!letter(c) && !(c >= '0' && c <= '9')) return false;
  return true;
}

}  // namespace

Phase read_phase(Node& n) {
  Phase ph;
  ph.name = n.require<std::string>("name");
  // The name prefixes the phase's output fields (NAME_density) and is quoted in messages.
  if (!is_identifier(ph.name))
    n.fail("name", fmt::format("a phase name of ASCII letters, digits and '_' that does not start with a digit (it "
                               "names the output fields: NAME_density), got '{}'",
                               config::printable(ph.name)));
  ph.eos = read_eos(n, ph.name, ph.material);
  if (const eos::Material* m = eos::find_material(ph.material); m && m->sg.pinf > 0.0)
    ph.reference_density = m->reference_density;  // a condensed material: its density is checked
  ph.allow_off_reference_density = n.get<bool>("allow_off_reference_density", false);
  n.finish();
  return ph;
}

MixtureValue read_state(Node& n, const std::vector<Phase>& phases, int dim, bool boundary) {
  const int np = static_cast<int>(phases.size());
  MixtureValue out(np);
  double p = n.get<double>("p", std::nan(""), pressure_range(boundary));
  std::optional<double> rho, T;
  if (n.has("rho")) rho = n.get<double>("rho", 0, density_range());
  if (n.has("T")) T = n.get<double>("T", 0, temperature_range());
  n.skip("rho");
  n.skip("T");
  auto vel = read_point(n, "velocity", dim, std::vector<double>(dim, 0.0), config::speed());
  std::vector<double> alphas;
  if (np == 1) {
    alphas = {1.0};
    n.get<double>("alpha", 1.0, config::in_range(1.0, 1.0));
  } else {
    alphas = n.get_vector("alpha", np, np, std::vector<double>{}, config::in_range(0.0, 1.0));
  }
  std::vector<std::optional<Node>> per_phase(np);
  if (n.has("phases")) {
    auto list = n.list("phases");
    if (static_cast<int>(list.size()) != np)
      n.fail("phases", fmt::format("a list of {} per-phase entries (one per phase)", np));
    for (int k = 0; k < np; ++k) per_phase[k] = list[k];
  }
  n.skip("phases");
  for (int k = 0; k < np; ++k) {
    PhaseValue& v = out[k];
    double pk = p, alpha = alphas.empty() ? std::nan("") : alphas[k];
    std::optional<double> rk = rho, Tk = T;
    auto velk = vel;
    if (per_phase[k]) {
      Node& q = *per_phase[k];
      for (const char* k2 : {"p", "alpha", "rho", "T"}) q.skip(k2);
      if (q.has("p")) pk = q.get<double>("p", 0, pressure_range(boundary));
      if (q.has("alpha")) alpha = q.get<double>("alpha", 0, config::in_range(0.0, 1.0));
      if (q.has("rho")) {
        rk = q.get<double>("rho", 0, density_range());
        Tk.reset();
      }
      if (q.has("T")) {
        Tk = q.get<double>("T", 0, temperature_range());
        if (!q.has("rho")) rk.reset();
      }
      velk = read_point(q, "velocity", dim, std::vector<double>(vel.begin(), vel.begin() + dim), config::speed());
      q.finish();
    }
    if (std::isnan(pk)) n.fail("p", fmt::format("a pressure [Pa] for phase '{}'", phases[k].name));
    if (std::isnan(alpha)) n.fail("alpha", fmt::format("a list of {} volume fractions", np));
    if (!rk && !Tk) n.fail("rho", fmt::format("rho [kg/m^3] or T [K] for phase '{}'", phases[k].name));
    v.alpha = alpha;
    v.p = pk;
    v.rho = rk ? *rk : phases[k].eos.density_from_pT(pk, *Tk);
    v.velocity = velk;
    if (!phases[k].eos.admissible(v.rho, v.p))
      n.fail("p", fmt::format("p + pinf > 0 for phase '{}' (p = {:g} Pa, pinf = {:g} Pa)", phases[k].name, v.p,
                              phases[k].eos.pinf));
    if (!rk && !density_range()(v.rho).empty())
      n.fail("T", fmt::format("a temperature that gives phase '{}' a density in (0, 1e5] kg/m^3, but T = {:g} K at "
                              "p = {:g} Pa gives rho = {:.4g} kg/m^3",
                              phases[k].name, *Tk, v.p, v.rho));
    check_reference_density(n, phases[k], v, rk ? std::nullopt : Tk);
  }
  if (np > 1) {
    double s = 0;
    for (auto& v : out) s += v.alpha;
    if (std::abs(s - 1.0) > 1e-9)
      n.fail("alpha", fmt::format("volume fractions that sum to 1 (they sum to {:.12g})", s));
  }
  n.finish();
  return out;
}

}  // namespace cosim::fluid::scene_readers
