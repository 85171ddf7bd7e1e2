#!/usr/bin/python3
"""PNG plots of a cosim run directory (coupled, fluid-only or solid-only).

Usage:
    /usr/bin/python3 python/plot_run.py RUN_DIR [--out DIR] [--reference CONFORMING_RUN_DIR] [--show-ghosts]

RUN_DIR is what `cosim run SCENE --out RUN_DIR` writes (scene.yaml, fluid/, and for a coupled run
coupler/ and solid/), or the output directory of fluid_solver or solid_solver alone (cosim.read_run).
Writes into --out (default RUN_DIR/plots/):

  motion.png     coupled: structure displacement (interface centre_x - its initial value) and velocity
                 against time; for a piston scene (name "piston...", rigid block "piston") also the
                 two-chamber adiabatic ODE
                   m x'' = A [pL0 (VL0/(VL0 + A x))^g - pR0 (VR0/(VR0 - A x))^g],  x(0) = x'(0) = 0,
                 the same ODE with the gas inertia (m + m_gas/3, dashed) and, with --reference, the
                 conforming all-Lagrangian run of `solid_solver configs/solid_piston_1d.yaml --out DIR`
                 (position = mean x of the piston block's nodes in each solid snapshot).
  interface.png  coupled: area-mean interface pressure and the interface force (ODE force for a piston).
  fields.png     last fluid snapshot: pressure, density, velocity magnitude (2D images; the cells inside a body,
                 embedded_category solid-cut, ghost and solid, masked grey, with --show-ghosts only the solid
                 ones; the embedded interface faces of the matching fluid_interface CSV as red points;
                 3D: the mid-plane z slice; 1D: line plots, velocity x). Solid-only run: the last solid
                 snapshot's pressure, density and velocity magnitude on the deformed mesh.
  timing.png     coupled: wall time per cycle, stacked solid / fluid / coupler / comm (coupler/timing.csv).
  blocks.png     solid-only: each block's mass-averaged velocity and energies (block_history.csv).

For a piston scene the maximum deviations of the run from each reference are printed as % of the ODE's
peak-to-peak amplitude. Exit status 2 when RUN_DIR (or the reference directory) is not a run directory.
"""
import argparse
import os
import sys

import cosim
from cosim import piston, plot


def piston_references(run, hist, reference_dir):
    """ODE curves (and the conforming run) for a piston scene; prints the deviations of the run."""
    try:
        par = piston.parameters(run.scene or {})
    except (KeyError, TypeError, IndexError, ValueError, StopIteration) as e:
        print(f"piston ODE skipped: {e}" if isinstance(e, ValueError) else
              f"piston ODE skipped: scene.yaml lacks what it needs ({e!r})")
        return None, []
    t_end = float(hist["time"][-1])
    try:  # the whole scheduled run (with its --set overrides), also for a run still in progress
        t_end = max(t_end, float(run.setting("coupling.time.end")))
    except (TypeError, ValueError):
        pass
    # The amplitude is the ODE's own (its turning points): over at least 1.5 periods, however short the run.
    t_amp = max(t_end, 1.5 * piston.small_amplitude_period(par))
    _, x_amp, _ = piston.solve(par, 0.0, t_amp)
    amp = float(x_amp.max() - x_amp.min())
    t, x, v = piston.solve(par, 0.0, t_end)
    print(f"piston ODE: A = {par['A']:.4g} m^2, m = {par['m']:.4g} kg, gamma = {par['gamma']:.4g}, "
          f"pL0 = {par['pL']:.4g} Pa, pR0 = {par['pR']:.4g} Pa, VL0 = {par['VL']:.4g} m^3, VR0 = {par['VR']:.4g} m^3; "
          f"turning points {x_amp.min():.4f} .. {x_amp.max():.4f} m (peak-to-peak {amp:.4f} m)")
    refs = [{"t": t, "x": x, "v": v, "label": "two-chamber ODE", "style": {"color": "k", "lw": 1.0}}]
    if "m_gas" in par:
        tg, xg, vg = piston.solve(par, par["m_gas"] / 3.0, t_end)
        refs.append({"t": tg, "x": xg, "v": vg, "label": f"ODE with gas inertia (m + {par['m_gas'] / 3:.3g} kg)",
                     "style": {"color": "k", "lw": 1.0, "ls": "--"}})
    if reference_dir:
        tr, xr, vr = piston.conforming_trajectory(cosim.read_run(reference_dir))
        refs.append({"t": tr, "x": xr, "v": vr, "label": "conforming all-Lagrangian run",
                     "style": {"color": "C3", "ls": "none", "marker": "o", "ms": 3}})
    run_x = hist["centre_x"] - hist["centre_x"][0]
    for r in refs:
        dev = piston.max_deviation(hist["time"], run_x, r["t"], r["x"])
        print(f"max deviation of the coupled run from the {r['label']}: {dev:.4g} m = {100 * dev / amp:.2f}% "
              f"of the ODE peak-to-peak amplitude")
    if reference_dir and "m_gas" in par:
        dev = piston.max_deviation(refs[-1]["t"], refs[-1]["x"], refs[1]["t"], refs[1]["x"])
        print(f"(for comparison: conforming run vs ODE with gas inertia: {100 * dev / amp:.2f}%)")
    return par, refs


def history(run, name):
    """A CSV table of the run that must have data rows."""
    table = run.histories[name]
    if not table or not len(next(iter(table.values()))):
        raise cosim.RunDirError(f"{run.histories.paths[name]}: no data rows")
    return table


def plot_coupled(run, reference, out_dir):
    hist = history(run, "interface_history")
    par, refs = None, []
    if run.name.startswith("piston"):
        par, refs = piston_references(run, hist, reference)
    elif reference:
        print(f"--reference ignored: scene '{run.name}' is not a piston scene")
    plot.plot_motion(hist, refs, f"{run.name}: structure (interface centre) motion", out_dir)
    plot.plot_interface(hist, par, f"{run.name}: interface pressure and force", out_dir)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("run_dir", metavar="RUN_DIR")
    ap.add_argument("--out", metavar="DIR", help="output directory (default RUN_DIR/plots)")
    ap.add_argument("--reference", metavar="CONFORMING_RUN_DIR",
                    help="output of `solid_solver configs/solid_piston_1d.yaml --out DIR` (piston scenes)")
    ap.add_argument("--show-ghosts", action="store_true",
                    help="mask only the embedded_category == solid cells (show ghost and solid-cut cell values)")
    args = ap.parse_args(argv)
    try:
        run = cosim.read_run(args.run_dir)
        if run.fluid is None and run.solid is None and "interface_history" not in run.histories:
            raise cosim.RunDirError(f"{args.run_dir}: nothing to plot: no fluid or solid snapshots and no "
                                    f"coupler/interface_history.csv")
        out_dir = args.out or os.path.join(args.run_dir, "plots")
        os.makedirs(out_dir, exist_ok=True)
        if "interface_history" in run.histories:
            plot_coupled(run, args.reference, out_dir)
        elif args.reference:
            print("--reference ignored: not a coupled run (no coupler/interface_history.csv)")
        if run.fluid is not None and len(run.fluid):
            plot.plot_fluid_fields(run.fluid[-1], out_dir, mask_ghosts=not args.show_ghosts)
        elif run.solid is not None and len(run.solid):
            plot.plot_solid_fields(run.solid[-1], out_dir)
            if "block_history" in run.histories:
                plot.plot_blocks(history(run, "block_history"), out_dir)
        if "timing" in run.histories:
            plot.plot_timing(history(run, "timing"), run.summaries.get("coupler"), out_dir)
    except cosim.RunDirError as e:
        print(f"plot_run.py: error: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
