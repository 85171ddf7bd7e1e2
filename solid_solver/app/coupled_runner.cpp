// The solid's coupled run (paper section 8, step 1; docs/protocol.md): each cycle the solid advances by the
// coupler's step under the interface pressures of the previous cycle, reports its exterior faces, takes
// the new face pressures and proposes its stable step. Snapshots when the coupler asks.
#include <fmt/format.h>
#include <omp.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <optional>

#include "common/checkpoint/checkpoint_sets.h"
#include "common/coupling/client.h"
#include "common/coupling/scene_hash.h"
#include "common/coupling/solver_loop.h"
#include "solid_solver/app/run_summary.h"
#include "solid_solver/app/runner.h"
#include "solid_solver/app/solid_checkpoint.h"
#include "solid_solver/coupled/interface_faces.h"
#include "solid_solver/io/block_history.h"
#include "solid_solver/io/solid_output.h"

namespace cosim::solid {

int run_solid_coupled(const RunOptions& opt) {
  SolidRun run = prepare_solid_run(opt);
  if (!run.sim) return run.exit_code;
  const SolidScene& scene = run.scene;
  std::unique_ptr<Simulation>& sim = run.sim;
  app::install_interrupt_handlers();
  io::SnapshotSeries series(opt.out_dir, "solid");
  std::optional<checkpoint::PartReader> part;
  SolidRunState restored;
  if (!opt.restart.empty()) {
    try {
      part.emplace(checkpoint::open_verified_part(opt.restart, kSolidPart, "solid"));
      restored = read_solid_part(*part, *sim, series);
    } catch (const std::exception& e) {
      spdlog::error("--restart {}: {}", opt.restart.string(), e.what());
      return 2;
    }
  }
  std::unique_ptr<coupling::Client> client =
      coupling::connect_solver(opt, coupling::Role::Solid, "solid_solver", {}, restored.cycle, restored.time);
  if (!client) return 5;
  const InterfaceFaceMap map = make_interface_face_map(sim->boundary_faces());
  spdlog::info("{}: {}D, {} elements, {} interface faces, coupled through {}", scene.name, scene.dim,
               sim->mesh().num_elements, sim->boundary_faces().count, opt.coupler);

  std::unique_ptr<BlockHistory> history;
  try {
    history = std::make_unique<BlockHistory>(opt.out_dir, part ? &*part : nullptr);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return part ? 2 : 4;
  }
  long cycles = restored.counters.value("cycles", 0L);
  RunRecord rec;
  rec.start = part ? restored.start : sim->energy();
  double solver_seconds = restored.counters.value("solver_seconds", 0.0);
  long substeps = restored.counters.value("solid_steps", 0L);
  coupling::InterfaceStates last = restored.last;  // held over the substeps of the next cycle
  bool apply_velocity = restored.apply_velocity;
  // The coupler's states of a cycle, for the solid's next step.
  const auto apply_states = [&](const coupling::InterfaceStates& st) {
    sim->set_face_pressures(st.face_pressure);
    // Robin: the fluid's impedance enters the solid's own step (no imposed velocity); impedance and
    // characteristic: the nodes of wetted faces take the interface velocity.
    const bool robin = client->mode() == coupling::Mode::Robin;
    if (robin) {
      if (st.face_impedance.size() != st.face_pressure.size())
        throw std::invalid_argument(fmt::format("InterfaceStates.face_impedance: {} values for {} faces (mode robin)",
                                                st.face_impedance.size(), st.count));
      sim->set_face_impedances(st.face_impedance);
    }
    apply_velocity =
        !robin && client->mode() != coupling::Mode::Standard && st.face_wetted.size() == st.face_pressure.size();
    if (apply_velocity) sim->set_face_normal_velocities(st.face_normal_velocity, st.face_wetted);
    last = st;
  };
  if (part) {  // the set's cycle ended with these states: set again on the restored faces (at t^n, as then)
    sim->boundary_faces();
    apply_states(restored.last);
    part.reset();
    spdlog::info("restarted from cycle {} at t = {:.9g} s ({})", restored.cycle, restored.time, opt.restart.string());
  }
  const auto cycle = [&](const coupling::Directive& d) {
    const auto t0 = std::chrono::steady_clock::now();
    // With the face pressures of the previous cycle; in substeps when the coupled step is longer than the
    // solid's stable step (numerics.max_subcycles > 1), the interface pressure and velocity held over them.
    if (d.dt > 0) {
      const int n = std::max(1, static_cast<int>(std::ceil(d.dt / sim->stable_dt() - 1e-9)));
      if (n > scene.numerics.max_subcycles)
        throw app::NumericalError(
            fmt::format("the coupled step {:.4g} s needs {} solid substeps, more than "
                        "solid.numerics.max_subcycles = {}",
                        d.dt, n, scene.numerics.max_subcycles));
      for (int k = 0; k < n; ++k) {
        if (k > 0 && apply_velocity) sim->set_face_normal_velocities(last.face_normal_velocity, last.face_wetted);
        sim->advance(d.dt / n);
      }
      substeps += n;
    }
    const coupling::Faces faces = interface_faces(sim->boundary_faces(), map, sim->state());
    solver_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    client->send_faces(faces);
    // The proposal does not depend on the states: sent at once, so that in the pipelined cycle the coupler
    // can decide the next step as soon as the fluid has proposed.
    client->propose_dt(scene.numerics.max_subcycles * sim->stable_dt());
    const coupling::InterfaceStates st = client->receive_states();
    if (st.count != faces.count)
      throw std::invalid_argument(
          fmt::format("InterfaceStates.count = {} but the solid has {} interface faces", st.count, faces.count));
    if (static_cast<int>(st.face_pressure.size()) != st.count)
      throw std::invalid_argument(
          fmt::format("InterfaceStates.face_pressure: {} values for {} faces", st.face_pressure.size(), st.count));
    apply_states(st);
    if (scene.history_every > 0 && ++cycles % scene.history_every == 0)
      app::as_io("the block history", [&] { history->record(*sim); });
  };
  const auto output = [&](const coupling::Directive&) {
    app::as_io("writing a snapshot", [&] {
      if (scene.write_snapshots) write_snapshot(series, *sim);
      history->record(*sim);
    });
  };
  const auto checkpoint = [&](const coupling::Directive& d) {
    SolidRunState st{
        d.cycle, d.time,         rec.start,
        last,    apply_velocity, {{"cycles", cycles}, {"solver_seconds", solver_seconds}, {"solid_steps", substeps}}};
    return app::as_io("writing the checkpoint part",
                      [&] { return write_solid_part(d.directory, *sim, series, *history, st); });
  };
  const coupling::SolverLoopResult res = coupling::run_solver_loop(*client, *sim, cycle, output, checkpoint);
  rec.status = res.status;
  rec.error = res.error;
  rec.wall = res.wall;
  rec.extra["coupling"] = {{"endpoint", opt.coupler},
                           {"cycles", res.cycles},
                           {"snapshots", res.snapshots},
                           {"checkpoints", res.checkpoints},
                           {"restarted_from", opt.restart.empty() ? nlohmann::json() : nlohmann::json(restored.cycle)},
                           {"solver_seconds", solver_seconds},
                           {"solid_steps", substeps}};
  try {
    write_summary(opt.out_dir, *sim, rec);
  } catch (const std::exception& e) {
    spdlog::error("cannot write summary.json: {}", e.what());
    return res.code ? res.code : 4;
  }
  if (res.code == 0)
    spdlog::info("done: t = {:.6g} in {} cycles, {:.2f} s wall ({:.2f} s solid solver), {} snapshot(s) in {}",
                 sim->time(), res.cycles, res.wall, solver_seconds, series.count(), opt.out_dir.string());
  return res.code;
}

}  // namespace cosim::solid
