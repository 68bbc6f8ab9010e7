#!/usr/bin/python3
"""Dask with 1 vs 2 local workers (wall time of scripts/terraweave-dask), syntheses as tasks.

    bench/dask_workers.py TERRAWEAVE [PIPELINE [--set KEY=VALUE ...]]

Default: pipelines/demo.yaml (19 syntheses on the real DEM and map of Olinda) in tiles of 64
pixels (overlap 4), without preview. Each worker has one thread (--nthreads 1) and each task
runs terraweave with TBB inside, so on a 2-core machine the ratio shows the overhead as much as
the scaling. Prints the driver's times per worker count (plan, syntheses with complete-plan,
tiles, finish) and the speed-up; never fails on time. The two runs' outputs are compared.
"""
import filecmp
import json
import os
import signal
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PYTHON = "/usr/bin/python3"


def start(command):
    return subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            start_new_session=True)


def main():
    terraweave = os.path.abspath(sys.argv[1])
    pipeline = sys.argv[2] if len(sys.argv) > 2 else os.path.join(ROOT, "pipelines", "demo.yaml")
    sets = sys.argv[3:] or ["--set", "output.tiles={size: 64, overlap: 4}",
                            "--set", "output.preview=false"]
    times = {}
    with tempfile.TemporaryDirectory(prefix="tw-bench-dask-") as tmp:
        for workers in (1, 2):
            processes = []
            try:
                sched = os.path.join(tmp, f"scheduler{workers}.json")
                processes.append(start(
                    [PYTHON, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
                     "--port", "0", "--no-dashboard", "--scheduler-file", sched]))
                while not os.path.exists(sched):
                    time.sleep(0.1)
                time.sleep(0.2)
                for _ in range(workers):
                    processes.append(start(
                        [PYTHON, "-m", "distributed.cli.dask_worker", "--scheduler-file", sched,
                         "--nthreads", "1", "--no-dashboard", "--no-nanny",
                         "--local-directory", tmp]))
                address = json.load(open(sched))["address"]
                started = time.monotonic()
                out = subprocess.run(
                    [PYTHON, os.path.join(ROOT, "scripts", "terraweave-dask"), pipeline,
                     "--scheduler", address, "--out", os.path.join(tmp, f"out{workers}"),
                     "--terraweave", terraweave, "--min-workers", str(workers)] + sets,
                    capture_output=True, text=True, check=False)
                if out.returncode != 0:
                    sys.exit(f"terraweave-dask failed ({out.returncode}):\n{out.stdout}{out.stderr}")
                out = out.stdout
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
        tiles = os.path.join(tmp, "out1", "tiles")
        same = not filecmp.dircmp(tiles, os.path.join(tmp, "out2", "tiles")).diff_files
    print(f"{os.path.basename(pipeline)} {' '.join(sets[1::2])}: 2 workers take "
          f"{times[2] / times[1]:.2f} x the time of 1 (speed-up {times[1] / times[2]:.2f}); "
          f"tiles {'identical' if same else 'DIFFER'}")


if __name__ == "__main__":
    main()
