/* crane-compare: the crane's manoeuvre under each controller of the platform, side by side.
 *
 *   crane-compare [MODEL] [--out DIR] [--t-end T] [--output-step DT] [--controllers LIST]
 *                 [--shaper-frequency F] [--shaper-damping Z] [--set PATH=VALUE] [--no-plots]
 *                 [--quiet]
 *
 * MODEL is a model file with the controller switches of crane/models/crane-control.yaml (the
 * paper crane with its controller platform, the default; a bare name is looked up in
 * crane/models/ here, then in the source tree). Each controller (cc_controllers below) is a run
 * of the model by bgsim's code path (bs_run_file, bgsim/bs_file.c) with its --set replacements,
 * into DIR/<controller>/ (bgsim's files: results.csv, status.txt, ...). The shapers are tuned to
 * the load's pendulum mode, found first by the modes of the model at its static start
 * (bs_run_file with --modes into DIR/modes/: the lowest elastic mode whose part is `load`),
 * unless --shaper-frequency gives it. --set PATH=VALUE (up to 8) goes to every run, the modes'
 * too, before the controller's own replacements. Then:
 *   DIR/comparison.csv   one row per controller: controller, status, the metrics (cc_metrics.c)
 *   DIR/comparison.md    the same as a Markdown table, with the units
 *   DIR/sway.png, theta_err.png, pressures.png (and plots.gp): the load's distance from rest,
 *                        the angle error, the line pressures over time, all controllers in each
 * Exit status 0 when every run completed, 1 when one failed or was refused (its row says so; the
 * others are kept), 2 for a bad command line (nothing run). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "bgsim.h"
#include "compare.h"
#include "pu_cli.h"
#include "pu_fs.h"
#include "pu_gnuplot.h"

#ifndef CC_VERSION
#define CC_VERSION "unknown"
#endif

/* The controllers of crane-control.yaml: the parameters that switch each on ("@f", "@z": the
 * shaper's frequency and damping). */
#define SHAPE(kind)                                                                                \
    "omega_ref.shaper=" kind, "alpha_ref.shaper=" kind, "theta_ref.shaper=" kind,                  \
        "shaper_frequency=@f", "shaper_damping=@z"
const cc_controller cc_controllers[] = {
    {"pid", "the paper's PID on the slewing rate", {NULL}},
    {"pid_2dof", "PID with the setpoint weight b = 0.5 and anti-windup (Tt = 5 s)",
     {"pid_b=0.5", "pid_tt=5", NULL}},
    {"feedforward", "PID and the pump feedforward of the reference rate", {"ff_on=1", NULL}},
    {"zv", "PID on a ZV-shaped reference", {SHAPE("zv"), NULL}},
    {"zvd", "PID on a ZVD-shaped reference", {SHAPE("zvd"), NULL}},
    {"zv_ff", "ZV-shaped reference, PID and feedforward", {SHAPE("zv"), "ff_on=1", NULL}},
    {"lqr", "LQR feedback of the sway around the PID's rate loop", {"lqr_on=1", NULL}},
};
const int cc_ncontrollers = (int)(sizeof cc_controllers / sizeof *cc_controllers);

#define CC_MAX_USER_SETS 8

typedef struct cc_options {
    const char *model, *out, *controllers;
    const char *user_sets[CC_MAX_USER_SETS]; /* --set PATH=VALUE, for every run */
    int nuser_sets;
    double t_end, output_step, shaper_f, shaper_z;
    int has_shaper_f, no_plots, quiet, help, version;
} cc_options;

#define AT(m) PU_CLI_AT(cc_options, m)

/* --set PATH=VALUE: kept for every run (the model reader checks the path and the value) */
static int take_set(const pu_cli_option *opt, const char *value, void *base, char *msg,
                    size_t size)
{
    (void)opt;
    cc_options *o = base;
    const char *eq = value ? strchr(value, '=') : NULL;
    if (!eq || eq == value || !eq[1] || eq - value >= 256) {
        snprintf(msg, size, "option --set expects PATH=VALUE (got '%s')", value ? value : "");
        return -1;
    }
    if (o->nuser_sets >= CC_MAX_USER_SETS) {
        snprintf(msg, size, "option --set given more than %d times", CC_MAX_USER_SETS);
        return -1;
    }
    o->user_sets[o->nuser_sets++] = value;
    return 0;
}
static const pu_cli_option options[] = {
    {.name = "--out", .kind = PU_CLI_STRING, .arg = "DIR",
     .help = "output folder (default results/compare/)", .at = AT(out)},
    {.name = "--t-end", .kind = PU_CLI_DOUBLE, .arg = "T",
     .help = "end time of every run in s (default 60)", .at = AT(t_end), .min = 0, .max = 1e9,
     .min_open = 1, .what = "a time > 0 in s"},
    {.name = "--output-step", .kind = PU_CLI_DOUBLE, .arg = "DT",
     .help = "output interval in s (default 0.02)", .at = AT(output_step), .min = 0, .max = 1e9,
     .min_open = 1, .what = "a time > 0 in s"},
    {.name = "--controllers", .kind = PU_CLI_STRING, .arg = "LIST",
     .help = "the controllers to run, by name, separated by commas (default: all)",
     .at = AT(controllers)},
    {.name = "--shaper-frequency", .kind = PU_CLI_DOUBLE, .arg = "F",
     .help = "the shapers' frequency in Hz (default: the load's pendulum mode, from the modes)",
     .at = AT(shaper_f), .seen = AT(has_shaper_f), .min = 0, .max = 1e6, .min_open = 1,
     .what = "a frequency > 0 in Hz"},
    {.name = "--shaper-damping", .kind = PU_CLI_DOUBLE, .arg = "Z",
     .help = "the shapers' damping ratio with --shaper-frequency (default 0)", .at = AT(shaper_z),
     .min = 0, .max = 1, .max_open = 1, .what = "a damping ratio in [0, 1)"},
    {.name = "--set", .kind = PU_CLI_CALL, .arg = "PATH=VALUE", .take = take_set,
     .help = "replace a model parameter in every run (--set ref_rate=0.05), before the "
             "controller's own"},
    {.name = "--no-plots", .kind = PU_CLI_FLAG, .help = "do not draw the figures",
     .at = AT(no_plots)},
    {.name = "--quiet", .kind = PU_CLI_FLAG, .help = "no progress lines (errors only)",
     .at = AT(quiet)},
    {.name = "--help", .alias = "-h", .kind = PU_CLI_STOP, .help = "this text", .at = AT(help)},
    {.name = "--version", .kind = PU_CLI_STOP, .help = "the version", .at = AT(version)},
};

static const pu_cli cli = {
    .program = "crane-compare",
    .usage = "[MODEL] [options]",
    .intro = "Runs the crane's manoeuvre once per controller and compares them: DIR/comparison.csv "
             "and .md (one row per controller), the figures sway.png, theta_err.png, "
             "pressures.png. MODEL (default crane/models/crane-control.yaml) must offer the "
             "controller switches of crane-control.yaml.",
    .options_title = "options:",
    .epilogue = "controllers: pid, pid_2dof, feedforward, zv, zvd, zv_ff, lqr (docs/control.md)",
    .options = options,
    .noptions = (int)(sizeof options / sizeof *options),
    .positional = AT(model),
    .positional_many = "more than one model given ('%s' and '%s')",
    .suggest = 1,
};

/* as given; a bare name in crane/models/ here, then in the source tree. 1 found. */
static int find_model(const char *arg, char *path, size_t size)
{
    const char *forms[3] = {"%s", "crane/models/%s", NULL};
#ifdef CC_SOURCE_ROOT
    forms[2] = CC_SOURCE_ROOT "/crane/models/%s";
#endif
    int nf = strchr(arg, '/') ? 1 : 3;
    for (int f = 0; f < nf && forms[f]; f++) {
        int len = snprintf(path, size, forms[f], arg);
        struct stat st;
        if (len > 0 && (size_t)len < size && stat(path, &st) == 0 && S_ISREG(st.st_mode)) return 1;
    }
    return 0;
}

/* bgsim's options for a run of model into dir with the replacements sets ("PATH=VALUE", "@f",
 * "@z" replaced); 0, or -1 (a set too long). */
static int run_options(const cc_options *o, const char *model, const char *dir,
                       const char *const *sets, double f, double z, int argc, char **argv,
                       bs_options *b, char (*values)[256])
{
    memset(b, 0, sizeof *b);
    const char *all[CC_MAX_USER_SETS + CC_MAX_SETS + 1];
    int na = 0;
    for (int i = 0; i < o->nuser_sets; i++) all[na++] = o->user_sets[i];
    for (int i = 0; sets && sets[i]; i++) all[na++] = sets[i];
    all[na] = NULL;
    sets = all;
    b->model = model;
    b->out = dir;
    b->max_rows = BS_DEFAULT_MAX_ROWS;
    b->quiet = 1;
    b->t_end = o->t_end;
    b->has_t_end = 1;
    b->output_step = o->output_step;
    b->has_output_step = 1;
    b->argc = argc;
    b->argv = argv;
    for (int i = 0; sets && sets[i]; i++) {
        const char *eq = strchr(sets[i], '=');
        if (!eq || i >= CC_MAX_USER_SETS + CC_MAX_SETS) return -1;
        snprintf(b->set_paths[i], sizeof b->set_paths[i], "%.*s", (int)(eq - sets[i]), sets[i]);
        if (!strcmp(eq + 1, "@f"))
            snprintf(values[i], 256, "%.10g", f);
        else if (!strcmp(eq + 1, "@z"))
            snprintf(values[i], 256, "%.10g", z);
        else
            snprintf(values[i], 256, "%s", eq + 1);
        b->sets[i].path = b->set_paths[i];
        b->sets[i].value = values[i];
        b->nsets = i + 1;
    }
    return 0;
}

/* The load's pendulum mode from DIR/modes/modes.csv: the first elastic mode whose part is
 * `load` (the modes are listed by increasing frequency). 0, or -1 (said on stderr). */
static int pendulum_mode(const char *dir, double *f, double *z)
{
    char path[CC_PATH];
    snprintf(path, sizeof path, "%s/modes/modes.csv", dir);
    FILE *fp = fopen(path, "r");
    if (!fp) {
        fprintf(stderr, "crane-compare: %s: %s\n", path, strerror(errno));
        return -1;
    }
    char line[4096];
    int found = 0;
    if (fgets(line, sizeof line, fp))
        while (!found && fgets(line, sizeof line, fp)) {
            int idx;
            double fr, dr;
            char kind[32], part[256];
            if (sscanf(line, "%d,%lf,%lf,%31[^,],%255[^,]", &idx, &fr, &dr, kind, part) == 5 &&
                !strcmp(kind, "elastic") && !strcmp(part, "load")) {
                *f = fr;
                *z = dr > 0 && dr < 1 ? dr : 0;
                found = 1;
            }
        }
    fclose(fp);
    if (!found)
        fprintf(stderr,
                "crane-compare: %s lists no elastic mode of the part 'load': give the shapers' "
                "frequency with --shaper-frequency\n",
                path);
    return found ? 0 : -1;
}

int cc_report(const char *dir, const char *model, double f, double z, const int *which, int n,
              const char *const *status, const cc_metrics *m, int plots, int quiet);

static int selected(const char *list, const char *name)
{
    if (!list) return 1;
    size_t n = strlen(name);
    for (const char *p = list; *p;) {
        size_t k = strcspn(p, ",");
        if (k == n && !strncmp(p, name, n)) return 1;
        p += k + (p[k] ? 1 : 0);
    }
    return 0;
}

int main(int argc, char **argv)
{
    cc_options o = {.model = "crane-control.yaml",
                    .out = "results/compare",
                    .t_end = 60,
                    .output_step = 0.02};
    char msg[512];
    const pu_cli_option *stop = NULL;
    int pr = pu_cli_parse(&cli, argc, argv, &o, &stop, msg, sizeof msg);
    if (pr == PU_CLI_ERROR) {
        fprintf(stderr, "crane-compare: %s\n(crane-compare --help lists the options)\n", msg);
        return RN_EXIT_USAGE;
    }
    if (pr == PU_CLI_STOPPED) {
        if (o.version) {
            printf("crane-compare %s\n", CC_VERSION);
            return 0;
        }
        char *h = pu_cli_help(&cli);
        if (h) fputs(h, stdout);
        free(h);
        return h ? 0 : RN_EXIT_RUN;
    }
    int which[CC_MAX_CTL], n = 0;
    for (int i = 0; i < cc_ncontrollers; i++)
        if (selected(o.controllers, cc_controllers[i].name)) which[n++] = i;
    if (o.controllers) { /* every name must be one */
        for (const char *p = o.controllers; *p;) {
            size_t k = strcspn(p, ",");
            int ok = 0;
            for (int i = 0; i < cc_ncontrollers; i++)
                ok |= strlen(cc_controllers[i].name) == k && !strncmp(p, cc_controllers[i].name, k);
            if (!ok) {
                fprintf(stderr,
                        "crane-compare: --controllers: '%.*s' is no controller (the controllers: "
                        "pid, pid_2dof, feedforward, zv, zvd, zv_ff, lqr)\n",
                        (int)k, p);
                return RN_EXIT_USAGE;
            }
            p += k + (p[k] ? 1 : 0);
        }
    }
    if (n == 0) {
        fprintf(stderr, "crane-compare: --controllers names no controller\n");
        return RN_EXIT_USAGE;
    }
    char model[CC_PATH];
    if (!find_model(o.model, model, sizeof model)) {
        fprintf(stderr, "crane-compare: model file '%s' not found (as given, in crane/models/)\n",
                o.model);
        return RN_EXIT_USAGE;
    }
    if (pu_mkdir_p(o.out, 0777, msg, sizeof msg) != 0) {
        fprintf(stderr, "crane-compare: %s\n", msg);
        return RN_EXIT_RUN;
    }
    double f = o.shaper_f, z = o.shaper_z;
    char dir[CC_PATH], values[CC_MAX_USER_SETS + CC_MAX_SETS][256];
    bs_options b;
    if (!o.has_shaper_f) {
        snprintf(dir, sizeof dir, "%s/modes", o.out);
        run_options(&o, model, dir, NULL, 0, 0, argc, argv, &b, values);
        b.modes = 1;
        int rc = bs_run_file("crane-compare", &b, argc, argv, NULL);
        if (rc != 0 || pendulum_mode(o.out, &f, &z) != 0) {
            fprintf(stderr, "crane-compare: the modes of %s failed (see %s/status.txt)\n", model,
                    dir);
            return rc == RN_EXIT_USAGE ? RN_EXIT_USAGE : RN_EXIT_RUN;
        }
    }
    if (!o.quiet) printf("crane-compare: %s, shapers at %.6g Hz, damping %.3g\n", model, f, z);
    const char *status[CC_MAX_CTL];
    cc_metrics met[CC_MAX_CTL];
    int failed = 0;
    for (int k = 0; k < n; k++) {
        const cc_controller *c = &cc_controllers[which[k]];
        snprintf(dir, sizeof dir, "%s/%s", o.out, c->name);
        if (run_options(&o, model, dir, c->sets, f, z, argc, argv, &b, values) != 0) return 2;
        int rc = bs_run_file("crane-compare", &b, argc, argv, NULL);
        if (rc == RN_EXIT_USAGE) return rc; /* the model refuses a switch: said on stderr */
        status[k] = rc == 0 ? "completed" : "failed";
        char path[CC_PATH + 16];
        snprintf(path, sizeof path, "%s/results.csv", dir);
        cc_table t;
        if (cc_table_read(path, &t, msg, sizeof msg) != 0 ||
            cc_metrics_of(&t, &met[k], msg, sizeof msg) != 0) {
            fprintf(stderr, "crane-compare: %s: %s\n", c->name, msg);
            for (size_t i = 0; i < sizeof met[k] / sizeof(double); i++) ((double *)&met[k])[i] = NAN;
            status[k] = "failed";
        }
        if (t.v) cc_table_free(&t);
        failed |= strcmp(status[k], "completed") != 0;
        if (!o.quiet)
            printf("  %-12s %s: sway after the stop %.3g m, angle error %.3g rad\n", c->name,
                   status[k], met[k].sway_residual_m, met[k].theta_err_max);
    }
    int rr = cc_report(o.out, model, f, z, which, n, status, met, !o.no_plots, o.quiet);
    return failed || rr ? RN_EXIT_RUN : 0;
}
