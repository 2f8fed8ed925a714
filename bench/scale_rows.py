#!/usr/bin/env python3
"""The scale bench's table (bench/README.md, "Scale"): rows of bench/scale_table.sh as one markdown table, a line per
mesh, with CPU seconds, peak MB and peak KB per input vertex of each tool.

    python3 bench/scale_rows.py scale_rows.tsv
"""
import sys

TOOLS = ["remesh", "pack", "draco"]
rows = {}
for line in open(sys.argv[1]):
    f = line.rstrip("\n").split("\t")
    if len(f) < 8:
        continue
    mesh, v, tool, cpu, peak_kb, code, size, out_v = f
    rows.setdefault((int(v), mesh), {})[tool] = (float(cpu), int(peak_kb), int(code), size, out_v)

print("| mesh | input V | remesh --grid: CPU s | peak MB | KB/V | pack 2e-4: CPU s | peak MB | KB/V | bytes | "
      "draco -qp 11 -cl 10: CPU s | peak MB | KB/V | bytes |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for (v, mesh), by_tool in sorted(rows.items()):
    cells = [mesh, f"{v:,}"]
    for tool in TOOLS:
        r = by_tool.get(tool)
        width = 3 if tool == "remesh" else 4
        if r is None:
            cells += ["not run"] + [""] * (width - 1)
            continue
        cpu, peak, code, size, _ = r
        if code != 0:
            cells += [f"exit {code}"] + [""] * (width - 1)
            continue
        cells += [f"{cpu:.1f}", f"{peak / 1024:.0f}", f"{peak / v:.2f}"]
        if tool != "remesh":
            cells.append(f"{int(size):,}" if size else "")
    print("| " + " | ".join(cells) + " |")
