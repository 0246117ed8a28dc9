/* The crane program's figures (crane_program.h): plots.gp, the paper's Fig. 5 a-f from
 * results.csv, drawn by gnuplot (pu_gnuplot.h) and checked; modes.png for --modes. */
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

/* Writes plots.gp (the paper's Fig. 5 a-f from results.csv) to f; returns the number of
 * figures in it. */
static int write_plot_script(FILE *f, const crane_scene *s, double radius, double reach)
{
    int nfig = 0;
    curve t, a, b;
    fprintf(f, "# Figures of the crane run (paper Fig. 5) from results.csv; run in this folder:\n"
               "#   gnuplot plots.gp\n"
               "set terminal png size 900,600 noenhanced\n");
    if (!curve_col(&t, crane_output_index("t"))) return 0;
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
    return nfig;
}

/* Runs gnuplot on script in the output folder, its messages into gnuplot.log; a signal stops
 * it. Its wait status, or -1 with the reason in msg. */
static int run_gnuplot(const cp_run *r, const char *exe, const char *script, char *msg, size_t size)
{
    pu_gnuplot_job job = {exe, r->rn.outdir, script, NULL, "gnuplot.log", rn_signal_flag()};
    return pu_gnuplot_run(&job, msg, size);
}

int cp_draw_figures(cp_run *r)
{
    int tx = crane_output_index("tip_x"), ty = crane_output_index("tip_y");
    double radius = tx >= 0 && ty >= 0 ? hypot(r->first_out[tx] - r->scene.joint_A[0],
                                               r->first_out[ty] - r->scene.joint_A[1])
                                       : r->scene.boom_tip_radius;
    char path[RN_PATH_SIZE], exe[RN_PATH_SIZE];
    rn_path_in(&r->rn, "plots.gp", path, sizeof path);
    char *gp = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&gp, &len);
    if (!f) return rn_write_failed(&r->rn, path, errno);
    int n = write_plot_script(f, &r->scene, radius, r->reach);
    if (fclose(f) != 0) {
        free(gp);
        return rn_write_failed(&r->rn, path, ENOMEM);
    }
    if (n == 0) {
        free(gp);
        return 0;
    }
    if (rn_save_atomic(path, gp, len) != 0) {
        int e = errno;
        free(gp);
        return rn_write_failed(&r->rn, path, e);
    }
    if (!pu_gnuplot_find(exe, sizeof exe)) {
        free(gp);
        if (!r->o->quiet) printf("gnuplot not found: figures skipped (plots.gp written)\n");
        return 0;
    }
    char why[512];
    int st = run_gnuplot(r, exe, "plots.gp", why, sizeof why), rc = 0;
    if (st == -1) {
        rc = rn_fail_run(&r->rn, "drawing the figures", why);
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
            rn_path_in(&r->rn, name, fig, sizeof fig);
            if (rn_signal())
                remove(fig);
            else if (!pu_png_whole(fig) && ml < sizeof missing)
                ml += (size_t)snprintf(missing + ml, sizeof missing - ml, "%s%s", ml ? ", " : "",
                                       name);
            p = e;
        }
        char first[256];
        pu_gnuplot_log_first(r->rn.outdir, "gnuplot.log", 0, first, sizeof first);
        if (!rn_signal() && (!WIFEXITED(st) || WEXITSTATUS(st) != 0 || missing[0])) {
            snprintf(msg, sizeof msg, "gnuplot %s %d%s%s%s%s%s",
                     WIFEXITED(st) ? "exited with" : "ended by signal",
                     WIFEXITED(st) ? WEXITSTATUS(st) : WTERMSIG(st),
                     missing[0] ? "; not written whole: " : "", missing,
                     first[0] ? " (gnuplot.log: " : "", first, first[0] ? ")" : "");
            rc = rn_fail_run(&r->rn, "drawing the figures", msg);
        } else if (!first[0]) {
            char log[RN_PATH_SIZE];
            rn_path_in(&r->rn, "gnuplot.log", log, sizeof log);
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
    int gs = run_gnuplot(r, exe, "modes.gp", why, sizeof why);
    rn_path_in(&r->rn, "modes.png", png, sizeof png);
    if (gs == -1 || !WIFEXITED(gs) || WEXITSTATUS(gs) != 0 || !pu_png_whole(png))
        return rn_fail_run(&r->rn, "drawing modes.png", "gnuplot failed (see gnuplot.log)");
    pu_gnuplot_log_first(r->rn.outdir, "gnuplot.log", 1, first, sizeof first);
    return 0;
}
