"""scripts/terraweave-dask against a real Dask scheduler and two workers on 127.0.0.1.

    dask_test.py TERRAWEAVE

1. The driver's output equals a local `terraweave run` of the same pipeline: the mosaics hold
   the untiled layers' pixels and report.json the same values (timings and the tile list
   aside); when the local run writes tiles itself, every file byte for byte.
2. A worker killed while it renders a tile (its process group: the worker and its
   render-tile): the tile reruns on the other worker and every output is byte-identical to 1.
The scheduler and workers are started and stopped here; nothing is left running.
"""
import json
import os
import signal
import subprocess
import sys
import tempfile
import time

import distributed_support as s

DRIVER = os.path.join(s.SOURCE_DIR, "scripts", "terraweave-dask")
PYTHON = "/usr/bin/python3"  # Debian's, where python3-distributed is


class Services:
    """A scheduler and workers, each in its own process group, killed at exit."""

    def __init__(self, folder):
        self.folder = folder
        self.processes = []
        self.scheduler_file = os.path.join(folder, "scheduler.json")

    def start(self, name, command, env=None):
        log = open(os.path.join(self.folder, name + ".log"), "w")
        p = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT, env=env,
                             start_new_session=True, cwd=self.folder)
        p.log_path = log.name
        self.processes.append(p)
        return p

    def scheduler(self):
        if os.path.exists(self.scheduler_file):
            os.remove(self.scheduler_file)
        self.start("scheduler", [PYTHON, "-m", "distributed.cli.dask_scheduler",
                                 "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                                 "--scheduler-file", self.scheduler_file])
        deadline = time.monotonic() + 30
        while not os.path.exists(self.scheduler_file):
            s.check(time.monotonic() < deadline, "the scheduler did not start")
            time.sleep(0.1)
        time.sleep(0.2)  # written, not only created
        return json.load(open(self.scheduler_file))["address"]

    def worker(self, name, extra_env=None):
        env = dict(os.environ, **(extra_env or {}))
        return self.start(name, [PYTHON, "-m", "distributed.cli.dask_worker",
                                 "--scheduler-file", self.scheduler_file, "--nthreads", "1",
                                 "--no-dashboard", "--no-nanny", "--name", name,
                                 "--local-directory", self.folder], env)

    @staticmethod
    def kill(p):
        try:
            os.killpg(p.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        p.wait()

    def stop(self):
        for p in reversed(self.processes):
            self.kill(p)
        self.processes = []


def driver(terraweave, address, out, **popen):
    command = [PYTHON, DRIVER, s.PIPELINE, "--scheduler", address, "--out", out,
               "--terraweave", terraweave, "--min-workers", "2"] + s.set_args()
    return subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            **popen)


def finished(p, what):
    output, _ = p.communicate(timeout=120)
    s.check(p.returncode == 0, f"{what}: driver exited {p.returncode}:\n{output}")
    return output


def main():
    terraweave = os.path.abspath(sys.argv[1])
    with tempfile.TemporaryDirectory(prefix="tw-dask-") as tmp:
        started = time.monotonic()
        local = os.path.join(tmp, "local")
        s.run([terraweave, "-q", "run", s.PIPELINE, "--out", local] + s.set_args())
        services = Services(tmp)
        try:
            address = services.scheduler()
            services.worker("a")
            services.worker("b")
            first = os.path.join(tmp, "dask1")
            output = finished(driver(terraweave, address, first), "first run")
            s.check("9 tiles on 2 workers" in output, f"unexpected summary:\n{output}")
            s.equals_local_run(local, first)
            print(f"dask: 9 tiles on 2 workers equal the local run ({time.monotonic() - started:.1f} s)")

            # Worker a pauses in the first tile it gets; b renders the rest, then a's tile.
            services.stop()
            address = services.scheduler()
            paused = services.worker("a", {"TERRAWEAVE_TEST_PAUSE_AT": "render-tile"})
            services.worker("b")
            second = os.path.join(tmp, "dask2")
            run = driver(terraweave, address, second)
            deadline = time.monotonic() + 60
            while "paused at render-tile" not in open(paused.log_path).read():
                s.check(time.monotonic() < deadline and run.poll() is None,
                        "worker a never paused in a tile:\n" + open(paused.log_path).read() +
                        (run.communicate()[0] if run.poll() is not None else ""))
                time.sleep(0.1)
            services.kill(paused)
            finished(run, "run with a killed worker")
            s.same_outputs(first, second)
            print(f"dask: a worker killed in a tile, outputs identical "
                  f"({time.monotonic() - started:.1f} s)")
        finally:
            services.stop()


if __name__ == "__main__":
    main()
