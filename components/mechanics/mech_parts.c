/* Point mass, fixed support, spherical and revolute joints (equations in mech_parts.h). */
#include "mech_parts.h"

#include <stdlib.h>
#include <string.h>

#include "mech_frame.h"
#include "mech_util.h"
#include "sig_sources.h"

typedef struct part {
    int kind;                  /* PART_* */
    int dim;                   /* port dimension (3 or 6) */
    double m, g[3];            /* point mass */
    int body_a;                /* revolute: body carrying the axis (-1: ground) */
    double a[3], e1[3], e2[3]; /* revolute axis and its normal pair, in A's frame */
    int drive;
    int angle;                 /* revolute with a prescribed angle (mech_revolute_angle) */
    int body_b;                /* its body B (-1: ground) */
    mech_angle_fn fn;          /* the angle profile and its user data, or */
    void *user;
    int source;                /* a signal source's (sig_sources.h) output, */
    int src_out;               /* SIG_VALUE or SIG_INTEGRAL, */
    bgr_model *model;          /* of this model (set at declaration) */
    /* ids filled at declaration */
    int f[3], e[3], s[3]; /* first flow / effort id and orientation of each port */
    int x, v, q;          /* states (point mass), quaternion of body A (revolute) */
    int qb, tau;          /* prescribed angle: quaternion of body B, the drive torque */
    mech_scales sc;       /* stated nominal scales */
} part;

enum { PART_MASS, PART_SUPPORT, PART_SPHERICAL, PART_REVOLUTE };

static void part_free(void *p)
{
    free(p);
}

static int label_eqs(bgr_element *el, bgr_model *m, int n, const char *base)
{
    const char **lab = calloc((size_t)n + 1, sizeof *lab);
    char(*buf)[24] = calloc((size_t)n + 1, sizeof *buf);
    int st = BG_ERR_MEMORY;
    if (lab && buf) {
        for (int i = 0; i < n; i++) {
            snprintf(buf[i], sizeof buf[i], "%s%d", base, i);
            lab[i] = buf[i];
        }
        st = bgr_declare_equations(el, m, n, lab);
    }
    free(lab);
    free(buf);
    if (st == BG_ERR_MEMORY)
        return bg_error_raise(bgr_model_error_mut(m), st, "bgr_compile", "out of memory");
    return st;
}

/* Axis vectors in the global frame and their derivatives with respect to q_A. */
static void revolute_axes(const part *p, const double *y, double *a, double *e1, double *e2,
                          double da[4][3], double de1[4][3], double de2[4][3])
{
    if (p->body_a < 0) {
        memcpy(a, p->a, 3 * sizeof *a);
        memcpy(e1, p->e1, 3 * sizeof *e1);
        memcpy(e2, p->e2, 3 * sizeof *e2);
        memset(da, 0, 12 * sizeof **da);
        memset(de1, 0, 12 * sizeof **de1);
        memset(de2, 0, 12 * sizeof **de2);
        return;
    }
    double R[9], dR[36];
    mech_quat_R(y + p->q, R, dR);
    mech_mv(R, p->a, a);
    mech_mv(R, p->e1, e1);
    mech_mv(R, p->e2, e2);
    for (int j = 0; j < 4; j++) {
        mech_mv(dR + 9 * j, p->a, da[j]);
        mech_mv(dR + 9 * j, p->e1, de1[j]);
        mech_mv(dR + 9 * j, p->e2, de2[j]);
    }
}

static void part_partials(const bgr_element *el, const double *y, mech_emit *E)
{
    const part *p = el->params;
    int row = 0;
    switch (p->kind) {
    case PART_MASS:
        for (int i = 0; i < 3; i++, row++) { /* x' = v */
            mech_dep(E, row, p->x + i, 1, 1.0);
            mech_dep(E, row, p->v + i, 0, -1.0);
        }
        for (int i = 0; i < 3; i++, row++) { /* m v' - s F - m g */
            mech_dep(E, row, p->v + i, 1, p->m);
            mech_dep(E, row, p->e[0] + i, 0, -p->s[0]);
        }
        for (int i = 0; i < 3; i++, row++) { /* v_port - v */
            mech_dep(E, row, p->f[0] + i, 0, 1.0);
            mech_dep(E, row, p->v + i, 0, -1.0);
        }
        break;
    case PART_SUPPORT:
        for (int i = 0; i < p->dim; i++, row++)
            mech_dep(E, row, p->f[0] + i, 0, 1.0);
        break;
    case PART_SPHERICAL:
        for (int i = 0; i < 3; i++, row++) {
            mech_dep(E, row, p->f[0] + i, 0, 1.0);
            mech_dep(E, row, p->f[1] + i, 0, -1.0);
        }
        for (int i = 0; i < 3; i++, row++) {
            mech_dep(E, row, p->e[0] + i, 0, p->s[0]);
            mech_dep(E, row, p->e[1] + i, 0, p->s[1]);
        }
        if (p->dim == 6)
            for (int k = 0; k < 2; k++)
                for (int i = 0; i < 3; i++, row++)
                    mech_dep(E, row, p->e[k] + 3 + i, 0, p->s[k]);
        break;
    case PART_REVOLUTE: {
        double a[3], e1[3], e2[3], da[4][3], de1[4][3], de2[4][3];
        revolute_axes(p, y, a, e1, e2, da, de1, de2);
        const double *wA = y + p->f[0] + 3, *wB = y + p->f[1] + 3;
        double dw[3] = {wB[0] - wA[0], wB[1] - wA[1], wB[2] - wA[2]};
        for (int i = 0; i < 3; i++, row++) {
            mech_dep(E, row, p->f[0] + i, 0, 1.0);
            mech_dep(E, row, p->f[1] + i, 0, -1.0);
        }
        const double *ev[2] = {e1, e2};
        double(*dev[2])[3] = {de1, de2};
        for (int r = 0; r < 2; r++, row++) { /* (wB - wA).e_r = 0 */
            for (int i = 0; i < 3; i++) {
                mech_dep(E, row, p->f[1] + 3 + i, 0, ev[r][i]);
                mech_dep(E, row, p->f[0] + 3 + i, 0, -ev[r][i]);
            }
            if (p->body_a >= 0)
                for (int j = 0; j < 4; j++)
                    mech_dep(E, row, p->q + j, 0, mech_dot(dw, dev[r][j]));
        }
        for (int i = 0; i < 3; i++, row++) { /* forces */
            mech_dep(E, row, p->e[0] + i, 0, p->s[0]);
            mech_dep(E, row, p->e[1] + i, 0, p->s[1]);
        }
        for (int i = 0; i < 3; i++, row++) { /* moments */
            mech_dep(E, row, p->e[0] + 3 + i, 0, p->s[0]);
            mech_dep(E, row, p->e[1] + 3 + i, 0, p->s[1]);
        }
        /* (s_B M_B).a + s_d e_d */
        const double *MB = y + p->e[1] + 3;
        for (int i = 0; i < 3; i++)
            mech_dep(E, row, p->e[1] + 3 + i, 0, p->s[1] * a[i]);
        if (p->body_a >= 0)
            for (int j = 0; j < 4; j++)
                mech_dep(E, row, p->q + j, 0, p->s[1] * mech_dot(MB, da[j]));
        if (p->drive) mech_dep(E, row, p->e[2], 0, p->s[2]);
        if (p->angle) mech_dep(E, row, p->tau, 0, 1.0);
        row++;
        if (p->drive || p->angle) { /* f_d - (wB - wA).a, or theta_ref'(t) - (wB - wA).a */
            if (p->drive) mech_dep(E, row, p->f[2], 0, 1.0);
            for (int i = 0; i < 3; i++) {
                mech_dep(E, row, p->f[1] + 3 + i, 0, -a[i]);
                mech_dep(E, row, p->f[0] + 3 + i, 0, a[i]);
            }
            if (p->body_a >= 0)
                for (int j = 0; j < 4; j++)
                    mech_dep(E, row, p->q + j, 0, -mech_dot(dw, da[j]));
            row++;
        }
        break;
    }
    }
}

/* The geometric angle of B relative to A about the axis (mech_parts.h): X = (R_A e1).(R_B e1),
 * Y = (R_A e2).(R_B e1), theta = atan2(Y, X); its partial derivatives with respect to q_A (dA,
 * when A is a body) and q_B (dB, when B is a body). R of the ground is the identity. */
static double revolute_angle(const part *p, const double *y, double dA[4], double dB[4])
{
    double RA[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, RB[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    double dRA[36], dRB[36];
    if (p->body_a >= 0) mech_quat_R(y + p->q, RA, dRA);
    if (p->body_b >= 0) mech_quat_R(y + p->qb, RB, dRB);
    double a1[3], a2[3], b1[3];
    mech_mv(RA, p->e1, a1);
    mech_mv(RA, p->e2, a2);
    mech_mv(RB, p->e1, b1);
    double X = mech_dot(a1, b1), Y = mech_dot(a2, b1), r2 = X * X + Y * Y;
    for (int j = 0; j < 4; j++) {
        double u[3], v[3];
        if (p->body_a >= 0) {
            mech_mv(dRA + 9 * j, p->e1, u);
            mech_mv(dRA + 9 * j, p->e2, v);
            dA[j] = (X * mech_dot(v, b1) - Y * mech_dot(u, b1)) / r2;
        }
        if (p->body_b >= 0) {
            mech_mv(dRB + 9 * j, p->e1, u);
            dB[j] = (X * mech_dot(a2, u) - Y * mech_dot(a1, u)) / r2;
        }
    }
    return atan2(Y, X);
}

/* theta_ref(t), and its rate into *rate: the profile function, or the signal source's output
 * (value: u, u'; integral: the integral of u from 0, u). NaN if the source cannot be read. */
static double angle_ref(const part *p, double t, double *rate)
{
    if (p->fn) return p->fn(p->user, t, rate);
    double u, du, I;
    if (sig_evaluate(p->model, p->source, t, &u, &du, &I) != BG_OK) return *rate = NAN;
    *rate = p->src_out == SIG_INTEGRAL ? u : du;
    return p->src_out == SIG_INTEGRAL ? I : u;
}

/* g = remainder(theta - theta_ref(t), 2 pi) and its gradient (q_A, then q_B). */
static int part_invariant(const bgr_element *el, double t, const double *y, double *g, double *dg)
{
    const part *p = el->params;
    double dA[4], dB[4], rate;
    double th = revolute_angle(p, y, dA, dB), ref = angle_ref(p, t, &rate);
    g[0] = remainder(th - ref, 6.283185307179586476925);
    if (!isfinite(g[0])) return 1;
    int k = 0;
    for (int j = 0; dg && p->body_a >= 0 && j < 4; j++)
        dg[k++] = dA[j];
    for (int j = 0; dg && p->body_b >= 0 && j < 4; j++)
        dg[k++] = dB[j];
    return 0;
}

static int revolute_angle_declare(bgr_element *el, bgr_model *m)
{
    part *p = el->params;
    if (!p->fn) {
        p->model = m;
        p->src_out = sig_source_output(m, p->source);
        if (p->src_out != SIG_VALUE && p->src_out != SIG_INTEGRAL) {
            bgr_element *src = bgr_element_get(m, p->source);
            return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "bgr_compile",
                                  "revolute joint %s: its angle profile %s (element %d) is not a "
                                  "signal source (sig_sources.h) with the output value or "
                                  "integral%s",
                                  el->name, src ? src->name : "?", p->source,
                                  p->src_out == SIG_RATE ? " (its output is the rate)" : "");
        }
    }
    static const char *const lab[1] = {"angle"};
    int st = bgr_declare_invariants(el, m, 1, lab);
    for (int j = 0; st == BG_OK && p->body_a >= 0 && j < 4; j++)
        st = bgr_declare_invariant_dep(el, m, 0, p->q + j);
    for (int j = 0; st == BG_OK && p->body_b >= 0 && j < 4; j++)
        st = bgr_declare_invariant_dep(el, m, 0, p->qb + j);
    return st;
}

/* Under a frame's motion (mech_frame.h): the ports' vectors, a point mass's x and v. */
static int part_frame(bgr_element *el, bgr_model *m, const part *p)
{
    int st = mech_frame_ports(el, m);
    if (st == BG_OK && p->kind == PART_MASS) {
        st = mech_frame_group(el, m, BGR_FRAME_POSITION, p->x);
        if (st == BG_OK) st = mech_frame_group(el, m, BGR_FRAME_VECTOR, p->v);
    }
    return st;
}

static int part_declare(bgr_element *el, bgr_model *m)
{
    part *p = el->params;
    for (int k = 0; k < el->nports; k++) {
        p->f[k] = bgr_fv(el, m, k, 0);
        p->e[k] = bgr_ev(el, m, k, 0);
        p->s[k] = el->sign[k];
    }
    int neq = 0;
    const char *base = "eq";
    switch (p->kind) {
    case PART_MASS:
        p->x = bgr_sv(el, 0);
        p->v = bgr_sv(el, 3);
        neq = 9;
        base = "mass";
        break;
    case PART_SUPPORT:
        neq = p->dim;
        base = "fixed";
        break;
    case PART_SPHERICAL:
        neq = 2 * p->dim;
        base = "joint";
        break;
    case PART_REVOLUTE:
        neq = 12 + (p->drive || p->angle);
        base = "joint";
        for (int k = 0; k < 1 + p->angle; k++) {
            int body = k ? p->body_b : p->body_a;
            if (body < 0) continue;
            bgr_ref r = {BGR_STATE, body, 9};
            int q = bgr_ref_var(m, r);
            bgr_element *b = bgr_element_get(m, body);
            if (q < 0 || !b || b->nstates != 13 || strcmp(b->cls->type, "body"))
                return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "bgr_compile",
                                      "revolute joint %s: %s = %d is not a rigid body", el->name,
                                      k ? "body_b" : "body_a", body);
            *(k ? &p->qb : &p->q) = q;
        }
        if (p->angle) {
            p->tau = bgr_av(el, 0);
            int st = bgr_declare_index2(el, m, p->tau);
            if (st != BG_OK) return st;
        }
        break;
    }
    int st = label_eqs(el, m, neq, base);
    if (st == BG_OK && p->angle) st = revolute_angle_declare(el, m);
    if (st != BG_OK) return st;
    int nv = bgr_nvars(m);
    double *zero = calloc((size_t)nv + 1, sizeof *zero);
    if (!zero)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "bgr_compile",
                              "out of memory");
    if (p->kind == PART_REVOLUTE && p->body_a >= 0) zero[p->q] = 1.0;
    mech_emit E = {1, el, m, NULL, 0, BG_OK};
    part_partials(el, zero, &E);
    free(zero);
    if (E.status != BG_OK) return E.status;
    /* Nominal magnitudes. A point mass: forces the stated force, else its weight m |g| (what
     * its port carries at rest); positions the stated length. A support's or joint's reactions
     * depend on what it carries, not on its parameters: the stated force and moment only (a
     * revolute joint's drive torque is a moment too). Velocities keep 1 (no time scale). */
    double F = p->sc.force;
    if (p->kind == PART_MASS && !(F > 0)) F = p->m * sqrt(mech_dot(p->g, p->g));
    for (int k = 0; k < el->nports && st == BG_OK; k++)
        st = mech_nominal_port(el, m, p->e[k], bgr_port_dim(el, m, k) == 1 ? 0 : p->dim, F,
                               p->sc.moment);
    if (p->kind == PART_REVOLUTE && p->drive && st == BG_OK)
        st = mech_nominal(el, m, p->e[2], p->sc.moment);
    if (p->kind == PART_REVOLUTE && p->angle && st == BG_OK)
        st = mech_nominal(el, m, p->tau, p->sc.moment);
    for (int i = 0; p->kind == PART_MASS && i < 3 && st == BG_OK; i++)
        st = mech_nominal(el, m, p->x + i, p->sc.length);
    if (st == BG_OK) st = part_frame(el, m, p);
    return st;
}


static int part_residual(const bgr_element *el, double t, const double *y, const double *yp,
                         double *F)
{
    const part *p = el->params;
    int row = 0;
    switch (p->kind) {
    case PART_MASS:
        for (int i = 0; i < 3; i++)
            F[row++] = yp[p->x + i] - y[p->v + i];
        for (int i = 0; i < 3; i++)
            F[row++] = p->m * yp[p->v + i] - p->s[0] * y[p->e[0] + i] - p->m * p->g[i];
        for (int i = 0; i < 3; i++)
            F[row++] = y[p->f[0] + i] - y[p->v + i];
        break;
    case PART_SUPPORT:
        for (int i = 0; i < p->dim; i++)
            F[row++] = y[p->f[0] + i];
        break;
    case PART_SPHERICAL:
        for (int i = 0; i < 3; i++)
            F[row++] = y[p->f[0] + i] - y[p->f[1] + i];
        for (int i = 0; i < 3; i++)
            F[row++] = p->s[0] * y[p->e[0] + i] + p->s[1] * y[p->e[1] + i];
        if (p->dim == 6)
            for (int k = 0; k < 2; k++)
                for (int i = 0; i < 3; i++)
                    F[row++] = p->s[k] * y[p->e[k] + 3 + i];
        break;
    case PART_REVOLUTE: {
        double a[3], e1[3], e2[3], da[4][3], de1[4][3], de2[4][3];
        revolute_axes(p, y, a, e1, e2, da, de1, de2);
        const double *wA = y + p->f[0] + 3, *wB = y + p->f[1] + 3;
        double dw[3] = {wB[0] - wA[0], wB[1] - wA[1], wB[2] - wA[2]};
        for (int i = 0; i < 3; i++)
            F[row++] = y[p->f[0] + i] - y[p->f[1] + i];
        F[row++] = mech_dot(dw, e1);
        F[row++] = mech_dot(dw, e2);
        for (int i = 0; i < 3; i++)
            F[row++] = p->s[0] * y[p->e[0] + i] + p->s[1] * y[p->e[1] + i];
        for (int i = 0; i < 3; i++)
            F[row++] = p->s[0] * y[p->e[0] + 3 + i] + p->s[1] * y[p->e[1] + 3 + i];
        F[row++] = p->s[1] * mech_dot(y + p->e[1] + 3, a) + (p->drive ? p->s[2] * y[p->e[2]] : 0) +
                   (p->angle ? y[p->tau] : 0);
        if (p->drive) F[row++] = y[p->f[2]] - mech_dot(dw, a);
        if (p->angle) { /* theta_ref'(t) - (wB - wA).a; a profile that fails gives NaN */
            double rate = NAN, th = angle_ref(p, t, &rate);
            F[row++] = isfinite(th) ? rate - mech_dot(dw, a) : NAN;
        }
        break;
    }
    }
    return 0;
}

static int part_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                         double *v)
{
    (void)t, (void)yp;
    mech_emit E = {0, NULL, NULL, v, 0, BG_OK};
    part_partials(el, y, &E);
    return 0;
}

/* The four kinds share one implementation and differ in the type name only. */
#define PART_CLASS(type_name)                                                                      \
    {                                                                                              \
        .type = type_name, .declare = part_declare, .residual = part_residual,                     \
        .jacobian = part_jacobian, .destroy = part_free, .invariant = part_invariant               \
    }
static const bgr_element_class mass_class = PART_CLASS("point mass");
static const bgr_element_class support_class = PART_CLASS("support");
static const bgr_element_class spherical_class = PART_CLASS("spherical joint");
static const bgr_element_class revolute_class = PART_CLASS("revolute joint");
#undef PART_CLASS

mech_scales *mech_parts_scales_(bgr_element *el)
{
    return el && (el->cls == &mass_class || el->cls == &support_class ||
                  el->cls == &spherical_class || el->cls == &revolute_class)
               ? &((part *)el->params)->sc
               : NULL;
}

static part *part_new(bgr_model *m, int kind, int dim)
{
    part *p = calloc(1, sizeof *p);
    if (!p) {
        bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "mech", "out of memory");
        return NULL;
    }
    p->kind = kind;
    p->dim = dim;
    p->body_a = -1;
    return p;
}

int mech_point_mass(bgr_model *m, bgr_comp c, const char *name, double mass, const double *gravity)
{
    const char *w = "mech_point_mass";
    if (bgr_check_value(m, c, name, w, "mass", mass, BGR_POSITIVE) ||
        bgr_check_values(m, c, name, w, "gravity", gravity, 3, BGR_FINITE))
        return BG_ERR_ARGUMENT;
    part *p = part_new(m, PART_MASS, 3);
    if (!p) return BG_ERR_MEMORY;
    p->m = mass;
    if (gravity) memcpy(p->g, gravity, sizeof p->g);
    static const char *const sn[6] = {"x0", "x1", "x2", "v0", "v1", "v2"};
    const int dims[1] = {3};
    return bgr_element_add(m, c, name, &mass_class, p, 1, dims, 6, sn, 0, NULL);
}

int mech_point_mass_set(bgr_model *m, int id, const double *x, const double *v)
{
    bgr_element *el = bgr_element_get(m, id);
    double *y0 = bgr_y0(m);
    if (!el || el->cls != &mass_class || !y0)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "mech_point_mass_set",
                              "element %d is not a point mass of a compiled model", id);
    for (int i = 0; i < 3; i++) {
        y0[el->state0 + i] = x ? x[i] : 0.0;
        y0[el->state0 + 3 + i] = v ? v[i] : 0.0;
    }
    return BG_OK;
}

int mech_point_mass_energy(const bgr_model *m, int id, const double *y, double *kinetic,
                           double *potential)
{
    const bgr_element *el = bgr_element_get((bgr_model *)m, id);
    if (!el || el->cls != &mass_class || !bgr_nvars(m) || !y || !kinetic || !potential)
        return BG_ERR_ARGUMENT;
    const part *p = el->params;
    const double *x = y + el->state0, *v = x + 3;
    *kinetic = 0.5 * p->m * mech_dot(v, v);
    *potential = -p->m * mech_dot(p->g, x);
    return BG_OK;
}

int mech_support(bgr_model *m, bgr_comp c, const char *name, int dim)
{
    if (dim != 3 && dim != 6)
        return bgr_refuse(m, c, name, "mech_support", "dim = %d, expected 3 or 6", dim);
    part *p = part_new(m, PART_SUPPORT, dim);
    if (!p) return BG_ERR_MEMORY;
    return bgr_element_add(m, c, name, &support_class, p, 1, &p->dim, 0, NULL, 0, NULL);
}

int mech_spherical(bgr_model *m, bgr_comp c, const char *name, int dim)
{
    if (dim != 3 && dim != 6)
        return bgr_refuse(m, c, name, "mech_spherical", "dim = %d, expected 3 or 6", dim);
    part *p = part_new(m, PART_SPHERICAL, dim);
    if (!p) return BG_ERR_MEMORY;
    const int dims[2] = {dim, dim};
    return bgr_element_add(m, c, name, &spherical_class, p, 2, dims, 0, NULL, 0, NULL);
}

/* The checks and the axes of a revolute joint (both constructors); NULL after a refusal. */
static part *revolute_new(bgr_model *m, bgr_comp c, const char *name, const char *w, int body_a,
                          const double *axis_a)
{
    if (!axis_a) {
        bgr_refuse(m, c, name, w, "the axis axis_a is NULL");
        return NULL;
    }
    if (bgr_check_values(m, c, name, w, "axis_a", axis_a, 3, BGR_FINITE)) return NULL;
    double n = sqrt(mech_dot(axis_a, axis_a));
    if (!(n > 0) || !isfinite(n)) {
        bgr_refuse(m, c, name, w,
                   "axis_a = (%g, %g, %g) has length %g, expected a nonzero finite axis", axis_a[0],
                   axis_a[1], axis_a[2], n);
        return NULL;
    }
    if (body_a < -1) {
        bgr_refuse(m, c, name, w,
                   "body_a = %d, expected -1 (a fixed global axis) or a body's element id", body_a);
        return NULL;
    }
    part *p = part_new(m, PART_REVOLUTE, 6);
    if (!p) return NULL;
    p->body_a = body_a;
    p->body_b = -1;
    for (int i = 0; i < 3; i++)
        p->a[i] = axis_a[i] / n;
    /* e1: the unit vector of the coordinate axis least aligned with a, made normal to a */
    int k = fabs(p->a[0]) <= fabs(p->a[1]) && fabs(p->a[0]) <= fabs(p->a[2]) ? 0
            : fabs(p->a[1]) <= fabs(p->a[2])                                 ? 1
                                                                             : 2;
    double u[3] = {0, 0, 0};
    u[k] = 1;
    double d = mech_dot(u, p->a);
    for (int i = 0; i < 3; i++)
        p->e1[i] = u[i] - d * p->a[i];
    double ne = sqrt(mech_dot(p->e1, p->e1));
    for (int i = 0; i < 3; i++)
        p->e1[i] /= ne;
    mech_cross(p->a, p->e1, p->e2);
    return p;
}

int mech_revolute(bgr_model *m, bgr_comp c, const char *name, int body_a, const double *axis_a,
                  int drive)
{
    part *p = revolute_new(m, c, name, "mech_revolute", body_a, axis_a);
    if (!p) return bgr_model_error(m) && bgr_model_error(m)->status < 0 ? bgr_model_error(m)->status
                                                                       : BG_ERR_ARGUMENT;
    p->drive = drive != 0;
    const int dims[3] = {6, 6, 1};
    return bgr_element_add(m, c, name, &revolute_class, p, 2 + p->drive, dims, 0, NULL, 0, NULL);
}

static int revolute_angle_add(bgr_model *m, bgr_comp c, const char *name, const char *w,
                              int body_a, const double *axis_a, int body_b, mech_angle_fn theta,
                              void *user, int source)
{
    if (body_b < -1 || (body_b == -1 && body_a == -1) || (body_b >= 0 && body_b == body_a))
        return bgr_refuse(m, c, name, w,
                          "body_b = %d (body_a = %d), expected -1 (the ground) or a body's element "
                          "id other than body_a, and not both -1",
                          body_b, body_a);
    part *p = revolute_new(m, c, name, w, body_a, axis_a);
    if (!p) return bgr_model_error(m) && bgr_model_error(m)->status < 0 ? bgr_model_error(m)->status
                                                                       : BG_ERR_ARGUMENT;
    p->angle = 1;
    p->body_b = body_b;
    p->fn = theta;
    p->user = user;
    p->source = source;
    const int dims[2] = {6, 6};
    static const char *const an[1] = {"torque"};
    return bgr_element_add(m, c, name, &revolute_class, p, 2, dims, 0, NULL, 1, an);
}

int mech_revolute_angle(bgr_model *m, bgr_comp c, const char *name, int body_a,
                        const double *axis_a, int body_b, mech_angle_fn theta, void *user)
{
    const char *w = "mech_revolute_angle";
    if (!theta) return bgr_refuse(m, c, name, w, "the angle profile theta is NULL");
    return revolute_angle_add(m, c, name, w, body_a, axis_a, body_b, theta, user, -1);
}

int mech_revolute_angle_source(bgr_model *m, bgr_comp c, const char *name, int body_a,
                               const double *axis_a, int body_b, int source)
{
    const char *w = "mech_revolute_angle_source";
    if (source < 0)
        return bgr_refuse(m, c, name, w, "source = %d, expected a signal source's element id",
                          source);
    return revolute_angle_add(m, c, name, w, body_a, axis_a, body_b, NULL, NULL, source);
}
