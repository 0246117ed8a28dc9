"""bgdae.DAE: a residual in Python against the C library's run of the same problem and against
analytic solutions."""
import math
import subprocess

import numpy as np
import pytest

import bgdae

G = 9.81


def pendulum(t, y, yp):
    """examples/residual_only.c's pendulum, term for term (tests/python/pendulum_ref.c)."""
    return np.array([yp[0] - y[2], yp[1] - y[3], yp[2] + y[4] * y[0],
                     yp[3] + y[4] * y[1] + G, y[0] * y[2] + y[1] * y[3]])


def test_pendulum_equals_the_c_run(pendulum_ref):
    out = subprocess.run([pendulum_ref, "1e-8", "1e-8"], check=True, capture_output=True,
                         text=True).stdout.splitlines()
    ref = np.array([[float(v) for v in line.split()] for line in out[:10]])
    counts = out[10].split()
    sol = bgdae.DAE(pendulum, [1, 0, 0, 0, 0]).solve(np.arange(1.0, 11.0), rtol=1e-8, atol=1e-8)
    assert np.max(np.abs(sol.t - ref[:, 0])) == 0
    assert np.max(np.abs(sol.y - ref[:, 1:])) <= 1e-12
    # the same steps: the same computation, not only the same answer
    assert sol.stats["steps"] == int(counts[1])
    assert sol.stats["newton_iters"] == int(counts[3])
    assert sol.stats["res_evals"] == int(counts[5])
    assert list(sol.kinds) == [0, 0, 0, 0, 2]


def pendulum_jac(t, y, yp):
    Jy = np.zeros((5, 5))
    Jy[0, 2] = Jy[1, 3] = -1
    Jy[2, 0] = Jy[2, 4] = 0
    Jy[2, 0], Jy[2, 4] = y[4], y[0]
    Jy[3, 1], Jy[3, 4] = y[4], y[1]
    Jy[4, :4] = [y[2], y[3], y[0], y[1]]
    Jyp = np.diag([1.0, 1, 1, 1, 0])
    return Jy, Jyp


@pytest.mark.parametrize("form", ["dense", "sparse"])
def test_pendulum_with_jacobian_conserves_energy(form):
    sp = pytest.importorskip("scipy.sparse") if form == "sparse" else None
    jac = pendulum_jac
    if sp:
        jac = lambda t, y, yp: tuple(sp.csc_matrix(a) for a in pendulum_jac(t, y, yp))
    Jy, Jyp = pendulum_jac(0, np.ones(5), np.zeros(5))
    dae = bgdae.DAE(pendulum, [1, 0, 0, 0, 0], jac=jac, jac_pattern=(Jy != 0, Jyp != 0),
                    kinds=["differential"] * 4 + ["index2"], names=["x", "y", "u", "v", "lam"])
    sol = dae.solve(np.linspace(0, 5, 11), rtol=1e-8, atol=1e-8)
    energy = 0.5 * (sol["u"] ** 2 + sol["v"] ** 2) + G * sol["y"]
    assert np.max(np.abs(energy)) < 1e-4  # released at rest from y = 0
    assert np.max(np.abs(np.hypot(sol["x"], sol["y"]) - 1)) < 1e-5
    assert sol.stats["res_evals_fd"] == 0 and sol.stats["jac_evals"] > 0
    # at t = 0 the rod force is 0 and the fall starts at g
    assert sol.yp[0, 3] == pytest.approx(-G, abs=1e-9)


def test_linear_ode_against_exp():
    k = 2.0
    sol = bgdae.DAE(lambda t, y, yp: yp + k * y, [1.0, 3.0]).solve(
        [0.5, 1.0, 2.0], rtol=1e-10, atol=1e-12)
    exact = np.exp(-k * sol.t)[:, None] * np.array([1.0, 3.0])
    assert np.max(np.abs(sol.y - exact) / exact) < 1e-7


def test_options_are_the_c_defaults_and_change_the_run():
    d = bgdae.default_options()
    assert d["rtol"] == 1e-6 and d["atol"] == 1e-8 and d["max_order"] == 0
    assert d["max_newton"] == 4 and d["max_steps"] == 100000 and d["index2"] == "exclude"
    dae = bgdae.DAE(pendulum, [1, 0, 0, 0, 0])
    a = dae.solve([1.0])
    b = dae.solve([1.0], **{k: v for k, v in d.items() if v is not None})
    assert a.stats["steps"] == b.stats["steps"] and np.array_equal(a.y, b.y)
    c = dae.solve([1.0], max_order=2)
    assert c.stats["steps_at_order"][3:] == (0, 0, 0, 0, 0)
    r = dae.solve([1.0], index2="reduce")
    assert r.stats["reduced_rows"] == 1


def test_static_equilibrium_of_a_spring():
    m, k = 2.0, 50.0  # y' = v, m v' = -k y - m g: at rest y = -m g / k
    dae = bgdae.DAE(lambda t, y, yp: np.array([yp[0] - y[1], m * yp[1] + k * y[0] + m * G]),
                    [0.0, 0.0])
    eq = dae.static()
    assert eq["y"][0] == pytest.approx(-m * G / k, rel=1e-10)
    assert abs(eq["y"][1]) < 1e-12 and eq["lambda"] == 1


def test_modes_of_a_damped_oscillator():
    m, k, c = 2.0, 8.0, 0.4  # f = sqrt(k/m) / (2 pi), zeta = c / (2 sqrt(k m))
    dae = bgdae.DAE(lambda t, y, yp: np.array([yp[0] - y[1], m * yp[1] + c * y[1] + k * y[0]]),
                    [0.0, 0.0], names=["pos", "vel"])
    modes = dae.modes()
    assert len(modes) == 1
    md = modes[0]
    assert md["frequency_hz"] == pytest.approx(math.sqrt(k / m) / (2 * math.pi), rel=1e-10)
    assert md["damping_ratio"] == pytest.approx(c / (2 * math.sqrt(k * m)), rel=1e-10)
    assert md["kind"] == "elastic" and "pos" in md["description"]
    # the shape: velocity = s * position for the eigenvalue s
    z = md["shape_re"] + 1j * md["shape_im"]
    s = md["re"] + 1j * md["im"]
    assert abs(z[1] - s * z[0]) < 1e-10 * abs(z[1])


def test_patterns_without_jacobian():
    Jy, Jyp = pendulum_jac(0, np.ones(5), np.zeros(5))
    given = bgdae.DAE(pendulum, [1, 0, 0, 0, 0], jac_pattern=(Jy != 0, Jyp != 0))
    found = bgdae.DAE(pendulum, [1, 0, 0, 0, 0])
    a, b = given.solve([2.0], rtol=1e-8, atol=1e-8), found.solve([2.0], rtol=1e-8, atol=1e-8)
    assert a.stats["pattern_nnz"] == 0 and b.stats["pattern_nnz"] == (Jy != 0).sum() + 4
    assert a.stats["res_evals_fd"] > 0 and a.stats["jac_evals"] > 0
    assert list(a.kinds) == [0, 0, 0, 0, 2]
    assert np.max(np.abs(a.y - b.y)) < 1e-9
