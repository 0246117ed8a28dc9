"""The index-2 pendulum from a Python residual (the Python twin of examples/residual_only.c):
velocity level, so the rod force lam is an index-2 unknown,
    x' = u,  y' = v,  u' = -lam x,  v' = -lam y - g,  0 = x u + y v.
Nothing but the residual is given: the solver finds the patterns, the kinds and consistent
initial values. Prints the state at t = 1..10 and checks the rod length and the energy.
    PYTHONPATH=build/python python3 examples/python/pendulum.py
"""
import sys

import numpy as np

import bgdae

G = 9.81


def pendulum(t, y, yp):
    x, yy, u, v, lam = y
    return np.array([yp[0] - u, yp[1] - v, yp[2] + lam * x, yp[3] + lam * yy + G,
                     x * u + yy * v])


dae = bgdae.DAE(pendulum, [1, 0, 0, 0, 0], names=["x", "y", "u", "v", "lam"])
sol = dae.solve(np.arange(1.0, 11.0), rtol=1e-8, atol=1e-8)
print("kinds found:", dict(zip(dae.names, sol.kinds)), "(0 differential, 2 index 2)")
for t, (x, y, u, v, lam) in zip(sol.t, sol.y):
    print(f"t = {t:4.1f}  x = {x:+.8f}  y = {y:+.8f}  lam = {lam:9.5f}  "
          f"|length - 1| = {abs(np.hypot(x, y) - 1):.1e}")
length = np.max(np.abs(np.hypot(sol["x"], sol["y"]) - 1))
energy = np.max(np.abs(0.5 * (sol["u"] ** 2 + sol["v"] ** 2) + G * sol["y"]))
st = sol.stats
print(f"steps {st['steps']}, Newton iterations {st['newton_iters']}, residuals {st['res_evals']}")
ok = length < 1e-5 and energy < 1e-4
print(f"rod length within {length:.1e}, energy within {energy:.1e}: {'ok' if ok else 'FAILED'}")
sys.exit(0 if ok else 1)
