#!/usr/bin/python3
"""Dask with 1 vs 2 local workers (wall time of scripts/terraweave-dask), issue #10.

    bench/dask_workers.py TERRAWEAVE [SIZE] [TILE]

A generated world of SIZE x SIZE cells (default 1024, 4 m) with generated.yaml's roads and river,
in tiles of TILE pixels (default 256, overlap 16). Prints the driver's times per worker count and
the speed-up; never fails on time. Each worker has one thread (--nthreads 1) and each tile runs
with TBB inside, so on a 2-core machine the ratio shows the overhead as much as the scaling.
"""
import json
import os
import signal
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PYTHON = "/usr/bin/python3"


def main():
    terraweave = os.path.abspath(sys.argv[1])
    size = int(sys.argv[2]) if len(sys.argv) > 2 else 1024
    tile = int(sys.argv[3]) if len(sys.argv) > 3 else 256
    overrides = [f"generate.width={size}", f"generate.height={size}",
                 f"generate.pixel_size={4096 / size}", f"output.tiles.size={tile}",
                 "output.tiles.overlap=16"]
    sets = [a for o in overrides for a in ("--set", o)]
    times = {}
    with tempfile.TemporaryDirectory(prefix="tw-bench-dask-") as tmp:
        for workers in (1, 2):
            processes = []
            try:
                sched = os.path.join(tmp, f"scheduler{workers}.json")
                processes.append(subprocess.Popen(
                    [PYTHON, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
                     "--port", "0", "--no-dashboard", "--scheduler-file", sched],
                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True))
                while not os.path.exists(sched):
                    time.sleep(0.1)
                time.sleep(0.2)
                for w in range(workers):
                    processes.append(subprocess.Popen(
                        [PYTHON, "-m", "distributed.cli.dask_worker", "--scheduler-file", sched,
                         "--nthreads", "1", "--no-dashboard", "--no-nanny",
                         "--local-directory", tmp],
                        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                        start_new_session=True))
                address = json.load(open(sched))["address"]
                started = time.monotonic()
                out = subprocess.run(
                    [PYTHON, os.path.join(ROOT, "scripts", "terraweave-dask"),
                     os.path.join(ROOT, "pipelines", "generated.yaml"), "--scheduler", address,
                     "--out", os.path.join(tmp, f"out{workers}"), "--terraweave", terraweave,
                     "--min-workers", str(workers)] + sets,
                    capture_output=True, text=True, check=True).stdout
                times[workers] = time.monotonic() - started
                print(f"{workers} worker{'s' if workers > 1 else ' '}: {times[workers]:7.2f} s wall")
                print("  " + out.strip().replace("\n", "\n  "))
            finally:
                for p in reversed(processes):
                    try:
                        os.killpg(p.pid, signal.SIGKILL)
                    except ProcessLookupError:
                        pass
                    p.wait()
    print(f"{size}^2 world, tiles of {tile}: 2 workers take {times[2] / times[1]:.2f} x the time "
          f"of 1 (speed-up {times[1] / times[2]:.2f})")


if __name__ == "__main__":
    main()
