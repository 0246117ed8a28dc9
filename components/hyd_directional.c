/* 4/3 proportional directional valve (equations in hyd_directional.h). */
#include "hyd_directional.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cmp_internal.h"

enum { PORT_P, PORT_T, PORT_A, PORT_B };

typedef struct dvalve {
    hyd_directional_spec sp; /* with the defaults filled in */
    bgr_ref command;
    double K;             /* q_n / f(dp_n) */
    double sp1;           /* sp(1 + u0), the opening's normalisation */
    int e[4], f[4], s[4]; /* ports P, T, A, B: effort, flow, orientation */
    int u;                /* the command's variable */
} dvalve;

/* f(dp) = dp (dp^2 + dp_l^2)^(-1/4) and f'(dp) = (dp^2/2 + dp_l^2) (dp^2 + dp_l^2)^(-5/4),
 * written with r = hypot(dp, dp_l) so that nothing overflows. */
static double orifice(double dp, double dpl, double *df)
{
    double r = hypot(dp, dpl), sr = sqrt(r), a = dp / r, b = dpl / r;
    *df = (0.5 * a * a + b * b) / sr;
    return dp / sr;
}

/* The opening o(z) = sp(z + u0) / sp(1 + u0) and its slope; the softplus's own slope into *dsp
 * (the switch's regime). */
static double opening(const dvalve *v, double z, double *dz, double *dsp)
{
    double d, o = cmp_softplus(z + v->sp.underlap, v->sp.spool_smoothing, &d) / v->sp1;
    *dz = d / v->sp1;
    if (dsp) *dsp = d;
    return o;
}

/* One edge X->Y: Q = K a f(dp) + G_l dp; dQ/ddp into *qdp, dQ/da into *qa. */
static double edge(const dvalve *v, double dp, double a, double *qdp, double *qa)
{
    double df, f = orifice(dp, v->sp.dp_laminar, &df);
    *qdp = v->K * a * df + v->sp.leakage;
    *qa = v->K * f;
    return v->K * a * f + v->sp.leakage * dp;
}

/* The four edges at y: flows Q[PA, BT, PB, AT], their slopes in dp and in u. */
typedef struct edges {
    double Q[4], dp[4], du[4];
} edges;

static void edges_eval(const dvalve *v, const double *y, edges *E)
{
    double pP = y[v->e[PORT_P]], pT = y[v->e[PORT_T]], pA = y[v->e[PORT_A]], pB = y[v->e[PORT_B]],
           u = y[v->u];
    double d1, d2, o1 = opening(v, u, &d1, NULL), o2 = opening(v, -u, &d2, NULL), qa;
    const double dps[4] = {pP - pA, pB - pT, pP - pB, pA - pT};
    for (int k = 0; k < 4; k++) {
        int pos = k < 2; /* PA, BT open with u > 0 */
        E->Q[k] = edge(v, dps[k], pos ? o1 : o2, &E->dp[k], &qa);
        E->du[k] = pos ? qa * d1 : -qa * d2;
    }
}

enum { E_PA, E_BT, E_PB, E_AT };

static int dvalve_declare(bgr_element *el, bgr_model *m)
{
    static const char *const lab[4] = {"flow_P", "flow_A", "flow_B", "continuity"};
    dvalve *v = el->params;
    for (int k = 0; k < 4; k++) {
        v->e[k] = bgr_ev(el, m, k, 0);
        v->f[k] = bgr_fv(el, m, k, 0);
        v->s[k] = el->sign[k];
    }
    v->u = bgr_ref_var(m, v->command);
    if (v->u < 0)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "bgr_compile",
                              "directional valve %s: its command refers to no unknown", el->name);
    int st = bgr_declare_equations(el, m, 4, lab);
    if (st) return st;
    const int P = PORT_P, T = PORT_T, A = PORT_A, B = PORT_B;
    /* q_P - Q_PA - Q_PB */
    CMP_DEP(el, m, 0, v->f[P], 0);
    CMP_DEP(el, m, 0, v->e[P], 0);
    CMP_DEP(el, m, 0, v->e[A], 0);
    CMP_DEP(el, m, 0, v->e[B], 0);
    CMP_DEP(el, m, 0, v->u, 0);
    /* q_A - Q_AT + Q_PA */
    CMP_DEP(el, m, 1, v->f[A], 0);
    CMP_DEP(el, m, 1, v->e[A], 0);
    CMP_DEP(el, m, 1, v->e[T], 0);
    CMP_DEP(el, m, 1, v->e[P], 0);
    CMP_DEP(el, m, 1, v->u, 0);
    /* q_B - Q_BT + Q_PB */
    CMP_DEP(el, m, 2, v->f[B], 0);
    CMP_DEP(el, m, 2, v->e[B], 0);
    CMP_DEP(el, m, 2, v->e[T], 0);
    CMP_DEP(el, m, 2, v->e[P], 0);
    CMP_DEP(el, m, 2, v->u, 0);
    for (int k = 0; k < 4; k++) /* sum of the inflows */
        CMP_DEP(el, m, 3, v->f[k], 0);
    /* two edges in series at the rated drop each: the supply pressure of the rated flow */
    for (int k = 0; k < 4; k++) {
        CMP_NOM(el, m, v->e[k], 2 * v->sp.dp_rated);
        CMP_NOM(el, m, v->f[k], v->sp.flow_rated);
    }
    return BG_OK;
}

static int dvalve_residual(const bgr_element *el, double t, const double *y, const double *yp,
                           double *F)
{
    (void)t, (void)yp;
    const dvalve *v = el->params;
    edges E;
    edges_eval(v, y, &E);
    double q[4];
    for (int k = 0; k < 4; k++)
        q[k] = v->s[k] * y[v->f[k]];
    F[0] = q[PORT_P] - E.Q[E_PA] - E.Q[E_PB];
    F[1] = q[PORT_A] - E.Q[E_AT] + E.Q[E_PA];
    F[2] = q[PORT_B] - E.Q[E_BT] + E.Q[E_PB];
    F[3] = q[0] + q[1] + q[2] + q[3];
    return 0;
}

static int dvalve_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                           double *w)
{
    (void)t, (void)yp;
    const dvalve *v = el->params;
    edges E;
    edges_eval(v, y, &E);
    const double *g = E.dp, *h = E.du;
    int n = 0;
    w[n++] = v->s[PORT_P]; /* flow_P: f_P, p_P, p_A, p_B, u */
    w[n++] = -g[E_PA] - g[E_PB];
    w[n++] = g[E_PA];
    w[n++] = g[E_PB];
    w[n++] = -h[E_PA] - h[E_PB];
    w[n++] = v->s[PORT_A]; /* flow_A: f_A, p_A, p_T, p_P, u */
    w[n++] = -g[E_AT] - g[E_PA];
    w[n++] = g[E_AT];
    w[n++] = g[E_PA];
    w[n++] = -h[E_AT] + h[E_PA];
    w[n++] = v->s[PORT_B]; /* flow_B: f_B, p_B, p_T, p_P, u */
    w[n++] = -g[E_BT] - g[E_PB];
    w[n++] = g[E_BT];
    w[n++] = g[E_PB];
    w[n++] = -h[E_BT] + h[E_PB];
    for (int k = 0; k < 4; k++) /* continuity */
        w[n++] = v->s[k];
    return 0;
}

/* The spool's two switches: 4 regime(P->A, B->T) + regime(P->B, A->T). */
static int dvalve_regime(const bgr_element *el, const double *y)
{
    const dvalve *v = el->params;
    double u = y[v->u], dz, d1, d2;
    opening(v, u, &dz, &d1);
    opening(v, -u, &dz, &d2);
    return 4 * cmp_regime(d1) + cmp_regime(d2);
}

static const char *vn(const bgr_model *m, int var)
{
    const char *s = bgr_var_name(m, var);
    return s ? s : "?";
}

static void dvalve_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    const dvalve *v = el->params;
    const char *u = vn(m, v->u);
    if (k == 0)
        snprintf(buf, n, "q_P = Q_PA + Q_PB,  Q_XY = %g o(+-%s) f(p_X - p_Y) + %g (p_X - p_Y)",
                 v->K, u, v->sp.leakage);
    else if (k == 1)
        snprintf(buf, n, "q_A = Q_AT - Q_PA,  o(z) = sp_%g(z + %g) / %g", v->sp.spool_smoothing,
                 v->sp.underlap, v->sp1);
    else if (k == 2)
        snprintf(buf, n, "q_B = Q_BT - Q_PB,  f(dp) = dp (dp^2 + %g^2)^(-1/4)", v->sp.dp_laminar);
    else
        snprintf(buf, n, "q_P + q_T + q_A + q_B = 0");
}

const bgr_element_class hyd_class_directional = {.type = "directional_valve",
                                                 .declare = dvalve_declare,
                                                 .residual = dvalve_residual,
                                                 .jacobian = dvalve_jacobian,
                                                 .describe = dvalve_describe,
                                                 .destroy = free,
                                                 .regime = dvalve_regime};

int hyd_directional_valve(bgr_model *m, bgr_comp c, const char *name, bgr_ref command,
                          const hyd_directional_spec *spec)
{
    const char *w = "hyd_directional_valve";
    if (!spec) return bgr_refuse(m, c, name, w, "spec = NULL, expected the parameters");
    hyd_directional_spec s = *spec;
    if (bgr_check_value(m, c, name, w, "flow_rated", s.flow_rated, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "dp_rated", s.dp_rated, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "underlap", s.underlap, BGR_NONNEGATIVE) ||
        bgr_check_value(m, c, name, w, "leakage", s.leakage, BGR_NONNEGATIVE) ||
        bgr_check_value(m, c, name, w, "dp_laminar", s.dp_laminar, BGR_NONNEGATIVE) ||
        bgr_check_value(m, c, name, w, "spool_smoothing", s.spool_smoothing, BGR_NONNEGATIVE))
        return BG_ERR_ARGUMENT;
    if (!(s.underlap <= 0.5))
        return bgr_refuse(m, c, name, w, "underlap = %g, expected 0 .. 0.5 (of the rated travel)",
                          s.underlap);
    if (s.dp_laminar == 0) s.dp_laminar = 0.01 * s.dp_rated;
    if (!(s.dp_laminar > 0) || !(s.dp_laminar <= s.dp_rated))
        return bgr_refuse(m, c, name, w, "dp_laminar = %g, expected > 0 and <= dp_rated = %g",
                          s.dp_laminar, s.dp_rated);
    if (s.spool_smoothing == 0) s.spool_smoothing = 1e-3;
    if (!(s.spool_smoothing <= 0.1))
        return bgr_refuse(m, c, name, w,
                          "spool_smoothing = %g, expected > 0 and <= 0.1 (of the rated travel; 0: "
                          "the default 1e-3)",
                          s.spool_smoothing);
    double df, K = s.flow_rated / orifice(s.dp_rated, s.dp_laminar, &df);
    if (!(K > 0) || !isfinite(K))
        return bgr_refuse(m, c, name, w,
                          "flow_rated / f(dp_rated) = %g (flow_rated = %g, dp_rated = %g), "
                          "expected a finite number > 0",
                          K, s.flow_rated, s.dp_rated);
    dvalve *v = calloc(1, sizeof *v);
    if (!v) return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, w, "out of memory");
    v->sp = s;
    v->command = command;
    v->K = K;
    v->sp1 = cmp_softplus(1 + s.underlap, s.spool_smoothing, &df);
    static const int dims[4] = {1, 1, 1, 1};
    return bgr_element_add(m, c, name, &hyd_class_directional, v, 4, dims, 0, NULL, 0, NULL);
}
