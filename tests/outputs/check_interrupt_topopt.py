#!/usr/bin/python3
"""Ctrl-C on fem-topopt: the run stops after the current iteration, writes the design reached with
PARTIAL.txt saying so, and exits with status 130.

    check_interrupt_topopt.py FEM_TOPOPT WORK_DIR

A 150 x 100 cantilever with a convergence tolerance no design meets runs for minutes; SIGINT is sent
after 1.5 s (setting up takes a fraction of that).
"""
import os
import signal
import subprocess
import sys
import time

program, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)
case = os.path.join(work, "long.toml")
out = os.path.join(work, "long_out")
with open(case, "w") as f:
    f.write("""[domain]
type = "rectangle"
size = [0.15, 0.1]
elements = [150, 100]
element = "quad4"
thickness = 0.001
[material]
E = 207e9
nu = 0.3
[optimization]
removed = 0.5
filter = "sensitivity"
filter_radius = 0.003
change_tolerance = 1e-9
max_iterations = 100000
[[support]]
box = [0.0, 0.0, 0.0, 0.1]
fix = ["x", "y"]
[[load]]
at = [0.15, 0.05]
force = [0.0, -3000.0]
""")
p = subprocess.Popen([program, case, "--output", out], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
time.sleep(1.5)
p.send_signal(signal.SIGINT)
stdout, stderr = p.communicate(timeout=120)
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


check(p.returncode == 130, f"exit status 130 (got {p.returncode}; stderr: {stderr.strip()[-300:]})")
check("fem-topopt: interrupted: stopped after iteration" in stderr, "stderr names the interruption")
partial = os.path.join(out, "PARTIAL.txt")
check(os.path.exists(partial), "PARTIAL.txt is written")
if os.path.exists(partial):
    note = open(partial).read()
    iterations = int(note.split("after iteration ")[1].split()[0])
    rows = [l for l in open(os.path.join(out, "history.dat")) if l.strip() and not l.startswith("#")]
    check(len(rows) - 1 == iterations or len(rows) == iterations,
          f"history.dat has the {iterations} iterations done ({len(rows)} lines)")
    check(os.path.exists(os.path.join(out, "design.vtu")) and os.path.exists(os.path.join(out, "manifest.txt")),
          "design.vtu and manifest.txt: the folder is a complete (partial) run")
check("INTERRUPTED (Ctrl-C) after" in stdout, "the summary says INTERRUPTED")
print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
