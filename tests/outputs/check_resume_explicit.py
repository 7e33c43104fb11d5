#!/usr/bin/env python3
"""A killed fem-explicit run resumes where it was (issue 14 item 6), tested on the real program.

A small explicit case with restart_interval runs once uninterrupted (the reference). The same case
is started into another folder and killed with SIGKILL as soon as its first restart dump exists;
nothing may then be under a final name (the dumps are in the run's staging folder). `fem-explicit
case.toml --output DIR --resume` continues from the last dump and its results must equal the
reference byte for byte: histories.h5 / .dat, energies.dat, von_mises.dat, the VTU series and its
.pvd, the same file list and manifest; run.json equal but for wall-clock figures. Restart dumps are
compared by name only (each records its run's staging folder path). --resume with nothing to resume
is refused (exit 2) with a message that says why.

usage: check_resume_explicit.py FEM_EXPLICIT WORK_DIR
"""
import json
import os
import shutil
import signal
import subprocess
import sys
import time

CASE = """# A steel bar struck at x = 0 (tests/explicit_case/cases/bar_wave.toml, finer and longer)
[control]
end_time = 1.6e-3
threads = 1
restart_interval = 3.0e-4

[output]
interval = 1.0e-5
vtu_interval = 4.0e-4
[[output.node]]
name = "free_end"
set = "x1-bar"

[[material]]
name = "steel"
E = 210e9
nu = 0.3
rho = 7800.0

[[part]]
name = "bar"
material = "steel"
mesh = "box"
size = [1.0, 0.02, 0.02]
elements = [200, 2, 2]

[[boundary]]
set = "x0-bar"
velocity = [1.0, 0.0, 0.0]
"""

# run.json keys that measure the machine, not the result.
WALL_CLOCK = ("wall_s", "timing_s", "element_cycles_per_s")

failures = []


def fail(message):
    failures.append(message)
    print("FAIL " + message)


def visible_files(folder):
    """Files under folder a user sees as results (not the lock, staging folders or temporaries)."""
    found = []
    for root, dirs, files in os.walk(folder):
        dirs[:] = [d for d in dirs if not d.startswith(".run-")]
        for f in files:
            if f != ".lock" and not f.endswith(".partial"):
                found.append(os.path.relpath(os.path.join(root, f), folder))
    return sorted(found)


def read(path):
    with open(path, "rb") as f:
        return f.read()


def without_wall_clock(value):
    if isinstance(value, dict):
        return {k: without_wall_clock(v) for k, v in value.items() if k not in WALL_CLOCK}
    if isinstance(value, list):
        return [without_wall_clock(v) for v in value]
    return value


def main():
    program, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    case = os.path.join(work, "bar.toml")
    with open(case, "w") as f:
        f.write(CASE)

    ref = os.path.join(work, "reference")
    t0 = time.monotonic()
    done = subprocess.run([program, case, "--output", ref, "--quiet"], capture_output=True, text=True)
    seconds = time.monotonic() - t0
    if done.returncode != 0:
        fail("the reference run failed:\n" + done.stdout + done.stderr)
        return
    print(f"reference run: {seconds:.2f} s")

    # Refused: nothing to resume (a complete run leaves no killed run behind).
    refused = subprocess.run([program, case, "--output", ref, "--resume", "--quiet"], capture_output=True, text=True)
    if refused.returncode != 2 or "no killed run to resume" not in refused.stderr:
        fail(f"--resume into a folder without a killed run: exit {refused.returncode}, {refused.stderr!r}")

    # The run to kill: SIGKILL as soon as its first restart dump is complete in its staging folder.
    out = os.path.join(work, "out")
    run = subprocess.Popen([program, case, "--output", out, "--quiet"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    dump = None
    while dump is None and run.poll() is None:
        if os.path.isdir(out):
            for d in os.listdir(out):
                if d.startswith(".run-") and os.path.isdir(os.path.join(out, d)):
                    dumps = [f for f in os.listdir(os.path.join(out, d)) if "-restart-" in f and f.endswith(".h5")]
                    if dumps:
                        dump = dumps[0]
        time.sleep(0.002)
    os.kill(run.pid, signal.SIGKILL) if run.poll() is None else None
    status = run.wait()
    if status != -signal.SIGKILL:
        fail(f"the run ended (status {status}) before it could be killed after its first dump: make the case longer")
        return
    print(f"killed after the dump {dump}")
    left = visible_files(out)
    if left:
        fail(f"the killed run left files under final names: {left}")

    # Resumed with the same command plus --resume.
    resumed = subprocess.run([program, case, "--output", out, "--resume"], capture_output=True, text=True)
    if resumed.returncode != 0:
        fail("the resumed run failed:\n" + resumed.stdout + resumed.stderr)
        return
    if "resuming from" not in resumed.stderr:
        fail("the resumed run does not say which dump it resumed from:\n" + resumed.stderr)
    files, ref_files = visible_files(out), visible_files(ref)
    if files != ref_files:
        fail(f"the resumed set's files {files} differ from the uninterrupted run's {ref_files}")
    leftovers = sorted(set(os.listdir(out)) - set(os.listdir(ref)))
    if leftovers:
        fail(f"the resumed run left {leftovers}")
    compared = 0
    for f in ref_files:
        if f in ("summary.txt", "run.json") or "-restart-" in f or f not in files:
            continue
        compared += 1
        if read(os.path.join(out, f)) != read(os.path.join(ref, f)):
            fail(f"{f} of the resumed run differs from the uninterrupted run's")
    with open(os.path.join(out, "run.json")) as a, open(os.path.join(ref, "run.json")) as b:
        if without_wall_clock(json.load(a)) != without_wall_clock(json.load(b)):
            fail("run.json of the resumed run differs from the uninterrupted run's (wall-clock figures aside)")
    print(f"resumed: {compared} files byte-identical to the uninterrupted run's, run.json equal")
    if compared < 6:
        fail(f"only {compared} files compared: the case no longer writes its histories and VTU series")

    # Refused: the killed run had written no dump yet.
    early = os.path.join(work, "early")
    run = subprocess.Popen([program, case, "--output", early, "--quiet"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    while run.poll() is None and not (os.path.isdir(early) and any(d.startswith(".run-") for d in os.listdir(early))):
        time.sleep(0.001)
    os.kill(run.pid, signal.SIGKILL) if run.poll() is None else None
    if run.wait() == -signal.SIGKILL and not any(
        "-restart-" in f for _, _, fs in os.walk(early) for f in fs
    ):
        refused = subprocess.run([program, case, "--output", early, "--resume", "--quiet"], capture_output=True, text=True)
        if refused.returncode != 2 or "wrote no restart dump" not in refused.stderr:
            fail(f"--resume after a kill before the first dump: exit {refused.returncode}, {refused.stderr!r}")


if __name__ == "__main__":
    main()
    if failures:
        sys.exit(1)
    print("ok")
