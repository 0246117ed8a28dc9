/* A model file SCENE (crane_program.h): `crane crane/models/paper.yaml` runs the model as bgsim
 * runs it, through bgsim's run of a model file (bgsim.h: bs_run_file; the same code path, so
 * that results.csv is bgsim's bit for bit), and adds the crane's own on top: Fig. 5 (cp_plots.c,
 * its columns found by name in results.csv) after a run that reached its end, and the summary's
 * final angle and peak deflections, read back from results.csv's columns.
 *
 * The command line maps onto bgsim's: --out, --t-end, --rtol, --atol, --output-step, --max-rows,
 * --static, --modes, --quiet, --vtk, --vtk-step as bgsim takes them, --set PATH=VALUE a model
 * parameter (mdl_set); --no-plots is the crane's. The options of INI scenes only (--elements,
 * --animate, --anim-step, --anim-scale) are refused with exit 2. The default
 * output folder is results/<the file's name without .yaml>/ (paper.yaml: results/paper/, as the
 * scene paper's). */
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "bgsim.h"
#include "crane_program.h"

/* the crane's additions, the hooks' context */
typedef struct model_extras {
    const cp_options *o;
    const char *file; /* the model file's name without its folder (the figures' titles) */
    int scanned;      /* rows read back (scan_rows): */
    cp_columns cols;
    cp_rows rows;
    double cx, cy; /* the slewing axis */
} model_extras;

int cp_is_model_file(const char *arg)
{
    size_t n = strlen(arg);
    return n > 5 && !strcmp(arg + n - 5, ".yaml");
}

int cp_find_model(const char *arg, char *path, size_t size, char *tried, size_t tsize)
{
    /* as given; a bare name in crane/models/ here, then in the source tree */
    const char *forms[3] = {"%s", "crane/models/%s", NULL};
#ifdef CRANE_SOURCE_ROOT
    forms[2] = CRANE_SOURCE_ROOT "/crane/models/%s";
#endif
    int nforms = strchr(arg, '/') ? 1 : 3;
    size_t tl = 0;
    tried[0] = '\0';
    for (int f = 0; f < nforms && forms[f]; f++) {
        int len = snprintf(path, size, forms[f], arg);
        if (len < 0 || (size_t)len >= size) continue;
        struct stat st;
        if (stat(path, &st) == 0 && S_ISREG(st.st_mode)) return 1;
        if (tl < tsize) {
            len = snprintf(tried + tl, tsize - tl, "%s%s", tl ? ", " : "", path);
            tl = len < 0 ? tsize : tl + (size_t)len;
        }
    }
    return 0;
}

/* The first option of INI scenes only that the command line gives, or NULL. */
static const char *ini_only_option(const cp_options *o)
{
    for (int i = 0; i < o->nsets; i++)
        if (!strcmp(o->sets[i].origin, "--elements")) return "--elements";
    if (o->viz.animate) return "--animate (--anim-step, --anim-scale)";
    return NULL;
}

/* --t-end, --rtol, --atol, --output-step (kept as scene-key overrides by cp_cli.c) into bgsim's
 * options, checked as bgsim checks them: a decimal number, in its range. 0, or RN_EXIT_USAGE
 * (said on stderr). */
static int solver_option(const cp_set_item *it, bs_options *b)
{
    static const struct {
        const char *name, *what;
        double min, max; /* min < value <= max */
        size_t at, has;
    } opts[] = {
        {"--t-end", "a time > 0 in s", 0, 1e300, offsetof(bs_options, t_end),
         offsetof(bs_options, has_t_end)},
        {"--rtol", "a number in (0, 1]", 0, 1, offsetof(bs_options, rtol),
         offsetof(bs_options, has_rtol)},
        {"--atol", "a number > 0", 0, 1e300, offsetof(bs_options, atol),
         offsetof(bs_options, has_atol)},
        {"--output-step", "a time > 0 in s", 0, 1e300, offsetof(bs_options, output_step),
         offsetof(bs_options, has_output_step)},
    };
    for (size_t k = 0; k < sizeof opts / sizeof *opts; k++) {
        if (strcmp(it->origin, opts[k].name)) continue;
        char *end;
        errno = 0;
        double v = strtod(it->value, &end);
        if (end == it->value || *end || strpbrk(it->value, "xX") || errno == ERANGE ||
            !(v > opts[k].min && v <= opts[k].max)) {
            fprintf(stderr,
                    "crane: option %s needs %s (got '%s')\n(crane --help lists the "
                    "options)\n",
                    opts[k].name, opts[k].what, it->value);
            return RN_EXIT_USAGE;
        }
        *(double *)((char *)b + opts[k].at) = v;
        *(int *)((char *)b + opts[k].has) = 1;
        return 0;
    }
    return 0;
}

/* The crane's command line as bgsim's options (b->model, b->out: the caller's). 0, or
 * RN_EXIT_USAGE (said on stderr). */
static int bgsim_options(const cp_options *o, bs_options *b)
{
    b->max_rows = o->max_rows;
    b->static_only = o->static_only;
    b->modes = o->modes;
    b->modes_t = o->modes_t;
    b->quiet = o->quiet;
    b->vtk = o->viz.vtk;
    b->has_vtk_step = o->viz.vtk_step > 0;
    b->vtk_step = o->viz.vtk_step;
    b->errest = o->errest; /* --error-estimate [K]: the runner's, as bgsim's */
    b->errest_factor = o->errest_factor;
    b->argc = o->argc;
    b->argv = o->argv;
    for (int i = 0; i < o->nsets; i++)
        if (solver_option(&o->sets[i], b) != 0) return RN_EXIT_USAGE;
    /* --set PATH=VALUE, as bgsim's take_set splits it */
    for (int i = 0; i < o->nset_raw; i++) {
        const char *v = o->set_raw[i], *eq = strchr(v, '=');
        if (!eq || eq == v || !eq[1] || eq - v >= (long)sizeof b->set_paths[0]) {
            fprintf(
                stderr,
                "crane: --set expects PATH=VALUE for a model file (a parameter or "
                "COMPONENT.PARAM, the path shorter than %zu characters), got '%s'\n(crane --help "
                "lists the options)\n",
                sizeof b->set_paths[0], v);
            return RN_EXIT_USAGE;
        }
        snprintf(b->set_paths[i], sizeof b->set_paths[i], "%.*s", (int)(eq - v), v);
        b->sets[i].path = b->set_paths[i];
        b->sets[i].value = eq + 1;
    }
    b->nsets = o->nset_raw;
    return 0;
}

/* results.csv read back once: its columns and rows (the figures and the summary). 0 or -1. */
static int scan_rows(bs_run *r, model_extras *x)
{
    if (x->scanned) return x->scanned > 0 ? 0 : -1;
    /* the slewing axis (the crane's model files: the parameters axis_x, axis_y; else 0, 0) */
    if (mdl_parameter(r->mm, "axis_x", &x->cx) != BG_OK || !isfinite(x->cx)) x->cx = 0;
    if (mdl_parameter(r->mm, "axis_y", &x->cy) != BG_OK || !isfinite(x->cy)) x->cy = 0;
    char csv[RN_PATH_SIZE];
    rn_path_in(&r->rn, "results.csv", csv, sizeof csv);
    int ok = cp_columns_read(csv, &x->cols) == 0 &&
             cp_rows_scan(csv, &x->cols, x->cx, x->cy, &x->rows) == 0;
    x->scanned = ok ? 1 : -1;
    return ok ? 0 : -1;
}

/* finish: Fig. 5 after a dynamic run that reached its end (bs_extras) */
static int draw_figures(bs_run *r, void *ctx)
{
    model_extras *x = ctx;
    if (x->o->no_plots || x->o->static_only || x->o->modes || r->rn.rows <= 1) return 0;
    if (scan_rows(r, x) != 0)
        return rn_fail_run(&r->rn, "drawing the figures: reading results.csv back",
                           strerror(errno));
    double tip_r = NAN;
    mdl_parameter(r->mm, "boom_tip_radius", &tip_r);
    int tx = cp_column(&x->cols, "tip_x"), ty = cp_column(&x->cols, "tip_y");
    char source[300];
    snprintf(source, sizeof source, "model file %.280s", x->file);
    cp_fig_info fi = {source, x->cx, x->cy, tip_r, x->rows.reach, tip_r};
    if (tx >= 0 && ty >= 0 && x->rows.rows > 0)
        fi.radius = hypot(x->rows.first[tx] - x->cx, x->rows.first[ty] - x->cy);
    if (!isfinite(fi.fallback_radius)) fi.fallback_radius = isfinite(fi.radius) ? fi.radius : 1;
    if (!isfinite(fi.radius)) fi.radius = 0;
    int rc = cp_figures(&r->rn, &fi, x->o->quiet);
    if (rn_signal() && !strcmp(r->rn.status, "completed"))
        snprintf(r->rn.reason, sizeof r->rn.reason,
                 "the run reached its end; %s received while drawing the figures: they were "
                 "not drawn",
                 rn_signal_name(rn_signal()));
    return rc;
}

/* summary: the crane's lines from results.csv's columns (bs_extras) */
static void summary_lines(const bs_run *r, void *ctx)
{
    model_extras *x = ctx;
    if (x->o->static_only || x->o->modes || r->rn.rows_disk < 1) return;
    if (scan_rows((bs_run *)r, x) != 0 || x->rows.rows < 1) return;
    const double *last = x->rows.last;
    int th = cp_column(&x->cols, "theta"), thr = cp_column(&x->cols, "theta_ref");
    int d1 = cp_column(&x->cols, "tip_defl_1"), d2 = cp_column(&x->cols, "tip_defl_2");
    if (th >= 0) printf("  final angle     theta = %.6f rad%s", last[th], thr >= 0 ? "" : "\n");
    if (th >= 0 && thr >= 0) printf(" (reference %.6f rad)\n", last[thr]);
    if (d1 >= 0 && d2 >= 0)
        printf("  peak tip deflections  %.6g m (luffing plane), %.6g m (sideways)\n",
               x->rows.peak[0], x->rows.peak[1]);
}

int cp_run_model(const cp_options *o, int argc, char **argv)
{
    char path[RN_PATH_SIZE], tried[2048], out[RN_PATH_SIZE];
    const char *bad = ini_only_option(o);
    if (bad) {
        fprintf(stderr,
                "crane: option %s belongs to INI scenes only, not to the model file %s (a model "
                "file states its parts itself; its parameters are set with --set NAME=VALUE: "
                "docs/crane-program.md)\n",
                bad, o->scene);
        return RN_EXIT_USAGE;
    }
    if (strlen(o->scene) > RN_OUT_MAX) {
        fprintf(stderr, "crane: the model file's path is %zu characters long, more than %d\n",
                strlen(o->scene), RN_OUT_MAX);
        return RN_EXIT_USAGE;
    }
    if (!cp_find_model(o->scene, path, sizeof path, tried, sizeof tried)) {
        fprintf(stderr, "crane: model file '%s' not found (tried %s)\n", o->scene, tried);
        return RN_EXIT_USAGE;
    }
    bs_options *b = calloc(1, sizeof *b);
    model_extras *x = calloc(1, sizeof *x);
    int rc = !b || !x ? RN_EXIT_RUN : bgsim_options(o, b);
    if (!b || !x) fprintf(stderr, "crane: out of memory\n");
    if (rc == 0) {
        const char *base = strrchr(path, '/');
        base = base ? base + 1 : path;
        /* the default folder: results/<the file's name without .yaml> (".yaml": "model") */
        size_t stem = strlen(base) - 5;
        snprintf(out, sizeof out, "results/%.*s", stem ? (int)stem : 5, stem ? base : "model");
        b->model = path;
        b->out = o->out ? o->out : out;
        x->o = o;
        x->file = base;
        bs_extras ex = {cp_run_files, NULL, draw_figures, summary_lines, x};
        if (!o->no_plots && !o->static_only && !o->modes)
            ex.not_done = ": the figures were not drawn";
        rc = bs_run_file("crane", b, argc, argv, &ex);
    }
    free(b);
    free(x);
    return rc;
}
