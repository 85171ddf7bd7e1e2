#include "launcher/energy_account.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "common/io/atomic_file.h"

namespace cosim::launcher {

namespace {
double phase_energy(const nlohmann::json& totals) {
  double e = 0;
  for (const auto& phase : totals) e += phase.at("energy").get<double>();
  return e;
}

// A solver's summary.json, parsed; `why` says what is wrong when it cannot be read.
std::optional<nlohmann::json> read_summary(const std::filesystem::path& dir, const char* solver, std::string& why) {
  const std::filesystem::path p = dir / solver / "summary.json";
  std::ifstream in(p);
  if (!in) {
    why = fmt::format("{}/summary.json is missing", solver);
    return std::nullopt;
  }
  try {
    return nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    why = fmt::format("{}/summary.json is not JSON ({})", solver, e.what());
    return std::nullopt;
  }
}

// The fluid's part: `totals.start` and `totals.end` (per phase, `energy`) are needed, `totals.boundary_inflow`
// is optional (0).
std::optional<nlohmann::json> fluid_part(const std::filesystem::path& dir, std::string& why) {
  const auto f = read_summary(dir, "fluid", why);
  if (!f) return std::nullopt;
  if (!f->contains("totals")) {
    why = "fluid/summary.json has no \"totals\" block";
    return std::nullopt;
  }
  try {
    const auto& t = f->at("totals");
    const double f0 = phase_energy(t.at("start")), f1 = phase_energy(t.at("end"));
    const double in = t.contains("boundary_inflow") ? phase_energy(t.at("boundary_inflow")) : 0.0;
    return nlohmann::json{{"start", f0}, {"end", f1}, {"change", f1 - f0}, {"boundary_inflow", in}};
  } catch (const std::exception& e) {
    why = fmt::format("fluid/summary.json: \"totals\" unreadable ({})", e.what());
    return std::nullopt;
  }
}

// The solid's part: `energy.start.total` and `energy.end.total` are needed, `energy.end.boundary_work` and
// `energy.end.ale_inflow` are optional (0).
std::optional<nlohmann::json> solid_part(const std::filesystem::path& dir, std::string& why) {
  const auto s = read_summary(dir, "solid", why);
  if (!s) return std::nullopt;
  if (!s->contains("energy")) {
    why = "solid/summary.json has no \"energy\" block";
    return std::nullopt;
  }
  try {
    const auto& se = s->at("energy");
    const double s0 = se.at("start").at("total").get<double>(), s1 = se.at("end").at("total").get<double>();
    return nlohmann::json{{"start", s0},
                          {"end", s1},
                          {"change", s1 - s0},
                          {"boundary_work", se.at("end").value("boundary_work", 0.0)},
                          {"ale_inflow", se.at("end").value("ale_inflow", 0.0)}};
  } catch (const std::exception& e) {
    why = fmt::format("solid/summary.json: \"energy\" unreadable ({})", e.what());
    return std::nullopt;
  }
}
}  // namespace

std::string write_energy_account(const std::filesystem::path& dir) {
  std::string why_f, why_s;
  const auto f = fluid_part(dir, why_f);
  const auto s = solid_part(dir, why_s);
  if (!f && !s) return why_f + "; " + why_s;
  nlohmann::json a;
  a["fluid"] = f ? *f : nlohmann::json();
  a["solid"] = s ? *s : nlohmann::json();
  if (f && s) {
    const auto num = [](const nlohmann::json& j, const char* k) { return j.at(k).get<double>(); };
    const double f0 = num(*f, "start"), s0 = num(*s, "start"), fin = num(*f, "boundary_inflow");
    const double total = num(*f, "change") + num(*s, "change");
    a["total_change"] = total;
    a["total_change_relative"] = (f0 + s0) != 0 ? total / std::abs(f0 + s0) : 0.0;
    a["interface_created"] = total - fin;
    a["interface_created_relative"] = (f0 + s0) != 0 ? (total - fin) / std::abs(f0 + s0) : 0.0;
  } else {  // one side's part alone: no totals
    a["missing"] = f ? why_s : why_f;
    std::cerr << fmt::format(
        "cosim: energy_account.json has the {} part only: {} (optional; docs/protocol.md, "
        "\"summary.json\")\n",
        f ? "fluid's" : "solid's", f ? why_s : why_f);
  }
  a["meaning"] =
      "total_change = fluid change + solid change; interface_created = total_change - fluid.boundary_inflow (the "
      "energy through the fluid's domain boundary): what the interface created (> 0) or lost (< 0), plus the work "
      "of the solid's own boundaries (fluid: flow cells, all phases; solid: internal + kinetic; J, per metre of "
      "depth in 2D); a solver whose summary.json has no energy block has its part null and there are no totals";
  try {
    io::write_file_atomically(dir / "energy_account.json", a.dump(2) + "\n");
  } catch (const std::exception& e) { return e.what(); }
  return "";
}

}  // namespace cosim::launcher
