/* Forward-mode automatic differentiation to second order in a fixed number of variables
 * (internal, header-only). A value carries its gradient and, when asked (order 2), its Hessian,
 * so that an element that writes its energy once gets exact first and second derivatives:
 * forces and their Jacobian without finite differences. Used by the co-rotational beam.
 * The operations fill the Hessian's upper triangle only (h[i][j], j >= i; every Hessian is
 * symmetric): ad_mirror copies it to the lower one for a value whose Hessian is read whole.
 * Order 3 (directional, for second derivatives along one direction d only): h[0 .. n - 1]
 * carries H d, at the cost of a gradient: (a b)'' d = H_a d b + a H_b d + g_a (g_b . d) +
 * g_b (g_a . d), f(a)'' d = f' H_a d + f'' g_a (g_a . d). */
#ifndef MECH_AD_H
#define MECH_AD_H

#include <math.h>
#include <string.h>

/* AD_N: the storage of a number's gradient (and the stride of its Hessian); an evaluation
 * differentiates in the first c->n <= AD_N variables (c->n = 0: all AD_N), so that an element
 * with fewer unknowns pays for its own. */
#define AD_N 16

typedef struct ad {
    double v;
    double g[AD_N];
    double h[AD_N * AD_N];
} ad;

typedef struct ad_ctx {
    int order;         /* 1: gradients only; 2: Hessians too; 3: the Hessian times dir only */
    const double *dir; /* order 3: the direction (n); h[0 .. n - 1] holds H dir */
    int n;             /* the variables, <= AD_N (0: AD_N) */
} ad_ctx;

/* the number of variables of an evaluation */
static inline int ad_n_(const ad_ctx *c)
{
    return c->n > 0 ? c->n : AD_N;
}

/* Every operation below is compiled for the two sizes an element uses (14 and AD_N), so that
 * its loops have bounds known to the compiler (unrolled and vectorised: a run-time bound made
 * the beam's residual a third slower): op(c, ...) calls op_k_(c, ..., n) with n a constant. */
#if defined(__GNUC__)
#define AD_KERNEL static inline __attribute__((always_inline))
#else
#define AD_KERNEL static inline
#endif

/* r = a.g . dir */
AD_KERNEL double ad_gdir_(const ad_ctx *c, const ad *a, const int n)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s += a->g[i] * c->dir[i];
    return s;
}

static inline void ad_const(const ad_ctx *c, double v, ad *r)
{
    r->v = v;
    memset(r->g, 0, sizeof r->g);
    if (c->order == 3)
        memset(r->h, 0, (size_t)ad_n_(c) * sizeof r->h[0]);
    else if (c->order > 1)
        memset(r->h, 0, sizeof r->h);
}

static inline void ad_var(const ad_ctx *c, double v, int i, ad *r)
{
    ad_const(c, v, r);
    r->g[i] = 1.0;
}

/* r = a + s b */
AD_KERNEL void ad_axpy_k_(const ad_ctx *c, const ad *a, double s, const ad *b, ad *r, const int n)
{
    r->v = a->v + s * b->v;
    for (int i = 0; i < n; i++)
        r->g[i] = a->g[i] + s * b->g[i];
    if (c->order == 3)
        for (int i = 0; i < n; i++)
            r->h[i] = a->h[i] + s * b->h[i];
    else if (c->order > 1)
        for (int i = 0; i < n; i++)
            for (int j = i; j < n; j++)
                r->h[i * AD_N + j] = a->h[i * AD_N + j] + s * b->h[i * AD_N + j];
}

static inline void ad_axpy(const ad_ctx *c, const ad *a, double s, const ad *b, ad *r)
{
    if (c->n == 14)
        ad_axpy_k_(c, a, s, b, r, 14);
    else
        ad_axpy_k_(c, a, s, b, r, AD_N);
}

AD_KERNEL void ad_scale_k_(const ad_ctx *c, double s, const ad *a, ad *r, const int n)
{
    r->v = s * a->v;
    for (int i = 0; i < n; i++)
        r->g[i] = s * a->g[i];
    if (c->order == 3)
        for (int i = 0; i < n; i++)
            r->h[i] = s * a->h[i];
    else if (c->order > 1)
        for (int i = 0; i < n; i++)
            for (int j = i; j < n; j++)
                r->h[i * AD_N + j] = s * a->h[i * AD_N + j];
}

static inline void ad_scale(const ad_ctx *c, double s, const ad *a, ad *r)
{
    if (c->n == 14)
        ad_scale_k_(c, s, a, r, 14);
    else
        ad_scale_k_(c, s, a, r, AD_N);
}

/* r = a b (r may alias neither) */
AD_KERNEL void ad_mul_k_(const ad_ctx *c, const ad *a, const ad *b, ad *r, const int n)
{
    r->v = a->v * b->v;
    for (int i = 0; i < n; i++)
        r->g[i] = a->g[i] * b->v + a->v * b->g[i];
    if (c->order == 3) {
        double ad = ad_gdir_(c, a, n), bd = ad_gdir_(c, b, n);
        for (int i = 0; i < n; i++)
            r->h[i] = a->h[i] * b->v + a->v * b->h[i] + a->g[i] * bd + b->g[i] * ad;
    } else if (c->order > 1)
        for (int i = 0; i < n; i++)
            for (int j = i; j < n; j++)
                r->h[i * AD_N + j] = a->h[i * AD_N + j] * b->v + a->v * b->h[i * AD_N + j] +
                                     a->g[i] * b->g[j] + a->g[j] * b->g[i];
}

static inline void ad_mul(const ad_ctx *c, const ad *a, const ad *b, ad *r)
{
    if (c->n == 14)
        ad_mul_k_(c, a, b, r, 14);
    else
        ad_mul_k_(c, a, b, r, AD_N);
}

/* r = f(a) for a scalar function with f, f', f'' at a->v (r may alias a) */
AD_KERNEL void ad_apply_k_(const ad_ctx *c, const ad *a, double f, double fp, double fpp, ad *r,
                           const int n)
{
    if (c->order == 3) {
        double gd = ad_gdir_(c, a, n);
        for (int i = 0; i < n; i++)
            r->h[i] = fp * a->h[i] + fpp * a->g[i] * gd;
    } else if (c->order > 1)
        for (int i = 0; i < n; i++)
            for (int j = i; j < n; j++)
                r->h[i * AD_N + j] = fp * a->h[i * AD_N + j] + fpp * a->g[i] * a->g[j];
    for (int i = 0; i < n; i++)
        r->g[i] = fp * a->g[i];
    r->v = f;
}

static inline void ad_apply(const ad_ctx *c, const ad *a, double f, double fp, double fpp, ad *r)
{
    if (c->n == 14)
        ad_apply_k_(c, a, f, fp, fpp, r, 14);
    else
        ad_apply_k_(c, a, f, fp, fpp, r, AD_N);
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
AD_KERNEL void ad_dot3s_k_(const ad_ctx *c, double s, const ad *a, const ad *b, int acc, ad *r,
                           const int n)
{
    const double a0 = a[0].v, a1 = a[1].v, a2 = a[2].v, b0 = b[0].v, b1 = b[1].v, b2 = b[2].v;
    double v = s * (a0 * b0 + a1 * b1 + a2 * b2);
    r->v = acc ? r->v + v : v;
    for (int i = 0; i < n; i++) {
        double g = s * (a[0].g[i] * b0 + a0 * b[0].g[i] + a[1].g[i] * b1 + a1 * b[1].g[i] +
                        a[2].g[i] * b2 + a2 * b[2].g[i]);
        r->g[i] = acc ? r->g[i] + g : g;
    }
    if (c->order == 3) {
        double ad[3], bd[3];
        for (int m = 0; m < 3; m++)
            ad[m] = ad_gdir_(c, &a[m], n), bd[m] = ad_gdir_(c, &b[m], n);
        for (int i = 0; i < n; i++) {
            double h = 0;
            for (int m = 0; m < 3; m++)
                h +=
                    a[m].h[i] * b[m].v + a[m].v * b[m].h[i] + a[m].g[i] * bd[m] + b[m].g[i] * ad[m];
            r->h[i] = acc ? r->h[i] + s * h : s * h;
        }
    } else if (c->order > 1)
        for (int i = 0; i < n; i++)
            for (int j = i; j < n; j++) {
                double h = 0;
                for (int m = 0; m < 3; m++)
                    h += a[m].h[i * AD_N + j] * b[m].v + a[m].v * b[m].h[i * AD_N + j] +
                         a[m].g[i] * b[m].g[j] + a[m].g[j] * b[m].g[i];
                r->h[i * AD_N + j] = acc ? r->h[i * AD_N + j] + s * h : s * h;
            }
}

static inline void ad_dot3s(const ad_ctx *c, double s, const ad *a, const ad *b, int acc, ad *r)
{
    if (c->n == 14)
        ad_dot3s_k_(c, s, a, b, acc, r, 14);
    else
        ad_dot3s_k_(c, s, a, b, acc, r, AD_N);
}

/* The Hessian's lower triangle from its upper one (order 2), for a value read whole. */
AD_KERNEL void ad_mirror_k_(const ad_ctx *c, ad *a, const int n)
{
    if (c->order == 2)
        for (int i = 0; i < n; i++)
            for (int j = 0; j < i; j++)
                a->h[i * AD_N + j] = a->h[j * AD_N + i];
}

static inline void ad_mirror(const ad_ctx *c, ad *a)
{
    if (c->n == 14)
        ad_mirror_k_(c, a, 14);
    else
        ad_mirror_k_(c, a, AD_N);
}

/* r = a . b for 3-vectors */
static inline void ad_dot3(const ad_ctx *c, const ad *a, const ad *b, ad *r)
{
    ad_dot3s(c, 1.0, a, b, 0, r);
}

#endif
