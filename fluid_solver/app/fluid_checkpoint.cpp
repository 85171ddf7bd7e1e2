#include "fluid_solver/app/fluid_checkpoint.h"

#include "common/checkpoint/checkpoint_sets.h"
#include "common/checkpoint/output_resume.h"
#include "common/checkpoint/part_file.h"

namespace cosim::fluid {

std::string write_fluid_part(const std::filesystem::path& dir, const FluidSimulation& sim,
                             const io::SnapshotSeries& series, const FluidRunState& run,
                             const coupled::CoupledBoundary* boundary) {
  checkpoint::PartWriter w(dir / kFluidPart, "fluid");
  w.put_integer("cycle", run.cycle);
  w.put_scalar("time", run.time);
  sim.save_state(w);
  if (boundary) boundary->save(w);
  checkpoint::put_series(w, "fluid", series);
  w.put_text("run.start_totals", run.start_totals.dump());
  w.put_text("run.counters", run.counters.dump());
  w.commit();
  return kFluidPart;
}

FluidRunState read_fluid_part(const std::filesystem::path& set, FluidSimulation& sim, io::SnapshotSeries& series,
                              coupled::CoupledBoundary* boundary) {
  const checkpoint::PartReader r = checkpoint::open_verified_part(set, kFluidPart, "fluid");
  FluidRunState run;
  run.cycle = r.integer("cycle");
  run.time = r.scalar("time");
  sim.restore_state(r);
  if (boundary) boundary->restore(r);
  checkpoint::resume_series(r, "fluid", series);
  // and the interface segments that go with the removed snapshots (fluid_output.h)
  io::remove_numbered_files(series.xdmf_path().parent_path(), "fluid_interface_", ".csv", series.count());
  run.start_totals = nlohmann::json::parse(r.text("run.start_totals"));
  run.counters = nlohmann::json::parse(r.text("run.counters"));
  return run;
}

}  // namespace cosim::fluid
