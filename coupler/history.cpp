#include "coupler/history.h"

#include <fmt/format.h>

#include <array>
#include <chrono>

#include "common/coupling/errors.h"

namespace cosim::coupler {

namespace {
std::ofstream open(const std::filesystem::path& p) {
  std::ofstream f(p);
  if (!f) throw coupling::CouplingError(fmt::format("{}: cannot write", p.string()));
  return f;
}
}  // namespace

History::History(const std::filesystem::path& dir) : dir_(dir) {
  hist_ = open(dir / "interface_history.csv");
  timing_ = open(dir / "timing.csv");
  hist_ << "cycle,time,dt,force_x,force_y,force_z,velocity_x,velocity_y,velocity_z,centre_x,centre_y,centre_z,"
           "pressure\n";
  timing_ << "cycle,wall,solid,fluid,coupler,comm\n";
}

void History::record(long cycle, double time, double dt, const coupling::Faces& faces,
                     const coupling::InterfaceStates& st, const CycleTiming& t) {
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
  hist_ << fmt::format("{},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g}\n",
                       cycle, time, dt, force[0], force[1], force[2], vel[0] * inv, vel[1] * inv, vel[2] * inv,
                       centre[0] * inv, centre[1] * inv, centre[2] * inv, pressure * inv);
  timing_ << fmt::format("{},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e}\n", cycle, t.wall, t.solid, t.fluid, t.coupler, t.comm());
}

void History::progress(long cycle, double time, double t_end, bool force) {
  const double now = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  if (!force && now - last_progress_ < 0.5) return;
  last_progress_ = now;
  hist_.flush();
  timing_.flush();
  const auto tmp = dir_ / "progress.txt.tmp";
  {
    std::ofstream f(tmp);
    f << fmt::format("{} {:.9g} {:.9g}\n", cycle, time, t_end);
  }
  std::error_code ec;
  std::filesystem::rename(tmp, dir_ / "progress.txt", ec);
}

}  // namespace cosim::coupler
