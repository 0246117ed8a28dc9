/* What the beam elements' tests share (beam_testlib.h). */
#include "beam_testlib.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bgr_analysis.h"
#include "bgr_elements.h"
#include "mech_body.h"
#include "mech_parts.h"
#include "tap.h"

static const double PI = 3.14159265358979323846;

bgr_model *bt_cantilever(const mech_section *section, int element, int n, double L, const double *g,
                         double Px, double P, int *nodes, int *elems)
{
    const double p0[3] = {0, 0, 0}, p1[3] = {L, 0, 0}, up[3] = {0, 0, 1};
    int extra[65];
    for (int k = 0; k <= n; k++)
        extra[k] = k == 0 || k == n;
    mech_section sec = *section;
    sec.element = element;
    bgr_model *m = bgr_model_create("cant");
    mech_beam_chain(m, 0, "beam", n, p0, p1, up, &sec, g, extra, NULL, nodes, elems);
    int clamp = mech_support(m, 0, "clamp", 6);
    bgr_bond(m, 0, "b_clamp", 6, bgr_port_of(m, clamp, 0),
             mech_beam_chain_port(m, nodes, n, extra, 0, 0), NULL, NULL);
    double load[6] = {Px, 0, -P, 0, 0, 0};
    int src = bgr_Se(m, 0, "tip_load", 6, load);
    bgr_bond(m, 0, "b_load", 6, bgr_port_of(m, src, 0),
             mech_beam_chain_port(m, nodes, n, extra, n, 0), NULL, NULL);
    if (bgr_compile(m) != BG_OK) {
        printf("# cantilever: %s\n", bgr_model_error(m)->message); /* a TAP comment */
        bgr_model_free(&m);
        return NULL;
    }
    mech_beam_chain_set(m, nodes, n, p0, p1);
    return m;
}

/* by Newton from its asymptote (n + 1/2) pi */
double bt_clamped_free_root(int n)
{
    double b = n == 0 ? 1.9 : (n + 0.5) * PI;
    for (int it = 0; it < 50; it++)
        b -= (cos(b) * cosh(b) + 1) / (cos(b) * sinh(b) - sin(b) * cosh(b));
    return b;
}

/* 3-point Gauss-Legendre on 400 panels */
double bt_slope_ratio(double b)
{
    const double gx[3] = {-sqrt(0.6), 0, sqrt(0.6)}, gw[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
    double s = (cosh(b) + cos(b)) / (sinh(b) + sin(b)), num = 0, den = 0;
    for (int p = 0; p < 400; p++)
        for (int g = 0; g < 3; g++) {
            double x = b * (p + 0.5 + 0.5 * gx[g]) / 400;
            double ph = cosh(x) - cos(x) - s * (sinh(x) - sin(x));
            double dp = b * (sinh(x) + sin(x) - s * (cosh(x) - cos(x)));
            num += gw[g] * dp * dp;
            den += gw[g] * ph * ph;
        }
    return num / den;
}

double bt_total_energy(const bgr_model *m, const int *nodes, const int *elems, int n,
                       const double *y)
{
    double E = 0;
    for (int k = 0; k <= n; k++) {
        double T, V;
        mech_body_energy(m, nodes[k], y, &T, &V);
        E += T;
    }
    for (int k = 0; k < n; k++)
        E += mech_beam_energy(m, elems[k], y) + mech_beam_kinetic(m, elems[k], y);
    return E;
}

double bt_release_in_mode(bgr_model *m, const int *nodes, int n, double L, int which, double vtip,
                          const int *extra, int nextra, char *msg, size_t msize)
{
    dae_modes *M = NULL;
    bg_error e = {0};
    if (bgr_modes(m, 0.0, NULL, NULL, NULL, &M, &e) != BG_OK) {
        snprintf(msg, msize, "%s", e.message);
        return NAN;
    }
    int N = bgr_n(m), found = -1, seen = 0;
    double *re = malloc((size_t)N * sizeof *re), *im = malloc((size_t)N * sizeof *im);
    for (int k = 0; re && im && k < dae_modes_count(M) && found < 0; k++) {
        if (dae_modes_get(M, k)->kind != DAE_MODE_ELASTIC) continue;
        dae_modes_vector(M, k, re, im);
        double s[3] = {0, 0, 0}; /* the node velocities' squares by direction */
        for (int j = 1; j <= n; j++)
            for (int c = 0; c < 3; c++) {
                int v = mech_body_var(m, nodes[j], 'v') + c;
                s[c] += re[v] * re[v] + im[v] * im[v];
            }
        if (s[2] > s[0] && s[2] > s[1] && ++seen == which) found = k;
    }
    double w = NAN;
    if (found >= 0) {
        w = dae_modes_get(M, found)->freq_hz * 2 * PI;
        int vt = mech_body_var(m, nodes[n], 'v') + 2;
        double ph = atan2(im[vt], re[vt]), c0 = cos(ph), s0 = sin(ph);
        double scale = vtip / hypot(re[vt], im[vt]);
        for (int j = 1; j <= n; j++) {
            double x[3] = {L * j / n, 0, 0}, v[3], wv[3];
            int iv = mech_body_var(m, nodes[j], 'v'), iw = mech_body_var(m, nodes[j], 'w');
            for (int c = 0; c < 3; c++) {
                v[c] = scale * (re[iv + c] * c0 + im[iv + c] * s0);
                wv[c] = scale * (re[iw + c] * c0 + im[iw + c] * s0);
            }
            mech_body_set(m, nodes[j], x, v, wv, NULL);
        }
        double *y0 = bgr_y0(m);
        for (int k = 0; k < nextra; k++)
            y0[extra[k]] = scale * (re[extra[k]] * c0 + im[extra[k]] * s0);
    } else {
        snprintf(msg, msize, "%s", re && im ? "no such mode" : "out of memory");
    }
    free(re);
    free(im);
    dae_modes_free(&M);
    return w;
}

int bt_run(bgr_model *m, const int *nodes, const int *elems, int n, double rtol, double T, int nout,
           int iz, const int *bubbles, int nb, const char *what, bt_run_out *o)
{
    dae_problem p;
    bgr_dae_problem(m, &p);
    dae_options opt;
    dae_options_default(&opt);
    opt.rtol = rtol;
    opt.atol = 1e-3 * rtol;
    opt.exclude_alg = 1;
    bg_error e = {0};
    dae_solver *s = dae_create(&p, &opt, &e);
    int N = bgr_n(m), r = s ? dae_init(s, 0, bgr_y0(m), bgr_yp0(m)) : -1;
    if (r == 0) r = dae_consistent_init(s);
    double *y = malloc((size_t)N * sizeof *y), *yp = malloc((size_t)N * sizeof *yp), t = 0;
    if (!y || !yp)
        r = -1;
    else
        memcpy(y, bgr_y0(m), (size_t)N * sizeof *y);
    double E0 = y ? bt_total_energy(m, nodes, elems, n, y) : 0, tprev = 0;
    double z0 = y && iz >= 0 ? y[iz] : 0, first = NAN, last = NAN;
    *o = (bt_run_out){.period = NAN};
    for (int j = 1; j <= nout && r == 0; j++) {
        r = dae_solve_to(s, T * j / nout, &t, y, yp);
        o->drift = fmax(o->drift, fabs(bt_total_energy(m, nodes, elems, n, y) - E0) / E0);
        for (int k = 0; k < n; k++)
            o->Tel = fmax(o->Tel, fabs(mech_beam_kinetic(m, elems[k], y)));
        for (int k = 0; k < nb; k++)
            o->bmax = fmax(o->bmax, fabs(y[bubbles[k]]));
        if (iz >= 0 && z0 < 0 && y[iz] >= 0) { /* linear interpolation: no curvature there */
            double tc = tprev + (t - tprev) * (-z0) / (y[iz] - z0);
            if (o->crossings++ == 0) first = tc;
            last = tc;
        }
        if (iz >= 0) z0 = y[iz];
        tprev = t;
    }
    if (o->crossings > 1) o->period = (last - first) / (o->crossings - 1);
    if (r != 0) tap_diag("%s: %s", what, s ? dae_get_error(s)->message : e.message);
    const dae_stats *ds = s ? dae_get_stats(s) : NULL;
    if (ds)
        tap_diag("%s: %ld steps (largest %.1e s), %ld Newton iterations, %ld Jacobians", what,
                 ds->steps, ds->h_max_used, ds->newton_iters, ds->jac_evals);
    dae_free(&s);
    free(y);
    free(yp);
    return r;
}
