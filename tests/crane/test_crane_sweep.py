#!/usr/bin/env python3
"""crane-sweep end to end, local engine (TAP).

The sweep file's checks (bad files and command lines: exit 2, a FILE:LINE message naming the
key and what was expected, nothing written); --list (the example's 3 x 3 grid, a range's values,
a Latin-hypercube sample: one value per stratum, the same for the same seed); a grid with a case
the crane refuses (invalid: inconsistent reference times) beside completed ones, its rows in case
order, the figures of completed cases, the heat maps; a case killed at a tiny per-case time limit
(the real crane, mid-run: timeout, its folder's status.txt interrupted); a case that crashes and
one that fails (a stand-in crane program: SIGSEGV, exit 1 with status.txt failed); an
interrupted sweep (SIGINT while its second case runs: exit 130, rows kept, the rest not_run)
completed by --resume (the completed case is kept, not rerun; the result equals an uninterrupted
sweep apart from the times) and a second --resume after a value changed (only that case runs).
Short horizons: about 10 s of CPU.

    test_crane_sweep.py CRANE_SWEEP CRANE SOURCE_ROOT
"""
import csv
import io
import math
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

SWEEP, CRANE, ROOT = sys.argv[1], sys.argv[2], sys.argv[3]
count = 0
failed = 0
TIMES = ("cpu_s", "wall_s")


def ok(cond, name, diag=None):
    global count, failed
    count += 1
    if not cond:
        failed += 1
    print(("ok" if cond else "not ok") + " %d - %s" % (count, name.replace("#", " ")))
    if not cond and diag:
        for line in str(diag).splitlines()[:40]:
            print("# " + line)
    sys.stdout.flush()
    return cond


def run(args, timeout=120, cwd=None):
    """crane-sweep with args; the crane under test unless args name another."""
    if args and "--crane" not in args:
        args = args + ["--crane", CRANE]
    p = subprocess.run([SWEEP] + args, capture_output=True, text=True, timeout=timeout, cwd=cwd)
    return p.returncode, p.stdout, p.stderr


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def strip_times(path):
    """sweep.csv without the time columns, as text."""
    with open(path, newline="") as f:
        r = list(csv.reader(f))
    keep = [i for i, h in enumerate(r[0]) if h not in TIMES]
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    for line in r:
        w.writerow([line[i] for i in keep])
    return out.getvalue()


def field(path, key):
    try:
        with open(path) as f:
            for line in f:
                if line.startswith(key + ":"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return None


def png_whole(path):
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError:
        return False
    return data[:8] == b"\x89PNG\r\n\x1a\n" and data[-8:-4] == b"IEND"


tmp = tempfile.mkdtemp(prefix="test_crane_sweep_")


def write(name, text):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        f.write(text)
    return path


# ------------------------------------------------------------------ the checks ----
BAD = [
    # (text, line, fragments of the message)
    ("[axis]\nkey = controller.kp\nvalues = 1, -1\n", 3,
     ["key 'values' in [axis]", "value 2 of controller.kp", "expected a number >= 0", "'-1'"]),
    ("[axis]\nkey = controller.kpp\nvalues = 1\n", 2,
     ["unknown scene key 'controller.kpp'", "did you mean 'controller.kp'"]),
    ("[axis]\nkey = controller.kp\nvaleus = 1\n", 3, ["unknown key 'valeus' in [axis]", "'values'"]),
    ("[axes]\nkey = controller.kp\n", 1, ["unknown section [axes]", "did you mean [axis]"]),
    ("[axis]\nkey = controller.kp\nfrom = 1\nto = 2\ncount = 0\n", 5,
     ["key 'count' in [axis]", "expected an integer in 1..100000", "'0'"]),
    ("[axis]\nkey = controller.kp\nfrom = 0x10\nto = 2\ncount = 2\n", 3,
     ["key 'from' in [axis]", "expected a decimal number"]),
    ("[axis]\nkey = controller.kp\nvalues = 1\nfrom = 1\n", 4, ["either 'values' (line 3)"]),
    ("[axis]\nkey = boom.elements\nfrom = 1\nto = 4\ncount = 3\n", 5,
     ["boom.elements is an integer key", "2.5"]),
    ("[axis]\nkey = controller.kp\nfrom = 0\nto = 1\ncount = 3\nspacing = log\n", 6,
     ["key 'spacing' in [axis]", "log spacing needs 'from' and 'to' > 0"]),
    ("[sweep]\nscene = no-such-scene\n[axis]\nkey = controller.kp\nvalues = 1\n", 2,
     ["key 'scene' in [sweep]", "not found"]),
    ("[sweep]\nreport = theta_end, omega_max\n[axis]\nkey = controller.kp\nvalues = 1\n", 2,
     ["key 'report' in [sweep]", "'omega_max'", "did you mean 'omega_err_max'"]),
    ("[sweep]\ntime_limit = -1\n[axis]\nkey = controller.kp\nvalues = 1\n", 2,
     ["key 'time_limit' in [sweep]", "expected a number >= 0"]),
    ("[set]\ncontroller.kp = 1\n[axis]\nkey = controller.kp\nvalues = 2\n", 4,
     ["controller.kp is swept here and set in [set] (line 2)"]),
    ("[axis]\nkey = solver.rtol\nvalues = 0.5, 1\n", 3,
     ["value 2 of solver.rtol", "expected a number in (0, 1)"]),
    ("[lhs]\nsamples = 4\ncontroller.kp = 2, 1\n", 3, ["[lhs] controller.kp", "LO < HI"]),
    ("[lhs]\nsamples = 4\nboom.foot = 0, 1\n", 3, ["only number and integer keys"]),
    ("[axis]\nkey = controller.kp\nkey = controller.kd\n", 3,
     ["key 'key' in [axis] given twice (first on line 2)"]),
    ("[sweep]\nname = a b\n", 2, ["key 'name' in [sweep]", "expected a name"]),
    ("; only a comment\n", 0, ["nothing to sweep"]),
]
for i, (text, line, frags) in enumerate(BAD):
    path = write("bad%02d.ini" % i, text)
    out = os.path.join(tmp, "bad_out%02d" % i)
    rc, so, se = run([path, "--out", out])
    where = "%s:%d:" % (path, line) if line else "%s:" % path
    good = rc == 2 and se.startswith(where) and all(f in se for f in frags) \
        and not os.path.exists(out)
    ok(good, "bad sweep file %d (%s): exit 2, %s %s" % (i, frags[0], where.split("/")[-1],
                                                       "nothing written"),
       "rc=%d stderr=%s" % (rc, se))

for args, frag in [([], "no sweep file given"), (["a.ini", "--jobs", "0"], "--jobs"),
                   (["a.ini", "--time-limit", "x"], "--time-limit"),
                   (["a.ini", "--engine", "pvm"], "--engine"), (["a.ini", "--reume"], "--resume"),
                   ([os.path.join(tmp, "none.ini")], "cannot open"),
                   ([tmp], "a directory, not a sweep file")]:
    rc, so, se = run(args)
    ok(rc == 2 and frag in se, "bad command line %s: exit 2 naming %s" % (args, frag),
       "rc=%d stderr=%s" % (rc, se))
rc, so, se = run([os.path.join(ROOT, "crane", "sweeps", "pid-kp-kd.ini"), "--crane",
                  os.path.join(tmp, "no-crane")])
ok(rc == 2 and "crane program was not found" in se, "a missing crane program: exit 2", se)

# ------------------------------------------------------------------ --list ----
rc, so, se = run([os.path.join(ROOT, "crane", "sweeps", "pid-kp-kd.ini"), "--list"])
listed = [line.split(",") for line in so.splitlines() if line and not line.startswith("#")]
expect = [["case", "controller.kp", "controller.kd"]] + \
    [[str(3 * i + j), kp, kd] for i, kp in enumerate(["2.5", "5", "10"])
     for j, kd in enumerate(["25", "50", "100"])]
ok(rc == 0 and listed == expect, "the example crane/sweeps/pid-kp-kd.ini lists 3 x 3 cases "
   "(Kp list x Kd log range, first axis slowest)", so + se)

path = write("range.ini", "[axis]\nkey = controller.ki\nfrom = 0\nto = 0.3\ncount = 4\n"
             "[axis]\nkey = boom.elements\nvalues = 4, 8\n")
rc, so, se = run([path, "--list"])
vals = [line.split(",")[1:] for line in so.splitlines()[2:]]
ok(rc == 0 and vals == [[a, b] for a in ["0", "0.1", "0.2", "0.3"] for b in ["4", "8"]],
   "a range's values are written short (0.1, not 0.1000000000000001), the product in order", so)

lhs = "[lhs]\nsamples = 8\nseed = %d\ncontroller.kp = 0.1, 10, log\ncontroller.kd = 20, 80\n" \
      "boom.elements = 4, 12\n"
outs = []
for seed in (7, 7, 8):
    rc, so, se = run([write("lhs%d.ini" % seed, lhs % seed), "--list"])
    outs.append([line.split(",")[1:] for line in so.splitlines()[2:]])
kp = [float(r[0]) for r in outs[0]]
kd = [float(r[1]) for r in outs[0]]
strata_kp = sorted(int(8 * (math.log(x) - math.log(0.1)) / (math.log(10) - math.log(0.1)))
                   for x in kp)
strata_kd = sorted(int(8 * (x - 20) / 60) for x in kd)
ok(len(outs[0]) == 8 and strata_kp == list(range(8)) and strata_kd == list(range(8))
   and all(r[2].isdigit() and 4 <= int(r[2]) <= 12 for r in outs[0]),
   "Latin hypercube: 8 samples, one in each eighth of each interval (log for kp), integers "
   "rounded", outs[0])
ok(outs[0] == outs[1] and outs[0] != outs[2], "the same seed gives the same sample, another "
   "seed another")

# ------------------------------------------ a grid with a case the crane refuses ----
grid = write("grid.ini", """; a completed case and a case the crane refuses (t1 > t2), twice
[sweep]
name = grid
report = theta_end, defl_side_max, p_high_max, steps, cpu_s, wall_s
[set]
solver.t_end = 0.05
solver.output_step = 0.01
[axis]
key = reference.t1
values = 1, 11
[axis]
key = controller.kp
values = 2.5, 5
""")
out = os.path.join(tmp, "grid")
t0 = time.time()
rc, so, se = run([grid, "--out", out, "--jobs", "2"])
r = rows(os.path.join(out, "sweep.csv")) if os.path.exists(os.path.join(out, "sweep.csv")) else []
ok(rc == 1 and [x["case"] for x in r] == ["0", "1", "2", "3"],
   "grid: exit 1 (a case did not complete), 4 rows in case order (%.1f s)" % (time.time() - t0),
   "rc=%d\n%s%s" % (rc, so, se))
if len(r) == 4:
    ok([x["status"] for x in r] == ["completed", "completed", "invalid", "invalid"]
       and [x["reference.t1"] for x in r] == ["1", "1", "11", "11"]
       and [x["controller.kp"] for x in r] == ["2.5", "5", "2.5", "5"],
       "grid: the rows carry the values; t1 = 11 is recorded as invalid", r)
    ok("t1" in r[2]["message"] and "expected" in r[2]["message"],
       "grid: the invalid row's message is the crane's (%s)" % r[2]["message"][:60])
    good = all(x["message"] == "" and float(x["t_reached"]) == 0.05 and float(x["steps"]) > 0
               and float(x["theta_end"]) > 0 and 1e6 < float(x["p_high_max"]) < 1e8
               and float(x["cpu_s"]) > 0 for x in r[:2])
    ok(good and r[0]["theta_end"] != r[1]["theta_end"] and r[2]["theta_end"] == "",
       "grid: completed rows have their figures (theta_end, defl_side_max, p_high_max, steps, "
       "cpu_s), different for different kp; the invalid row none", r[:3])
    res = rows(os.path.join(out, "cases", "0001", "results.csv"))
    theta = float(res[-1]["theta [rad]"])
    side = max(abs(float(x["tip_defl_2 [m]"])) for x in res)
    ok(abs(theta - float(r[1]["theta_end"])) <= 1e-9 * max(1, abs(theta))
       and abs(side - float(r[1]["defl_side_max"])) <= 1e-9 * max(1, side),
       "grid: the figures are those of the case's results.csv")
st = os.path.join(out, "status.txt")
ok(field(st, "status") == "completed" and field(st, "completed") == "2"
   and field(st, "invalid") == "2" and field(st, "engine") == "local, 2 jobs",
   "grid: the sweep's status.txt: completed, 2 completed, 2 invalid", open(st).read()
   if os.path.exists(st) else "no status.txt")
pngs = ["plot_%s.png" % q for q in ("theta_end", "defl_side_max", "p_high_max", "steps", "cpu_s",
                                     "wall_s")]
ok(all(png_whole(os.path.join(out, p)) for p in pngs)
   and os.path.exists(os.path.join(out, "plots.gp"))
   and "with image" in open(os.path.join(out, "plots.gp")).read(),
   "grid: a heat map per reported quantity (whole PNGs, plots.gp)",
   sorted(os.listdir(out)) if os.path.isdir(out) else "no folder")
case0 = os.path.join(out, "cases", "0000")
ok(all(os.path.exists(os.path.join(case0, f)) for f in
       ("status.txt", "results.csv", "solver_stats.txt", "scene.ini", "model_stats.txt",
        "crane.log", "case.txt"))
   and field(os.path.join(case0, "case.txt"), "status") == "completed"
   and "--set" in (field(os.path.join(case0, "case.txt"), "command") or ""),
   "grid: a case's folder holds the crane's files, its log and case.txt (command, status)")

# ------------------------------------------ a case killed at the time limit ----
tl = write("timelimit.ini", """[sweep]
name = timelimit
report = theta_end, steps, cpu_s
[set]
solver.t_end = 300
solver.output_step = 0.01
[axis]
key = controller.kp
values = 5
""")
out = os.path.join(tmp, "timelimit")
t0 = time.time()
rc, so, se = run([tl, "--out", out, "--time-limit", "0.8", "--no-plots"])
el = time.time() - t0
r = rows(os.path.join(out, "sweep.csv")) if os.path.exists(os.path.join(out, "sweep.csv")) else []
cst = os.path.join(out, "cases", "0000", "status.txt")
ok(rc == 1 and len(r) == 1 and r[0]["status"] == "timeout"
   and "time limit of 0.8 s" in r[0]["message"] and el < 8,
   "a tiny per-case time limit (--time-limit 0.8): the crane is stopped mid-run, the row says "
   "timeout (%.1f s)" % el, "rc=%d %s %s" % (rc, r, se))
ok(field(cst, "status") == "interrupted" and "SIGTERM" in (field(cst, "reason") or ""),
   "the stopped case's own status.txt says interrupted (SIGTERM)", field(cst, "reason"))

# ------------------------------------------ crashed and failed cases ----
fake = write("fake-crane", """#!/bin/sh
# stands in for the crane: kp = 7 crashes (SIGSEGV), kp = 8 fails (exit 1, status.txt failed)
out=""; prev=""
for a in "$@"; do
  [ "$prev" = "--out" ] && out="$a"
  [ "$a" = "controller.kp=7" ] && kill -SEGV $$
  if [ "$a" = "controller.kp=8" ]; then
    mkdir -p "$out"
    printf 'status: failed\\nreason: solver: a stand-in failure at t = 0.01 s\\nt_reached: 0.01 s\\n' \\
      > "$out/status.txt"
    exit 1
  fi
  prev="$a"
done
exec "%s" "$@"
""" % CRANE)
os.chmod(fake, 0o755)
cr = write("crash.ini", """[sweep]
name = crash
report = theta_end, steps, cpu_s
[set]
solver.t_end = 0.05
solver.output_step = 0.01
[axis]
key = controller.kp
values = 5, 7, 8
""")
out = os.path.join(tmp, "crash")
rc, so, se = run([cr, "--out", out, "--crane", fake, "--jobs", "3"])
r = rows(os.path.join(out, "sweep.csv")) if os.path.exists(os.path.join(out, "sweep.csv")) else []
ok(rc == 1 and [x["status"] for x in r] == ["completed", "crashed", "failed"],
   "a crashing case (SIGSEGV) and a failing one (exit 1) are rows; the others complete",
   "rc=%d %s %s" % (rc, r, se))
if len(r) == 3:
    ok("SIGSEGV" in r[1]["message"] and "stand-in failure" in r[2]["message"]
       and r[2]["t_reached"] == "0.01",
       "their messages: the signal; status.txt's reason and t_reached", r[1:])
ok(png_whole(os.path.join(out, "plot_theta_end.png"))
   and "with linespoints" in open(os.path.join(out, "plots.gp")).read(),
   "a 1-D sweep draws line plots")

# ------------------------------------------ interrupted, then --resume ----
# the paper scene's full 20 s (some 0.5 s of CPU a case): SIGINT comes while case 1 runs
text = """[sweep]
name = resume
[set]
solver.t_end = 20
solver.output_step = 0.01
[axis]
key = controller.kp
values = %s
"""
rs = write("resume.ini", text % "1, 2, 3, 4")
out = os.path.join(tmp, "resume")
csvp = os.path.join(out, "sweep.csv")
p = subprocess.Popen([SWEEP, rs, "--out", out, "--jobs", "1", "--no-plots", "--crane", CRANE],
                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
t0 = time.time()
seen = 0
while time.time() - t0 < 60 and p.poll() is None:
    try:
        with open(csvp) as f:
            seen = len(f.read().splitlines())
    except OSError:
        seen = 0
    if seen >= 2:
        break
    time.sleep(0.02)
first_row_early = seen >= 2 and p.poll() is None
time.sleep(0.1)
p.send_signal(signal.SIGINT)
so, se = p.communicate(timeout=60)
r = rows(csvp) if os.path.exists(csvp) else []
st = [x["status"] for x in r]
ok(first_row_early, "rows are written as the cases finish (case 0's row while case 1 runs)")
ok(p.returncode == 130 and len(r) == 4 and st[0] == "completed" and "not_run" in st
   and field(os.path.join(out, "status.txt"), "status") == "interrupted",
   "SIGINT: exit 130, status interrupted, every case a row (%s)" % ", ".join(st),
   "rc=%s\n%s%s" % (p.returncode, so, se))
started0 = field(os.path.join(out, "cases", "0000", "case.txt"), "started")
pid0 = field(os.path.join(out, "cases", "0000", "status.txt"), "pid")
rc, so, se = run([rs, "--out", out, "--resume", "--jobs", "2", "--no-plots"])
r = rows(csvp) if os.path.exists(csvp) else []
ok(rc == 0 and [x["status"] for x in r] == ["completed"] * 4
   and field(os.path.join(out, "status.txt"), "status") == "completed"
   and "1 cases completed earlier are kept, 3 to run" in so,
   "--resume completes the sweep: 1 case kept, 3 run, all completed", so + se)
ok(field(os.path.join(out, "cases", "0000", "case.txt"), "started") == started0
   and field(os.path.join(out, "cases", "0000", "status.txt"), "pid") == pid0
   and r and r[0]["cpu_s"] != "",
   "--resume did not rerun the completed case (its case.txt and status.txt unchanged, its CPU "
   "time kept)")
ref = os.path.join(tmp, "resume-ref")
rc2, so2, se2 = run([rs, "--out", ref, "--jobs", "2", "--no-plots", "--quiet"])
ok(rc2 == 0 and os.path.exists(csvp) and strip_times(csvp) == strip_times(os.path.join(ref,
                                                                                      "sweep.csv")),
   "the resumed sweep.csv equals an uninterrupted sweep's apart from the times",
   so2 + se2)
write("resume.ini", text % "1, 2, 3, 5")
rc, so, se = run([rs, "--out", out, "--resume", "--no-plots"])
r = rows(csvp) if os.path.exists(csvp) else []
ok(rc == 0 and "3 cases completed earlier are kept, 1 to run" in so
   and [x["controller.kp"] for x in r] == ["1", "2", "3", "5"],
   "--resume after a value changed runs that case again (its scene.ini differs)", so + se)

shutil.rmtree(tmp, ignore_errors=True)
print("1..%d" % count)
sys.exit(1 if failed else 0)
