/* The crane program's figures (crane_program.h): plots.gp, the paper's Fig. 5 a-f from
 * results.csv, drawn by gnuplot (pu_gnuplot.h) and checked; modes.png for --modes. The figures
 * find their columns by name in results.csv's header (cp_columns.c), so that they serve the
 * crane's results from a scene (crane_outputs.c's columns, with units) and from a model file
 * (the file's outputs: the same names, without units, and tip_radius besides). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "crane_program.h"
#include "crane_scene.h"
#include "pu_gnuplot.h"

/* A curve of the figures: an output column, or the difference ref - val of two (the errors,
 * when the model gives the quantities and their references only). */
typedef struct curve {
    char using[32]; /* gnuplot "using" part: "8" or "($5-$4)" */
    char label[96]; /* with unit */
} curve;

/* Column of output a, or of b if the file has no a (-1: neither). */
static int col_any(const cp_columns *cs, const char *a, const char *b)
{
    int c = cp_column(cs, a);
    return c >= 0 || !b ? c : cp_column(cs, b);
}

static int curve_col(const cp_columns *cs, curve *cv, int c)
{
    if (c < 0) return 0;
    snprintf(cv->using, sizeof cv->using, "%d", c + 1);
    snprintf(cv->label, sizeof cv->label, "%s", cp_column_label(cs, c));
    return 1;
}

/* err_name if the file has it, else ref - val labelled "err_name = ref - val [unit]". */
static int curve_err(const cp_columns *cs, curve *cv, const char *err_name, const char *val,
                     const char *ref)
{
    if (curve_col(cs, cv, cp_column(cs, err_name))) return 1;
    int v = cp_column(cs, val), r = cp_column(cs, ref);
    if (v < 0 || r < 0) return 0;
    const char *unit = strchr(cp_column_label(cs, v), '[');
    snprintf(cv->using, sizeof cv->using, "($%d-$%d)", r + 1, v + 1);
    snprintf(cv->label, sizeof cv->label, "%s = %s - %s %s", err_name, ref, val, unit ? unit : "");
    return 1;
}

static void gp_head(FILE *f, const char *file, const char *title, const cp_fig_info *fi,
                    const curve *x, const curve *y)
{
    fprintf(f, "\nreset\nset datafile separator ','\nset grid\nset key top right\n");
    fprintf(f, "set output '%s'\nset title '%s (%s)'\n", file, title, fi->source);
    fprintf(f, "set xlabel '%s'\nset ylabel '%s'\n", x->label, y->label);
}

/* Writes plots.gp (the paper's Fig. 5 a-f from results.csv, its columns cs found by name) to f;
 * returns the number of figures in it. A figure whose columns the file lacks is left out. */
static int write_plot_script(FILE *f, const cp_columns *cs, const cp_fig_info *fi)
{
    int nfig = 0;
    curve t, a, b;
    fprintf(f, "# Figures of the crane run (paper Fig. 5) from results.csv; run in this folder:\n"
               "#   gnuplot plots.gp\n"
               "set terminal png size 900,600 noenhanced\n");
    if (!curve_col(cs, &t, cp_column(cs, "t"))) return 0;
    /* (a) the tip's path seen from above, with the circle of the tip radius */
    if (curve_col(cs, &a, cp_column(cs, "tip_x")) && curve_col(cs, &b, cp_column(cs, "tip_y"))) {
        gp_head(f, "fig5a.png", "(a) boom tip trajectory in the X0Y0 plane", fi, &a, &b);
        /* the whole circle through the tip's start, centred on the slewing axis */
        double cx = fi->cx, cy = fi->cy, radius = fi->radius;
        double h = fmax(1.1 * radius, 1.05 * fi->reach);
        if (!(h > 0)) h = 1.1 * fi->fallback_radius + 1;
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
        if (curve_col(cs, &a, col_any(cs, defl[k][1], defl[k][2]))) {
            gp_head(f, defl[k][0], defl_title[k], fi, &t, &a);
            fprintf(f, "plot 'results.csv' using 1:%s with lines lw 2 notitle\n", a.using);
            nfig++;
        }
    /* (d), (e) angle and angular velocity with their references */
    static const char *ref[2][4] = {
        {"fig5d.png", "theta", "theta_ref", "(d) platform rotation angle"},
        {"fig5e.png", "omega", "omega_ref", "(e) platform angular velocity"}};
    for (int k = 0; k < 2; k++)
        if (curve_col(cs, &a, cp_column(cs, ref[k][1])) &&
            curve_col(cs, &b, cp_column(cs, ref[k][2]))) {
            gp_head(f, ref[k][0], ref[k][3], fi, &t, &a);
            fprintf(f,
                    "plot 'results.csv' using 1:%s with lines lw 2 title '%s', \\\n"
                    "     'results.csv' using 1:%s with lines lw 1 dt 2 title '%s'\n",
                    a.using, a.label, b.using, b.label);
            nfig++;
        }
    /* (f) velocity error (left axis) and acceleration error (right axis) */
    if (curve_err(cs, &a, "omega_err", "omega", "omega_ref") &&
        curve_err(cs, &b, "alpha_err", "alpha", "alpha_ref")) {
        gp_head(f, "fig5f.png", "(f) angular velocity and acceleration errors", fi, &t, &a);
        fprintf(f, "set y2label '%s'\nset ytics nomirror\nset y2tics\n", b.label);
        fprintf(f,
                "plot 'results.csv' using 1:%s with lines lw 2 title '%s' axes x1y1, \\\n"
                "     'results.csv' using 1:%s with lines lw 1 title '%s' axes x1y2\n",
                a.using, a.label, b.using, b.label);
        nfig++;
    }
    fprintf(f, "\nunset output\n");
    return nfig;
}

/* Runs gnuplot on script in the output folder, its messages into gnuplot.log; a signal stops
 * it. Its wait status, or -1 with the reason in msg. */
static int run_gnuplot(const rn_run *rn, const char *exe, const char *script, char *msg,
                       size_t size)
{
    pu_gnuplot_job job = {exe, rn->outdir, script, NULL, "gnuplot.log", rn_signal_flag()};
    return pu_gnuplot_run(&job, msg, size);
}

int cp_draw_figures(cp_run *r)
{
    int tx = crane_output_index("tip_x"), ty = crane_output_index("tip_y");
    char source[128];
    snprintf(source, sizeof source, "scene %s", r->scene.name);
    cp_fig_info fi = {source, r->scene.joint_A[0], r->scene.joint_A[1], r->scene.boom_tip_radius,
                      r->reach, r->scene.boom_tip_radius};
    if (tx >= 0 && ty >= 0)
        fi.radius = hypot(r->first_out[tx] - fi.cx, r->first_out[ty] - fi.cy);
    return cp_figures(&r->rn, &fi, r->o->quiet);
}

int cp_figures(rn_run *rn, const cp_fig_info *fi, int quiet)
{
    char path[RN_PATH_SIZE], exe[RN_PATH_SIZE];
    cp_columns *cs = malloc(sizeof *cs);
    rn_path_in(rn, "results.csv", path, sizeof path);
    if (!cs) return rn_fail_run(rn, "drawing the figures", "out of memory");
    if (cp_columns_read(path, cs) != 0) {
        int e = errno;
        free(cs);
        return rn_fail_run(rn, "drawing the figures: reading the header of results.csv",
                           strerror(e));
    }
    rn_path_in(rn, "plots.gp", path, sizeof path);
    char *gp = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&gp, &len);
    if (!f) {
        free(cs);
        return rn_write_failed(rn, path, errno);
    }
    int n = write_plot_script(f, cs, fi);
    free(cs);
    if (fclose(f) != 0) {
        free(gp);
        return rn_write_failed(rn, path, ENOMEM);
    }
    if (n == 0) {
        free(gp);
        return 0;
    }
    if (rn_save_atomic(path, gp, len) != 0) {
        int e = errno;
        free(gp);
        return rn_write_failed(rn, path, e);
    }
    if (!pu_gnuplot_find(exe, sizeof exe)) {
        free(gp);
        if (!quiet) printf("gnuplot not found: figures skipped (plots.gp written)\n");
        return 0;
    }
    char why[512];
    int st = run_gnuplot(rn, exe, "plots.gp", why, sizeof why), rc = 0;
    if (st == -1) {
        rc = rn_fail_run(rn, "drawing the figures", why);
    } else {
        /* each figure the script names ("set output 'fig5a.png'") must be a whole PNG */
        char missing[512] = "", msg[1024];
        size_t ml = 0;
        for (const char *p = gp; (p = strstr(p, "set output '")) != NULL;) {
            p += strlen("set output '");
            const char *e = strchr(p, '\'');
            if (!e) break;
            char name[64], fig[RN_PATH_SIZE];
            snprintf(name, sizeof name, "%.*s", (int)(e - p), p);
            rn_path_in(rn, name, fig, sizeof fig);
            if (rn_signal())
                remove(fig);
            else if (!pu_png_whole(fig) && ml < sizeof missing)
                ml += (size_t)snprintf(missing + ml, sizeof missing - ml, "%s%s", ml ? ", " : "",
                                       name);
            p = e;
        }
        char first[256];
        pu_gnuplot_log_first(rn->outdir, "gnuplot.log", 0, first, sizeof first);
        if (!rn_signal() && (!WIFEXITED(st) || WEXITSTATUS(st) != 0 || missing[0])) {
            snprintf(msg, sizeof msg, "gnuplot %s %d%s%s%s%s%s",
                     WIFEXITED(st) ? "exited with" : "ended by signal",
                     WIFEXITED(st) ? WEXITSTATUS(st) : WTERMSIG(st),
                     missing[0] ? "; not written whole: " : "", missing,
                     first[0] ? " (gnuplot.log: " : "", first, first[0] ? ")" : "");
            rc = rn_fail_run(rn, "drawing the figures", msg);
        } else if (!first[0]) {
            char log[RN_PATH_SIZE];
            rn_path_in(rn, "gnuplot.log", log, sizeof log);
            remove(log);
        }
    }
    free(gp);
    return rc;
}

int cp_draw_modes(cp_run *r)
{
    char exe[RN_PATH_SIZE], png[RN_PATH_SIZE], why[512], first[256];
    if (r->o->no_plots || !pu_gnuplot_find(exe, sizeof exe)) return 0;
    int gs = run_gnuplot(&r->rn, exe, "modes.gp", why, sizeof why);
    rn_path_in(&r->rn, "modes.png", png, sizeof png);
    if (gs == -1 || !WIFEXITED(gs) || WEXITSTATUS(gs) != 0 || !pu_png_whole(png))
        return rn_fail_run(&r->rn, "drawing modes.png", "gnuplot failed (see gnuplot.log)");
    pu_gnuplot_log_first(r->rn.outdir, "gnuplot.log", 1, first, sizeof first);
    return 0;
}
