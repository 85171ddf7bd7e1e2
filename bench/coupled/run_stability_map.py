#!/usr/bin/python3
"""Stability and consistency map of the coupled scenes: density ratio x CFL number x interface condition.

Scenes (all with a deformable structure, so that the interface conditions differ):
  piston     configs/piston_light_2d.yaml: a gas slab (ideal gas, 1.5e5 Pa) between two gas chambers
             (1 kg/m^3); solid.blocks.0.density = ratio x 1 kg/m^3; run to t = 20 ms.
  advection  bench/coupled/advection_deformable.yaml: an ideal-gas block at the fluid's pressure moving with
             the flow (fluid 1 kg/m^3); solid.blocks.0.density = ratio x 1 kg/m^3; 200 cycles.
For every ratio in 1e-3 .. 1e3 and CFL in 0.1 .. 0.9 (fluid.time.cfl and solid.numerics.cfl together) and
both coupling.mode values, one short `cosim run`, classified as:
  blows up    the run failed (non-zero exit: a solver stopped on an inadmissible state, a degenerate
              geometry, a collapsed time step, ...) or interface_history.csv holds a non-finite number;
  oscillates  piston: the high-frequency index H > H_MAX (below); advection: the block's face-averaged
              velocity deviates from the initial (0.1, 0.1) m/s by more than 1e-6 relative at any cycle
              (paper 9.2: nothing may happen); sod, panel: H of the structure's face-averaged velocity_x over
              a window of 1/20 of the run (these runs are not classified oscillating by anything else);
  stable      otherwise.
High-frequency index H (piston): the face-averaged velocity_x(t) of interface_history.csv is put on a uniform
time grid, low-passed with a moving average over T_C = 1 ms (a wave period of about 4 fluid cells,
4 x 0.1 m / 374 m/s: any faster motion cannot be a wave the fluid resolves), and
  H = rms(v - v_lowpass) / max|v_lowpass|
over [T_C, t_end - T_C/2] (the first millisecond holds the impulsive start). H_MAX = 0.05, i.e. a ringing
of 5% rms of the motion; the script prints the H of the runs that are smooth by construction (ratio >= 100,
stiff heavy slab, velocity monotone) so that the margin can be checked on every run of the map. The same
index over the first 5 ms only (index_early in the CSV; "rings < 5 ms" in the plot) flags stable runs whose
start transient rings and then decays.
Consistency: the response at the end time per CFL number (piston: face-averaged velocity_x at 20 ms; sod:
the foreground's centre_x; panel: its face-averaged velocity_x), and its spread over the CFL numbers as a
fraction of the response's range over the run (max - min of the same history): a time-step-consistent
coupling gives the same value for every step. Printed as a table and drawn in the right-hand column of the
plot (response vs CFL, one line per ratio). Also printed: why the failed runs stopped.

The four binaries are copied to WORK/bin first (a rebuild of the build tree during the map cannot mix
versions). Runs use OMP_NUM_THREADS=1, --jobs at a time.

Usage: bench/coupled/run_stability_map.py [--quick] [--modes robin,impedance] [--scenes piston,advection]
                                         [--jobs N] [--work DIR] [--cosim PATH]
Writes bench/results/coupled_stability_map.csv and bench/results/coupled_stability_map.png
(_quick.csv/.png with --quick).
"""
import argparse
import concurrent.futures as cf
import csv
import math
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
RATIOS = [1e-3, 1e-2, 0.1, 1.0, 10.0, 100.0, 1e3]
CFLS = [0.1, 0.3, 0.5, 0.7, 0.9, 1.0]
QUICK_RATIOS = [1e-3, 1.0, 1e3]
QUICK_CFLS = [0.1, 0.5, 1.0]
MODES = ["robin", "impedance", "characteristic", "standard"]  # methods §4.1, §4.4
SCENES = {
    "piston": {
        "file": ROOT / "configs" / "piston_light_2d.yaml",
        "fluid_density": 1.0,
        "sets": ["coupling.time.end=0.02", "coupling.output.interval=0.02", "coupling.time.max_cycles=50000"],
    },
    "advection": {
        "file": ROOT / "bench" / "coupled" / "advection_deformable.yaml",
        "fluid_density": 1.0,
        "sets": ["coupling.time.max_cycles=200"],
    },
    "sod": {
        "file": ROOT / "configs" / "modified_sod_2d.yaml",
        "fluid_density": 0.125,
        "sets": ["fluid.mesh.cells=[64,64]", "solid.mesh.cells=[16,16]", "coupling.output.interval=0.28",
                 "coupling.time.max_cycles=200000"],
        "response": "centre_x",
    },
    "panel": {
        "file": ROOT / "configs" / "shock_panel_2d.yaml",
        "fluid_density": 1.161,
        "sets": ["coupling.time.end=5.0e-4", "coupling.output.interval=5.0e-4", "coupling.output.times=[5.0e-4]",
                 "coupling.time.max_cycles=200000"],
        "ratios": [6760.0],
        "own_density": True,  # the scene's density: solid.blocks.0.density is not set
        "response": "velocity_x",
    },
}
T_C = 1e-3       # s, low-pass window of the piston's high-frequency index
H_MAX = 0.05     # piston: oscillates above this
T_EARLY = 5e-3   # piston: the same index over the first 5 ms only (start transient; reported, not classified)
ADV_TOL = 1e-6   # advection: relative velocity deviation allowed
ADV_V0 = 0.1     # advection: the block's (and the flow's) velocity components


def snapshot_binaries(cosim, work):
    """Copies cosim and the three processes it starts (found next to it) into WORK/bin, so that a rebuild of
    the build tree during the map does not mix versions or remove a binary under a running map."""
    src = Path(cosim).resolve().parent
    dst = work / "bin"
    dst.mkdir(parents=True, exist_ok=True)
    for exe in ("cosim", "coupler", "fluid_solver", "solid_solver"):
        for attempt in range(30):  # a binary being relinked may be missing for a moment
            try:
                shutil.copy2(src / exe, dst / exe)
                break
            except OSError:
                time.sleep(1)
        else:
            raise SystemExit(f"cannot copy {src / exe}")
    return dst / "cosim"


def read_history(run_dir):
    p = run_dir / "coupler" / "interface_history.csv"
    if not p.exists() or p.stat().st_size == 0:
        return None
    with open(p) as f:
        rows = list(csv.reader(f))
    if len(rows) < 2:
        return None
    head = rows[0]
    data = {}
    for k, name in enumerate(head):
        vals = []
        for r in rows[1:]:
            try:
                vals.append(float(r[k]))
            except (ValueError, IndexError):
                vals.append(float("nan"))
        data[name] = np.array(vals)
    return data


def relative_tv(v):
    if len(v) < 2:
        return 0.0
    rng = v.max() - v.min()
    return float(np.abs(np.diff(v)).sum() / rng) if rng > 0 else 0.0


def high_frequency_index(t, v, t_c=T_C):
    """rms of v minus its moving average over t_c, relative to the largest |moving average|, on
    [t_c, t_end - t_c/2]; nan if the run is shorter than 2 t_c."""
    t_end = t[-1]
    if t_end < 2 * t_c or len(t) < 4:
        return float("nan")
    # uniform grid fine enough to keep every cycle's sample (at least 4 points per smallest step)
    dts = np.diff(t)
    h = max(min(dts[dts > 0].min() / 2, t_c / 50), t_end / 2e6)
    tu = np.arange(0.0, t_end, h)
    vu = np.interp(tu, t, v)
    w = max(1, int(round(t_c / h)))
    c = np.concatenate([[0.0], np.cumsum(vu)])
    lp = np.full_like(vu, np.nan)
    half = w // 2
    idx = np.arange(half, len(vu) - (w - half))
    lp[idx] = (c[idx - half + w] - c[idx - half]) / w
    sel = (tu >= t_c) & (tu <= t_end - t_c / 2) & np.isfinite(lp)
    if sel.sum() < 4:
        return float("nan")
    hf = vu[sel] - lp[sel]
    scale = np.abs(lp[sel]).max()
    return float(np.sqrt(np.mean(hf ** 2)) / scale) if scale > 0 else float("nan")


def failure_reason(text):
    m = re.search(r"reported an error: (.*)", text)
    if m:
        return m.group(1).strip()[:160]
    m = re.search(r"cosim: (.* failed with exit code \d+)", text)
    if m:
        return m.group(1).strip()[:160]
    lines = [l.strip() for l in text.splitlines() if l.strip()]
    return lines[-1][:160] if lines else ""


def scene_ratios(scene, ratios):
    only = SCENES[scene].get("ratios")
    return only if only else ratios


def run_one(cosim, work, scene, mode, ratio, cfl):
    sc = SCENES[scene]
    out = work / f"{scene}_{mode}_r{ratio:g}_c{cfl:g}"
    if out.exists():
        shutil.rmtree(out)
    sets = list(sc["sets"]) + [
        f"coupling.mode={mode}",
        f"fluid.time.cfl={cfl:g}",
        f"solid.numerics.cfl={cfl:g}",
    ] + ([] if sc.get("own_density") else [f"solid.blocks.0.density={ratio * sc['fluid_density']:g}"])
    cmd = [str(cosim), "run", str(sc["file"]), "--out", str(out), "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    env = dict(os.environ, OMP_NUM_THREADS="1")  # two runs share the cores
    t0 = time.perf_counter()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env, timeout=900)
    wall = time.perf_counter() - t0
    row = {"scene": scene, "mode": mode, "ratio": ratio, "cfl": cfl, "exit_code": p.returncode,
           "wall_s": round(wall, 3), "cycles": 0, "t_reached": float("nan"), "finite": True,
           "index": float("nan"), "tv_range": float("nan"), "v_end": float("nan"), "index_early": float("nan"),
           "response_end": float("nan"), "response_range": float("nan"), "reason": ""}
    h = read_history(out)
    if h is not None:
        row["cycles"] = int(len(h["cycle"]) - 1)
        row["t_reached"] = float(h["time"][-1])
        numeric = np.concatenate([h[k] for k in h])
        row["finite"] = bool(np.isfinite(numeric).all())
        vx = h["velocity_x"]
        row["v_end"] = float(vx[-1])
        resp = h[SCENES[scene].get("response", "velocity_x")]
        if np.isfinite(resp).all():
            row["response_end"] = float(resp[-1])
            row["response_range"] = float(resp.max() - resp.min())
        if np.isfinite(vx).all():
            row["tv_range"] = relative_tv(vx)
            if scene in ("sod", "panel"):
                row["index"] = high_frequency_index(h["time"], vx, h["time"][-1] / 20)
            elif scene == "piston":
                row["index"] = high_frequency_index(h["time"], vx)
                early = h["time"] <= T_EARLY + 1e-12
                if early.sum() > 4:
                    row["index_early"] = high_frequency_index(h["time"][early], vx[early])
            else:
                dev = np.maximum(np.abs(h["velocity_x"] - ADV_V0), np.abs(h["velocity_y"] - ADV_V0)) / ADV_V0
                row["index"] = float(dev.max())
    if p.returncode != 0:
        row["reason"] = failure_reason(p.stdout)
    row["class"] = classify(row)
    return row


def classify(r):
    if r["exit_code"] != 0 or not r["finite"]:
        return "blows up"
    if r["scene"] != "advection":
        return "oscillates" if (not math.isfinite(r["index"]) or r["index"] > H_MAX) else "stable"
    return "oscillates" if r["index"] > ADV_TOL else "stable"


SYMBOL = {"stable": "S", "oscillates": "O", "blows up": "X"}
COLOUR = {"stable": "#4caf50", "oscillates": "#ffb300", "blows up": "#d32f2f"}


def print_tables(rows, ratios, cfls):
    print("\nStability map (S stable, O oscillates, X blows up); number = classification index")
    print(f"  piston, sod, panel: high-frequency index H (threshold {H_MAX}); advection: max relative velocity "
          f"deviation (threshold {ADV_TOL:g})")
    by = {(r["scene"], r["mode"], r["ratio"], r["cfl"]): r for r in rows}
    for scene in SCENES:
        for mode in MODES:
            print(f"\n### {scene}, {mode} conditions\n")
            print("| ratio \\ CFL | " + " | ".join(f"{c:g}" for c in cfls) + " |")
            print("|---" * (len(cfls) + 1) + "|")
            for ratio in scene_ratios(scene, ratios):
                cells = []
                for c in cfls:
                    r = by.get((scene, mode, ratio, c))
                    if r is None:
                        cells.append("")
                        continue
                    num = r["index"]
                    s = "-" if not math.isfinite(num) else f"{num:.2g}"
                    if r["class"] == "blows up":
                        s = f"exit {r['exit_code']}" if r["exit_code"] else "nan"
                    cells.append(f"{SYMBOL[r['class']]} {s}")
                print(f"| {ratio:g} | " + " | ".join(cells) + " |")


def consistency(rows, scene, mode, ratio, cfls):
    """(CFLs, responses at the end, spread over the CFLs / the response's range) of the completed runs."""
    rs = [r for r in rows if (r["scene"], r["mode"], r["ratio"]) == (scene, mode, ratio) and r["cfl"] in cfls
          and r["exit_code"] == 0 and math.isfinite(r["response_end"])]
    rs.sort(key=lambda r: r["cfl"])
    if len(rs) < 2:
        return [], [], float("nan")
    vals = [r["response_end"] for r in rs]
    rng = max(r["response_range"] for r in rs)
    return [r["cfl"] for r in rs], vals, (max(vals) - min(vals)) / rng if rng > 0 else 0.0


def print_consistency(rows, ratios, cfls):
    print("\nConsistency: the response at the end time per CFL (completed runs); spread = (max - min) over the CFL "
          "numbers / the response's range over the run")
    for scene in SCENES:
        if scene == "advection":
            continue
        what = SCENES[scene].get("response", "velocity_x")
        print(f"\n### {scene}: {what} at the end\n")
        print("| mode | ratio | " + " | ".join(f"CFL {c:g}" for c in cfls) + " | spread / range |")
        print("|---|---" + "|---" * len(cfls) + "|---|")
        for mode in MODES:
            for ratio in scene_ratios(scene, ratios):
                cs, vals, spread = consistency(rows, scene, mode, ratio, cfls)
                got = dict(zip(cs, vals))
                cells = [f"{got[c]:.4g}" if c in got else "-" for c in cfls]
                sp = f"{100 * spread:.1f}%" if math.isfinite(spread) else "-"
                print(f"| {mode} | {ratio:g} | " + " | ".join(cells) + f" | {sp} |")


def plot(rows, ratios, cfls, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Patch

    by = {(r["scene"], r["mode"], r["ratio"], r["cfl"]): r for r in rows}
    ncol = len(MODES) + 1
    fig, axes = plt.subplots(len(SCENES), ncol, figsize=(3.6 * ncol, 3.3 * len(SCENES)), squeeze=False)
    for i, scene in enumerate(SCENES):
        sr = scene_ratios(scene, ratios)
        for j, mode in enumerate(MODES):
            ax = axes[i][j]
            for yi, ratio in enumerate(sr):
                for xi, c in enumerate(cfls):
                    r = by.get((scene, mode, ratio, c))
                    if r is None:
                        continue
                    ax.add_patch(plt.Rectangle((xi - 0.5, yi - 0.5), 1, 1, facecolor=COLOUR[r["class"]],
                                               edgecolor="white", lw=2))
                    if r["class"] == "blows up":
                        txt = f"exit {r['exit_code']}" if r["exit_code"] else "nan"
                    else:
                        txt = f"{r['index']:.1e}" if scene == "advection" else f"{r['index']:.3f}"
                        if scene == "piston" and math.isfinite(r["index_early"]) and r["index_early"] > H_MAX:
                            txt += "\nrings < 5 ms"
                    ax.text(xi, yi, txt, ha="center", va="center", fontsize=6)
            ax.set_xlim(-0.5, len(cfls) - 0.5)
            ax.set_ylim(-0.5, len(sr) - 0.5)
            ax.set_xticks(range(len(cfls)))
            ax.set_xticklabels([f"{c:g}" for c in cfls])
            ax.set_yticks(range(len(sr)))
            ax.set_yticklabels([f"{r:g}" for r in sr])
            ax.set_xlabel("CFL (fluid and solid)")
            ax.set_ylabel("solid / fluid density ratio")
            ax.set_title(f"{scene}: {mode}", fontsize=9)
        # Consistency panel: the default condition's response at the end vs the CFL number, one line per ratio,
        # normalised by the response's range over the run (a consistent coupling gives flat lines).
        ax = axes[i][ncol - 1]
        if scene == "advection":
            ax.axis("off")
            continue
        for ratio in sr:
            cs, vals, spread = consistency(rows, scene, MODES[0], ratio, cfls)
            if cs:
                rng = max(r["response_range"] for r in rows if (r["scene"], r["mode"], r["ratio"]) ==
                          (scene, MODES[0], ratio) and math.isfinite(r["response_range"]))
                ref = vals[0]
                ax.plot(cs, [(v - ref) / rng if rng > 0 else 0 for v in vals], "o-", ms=3,
                        label=f"{ratio:g} ({100 * spread:.1f}%)")
        ax.axhspan(-0.05, 0.05, color="0.9", zorder=0)
        ax.set_xlabel("CFL")
        ax.set_ylabel("(response - response at smallest CFL) / range")
        ax.set_title(f"{scene}: {MODES[0]}, consistency", fontsize=9)
        ax.legend(fontsize=6, title="ratio (spread)", title_fontsize=6)
    fig.legend(handles=[Patch(color=COLOUR[k], label=k) for k in COLOUR], loc="lower center", ncol=3)
    fig.suptitle(f"Coupled stability map (numbers: H, threshold {H_MAX}; advection max |dv|/v, threshold "
                 f"{ADV_TOL:g}) and consistency in the step (right; grey band: 5% of the range)", fontsize=10)
    fig.tight_layout(rect=(0, 0.04, 1, 0.97))
    fig.savefig(path, dpi=100)


def main():
    global MODES, SCENES
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="3 ratios x 3 CFL numbers")
    ap.add_argument("--modes", default=",".join(MODES), help="interface conditions (default: all four)")
    ap.add_argument("--scenes", default=",".join(SCENES), help="scenes (default: all four)")
    ap.add_argument("--jobs", type=int, default=2, help="runs at a time (default 2)")
    ap.add_argument("--work", default="/tmp/cosim_stability_map", help="run directories (overwritten)")
    ap.add_argument("--cosim", default=str(ROOT / "build" / "bin" / "cosim"))
    ap.add_argument("--results", default=str(RESULTS))
    a = ap.parse_args()
    for m in a.modes.split(","):
        if m not in MODES:
            ap.error(f"--modes: unknown condition {m!r}; expected some of {', '.join(MODES)}")
    for sc in a.scenes.split(","):
        if sc not in SCENES:
            ap.error(f"--scenes: unknown scene {sc!r}; expected some of {', '.join(SCENES)}")
    MODES = [m for m in MODES if m in a.modes.split(",")]
    SCENES = {k: v for k, v in SCENES.items() if k in a.scenes.split(",")}
    ratios, cfls = (QUICK_RATIOS, QUICK_CFLS) if a.quick else (RATIOS, CFLS)
    work = Path(a.work)
    work.mkdir(parents=True, exist_ok=True)
    cosim = snapshot_binaries(a.cosim, work)
    results = Path(a.results)
    results.mkdir(parents=True, exist_ok=True)
    print(provenance(Path(cosim).parent))
    cases = [(s, m, r, c) for s in SCENES for m in MODES for r in scene_ratios(s, ratios) for c in cfls]
    # the expensive runs (light solids, small CFL: many cycles) first, so that the pool ends evenly
    cases.sort(key=lambda x: (x[0] not in ("piston", "sod"), x[2], x[3]))
    t0 = time.perf_counter()
    rows = []
    with cf.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as ex:
        futs = {ex.submit(run_one, cosim, work, *cs): cs for cs in cases}
        for k, f in enumerate(cf.as_completed(futs), 1):
            r = f.result()
            rows.append(r)
            print(f"[{k:3d}/{len(cases)}] {r['scene']:9s} {r['mode']:14s} ratio {r['ratio']:<6g} cfl {r['cfl']:<4g} "
                  f"exit {r['exit_code']} cycles {r['cycles']:6d} t {r['t_reached']:.3g} s  {r['wall_s']:7.2f} s  "
                  f"-> {r['class']}", flush=True)
    total = time.perf_counter() - t0
    rows.sort(key=lambda r: (list(SCENES).index(r["scene"]), MODES.index(r["mode"]), r["ratio"], r["cfl"]))

    print_tables(rows, ratios, cfls)
    smooth = [r["index"] for r in rows if r["scene"] == "piston" and r["ratio"] >= 100 and r["exit_code"] == 0
              and math.isfinite(r["index"])]
    if smooth:
        print(f"\nthreshold check: H of the smooth reference runs (piston, ratio >= 100, {len(smooth)} runs): "
              f"max {max(smooth):.4f}, median {float(np.median(smooth)):.4f}; H_MAX = {H_MAX}")
    ring = [r for r in rows if r["scene"] == "piston" and r["class"] == "stable"
            and math.isfinite(r["index_early"]) and r["index_early"] > H_MAX]
    if ring:
        print("\npiston runs classified stable that ring in their first 5 ms (H over [1, 5] ms > H_MAX, decaying "
              "later): " + ", ".join(f"{r['mode']} {r['ratio']:g}/{r['cfl']:g} (H {r['index_early']:.3f})"
                                     for r in ring))
    print_consistency(rows, ratios, cfls)
    fails = [r for r in rows if r["class"] == "blows up"]
    if fails:
        print("\nwhy the failed runs stopped (grouped by message; ratio/cfl of each run, message of the first):")
        seen = {}
        for r in fails:
            key = re.sub(r"[-+]?\d[\d.e+-]*", "#", r["reason"])[:70]
            seen.setdefault((r["scene"], r["mode"], key), []).append(r)
        for (scene, mode, _), rs in seen.items():
            cases_txt = ", ".join(f"{r['ratio']:g}/{r['cfl']:g}" for r in rs)
            print(f"  {scene} {mode} (ratio/cfl {cases_txt}): {rs[0]['reason']}")
    counts = {k: sum(1 for r in rows if r["class"] == k) for k in COLOUR}
    print(f"\n{len(rows)} runs in {total:.1f} s with {a.jobs} at a time; " +
          ", ".join(f"{v} {k}" for k, v in counts.items()))

    name = "coupled_stability_map" + ("_quick" if a.quick else "")
    csv_path = results / f"{name}.csv"
    keys = ["scene", "mode", "ratio", "cfl", "class", "index", "index_early", "tv_range", "v_end", "response_end",
            "response_range", "exit_code", "finite", "cycles", "t_reached", "wall_s", "reason"]
    with open(csv_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: r[k] for k in keys})
    png = results / f"{name}.png"
    plot(rows, ratios, cfls, png)
    print(f"wrote {csv_path.relative_to(ROOT) if csv_path.is_relative_to(ROOT) else csv_path} and "
          f"{png.relative_to(ROOT) if png.is_relative_to(ROOT) else png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
