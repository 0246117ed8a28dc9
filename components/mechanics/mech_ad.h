/* Forward-mode automatic differentiation to second order in a fixed number of variables
 * (internal, header-only). A value carries its gradient and, when asked (order 2), its Hessian,
 * so that an element that writes its energy once gets exact first and second derivatives:
 * forces and their Jacobian without finite differences. Used by the co-rotational beam.
 * The operations fill the Hessian's upper triangle only (h[i][j], j >= i; every Hessian is
 * symmetric): ad_mirror copies it to the lower one for a value whose Hessian is read whole.
 * Order 3 (directional, for second derivatives along one direction d only): h[0 .. AD_N - 1]
 * carries H d, at the cost of a gradient: (a b)'' d = H_a d b + a H_b d + g_a (g_b . d) +
 * g_b (g_a . d), f(a)'' d = f' H_a d + f'' g_a (g_a . d). */
#ifndef MECH_AD_H
#define MECH_AD_H

#include <math.h>
#include <string.h>

#define AD_N 14

typedef struct ad {
    double v;
    double g[AD_N];
    double h[AD_N * AD_N];
} ad;

typedef struct ad_ctx {
    int order;         /* 1: gradients only; 2: Hessians too; 3: the Hessian times dir only */
    const double *dir; /* order 3: the direction (AD_N); h[0 .. AD_N - 1] holds H dir */
} ad_ctx;

/* r (AD_N) = a.g . dir */
static inline double ad_gdir_(const ad_ctx *c, const ad *a)
{
    double s = 0;
    for (int i = 0; i < AD_N; i++)
        s += a->g[i] * c->dir[i];
    return s;
}

static inline void ad_const(const ad_ctx *c, double v, ad *r)
{
    r->v = v;
    memset(r->g, 0, sizeof r->g);
    if (c->order == 3)
        memset(r->h, 0, AD_N * sizeof r->h[0]);
    else if (c->order > 1)
        memset(r->h, 0, sizeof r->h);
}

static inline void ad_var(const ad_ctx *c, double v, int i, ad *r)
{
    ad_const(c, v, r);
    r->g[i] = 1.0;
}

/* r = a + s b */
static inline void ad_axpy(const ad_ctx *c, const ad *a, double s, const ad *b, ad *r)
{
    r->v = a->v + s * b->v;
    for (int i = 0; i < AD_N; i++)
        r->g[i] = a->g[i] + s * b->g[i];
    if (c->order == 3)
        for (int i = 0; i < AD_N; i++)
            r->h[i] = a->h[i] + s * b->h[i];
    else if (c->order > 1)
        for (int i = 0; i < AD_N; i++)
            for (int j = i; j < AD_N; j++)
                r->h[i * AD_N + j] = a->h[i * AD_N + j] + s * b->h[i * AD_N + j];
}

static inline void ad_scale(const ad_ctx *c, double s, const ad *a, ad *r)
{
    r->v = s * a->v;
    for (int i = 0; i < AD_N; i++)
        r->g[i] = s * a->g[i];
    if (c->order == 3)
        for (int i = 0; i < AD_N; i++)
            r->h[i] = s * a->h[i];
    else if (c->order > 1)
        for (int i = 0; i < AD_N; i++)
            for (int j = i; j < AD_N; j++)
                r->h[i * AD_N + j] = s * a->h[i * AD_N + j];
}

/* r = a b (r may alias neither) */
static inline void ad_mul(const ad_ctx *c, const ad *a, const ad *b, ad *r)
{
    r->v = a->v * b->v;
    for (int i = 0; i < AD_N; i++)
        r->g[i] = a->g[i] * b->v + a->v * b->g[i];
    if (c->order == 3) {
        double ad = ad_gdir_(c, a), bd = ad_gdir_(c, b);
        for (int i = 0; i < AD_N; i++)
            r->h[i] = a->h[i] * b->v + a->v * b->h[i] + a->g[i] * bd + b->g[i] * ad;
    } else if (c->order > 1)
        for (int i = 0; i < AD_N; i++)
            for (int j = i; j < AD_N; j++)
                r->h[i * AD_N + j] = a->h[i * AD_N + j] * b->v + a->v * b->h[i * AD_N + j] +
                                     a->g[i] * b->g[j] + a->g[j] * b->g[i];
}

/* r = f(a) for a scalar function with f, f', f'' at a->v (r may alias a) */
static inline void ad_apply(const ad_ctx *c, const ad *a, double f, double fp, double fpp, ad *r)
{
    if (c->order == 3) {
        double gd = ad_gdir_(c, a);
        for (int i = 0; i < AD_N; i++)
            r->h[i] = fp * a->h[i] + fpp * a->g[i] * gd;
    } else if (c->order > 1)
        for (int i = 0; i < AD_N; i++)
            for (int j = i; j < AD_N; j++)
                r->h[i * AD_N + j] = fp * a->h[i * AD_N + j] + fpp * a->g[i] * a->g[j];
    for (int i = 0; i < AD_N; i++)
        r->g[i] = fp * a->g[i];
    r->v = f;
}

static inline void ad_sqrt(const ad_ctx *c, const ad *a, ad *r)
{
    double s = sqrt(a->v);
    ad_apply(c, a, s, 0.5 / s, -0.25 / (s * a->v), r);
}

static inline void ad_inv(const ad_ctx *c, const ad *a, ad *r)
{
    double x = a->v;
    ad_apply(c, a, 1.0 / x, -1.0 / (x * x), 2.0 / (x * x * x), r);
}

/* r = s (a . b) for 3-vectors in one pass, or r += s (a . b) when acc (r may alias neither; a
 * and b may be the same). Without acc r's old contents are not read (they may be garbage). */
static inline void ad_dot3s(const ad_ctx *c, double s, const ad *a, const ad *b, int acc, ad *r)
{
    const double a0 = a[0].v, a1 = a[1].v, a2 = a[2].v, b0 = b[0].v, b1 = b[1].v, b2 = b[2].v;
    double v = s * (a0 * b0 + a1 * b1 + a2 * b2);
    r->v = acc ? r->v + v : v;
    for (int i = 0; i < AD_N; i++) {
        double g = s * (a[0].g[i] * b0 + a0 * b[0].g[i] + a[1].g[i] * b1 + a1 * b[1].g[i] +
                        a[2].g[i] * b2 + a2 * b[2].g[i]);
        r->g[i] = acc ? r->g[i] + g : g;
    }
    if (c->order == 3) {
        double ad[3], bd[3];
        for (int m = 0; m < 3; m++)
            ad[m] = ad_gdir_(c, &a[m]), bd[m] = ad_gdir_(c, &b[m]);
        for (int i = 0; i < AD_N; i++) {
            double h = 0;
            for (int m = 0; m < 3; m++)
                h += a[m].h[i] * b[m].v + a[m].v * b[m].h[i] + a[m].g[i] * bd[m] + b[m].g[i] * ad[m];
            r->h[i] = acc ? r->h[i] + s * h : s * h;
        }
    } else if (c->order > 1)
        for (int i = 0; i < AD_N; i++)
            for (int j = i; j < AD_N; j++) {
                double h = 0;
                for (int m = 0; m < 3; m++)
                    h += a[m].h[i * AD_N + j] * b[m].v + a[m].v * b[m].h[i * AD_N + j] +
                         a[m].g[i] * b[m].g[j] + a[m].g[j] * b[m].g[i];
                r->h[i * AD_N + j] = acc ? r->h[i * AD_N + j] + s * h : s * h;
            }
}

/* The Hessian's lower triangle from its upper one (order 2), for a value read whole. */
static inline void ad_mirror(const ad_ctx *c, ad *a)
{
    if (c->order == 2)
        for (int i = 0; i < AD_N; i++)
            for (int j = 0; j < i; j++)
                a->h[i * AD_N + j] = a->h[j * AD_N + i];
}

/* r = a . b for 3-vectors */
static inline void ad_dot3(const ad_ctx *c, const ad *a, const ad *b, ad *r)
{
    ad_dot3s(c, 1.0, a, b, 0, r);
}

#endif
