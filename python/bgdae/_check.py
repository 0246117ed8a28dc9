"""Argument checks: every refusal names the argument and says what was expected."""
import math
import numbers
import re

import numpy as np


def callable_arg(name, f, optional=False):
    if f is None and optional:
        return None
    if not callable(f):
        raise TypeError(f"{name}: expected a callable, got {type(f).__name__}")
    return f


def real(name, x):
    if isinstance(x, bool) or not isinstance(x, numbers.Real):
        raise TypeError(f"{name}: expected a real number, got {type(x).__name__}")
    x = float(x)
    if not math.isfinite(x):
        raise ValueError(f"{name}: {x} is not finite")
    return x


def integer(name, x):
    if isinstance(x, bool):
        return int(x)
    if not isinstance(x, numbers.Integral):
        raise TypeError(f"{name}: expected an integer, got {type(x).__name__}")
    return int(x)


def vector(name, x, n=None, finite=True):
    """A 1-D float64 array (a copy) of n values (any number if n is None), all finite."""
    a = np.asarray(x)
    if a.dtype == object or not (np.issubdtype(a.dtype, np.floating)
                                 or np.issubdtype(a.dtype, np.integer)
                                 or a.dtype == np.bool_):
        raise TypeError(f"{name}: expected real numbers, got dtype {a.dtype}")
    if a.ndim != 1:
        raise ValueError(f"{name}: expected a 1-D array, got shape {a.shape}")
    if n is not None and a.shape[0] != n:
        raise ValueError(f"{name}: expected {n} values, got {a.shape[0]}")
    a = np.array(a, dtype=np.float64)
    if finite and not np.all(np.isfinite(a)):
        i = int(np.flatnonzero(~np.isfinite(a))[0])
        raise ValueError(f"{name}: {name}[{i}] is {a[i]} (expected finite values)")
    return a


def names(name, x, n):
    if x is None:
        return None
    if isinstance(x, str):
        raise TypeError(f"{name}: expected a sequence of {n} strings, got a string")
    x = list(x)
    if len(x) != n:
        raise ValueError(f"{name}: expected {n} names, got {len(x)}")
    for i, s in enumerate(x):
        if not isinstance(s, str):
            raise TypeError(f"{name}: {name}[{i}] is a {type(s).__name__}, expected a string")
    return x


KIND_NAMES = {"differential": 0, "diff": 0, "algebraic": 1, "alg": 1, "index1": 1,
              "index2": 2, "index-2": 2, "alg2": 2}


def kinds(x, n):
    if x is None:
        return None
    out = []
    for i, k in enumerate(list(x) if not isinstance(x, str) else [x]):
        if isinstance(k, str):
            if k.lower() not in KIND_NAMES:
                raise ValueError(f"kinds: kinds[{i}] = {k!r} (expected one of "
                                 "'differential', 'algebraic', 'index2')")
            out.append(KIND_NAMES[k.lower()])
        elif isinstance(k, numbers.Integral) and 0 <= int(k) <= 2:
            out.append(int(k))
        else:
            raise ValueError(f"kinds: kinds[{i}] = {k!r} (expected 0, 1, 2 or a kind's name)")
    if len(out) != n:
        raise ValueError(f"kinds: expected {n} values, got {len(out)}")
    return np.array(out, dtype=np.int32)


def pattern(name, p, n):
    """A pattern as (indptr, indices) int32 arrays, rows ascending in each column: from a
    scipy.sparse matrix (its stored entries) or a dense (n, n) array (its nonzeros)."""
    if p is None:
        return None
    if hasattr(p, "tocsc"):
        if p.shape != (n, n):
            raise ValueError(f"{name}: expected shape ({n}, {n}), got {p.shape}")
        c = p.tocsc(copy=True)
        c.sum_duplicates()
        c.sort_indices()
        return (np.ascontiguousarray(c.indptr, dtype=np.int32),
                np.ascontiguousarray(c.indices, dtype=np.int32))
    a = np.asarray(p)
    if a.dtype == object or not (np.issubdtype(a.dtype, np.number) or a.dtype == np.bool_):
        raise TypeError(f"{name}: expected a 2-D array or a scipy.sparse matrix, "
                        f"got dtype {a.dtype}")
    if a.shape != (n, n):
        raise ValueError(f"{name}: expected shape ({n}, {n}), got {a.shape}")
    nz = a != 0
    indptr = np.zeros(n + 1, dtype=np.int32)
    indptr[1:] = np.cumsum(nz.sum(axis=0))
    indices = np.nonzero(nz.T)[1].astype(np.int32)
    return indptr, indices


def name_unknown(exc, names):
    """exc.unknown: the first unknown the solver's message names (a name of names, or "y[i]"
    when the problem has none), None when it names none."""
    msg = getattr(exc, "message", "") or ""
    found = None
    if names:
        best = len(msg) + 1
        for nm in names:
            m = re.search(r"(?<![\w/.\[])" + re.escape(nm) + r"(?![\w/.\[])", msg)
            if m and m.start() < best:
                best, found = m.start(), nm
    else:
        m = re.search(r"\by\[(\d+)\]", msg)
        found = m.group(0) if m else None
    exc.unknown = found
    return exc
