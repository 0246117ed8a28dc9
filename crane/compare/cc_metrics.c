/* The metrics of a controlled crane's run (compare.h), from the columns of its results.csv
 * (crane/models/crane-control.yaml's outputs): t, theta, theta_ref, omega, omega_ref,
 * sway_distance, swing_angle, tip_defl_1, tip_defl_2, p_high, p_low, pump_x, pump_power.
 * "During the motion" is t <= t_ref_end, the last row where the reference rate omega_ref is not
 * zero (a shaped reference ends later than the paper's); "after the stop" the rows after it.
 * The energy is the trapezoidal rule over the rows of max(pump_power, 0). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "compare.h"

const char *const cc_metric_names[] = {
    "theta_err_max", "theta_err_rms",      "omega_err_max",  "omega_err_rms", "theta_end_err",
    "sway_max_m",    "sway_residual_m",    "swing_residual_deg", "sway_settle_s", "defl_luff_max",
    "defl_side_max", "p_high_max",         "p_low_max",      "p_max",         "energy_j",
    "x_max",         "t_ref_end"};
const char *const cc_metric_units[] = {"rad", "rad", "rad/s", "rad/s", "rad", "m",  "m",  "deg", "s",
                                       "m",   "m",   "Pa",    "Pa",    "Pa",  "J",  "1",  "s"};
const int cc_nmetrics = (int)(sizeof cc_metric_names / sizeof *cc_metric_names);

void cc_metric_values(const cc_metrics *m, double *v)
{
    const double w[] = {m->theta_err_max, m->theta_err_rms, m->omega_err_max, m->omega_err_rms,
                        m->theta_end_err, m->sway_max_m,    m->sway_residual_m,
                        m->swing_residual_deg, m->sway_settle_s, m->defl_luff_max,
                        m->defl_side_max, m->p_high_max,    m->p_low_max,    m->p_max,
                        m->energy_j,      m->x_max,         m->t_ref_end};
    memcpy(v, w, sizeof w);
}

void cc_table_free(cc_table *t)
{
    for (int i = 0; i < t->ncols; i++) free(t->names[i]);
    free(t->names);
    free(t->v);
    memset(t, 0, sizeof *t);
}

int cc_table_col(const cc_table *t, const char *name)
{
    for (int i = 0; i < t->ncols; i++)
        if (!strcmp(t->names[i], name)) return i;
    return -1;
}

/* one line of any length into *buf; 0 at the end of the file */
static int read_line(FILE *f, char **buf, size_t *cap)
{
    return getline(buf, cap, f) > 0;
}

int cc_table_read(const char *path, cc_table *t, char *msg, size_t size)
{
    memset(t, 0, sizeof *t);
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(msg, size, "%s: %s", path, strerror(errno));
        return -1;
    }
    char *line = NULL;
    size_t cap = 0;
    int st = -1;
    if (!read_line(f, &line, &cap)) {
        snprintf(msg, size, "%s: empty", path);
        goto done;
    }
    line[strcspn(line, "\r\n")] = '\0';
    for (char *p = line; p;) {
        char *comma = strchr(p, ',');
        if (comma) *comma = '\0';
        char **nn = realloc(t->names, sizeof *nn * (size_t)(t->ncols + 1));
        if (!nn) goto oom;
        t->names = nn;
        if (!(t->names[t->ncols] = strdup(p))) goto oom;
        t->ncols++;
        p = comma ? comma + 1 : NULL;
    }
    size_t rcap = 0;
    while (read_line(f, &line, &cap)) {
        if ((size_t)(t->nrows + 1) * (size_t)t->ncols > rcap) {
            rcap = rcap ? 2 * rcap : (size_t)t->ncols * 1024;
            double *nv = realloc(t->v, sizeof *nv * rcap);
            if (!nv) goto oom;
            t->v = nv;
        }
        double *row = t->v + (size_t)t->nrows * (size_t)t->ncols;
        char *p = line;
        for (int c = 0; c < t->ncols; c++) {
            char *end;
            row[c] = strtod(p, &end);
            if (end == p) row[c] = NAN; /* an empty or non-numeric field */
            p = strchr(end, ',');
            if (!p) {
                if (c + 1 < t->ncols) {
                    snprintf(msg, size, "%s: row %d has %d fields, expected %d", path,
                             t->nrows + 2, c + 1, t->ncols);
                    goto done;
                }
                break;
            }
            p++;
        }
        t->nrows++;
    }
    st = 0;
    goto done;
oom:
    snprintf(msg, size, "%s: out of memory", path);
done:
    free(line);
    fclose(f);
    if (st) cc_table_free(t);
    return st;
}

int cc_metrics_of(const cc_table *t, cc_metrics *m, char *msg, size_t size)
{
    static const char *const need[] = {"t",          "theta",      "theta_ref",  "omega",
                                       "omega_ref",  "sway_distance", "swing_angle", "tip_defl_1",
                                       "tip_defl_2", "p_high",     "p_low",      "pump_x",
                                       "pump_power"};
    enum { T, TH, THR, OM, OMR, SW, SA, D1, D2, PH, PL, X, PW, NC };
    int col[NC];
    for (int k = 0; k < NC; k++)
        if ((col[k] = cc_table_col(t, need[k])) < 0) {
            snprintf(msg, size, "results.csv has no column '%s' (the model's outputs must name it)",
                     need[k]);
            return -1;
        }
    if (t->nrows < 2) {
        snprintf(msg, size, "results.csv has %d rows, expected 2 or more", t->nrows);
        return -1;
    }
#define V(r, k) (t->v[(size_t)(r) * (size_t)t->ncols + (size_t)col[k]])
    int n = t->nrows, last = 0;
    for (int r = 0; r < n; r++)
        if (fabs(V(r, OMR)) > 1e-12) last = r;
    int stop = last + 1 < n ? last + 1 : n - 1; /* the first row at rest */
    memset(m, 0, sizeof *m);
    m->t_ref_end = V(stop, T);
    double ste = 0, swe = 0, tm = 0, settle_row = -1;
    for (int r = 0; r < n; r++) {
        double dt = r + 1 < n ? V(r + 1, T) - V(r, T) : 0;
        double the = fabs(V(r, TH) - V(r, THR)), ome = fabs(V(r, OM) - V(r, OMR));
        if (r <= stop) {
            m->theta_err_max = fmax(m->theta_err_max, the);
            m->omega_err_max = fmax(m->omega_err_max, ome);
            if (r < stop) {
                double the1 = V(r + 1, TH) - V(r + 1, THR), ome1 = V(r + 1, OM) - V(r + 1, OMR);
                ste += 0.5 * dt * (the * the + the1 * the1);
                swe += 0.5 * dt * (ome * ome + ome1 * ome1);
                tm += dt;
            }
        } else {
            m->sway_residual_m = fmax(m->sway_residual_m, V(r, SW));
            m->swing_residual_deg = fmax(m->swing_residual_deg, fabs(V(r, SA)));
        }
        if (r >= stop && V(r, SW) > CC_SETTLE_BAND) settle_row = r;
        m->sway_max_m = fmax(m->sway_max_m, V(r, SW));
        m->defl_luff_max = fmax(m->defl_luff_max, fabs(V(r, D1)));
        m->defl_side_max = fmax(m->defl_side_max, fabs(V(r, D2)));
        m->p_high_max = fmax(m->p_high_max, V(r, PH));
        m->p_low_max = fmax(m->p_low_max, V(r, PL));
        m->x_max = fmax(m->x_max, fabs(V(r, X)));
        if (r + 1 < n) m->energy_j += 0.5 * dt * (fmax(V(r, PW), 0) + fmax(V(r + 1, PW), 0));
    }
    m->theta_err_rms = tm > 0 ? sqrt(ste / tm) : 0;
    m->omega_err_rms = tm > 0 ? sqrt(swe / tm) : 0;
    m->theta_end_err = fabs(V(n - 1, TH) - V(n - 1, THR));
    m->p_max = fmax(m->p_high_max, m->p_low_max);
    /* within the band from the row after the last one outside it; never: infinite */
    m->sway_settle_s = settle_row < 0        ? 0
                       : settle_row >= n - 1 ? INFINITY
                                             : V((int)settle_row + 1, T) - m->t_ref_end;
#undef V
    return 0;
}
