#!/usr/bin/env python3
"""The integrator's file index (the header comment of solver/bg_dae_impl.h) against solver/.

Method: the index's entries are the lines " *   NAME.c|h  description" of the comment; the
paragraph after them ("The rest of solver/ ...") names the other files, by their base name
(bg_sparse: bg_sparse.c and bg_sparse.h) or in full. Every file of solver/ (*.c, *.h) must be
named in one of the two, every entry of the index must be a file of solver/, and the integrator's
own files (bg_dae*, dae_*) must be in the index itself, so that a file added or removed without
the index fails here. TAP on stdout; exit status 1 on a failure.

usage: check_dae_index.py SOLVER_DIR
"""
import os
import re
import sys


def main():
    solver = sys.argv[1]
    with open(os.path.join(solver, "bg_dae_impl.h"), encoding="utf-8") as f:
        text = f.read()
    comment = text[: text.index("*/")]
    index = re.findall(r"^ \*   (\w+\.[ch])\s", comment, re.M)
    rest_at = comment.find("The rest of solver/")
    rest = comment[rest_at:] if rest_at >= 0 else ""
    rest_names = set(re.findall(r"\b(bg_\w+(?:\.[ch])?)\b", rest))
    files = sorted(n for n in os.listdir(solver) if n.endswith((".c", ".h")))

    checks = []
    checks.append((len(index) > 0 and rest_at >= 0,
                   "bg_dae_impl.h has the index and its 'The rest of solver/' paragraph", ""))
    missing = [n for n in index if n not in files]
    checks.append((not missing, "every file of the index is in solver/",
                   "in the index, not in solver/: " + ", ".join(missing)))
    unnamed = [n for n in files
               if n not in index and n not in rest_names and os.path.splitext(n)[0] not in rest_names]
    checks.append((not unnamed, "every file of solver/ is named in the index or after it",
                   "not named in bg_dae_impl.h's index: " + ", ".join(unnamed)))
    own = [n for n in files if (n.startswith("dae_") or n.startswith("bg_dae")) and n not in index]
    checks.append((not own, "the integrator's files (bg_dae*, dae_*) are all in the index",
                   "integrator files missing from the index: " + ", ".join(own)))
    twice = sorted({n for n in index if index.count(n) > 1})
    checks.append((not twice, "no file twice in the index", "twice: " + ", ".join(twice)))

    print("1..%d" % len(checks))
    bad = 0
    for i, (ok, name, diag) in enumerate(checks, 1):
        print("%s %d - %s" % ("ok" if ok else "not ok", i, name))
        if not ok:
            bad += 1
            print("# " + diag)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
