/* Double-acting hydraulic cylinder (equations in hyd_cylinder.h). */
#include "hyd_cylinder.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cmp_internal.h"
#include "mech_util.h"

typedef struct cylinder {
    hyd_cylinder_spec sp;
    double p_nom, v_nom;        /* stated nominal pressure and speed (0: none) */
    int f[2], e[2], s[2], d;    /* mechanical ports A, B: first flow / effort id, orientation; d */
    int pa, pb;                 /* chamber pressures (states) */
    int ea, qa, sa, eb, qb, sb; /* hydraulic ports a, b */
} cylinder;

/* The kinematics and the chamber laws at y: length, direction, extension and its rate, the
 * volumes, the leakage, the net inflows R_a, R_b of the two chambers and the tension. */
typedef struct cyl_point {
    double L, u[3], dv[3], x, xd, Va, Vb, ql, Ra, Rb, T;
} cyl_point;

static void cyl_eval(const cylinder *c, const double *y, cyl_point *k)
{
    const hyd_cylinder_spec *s = &c->sp;
    const double *d = y + c->d, *vA = y + c->f[0], *vB = y + c->f[1];
    k->L = sqrt(mech_dot(d, d));
    double L = k->L > 0 ? k->L : 1e-300; /* declaration pass (d = 0): values unused */
    for (int i = 0; i < 3; i++) {
        k->u[i] = d[i] / L;
        k->dv[i] = vB[i] - vA[i];
    }
    k->x = k->L - s->length_min;
    k->xd = mech_dot(k->u, k->dv);
    k->Va = s->volume_a0 + s->area_a * k->x;
    k->Vb = s->volume_b0 + s->area_b * (s->stroke - k->x);
    double pa = y[c->pa], pb = y[c->pb];
    k->ql = s->leakage * (pa - pb);
    k->Ra = c->sa * y[c->qa] - s->area_a * k->xd - k->ql;
    k->Rb = c->sb * y[c->qb] + s->area_b * k->xd + k->ql;
    k->T = -(pa * s->area_a - pb * s->area_b) + s->friction * k->xd;
}

/* Every partial derivative, in one order for the declaration and the values (mech_emit). Rows:
 * 0-2 stretch, 3 pressure_a, 4 pressure_b, 5-7 forceA, 8-10 forceB, 11 port_a, 12 port_b. */
static void cyl_partials(const bgr_element *el, const double *y, mech_emit *E)
{
    const cylinder *c = el->params;
    const hyd_cylinder_spec *s = &c->sp;
    cyl_point k;
    cyl_eval(c, y, &k);
    double L = k.L > 0 ? k.L : 1e-300, Va = k.Va != 0 ? k.Va : 1e-300,
           Vb = k.Vb != 0 ? k.Vb : 1e-300;
    const double *u = k.u;
    double dxd[3]; /* dx'/dd_j = (dv_j - x' u_j) / L; dx/dd_j = u_j */
    for (int j = 0; j < 3; j++)
        dxd[j] = (k.dv[j] - k.xd * u[j]) / L;
    double ga = s->beta / Va, gb = s->beta / Vb, G = s->leakage;
    for (int i = 0; i < 3; i++) { /* d' - (v_B - v_A) */
        mech_dep(E, i, c->d + i, 1, 1.0);
        mech_dep(E, i, c->f[1] + i, 0, -1.0);
        mech_dep(E, i, c->f[0] + i, 0, 1.0);
    }
    /* p_a' - (beta / V_a) R_a, V_a = V_a0 + A_a x, R_a = q_a - A_a x' - G (p_a - p_b) */
    mech_dep(E, 3, c->pa, 1, 1.0);
    mech_dep(E, 3, c->qa, 0, -ga * c->sa);
    mech_dep(E, 3, c->pa, 0, ga * G);
    mech_dep(E, 3, c->pb, 0, -ga * G);
    for (int j = 0; j < 3; j++)
        mech_dep(E, 3, c->d + j, 0, ga / Va * k.Ra * s->area_a * u[j] + ga * s->area_a * dxd[j]);
    for (int j = 0; j < 3; j++) {
        mech_dep(E, 3, c->f[1] + j, 0, ga * s->area_a * u[j]);
        mech_dep(E, 3, c->f[0] + j, 0, -ga * s->area_a * u[j]);
    }
    /* p_b' - (beta / V_b) R_b, V_b = V_b0 + A_b (stroke - x), R_b = q_b + A_b x' + G (p_a - p_b) */
    mech_dep(E, 4, c->pb, 1, 1.0);
    mech_dep(E, 4, c->qb, 0, -gb * c->sb);
    mech_dep(E, 4, c->pa, 0, -gb * G);
    mech_dep(E, 4, c->pb, 0, gb * G);
    for (int j = 0; j < 3; j++)
        mech_dep(E, 4, c->d + j, 0, -gb / Vb * k.Rb * s->area_b * u[j] - gb * s->area_b * dxd[j]);
    for (int j = 0; j < 3; j++) {
        mech_dep(E, 4, c->f[1] + j, 0, -gb * s->area_b * u[j]);
        mech_dep(E, 4, c->f[0] + j, 0, gb * s->area_b * u[j]);
    }
    /* s_A F_A + T u (sg = 1), s_B F_B - T u (sg = -1); T = -(p_a A_a - p_b A_b) + c x' */
    for (int p = 0; p < 2; p++) {
        double sg = p == 0 ? 1.0 : -1.0;
        for (int i = 0; i < 3; i++) {
            int row = 5 + 3 * p + i;
            mech_dep(E, row, c->e[p] + i, 0, c->s[p]);
            for (int j = 0; j < 3; j++) {
                double du = ((i == j) - u[i] * u[j]) / L;
                mech_dep(E, row, c->d + j, 0, sg * (s->friction * dxd[j] * u[i] + k.T * du));
            }
            for (int j = 0; j < 3; j++) {
                mech_dep(E, row, c->f[1] + j, 0, sg * s->friction * u[j] * u[i]);
                mech_dep(E, row, c->f[0] + j, 0, -sg * s->friction * u[j] * u[i]);
            }
            mech_dep(E, row, c->pa, 0, -sg * s->area_a * u[i]);
            mech_dep(E, row, c->pb, 0, sg * s->area_b * u[i]);
        }
    }
    mech_dep(E, 11, c->ea, 0, 1.0); /* e_a - p_a */
    mech_dep(E, 11, c->pa, 0, -1.0);
    mech_dep(E, 12, c->eb, 0, 1.0); /* e_b - p_b */
    mech_dep(E, 12, c->pb, 0, -1.0);
}

static int cyl_declare(bgr_element *el, bgr_model *m)
{
    static const char *const lab[13] = {
        "stretch0", "stretch1", "stretch2", "pressure_a", "pressure_b", "forceA0", "forceA1",
        "forceA2",  "forceB0",  "forceB1",  "forceB2",    "port_a",     "port_b"};
    cylinder *c = el->params;
    for (int k = 0; k < 2; k++) {
        c->f[k] = bgr_fv(el, m, k, 0);
        c->e[k] = bgr_ev(el, m, k, 0);
        c->s[k] = el->sign[k];
    }
    c->ea = bgr_ev(el, m, 2, 0);
    c->qa = bgr_fv(el, m, 2, 0);
    c->sa = el->sign[2];
    c->eb = bgr_ev(el, m, 3, 0);
    c->qb = bgr_fv(el, m, 3, 0);
    c->sb = el->sign[3];
    c->d = bgr_sv(el, 0);
    c->pa = bgr_sv(el, 3);
    c->pb = bgr_sv(el, 4);
    int st = bgr_declare_equations(el, m, 13, lab);
    if (st != BG_OK) return st;
    double *zero = calloc((size_t)bgr_nvars(m) + 1, sizeof *zero);
    if (!zero)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "bgr_compile",
                              "out of memory");
    mech_emit E = {1, el, m, NULL, 0, BG_OK};
    cyl_partials(el, zero, &E);
    free(zero);
    if (E.status != BG_OK) return E.status;
    /* The length of the member for d (its largest, L_min + stroke); the stated pressure for the
     * chambers and the hydraulic ports, the force it gives on the piston for the mechanical
     * ports; the flows the stated speed displaces. */
    const hyd_cylinder_spec *s = &c->sp;
    for (int i = 0; i < 3; i++)
        CMP_NOM(el, m, c->d + i, s->length_min + s->stroke);
    CMP_NOM(el, m, c->pa, c->p_nom);
    CMP_NOM(el, m, c->pb, c->p_nom);
    CMP_NOM(el, m, c->ea, c->p_nom);
    CMP_NOM(el, m, c->eb, c->p_nom);
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < 3; i++)
            CMP_NOM(el, m, c->e[k] + i, c->p_nom * s->area_a);
    CMP_NOM(el, m, c->qa, c->v_nom * s->area_a);
    CMP_NOM(el, m, c->qb, c->v_nom * s->area_b);
    return BG_OK;
}

static int cyl_residual(const bgr_element *el, double t, const double *y, const double *yp,
                        double *F)
{
    (void)t;
    const cylinder *c = el->params;
    cyl_point k;
    cyl_eval(c, y, &k);
    if (!(k.L > 0) || !(k.x >= 0) || !(k.x <= c->sp.stroke)) {
        /* the piston beyond an end of its stroke (no end stops): recoverable, the step is cut;
         * the NaN rows name the cylinder's equation in the integrator's message */
        F[3] = F[4] = NAN;
        return 1;
    }
    for (int i = 0; i < 3; i++)
        F[i] = yp[c->d + i] - k.dv[i];
    F[3] = yp[c->pa] - c->sp.beta / k.Va * k.Ra;
    F[4] = yp[c->pb] - c->sp.beta / k.Vb * k.Rb;
    for (int i = 0; i < 3; i++) {
        F[5 + i] = c->s[0] * y[c->e[0] + i] + k.T * k.u[i];
        F[8 + i] = c->s[1] * y[c->e[1] + i] - k.T * k.u[i];
    }
    F[11] = y[c->ea] - y[c->pa];
    F[12] = y[c->eb] - y[c->pb];
    return 0;
}

static int cyl_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                        double *v)
{
    (void)t, (void)yp;
    mech_emit E = {0, NULL, NULL, v, 0, BG_OK};
    cyl_partials(el, y, &E);
    return 0;
}

static void cyl_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    const cylinder *c = el->params;
    const hyd_cylinder_spec *s = &c->sp;
    const char *pa = bgr_var_name(m, c->pa), *pb = bgr_var_name(m, c->pb);
    pa = pa ? pa : "p_a";
    pb = pb ? pb : "p_b";
    if (k < 3)
        snprintf(buf, n, "d%d' = v_B%d - v_A%d", k, k, k);
    else if (k == 3)
        snprintf(buf, n, "%s' = %g / (%g + %g x) * (q_a - %g x' - %g (%s - %s)),  x = |d| - %g", pa,
                 s->beta, s->volume_a0, s->area_a, s->area_a, s->leakage, pa, pb, s->length_min);
    else if (k == 4)
        snprintf(buf, n,
                 "%s' = %g / (%g + %g (%g - x)) * (q_b + %g x' + %g (%s - %s)),  x = |d| - %g", pb,
                 s->beta, s->volume_b0, s->area_b, s->stroke, s->area_b, s->leakage, pa, pb,
                 s->length_min);
    else if (k < 11)
        snprintf(buf, n, "s_%c F_%c%d = %sT u%d,  T = -(%g %s - %g %s) + %g x'", k < 8 ? 'A' : 'B',
                 k < 8 ? 'A' : 'B', (k - 5) % 3, k < 8 ? "-" : "", (k - 5) % 3, s->area_a, pa,
                 s->area_b, pb, s->friction);
    else
        snprintf(buf, n, "%s = %s", k == 11 ? "e_a" : "e_b", k == 11 ? pa : pb);
}

const bgr_element_class hyd_class_cylinder = {.type = "cylinder",
                                              .declare = cyl_declare,
                                              .residual = cyl_residual,
                                              .jacobian = cyl_jacobian,
                                              .describe = cyl_describe,
                                              .destroy = free};

int hyd_cylinder(bgr_model *m, bgr_comp c, const char *name, const hyd_cylinder_spec *spec)
{
    const char *w = "hyd_cylinder";
    if (!spec) return bgr_refuse(m, c, name, w, "spec = NULL, expected the parameters");
    const hyd_cylinder_spec *s = spec;
    if (bgr_check_value(m, c, name, w, "area_a", s->area_a, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "area_b", s->area_b, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "length_min", s->length_min, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "stroke", s->stroke, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "volume_a0", s->volume_a0, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "volume_b0", s->volume_b0, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "beta", s->beta, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "friction", s->friction, BGR_NONNEGATIVE) ||
        bgr_check_value(m, c, name, w, "leakage", s->leakage, BGR_NONNEGATIVE))
        return BG_ERR_ARGUMENT;
    if (!(s->area_b <= s->area_a))
        return bgr_refuse(m, c, name, w,
                          "area_b = %g, expected <= area_a = %g (the annulus is the piston less "
                          "the rod)",
                          s->area_b, s->area_a);
    if (!isfinite(s->beta / s->volume_a0) || !isfinite(s->beta / s->volume_b0) ||
        !isfinite(s->length_min + s->stroke))
        return bgr_refuse(m, c, name, w,
                          "beta / volume_a0 = %g, beta / volume_b0 = %g, length_min + stroke = "
                          "%g, expected finite numbers",
                          s->beta / s->volume_a0, s->beta / s->volume_b0,
                          s->length_min + s->stroke);
    cylinder *q = calloc(1, sizeof *q);
    if (!q) return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, w, "out of memory");
    q->sp = *s;
    static const char *const sn[5] = {"d0", "d1", "d2", "p_a", "p_b"};
    static const int dims[4] = {3, 3, 1, 1};
    return bgr_element_add(m, c, name, &hyd_class_cylinder, q, 4, dims, 5, sn, 0, NULL);
}

/* The cylinder element id of a compiled model, else NULL. */
static const cylinder *compiled_cylinder(const bgr_model *m, int id)
{
    bgr_element *el = bgr_element_get((bgr_model *)m, id);
    if (!el || el->cls != &hyd_class_cylinder || !bgr_n(m)) return NULL;
    return el->params;
}

int hyd_cylinder_set(bgr_model *m, int id, const double *xa, const double *xb, double p_a,
                     double p_b)
{
    const cylinder *c = compiled_cylinder(m, id);
    double *y0 = bgr_y0(m);
    if (!c || !y0)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "hyd_cylinder_set",
                              "element %d is not a cylinder of a compiled model", id);
    if (!xa || !xb || !isfinite(p_a) || !isfinite(p_b))
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "hyd_cylinder_set",
                              "element %d: both end points and finite pressures are needed (p_a "
                              "= %g, p_b = %g)",
                              id, p_a, p_b);
    for (int i = 0; i < 3; i++)
        y0[c->d + i] = xb[i] - xa[i];
    y0[c->pa] = p_a;
    y0[c->pb] = p_b;
    y0[c->ea] = p_a; /* the port efforts, so that the algebraic start is consistent already */
    y0[c->eb] = p_b;
    return BG_OK;
}

int hyd_cylinder_set_nominal(bgr_model *m, int id, double pressure, double speed)
{
    double v[2] = {pressure, speed};
    void *q = NULL;
    int st = cmp_check_scales(m, id, &hyd_class_cylinder, "a hydraulic cylinder",
                              "hyd_cylinder_set_nominal", v, 2, &q);
    if (st != BG_OK) return st;
    ((cylinder *)q)->p_nom = pressure;
    ((cylinder *)q)->v_nom = speed;
    return BG_OK;
}

/* g(p) = beta (exp(p / beta) - 1) - p, the free energy per unit volume, without cancellation
 * for small p / beta (expm1) */
static double oil_energy_density(double p, double beta)
{
    return beta * expm1(p / beta) - p;
}

int hyd_cylinder_evaluate(const bgr_model *m, int id, const double *y, hyd_cylinder_values *out)
{
    const cylinder *c = compiled_cylinder(m, id);
    if (!c || !y || !out) {
        if (m)
            bg_error_raise(
                bgr_model_error_mut((bgr_model *)m), BG_ERR_ARGUMENT, "hyd_cylinder_evaluate",
                "element %d is not a cylinder of a compiled model, or y or out is NULL", id);
        return BG_ERR_ARGUMENT;
    }
    const hyd_cylinder_spec *s = &c->sp;
    cyl_point k;
    cyl_eval(c, y, &k);
    double pa = y[c->pa], pb = y[c->pb], qa = c->sa * y[c->qa], qb = c->sb * y[c->qb];
    double ga = oil_energy_density(pa, s->beta), gb = oil_energy_density(pb, s->beta);
    out->extension = k.x;
    out->rate = k.xd;
    out->volume_a = k.Va;
    out->volume_b = k.Vb;
    out->tension = k.T;
    out->leak_flow = k.ql;
    out->energy = k.Va * ga + k.Vb * gb;
    out->power_hydraulic = pa * qa + pb * qb;
    out->power_convected = ga * qa + gb * qb;
    out->power_mechanical = k.T * k.xd;
    out->dissipation_friction = s->friction * k.xd * k.xd;
    /* (p_a + g_a) - (p_b + g_b) = beta (exp(p_a/beta) - exp(p_b/beta)) */
    out->dissipation_leakage = k.ql * s->beta * (expm1(pa / s->beta) - expm1(pb / s->beta));
    return BG_OK;
}
