/* Tests of the IVP Test Set problems of the benchmark collection (bench/problems.h,
 * bp_testset_get): crank, pump, transamp, chemakzo and nand, against truths that do not come from
 * the solver: the published definitions (structure, kinds, scored components), central
 * differences, the published reference end values. What is asserted, for each problem:
 *   - the table entry: found by name, kinds equal dae_classify's on the declared patterns (a
 *     variable is differential iff its dF/dy' column is not empty), the scored components of the
 *     IVP Test Set (docs/testset.md), breakpoints ascending inside (t0, tend);
 *   - the analytic Jacobians dF/dy and dF/dy' against central differences (bp_check_jacobian) at
 *     (t0, y0, yp0) and at a perturbed point (plus, for pump, points in the other regions of the
 *     transistor charge model);
 *   - the initial values are consistent: F(t0, y0, yp0) is zero up to round-off relative to the
 *     size of the terms, and dae_consistent_init leaves them where they are; for crank, whose
 *     published values satisfy the algebraic rows only to about 1e-7, that dae_consistent_init
 *     takes the published values to a scaled residual <= 1e-10, next to the stored consistent set;
 *   - the solver (dae_create, dae_init, dae_consistent_init, dae_solve_to with t_stop = tend and
 *     the problem's breakpoints) reaches tend at rtol 1e-6 with mescd >= -log10(rtol) - 1.5, with
 *     two tolerance conventions: A, that of the IVP Test Set drivers (atol = rtol; pump: its
 *     per-component vector), and B, that of bench/ida_compare (atol = 1e-2 rtol). Where the
 *     bound is not met or the solver fails, the assertion says so and why (see the comments at
 *     the expectations table). scd, mescd, the index-2 components apart,
 *     steps and rejections are printed as TAP diagnostics. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bg_dae.h"
#include "bg_fdjac.h"
#include "bg_sparse.h"
#include "problems.h"
#include "tap.h"

#define MAXN 24
#define NPROB 5

static const char *const prob_names[NPROB] = {"crank", "pump", "transamp", "chemakzo", "nand"};

/* ---- 1. the table ---- */

static void test_table(void)
{
    tap_ok(bp_testset_count() == NPROB, "table: %d test-set problems", bp_testset_count());
    for (int q = 0; q < NPROB; q++) {
        const bp_problem *p = bp_find(prob_names[q]);
        int found = 0;
        for (int i = 0; i < bp_testset_count(); i++)
            found |= bp_testset_get(i) == p;
        if (!tap_ok(p && found && p->n <= MAXN, "table: %s found by name in the test-set table",
                    prob_names[q]))
            continue;
        /* kinds: as dae_classify finds them from the patterns, and DIFF iff dF/dy' column */
        sp_csc *jy = NULL, *jyp = NULL;
        int kind[MAXN], ok = p->patterns(&jy, &jyp) == 0, nalg2 = -1, diffok = 1, n2 = 0;
        if (ok) nalg2 = dae_classify(jy, jyp, kind);
        for (int j = 0; ok && j < p->n; j++) {
            ok = ok && kind[j] == p->kind[j];
            diffok = diffok && (p->kind[j] == DAE_DIFF) == (jyp->colptr[j + 1] > jyp->colptr[j]);
            n2 += p->kind[j] == DAE_ALG2;
        }
        tap_ok(ok && diffok && nalg2 == n2,
               "table: %s: kinds equal dae_classify's (%d index-2), differential iff y' appears",
               p->name, nalg2);
        sp_csc_free(&jy);
        sp_csc_free(&jyp);
        /* the scored components (docs/testset.md) */
        int sc = 1;
        for (int j = 0; j < p->n; j++) {
            int want = 1;
            if (!strcmp(p->name, "crank")) want = j < 7 || j >= 21;
            if (!strcmp(p->name, "pump")) want = j != 8;
            if (!strcmp(p->name, "nand")) want = j == 4;
            sc = sc && (p->scored ? p->scored[j] != 0 : 1) == want;
        }
        tap_ok(sc && p->yref && p->ref_source && p->names,
               "table: %s: reference (%s), names and scored components as in docs/testset.md",
               p->name, p->ref_source ? p->ref_source : "none");
        int bpok = 1;
        for (int k = 0; k < p->nbreakpoints; k++)
            bpok = bpok && p->breakpoints[k] > p->t0 && p->breakpoints[k] < p->tend &&
                   (k == 0 || p->breakpoints[k] > p->breakpoints[k - 1]);
        tap_ok(bpok, "table: %s: %d breakpoints ascending inside (t0, tend)", p->name,
               p->nbreakpoints);
    }
    const bp_problem *pu = bp_find("pump");
    /* pumpi.f: kinks of Vin at 50, 60, 110, 120 ns + k 120 ns; 40 in [0, 1200 ns], the last = tend
     */
    int ok = pu && pu->nbreakpoints == 39 && fabs(pu->breakpoints[0] - 50e-9) < 1e-20 &&
             fabs(pu->breakpoints[38] - 1190e-9) < 1e-20;
    for (int k = 0; ok && k < 39; k++) {
        static const double off[4] = {50e-9, 60e-9, 110e-9, 120e-9};
        ok = fabs(pu->breakpoints[k] - (off[k % 4] + (k / 4) * 120e-9)) < 1e-18;
    }
    tap_ok(ok, "table: pump: the 39 kinks of Vin inside (0, 1200 ns) (the 40th is tend)");
}

/* ---- 2. Jacobians ---- */

/* Typical magnitudes for components that are zero both at t0 and at tend. */
static double typical(const bp_problem *p, int k)
{
    if (!strcmp(p->name, "pump")) return k < 5 ? 1e-13 : (k < 8 ? 5.0 : 1e-3);
    return 1.0;
}

/* A perturbed point on the scale of the solution: y0 + 10 % of (|y0| + |yref|). */
static void perturbed(const bp_problem *p, double *y, double *yp)
{
    double yref[MAXN], T = p->tend - p->t0;
    bp_reference(p, yref);
    for (int k = 0; k < p->n; k++) {
        double sc = fabs(p->y0[k]) + fabs(yref[k]);
        if (sc == 0.0) sc = typical(p, k);
        y[k] = p->y0[k] + 0.1 * sin(k + 1.0) * sc;
        yp[k] = p->yp0[k] + 0.1 * sin(2.0 * k + 1.0) * (fabs(p->yp0[k]) + sc / T);
    }
}

/* Floor of the relative error (|analytic - fd| / (|fd| + floor)). crank: the rows of the elastic
 * coordinates hold stiffness terms K q of about 2e3 (E = 2e11, K up to 2e8) next to entries of
 * 1e-8, and central differences with steps of 6e-6 carry round-off of eps |F| / h ~ 1e-7 there
 * (measured differences up to 4e-9 on entries of 3e-5): with floor 1e-2, entries below 1e-2 are
 * compared absolutely to 1e-7, the larger ones relatively to 1e-5. (Offline, against central
 * differences in quadruple precision, every entry of crank's analytic dF/dy agreed to 2e-13.) */
static double jac_floor(const bp_problem *p)
{
    return !strcmp(p->name, "crank") ? 1e-2 : 1e-6;
}

static void check_jac(const bp_problem *p, double t, const double *y, const double *yp,
                      const char *where)
{
    double ey, eyp;
    int st = bp_check_jacobian(p, t, y, yp, jac_floor(p), &ey, &eyp);
    tap_ok(st == 0 && ey <= 1e-5 && eyp <= 1e-5,
           "jacobian: %s at %s: max rel err dF/dy %.2g, dF/dy' %.2g", p->name, where, ey, eyp);
}

static void test_jacobians(void)
{
    for (int q = 0; q < NPROB; q++) {
        const bp_problem *p = bp_find(prob_names[q]);
        double y[MAXN], yp[MAXN];
        check_jac(p, p->t0, p->y0, p->yp0, "(t0, y0, yp0)");
        perturbed(p, y, yp);
        check_jac(p, p->t0 + 0.37 * (p->tend - p->t0), y, yp, "a perturbed point");
    }
    /* pump: the perturbed point lies in region 2 of the charge model (vgb > vfb, ugs <= vte);
     * regions 3 (conducting; with ugdt > 0 and = 0), 3 with source and drain exchanged, and 1 */
    const bp_problem *p = bp_find("pump");
    static const double v[4][3] = {{10, 2, 4}, {5, 1, 6}, {10, 4, 2}, {-2, 0.5, 0.3}};
    static const char *const what[4] = {"region 3", "region 3 with ugdt = 0",
                                        "region 3, source and drain exchanged", "region 1"};
    for (int r = 0; r < 4; r++) {
        double y[9], yp[9];
        perturbed(p, y, yp);
        y[5] = v[r][0], y[6] = v[r][1], y[7] = v[r][2];
        check_jac(p, 0.55e-7, y, yp, what[r]);
    }
}

/* ---- 3. initial values ---- */

/* max_i |F_i| / s_i with s_i = sum_j |dF_i/dy_j y_j| + |dF_i/dy'_j y'_j| (the size of the terms;
 * exact for residuals linear in y, y'); 0 where F_i = 0. */
static double scaled_residual(const bp_problem *p, double t, const double *y, const double *yp)
{
    sp_csc *jy = NULL, *jyp = NULL;
    double F[MAXN], s[MAXN], r = INFINITY;
    if (p->patterns(&jy, &jyp) == 0 && p->jac(NULL, t, y, yp, jy, jyp) == 0 &&
        p->res(NULL, t, y, yp, F) == 0) {
        memset(s, 0, sizeof s);
        for (int j = 0; j < p->n; j++) {
            for (int k = jy->colptr[j]; k < jy->colptr[j + 1]; k++)
                s[jy->rowind[k]] += fabs(jy->val[k] * y[j]);
            for (int k = jyp->colptr[j]; k < jyp->colptr[j + 1]; k++)
                s[jyp->rowind[k]] += fabs(jyp->val[k] * yp[j]);
        }
        r = 0;
        for (int i = 0; i < p->n; i++)
            if (F[i] != 0.0) r = fmax(r, fabs(F[i]) / s[i]);
    }
    sp_csc_free(&jy);
    sp_csc_free(&jyp);
    return r;
}

/* dae_init from (y0, yp0), dae_consistent_init; the state after it in y, yp. Returns the
 * solver's code (-1000: not created). */
static int consistent_from(const bp_problem *p, const double *y0, const double *yp0, double *y,
                           double *yp, double *init_res)
{
    bp_instance in;
    dae_options o;
    bg_error err = {0};
    dae_options_default(&o);
    o.rtol = 1e-6;
    o.atol = 1e-6;
    int r = -1000;
    *init_res = INFINITY;
    if (bp_instance_init(&in, p) != 0) return r;
    dae_solver *s = dae_create(&in.dp, &o, &err);
    if (s) {
        r = dae_init(s, p->t0, y0, yp0);
        if (r == 0) r = dae_consistent_init(s);
        if (r == 0) r = dae_dense(s, p->t0, y, yp);
        if (r != 0) tap_diag("%s: consistent init: %s", p->name, dae_get_error(s)->message);
        *init_res = dae_get_stats(s)->init_residual;
    } else {
        tap_diag("%s: dae_create: %s", p->name, err.message);
    }
    dae_free(&s);
    bp_instance_free(&in);
    return r;
}

static void test_initial_values(void)
{
    for (int q = 0; q < NPROB; q++) {
        const bp_problem *p = bp_find(prob_names[q]);
        double r = scaled_residual(p, p->t0, p->y0, p->yp0);
        tap_ok(r <= 1e-12, "init: %s: F(t0, y0, yp0) = 0 up to round-off (%.3g of the terms)",
               p->name, r);
        /* dae_consistent_init keeps consistent values (y' of the algebraic variables aside) */
        double y[MAXN], yp[MAXN], ir, dy = 0, dyp = 0;
        int ret = consistent_from(p, p->y0, p->yp0, y, yp, &ir);
        for (int j = 0; j < p->n; j++) {
            dy = fmax(dy, fabs(y[j] - p->y0[j]) / (fabs(p->y0[j]) + 1e-6 * typical(p, j)));
            if (p->kind[j] == DAE_DIFF)
                dyp = fmax(dyp, fabs(yp[j] - p->yp0[j]) / (fabs(p->yp0[j]) + 1e-6));
        }
        /* y' tolerance 1e-5: dae_consistent_init differentiates the constraint rows in t by
         * one-sided differences, from dt = cbrt(eps) = 6e-6 at t = 0 (no stop time given here)
         * down by factors of 8 until two estimates agree to 1e-3. pump's input is 0 for 5 ns
         * and then ramps (period 120 ns): with dt fixed at 6e-6 s the difference spanned 50
         * periods, gave dF/dt = -9e5 V/s for 0 = y6 - Vin(t) instead of 0, and consistent
         * initialisation set vgate' = 9.0e5 V/s and the index-2 current y9 = -6.9e-8 A where
         * everything is 0 (a known failure until the step adapted). */
        int ok = ret == 0 && ir <= 1e-10 && dy <= 1e-9 && dyp <= 1e-5;
        tap_ok(ok,
               "init: %s: dae_consistent_init keeps y0 (rel change %.2g) and y0' (%.2g), "
               "scaled residual %.2g",
               p->name, dy, dyp, ir);
    }
    /* crank from the published values (9 digits: algebraic rows satisfied to about 1e-7) */
    const bp_problem *p = bp_find("crank");
    double r = scaled_residual(p, p->t0, p->y0_published, p->yp0_published);
    tap_diag("crank: published initial values: scaled residual %.3g", r);
    tap_ok(r > 1e-9, "init: crank: the published values are not consistent (%.3g of the terms)", r);
    double y[MAXN], yp[MAXN], ir, dpos = 0, dvel = 0, dalg = 0;
    int ret = consistent_from(p, p->y0_published, p->yp0_published, y, yp, &ir);
    for (int j = 0; j < 24; j++) {
        double d = fabs(y[j] - p->y0[j]);
        if (j < 7)
            dpos = fmax(dpos, d); /* m and rad */
        else if (j < 14)
            dvel = fmax(dvel, d / 150.0); /* relative to vphi1 */
        else
            dalg = fmax(dalg, d / 5062.0); /* relative to |ax3(0)| */
    }
    tap_diag("crank: consistent init from the published values: init_residual %.3g, differences "
             "to the stored consistent set: positions %.2g (absolute), velocities %.2g (of 150), "
             "w and lam %.2g (of 5062)",
             ir, dpos, dvel, dalg);
    tap_ok(ret == 0 && ir <= 1e-10,
           "init: crank: dae_consistent_init takes the published values to scaled residual %.3g "
           "<= 1e-10",
           ir);
    /* Two consistent completions of the same 9-digit data: the stored set corrects vphi2 alone
     * (by 4e-8); the solver's least (Euclidean) change of the differential variables spreads the
     * correction over vphi2 and q4 (dVLC1/dq4 = vphi2 cos(phi2) = -75), so that positions move
     * by some 1e-11 m. Both stay within the published values' own inconsistency. */
    tap_ok(ret == 0 && dpos <= 1e-9 && dvel <= 1e-9 && dalg <= 1e-6,
           "init: crank: ... within the published values' inconsistency of the stored consistent "
           "set (positions %.2g m/rad, velocities %.2g, w/lam %.2g)",
           dpos, dvel, dalg);
}

/* ---- 4. the solver against the references ---- */

typedef struct run_out {
    int ret;
    double t;
    double y[MAXN];
    dae_stats st;
    char msg[BG_MESSAGE_SIZE + 16];
} run_out;

static void run(const bp_problem *p, const dae_options *o, run_out *out)
{
    bp_instance in;
    bg_error err = {0};
    double yp[MAXN];
    memset(out, 0, sizeof *out);
    out->ret = -1000;
    out->t = p->t0;
    if (bp_instance_init(&in, p) != 0) return;
    dae_solver *s = dae_create(&in.dp, o, &err);
    if (!s) {
        snprintf(out->msg, sizeof out->msg, "dae_create: %s", err.message);
    } else {
        int r = dae_init(s, p->t0, p->y0, p->yp0);
        if (r == 0) r = dae_consistent_init(s);
        while (r >= 0 && r != DAE_TSTOP_RETURN &&
               (r = dae_solve_to(s, p->tend, &out->t, out->y, yp)) == 0 && out->t < p->tend)
            ;
        if (r == DAE_TSTOP_RETURN) r = 0;
        if (r < 0) {
            snprintf(out->msg, sizeof out->msg, "%s", dae_get_error(s)->message);
            dae_dense(s, dae_current_time(s), out->y, yp);
        }
        out->ret = r;
        out->st = *dae_get_stats(s);
    }
    dae_free(&s);
    bp_instance_free(&in);
}

/* mescd over the components 0..m-1 only (the test set's crank: y1..y7) */
static double mescd_first(const double *y, const double *yref, int m, double ratio)
{
    double e = 0;
    for (int i = 0; i < m; i++)
        e = fmax(e, fabs(y[i] - yref[i]) / (ratio + fabs(yref[i])));
    return e > 0 ? -log10(e) : INFINITY;
}

/* What is asserted per problem and convention, and why where it is not the plain bound. */
typedef struct expect {
    const char *name;
    int conv;         /* 'A': test-set tolerances, 'B': atol = 1e-2 rtol */
    double min_mescd; /* bound on mescd (non-index-2 components) */
    double min_scd;   /* bound on scd, or -INF */
    int nscale;       /* newton_index2_scale_h = 1 */
} expect;

/* rtol = 1e-6 throughout, so the plain bound is mescd >= 4.5.
 * crank: the components are positions (y1..y7, scored), velocities (y8..y14) and index-2
 *   accelerations and multipliers. The elastic coordinates q oscillate undamped (E = 2e11,
 *   periods near 2e-4 s): the global error of their velocities adds up over the steps (no
 *   contraction) and ends far above the tolerance (vq3, vq4: 2e-5 absolute with atol = 1e-6,
 *   1e-4 with atol = 1e-8). IDA does the same (mescd 3.74 at A); MEBDFI's published runs reach
 *   scd 0.08 at 1e-6 (docs/mebdfi_stats.md; that scd includes the velocities). The IVP Test
 *   Set's own mescd for crank is over y1..y7: that one gets the plain bound 4.5 in both
 *   conventions (measured 6.2..6.5 at A, 5.8 at B). mescd over y1..y14
 *   is held to 3.5 at A (measured 3.8..4.4 over the solver revisions of this work) and to 1.5
 *   at B (measured 2.1..2.4, atol/rtol = 1e-2 makes the denominators of the velocities 1e-2),
 *   scd (relative errors of y1..y7, q ~ 1e-5 against atol = 1e-6) to 2.0 at A (measured 2.7).
 *   B with the solver before commit e199932 failed: DAE_CONV_FAIL at t = 0, h cut to 1.8e-17
 *   (the multipliers' Newton corrections carry round-off growing like 1/h^2 and cannot meet
 *   atol = 1e-8 in full weight; IDA fails the same way). Since e199932 (Newton accepts the
 *   round-off floor of index-2 unknowns) it reaches tend; B with newton_index2_scale_h = 1
 *   passes with either. (At rtol 1e-8, atol 1e-10 it still fails, DAE_CONV_FAIL at
 *   t = 1.1e-11 with h = 4.6e-20: not asserted here.)
 * pump A (the test set's pumpi.f: atol 1e-6 tol on the charges y1..y5, tol on the voltages,
 *   rtol = atol = 1000 on y9, i.e. y9 out of every test): plain bound with atol = rtol in mescd
 *   (y2..y8 end at 0 and y1 at QG(0, 0, 0), so it is easily met). The index-2 current y9 is
 *   printed apart: 2.1..3.1 digits at 1e-6 over the solver revisions (IDA with the same
 *   tolerances: 3.2); the transistor switches off about 0.1 ns before tend, a kink in y1 that
 *   the last steps cross (the BDF derivative that gives y9 = -y1' still spans it). Asserted
 *   >= 1.5 digits.
 * pump B (scalar atol 1e-8): the steps collapse just after breakpoints where the transistor
 *   switches and the gate capacitance dQG/dVG jumps by a factor 60 (y9 jumps); the solver
 *   restarts there as at an unannounced jump. It stopped with DAE_STEP_TOO_SMALL (h ~ 1e-22) at
 *   t = 50.1 ns before e199932, at 119.9 or 170.1 ns after it, until the first step after such
 *   a restart followed the new y' instead of the collapsed step (IDA fails at 50.1 ns). Plain
 *   bound; y9 to 1.5 digits as in A (measured 5.98 and 1.90).
 * transamp, chemakzo, nand: the plain bound in both conventions. */
static const expect expectations[] = {
    {"crank", 'A', 3.5, 2.0, 0},          {"crank", 'B', 1.5, -INFINITY, 0},
    {"crank", 'B', 1.5, -INFINITY, 1},    {"pump", 'A', 4.5, -INFINITY, 0},
    {"pump", 'B', 4.5, -INFINITY, 0},     {"transamp", 'A', 4.5, -INFINITY, 0},
    {"transamp", 'B', 4.5, -INFINITY, 0}, {"chemakzo", 'A', 4.5, -INFINITY, 0},
    {"chemakzo", 'B', 4.5, -INFINITY, 0}, {"nand", 'A', 4.5, -INFINITY, 0},
    {"nand", 'B', 4.5, -INFINITY, 0},
};

/* Options for a run over the whole interval with the problem's breakpoints; convention A
 * (atol = rtol; pump: pumpi.f's per-component vector, into av) or B (atol = 1e-2 rtol). */
static void solve_options(const bp_problem *p, int conv, double rtol, double *av, dae_options *o)
{
    dae_options_default(o);
    o->rtol = rtol;
    o->atol = conv == 'A' ? rtol : 1e-2 * rtol;
    if (conv == 'A' && !strcmp(p->name, "pump")) {
        for (int i = 0; i < 9; i++)
            av[i] = i < 5 ? 1e-6 * rtol : (i < 8 ? rtol : 1000.0);
        o->atol_vec = av;
    }
    o->has_t_stop = 1;
    o->t_stop = p->tend;
    o->breakpoints = p->breakpoints;
    o->nbreakpoints = p->nbreakpoints;
}

static void test_solver(void)
{
    const double rtol = 1e-6;
    for (size_t e = 0; e < sizeof expectations / sizeof expectations[0]; e++) {
        const expect *x = &expectations[e];
        const bp_problem *p = bp_find(x->name);
        double yref[MAXN], av[MAXN];
        dae_options o;
        solve_options(p, x->conv, rtol, av, &o);
        o.newton_index2_scale_h = x->nscale;
        run_out r;
        run(p, &o, &r);
        bp_reference(p, yref);
        bp_score s;
        bp_score_compute(p, r.y, yref, rtol, o.atol, &s);
        char what[160];
        snprintf(what, sizeof what, "%s %c rtol %g atol %g%s", p->name, x->conv, rtol, o.atol,
                 x->nscale ? " newton_index2_scale_h" : "");
        if (r.ret < 0)
            tap_diag("%s: %s (%d) at t = %.17g: %s", what, dae_return_name(r.ret), r.ret, r.t,
                     r.msg);
        tap_diag("%s: steps %ld, rejected %ld, Newton failures %ld, Jacobians %ld; scd %.2f, "
                 "mescd %.2f; index 2: scd %.2f, mescd %.2f",
                 what, r.st.steps, r.st.rejected_error, r.st.newton_fails, r.st.jac_evals, s.scd,
                 s.mescd, s.scd_i2, s.mescd_i2);
        /* the analytic Jacobians are right (the jacobian: tests above): the automatic check
         * that a slow Newton rate calls for (dae_nls.c; the pump's restarts contract at 0.23)
         * must agree with them */
        tap_ok(r.st.warnings == 0, "%s: no warning (%ld): no false alarm of the Jacobian check",
               what, r.st.warnings);
        int reached = r.ret == 0 && r.t == p->tend;
        int ok = reached && s.mescd >= x->min_mescd && s.scd >= x->min_scd;
        tap_ok(ok, "solve: %s reaches tend (%s) with mescd %.2f >= %.1f, scd %.2f >= %.1f", what,
               r.ret == 0 ? "ok" : dae_return_name(r.ret), s.mescd, x->min_mescd, s.scd,
               x->min_scd);
        if (!strcmp(p->name, "crank")) {
            double m7 = mescd_first(r.y, yref, 7, o.atol / rtol);
            tap_ok(reached && m7 >= 4.5,
                   "solve: %s: the test set's mescd for crank (y1..y7) %.2f >= 4.5", what, m7);
        }
        if (!strcmp(p->name, "pump")) {
            double d9 = -log10(fabs(r.y[8] - yref[8]) / fabs(yref[8]));
            tap_diag("%s: index-2 current y9 = %.10g (reference %.10g): %.2f digits", what, r.y[8],
                     yref[8], d9);
            tap_ok(reached && d9 >= 1.5, "solve: %s: index-2 y9 to %.2f >= 1.5 digits", what, d9);
        }
    }
}

/* pump at the tight tolerances of the benchmark (convention A), where the transistors switch
 * off about 0.1 ns before the ends of Vin's falling ramps (t = 1079.9 and 1199.9 ns): the
 * Newton matrix goes singular there and the accepted steps close in on the switch geometrically,
 * with the Newton iteration failing on every step that would cross it, until the error test
 * fails at round-off. The solver must restart past the switch (as at an unannounced jump) and
 * reach tend. Measured before that restart: DAE_STEP_TOO_SMALL at t = 1079.9 ns at rtol 2.82e-11
 * (and, with the Newton iteration's extension past max_newton, at 1e-10 and 1.68e-11). */
/* Problem p in convention conv at rtol over the whole interval, scored against the reference
 * (mescd with atol = rtol in A, the run's atol in B). */
static void run_scored(const bp_problem *p, int conv, double rtol, double *av, dae_options *o,
                       run_out *r, double *yref, bp_score *s)
{
    solve_options(p, conv, rtol, av, o);
    run(p, o, r);
    bp_reference(p, yref);
    bp_score_compute(p, r->y, yref, rtol, conv == 'A' ? rtol : o->atol, s);
}

static void test_pump_tight(void)
{
    const bp_problem *p = bp_find("pump");
    const double rtols[] = {1e-9, 1e-10, 2.82e-11, 1.68e-11};
    for (int k = 0; k < 4; k++) {
        double rtol = rtols[k], av[9], yref[MAXN];
        dae_options o;
        run_out r;
        bp_score s;
        run_scored(p, 'A', rtol, av, &o, &r, yref, &s);
        /* the charges (the differential unknowns) within 10 of their own tolerances; the
         * voltages follow from them through capacitances of 0.4 pF to 4 pF, so a charge error
         * inside its tolerance 1e-6 rtol (Coulomb) may move a voltage by up to 2.5e6 rtol: they
         * are not held to rtol (mescd printed) */
        double qerr = 0;
        for (int i = 0; i < 5; i++)
            qerr = fmax(qerr, fabs(r.y[i] - yref[i]) / (av[i] + rtol * fabs(yref[i])));
        tap_ok(r.ret == 0 && r.t == p->tend && qerr <= 10,
               "pump A rtol %g: reaches tend (%s at t = %.17g, %ld restarts) with the charges "
               "within %.2f <= 10 tolerances (mescd %.2f) %s",
               rtol, r.ret == 0 ? "ok" : dae_return_name(r.ret), r.t, r.st.restarts, qerr, s.mescd,
               r.msg);
    }
    /* convention B (one atol, 1e-2 rtol, for charges, voltages and the current alike): the
     * steps collapse just after breakpoints where the transistor switches and its gate
     * capacitance jumps 60-fold, and the solver restarts there as at an unannounced jump. Until
     * the first step after such a restart followed the new y' (it was capped by the collapsed
     * step), every rtol from 1e-6 to 2e-8 stopped with DAE_STEP_TOO_SMALL at 119.9 to 890.1
     * ns. Accuracy: mescd as the test set scores it (the charges, about 1e-13 C, are far
     * inside atol; the voltages decide it) within 300 tolerances, mescd >= -log10(rtol) - 2.5
     * (measured: 1.7 to 4.5 digits above -log10(rtol) - 2.5 between 1e-5 and 1e-8, 0.36 at
     * 5e-9). At 1e-9 and 1e-10 the run still stops (at 650.1 and 530.1 ns: a Newton iteration
     * at rate 0.44 that does not finish within the step's iterations): not asserted. */
    const double rtols_b[] = {1e-5, 1e-6, 3e-7, 1e-7, 2e-8, 1e-8, 5e-9};
    for (int k = 0; k < 7; k++) {
        double rtol = rtols_b[k], av[9], yref[MAXN];
        dae_options o;
        run_out r;
        bp_score s;
        run_scored(p, 'B', rtol, av, &o, &r, yref, &s);
        double bound = -log10(rtol) - 2.5;
        tap_ok(r.ret == 0 && r.t == p->tend && s.mescd >= bound,
               "pump B rtol %g: reaches tend (%s at t = %.17g, %ld restarts) with mescd %.2f >= "
               "%.2f %s",
               rtol, r.ret == 0 ? "ok" : dae_return_name(r.ret), r.t, r.st.restarts, s.mescd, bound,
               r.msg);
    }
}

/* rtol = 0, atol alone (1e-8): the Newton iteration's round-off floor for index-2 unknowns was
 * 10 eps / rtol of the tolerance, infinite here, so every iteration after the first was
 * accepted: the pump stopped with DAE_ERR_FAIL at 50.1 ns. The error of the unknowns that are
 * not index 2 against the published reference, within 10 atol (measured 2.5e-12). */
static void test_pump_atol_only(void)
{
    const bp_problem *p = bp_find("pump");
    double av[MAXN], yref[MAXN];
    dae_options o;
    solve_options(p, 'B', 1e-6, av, &o);
    o.rtol = 0;
    o.atol = 1e-8;
    run_out r;
    run(p, &o, &r);
    bp_reference(p, yref);
    double e = 0;
    for (int i = 0; i < p->n; i++)
        if (p->kind[i] != DAE_ALG2) e = fmax(e, fabs(r.y[i] - yref[i]));
    tap_ok(r.ret == 0 && r.t == p->tend && e <= 10 * o.atol,
           "pump rtol 0, atol 1e-8: reaches tend (%s at t = %.17g) with the error %.3g <= 1e-7 "
           "%s",
           r.ret == 0 ? "ok" : dae_return_name(r.ret), r.t, e, r.msg);
}

/* crank at the tight tolerances (convention A, atol = rtol): its first steps, about 1e-12 s,
 * leave the index-2 unknowns (accelerations, multipliers) with corrections that are rounding
 * amplified by 1/h and 1/h^2, while the positions' and velocities' corrections sit at their own
 * rounding, eps |y| against rtol |y|, i.e. 2.2e-6 of the tolerance at rtol 1e-10. The Newton
 * iteration accepted the index-2 round-off floor only below 1e-6, so every rtol from 1e-10 down
 * stopped with DAE_CONV_FAIL at t = 4.5e-12 (1e-11: 4.5e-13); the floor is now also ten times
 * that rounding. Accuracy: the test set's mescd over the positions y1..y7, within the plain
 * bound -log10(rtol) - 1.5 as at rtol 1e-6, and scd (relative errors of y1..y7) printed. */
static void test_crank_tight(void)
{
    const bp_problem *p = bp_find("crank");
    const double rtols[] = {1e-10, 1e-11, 1e-12};
    for (int k = 0; k < 3; k++) {
        double rtol = rtols[k], av[MAXN], yref[MAXN];
        dae_options o;
        run_out r;
        bp_score s;
        run_scored(p, 'A', rtol, av, &o, &r, yref, &s);
        double m7 = mescd_first(r.y, yref, 7, 1.0), bound = -log10(rtol) - 1.5;
        tap_ok(r.ret == 0 && r.t == p->tend && m7 >= bound,
               "crank A rtol %g: reaches tend (%s at t = %.17g) with mescd(y1..y7) %.2f >= %.2f "
               "(scd %.2f, %ld steps) %s",
               rtol, r.ret == 0 ? "ok" : dae_return_name(r.ret), r.t, m7, bound, s.scd, r.st.steps,
               r.msg);
    }
}

int main(void)
{
    test_table();
    test_jacobians();
    test_initial_values();
    test_solver();
    test_pump_tight();
    test_crank_tight();
    test_pump_atol_only();
    return tap_done();
}
