"""The Python package's overhead over the C++ call (docs/python.md, `make bench`):
meander.curve(mesh) against the same work in meander_bench_stages (check and make_curve:
its total less reading and writing), both the median of RUNS runs on one mesh, in the
same run. Usage: /usr/bin/python3 bench/python_overhead.py BUILD MESH [RUNS]
(PYTHONPATH=BUILD/python)."""

import re
import statistics
import subprocess
import sys
import time

import meander

build, path = sys.argv[1], sys.argv[2]
runs = int(sys.argv[3]) if len(sys.argv) > 3 else 5

mesh = meander.read(path)
seconds = []
for _ in range(runs):
    start = time.perf_counter()
    curves = meander.curve(mesh)
    seconds.append(time.perf_counter() - start)
    del curves
python = statistics.median(seconds)

table = subprocess.run([f"{build}/bench/meander_bench_stages", path, "--runs", str(runs)], check=True,
                       capture_output=True, text=True).stdout
stage = {name: float(ms) / 1e3 for name, ms in re.findall(r"^\| (\w[\w ]*?) \| ([0-9.]+) \|$", table, re.M)}
native = stage["total"] - stage["read"] - stage["write"]
print(f"| meander.curve on {path.rsplit('/', 1)[-1]} ({mesh.num_faces} faces) | {python:.3f} s | {native:.3f} s | "
      f"{100 * (python / native - 1):+.1f}% |")
