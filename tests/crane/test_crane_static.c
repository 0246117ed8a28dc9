/* The crane's static start and modes (crane/crane_static.h) and the program's --static and
 * --modes:
 *   - the paper scene at rest: the tip at the scene's radius, the rope carrying the load's
 *     weight, the two ties the same tension, the base carrying the whole weight, theta = 0,
 *     nothing moving; against the damped settling it replaces (the same equilibrium within the
 *     settling's own accuracy, 1e-5 of the radius), and its cost;
 *   - contradictory scenes of our own, each refused with CRANE_ERR_START and the keys named:
 *     a tie anchor in front of the boom that cannot hold it, no ties, a boom of nearly no
 *     stiffness, a load heavier than the boom can carry, a rope longer than the tip is high;
 *   - the modes at the start: no rigid mode (the drive holds the platform), the load's
 *     pendulum at sqrt(g / l) (l the rope's length to the tip), the boom's and the hydraulics'
 *     modes named by their parts, constraint modes apart; the 16-element crane in well under a
 *     second (reported);
 *   - the program: --static writes equilibrium.csv and static.txt (exit 0), a contradictory
 *     scene exits 2 naming the keys in the message, status.txt and static.txt, --modes writes
 *     modes.csv (and modes.png with gnuplot). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "crane_scene.h"
#include "crane_spawn.h"
#include "crane_static.h"
#include "tap.h"

static double wall(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void test_paper_start(void)
{
    crane_scene s;
    crane_scene_default(&s);
    bg_error err = {0};
    crane *c = crane_build(&s, &err);
    crane_start_report rep;
    double t0 = wall();
    int st = c ? crane_static_start(c, &rep, &err) : -1;
    double ts = wall() - t0;
    tap_ok(st == BG_OK && rep.ok, "paper: static start verified in %.3f s, %d solves (%s)", ts,
           rep.solves, st ? err.message : "ok");
    if (st != BG_OK) {
        crane_free(&c);
        return;
    }
    crane_geom *g = malloc(sizeof *g);
    bgr_model *m = crane_model(c);
    crane_geometry(c, 0.0, bgr_y0(m), NULL, g);
    double W = s.load_mass * s.g;
    tap_ok(fabs(rep.radius - s.boom_tip_radius) <= 1e-8 * s.boom_tip_radius,
           "paper: tip at %.12g m from the axis (scene %g)", rep.radius, s.boom_tip_radius);
    tap_close(g->rope_tension, W, 1e-9, 0, "paper: the rope carries the load's weight %.6g N", W);
    tap_close(g->tie_tension[0], g->tie_tension[1], 1e-9, 0,
              "paper: both ties carry %.6g N (symmetric)", g->tie_tension[0]);
    /* the ties' halves at the tip count; those at the gantry are in the platform's mass */
    double Wall = (s.platform_mass + s.cw_mass + s.load_mass +
                   s.boom_rho * s.boom_A * s.boom_length +
                   2 * 0.5 * s.tie_rho * s.tie_A * rep.tie_L0) *
                  s.g;
    int vz = bgr_find_var(m, "crane/b_base/e2");
    tap_ok(vz >= 0 && fabs(bgr_y0(m)[vz] - Wall) <= 1e-8 * Wall,
           "paper: the base carries the whole weight %.9g N (%.9g)", Wall,
           vz >= 0 ? bgr_y0(m)[vz] : NAN);
    tap_ok(fabs(g->theta) < 1e-12 && rep.kinetic < 1e-12 && rep.hinge_gap < 1e-9,
           "paper: theta = %.2g, kinetic energy %.2g J, hinge gap %.2g m", g->theta, rep.kinetic,
           rep.hinge_gap);
    /* against the damped settling */
    crane *d = crane_build(&s, &err);
    t0 = wall();
    int sd = d ? crane_settle_damped(d, &err) : -1;
    double tdamp = wall() - t0;
    crane_geom *gd = malloc(sizeof *gd);
    if (sd == BG_OK) crane_geometry(d, 0.0, bgr_y0(crane_model(d)), NULL, gd);
    double dtip = sd == BG_OK ? fabs(gd->node[gd->nodes - 1][2] - g->node[g->nodes - 1][2]) : NAN;
    double dload = sd == BG_OK ? fabs(gd->load[2] - g->load[2]) : NAN;
    double dL0 = sd == BG_OK ? fabs(crane_tie_length(d) - rep.tie_L0) : NAN;
    tap_ok(sd == BG_OK && dtip < 1e-4 && dload < 1e-4 && dL0 < 1e-4,
           "paper: the damped settling (%.3f s) agrees: tip height %.2g m, load height %.2g m, "
           "ties' length %.2g m apart (the static start: %.3f s)",
           tdamp, dtip, dload, dL0, ts);
    free(gd);
    free(g);
    crane_free(&d);
    crane_free(&c);
}

typedef struct bad {
    const char *label;
    void (*set)(crane_scene *s);
    const char *key; /* a key the message must name */
} bad;

static void tie_in_front(crane_scene *s)
{
    s->gantry_top[0] = 20, s->gantry_top[1] = 0, s->gantry_top[2] = 5;
}
static void no_ties(crane_scene *s)
{
    s->ties = 0;
}
static void soft_boom(crane_scene *s)
{
    s->boom_E = 1e3;
}
static void heavy_load(crane_scene *s)
{
    s->load_mass = 1e8;
}
static void long_rope(crane_scene *s)
{
    s->rope_length = 90;
}

static void test_contradictions(void)
{
    const bad cases[] = {{"a tie anchor in front of the boom", tie_in_front, "[ties] gantry_top"},
                         {"no ties", no_ties, "[ties] enabled"},
                         {"a boom of E = 1 kPa", soft_boom, "[boom] E"},
                         {"a load of 1e8 kg", heavy_load, "[load] mass"},
                         {"a rope longer than the tip is high", long_rope, "[rope] length"}};
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        crane_scene s;
        crane_scene_default(&s);
        cases[i].set(&s);
        bg_error err = {0};
        crane *c = crane_build(&s, &err);
        crane_start_report rep;
        double t0 = wall();
        int st = c ? crane_static_start(c, &rep, &err) : -1;
        tap_ok(st == CRANE_ERR_START && !rep.ok && strstr(err.message, cases[i].key),
               "%s: refused in %.2f s, naming %s: %.300s", cases[i].label, wall() - t0,
               cases[i].key, err.message);
        crane_free(&c);
    }
}

static void test_modes(void)
{
    crane_scene s;
    crane_scene_default(&s);
    bg_error err = {0};
    crane *c = crane_build(&s, &err);
    if (!c || crane_settle(c, &err) != BG_OK) {
        tap_ok(0, "modes: static start (%s)", err.message);
        crane_free(&c);
        return;
    }
    dae_modes *M = NULL;
    double t0 = wall();
    int st = crane_modes(c, 0.0, &M, NULL, &err);
    double tm = wall() - t0;
    int ne = 0, nr = -1, nc = 0, method = 0;
    dae_modes_info(M, &ne, &nr, &nc, NULL, NULL, &method);
    tap_ok(st == BG_OK && method == DAE_MODES_DENSE && ne > 90 && nr == 0 && nc > 0,
           "paper modes (16 elements, dense): %d elastic, %d rigid, %d constraint in %.3f s", ne,
           nr, nc, tm);
    /* the load's pendulum: l from the tip to the load */
    crane_geom *g = malloc(sizeof *g);
    crane_geometry(c, 0.0, bgr_y0(crane_model(c)), NULL, g);
    double l = g->node[g->nodes - 1][2] - g->load[2], wp = sqrt(s.g / l) / (2 * 3.14159265358979);
    int pend = 0, boom = 0, hyd = 0;
    char part[64];
    for (int k = 0; k < dae_modes_count(M); k++) {
        const dae_mode *md = dae_modes_get(M, k);
        if (md->kind != DAE_MODE_ELASTIC) continue;
        crane_mode_part(M, k, part, sizeof part);
        if (!strcmp(part, "load") && fabs(md->freq_hz - wp) < 0.03 * wp) pend++;
        boom += !strcmp(part, "boom");
        hyd += !strcmp(part, "hydraulics");
    }
    tap_ok(pend == 2 && boom > 50 && hyd >= 2,
           "paper modes: the load's two pendulum modes within 3 %% of sqrt(g/l)/(2 pi) = %.5f Hz "
           "(%d found), %d boom modes, %d hydraulic modes",
           wp, pend, boom, hyd);
    free(g);
    dae_modes_free(&M);
    crane_free(&c);
}

static void test_program(void)
{
    result r;
    char out[4200];
    snprintf(out, sizeof out, "%s/static", tmp);
    run(NULL, (const char *[]){"paper", "--static", "--out", out, "--quiet", NULL}, "static", 60,
        &r);
    tap_ok(r.exited && r.code == 0 && first_line_is(out, "equilibrium.csv", "name,x [m],y [m],z [m],value,unit") &&
               file_contains(out, "equilibrium.csv", "rope_tension,,,,593760") &&
               file_contains(out, "static.txt", "static start: verified") &&
               !file_exists(out, "results.csv"),
           "crane --static: exit %d, equilibrium.csv (rope tension 593760 N) and static.txt, no "
           "results.csv",
           r.code);
    snprintf(out, sizeof out, "%s/bad", tmp);
    run(NULL,
        (const char *[]){"paper", "--static", "--set", "rope.length=90", "--out", out, "--quiet",
                         NULL},
        "bad", 60, &r);
    tap_ok(r.exited && r.code == 2 && strstr(r.err, "[rope] length") &&
               file_contains(out, "status.txt", "[rope] length") &&
               file_contains(out, "static.txt", "FAILED") &&
               file_exists(out, "equilibrium.csv"),
           "crane --static with a rope longer than the tip is high: exit %d, the key named in the "
           "message, status.txt and static.txt (%.200s)",
           r.code, r.err);
    snprintf(out, sizeof out, "%s/badrun", tmp);
    run(NULL,
        (const char *[]){"paper", "--set", "ties.enabled=false", "--out", out, "--quiet",
                         "--no-plots", NULL},
        "badrun", 60, &r);
    tap_ok(r.exited && r.code == 2 && strstr(r.err, "[ties] enabled") &&
               !file_exists(out, "results.csv"),
           "crane without ties: the run refused at its start, exit %d (%.200s)", r.code, r.err);
    snprintf(out, sizeof out, "%s/modes", tmp);
    run(NULL, (const char *[]){"paper", "--modes", "--out", out, "--quiet", NULL}, "modes", 60,
        &r);
    tap_ok(r.exited && r.code == 0 &&
               first_line_is(out, "modes.csv", "index,frequency_hz,damping_ratio,kind,part,dominant") &&
               file_contains(out, "modes.csv", ",elastic,load,") &&
               file_contains(out, "modes.csv", ",constraint,"),
           "crane --modes: exit %d, modes.csv with the load's modes and the constraint modes",
           r.code);
    char gp[64];
    int have_gnuplot = system("command -v gnuplot > /dev/null 2>&1") == 0;
    snprintf(gp, sizeof gp, "%s", have_gnuplot ? "modes.png" : "modes.gp");
    tap_ok(file_nonempty(out, gp), "crane --modes: %s written", gp);
    snprintf(out, sizeof out, "%s/modes2", tmp);
    run(NULL,
        (const char *[]){"paper", "--modes", "0.5", "--elements", "4", "--out", out,
                         "--no-plots", NULL},
        "modes2", 120, &r);
    tap_ok(r.exited && r.code == 0 && file_contains(out, "modes.csv", ",elastic,"),
           "crane --modes 0.5 (4 elements): exit %d, the modes after half a second of the run",
           r.code);
    /* an analysis says what it did, not a run stopped at t = 0.5 of 20 s */
    tap_ok(strstr(r.out, "crane: scene paper, the modes at t = 0.5 s: completed") &&
               !strstr(r.out, "(of 20 s)"),
           "crane --modes: the summary names the analysis, no run's end time (%.300s)", r.out);
    run(NULL, (const char *[]){"paper", "--modes=-1", NULL}, "modesbad", 30, &r);
    tap_ok(r.exited && r.code == 2 && strstr(r.err, "--modes"),
           "crane --modes=-1: exit 2 (%.100s)", r.err);
}

/* The counts of modes docs/crane.md states for the scene at the static start, in its item "The
 * modes at the start" after the text lead ("no rigid mode and ": the constraint modes; "paper-undamped: ": the elastic ones and,
 * after "and ", the constraint ones): ne (or -1) and nc. */
static void documented_counts(const char *doc, const char *lead, int *ne, int *nc)
{
    *ne = *nc = -1;
    const char *at = doc ? strstr(doc, "**The modes at the start**") : NULL;
    const char *p = at ? strstr(at, lead) : NULL;
    if (!p) return;
    p += strlen(lead);
    char *end;
    long a = strtol(p, &end, 10);
    if (!strncmp(end, " constraint modes", 17)) {
        *nc = (int)a;
        return;
    }
    *ne = (int)a;
    const char *q = strstr(end, "and ");
    if (q) *nc = (int)strtol(q + 4, NULL, 10);
}

/* docs/crane.md's counts of the paper and paper-undamped scenes' modes at the start against the
 * computed ones. */
static void test_documented_modes(const char *docs, const char *scenes_dir)
{
    static char doc[1 << 17];
    FILE *f = fopen(docs, "r");
    size_t n = f ? fread(doc, 1, sizeof doc - 1, f) : 0;
    doc[n] = '\0';
    if (f) fclose(f);
    struct {
        const char *scene, *lead;
    } cases[] = {{"paper.ini", "no rigid mode and "}, {"paper-undamped.ini", "paper-undamped: "}};
    for (int i = 0; i < 2; i++) {
        char path[4200];
        snprintf(path, sizeof path, "%s/%s", scenes_dir, cases[i].scene);
        crane_scene s;
        bg_error err = {0};
        crane *c = NULL;
        dae_modes *M = NULL;
        int de, dc, ne = -1, nr = -1, nc = -1;
        documented_counts(doc, cases[i].lead, &de, &dc);
        if (crane_scene_load(&s, path, &err) == BG_OK && (c = crane_build(&s, &err)) &&
            crane_settle(c, &err) == BG_OK && crane_modes(c, 0.0, &M, NULL, &err) == BG_OK)
            dae_modes_info(M, &ne, &nr, &nc, NULL, NULL, NULL);
        tap_ok(dc > 0 && nc == dc && (de < 0 || ne == de),
               "%s: docs/crane.md's %d constraint modes (%d elastic) are the %d (%d) computed (%s)",
               cases[i].scene, dc, de, nc, ne, err.message);
        dae_modes_free(&M);
        crane_free(&c);
    }
}

int main(int argc, char **argv)
{
    test_paper_start();
    test_contradictions();
    test_modes();
    if (argc >= 4) test_documented_modes(argv[3], argv[2]);
    if (argc >= 3 && spawn_setup(argc, argv, "crane_static") == 0) test_program();
    return tap_done();
}
