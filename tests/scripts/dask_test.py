"""scripts/terraweave-dask against a real Dask scheduler and two workers on 127.0.0.1.

    dask_test.py TERRAWEAVE

On distributed_support's roads world (five syntheses, nine tiles):
1. Syntheses and tiles as tasks, one worker killed while it synthesizes a feature (its process
   group: the worker and its synth-feature): the DAG reruns that task on the other worker, and
   every output is byte-identical to a local `terraweave run` (report.json: the same values but
   timings and cache statuses, which differ between no cache and a new one).
2. One road changed, rerun with --cache on a copy of the local run's cache: the driver rebuilds
   the same syntheses ({1, 2}; R4's task reuses its synthesis by the finer check) and the same
   tiles as the local cached rerun, and every output,
   report.json's statuses included, equals the local run's.
The scheduler and workers are started and stopped here; nothing is left running.
"""
import json
import os
import shutil
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


def driver(terraweave, address, pipeline, out, extra=(), **popen):
    command = [PYTHON, DRIVER, pipeline, "--scheduler", address, "--out", out,
               "--terraweave", terraweave, "--min-workers", "2"] + list(extra)
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
        pipeline = s.write_roads_world(os.path.join(tmp, "world"))
        local_cache = os.path.join(tmp, "cache")
        local = os.path.join(tmp, "local")
        s.run([terraweave, "-q", "run", pipeline, "--out", local, "--cache", local_cache])
        services = Services(tmp)
        try:
            address = services.scheduler()
            # Worker a pauses in the first synthesis it gets; b runs the rest, then a's task.
            paused = services.worker("a", {"TERRAWEAVE_TEST_PAUSE_AT": "synth-feature"})
            services.worker("b")
            first = os.path.join(tmp, "dask1")
            run = driver(terraweave, address, pipeline, first)
            deadline = time.monotonic() + 60
            while "paused at synth-feature" not in open(paused.log_path).read():
                s.check(time.monotonic() < deadline and run.poll() is None,
                        "worker a never paused in a synthesis:\n" + open(paused.log_path).read() +
                        (run.communicate()[0] if run.poll() is not None else ""))
                time.sleep(0.1)
            services.kill(paused)
            services.worker("c")
            output = finished(run, "run with a killed worker")
            s.check("5 tasks of 5 features" in output and "9 tiles on 2 workers" in output,
                    f"unexpected summary:\n{output}")
            s.same_outputs(local, first, ignore={"cache"})
            print(f"dask: 5 syntheses and 9 tiles as tasks, a worker killed in a synthesis, "
                  f"outputs equal the local run ({time.monotonic() - started:.1f} s)")

            # One road changed: the local cached rerun and the driver's, from the same cache.
            dask_cache = os.path.join(tmp, "dask-cache")
            shutil.copytree(local_cache, dask_cache, symlinks=True)
            s.write_roads_world(os.path.join(tmp, "world"), s.ROADS_R1_MOVED)
            rerun = os.path.join(tmp, "local-rerun")
            s.run([terraweave, "-q", "run", pipeline, "--out", rerun, "--cache", local_cache])
            second = os.path.join(tmp, "dask2")
            output = finished(driver(terraweave, address, pipeline, second,
                                     ["--cache", dask_cache]), "rerun with a cache")
            s.check("3 tasks of 5 features" in output, f"unexpected summary:\n{output}")
            s.same_outputs(rerun, second)
            features, tiles = s.cache_statuses(second)
            rebuilt = {fid for fid, (status, _) in features.items() if status == "rebuilt"}
            s.check(rebuilt == s.REBUILT_WHEN_R1_MOVED, f"rebuilt syntheses {features}")
            rebuilt_tiles = [i for i, (status, _) in tiles.items() if status == "rebuilt"]
            s.check(0 < len(rebuilt_tiles) < len(tiles) == 9, f"tiles {tiles}")
            print(f"dask: one road changed, --cache: syntheses {sorted(rebuilt)} and tiles "
                  f"{sorted(rebuilt_tiles)} rebuilt as in the local run, outputs equal "
                  f"({time.monotonic() - started:.1f} s)")
        finally:
            services.stop()


if __name__ == "__main__":
    main()
