#!/usr/bin/env python3
"""Packing from Python vs the CLI, same configuration (bench/RESULTS.md, "Python module").

    PYTHONPATH=build/python python3 bench/python_pack.py [--cli build/aggpack] [--count 100000]
                                                         [--repeats 3]

The configuration is pack_bench's 100k case (BM_Random100kFuller35): Fuller-Thompson 5-20 mm
(q = 0.5), alpha 0.5, L = r, random sequential addition to 35 % solid in a cube sized for about
COUNT particles (pack_bench's cube_for: a particle fills 0.22 of its control sphere), seed 1.
Each run is a whole process doing the same work: parse the config, pack, write the native file.
  cli:    aggpack pack CONFIG -o cli.h5 --progress none
  python: python3 -c 'import aggpack; aggpack.pack(PackConfig.from_file(CONFIG)).write(py.h5)'
Runs alternate (cli, python, cli, ...) so that a change in machine load hits both; the table shows
every run and the medians of wall and CPU (user + sys) time. The two files must be
byte-identical.
"""
import argparse
import filecmp
import math
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--cli", default="build/aggpack", help="the aggpack CLI")
parser.add_argument("--count", type=float, default=1e5, help="particles to aim for")
parser.add_argument("--repeats", type=int, default=3, help="runs of each")
args = parser.parse_args()

# pack_bench's cube_for(fuller4(), count, 0.35): E[d^3] by number of the Fuller curve.
d_min, d_max, q = 0.005, 0.02, 0.5
integral = q / (d_max**q - d_min**q) * (d_max ** (q - 3) - d_min ** (q - 3)) / (q - 3)
mean_cubed = 1.0 / integral
side = (args.count * 0.22 * math.pi / 6 * mean_cubed / 0.35) ** (1 / 3)
config = f"""
[container]
length = {side!r}
width = {side!r}
depth = {side!r}
[particle]
alpha = 0.5
edge_length = 0.0
edge_length_ratio = 1.0
[grading]
kind = "fuller"
size_min = {d_min}
size_max = {d_max}
exponent = {q}
[packer]
kind = "random"
seed = 1
target_fraction = 0.35
"""
folder = tempfile.mkdtemp(prefix="aggpack-bench-")
config_path = os.path.join(folder, "bench.toml")
with open(config_path, "w") as f:
    f.write(config)
cli_out = os.path.join(folder, "cli.h5")
py_out = os.path.join(folder, "py.h5")
python_code = ("import aggpack, sys; "
               "p = aggpack.pack(aggpack.PackConfig.from_file(sys.argv[1])); "
               "p.write(sys.argv[2]); "
               "print(len(p), p.report['solid_fraction'], p.report['placement_seconds'])")
commands = {
    "cli": [args.cli, "pack", config_path, "-o", cli_out, "--force", "--progress", "none"],
    "python": [sys.executable, "-c", python_code, config_path, py_out],
}
times = {"cli": [], "python": []}
cpu = {"cli": [], "python": []}
print(f"cube side {side:.4f} m; {os.cpu_count()} cores; load {os.getloadavg()}")
for run in range(args.repeats):
    for name, command in commands.items():
        usage = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        result = subprocess.run(command, capture_output=True, text=True, check=False)
        elapsed = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu_seconds = (after.ru_utime - usage.ru_utime) + (after.ru_stime - usage.ru_stime)
        cpu[name].append(cpu_seconds)
        if result.returncode != 0:
            sys.exit(f"{name} failed: {result.stderr}")
        times[name].append(elapsed)
        last = result.stdout.strip().splitlines()[-1] if name == "python" else ""
        print(f"run {run + 1} {name:6s} {elapsed:7.2f} s wall {cpu_seconds:7.2f} s CPU  {last}")
same = filecmp.cmp(cli_out, py_out, shallow=False)
cli, py = statistics.median(times["cli"]), statistics.median(times["python"])
print(f"median wall: cli {cli:.2f} s, python {py:.2f} s, python / cli = {py / cli:.3f} "
      f"({100 * (py / cli - 1):+.1f} %); native files identical: {same}")
cli_cpu, py_cpu = statistics.median(cpu["cli"]), statistics.median(cpu["python"])
print(f"median CPU:  cli {cli_cpu:.2f} s, python {py_cpu:.2f} s, python / cli = "
      f"{py_cpu / cli_cpu:.3f} ({100 * (py_cpu / cli_cpu - 1):+.1f} %)")
print(f"load after: {os.getloadavg()}")
sys.exit(0 if same else 1)
