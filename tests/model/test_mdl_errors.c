/* The model reader's errors: each bad input is refused (NULL) with a message that names the
 * file, line and column, the component path or key, and what was expected (the nearest names
 * where a name is unknown). Also the features around them that must work: subsystems nested
 * two deep with outer ports, repetition with bonds between the repeated instances, includes
 * (read once, a loop refused), replacements of component parameters. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bgr_model.h"
#include "mdl_model.h"
#include "tap.h"

#define HEAD "format: bgsim 1\nname: t\n"
/* a mass on a spring from a fixed point: every port bonded */
#define SPRING                                                                                     \
    "components:\n"                                                                                \
    "  top: {type: mech.support, dim: 3}\n"                                                        \
    "  spring: {type: mech.spring, k: 100, L0: 1}\n"                                               \
    "  load: {type: mech.point_mass, mass: 2, position: [0, 0, -1]}\n"                             \
    "bonds:\n"                                                                                     \
    "  - top.p -> spring.a\n"                                                                      \
    "  - spring.b -> load.p\n"

typedef struct bad {
    const char *what, *text, *want[4];
} bad;

static const bad cases[] = {
    {"no format line", "name: t\n" SPRING, {"m.yaml:1:1", "format", "bgsim 1"}},
    {"unknown top-level key", HEAD "componets: {}\n" SPRING, {"m.yaml:3:1", "componets", "components"}},
    {"unknown type, nearest named", HEAD "components:\n  p: {type: hyd.pmup}\n",
     {"m.yaml:4:13", "hyd.pmup", "did you mean 'hyd.pump'"}},
    {"unknown parameter, nearest named",
     HEAD "components:\n  top: {type: mech.support, dim: 3}\n"
          "  spring: {type: mech.spring, k: 100, L00: 1}\n",
     {"m.yaml:5:39", "spring", "'L00'", "did you mean 'L0'"}},
    {"value out of range, with its unit",
     HEAD "components:\n  s: {type: mech.spring, k: -100, L0: 1}\n",
     {"m.yaml:4:29", "s.k", "-100 is out of range", "N/m"}},
    {"required parameter missing", HEAD "components:\n  s: {type: mech.spring, k: 100}\n",
     {"m.yaml:4:3", "needs 'L0'", "m"}},
    {"unknown port, the element's ports listed",
     HEAD "components:\n  top: {type: mech.support, dim: 3}\n  s: {type: mech.spring, k: 1, L0: 1}\n"
          "bonds:\n  - top.p -> s.c\n",
     {"m.yaml:7:5", "no port 'c'", "its ports: a, b"}},
    {"unknown component in a path",
     HEAD "components:\n  top: {type: mech.support, dim: 3}\nbonds:\n  - top.p -> sprng.a\n",
     {"m.yaml:6:5", "no component 'sprng'"}},
    {"port left unbonded", HEAD "components:\n  top: {type: mech.support, dim: 3}\n",
     {"m.yaml:4:3", "top", "port 'p'", "not bonded"}},
    {"bond joining 3D and 6D ports",
     HEAD "components:\n  a: {type: mech.support, dim: 6}\n  b: {type: mech.free, dim: 3}\n"
          "bonds:\n  - a.p -> b.p\n",
     {"m.yaml:7:5", "6D port", "3D port"}},
    {"bond joining hydraulic and rotational ports",
     HEAD "components:\n  t: {type: hyd.tank, pressure: 1e5}\n  j: {type: rot.damper, b: 1}\n"
          "bonds:\n  - t.p -> j.p\n",
     {"m.yaml:7:5", "hydraulic", "rotational"}},
    {"port bonded twice",
     HEAD "components:\n  a: {type: mech.support, dim: 3}\n  b: {type: mech.free, dim: 3}\n"
          "  c: {type: mech.free, dim: 3}\nbonds:\n  - a.p -> b.p\n  - a.p -> c.p\n",
     {"m.yaml:9:5", "bonded already", "m.yaml:8:5"}},
    {"cycle among parameters", HEAD "parameters: {a: b + 1, b: 2*c, c: a}\n" SPRING,
     {"m.yaml:3", "cycle", "a -> b -> c -> a"}},
    {"unknown name in an expression", HEAD "parameters: {a: 2*bb}\n" SPRING,
     {"m.yaml:3:17", "unknown name 'bb'"}},
    {"syntax error in an expression, its column", HEAD "parameters: {a: 2*(3 + }\n" SPRING,
     {"m.yaml:3", "a:", "'2*(3 +'"}},
    {"parameter named like a function", HEAD "parameters: {sin: 1}\n" SPRING,
     {"m.yaml:3:14", "'sin'", "function or constant"}},
    {"subsystem containing itself",
     HEAD "subsystems:\n  loop:\n    components:\n      x: {type: loop}\n"
          "components:\n  l: {type: loop}\n",
     {"m.yaml:6:17", "l.x", "contains itself"}},
    {"structurally singular model",
     HEAD "components:\n  j: {type: bg.one, ports: [a, b, c], dim: 1}\n"
          "  s1: {type: bg.Sf, value: [1]}\n  s2: {type: bg.Sf, value: [1]}\n"
          "  r: {type: bg.R, resistance: 2}\n"
          "bonds:\n  - s1.p -> j.a\n  - s2.p -> j.b\n  - j.c -> r.p\n",
     {"m.yaml", "structurally singular", "equations t/", "unknowns t/"}},
    {"YAML syntax error", HEAD "components: {a: [}\n", {"m.yaml:3", "flow"}},
    {"a vector of the wrong length",
     HEAD "components:\n  m: {type: mech.point_mass, mass: 1, gravity: [0, -9.81]}\n"
          "  f: {type: mech.free, dim: 3}\nbonds:\n  - m.p -> f.p\n",
     {"m.yaml:4:48", "m.gravity", "expected 3 numbers, got 2"}},
    {"signal offered by nobody",
     HEAD "components:\n  c: {type: sig.constant, value: 1}\n  g: {type: sig.gain, input: c.z, gain: 2}\n",
     {"m.yaml:5:30", "g.input", "no signal 'z'", "its signals: y"}},
};

static int has_all(const char *msg, const char *const *want)
{
    for (int i = 0; i < 4 && want[i]; i++)
        if (!strstr(msg, want[i])) return 0;
    return 1;
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

int main(void)
{
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        bg_error e = {0};
        mdl_model *mm = mdl_load_string(cases[i].text, "m.yaml", NULL, 0, &e);
        tap_ok(!mm && has_all(e.message, cases[i].want), "%s: %s", cases[i].what,
               mm ? "accepted" : e.message);
        mdl_free(&mm);
    }

    /* nesting, outer ports, repetition with bonds between the repeated instances, a replacement
     * of a component's parameter */
    static const char *chain =
        HEAD "parameters: {n: 3}\n"
             "subsystems:\n"
             "  spring2:\n"
             "    parameters: {k: 1}\n"
             "    ports: {a: s.a, b: s.b}\n"
             "    components:\n"
             "      s: {type: mech.spring, k: k, L0: 0.5}\n"
             "  link:\n"
             "    parameters: {k: 1, z: 0}\n"
             "    ports: {a: inner.a, b: node.b}\n"
             "    components:\n"
             "      inner: {type: spring2, k: 2*k}\n"
             "      node:\n"
             "        type: mech.body\n"
             "        mass: 1\n"
             "        inertia: [1e-3, 0, 0, 0, 1e-3, 0, 0, 0, 1e-3]\n"
             "        gravity: [0, 0, -9.81]\n"
             "        points: {a: {r: [0, 0, 0], dim: 3}, b: {r: [0, 0, 0], dim: 3}}\n"
             "        position: [0, 0, z]\n"
             "    bonds: [inner.b -> node.a]\n"
             "components:\n"
             "  top: {type: mech.support, dim: 3}\n"
             "  seg: {for: {i: [0, n - 1]}, type: link, k: 100*(i + 1), z: -0.5*(i + 1)}\n"
             "  load: {type: mech.point_mass, mass: 1, gravity: [0, 0, -9.81], position: [0, 0, -1.5]}\n"
             "bonds:\n"
             "  - top.p -> seg[0].a\n"
             "  - {from: \"seg[i].b\", to: \"seg[i+1].a\", for: {i: [0, n - 2]}}\n"
             "  - seg[2].b -> load.p\n"
             "outputs: {z: load.x2}\n";
    bg_error e = {0};
    mdl_set set = {"seg[1].k", "7"};
    mdl_model *mm = mdl_load_string(chain, "chain.yaml", &set, 1, &e);
    tap_ok(mm != NULL, "three links of two nested subsystems, bonded in a loop (%s)",
           mm ? "ok" : e.message);
    if (mm) {
        tap_ok(bgr_find_var(mdl_bgr(mm), "t/seg[2]/inner/s/d0") >= 0,
               "unknowns named through the nesting (t/seg[2]/inner/s/d0)");
        /* springs in series, k_i = 2 * 100 (i + 1) but seg[1]'s replaced by 7: 200, 14, 600,
         * carrying 4, 3 and 2 unit masses (the nodes' and the load's) */
        double z = 0;
        int r = mdl_static(&mm, NULL, NULL, &e);
        if (r == BG_OK) r = mdl_outputs(mm, 0, bgr_y0(mdl_bgr(mm)), &z, &e);
        tap_ok(r == BG_OK, "static rest of the chain (%s)", r == BG_OK ? "ok" : e.message);
        tap_close(z, -(1.5 + 9.81 * (4 / 200.0 + 3 / 14.0 + 2 / 600.0)), 1e-7, 0,
                  "rests at -(3 L0 + g sum m_i/k_i): the nesting, the loop and the replacement");
        mdl_free(&mm);
    }
    set.path = "seg[9].k";
    mm = mdl_load_string(chain, "chain.yaml", &set, 1, &e);
    tap_ok(!mm && strstr(e.message, "--set") && strstr(e.message, "seg[9].k"),
           "a replacement naming no parameter is refused (%s)", e.message);
    mdl_free(&mm);

    /* includes: parameters and subsystems from another file, read once; a loop refused */
    char dir[] = "/tmp/mdl_errors_XXXXXX";
    if (!mkdtemp(dir)) return tap_done();
    char a[256], b[256], main_path[256], loop_a[256], loop_b[256];
    snprintf(a, sizeof a, "%s/lib.yaml", dir);
    snprintf(b, sizeof b, "%s/more.yaml", dir);
    snprintf(main_path, sizeof main_path, "%s/main.yaml", dir);
    write_file(a, "format: bgsim 1\nname: lib\nparameters: {k: 250}\ninclude: [more.yaml]\n"
                  "subsystems:\n  spring1:\n    parameters: {k: 1}\n    ports: {a: s.a, b: s.b}\n"
                  "    components:\n      s: {type: mech.spring, k: k, L0: 1}\n");
    write_file(b, "format: bgsim 1\nname: more\nparameters: {m: 3, k: 999}\n");
    write_file(main_path, HEAD "include: [lib.yaml, more.yaml]\nparameters: {k: 400}\n"
                                "components:\n  top: {type: mech.support, dim: 3}\n"
                                "  sp: {type: spring1, k: k}\n"
                                "  load: {type: mech.point_mass, mass: m, position: [0, 0, -1]}\n"
                                "bonds:\n  - top.p -> sp.a\n  - sp.b -> load.p\n");
    mm = mdl_load(main_path, NULL, 0, &e);
    double k = 0, m = 0;
    tap_ok(mm && mdl_parameter(mm, "k", &k) == BG_OK && mdl_parameter(mm, "m", &m) == BG_OK &&
               k == 400 && m == 3,
           "includes: the including file's k wins (%g), m comes from an include of an include (%g)%s%s",
           k, m, mm ? "" : ": ", mm ? "" : e.message);
    mdl_free(&mm);
    snprintf(loop_a, sizeof loop_a, "%s/la.yaml", dir);
    snprintf(loop_b, sizeof loop_b, "%s/lb.yaml", dir);
    write_file(loop_a, "format: bgsim 1\nname: la\ninclude: [lb.yaml]\n");
    write_file(loop_b, "format: bgsim 1\nname: lb\ninclude: [la.yaml]\n");
    write_file(main_path, HEAD "include: [la.yaml]\n" SPRING);
    mm = mdl_load(main_path, NULL, 0, &e);
    tap_ok(!mm && strstr(e.message, "lb.yaml:3:11") && strstr(e.message, "include loop"),
           "an include loop is refused where it closes (%s)", e.message);
    mdl_free(&mm);
    write_file(main_path, HEAD "include: [nothere.yaml]\n" SPRING);
    mm = mdl_load(main_path, NULL, 0, &e);
    tap_ok(!mm && strstr(e.message, "main.yaml:3:11") && strstr(e.message, "nothere.yaml"),
           "a missing include is named (%s)", e.message);
    mdl_free(&mm);
    unlink(a), unlink(b), unlink(main_path), unlink(loop_a), unlink(loop_b);
    rmdir(dir);
    return tap_done();
}
