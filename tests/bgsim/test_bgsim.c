/* bgsim end to end (TAP): the double pendulum's results.csv against the same run through the C
 * API, bad model files (exit 2, the reader's FILE:LINE:COL, nothing written), --set, --static
 * on a hanging mass against its closed-form rest position, --modes on a mass-spring against
 * sqrt(k/m)/(2 pi), --error-estimate on the mass-spring against its exact solution (the
 * estimate within a factor 3 of the true error; unavailable; refused beside --static and
 * --modes), SIGTERM during a long run (interrupted, exit 143, whole rows), --list-types against
 * the type table, --describe. The program is started as the crane program's tests start
 * theirs (tests/crane/crane_spawn.h).
 *
 *   test_bgsim BGSIM EXAMPLES_MODELS_DIR */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "crane/crane_spawn.h"
#include "mdl_model.h"
#include "mdl_types.h"
#include "tap.h"

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

/* The double pendulum through the C API at the file's settings, each row formatted as
 * results.csv writes it (%.12g), compared with the file line by line: 1 when all agree. */
static int same_as_api(const char *model, const char *dir, char *why, size_t wsize)
{
    bg_error err = {0};
    mdl_model *mm = mdl_load(model, NULL, 0, &err);
    if (!mm) {
        snprintf(why, wsize, "mdl_load: %.400s", err.message);
        return 0;
    }
    bgr_model *m = mdl_bgr(mm);
    dae_problem p;
    dae_options o;
    double *bk = NULL;
    int n = bgr_n(m), no = mdl_noutputs(mm), ok = 1;
    mdl_dae_problem(mm, &p);
    mdl_dae_options(mm, &o, &bk);
    dae_solver *s = dae_create(&p, &o, &err);
    double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp);
    double *out = malloc((size_t)(no + 1) * sizeof *out);
    char path[8400], line[4096], want[4096];
    snprintf(path, sizeof path, "%s/results.csv", dir);
    FILE *f = fopen(path, "r");
    if (!s || !f || dae_init(s, 0.0, bgr_y0(m), bgr_yp0(m)) != BG_OK ||
        dae_consistent_init(s) < 0 || !fgets(line, sizeof line, f)) {
        snprintf(why, wsize, "the API run or results.csv could not start");
        ok = 0;
    }
    const mdl_solver_settings *st = mdl_solver(mm);
    long nout = (long)ceil(st->t_end / st->output_step - 1e-9);
    for (long k = 0; ok && k <= nout; k++) {
        double tout = k == nout ? st->t_end : (double)k * st->output_step, t = 0;
        if (k == 0)
            dae_dense(s, 0.0, y, yp);
        else if (dae_solve_to(s, tout, &t, y, yp) < 0) {
            snprintf(why, wsize, "dae_solve_to failed at %g", tout);
            ok = 0;
            break;
        }
        mdl_outputs(mm, k ? t : 0.0, y, out, &err);
        size_t len = (size_t)snprintf(want, sizeof want, "%.12g", k ? t : 0.0);
        for (int i = 0; i < no; i++)
            len += (size_t)snprintf(want + len, sizeof want - len, ",%.12g", out[i]);
        snprintf(want + len, sizeof want - len, "\n");
        if (!fgets(line, sizeof line, f) || strcmp(line, want)) {
            snprintf(why, wsize, "row %ld: file '%.80s', API '%.80s'", k, line, want);
            ok = 0;
        }
    }
    if (ok && fgets(line, sizeof line, f)) {
        snprintf(why, wsize, "results.csv has more rows than the API run");
        ok = 0;
    }
    if (f) fclose(f);
    dae_free(&s);
    free(y), free(yp), free(out), free(bk);
    mdl_free(&mm);
    return ok;
}

/* The value of the equilibrium.csv row kind,name. NAN if missing. */
static double equilibrium_value(const char *dir, const char *kind_name)
{
    char p[4200], line[4096];
    snprintf(p, sizeof p, "%s/equilibrium.csv", dir);
    FILE *f = fopen(p, "r");
    double v = NAN;
    size_t l = strlen(kind_name);
    while (f && fgets(line, sizeof line, f))
        if (!strncmp(line, kind_name, l) && line[l] == ',') v = strtod(line + l + 1, NULL);
    if (f) fclose(f);
    return v;
}

/* results.csv: every line ends with a newline and has ncols fields; the number of rows. */
static long whole_rows(const char *dir, int ncols)
{
    char p[4200];
    snprintf(p, sizeof p, "%s/results.csv", dir);
    FILE *f = fopen(p, "r");
    if (!f) return -1;
    long rows = -1;
    int c, fields = 1, last = '\n';
    while ((c = fgetc(f)) != EOF) {
        if (c == ',') fields++;
        if (c == '\n') {
            if (fields != ncols) rows = -1000000;
            rows++, fields = 1;
        }
        last = c;
    }
    fclose(f);
    return last == '\n' ? rows : -1;
}

static const char HANG[] = "format: bgsim 1\n"
                           "name: hanging-mass\n"
                           "parameters: {m: 2.0, k: 400.0, L0: 0.5, g: 9.81}\n"
                           "components:\n"
                           "  ground: {type: mech.support, dim: 3}\n"
                           "  spring: {type: mech.spring, k: k, L0: L0}\n"
                           "  mass: {type: mech.point_mass, mass: m, gravity: [0, 0, -g], "
                           "position: [0, 0, -L0]}\n"
                           "bonds:\n"
                           "  - ground.p -> spring.a\n"
                           "  - spring.b -> mass.p\n"
                           "outputs:\n"
                           "  z: mass.x2\n"
                           "start: static\n";

static const char MS[] = "format: bgsim 1\n"
                         "name: mass-spring\n"
                         "parameters: {m: 2.0, k: 800.0}\n"
                         "components:\n"
                         "  j: {type: bg.one, ports: [a, b]}\n"
                         "  mass: {type: bg.I, mass: m}\n"
                         "  spring: {type: bg.C, stiffness: k}\n"
                         "bonds:\n"
                         "  - j.a -> mass.p\n"
                         "  - j.b -> spring.p\n"
                         "initial: {spring.q: 0.01}\n"
                         "outputs:\n"
                         "  q: spring.q\n";

/* The largest |q - q0 cos(w t)| over the rows of results.csv (t,q): the run's true error
 * against the exact solution. NAN if the file cannot be read or has no row. */
static double true_error(const char *dir, double q0, double w, long *rows)
{
    char p[4200], line[256];
    snprintf(p, sizeof p, "%s/results.csv", dir);
    FILE *f = fopen(p, "r");
    double e = NAN, t, q;
    *rows = 0;
    if (!f) return NAN;
    if (fgets(line, sizeof line, f) && !strcmp(line, "t,q\n"))
        while (fgets(line, sizeof line, f) && sscanf(line, "%lf,%lf", &t, &q) == 2) {
            double d = fabs(q - q0 * cos(w * t));
            if (isnan(e) || d > e) e = d;
            (*rows)++;
        }
    fclose(f);
    return e;
}

/* error_estimate.csv with one column: its header, then "name,max_abs_error,t_at_max,
 * max_abs_value,max_rel_error,t_covered,estimate" with the numbers in v[0..4] (NAN where empty)
 * and the estimate's word in word. 1 when well formed: the header, 7 fields, nothing after. */
static int estimate_file(const char *dir, const char *name, double v[5], char *word, size_t wsize)
{
    char p[4200], text[4096];
    snprintf(p, sizeof p, "%s/error_estimate.csv", dir);
    text[0] = '\0';
    slurp(p, text, sizeof text);
    static const char head[] =
        "column,max_abs_error,t_at_max [s],max_abs_value,max_rel_error,t_covered [s],estimate\n";
    size_t l = strlen(name);
    if (strncmp(text, head, sizeof head - 1)) return 0;
    char *line = text + sizeof head - 1, *end = strchr(line, '\n');
    if (!end || end[1] || strncmp(line, name, l) || line[l] != ',') return 0;
    *end = '\0';
    char *q = line + l + 1;
    for (int i = 0; i < 5; i++) {
        size_t n = strcspn(q, ",");
        if (!q[n]) return 0;
        v[i] = n ? strtod(q, NULL) : NAN;
        q += n + 1;
    }
    if (strchr(q, ',') || !*q) return 0;
    snprintf(word, wsize, "%s", q);
    return 1;
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        printf("Bail out! usage: test_bgsim BGSIM MODELS_DIR\n");
        return 1;
    }
    if (spawn_setup(argc, argv, "bgsim") != 0) return 1;
    char dp[2200], dir[2048], path[4200], why[512];
    snprintf(dp, sizeof dp, "%s/double-pendulum.yaml", scenes);
    result r;

    run(tmp, (const char *[]){"--help", NULL}, "help", 30, &r);
    tap_ok(r.exited && r.code == 0 && strstr(r.out, "usage: bgsim MODEL"), "--help: exit 0");
    run(tmp, (const char *[]){"--version", NULL}, "version", 30, &r);
    tap_ok(r.exited && r.code == 0 && strstr(r.out, "bgsim (bgdae)"), "--version: exit 0");

    /* the double pendulum at the file's settings, against the C API */
    snprintf(dir, sizeof dir, "%s/dp", tmp);
    run(tmp, (const char *[]){dp, "--out", dir, "--quiet", NULL}, "dp", 120, &r);
    tap_ok(r.exited && r.code == 0, "double pendulum: exit 0 (%d: %.200s)", r.code, r.err);
    tap_ok(first_line_is(dir, "status.txt", "status: completed") &&
               file_contains(dir, "status.txt", "\nmodel: double-pendulum (") &&
               file_contains(dir, "status.txt", "\nrows: 501\n"),
           "double pendulum: status.txt completed, the model, 501 rows");
    tap_ok(file_nonempty(dir, "model.yaml") && file_nonempty(dir, "model_stats.txt") &&
               file_contains(dir, "model_stats.txt", "unknowns by top-level instance") &&
               file_contains(dir, "solver_stats.txt", "# CSV\n") &&
               first_line_is(dir, "results.csv", "t,x1,z1,x2,z2"),
           "double pendulum: model.yaml, model_stats.txt, solver_stats.txt, results.csv");
    why[0] = '\0';
    tap_ok(same_as_api(dp, dir, why, sizeof why), "results.csv = the C API's run, bit for bit %s",
           why);

    /* --vtk: a frame a second (t = 0 .. 5: 6 frames), the rods drawn: the second hinge at
     * L1 (sin 60, 0, -cos 60) in the first frame; refused beside --static */
    snprintf(dir, sizeof dir, "%s/dpvtk", tmp);
    run(tmp, (const char *[]){dp, "--out", dir, "--vtk-step", "1", "-q", NULL}, "dpvtk", 120, &r);
    char pvd[1 << 12] = "", frame0[1 << 14] = "";
    snprintf(path, sizeof path, "%s/model.pvd", dir);
    slurp(path, pvd, sizeof pvd);
    snprintf(path, sizeof path, "%s/vtk/frame_00000.vtp", dir);
    slurp(path, frame0, sizeof frame0);
    int nsets = 0;
    for (const char *q = pvd; (q = strstr(q, "<DataSet ")); q++)
        nsets++;
    tap_ok(r.exited && r.code == 0 && nsets == 6 && strstr(pvd, "timestep=\"5\"") &&
               strstr(pvd, "</VTKFile>"),
           "--vtk-step 1: model.pvd lists 6 frames, t = 0 .. 5 (%d)", nsets);
    tap_ok(strstr(frame0, "NumberOfPoints=\"7\" NumberOfVerts=\"3\" NumberOfLines=\"4\"") &&
               strstr(frame0, "0.8660254038 0 -0.5") && strstr(frame0, "1 rod1.body"),
           "frame 0: the ground and two rods, the second hinge at (0.866, 0, -0.5)");
    snprintf(dir, sizeof dir, "%s/dpvtkstatic", tmp);
    run(tmp, (const char *[]){dp, "--out", dir, "--vtk", "--static", NULL}, "dpvtks", 60, &r);
    tap_ok(r.exited && r.code == 2 && strstr(r.err, "--vtk belongs to the dynamic run"),
           "--vtk with --static: exit 2");

    /* --set moves the start: theta1 = 30 deg puts the upper rod's centre at x = L1/2 sin 30 */
    snprintf(dir, sizeof dir, "%s/dpset", tmp);
    run(tmp, (const char *[]){dp, "--out", dir, "--set", "theta1=30*deg", "--t-end", "0.1", "-q",
                              NULL},
        "dpset", 60, &r);
    snprintf(path, sizeof path, "%s/results.csv", dir);
    char text[1 << 14];
    slurp(path, text, sizeof text);
    const char *row0 = strchr(text, '\n');
    tap_ok(r.exited && r.code == 0 && row0 && !strncmp(row0 + 1, "0,0.25,", 7) &&
               whole_rows(dir, 5) == 11,
           "--set theta1=30*deg --t-end 0.1: the t = 0 row has x1 = 0.25, 11 rows");
    tap_ok(file_contains(dir, "model.yaml", "theta1") &&
               file_contains(dir, "model.yaml", "t_end: 0.10000000000000001"),
           "model.yaml records the replacement and the solver override");

    /* bad model files: exit 2, FILE:LINE:COL and the nearest name, nothing written */
    static const struct {
        const char *text, *want, *near;
    } bad[] = {
        {"format: bgsim 1\nname: b\ncomponents:\n  ground: {type: mech.suport, dim: 3}\n",
         "bad0.yaml:4:", "mech.support"},
        {"format: bgsim 1\nname: b\ncomponents:\n  m: {type: mech.point_mass, mass: -1}\n",
         "bad1.yaml:4:", "out of range"},
    };
    for (int i = 0; i < 2; i++) {
        snprintf(path, sizeof path, "%s/bad%d.yaml", tmp, i);
        write_text(path, bad[i].text);
        snprintf(dir, sizeof dir, "%s/badout%d", tmp, i);
        char tag[16];
        snprintf(tag, sizeof tag, "bad%d", i);
        run(tmp, (const char *[]){path, "--out", dir, NULL}, tag, 30, &r);
        struct stat sb;
        tap_ok(r.exited && r.code == 2 && strstr(r.err, bad[i].want) &&
                   strstr(r.err, bad[i].near) && stat(dir, &sb) != 0,
               "bad model %d: exit 2 (%d), '%s...' and '%s' on stderr, nothing written", i,
               r.code, bad[i].want, bad[i].near);
        if (!(r.exited && r.code == 2)) tap_diag("stderr: %s", r.err);
    }
    snprintf(dir, sizeof dir, "%s/badset", tmp);
    run(tmp, (const char *[]){dp, "--out", dir, "--set", "m1=-1", NULL}, "badset", 30, &r);
    tap_ok(r.exited && r.code == 2 && strstr(r.err, "double-pendulum.yaml:") &&
               !file_exists(tmp, "badset"),
           "--set m1=-1: exit 2 with the file's position, nothing written");

    /* --static on a hanging mass: z = -(L0 + m g / k) */
    snprintf(path, sizeof path, "%s/hang.yaml", tmp);
    write_text(path, HANG);
    snprintf(dir, sizeof dir, "%s/hang", tmp);
    run(tmp, (const char *[]){path, "--static", "--out", dir, "-q", NULL}, "hang", 60, &r);
    double z = equilibrium_value(dir, "output,z"), want = -(0.5 + 2.0 * 9.81 / 400.0);
    tap_ok(r.exited && r.code == 0 && fabs(z - want) < 1e-9 &&
               fabs(equilibrium_value(dir, "unknown,mass.x2") - want) < 1e-9,
           "--static hanging mass: z = %.12g (closed form %.12g)", z, want);
    tap_ok(file_contains(dir, "static.txt", "load_factor: 1\n") &&
               file_contains(dir, "static.txt", "trim: none") && !file_exists(dir, "results.csv"),
           "--static: static.txt with the load factor, no results.csv");

    /* --modes on the hanging double pendulum: the two swings of the linearised Lagrangian
     * equations, M theta'' + K theta = 0 with M = [m1 L1^2/3 + m2 L1^2, m2 L1 L2/2; m2 L1 L2/2,
     * m2 L2^2/3], K = diag((m1/2 + m2) g L1, m2 g L2/2) (L1 1, L2 0.7, m1 1, m2 0.5, g 9.81): the
     * static start comes first, else the rods' tensions are zero and so is the swing's stiffness */
    {
        double L1 = 1, L2 = 0.7, m1 = 1, m2 = 0.5, g = 9.81;
        double M11 = m1 * L1 * L1 / 3 + m2 * L1 * L1, M12 = m2 * L1 * L2 / 2, M22 = m2 * L2 * L2 / 3;
        double K1 = (m1 / 2 + m2) * g * L1, K2 = m2 * g * L2 / 2;
        /* det(K - w^2 M) = 0: a w^4 + b w^2 + c = 0 */
        double a = M11 * M22 - M12 * M12, b = -(K1 * M22 + K2 * M11), c = K1 * K2;
        double d = sqrt(b * b - 4 * a * c), w1 = sqrt((-b - d) / (2 * a)), w2 = sqrt((-b + d) / (2 * a));
        double f1 = w1 / (2 * acos(-1.0)), f2 = w2 / (2 * acos(-1.0));
        snprintf(dir, sizeof dir, "%s/dpmodes", tmp);
        run(tmp, (const char *[]){dp, "--out", dir, "--modes", "--set", "theta1=0", "--set",
                                  "theta2=0", "-q", NULL},
            "dpmodes", 60, &r);
        snprintf(path, sizeof path, "%s/modes.csv", dir);
        char mt[1 << 15] = "";
        slurp(path, mt, sizeof mt);
        int got1 = 0, got2 = 0;
        for (const char *q = strchr(mt, '\n'); q && q[1]; q = strchr(q + 1, '\n')) {
            double f = 0;
            if (sscanf(q + 1, "%*d,%lf", &f) == 1) {
                got1 |= fabs(f - f1) < 1e-6 * f1;
                got2 |= fabs(f - f2) < 1e-6 * f2;
            }
        }
        tap_ok(r.exited && r.code == 0 && got1 && got2,
               "--modes, hanging double pendulum: %.6f and %.6f Hz (linearised Lagrangian)", f1, f2);
    }

    /* a trimmed start replaces the model (mdl_static): L0 found so that the mass rests at
     * z = -1, L0 = 1 - m g / k; the program's record of the model's name must outlive the
     * model it came from (the summary and status.txt name it) */
    char hang_trim[sizeof HANG + 200];
    snprintf(hang_trim, sizeof hang_trim, "%strim: {adjust: L0, until: z, equals: -1, between: "
             "[0.5, 1]}\n", HANG);
    snprintf(path, sizeof path, "%s/hangtrim.yaml", tmp);
    write_text(path, hang_trim);
    snprintf(dir, sizeof dir, "%s/hangtrim", tmp);
    run(tmp, (const char *[]){path, "--static", "--out", dir, NULL}, "hangtrim", 60, &r);
    z = equilibrium_value(dir, "output,z");
    tap_ok(r.exited && r.code == 0 && fabs(z + 1) < 1e-6 &&
               file_contains(dir, "static.txt", "trim_value: L0 = 0.95095") &&
               file_contains(dir, "status.txt", "\nmodel: hanging-mass (") &&
               strstr(r.out, "bgsim: model hanging-mass, the static equilibrium"),
           "trimmed --static: z = %.9g, L0 = 1 - m g / k, the model still named", z);

    /* --modes on a mass-spring: sqrt(k/m) / (2 pi) */
    snprintf(path, sizeof path, "%s/ms.yaml", tmp);
    write_text(path, MS);
    snprintf(dir, sizeof dir, "%s/ms", tmp);
    run(tmp, (const char *[]){path, "--modes", "--out", dir, "-q", NULL}, "ms", 60, &r);
    snprintf(path, sizeof path, "%s/modes.csv", dir);
    slurp(path, text, sizeof text);
    const char *m1 = strstr(text, "\n1,");
    double f = m1 ? strtod(m1 + 3, NULL) : NAN;
    double fw = sqrt(800.0 / 2.0) / (2 * 3.14159265358979323846);
    tap_ok(r.exited && r.code == 0 && fabs(f - fw) < 1e-8 * fw && strstr(text, ",elastic,mass,"),
           "--modes mass-spring: %.10g Hz (sqrt(k/m)/(2 pi) = %.10g)", f, fw);
    /* --modes T at a time of the run: the state moves, the frozen linearisation is asked for;
     * the spring is linear, so its modes are those at rest; T beyond t_end refused */
    snprintf(path, sizeof path, "%s/ms.yaml", tmp);
    snprintf(dir, sizeof dir, "%s/msT", tmp);
    run(tmp, (const char *[]){path, "--modes", "0.05", "--out", dir, "-q", NULL}, "msT", 60, &r);
    snprintf(path, sizeof path, "%s/modes.csv", dir);
    slurp(path, text, sizeof text);
    m1 = strstr(text, "\n1,");
    f = m1 ? strtod(m1 + 3, NULL) : NAN;
    tap_ok(r.exited && r.code == 0 && fabs(f - fw) < 1e-8 * fw,
           "--modes 0.05 mass-spring (in motion): %.10g Hz (sqrt(k/m)/(2 pi) = %.10g; exit %d: "
           "%.200s)", f, fw, r.code, r.err);
    snprintf(path, sizeof path, "%s/ms.yaml", tmp);
    run(tmp, (const char *[]){path, "--modes", "1e300", "--out", "msbig", "-q", NULL}, "msbig", 60,
        &r);
    tap_ok(r.exited && r.code == 2 && strstr(r.err, "t_end") && !file_exists(tmp, "msbig"),
           "--modes 1e300: beyond t_end, exit 2, nothing written (%d: %.200s)", r.code, r.err);

    /* --error-estimate against an independent truth: the mass-spring released from rest,
     * q(t) = q0 cos(w t) with w = sqrt(k/m) = 20 rad/s, over 2 s (201 rows, 6.4 periods) at
     * rtol 1e-6: the estimate (the largest |q(rtol) - q(rtol / 100)| over the rows) within a
     * factor 3 of the true error (the largest |q - q0 cos(w t)| over the rows of results.csv) */
    {
        double q0 = 0.01, w = sqrt(800.0 / 2.0), v[5] = {NAN, NAN, NAN, NAN, NAN};
        char word[64] = "";
        long nrows = 0;
        snprintf(path, sizeof path, "%s/msexact.yaml", tmp);
        write_text(path, MS);
        snprintf(dir, sizeof dir, "%s/msest", tmp);
        run(tmp, (const char *[]){path, "--out", dir, "--t-end", "2", "--output-step", "0.01",
                                  "--rtol", "1e-6", "--atol", "1e-9", "--error-estimate", NULL},
            "msest", 60, &r);
        double truth = true_error(dir, q0, w, &nrows);
        int formed = estimate_file(dir, "q", v, word, sizeof word);
        double ratio = v[0] / truth;
        tap_ok(r.exited && r.code == 0 && nrows == 201 && truth > 0 && ratio >= 1.0 / 3 &&
                   ratio <= 3,
               "--error-estimate, mass-spring: estimate %.4g, true error %.4g (ratio %.3f, "
               "within a factor 3)",
               v[0], truth, ratio);
        tap_ok(formed && !strcmp(word, "available") && v[1] >= 0 && v[1] <= 2 &&
                   fabs(v[2] - q0) < 1e-6 * q0 && fabs(v[3] - v[0] / v[2]) <= 1e-5 * v[3] &&
                   v[4] == 2,
               "error_estimate.csv well formed: q's error, its time %g, max |q| %g, the ratio, "
               "covered to t = %g, available",
               v[1], v[2], v[4]);
        tap_ok(file_contains(dir, "status.txt", "\nerror_estimate: available over 201 rows up to "
                                                "t = 2 s\n") &&
                   file_contains(dir, "solver_stats.txt",
                                 "\nerror_estimate: a second run at rtol / 100 and atol / 100 "
                                 "(rtol 1e-08, atol 1e-11)") &&
                   file_contains(dir, "solver_stats.txt", "\nerror_estimate_run: steps=") &&
                   file_contains(dir, "solver_stats.txt", "\nerror_estimate_largest: q: ") &&
                   strstr(r.out, "  error estimate (available, against rtol 1e-08): largest "
                                 "relative error"),
               "--error-estimate: the lines of status.txt, solver_stats.txt and the summary");

        /* K = 1e12 puts the companion's tolerances below round-off: unavailable with the
         * reason, the run itself completed */
        snprintf(dir, sizeof dir, "%s/msestbad", tmp);
        run(tmp, (const char *[]){path, "--out", dir, "--t-end", "0.5", "--rtol", "1e-6",
                                  "--error-estimate", "1e12", "-q", NULL},
            "msestbad", 60, &r);
        formed = estimate_file(dir, "q", v, word, sizeof word);
        tap_ok(r.exited && r.code == 0 && first_line_is(dir, "status.txt", "status: completed") &&
                   formed && !strcmp(word, "unavailable") && isnan(v[0]) &&
                   file_contains(dir, "status.txt", "\nerror_estimate: unavailable: the run at "
                                                    "the tighter tolerances: ") &&
                   strstr(r.err, "the error estimate is unavailable: "),
               "--error-estimate 1e12: unavailable with the reason, the run completed (exit %d)",
               r.code);

        snprintf(dir, sizeof dir, "%s/msestst", tmp);
        run(tmp, (const char *[]){path, "--error-estimate", "--static", "--out", dir, NULL},
            "msestst", 30, &r);
        tap_ok(r.exited && r.code == 2 &&
                   strstr(r.err, "option --error-estimate belongs to the dynamic run, not to "
                                 "--static") &&
                   !file_exists(tmp, "msestst"),
               "--error-estimate --static: exit 2 (%d), nothing written", r.code);
        run(tmp, (const char *[]){path, "--modes", "--error-estimate", "50", NULL}, "msestmd", 30,
            &r);
        tap_ok(r.exited && r.code == 2 && strstr(r.err, "not to --modes"),
               "--modes --error-estimate 50: exit 2 (%d)", r.code);
    }

    /* SIGTERM during a long run: interrupted, exit 143, whole rows */
    snprintf(dir, sizeof dir, "%s/long", tmp);
    pid_t pid = start(tmp, (const char *[]){dp, "--out", dir, "--t-end", "1e5", "--max-rows",
                                  "100000000", "-q", NULL},
                "long");
    double t0 = now_s();
    char st[4200];
    snprintf(st, sizeof st, "%s/results.csv", dir);
    struct stat sb;
    while (now_s() - t0 < 20 && (stat(st, &sb) != 0 || sb.st_size < 20000))
        sleep_ms(20);
    kill(pid, SIGTERM);
    finish(pid, 30, "long", &r);
    long rows = whole_rows(dir, 5);
    tap_ok(r.exited && r.code == 143 && first_line_is(dir, "status.txt", "status: interrupted") &&
               file_contains(dir, "status.txt", "SIGTERM received at t = ") && rows > 10,
           "SIGTERM: exit 143 (%d), status interrupted, %ld whole rows", r.code, rows);

    /* --list-types: every type of the table; --describe */
    run(tmp, (const char *[]){"--list-types", NULL}, "types", 30, &r);
    int all = r.exited && r.code == 0;
    for (int i = 0; i < mdl_type_count() && all; i++) {
        char want_line[128];
        snprintf(want_line, sizeof want_line, "%s ", mdl_type_at(i)->name);
        if (!strstr(r.out, want_line)) {
            all = 0;
            tap_diag("missing: %s", mdl_type_at(i)->name);
        }
    }
    tap_ok(all, "--list-types lists the %d types of the table", mdl_type_count());
    run(tmp, (const char *[]){"--describe", "mech.body", NULL}, "describe", 30, &r);
    tap_ok(r.exited && r.code == 0 && !strncmp(r.out, "mech.body:", 10) &&
               strstr(r.out, "parameters:"),
           "--describe mech.body: exit 0, its parameters");
    run(tmp, (const char *[]){"--describe", "mech.bdy", NULL}, "nope", 30, &r);
    tap_ok(r.exited && r.code == 2 && strstr(r.err, "unknown type 'mech.bdy'") &&
               strstr(r.err, "mech.body"),
           "--describe mech.bdy: exit 2, the nearest name mech.body");
    run(tmp, (const char *[]){"--describe", "nope", NULL}, "nope2", 30, &r);
    tap_ok(r.exited && r.code == 2 && strstr(r.err, "nearest:"), "--describe nope: exit 2");
    run(tmp, (const char *[]){dp, "--list-unknowns", NULL}, "unk", 30, &r);
    tap_ok(r.exited && r.code == 0 && strstr(r.out, "rod1.body.x0  differential"),
           "--list-unknowns: the names `initial:` uses");
    return tap_done();
}
