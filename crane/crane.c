/* crane: simulates the hydraulically driven rotary crane of the crane paper (docs/crane.md) from a
 * scene file and writes the results.
 *
 *   crane [SCENE] [--out DIR] [--t-end T] [--rtol R] [--atol A] [--elements N]
 *         [--output-step DT] [--set SECTION.KEY=VALUE]... [--no-plots] [--quiet] [--help]
 *         [--version]
 *
 * Flow: scene file (crane_scene_load) -> command-line overrides -> crane_build -> static
 * equilibrium (crane_settle, if the scene asks) -> bgr_dae_problem -> bg_dae (rtol, atol, stop at
 * t_end, the reference's corners as breakpoints, algebraic variables out of the error test) ->
 * consistent initial values -> one CSV row per output time (crane_outputs), streamed ->
 * statistics, figures (gnuplot, skipped when it is missing), summary.
 *
 * Writes into DIR (default results/<scene name>/): results.csv, model_stats.txt,
 * solver_stats.txt, scene.ini (the scene as run, overrides included), status.txt (how the run
 * ended: completed, interrupted, failed, with the reason), plots.gp and fig5a.png .. fig5f.png.
 * SIGINT/SIGTERM stop the run after the current output step: the rows written stay, the CSV is
 * closed cleanly and status.txt says so. Exit status: 0 completed; 1 the model or the solver
 * failed, or a file could not be written; 2 bad command line or scene file; 128 + signal number
 * when interrupted. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "crane_model.h"
#include "crane_scene.h"

#ifndef CRANE_VERSION
#define CRANE_VERSION "unknown"
#endif

#define DEFAULT_SCENE "crane/scenes/paper.ini"
#define MAX_SETS 64

enum { EXIT_OK = 0, EXIT_RUN = 1, EXIT_USAGE = 2 };

/* Signals. While the output loop runs (PHASE_LOOP) a signal only sets g_signal: the loop stops
 * after the current output step and everything is closed in order. While the model is built,
 * settled or initialised (PHASE_SETUP: long library calls that cannot be stopped), the handler
 * writes the prepared status.txt with async-signal-safe calls and ends the program at once. */
enum { PHASE_OTHER = 0, PHASE_SETUP = 1, PHASE_LOOP = 2 };
static volatile sig_atomic_t g_signal = 0, g_phase = PHASE_OTHER;
static char g_status_path[4200];
static char g_status_text[2][1024]; /* [0] SIGINT, [1] SIGTERM */
static size_t g_status_len[2];

static void on_signal(int sig)
{
    g_signal = sig;
    if (g_phase == PHASE_SETUP) {
        int k = sig == SIGTERM;
        int fd = open(g_status_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) {
            if (write(fd, g_status_text[k], g_status_len[k]) < 0) {
            }
            close(fd);
        }
        static const char note[] = "crane: interrupted\n";
        if (write(STDERR_FILENO, note, sizeof note - 1) < 0) {
        }
        _exit(128 + sig);
    }
}

static const char *USAGE =
    "usage: crane [SCENE] [options]\n"
    "\n"
    "Simulates the hydraulically driven rotary crane (docs/crane.md) described by the\n"
    "scene file SCENE (default " DEFAULT_SCENE "; a bare name such as 'rigid-boom' is looked up\n"
    "in crane/scenes/) and writes the results into DIR.\n"
    "\n"
    "options (a value may also be given as --option=VALUE):\n"
    "  --out DIR            output folder (default results/<scene name>/)\n"
    "  --t-end T            end time in s (scene [solver] t_end; paper: 20)\n"
    "  --rtol R             relative tolerance (scene [solver] rtol; paper: 1e-6)\n"
    "  --atol A             absolute tolerance (scene [solver] atol; paper: 1e-6)\n"
    "  --elements N         beam elements of the boom, 0..512 (0: rigid boom)\n"
    "  --output-step DT     output interval in s (scene [solver] output_step; paper: 0.001)\n"
    "  --set SEC.KEY=VALUE  set any scene key, e.g. --set hydraulics.enabled=false\n"
    "  --no-plots           do not draw the figures\n"
    "  --quiet              no progress line and no summary (errors only)\n"
    "  --help               this text\n"
    "  --version            the program's version\n"
    "\n"
    "files in DIR: results.csv (one row per output time, streamed), model_stats.txt,\n"
    "solver_stats.txt, scene.ini (the scene as run), status.txt, plots.gp, fig5a.png ..\n"
    "fig5f.png (with gnuplot).\n"
    "exit status: 0 completed, 1 the run failed, 2 bad command line or scene file,\n"
    "128 + N interrupted by signal N.\n";

/* ------------------------------------------------------------ command line ---- */

typedef struct set_item {
    char section[64], key[64];
    const char *value;
    char origin[96];
} set_item;

typedef struct options {
    const char *scene, *out;
    set_item sets[MAX_SETS];
    int nsets;
    int no_plots, quiet;
} options;

static int usage_error(const char *fmt, const char *a, const char *b)
{
    fprintf(stderr, "crane: ");
    fprintf(stderr, fmt, a, b);
    fprintf(stderr, "\n(crane --help lists the options)\n");
    return EXIT_USAGE;
}

static int add_set(options *o, const char *section, const char *key, const char *value,
                   const char *origin)
{
    if (o->nsets >= MAX_SETS) return usage_error("too many overrides (at most %s)%s", "64", "");
    set_item *it = &o->sets[o->nsets++];
    snprintf(it->section, sizeof it->section, "%s", section);
    snprintf(it->key, sizeof it->key, "%s", key);
    it->value = value;
    snprintf(it->origin, sizeof it->origin, "%s", origin);
    return EXIT_OK;
}

/* Returns -1 to go on, or an exit status (help and version: 0). */
static int parse_args(int argc, char **argv, options *o)
{
    static const struct {
        const char *name, *section, *key;
    } valued[] = {{"--out", NULL, NULL},
                  {"--t-end", "solver", "t_end"},
                  {"--rtol", "solver", "rtol"},
                  {"--atol", "solver", "atol"},
                  {"--elements", "boom", "elements"},
                  {"--output-step", "solver", "output_step"},
                  {"--set", NULL, NULL}};
    static const char *flags[] = {"--no-plots", "--quiet", "--help", "--version"};
    const int nvalued = (int)(sizeof valued / sizeof *valued), nflags = 4;
    int positional_only = 0;
    memset(o, 0, sizeof *o);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (positional_only || a[0] != '-' || !strcmp(a, "-")) {
            if (o->scene)
                return usage_error("more than one scene given ('%s' and '%s')", o->scene, a);
            o->scene = a;
            continue;
        }
        if (!strcmp(a, "--")) {
            positional_only = 1;
            continue;
        }
        if (!strcmp(a, "-h")) a = "--help";
        if (!strcmp(a, "-q")) a = "--quiet";
        if (!strcmp(a, "-V")) a = "--version";
        char name[64];
        const char *eq = strchr(a, '='), *value = NULL;
        size_t n = eq ? (size_t)(eq - a) : strlen(a);
        if (n >= sizeof name) n = sizeof name - 1;
        memcpy(name, a, n);
        name[n] = '\0';
        int found = 0;
        for (int k = 0; k < nflags && !found; k++)
            if (!strcmp(name, flags[k])) {
                found = 1;
                if (eq) return usage_error("option %s takes no value (got '%s')", name, eq + 1);
                if (k == 0) o->no_plots = 1;
                if (k == 1) o->quiet = 1;
                if (k == 2) {
                    fputs(USAGE, stdout);
                    return EXIT_OK;
                }
                if (k == 3) {
                    printf("crane (bgdae) %s\n", CRANE_VERSION);
                    return EXIT_OK;
                }
            }
        for (int k = 0; k < nvalued && !found; k++) {
            if (strcmp(name, valued[k].name)) continue;
            found = 1;
            if (eq)
                value = eq + 1;
            else if (i + 1 < argc)
                value = argv[++i];
            else
                return usage_error("option %s needs a value%s", name, "");
            if (!*value) return usage_error("option %s needs a value (got '%s')", name, value);
            if (!eq && !strncmp(value, "--", 2))
                return usage_error("option %s needs a value (got the option '%s')", name, value);
            if (!strcmp(name, "--out")) {
                o->out = value;
            } else if (!strcmp(name, "--set")) {
                const char *dot = strchr(value, '.'), *veq = strchr(value, '=');
                if (!dot || !veq || dot > veq || dot == value || veq == dot + 1)
                    return usage_error("--set expects SECTION.KEY=VALUE, got '%s'%s", value, "");
                char sec[64], key[64];
                snprintf(sec, sizeof sec, "%.*s", (int)(dot - value), value);
                snprintf(key, sizeof key, "%.*s", (int)(veq - dot - 1), dot + 1);
                char origin[96];
                snprintf(origin, sizeof origin, "--set %.40s.%.40s", sec, key);
                int r = add_set(o, sec, key, veq + 1, origin);
                if (r) return r;
            } else {
                int r = add_set(o, valued[k].section, valued[k].key, value, name);
                if (r) return r;
            }
        }
        if (!found) {
            const char *best = NULL;
            int bd = 1 << 30;
            for (int k = 0; k < nvalued + nflags; k++) {
                const char *cand = k < nvalued ? valued[k].name : flags[k - nvalued];
                int d = crane_scene_edit_distance(name, cand);
                if (d < bd) bd = d, best = cand;
            }
            return usage_error("unknown option '%s'; did you mean %s?", name, best);
        }
    }
    return -1;
}

/* ---------------------------------------------------------------- files ---- */

static int is_file(const char *p)
{
    struct stat st;
    return stat(p, &st) == 0 && S_ISREG(st.st_mode);
}

/* Finds the scene: as given, then (bare names) in crane/scenes/ with or without .ini, relative
 * to the current folder, then to the source tree and the installed data folder. */
static int find_scene(const char *arg, char *path, size_t size, char *tried, size_t tsize)
{
    const char *roots[3] = {"", NULL, NULL};
    int nroots = 1;
#ifdef CRANE_SOURCE_ROOT
    roots[nroots++] = CRANE_SOURCE_ROOT "/";
#endif
    const char *base = strrchr(arg, '/');
    base = base ? base + 1 : arg;
    /* forms: as given; bare names in crane/scenes/, with or without .ini */
    const char *pre[3] = {"", "crane/scenes/", "crane/scenes/"}, *suf[3] = {"", "", ".ini"};
    int nforms = strchr(arg, '/') ? 1 : 3;
    size_t tl = 0;
    tried[0] = '\0';
    for (int r = 0; r < nroots; r++) {
        if (r > 0 && arg[0] == '/') break;
        for (int f = 0; f < nforms; f++) {
            int len = snprintf(path, size, "%s%s%s%s", roots[r], pre[f], arg, suf[f]);
            if (len < 0 || (size_t)len >= size) continue;
            if (is_file(path)) return 1;
            if (tl < tsize) {
                len = snprintf(tried + tl, tsize - tl, "%s%s", tl ? ", " : "", path);
                tl = len < 0 ? tsize : tl + (size_t)len;
            }
        }
    }
#ifdef CRANE_DATA_DIR
    for (int f = 1; f < 3; f++) {
        int len = snprintf(path, size, "%s/%s%s", CRANE_DATA_DIR, base, suf[f]);
        if (len >= 0 && (size_t)len < size && is_file(path)) return 1;
    }
#else
    (void)base;
#endif
    return 0;
}

static int mkdir_p(const char *dir)
{
    char buf[4096];
    if (snprintf(buf, sizeof buf, "%s", dir) >= (int)sizeof buf) return -1;
    for (char *p = buf + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST) return -1;
            *p = '/';
        }
    if (mkdir(buf, 0777) != 0 && errno != EEXIST) return -1;
    struct stat st;
    return stat(buf, &st) == 0 && S_ISDIR(st.st_mode) ? 0 : -1;
}

static FILE *open_out(const char *dir, const char *name, char *path, size_t size)
{
    snprintf(path, size, "%s/%s", dir, name);
    return fopen(path, "w");
}

static double wall_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* ---------------------------------------------------------------- figures ---- */

static int have_gnuplot(void)
{
    return system("command -v gnuplot >/dev/null 2>&1") == 0;
}

/* Single-quoted for the shell. */
static void shell_quote(const char *s, char *buf, size_t size)
{
    size_t n = 0;
    if (size < 3) return;
    buf[n++] = '\'';
    for (; *s && n + 5 < size; s++) {
        if (*s == '\'') {
            memcpy(buf + n, "'\\''", 4);
            n += 4;
        } else {
            buf[n++] = *s;
        }
    }
    buf[n++] = '\'';
    buf[n] = '\0';
}

/* A curve of the figures: an output column, or the difference ref - val of two (the errors,
 * when the model gives the quantities and their references only). */
typedef struct curve {
    char using[32]; /* gnuplot "using" part: "8" or "($5-$4)" */
    char label[96]; /* with unit */
} curve;

/* Column of output a, or of b if the model has no a (-1: neither). */
static int col_any(const char *a, const char *b)
{
    int c = crane_output_index(a);
    return c >= 0 || !b ? c : crane_output_index(b);
}

static int curve_col(curve *cv, int c)
{
    if (c < 0) return 0;
    snprintf(cv->using, sizeof cv->using, "%d", c + 1);
    snprintf(cv->label, sizeof cv->label, "%s", crane_output_names[c]);
    return 1;
}

/* err_name if the model has it, else ref - val labelled "err_name = ref - val [unit]". */
static int curve_err(curve *cv, const char *err_name, const char *val, const char *ref)
{
    if (curve_col(cv, crane_output_index(err_name))) return 1;
    int v = crane_output_index(val), r = crane_output_index(ref);
    if (v < 0 || r < 0) return 0;
    const char *unit = strchr(crane_output_names[v], '[');
    snprintf(cv->using, sizeof cv->using, "($%d-$%d)", r + 1, v + 1);
    snprintf(cv->label, sizeof cv->label, "%s = %s - %s %s", err_name, ref, val, unit ? unit : "");
    return 1;
}

static void gp_head(FILE *f, const char *file, const char *title, const crane_scene *s,
                    const curve *x, const curve *y)
{
    fprintf(f, "\nreset\nset datafile separator ','\nset grid\nset key top right\n");
    fprintf(f, "set output '%s'\nset title '%s (scene %s)'\n", file, title, s->name);
    fprintf(f, "set xlabel '%s'\nset ylabel '%s'\n", x->label, y->label);
}

/* Writes plots.gp into dir (the paper's Fig. 5 a-f from results.csv); returns the number of
 * figures in it. */
static int write_plot_script(const char *dir, const crane_scene *s, double radius, double reach)
{
    char path[4200];
    FILE *f = open_out(dir, "plots.gp", path, sizeof path);
    if (!f) return 0;
    int nfig = 0;
    curve t, a, b;
    fprintf(f, "# Figures of the crane run (paper Fig. 5) from results.csv; run in this folder:\n"
               "#   gnuplot plots.gp\n"
               "set terminal png size 900,600 noenhanced\n");
    if (!curve_col(&t, crane_output_index("t"))) {
        fclose(f);
        return 0;
    }
    /* (a) the tip's path seen from above, with the circle of the tip radius */
    if (curve_col(&a, crane_output_index("tip_x")) && curve_col(&b, crane_output_index("tip_y"))) {
        gp_head(f, "fig5a.png", "(a) boom tip trajectory in the X0Y0 plane", s, &a, &b);
        /* the whole circle through the tip's start, centred on the slewing axis */
        double cx = s->joint_A[0], cy = s->joint_A[1], h = fmax(1.1 * radius, 1.05 * reach);
        if (!(h > 0)) h = 1.1 * s->boom_tip_radius + 1;
        fprintf(f, "set size ratio -1\nset key below\n");
        fprintf(f, "set xrange [%.9g:%.9g]\nset yrange [%.9g:%.9g]\n", cx - h, cx + h, cy - h,
                cy + h);
        fprintf(f,
                "set object 1 circle at %.17g,%.17g size %.17g fs empty border lc rgb 'gray' "
                "dt 2\n",
                cx, cy, radius);
        fprintf(f,
                "plot 'results.csv' using %s:%s with lines lw 2 title 'boom tip', \\\n"
                "     NaN with lines lc rgb 'gray' dt 2 title 'circle of the initial radius "
                "%.4g m'\n",
                a.using, b.using, radius);
        nfig++;
    }
    /* (b), (c) the tip's transversal deflections */
    static const char *defl[2][3] = {{"fig5b.png", "tip_defl_1", "defl_luff"},
                                     {"fig5c.png", "tip_defl_2", "defl_side"}};
    static const char *defl_title[2] = {
        "(b) transversal deflection of the boom tip in the luffing plane",
        "(c) transversal deflection of the boom tip out of the luffing plane"};
    for (int k = 0; k < 2; k++)
        if (curve_col(&a, col_any(defl[k][1], defl[k][2]))) {
            gp_head(f, defl[k][0], defl_title[k], s, &t, &a);
            fprintf(f, "plot 'results.csv' using 1:%s with lines lw 2 notitle\n", a.using);
            nfig++;
        }
    /* (d), (e) angle and angular velocity with their references */
    static const char *ref[2][4] = {
        {"fig5d.png", "theta", "theta_ref", "(d) platform rotation angle"},
        {"fig5e.png", "omega", "omega_ref", "(e) platform angular velocity"}};
    for (int k = 0; k < 2; k++)
        if (curve_col(&a, crane_output_index(ref[k][1])) &&
            curve_col(&b, crane_output_index(ref[k][2]))) {
            gp_head(f, ref[k][0], ref[k][3], s, &t, &a);
            fprintf(f,
                    "plot 'results.csv' using 1:%s with lines lw 2 title '%s', \\\n"
                    "     'results.csv' using 1:%s with lines lw 1 dt 2 title '%s'\n",
                    a.using, a.label, b.using, b.label);
            nfig++;
        }
    /* (f) velocity error (left axis) and acceleration error (right axis) */
    if (curve_err(&a, "omega_err", "omega", "omega_ref") &&
        curve_err(&b, "alpha_err", "alpha", "alpha_ref")) {
        gp_head(f, "fig5f.png", "(f) angular velocity and acceleration errors", s, &t, &a);
        fprintf(f, "set y2label '%s'\nset ytics nomirror\nset y2tics\n", b.label);
        fprintf(f,
                "plot 'results.csv' using 1:%s with lines lw 2 title '%s' axes x1y1, \\\n"
                "     'results.csv' using 1:%s with lines lw 1 title '%s' axes x1y2\n",
                a.using, a.label, b.using, b.label);
        nfig++;
    }
    fprintf(f, "\nunset output\n");
    fclose(f);
    return nfig;
}

/* --------------------------------------------------------------- the run ---- */

typedef struct run {
    const options *o;
    crane_scene scene;
    char scene_path[1024], outdir[2048];
    crane *c;
    dae_solver *s;
    FILE *csv;
    long rows;
    double t, t_start, wall0;
    const char *status; /* "completed", "interrupted", "failed" */
    char reason[BG_MESSAGE_SIZE + 64];
    double peak[2], first_out[CRANE_NOUT], final_out[CRANE_NOUT];
    double reach; /* largest |tip_x - A_x|, |tip_y - A_y| */
    int have_final;
} run;

static void write_status(run *r)
{
    char path[4200];
    FILE *f = open_out(r->outdir, "status.txt", path, sizeof path);
    if (!f) {
        fprintf(stderr, "crane: cannot write %s: %s\n", path, strerror(errno));
        return;
    }
    const dae_stats *st = r->s ? dae_get_stats(r->s) : NULL;
    fprintf(f, "status: %s\n", r->status);
    fprintf(f, "reason: %s\n", r->reason[0] ? r->reason : "-");
    fprintf(f, "scene: %s (%s)\n", r->scene.name, r->scene_path);
    fprintf(f, "t_reached: %.9g s\n", r->t);
    fprintf(f, "t_end: %.9g s\n", r->scene.t_end);
    fprintf(f, "rows: %ld\n", r->rows);
    fprintf(f, "steps: %ld\n", st ? st->steps : 0L);
    fprintf(f, "wall_time: %.3f s\n", wall_now() - r->wall0);
    fclose(f);
}

static int fail_run(run *r, const char *what, const char *msg)
{
    r->status = "failed";
    snprintf(r->reason, sizeof r->reason, "%s: %s", what, msg);
    fprintf(stderr, "crane: %s: %s\n", what, msg);
    return EXIT_RUN;
}

static void write_row(run *r, double t, const double *out)
{
    fprintf(r->csv, "%.12g", t);
    for (int i = 1; i < CRANE_NOUT; i++)
        fprintf(r->csv, ",%.12g", out[i]);
    fputc('\n', r->csv);
    fflush(r->csv);
    r->rows++;
    int d1 = col_any("tip_defl_1", "defl_luff"), d2 = col_any("tip_defl_2", "defl_side");
    if (d1 >= 0 && fabs(out[d1]) > r->peak[0]) r->peak[0] = fabs(out[d1]);
    if (d2 >= 0 && fabs(out[d2]) > r->peak[1]) r->peak[1] = fabs(out[d2]);
    int tx = crane_output_index("tip_x"), ty = crane_output_index("tip_y");
    if (tx >= 0 && ty >= 0) {
        double ex = fabs(out[tx] - r->scene.joint_A[0]), ey = fabs(out[ty] - r->scene.joint_A[1]);
        if (isfinite(ex) && ex > r->reach) r->reach = ex;
        if (isfinite(ey) && ey > r->reach) r->reach = ey;
    }
    if (r->rows == 1) memcpy(r->first_out, out, sizeof r->first_out);
    memcpy(r->final_out, out, sizeof r->final_out);
    r->final_out[0] = t;
    r->have_final = 1;
}

static void progress(run *r, int tty, double *last)
{
    if (!tty) return;
    double now = wall_now();
    if (now - *last < 0.25) return;
    *last = now;
    const dae_stats *st = dae_get_stats(r->s);
    double el = now - r->t_start, frac = r->t / r->scene.t_end;
    char eta[32] = "?";
    if (frac > 1e-3) snprintf(eta, sizeof eta, "%.0f s", el * (1 - frac) / frac);
    fprintf(stderr, "\r  t = %8.4f s  %5.1f %%  steps %7ld  h %9.3e s  left %-10s", r->t,
            100 * frac, st->steps, st->h_last, eta);
    fflush(stderr);
}

static int write_solver_stats(run *r, const dae_options *dopt, int nbk, const double *bk)
{
    char path[4200], line[2048], head[2048], row[2048];
    FILE *f = open_out(r->outdir, "solver_stats.txt", path, sizeof path);
    if (!f) return -1;
    const dae_stats *st = dae_get_stats(r->s);
    double wall = wall_now() - r->wall0;
    dae_stats_line(st, line, sizeof line);
    dae_stats_csv_header(head, sizeof head);
    dae_stats_csv(st, row, sizeof row);
    fprintf(f, "# crane solver statistics\n");
    fprintf(f, "scene: %s (%s)\nstatus: %s\n", r->scene.name, r->scene_path, r->status);
    fprintf(f, "rtol: %g\natol: %g\nt_end: %g s\noutput_step: %g s\n", dopt->rtol, dopt->atol,
            r->scene.t_end, r->scene.output_step);
    fprintf(f, "error test: algebraic and index-2 variables excluded\n");
    fprintf(f, "absolute tolerances: %s\nstability guard: %s\nbreakpoints:",
            r->scene.nominal_scales
                ? "atol times each unknown's nominal magnitude (the scales in model_stats.txt)"
                : "atol in SI units",
            dopt->stability_guard ? "on (order 2 where fast modes hold orders 3..5)" : "off");
    for (int i = 0; i < nbk; i++)
        fprintf(f, " %g", bk[i]);
    fprintf(f, "%s\n", nbk ? "" : " none");
    fprintf(f, "t_reached: %.9g s\nrows: %ld\nwall_time: %.3f s\n", r->t, r->rows, wall);
    fprintf(f, "%s\n\n# CSV\n%s,wall_s\n%s,%.3f\n", line, head, row, wall);
    int bad = ferror(f);
    return (fclose(f) != 0 || bad) ? -1 : 0;
}

static int write_model_stats(run *r)
{
    char path[4200];
    FILE *f = open_out(r->outdir, "model_stats.txt", path, sizeof path);
    if (!f) return -1;
    fprintf(f, "# crane model statistics\nscene: %s (%s)\n", r->scene.name, r->scene_path);
    crane_stats_print(r->c, f);
    int bad = ferror(f);
    return (fclose(f) != 0 || bad) ? -1 : 0;
}

static int write_scene_copy(run *r)
{
    char path[4200];
    FILE *f = open_out(r->outdir, "scene.ini", path, sizeof path);
    if (!f) return -1;
    fprintf(f, "; the scene as run: %s with the command-line overrides\n", r->scene_path);
    int rc = crane_scene_write(&r->scene, f);
    return (fclose(f) != 0 || rc) ? -1 : 0;
}

static void draw_figures(run *r)
{
    int tx = crane_output_index("tip_x"), ty = crane_output_index("tip_y");
    double radius = tx >= 0 && ty >= 0 ? hypot(r->first_out[tx] - r->scene.joint_A[0],
                                               r->first_out[ty] - r->scene.joint_A[1])
                                       : r->scene.boom_tip_radius;
    int n = write_plot_script(r->outdir, &r->scene, radius, r->reach);
    if (n == 0) return;
    if (!have_gnuplot()) {
        if (!r->o->quiet) printf("gnuplot not found: figures skipped (plots.gp written)\n");
        return;
    }
    char q[4200], cmd[4400];
    shell_quote(r->outdir, q, sizeof q);
    snprintf(cmd, sizeof cmd, "cd %s && gnuplot plots.gp >/dev/null 2>gnuplot.log", q);
    if (system(cmd) != 0) {
        if (!r->o->quiet) printf("gnuplot failed: see %s/gnuplot.log\n", r->outdir);
    } else {
        char log[4200];
        snprintf(log, sizeof log, "%s/gnuplot.log", r->outdir);
        struct stat st;
        if (stat(log, &st) == 0 && st.st_size == 0) remove(log);
    }
}

static void summary(run *r)
{
    const dae_stats *st = r->s ? dae_get_stats(r->s) : NULL;
    int th = crane_output_index("theta"), thr = crane_output_index("theta_ref");
    printf("crane: scene %s, %s at t = %g s (of %g s)\n", r->scene.name, r->status, r->t,
           r->scene.t_end);
    if (r->have_final && th >= 0)
        printf("  final angle     theta = %.6f rad%s", r->final_out[th], thr >= 0 ? "" : "\n");
    if (r->have_final && th >= 0 && thr >= 0) printf(" (reference %.6f rad)\n", r->final_out[thr]);
    if (r->rows > 0 && col_any("tip_defl_1", "defl_luff") >= 0)
        printf("  peak tip deflections  %.6g m (luffing plane), %.6g m (sideways)\n", r->peak[0],
               r->peak[1]);
    if (st)
        printf("  steps %ld (rejected %ld), Newton iterations %ld, Jacobians %ld\n", st->steps,
               st->rejected_error, st->newton_iters, st->jac_evals);
    printf("  wall time %.2f s; results in %s/\n", wall_now() - r->wall0, r->outdir);
}

/* Enters a phase; for PHASE_SETUP, prepares the status.txt a signal would leave. */
static void set_phase(run *r, int phase, const char *what)
{
    g_phase = PHASE_OTHER;
    if (phase == PHASE_SETUP) {
        snprintf(g_status_path, sizeof g_status_path, "%s/status.txt", r->outdir);
        for (int k = 0; k < 2; k++) {
            int n = snprintf(g_status_text[k], sizeof g_status_text[k],
                             "status: interrupted\nreason: %s received while %s (no results "
                             "written)\nscene: %s (%s)\nt_reached: 0 s\nt_end: %.9g s\nrows: 0\n",
                             k ? "SIGTERM" : "SIGINT", what, r->scene.name, r->scene_path,
                             r->scene.t_end);
            g_status_len[k] = n < 0                                 ? 0
                              : (size_t)n < sizeof g_status_text[k] ? (size_t)n
                                                                    : sizeof g_status_text[k] - 1;
        }
    }
    g_phase = phase;
    if (phase == PHASE_SETUP && g_signal) on_signal((int)g_signal); /* arrived just before */
}

static int simulate(run *r)
{
    const options *o = r->o;
    bg_error err = {0};
    int tty = isatty(STDERR_FILENO) && !o->quiet;
    double *bk = NULL, *y = NULL, *yp = NULL;
    int code = EXIT_OK, nbk = 0;
    dae_options dopt;
    dae_options_default(&dopt);

    if (tty) fprintf(stderr, "crane: building the model (scene %s)\n", r->scene.name);
    set_phase(r, PHASE_SETUP, "building the model");
    r->c = crane_build(&r->scene, &err);
    if (!r->c) return fail_run(r, "building the model", err.message);
    if (write_model_stats(r) != 0)
        fprintf(stderr, "crane: cannot write %s/model_stats.txt\n", r->outdir);
    if (r->scene.static_start) {
        if (tty) fprintf(stderr, "crane: static equilibrium under gravity\n");
        set_phase(r, PHASE_SETUP, "finding the static equilibrium");
        bg_error_clear(&err);
        int rc = crane_settle(r->c, &err);
        if (rc != BG_OK) return fail_run(r, "settling", err.message);
    }
    bgr_model *m = crane_model(r->c);
    dae_problem p;
    if (bgr_dae_problem(m, &p) != BG_OK) return fail_run(r, "problem", bgr_model_error(m)->message);
    int n = p.n;

    int cap = 64;
    bk = malloc((size_t)cap * sizeof *bk);
    y = malloc((size_t)n * sizeof *y);
    yp = malloc((size_t)n * sizeof *yp);
    if (!bk || !y || !yp) {
        code = fail_run(r, "memory", "out of memory");
        goto done;
    }
    nbk = crane_breakpoints(r->c, bk, cap);
    if (nbk > cap) { /* more than fit: ask again with room for all */
        double *nb = realloc(bk, (size_t)nbk * sizeof *bk);
        if (!nb) {
            code = fail_run(r, "memory", "out of memory");
            goto done;
        }
        bk = nb;
        cap = nbk;
        nbk = crane_breakpoints(r->c, bk, cap);
    }
    if (nbk < 0) nbk = 0;
    if (nbk > cap) nbk = cap;

    dopt.rtol = r->scene.rtol;
    dopt.atol = r->scene.atol;
    dopt.has_t_stop = 1;
    dopt.t_stop = r->scene.t_end;
    dopt.breakpoints = bk;
    dopt.nbreakpoints = nbk;
    dopt.exclude_alg = 1;
    dopt.stability_guard = r->scene.stability_guard;
    dopt.max_steps = 10000000;
    bg_error_clear(&err);
    r->s = dae_create(&p, &dopt, &err);
    if (!r->s) {
        code = fail_run(r, "solver", err.message);
        goto done;
    }
    set_phase(r, PHASE_SETUP, "computing consistent initial values");
    int rc = dae_init(r->s, 0.0, bgr_y0(m), bgr_yp0(m));
    if (rc == BG_OK) rc = dae_consistent_init(r->s);
    if (rc != BG_OK) {
        code = fail_run(r, "consistent initial values", dae_get_error(r->s)->message);
        goto done;
    }

    char path[4200];
    r->csv = open_out(r->outdir, "results.csv", path, sizeof path);
    if (!r->csv) {
        code = fail_run(r, "cannot write results.csv", strerror(errno));
        goto done;
    }
    for (int i = 0; i < CRANE_NOUT; i++)
        fprintf(r->csv, "%s%s", i ? "," : "", crane_output_names[i]);
    fputc('\n', r->csv);

    double out[CRANE_NOUT];
    dae_dense(r->s, 0.0, y, yp);
    crane_outputs(r->c, 0.0, y, yp, out);
    write_row(r, 0.0, out);

    double dt = r->scene.output_step, tend = r->scene.t_end, last = 0;
    long nout = (long)ceil(tend / dt - 1e-9);
    if (nout < 1) nout = 1;
    r->t_start = wall_now();
    set_phase(r, PHASE_LOOP, NULL);
    for (long k = 1; k <= nout; k++) {
        if (g_signal) break;
        double tout = k == nout ? tend : (double)k * dt, tret = r->t;
        if (tout > tend) tout = tend;
        rc = dae_solve_to(r->s, tout, &tret, y, yp);
        if (rc < 0) {
            r->t = tret;
            if (tty) fprintf(stderr, "\n");
            char msg[BG_MESSAGE_SIZE + 64];
            snprintf(msg, sizeof msg, "%s (%s)", dae_get_error(r->s)->message, dae_return_name(rc));
            code = fail_run(r, "solver", msg);
            goto done;
        }
        r->t = tret;
        crane_outputs(r->c, tret, y, yp, out);
        write_row(r, tret, out);
        if (ferror(r->csv)) {
            code = fail_run(r, "writing results.csv", strerror(errno));
            goto done;
        }
        progress(r, tty, &last);
    }
    if (tty) fprintf(stderr, "\r%*s\r", 78, "");
    if (g_signal) {
        r->status = "interrupted";
        snprintf(r->reason, sizeof r->reason, "%s received at t = %g s",
                 g_signal == SIGINT    ? "SIGINT"
                 : g_signal == SIGTERM ? "SIGTERM"
                                       : "signal",
                 r->t);
        fprintf(stderr, "crane: interrupted (%s); %ld rows kept in %s/results.csv\n",
                g_signal == SIGINT ? "SIGINT" : "SIGTERM", r->rows, r->outdir);
        code = 128 + (int)g_signal;
    } else {
        r->status = "completed";
    }

done:
    set_phase(r, PHASE_OTHER, NULL);
    if (r->csv) {
        if (fclose(r->csv) != 0 && code == EXIT_OK)
            code = fail_run(r, "closing results.csv", strerror(errno));
        r->csv = NULL;
    }
    if (r->s && write_solver_stats(r, &dopt, nbk, bk) != 0)
        fprintf(stderr, "crane: cannot write %s/solver_stats.txt\n", r->outdir);
    free(bk);
    free(y);
    free(yp);
    return code;
}

int main(int argc, char **argv)
{
    options o;
    int rc = parse_args(argc, argv, &o);
    if (rc >= 0) return rc;

    run r;
    memset(&r, 0, sizeof r);
    r.o = &o;
    r.wall0 = wall_now();
    r.status = "failed";

    char tried[2048];
    const char *arg = o.scene ? o.scene : DEFAULT_SCENE;
    if (!find_scene(arg, r.scene_path, sizeof r.scene_path, tried, sizeof tried)) {
        fprintf(stderr, "crane: scene file '%s' not found (tried %s)\n", arg, tried);
        return EXIT_USAGE;
    }
    bg_error err = {0};
    if (crane_scene_load(&r.scene, r.scene_path, &err) != BG_OK) {
        fprintf(stderr, "%s\n", err.message);
        return EXIT_USAGE;
    }
    for (int i = 0; i < o.nsets; i++) {
        set_item *it = &o.sets[i];
        if (crane_scene_set(&r.scene, it->section, it->key, it->value, it->origin, &err) != BG_OK) {
            fprintf(stderr, "crane: %s\n", err.message);
            return EXIT_USAGE;
        }
    }
    if (o.nsets && crane_scene_check(&r.scene, "command line", &err) != BG_OK) {
        fprintf(stderr, "crane: %s\n", err.message);
        return EXIT_USAGE;
    }

    if (o.out)
        snprintf(r.outdir, sizeof r.outdir, "%s", o.out);
    else
        snprintf(r.outdir, sizeof r.outdir, "results/%s", r.scene.name);
    size_t ol = strlen(r.outdir);
    while (ol > 1 && r.outdir[ol - 1] == '/')
        r.outdir[--ol] = '\0';
    if (mkdir_p(r.outdir) != 0) {
        fprintf(stderr, "crane: cannot create the output folder %s: %s\n", r.outdir,
                strerror(errno));
        return EXIT_RUN;
    }
    if (write_scene_copy(&r) != 0) fprintf(stderr, "crane: cannot write %s/scene.ini\n", r.outdir);

    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND; /* a second signal ends the program at once */
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);

    rc = simulate(&r);
    g_phase = PHASE_OTHER;
    write_status(&r);
    if (r.rows > 1 && !o.no_plots && !g_signal) draw_figures(&r);
    if (!o.quiet) summary(&r);
    dae_free(&r.s);
    crane_free(&r.c);
    return rc;
}
