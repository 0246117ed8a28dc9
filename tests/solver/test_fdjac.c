/* Unit tests of bg_fdjac: column colouring (validity checked independently, greedy order,
 * p+q+1 groups on banded patterns), coloured forward-difference Jacobians against analytic
 * derivatives (values, step formula, number of function calls, callback failures) and the
 * Jacobian checker (correct, wrong and missing entries). */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bg_fdjac.h"
#include "tap.h"
#include "testutil.h"

/* ---- helpers ---- */

/* Full band: A(i,j) present iff -q <= j - i <= p... i.e. i - j <= p (lower) and j - i <= q
 * (upper). */
static sp_csc *band_pattern(int n, int p, int q)
{
    unsigned char *mask = calloc((size_t)n * n, 1);
    int i, j;
    sp_csc *A;
    for (j = 0; j < n; j++)
        for (i = 0; i < n; i++)
            if (i - j <= p && j - i <= q) mask[i + (size_t)j * n] = 1;
    A = tu_csc_from_mask(n, n, mask, NULL);
    free(mask);
    return A;
}

/* Value stored at (i,j) in A, or 0 if absent; *found tells which. */
static double entry(const sp_csc *A, int i, int j, int *found)
{
    int p;
    for (p = A->colptr[j]; p < A->colptr[j + 1]; p++)
        if (A->rowind[p] == i) {
            if (found) *found = 1;
            return A->val[p];
        }
    if (found) *found = 0;
    return 0.0;
}

/* Greedy colouring in natural column order computed here: column j takes the smallest group
 * used by none of the earlier columns sharing a row with it. Returns the number of groups. */
static int my_greedy(const sp_csc *P, int *group)
{
    int m = P->nrow, n = P->ncol, i, j, p, q, ng = 0;
    /* Row-wise lists of columns. */
    int *rcnt = calloc((size_t)m + 1, sizeof(int)), *rcol = malloc(sizeof(int) * (P->nnz + 1));
    int *fill = malloc(sizeof(int) * (m + 1)), *forbid = malloc(sizeof(int) * (n + 1));
    for (p = 0; p < P->nnz; p++)
        rcnt[P->rowind[p] + 1]++;
    for (i = 0; i < m; i++)
        rcnt[i + 1] += rcnt[i];
    memcpy(fill, rcnt, sizeof(int) * m);
    for (j = 0; j < n; j++)
        for (p = P->colptr[j]; p < P->colptr[j + 1]; p++)
            rcol[fill[P->rowind[p]]++] = j;
    for (j = 0; j <= n; j++)
        forbid[j] = -1;
    for (j = 0; j < n; j++) {
        int g = 0;
        for (p = P->colptr[j]; p < P->colptr[j + 1]; p++) {
            i = P->rowind[p];
            for (q = rcnt[i]; q < rcnt[i + 1]; q++)
                if (rcol[q] < j) forbid[group[rcol[q]]] = j;
        }
        while (forbid[g] == j)
            g++;
        group[j] = g;
        if (g + 1 > ng) ng = g + 1;
    }
    free(rcnt);
    free(rcol);
    free(fill);
    free(forbid);
    return ng;
}

/* Independent check of a colouring: consistent arrays, and no two columns of one group share a
 * row. Writes the first fault to why. */
static int my_colouring_ok(const sp_colouring *c, const sp_csc *P, char *why, size_t nwhy)
{
    int n = P->ncol, g, j, k, p;
    int *stamp, *seen;
    int ok = 1;
    if (c->ncol != n) {
        snprintf(why, nwhy, "ncol %d != %d", c->ncol, n);
        return 0;
    }
    if (n > 0 && (c->ngroups < 1 || c->ngroups > n)) {
        snprintf(why, nwhy, "ngroups %d out of [1,%d]", c->ngroups, n);
        return 0;
    }
    for (j = 0; j < n; j++)
        if (c->group[j] < 0 || c->group[j] >= c->ngroups) {
            snprintf(why, nwhy, "group[%d] = %d out of range", j, c->group[j]);
            return 0;
        }
    if (c->gptr[0] != 0 || c->gptr[c->ngroups] != n) {
        snprintf(why, nwhy, "gptr[0] = %d, gptr[ngroups] = %d", c->gptr[0], c->gptr[c->ngroups]);
        return 0;
    }
    seen = calloc((size_t)n + 1, sizeof(int));
    for (g = 0; g < c->ngroups && ok; g++) {
        if (c->gptr[g + 1] <= c->gptr[g]) {
            snprintf(why, nwhy, "group %d empty or gptr decreasing", g);
            ok = 0;
            break;
        }
        for (k = c->gptr[g]; k < c->gptr[g + 1]; k++) {
            j = c->gcols[k];
            if (j < 0 || j >= n || seen[j] || c->group[j] != g) {
                snprintf(why, nwhy, "gcols[%d] = %d inconsistent with group %d", k, j, g);
                ok = 0;
                break;
            }
            seen[j] = 1;
        }
    }
    free(seen);
    if (!ok) return 0;
    /* Structural orthogonality, from group[] alone. */
    stamp = malloc(sizeof(int) * (P->nrow + 1));
    for (g = 0; g < c->ngroups && ok; g++) {
        for (k = 0; k < P->nrow; k++)
            stamp[k] = -1;
        for (j = 0; j < n && ok; j++) {
            if (c->group[j] != g) continue;
            for (p = P->colptr[j]; p < P->colptr[j + 1]; p++) {
                int i = P->rowind[p];
                if (stamp[i] >= 0) {
                    snprintf(why, nwhy, "columns %d and %d of group %d share row %d", stamp[i], j,
                             g, i);
                    ok = 0;
                    break;
                }
                stamp[i] = j;
            }
        }
    }
    free(stamp);
    return ok;
}

/* ---- colouring ---- */

static void test_colour_random(tap_rng *r, int m, int n, double density)
{
    sp_csc *P = tu_random_csc(r, m, n, density, 0.5, 2.0, 1);
    sp_colouring *c = P ? sp_colour(P) : NULL;
    int *mine = malloc(sizeof(int) * (n + 1));
    char why[160] = "";
    int ng, j, same = 1;
    if (!tap_ok(c != NULL, "colour random %dx%d d=%g: sp_colour", m, n, density)) goto out;
    if (!tap_ok(my_colouring_ok(c, P, why, sizeof why),
                "colour random %dx%d d=%g: valid by own check (%d groups)", m, n, density,
                c->ngroups))
        tap_diag("%s", why);
    else {
        tap_ok(sp_colouring_valid(c, P) == 1, "colour random %dx%d d=%g: sp_colouring_valid", m, n,
               density);
        ng = my_greedy(P, mine);
        for (j = 0; j < n; j++)
            same = same && mine[j] == c->group[j];
        if (!tap_ok(ng == c->ngroups && same,
                    "colour random %dx%d d=%g: greedy natural-order colouring (%d groups)", m, n,
                    density, ng))
            tap_diag("own greedy: %d groups, sp_colour: %d", ng, c->ngroups);
    }
out:
    sp_colouring_free(&c);
    sp_csc_free(&P);
    free(mine);
}

static void test_colour_special(void)
{
    sp_csc *D = band_pattern(7, 0, 0), *F = band_pattern(6, 5, 5), *Z = sp_csc_alloc(4, 5, 0);
    sp_colouring *c;
    char why[160] = "";
    int *grp = malloc(sizeof(int) * 6), *gptr = malloc(sizeof(int) * 7);
    int *gcols = malloc(sizeof(int) * 6), j;
    sp_colouring fake;

    c = sp_colour(D);
    tap_ok(c && c->ngroups == 1 && my_colouring_ok(c, D, why, sizeof why),
           "colour: diagonal 7x7 has 1 group");
    sp_colouring_free(&c);
    tap_ok(c == NULL, "sp_colouring_free sets NULL");
    c = sp_colour(F);
    tap_ok(c && c->ngroups == 6 && my_colouring_ok(c, F, why, sizeof why),
           "colour: full 6x6 has 6 groups");
    sp_colouring_free(&c);
    c = Z ? sp_colour(Z) : NULL;
    tap_ok(c && c->ngroups == 1 && my_colouring_ok(c, Z, why, sizeof why),
           "colour: 4x5 without entries has 1 group");
    sp_colouring_free(&c);

    /* Hand-made colourings for sp_colouring_valid. */
    fake.ncol = 6;
    fake.group = grp;
    fake.gptr = gptr;
    fake.gcols = gcols;
    fake.ngroups = 1; /* all columns together: wrong for the full matrix */
    gptr[0] = 0;
    gptr[1] = 6;
    for (j = 0; j < 6; j++) {
        grp[j] = 0;
        gcols[j] = j;
    }
    tap_ok(F && sp_colouring_valid(&fake, F) == 0,
           "sp_colouring_valid: one group on full 6x6 -> 0");
    fake.ngroups = 6; /* one column per group: valid */
    for (j = 0; j < 6; j++) {
        grp[j] = j;
        gptr[j + 1] = j + 1;
    }
    tap_ok(F && sp_colouring_valid(&fake, F) == 1, "sp_colouring_valid: one column per group -> 1");
    /* Columns 0 and 2 of a tridiagonal 6x6 share row 1. */
    sp_csc_free(&F);
    F = band_pattern(6, 1, 1);
    fake.ngroups = 3;
    {
        static const int g[] = {0, 1, 0, 2, 1, 2}, gp[] = {0, 2, 4, 6}, gc[] = {0, 2, 1, 4, 3, 5};
        memcpy(grp, g, sizeof g);
        memcpy(gptr, gp, sizeof gp);
        memcpy(gcols, gc, sizeof gc);
    }
    tap_ok(F && sp_colouring_valid(&fake, F) == 0,
           "sp_colouring_valid: tridiagonal, columns 0 and 2 together -> 0");
    {
        static const int g[] = {0, 1, 2, 0, 1, 2}, gp[] = {0, 2, 4, 6}, gc[] = {0, 3, 1, 4, 2, 5};
        memcpy(grp, g, sizeof g);
        memcpy(gptr, gp, sizeof gp);
        memcpy(gcols, gc, sizeof gc);
    }
    tap_ok(F && sp_colouring_valid(&fake, F) == 1, "sp_colouring_valid: tridiagonal, j mod 3 -> 1");

    sp_csc_free(&D);
    sp_csc_free(&F);
    sp_csc_free(&Z);
    free(grp);
    free(gptr);
    free(gcols);
}

static void test_colour_band(int n, int p, int q)
{
    sp_csc *P = band_pattern(n, p, q);
    sp_colouring *c = P ? sp_colour(P) : NULL;
    char why[160] = "";
    int j, mod = 1;
    if (!tap_ok(c != NULL, "band n=%d p=%d q=%d: sp_colour", n, p, q)) goto out;
    if (!tap_ok(c->ngroups == p + q + 1, "band n=%d p=%d q=%d: %d groups == p+q+1", n, p, q,
                c->ngroups))
        tap_diag("want %d", p + q + 1);
    tap_ok(my_colouring_ok(c, P, why, sizeof why) && sp_colouring_valid(c, P) == 1,
           "band n=%d p=%d q=%d: valid %s", n, p, q, why);
    for (j = 0; j < n; j++)
        mod = mod && c->group[j] == j % (p + q + 1);
    tap_ok(mod, "band n=%d p=%d q=%d: group[j] == j mod (p+q+1)", n, p, q);
out:
    sp_colouring_free(&c);
    sp_csc_free(&P);
}

/* ---- a nonlinear chain function with bandwidths p = q = 2 ----
 * f_i = x_{i-1} - 2 x_i + x_{i+1} + h2 exp(x_i) + sin(x_i x_{i+1}) + x_{i+2}^2/2 + x_{i-2}^3/2 */
typedef struct chain {
    int n;
    double h2;
    long calls;
    long fail_at; /* call number (0-based) that fails, -1: never */
    int fail_status;
} chain;

static int chain_f(void *user, const double *x, double *f)
{
    chain *c = user;
    int n = c->n, i;
    long call = c->calls++;
    if (call == c->fail_at) return c->fail_status;
    for (i = 0; i < n; i++) {
        double v = -2.0 * x[i] + c->h2 * exp(x[i]);
        if (i > 0) v += x[i - 1];
        if (i + 1 < n) v += x[i + 1] + sin(x[i] * x[i + 1]);
        if (i + 2 < n) v += 0.5 * x[i + 2] * x[i + 2];
        if (i >= 2) v += 0.5 * x[i - 2] * x[i - 2] * x[i - 2];
        f[i] = v;
    }
    return 0;
}

/* Analytic dF_i/dx_j. */
static double chain_d(const chain *c, const double *x, int i, int j)
{
    int n = c->n;
    if (j == i - 2) return 1.5 * x[i - 2] * x[i - 2];
    if (j == i - 1) return 1.0;
    if (j == i) {
        double v = -2.0 + c->h2 * exp(x[i]);
        if (i + 1 < n) v += cos(x[i] * x[i + 1]) * x[i + 1];
        return v;
    }
    if (j == i + 1) return 1.0 + cos(x[i] * x[i + 1]) * x[i];
    if (j == i + 2) return x[i + 2];
    return 0.0;
}

/* Analytic Jacobian on the band pattern, optionally without entry (skip_i, skip_j). */
static sp_csc *chain_jac(const chain *c, const double *x, int skip_i, int skip_j)
{
    int n = c->n, i, j;
    unsigned char *mask = calloc((size_t)n * n, 1);
    double *vals = calloc((size_t)n * n, sizeof(double));
    sp_csc *J;
    for (j = 0; j < n; j++)
        for (i = 0; i < n; i++)
            if (abs(i - j) <= 2 && !(i == skip_i && j == skip_j)) {
                mask[i + (size_t)j * n] = 1;
                vals[i + (size_t)j * n] = chain_d(c, x, i, j);
            }
    J = tu_csc_from_mask(n, n, mask, vals);
    free(mask);
    free(vals);
    return J;
}

static void test_fdjac_chain(tap_rng *r, int n)
{
    chain c = {n, 1.0 / ((n + 1.0) * (n + 1.0)), 0, -1, 0};
    double *x = malloc(sizeof(double) * n), *x0 = malloc(sizeof(double) * n);
    double *f0 = malloc(sizeof(double) * n);
    sp_csc *P = band_pattern(n, 2, 2), *J = NULL;
    sp_fdjac *d = NULL;
    int i, j, p, ok, rc, ng, want_ng = n < 5 ? n : 5;
    long before;
    double worst = 0.0;

    for (i = 0; i < n; i++) {
        x[i] = tap_rng_range(r, 0.4, 0.9) * (tap_rng_unif(r) < 0.3 ? -1.0 : 1.0);
        x0[i] = x[i];
    }
    d = P ? sp_fdjac_create(P) : NULL;
    if (!tap_ok(d != NULL, "fdjac chain n=%d: sp_fdjac_create", n)) goto out;
    ng = sp_fdjac_ngroups(d);
    tap_ok(ng == want_ng, "fdjac chain n=%d: %d groups (want %d)", n, ng, want_ng);
    tap_ok(sp_fdjac_calls(d) == 0, "fdjac chain n=%d: no calls before eval", n);
    J = sp_csc_copy(P);
    if (!J) goto out;
    for (p = 0; p < J->nnz; p++)
        J->val[p] = NAN;
    chain_f(&c, x, f0);
    before = c.calls;
    rc = sp_fdjac_eval(d, chain_f, &c, x, f0, NULL, J);
    tap_ok(rc == 0, "fdjac chain n=%d: eval returns 0 (got %d)", n, rc);
    tap_ok(c.calls - before == ng, "fdjac chain n=%d: f called once per group (%ld calls)", n,
           c.calls - before);
    tap_ok(sp_fdjac_calls(d) == ng, "fdjac chain n=%d: sp_fdjac_calls == %d (got %ld)", n, ng,
           sp_fdjac_calls(d));
    tap_ok(memcmp(x, x0, sizeof(double) * n) == 0, "fdjac chain n=%d: x unchanged", n);
    tap_ok(sp_csc_same_pattern(J, P), "fdjac chain n=%d: J keeps its pattern", n);
    ok = 1;
    for (j = 0; j < n; j++)
        for (p = J->colptr[j]; p < J->colptr[j + 1]; p++) {
            double want = chain_d(&c, x, J->rowind[p], j);
            double e = fabs(J->val[p] - want) / fmax(1.0, fabs(want));
            if (!(e <= 1e-6)) {
                if (ok)
                    tap_diag("J(%d,%d) = %.10g, analytic %.10g", J->rowind[p], j, J->val[p], want);
                ok = 0;
            }
            if (e > worst) worst = e;
        }
    tap_ok(ok, "fdjac chain n=%d: matches analytic Jacobian to 1e-6 (worst %.2e)", n, worst);
    /* Second evaluation at another point. */
    for (i = 0; i < n; i++)
        x[i] = x0[i] = tap_rng_range(r, -1.0, 1.0);
    chain_f(&c, x, f0);
    before = c.calls;
    rc = sp_fdjac_eval(d, chain_f, &c, x, f0, NULL, J);
    ok = rc == 0 && c.calls - before == ng && sp_fdjac_calls(d) == 2L * ng;
    for (j = 0; j < n; j++)
        for (p = J->colptr[j]; p < J->colptr[j + 1]; p++) {
            double want = chain_d(&c, x, J->rowind[p], j);
            if (!(fabs(J->val[p] - want) <= 1e-6 * fmax(1.0, fabs(want)))) ok = 0;
        }
    tap_ok(ok, "fdjac chain n=%d: second eval right, calls add up to %d", n, 2 * ng);

    /* A failing callback: its status is returned. */
    c.fail_at = c.calls + 2;
    c.fail_status = 1;
    rc = sp_fdjac_eval(d, chain_f, &c, x, f0, NULL, J);
    tap_ok(rc == 1, "fdjac chain n=%d: recoverable callback failure returned (got %d)", n, rc);
    c.fail_at = c.calls + 1;
    c.fail_status = -2;
    rc = sp_fdjac_eval(d, chain_f, &c, x, f0, NULL, J);
    tap_ok(rc == -2, "fdjac chain n=%d: fatal callback status returned (got %d)", n, rc);
out:
    sp_fdjac_free(&d);
    tap_ok(d == NULL, "sp_fdjac_free sets NULL");
    sp_csc_free(&P);
    sp_csc_free(&J);
    free(x);
    free(x0);
    free(f0);
}

/* ---- a rectangular function on a random pattern: f_i = sum_j a_ij sin(x_j + 0.1 i) ---- */
typedef struct sinfun {
    const sp_csc *A;
    long calls;
} sinfun;

static int sinfun_f(void *user, const double *x, double *f)
{
    sinfun *s = user;
    const sp_csc *A = s->A;
    int i, j, p;
    s->calls++;
    for (i = 0; i < A->nrow; i++)
        f[i] = 0.0;
    for (j = 0; j < A->ncol; j++)
        for (p = A->colptr[j]; p < A->colptr[j + 1]; p++) {
            i = A->rowind[p];
            f[i] += A->val[p] * sin(x[j] + 0.1 * i);
        }
    return 0;
}

static void test_fdjac_rect(tap_rng *r, int m, int n, double density)
{
    sp_csc *A = tu_random_csc(r, m, n, density, 0.5, 2.0, 1), *J = NULL;
    sinfun s = {A, 0};
    double *x = malloc(sizeof(double) * n), *f0 = malloc(sizeof(double) * m);
    int *grp = malloc(sizeof(int) * (n + 1));
    sp_fdjac *d = A ? sp_fdjac_create(A) : NULL;
    int j, p, ok = 1, rc, ng;
    if (!tap_ok(d != NULL, "fdjac random %dx%d: create", m, n)) goto out;
    ng = my_greedy(A, grp);
    tap_ok(sp_fdjac_ngroups(d) == ng, "fdjac random %dx%d: %d groups (own greedy %d)", m, n,
           sp_fdjac_ngroups(d), ng);
    J = sp_csc_copy(A);
    for (p = 0; p < J->nnz; p++)
        J->val[p] = NAN;
    for (j = 0; j < n; j++)
        x[j] = tap_rng_range(r, -2.0, 2.0);
    sinfun_f(&s, x, f0);
    s.calls = 0;
    rc = sp_fdjac_eval(d, sinfun_f, &s, x, f0, NULL, J);
    tap_ok(rc == 0 && s.calls == sp_fdjac_ngroups(d) && sp_fdjac_calls(d) == s.calls,
           "fdjac random %dx%d: one call per group (%ld)", m, n, s.calls);
    for (j = 0; j < n; j++)
        for (p = J->colptr[j]; p < J->colptr[j + 1]; p++) {
            double want = A->val[p] * cos(x[j] + 0.1 * A->rowind[p]);
            if (!(fabs(J->val[p] - want) <= 1e-6 * fmax(1.0, fabs(want)))) {
                if (ok) tap_diag("J(%d,%d) = %.10g, want %.10g", A->rowind[p], j, J->val[p], want);
                ok = 0;
            }
        }
    tap_ok(ok, "fdjac random %dx%d: matches analytic Jacobian to 1e-6", m, n);
out:
    sp_fdjac_free(&d);
    sp_csc_free(&A);
    sp_csc_free(&J);
    free(x);
    free(f0);
    free(grp);
}

/* ---- the step: h_j = sqrt(eps) max(|x_j|, typ_j), sign of x_j ----
 * f_j = (x_j - c_j)^2 with x_j - c_j small: the forward difference is 2 (x_j - c_j) + h_j, so the
 * step can be read off the result. */
typedef struct quad {
    int n;
    const double *c;
} quad;

static int quad_f(void *user, const double *x, double *f)
{
    const quad *q = user;
    int j;
    for (j = 0; j < q->n; j++)
        f[j] = (x[j] - q->c[j]) * (x[j] - q->c[j]);
    return 0;
}

static void test_fdjac_step(void)
{
    enum { N = 7 };
    static const double x[N] = {0.5, -0.5, 5.0, -3.0, 2.0, 1e-3, -1e-3};
    static const double c[N] = {0.499, -0.501, 4.999, -3.001, 2.001, 0.0, 0.0};
    static const double typ[N] = {1.0, 1.0, 1.0, 1.0, 1e3, 1e4, 1e4};
    quad q = {N, c};
    sp_csc *P = band_pattern(N, 0, 0), *J = sp_csc_copy(P);
    sp_fdjac *d = sp_fdjac_create(P);
    double f0[N], se = sqrt(DBL_EPSILON);
    int t, j;
    if (!tap_ok(d && J, "fdjac step: create")) goto out;
    tap_ok(sp_fdjac_ngroups(d) == 1, "fdjac step: diagonal pattern has 1 group");
    quad_f(&q, x, f0);
    for (t = 0; t < 2; t++) {
        const double *ty = t ? typ : NULL;
        int rc = sp_fdjac_eval(d, quad_f, &q, x, f0, ty, J);
        tap_ok(rc == 0, "fdjac step (typ %s): eval returns 0", t ? "given" : "NULL");
        for (j = 0; j < N; j++) {
            double s = fmax(fabs(x[j]), ty ? ty[j] : 1.0);
            double h = (x[j] < 0 ? -1.0 : 1.0) * se * s;
            double dlt = x[j] - c[j];
            double got = J->val[j] - 2.0 * dlt;
            tap_close(got, h, 1e-2, 0.0,
                      "fdjac step (typ %s): x=%g typ=%g: J - f' == h = %s sqrt(eps) * %g",
                      t ? "given" : "NULL", x[j], ty ? ty[j] : 1.0, x[j] < 0 ? "-" : "+", s);
        }
    }
    tap_ok(sp_fdjac_calls(d) == 2, "fdjac step: 2 calls for 2 evals of 1 group");
out:
    sp_fdjac_free(&d);
    sp_csc_free(&P);
    sp_csc_free(&J);
}

/* ---- Jacobian checker ---- */

static int check_worst_consistent(const sp_jac_entry *w, int nw, const sp_csc *J, const chain *c,
                                  const double *x, double floor_, double max_err)
{
    int k;
    if (nw > 0 && w[0].err != max_err) return 0;
    for (k = 0; k < nw; k++) {
        int found;
        double a = entry(J, w[k].row, w[k].col, &found);
        double truth = chain_d(c, x, w[k].row, w[k].col);
        if (k > 0 && w[k].err > w[k - 1].err) return 0;
        if (w[k].analytic != a) return 0;
        if (!(fabs(w[k].fd - truth) <= 1e-6 * fmax(1.0, fabs(truth)))) return 0;
        if (!(fabs(w[k].err - fabs(w[k].analytic - w[k].fd) / (fabs(w[k].fd) + floor_)) <=
              1e-9 * w[k].err + 1e-15))
            return 0;
    }
    return 1;
}

static void test_jac_check(tap_rng *r, int n)
{
    chain c = {n, 1.0 / ((n + 1.0) * (n + 1.0)), 0, -1, 0};
    double *x = malloc(sizeof(double) * n), max_err = -1.0, floor_ = 1e-6, tol = 1e-6;
    sp_jac_entry worst[5];
    sp_csc *J = NULL, *Jm = NULL;
    int i, rc, pos;
    double truth;

    for (i = 0; i < n; i++)
        x[i] = tap_rng_range(r, 0.4, 0.9) * (i % 3 == 1 ? -1.0 : 1.0);
    J = chain_jac(&c, x, -1, -1);
    if (!J) goto out;

    /* Correct Jacobian. */
    memset(worst, 0, sizeof worst);
    rc = sp_jac_check(J, chain_f, &c, n, x, floor_, tol, worst, 5, &max_err);
    tap_ok(rc == 0, "jac_check n=%d: correct Jacobian -> 0 entries above tol (got %d)", n, rc);
    tap_ok(max_err >= 0.0 && max_err < 1e-6, "jac_check n=%d: correct Jacobian max_err %.2e < 1e-6",
           n, max_err);
    tap_ok(check_worst_consistent(worst, 5, J, &c, x, floor_, max_err),
           "jac_check n=%d: worst[] sorted, consistent with J, fd and err formula", n);
    max_err = -1.0;
    rc = sp_jac_check(J, chain_f, &c, n, x, floor_, tol, NULL, 0, &max_err);
    tap_ok(rc == 0 && max_err >= 0.0 && max_err < 1e-6, "jac_check n=%d: nworst = 0 works", n);

    /* One wrong entry (5,6): d f_5 / d x_6. */
    pos = sp_csc_find(J, 5, 6);
    truth = J->val[pos];
    J->val[pos] += 0.37;
    memset(worst, 0, sizeof worst);
    rc = sp_jac_check(J, chain_f, &c, n, x, floor_, tol, worst, 5, &max_err);
    tap_ok(rc == 1, "jac_check n=%d: one wrong entry -> 1 entry above tol (got %d)", n, rc);
    if (!tap_ok(worst[0].row == 5 && worst[0].col == 6, "jac_check n=%d: worst entry is (5,6)", n))
        tap_diag("reported (%d,%d)", worst[0].row, worst[0].col);
    tap_ok(worst[0].analytic == truth + 0.37, "jac_check n=%d: worst.analytic is the wrong value",
           n);
    tap_close(worst[0].fd, truth, 1e-6, 0.0, "jac_check n=%d: worst.fd is the true derivative", n);
    tap_close(worst[0].err, 0.37 / (fabs(truth) + floor_), 1e-6, 0.0,
              "jac_check n=%d: worst.err == |a - fd| / (|fd| + floor)", n);
    tap_ok(max_err == worst[0].err && worst[1].err < tol, "jac_check n=%d: max_err == worst[0].err",
           n);
    J->val[pos] = truth;

    /* A small relative error (1e-3) on (7,5), a d x_{i-2} term. */
    pos = sp_csc_find(J, 7, 5);
    truth = J->val[pos];
    J->val[pos] *= 1.001;
    rc = sp_jac_check(J, chain_f, &c, n, x, floor_, tol, worst, 5, &max_err);
    tap_ok(rc == 1 && worst[0].row == 7 && worst[0].col == 5,
           "jac_check n=%d: 1e-3 relative error found at (7,5) (got rc %d at (%d,%d))", n, rc,
           worst[0].row, worst[0].col);
    tap_close(max_err, 1e-3, 1e-3, 0.0, "jac_check n=%d: its err is 1e-3", n);
    /* The count is of entries with err > tol: tol just below and just above that error. */
    rc = sp_jac_check(J, chain_f, &c, n, x, floor_, 0.8e-3, NULL, 0, &max_err);
    tap_ok(rc == 1, "jac_check n=%d: err 1e-3 > tol 8e-4 counted (got %d)", n, rc);
    rc = sp_jac_check(J, chain_f, &c, n, x, floor_, 1.2e-3, NULL, 0, &max_err);
    tap_ok(rc == 0, "jac_check n=%d: err 1e-3 < tol 1.2e-3 not counted (got %d)", n, rc);
    J->val[pos] = truth;

    /* Entry (8,10) missing from the analytic pattern. */
    Jm = chain_jac(&c, x, 8, 10);
    memset(worst, 0, sizeof worst);
    rc = sp_jac_check(Jm, chain_f, &c, n, x, floor_, tol, worst, 5, &max_err);
    tap_ok(rc == 1, "jac_check n=%d: one missing entry -> 1 entry above tol (got %d)", n, rc);
    if (!tap_ok(worst[0].row == 8 && worst[0].col == 10,
                "jac_check n=%d: missing entry (8,10) reported", n))
        tap_diag("reported (%d,%d)", worst[0].row, worst[0].col);
    tap_ok(worst[0].analytic == 0.0, "jac_check n=%d: missing entry has analytic == 0", n);
    tap_close(worst[0].fd, x[10], 1e-6, 0.0, "jac_check n=%d: missing entry fd == x_10", n);

    /* A fatal callback status. */
    c.fail_at = c.calls + 3;
    c.fail_status = -7;
    rc = sp_jac_check(J, chain_f, &c, n, x, floor_, tol, worst, 5, &max_err);
    tap_ok(rc < 0, "jac_check n=%d: fatal callback -> negative return (got %d)", n, rc);
    c.fail_at = -1;
out:
    sp_csc_free(&J);
    sp_csc_free(&Jm);
    free(x);
}

/* The checker on a rectangular Jacobian. */
static void test_jac_check_rect(tap_rng *r, int m, int n)
{
    sp_csc *A = tu_random_csc(r, m, n, 0.2, 0.5, 2.0, 1), *J = NULL;
    sinfun s = {A, 0};
    double *x = malloc(sizeof(double) * n), max_err = -1.0;
    sp_jac_entry worst[3];
    int j, p, rc;
    if (!A) goto out;
    for (j = 0; j < n; j++)
        x[j] = tap_rng_range(r, -1.0, 1.0);
    J = sp_csc_copy(A);
    for (j = 0; j < n; j++)
        for (p = J->colptr[j]; p < J->colptr[j + 1]; p++)
            J->val[p] = A->val[p] * cos(x[j] + 0.1 * J->rowind[p]);
    rc = sp_jac_check(J, sinfun_f, &s, m, x, 1e-6, 1e-6, worst, 3, &max_err);
    tap_ok(rc == 0 && max_err < 1e-6, "jac_check random %dx%d: correct -> 0 (rc %d, max_err %.2e)",
           m, n, rc, max_err);
    if (J->nnz > 0) {
        int q = J->nnz / 2, col = 0;
        while (J->colptr[col + 1] <= q)
            col++;
        J->val[q] = -J->val[q];
        rc = sp_jac_check(J, sinfun_f, &s, m, x, 1e-6, 1e-6, worst, 3, &max_err);
        tap_ok(rc == 1 && worst[0].row == J->rowind[q] && worst[0].col == col,
               "jac_check random %dx%d: sign error at (%d,%d) found (rc %d, at (%d,%d))", m, n,
               J->rowind[q], col, rc, worst[0].row, worst[0].col);
    }
out:
    sp_csc_free(&A);
    sp_csc_free(&J);
    free(x);
}

int main(void)
{
    tap_rng r = tap_rng_seed(0xfd1ac0ffeeull);
    static const int ns[] = {8, 13, 60, 200};
    static const int ps[] = {0, 1, 2, 4};
    static const int qs[] = {0, 1, 3};
    size_t a, b, k;

    test_colour_special();
    test_colour_random(&r, 1, 1, 1.0);
    test_colour_random(&r, 10, 10, 0.3);
    test_colour_random(&r, 30, 50, 0.1);
    test_colour_random(&r, 200, 100, 0.03);
    test_colour_random(&r, 100, 300, 0.02);
    test_colour_random(&r, 400, 400, 0.01);
    for (k = 0; k < sizeof ns / sizeof ns[0]; k++)
        for (a = 0; a < sizeof ps / sizeof ps[0]; a++)
            for (b = 0; b < sizeof qs / sizeof qs[0]; b++)
                if (ns[k] >= ps[a] + qs[b] + 1) test_colour_band(ns[k], ps[a], qs[b]);

    test_fdjac_chain(&r, 5);
    test_fdjac_chain(&r, 12);
    test_fdjac_chain(&r, 100);
    test_fdjac_rect(&r, 20, 35, 0.15);
    test_fdjac_rect(&r, 50, 30, 0.1);
    test_fdjac_step();

    test_jac_check(&r, 12);
    test_jac_check(&r, 40);
    test_jac_check_rect(&r, 15, 25);
    return tap_done();
}
