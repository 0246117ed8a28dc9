/* Pictures of a sweep (sweep_plot.h). */
#include "sweep_plot.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "crane_scene.h"
#include "pu_fs.h"
#include "pu_gnuplot.h"
#include "sweep_engine.h"

static int numeric(const sweep_param *p)
{
    return p->type == CRANE_KEY_NUMBER || p->type == CRANE_KEY_INTEGER;
}

/* A text for a gnuplot single-quoted string. */
static void gp_quote(const char *in, char *out, size_t size)
{
    size_t n = 0;
    for (; *in && n + 3 < size; in++) {
        if (*in == '\'') out[n++] = '\'';
        out[n++] = *in;
    }
    out[n] = '\0';
}

typedef struct sort_item {
    double x;
    long index;
} sort_item;

static int by_x(const void *a, const void *b)
{
    const sort_item *p = a, *q = b;
    if (p->x < q->x) return -1;
    if (p->x > q->x) return 1;
    return p->index < q->index ? -1 : p->index > q->index;
}

/* The tics of axis a: ("label" i, ...) with the values' texts. */
static void axis_tics(FILE *f, const sweep_spec *s, int a, const char *which)
{
    const sweep_axis *ax = &s->axes[a];
    fprintf(f, "set %stics (", which);
    for (int i = 0; i < ax->npoints; i++) {
        char q[2 * SWEEP_VALUE_SIZE];
        gp_quote(ax->values[(size_t)i * (size_t)ax->nparams], q, sizeof q);
        fprintf(f, "%s'%s' %d", i ? ", " : "", q, i);
    }
    fprintf(f, ")\n");
}

int sweep_plot(const sweep_spec *s, const sweep_row *rows, const char *outdir, int *nfig, char *msg,
               size_t size)
{
    *nfig = 0;
    msg[0] = '\0';
    enum { NONE, LINE, HEAT, SCATTER } kind = NONE;
    if (s->naxes == 1 && s->axes[0].nparams == 1)
        kind = LINE;
    else if (s->naxes == 2 && s->axes[0].nparams == 1 && s->axes[1].nparams == 1 &&
             s->axes[0].kind != SWEEP_AXIS_LHS && s->axes[1].kind != SWEEP_AXIS_LHS)
        kind = HEAT;
    else if (s->naxes == 1 && s->axes[0].kind == SWEEP_AXIS_LHS && s->axes[0].nparams == 2)
        kind = SCATTER;
    if (kind == NONE) {
        snprintf(msg, size,
                 "no pictures: %d swept keys on %d axes (pictures are drawn for one "
                 "key, a grid of two, or a sample of two)",
                 s->nparams, s->naxes);
        return 0;
    }
    /* plot.dat: case, status, the coordinates, the keys' values (the index for keys that are
     * not numbers), the quantities (NaN: none); a line plot's rows sorted by the key's value */
    char path[SWEEP_PATH_SIZE + 256];
    char *dat = NULL, *gp = NULL;
    size_t dlen = 0, glen = 0;
    FILE *f = open_memstream(&dat, &dlen);
    if (!f) {
        snprintf(msg, size, "out of memory");
        return -1;
    }
    int cstat = 2, ccoord = 3, cparam = 3 + s->naxes, cq = cparam + s->nparams;
    fprintf(f, "# crane-sweep %s: case status", s->name);
    for (int a = 0; a < s->naxes; a++)
        fprintf(f, " i%d", a);
    for (int p = 0; p < s->nparams; p++)
        fprintf(f, " %s", s->params[p].name);
    for (int i = 0; i < s->nreport; i++)
        fprintf(f, " %s", sweep_report_name(s, i));
    fprintf(f, "\n");
    sort_item *order = malloc((size_t)s->ncases * sizeof *order);
    if (!order) {
        fclose(f);
        free(dat);
        snprintf(msg, size, "out of memory");
        return -1;
    }
    for (long c = 0; c < s->ncases; c++) {
        order[c].index = c;
        order[c].x =
            kind == LINE && numeric(&s->params[0]) ? atof(sweep_case_value(s, c, 0)) : (double)c;
    }
    if (kind == LINE) qsort(order, (size_t)s->ncases, sizeof *order, by_x);
    int *has = calloc((size_t)s->nreport, sizeof *has);
    long incomplete = 0;
    for (long k = 0; k < s->ncases; k++) {
        long c = order[k].index;
        const sweep_row *row = &rows[c];
        int coord[SWEEP_MAX_AXES];
        sweep_case_coords(s, c, coord);
        fprintf(f, "%ld %s", c, sweep_status_name(row->status));
        incomplete += row->status != SWEEP_COMPLETED;
        for (int a = 0; a < s->naxes; a++)
            fprintf(f, " %d", coord[a]);
        for (int p = 0; p < s->nparams; p++) {
            if (numeric(&s->params[p]))
                fprintf(f, " %s", sweep_case_value(s, c, p));
            else
                fprintf(f, " %d", coord[s->params[p].axis]);
        }
        for (int i = 0; i < s->nreport; i++) {
            double x = sweep_report_value(s, row, i);
            if (isfinite(x)) {
                fprintf(f, " %.10g", x);
                if (has) has[i] = 1;
            } else {
                fprintf(f, " NaN");
            }
        }
        fprintf(f, "\n");
    }
    free(order);
    if (fclose(f) != 0 || !has) {
        free(dat);
        free(has);
        snprintf(msg, size, "out of memory");
        return -1;
    }
    snprintf(path, sizeof path, "%s/plot.dat", outdir);
    if (pu_write_atomic(path, dat, dlen) != 0) {
        snprintf(msg, size, "cannot write %s: %s", path, strerror(errno));
        free(dat);
        free(has);
        return -1;
    }
    free(dat);

    /* plots.gp */
    f = open_memstream(&gp, &glen);
    if (!f) {
        free(has);
        snprintf(msg, size, "out of memory");
        return -1;
    }
    char name[2 * sizeof s->name];
    gp_quote(s->name, name, sizeof name);
    fprintf(f, "# Pictures of the sweep %s from plot.dat; run in this folder: gnuplot plots.gp\n",
            name);
    fprintf(f, "set terminal png size 900,650 noenhanced\n");
    char names[SWEEP_MAX_REPORT][180];
    int nnames = 0, skipped = 0;
    for (int i = 0; i < s->nreport; i++) {
        const char *qname = sweep_report_name(s, i), *qunit = sweep_report_unit(s, i),
                   *qstem = sweep_report_stem(s, i);
        if (!has[i]) { /* no case has it (e.g. pressures without hydraulics) */
            skipped++;
            continue;
        }
        char label[200], title[500];
        snprintf(label, sizeof label, "%s%s%s%s", qname, qunit[0] ? " [" : "", qunit,
                 qunit[0] ? "]" : "");
        snprintf(title, sizeof title, "%s, sweep %s%s", label, name,
                 incomplete ? " (cases without a value: see sweep.csv)" : "");
        snprintf(names[nnames++], sizeof names[0], "plot_%s.png", qstem);
        int col = cq + i;
        fprintf(f, "\nreset\nset output 'plot_%s.png'\nset title '%s'\n", qstem, title);
        if (kind == LINE) {
            const sweep_param *p = &s->params[0];
            fprintf(f, "set grid\nset xlabel '%s'\nset ylabel '%s'\n", p->name, label);
            if (p->log) fprintf(f, "set logscale x\n");
            if (!numeric(p)) axis_tics(f, s, 0, "x");
            fprintf(f, "plot 'plot.dat' using %d:%d with linespoints lw 2 pt 7 notitle\n", cparam,
                    col);
        } else if (kind == HEAT) {
            fprintf(f, "set xlabel '%s'\nset ylabel '%s'\nset cblabel '%s'\n", s->params[0].name,
                    s->params[1].name, label);
            fprintf(f, "set xrange [-0.5:%d.5]\nset yrange [-0.5:%d.5]\n", s->axes[0].npoints - 1,
                    s->axes[1].npoints - 1);
            axis_tics(f, s, 0, "x");
            axis_tics(f, s, 1, "y");
            fprintf(f, "set palette rgbformulae 33,13,10\nset tics out\n");
            fprintf(f,
                    "plot 'plot.dat' using %d:%d:%d with image notitle, \\\n"
                    "     'plot.dat' using %d:%d:(strcol(%d) eq 'completed' ? sprintf('%%.4g', "
                    "column(%d)) : strcol(%d)) with labels notitle\n",
                    ccoord, ccoord + 1, col, ccoord, ccoord + 1, cstat, col, cstat);
        } else {
            const sweep_param *a = &s->params[0], *b = &s->params[1];
            fprintf(f, "set grid\nset xlabel '%s'\nset ylabel '%s'\nset cblabel '%s'\n", a->name,
                    b->name, label);
            if (a->log) fprintf(f, "set logscale x\n");
            if (b->log) fprintf(f, "set logscale y\n");
            fprintf(f, "set palette rgbformulae 33,13,10\n");
            fprintf(f, "plot 'plot.dat' using %d:%d:%d with points pt 7 ps 1.5 palette notitle\n",
                    cparam, cparam + 1, col);
        }
    }
    fprintf(f, "\nunset output\n");
    free(has);
    if (fclose(f) != 0) {
        free(gp);
        snprintf(msg, size, "out of memory");
        return -1;
    }
    snprintf(path, sizeof path, "%s/plots.gp", outdir);
    int rc = pu_write_atomic(path, gp, glen);
    free(gp);
    if (rc != 0) {
        snprintf(msg, size, "cannot write %s: %s", path, strerror(errno));
        return -1;
    }
    char exe[SWEEP_PATH_SIZE];
    if (!pu_gnuplot_find(exe, sizeof exe)) {
        snprintf(msg, size, "gnuplot not found: pictures skipped (plots.gp written)");
        return 0;
    }
    for (int i = 0; i < nnames; i++) { /* no picture of an earlier sweep stands for this one */
        snprintf(path, sizeof path, "%s/%.179s", outdir, names[i]);
        unlink(path);
    }
    /* gnuplot plots.gp in the output folder (pu_gnuplot.h: started as the cases are, by
     * posix_spawn: an MPI rank does not fork), its messages into gnuplot.log */
    pu_gnuplot_job job = {exe, outdir, "plots.gp", NULL, "gnuplot.log", NULL};
    int st = pu_gnuplot_run(&job, msg, size);
    if (st == -1) return -1;
    char missing[512] = "", first[256] = "";
    size_t ml = 0;
    for (int i = 0; i < nnames; i++) {
        snprintf(path, sizeof path, "%s/%.179s", outdir, names[i]);
        if (pu_png_whole(path))
            (*nfig)++;
        else if (ml < sizeof missing)
            ml += (size_t)snprintf(missing + ml, sizeof missing - ml, "%s%s", ml ? ", " : "",
                                   names[i]);
    }
    pu_gnuplot_log_first(outdir, "gnuplot.log", 1, first, sizeof first);
    if (!WIFEXITED(st) || WEXITSTATUS(st) != 0 || missing[0]) {
        snprintf(msg, size, "gnuplot %s %d%s%s%s%s%s",
                 WIFEXITED(st) ? "exited with" : "ended by signal",
                 WIFEXITED(st) ? WEXITSTATUS(st) : WTERMSIG(st), missing[0] ? "; not drawn: " : "",
                 missing, first[0] ? " (gnuplot.log: " : "", first, first[0] ? ")" : "");
        return -1;
    }
    if (skipped)
        snprintf(msg, size, "%d pictures; %d quantities without a value in any case not drawn",
                 *nfig, skipped);
    else
        snprintf(msg, size, "%d pictures", *nfig);
    return 0;
}
