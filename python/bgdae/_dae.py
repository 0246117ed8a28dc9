"""A DAE F(t, y, y') = 0 given by Python callables (bgdae.DAE)."""
import numbers

import numpy as np

from . import _check, _core

DIFFERENTIAL, ALGEBRAIC, INDEX2 = 0, 1, 2

_INDEX2 = {"exclude": 0, "scale_h": 1, "reduce": 2}
_LINSOL = {"klu": 0, "dense": 1}
_FLOATS = {"rtol", "atol", "h_init", "h_min", "h_max", "newton_dgmax", "t_stop"}
_STATIC = {"rtol", "atol", "max_newton", "max_steps", "continuation", "dlambda", "dlambda_min",
           "h0", "h_max"}


def default_options():
    """The C library's defaults (dae_options_default), index2 and linsol by name."""
    d = _core.default_options()
    d["index2"] = {v: k for k, v in _INDEX2.items()}[d["index2"]]
    d["linsol"] = {v: k for k, v in _LINSOL.items()}[d["linsol"]]
    for k in ("exclude_alg", "fixed_step", "no_timing", "newton_index2_scale_h",
              "check_jacobian", "stability_guard"):
        d[k] = bool(d[k])
    d["t_stop"] = None
    d["breakpoints"] = None
    return d


_DEFAULTS = default_options()


def _options(kw, n):
    """The keyword options checked and converted for the C layer (only those given)."""
    out = {}
    for k, v in kw.items():
        if k not in _DEFAULTS:
            raise TypeError(f"unknown solver option '{k}' (options: {', '.join(sorted(_DEFAULTS))})")
        if v is None and k in ("t_stop", "breakpoints"):
            continue
        if k == "index2":
            if v not in _INDEX2 and v not in (0, 1, 2):
                raise ValueError(f"index2: {v!r} (expected 'exclude', 'scale_h' or 'reduce')")
            out[k] = _INDEX2.get(v, v)
        elif k == "linsol":
            if v not in _LINSOL:
                raise ValueError(f"linsol: {v!r} (expected 'klu' or 'dense')")
            out[k] = _LINSOL[v]
        elif k == "atol" and not isinstance(v, numbers.Real):
            out[k] = _check.vector("atol", v, n)
        elif k == "breakpoints":
            out[k] = _check.vector("breakpoints", v)
        elif k in _FLOATS:
            out[k] = _check.real(k, v)
        else:
            out[k] = _check.integer(k, v)
    return out


class Solution:
    """The states at the requested times: t (m,), y and yp (m, n), stats (a dict of the
    solver's statistics), kinds (the kinds the solver used), warning ("" if none);
    sol["name"] is the column of the unknown of that name."""

    def __init__(self, r, names):
        self.t, self.y, self.yp = r["t"], r["y"], r["yp"]
        self.stats, self.kinds, self.warning = r["stats"], r["kinds"], r["warning"]
        self.names = names

    def __getitem__(self, name):
        if self.names is None or name not in self.names:
            raise KeyError(f"{name}: no unknown of this name")
        return self.y[:, self.names.index(name)]

    def __repr__(self):
        return (f"<bgdae.Solution: {len(self.t)} times, {self.y.shape[1]} unknowns, "
                f"{self.stats['steps']} steps>")


class DAE:
    """F(t, y, y') = 0 from Python.

    residual(t, y, yp) -> r: n values (numpy arrays of n floats in, copies the callable may
    keep). y0 (n values) fixes n; yp0 (default zeros) and t0 (default 0) the start.
    jac(t, y, yp) -> (dF/dy, dF/dyp): each a dense (n, n) array or a scipy.sparse matrix,
    zero outside the patterns; without it, coloured finite differences on the patterns.
    jac_pattern=(Py, Pyp): the patterns of dF/dy and dF/dyp (scipy.sparse matrices or dense
    arrays, nonzeros); without them the solver finds them from the residual.
    kinds: per unknown 'differential', 'algebraic' or 'index2' (or 0, 1, 2); without them
    classified from the patterns. names, eq_names: for the messages. nominal: magnitudes
    (atol times nominal[i] per unknown).
    """

    def __init__(self, residual, y0, yp0=None, t0=0.0, *, jac=None, jac_pattern=None,
                 kinds=None, names=None, eq_names=None, nominal=None):
        self.residual = _check.callable_arg("residual", residual)
        self.jac = _check.callable_arg("jac", jac, optional=True)
        self.y0 = _check.vector("y0", y0)
        n = self.n = len(self.y0)
        if n < 1:
            raise ValueError("y0: expected at least one value")
        self.yp0 = None if yp0 is None else _check.vector("yp0", yp0, n)
        self.t0 = _check.real("t0", t0)
        if jac_pattern is not None:
            if not (isinstance(jac_pattern, (tuple, list)) and len(jac_pattern) == 2):
                raise TypeError("jac_pattern: expected a pair (pattern of dF/dy, of dF/dyp)")
            self._pat = (_check.pattern("jac_pattern[0]", jac_pattern[0], n),
                         _check.pattern("jac_pattern[1]", jac_pattern[1], n))
        elif self.jac is not None:
            raise ValueError("jac_pattern: needed with jac (the patterns of dF/dy and dF/dyp "
                             "on which jac gives its values)")
        else:
            self._pat = (None, None)
        self.kinds = _check.kinds(kinds, n)
        self.names = _check.names("names", names, n)
        self.eq_names = _check.names("eq_names", eq_names, n)
        self.nominal = None if nominal is None else _check.vector("nominal", nominal, n)
        if self.nominal is not None and np.any(self.nominal <= 0):
            raise ValueError("nominal: expected values > 0")

    def _args(self, **more):
        return dict(res=self.residual, jac=self.jac, n=self.n, jy_pattern=self._pat[0],
                    jyp_pattern=self._pat[1], kinds=self.kinds, names=self.names,
                    eq_names=self.eq_names, nominal=self.nominal, **more)

    def solve(self, t_out, *, consistent=True, **options):
        """The states at the times t_out (ascending, >= t0; t0 itself gives the start) from
        consistent initial values (consistent=False: y0, yp0 as given). Options: the fields
        of the C library's dae_options by name (bgdae.default_options()). Raises SolverError
        on a failure of the solver: message, status, t, unknown (the unknown the message
        names, or None), and what was computed (t_out, y, yp, stats)."""
        t = np.atleast_1d(_check.vector("t_out", np.atleast_1d(t_out)))
        if len(t) == 0:
            raise ValueError("t_out: expected at least one time")
        if np.any(np.diff(t) < 0):
            raise ValueError("t_out: expected ascending times")
        if t[0] < self.t0:
            raise ValueError(f"t_out: {t[0]} is before t0 = {self.t0}")
        try:
            r = _core.dae_solve(**self._args(t0=self.t0, y0=self.y0, yp0=self.yp0, t_out=t,
                                             options=_options(options, self.n),
                                             consistent=bool(consistent)))
        except _core.SolverError as e:
            raise _check.name_unknown(e, self.names)
        return Solution(r, self.names)

    def static(self, y=None, t=None, **options):
        """The equilibrium F(t, y, 0) = 0 from y (default y0) by the library's continuation
        (dae_static_solve): a dict with y, yp and the solve's figures."""
        y = self.y0 if y is None else _check.vector("y", y, self.n)
        t = self.t0 if t is None else _check.real("t", t)
        for k, v in options.items():
            if k not in _STATIC:
                raise TypeError(f"unknown static option '{k}' (options: {', '.join(sorted(_STATIC))})")
            _check.real(k, v)
        return _core.dae_static(**self._args(t0=t, y0=y, options=options))

    def modes(self, y=None, yp=None, t=None):
        """The modes of the linearisation at (t, y, yp) (default the start; yp default 0):
        a list of dicts with frequency_hz, damping_ratio, kind, the eigenvalue re, im, a
        description by the names, and the shape (shape_re, shape_im: n values)."""
        y = self.y0 if y is None else _check.vector("y", y, self.n)
        yp = None if yp is None else _check.vector("yp", yp, self.n)
        t = self.t0 if t is None else _check.real("t", t)
        return _core.dae_modes(**self._args(t0=t, y0=y, yp0=yp))
