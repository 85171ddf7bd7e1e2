#!/usr/bin/python3
"""Markdown table and bar plot of bench/solid/results/sedov_bench.csv (written by run_sedov_bench.sh).

Usage: plot_sedov_bench.py CSV PNG. The LULESH 2.0 reference (serial, 30^3, same machine class: 1.44e6
zone-cycles/s, 932 cycles, 21% energy loss) was measured with LULESH's own `-s 30` run on this machine.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LULESH_ZCS = 1.44e6


def main():
    rows = list(csv.DictReader(open(sys.argv[1])))
    print("| N^3 | strength | threads | steps | wall [s] | zone-cycles/s | vs LULESH serial | state bytes/element "
          "| max RSS [MB] | load avg | energy error |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        zcs = float(r["zone_cycles_per_s"])
        print(f"| {r['n']}^3 | {r['strength']} | {r['threads']} | {r['steps']} | {float(r['wall_s']):.2f} | "
              f"{zcs / 1e6:.2f} M | {zcs / LULESH_ZCS:.2f}x | {r['bytes_per_element']} | "
              f"{r.get('max_rss_mb', '?')} | {r.get('load1', '?')} | {float(r['rel_energy_error']):.1e} |")
    if rows:
        print(f"\nhost: {rows[0]['host_cpu']}")
    labels = [f"{r['n']}^3\n{'str' if r['strength'] == 'on' else 'hydro'}\n{r['threads']}T" for r in rows]
    vals = [float(r["zone_cycles_per_s"]) / 1e6 for r in rows]
    colors = ["tab:blue" if r["strength"] == "off" else "tab:orange" for r in rows]
    fig, ax = plt.subplots(figsize=(max(6, 0.9 * len(rows)), 4))
    ax.bar(range(len(rows)), vals, color=colors)
    ax.axhline(LULESH_ZCS / 1e6, color="k", ls="--", lw=1, label="LULESH 2.0 serial, 30^3")
    ax.set_xticks(range(len(rows)))
    ax.set_xticklabels(labels, fontsize=8)
    ax.set_ylabel("million zone-cycles / s")
    ax.set_title("solid_solver, LULESH Sedov setup (blue: strength off, orange: on)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=120)
    print(f"plot: {sys.argv[2]}")


if __name__ == "__main__":
    main()
