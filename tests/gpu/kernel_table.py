#!/usr/bin/env python3
"""Per-kernel time table from an Nsight Compute CSV (`ncu --csv --metrics gpu__time_duration.sum
--log-file FILE ...`): kernels grouped by name, with total time, calls, mean and share, largest first.
A parallel_for kernel is named by the function its lambda was written in (the launch site), since every
parallel_for launches the same template. Usage: kernel_table.py PROFILE.csv"""
import csv
import re
import sys
from collections import defaultdict

if len(sys.argv) != 2:
    sys.exit(__doc__)
try:
    lines = open(sys.argv[1], encoding="utf-8", errors="replace").read().splitlines()
except OSError as e:
    sys.exit(f"kernel_table: {sys.argv[1]}: {e.strerror}")
start = next((i for i, l in enumerate(lines) if l.startswith('"ID"')), None)
if start is None:
    sys.exit(f"kernel_table: {sys.argv[1]}: no ncu CSV header (\"ID\",...) in the file")


def short_name(kernel):
    if "parallel_for_kernel" in kernel:
        # nvcc names an extended lambda by a tag holding its enclosing function: __nv_dl_tag<..., &goris::f<T>, N>
        site = re.search(r"&(goris::[A-Za-z0-9_:]+)", kernel)
        return "parallel_for @ " + (site.group(1).replace("backend_nvcc::", "") if site else "?")
    base = re.sub(r"^(void )?", "", kernel)
    return re.split(r"[<(]", base, maxsplit=1)[0].replace("backend_nvcc::", "")


time_ns, calls = defaultdict(float), defaultdict(int)
for row in csv.DictReader(lines[start:]):
    if row.get("Metric Name") != "gpu__time_duration.sum":
        continue
    name = short_name(row.get("Kernel Name", "?"))
    unit = row.get("Metric Unit", "nsecond")
    value = float(row["Metric Value"].replace(",", ""))
    time_ns[name] += value * {"nsecond": 1, "usecond": 1e3, "msecond": 1e6, "second": 1e9}.get(unit, 1)
    calls[name] += 1
total = sum(time_ns.values())
if total == 0:
    sys.exit(f"kernel_table: {sys.argv[1]}: no gpu__time_duration.sum values")
print(f"{sum(calls.values())} kernel launches, {total / 1e6:.3f} ms of kernel time in all\n")
print("| kernel | total ms | calls | mean us | share |")
print("|---|--:|--:|--:|--:|")
for name in sorted(time_ns, key=time_ns.get, reverse=True):
    print(f"| {name} | {time_ns[name] / 1e6:.3f} | {calls[name]} | {time_ns[name] / calls[name] / 1e3:.1f} | "
          f"{100 * time_ns[name] / total:.1f} % |")
