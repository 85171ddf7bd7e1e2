#!/usr/bin/python3
"""Fluid solver benchmarks: run time against error (Sod, smooth wave) and throughput (2D, and the 3D blast).

Runs the benchmark programs built in build/bin, prints markdown tables and writes PNG plots to
bench/results/. Everything in one run, side by side, so that the ratios are comparable on a noisy
machine. Usage: /usr/bin/python3 bench/fluid/run_fluid_benchmarks.py [--quick]
"""
import argparse
import csv
import io
import json
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BIN = os.path.join(ROOT, "build", "bin")
OUT = os.path.join(ROOT, "bench", "results")


def run(cmd):
    return subprocess.run(cmd, check=True, capture_output=True, text=True, cwd=ROOT).stdout


def error_vs_time(quick):
    args = [os.path.join(BIN, "fluid_error_vs_time")]
    if quick:
        args += ["--sod-max", "1600", "--wave-max", "256"]
    rows = list(csv.DictReader(io.StringIO(run(args))))
    for r in rows:
        r["N"], r["order"] = int(r["N"]), int(r["order"])
        r["wall_s"], r["l1_rho"] = float(r["wall_s"]), float(r["l1_rho"])
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, problem, title in zip(axes, ["sod", "wave"], ["Sod, t = 0.2", "smooth density wave, one period"]):
        for flux, color in [("aufs", "C0"), ("hllc", "C1"), ("rusanov", "C2")]:
            for order, style in [(1, "--o"), (2, "-s")]:
                pts = [r for r in rows if r["problem"] == problem and r["flux"] == flux and r["order"] == order]
                ax.loglog([p["wall_s"] for p in pts], [p["l1_rho"] for p in pts], style, color=color, ms=3,
                          label=f"{flux} {'MUSCL' if order == 2 else '1st order'}")
        ax.set_xlabel("wall time [s] (1 thread)")
        ax.set_ylabel("L1 density error")
        ax.set_title(title)
        ax.grid(alpha=0.3, which="both")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "fluid_error_vs_time.png"), dpi=110)
    print("\n### Sod L1(density) error and wall time (1 thread)\n")
    ns = sorted({r["N"] for r in rows if r["problem"] == "sod"})
    print("| scheme | " + " | ".join(f"N={n}" for n in ns) + " |")
    print("|---|" + "---|" * len(ns))
    for flux in ["aufs", "hllc", "rusanov"]:
        for order in [1, 2]:
            pts = {r["N"]: r for r in rows if r["problem"] == "sod" and r["flux"] == flux and r["order"] == order}
            name = f"{flux} {'MUSCL' if order == 2 else '1st'}"
            print(f"| {name} | " + " | ".join(f"{pts[n]['l1_rho']:.2e} ({pts[n]['wall_s']:.3g} s)" for n in ns) + " |")
    print("\n### Smooth wave L1(density) error and observed order (finest pair)\n")
    print("| scheme | finest N | L1 | order | wall [s] |")
    print("|---|---|---|---|---|")
    import math
    for flux in ["aufs", "hllc", "rusanov"]:
        for order in [1, 2]:
            pts = sorted([r for r in rows if r["problem"] == "wave" and r["flux"] == flux and r["order"] == order],
                         key=lambda r: r["N"])
            a, b = pts[-2], pts[-1]
            p = math.log(a["l1_rho"] / b["l1_rho"]) / math.log(b["N"] / a["N"])
            print(f"| {flux} {'MUSCL' if order == 2 else '1st'} | {b['N']} | {b['l1_rho']:.2e} | {p:.2f} | {b['wall_s']:.3g} |")
    return rows


def throughput(quick):
    scenes = [("bench/fluid/riemann_2d.yaml", "single phase, MUSCL-AUFS-RK2"),
              ("bench/fluid/water_air_2d.yaml", "two-phase DEM water/air, instant relaxation"),
              ("bench/fluid/two_phase_2d.yaml", "two-phase DEM air/tungsten, drag + heat")]
    steps = "3" if quick else "6"
    results = []
    for scene, label in scenes:
        for threads in [1, 2]:
            best = None
            for _ in range(2 if quick else 3):  # best of a few: the machine is noisy
                out = json.loads(run([os.path.join(BIN, "fluid_throughput"), scene, "--steps", steps,
                                      "--threads", str(threads)]))
                if best is None or out["cell_updates_per_s"] > best["cell_updates_per_s"]:
                    best = out
            best["label"] = label
            results.append(best)
    print("\n### Throughput, 2D, 1000 x 1000 cells\n")
    print("| scene | threads | Mcell-updates/s | speed-up | bytes/cell | " + ROOFLINE_HEADER)
    print("|---|---|---|---|---|---|---|---|---|")
    for i, r in enumerate(results):
        base = results[i - (i % 2)]["cell_updates_per_s"]
        print(f"| {r['label']} | {r['threads']} | {r['cell_updates_per_s'] / 1e6:.2f} | "
              f"{r['cell_updates_per_s'] / base:.2f} | {r['bytes_per_cell']:.0f} | {roofline(r)}")
    print(ROOFLINE_NOTE)
    fig, ax = plt.subplots(figsize=(7, 3.5))
    labels = [r["label"] for r in results[::2]]
    x = range(len(labels))
    ax.bar([i - 0.2 for i in x], [r["cell_updates_per_s"] / 1e6 for r in results[::2]], 0.4, label="1 thread")
    ax.bar([i + 0.2 for i in x], [r["cell_updates_per_s"] / 1e6 for r in results[1::2]], 0.4, label="2 threads")
    ax.set_xticks(list(x))
    ax.set_xticklabels([lbl.replace(", ", "\n") for lbl in labels], fontsize=8)
    ax.set_ylabel("million cell-updates / s")
    ax.legend()
    ax.grid(alpha=0.3, axis="y")
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "fluid_throughput.png"), dpi=110)
    return results


ROOFLINE_HEADER = "bytes/cell-update | triad GB/s | of the bandwidth ceiling |"
ROOFLINE_NOTE = ("\nbytes/cell-update: what the step's passes read and write per cell (fluid_solver/core/solver.h, "
                 "traffic_bytes_per_cell_update); triad: STREAM's a = b + s c on the same threads in the same run; "
                 "ceiling = triad / bytes per cell-update.")


def roofline(r):
    """The roofline columns of a fluid_throughput result."""
    return (f"{r['traffic_bytes_per_cell_update']:.0f} | {r['triad_bytes_per_s'] / 1e9:.1f} | "
            f"{100 * r['fraction_of_ceiling']:.0f}% of {r['ceiling_cell_updates_per_s'] / 1e6:.1f} M/s |")


def cube_run(scene, n, threads, steps, extra=()):
    """fluid_throughput's result for `scene` on an n^3 mesh, with n added."""
    cmd = [os.path.join(BIN, "fluid_throughput"), scene, "--steps", str(steps), "--threads", str(threads),
           "--set", f"fluid.mesh.cells=[{n},{n},{n}]", *extra]
    return json.loads(run(cmd)) | {"n": n}


def throughput_3d(quick):
    """The 3D tungsten blast's fluid (bench/fluid/tungsten_blast_3d_fluid.yaml: air and dispersed tungsten
    particles, drag, heat exchange, granular temperature): at 120^3 from its initial state (a quiescent domain
    around the hot sphere), and at 64^3 developed (timed after 0.6 ms, the blast across the domain and the cloud
    on its way); one and two threads."""
    scene = "bench/fluid/tungsten_blast_3d_fluid.yaml"
    cases = [(120 if not quick else 64, 0.0), (64 if not quick else 40, 6e-4)]
    rows = []
    for n, after in cases:
        for threads in [1, 2]:
            extra = ["--after", str(after)] if after > 0 else []
            rows.append(cube_run(scene, n, threads, 4 if quick else 8, extra) | {"after": after})
    print("\n### Throughput, 3D two-phase (tungsten blast fluid)\n")
    print("| cells | timed after | threads | Mcell-updates/s | per thread | bytes/cell | " + ROOFLINE_HEADER)
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        rate = r["cell_updates_per_s"] / 1e6
        print(f"| {r['n']}^3 | {r['after'] * 1e3:.1f} ms | {r['threads']} | {rate:.2f} | {rate / r['threads']:.2f} | "
              f"{r['bytes_per_cell']:.0f} | {roofline(r)}")
    print(ROOFLINE_NOTE)
    return rows


def throughput_3d_sizes(quick):
    """3D at 128^3 and 256^3 (64^3 and 96^3 with --quick), one and two threads, from the initial state: single
    phase (bench/fluid/blast_3d.yaml, a blast in air) and two-phase (the tungsten blast's fluid, with drag, heat
    exchange and granular temperature)."""
    scenes = [("single phase, blast", "bench/fluid/blast_3d.yaml"),
              ("air/tungsten, drag + heat", "bench/fluid/tungsten_blast_3d_fluid.yaml")]
    rows = []
    for label, scene in scenes:
        for n in ([64, 96] if quick else [128, 256]):
            for threads in [1, 2]:
                rows.append(cube_run(scene, n, threads, 4) | {"label": label})
    print("\n### Throughput, 3D, by size\n")
    print("| scene | cells | threads | Mcell-updates/s | per thread | bytes/cell | " + ROOFLINE_HEADER)
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        rate = r["cell_updates_per_s"] / 1e6
        print(f"| {r['label']} | {r['n']}^3 | {r['threads']} | {rate:.2f} | {rate / r['threads']:.2f} | "
              f"{r['bytes_per_cell']:.0f} | {roofline(r)}")
    print(ROOFLINE_NOTE)
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="smaller sizes (a minute)")
    ap.add_argument("--only", choices=["error", "throughput", "3d", "3d-sizes"], help="run one part only")
    a = ap.parse_args()
    for exe in ["fluid_error_vs_time", "fluid_throughput"]:
        if not os.path.exists(os.path.join(BIN, exe)):
            sys.exit(f"{exe} not built: run scripts/build.sh first")
    os.makedirs(OUT, exist_ok=True)
    parts = {"error": error_vs_time, "throughput": throughput, "3d": throughput_3d, "3d-sizes": throughput_3d_sizes}
    for name, part in parts.items():
        if a.only in (None, name):
            part(a.quick)
    print(f"\nplots: {OUT}/fluid_error_vs_time.png, {OUT}/fluid_throughput.png")


if __name__ == "__main__":
    main()
