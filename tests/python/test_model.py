"""bgdae.Model: a model file run from Python against the program bgsim's run of it (the same
numbers, in the digits results.csv writes; the same steps), parameters, the static
equilibrium, the modes, the error estimate, bad input."""
import csv
import os
import subprocess

import numpy as np
import pytest

import bgdae


def bgsim_run(bgsim, tmp_path, model, *args):
    out = tmp_path / "run"
    subprocess.run([bgsim, model, "--out", str(out), "--quiet", *args], check=True)
    return out


def stats_counts(path):
    """steps, newton, jac of solver_stats.txt's CSV block."""
    lines = path.read_text().splitlines()
    i = lines.index("# CSV")
    row = dict(zip(lines[i + 1].split(","), lines[i + 2].split(",")))
    return int(row["steps"]), int(row["newton"]), int(row["jac"])


def test_crane_equals_bgsim(bgsim, root, tmp_path):
    model = os.path.join(root, "crane", "models", "paper.yaml")
    out = bgsim_run(bgsim, tmp_path, model, "--t-end", "0.3", "--set", "kp=6.5")
    with open(out / "results.csv") as f:
        rows = list(csv.reader(f))
    run = bgdae.Model(model, set={"kp": 6.5}).run(t_end=0.3)
    assert rows[0] == ["t"] + run.names
    assert len(rows) - 1 == len(run.t) == 301
    # every value as results.csv writes it (%.12g): the same text
    mine = [["%.12g" % v for v in [t, *o]] for t, o in zip(run.t, run.outputs)]
    assert mine == rows[1:]
    assert stats_counts(out / "solver_stats.txt") == (
        run.stats["steps"], run.stats["newton_iters"], run.stats["jac_evals"])
    assert run.static is not None and run.static["trimmed"] == 1


def test_double_pendulum_error_estimate_and_static_equal_bgsim(bgsim, root, tmp_path):
    model = os.path.join(root, "examples", "models", "double-pendulum.yaml")
    out = bgsim_run(bgsim, tmp_path, model, "--error-estimate", "--t-end", "1")
    run = bgdae.Model(model).run(t_end=1, error_estimate=True)
    with open(out / "error_estimate.csv") as f:
        est = {r["column"]: r for r in csv.DictReader(f)}
    cols = run.error_estimate["columns"]
    assert set(est) == set(run.names)
    for name, r in est.items():
        assert "%g" % cols[name]["max_error"] == r["max_abs_error"]
        assert "%g" % cols[name]["t_at"] == r["t_at_max [s]"]
    out2 = bgsim_run(bgsim, tmp_path / "s", model, "--static")
    with open(out2 / "equilibrium.csv") as f:
        eq = {r["name"]: float(r["value"]) for r in csv.DictReader(f) if r["kind"] == "output"}
    mine = bgdae.Model(model).static()["outputs"]
    assert mine == eq  # %.17g: the same doubles


def test_modes_equal_bgsim(bgsim, root, tmp_path):
    model = os.path.join(root, "examples", "models", "double-pendulum.yaml")
    out = bgsim_run(bgsim, tmp_path, model, "--modes")
    with open(out / "modes.csv") as f:
        ref = list(csv.DictReader(f))
    m = bgdae.Model(model)
    modes = m.modes()
    assert len(modes) == len(ref)
    for md, r in zip(modes, ref):
        assert "%.10g" % md["frequency_hz"] == r["frequency_hz"] and md["kind"] == r["kind"]
        assert md["shape_re"].shape == (m.n,)
    # the shape's largest weighted amplitude is 1 and names an unknown of the model
    k = int(np.argmax(np.abs(modes[0]["shape_re"] + 1j * modes[0]["shape_im"])))
    assert m.unknowns[k].replace("/", "") and modes[0]["description"]


def test_parameters_read_and_set(root):
    model = os.path.join(root, "examples", "models", "double-pendulum.yaml")
    m = bgdae.Model(model)
    assert m.parameter("L1") == 1.0 and m.parameter("m2") == 0.5
    m2 = m.with_set(L1=2.0, theta1="45*deg")
    assert m2.parameter("L1") == 2.0
    assert m2.parameter("theta1") == pytest.approx(np.pi / 4, rel=1e-15)
    assert m.parameter("L1") == 1.0  # the first model keeps its own
    r1, r2 = m.run(t_end=0.1), m2.run(t_end=0.1)
    # at t = 0 the upper rod's centre is at L1/2 sin(theta1)
    assert r2["x1"][0] == pytest.approx(1.0 * np.sin(np.pi / 4), rel=1e-12)
    assert r1["x1"][0] == pytest.approx(0.5 * np.sin(np.pi / 3), rel=1e-12)
    # a second run of the same model gives the same numbers
    assert np.array_equal(m.run(t_end=0.1).outputs, r1.outputs)


def test_bad_model_input(root, tmp_path):
    model = os.path.join(root, "examples", "models", "double-pendulum.yaml")
    with pytest.raises(OSError, match="nowhere.yaml"):
        bgdae.Model(tmp_path / "nowhere.yaml")
    with pytest.raises(ValueError, match="L7"):
        bgdae.Model(model, set={"L7": 1.0})
    with pytest.raises(TypeError, match="set: L1: expected a number or an expression string"):
        bgdae.Model(model, set={"L1": [1, 2]})
    with pytest.raises(KeyError, match="nothing"):
        bgdae.Model(model).parameter("nothing")
    with pytest.raises(ValueError, match=r"t_end: -1.0 \(expected > 0\)"):
        bgdae.Model(model).run(t_end=-1)
    with pytest.raises(ValueError, match="error_estimate: 0.5 is out of range"):
        bgdae.Model(model).run(error_estimate=0.5)
    bad = tmp_path / "bad.yaml"
    bad.write_text("format: bgsim 1\nname: x\ncomponents:\n  a: {type: mech.nothing}\n")
    with pytest.raises(ValueError, match=r"bad.yaml:4"):
        bgdae.Model(bad)


def test_the_gil_is_released_during_a_run(root):
    import threading
    import time
    m = bgdae.Model(os.path.join(root, "crane", "models", "paper.yaml"))
    box = {}
    th = threading.Thread(target=lambda: box.setdefault("run", m.run(t_end=0.5)))
    t0 = time.perf_counter()
    th.start()
    stamps, refused = [], None
    while th.is_alive():
        stamps.append(time.perf_counter())
        if refused is None and len(stamps) > 100:
            try:
                m.run(t_end=0.1)
                refused = False
            except RuntimeError as e:  # one call at a time on a model
                refused = "in use" in str(e)
        time.sleep(0)
    wall = time.perf_counter() - t0
    th.join()
    gaps = np.diff([t0] + stamps + [time.perf_counter()])
    # the main thread ran all along: no pause near the run's length
    assert len(box["run"].t) == 501 and wall > 0.1
    assert gaps.max() < 0.5 * wall, (gaps.max(), wall)
    assert refused is True
