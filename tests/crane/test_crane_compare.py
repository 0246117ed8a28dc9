#!/usr/bin/env python3
"""crane-compare end to end (TAP), on a shortened manoeuvre.

Three controllers of crane/models/crane-control.yaml (pid, zv, lqr) over the first 24 s, the
shapers at a given frequency (--shaper-frequency: no modes run): comparison.csv has one row per
controller with the columns the program documents; its metrics are recomputed here from each
controller's results.csv by their definitions (docs/control.md): the largest angle error and the
rms rate error while the reference moves, the load's largest distance from rest after the
reference stops, the largest side deflection, the largest pressure, the pump's energy (the
trapezoidal rule over max(power, 0)); the ZV controller's reference ends later by half the
shaper's period 1 / (2 f); comparison.md has a row per controller; bad options are refused with
exit status 2 and nothing run.

    test_crane_compare.py CRANE_COMPARE_EXECUTABLE
"""
import csv
import math
import os
import shutil
import subprocess
import sys
import tempfile

EXE = sys.argv[1]
count = 0
failed = 0


def ok(cond, name, diag=None):
    global count, failed
    count += 1
    if not cond:
        failed += 1
    print(("ok" if cond else "not ok") + " %d - %s" % (count, name.replace("#", " ")))
    if not cond and diag:
        for line in str(diag).splitlines():
            print("# " + line)
    sys.stdout.flush()
    return cond


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def metrics(res):
    """the definitions, from a run's results.csv"""
    t = [float(r["t"]) for r in res]
    moving = [i for i, r in enumerate(res) if abs(float(r["omega_ref"])) > 1e-12]
    stop = min(moving[-1] + 1, len(res) - 1)
    m = {"t_ref_end": t[stop]}
    m["theta_err_max"] = max(abs(float(r["theta"]) - float(r["theta_ref"])) for r in res[: stop + 1])
    sq = 0
    for i in range(stop):
        e0 = float(res[i]["omega"]) - float(res[i]["omega_ref"])
        e1 = float(res[i + 1]["omega"]) - float(res[i + 1]["omega_ref"])
        sq += 0.5 * (t[i + 1] - t[i]) * (e0 * e0 + e1 * e1)
    m["omega_err_rms"] = math.sqrt(sq / (t[stop] - t[0]))
    m["sway_residual_m"] = max([float(r["sway_distance"]) for r in res[stop + 1:]] or [0])
    m["defl_side_max"] = max(abs(float(r["tip_defl_2"])) for r in res)
    m["p_max"] = max(max(float(r["p_high"]), float(r["p_low"])) for r in res)
    pw = [max(float(r["pump_power"]), 0) for r in res]
    m["energy_j"] = sum(0.5 * (t[i + 1] - t[i]) * (pw[i] + pw[i + 1]) for i in range(len(t) - 1))
    return m


def main():
    tmp = tempfile.mkdtemp(prefix="crane_compare_")
    try:
        out = os.path.join(tmp, "cmp")
        f = 0.0572
        p = subprocess.run([EXE, "--out", out, "--t-end", "24", "--output-step", "0.05",
                            "--controllers", "pid,zv,lqr", "--shaper-frequency", str(f),
                            "--no-plots", "--quiet"], capture_output=True, text=True)
        ok(p.returncode == 0, "crane-compare on 3 controllers, 24 s: exit 0",
           p.stdout + p.stderr)
        tab = rows(os.path.join(out, "comparison.csv"))
        names = [r["controller"] for r in tab]
        ok(names == ["pid", "zv", "lqr"] and all(r["status"] == "completed" for r in tab),
           "comparison.csv: one completed row per controller, in order (%s)" % names)
        need = ["controller", "theta_err_max", "omega_err_rms", "sway_residual_m",
                "sway_settle_s", "defl_side_max", "p_max", "energy_j", "x_max"]
        ok(all(k in tab[0] for k in need), "comparison.csv has the columns " + ", ".join(need),
           list(tab[0].keys()))
        for r in tab:
            res = rows(os.path.join(out, r["controller"], "results.csv"))
            m = metrics(res)
            worst = max(abs(float(r[k]) - v) / max(abs(v), 1e-12) for k, v in m.items())
            ok(worst < 1e-5, "%s: the metrics recomputed from its results.csv agree (largest "
               "relative difference %.1e)" % (r["controller"], worst),
               {k: (r[k], v) for k, v in m.items()})
        pid, zv = tab[0], tab[1]
        ok(abs(float(pid["t_ref_end"]) - 12) < 1e-9 and
           abs(float(zv["t_ref_end"]) - (12 + 1 / (2 * f))) < 0.05 + 1e-9,
           "the reference stops at 12 s, the ZV-shaped one half a period later: %s s "
           "(12 + 1 / (2 f) = %.2f s)" % (zv["t_ref_end"], 12 + 1 / (2 * f)))
        with open(os.path.join(out, "comparison.md")) as fm:
            md = fm.read()
        ok(all("| %s |" % n in md for n in names), "comparison.md has a row per controller")
        p = subprocess.run([EXE, "--out", os.path.join(tmp, "bad"), "--controllers", "pid,foo"],
                           capture_output=True, text=True)
        ok(p.returncode == 2 and "'foo' is no controller" in p.stderr and
           not os.path.exists(os.path.join(tmp, "bad")),
           "an unknown controller: exit 2, named, nothing written", p.stderr)
        p = subprocess.run([EXE, "no-such-model.yaml"], capture_output=True, text=True)
        ok(p.returncode == 2 and "no-such-model.yaml" in p.stderr,
           "a missing model file: exit 2, named", p.stderr)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print("1..%d" % count)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
