#include "solid_solver/app/solid_checkpoint.h"

#include "common/checkpoint/output_resume.h"
#include "common/checkpoint/part_file.h"

namespace cosim::solid {

std::string write_solid_part(const std::filesystem::path& dir, const Simulation& sim, const io::SnapshotSeries& series,
                             const BlockHistory& history, const SolidRunState& run) {
  checkpoint::PartWriter w(dir / kSolidPart, "solid");
  w.put_integer("cycle", run.cycle);
  w.put_scalar("time", run.time);
  sim.save_state(w);
  checkpoint::put_series(w, "solid", series);
  history.save(w);
  const double start[4] = {run.start.internal, run.start.kinetic, run.start.boundary_work, run.start.ale_inflow};
  w.put("run.start_energy", std::span<const double>(start, 4));
  w.put("run.last.face_pressure", run.last.face_pressure);
  w.put("run.last.face_impedance", run.last.face_impedance);
  w.put("run.last.face_normal_velocity", run.last.face_normal_velocity);
  w.put_flags("run.last.face_wetted", run.last.face_wetted);
  w.put_integer("run.last.count", run.last.count);
  w.put_integer("run.apply_velocity", run.apply_velocity ? 1 : 0);
  w.put_text("run.counters", run.counters.dump());
  w.commit();
  return kSolidPart;
}

SolidRunState read_solid_part(const checkpoint::PartReader& r, Simulation& sim, io::SnapshotSeries* series) {
  SolidRunState run;
  run.cycle = r.integer("cycle");
  run.time = r.scalar("time");
  sim.restore_state(r);
  if (series) checkpoint::resume_series(r, "solid", *series);
  const std::vector<double> start = r.doubles("run.start_energy", 4);
  run.start = {start[0], start[1], start[2], start[3]};
  run.last.count = static_cast<int>(r.integer("run.last.count"));
  run.last.face_pressure = r.doubles("run.last.face_pressure");
  run.last.face_impedance = r.doubles("run.last.face_impedance");
  run.last.face_normal_velocity = r.doubles("run.last.face_normal_velocity");
  run.last.face_wetted = r.flags("run.last.face_wetted");
  run.apply_velocity = r.integer("run.apply_velocity") != 0;
  run.counters = nlohmann::json::parse(r.text("run.counters"));
  return run;
}

}  // namespace cosim::solid
