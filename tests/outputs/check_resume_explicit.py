#!/usr/bin/env python3
"""A killed fem-explicit run resumes where it was (issue 14 item 6), tested on the real program.

A small explicit case with restart_interval runs once uninterrupted (the reference). The same case
is started into another folder and killed with SIGKILL as soon as its first restart dump exists,
resumed with `fem-explicit case.toml --output DIR --resume` and killed again after its next dump;
nothing may then be under a final name (the dumps are in the run's staging folder). A last
`--resume` continues from the last dump to the end, and its results must equal the reference byte
for byte. The same case in two [[phase]]s is killed in its second phase and resumed. Compared:
histories.h5 / .dat, energies.dat, von_mises.dat, the VTU series and its .pvd byte for byte, the
same file list and manifest, run.json equal but for wall-clock figures; restart dumps by name only
(each records its run's staging folder path). --resume with nothing to resume is refused (exit 2)
with a message that says why.

usage: check_resume_explicit.py FEM_EXPLICIT WORK_DIR
"""
import json
import os
import shutil
import signal
import subprocess
import sys
import time

# The case: tests/explicit_case/cases/bar_wave.toml (a struck steel bar), longer and finer, with
# restart dumps and a VTU series. Each edit must apply exactly once.
CASE_EDITS = [
    ("end_time = 4.0e-4 ", "end_time = 1.6e-3\nrestart_interval = 3.0e-4 "),
    ("interval = 2.0e-6", "interval = 1.0e-5\nvtu_interval = 4.0e-4"),
    ("nu = 0.0", "nu = 0.3"),
    ("elements = [100, 1, 1]", "elements = [200, 2, 2]"),
]

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
            if f not in (".lock", ".manifest-pending") and not f.endswith(".partial"):
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


def dumps_in_staging(folder):
    """The restart dumps in the staging folders of folder (a live or killed run's)."""
    found = []
    if os.path.isdir(folder):
        for d in os.listdir(folder):
            if d.startswith(".run-") and os.path.isdir(os.path.join(folder, d)):
                for _, _, files in os.walk(os.path.join(folder, d)):  # a phased case: one folder a phase
                    found += [f for f in files if "-restart-" in f and f.endswith(".h5")]
    return sorted(found)


def kill_after_dumps(command, folder, count):
    """Starts command, kills it with SIGKILL once count dumps are in folder's staging folder."""
    run = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    while run.poll() is None and len(dumps_in_staging(folder)) < count:
        time.sleep(0.005)
    if run.poll() is None:
        os.kill(run.pid, signal.SIGKILL)
    status = run.wait()
    if status != -signal.SIGKILL:
        fail(f"{command} ended (status {status}) before it could be killed after dump {count}: make the case longer")
        return False
    print(f"killed after {dumps_in_staging(folder)}")
    return True


def main():
    program, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "explicit_case", "cases", "bar_wave.toml")) as f:
        text = f.read()
    for old, new in CASE_EDITS:
        if text.count(old) != 1:
            fail(f"bar_wave.toml no longer holds '{old}' once: update CASE_EDITS")
            return
        text = text.replace(old, new)
    case = os.path.join(work, "bar.toml")
    with open(case, "w") as f:
        f.write(text)
    if not check_resume(program, os.path.join(work, "one"), case, [1, 2]):
        return
    # The same in two phases (the hand's grasp-then-flip restart): phase a ends at 7e-4 s with its
    # third dump; killed after the fourth (phase b's first), phase a is taken as the killed run
    # completed it and phase b continues from its own dump.
    phased = os.path.join(work, "bar-phases.toml")
    with open(phased, "w") as f:
        f.write(text + '\n[[phase]]\nname = "a"\n[[phase]]\nname = "b"\nstart_time = 7.0e-4\n')
    check_resume(program, os.path.join(work, "phases"), phased, [4], refusals=False)


def check_resume(program, work, case, kills, refusals=True):
    """Runs case uninterrupted and killed after each count of dumps in kills (resuming after each
    kill but the first), then resumed to the end; the results must be the uninterrupted run's.
    refusals: also --resume with nothing to resume, and after a kill before the first dump."""
    ref = os.path.join(work, "reference")
    t0 = time.monotonic()
    done = subprocess.run([program, case, "--output", ref, "--quiet"], capture_output=True, text=True)
    seconds = time.monotonic() - t0
    if done.returncode != 0:
        fail("the reference run failed:\n" + done.stdout + done.stderr)
        return False
    print(f"reference run: {seconds:.2f} s")

    # Refused: nothing to resume (a complete run leaves no killed run behind).
    if refusals:
        refused = subprocess.run([program, case, "--output", ref, "--resume", "--quiet"], capture_output=True, text=True)
        if refused.returncode != 2 or "no killed run to resume" not in refused.stderr:
            fail(f"--resume into a folder without a killed run: exit {refused.returncode}, {refused.stderr!r}")

    # The run to kill: SIGKILL as soon as its kills[0]-th restart dump is complete in its staging
    # folder; resumed and killed again after kills[1] dumps, and so on; resumed to the end.
    out = os.path.join(work, "out")
    for k, count in enumerate(kills):
        if not kill_after_dumps([program, case, "--output", out, "--quiet"] + (["--resume"] if k else []), out, count):
            return False
        left = visible_files(out)
        if left:
            fail(f"the killed run left files under final names: {left}")
    killed_at = dumps_in_staging(out)  # the last one is where the run must resume

    # Resumed with the same command plus --resume.
    resumed = subprocess.run([program, case, "--output", out, "--resume"], capture_output=True, text=True)
    if resumed.returncode != 0:
        fail("the resumed run failed:\n" + resumed.stdout + resumed.stderr)
        return False
    if "resuming from" not in resumed.stderr or killed_at[-1] not in resumed.stderr:
        fail(f"the resumed run does not say it resumed from the last dump {killed_at[-1]}:\n" + resumed.stderr)
    files, ref_files = visible_files(out), visible_files(ref)
    if files != ref_files:
        fail(f"the resumed set's files {files} differ from the uninterrupted run's {ref_files}")
    leftovers = sorted(set(os.listdir(out)) - set(os.listdir(ref)))
    if leftovers:
        fail(f"the resumed run left {leftovers}")
    compared = 0
    for f in ref_files:
        if os.path.basename(f) in ("summary.txt", "run.json") or "-restart-" in f or f not in files:
            continue
        compared += 1
        if read(os.path.join(out, f)) != read(os.path.join(ref, f)):
            fail(f"{f} of the resumed run differs from the uninterrupted run's")
    for f in [f for f in ref_files if os.path.basename(f) == "run.json"]:
        with open(os.path.join(out, f)) as a, open(os.path.join(ref, f)) as b:
            if without_wall_clock(json.load(a)) != without_wall_clock(json.load(b)):
                fail(f"{f} of the resumed run differs from the uninterrupted run's (wall-clock figures aside)")
    print(f"resumed: {compared} files byte-identical to the uninterrupted run's, run.json equal")
    if compared < 6:
        fail(f"only {compared} files compared: the case no longer writes its histories and VTU series")

    if not refusals:
        return True
    # Refused: the killed run had written no dump yet.
    early = os.path.join(work, "early")
    run = subprocess.Popen([program, case, "--output", early, "--quiet"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    while run.poll() is None and not (os.path.isdir(early) and any(d.startswith(".run-") for d in os.listdir(early))):
        time.sleep(0.001)
    os.kill(run.pid, signal.SIGKILL) if run.poll() is None else None
    if run.wait() == -signal.SIGKILL and not any(
        "-restart-" in f for _, _, fs in os.walk(early) for f in fs
    ):
        print("killed before its first dump: --resume refused")
        refused = subprocess.run([program, case, "--output", early, "--resume", "--quiet"], capture_output=True, text=True)
        if refused.returncode != 2 or "wrote no restart dump" not in refused.stderr:
            fail(f"--resume after a kill before the first dump: exit {refused.returncode}, {refused.stderr!r}")
    return True


if __name__ == "__main__":
    main()
    if failures:
        sys.exit(1)  # the work folder stays, to look at
    shutil.rmtree(sys.argv[2], ignore_errors=True)
    print("ok")
