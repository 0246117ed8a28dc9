#!/usr/bin/env python3
"""crane-sweep over a model file's parameters (TAP): each case a bgsim run.

A mass-spring model written here (bg.I mass m, bg.C stiffness k on a 1-junction, started at
x = 0 with momentum p0): x(t) = A sin(w t), w = sqrt(k/m), A = p0/(m w). Its stiffness k is swept
over 3 values with m replaced in [set], and the summary quantities of sweep.csv, computed by
crane-sweep from each case's results.csv, are checked against the closed form per case:
max(x) = A, min(x) = -A, end(x) = A sin(w T), rms(x) = A sqrt((1 - sin(2 w T)/(2 w T))/2),
mean(abs(x)) = A (2 n + 1 - cos(w T - n pi))/(w T) with n = floor(w T/pi) (|sin| integrated
over the whole half-waves and the last part of one); and the period found from results.csv's
zero crossings against 2 pi sqrt(m/k). Bad sweep files are refused at --list with the file's position (exit 2,
nothing run): an axis naming no parameter of the model, a value out of the model's range (the
model reader's FILE:LINE:COL), a quantity of a column the model has not, an unknown function.
--resume keeps the completed cases. The MPI engine once (mpirun -n 2: the same sweep.csv apart
from the times) when crane-sweep was built with MPI and mpirun is there.

    test_crane_sweep_model.py CRANE_SWEEP BGSIM mpi|no-mpi
"""
import csv
import io
import math
import os
import shutil
import subprocess
import sys
import tempfile

SWEEP, BGSIM, BUILT = sys.argv[1:4]
count = 0
failed = 0


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


def run(args, timeout=120, prefix=None, env=None):
    cmd = (prefix or []) + [SWEEP] + args + ["--bgsim", BGSIM]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env)
    return p.returncode, p.stdout, p.stderr


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def strip_times(path):
    with open(path, newline="") as f:
        r = list(csv.reader(f))
    keep = [i for i, h in enumerate(r[0]) if h not in ("cpu_s", "wall_s")]
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    for line in r:
        w.writerow([line[i] for i in keep])
    return out.getvalue()


def rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


tmp = tempfile.mkdtemp(prefix="test_crane_sweep_model_")
M, P0, T = 4.5, 0.5, 2.5
KS = (200.0, 800.0, 3200.0)
with open(os.path.join(tmp, "ms.yaml"), "w") as f:
    f.write("""format: bgsim 1
name: mass-spring
parameters: {m: 2.0, k: 800.0, p0: %g}
components:
  j: {type: bg.one, ports: [a, b]}
  mass: {type: bg.I, mass: m}
  spring: {type: bg.C, stiffness: k}
bonds:
  - j.a -> mass.p
  - j.b -> spring.p
initial: {mass.p: p0}
outputs:
  x: spring.q
solver: {t_end: 5, output_step: 0.0005, rtol: 1e-10, atol: 1e-12}
""" % P0)
os.makedirs(os.path.join(tmp, "sweeps"))
good = os.path.join(tmp, "sweeps", "k.ini")
with open(good, "w") as f:
    f.write("""; the stiffness over 3 values, the mass replaced for every case
[sweep]
model = ../ms.yaml
t_end = %g
quantities = max(x), min(x), end(x), rms(x), mean(abs(x)), maxabs(x), steps
[set]
m = %g
[axis]
key = k
values = %s
""" % (T, M, ", ".join("%g" % k for k in KS)))

# --list: the cases, nothing run
rc, out, err = run([good, "--list"])
ok(rc == 0 and "3 cases of the model" in out and out.strip().splitlines()[1:] ==
   ["case,k", "0,200", "1,800", "2,3200"], "--list: 3 cases of the model", out + err)

# the sweep, local engine
local = os.path.join(tmp, "local")
rc, out, err = run([good, "--out", local, "--jobs", "2", "--no-plots"])
ok(rc == 0, "local engine: 3 cases completed, exit 0", out + err)
rs = rows(os.path.join(local, "sweep.csv"))
ok([r["status"] for r in rs] == ["completed"] * 3 and [r["k"] for r in rs] == ["200", "800", "3200"],
   "sweep.csv: a row per case in order, completed", rs)
for r, k in zip(rs, KS):
    w = math.sqrt(k / M)
    a = P0 / (M * w)
    wt = w * T
    rms = a * math.sqrt((1 - math.sin(2 * wt) / (2 * wt)) / 2)
    nh = math.floor(wt / math.pi)  # whole half-waves in [0, T]
    mabs = a / wt * (2 * nh + 1 - math.cos(wt - nh * math.pi))
    got = {q: float(r[q]) for q in ("max(x)", "min(x)", "end(x)", "rms(x)", "mean(abs(x))",
                                    "maxabs(x)")}
    # output step 0.5 ms: a peak sampled within (w dt)^2/8 = 2e-4 of A at w = 26.7; the
    # trapezoidal rule's rms and mean within (w dt)^2/12
    ok(rel(got["max(x)"], a) < 1e-3 and rel(got["min(x)"], -a) < 1e-3 and
       rel(got["maxabs(x)"], a) < 1e-3,
       "k = %g: max(x) %.9g, min(x), maxabs(x) = A = p0/sqrt(k m) = %.9g" % (k, got["max(x)"], a),
       got)
    ok(abs(got["end(x)"] - a * math.sin(wt)) < 1e-6 * a,
       "k = %g: end(x) %.9g = A sin(w T) = %.9g" % (k, got["end(x)"], a * math.sin(wt)))
    ok(rel(got["rms(x)"], rms) < 1e-4 and rel(got["mean(abs(x))"], mabs) < 1e-4,
       "k = %g: rms(x) %.9g (closed form %.9g), mean(abs(x)) %.9g (%.9g)"
       % (k, got["rms(x)"], rms, got["mean(abs(x))"], mabs))
    # the period from the case's results.csv: twice the mean spacing of the zero crossings
    # after t = 0, each linearly interpolated between its two rows
    case = os.path.join(local, "cases", "%04d" % int(r["case"]), "results.csv")
    with open(case, newline="") as f:
        data = [(float(x["t"]), float(x["x"])) for x in csv.DictReader(f)]
    zc = [t0 - x0 * (t1 - t0) / (x1 - x0) for (t0, x0), (t1, x1) in zip(data[1:], data[2:])
          if (x0 < 0) != (x1 < 0)]
    period = 2 * (zc[-1] - zc[0]) / (len(zc) - 1) if len(zc) > 1 else float("nan")
    ok(rel(period, 2 * math.pi / w) < 1e-5,
       "k = %g: period from results.csv %.9g s = 2 pi sqrt(m/k) = %.9g s (%d crossings)"
       % (k, period, 2 * math.pi / w, len(zc)))
ok("--set m=4.5 --set k=800" in (open(os.path.join(local, "cases", "0001", "case.txt")).read())
   and "--t-end 2.5 " in open(os.path.join(local, "cases", "0001", "case.txt")).read(),
   "case.txt: bgsim with --t-end and --set for [set] and the swept value")

# --resume: every case kept
rc, out, err = run([good, "--out", local, "--resume", "--no-plots"])
ok(rc == 0 and "3 cases completed earlier are kept, 0 to run" in out and
   strip_times(os.path.join(local, "sweep.csv")).count("completed") == 3,
   "--resume: the 3 completed cases kept, none run", out + err)


# refused at --list: exit 2, FILE:LINE, nothing written
def bad(name, text, want, what):
    path = os.path.join(tmp, "sweeps", name)
    with open(path, "w") as f:
        f.write(text)
    outdir = os.path.join(tmp, "bad_" + name)
    rc, out, err = run([path, "--list", "--out", outdir])
    ok(rc == 2 and all(w in err for w in want) and not os.path.exists(outdir),
       "refused at --list: %s" % what, "rc %d\n%s%s" % (rc, out, err))


bad("name.ini", "[sweep]\nmodel = ../ms.yaml\n[axis]\nkey = kk\nvalues = 1, 2\n",
    [os.path.join(tmp, "sweeps", "name.ini") + ":5: ", "of kk", "no parameter 'kk'",
     "did you mean 'k'"], "an axis naming no parameter of the model, the file's line")
bad("value.ini", "[sweep]\nmodel = ../ms.yaml\n[axis]\nkey = spring.stiffness\nvalues = 1, -2\n",
    ["value.ini:5: ", "value 2 of spring.stiffness", "ms.yaml:7:", "out of range"],
    "a value out of the model's range, the model reader's FILE:LINE:COL")
bad("path.ini", "[sweep]\nmodel = ../ms.yaml\n[set]\nspring.stifness = 3\n[axis]\nkey = m\n"
    "values = 1\n", ["path.ini:4: [set] spring.stifness", "names no parameter"],
    "[set] naming no component parameter")
bad("column.ini", "[sweep]\nmodel = ../ms.yaml\nquantities = max(abs(y))\n[axis]\nkey = k\n"
    "values = 1\n", ["column.ini:3: ", "no output 'y'", "t, x"],
    "a quantity of a column the model has not")
bad("func.ini", "[sweep]\nmodel = ../ms.yaml\nquantities = median(x)\n[axis]\nkey = k\n"
    "values = 1\n", ["func.ini:3: ", "unknown function 'median'"], "an unknown function")
bad("both.ini", "[sweep]\nmodel = ../ms.yaml\nreport = steps\n[axis]\nkey = k\nvalues = 1\n",
    ["both.ini:3: ", "quantities"], "report (a scene's) in a model sweep")

# the MPI engine once
mpirun = shutil.which("mpirun") or shutil.which("mpiexec")
if BUILT != "mpi" or not mpirun:
    count += 1
    print("ok %d - MPI engine # SKIP crane-sweep built without MPI or mpirun missing" % count)
else:
    env = dict(os.environ)
    env.update({"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
                "OMPI_MCA_btl_vader_single_copy_mechanism": "none", "OMP_NUM_THREADS": "1"})
    if "ASAN_OPTIONS" in env:  # Open MPI's own allocations (test_crane_sweep_mpi.py)
        env["ASAN_OPTIONS"] += ":detect_leaks=0"
    mpi = os.path.join(tmp, "mpi")
    rc, out, err = run([good, "--out", mpi, "--no-plots"], timeout=240,
                       prefix=[mpirun, "--oversubscribe", "-n", "2"], env=env)
    ok(rc == 0 and strip_times(os.path.join(mpi, "sweep.csv")) ==
       strip_times(os.path.join(local, "sweep.csv")),
       "mpirun -n 2: the local engine's sweep.csv apart from the times", out + err)

print("1..%d" % count)
if failed == 0:
    shutil.rmtree(tmp, ignore_errors=True)
sys.exit(1 if failed else 0)
