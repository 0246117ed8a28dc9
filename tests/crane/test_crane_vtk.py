#!/usr/bin/env python3
"""The crane program's ParaView series and animation (crane --vtk, --animate), end to end (TAP).

Short runs of the paper scene and the rigid boom: crane.pvd and every vtk/frame_NNNNN.vtp parse
as XML (xml.etree); the collection lists exactly the frame files, at the frame times; each
piece's arrays have one tuple per point or cell, its cells index its points, the boom has the
model's node count (model_stats.txt); frame 0 is the start (the tip and load points and the
tensions of results.csv's first row, no deflection), a later frame its row of results.csv; the
animated GIF has one image per frame (its blocks walked), the still is a PNG; a second run into
the same folder leaves no stale frames; without the options none of these files appear; bad
values are refused with exit status 2.

    test_crane_vtk.py CRANE_EXECUTABLE SCENES_DIR
"""
import csv
import math
import os
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

EXE, SCENES = sys.argv[1], sys.argv[2]
count = 0
failed = 0


def ok(cond, name, diag=None):
    global count, failed
    count += 1
    if not cond:
        failed += 1
    print(("ok" if cond else "not ok") + " %d - %s" % (count, name.replace("#", " ")))
    if not cond and diag:
        for line in str(diag).splitlines():
            print("# " + line)
    sys.stdout.flush()
    return cond


def skip(name, why):
    global count
    count += 1
    print("ok %d - %s # SKIP %s" % (count, name, why))


def run(args, timeout=120):
    p = subprocess.run([EXE] + args, capture_output=True, text=True, timeout=timeout)
    return p.returncode, p.stdout, p.stderr


def numbers(elem):
    return [float(x) for x in (elem.text or "").split()]


def tuples(values, ncomp):
    return [values[i:i + ncomp] for i in range(0, len(values), ncomp)]


def parse_vtp(path):
    """The piece of a .vtp: counts, points, arrays {name: (ncomp, values)}, cells, field."""
    root = ET.parse(path).getroot()
    assert root.tag == "VTKFile" and root.get("type") == "PolyData", "not a PolyData file"
    poly = root.find("PolyData")
    pieces = poly.findall("Piece")
    assert len(pieces) == 1, "%d pieces" % len(pieces)
    pc = pieces[0]
    d = {"np": int(pc.get("NumberOfPoints")), "nv": int(pc.get("NumberOfVerts")),
         "nl": int(pc.get("NumberOfLines")), "point": {}, "cell": {}, "field": {}}
    for name, tag in (("point", "PointData"), ("cell", "CellData")):
        for a in pc.find(tag).findall("DataArray"):
            d[name][a.get("Name")] = (int(a.get("NumberOfComponents", "1")), numbers(a))
    fd = poly.find("FieldData")
    for a in (fd.findall("DataArray") if fd is not None else []):
        d["field"][a.get("Name")] = (int(a.get("NumberOfTuples")), numbers(a))
    pts = pc.find("Points").find("DataArray")
    d["points"] = tuples(numbers(pts), int(pts.get("NumberOfComponents")))
    for kind in ("Verts", "Lines"):
        arrays = {a.get("Name"): [int(v) for v in numbers(a)]
                  for a in pc.find(kind).findall("DataArray")}
        d[kind] = (arrays["connectivity"], arrays["offsets"])
    return d


def check_piece(d):
    """Every array has one tuple per point (cell), the cells index the points."""
    errs = []
    if len(d["points"]) != d["np"] or any(len(p) != 3 for p in d["points"]):
        errs.append("points: %d tuples for %d" % (len(d["points"]), d["np"]))
    for name, (nc, vals) in d["point"].items():
        if len(vals) != nc * d["np"]:
            errs.append("point array %s: %d values for %d x %d" % (name, len(vals), d["np"], nc))
    for name, (nc, vals) in d["cell"].items():
        if len(vals) != nc * (d["nv"] + d["nl"]):
            errs.append("cell array %s: %d values" % (name, len(vals)))
    for kind, n in (("Verts", d["nv"]), ("Lines", d["nl"])):
        conn, off = d[kind]
        if len(off) != n or (off and off[-1] != len(conn)) or off != sorted(off):
            errs.append("%s: offsets %s for %d cells of %d ids" % (kind, off, n, len(conn)))
        if any(i < 0 or i >= d["np"] for i in conn):
            errs.append("%s: an index outside 0..%d" % (kind, d["np"] - 1))
    for name, (nt, vals) in d["field"].items():
        if len(vals) != nt:
            errs.append("field %s: %d values for %d tuples" % (name, len(vals), nt))
    return errs


def parse_pvd(path):
    root = ET.parse(path).getroot()
    assert root.tag == "VTKFile" and root.get("type") == "Collection", "not a collection"
    return [(float(ds.get("timestep")), ds.get("file"))
            for ds in root.find("Collection").findall("DataSet")]


def gif_info(path):
    """(width, height, images, looping) of a GIF, by walking its blocks."""
    b = open(path, "rb").read()
    assert b[:6] in (b"GIF87a", b"GIF89a"), "no GIF header"
    w, h, packed = b[6] | b[7] << 8, b[8] | b[9] << 8, b[10]
    i = 13 + (3 << ((packed & 7) + 1) if packed & 0x80 else 0)
    images, loop = 0, False

    def sub_blocks(i):
        while b[i]:
            i += b[i] + 1
        return i + 1

    while i < len(b):
        if b[i] == 0x3B:  # trailer
            return w, h, images, loop
        if b[i] == 0x21:  # extension: label, sub-blocks
            if b[i + 1] == 0xFF and b[i + 3:i + 14] == b"NETSCAPE2.0":
                loop = True
            i = sub_blocks(i + 2)
        elif b[i] == 0x2C:  # image descriptor, local colour table, LZW size, data
            images += 1
            p = b[i + 9]
            i += 10 + (3 << ((p & 7) + 1) if p & 0x80 else 0)
            i = sub_blocks(i + 1)
        else:
            raise ValueError("unexpected block 0x%02x at %d" % (b[i], i))
    raise ValueError("no trailer")


def csv_rows(path):
    with open(path) as f:
        r = list(csv.reader(f))
    head = [h.split(" ")[0] for h in r[0]]
    return [dict(zip(head, map(float, row))) for row in r[1:]]


def model_elements(out):
    for line in open(os.path.join(out, "model_stats.txt")):
        if line.startswith("boom beam elements"):
            return int(line.split()[-1])
    return -1


def scene_values(out, section, key):
    """The numbers of key in [section] of the scene as run (scene.ini)."""
    sec = None
    for line in open(os.path.join(out, "scene.ini")):
        s = line.split(";")[0].strip()
        if s.startswith("["):
            sec = s.strip("[]")
        elif sec == section and "=" in s and s.split("=")[0].strip() == key:
            return [float(x) for x in s.split("=", 1)[1].split(",")]
    return []


def dist(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


def points_of(d, part):
    parts = d["point"]["part"][1]
    return [p for p, q in zip(d["points"], parts) if q == part]


def boom_array(d, name):
    """The boom's values of a point array, by node index (node >= 0)."""
    nc, vals = d["point"][name]
    nodes = d["point"]["node"][1]
    return {int(k): vals[i * nc:(i + 1) * nc] for i, k in enumerate(nodes) if k >= 0}


def series(out, want_frames, step, elements, beam):
    """Checks the ParaView series in out; returns the parsed frames."""
    pvd = os.path.join(out, "crane.pvd")
    try:
        listed = parse_pvd(pvd)
    except Exception as e:  # noqa: BLE001 - reported as a test failure
        ok(False, "crane.pvd parses", e)
        return []
    ok(True, "crane.pvd parses as a VTK collection")
    ok(len(listed) == want_frames,
       "crane.pvd lists %d frames (want %d)" % (len(listed), want_frames))
    ok(all(abs(t - k * step) < 1e-9 for k, (t, _) in enumerate(listed)),
       "the frames' times are 0, %g, %g, ..." % (step, 2 * step), [t for t, _ in listed])
    on_disk = sorted("vtk/" + f for f in os.listdir(os.path.join(out, "vtk")))
    ok(sorted(f for _, f in listed) == on_disk,
       "the collection lists every .vtp in vtk/ and no other (%d files)" % len(on_disk),
       "listed %s\non disk %s" % ([f for _, f in listed], on_disk))
    frames, errs = [], []
    for t, f in listed:
        try:
            d = parse_vtp(os.path.join(out, f))
        except Exception as e:  # noqa: BLE001
            errs.append("%s: %s" % (f, e))
            continue
        errs += ["%s: %s" % (f, e) for e in check_piece(d)]
        if abs(d["field"]["TimeValue"][1][0] - t) > 1e-9:
            errs.append("%s: TimeValue %g, timestep %g" % (f, d["field"]["TimeValue"][1][0], t))
        frames.append(d)
    ok(not errs and len(frames) == len(listed),
       "every .vtp parses; arrays of one tuple per point and cell; cells index the points",
       "\n".join(errs[:10]))
    nb = [len(points_of(d, 1)) for d in frames]
    ok(nb and all(n == elements + 1 for n in nb) if beam else all(n == 2 for n in nb),
       "boom points per frame %s = the model's nodes (%d elements)" % (sorted(set(nb)), elements))
    names = {"part", "node", "mass", "deflection", "deflection_luff", "deflection_side"}
    if beam:
        names |= {"section_force", "section_moment", "section_force_local", "section_moment_local"}
    have = set(frames[0]["point"]) if frames else set()
    ok(have == names, "point data arrays: %s" % ", ".join(sorted(have)), "want %s" % sorted(names))
    return frames


def main():
    tmp = tempfile.mkdtemp(prefix="crane_vtk_")
    try:
        tests(tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print("1..%d" % count)
    return 1 if failed else 0


def tests(tmp):
    gnuplot = shutil.which("gnuplot") is not None
    paper = os.path.join(SCENES, "paper.ini")
    out = os.path.join(tmp, "paper")
    rc, so, se = run([paper, "--t-end", "0.5", "--out", out, "--no-plots", "--quiet", "--vtk",
                      "--animate"])
    if not ok(rc == 0, "paper --t-end 0.5 --vtk --animate: exit 0", se):
        return
    elements = model_elements(out)
    frames = series(out, 11, 0.05, elements, True)
    rows = csv_rows(os.path.join(out, "results.csv"))
    if frames:
        f0, r0 = frames[0], rows[0]
        pts = {int(k): p for p, k in zip(f0["points"], f0["point"]["node"][1]) if k >= 0}
        ok(dist(pts[elements], [r0["tip_x"], r0["tip_y"], r0["tip_z"]]) < 1e-6,
           "frame 0: tip node = the start's tip_x/y/z", (pts[elements], r0))
        foot = scene_values(out, "boom", "foot")
        ok(len(foot) == 3 and dist(pts[0], foot) < 1e-3,
           "frame 0: node 0 at the boom foot %s" % foot, pts[0])
        chord = [pts[elements][i] - pts[0][i] for i in range(3)]
        L = math.sqrt(sum(c * c for c in chord))
        off = max(math.sqrt(max(0.0, dist(p, pts[0]) ** 2 -
                                (sum((p[i] - pts[0][i]) * chord[i] for i in range(3)) / L) ** 2))
                  for p in pts.values())
        ok(abs(L - 76) < 0.05 and off < 0.1,
           "frame 0: the boom's nodes on its 76 m chord (length %.4f m, off by %.3g m)" % (L, off))
        load = points_of(f0, 3)
        ok(len(load) == 1 and dist(load[0], [r0["load_x"], r0["load_y"], r0["load_z"]]) < 1e-6,
           "frame 0: load point = the start's load_x/y/z")
        masses = sorted(v for v in f0["point"]["mass"][1] if v)
        want = sorted(scene_values(out, "load", "mass") +
                      scene_values(out, "counterweight", "mass"))
        ok(masses == want and len(masses) == 2,
           "point masses: load and counterweight %s kg" % masses, want)
        dmax = max(abs(v) for n in ("deflection", "deflection_luff", "deflection_side")
                   for v in f0["point"][n][1])
        ok(dmax < 1e-9, "frame 0: no deflection (%.3g m)" % dmax)
        fd = f0["field"]
        ok(abs(fd["rope_tension"][1][0] - r0["rope_force"]) < 1e-6 * r0["rope_force"] and
           fd["tie_tension"][0] == 2 and abs(fd["p_high"][1][0] - r0["p_high"]) < 1e-3,
           "frame 0: rope tension, two tie tensions, p_high as results.csv")
        parts = f0["cell"]["part"][1]
        ok(sorted(set(int(p) for p in parts)) == list(range(8)) and
           sum(1 for p in parts if p == 5) == 2,
           "cells of every part (platform, boom, gantry, load, counterweight, 2 ties, rope, foot)",
           parts)
        # frame 5 at t = 0.25 against results.csv's row there
        f5 = frames[5]
        r = min(rows, key=lambda q: abs(q["t"] - 0.25))
        p5 = {int(k): p for p, k in zip(f5["points"], f5["point"]["node"][1]) if k >= 0}
        dl = boom_array(f5, "deflection_luff")[elements][0]
        ds = boom_array(f5, "deflection_side")[elements][0]
        ok(abs(r["t"] - 0.25) < 1e-12 and
           dist(p5[elements], [r["tip_x"], r["tip_y"], r["tip_z"]]) < 1e-6 and
           abs(dl - r["tip_defl_1"]) < 1e-8 and abs(ds - r["tip_defl_2"]) < 1e-8 and abs(ds) > 1e-3,
           "frame 5 (t = 0.25 s): tip and its deflections (%.4g, %.4g m) = results.csv" % (dl, ds))
        N = [v[0] for v in boom_array(f5, "section_force_local").values()]
        ok(all(n < 0 for n in N),
           "frame 5: the boom in compression (N %.4g .. %.4g N)" % (min(N), max(N)))
    # the animation
    dat = open(os.path.join(out, "anim.dat")).read()
    ok(dat.count("# frame ") == 6 and
       len([l for l in open(os.path.join(out, "anim_track.dat")) if not l.startswith("#")]) == 6,
       "anim.dat and anim_track.dat: 6 frames (0.5 s every 0.1 s)")
    ok(os.path.exists(os.path.join(out, "anim.gp")), "anim.gp written")
    if gnuplot:
        try:
            w, h, images, loop = gif_info(os.path.join(out, "crane.gif"))
            ok(images == 6 and loop,
               "crane.gif: %d images (want 6), %dx%d, looping" % (images, w, h))
        except Exception as e:  # noqa: BLE001
            ok(False, "crane.gif: a GIF", e)
        png = open(os.path.join(out, "crane_frame.png"), "rb").read(8)
        ok(png == b"\x89PNG\r\n\x1a\n", "crane_frame.png: a PNG")
    else:
        skip("crane.gif: 6 images", "gnuplot not installed")
        skip("crane_frame.png", "gnuplot not installed")

    # the rigid boom; then fewer frames into the same folder: no stale frames
    rigid = os.path.join(SCENES, "rigid-boom.ini")
    out = os.path.join(tmp, "rigid")
    rc, so, se = run([rigid, "--t-end", "0.5", "--out", out, "--no-plots", "--quiet", "--vtk"])
    ok(rc == 0 and len(os.listdir(os.path.join(out, "vtk"))) == 11,
       "rigid boom --vtk: 11 frames", se)
    rc, so, se = run([rigid, "--t-end", "0.5", "--out", out, "--no-plots", "--quiet",
                      "--vtk-step", "0.25"])
    ok(rc == 0, "rigid boom --vtk-step 0.25 into the same folder: exit 0", se)
    series(out, 3, 0.25, model_elements(out), False)
    ok(not os.path.exists(os.path.join(out, "anim.dat")), "no animation without --animate")

    # nothing without the options; bad values
    out = os.path.join(tmp, "plain")
    rc, so, se = run([paper, "--t-end", "0.05", "--out", out, "--no-plots", "--quiet"])
    extra = [f for f in ("crane.pvd", "vtk", "anim.dat", "anim_track.dat", "anim.gp", "crane.gif",
                         "crane_frame.png") if os.path.exists(os.path.join(out, f))]
    ok(rc == 0 and not extra, "without --vtk and --animate: none of their files", extra)
    for args in (["--vtk-step", "0"], ["--anim-scale", "abc"], ["--anim-step=-1"], ["--vtk=1"]):
        rc, so, se = run([paper, "--t-end", "0.05", "--out", out, "--quiet"] + args)
        ok(rc == 2 and args[0].split("=")[0] in se, "%s: exit 2 naming the option" % " ".join(args),
           (rc, se))


if __name__ == "__main__":
    sys.exit(main())
