"""bgdae against SciPy's solve_ivp (Radau, BDF, LSODA) on two stiff problems where both apply:
Robertson's chemical kinetics (to t = 1e5) and van der Pol's oscillator (mu = 1000, to t = 3000).
Per solver and tolerance: the error at the final time against a reference (bgdae at rtol 1e-12)
and the run time (median of a few runs). bgdae gets the problems as DAE residuals (dense linear algebra: n = 2, 3)
F = y' - f(t, y) with their analytic Jacobians, SciPy as f with the same Jacobians.
Writes a table, and error against time in compare_scipy.png when matplotlib is installed.
    PYTHONPATH=build/python python3 examples/python/compare_scipy.py [--quick] [--out DIR]
"""
import argparse
import os
import time

import numpy as np

import bgdae

try:
    from scipy.integrate import solve_ivp
except ImportError:
    solve_ivp = None


def robertson():
    def f(t, y):
        return np.array([-0.04 * y[0] + 1e4 * y[1] * y[2],
                         0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] ** 2,
                         3e7 * y[1] ** 2])

    def jac(t, y):
        return np.array([[-0.04, 1e4 * y[2], 1e4 * y[1]],
                         [0.04, -1e4 * y[2] - 6e7 * y[1], -1e4 * y[1]],
                         [0, 6e7 * y[1], 0]])
    return "Robertson", f, jac, np.array([1.0, 0, 0]), 1e5, 1e-4  # atol = 1e-4 rtol: y2 ~ 1e-5


def vanderpol(mu=1000.0):
    def f(t, y):
        return np.array([y[1], mu * (1 - y[0] ** 2) * y[1] - y[0]])

    def jac(t, y):
        return np.array([[0, 1], [-2 * mu * y[0] * y[1] - 1, mu * (1 - y[0] ** 2)]])
    return "van der Pol (mu = 1000)", f, jac, np.array([2.0, 0]), 3000.0, 1.0


def run_bgdae(f, jac, y0, t_end, rtol, atol):
    n = len(y0)
    full = np.ones((n, n))
    dae = bgdae.DAE(lambda t, y, yp: yp - f(t, y), y0,
                    jac=lambda t, y, yp: (-jac(t, y), np.eye(n)),
                    jac_pattern=(full, np.eye(n)))
    s = dae.solve([t_end], rtol=rtol, atol=atol, linsol="dense")
    return s.y[-1], s.stats["steps"]


def run_scipy(method, f, jac, y0, t_end, rtol, atol):
    r = solve_ivp(f, (0, t_end), y0, method=method, rtol=rtol, atol=atol, jac=jac)
    if not r.success:
        raise RuntimeError(r.message)
    return r.y[:, -1], r.nfev


def timed(fn, repeat):
    times, out = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times)), out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="two tolerances, one run each")
    ap.add_argument("--out", default=".", help="folder for compare_scipy.png")
    a = ap.parse_args()
    if solve_ivp is None:
        print("scipy is not installed (Debian: python3-scipy): only bgdae runs")
    tols = [1e-4, 1e-7] if a.quick else [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8]
    repeat = 1 if a.quick else 3
    methods = ["bgdae"] + (["Radau", "BDF", "LSODA"] if solve_ivp else [])
    results = {}
    for name, f, jac, y0, t_end, atol_factor in (robertson(), vanderpol()):
        ref, _ = run_bgdae(f, jac, y0, t_end, 1e-12, 1e-12 * atol_factor)
        print(f"\n{name}, t_end = {t_end:g}; error = max |y - y_ref| / max(|y_ref|, atol)")
        print(f"{'solver':8} {'rtol':>7} {'error':>9} {'time [s]':>9}")
        for m in methods:
            for rtol in tols:
                atol = rtol * atol_factor
                fn = (lambda: run_bgdae(f, jac, y0, t_end, rtol, atol)) if m == "bgdae" else \
                     (lambda: run_scipy(m, f, jac, y0, t_end, rtol, atol))
                try:
                    sec, (y, _) = timed(fn, repeat)
                except Exception as e:  # a failure is a result of the comparison
                    print(f"{m:8} {rtol:7.0e} failed: {e}")
                    continue
                err = float(np.max(np.abs(y - ref) / np.maximum(np.abs(ref), atol)))
                results.setdefault(name, {}).setdefault(m, []).append((sec, err))
                print(f"{m:8} {rtol:7.0e} {err:9.2e} {sec:9.4f}")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("\nmatplotlib is not installed (Debian: python3-matplotlib): no plot")
        return
    fig, axes = plt.subplots(1, len(results), figsize=(11, 4.5))
    for ax, (name, by) in zip(np.atleast_1d(axes), results.items()):
        for m, pts in by.items():
            ax.loglog([p[1] for p in pts], [p[0] for p in pts], "o-", label=m)
        ax.set_title(name)
        ax.set_xlabel("relative error at t_end")
        ax.set_ylabel("run time [s]")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.tight_layout()
    path = os.path.join(a.out, "compare_scipy.png")
    fig.savefig(path, dpi=120)
    print(f"\nplot: {path}")


if __name__ == "__main__":
    main()
