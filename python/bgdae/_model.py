"""Model files (bgdae.Model): the C library's mdl_load, run as the program bgsim runs them."""
import numbers
import os

import numpy as np

from . import _check, _core


def _value(path, v):
    """A replacement's value as the file would write it."""
    if isinstance(v, str):
        if not v.strip():
            raise ValueError(f"set: {path}: an empty value")
        return v
    if isinstance(v, bool) or not isinstance(v, numbers.Real):
        raise TypeError(f"set: {path}: expected a number or an expression string, "
                        f"got {type(v).__name__}")
    return repr(float(v)) if not isinstance(v, numbers.Integral) else str(int(v))


class ModelRun:
    """A run's rows: t (m,), outputs (m, k) with their names, run["name"] a column; y, yp
    the state of the last row; stats (the solver's), static (the static start's figures or
    None), error_estimate (per output: max_error, t_at, max_abs; None unless asked for)."""

    def __init__(self, r, names):
        self.t, self.outputs, self.names = r["t"], r["outputs"], list(names)
        self.y, self.yp, self.stats = r["y"], r["yp"], r["stats"]
        self.static, self.warning = r["static"], r["warning"]
        e = r["error_estimate"]
        if e is not None:
            e = dict(e)
            e["columns"] = {nm: {"max_error": e["max_error"][i], "t_at": e["t_at"][i],
                                 "max_abs": e["max_abs"][i]} for i, nm in enumerate(names)}
        self.error_estimate = e

    def __getitem__(self, name):
        if name == "t":
            return self.t
        if name not in self.names:
            raise KeyError(f"{name}: no output of this name (outputs: {', '.join(self.names)})")
        return self.outputs[:, self.names.index(name)]

    def __repr__(self):
        return (f"<bgdae.ModelRun: {len(self.t)} rows to t = {self.t[-1]:g}, "
                f"{len(self.names)} outputs, {self.stats['steps']} steps>")


class Model:
    """A model file (docs/model-format.md) read with replacements: set={"kp": 8,
    "boom.seg[3].L": "L1/2"} as bgsim's --set PATH=VALUE. Its unknowns, equations, outputs,
    kinds, start values and solver settings are attributes; parameter(name) reads a model
    parameter; with_set(...) loads the file again with more replacements."""

    def __init__(self, path, set=None):
        if not isinstance(path, (str, os.PathLike)):
            raise TypeError(f"path: expected a file name, got {type(path).__name__}")
        self.path = os.fspath(path)
        if set is not None and not isinstance(set, dict):
            raise TypeError(f"set: expected a dict {{path: value}}, got {type(set).__name__}")
        self.sets = {str(k): _value(k, v) for k, v in (set or {}).items()}
        self._load()

    def _load(self):
        self._m = _core.Model(self.path, list(self.sets.items()))
        info = self._m.info()
        for k in ("name", "file", "start", "unknowns", "equations", "outputs", "kinds", "y0",
                  "yp0", "nominal", "settings"):
            setattr(self, k, info[k])
        self.n = len(self.unknowns)

    def _fresh(self):
        if self._m.busy:
            raise RuntimeError(f"the model {self.name!r} is in use by another thread's call "
                               "(one call at a time on a Model)")
        if self._m.used:  # a run's static start changed the loaded model
            self._load()
        return self._m

    def with_set(self, set=None, **kw):
        """A new Model: this one's replacements, then set's and kw's."""
        s = dict(self.sets)
        s.update(set or {})
        s.update(kw)
        return Model(self.path, s)

    def parameter(self, name):
        if not isinstance(name, str):
            raise TypeError(f"name: expected a string, got {type(name).__name__}")
        return self._m.parameter(name)

    def run(self, t_end=None, output_step=None, rtol=None, atol=None, error_estimate=None):
        """The run bgsim makes (same settings, start, steps and rows): a ModelRun. The file's
        solver settings unless given; error_estimate=K (> 1; True: 100) adds the companion run
        at rtol/K, atol/K. Raises SolverError (with t, outputs of the rows computed)."""
        ov = {}
        for k, v in (("t_end", t_end), ("output_step", output_step), ("rtol", rtol),
                     ("atol", atol)):
            if v is not None:
                ov[k] = _check.real(k, v)
                if ov[k] <= 0:
                    raise ValueError(f"{k}: {ov[k]} (expected > 0)")
        k = 0.0
        if error_estimate is True:
            k = 100.0
        elif error_estimate not in (None, False):
            k = _check.real("error_estimate", error_estimate)
        try:
            r = self._fresh().run(error_estimate=k, **ov)
        except _core.SolverError as e:
            raise _check.name_unknown(e, self.unknowns)
        return ModelRun(r, self.outputs)

    def static(self):
        """The static equilibrium (with the file's trim): y, the outputs there (a dict by
        name) and the solve's report."""
        r = self._fresh().static()
        info = self._m.info()
        r["outputs"] = dict(zip(info["outputs"], r["outputs"]))
        return r

    def modes(self, t=0.0):
        """The modes at time t as bgsim --modes T finds them (t = 0: at the static
        equilibrium): dicts with frequency_hz, damping_ratio, kind, description and the
        shape over the unknowns (shape_re, shape_im; names in self.unknowns)."""
        return self._fresh().modes(_check.real("t", t))

    def __repr__(self):
        return f"<bgdae.Model {self.name!r} ({self.file}): {self.n} unknowns, {len(self.outputs)} outputs>"
