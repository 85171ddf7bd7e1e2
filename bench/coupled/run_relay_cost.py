#!/usr/bin/python3
"""What the rank-0 relay of a coupled fluid on several ranks costs per cycle on the tungsten blast, against what
"every rank talks to the coupler" could save and would cost.

A coupled fluid on P ranks has one connection, on rank 0 (common/coupling/rank_relay.h): rank 0 broadcasts every
message it receives (the directive, the Faces, the InterfaceStates) and the ranks merge their samples with an
all-gather before rank 0 sends them. The fluid's summary.json (parallel.relay) has, per rank, the seconds of each
collective split in two stages: the lengths' stage (`wait`: a rank waits there for the slowest rank to arrive, or
for rank 0 to have received the coupler's message) and the bytes' stage (`transfer`), plus the relay's protobuf
encoding on rank 0 and decoding on every rank (`codec`). Per cycle (divided by the coupled cycles):

  bcast wait/transfer  the relayed messages' broadcast;       samples wait/transfer  the samples' all-gather;
  codec                re-encoding and decoding the relayed messages;
  saving bound         the largest over the ranks of (bcast transfer + samples transfer + codec): what talking to the
                       coupler from every rank could save at most (each rank would still receive its faces and
                       states and send its samples; the waits stay, moved into the coupler);
  alternative's cost   (P - 1) times the relayed bytes through the coupler's one thread again, at 0.42-4.4 us per
                       face of ~394 B (1.1-11 ms per MB: docs/benchmarks.md "The coupler's cost against the interface
                       size", buffers kept .. glibc default), plus the coupler's own split and merge, 0.05 us per face
                       and rank.

wall, fluid, comm: the coupler's cycle, means over every cycle (coupler_summary.json per_cycle_seconds), as the
relay's figures are (its seconds over the whole run divided by the cycles).

Runs (each once, in this order): the CI size of tests/coupled/test_tungsten_blast.cpp (32^3 fluid, 4 x 10 x 10
solid, to t = 3e-4 s) on --ci-ranks fluid ranks, then the scene's 120^3 for about 30 cycles (to t = 1.2e-5 s) on
--full-ranks (two fluid snapshots of 290 MB in the run folder). The load average is printed before each
run: the numbers are this machine's while it runs them.

Usage: nice /usr/bin/python3 bench/coupled/run_relay_cost.py [--ci-ranks 2,3] [--full-ranks 2] [--no-full]
       [--build build] [--work DIR]
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_common import ROOT, provenance, timed_run  # noqa: E402

SCENE = ROOT / "configs" / "tungsten_blast_3d.yaml"
SIZES = {
    "ci": {"fluid": 32, "solid": (4, 10, 10),
           "sets": ["fluid.mesh.cells=[32,32,32]", "solid.mesh.cells=[4,10,10]", "coupling.time.end=3e-4"]},
    "full": {"fluid": 120, "solid": (10, 40, 40),
             "sets": ["coupling.time.end=1.2e-5", "coupling.output.interval=1e-3"]},
}
MS_PER_MB = (1.07, 11.1)  # coupler comm per MB relayed again: buffers kept .. glibc default (docs/benchmarks.md)
OWN_US_PER_FACE = 0.05


def run_one(build, work, size, ranks):
    out = work / f"{size}_{ranks}"
    shutil.rmtree(out, ignore_errors=True)
    cmd = [str(build / "bin" / "cosim"), "run", str(SCENE), "--quiet", "--out", str(out), "--fluid-ranks", str(ranks)]
    for s in SIZES[size]["sets"]:
        cmd += ["--set", s]
    load = os.getloadavg()
    seconds = timed_run(cmd, work / f"{size}_{ranks}.log")
    summary = json.load(open(out / "fluid" / "summary.json"))
    par = summary["parallel"]
    if par["ranks"] != ranks:
        sys.exit(f"{out}: the fluid ran on {par['ranks']} ranks, not {ranks}")
    cycles = summary["coupling"]["cycles"]
    relay = par["relay"]
    ms = lambda seconds: 1e3 * seconds / cycles  # noqa: E731
    per_rank = []
    for q in range(ranks):
        per_rank.append({
            "bcast_wait": ms(relay["relayed"]["wait_s"][q]), "bcast_transfer": ms(relay["relayed"]["transfer_s"][q]),
            "samples_wait": ms(relay["samples"]["wait_s"][q]),
            "samples_transfer": ms(relay["samples"]["transfer_s"][q]), "codec": ms(relay["codec_s"][q])})
    nx, ny, nz = SIZES[size]["solid"]
    faces = 2 * (nx * ny + ny * nz + nz * nx)
    relayed_mb = relay["relayed"]["bytes"][0] / cycles / 1e6
    bound = max(r["bcast_transfer"] + r["samples_transfer"] + r["codec"] for r in per_rank)
    own = (ranks - 1) * faces * OWN_US_PER_FACE * 1e-3
    cost = tuple(own + (ranks - 1) * relayed_mb * m for m in MS_PER_MB)
    return {"size": size, "ranks": ranks, "cycles": cycles, "faces": faces, "load": load, "seconds": seconds,
            "timing": json.load(open(out / "coupler" / "coupler_summary.json"))["per_cycle_seconds"], "per_rank": per_rank, "relayed_mb": relayed_mb,
            "bound": bound, "cost": cost}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ci-ranks", default="2,3")
    ap.add_argument("--full-ranks", default="2")
    ap.add_argument("--no-full", action="store_true", help="the CI size only")
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--work", help="run folder (default: a temporary one in /dev/shm, removed)")
    args = ap.parse_args()
    build = Path(args.build).resolve()
    # In memory where there is /dev/shm: the 290 MB snapshot of 120^3 written to a loaded disk at the end outlasts the
    # launcher's 10 s grace after the coupler ended.
    shm = "/dev/shm" if os.path.isdir("/dev/shm") else None
    work = Path(args.work) if args.work else Path(tempfile.mkdtemp(prefix="relay_cost_", dir=shm))
    work.mkdir(parents=True, exist_ok=True)
    plan = [("ci", int(p)) for p in args.ci_ranks.split(",") if p]
    if not args.no_full:
        plan += [("full", int(p)) for p in args.full_ranks.split(",") if p]
    print(provenance(build.joinpath("bin")))
    results = []
    for size, ranks in plan:
        print(f"running {size} on {ranks} fluid ranks (load average {os.getloadavg()[0]:.1f}) ...", flush=True)
        results.append(run_one(build, work, size, ranks))
    print()
    print("ms per cycle; per rank r0 / r1 / ...; load average (1 min) before each run")
    print()
    print("| fluid | ranks | cycles | load | wall | fluid | comm | bcast wait | bcast transfer | samples wait | "
          "samples transfer | codec | relayed MB | saving bound | share of wall | alternative's cost |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in results:
        col = lambda k: " / ".join(f"{p[k]:.2f}" for p in r["per_rank"])  # noqa: E731
        t = r["timing"]
        print(f"| {SIZES[r['size']]['fluid']}^3 | {r['ranks']} | {r['cycles']} | {r['load'][0]:.1f} | "
              f"{1e3 * t['wall']:.1f} | {1e3 * t['fluid']:.1f} | {1e3 * t['comm']:.2f} | {col('bcast_wait')} | "
              f"{col('bcast_transfer')} | {col('samples_wait')} | {col('samples_transfer')} | {col('codec')} | "
              f"{r['relayed_mb']:.3f} | {r['bound']:.2f} | {100 * r['bound'] / (1e3 * t['wall']):.1f}% | "
              f"{r['cost'][0]:.2f}-{r['cost'][1]:.2f} |")
    if not args.work:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
