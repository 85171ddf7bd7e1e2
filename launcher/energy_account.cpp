#include "launcher/energy_account.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "common/io/atomic_file.h"

namespace cosim::launcher {

namespace {
nlohmann::json read_json(const std::filesystem::path& p) {
  std::ifstream in(p);
  if (!in) throw std::runtime_error(fmt::format("{} is missing", p.string()));
  return nlohmann::json::parse(in);
}

double phase_energy(const nlohmann::json& totals) {
  double e = 0;
  for (const auto& phase : totals) e += phase.at("energy").get<double>();
  return e;
}
}  // namespace

std::string write_energy_account(const std::filesystem::path& dir) {
  try {
    const nlohmann::json f = read_json(dir / "fluid" / "summary.json");
    const nlohmann::json s = read_json(dir / "solid" / "summary.json");
    const double f0 = phase_energy(f.at("totals").at("start")), f1 = phase_energy(f.at("totals").at("end"));
    const auto& se = s.at("energy");
    const double s0 = se.at("start").at("total").get<double>(), s1 = se.at("end").at("total").get<double>();
    const double work = se.at("end").at("boundary_work").get<double>();
    const double inflow = se.at("end").value("ale_inflow", 0.0);
    const double total = (f1 - f0) + (s1 - s0);
    const auto& ft = f.at("totals");
    const double fin = ft.contains("boundary_inflow") ? phase_energy(ft.at("boundary_inflow")) : 0.0;
    nlohmann::json a;
    a["fluid"] = {{"start", f0}, {"end", f1}, {"change", f1 - f0}, {"boundary_inflow", fin}};
    a["solid"] = {{"start", s0}, {"end", s1}, {"change", s1 - s0}, {"boundary_work", work}, {"ale_inflow", inflow}};
    a["total_change"] = total;
    a["total_change_relative"] = (f0 + s0) != 0 ? total / std::abs(f0 + s0) : 0.0;
    a["interface_created"] = total - fin;
    a["interface_created_relative"] = (f0 + s0) != 0 ? (total - fin) / std::abs(f0 + s0) : 0.0;
    a["meaning"] =
        "total_change = fluid change + solid change; interface_created = total_change - fluid.boundary_inflow (the "
        "energy through the fluid's domain boundary): what the interface created (> 0) or lost (< 0), plus the work "
        "of the solid's own boundaries (fluid: flow cells, all phases; solid: internal + kinetic; J, per metre of "
        "depth in 2D)";
    io::write_file_atomically(dir / "energy_account.json", a.dump(2) + "\n");
  } catch (const std::exception& e) { return e.what(); }
  return "";
}

}  // namespace cosim::launcher
