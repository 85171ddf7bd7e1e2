#!/usr/bin/python3
"""The flagship scene at full size: paper 9.6, a tungsten-laden blast on a clamped steel target in 3D
(configs/tungsten_blast_3d.yaml: 120^3 background, 10 x 40 x 40 target, 1 ms).

Runs `cosim run` with a progress line (cycle, t / t_end, wall per cycle, ETA, from the coupler's interface
history), then prints: wall time, cycles, the fluid's M cell-updates/s over its own solver time and over the
wall time, the geometry's share of the cycle, the per-phase mass balance (start, through the domain boundary,
through the target's walls, with the cells it covered or uncovered, unaccounted), the fluid's state bytes per cell and the peak memory of the largest process; and writes the plots (paper
Figs. 9-10): particle volume fraction on the mid-plane z = 0.5 before and after the cloud reaches the target,
von Mises stress in the target at the end, the target's mean velocity and plastic work over time
(bench/results/tungsten_blast_fields.png, tungsten_blast_target.png).

Usage: bench/coupled/run_tungsten_blast.py [--cells N] [--target NX NY NZ] [--end S] [--build DIR] [--work DIR]
(--cells 40 --target 4 12 12 --end 3e-4: a check of the script in about a minute)
"""
import argparse
import csv
import glob
import json
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import h5py
import matplotlib
import numpy as np

from bench_common import RESULTS, ROOT, provenance

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def last_row(path):
    """The last complete line of a CSV being written, as a dict (None before the first)."""
    try:
        with open(path) as fh:
            lines = fh.read().splitlines()
    except OSError:
        return None
    if len(lines) < 2:
        return None
    header = lines[0].split(",")
    for line in reversed(lines[1:]):
        vals = line.split(",")
        if len(vals) == len(header):
            return dict(zip(header, vals))
    return None


def run_with_progress(cmd, run_dir, t_end, log):
    """Runs cmd, printing one progress line every 10 s (on a terminal: rewritten in place)."""
    t0 = time.perf_counter()
    tty = sys.stdout.isatty()
    with open(log, "w") as fh:
        proc = subprocess.Popen(cmd, stdout=fh, stderr=subprocess.STDOUT)
        while proc.poll() is None:
            time.sleep(10)
            row = last_row(Path(run_dir) / "coupler" / "interface_history.csv")
            wall = time.perf_counter() - t0
            if row:
                t, cyc = float(row["time"]), int(row["cycle"])
                eta = wall * (t_end - t) / t if t > 0 else float("nan")
                line = (f"cycle {cyc}, t = {t:.4g} / {t_end:.4g} s, {1e3 * wall / max(cyc, 1):.0f} ms/cycle, "
                        f"wall {wall / 60:.1f} min, ETA {eta / 60:.1f} min")
                print("\r" + line + " " * 8 if tty else line, end="" if tty else "\n", flush=True)
    if tty:
        print()
    if proc.returncode != 0:
        sys.exit(f"failed ({proc.returncode}): {' '.join(cmd)}; see {log}")
    return time.perf_counter() - t0


def field_at(run, t_target):
    """The fluid snapshot nearest to t_target: (time, tungsten alpha, embedded category), arrays [z, y, x]."""
    best = None
    for fn in sorted(glob.glob(str(Path(run) / "fluid" / "fluid_*.h5"))):
        with h5py.File(fn) as f:
            t = float(f.attrs["time"])
            if best is None or abs(t - t_target) < abs(best[0] - t_target):
                best = (t, fn)
    with h5py.File(best[1]) as f:
        return best[0], f["cell/tungsten_alpha"][...], f["cell/embedded_category"][...]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cells", type=int, default=120)
    ap.add_argument("--target", type=int, nargs=3, default=[10, 40, 40])
    ap.add_argument("--end", type=float, default=1.0e-3)
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--work", default=None)
    args = ap.parse_args()
    work = Path(args.work or tempfile.mkdtemp(prefix="tungsten_blast_"))
    work.mkdir(parents=True, exist_ok=True)
    run = work / f"run_{args.cells}"
    n = args.cells
    cmd = [str(Path(args.build) / "bin" / "cosim"), "run", str(ROOT / "configs" / "tungsten_blast_3d.yaml"),
           "--out", str(run), "--quiet", "--set", f"fluid.mesh.cells=[{n},{n},{n}]",
           "--set", "solid.mesh.cells=[{},{},{}]".format(*args.target), "--set", f"coupling.time.end={args.end}",
           "--set", f"coupling.output.interval={args.end / 10}"]
    print(provenance(Path(args.build) / "bin"))
    print(f"{n}^3 background, target {args.target}, end {args.end} s, run in {run}")
    wall = run_with_progress(cmd, run, args.end, str(run) + ".log")

    fs = json.load(open(run / "fluid" / "summary.json"))
    ss = json.load(open(run / "solid" / "summary.json"))
    cs = json.load(open(run / "coupler" / "coupler_summary.json"))
    acc = json.load(open(run / "energy_account.json"))
    c = fs["coupling"]
    cycles = c["cycles"]
    updates = float(n) ** 3 * cycles
    print("\n| quantity | value |\n|---|---|")
    print(f"| wall time | {wall:.0f} s ({wall / 60:.1f} min), {cycles} cycles, {1e3 * wall / cycles:.0f} ms/cycle |")
    print(f"| fluid M cell-updates/s | {updates / c['flow_solver_seconds'] / 1e6:.2f} over its solver time, "
          f"{updates / wall / 1e6:.2f} over the wall time ({fs['threads']} threads) |")
    print(f"| geometry share of the cycle | {c['geometry_seconds'] / wall:.1%} ({c['geometry_seconds']:.0f} s) |")
    print(f"| solid solver time | {ss.get('coupling', {}).get('solver_seconds', float('nan')):.2f} s |")
    rss = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024  # KiB on Linux
    print(f"| memory | fluid state {fs['state_bytes_per_cell']:.0f} bytes/cell; peak of the largest process "
          f"{rss:.0f} MiB |")
    t = fs["totals"]
    for k in range(2):
        m0, inflow, made = t["start"][k]["mass"], t["boundary_inflow"][k]["mass"], t["created"][k]["mass"]
        em = fs["embedded"]["mass"][k]
        print(f"| {t['start'][k]['phase']} mass | {m0:.5g} kg, through the domain boundary {inflow:+.4g}, through "
              f"the target's walls {em['through_walls']:+.3g}, with the cells it covered or uncovered "
              f"{em['cells_uncovered']:+.3g}, unaccounted {em['unaccounted']:+.1e} ({em['unaccounted'] / m0:.0e}) |")
    print(f"| energy created at the interface | {acc['interface_created_relative']:.2e} of the total |")
    print(f"| coupler | {cs.get('status', '?')} |")

    # Target histories
    tb, vb, wp, vm = [], [], [], []
    with open(run / "solid" / "block_history.csv") as fh:
        for r in csv.DictReader(fh):
            tb.append(float(r["time"]))
            vb.append(float(r["velocity_x"]))
            wp.append(float(r["plastic_work"]))
            vm.append(float(r["max_von_mises"]))
    print(f"| target | peak mean velocity {max(vb):.3g} m/s, plastic work at the end {wp[-1]:.4g} J, "
          f"max von Mises {max(vm) / 1e6:.0f} MPa |")

    # The particles in front of the target (x in [0.30, 0.45], |y - 0.5|, |z - 0.5| < 0.25, flow cells): their
    # mass and mass-weighted mean x velocity per snapshot; a reflection turns the velocity negative.
    print("\n| t [ms] | tungsten mass in front of the target [kg] | its mean x velocity [m/s] |\n|---|---|---|")
    tf, uf = [], []
    for fn in sorted(glob.glob(str(run / "fluid" / "fluid_*.h5"))):
        with h5py.File(fn) as f:
            a, r = f["cell/tungsten_alpha"][...], f["cell/tungsten_density"][...]
            ux, k = f["cell/tungsten_velocity"][..., 0], f["cell/embedded_category"][...]
            x = (np.arange(a.shape[2]) + 0.5) / a.shape[2]
            X, Y, Z = x[None, None, :], x[None, :, None], x[:, None, None]
            sel = (X > 0.30) & (X < 0.45) & (abs(Y - 0.5) < 0.25) & (abs(Z - 0.5) < 0.25) & (k <= 1)
            m = a * r * sel
            tf.append(float(f.attrs["time"]))
            uf.append(float(np.sum(m * ux) / max(np.sum(m), 1e-300)))
            print(f"| {tf[-1] * 1e3:.2f} | {np.sum(m) / a.size:.4g} | {uf[-1]:.1f} |")

    RESULTS.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    for ax, frac in zip(axes[:2], (0.25, 1.0)):
        tt, a, k = field_at(run, frac * args.end)
        mid = a.shape[0] // 2
        im = ax.imshow(np.where(k[mid] <= 1, a[mid], np.nan), origin="lower", extent=[0, 1, 0, 1],
                       cmap="viridis", vmin=0, vmax=max(1e-3, float(np.nanmax(a[mid]))))
        ax.set_title(f"tungsten volume fraction, z = 0.5, t = {tt * 1e3:.2f} ms")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        fig.colorbar(im, ax=ax, shrink=0.8)
    sol = sorted(glob.glob(str(run / "solid" / "solid_*.h5")))[-1]
    with h5py.File(sol) as f:
        xyz = f["grid/coordinates"][...]
        conn = f["grid/connectivity"][...]
        vmis = f["cell/von_mises"][...]
    cen = xyz[conn].mean(axis=1)
    z_layer = cen[np.argmin(np.abs(cen[:, 2] - 0.5)), 2]  # the element layer next to the mid-plane
    sel = np.abs(cen[:, 2] - z_layer) < 0.25 * 0.5 / args.target[2]  # a quarter of an element: deformed
    sc = axes[2].scatter(cen[sel, 0], cen[sel, 1], c=vmis[sel] / 1e6, s=30, marker="s", cmap="inferno")
    axes[2].set_aspect("equal")
    axes[2].set_xlim(0.4, 0.6)
    axes[2].set_title(f"target von Mises [MPa], z = {z_layer:.3f}, t = {tb[-1] * 1e3:.2f} ms")
    axes[2].set_xlabel("x [m]")
    axes[2].set_ylabel("y [m]")
    fig.colorbar(sc, ax=axes[2], shrink=0.8)
    fig.tight_layout()
    fig.savefig(RESULTS / "tungsten_blast_fields.png", dpi=110)

    fig, ax = plt.subplots(1, 3, figsize=(15, 4))
    ax[2].plot(np.array(tf) * 1e3, uf, "o-")
    ax[2].axhline(0, color="k", lw=0.5)
    ax[2].set_xlabel("t [ms]")
    ax[2].set_ylabel("particles in front of the target: mean u_x [m/s]")
    ax[0].plot(np.array(tb) * 1e3, vb)
    ax[0].set_xlabel("t [ms]")
    ax[0].set_ylabel("target mean velocity x [m/s]")
    ax[1].plot(np.array(tb) * 1e3, wp)
    ax[1].set_xlabel("t [ms]")
    ax[1].set_ylabel("target plastic work [J]")
    fig.suptitle(f"paper 9.6: {n}^3 background, target {args.target[0]} x {args.target[1]} x {args.target[2]}")
    fig.tight_layout()
    fig.savefig(RESULTS / "tungsten_blast_target.png", dpi=110)
    print(f"plots: {RESULTS / 'tungsten_blast_fields.png'}, {RESULTS / 'tungsten_blast_target.png'}")


if __name__ == "__main__":
    main()
