#!/usr/bin/python3
"""The fluid solver on ranks and threads: throughput, parallel efficiency, the halo's share, and a scaling model.

Runs build/bin/fluid_solver on the benchmark scenes of bench/fluid/ (2D 1000^2 and 3D 128^3, single phase and
air/tungsten) as 1 rank x 1 thread, 1 rank x 2 threads and 2 ranks x 1 thread (mpirun), in alternation, `--repeats`
rounds, and takes each configuration's best round. The rate counts the steps only (the summary's wall time less its
output_seconds). Also 2 and 4 ranks on the machine's cores with passive and spinning waits, and the snapshot write
rate (collective parallel HDF5) on 1, 2 and 4 ranks. Prints markdown tables, writes bench/results/fluid_ranks.png
and fluid_ranks_model.png.

Then a model of the tungsten scene at 1000^3 on 1 to 4096 ranks: computation per rank from the measured one-core
rate of the 3D air/tungsten scene, the halo from the bytes the solver sends per step (two ghost layers of every
primitive per face, two Runge-Kutta stages) over a stated network, one reduction per step.

Usage: /usr/bin/python3 bench/parallel/run_fluid_ranks.py [--quick] [--repeats N] [--only ranks|waits|halo|snapshots]
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BIN = os.path.join(ROOT, "build", "bin", "fluid_solver")
OUT = os.path.join(ROOT, "bench", "results")
MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe", "--bind-to", "none"]

# name, scene, mesh, steps (quick steps), doubles exchanged per ghost cell (the primitives)
SCENES = [
    ("2D single phase 1000^2", "bench/fluid/riemann_2d.yaml", [1000, 1000], 40, 10),
    ("2D air/tungsten 1000^2", "bench/fluid/two_phase_2d.yaml", [1000, 1000], 20, 5),
    ("3D single phase 128^3", "bench/fluid/blast_3d.yaml", [128, 128, 128], 10, 3),
    ("3D air/tungsten 128^3", "bench/fluid/tungsten_blast_3d_fluid.yaml", [128, 128, 128], 6, 2),
]
CONFIGS = [(1, 1), (1, 2), (2, 1)]  # (ranks, threads per rank)


def run(scene, mesh, steps, ranks, threads, work, env=None):
    out = os.path.join(work, "run")
    shutil.rmtree(out, ignore_errors=True)
    cmd = ([] if ranks == 1 else MPIRUN + ["-np", str(ranks)]) + [
        BIN, os.path.join(ROOT, scene), "--out", out, "--quiet", "--threads", str(threads),
        "--set", "fluid.mesh.cells=[%s]" % ",".join(map(str, mesh)),
        "--set", "fluid.time.max_steps=%d" % steps]
    subprocess.run(cmd, check=True, capture_output=True, text=True, env=dict(os.environ, **(env or {})))
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    stepping = s["wall_time_s"] - s.get("output_seconds", 0.0)
    cells = math.prod(mesh)
    return {"rate": cells * s["steps"] / stepping, "halo_share": s["parallel"]["halo_seconds"] / stepping,
            "wait_share": s["parallel"].get("halo_wait_seconds", 0.0) / stepping,
            "halo_bytes_per_step": s["parallel"]["halo_bytes"] / s["steps"], "steps": s["steps"]}


def measure(quick, repeats):
    work = tempfile.mkdtemp(prefix="fluid_ranks_")
    results = {}
    try:
        for name, scene, mesh, steps, quick_steps in SCENES:
            n = quick_steps if quick else steps
            best = {}
            for _ in range(repeats):  # alternation: the machine's load falls on every configuration alike
                for ranks, threads in CONFIGS:
                    r = run(scene, mesh, n, ranks, threads, work)
                    key = (ranks, threads)
                    if key not in best or r["rate"] > best[key]["rate"]:
                        best[key] = r
            results[name] = best
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return results


WAITS = ("passive", "sleep", "spin")  # COSIM_MPI_WAIT: yield then sleep (default), sleep at once, spin


def oversubscription(quick, repeats):
    """2 and 4 ranks of one thread, blocks of 500^2 (2D air/tungsten 1000^2) and 250^2 (single phase): each way of
    waiting (common/parallel/mpi/passive_wait.cpp)."""
    work = tempfile.mkdtemp(prefix="fluid_ranks_")
    cases = [("2D air/tungsten 1000^2", "bench/fluid/two_phase_2d.yaml", {2: [1000, 1000], 4: [1000, 1000]},
              5 if quick else 20),
             ("2D single phase, 250^2 per rank", "bench/fluid/riemann_2d.yaml", {2: [250, 500], 4: [500, 500]},
              20 if quick else 200)]
    best = {}
    try:
        for _ in range(repeats):
            for name, scene, meshes, steps in cases:
                for ranks in (2, 4):
                    for wait in WAITS:
                        r = run(scene, meshes[ranks], steps, ranks, 1, work, {"COSIM_MPI_WAIT": wait})
                        key = (name, ranks, wait)
                        if key not in best or r["rate"] > best[key]["rate"]:
                            best[key] = r
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print("\n| %d cores | ranks x 1 thread | yield, then sleep (default) [Mcell/s] | sleep at once | spin |"
          % os.cpu_count())
    print("|---|---|---|---|---|")
    for name, _, _, _ in cases:
        for ranks in (2, 4):
            print("| %s | %d | %s |" % (name, ranks, " | ".join("%.2f" % (best[(name, ranks, w)]["rate"] / 1e6)
                                                               for w in WAITS)))


def halo_sweep(quick, repeats):
    """The halo against the cells per rank: 2 ranks x 1 thread, each an N^2 (2D) or N^3 (3D) block, one phase."""
    work = tempfile.mkdtemp(prefix="fluid_ranks_")
    rows = []
    try:
        for dim, sizes, scene in ((2, (125, 250, 500), "bench/fluid/riemann_2d.yaml"),
                                  (3, (32, 64), "bench/fluid/blast_3d.yaml")):
            for n in sizes:
                mesh = [n] * (dim - 1) + [2 * n]  # split across the slowest axis: two n^dim blocks
                steps = (20 if quick else 200) if dim == 2 else (5 if quick else 20)
                best = None
                for _ in range(repeats):
                    r = run(scene, mesh, steps, 2, 1, work)
                    if best is None or r["rate"] > best["rate"]:
                        best = r
                step_s = 2 * n ** dim / best["rate"]
                rows.append((dim, n, best["halo_bytes_per_step"], best["halo_share"] * step_s, best["halo_share"],
                             best["wait_share"]))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print("\n| block per rank (2 ranks x 1 thread, one phase) | halo bytes per step (both ranks) | halo time per step "
          "| share of the step | of it waiting |")
    print("|---|---|---|---|---|")
    for dim, n, b, t, share, wait in rows:
        print("| %d^%d | %.0f kB | %.2f ms | %.1f%% | %.1f%% |" % (n, dim, b / 1e3, 1e3 * t, 100 * share, 100 * wait))


def snapshot_rate(repeats):
    """Bytes per second of the snapshots of the 2D air/tungsten scene at 1000^2 on 1, 2 and 4 ranks."""
    work = tempfile.mkdtemp(prefix="fluid_ranks_")
    print("\n| snapshot of 2D air/tungsten 1000^2 | ranks | size | seconds | MB/s | against 1 rank |")
    print("|---|---|---|---|---|---|")
    base = None
    try:
        for ranks in (1, 2, 4):
            best = None
            for _ in range(repeats):
                out = os.path.join(work, "run")
                shutil.rmtree(out, ignore_errors=True)
                cmd = ([] if ranks == 1 else MPIRUN + ["-np", str(ranks)]) + [
                    BIN, os.path.join(ROOT, "bench/fluid/two_phase_2d.yaml"), "--out", out, "--quiet", "--threads",
                    "1", "--set", "fluid.time.max_steps=1"]
                subprocess.run(cmd, check=True, capture_output=True, text=True)
                with open(os.path.join(out, "summary.json")) as f:
                    s = json.load(f)
                files = [os.path.join(out, n) for n in os.listdir(out) if n.startswith("fluid_") and n.endswith(".h5")]
                size = sum(os.path.getsize(f) for f in files)
                seconds = s["output_seconds"]
                if best is None or seconds < best[1]:
                    best = (size, seconds, len(files))
            size, seconds, count = best
            rate = size / seconds
            base = base or rate
            print("| %d snapshot(s) | %d | %.0f MB | %.2f | %.0f | %.2f |" % (count, ranks, size / 1e6, seconds,
                                                                        rate / 1e6, rate / base))
    finally:
        shutil.rmtree(work, ignore_errors=True)


def print_table(results):
    print("| scene | 1 rank x 1 thread [Mcell/s] | 1 rank x 2 threads | 2 ranks x 1 thread | "
          "2x1 / 1x2 | efficiency 2x1 | halo share 2x1 | halo per step |")
    print("|---|---|---|---|---|---|---|---|")
    for name, best in results.items():
        r11, r12, r21 = best[(1, 1)], best[(1, 2)], best[(2, 1)]
        print("| %s | %.2f | %.2f | %.2f | %.2f | %.0f%% | %.1f%% | %.1f MB |" % (
            name, r11["rate"] / 1e6, r12["rate"] / 1e6, r21["rate"] / 1e6, r21["rate"] / r12["rate"],
            100 * r21["rate"] / (2 * r11["rate"]), 100 * r21["halo_share"], r21["halo_bytes_per_step"] / 1e6))


def plot(results):
    fig, ax = plt.subplots(figsize=(9, 4.2))
    names = list(results)
    width = 0.25
    for i, (ranks, threads) in enumerate(CONFIGS):
        ax.bar([x + (i - 1) * width for x in range(len(names))],
               [results[n][(ranks, threads)]["rate"] / 1e6 for n in names], width,
               label="%d rank(s) x %d thread(s)" % (ranks, threads))
    ax.set_xticks(range(len(names)))
    ax.set_xticklabels(names, fontsize=8)
    ax.set_ylabel("cell updates per second [M]")
    ax.set_title("fluid_solver on 2 cores: ranks against threads (best of the rounds)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "fluid_ranks.png"), dpi=110)


# The scaling model's cluster: nodes of 64 cores (one rank per core, the node's ranks a cube of 4^3 blocks) sharing
# one 100 Gb/s link; 1.5 us per message; a reduction of log2(P) latencies. Halo bytes between the ranks of a node
# move through memory and are not counted; the node's outer faces go over its link.
BANDWIDTH = 100e9 / 8
LATENCY = 1.5e-6
NODE_CORES = 64
PRIMITIVES = 13  # doubles per ghost cell of the air/tungsten scene (two phases' rho, u[3], p, c, alpha, ...)


def step_model(n, ranks, rate_per_core):
    """(computation, communication) seconds per step of a cubic block of n^3 cells on each of `ranks` ranks."""
    compute = n ** 3 / rate_per_core
    if ranks == 1:
        return compute, 0.0
    per_node = min(ranks, NODE_CORES)
    nodes = ranks / per_node
    side = n * per_node ** (1 / 3)  # the node's cube of blocks
    node_bytes = (6 * side * side * 2 * PRIMITIVES * 8) if nodes > 1 else 0.0  # two ghost layers per outer face
    stage = 3 * 2 * LATENCY + node_bytes / BANDWIDTH  # the three axes one after the other
    return compute, 2 * stage + LATENCY * math.log2(ranks)  # two Runge-Kutta stages, one reduction


def scaling_model(results):
    rate = results["3D air/tungsten 128^3"][(1, 1)]["rate"]
    ranks = [2 ** k for k in range(0, 13)]
    strong, weak = [], []
    t1 = None
    for p in ranks:  # strong: 1000^3 cells over p ranks; weak: 128^3 cells per rank
        n = 1000 / p ** (1 / 3)
        c, h = step_model(n, p, rate)
        t = c + h
        t1 = t1 or t
        strong.append(t1 / (p * t))
        c, h = step_model(128, p, rate)
        weak.append(c / (c + h))
    fig, ax = plt.subplots(figsize=(7, 4.2))
    ax.semilogx(ranks, strong, "o-", base=2, label="strong: 1000^3 cells")
    ax.semilogx(ranks, weak, "s-", base=2, label="weak: 128^3 cells per rank")
    ax.axhline(0.8, color="gray", lw=0.8, ls="--")
    ax.set_xlabel("ranks (one core each)")
    ax.set_ylabel("parallel efficiency")
    ax.set_ylim(0, 1.05)
    ax.set_title("Model, air/tungsten: %.2f Mcell/s per core (measured), 64 cores per node on 100 Gb/s, 1.5 us"
                 % (rate / 1e6), fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "fluid_ranks_model.png"), dpi=110)
    print("\n| ranks | cells per rank (strong) | strong efficiency | weak efficiency (128^3 per rank) |")
    print("|---|---|---|---|")
    for p, s, w in zip(ranks, strong, weak):
        print("| %d | %.3g | %.0f%% | %.0f%% |" % (p, 1e9 / p, 100 * s, 100 * w))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer steps")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--only", choices=("ranks", "waits", "halo", "snapshots"), action="append",
                    help="only these parts (repeatable): ranks against threads with the model, the ways of waiting, "
                         "the halo sweep, the snapshot rate")
    a = ap.parse_args()
    parts = set(a.only or ("ranks", "waits", "halo", "snapshots"))
    os.makedirs(OUT, exist_ok=True)
    if "ranks" in parts:
        results = measure(a.quick, a.repeats)
        print_table(results)
        plot(results)
        scaling_model(results)
    if "waits" in parts:
        oversubscription(a.quick, a.repeats)
    if "halo" in parts:
        halo_sweep(a.quick, a.repeats)
    if "snapshots" in parts:
        snapshot_rate(a.repeats)


if __name__ == "__main__":
    main()
