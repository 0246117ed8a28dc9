/* Spring/damper, truss and rope between two points (equations in mech_axial.h). */
#include "mech_axial.h"

#include <stdlib.h>
#include <string.h>

#include "cmp_internal.h"
#include "mech_frame.h"
#include "mech_util.h"

typedef struct axial {
    int rope;
    double k, c, L0, eps;
    int f[2], e[2], s[2], d; /* ids: flows, efforts, orientation, state */
    mech_scales sc;          /* stated nominal scales */
} axial;

static void axial_free(void *p)
{
    free(p);
}

/* T and its partial derivatives with respect to L and L'. */
static double tension(const axial *a, double L, double Ld, double *TL, double *TLd)
{
    double x = L - a->L0;
    if (!a->rope) {
        *TL = a->k;
        *TLd = a->c;
        return a->k * x + a->c * Ld;
    }
    /* s = eps log(1 + e^(x/eps)) (softplus), h = s' = logistic(x/eps), evaluated without
     * overflow on either side */
    double z = x / a->eps, ez = exp(-fabs(z));
    double s = a->eps * log1p(ez) + (z > 0 ? x : 0.0);
    double h = z > 0 ? 1.0 / (1.0 + ez) : ez / (1.0 + ez);
    double hp = h * (1 - h) / a->eps;
    *TL = a->k * h + a->c * Ld * hp;
    *TLd = a->c * h;
    return a->k * s + a->c * Ld * h;
}

static void axial_partials(const bgr_element *el, const double *y, mech_emit *E)
{
    const axial *a = el->params;
    const double *d = y + a->d, *vA = y + a->f[0], *vB = y + a->f[1];
    double L = sqrt(mech_dot(d, d)), u[3], dv[3];
    if (!(L > 0)) L = 1e-300; /* declaration pass (d = 0): values unused */
    for (int i = 0; i < 3; i++) {
        u[i] = d[i] / L;
        dv[i] = vB[i] - vA[i];
    }
    double Ld = mech_dot(u, dv), TL, TLd, T = tension(a, L, Ld, &TL, &TLd);
    /* du_i/dd_j = (delta_ij - u_i u_j)/L; dLd/dd_j = (dv_j - Ld u_j)/L */
    double dLd[3];
    for (int j = 0; j < 3; j++)
        dLd[j] = (dv[j] - Ld * u[j]) / L;
    int row = 0;
    for (int i = 0; i < 3; i++, row++) { /* d' - (vB - vA) */
        mech_dep(E, row, a->d + i, 1, 1.0);
        mech_dep(E, row, a->f[1] + i, 0, -1.0);
        mech_dep(E, row, a->f[0] + i, 0, 1.0);
    }
    for (int k = 0; k < 2; k++) { /* s_A F_A + T u (k = 0);  s_B F_B - T u (k = 1) */
        double sg = k == 0 ? 1.0 : -1.0;
        for (int i = 0; i < 3; i++, row++) {
            mech_dep(E, row, a->e[k] + i, 0, a->s[k]);
            for (int j = 0; j < 3; j++) {
                double dT = TL * u[j] + TLd * dLd[j];
                double du = ((i == j) - u[i] * u[j]) / L;
                mech_dep(E, row, a->d + j, 0, sg * (dT * u[i] + T * du));
            }
            for (int j = 0; j < 3; j++) {
                mech_dep(E, row, a->f[1] + j, 0, sg * TLd * u[j] * u[i]);
                mech_dep(E, row, a->f[0] + j, 0, -sg * TLd * u[j] * u[i]);
            }
        }
    }
}

static int axial_declare(bgr_element *el, bgr_model *m)
{
    axial *a = el->params;
    for (int k = 0; k < 2; k++) {
        a->f[k] = bgr_fv(el, m, k, 0);
        a->e[k] = bgr_ev(el, m, k, 0);
        a->s[k] = el->sign[k];
    }
    a->d = bgr_sv(el, 0);
    static const char *const lab[9] = {"stretch0", "stretch1", "stretch2", "forceA0", "forceA1",
                                       "forceA2",  "forceB0",  "forceB1",  "forceB2"};
    int st = bgr_declare_equations(el, m, 9, lab);
    if (st != BG_OK) return st;
    double *zero = calloc((size_t)bgr_nvars(m) + 1, sizeof *zero);
    if (!zero)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "bgr_compile",
                              "out of memory");
    mech_emit E = {1, el, m, NULL, 0, BG_OK};
    axial_partials(el, zero, &E);
    free(zero);
    if (E.status != BG_OK) return E.status;
    /* Nominal magnitudes. d: the stated length, else L0 (|d| is the member's length, L0 to within
     * its strain). The tension, hence the port forces, is the stiffness times an elongation that
     * the parameters do not give (what the member carries): the stated force only (k times a
     * deformation scale, or the weight it holds). */
    int st2 = BG_OK;
    for (int i = 0; i < 3 && st2 == BG_OK; i++)
        st2 = mech_nominal(el, m, a->d + i, a->sc.length > 0 ? a->sc.length : a->L0);
    for (int k = 0; k < 2 && st2 == BG_OK; k++)
        st2 = mech_nominal_port(el, m, a->e[k], 3, a->sc.force, 0.0);
    /* under a frame's motion (mech_frame.h): d and the ports' vectors */
    if (st2 == BG_OK) st2 = mech_frame_group(el, m, BGR_FRAME_VECTOR, a->d);
    if (st2 == BG_OK) st2 = mech_frame_ports(el, m);
    return st2;
}

static int axial_residual(const bgr_element *el, double t, const double *y, const double *yp,
                          double *F)
{
    (void)t;
    const axial *a = el->params;
    const double *d = y + a->d, *vA = y + a->f[0], *vB = y + a->f[1];
    double L = sqrt(mech_dot(d, d)), u[3], dv[3];
    if (!(L > 0)) return 1; /* the two points met: recoverable, the step is cut */
    for (int i = 0; i < 3; i++) {
        u[i] = d[i] / L;
        dv[i] = vB[i] - vA[i];
    }
    double TL, TLd, T = tension(a, L, mech_dot(u, dv), &TL, &TLd);
    for (int i = 0; i < 3; i++)
        F[i] = yp[a->d + i] - dv[i];
    for (int i = 0; i < 3; i++) {
        F[3 + i] = a->s[0] * y[a->e[0] + i] + T * u[i];
        F[6 + i] = a->s[1] * y[a->e[1] + i] - T * u[i];
    }
    return 0;
}

static int axial_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                          double *v)
{
    (void)t, (void)yp;
    mech_emit E = {0, NULL, NULL, v, 0, BG_OK};
    axial_partials(el, y, &E);
    return 0;
}

/* A rope's regime: slack, in the smooth band around its unstretched length, taut (the slope h of
 * its softplus, as in tension); a bar has one. */
static int axial_regime(const bgr_element *el, const double *y)
{
    const axial *a = el->params;
    if (!a->rope) return cmp_regime(1.0);
    const double *d = y + a->d;
    double h;
    cmp_softplus(sqrt(mech_dot(d, d)) - a->L0, a->eps, &h);
    return cmp_regime(h);
}

static const bgr_element_class axial_class = {.type = "axial",
                                              .declare = axial_declare,
                                              .residual = axial_residual,
                                              .jacobian = axial_jacobian,
                                              .destroy = axial_free,
                                              .regime = axial_regime};

mech_scales *mech_axial_scales_(bgr_element *el)
{
    return el && el->cls == &axial_class ? &((axial *)el->params)->sc : NULL;
}

/* The parameters are checked by the constructors (where: their names). */
static int add_axial(bgr_model *m, bgr_comp c, const char *name, int rope, double k, double cd,
                     double L0, double eps)
{
    axial *a = calloc(1, sizeof *a);
    if (!a)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "mech_axial", "out of memory");
    a->rope = rope;
    a->k = k;
    a->c = cd;
    a->L0 = L0;
    a->eps = eps > 0 ? eps : 1e-4 * L0;
    static const char *const sn[3] = {"d0", "d1", "d2"};
    const int dims[2] = {3, 3};
    return bgr_element_add(m, c, name, &axial_class, a, 2, dims, 3, sn, 0, NULL);
}

int mech_spring(bgr_model *m, bgr_comp c, const char *name, double k, double c_damp, double L0)
{
    const char *w = "mech_spring";
    if (bgr_check_value(m, c, name, w, "k", k, BGR_NONNEGATIVE) ||
        bgr_check_value(m, c, name, w, "c_damp", c_damp, BGR_NONNEGATIVE) ||
        bgr_check_value(m, c, name, w, "L0", L0, BGR_POSITIVE))
        return BG_ERR_ARGUMENT;
    return add_axial(m, c, name, 0, k, c_damp, L0, 0);
}

int mech_truss(bgr_model *m, bgr_comp c, const char *name, double E, double A, double L0,
               double c_damp)
{
    const char *w = "mech_truss";
    if (bgr_check_value(m, c, name, w, "E", E, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "A", A, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "L0", L0, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "c_damp", c_damp, BGR_NONNEGATIVE))
        return BG_ERR_ARGUMENT;
    double k = E * A / L0;
    if (!(k > 0) || !isfinite(k))
        return bgr_refuse(m, c, name, w,
                          "E A / L0 = %g (E = %g, A = %g, L0 = %g), expected a finite stiffness "
                          "> 0",
                          k, E, A, L0);
    return add_axial(m, c, name, 0, k, c_damp, L0, 0);
}

int mech_rope(bgr_model *m, bgr_comp c, const char *name, double k, double c_damp, double L0,
              double eps)
{
    const char *w = "mech_rope";
    if (bgr_check_value(m, c, name, w, "k", k, BGR_NONNEGATIVE) ||
        bgr_check_value(m, c, name, w, "c_damp", c_damp, BGR_NONNEGATIVE) ||
        bgr_check_value(m, c, name, w, "L0", L0, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "eps", eps, BGR_FINITE))
        return BG_ERR_ARGUMENT;
    if (!(eps > 0) && !(1e-4 * L0 > 0))
        return bgr_refuse(m, c, name, w,
                          "eps = %g asks for the default width 1e-4 L0 = %g (L0 = %g), expected a "
                          "width > 0: give eps > 0",
                          eps, 1e-4 * L0, L0);
    return add_axial(m, c, name, 1, k, c_damp, L0, eps);
}

int mech_axial_set(bgr_model *m, int id, const double *xa, const double *xb)
{
    bgr_element *el = bgr_element_get(m, id);
    double *y0 = bgr_y0(m);
    if (!el || el->cls != &axial_class || !y0)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "mech_axial_set",
                              "element %d is not an axial element of a compiled model", id);
    if (!xa || !xb)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "mech_axial_set",
                              "element %d: both end points are needed", id);
    for (int i = 0; i < 3; i++)
        y0[el->state0 + i] = xb[i] - xa[i];
    return BG_OK;
}

double mech_axial_tension(const bgr_model *m, int id, const double *y)
{
    bgr_element *el = bgr_element_get((bgr_model *)m, id);
    if (!el || el->cls != &axial_class || !bgr_n(m) || !y) return NAN;
    const axial *a = el->params;
    const double *d = y + a->d, *vA = y + a->f[0], *vB = y + a->f[1];
    double L = sqrt(mech_dot(d, d)), dv[3] = {vB[0] - vA[0], vB[1] - vA[1], vB[2] - vA[2]};
    double TL, TLd;
    return tension(a, L, mech_dot(d, dv) / L, &TL, &TLd);
}

double mech_axial_dissipation(const bgr_model *m, int id, const double *y)
{
    bgr_element *el = bgr_element_get((bgr_model *)m, id);
    if (!el || el->cls != &axial_class || !bgr_n(m) || !y) return NAN;
    const axial *a = el->params;
    const double *d = y + a->d, *vA = y + a->f[0], *vB = y + a->f[1];
    double L = sqrt(mech_dot(d, d)), dv[3] = {vB[0] - vA[0], vB[1] - vA[1], vB[2] - vA[2]};
    double Ld = mech_dot(d, dv) / L, TL, TLd;
    tension(a, L, Ld, &TL, &TLd); /* TLd: the damping coefficient c (rope: c h) */
    return TLd * Ld * Ld;
}

/* -Li2(-u) for 0 <= u <= 1: the alternating series sum (-1)^(n+1) u^n / n^2. */
static double neg_li2_neg(double u)
{
    double sum = 0, un = 1;
    for (int n = 1; n < 200000; n++) {
        un *= u;
        double term = un / ((double)n * n);
        sum += n % 2 ? term : -term;
        if (term < 1e-17 * sum) break;
    }
    return sum;
}

double mech_axial_energy(const bgr_model *m, int id, const double *y)
{
    bgr_element *el = bgr_element_get((bgr_model *)m, id);
    if (!el || el->cls != &axial_class || !bgr_n(m) || !y) return NAN;
    const axial *a = el->params;
    const double *d = y + a->d;
    double x = sqrt(mech_dot(d, d)) - a->L0;
    if (!a->rope) return 0.5 * a->k * x * x;
    /* k times the integral of softplus from -inf: eps^2 (-Li2(-e^z)), z = x / eps, written with
     * -Li2(-e^z) = z^2/2 + pi^2/6 - (-Li2(-e^-z)) for z > 0 */
    const double pi = 3.14159265358979323846;
    double z = x / a->eps;
    double F = z > 0 ? 0.5 * z * z + pi * pi / 6 - neg_li2_neg(exp(-z)) : neg_li2_neg(exp(z));
    return a->k * a->eps * a->eps * F;
}
