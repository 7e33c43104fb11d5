#!/usr/bin/python3
"""Reads an explicit run's outputs with readers that share no code with ours, as a user would.

    check_outputs.py EXPLICIT_OUTPUTS_PROGRAM WORK_DIR

Runs tests/outputs/explicit_outputs.cpp twice:
1. to the end: the PVD (xml.etree) lists the VTU files with their times (0, every 2 ms, the end),
   each VTU (meshio) carries part ids, displacement, velocity, von Mises stress and contact pressure
   with the values the solver held (printed by the program); the HDF5 file (h5py) has the layout of
   lib/io/README.md and the same histories; stderr shows one progress line per 10 %.
2. with SIGINT raised at 8 ms (Ctrl-C): exit status 130, a message on stderr, the outputs written up
   to the stop and marked partial.
Debian's python3-meshio and python3-h5py (make deps).
"""
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import meshio
import numpy as np

failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def run(program, out_dir, extra):
    r = subprocess.run([program, out_dir] + extra, capture_output=True, text=True)
    expected = {}
    for line in r.stdout.splitlines():
        if line.startswith("expected "):
            key, *values = line.split()[1:]
            if key == "node":
                expected[f"node {values[0]}"] = [float(v) for v in values[1:]]
            else:
                expected[key] = float(values[0])
    return r, expected


def read_pvd(path):
    root = ET.parse(path).getroot()
    return [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]


def close(a, b, rel, floor=0.0):
    return abs(a - b) <= rel * max(abs(a), abs(b)) + floor


def main():
    program, work = sys.argv[1], sys.argv[2]
    full, partial = os.path.join(work, "full"), os.path.join(work, "partial")

    # ---- 1. a whole run ------------------------------------------------------------------------
    r, e = run(program, full, [])
    check(r.returncode == 0, f"the run ends with status 0 (got {r.returncode}: {r.stderr.strip()[-300:]})")
    progress = [l for l in r.stderr.splitlines() if l.startswith("block on plate:") and " %" in l]
    check(len(progress) == 10 and "100.0 %" in progress[-1] and "element-cycles/s" in progress[0],
          f"stderr (not a terminal) has one progress line per 10 %: {len(progress)} lines")

    series = read_pvd(os.path.join(full, "run.pvd"))
    times = [t for t, _ in series]
    check(len(series) == 11, f"the PVD lists 11 states (0, every 2 ms, 20 ms): {len(series)}")
    check(times[0] == 0.0 and all(b > a for a, b in zip(times, times[1:])), "times start at 0 and increase")
    dt = e["max_dt"]
    gaps = np.diff(times)
    check(np.all(gaps[:-1] >= 2e-3 * (1 - 1e-9)) and np.all(gaps[:-1] <= 2e-3 + dt * (1 + 1e-9)),
          f"a state at the first cycle 2 ms or more after the last one (dt <= {dt:.3g} s): "
          f"{[f'{t:.6g}' for t in times]}")

    meshes = [meshio.read(os.path.join(full, f)) for _, f in series]
    m = meshes[-1]
    n_points = len(m.points)
    check(all(len(x.points) == n_points for x in meshes), "every VTU has the same points")
    for name in ("displacement", "velocity", "contact_pressure"):
        check(name in m.point_data, f"point field '{name}'")
    for name in ("part", "von_mises"):
        check(name in m.cell_data, f"cell field '{name}'")
    cell_types = [b.type for b in m.cells]
    part = np.concatenate(m.cell_data["part"])
    check(sorted(set(part.tolist())) == [0, 1] and cell_types == ["hexahedron", "quad"],
          f"part ids 0 (block, hexahedra) and 1 (plate, quads): {sorted(set(part.tolist()))}, {cell_types}")
    check(np.sum(part == 0) == 18 and np.sum(part == 1) == 36, "18 block cells, 36 plate cells")

    # Values against the solver's memory (VTU fields are single precision: 1e-6).
    u, v = m.point_data["displacement"], m.point_data["velocity"]
    for node in (0, 40):
        want = e[f"node {node}"]
        check(all(close(u[node][k], want[k], 1e-6, 1e-12) for k in range(3)),
              f"node {node} displacement {u[node].tolist()} = {want[:3]}")
        check(all(close(v[node][k], want[3 + k], 1e-6, 1e-12) for k in range(3)),
              f"node {node} velocity {v[node].tolist()} = {want[3:]}")
    # The deformed coordinates are the reference plus the displacement.
    ref = meshes[0].points
    check(np.allclose(m.points, ref + u, rtol=0, atol=1e-7), "points = first state's points + displacement")
    vm = np.concatenate(m.cell_data["von_mises"])
    check(close(vm[part == 0].max(), e["block_max_von_mises"], 1e-6), f"largest block von Mises {vm.max():.6g} Pa")
    check(np.all(vm[part == 1] == 0), "no stress on the rigid plate")

    # Contact pressure: on the block's bottom nodes only; times the nodes' tributary areas (the 3 x 3
    # grid of bottom faces in the deformed state, projected on the plate: a quarter of each face to
    # each of its corners) it sums to the force on the plate.
    p = m.point_data["contact_pressure"]
    bottom = np.where((np.abs(ref[:, 2]) < 1e-9) & (np.arange(n_points) < 48))[0]
    check(len(bottom) == 16 and np.all(p[np.setdiff1d(np.arange(n_points), bottom)] == 0),
          "pressure only on the block's 16 bottom nodes")
    grid = {(round(ref[i, 0] / 0.01), round(ref[i, 1] / 0.01)): i for i in bottom}
    area = np.zeros(n_points)
    x = m.points
    for i in range(3):
        for j in range(3):
            q = [grid[(i, j)], grid[(i + 1, j)], grid[(i + 1, j + 1)], grid[(i, j + 1)]]
            d1, d2 = x[q[2]] - x[q[0]], x[q[3]] - x[q[1]]
            a = 0.5 * abs(d1[0] * d2[1] - d1[1] * d2[0])
            area[q] += a / 4
    force = float(np.sum(p * area))
    weight = 1000 * 0.03 * 0.03 * 0.015 * 49.05
    check(close(force, weight, 0.2), f"about the block's weight under 5 g, {weight:.4g} N (damped, settling)")

    # HDF5 histories (layout: lib/io/README.md).
    with h5py.File(os.path.join(full, "run.h5"), "r") as h:
        for name in ("time", "energy/kinetic", "energy/internal", "energy/hourglass", "energy/damping",
                     "energy/viscous", "energy/external_work", "energy/contact", "energy/balance_error",
                     "history/corner/displacement", "history/corner/velocity", "history/top/displacement",
                     "max_von_mises/block"):
            check(name in h, f"HDF5 dataset '{name}'")
        t = h["time"][()]
        check(len(t) == e["history_samples"], f"{len(t)} history samples")
        check(close(t[-1], e["end_time"], 1e-12), "the last sample is at the end time")
        check(h["history/top/displacement"].shape == (len(t), 3), "history/top/displacement is samples x 3")
        check(h["history/top/displacement"].attrs["node"] == 40, "its node attribute")
        check(np.allclose(h["history/top/displacement"][-1], e["node 40"][:3], rtol=1e-14, atol=0),
              "the last top displacement equals the solver's, bit for bit")
        check(h["energy/kinetic"][-1] == e["last_kinetic"], "the last kinetic energy equals the solver's")
        check("summary" in h.attrs and "partial" not in h.attrs, "summary attribute, not partial")

    # ---- 2. interrupted by SIGINT at 8 ms ------------------------------------------------------------
    r, e = run(program, partial, ["--interrupt-at", "0.008"])
    check(r.returncode == 130, f"Ctrl-C: exit status 130 (got {r.returncode})")
    check("interrupted: explicit run 'block on plate': partial: interrupted (Ctrl-C) at t = 0.008" in r.stderr,
          f"stderr says it was interrupted and where: {r.stderr.strip().splitlines()[-1] if r.stderr.strip() else ''}")
    with h5py.File(os.path.join(partial, "run.h5"), "r") as h:
        note = h.attrs.get("partial", "")
        if isinstance(note, bytes):
            note = note.decode()
        check(note.startswith("partial: interrupted"), f"run.h5 is marked partial: '{note}'")
        t = h["time"][()]
        check(0.008 <= t[-1] < 0.0085, f"its histories end at the stop, t = {t[-1]:.6g} s")
    series = read_pvd(os.path.join(partial, "run.pvd"))
    check(0.008 <= series[-1][0] < 0.0085 and all(os.path.exists(os.path.join(partial, f)) for _, f in series),
          f"the VTU series ends with the state at the stop ({series[-1][0]:.6g} s), every file there")
    check(not any(f.endswith(".partial") for f in os.listdir(partial)), "no half-written file left")

    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
