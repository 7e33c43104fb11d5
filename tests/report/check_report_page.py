#!/usr/bin/python3
"""Opens the report page in the program a reader uses, a web browser (Debian's chromium, headless).

    check_report_page.py fixture FEM_REPORT WORK_DIR SCREENSHOT_DIR
        Builds a small build/results-like folder (three studies: one with every verdict, kind and a
        thesis discrepancy, figures as PNG, SVG and a regenerated Markdown table, and thesis values
        on a curve of ours; one with a figure only; one not run), writes its report with fem-report,
        opens REPORT.html#selftest and checks what the page did against what this script put in:
        every image loads, every in-page link has its target and every file link its file, every
        count at the top and every filter shows exactly the checks it should (by id), the figures
        open full size, the curve plot marks the thesis's points. Saves a screenshot.
    check_report_page.py page REPORT.html SCREENSHOT_DIR
        The same page checks on a report already written (`make report`): images, links, and every
        count at the top equal to the rows its filter shows; saves desktop and narrow screenshots.

The page writes what it saw into <pre id="selftest"> (lib/check/report_html.cpp); chromium
--dump-dom prints the DOM after the page's scripts ran.
"""
import html
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import zlib

failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def chromium(args, url):
    cmd = ["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
           "--no-first-run", "--disable-extensions", "--disable-background-networking"] + args + [url]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=180)
    if r.returncode != 0:
        print(r.stderr[-2000:])
    return r


def selftest(page, shot=None, width=1400, height=1000, then=""):
    """Runs the page's self-test; with `shot`, also saves a screenshot of the page (filtered by `then`
    afterwards, e.g. "verdict=miss") from the same browser run."""
    args = ["--virtual-time-budget=10000", "--dump-dom"]
    if shot:
        os.makedirs(os.path.dirname(shot), exist_ok=True)
        if os.path.exists(shot):
            os.remove(shot)
        args += [f"--window-size={width},{height}", f"--screenshot={shot}"]
    r = chromium(args, "file://" + os.path.abspath(page) + "#selftest" + (";filter=" + then if then else ""))
    if shot:
        check(os.path.exists(shot) and os.path.getsize(shot) > 10000, f"screenshot {shot} ({width}x{height})")
    m = re.search(r'<pre id="selftest">(.*?)</pre>', r.stdout, re.S)
    if not m or not m.group(1).strip():
        check(False, "the page ran its self-test (no result in <pre id=selftest>)")
        print(r.stdout[-3000:], r.stderr[-3000:])
        sys.exit(1)
    out = json.loads(html.unescape(m.group(1)))
    if "error" in out:
        check(False, "the page's self-test raised: " + out["error"])
        sys.exit(1)
    return out


def screenshot(page, path, width, height, fragment=""):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    if os.path.exists(path):
        os.remove(path)
    chromium([f"--window-size={width},{height}", f"--screenshot={path}"], "file://" + os.path.abspath(page) + fragment)
    ok = os.path.exists(path) and os.path.getsize(path) > 10000
    check(ok, f"screenshot {path} ({width}x{height})")


def page_checks(out, page_dir):
    """What holds for any report page."""
    check(out["images"] > 0 and not out["broken_images"],
          f"every image loads ({out['images']} images; broken: {out['broken_images']})")
    check(not out["broken_anchors"], f"every in-page link has its target ({out['anchors']} links; broken: {out['broken_anchors']})")
    missing = sorted({f for f in out["files"] if not os.path.exists(os.path.join(page_dir, f.split("#")[0]))})
    check(not missing, f"every file the page links or shows exists beside it ({len(out['files'])} references; missing: {missing})")
    for f in out["filters"]:
        if f["expected"] is not None:  # a count at the top: it filters to exactly what it counts
            check(f["rendered"] == f["expected"] == int(f["status"]),
                  f"count '{f['name']}' ({f['expected']}) shows {f['rendered']} rows, status says {f['status']}")
    check(out["after_reset"] == out["checks"], f"'Show all' shows every check again ({out['after_reset']} of {out['checks']})")
    lb = out["lightbox"]
    check(lb.get("opened") and lb.get("src") == lb.get("thumb") and lb.get("closed"),
          f"a thumbnail opens its figure full size and closes again ({lb})")


# ------------------------------------------------------------------------------------------------
# The fixture: records as the studies write them (DESIGN.md "Outputs"), with known verdicts.

def png(path, w=120, h=80):
    """A small valid PNG (a colour ramp), written without any imaging library."""
    raw = b"".join(b"\x00" + b"".join(bytes((x * 2 % 256, y * 3 % 256, 150)) for x in range(w)) for y in range(h))
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


REFERENCE = {
    "demo_a_verdicts": '''study = "demo_a_verdicts"
title = "Fixture study with every verdict"
section = "Sec 9.1"
[figures]
"Fig 9-1" = ["fig-9-1.png", "fig-9-1.svg"]
"Table 9-2" = ["table-9-2.md"]
''',
    "demo_b_figure": '''study = "demo_b_figure"
title = "Fixture study with a figure only"
section = "Sec 9.2"
[figures]
"Fig 9-9" = ["fig-9-9.png"]
''',
    "demo_c_not_run": '''study = "demo_c_not_run"
title = "Fixture study not run"
section = "Sec 9.3"
''',
}


def record(id, source, kind, basis, thesis, ours, passed, tol=None, known_miss=None, discrepancy=None, reference=None,
           curve=None, unit="", full_only=None):
    r = {"id": id, "source": source, "quantity": "q " + id, "unit": unit, "basis": basis, "kind": kind,
         "thesis": thesis, "reproduced": ours, "tolerance": tol, "passed": passed, "note": "note of " + id}
    if known_miss:
        r["known_miss"] = known_miss
    if discrepancy:
        r["discrepancy"], r["reference"] = discrepancy, reference
    if curve:
        r["curve"] = curve
    if full_only:  # a run without --full lists it, not judged (check::Verdict::NotRun)
        r["full_only"], r["not_run"] = full_only, True
    return r


CURVE = {"file": "fig-9-1.dat", "x": "t_ms", "y": "twist_deg", "x_label": "time (ms)"}
CHECKS = {
    "demo_a_verdicts": [
        record("fig-9-1/peak", "Fig 9-1", "reproduction", "model", 25.5, 29.4, False, {"rel": 0.15},
               known_miss="the loads dent single nodes", curve=dict(CURVE, at=5.7), unit="deg"),
        record("fig-9-1/start", "Fig 9-1", "reproduction", "model", 2.0, 2.04, True, {"rel": 0.1}, curve=dict(CURVE, at=1.0),
               unit="deg"),
        record("table-9-2/dt", "Table 9-2", "reproduction", "model", 1.26, 1.9, False, {"rel": 0.1}, unit="us"),
        record("table-9-2/steps", "Table 9-2", "consistency", "exact", 1070, 1071.05, True, {"abs": 2},
               discrepancy="the thesis rounds dt first", reference=1071.06),
        record("table-9-2/order", "Table 9-2", "trend", "trend", "case 2", "case 2", True),
        record("table-9-2/volume", "Table 9-2", "verification", "exact", 0.3, 0.3, True, {"abs": 1e-6}),
        record("table-9-2/experiment", "Table 9-2", "shown", "experiment", 25.0, 14.8, None),
        record("eq-9-1/fit", "Eq 9-1", "consistency", "reconstructed", 3.0, 3.01, True, {"rel": 0.01}),
        record("eq-9-1/long", "Eq 9-1", "reproduction", "model", 4.0, None, None, {"rel": 0.1}, full_only="runs too long"),
    ],
    "demo_b_figure": [
        record("fig-9-9/miss-trend", "Fig 9-9", "trend", "trend", "grows", "shrinks", False, known_miss="no contact model"),
    ],
}


def verdict(r):
    """The classification check::verdict() makes (lib/check/study.cpp), restated for the expectations."""
    if r.get("not_run"):
        return "notrun"
    if r["passed"] is None:
        return "shown"
    if not r.get("known_miss"):
        return "pass" if r["passed"] else "fail"
    return "fail" if r["passed"] else "miss"


def make_fixture(work):
    shutil.rmtree(work, ignore_errors=True)
    for d in ("reference", "results", "figures"):
        os.makedirs(os.path.join(work, d))
    for study, text in REFERENCE.items():
        with open(os.path.join(work, "reference", study + ".toml"), "w") as f:
            f.write(text)
    for study, records in CHECKS.items():
        os.makedirs(os.path.join(work, "results", study))
        with open(os.path.join(work, "results", study, "checks.json"), "w") as f:
            json.dump(records, f, indent=1)
    with open(os.path.join(work, "results", "demo_a_verdicts", "runs.json"), "w") as f:
        json.dump([{"name": "run 1", "values": {"steps": 100, "wall_s": 0.5}}], f)
    with open(os.path.join(work, "results", "demo_a_verdicts", "fig-9-1.dat"), "w") as f:
        f.write("# t_ms twist_deg\n")
        for k in range(101):  # twist = 30 sin(pi t / 12) deg over t = 0..10 ms
            t = k / 10
            f.write(f"{t} {30 * math.sin(math.pi * t / 12)}\n")
    figures = os.path.join(work, "figures")
    png(os.path.join(figures, "fig-9-1.png"))
    png(os.path.join(figures, "fig-9-9.png"), 200, 100)
    with open(os.path.join(figures, "fig-9-1.svg"), "w") as f:
        f.write('<svg xmlns="http://www.w3.org/2000/svg" width="200" height="100"><rect width="200" height="100" '
                'fill="#cde"/><text x="20" y="55">Fig 9-1</text></svg>\n')
    with open(os.path.join(figures, "table-9-2.md"), "w") as f:
        f.write("| case | dt (us) |\n|---|---|\n| C | 1.9 |\n| D | 0.3 \\| 0.2 |\n")


def fixture(fem_report, work, shots):
    make_fixture(work)
    page_dir = os.path.join(work, "figures")
    r = subprocess.run([fem_report, "--reference", os.path.join(work, "reference"), "--results",
                        os.path.join(work, "results"), "--figures", page_dir], capture_output=True, text=True)
    check(r.returncode == 0, f"fem-report writes the fixture's report ({r.stdout.strip()} {r.stderr.strip()})")
    page = os.path.join(page_dir, "REPORT.html")
    # The screenshot shows the page filtered to the known misses: the plot of a thesis value on our curve.
    out = selftest(page, os.path.join(shots, "report-page.png"), then="verdict=miss")
    page_checks(out, page_dir)

    records = [r for study in CHECKS.values() for r in study]
    check(out["checks"] == len(records), f"the page lists every check once ({out['checks']} of {len(records)})")
    check(out["images"] == 3, f"the three image figures are on the page ({out['images']}); the Markdown table is inlined")
    expected = {
        "verdict=pass": {r["id"] for r in records if verdict(r) == "pass"},
        "verdict=fail": {r["id"] for r in records if verdict(r) == "fail"},
        "verdict=miss": {r["id"] for r in records if verdict(r) == "miss"},
        "verdict=shown": {r["id"] for r in records if verdict(r) == "shown"},
        "verdict=notrun": {r["id"] for r in records if verdict(r) == "notrun"},
        "disc=1": {r["id"] for r in records if r.get("discrepancy")},
        "": {r["id"] for r in records},
    }
    for k in ("reproduction", "trend", "consistency", "verification", "shown"):
        expected["kind=" + k] = {r["id"] for r in records if r["kind"] == k}
    for b in ("exact", "model", "reconstructed", "trend", "experiment"):
        expected["basis=" + b] = {r["id"] for r in records if r["basis"] == b}
    seen = set()
    for f in out["filters"]:
        want = expected.get(f["filter"])
        if want is None:
            check(False, f"filter '{f['filter']}' is one the fixture knows")
            continue
        seen.add(f["filter"])
        check(set(f["ids"]) == want and f["rendered"] == len(want),
              f"filter '{f['name']}' ({f['filter'] or 'none'}) shows exactly {sorted(want)}: {sorted(f['ids'])}")
        if f["expected"] is not None:
            check(f["expected"] == len(want), f"the count '{f['name']}' at the top is {len(want)}")
    for needed in ("verdict=fail", "verdict=miss", "disc=1", "kind=reproduction", "basis=reconstructed"):
        check(needed in seen, f"the page offers the filter {needed}")
    check(out["plots"] == 1 and out["plot_points"] == 2,
          f"one plot marks the thesis's two values on our curve ({out['plots']} plots, {out['plot_points']} points)")

    with open(os.path.join(page_dir, "REPORT.md")) as f:
        md = f.read()
    at_peak = 30 * math.sin(math.pi * 5.7 / 12)
    check(f"| fig-9-1/peak | 5.7 | 25.5 | 21.675 .. 29.325 | {at_peak:.6g} | 29.4 | not reproduced |" in md,
          "REPORT.md lists the thesis's point with its band and our curve there (the same model as the page)")
    check("| D | 0.3 \\| 0.2 |" in md, "REPORT.md inlines the regenerated Markdown table")


def page(path, shots):
    out = selftest(path, os.path.join(shots, "REPORT-desktop.png"))
    page_checks(out, os.path.dirname(os.path.abspath(path)))
    screenshot(path, os.path.join(shots, "REPORT-narrow.png"), 420, 900)


if __name__ == "__main__":
    if len(sys.argv) == 5 and sys.argv[1] == "fixture":
        fixture(*sys.argv[2:])
    elif len(sys.argv) == 4 and sys.argv[1] == "page":
        page(*sys.argv[2:])
    else:
        print(__doc__)
        sys.exit(2)
    print(f"{len(failures)} failures" if failures else "all page checks passed")
    sys.exit(1 if failures else 0)
