"""The crane's PID gains swept from Python: the paper's crane (crane/models/paper.yaml) run for
each (kp, ki) with the replacements bgsim's --set makes, and per case the slewing angle's
overshoot past its reference, the largest angle error and the final error, the steps and the
run time. The model's own C residual and Jacobian run; Python only loops and reads outputs.
    PYTHONPATH=build/python python3 examples/python/crane_sweep.py [--t-end 20] [--out DIR]
(t_end 20 s is the whole slew, about a minute per case; the default 2 s is the start of it.)
"""
import argparse
import itertools
import os
import time

import numpy as np

import bgdae

HERE = os.path.dirname(os.path.abspath(__file__))
MODEL = os.path.join(HERE, "..", "..", "crane", "models", "paper.yaml")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t-end", type=float, default=2.0, help="seconds simulated per case")
    ap.add_argument("--kp", type=float, nargs="+", default=[2.5, 5, 10])
    ap.add_argument("--ki", type=float, nargs="+", default=[1, 2, 4])
    ap.add_argument("--out", default=None, help="folder for sweep.csv (default: none)")
    a = ap.parse_args()
    base = bgdae.Model(MODEL)
    print(f"{base.name}: {base.n} unknowns; the file's gains kp = {base.parameter('kp'):g}, "
          f"ki = {base.parameter('ki'):g}; t_end = {a.t_end:g} s")
    rows = []
    print(f"{'kp':>6} {'ki':>6} {'overshoot':>10} {'max |err|':>10} {'end err':>10} "
          f"{'steps':>6} {'wall [s]':>8}")
    for kp, ki in itertools.product(a.kp, a.ki):
        m = base.with_set(kp=kp, ki=ki)
        t0 = time.perf_counter()
        try:
            run = m.run(t_end=a.t_end)
        except bgdae.SolverError as e:
            print(f"{kp:6g} {ki:6g} failed at t = {e.t:g}: {e.message}")
            continue
        wall = time.perf_counter() - t0
        err = run["theta"] - run["theta_ref"]
        over = float(np.max(run["theta"] - np.max(run["theta_ref"])))
        row = (kp, ki, max(over, 0.0), float(np.max(np.abs(err))), float(err[-1]),
               run.stats["steps"], wall)
        rows.append(row)
        print(f"{kp:6g} {ki:6g} {row[2]:10.3e} {row[3]:10.3e} {row[4]:10.3e} {row[5]:6d} "
              f"{wall:8.2f}")
    if a.out:
        os.makedirs(a.out, exist_ok=True)
        path = os.path.join(a.out, "sweep.csv")
        with open(path, "w") as f:
            f.write("kp,ki,overshoot_rad,max_abs_error_rad,end_error_rad,steps,wall_s\n")
            for r in rows:
                f.write(",".join(f"{v:.9g}" for v in r) + "\n")
        print(f"table: {path}")


if __name__ == "__main__":
    main()
