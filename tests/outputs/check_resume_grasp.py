#!/usr/bin/env python3
"""A killed `chicken_shackling --grasp` run resumes where it was (issue 12: a Table 5-4 case takes
40-60 min of one core, longer than a session's spare time), tested on the real program.

Case 4 runs to 3 ms with a restart dump every 1 ms, once uninterrupted (the reference). The same
run is started into another folder and killed with SIGKILL as soon as its first dump exists, then
resumed with `--resume`: the record grasp-case-4.dat (written row by row, read back up to the dump),
the VTU series, its .pvd and the end surfaces must equal the reference byte for byte, and the end
dump must be the only dump left. `--resume` with no killed run is refused (exit 2) saying why.
The reference record then goes through `--grasp-verdicts`, which regenerates Table 5-4 from
records (table-5-4.md): Case 4's row says it ran to 3 ms, with the drum angle 45 rpm turns in it.

usage: check_resume_grasp.py CHICKEN_SHACKLING WORK_DIR
"""
import os
import shutil
import signal
import subprocess
import sys
import time

from check_resume_explicit import dumps_in_staging, fail, failures, read  # the fem-explicit resume check's helpers


def main():
    program, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    grasp = [program, "--grasp", "4", "0.003", "--dump-every", "0.001"]
    ref, out = os.path.join(work, "reference"), os.path.join(work, "out")
    done = subprocess.run(grasp + ["--results", ref], capture_output=True, text=True)
    if done.returncode != 0:
        fail("the reference run failed:\n" + done.stdout + done.stderr)
        return
    refused = subprocess.run(grasp + ["--results", ref, "--resume"], capture_output=True, text=True)
    if refused.returncode != 2 or "no killed run" not in refused.stderr:
        fail(f"--resume without a killed run: exit {refused.returncode}, {refused.stderr!r}")

    run = subprocess.Popen(grasp + ["--results", out], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    while run.poll() is None and not dumps_in_staging(out):
        time.sleep(0.005)
    if run.poll() is None:
        os.kill(run.pid, signal.SIGKILL)
    if run.wait() != -signal.SIGKILL:
        fail("the run ended before it could be killed after its first dump: make it longer")
        return
    killed_at = dumps_in_staging(out)
    print(f"killed after {killed_at}")
    resumed = subprocess.run(grasp + ["--results", out, "--resume"], capture_output=True, text=True)
    if resumed.returncode != 0:
        fail("the resumed run failed:\n" + resumed.stdout + resumed.stderr)
        return
    if "resuming grasp-case-4 from " + killed_at[-1] not in resumed.stdout:
        fail(f"the resumed run does not say it resumed from the newest dump {killed_at[-1]}:\n" + resumed.stdout)
    names = sorted(f for f in os.listdir(ref) if not f.startswith("."))
    if sorted(f for f in os.listdir(out) if not f.startswith(".")) != names:
        fail(f"the resumed run's files {sorted(os.listdir(out))} differ from the reference's {names}")
    dumps = [f for f in names if "-restart-" in f]
    if len(dumps) != 1:
        fail(f"the finished run keeps {dumps}: only the end state's dump should stay")
    compared = [f for f in names if f.endswith((".dat", ".vtu", ".pvd"))]
    for f in compared:
        if os.path.exists(os.path.join(out, f)) and read(os.path.join(out, f)) != read(os.path.join(ref, f)):
            fail(f"{f} of the resumed run differs from the uninterrupted run's")
    rows = [l for l in read(os.path.join(ref, "grasp-case-4.dat")).decode().splitlines() if not l.startswith("#")]
    if len(rows) != 4 or len(compared) < 7:
        fail(f"the record has {len(rows)} rows (4 expected: 0..3 ms) and {len(compared)} files were compared")
    print(f"resumed: {len(compared)} files byte-identical to the uninterrupted run's ({len(rows)} record rows)")

    verdicts = os.path.join(work, "verdicts")
    judged = subprocess.run([program, "--grasp-verdicts", os.path.join(ref, "grasp-case-4.dat"), "--results", verdicts],
                            capture_output=True, text=True)
    table = os.path.join(verdicts, "table-5-4.md")
    if judged.returncode != 0 or not os.path.exists(table):
        fail("--grasp-verdicts on the reference record failed:\n" + judged.stdout + judged.stderr)
        return
    row = [l for l in read(table).decode().splitlines() if l.startswith("| 4 ")]
    # 45 rpm for 3 ms: 45 * 360 / 60 * 0.003 = 0.81 deg, printed to 0.1 deg
    if len(row) != 1 or not row[0].startswith("| 4 (run to 0.003 s) | 45 / 20 / 40 | 0.8 |"):
        fail(f"table-5-4.md's Case 4 row: {row}")
    print("table-5-4.md: " + row[0][:60])


if __name__ == "__main__":
    main()
    if failures:
        sys.exit(1)  # the work folder stays, to look at
    shutil.rmtree(sys.argv[2], ignore_errors=True)
    print("ok")
