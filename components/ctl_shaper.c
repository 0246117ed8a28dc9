/* Input shapers (equations in ctl_shaper.h). */
#include "ctl_shaper.h"

#include <math.h>
#include <stdlib.h>

#include "bgr_check.h"
#include "cmp_internal.h"

int ctl_shaper_impulses(ctl_shaper_kind kind, double freq_hz, double zeta, double *A, double *t)
{
    if ((kind != CTL_SHAPER_ZV && kind != CTL_SHAPER_ZVD) || !A || !t || !(freq_hz > 0) ||
        !isfinite(freq_hz) || !(zeta >= 0 && zeta < 1))
        return BG_ERR_ARGUMENT;
    double s = sqrt(1 - zeta * zeta), K = exp(-zeta * (CMP_TWO_PI / 2) / s);
    double Td = 1.0 / (freq_hz * s); /* 2 pi / w_d */
    if (kind == CTL_SHAPER_ZV) {
        A[0] = 1 / (1 + K);
        A[1] = K / (1 + K);
        t[0] = 0;
        t[1] = Td / 2;
        return 2;
    }
    double d = (1 + K) * (1 + K);
    A[0] = 1 / d;
    A[1] = 2 * K / d;
    A[2] = K * K / d;
    t[0] = 0;
    t[1] = Td / 2;
    t[2] = Td;
    return 3;
}

double ctl_shaper_vibration(int n, const double *A, const double *t, double omega, double zeta)
{
    if (n < 1 || !A || !t || !(omega > 0) || !(zeta >= 0 && zeta < 1)) return NAN;
    double wd = omega * sqrt(1 - zeta * zeta), c = 0, s = 0;
    for (int i = 0; i < n; i++) {
        double e = A[i] * exp(zeta * omega * t[i]);
        c += e * cos(wd * t[i]);
        s += e * sin(wd * t[i]);
    }
    return exp(-zeta * omega * t[n - 1]) * hypot(c, s);
}

/* r(tau) of the piecewise linear r: v_0 before t_0, v_(n-1) after t_(n-1) */
static double pwl_at(int n, const double *t, const double *v, double tau)
{
    if (tau <= t[0]) return v[0];
    if (tau >= t[n - 1]) return v[n - 1];
    int k = 0;
    while (k + 1 < n - 1 && tau >= t[k + 1]) k++;
    return v[k] + (v[k + 1] - v[k]) * (tau - t[k]) / (t[k + 1] - t[k]);
}

static int cmp_dbl(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

int ctl_shaped_pwl(bgr_model *m, bgr_comp c, const char *name, int n, const double *t,
                   const double *v, ctl_shaper_kind kind, double freq_hz, double zeta,
                   sig_output out)
{
    const char *w = "ctl_shaped_pwl";
    double A[CTL_SHAPER_MAX], ti[CTL_SHAPER_MAX];
    if (n < 1 || !t || !v) return bgr_refuse(m, c, name, w, "expected n >= 1 knots, got %d", n);
    if (bgr_check_value(m, c, name, w, "frequency", freq_hz, BGR_POSITIVE)) return BG_ERR_ARGUMENT;
    if (!(zeta >= 0 && zeta < 1))
        return bgr_refuse(m, c, name, w, "damping = %g, expected 0 <= damping < 1", zeta);
    int ni = ctl_shaper_impulses(kind, freq_hz, zeta, A, ti);
    if (ni < 0) return bgr_refuse(m, c, name, w, "kind = %d, expected ZV (0) or ZVD (1)", kind);
    for (int k = 0; k < n; k++)
        if (!isfinite(t[k]) || !isfinite(v[k]) || (k > 0 && !(t[k] > t[k - 1])))
            return bgr_refuse(m, c, name, w,
                              "knot %d (%g, %g): expected finite values, times strictly "
                              "increasing",
                              k, t[k], v[k]);
    double *tk = malloc(sizeof *tk * (size_t)(2 * n * ni));
    if (!tk) return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, w, "out of memory");
    double *vk = tk + n * ni;
    int nk = 0;
    for (int i = 0; i < ni; i++)
        for (int k = 0; k < n; k++) tk[nk++] = t[k] + ti[i];
    qsort(tk, (size_t)nk, sizeof *tk, cmp_dbl);
    /* merge knots closer than a relative 1e-12 of the span: a sig_pwl needs them increasing */
    double span = fmax(tk[nk - 1] - tk[0], 1.0);
    int u = 0;
    for (int k = 0; k < nk; k++)
        if (u == 0 || tk[k] - tk[u - 1] > 1e-12 * span) tk[u++] = tk[k];
    for (int k = 0; k < u; k++) {
        double s = 0;
        for (int i = 0; i < ni; i++) s += A[i] * pwl_at(n, t, v, tk[k] - ti[i]);
        vk[k] = s;
    }
    int id = sig_pwl(m, c, name, u, tk, vk, out);
    free(tk);
    return id;
}
