"""The examples of examples/python/ run to their end (each checks its own figures where it has
any: the pendulum its rod length and energy)."""
import os
import subprocess
import sys

import pytest


def run(root, name, *args):
    return subprocess.run([sys.executable, os.path.join(root, "examples", "python", name), *args],
                          capture_output=True, text=True, timeout=600)


def test_pendulum_example(root):
    r = run(root, "pendulum.py")
    assert r.returncode == 0, r.stderr
    assert "energy within" in r.stdout and r.stdout.rstrip().endswith("ok")


def test_crane_sweep_example(root, tmp_path):
    r = run(root, "crane_sweep.py", "--t-end", "0.05", "--kp", "5", "10", "--ki", "2",
            "--out", str(tmp_path))
    assert r.returncode == 0, r.stderr
    rows = (tmp_path / "sweep.csv").read_text().splitlines()
    assert rows[0].startswith("kp,ki,") and len(rows) == 3


def test_compare_scipy_example(root, tmp_path):
    pytest.importorskip("scipy")
    r = run(root, "compare_scipy.py", "--quick", "--out", str(tmp_path))
    assert r.returncode == 0, r.stderr
    for m in ("bgdae", "Radau", "BDF", "LSODA"):
        assert m in r.stdout
    try:
        import matplotlib  # noqa: F401
        assert (tmp_path / "compare_scipy.png").stat().st_size > 0
    except ImportError:
        pass
