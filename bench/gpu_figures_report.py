#!/usr/bin/env python3
"""gpu_figures.md from what bench/gpu_figures.sh wrote in OUT: the device, its driver, each command
and its wall time, the rectification pass's cost per variant (ms and ratio to the RGB box), the TAA
runs' ghosting, and FLIP per pair.

Usage: gpu_figures_report.py OUT QUICK
"""
import csv
import json
import os
import sys


def rows(path):
    with open(path, encoding="utf-8") as f:
        return list(csv.DictReader(f))


def main():
    out, quick = sys.argv[1], sys.argv[2] == "1"
    run = json.load(open(os.path.join(out, "bench", "cost.json"), encoding="utf-8"))["run"]
    walls = dict(line.split() for line in open(os.path.join(out, "wall_seconds.txt"), encoding="utf-8"))
    lines = ["# GPU figures (bench/gpu_figures.sh)", ""]
    if quick:
        lines += ["**--quick: small sizes and few frames, a check of the script, not figures to report.**", ""]
    lines += [f"- device: {run['device']} ({run['device_type']})", f"- driver: {run['driver']}",
              f"- machine: {run['machine']}", f"- kdop: {run['kdop_version']} (commit {run['commit']})",
              f"- date: {run['date']}", ""]

    lines += ["## The rectification pass", "",
              "Median of interleaved dispatches at the figures' size (`kdop bench`, cost.csv); marginal: over "
              "the gather baseline, which reads the same neighborhood and history and clips nothing.", "",
              "| variant | ms | marginal ms | ratio to aabb-clip-n9 |", "|---|--:|--:|--:|"]
    bench = rows(os.path.join(out, "bench", "cost.csv"))
    box = next(float(r["ms_median"]) for r in bench if r["variant"] == "aabb-clip-n9")
    for r in bench:
        ms = float(r["ms_median"])
        if r["marginal_ms"]:  # a clip; the baselines follow
            lines.append(f"| {r['variant']} | {ms:.4f} | {float(r['marginal_ms']):.4f} | {ms / box:.2f} |")
    baselines = [f"{r['variant']} {float(r['ms_median']):.4f} ms" for r in bench if not r["marginal_ms"]]
    lines += ["", "Baselines: " + ", ".join(baselines) + ".", ""]

    lines += ["## The TAA runs", ""]
    for folder, what in (("taa", "the default `kdop taa` run"), ("taa-sequence", "a sequence of grass3d")):
        taa = rows(os.path.join(out, folder, "taa.csv"))
        least = min(taa, key=lambda r: float(r["ghosting"]) if r["ghosting"] else float("inf"))
        lines.append(f"- {what}: {len(taa)} rows; least ghosting {least['variant']} on {least['scene']}, "
                     f"{float(least['ghosting']):.4f}")
    lines.append("")

    lines += ["## Commands and wall times", "",
              "Each command's whole process, start-up included (flip_ldr and flip_hdr: one pair each).", "",
              "| step | seconds | command |", "|---|--:|---|"]
    for line in open(os.path.join(out, "commands.txt"), encoding="utf-8"):
        name, command = line[3:].split(": ", 1)
        lines.append(f"| {name} | {walls.get(name, '?')} | `{command.strip()}` |")
    lines.append("")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
