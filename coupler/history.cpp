#include "coupler/history.h"

#include <fmt/format.h>

#include <array>
#include <chrono>

#include "common/app/errors.h"
#include "common/checkpoint/output_resume.h"

namespace cosim::coupler {

namespace {
// The histories' lines reach the file whole or not at all (io::LineLog). A table that cannot be written is an I/O
// failure; one that cannot continue from the checkpoint (shorter than it recorded) a restart that cannot be used.
io::LineLog open(const std::filesystem::path& p, std::string_view header, const checkpoint::PartReader* resume,
                 const std::string& name) {
  if (resume) {
    try {
      return checkpoint::resume_log(*resume, name, p);
    } catch (const std::exception& e) { throw app::InputError(e.what()); }
  }
  return app::as_io(p.string(), [&] { return io::LineLog(p, header); });
}
void append(io::LineLog& log, const std::string& line) {
  app::as_io("interface history", [&] { log.append(line); });
}
}  // namespace

History::History(const std::filesystem::path& dir, const checkpoint::PartReader* resume)
    : dir_(dir),
      hist_(open(dir / "interface_history.csv",
                 "cycle,time,dt,force_x,force_y,force_z,velocity_x,velocity_y,velocity_z,centre_x,centre_y,centre_z,"
                 "pressure\n",
                 resume, "interface_history")),
      timing_(open(dir / "timing.csv", "cycle,wall,solid,fluid,coupler,output,comm\n", resume, "timing")),
      interface_(dir, "interface") {
  if (resume) {
    try {
      checkpoint::resume_series(*resume, "interface", interface_);
    } catch (const std::exception& e) { throw app::InputError(e.what()); }
    bool has_phases = false;  // the set of a one-phase run records no interface_phases.csv
    try {
      has_phases = resume->integer("log.interface_phases") >= 0;
    } catch (const std::exception&) {}
    if (has_phases) phases_.emplace(open(dir / "interface_phases.csv", "", resume, "interface_phases"));
  }
}

void History::save(checkpoint::PartWriter& w) const {
  checkpoint::put_log(w, "interface_history", hist_);
  checkpoint::put_log(w, "timing", timing_);
  checkpoint::put_series(w, "interface", interface_);
  if (phases_) checkpoint::put_log(w, "interface_phases", *phases_);
}

void History::record_phases(long cycle, double time, const coupling::Faces& faces,
                            const coupling::FluidSamples& samples, const coupling::InterfaceStates& st,
                            const std::vector<std::string>& names) {
  const int np = st.phases, d = faces.dim;
  const auto values = static_cast<std::size_t>(faces.count) * static_cast<std::size_t>(np);
  if (np < 2 || samples.alpha.size() != values || st.pressure.size() != values ||
      st.face_wetted.size() != static_cast<std::size_t>(faces.count))
    return;
  if (!phases_) {
    std::string header = "cycle,time";
    for (int k = 0; k < np; ++k) {
      const std::string n = static_cast<std::size_t>(np) == names.size() ? names[k] : fmt::format("phase{}", k);
      header += fmt::format(",{0}_force_x,{0}_force_y,{0}_force_z", n);
    }
    phases_.emplace(open(dir_ / "interface_phases.csv", header + "\n", nullptr, ""));
  }
  // The solid's face pressure is sum_k alpha_k p_I,k / sum_j alpha_j on wetted faces (interface_conditions):
  // phase k's share of the force -sum p A n is its term of that sum.
  std::vector<double> force(static_cast<std::size_t>(3 * np), 0.0);
  for (int f = 0; f < faces.count; ++f) {
    if (!st.face_wetted[f]) continue;
    double sum_a = 0.0;
    for (int k = 0; k < np; ++k) sum_a += samples.alpha[static_cast<std::size_t>(f) * np + k];
    if (!(sum_a > 0.0)) continue;
    for (int k = 0; k < np; ++k) {
      const std::size_t i = static_cast<std::size_t>(f) * np + k;
      const double load = samples.alpha[i] * st.pressure[i] / sum_a * faces.area[f];
      for (int c = 0; c < d; ++c) force[3 * k + c] -= load * faces.normal[f * d + c];
    }
  }
  std::string row = fmt::format("{},{:.12g}", cycle, time);
  for (const double v : force) row += fmt::format(",{:.12g}", v);
  append(*phases_, row + "\n");
}

void History::record(long cycle, double time, double dt, const coupling::Faces& faces,
                     const coupling::InterfaceStates& st) {
  std::array<double, 3> force{}, vel{}, centre{};
  double area = 0.0, pressure = 0.0;
  const int d = faces.dim;
  for (int f = 0; f < faces.count; ++f) {
    const double a = faces.area[f], p = st.face_pressure.empty() ? 0.0 : st.face_pressure[f];
    for (int c = 0; c < d; ++c) {
      force[c] -= p * a * faces.normal[f * d + c];
      vel[c] += a * faces.velocity[f * d + c];
      centre[c] += a * faces.centre[f * d + c];
    }
    area += a;
    pressure += a * p;
  }
  const double inv = area > 0 ? 1.0 / area : 0.0;
  append(hist_,
         fmt::format(
             "{},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g}\n",
             cycle, time, dt, force[0], force[1], force[2], vel[0] * inv, vel[1] * inv, vel[2] * inv, centre[0] * inv,
             centre[1] * inv, centre[2] * inv, pressure * inv));
}

double output_on_path(const CycleTiming& t, double solid_out, double fluid_out) {
  const double steps = t.steps();
  return std::max({solid_out + t.solid_on_path(), fluid_out + t.fluid_on_path(), steps}) - steps;
}

void History::record_timing(long cycle, const CycleTiming& t) {
  append(timing_, fmt::format("{},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e}\n", cycle, t.wall, t.solid, t.fluid,
                              t.coupler, t.output, t.comm()));
}

void History::progress(long cycle, double time, double t_end, double dt, bool force) {
  const double now = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  if (!force && now - last_progress_ < 0.5) return;
  last_progress_ = now;
  const auto tmp = dir_ / "progress.txt.tmp";
  {
    std::ofstream f(tmp);
    f << fmt::format("{} {:.9g} {:.9g} {:.9g}\n", cycle, time, t_end, dt);
  }
  std::error_code ec;
  std::filesystem::rename(tmp, dir_ / "progress.txt", ec);
}

void History::snapshot(long cycle, double time, const coupling::Faces& f, const coupling::InterfaceStates& st) {
  const bool polygons = (f.dim == 2 && f.nodes_per_face == 2) || (f.dim == 3 && f.nodes_per_face == 4);
  if (!polygons || f.count == 0 || st.count != f.count) return;
  const std::vector<std::int64_t> conn(f.face_vertex.begin(), f.face_vertex.end());
  const io::UnstructuredGrid g{
      f.dim,   f.vertex_position.data(), static_cast<std::int64_t>(f.vertex_position.size() / f.dim), conn.data(),
      f.count, f.nodes_per_face};
  std::vector<double> wetted(f.count, 1.0), p(f.count, 0.0), u(f.count, 0.0);
  for (int i = 0; i < f.count; ++i) {
    if (!st.face_wetted.empty()) wetted[i] = st.face_wetted[i] ? 1.0 : 0.0;
    if (!st.face_pressure.empty()) p[i] = st.face_pressure[i];
    if (!st.face_normal_velocity.empty()) u[i] = st.face_normal_velocity[i];
  }
  const std::vector<io::FieldView> fields = {{"pressure", p.data(), 1, io::Center::Cell},
                                             {"normal_velocity", u.data(), 1, io::Center::Cell},
                                             {"normal_stress", f.normal_stress.data(), 1, io::Center::Cell},
                                             {"impedance", f.impedance.data(), 1, io::Center::Cell},
                                             {"wetted", wetted.data(), 1, io::Center::Cell},
                                             {"normal", f.normal.data(), f.dim, io::Center::Cell},
                                             {"velocity", f.velocity.data(), f.dim, io::Center::Cell}};
  interface_.write(time, cycle, g, fields);
}

}  // namespace cosim::coupler
