#!/usr/bin/python3
"""Overhead of the coupled cycle in both coupling schemes (coupling.scheme: pipelined, the default, and
sequential; docs/protocol.md "Schemes"): everything that is not solver work, per cycle and as a fraction of
wall time, against bare ZeroMQ patterns between processes on the same machine.

For each scene (configs/piston_2d.yaml: rigid piston, 12 interface faces; bench/coupled/
overhead_128.yaml: 128 x 128 air, 32 x 32 steel block, 128 faces, 300 cycles), each OpenMP setting
(OMP_NUM_THREADS=1, and the default) and each transport (ipc://, the launcher's default, and tcp:// with
`cosim run --tcp`), --repeat times, and within each repeat for both schemes (`--set coupling.scheme=...`;
the order of the two alternates from repeat to repeat, so that a drift of the machine favours neither):
  1. coupled_zmq_round_trip (bench/coupled/zmq_round_trip.cpp) for the scene's face count, right before
     the coupled run of the scheme (this machine's latency drifts by 2x within minutes, so yardstick and run
     are taken together): a 64 B round trip; the scheme's critical path as request/reply pairs of the real
     message sizes ("cycle": sequential, 3 round trips decision -> faces, faces -> samples, states ->
     proposal; "cycle_pipelined": pipelined, 1 round trip samples -> states); and the whole cycle between
     three processes with all nine messages in the scheme's order and no work ("protocol" for sequential,
     "protocol_pipelined" for pipelined);
  2. `cosim run` of the scene with the scheme; coupler/timing.csv gives the steady-state cycle (cycles 3 ..
     last-1; cycles 0-2 write the first snapshots), coupler_summary.json the whole-run means;
  3. the three-process pattern of the scheme again, with the solvers' measured busy times as busy loops
     (solid; fluid sampling = geometry_seconds of fluid/summary.json; fluid advance = the rest): what
     communication costs when the cores are also busy with solver work, without any solver, protobuf or
     coupler code. The bare pattern subtracts the same work as the coupler's comm (below).
Per scheme, the repeat with the median comm is reported; ratios are taken within a repeat. The wall-time ratio
sequential / pipelined is taken per repeat (both runs of one repeat) and its median reported.

Definitions (coupler/cycle.cpp, coupler/history.h CycleTiming): wall = the coupler's wall time of a cycle
(DtDecision n sent .. DtDecision n+1 sent); solid, fluid = the solvers' busy_seconds (work outside protocol
calls) reported in that window; coupler = the coupler's own work (interface conditions, history); comm =
everything else (ZeroMQ, protobuf encode/decode/validate, waiting to be scheduled):
  sequential: comm = wall - coupler - solid - fluid (one solver works at a time);
  pipelined:  comm = wall - coupler - max(solid, fluid) (the solid's step n+1 overlaps the fluid's step n).
Overhead = comm + coupler; "overhead share of wall" = (comm + coupler) / wall, per row.
Per-exchange ratios, comparing comm per cycle with the bare patterns of the same scheme:
  sequential: 4 exchanges per cycle, as the issue counts them (decision->faces, faces->samples,
    samples->states, states->proposal); comm / exchange = comm / 4, against the bare 64 B round trip. They
    overlap: the critical path holds 6 one-way messages = 3 round trips, which the bare "cycle" pattern
    reproduces; comm / bare "cycle" is the per-exchange ratio for any exchange count.
  pipelined: 1 exchange per cycle on the critical path, the round trip samples -> states (the solid's step,
    the next DtDecision and the faces all reach the fluid while it advances, so when the fluid is the slower
    solver, as in both scenes, they wait in its queue); comm / exchange = comm / 1, against the bare 64 B
    round trip; comm / bare "cycle_pipelined" (that one round trip with the real sizes) is the ratio to the
    bare critical path.
  both: comm / the bare three-process pattern of the same scheme with the solvers' busy loops ("protocol" or
    "protocol_pipelined", the same work subtracted as in the coupler's comm).

With --perf (--perf-only: nothing else): overhead_128 (OMP 1, ipc, the default scheme) under `perf sched record`
(context switches and scheduling delays per cycle and thread), and CPU time and context switches per cycle and process
(/usr/bin/time around each process, 900- minus 300-cycle run).

Usage: bench/coupled/run_overhead.py [--quick] [--repeat N] [--no-tcp] [--perf | --perf-only] [--work DIR]
                                     [--build DIR ...]
Binaries (cosim, coupler, fluid_solver, solid_solver, coupled_zmq_round_trip) are taken from the first build
directory that has them: --build DIR (repeatable), else $COSIM_BUILD_DIRS (build directories separated by ':'),
else build/ then build-c/; relative paths are tried from the working directory, then from the repository root.
Writes bench/results/coupled_overhead.png (--quick: coupled_overhead_quick.png) and prints markdown tables.
"""
import argparse
import csv
import json
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_common import RESULTS, ROOT, provenance  # noqa: E402
SCHEMES = ("pipelined", "sequential")
# Per scheme: exchanges per cycle (sequential: as the issue counts them; pipelined: the one round trip on the
# critical path), the bare critical-path pattern and the bare three-process pattern of coupled_zmq_round_trip.
EXCHANGES = {"sequential": 4, "pipelined": 1}
CRITICAL = {"sequential": "cycle", "pipelined": "cycle_pipelined"}
PROTOCOL = {"sequential": "protocol", "pipelined": "protocol_pipelined"}
CRITICAL_LABEL = {"sequential": "3 RT", "pipelined": "1 RT"}
SCENES = {
    # name: (scene file, interface faces of the solid box = 2 (nx + ny), --set for --quick)
    "piston_2d": (ROOT / "configs" / "piston_2d.yaml", 2 * (2 + 4), ["coupling.time.end=0.05"]),
    "overhead_128": (ROOT / "bench" / "coupled" / "overhead_128.yaml", 2 * (32 + 32), []),
}
TARGET_FRACTION = 0.05
TARGET_RATIO = 3.0


def find_bins(names, build_dirs):
    """The first build directory's bin/ that holds all of `names` (relative directories: from the working
    directory, then from the repository root); None when none does."""
    for d in build_dirs:
        for base in (Path(d), ROOT / d):
            if all((base / "bin" / n).exists() for n in names):
                return (base / "bin").resolve()
    return None


def bare(exe, faces, transport, count, protocol_work=(0, 0, 0), patterns="small,cycle,protocol"):
    cmd = [str(exe), "--faces", str(faces), "--count", str(count), "--transport", transport, "--patterns", patterns,
           "--protocol-work", ",".join(str(int(round(w * 1e6))) for w in protocol_work), "--json"]
    out = subprocess.run(cmd, check=True, stdout=subprocess.PIPE, text=True).stdout
    res = {}
    for line in out.splitlines():
        if line.startswith("{"):
            d = json.loads(line)
            res[d["pattern"]] = d
    missing = [p for p in patterns.split(",") if p not in res]
    if missing:
        raise SystemExit(f"{exe} did not measure {', '.join(missing)}: rebuild it (ninja coupled_zmq_round_trip)")
    return res


def read_timing(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    data = {c: np.array([float(r[c]) for r in rows]) for c in ["wall", "solid", "fluid", "coupler", "comm"]}
    data["cycle"] = np.array([int(r["cycle"]) for r in rows])
    return data


def omp_env(threads):
    env = dict(os.environ)
    env.pop("OMP_NUM_THREADS", None)
    if threads:
        env["OMP_NUM_THREADS"] = str(threads)
    return env


def coupled_run(cosim, scene, out, threads, tcp, extra_sets, scheme=None):
    if out.exists():
        shutil.rmtree(out)
    cmd = [str(cosim), "run", str(scene), "--out", str(out), "--quiet"]
    if scheme:
        extra_sets = list(extra_sets) + [f"coupling.scheme={scheme}"]
    for s in extra_sets:
        cmd += ["--set", s]
    if tcp:
        cmd.append("--tcp")
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=omp_env(threads))
    if p.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stdout}")
    summ = json.loads((out / "coupler" / "coupler_summary.json").read_text())
    fl = json.loads((out / "fluid" / "summary.json").read_text())["coupling"]
    tm = read_timing(out / "coupler" / "timing.csv")
    steady = (tm["cycle"] >= 3) & (tm["cycle"] < tm["cycle"].max())
    r = {"cycles": summ["cycles"], "summary": summ["per_cycle_seconds"], "comm_fraction_summary": summ["comm_fraction"],
         "fluid_geometry": fl["geometry_seconds"] / max(1, fl["cycles"]), "scheme": fl.get("scheme")}
    for c in ["wall", "solid", "fluid", "coupler", "comm"]:
        r[c] = float(tm[c][steady].mean())
        r[c + "_median"] = float(np.median(tm[c][steady]))
        r[c + "_p90"] = float(np.percentile(tm[c][steady], 90))
    return r


def perf_sched(cmd, env, data):
    """Runs cmd under `perf sched record`; returns `perf sched timehist` events as
    (time, task, tid, pid, sch_delay_s, run_s), or None when perf is not usable."""
    if shutil.which("perf") is None:
        return None
    p = subprocess.run(["perf", "sched", "record", "-o", str(data), "--"] + cmd, env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        print(f"perf sched record failed ({p.returncode}): {p.stdout[-500:]}")
        return None
    out = subprocess.run(["perf", "sched", "timehist", "-i", str(data)], stdout=subprocess.PIPE,
                         stderr=subprocess.DEVNULL, text=True).stdout
    rx = re.compile(r"^\s*([\d.]+)\s+\[(\d+)\]\s+(.+?)\[(\d+)(?:/(\d+))?\]\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)\s*$")
    ev = []
    for line in out.splitlines():
        m = rx.match(line)
        if m:
            tid = int(m.group(4))
            pid = int(m.group(5)) if m.group(5) else tid
            ev.append((float(m.group(1)), m.group(3), tid, pid, float(m.group(7)) * 1e-3, float(m.group(8)) * 1e-3))
    return ev


def sched_rows(ev, programs, quantiles=(0.1, 0.9)):
    """Per thread group of `programs`: (group, switches, scheduling delay [s], run time [s]) summed over the
    middle of the programs' activity; other tasks of the machine in one row. Returns (rows, window [s])."""
    names = {pid: task for _, task, tid, pid, _, _ in ev if tid == pid}
    ts = np.array([e[0] for e in ev if names.get(e[3]) in programs])
    if len(ts) == 0:
        return None
    lo, hi = np.quantile(ts, quantiles[0]), np.quantile(ts, quantiles[1])
    groups = {}
    for t, task, tid, pid, sd, rt in ev:
        if not lo <= t <= hi:
            continue
        prog = names.get(pid, "")
        if prog in programs:
            kind = ("main thread" if tid == pid else "ZeroMQ I/O thread" if task.startswith("ZMQbg/IO") else
                    "ZeroMQ reaper" if task.startswith("ZMQbg/Reaper") else "other thread (heartbeat, OpenMP)")
            key = f"{prog}: {kind}"
        elif task.startswith(("swapper", "perf", "cosim")):
            continue
        else:
            key = "other processes of the machine"
        g = groups.setdefault(key, [0, 0.0, 0.0])
        g[0] += 1
        g[1] += sd
        g[2] += rt
    return [(k, *groups[k]) for k in sorted(groups)], hi - lo


def perf_part(a, work, cosim, bindir, t_start):
    """The --perf measurements: perf sched of overhead_128, then CPU time per cycle and process."""
    env = omp_env(1)
    out = work / "perf_overhead_128"
    if out.exists():
        shutil.rmtree(out)
    ev = perf_sched([str(cosim), "run", str(SCENES["overhead_128"][0]), "--out", str(out), "--quiet"], env,
                    work / "perf_coupled.data")
    res = sched_rows(ev, {"coupler", "fluid_solver", "solid_solver"}) if ev else None
    if res:
        rows, span = res
        tm = read_timing(out / "coupler" / "timing.csv")
        wall = float(tm["wall"][3:-1].mean())
        n = span / wall
        print(f"\n## perf sched: overhead_128, OMP_NUM_THREADS=1, ipc (under perf: wall {wall * 1e3:.3f} ms per "
              f"cycle, {n:.0f} cycles in the window; perf itself slows every switch)\n")
        print("| thread | switches per cycle | scheduling delay (woken -> running) per cycle [us] | "
              "run time per cycle [us] |")
        print("|---|---|---|---|")
        tot = [0.0, 0.0, 0.0]
        for key, c, sd, rn in rows:
            print(f"| {key} | {c / n:.1f} | {sd / n * 1e6:.1f} | {rn / n * 1e6:.1f} |")
            if not key.startswith("other processes"):
                tot = [tot[0] + c / n, tot[1] + sd / n, tot[2] + rn / n]
        print(f"| all threads of the run | {tot[0]:.1f} | {tot[1] * 1e6:.1f} | {tot[2] * 1e6:.1f} |")

    if Path("/usr/bin/time").exists():
        # CPU time and context switches per cycle and process: /usr/bin/time around each process (launcher's
        # --*-exe), runs of 300 and 900 cycles, difference / 600 (start-up and snapshots cancel out)
        acc = {}
        for n in (300, 900):
            out = work / f"cpu_{n}"
            if out.exists():
                shutil.rmtree(out)
            cmd = [str(cosim), "run", str(SCENES["overhead_128"][0]), "--out", str(out), "--quiet", "--set",
                   f"coupling.time.max_cycles={n}"]
            for role, exe in (("coupler", "coupler"), ("fluid", "fluid_solver"), ("solid", "solid_solver")):
                cmd += [f"--{role}-exe", f"/usr/bin/time -o {work}/cpu_{n}_{role}.txt -f %U,%S,%w,%c {bindir / exe}"]
            subprocess.run(cmd, check=True, env=omp_env(1), stdout=subprocess.DEVNULL)
            for role in ("coupler", "fluid", "solid"):
                line = (work / f"cpu_{n}_{role}.txt").read_text().strip().splitlines()[-1]
                acc[(n, role)] = [float(x) for x in line.split(",")]
        wall = {n: json.loads((work / f"cpu_{n}" / "coupler" / "coupler_summary.json").read_text())
                ["per_cycle_seconds"]["wall"] for n in (300, 900)}
        print("\n## CPU per cycle and process (overhead_128, OMP_NUM_THREADS=1, ipc; /usr/bin/time, "
              "(900-cycle run - 300-cycle run) / 600; 10 ms clock resolution)\n")
        print("| process | user [us] | system [us] | voluntary switches | involuntary switches (preempted) |")
        print("|---|---|---|---|---|")
        for role in ("coupler", "fluid", "solid"):
            d = [(acc[(900, role)][i] - acc[(300, role)][i]) / 600 for i in range(4)]
            print(f"| {role} | {d[0] * 1e6:.0f} | {d[1] * 1e6:.0f} | {d[2]:.1f} | {d[3]:.1f} |")
        print(f"\n(wall per cycle of the two runs: {wall[300] * 1e3:.3f} and {wall[900] * 1e3:.3f} ms)")

    if t_start is not None:
        print(f"\ntotal benchmark time {time.perf_counter() - t_start:.0f} s; load average after: "
              f"{' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="shorter piston run, one repeat, fewer round trips")
    ap.add_argument("--repeat", type=int, default=3, help="repeats per configuration (median reported)")
    ap.add_argument("--work", default="/tmp/cosim_overhead", help="run directories (overwritten)")
    ap.add_argument("--build", action="append", default=None,
                    help="build directory with bin/, repeatable (default: $COSIM_BUILD_DIRS, ':'-separated, else "
                         "build, then build-c)")
    ap.add_argument("--no-tcp", action="store_true", help="ipc:// only")
    ap.add_argument("--perf", action="store_true",
                    help="also run overhead_128 (OMP 1, ipc, default scheme) under `perf sched record`: context "
                         "switches and scheduling delays per cycle and thread")
    ap.add_argument("--perf-only", action="store_true", help="only the --perf measurements")
    a = ap.parse_args()
    a.perf = a.perf or a.perf_only
    env_builds = [d for d in os.environ.get("COSIM_BUILD_DIRS", "").split(":") if d]
    builds = a.build or env_builds or [str(ROOT / "build"), str(ROOT / "build-c")]
    exes = ("cosim", "coupler", "fluid_solver", "solid_solver", "coupled_zmq_round_trip")
    src = find_bins(exes, builds)
    if not src:
        raise SystemExit(f"need {', '.join(exes)} in the bin/ of one of {builds} (ninja coupled_zmq_round_trip)")
    work = Path(a.work)
    work.mkdir(parents=True, exist_ok=True)
    bindir = work / "bin"  # private copies: a rebuild of the tree during the benchmark must not change them
    bindir.mkdir(exist_ok=True)
    for exe in exes:
        shutil.copy2(src / exe, bindir / exe)
    cosim, rt = bindir / "cosim", bindir / "coupled_zmq_round_trip"
    print(f"binaries from {src}; " + provenance(bindir))
    repeat = 1 if a.quick else max(1, a.repeat)
    count = 1000 if a.quick else 3000
    transports = ["ipc"] if a.no_tcp else ["ipc", "tcp"]
    t_start = time.perf_counter()
    print(f"machine: {os.cpu_count()} logical CPUs; load average before: "
          f"{' '.join(f'{x:.2f}' for x in os.getloadavg())}")

    results = []  # one per scene, OMP setting, transport and scheme: the repeat with the median comm
    ratios = []  # one per scene, OMP setting and transport: wall sequential / pipelined
    for name, (scene, faces, quick_sets) in ({} if a.perf_only else SCENES).items():
        for threads in (1, None):
            for tr in transports:
                reps = {sc: [] for sc in SCHEMES}
                for k in range(repeat):
                    for scheme in (SCHEMES if k % 2 == 0 else SCHEMES[::-1]):
                        crit, proto = CRITICAL[scheme], PROTOCOL[scheme]
                        b = bare(rt, faces, tr, count, patterns=f"small,{crit},{proto}")
                        out = work / f"{name}_{scheme}_{'omp1' if threads else 'ompdef'}_{tr}_{k}"
                        r = coupled_run(cosim, scene, out, threads, tr == "tcp", quick_sets if a.quick else [], scheme)
                        if r["scheme"] != scheme:
                            raise SystemExit(f"{out}: the fluid ran the {r['scheme']} scheme, not {scheme}")
                        geo = min(r["fluid_geometry"], r["fluid_median"])
                        work_us = (r["solid_median"], geo, r["fluid_median"] - geo)
                        bw = bare(rt, faces, tr, count, work_us, proto)
                        r.update({"bare": b, "bare_work": bw[proto], "work_us": work_us, "repeat": k})
                        reps[scheme].append(r)
                rw = [s["wall"] / p["wall"] for s, p in zip(reps["sequential"], reps["pipelined"])]
                ratios.append({"scene": name, "threads": "1" if threads else "default", "transport": tr,
                               "ratios": rw, "ratio": float(np.median(rw))})
                for scheme in SCHEMES:
                    rs = sorted(reps[scheme], key=lambda x: x["comm"])
                    r = rs[len(rs) // 2]
                    r.update({"scene": name, "scheme": scheme, "threads": "1" if threads else "default",
                              "transport": tr, "faces": faces, "comm_all": [x["comm"] for x in reps[scheme]]})
                    results.append(r)
                    print(f"  {name} {scheme} OMP {r['threads']} {tr}: {r['cycles']} cycles, wall per cycle "
                          + ", ".join(f"{x['wall'] * 1e6:.0f}" for x in reps[scheme]) + " us, comm per cycle "
                          + ", ".join(f"{x * 1e6:.0f}" for x in r["comm_all"]) + " us; bare 64 B round trip "
                          + ", ".join(f"{x['bare']['small']['median_s'] * 1e6:.0f}" for x in reps[scheme]) + " us",
                          flush=True)
                print(f"  {name} OMP {ratios[-1]['threads']} {tr}: wall sequential / pipelined "
                      + ", ".join(f"{x:.2f}" for x in rw), flush=True)

    if a.perf_only:
        return perf_part(a, work, cosim, bindir, t_start)
    for r in results:
        b, sc = r["bare"], r["scheme"]
        r["b_small"] = b["small"]["median_s"]
        r["b_cycle"] = b[CRITICAL[sc]]["median_s"]
        r["b_proto"] = b[PROTOCOL[sc]]["median_s"]
        r["b_proto_work"] = r["bare_work"]["median_s"]
        r["pbuf"] = b["protobuf"]["median_s"]
        r["exchanges"] = EXCHANGES[sc]
        r["per_ex"] = r["comm"] / EXCHANGES[sc]
        r["ratio"] = r["per_ex"] / r["b_small"]
        r["ratio_cycle"] = r["comm"] / r["b_cycle"]
        r["ratio_proto"] = r["comm"] / r["b_proto_work"] if r["b_proto_work"] > 0 else float("nan")
        r["comm_frac"] = r["comm"] / r["wall"]
        r["overhead_frac"] = (r["comm"] + r["coupler"]) / r["wall"]

    print("\n## Coupled cycle per cycle and scheme (steady-state means from timing.csv; times in ms)\n")
    print("comm = wall - coupler - (solid + fluid) (sequential) or - max(solid, fluid) (pipelined); overhead share "
          "= (comm + coupler) / wall; exchanges/cycle: sequential 4 as the issue counts them (3 round trips on the "
          "critical path), pipelined 1 (samples -> states); critical path = bare \"cycle\" (3 RT) or "
          "\"cycle_pipelined\" (1 RT), real sizes; 3-process cycle = bare \"protocol\" or \"protocol_pipelined\" "
          "with the solvers' busy loops.\n")
    print("| scene | scheme | OMP threads | transport | cycles | wall | solid | fluid | coupler | comm | comm % wall | "
          "overhead share of wall % | exchanges/cycle | comm/exchange [us] | bare RT 64 B [us] | ratio | "
          "comm / bare critical path (real sizes) | comm / bare 3-process cycle of the scheme |")
    print("|---" * 18 + "|")
    for r in results:
        print(f"| {r['scene']} | {r['scheme']} | {r['threads']} | {r['transport']} | {r['cycles']} | "
              f"{r['wall'] * 1e3:.3f} | {r['solid'] * 1e3:.3f} | {r['fluid'] * 1e3:.3f} | {r['coupler'] * 1e3:.4f} | "
              f"{r['comm'] * 1e3:.3f} | {100 * r['comm_frac']:.1f} | {100 * r['overhead_frac']:.1f} | "
              f"{r['exchanges']} | {r['per_ex'] * 1e6:.1f} | {r['b_small'] * 1e6:.1f} | {r['ratio']:.2f} | "
              f"{r['ratio_cycle']:.2f} ({CRITICAL_LABEL[r['scheme']]}) | {r['ratio_proto']:.2f} |")

    print("\n## Wall time per cycle, sequential / pipelined (steady state; ratio per repeat, median)\n")
    print("| scene | OMP threads | transport | wall sequential [ms] | wall pipelined [ms] | sequential / pipelined "
          "| per repeat |")
    print("|---" * 7 + "|")
    for q in ratios:
        w = {r["scheme"]: r["wall"] for r in results
             if (r["scene"], r["threads"], r["transport"]) == (q["scene"], q["threads"], q["transport"])}
        print(f"| {q['scene']} | {q['threads']} | {q['transport']} | {w['sequential'] * 1e3:.3f} | "
              f"{w['pipelined'] * 1e3:.3f} | {q['ratio']:.2f} | {', '.join(f'{x:.2f}' for x in q['ratios'])} |")

    print("\n## Whole-run means from coupler_summary.json (ms per cycle; includes the first cycles and snapshots)\n")
    print("| scene | scheme | OMP threads | transport | wall | solid | fluid | coupler | comm | comm_fraction |")
    print("|---" * 10 + "|")
    for r in results:
        s = r["summary"]
        print(f"| {r['scene']} | {r['scheme']} | {r['threads']} | {r['transport']} | {s['wall'] * 1e3:.3f} | "
              f"{s['solid'] * 1e3:.3f} | {s['fluid'] * 1e3:.3f} | {s['coupler'] * 1e3:.4f} | {s['comm'] * 1e3:.3f} | "
              f"{100 * r['comm_fraction_summary']:.1f} % |")

    print("\n## Where comm goes (us per cycle, medians; bare numbers of the same scheme measured next to each run)\n")
    print("| scene | scheme | OMP threads | transport | comm (coupled run) | bare: critical path, 2 processes | "
          "bare: whole cycle, 3 processes, 9 messages | same + solver busy loops (solid/sample/advance us) | "
          "protobuf layer (1 process) |")
    print("|---" * 9 + "|")
    for r in results:
        w = "/".join(f"{x * 1e6:.0f}" for x in r["work_us"])
        print(f"| {r['scene']} | {r['scheme']} | {r['threads']} | {r['transport']} | {r['comm_median'] * 1e6:.0f} | "
              f"{r['b_cycle'] * 1e6:.0f} ({CRITICAL_LABEL[r['scheme']]}) | {r['b_proto'] * 1e6:.0f} | "
              f"{r['b_proto_work'] * 1e6:.0f} ({w}) | {r['pbuf'] * 1e6:.0f} |")

    print("\n## Targets\n")
    for r in results:
        if r["scene"] != "overhead_128":
            continue
        f_ok = r["overhead_frac"] < TARGET_FRACTION
        q_ok = r["ratio"] <= TARGET_RATIO
        print(f"- overhead_128, {r['scheme']}, OMP {r['threads']}, {r['transport']}: overhead (comm + coupler) "
              f"{100 * r['overhead_frac']:.1f} % of wall (target < {100 * TARGET_FRACTION:.0f} %): "
              f"{'met' if f_ok else 'NOT met'}; comm per exchange ({r['exchanges']} per cycle) {r['ratio']:.2f}x the "
              f"bare 64 B round trip (target <= {TARGET_RATIO:g}x): {'met' if q_ok else 'NOT met'}; "
              f"{r['ratio_cycle']:.2f}x the bare critical path with the real message sizes "
              f"({CRITICAL_LABEL[r['scheme']]})")

    if a.perf:
        perf_part(a, work, cosim, bindir, None)
    print(f"\ntotal benchmark time {time.perf_counter() - t_start:.0f} s; load average after: "
          f"{' '.join(f'{x:.2f}' for x in os.getloadavg())}")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Patch

    fig, axes = plt.subplots(1, len(SCENES), figsize=(7.5 * len(SCENES), 5.8), squeeze=False)
    colours = {"solid": "#1f77b4", "fluid": "#2ca02c", "coupler": "#9467bd", "comm": "#d62728"}
    width = 0.38
    for ax, name in zip(axes[0], SCENES):
        configs = [(r["threads"], r["transport"]) for r in results if r["scene"] == name and r["scheme"] == SCHEMES[0]]
        top, ticks, labels = 0.0, [], []
        for j, cfg in enumerate(configs):
            for i, scheme in enumerate(SCHEMES):
                r = next(x for x in results if x["scene"] == name and x["scheme"] == scheme
                         and (x["threads"], x["transport"]) == cfg)
                xc = j + (i - 0.5) * (width + 0.02)
                # Bars add up to the wall time: sequential, solid + fluid + coupler + comm; pipelined, the longer
                # solver + coupler + comm, the shorter (overlapped) solver hatched inside the longer one.
                if scheme == "pipelined":
                    long_, short = ("fluid", "solid") if r["fluid"] >= r["solid"] else ("solid", "fluid")
                    parts = [long_, "coupler", "comm"]
                else:
                    parts = ["solid", "fluid", "coupler", "comm"]
                bottom = 0.0
                for c in parts:
                    v = r[c] * 1e3
                    ax.bar(xc, v, bottom=bottom, color=colours[c], width=width)
                    bottom += v
                if scheme == "pipelined":
                    ax.bar(xc - width / 4, r[short] * 1e3, bottom=0.0, width=width / 2, fill=False,
                           edgecolor=colours[short], hatch="///", lw=0.8)
                base = bottom - r["comm"] * 1e3
                ax.plot([xc - width / 2, xc + width / 2], [base + r["b_cycle"] * 1e3] * 2, "k--", lw=1.2)
                ax.plot([xc - width / 2, xc + width / 2], [base + r["b_proto_work"] * 1e3] * 2, "k:", lw=1.5)
                ax.text(xc, bottom, f"{100 * r['overhead_frac']:.0f}%", ha="center", va="bottom", fontsize=7)
                top = max(top, bottom)
                ticks.append(xc)
                labels.append(f"{'pipe' if scheme == 'pipelined' else 'seq'}\nOMP {cfg[0]}\n{cfg[1]}")
        ax.set_xticks(ticks)
        ax.set_xticklabels(labels, fontsize=7)
        ax.set_ylabel("ms per cycle")
        ax.set_ylim(0, top * 1.4)
        ax.set_title(f"{name} ({SCENES[name][1]} interface faces); % = overhead share of wall", fontsize=10)
        handles = [Patch(color=colours[c], label=c) for c in ("solid", "fluid", "coupler", "comm")]
        handles += [Patch(fill=False, hatch="///", edgecolor="grey", label="overlapped solver work (pipelined)"),
                    plt.Line2D([], [], color="k", ls="--", lw=1.2,
                               label="comm of the bare critical path (seq 3 RT, pipe 1 RT)"),
                    plt.Line2D([], [], color="k", ls=":", lw=1.5,
                               label="comm of the bare 3-process cycle of the scheme with busy loops")]
        ax.legend(handles=handles, fontsize=7, loc="upper left")
    fig.suptitle("Coupled cycle per scheme (pipe = pipelined, seq = sequential): solver work, coupler work and "
                 "communication per cycle (steady state)", fontsize=11)
    fig.tight_layout()
    RESULTS.mkdir(parents=True, exist_ok=True)
    png = RESULTS / ("coupled_overhead_quick.png" if a.quick else "coupled_overhead.png")
    fig.savefig(png, dpi=110)
    print(f"wrote {png.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
