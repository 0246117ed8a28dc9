"""Runs the Python package's tests (pytest) and reports one TAP point per test ("ok N - id",
"not ok N - id", the plan "1..N" last), so that tools/test.sh counts them with the other
tests' points. Exit status: pytest's (77, a skip for meson, when pytest is missing)."""
import os
import sys

try:
    import pytest
except ImportError:
    print("1..0 # SKIP python3-pytest is not installed")
    sys.exit(77)


class Tap:
    def __init__(self):
        self.n = 0
        self.lines = []

    def pytest_runtest_logreport(self, report):
        if report.when == "call" or (report.when == "setup" and not report.passed):
            self.n += 1
            if report.skipped:
                self.lines.append(f"ok {self.n} - {report.nodeid} # SKIP")
            else:
                self.lines.append(f"{'ok' if report.passed else 'not ok'} {self.n} - {report.nodeid}")


tap = Tap()
here = os.path.dirname(os.path.abspath(__file__))
rc = pytest.main([here, "-q", "-p", "no:cacheprovider", *sys.argv[1:]], plugins=[tap])
print("\n".join(tap.lines))
print(f"1..{tap.n}")
sys.exit(int(rc))
