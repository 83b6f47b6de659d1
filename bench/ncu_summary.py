#!/usr/bin/env python3
"""Markdown tables from Nsight Compute CSV reports (ncu --csv --page details), as bench/gpu_run.sh
writes them: one row per profiled kernel with the numbers docs/benchmarks.md reasons from.

usage: bench/ncu_summary.py PIXELS REPORT.csv [REPORT.csv ...] > profile.md
PIXELS: the frame's pixel count, for the per-pixel byte columns (1920*1080 = 2073600)."""
import csv
import io
import sys
from collections import OrderedDict


def load(path):
    lines = [line for line in open(path, encoding="utf-8") if line.startswith('"')]
    rows = list(csv.reader(io.StringIO("".join(lines))))
    header, rows = rows[0], rows[1:]
    col = {h: i for i, h in enumerate(header)}
    kernels = OrderedDict()
    for r in rows:
        k = kernels.setdefault(r[col["ID"]], {"name": r[col["Kernel Name"]], "m": {}, "rules": []})
        name = r[col["Metric Name"]]
        if name:
            k["m"][name] = r[col["Metric Value"]]
        elif "Rule Description" in col and r[col["Rule Description"]]:
            k["rules"].append((r[col["Rule Name"]], r[col["Rule Description"]]))
    return kernels


def num(k, name):
    v = k["m"].get(name, "")
    try:
        return float(v.replace(",", ""))
    except ValueError:
        return float("nan")


def short_name(name):
    for key in ("demodulate_reproject", "variance_kernel", "atrous_kernel", "DemodulateKernel",
                "ReprojectKernel", "VarianceKernel", "AtrousKernel", "CopyRgbKernel",
                "RemodulateKernel"):
        if key in name:
            return key
    return name[:40]


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    pixels = float(sys.argv[1])
    for path in sys.argv[2:]:
        kernels = load(path)
        print(f"\n### {path.split('/')[-1]}\n")
        print("| # | kernel | µs | SM MHz | DRAM % | L1 % | L2 % | SM % | issue busy % | IPC | "
              "occupancy theor. / achieved % | regs | active threads/warp | DRAM B/px R+W | "
              "L2 B/px | L1 B/px |")
        print("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|")
        for kid, k in kernels.items():
            dram = (num(k, "dram__bytes_read.sum") + num(k, "dram__bytes_write.sum")) / pixels
            print(f"| {kid} | {short_name(k['name'])} | {num(k, 'Duration') / 1e3:.1f} | "
                  f"{num(k, 'SM Frequency') / 1e6:.0f} | {num(k, 'DRAM Throughput'):.0f} | "
                  f"{num(k, 'L1/TEX Cache Throughput'):.0f} | {num(k, 'L2 Cache Throughput'):.0f} | "
                  f"{num(k, 'Compute (SM) Throughput'):.0f} | {num(k, 'Issue Slots Busy'):.0f} | "
                  f"{num(k, 'Executed Ipc Active'):.2f} | "
                  f"{num(k, 'Theoretical Occupancy'):.0f} / {num(k, 'Achieved Occupancy'):.0f} | "
                  f"{num(k, 'Registers Per Thread'):.0f} | "
                  f"{num(k, 'Avg. Active Threads Per Warp'):.1f} | {dram:.0f} | "
                  f"{num(k, 'lts__t_bytes.sum') / pixels:.0f} | "
                  f"{num(k, 'l1tex__t_bytes.sum') / pixels:.0f} |")
        print("\nProfiler findings (first sentence of each rule, per kernel):\n")
        for kid, k in kernels.items():
            seen = set()
            for rule, text in k["rules"]:
                first = text.split(". ")[0].rstrip(".") + "."
                if rule in seen or "could not be found" in first or "Check the" in first:
                    continue
                seen.add(rule)
                print(f"- {kid} {short_name(k['name'])}, {rule}: {first}")


if __name__ == "__main__":
    main()
