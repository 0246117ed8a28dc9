#!/usr/bin/env python3
"""Compares the symbols a shared library exports with what its public headers declare.

    check-exports.py [--tap] [--cc CC] [-I DIR]... LIBRARY HEADER...

The headers are preprocessed together (CC -E, default $CC or cc; the folder of each header is on
the include path besides the -I folders) and every function or object
declared at file scope in one of them is collected: declarations in other files (the system
headers they include), typedefs, static (inline) functions, and struct, union and enum tags are
left out. The exported symbols are the defined dynamic symbols of LIBRARY (nm -D
--defined-only); names beginning with an underscore are the toolchain's (sanitizer and coverage
runtimes), not the library's, and are ignored, as are the few that gcc's coverage runtime
(libgcov, linked into a --coverage build) exports without one (TOOLCHAIN below). Prints one line per symbol found on one side
only and exits with status 1 when there is any, with status 0 (and a line with the count)
when both sides agree; status 2 when the tools fail. --tap: the result as one TAP test point (for meson test),
the symbols as comments."""
import os
import re
import subprocess
import sys
import tempfile

TOKEN = re.compile(r"""
    (?P<ws>\s+)
  | (?P<str>"(?:\\.|[^"\\])*" | '(?:\\.|[^'\\])*')
  | (?P<id>[A-Za-z_]\w*)
  | (?P<num>\.?\d(?:[\w.]|[eEpP][+-])*)
  | (?P<op>\.\.\.|->|[^\s\w])
""", re.X)


def preprocess(cc, headers, incdirs):
    """The text the headers contribute, with the system headers' lines left out."""
    with tempfile.NamedTemporaryFile("w", suffix=".c", delete=False) as f:
        for h in headers:
            f.write('#include "%s"\n' % os.path.abspath(h))
        src = f.name
    try:
        dirs = incdirs + [os.path.dirname(os.path.abspath(h)) for h in headers]
        cmd = cc.split() + ["-E", "-std=c11"] + ["-I" + d for d in dict.fromkeys(dirs)] + [src]
        out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    finally:
        os.unlink(src)
    ours = {os.path.realpath(h) for h in headers}
    keep, text = False, []
    for line in out.splitlines():
        m = re.match(r'#\s*(?:line\s+)?\d+\s+"([^"]*)"', line)
        if m:
            keep = os.path.realpath(m.group(1)) in ours
        elif keep and not line.startswith("#"):
            text.append(line)
    return "\n".join(text)


def tokens(text):
    for m in TOKEN.finditer(text):
        if m.lastgroup != "ws":
            yield m.group()


def strip_groups(toks, open_, close):
    """toks without the bracketed groups open_ ... close (nested)."""
    out, depth = [], 0
    for t in toks:
        if t == open_:
            depth += 1
        elif t == close:
            depth -= 1
        elif depth == 0:
            out.append(t)
    return out


def strip_attributes(toks):
    out, i = [], 0
    while i < len(toks):
        if toks[i] in ("__attribute__", "__attribute", "__declspec", "__asm__", "__asm", "asm"):
            i += 1
            depth = 0
            while i < len(toks):
                depth += toks[i] == "("
                depth -= toks[i] == ")"
                i += 1
                if depth == 0:
                    break
        else:
            out.append(toks[i])
            i += 1
    return out


def declared_names(text):
    """Names of the functions and objects declared (not static, not typedef) at file scope."""
    names = set()
    decl, brace, paren = [], 0, 0
    toks = list(tokens(text))
    for i, t in enumerate(toks):
        decl.append(t)
        if t == "{":
            brace += 1
        elif t == "}":
            brace -= 1
            # the end of a function body (a static inline function): no ';' follows
            if brace == 0 and paren == 0 and ")" in strip_groups(decl[:-1], "{", "}") \
                    and (i + 1 == len(toks) or toks[i + 1] != ";") \
                    and decl[0] not in ("typedef", "struct", "union", "enum"):
                decl = []
        elif t == "(":
            paren += 1
        elif t == ")":
            paren -= 1
        elif t == ";" and brace == 0 and paren == 0:
            names |= names_of(decl[:-1])
            decl = []
    return names


def names_of(decl):
    d = strip_attributes(decl)
    d = strip_groups(d, "{", "}")
    if not d or d[0] in ("typedef", "_Static_assert", "static_assert"):
        return set()
    head = d[: d.index("(")] if "(" in d else d
    if "static" in head:
        return set()
    # declarators, split at commas outside parentheses and brackets
    parts, cur, depth = [], [], 0
    for t in d:
        depth += t in "(["
        depth -= t in ")]"
        if t == "," and depth == 0:
            parts.append(cur)
            cur = []
        else:
            cur.append(t)
    parts.append(cur)
    found = set()
    for p in parts:
        if "=" in p:
            p = p[: p.index("=")]
        name = None
        for j, t in enumerate(p):
            if t == "(":
                if j + 1 < len(p) and p[j + 1] == "*":  # (*name)(...): a function pointer
                    ids = [x for x in p[j + 2:] if re.match(r"[A-Za-z_]\w*$", x)]
                    name = ids[0] if ids else None
                break
            if t == "[":
                break
            if re.match(r"[A-Za-z_]\w*$", t) and t not in ("struct", "union", "enum"):
                name = t
        # a bare "struct tag" (a forward declaration) declares no object
        if name and not (len(p) == 2 and p[0] in ("struct", "union", "enum")):
            found.add(name)
    return found


TOOLCHAIN = {"mangle_path"}  # libgcov's, in a build with --coverage


def exported(lib):
    out = subprocess.run(["nm", "-D", "--defined-only", lib], check=True, capture_output=True,
                         text=True).stdout
    syms = set()
    for line in out.splitlines():
        f = line.split()
        if len(f) >= 3 and not f[2].startswith("_") and f[2].split("@")[0] not in TOOLCHAIN:
            syms.add(f[2].split("@")[0])
    return syms


def main(argv):
    cc = os.environ.get("CC", "cc")
    lib, headers, incdirs, tap = None, [], [], False
    args = iter(argv)
    for a in args:
        if a == "--tap":
            tap = True
        elif a == "-I":
            incdirs.append(next(args))
        elif a.startswith("-I"):
            incdirs.append(a[2:])
        elif a == "--cc":
            cc = next(args)
        elif lib is None:
            lib = a
        else:
            headers.append(a)
    if lib is None or not headers:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    name = "exported symbols of %s = declarations of %d public headers" % (
        os.path.basename(lib), len(headers))
    if tap:
        print("1..1")
    try:
        declared = declared_names(preprocess(cc, headers, incdirs))
        syms = exported(lib)
    except (OSError, subprocess.CalledProcessError) as e:
        err = getattr(e, "stderr", None)
        msg = "check-exports: %s%s" % (e, "\n" + err if err else "")
        if tap:
            print("\n".join("# " + l for l in msg.splitlines()))
            print("not ok 1 - %s: the tools failed" % name)
        else:
            print(msg, file=sys.stderr)
        return 2
    missing = sorted(declared - syms)
    extra = sorted(syms - declared)
    lines = ["declared in the public headers, not exported: %s" % n for n in missing]
    lines += ["exported, not declared in the public headers: %s" % n for n in extra]
    if missing or extra:
        summary = "%d declared but not exported, %d exported but not declared" % (
            len(missing), len(extra))
        if tap:
            print("\n".join("# " + l for l in lines))
            print("not ok 1 - %s: %s" % (name, summary))
        else:
            print("\n".join(lines))
            print("check-exports: %s (%s)" % (summary, lib))
        return 1
    print("%s%s (%d symbols)" % ("ok 1 - " if tap else "", name, len(syms)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
