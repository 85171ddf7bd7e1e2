#!/usr/bin/python3
"""What one coupler process costs per cycle against the number of interface faces, with synthetic peers.

For each face count N (default 1e2, 1e3, 1e4, 1e5, 1e6), the coupler runs a scene of --cycles cycles (dt 1e-4 s,
the default robin interface conditions, the default pipelined scheme) between two
cosim_scripted_peer processes that do no solver work: the solid sends N quads in 3D (`--faces N`: a grid of 1 cm
squares with their vertices, as the solid solver sends its exterior faces), the fluid answers each face with a
fixed state of --phases phases. Per cycle (steady state: cycles --skip .. last-1 of coupler/timing.csv; coupler/history.h
CycleTiming):
  coupler = the coupler's own work: the faces and samples out of protobuf into arrays, the interface conditions,
            the states into protobuf, the interface history;
  comm    = wall - coupler - output - max(solid, fluid) (pipelined, as bench/coupled/run_overhead.py defines it):
            ZeroMQ, protobuf encode/decode/validate in all three processes, waiting to be scheduled;
  solid, fluid = the scripted peers' work outside protocol calls (building the faces, the samples);
  bytes   = the encoded envelopes the coupler received and sent per cycle (coupler_summary.json message_bytes);
  wall    = the coupler's cycle.
Repeats alternate the order of the sizes (up, then down, ...); per size and column the median of --repeat runs.
Cost per face: a weighted least-squares fit c = c0 + c1 N over the sizes (weights 1/c: each size counts by its
relative error), for coupler and comm.

The 5% limit: the yardstick is the flagship's measured cycle, 352 ms at 120^3 on 2 cores (docs/tungsten_blast_3d.md,
"The full run"; --cycle-seconds to change it). The coupler's cost exceeds 5% of it at N5 = (0.05 T - c0) / c1
faces. With P fluid ranks of 120^3 cells each the cycle stays T (weak scaling) while the scene grows P times in
volume: a target refined with the background has 4800 P^(2/3) faces (10 x 40 x 40 hexes: 2 (400 + 400 + 1600)
exterior quads), so the limit is reached at P = (N5 / 4800)^(3/2).

Message buffers (--malloc default,kept): this machine (a paravirtualised guest) pays dearly for page faults, and
with glibc's default thresholds a large message lands in memory the allocator had given back to the kernel (a
trimmed heap or a fresh mapping), whose pages fault again in each copy: protobuf encode, ZeroMQ's frame, the kernel's socket buffer, the receiver's
frame, protobuf decode, the coupler's arrays. `kept` runs all three processes with
GLIBC_TUNABLES=glibc.malloc.mmap_max=0:glibc.malloc.trim_threshold=16 GiB (no mappings, no trimming: freed buffers
are reused by the next message): what reusing the message buffers would give, without changing any code. Each mode
runs every size within each repeat, their order alternating too. The peers do no work, so every transfer is on
the critical path: an upper bound of what the faces cost a real pipelined cycle (docs/benchmarks.md compares it with
the real scene).

The fluid peer has --phases 2 (default; the tungsten blast's air and tungsten): its samples and states carry two
phases per face. Sizes from --large-from (1e6) on run --large-cycles (12) cycles: a cycle there takes seconds.

Usage: nice -n 10 bench/coupled/run_coupler_scaling.py [--sizes 100,1000,...] [--cycles 30] [--skip 3]
       [--repeat 3] [--malloc default,kept] [--phases 2] [--work DIR] [--build DIR] [--no-plot]
Writes bench/results/coupler_scaling.png and prints markdown tables.
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_common import RESULTS, ROOT, provenance  # noqa: E402

DT = 1e-4
YARDSTICK = 0.352  # s per cycle: docs/tungsten_blast_3d.md, "The full run" (120^3, 2 threads, 2026-12-06)
TARGETS = {  # the tungsten blast's target box (hexes along x, y, z); all its exterior quads go to the coupler
    "CI test 4 x 10 x 10": (4, 10, 10),
    "flagship figure 4 x 16 x 16": (4, 16, 16),
    "scene 10 x 40 x 40": (10, 40, 40),
}
FRACTION = 0.05
COLUMNS = ["wall", "solid", "fluid", "coupler", "comm", "bytes"]
MALLOC = {"default": "", "kept": "glibc.malloc.mmap_max=0:glibc.malloc.trim_threshold=17179869184"}


def exterior_quads(nx, ny, nz):
    return 2 * (nx * ny + ny * nz + nz * nx)


def find_bin_dir(build_dirs):
    for d in build_dirs:
        for base in (Path(d), ROOT / d):
            if all((base / "bin" / n).exists() for n in ("coupler", "cosim_scripted_peer")):
                return (base / "bin").resolve()
    sys.exit("no build directory with bin/coupler and bin/cosim_scripted_peer: build first (ninja -C build)")


def run_once(bins, work, faces, cycles, mode, phases):
    """One coupled run of cycles 0 .. `cycles` with N = faces; returns timing.csv's rows and the summary."""
    d = work / f"n{faces}_{mode}"
    shutil.rmtree(d, ignore_errors=True)
    d.mkdir(parents=True)
    timeout = max(10.0, 60.0 * faces / 1e5)  # the coupler's limit for a silent peer; a cycle at 1e6 takes seconds
    scene = d / "scene.yaml"
    scene.write_text("name: coupler_scaling\nfluid: {dummy: 1}\nsolid: {dummy: 1}\ncoupling:\n"
                     f"  time: {{end: {cycles * DT:.6e}}}\n  timeout: {timeout:g}\n  connect_timeout: 60\n")
    ep = "ipc://" + str(d / "c.sock")
    env = dict(os.environ, OMP_NUM_THREADS="1")
    env.pop("GLIBC_TUNABLES", None)
    if MALLOC[mode]:
        env["GLIBC_TUNABLES"] = MALLOC[mode]
    peer = [str(bins / "cosim_scripted_peer"), "--endpoint", ep, "--token", "tok", "--scene", str(scene),
            "--dt", f"{DT:g}", "--connect-timeout", "60"]
    cmds = {"coupler": [str(bins / "coupler"), str(scene), "--endpoint", ep, "--token", "tok", "--out",
                        str(d / "out"), "--quiet"],
            "fluid": peer + ["--role", "fluid", "--phases", str(phases)],
            "solid": peer + ["--role", "solid", "--faces", str(faces)]}
    procs = {}
    for name, cmd in cmds.items():
        with open(d / f"{name}.log", "w") as log:
            procs[name] = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, env=env)
    deadline = time.time() + 120 + timeout * (cycles + 2)
    for name, p in procs.items():
        try:
            p.wait(timeout=max(1.0, deadline - time.time()))
        except subprocess.TimeoutExpired:
            for q in procs.values():
                q.kill()
                q.wait()
            sys.exit(f"N = {faces}: the {name} did not end; see {d}")
    for name, p in procs.items():
        if p.returncode != 0:
            sys.exit(f"N = {faces}: {name} exited {p.returncode}; see {d / (name + '.log')}")
    with open(d / "out" / "timing.csv") as f:
        rows = list(csv.DictReader(f))
    summary = json.loads((d / "out" / "coupler_summary.json").read_text())
    shutil.rmtree(d / "out", ignore_errors=True)  # the interface snapshots of 1e6 faces are large
    return rows, summary


def steady(rows, summary, skip):
    """Means per cycle of cycles skip .. last-1 (the last one writes the final snapshot); bytes per cycle."""
    use = [r for r in rows if skip <= int(r["cycle"]) < int(rows[-1]["cycle"])]
    out = {c: float(np.mean([float(r[c]) for r in use])) for c in ("wall", "solid", "fluid", "coupler", "comm")}
    mb = summary["message_bytes"]
    out["bytes"] = sum(mb[r][k] for r in ("fluid", "solid") for k in ("received", "sent")) / (summary["cycles"] + 1)
    out["cycles"] = len(use)
    return out


def fit(n, c):
    """Weighted least squares c = c0 + c1 n (weights 1/c: relative errors); returns (c0, c1)."""
    n, c = np.asarray(n, float), np.asarray(c, float)
    w = 1.0 / c
    a = np.vstack([np.ones_like(n), n]).T * w[:, None]
    c0, c1 = np.linalg.lstsq(a, c * w, rcond=None)[0]
    return c0, c1


def ms(x):
    return f"{x * 1e3:.3g}" if abs(x) >= 1e-3 else f"{x * 1e3:.3f}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sizes", default="100,1000,10000,100000,1000000")
    ap.add_argument("--cycles", type=int, default=30)
    ap.add_argument("--large-from", type=float, default=1e6)
    ap.add_argument("--large-cycles", type=int, default=12)
    ap.add_argument("--skip", type=int, default=3)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--malloc", default="default,kept")
    ap.add_argument("--phases", type=int, default=2)
    ap.add_argument("--cycle-seconds", type=float, default=YARDSTICK)
    ap.add_argument("--work", default=None)
    ap.add_argument("--build", action="append", default=None)
    ap.add_argument("--no-plot", action="store_true")
    a = ap.parse_args()
    sizes = [int(float(s)) for s in a.sizes.split(",")]
    modes = a.malloc.split(",")
    for m in modes:
        if m not in MALLOC:
            sys.exit(f"--malloc {m}: expected one of {', '.join(MALLOC)}")
    env_dirs = os.environ.get("COSIM_BUILD_DIRS", "")
    bins = find_bin_dir(a.build or (env_dirs.split(":") if env_dirs else ["build", "build-c"]))
    work = Path(a.work) if a.work else Path(tempfile.mkdtemp(prefix="coupler_scaling_"))
    work.mkdir(parents=True, exist_ok=True)
    print(f"<!-- {provenance(bins)}; load average before: {os.getloadavg()[0]:.2f} -->")
    res = {(n, m): [] for n in sizes for m in modes}
    started = time.time()
    for rep in range(a.repeat):
        for n in (sizes if rep % 2 == 0 else sizes[::-1]):
            for m in (modes if rep % 2 == 0 else modes[::-1]):
                cycles = a.large_cycles if n >= a.large_from else a.cycles
                rows, summary = run_once(bins, work, n, cycles, m, a.phases)
                r = steady(rows, summary, a.skip)
                res[(n, m)].append(r)
                print(f"<!-- repeat {rep + 1}, N = {n}, malloc {m}: wall {r['wall'] * 1e3:.3f} ms, coupler "
                      f"{r['coupler'] * 1e3:.3f} ms, comm {r['comm'] * 1e3:.3f} ms over {r['cycles']} cycles; "
                      f"{time.time() - started:.0f} s, load {os.getloadavg()[0]:.2f} -->", flush=True)
    med = {k: {c: float(np.median([r[c] for r in v])) for c in COLUMNS} for k, v in res.items()}
    rng = {k: {c: (min(r[c] for r in v), max(r[c] for r in v)) for c in COLUMNS} for k, v in res.items()}
    print(f"<!-- load average after: {os.getloadavg()[0]:.2f}; {time.time() - started:.0f} s -->\n")

    print(f"Per cycle, ms, median of {a.repeat} (cycles {a.skip} .. last-1 of each run; comm min-max over the "
          f"repeats); fluid peer with {a.phases} phase(s):\n")
    print("| faces N | malloc | wall | coupler (own work) | comm | comm min-max | solid peer | fluid peer | "
          "message bytes per cycle | coupler us/face | comm us/face |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for m in modes:
        for n in sizes:
            x, r = med[(n, m)], rng[(n, m)]
            print(f"| {n:,} | {m} | {ms(x['wall'])} | {ms(x['coupler'])} | {ms(x['comm'])} | {ms(r['comm'][0])}-"
                  f"{ms(r['comm'][1])} | {ms(x['solid'])} | {ms(x['fluid'])} | {x['bytes'] / 1e6:.3g} MB | "
                  f"{x['coupler'] / n * 1e6:.3f} | {x['comm'] / n * 1e6:.3f} |")

    limit = FRACTION * a.cycle_seconds
    print(f"\nFit c = c0 + c1 N over the sizes (weights 1/c); N5 = (5% of a {a.cycle_seconds * 1e3:.0f} ms cycle "
          f"- c0) / c1 = ({limit * 1e3:.1f} ms - c0) / c1; P5 = (N5 / 4800)^(3/2) fluid ranks of 120^3 when the "
          "target is refined with the background:\n")
    print("| malloc | cost | c0 [ms] | c1 [us/face] | N5 | P5 |")
    print("|---|---|---|---|---|---|")
    fits = {}
    for m in modes:
        cw = [med[(n, m)]["coupler"] for n in sizes]
        cm = [med[(n, m)]["comm"] for n in sizes]
        for label, c in (("coupler own work", cw), ("comm", cm), ("coupler + comm", [u + v for u, v in zip(cw, cm)])):
            c0, c1 = fit(sizes, c)
            fits[(m, label)] = (c0, c1)
            n5 = (limit - c0) / c1
            p5 = f"{(n5 / 4800.0) ** 1.5:,.1f}" if n5 > 0 else "-"
            print(f"| {m} | {label} | {c0 * 1e3:.3f} | {c1 * 1e6:.4f} | {n5:,.0f} | {p5} |")

    print("\nThe tungsten blast's target (exterior quads of the solid box), coupler + comm from the fit:\n")
    print("| target mesh | faces | " + " | ".join(f"{m}: ms per cycle, share of {a.cycle_seconds * 1e3:.0f} ms"
                                              for m in modes) + " |")
    print("|---|---|" + "---|" * len(modes))
    for label, dims in TARGETS.items():
        nf = exterior_quads(*dims)
        cells = []
        for m in modes:
            c0, c1 = fits[(m, "coupler + comm")]
            cells.append(f"{(c0 + c1 * nf) * 1e3:.2f} ms, {(c0 + c1 * nf) / a.cycle_seconds * 100:.1f}%")
        print(f"| {label} | {nf:,} | " + " | ".join(cells) + " |")

    if a.no_plot:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7.5, 5))
    n = np.array(sizes, float)
    colours = {"wall": "k", "coupler": "C0", "comm": "C1"}
    for m in modes:
        style = "-o" if m == modes[0] else "--s"
        for c in ("wall", "comm", "coupler"):
            ax.loglog(n, [med[(x, m)][c] * 1e3 for x in sizes], style, color=colours[c], ms=4,
                      label=f"{c}, malloc {m}")
    ax.axhline(limit * 1e3, color="C3", lw=1, label=f"5% of the flagship's {a.cycle_seconds * 1e3:.0f} ms cycle")
    nf = exterior_quads(*TARGETS["scene 10 x 40 x 40"])
    ax.axvline(nf, color="0.5", lw=0.8, ls=":")
    ax.annotate("tungsten blast target\n10 x 40 x 40: 4800 faces", (nf, limit * 1e3), fontsize=8, color="0.3",
                xytext=(4, -40), textcoords="offset points")
    ax.set_xlabel("interface faces N (3D quads)")
    ax.set_ylabel("ms per cycle")
    ax.set_title(f"one coupler between scripted peers, {a.phases} fluid phases (median of {a.repeat})", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    RESULTS.mkdir(parents=True, exist_ok=True)
    out = RESULTS / "coupler_scaling.png"
    fig.savefig(out, dpi=110)
    print(f"\nwrote {out.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
