#include "coupler/cycle.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <nlohmann/json.hpp>
#include <thread>

#include "common/app/errors.h"
#include "common/app/run_driver.h"
#include "common/checkpoint/checkpoint_sets.h"
#include "common/checkpoint/part_file.h"
#include "common/coupling/errors.h"
#include "common/coupling/wire.h"
#include "coupler/history.h"
#include "coupler/interface_conditions.h"
#include "coupler/pressure_predictor.h"

namespace cosim::coupler {

using coupling::Role;
namespace pb = coupling::pb;

namespace {
double now_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

pb::Envelope envelope(const Hub& hub, long cycle, double t) {
  return coupling::make_envelope(Role::Coupler, hub.token(), cycle, t);
}
}  // namespace

double choose_dt(double proposal_min, double dt_max, double t, double t_next_output) {
  double dt = proposal_min;
  if (dt_max > 0) dt = std::min(dt, dt_max);
  const double remaining = t_next_output - t;
  if (dt >= remaining) return remaining;
  if (dt > 0.5 * remaining) return 0.5 * remaining;
  return dt;
}

namespace {

struct Loop {
  Loop(const CouplerConfig& c, Hub& h, const std::filesystem::path& dir, const CheckpointContext& k)
      : cfg(c), hub(h), ck(k), history(dir, k.restart), predictor(c.mode == coupling::Mode::Robin) {}
  const CouplerConfig& cfg;
  Hub& hub;
  const CheckpointContext& ck;
  History history;
  RunSummary sum;

  void send_both(pb::Envelope& e) {
    hub.send(Role::Fluid, e);
    hub.send(Role::Solid, e);
  }

  coupling::Faces last_faces;  // of the last cycle, for the interface snapshots
  coupling::InterfaceStates last_states;
  coupling::FluidSamples last_samples;  // of the last cycle (after the predictor), for interface_phases.csv
  PressurePredictor predictor;

  // Timing of the open cycle: from its DtDecision to the next one (or the end of the run); a cycle that writes a
  // checkpoint ends when both solvers have written their parts, and the next one begins there.
  CycleTiming open;
  long open_cycle = -1;
  double open_start = 0;
  struct Work {  // a peer's reported work at the start of the cycle, and in its checkpoint phase
    double busy = 0, output = 0;
  } start_f, start_s, ck_f, ck_s;
  double ck_wall = 0;          // the checkpoint phase (both parts requested .. both written) less the steps within it
  double own_output = 0;       // the coupler's interface snapshots in the open cycle [s]
  double output_sent = -1;     // when the open cycle's first OutputRequest went out (steady clock [s]; -1: none)
  double carry = 0;            // the cycle before, from its first OutputRequest to its end: the solvers wrote then
  double fluid_released = -1;  // when the open cycle's states went to the fluid (steady clock [s])
  double spill = 0;  // the cycle before, from its states to the fluid to its end: the pipelined fluid stepped then
  bool first_row = true;
  double first_solid_spill = 0, first_fluid_spill = 0;  // the first cycle: from each solver's Hello to its start

  void close_timing() {
    if (open_cycle < 0) return;
    open.wall = now_s() - open_start;
    const auto steps_and_output = [&](Role r, const Work& start, const Work& in_checkpoint) {
      const Peer& p = hub.peer(r);
      const double output = p.output - start.output - in_checkpoint.output;
      return std::pair{p.busy - start.busy - in_checkpoint.busy - output, output};
    };
    const auto [solid, solid_out] = steps_and_output(Role::Solid, start_s, ck_s);
    const auto [fluid, fluid_out] = steps_and_output(Role::Fluid, start_f, ck_f);
    open.solid = solid;
    open.fluid = fluid;
    open.overlapped = cfg.scheme == coupling::Scheme::Pipelined;
    if (open.overlapped) open.fluid_spill = spill;
    if (first_row) {
      open.solid_spill = first_solid_spill;
      open.fluid_spill = first_fluid_spill;
    }
    first_row = false;
    // The solvers' snapshots, requested at the end of the cycle before, ran beside the coupler's own there (carry)
    // and at once in both solvers; the checkpoint phase is its own stretch.
    open.output =
        own_output + ck_wall + output_on_path(open, std::max(0.0, solid_out - carry), std::max(0.0, fluid_out - carry));
    history.record_timing(open_cycle, open);
    sum.total.wall += open.wall;
    sum.total.solid += open.solid;
    sum.total.fluid += open.fluid;
    sum.total.coupler += open.coupler;
    sum.total.output += open.output;
    sum.total.overlapped = open.overlapped;
    open_cycle = -1;
  }

  void open_timing(long n) {
    if (open_cycle == n) return;  // opened at the end of the previous cycle's checkpoint
    close_timing();
    open = {};
    open_cycle = n;
    open_start = now_s();
    if (first_row) {  // a solver may set itself up between its Hello and its first message
      first_solid_spill = open_start - hub.peer(Role::Solid).last_seen;
      first_fluid_spill = open_start - hub.peer(Role::Fluid).last_seen;
    }
    const auto work_of = [&](Role r) { return Work{hub.peer(r).busy, hub.peer(r).output}; };
    start_f = work_of(Role::Fluid);
    start_s = work_of(Role::Solid);
    ck_f = ck_s = Work{};
    ck_wall = 0;
    carry = output_sent < 0 ? 0.0 : now_s() - output_sent;
    spill = fluid_released < 0 ? 0.0 : now_s() - fluid_released;
    fluid_released = -1;
    own_output = 0;
    output_sent = -1;
  }

  // Runs f as the coupler's own work of the open cycle (timed) and returns its result.
  template <class F>
  auto work(F&& f) {
    struct Clock {  // adds the elapsed time when the work is done, whatever it returns
      double& total;
      double start = now_s();
      ~Clock() { total += now_s() - start; }
    } clock{open.coupler};
    return f();
  }

  // One cycle; returns the smallest proposal for the next one. The coupler's order is the same in both
  // schemes: the fluid's place of its DtProposal (before or after its advance) makes the cycle pipelined.
  double cycle(long n, double t, double dt) {
    open_timing(n);
    pb::Envelope d = envelope(hub, n, t);
    d.mutable_dt_decision()->set_dt(dt);
    d.mutable_dt_decision()->set_target_time(t + dt);
    send_both(d);

    // Work that waits for the solid (faces) is done before the fluid's samples arrive; from the samples to the
    // fluid's states (the pipelined cycle's critical path) only the interface conditions.
    pb::Envelope faces_msg = hub.expect(Role::Solid, pb::Envelope::kFaces, n);
    pb::Envelope fwd = work([&] {
      last_faces = coupling::from_pb(faces_msg.faces());  // kept for the interface snapshots
      pb::Envelope e = envelope(hub, n, t + dt);
      e.mutable_faces()->Swap(faces_msg.mutable_faces());
      return e;
    });
    hub.send(Role::Fluid, fwd);
    pb::Envelope samples_msg = hub.expect(Role::Fluid, pb::Envelope::kSamples, n);

    const coupling::Faces& faces = last_faces;
    pb::Envelope to_fluid = work([&] {
      coupling::FluidSamples& samples = last_samples;
      samples = coupling::from_pb(samples_msg.samples());
      if (samples.count != faces.count)
        hub.reject(Role::Fluid,
                   fmt::format("sent FluidSamples.count = {}, but the solid has {} faces", samples.count, faces.count));
      if (cfg.pressure_predictor) predictor.apply(samples, t, dt);
      last_states = interface_conditions(faces, samples, cfg.mode);
      pb::Envelope e = envelope(hub, n, t + dt);
      coupling::to_pb(last_states, *e.mutable_states());
      e.mutable_states()->clear_face_pressure();
      e.mutable_states()->clear_face_normal_velocity();
      e.mutable_states()->clear_face_wetted();
      e.mutable_states()->clear_face_impedance();
      return e;
    });
    hub.send(Role::Fluid, to_fluid);
    fluid_released = now_s();
    pb::Envelope to_solid = work([&] {
      pb::Envelope e = envelope(hub, n, t + dt);
      coupling::to_pb(last_states, *e.mutable_states());
      e.mutable_states()->set_phases(0);
      e.mutable_states()->clear_pressure();
      e.mutable_states()->clear_normal_velocity();
      return e;
    });
    hub.send(Role::Solid, to_solid);

    auto proposals = hub.expect_both(pb::Envelope::kDtProposal, n);
    work([&] {
      history.record(n, t + dt, dt, faces, last_states);
      history.record_phases(n, t + dt, faces, last_samples, last_states, hub.peer(Role::Fluid).phase_names);
    });
    return std::min(proposals[0].dt_proposal().dt(), proposals[1].dt_proposal().dt());
  }

  // The state the loop starts from: cycle 0 at t = 0, or the cycle after a checkpoint set.
  struct Start {
    long cycle = 0;
    double time = 0, proposal = 0;
    int out_index = 0;
  };

  Start restore(const checkpoint::PartReader& r) {
    Start s;
    s.cycle = r.integer("cycle") + 1;
    s.time = r.scalar("time");
    s.proposal = r.scalar("proposal");
    s.out_index = static_cast<int>(r.integer("out_index"));
    predictor.restore(r);
    const std::vector<double> tot = r.doubles("run.totals", 5);
    sum.total.wall = tot[0];
    sum.total.solid = tot[1];
    sum.total.fluid = tot[2];
    sum.total.coupler = tot[3];
    sum.total.output = tot[4];
    sum.cycles = s.cycle - 1;
    sum.time = s.time;
    if (s.time >= cfg.t_end * (1.0 - 1e-14))
      throw app::InputError(
          fmt::format("--restart {}: the checkpoint is at t = {:.9g} s, at or after the "
                      "scene's end time coupling.time.end = {:g} s",
                      r.path().parent_path().string(), s.time, cfg.t_end));
    spdlog::info("restarted from cycle {} at t = {:.9g} s ({})", s.cycle - 1, s.time, r.path().parent_path().string());
    return s;
  }

  // Asks both solvers for their parts of set n; once both have confirmed, closes cycle n's timing (its row is then
  // part of the set) and, as work of cycle n + 1, writes its own part and completes the set with its manifest;
  // older sets beyond cfg.checkpoint.keep are removed.
  void write_checkpoint(long n, double t, double proposal, int out_index) {
    std::filesystem::path dir;
    try {
      dir = checkpoint::prepare_set(ck.root, n);
    } catch (const std::exception& e) { throw app::IoError(e.what()); }
    pb::Envelope req = envelope(hub, n, t);
    req.mutable_checkpoint_request()->set_directory(dir.string());
    const double phase_start = now_s();
    const Work before_f{hub.peer(Role::Fluid).busy, hub.peer(Role::Fluid).output},
        before_s{hub.peer(Role::Solid).busy, hub.peer(Role::Solid).output};
    send_both(req);
    const auto done = hub.expect_both(pb::Envelope::kCheckpointWritten, n);
    // The parts' writing is output, not steps; other work reported in the phase (the pipelined fluid's step after
    // its proposal) stays a step and, on the phase's critical path before the output, is not counted twice.
    const auto output_in_phase = [&](Role r, const Work& before) {
      const double out = hub.peer(r).output - before.output;
      return std::pair{Work{out, out}, hub.peer(r).busy - before.busy - out};
    };
    const auto [out_f, steps_f] = output_in_phase(Role::Fluid, before_f);
    const auto [out_s, steps_s] = output_in_phase(Role::Solid, before_s);
    ck_f = out_f;
    ck_s = out_s;
    ck_wall = std::max(0.0, now_s() - phase_start - std::max(steps_f, steps_s));
    open_timing(n + 1);
    carry = 0;  // the solvers' snapshots of cycle n were reported in the phase
    work([&] {
      app::as_io("the coupler's checkpoint part", [&] {
        checkpoint::PartWriter w(dir / kCouplerPart, "coupler");
        w.put_integer("cycle", n);
        w.put_scalar("time", t);
        w.put_scalar("proposal", proposal);
        w.put_integer("out_index", out_index);
        predictor.save(w);
        history.save(w);
        const double tot[5] = {sum.total.wall, sum.total.solid, sum.total.fluid, sum.total.coupler, sum.total.output};
        w.put("run.totals", std::span<const double>(tot, 5));
        w.commit();

        nlohmann::json m = checkpoint::scene_record(ck.scene_file, ck.overrides);
        m["parts"] = {kCouplerPart, done[0].checkpoint_written().part(), done[1].checkpoint_written().part()};
        m["scene_hash"] = ck.scene_hash;
        checkpoint::write_manifest(dir, n, t, m);
        checkpoint::prune(ck.root, cfg.checkpoint.keep);
      });
    });
    spdlog::info("checkpoint of cycle {} at t = {:.9g} s: {}", n, t, dir.string());
  }

  void run() {
    const checkpoint::PartReader* resume = ck.restart;
    hub.handshake();
    const Start start = resume ? restore(*resume) : Start{};
    double t = start.time, dt = 0.0;
    std::size_t next_out = 0;
    while (next_out < cfg.output_times.size() && t >= cfg.output_times[next_out] * (1.0 - 1e-14)) ++next_out;
    int out_index = start.out_index;
    if (resume) dt = choose_dt(start.proposal, cfg.dt_max, t, cfg.output_times[next_out]);
    const auto output = [&](long n) {
      pb::Envelope o = envelope(hub, n, t);
      o.mutable_output_request()->set_index(out_index++);
      if (output_sent < 0) output_sent = now_s();
      send_both(o);
      const double began = now_s();
      app::as_io("the interface snapshot", [&] { history.snapshot(n, t, last_faces, last_states); });
      own_output += now_s() - began;
    };
    for (long n = start.cycle;; ++n) {
      const double t_prev = t;
      const double proposal = cycle(n, t, dt);
      if (n == cfg.stall_after_cycle) std::this_thread::sleep_for(std::chrono::duration<double>(cfg.stall_seconds));
      t += dt;
      sum.cycles = n;
      sum.time = t;
      if (n == 0) output(n);
      while (next_out < cfg.output_times.size() && t >= cfg.output_times[next_out] * (1.0 - 1e-14)) {
        output(n);
        ++next_out;
      }
      history.progress(n, t, cfg.t_end, dt);
      if (t >= cfg.t_end * (1.0 - 1e-14) || next_out >= cfg.output_times.size()) {
        sum.message = fmt::format("completed: t = {:.9g} s after {} cycles", t, n);
        break;
      }
      if (n >= cfg.max_cycles) {
        output(n);  // the state where the run stopped
        sum.message = fmt::format("stopped at max_cycles = {} (t = {:.9g} s)", cfg.max_cycles, t);
        spdlog::warn("{}", sum.message);
        break;
      }
      if (cfg.checkpoint.enabled() && cfg.checkpoint.due(n, t_prev, t)) write_checkpoint(n, t, proposal, out_index);
      dt = choose_dt(proposal, cfg.dt_max, t, cfg.output_times[next_out]);
      if (!(dt > 0)) throw coupling::ProtocolError(fmt::format("time step collapsed to {:g} s at t = {:.9g} s", dt, t));
    }
    history.progress(sum.cycles, t, cfg.t_end, dt, true);
    hub.stop_all(sum.message, false);
    close_timing();
  }
};

}  // namespace

RunSummary run_coupled(const CouplerConfig& cfg, Hub& hub, const std::filesystem::path& out_dir,
                       const CheckpointContext& ck) {
  RunSummary s;
  try {
    if (!ck.restart && !ck.root.empty()) checkpoint::clear(ck.root);  // an earlier run's sets
    Loop loop(cfg, hub, out_dir, ck);
    try {
      loop.run();
      return loop.sum;
    } catch (...) {
      s = loop.sum;
      throw;
    }
  } catch (const coupling::CouplingError& e) {
    const bool interrupted = app::interrupted();
    s.code = interrupted ? 130 : 5;
    s.status = interrupted ? "interrupted" : "failed";
    s.message = e.what();
  } catch (const std::exception& e) {
    // Typed failures keep their code (a bad restart 2, its outputs 4: common/app/errors.h); any other is 1.
    s.code = app::exit_code_of(e);
    s.status = "failed";
    s.message = s.code == app::kExitUnforeseen ? fmt::format("unforeseen failure: {}", e.what()) : e.what();
  }
  spdlog::error("{}", s.message);
  hub.stop_all("coupler: " + s.message, true);
  return s;
}

}  // namespace cosim::coupler
