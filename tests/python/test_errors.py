"""Failures: the solver's as SolverError with its message, the callback's own exception, and
bad arguments refused with ValueError or TypeError naming the argument."""
import traceback

import numpy as np
import pytest

import bgdae


def blowup(t, y, yp):
    return np.array([yp[0] - y[0] ** 2])  # y = 1 / (1 - t): infinite at t = 1


def test_solver_failure_names_the_unknown_and_time():
    with pytest.raises(bgdae.SolverError) as ei:
        bgdae.DAE(blowup, [1.0], names=["blowup"]).solve([0.5, 2.0])
    e = ei.value
    assert e.status == "DAE_STEP_TOO_SMALL" and e.code < 0
    assert "blowup" in e.message and "at t = 0.99" in e.message and e.unknown == "blowup"
    assert 0.99 < e.t < 1.0
    # the rows computed before the failure are kept: y(0.5) = 2
    assert list(e.t_out) == [0.5]
    assert e.y.shape == (1, 1) and e.y[0, 0] == pytest.approx(2.0, rel=1e-4)
    assert str(e) == e.message


def test_initialisation_failure():
    def contradicting(t, y, yp):  # 0 = z^2 + 1 has no real solution
        return np.array([yp[0] + y[0], y[1] ** 2 + 1])
    with pytest.raises(bgdae.SolverError) as ei:
        bgdae.DAE(contradicting, [1.0, 0.0], names=["x", "z"]).solve([1.0])
    assert ei.value.status == "DAE_INIT_FAIL" and "t = 0" in ei.value.message


class Boom(Exception):
    pass


def test_callback_exception_propagates_with_its_traceback():
    calls = []

    def residual(t, y, yp):
        calls.append(t)
        if t > 0.5:
            raise Boom(f"at {t}")
        return yp + y

    with pytest.raises(Boom) as ei:
        bgdae.DAE(residual, [1.0]).solve([1.0])
    tb = "".join(traceback.format_tb(ei.value.__traceback__))
    assert "raise Boom" in tb and "residual" in tb
    n = len(calls)
    assert calls[-1] > 0.5 and all(c <= 0.5 for c in calls[:-1])  # no call after it
    assert n > 1


def test_jacobian_exception_propagates():
    def jac(t, y, yp):
        raise KeyError("no Jacobian here")
    with pytest.raises(KeyError, match="no Jacobian here"):
        bgdae.DAE(lambda t, y, yp: yp + y, [1.0], jac=jac,
                  jac_pattern=(np.eye(1), np.eye(1))).solve([1.0])


def test_residual_of_the_wrong_shape():
    with pytest.raises(ValueError, match="residual: returned 3 values"):
        bgdae.DAE(lambda t, y, yp: np.zeros(3), [1.0, 2.0]).solve([1.0])
    with pytest.raises(TypeError, match="residual: must return an array of floats"):
        bgdae.DAE(lambda t, y, yp: "abc", [1.0]).solve([1.0])


def test_jacobian_of_the_wrong_shape_or_outside_the_pattern():
    f = lambda t, y, yp: yp + y
    one = (np.eye(1), np.eye(1))
    with pytest.raises(ValueError, match=r"jac: dF/dy has shape \(2, 2\), expected \(1, 1\)"):
        bgdae.DAE(f, [1.0], jac=lambda t, y, yp: (np.eye(2), np.eye(2)),
                  jac_pattern=one).solve([1.0])
    with pytest.raises(TypeError, match="jac: must return a pair"):
        bgdae.DAE(f, [1.0], jac=lambda t, y, yp: np.eye(1), jac_pattern=one).solve([1.0])
    with pytest.raises(ValueError, match="jac_pattern: needed with jac"):
        bgdae.DAE(f, [1.0], jac=lambda t, y, yp: one)
    g = lambda t, y, yp: np.array([yp[0] + y[0], yp[1] + y[1]])
    with pytest.raises(ValueError, match=r"jac: dF/dy has the entry \(1, 0\) = 1 outside its pattern"):
        bgdae.DAE(g, [1.0, 1.0], jac=lambda t, y, yp: (np.ones((2, 2)), np.eye(2)),
                  jac_pattern=(np.eye(2), np.eye(2))).solve([1.0])


@pytest.mark.parametrize("kwargs, exc, text", [
    (dict(residual=3), TypeError, "residual: expected a callable, got int"),
    (dict(jac="x"), TypeError, "jac: expected a callable, got str"),
    (dict(y0=[[1.0, 0.0]]), ValueError, r"y0: expected a 1-D array, got shape \(1, 2\)"),
    (dict(y0=["a", "b"]), TypeError, "y0: expected real numbers, got dtype <U1"),
    (dict(y0=[1 + 2j, 0]), TypeError, "y0: expected real numbers, got dtype complex128"),
    (dict(y0=[1.0, float("nan")]), ValueError, r"y0: y0\[1\] is nan"),
    (dict(yp0=[1.0]), ValueError, "yp0: expected 2 values, got 1"),
    (dict(yp0=[0.0, float("inf")]), ValueError, r"yp0: yp0\[1\] is inf"),
    (dict(t0=float("nan")), ValueError, "t0: nan is not finite"),
    (dict(kinds=["differential", "fast"]), ValueError, r"kinds: kinds\[1\] = 'fast'"),
    (dict(names=["a"]), ValueError, "names: expected 2 names, got 1"),
    (dict(names=["a", 2]), TypeError, r"names: names\[1\] is a int"),
    (dict(jac_pattern=(np.eye(3), np.eye(2))), ValueError,
     r"jac_pattern\[0\]: expected shape \(2, 2\), got \(3, 3\)"),
    (dict(nominal=[1.0, -1.0]), ValueError, "nominal: expected values > 0"),
])
def test_bad_arguments_are_refused(kwargs, exc, text):
    args = dict(residual=lambda t, y, yp: yp + y, y0=[1.0, 0.0])
    args.update(kwargs)
    with pytest.raises(exc, match=text):
        bgdae.DAE(args.pop("residual"), args.pop("y0"), **args)


@pytest.mark.parametrize("t_out, options, exc, text", [
    ([1.0, float("nan")], {}, ValueError, r"t_out: t_out\[1\] is nan"),
    ([2.0, 1.0], {}, ValueError, "t_out: expected ascending times"),
    ([-1.0], {}, ValueError, "t_out: -1.0 is before t0"),
    ([1.0], {"rtool": 1e-3}, TypeError, "unknown solver option 'rtool'"),
    ([1.0], {"rtol": "tight"}, TypeError, "rtol: expected a real number, got str"),
    ([1.0], {"max_order": 2.5}, TypeError, "max_order: expected an integer, got float"),
    ([1.0], {"index2": "drop"}, ValueError, "index2: 'drop'"),
    ([1.0], {"atol": [1e-8]}, ValueError, "atol: expected 2 values, got 1"),
])
def test_bad_solve_arguments_are_refused(t_out, options, exc, text):
    dae = bgdae.DAE(lambda t, y, yp: yp + y, [1.0, 0.0])
    with pytest.raises(exc, match=text):
        dae.solve(t_out, **options)


def test_options_out_of_range_are_the_library_s_refusal():
    with pytest.raises(bgdae.SolverError, match="max_order") as ei:
        bgdae.DAE(lambda t, y, yp: yp + y, [1.0]).solve([1.0], max_order=9)
    assert ei.value.status == "BG_ERR_ARGUMENT"


def test_keyboard_interrupt_stops_a_solve():
    import _thread
    calls = []

    def residual(t, y, yp):
        calls.append(t)
        if len(calls) == 50:  # as Ctrl-C: SIGINT's flag set, seen in Python or in C
            _thread.interrupt_main()
        return yp + y
    with pytest.raises(KeyboardInterrupt):
        bgdae.DAE(residual, [1.0]).solve([1e6], rtol=1e-12, atol=1e-14)
    assert 50 <= len(calls) <= 51


def test_core_refuses_missing_arguments():
    from bgdae import _core
    with pytest.raises(TypeError, match="the argument consistent is required"):
        _core.dae_solve(res=lambda t, y, yp: yp, jac=None, n=1, t0=0.0, y0=[1.0], t_out=[1.0])
    with pytest.raises(ValueError, match="n must be in 1..1e8"):
        _core.dae_static(res=1, jac=None, n=1, t0=0.0, y0=[1.0])


def test_unnamed_unknowns_are_named_by_index():
    def f(t, y, yp):
        return np.array([yp[0] + y[0], yp[1] - y[1] ** 2])
    with pytest.raises(bgdae.SolverError) as ei:
        bgdae.DAE(f, [1.0, 1.0]).solve([2.0])
    assert ei.value.unknown == "y[1]" and "y[1]" in ei.value.message
