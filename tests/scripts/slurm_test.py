"""scripts/slurm/terraweave-slurm with a stand-in sbatch that runs what Slurm would: every
array task of a job (SLURM_ARRAY_TASK_ID set, in reverse order), only if the jobs it depends on
succeeded (--dependency=afterok). On distributed_support's roads world: the syntheses in two
waves (feature 1 waits for feature 0, whose canvas it meets), complete-plan, the tiles, finish;
the result equals a local run.

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
    kind, *after = options["dependency"].split(":")
    assert kind == "afterok", options["dependency"]
    ok = all(state["jobs"][a]["ok"] for a in after)
if ok:
    tasks = [None]
    if "array" in options:  # "0-8", "0,2,3" or both
        tasks = []
        for part in options["array"].split(","):
            first, _, last = part.partition("-")
            tasks += range(int(first), int(last or first) + 1)
        tasks.reverse()
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
        pipeline = s.write_roads_world(os.path.join(tmp, "world"))
        local = os.path.join(tmp, "local")
        s.run([terraweave, "-q", "run", pipeline, "--out", local])
        sbatch = os.path.join(tmp, "sbatch")
        with open(sbatch, "w") as f:
            f.write(FAKE_SBATCH)
        os.chmod(sbatch, os.stat(sbatch).st_mode | stat.S_IEXEC)
        state = os.path.join(tmp, "sbatch.json")
        env = dict(os.environ, TERRAWEAVE=terraweave, SBATCH=sbatch, FAKE_SBATCH_STATE=state)
        out = os.path.join(tmp, "slurm")
        printed = s.run([SUBMIT, pipeline, "--out", out, "--", "--time=00:10:00"], env=env,
                        cwd=tmp)
        jobs = json.load(open(state))["jobs"]
        s.check([j["script"] for j in jobs.values()] ==
                ["synth-feature.sbatch", "synth-feature.sbatch", "complete-plan.sbatch",
                 "render-tile.sbatch", "finish.sbatch"], f"submitted {jobs}")
        s.check(all(j["ok"] for j in jobs.values()), f"a job failed: {jobs}")
        waves = [jobs["1000"]["options"], jobs["1001"]["options"]]
        s.check(waves[0]["array"] == "0,2,3,4" and "dependency" not in waves[0] and
                waves[1]["array"] == "1" and waves[1]["dependency"] == "afterok:1000",
                f"synthesis waves: {waves}")
        s.check(jobs["1002"]["options"]["dependency"] == "afterok:1001", f"{jobs['1002']}")
        tiles, finish = jobs["1003"]["options"], jobs["1004"]["options"]
        s.check(tiles["array"] == "0-8" and tiles["dependency"] == "afterok:1002", f"{tiles}")
        s.check(finish["dependency"] == "afterok:1003", f"finish job: {finish}")
        s.check(all(j["options"]["time"] == "00:10:00" for j in jobs.values()),
                "sbatch arguments were not passed on")
        s.check("job 1003 (9 array tasks)" in printed, printed)
        s.same_outputs(local, out)
        print("slurm: 2 synthesis waves + complete-plan + 9 tiles (reverse order) + finish "
              "equal the local run")


if __name__ == "__main__":
    main()
