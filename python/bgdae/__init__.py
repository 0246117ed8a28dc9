"""bgdae from Python: the modified-BDF solver for index-2 DAEs F(t, y, y') = 0 and the
project's model files, on numpy arrays (docs/python.md).

    import bgdae
    sol = bgdae.DAE(F, y0).solve([1.0, 2.0])        # F(t, y, yp) -> residual array
    run = bgdae.Model("crane/models/paper.yaml").run(t_end=1.0)

DAE: a residual (and optionally its Jacobians) as Python callables; solve, static, modes.
Model: a model file (the C residual and Jacobian; the integration runs without the GIL).
SolverError: a failure of the library, with its message, status, code and time.
"""
from ._core import SolverError
from ._dae import DAE, Solution, DIFFERENTIAL, ALGEBRAIC, INDEX2, default_options
from ._model import Model, ModelRun

__all__ = ["DAE", "Solution", "Model", "ModelRun", "SolverError", "DIFFERENTIAL",
           "ALGEBRAIC", "INDEX2", "default_options"]
