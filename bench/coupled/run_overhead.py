#!/usr/bin/python3
"""Overhead of the coupled cycle: everything that is not solver work, per cycle and as a fraction of wall
time, against a bare ZeroMQ round trip between two processes on the same machine.

For each scene (configs/piston_2d.yaml: rigid piston, 12 interface faces; bench/coupled/
overhead_128.yaml: 128 x 128 air, 32 x 32 steel block, 128 faces, 300 cycles), each OpenMP setting
(OMP_NUM_THREADS=1, and the default) and each transport (ipc://, the launcher's default, and tcp:// with
`cosim run --tcp`), --repeat times:
  1. coupled_zmq_round_trip (bench/coupled/zmq_round_trip.cpp) for the scene's face count, right before
     the coupled run (this machine's latency drifts by 2x within minutes, so yardstick and run are taken
     together): a 64 B round trip; the cycle's critical path as 3 request/reply pairs of the real message
     sizes (decision -> faces, faces -> samples, states -> proposal); and the whole cycle between three
     processes with all nine messages and no work ("protocol");
  2. `cosim run` of the scene; coupler/timing.csv gives the steady-state cycle (cycles 3 .. last-1; cycles
     0-2 write the first snapshots), coupler_summary.json the whole-run means;
  3. the three-process protocol again, with the solvers' measured busy times as busy loops (solid; fluid
     sampling = geometry_seconds of fluid/summary.json; fluid advance = the rest): what communication costs
     when the cores are also busy with solver work, without any solver, protobuf or coupler code.
The repeat with the median comm is reported; ratios are taken within a repeat.

Definitions (coupler/cycle.cpp): wall = the coupler's wall time of a cycle (DtDecision sent .. both
DtProposals received); solid, fluid = the solvers' busy_seconds (work outside protocol calls); coupler = the
coupler's own work (interface conditions, history); comm = wall - solid - fluid - coupler (ZeroMQ, protobuf
encode/decode/validate, waiting to be scheduled). Overhead = comm + coupler.
Exchanges per cycle: 4, as the issue counts them (decision->faces, faces->samples, samples->states,
states->proposal). They overlap: the critical path holds 6 one-way messages = 3 round trips, which the bare
"cycle" pattern reproduces; comm per cycle / bare cycle is the per-exchange ratio for any exchange count.

With --perf (--perf-only: nothing else): overhead_128 (OMP 1, ipc) under `perf sched record` (context
switches and scheduling delays per cycle and thread), and CPU time and context switches per cycle and process
(/usr/bin/time around each process, 900- minus 300-cycle run).

Usage: bench/coupled/run_overhead.py [--quick] [--repeat N] [--no-tcp] [--perf | --perf-only] [--work DIR]
Writes bench/results/coupled_overhead.png and prints markdown tables.
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
EXCHANGES = 4  # per cycle, as the issue counts them
SCENES = {
    # name: (scene file, interface faces of the solid box = 2 (nx + ny), --set for --quick)
    "piston_2d": (ROOT / "configs" / "piston_2d.yaml", 2 * (2 + 4), ["coupling.time.end=0.05"]),
    "overhead_128": (ROOT / "bench" / "coupled" / "overhead_128.yaml", 2 * (32 + 32), []),
}
TARGET_FRACTION = 0.05
TARGET_RATIO = 3.0


def find_bin(name, build_dirs):
    for d in build_dirs:
        p = Path(d) / "bin" / name
        if p.exists():
            return p
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


def coupled_run(cosim, scene, out, threads, tcp, extra_sets):
    if out.exists():
        shutil.rmtree(out)
    cmd = [str(cosim), "run", str(scene), "--out", str(out), "--quiet"]
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
         "fluid_geometry": fl["geometry_seconds"] / max(1, fl["cycles"])}
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
                    help="build directory with bin/ (default: build, then build-c)")
    ap.add_argument("--no-tcp", action="store_true", help="ipc:// only")
    ap.add_argument("--perf", action="store_true",
                    help="also run overhead_128 (OMP 1, ipc) under `perf sched record`: context switches and "
                         "scheduling delays per cycle and thread")
    ap.add_argument("--perf-only", action="store_true", help="only the --perf measurements")
    a = ap.parse_args()
    a.perf = a.perf or a.perf_only
    builds = a.build or [str(ROOT / "build"), str(ROOT / "build-c")]
    cosim = find_bin("cosim", builds)
    rt = find_bin("coupled_zmq_round_trip", builds)
    if not cosim or not rt:
        raise SystemExit(f"need cosim and coupled_zmq_round_trip in one of {builds} (ninja coupled_zmq_round_trip)")
    work = Path(a.work)
    work.mkdir(parents=True, exist_ok=True)
    bindir = work / "bin"  # private copies: a rebuild of the tree during the benchmark must not change them
    bindir.mkdir(exist_ok=True)
    for exe in ("cosim", "coupler", "fluid_solver", "solid_solver"):
        shutil.copy2(cosim.parent / exe, bindir / exe)
    shutil.copy2(rt, bindir / rt.name)
    cosim, rt = bindir / "cosim", bindir / rt.name
    print(provenance(Path(cosim).parent))
    repeat = 1 if a.quick else max(1, a.repeat)
    count = 1000 if a.quick else 3000
    transports = ["ipc"] if a.no_tcp else ["ipc", "tcp"]
    t_start = time.perf_counter()
    print(f"machine: {os.cpu_count()} logical CPUs; load average before: "
          f"{' '.join(f'{x:.2f}' for x in os.getloadavg())}")

    results = []
    for name, (scene, faces, quick_sets) in ({} if a.perf_only else SCENES).items():
        for threads in (1, None):
            for tr in transports:
                reps = []
                for k in range(repeat):
                    b = bare(rt, faces, tr, count)
                    out = work / f"{name}_{'omp1' if threads else 'ompdef'}_{tr}_{k}"
                    r = coupled_run(cosim, scene, out, threads, tr == "tcp", quick_sets if a.quick else [])
                    geo = min(r["fluid_geometry"], r["fluid_median"])
                    bw = bare(rt, faces, tr, count, (r["solid_median"], geo, r["fluid_median"] - geo), "protocol")
                    r.update({"bare": b, "bare_work": bw["protocol"], "work_us": (r["solid_median"], geo,
                                                                                   r["fluid_median"] - geo)})
                    reps.append(r)
                reps.sort(key=lambda x: x["comm"])
                r = reps[len(reps) // 2]
                r.update({"scene": name, "threads": "1" if threads else "default", "transport": tr, "faces": faces,
                          "comm_all": [x["comm"] for x in reps]})
                results.append(r)
                print(f"  {name} OMP {r['threads']} {tr}: {r['cycles']} cycles, comm per cycle "
                      + ", ".join(f"{x * 1e6:.0f}" for x in r["comm_all"]) + " us; bare 64 B round trip "
                      + ", ".join(f"{x['bare']['small']['median_s'] * 1e6:.0f}" for x in reps) + " us", flush=True)

    if a.perf_only:
        return perf_part(a, work, cosim, bindir, t_start)
    for r in results:
        b = r["bare"]
        r["b_small"] = b["small"]["median_s"]
        r["b_cycle"] = b["cycle"]["median_s"]
        r["b_proto"] = b["protocol"]["median_s"]
        r["b_proto_work"] = r["bare_work"]["median_s"]
        r["pbuf"] = b["protobuf"]["median_s"]
        r["per_ex"] = r["comm"] / EXCHANGES
        r["ratio"] = r["per_ex"] / r["b_small"]
        r["ratio_cycle"] = r["comm"] / r["b_cycle"]
        r["comm_frac"] = r["comm"] / r["wall"]
        r["overhead_frac"] = (r["comm"] + r["coupler"]) / r["wall"]

    print("\n## Coupled cycle per cycle (steady-state means from timing.csv; times in ms)\n")
    print("| scene | OMP threads | transport | cycles | wall | solid | fluid | coupler | comm | comm % wall | "
          "overhead % wall | exchanges/cycle | comm/exchange [us] | bare RT 64 B [us] | ratio | "
          "comm / bare critical path (3 RT, real sizes) |")
    print("|---" * 16 + "|")
    for r in results:
        print(f"| {r['scene']} | {r['threads']} | {r['transport']} | {r['cycles']} | {r['wall'] * 1e3:.3f} | "
              f"{r['solid'] * 1e3:.3f} | {r['fluid'] * 1e3:.3f} | {r['coupler'] * 1e3:.4f} | {r['comm'] * 1e3:.3f} | "
              f"{100 * r['comm_frac']:.1f} | {100 * r['overhead_frac']:.1f} | {EXCHANGES} | {r['per_ex'] * 1e6:.1f} | "
              f"{r['b_small'] * 1e6:.1f} | {r['ratio']:.2f} | {r['ratio_cycle']:.2f} |")

    print("\n## Whole-run means from coupler_summary.json (ms per cycle; includes the first cycles and snapshots)\n")
    print("| scene | OMP threads | transport | wall | solid | fluid | coupler | comm | comm_fraction |")
    print("|---" * 9 + "|")
    for r in results:
        s = r["summary"]
        print(f"| {r['scene']} | {r['threads']} | {r['transport']} | {s['wall'] * 1e3:.3f} | {s['solid'] * 1e3:.3f} | "
              f"{s['fluid'] * 1e3:.3f} | {s['coupler'] * 1e3:.4f} | {s['comm'] * 1e3:.3f} | "
              f"{100 * r['comm_fraction_summary']:.1f} % |")

    print("\n## Where comm goes (us per cycle, medians; bare numbers measured next to each run)\n")
    print("| scene | OMP threads | transport | comm (coupled run) | bare: 3 RT critical path, 2 processes | "
          "bare: whole cycle, 3 processes, 9 messages | same + solver busy loops (solid/sample/advance us) | "
          "protobuf layer (1 process) |")
    print("|---" * 8 + "|")
    for r in results:
        w = "/".join(f"{x * 1e6:.0f}" for x in r["work_us"])
        print(f"| {r['scene']} | {r['threads']} | {r['transport']} | {r['comm_median'] * 1e6:.0f} | "
              f"{r['b_cycle'] * 1e6:.0f} | {r['b_proto'] * 1e6:.0f} | {r['b_proto_work'] * 1e6:.0f} ({w}) | "
              f"{r['pbuf'] * 1e6:.0f} |")

    print("\n## Targets\n")
    for r in results:
        if r["scene"] != "overhead_128":
            continue
        f_ok = r["overhead_frac"] < TARGET_FRACTION
        q_ok = r["ratio"] <= TARGET_RATIO
        print(f"- overhead_128, OMP {r['threads']}, {r['transport']}: overhead (comm + coupler) "
              f"{100 * r['overhead_frac']:.1f} % of wall (target < {100 * TARGET_FRACTION:.0f} %): "
              f"{'met' if f_ok else 'NOT met'}; comm per exchange {r['ratio']:.2f}x the bare 64 B round trip "
              f"(target <= {TARGET_RATIO:g}x): {'met' if q_ok else 'NOT met'}; {r['ratio_cycle']:.2f}x the bare "
              f"critical path with the real message sizes")

    if a.perf:
        perf_part(a, work, cosim, bindir, None)
    print(f"\ntotal benchmark time {time.perf_counter() - t_start:.0f} s; load average after: "
          f"{' '.join(f'{x:.2f}' for x in os.getloadavg())}")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(SCENES), figsize=(6.5 * len(SCENES), 5.5), squeeze=False)
    colours = {"solid": "#1f77b4", "fluid": "#2ca02c", "coupler": "#9467bd", "comm": "#d62728"}
    for ax, name in zip(axes[0], SCENES):
        rs = [r for r in results if r["scene"] == name]
        x = np.arange(len(rs))
        bottom = np.zeros(len(rs))
        for c in ("solid", "fluid", "coupler", "comm"):
            v = np.array([r[c] * 1e3 for r in rs])
            ax.bar(x, v, bottom=bottom, color=colours[c], label=c, width=0.6)
            bottom += v
        for i, r in enumerate(rs):
            base = bottom[i] - r["comm"] * 1e3
            ax.plot([i - 0.3, i + 0.3], [base + r["b_cycle"] * 1e3] * 2, "k--", lw=1.2,
                    label="comm of a bare critical path (3 RT)" if i == 0 else None)
            ax.plot([i - 0.3, i + 0.3], [base + r["b_proto_work"] * 1e3] * 2, "k:", lw=1.5,
                    label="comm of the bare 3-process cycle with busy loops" if i == 0 else None)
            ax.text(i, bottom[i], f"{100 * r['overhead_frac']:.0f}%", ha="center", va="bottom", fontsize=8)
        ax.set_xticks(x)
        ax.set_xticklabels([f"OMP {r['threads']}\n{r['transport']}" for r in rs], fontsize=8)
        ax.set_ylabel("ms per cycle")
        ax.set_ylim(0, bottom.max() * 1.35)
        ax.set_title(f"{name} ({rs[0]['faces']} interface faces); % = overhead of wall", fontsize=10)
        ax.legend(fontsize=7, loc="upper left")
    fig.suptitle("Coupled cycle: solver work, coupler work and communication per cycle (steady state)")
    fig.tight_layout()
    RESULTS.mkdir(parents=True, exist_ok=True)
    png = RESULTS / ("coupled_overhead_quick.png" if a.quick else "coupled_overhead.png")
    fig.savefig(png, dpi=110)
    print(f"wrote {png.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
