/* crane-compare's table and figures (compare.h): comparison.csv, comparison.md and, with
 * gnuplot, plots.gp with sway.png, theta_err.png and pressures.png, each over every
 * controller's DIR/<controller>/results.csv, their columns found by name. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "compare.h"
#include "pu_gnuplot.h"

static void num(FILE *f, double v)
{
    if (isnan(v))
        fputs("", f);
    else if (isinf(v))
        fputs("inf", f);
    else
        fprintf(f, "%.6g", v);
}

/* the 1-based column of name in dir/<ctl>/results.csv's header, 0 if none */
static int column_of(const char *dir, const char *ctl, const char *name)
{
    char path[CC_PATH + 64], line[8192];
    snprintf(path, sizeof path, "%s/%s/results.csv", dir, ctl);
    FILE *f = fopen(path, "r");
    if (!f) return 0;
    int col = 0;
    if (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = '\0';
        int k = 1;
        for (char *p = line; p; k++) {
            char *c = strchr(p, ',');
            size_t len = c ? (size_t)(c - p) : strlen(p);
            if (len == strlen(name) && !strncmp(p, name, len)) {
                col = k;
                break;
            }
            p = c ? c + 1 : NULL;
        }
    }
    fclose(f);
    return col;
}

/* one figure: for each controller the expression of columns (a gnuplot using clause with
 * %d for the columns a, b); second: a dashed second curve (b alone) or NULL */
static void figure(FILE *g, const char *dir, const int *which, int n, const char *png,
                   const char *title, const char *ylabel, const char *a, const char *b,
                   const char *expr, const char *expr2)
{
    fprintf(g, "set output '%s'\nset title \"%s\"\nset ylabel \"%s\"\nplot ", png, title, ylabel);
    int first = 1;
    for (int k = 0; k < n; k++) {
        const char *name = cc_controllers[which[k]].name;
        int ca = column_of(dir, name, "t"), cb = column_of(dir, name, a),
            cc = b ? column_of(dir, name, b) : 0;
        if (!ca || !cb || (b && !cc)) continue;
        char u[256];
        snprintf(u, sizeof u, expr, cb, cc);
        fprintf(g, "%s'%s/results.csv' every ::1 using %d:%s with lines lw 2 lc %d title '%s'",
                first ? "" : ", \\\n     ", name, ca, u, k + 1, name);
        if (expr2) {
            snprintf(u, sizeof u, expr2, cb, cc);
            fprintf(g, ", \\\n     '%s/results.csv' every ::1 using %d:%s with lines lw 1 dt 2 "
                       "lc %d notitle",
                    name, ca, u, k + 1);
        }
        first = 0;
    }
    fputs("\n", g);
}

static int plots(const char *dir, const int *which, int n, int quiet)
{
    char exe[CC_PATH], path[CC_PATH + 16], msg[512];
    if (!pu_gnuplot_find(exe, sizeof exe)) {
        if (!quiet) printf("crane-compare: gnuplot not found, no figures\n");
        return 0;
    }
    snprintf(path, sizeof path, "%s/plots.gp", dir);
    FILE *g = fopen(path, "w");
    if (!g) return -1;
    fputs("# crane-compare's figures: gnuplot plots.gp in this folder\n"
          "set datafile separator ','\nset terminal pngcairo size 1100,650 noenhanced\n"
          "set grid\nset key outside right\nset xlabel 't (s)'\n",
          g);
    figure(g, dir, which, n, "sway.png", "The load's distance from its rest point",
           "distance (m)", "sway_distance", NULL, "(column(%d))", NULL);
    figure(g, dir, which, n, "theta_err.png", "Slewing angle error theta - theta_ref",
           "error (rad)", "theta", "theta_ref", "(column(%d) - column(%d))", NULL);
    figure(g, dir, which, n, "pressures.png",
           "Line pressures: high side (solid), low side (dashed)", "pressure (MPa)", "p_high",
           "p_low", "(column(%d) / 1e6)", "(column(%2$d) / 1e6)");
    if (fclose(g) != 0) return -1;
    pu_gnuplot_job job = {.exe = exe, .dir = dir, .script = "plots.gp", .log = "plots.log"};
    int st = pu_gnuplot_run(&job, msg, sizeof msg);
    if (st != 0) {
        fprintf(stderr, "crane-compare: gnuplot failed (%s; see %s/plots.log)\n",
                st < 0 ? msg : "its exit status", dir);
        return -1;
    }
    pu_gnuplot_log_first(dir, "plots.log", 1, msg, sizeof msg);
    return 0;
}

int cc_report(const char *dir, const char *model, double f, double z, const int *which, int n,
              const char *const *status, const cc_metrics *m, int with_plots, int quiet)
{
    char path[CC_PATH + 32];
    double v[32];
    snprintf(path, sizeof path, "%s/comparison.csv", dir);
    FILE *c = fopen(path, "w");
    snprintf(path, sizeof path, "%s/comparison.md", dir);
    FILE *md = fopen(path, "w");
    if (!c || !md) {
        if (c) fclose(c);
        if (md) fclose(md);
        fprintf(stderr, "crane-compare: cannot write %s/comparison.csv and .md\n", dir);
        return -1;
    }
    fputs("controller,status", c);
    for (int i = 0; i < cc_nmetrics; i++) fprintf(c, ",%s", cc_metric_names[i]);
    fputs("\n", c);
    fprintf(md,
            "Model `%s`, shapers at %.5g Hz (damping %.3g); \"after the stop\": from the end of "
            "the (shaped) reference; settling: the load within %.2g m of rest (inf: not within the "
            "run).\n\n| controller |",
            model, f, z, CC_SETTLE_BAND);
    for (int i = 0; i < cc_nmetrics; i++)
        fprintf(md, " %s (%s) |", cc_metric_names[i], cc_metric_units[i]);
    fputs("\n|---|", md);
    for (int i = 0; i < cc_nmetrics; i++) fputs("---|", md);
    fputs("\n", md);
    for (int k = 0; k < n; k++) {
        const char *name = cc_controllers[which[k]].name;
        cc_metric_values(&m[k], v);
        fprintf(c, "%s,%s", name, status[k]);
        fprintf(md, "| %s%s |", name, strcmp(status[k], "completed") ? " (failed)" : "");
        for (int i = 0; i < cc_nmetrics; i++) {
            fputs(",", c);
            num(c, v[i]);
            fputs(" ", md);
            num(md, v[i]);
            fputs(" |", md);
        }
        fputs("\n", c);
        fputs("\n", md);
    }
    fputs("\nControllers:\n\n", md);
    for (int k = 0; k < n; k++)
        fprintf(md, "- `%s`: %s\n", cc_controllers[which[k]].name, cc_controllers[which[k]].what);
    int bad = fclose(c) != 0;
    bad |= fclose(md) != 0;
    if (bad) {
        fprintf(stderr, "crane-compare: writing %s/comparison.csv or .md failed\n", dir);
        return -1;
    }
    return with_plots ? plots(dir, which, n, quiet) : 0;
}
