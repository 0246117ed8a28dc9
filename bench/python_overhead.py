"""What Python costs (a benchmark, not a test): a residual in Python against the same residual
in C, on the index-2 pendulum (5 unknowns) and on a 1 000-unknown heat equation, and the crane
model run from Python (bgdae.Model.run) against the program bgsim. The runs make the same steps
on both sides (checked); the figures are medians of --repeat runs, so noise from a busy machine
shows in their spread, printed beside them.
    PYTHONPATH=build/python python3 bench/python_overhead.py [--build build] [--repeat 5]
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

import bgdae

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def pendulum(t, y, yp):
    return np.array([yp[0] - y[2], yp[1] - y[3], yp[2] + y[4] * y[0],
                     yp[3] + y[4] * y[1] + 9.81, y[0] * y[2] + y[1] * y[3]])


def heat_residual(n):
    d = float(n) * n

    def f(t, y, yp):
        lap = -2 * y
        lap[1:] += y[:-1]
        lap[:-1] += y[1:]
        return yp - d * lap
    return f


def c_run(exe, *args):
    out = subprocess.run([exe, *args], check=True, capture_output=True, text=True).stdout.split()
    v = dict(zip(out[::2], out[1::2]))
    return int(v["steps"]), int(v["res"]), float(v["t_res"]), float(v["wall"])


def py_run(dae, t_end, rtol):
    t0 = time.perf_counter()
    s = dae.solve([t_end], rtol=rtol, atol=rtol)
    wall = time.perf_counter() - t0
    st = s.stats
    return st["steps"], st["res_evals"] + st["res_evals_fd"], st["t_res"], wall


def median(xs):
    return float(np.median(xs)), float(np.max(xs) - np.min(xs))


def residual_cost(name, exe, c_args, dae, t_end, rtol, repeat):
    c = [c_run(exe, *c_args) for _ in range(repeat)]
    p = [py_run(dae, t_end, rtol) for _ in range(repeat)]
    assert c[0][:2] == p[0][:2], f"{name}: the runs differ: C {c[0][:2]}, Python {p[0][:2]}"
    steps, res = c[0][:2]
    c_call, c_spread = median([x[2] / res * 1e6 for x in c])
    p_call, p_spread = median([x[2] / res * 1e6 for x in p])
    c_wall, _ = median([x[3] for x in c])
    p_wall, _ = median([x[3] for x in p])
    print(f"{name}: {steps} steps, {res} residual calls on both sides")
    print(f"  per residual call: C {c_call:.3f} us (spread {c_spread:.3f}), "
          f"Python {p_call:.2f} us (spread {p_spread:.2f}): {p_call / c_call:.0f} times")
    print(f"  whole solve: C {c_wall:.4f} s, Python {p_wall:.4f} s: {p_wall / c_wall:.1f} times")


def crane(bgsim, t_end, repeat):
    model = os.path.join(ROOT, "crane", "models", "paper.yaml")
    tmp = tempfile.mkdtemp()
    try:
        prog, py = [], []
        for _ in range(repeat):
            t0 = time.perf_counter()
            subprocess.run([bgsim, model, "--t-end", str(t_end), "--out", tmp, "--quiet"],
                           check=True)
            prog.append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            run = bgdae.Model(model).run(t_end=t_end)
            py.append(time.perf_counter() - t0)
    finally:
        shutil.rmtree(tmp)
    pm, ps = median(prog)
    qm, qs = median(py)
    print(f"crane (paper.yaml, t_end = {t_end:g} s, {run.stats['steps']} steps, "
          f"{len(run.t)} rows), load + run:")
    print(f"  bgsim {pm:.3f} s (spread {ps:.3f}), Python {qm:.3f} s (spread {qs:.3f}): "
          f"Python / bgsim = {qm / pm:.3f}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--crane-t-end", type=float, default=2.0)
    a = ap.parse_args()
    ref = os.path.join(a.build, "python", "python_overhead_ref")
    bgsim = os.path.join(a.build, "bgsim", "bgsim")
    for p in (ref, bgsim):
        if not os.access(p, os.X_OK):
            sys.exit(f"python_overhead: {p} is missing (ninja -C {a.build})")
    residual_cost("pendulum (5 unknowns, rtol 1e-8)", ref, ["pendulum", "1e-8"],
                  bgdae.DAE(pendulum, [1, 0, 0, 0, 0]), 10.0, 1e-8, a.repeat)
    n = 1000
    y0 = np.sin(np.pi * np.arange(1, n + 1) / (n + 1))
    residual_cost(f"heat equation ({n} unknowns, rtol 1e-6)", ref, ["heat", str(n), "1e-6"],
                  bgdae.DAE(heat_residual(n), y0), 0.1, 1e-6, a.repeat)
    crane(bgsim, a.crane_t_end, a.repeat)


if __name__ == "__main__":
    main()
