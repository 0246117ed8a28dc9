"""1000 repeated solves leave the reference counts and the memory where they were: Python's
(tracemalloc) and the process's (the C library's allocations: resident set size)."""
import gc
import os
import sys
import tracemalloc
import weakref

import numpy as np

import bgdae


# AddressSanitizer keeps freed memory in quarantine: the resident size then says nothing
UNDER_ASAN = "asan" in os.environ.get("LD_PRELOAD", "")


def rss_kib():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") // 1024


def pendulum(t, y, yp):
    return np.array([yp[0] - y[2], yp[1] - y[3], yp[2] + y[4] * y[0],
                     yp[3] + y[4] * y[1] + 9.81, y[0] * y[2] + y[1] * y[3]])


def failing(t, y, yp):
    if t > 0.1:
        raise ArithmeticError("stop")
    return yp + y


def test_1000_solves_keep_references_and_memory():
    y0 = np.array([1.0, 0, 0, 0, 0])
    t_out = np.array([0.5, 1.0])
    dae = bgdae.DAE(pendulum, y0, names=["x", "y", "u", "v", "lam"])
    bad = bgdae.DAE(failing, [1.0])
    stiff = bgdae.DAE(lambda t, y, yp: yp + y ** 2 * 1e3, [1.0], names=["s"])

    def once(i):
        dae.solve(t_out, rtol=1e-4, atol=1e-6)
        if i % 10 == 0:
            try:
                bad.solve([1.0])
            except ArithmeticError:
                pass
            try:
                stiff.solve([1.0], max_steps=3)
            except bgdae.SolverError:
                pass

    tracemalloc.start()
    for i in range(300):  # warm-up: caches, first allocations (one of about 1 MB)
        once(i)
    gc.collect()
    refs = [sys.getrefcount(x) for x in (pendulum, y0, t_out, dae, failing, bgdae.SolverError)]
    rss0 = rss_kib()
    snap0 = tracemalloc.take_snapshot()
    for i in range(1000):
        once(i)
    gc.collect()
    snap1 = tracemalloc.take_snapshot()
    rss1 = rss_kib()
    tracemalloc.stop()
    diff = snap1.compare_to(snap0, "lineno")
    grown = sum(s.size_diff for s in diff)
    blocks = sum(s.count_diff for s in diff)
    top = "\n".join(str(s) for s in diff[:3])
    assert refs == [sys.getrefcount(x) for x in (pendulum, y0, t_out, dae, failing,
                                                   bgdae.SolverError)]
    # anything kept per solve is at least one block per solve (1000); a cache of the
    # interpreter or numpy that grows once (a block of about 1 MB seen at times) is not
    assert blocks < 100, f"{blocks} Python blocks more after 1000 solves:\n{top}"
    assert grown < 4 * 1024 * 1024, f"Python memory grew by {grown} bytes:\n{top}"
    assert UNDER_ASAN or rss1 - rss0 < 4 * 1024, f"resident memory grew by {rss1 - rss0} KiB"


def test_300_model_loads_and_runs_keep_memory(root):
    path = os.path.join(root, "examples", "models", "double-pendulum.yaml")
    m = bgdae.Model(path)
    for _ in range(5):
        m.run(t_end=0.01)
    gc.collect()
    rss0 = rss_kib()
    for _ in range(300):
        r = m.run(t_end=0.01)
    gc.collect()
    assert UNDER_ASAN or rss_kib() - rss0 < 4 * 1024
    held = weakref.ref(r.outputs)
    del r
    gc.collect()
    assert held() is None  # the run's arrays are freed with it
