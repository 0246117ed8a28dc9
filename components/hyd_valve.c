/* Laminar leakage and relief valve (equations in hyd_valve.h). */
#include "hyd_valve.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cmp_internal.h"

typedef struct valve {
    int relief;
    double G, pc, eps;
    double pf, qr; /* relief valve: full-flow pressure and rated flow (the nominal scales) */
    int pa, qa, pb, qb, sa, sb;
} valve;

static double valve_flow(const valve *q, double dp, double *dq)
{
    if (!q->relief) {
        *dq = q->G;
        return q->G * dp;
    }
    double d, s = cmp_softplus(dp - q->pc, q->eps, &d);
    *dq = q->G * d;
    return q->G * s;
}

static int valve_declare(bgr_element *el, bgr_model *m)
{
    static const char *const lab[2] = {"flow", "continuity"};
    valve *q = el->params;
    q->pa = bgr_ev(el, m, 0, 0);
    q->qa = bgr_fv(el, m, 0, 0);
    q->pb = bgr_ev(el, m, 1, 0);
    q->qb = bgr_fv(el, m, 1, 0);
    q->sa = el->sign[0];
    q->sb = el->sign[1];
    int st = bgr_declare_equations(el, m, 2, lab);
    if (st) return st;
    CMP_DEP(el, m, 0, q->qa, 0);
    CMP_DEP(el, m, 0, q->pa, 0);
    CMP_DEP(el, m, 0, q->pb, 0);
    CMP_DEP(el, m, 1, q->qb, 0);
    CMP_DEP(el, m, 1, q->qa, 0);
    if (q->relief) {
        /* The full-flow pressure is the highest pressure the valve lets the circuit reach at its
         * rated flow (it caps the pressure difference in [p_c - a few eps, p_f]): the scale of
         * the pressures at its ports, and the rated flow the scale of the flow through it. A
         * leakage has a conductance only, no pressure or flow of its own: nothing declared. */
        double p = fmax(fabs(q->pc), fabs(q->pf));
        CMP_NOM(el, m, q->pa, p);
        CMP_NOM(el, m, q->pb, p);
        CMP_NOM(el, m, q->qa, q->qr);
        CMP_NOM(el, m, q->qb, q->qr);
    }
    return BG_OK;
}

static int valve_residual(const bgr_element *el, double t, const double *y, const double *yp,
                          double *F)
{
    (void)t, (void)yp;
    const valve *q = el->params;
    double dq, qin = q->sa * y[q->qa], qout = -q->sb * y[q->qb];
    F[0] = qin - valve_flow(q, y[q->pa] - y[q->pb], &dq);
    F[1] = qout - qin;
    return 0;
}

static int valve_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                          double *v)
{
    (void)t, (void)yp;
    const valve *q = el->params;
    double dq;
    valve_flow(q, y[q->pa] - y[q->pb], &dq);
    v[0] = q->sa;
    v[1] = -dq;
    v[2] = dq;
    v[3] = -q->sb;
    v[4] = -q->sa;
    return 0;
}

/* The relief valve's regime: closed, opening (the smooth band around cracking), open. */
static int relief_regime(const bgr_element *el, const double *y)
{
    const valve *q = el->params;
    double d;
    cmp_softplus(y[q->pa] - y[q->pb] - q->pc, q->eps, &d);
    return cmp_regime(d);
}

static const char *vn(const bgr_model *m, int v)
{
    const char *s = bgr_var_name(m, v);
    return s ? s : "?";
}

static void valve_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    const valve *q = el->params;
    const char *sa = q->sa > 0 ? "" : "-", *sb = q->sb > 0 ? "-" : "";
    if (k == 1)
        snprintf(buf, n, "%s%s = %s%s", sb, vn(m, q->qb), sa, vn(m, q->qa));
    else if (q->relief)
        snprintf(buf, n, "%s%s = %g * softplus_%g(%s - %s - %g)", sa, vn(m, q->qa), q->G, q->eps,
                 vn(m, q->pa), vn(m, q->pb), q->pc);
    else
        snprintf(buf, n, "%s%s = %g * (%s - %s)", sa, vn(m, q->qa), q->G, vn(m, q->pa),
                 vn(m, q->pb));
}

const bgr_element_class hyd_class_leakage = {.type = "leakage",
                                             .declare = valve_declare,
                                             .residual = valve_residual,
                                             .jacobian = valve_jacobian,
                                             .describe = valve_describe,
                                             .destroy = free};
const bgr_element_class hyd_class_relief = {.type = "relief",
                                            .declare = valve_declare,
                                            .residual = valve_residual,
                                            .jacobian = valve_jacobian,
                                            .describe = valve_describe,
                                            .destroy = free,
                                            .regime = relief_regime};

static int add_valve(bgr_model *m, bgr_comp c, const char *name, const bgr_element_class *cls,
                     int relief, double G, double pc, double eps, const char *where)
{
    valve *q = calloc(1, sizeof *q);
    if (!q) return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, where, "out of memory");
    q->relief = relief;
    q->G = G;
    q->pc = pc;
    q->eps = eps;
    static const int dims[2] = {1, 1};
    return bgr_element_add(m, c, name, cls, q, 2, dims, 0, NULL, 0, NULL);
}

int hyd_leakage(bgr_model *m, bgr_comp c, const char *name, double G)
{
    if (bgr_check_value(m, c, name, "hyd_leakage", "G", G, BGR_NONNEGATIVE)) return BG_ERR_ARGUMENT;
    return add_valve(m, c, name, &hyd_class_leakage, 0, G, 0.0, 1.0, "hyd_leakage");
}

int hyd_relief_valve(bgr_model *m, bgr_comp c, const char *name, double p_crack, double p_full,
                     double q_rated, double eps)
{
    const char *w = "hyd_relief_valve";
    if (bgr_check_value(m, c, name, w, "p_crack", p_crack, BGR_FINITE) ||
        bgr_check_value(m, c, name, w, "p_full", p_full, BGR_FINITE) ||
        bgr_check_value(m, c, name, w, "q_rated", q_rated, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "eps", eps, BGR_POSITIVE))
        return BG_ERR_ARGUMENT;
    if (!(p_full > p_crack))
        return bgr_refuse(m, c, name, w, "p_full = %g, expected > p_crack = %g", p_full, p_crack);
    /* the conductance of the open valve: the rated flow over the pressure band */
    double G = q_rated / (p_full - p_crack);
    if (!(G > 0) || !isfinite(G))
        return bgr_refuse(m, c, name, w,
                          "q_rated / (p_full - p_crack) = %g (q_rated = %g, p_full = %g, "
                          "p_crack = %g), expected a finite number > 0",
                          G, q_rated, p_full, p_crack);
    int id = add_valve(m, c, name, &hyd_class_relief, 1, G, p_crack, eps, w);
    bgr_element *el = id >= 0 ? bgr_element_get(m, id) : NULL;
    if (el) {
        valve *q = el->params;
        q->pf = p_full;
        q->qr = q_rated;
    }
    return id;
}
