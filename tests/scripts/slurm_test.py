"""scripts/slurm/terraweave-slurm with a stand-in sbatch that runs what Slurm would: every
array task of render-tile.sbatch (SLURM_ARRAY_TASK_ID set, in reverse order) and then, only if
they all succeeded (--dependency=afterok), finish.sbatch. The result equals a local run.

    slurm_test.py TERRAWEAVE
"""
import json
import os
import stat
import subprocess
import sys
import tempfile

import distributed_support as s

SUBMIT = os.path.join(s.SOURCE_DIR, "scripts", "slurm", "terraweave-slurm")

FAKE_SBATCH = r'''#!/usr/bin/python3
import json, os, subprocess, sys
state_path = os.environ["FAKE_SBATCH_STATE"]
state = json.load(open(state_path)) if os.path.exists(state_path) else {"jobs": {}}
args = sys.argv[1:]
options = {}
while args and args[0].startswith("--"):
    key, _, value = args.pop(0)[2:].partition("=")
    options[key] = value
script, script_args = args[0], args[1:]
assert "parsable" in options, "submitted without --parsable"
job = str(1000 + len(state["jobs"]))
ok = True
if "dependency" in options:
    kind, _, after = options["dependency"].partition(":")
    assert kind == "afterok", options["dependency"]
    ok = state["jobs"][after]["ok"]
if ok:
    first, _, last = options.get("array", "0-0").partition("-")
    tasks = range(int(last), int(first) - 1, -1) if "array" in options else [None]
    for task in tasks:
        env = dict(os.environ, SLURM_JOB_ID=job)
        if task is not None:
            env["SLURM_ARRAY_TASK_ID"] = str(task)
        with open(f"slurm-{job}_{task}.out", "w") as log:  # as Slurm, not on sbatch's stdout
            ok = subprocess.run(["bash", script] + script_args, env=env, stdout=log,
                                stderr=subprocess.STDOUT).returncode == 0 and ok
state["jobs"][job] = {"script": os.path.basename(script), "options": options, "ok": ok}
json.dump(state, open(state_path, "w"))
print(job)
'''


def main():
    terraweave = os.path.abspath(sys.argv[1])
    with tempfile.TemporaryDirectory(prefix="tw-slurm-") as tmp:
        local = os.path.join(tmp, "local")
        s.run([terraweave, "-q", "run", s.PIPELINE, "--out", local] + s.set_args())
        sbatch = os.path.join(tmp, "sbatch")
        with open(sbatch, "w") as f:
            f.write(FAKE_SBATCH)
        os.chmod(sbatch, os.stat(sbatch).st_mode | stat.S_IEXEC)
        state = os.path.join(tmp, "sbatch.json")
        env = dict(os.environ, TERRAWEAVE=terraweave, SBATCH=sbatch, FAKE_SBATCH_STATE=state)
        out = os.path.join(tmp, "slurm")
        printed = s.run([SUBMIT, s.PIPELINE, "--out", out] + s.set_args() +
                        ["--", "--time=00:10:00"], env=env, cwd=tmp)
        jobs = json.load(open(state))["jobs"]
        s.check([j["script"] for j in jobs.values()] == ["render-tile.sbatch", "finish.sbatch"],
                f"submitted {jobs}")
        array, finish = jobs["1000"], jobs["1001"]
        s.check(array["options"]["array"] == "0-8" and array["ok"], f"array job: {array}")
        s.check(finish["options"]["dependency"] == "afterok:1000" and finish["ok"],
                f"finish job: {finish}")
        s.check(array["options"]["time"] == "00:10:00", "sbatch arguments were not passed on")
        s.check("job 1000 (9 array tasks)" in printed, printed)
        s.equals_local_run(local, out)
        print("slurm: 9 array tasks in reverse order + finish equal the local run")


if __name__ == "__main__":
    main()
