#!/usr/bin/env python3
"""crane-sweep under faults and hostile input (TAP).

- a sweep killed by SIGKILL whose crane keeps running: --resume leaves that case's folder to it
  (row not_run naming its pid; its status.txt and process untouched) and, once it has ended,
  runs the case afresh (its figures from the new run: t_reached is the new t_end);
- a case's crane.log linked to /dev/full, its status.txt to /dev/zero, the sweep's status.txt to
  /dev/zero: the sweep ends (it read only regular files), replaces the links and answers SIGTERM;
- an axis of 100000 values: --list prints them, a SIGTERM meanwhile ends it at once, a repeat
  in such a range or in a list (also '1' against '1.0') is found and named;
- a full disk (a 64 kB tmpfs, when it can be mounted): the rows say the disk is full, not
  crashed, and status.txt is final; a file size limit (RLIMIT_FSIZE) is named as such;
- messages: --crane naming a folder or a file without execute bit, a case folder that is a
  file, a symbolic link loop as the sweep file, its scene or its model;
- the sweep file's numbers at their limits: a range whose ends' difference or ratio overflows;
  NaN, Inf, 1e999, negative, non-integer and too large counts, seeds and intervals, too many
  cases, a FIFO or a 2 MB file as the sweep file, bad --time-limit, --jobs and --out.

    test_crane_sweep_faults.py CRANE_SWEEP CRANE SOURCE_ROOT
"""
import csv
import os
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time

SWEEP, CRANE, ROOT = sys.argv[1], sys.argv[2], sys.argv[3]
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


def skip(name, why):
    global count
    count += 1
    print("ok %d - %s # SKIP %s" % (count, name, why))


def run(args, timeout=120, **kw):
    if args and "--crane" not in args:
        args = args + ["--crane", CRANE]
    try:
        p = subprocess.run([SWEEP] + args, capture_output=True, text=True, timeout=timeout, **kw)
    except subprocess.TimeoutExpired as e:
        return None, str(e.stdout or ""), "timed out after %s s" % timeout
    return p.returncode, p.stdout, p.stderr


def rows(path):
    try:
        with open(path, newline="") as f:
            return list(csv.DictReader(f))
    except OSError:
        return []


def field(path, key):
    try:
        with open(path) as f:
            for line in f:
                if line.startswith(key + ":"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return None


def alive(pid):
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def wait_gone(pid, limit):
    t0 = time.time()
    while alive(pid) and time.time() - t0 < limit:
        time.sleep(0.05)
    return not alive(pid)


tmp = tempfile.mkdtemp(prefix="test_crane_sweep_faults_")


def write(name, text):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        f.write(text)
    return path


ONE = """[sweep]
name = %s
[set]
solver.t_end = %s
solver.output_step = 0.01
[axis]
key = controller.kp
values = 5
"""

# ------------------------------------------- a crane left running by a killed sweep ----
sw = write("orphan.ini", ONE % ("orphan", "300"))
out = os.path.join(tmp, "orphan")
case = os.path.join(out, "cases", "0000")
p = subprocess.Popen([SWEEP, sw, "--out", out, "--no-plots", "--crane", CRANE],
                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
t0 = time.time()
pid = None
while time.time() - t0 < 30:
    if field(os.path.join(case, "status.txt"), "status") == "running":
        v = field(os.path.join(case, "status.txt"), "pid")
        pid = int(v) if v and v.isdigit() else None
        if pid:
            break
    time.sleep(0.05)
p.kill()  # SIGKILL: the sweep ends, its crane goes on
p.wait()
ok(pid is not None and alive(pid), "the sweep killed by SIGKILL leaves its crane running",
   "pid %s" % pid)
if pid:
    # --time-limit: a second crane started in the folder (the defect) is stopped soon
    rc, so, se = run([sw, "--out", out, "--resume", "--no-plots", "--time-limit", "3"])
    r = rows(os.path.join(out, "sweep.csv"))
    ok(rc == 1 and len(r) == 1 and r[0]["status"] == "not_run"
       and "pid %d" % pid in r[0]["message"] and "in use" in r[0]["message"],
       "--resume while that crane runs: the case is not run, its row names the running crane",
       "rc=%s %s %s" % (rc, r, se))
    ok(alive(pid) and field(os.path.join(case, "status.txt"), "status") == "running"
       and field(os.path.join(case, "status.txt"), "pid") == str(pid),
       "the running crane and its status.txt are left alone")
    os.kill(pid, signal.SIGTERM)
    ok(wait_gone(pid, 30), "the crane stops at SIGTERM")
    # once it has ended, a resume (now t_end 0.05) runs the case and reads the new results
    write("orphan.ini", ONE % ("orphan", "0.05"))
    rc, so, se = run([sw, "--out", out, "--resume", "--no-plots"])
    r = rows(os.path.join(out, "sweep.csv"))
    res = rows(os.path.join(case, "results.csv"))
    ok(rc == 0 and len(r) == 1 and r[0]["status"] == "completed"
       and float(r[0]["t_reached"]) == 0.05 and len(res) == 6
       and abs(float(res[-1]["theta [rad]"]) - float(r[0]["theta_end"])) < 1e-9,
       "after it ended, --resume runs the case: its figures are the new run's (t = 0.05 s, "
       "6 rows)", "rc=%s %s %s" % (rc, r, se))

# ------------------------------------ files linked to devices that never end ----
sw = write("dev.ini", (ONE % ("dev", "0.02")).replace("values = 5", "values = 5, 6"))
out = os.path.join(tmp, "dev")
for c in ("0000", "0001"):
    os.makedirs(os.path.join(out, "cases", c))
os.symlink("/dev/full", os.path.join(out, "cases", "0000", "crane.log"))
os.symlink("/dev/zero", os.path.join(out, "cases", "0001", "status.txt"))
os.symlink("/dev/zero", os.path.join(out, "status.txt"))
p = subprocess.Popen([SWEEP, sw, "--out", out, "--resume", "--no-plots", "--jobs", "1",
                      "--crane", CRANE], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
try:
    so, se = p.communicate(timeout=60)
    hung = False
except subprocess.TimeoutExpired:
    hung = True
    p.send_signal(signal.SIGTERM)
    try:
        so, se = p.communicate(timeout=10)
        term = "ended at SIGTERM"
    except subprocess.TimeoutExpired:
        p.kill()
        so, se = p.communicate()
        term = "ignored SIGTERM"
r = rows(os.path.join(out, "sweep.csv"))
ok(not hung and p.returncode == 0 and [x["status"] for x in r] == ["completed"] * 2,
   "crane.log -> /dev/full, status.txt -> /dev/zero: the sweep ends, both cases completed",
   "hung (%s)" % term if hung else "rc=%s %s %s" % (p.returncode, r, se))
ok(not os.path.islink(os.path.join(out, "cases", "0000", "crane.log"))
   and field(os.path.join(out, "status.txt"), "status") == "completed",
   "the links are replaced by the sweep's own files")

# ------------------------------------------------------- 100000 values on an axis ----
big = write("big.ini", "[axis]\nkey = controller.kp\nfrom = 1\nto = 2\ncount = 100000\n")
rc, so, se = run([big, "--list"], timeout=240)
lines = so.splitlines()
ok(rc == 0 and len(lines) == 100002 and lines[-1] == "99999,2" and lines[2] == "0,1",
   "an axis of 100000 values: --list prints them all", "rc=%s %s" % (rc, se[:300]))
p = subprocess.Popen([SWEEP, big, "--list"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
time.sleep(0.3)
p.send_signal(signal.SIGTERM)
try:
    p.wait(timeout=5)
    ended = True
except subprocess.TimeoutExpired:
    p.kill()
    p.wait()
    ended = False
ok(ended and p.returncode in (0, -signal.SIGTERM),
   "SIGTERM while the sweep file is read: it ends at once (exit %s)" % p.returncode)
dup = write("dup.ini", "[axis]\nkey = controller.kp\nfrom = 1\nto = 1.0000001\ncount = 100000\n")
rc, so, se = run([dup, "--list"], timeout=240)
ok(rc == 2 and "dup.ini:5:" in se and "gives the value 1 twice (values 1 and 2" in se,
   "a repeat in a range of 100000 values is found (12 digits: 1, 1, ...)", se)
for text, frag in [("3, 1, 2, 1, 3", "value 4 of controller.kp ('1') repeats value 2"),
                   ("1, 2, 1.0", "value 3 of controller.kp ('1.0') repeats value 1 ('1')"),
                   ("0, -0", "value 2 of controller.kp ('-0') repeats value 1")]:
    rc, so, se = run([write("dupl.ini", "[axis]\nkey = controller.kp\nvalues = %s\n" % text),
                      "--list"])
    ok(rc == 2 and frag in se, "values = %s: the first repeat is named" % text, se)

# ----------------------------------------------------------------- a full disk ----
mnt = os.path.join(tmp, "mnt")
os.makedirs(mnt)
mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", mnt],
                         capture_output=True).returncode == 0 if os.geteuid() == 0 else False
full = write("full.ini", ONE.replace("values = 5", "values = 5, 6").replace(
    "output_step = 0.01", "output_step = 0.001") % ("full", "0.5"))
if mounted:
    try:
        out = os.path.join(mnt, "out")
        rc, so, se = run([full, "--out", out, "--no-plots", "--jobs", "1"], timeout=120)
        st = field(os.path.join(out, "status.txt"), "status")
        msgs = [line for line in so.splitlines() if line.startswith("[")]
        ok(rc == 1 and st in ("completed", "failed") and len(msgs) == 2
           and all("failed: the disk is full" in m for m in msgs)
           and not any("crashed" in m for m in msgs),
           "a full disk (64 kB tmpfs): status.txt is final (%s), the rows say the disk is full"
           % st, "rc=%s\n%s%s" % (rc, so, se))
        r = rows(os.path.join(out, "sweep.csv"))
        ok(not r or all(x["status"] == "failed" and "disk is full" in x["message"] for x in r),
           "sweep.csv (rewritten in place) holds whole rows", r)
    finally:
        subprocess.run(["umount", mnt], capture_output=True)
else:
    skip("a full disk (64 kB tmpfs)", "tmpfs cannot be mounted here")
    skip("sweep.csv on a full disk", "tmpfs cannot be mounted here")


def fsize_limit():
    resource.setrlimit(resource.RLIMIT_FSIZE, (20000, 20000))


out = os.path.join(tmp, "fsize")
rc, so, se = run([full, "--out", out, "--no-plots", "--jobs", "1"], preexec_fn=fsize_limit)
r = rows(os.path.join(out, "sweep.csv"))
ok(rc == 1 and len(r) == 2 and all(x["status"] == "failed" and "file size limit" in x["message"]
                                   for x in r),
   "a file size limit (RLIMIT_FSIZE 20 kB, SIGXFSZ): the rows say so, not crashed",
   "rc=%s %s %s" % (rc, r, se))

# ---------------------------------------------------------------------- messages ----
sw = write("msg.ini", ONE % ("msg", "0.02"))
noexec = write("noexec", "#!/bin/sh\n")
for crane, frag in [(tmp, "is a directory"), (noexec, "not executable")]:
    rc, so, se = run([sw, "--out", os.path.join(tmp, "msg"), "--crane", crane])
    ok(rc == 2 and frag in se and "not found" not in se,
       "--crane %s: says %s" % ("a folder" if crane == tmp else "noexec", frag), se)
out = os.path.join(tmp, "casefile")
os.makedirs(os.path.join(out, "cases"))
write("casefile/cases/0000", "a file where the case's folder goes\n")
rc, so, se = run([sw, "--out", out, "--no-plots"])
r = rows(os.path.join(out, "sweep.csv"))
ok(rc == 1 and len(r) == 1 and r[0]["status"] == "failed"
   and "is a regular file, not a folder" in r[0]["message"]
   and "No such file" not in r[0]["message"],
   "a case folder that is a file: the row says so", "rc=%s %s %s" % (rc, r, se))
loop1, loop2 = os.path.join(tmp, "loop1"), os.path.join(tmp, "loop2")
os.symlink(loop2, loop1)
os.symlink(loop1, loop2)
rc, so, se = run([loop1, "--list"])
ok(rc == 2 and "Too many levels of symbolic links" in se, "a symbolic link loop as the sweep file "
   "is named as such", se)
for key, extra in [("scene", "[axis]\nkey = controller.kp\nvalues = 1\n"),
                   ("model", "[axis]\nkey = k\nvalues = 1\n")]:
    rc, so, se = run([write("loop-%s.ini" % key, "[sweep]\n%s = %s\n%s" % (key, loop1, extra)),
                      "--list"])
    ok(rc == 2 and "Too many levels of symbolic links" in se and "not found" not in se,
       "a symbolic link loop as the %s: named as such, not 'not found'" % key, se)

# ---------------------------------------------------- numbers at their limits ----
for text, want in [("from = -1e308\nto = 1e308\ncount = 3\n", ["-1e+308", "0", "1e+308"]),
                   ("from = 1e-300\nto = 1e300\ncount = 3\nspacing = log\n",
                    ["1e-300", "1", "1e+300"])]:
    rc, so, se = run([write("huge.ini", "[axis]\nkey = reference.rate\n" + text), "--list"])
    vals = [line.split(",")[1] for line in so.splitlines()[2:]]
    ok(rc == 0 and vals == want, "a range %s: finite values %s (the ends' %s overflows)"
       % (text.replace("\n", " ").strip(), ", ".join(want),
          "ratio" if "log" in text else "difference"), "rc=%s %s %s" % (rc, so, se))
rc, so, se = run([write("rep.ini", "[sweep]\nreport =\n[axis]\nkey = controller.kp\nvalues = 1\n"),
                  "--list"])
ok(rc == 2 and "quantity 1 is empty" in se, "an empty report: 'quantity 1 is empty'", se)

# the sweep file's numbers and the command line's, refused with the key and the value (these
# were right before; kept here so that they stay so)
AX = "[axis]\nkey = controller.kp\n"
LIMITS = [
    ("[sweep]\ntime_limit = nan\n" + AX + "values = 1\n", 2, "got 'nan'"),
    ("[sweep]\ntime_limit = inf\n" + AX + "values = 1\n", 2, "got 'inf'"),
    (AX + "values = 1, nan\n", 3, "got 'nan'"),
    (AX + "values = inf\n", 3, "got 'inf'"),
    (AX + "values = 1e999\n", 3, "got '1e999'"),
    (AX + "from = nan\nto = 1\ncount = 2\n", 3, "key 'from' in [axis]"),
    (AX + "from = 0\nto = inf\ncount = 2\n", 4, "key 'to' in [axis]"),
    (AX + "from = 1\nto = 2\ncount = -3\n", 5, "expected an integer in 1..100000, got '-3'"),
    (AX + "from = 1\nto = 2\ncount = 1e3\n", 5, "got '1e3'"),
    (AX + "from = 1\nto = 2\ncount = 100001\n", 5, "got '100001'"),
    ("[axis]\nkey = boom.elements\nfrom = -1e300\nto = 1e300\ncount = 3\n", 3,
     "expected an integer in 0..512"),
    ("[axis]\nkey = platform.joint_A\nvalues = 0,0,0 | 0,0,nan\n", 3, "three finite numbers"),
    ("[lhs]\nsamples = 3\nseed = -1\ncontroller.kp = 1, 2\n", 3, "key 'seed' in [lhs]"),
    ("[lhs]\nsamples = 3\ncontroller.kp = nan, 2\n", 3, "got 'nan, 2'"),
    ("[lhs]\nsamples = 3\ncontroller.kp = 0, inf\n", 3, "got '0, inf'"),
    (AX + "from = 1\nto = 2\ncount = 1000\n[axis]\nkey = controller.kd\nfrom = 1\nto = 2\n"
     "count = 1000\n", 10, "the axes make 1000000 cases, more than 100000"),
    ("[sweep]\nreport = steps, steps\n" + AX + "values = 1\n", 2, "'steps' named twice"),
    ("[sweep]\ncase_figures = maybe\n" + AX + "values = 1\n", 2, "expected a boolean"),
]
for i, (text, line, frag) in enumerate(LIMITS):
    path = write("lim%02d.ini" % i, text)
    rc, so, se = run([path, "--list"])
    ok(rc == 2 and se.startswith("%s:%d:" % (path, line)) and frag in se,
       "sweep file %s: line %d, %s" % (text.replace("\n", " ").strip()[:60], line, frag), se)
fifo = os.path.join(tmp, "fifo.ini")
os.mkfifo(fifo)
rc, so, se = run([fifo, "--list"], timeout=20)
ok(rc == 2 and "a FIFO (named pipe), not a sweep file" in se, "a FIFO as the sweep file: "
   "refused without blocking", se)
with open(os.path.join(tmp, "big-file.ini"), "w") as f:
    f.write(";" * (1 << 21))
rc, so, se = run([os.path.join(tmp, "big-file.ini"), "--list"])
ok(rc == 2 and "larger than 1 MB" in se, "a sweep file of 2 MB: refused", se)
for args, frag in [(["--time-limit", "nan"], "--time-limit needs"),
                   (["--time-limit", "inf"], "--time-limit needs"),
                   (["--jobs", "1e3"], "--jobs needs"), (["--jobs", "-1"], "--jobs needs"),
                   (["--out", sw], "is a regular file, not a folder"),
                   (["--out", "/dev/full"], "is a character device, not a folder")]:
    rc, so, se = run([sw] + args)
    ok(rc in (1, 2) and frag in se, "command line %s: %s" % (" ".join(args[:1] + [
        os.path.basename(args[1])]), frag), "rc=%s %s" % (rc, se))

shutil.rmtree(tmp, ignore_errors=True)
print("1..%d" % count)
sys.exit(1 if failed else 0)
