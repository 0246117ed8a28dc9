/* Helpers shared by the bond-graph tests (header-only, all static).
 *
 *   vid / eqid        variable / equation id by a printf-formatted path (-1 and a diagnostic if
 *                     absent)
 *   bond registry     bonds made through reg_bond() are recorded with the orientation each end
 *                     sees, from the test's own knowledge of the call (start: -1, end: +1), so
 *                     that power sums never trust the library's bookkeeping
 *   power_sum         sum over an element's ports of s_k e_k . f_k, read from a solution vector by
 *                     the bonds' names (bgr_find_var)
 *   start_solver      a dae_solver for a compiled model, started from bgr_y0/bgr_yp0 and made
 *                     consistent
 *   build_rlc         the series RLC circuit used by several tests */
#ifndef BG_TESTS_BGTEST_H
#define BG_TESTS_BGTEST_H

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bgr_elements.h"
#include "bgr_model.h"
#include "modeltest.h"
#include "tap.h"

#define BGT_PATH 256

TAP_PRINTF(2, 3) static int vid(const bgr_model *m, const char *fmt, ...)
{
    char path[BGT_PATH];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(path, sizeof path, fmt, ap);
    va_end(ap);
    int v = bgr_find_var(m, path);
    if (v < 0) tap_diag("no variable named %s", path);
    return v;
}

TAP_PRINTF(2, 3) static int eqid(const bgr_model *m, const char *fmt, ...)
{
    char path[BGT_PATH];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(path, sizeof path, fmt, ap);
    va_end(ap);
    int e = bgr_find_eq(m, path);
    if (e < 0) tap_diag("no equation named %s", path);
    return e;
}

/* ---- bond registry ---- */

typedef struct reg_end {
    int elem, port, sign, d;
    char path[BGT_PATH]; /* full path of the bond: component path / bond name */
} reg_end;

typedef struct bond_reg {
    reg_end *end;
    int n, cap;
} bond_reg;

TAP_UNUSED static void reg_free(bond_reg *r)
{
    free(r->end);
    r->end = NULL;
    r->n = r->cap = 0;
}

static void reg_push(bond_reg *r, int elem, int port, int sign, int d, const char *path)
{
    if (r->n == r->cap) {
        int nc = r->cap ? 2 * r->cap : 64;
        reg_end *p = realloc(r->end, (size_t)nc * sizeof *p);
        if (!p) return;
        r->end = p;
        r->cap = nc;
    }
    reg_end *e = &r->end[r->n++];
    e->elem = elem;
    e->port = port;
    e->sign = sign;
    e->d = d;
    snprintf(e->path, sizeof e->path, "%s", path);
}

/* bgr_bond with default labels, recorded in r (r may be NULL). Returns the bond id. */
TAP_UNUSED static int reg_bond(bgr_model *m, bond_reg *r, bgr_comp c, const char *name, int d,
                               bgr_port a, bgr_port b)
{
    int id = bgr_bond(m, c, name, d, a, b, NULL, NULL);
    if (id < 0) {
        tap_diag("bgr_bond %s failed: %s", name, bgr_model_error(m)->message);
        return id;
    }
    if (r) {
        char path[BGT_PATH];
        snprintf(path, sizeof path, "%s/%s", bgr_component_path(m, c), name);
        reg_push(r, a.elem, a.port, -1, d, path);
        reg_push(r, b.elem, b.port, +1, d, path);
    }
    return id;
}

TAP_UNUSED static bgr_port P(const bgr_model *m, int elem, int port)
{
    return bgr_port_of(m, elem, port);
}

/* Variable id of effort (flow = 0) or flow (flow = 1) component i of a registered bond. */
static int reg_var(const bgr_model *m, const reg_end *e, int flow, int i)
{
    if (e->d == 1) return vid(m, "%s/%s", e->path, flow ? "f" : "e");
    return vid(m, "%s/%s%d", e->path, flow ? "f" : "e", i);
}

/* Oriented power into element elem: sum over its ports and components of s e f; *scale gets the
 * sum of |e f|. *nports the number of ports found. */
TAP_UNUSED static double power_sum(const bgr_model *m, const bond_reg *r, int elem, const double *y,
                                   double *scale, int *nports)
{
    double sum = 0, sc = 0;
    int np = 0;
    for (int k = 0; k < r->n; k++) {
        const reg_end *e = &r->end[k];
        if (e->elem != elem) continue;
        np++;
        for (int i = 0; i < e->d; i++) {
            double pe = at(y, reg_var(m, e, 0, i)) * at(y, reg_var(m, e, 1, i));
            sum += e->sign * pe;
            sc += fabs(pe);
        }
    }
    if (scale) *scale = sc;
    if (nports) *nports = np;
    return sum;
}

/* ---- solving ---- */

/* A solver for the compiled model m, started at t0 from bgr_y0/bgr_yp0 and made consistent.
 * roots (may be NULL) adds one event function. NULL on failure (diagnostic printed). */
TAP_UNUSED static dae_solver *start_solver(bgr_model *m, double rtol, double atol, double t0,
                                           dae_root_fn roots)
{
    dae_options o;
    dae_options_default(&o);
    o.rtol = rtol;
    o.atol = atol;
    return model_solver(m, &o, roots, t0);
}

/* A point that satisfies the element equations to rounding near the solver's output (t, y, yp):
 * a fresh solver started there and made consistent (the integrator itself satisfies the
 * algebraic equations only to its Newton tolerance). y, yp are overwritten; returns BG_OK. */
TAP_UNUSED static int polish(bgr_model *m, double t, double *y, double *yp)
{
    dae_problem p;
    dae_options o;
    bg_error err;
    memset(&err, 0, sizeof err);
    if (bgr_dae_problem(m, &p) != BG_OK) return BG_ERR_ARGUMENT;
    dae_options_default(&o);
    o.rtol = 1e-10;
    o.atol = 1e-12;
    dae_solver *s = dae_create(&p, &o, &err);
    if (!s) return BG_ERR_MEMORY;
    int r = dae_init(s, t, y, yp);
    if (r == BG_OK) r = dae_consistent_init(s);
    if (r == BG_OK) r = dae_dense(s, t, y, yp);
    if (r != BG_OK) tap_diag("polish at t = %g: %s", t, dae_get_error(s)->message);
    dae_free(&s);
    return r;
}

/* ---- the series RLC circuit ----
 * Se(V) -> 1-junction J (current i) -> I(L), C(stiffness 1/Cap); the resistor's bond points
 * from R to J (reversed), which must not change the physics: L q'' + R q' + q/Cap = V. */
typedef struct rlc_ids {
    int V, J, L, C, R;
} rlc_ids;

TAP_UNUSED static bgr_model *build_rlc(double V, double L, double Cap, double R, bond_reg *reg,
                                       rlc_ids *ids)
{
    bgr_model *m = bgr_model_create("rlc");
    if (!m) return NULL;
    rlc_ids k;
    k.V = bgr_Se(m, 0, "V", 1, &V);
    k.J = bgr_one(m, 0, "J", 4, 1);
    k.L = bgr_I(m, 0, "L", 1, L);
    k.C = bgr_C(m, 0, "C", 1, 1.0 / Cap);
    k.R = bgr_R(m, 0, "R", 1, R);
    if (k.V < 0 || k.J < 0 || k.L < 0 || k.C < 0 || k.R < 0 ||
        reg_bond(m, reg, 0, "bse", 1, P(m, k.V, 0), P(m, k.J, 0)) < 0 ||
        reg_bond(m, reg, 0, "bL", 1, P(m, k.J, 1), P(m, k.L, 0)) < 0 ||
        reg_bond(m, reg, 0, "bC", 1, P(m, k.J, 2), P(m, k.C, 0)) < 0 ||
        reg_bond(m, reg, 0, "bR", 1, P(m, k.R, 0), P(m, k.J, 3)) < 0) {
        tap_diag("building the RLC model failed: %s", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return NULL;
    }
    if (ids) *ids = k;
    return m;
}

#endif
