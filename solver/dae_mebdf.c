/* The modified extended BDF (MEBDF) step of the integrator (options.method = DAE_MEBDF).
 *
 * Method (J. R. Cash, "On the integration of stiff systems of ODEs using extended backward
 * differentiation formulae", Numer. Math. 34 (1980) 235-246; "The integration of stiff initial
 * value problems in ODEs using modified extended backward differentiation formulae", Comput.
 * Math. Appl. 9 (1983) 645-657; "Modified extended backward differentiation formulae for the
 * numerical solution of stiff initial value problems in ODEs and DAEs", J. Comput. Appl. Math.
 * 125 (2000) 117-130). With k past values y_{n+1-j} (j = 1..k) at a constant step h, one step
 * of order k + 1:
 *   1. the BDF of order k at t_{n+1}:  ybar_{n+1} + sum_j a_j y_{n+1-j} = h beta ybar'_{n+1};
 *   2. the BDF of order k at t_{n+2} from it:
 *        ybar_{n+2} + a_1 ybar_{n+1} + sum_{j>=2} a_j y_{n+2-j} = h beta ybar'_{n+2};
 *   3. the modified extended formula at t_{n+1}:
 *        y_{n+1} + sum_j ah_j y_{n+1-j}
 *            = h (beta y'_{n+1} + (b1 - beta) ybar'_{n+1} + b2 ybar'_{n+2}),
 *      where y_{n+1} + sum ah_j y_{n+1-j} = h (b1 y'_{n+1} + b2 y'_{n+2}) is the extended BDF
 *      (exact for polynomials of degree k + 1). Writing beta, BDF's coefficient, in front of the
 *      unknown derivative is Cash's modification: all three stages have the Newton matrix
 *      dF/dy + dF/dy' / (h beta) of BDF, factored once.
 * For F(t, y, y') = 0 the derivatives are those each stage's Newton iteration solves for (the
 * stage's y' with F(t, y, y') = 0), so every stage is the shared corrector daei_newton on
 * y' = yp_pred + cj (y - y_pred), cj = 1 / (h beta), with its own (y_pred, yp_pred):
 *   stage 1  BDF's prediction (dae_step.c);
 *   stage 2  y_pred = the polynomial through ybar_{n+1}, y_n, .., y_{n+1-k} at t_{n+2},
 *            yp_pred = cj (y_pred + a_1 ybar_{n+1} + sum_{j>=2} a_j y_{n+2-j});
 *   stage 3  y_pred = ybar_{n+1},
 *            yp_pred = cj (ybar_{n+1} + sum ah_j y_{n+1-j}) - ((b1 - beta) ybar'_{n+1}
 *                      + b2 ybar'_{n+2}) / beta.
 * Round-off: the sums in cj (..) are O(h y') while their terms are O(y), so formed from the values
 * they carry a rounding of eps |y| that cj = 1/(h beta) turns into eps |y| / (h beta) in yp_pred.
 * The Newton iteration answers that residual with corrections of eps |y| in y (below the resolution
 * of the larger unknowns) and, through an index-2 constraint, of cj eps |y| in its multiplier. They
 * are therefore formed in differences to y_n, whose rounding is relative to the differences
 * themselves: each formula's weights sum to 0 (the extrapolation's to 1), so y_n drops out; the
 * past values enter as P(t_{n+1} - j h) - y_n = sum_{i>=1} c_i phi_i (the history's differences),
 * and ybar_{n+1} - y_n = phi_1 + .. + phi_k + ee_1 (the predictor's differences and stage 1's
 * accumulated corrections, never y - y_n). This is the rule of the codes the method comes from:
 * BDF's corrector on y - y_pred with y' = y'_pred + cj (y - y_pred) (DASSL, IDA; Brenan, Campbell
 * and Petzold 1996, sec. 5.2), Cash's MEBDF code (ACM TOMS algorithm 703), which keeps backward
 * differences and sums its corrections apart from y (STIFF, ITRAT2), and Hairer and Wanner's
 * implicit Runge-Kutta stages solved for the smaller z_i = Y_i - y_0 against round-off (Solving
 * ODEs II, 2nd ed., sec. IV.8). Formed from the values, an index-2 problem started at a tiny
 * step (lin2 at rtol 1e-9: 8.7e-12) asks corrections below the ulp of the other unknowns, its
 * constraint cannot be met and the iteration cycles at rate 1 (tests/solver/test_dae_mebdf.c,
 * 6).
 * Coefficients (k = 1..7, options.max_order; mebdf_coeffs solves the order conditions, constant
 * step):
 *   k  beta        b1          b2           order  stability angle
 *   1  1           1.5         -0.5         2      90 (A-stable)
 *   2  2/3         0.95652174  -0.17391304  3      90 (A-stable)
 *   3  6/11        0.76142132  -0.09137056  4      90 (A-stable)
 *   4  12/25       0.65733707  -0.05757697  5      88.36
 *   5  60/137      0.59119244  -0.04021717  6      83.07
 *   6  20/49       0.54475876  -0.03001426  7      74.48
 *   7  140/363     0.50999746  -0.02345586  8      61.98
 * (BDF stages of orders 6 and 7 are not zero-stable as methods of their own; MEBDF built on them
 * is, with the principal root alone on the unit circle at h lambda = 0, as Cash's analysis has
 * it: his codes use k up to 7 as well, MEBDFI's drivers with orders up to 8.)
 * The angles were computed here (the A(alpha) angle: the largest alpha for which the spectral
 * radius of the step's k x k amplification matrix on y' = lambda y stays <= 1 on the rays
 * h lambda = -r exp(+-i alpha), 1e-3 <= r <= 1e6, and on the imaginary axis for k <= 3) and
 * agree with Cash's table (1983, 2000); BDF of orders 2..6: 90, 86.03, 73.35, 51.84, 17.84.
 * The orders up to 8 serve tight tolerances on problems without undamped fast modes: on
 * transamp (max_order 7) 1.13, 1.14, 1.19, 1.25 times MEBDFI's published steps at rtol 1e-4,
 * 1e-6, 1e-8, 1e-10 with 4.63, 5.49, 8.49, 10.57 correct digits (medians over 0.8 .. 1.25 times
 * each rtol 3.82, 6.59, 9.46, 10.79: one run's digits scatter by about one either way; k <= 5:
 * 1.07, 1.18, 1.37, 1.76 times the steps; orders 7 and 8 take 85 % of the steps at 1e-10); on
 * undamped oscillations their stability angles make them worse than orders up to 4.
 * tests/solver/test_dae_mebdf.c measures the amplification on the imaginary axis.
 * Variable step: as in BDF's fixed-leading-coefficient form (dae_step.c), the past values are
 * those of the history's predictor polynomial of degree k at t_{n+1} - j h (j = 1..k): the
 * variable-step history is interpolated onto the constant step h the formulas are written
 * for, which Cash's codes do by rescaling their difference arrays at a step change. Stage 1 is
 * then exactly BDF's step; the history (phi), dense output, roots and statistics are BDF's,
 * applied to the MEBDF solution.
 * Error control (options.mebdf_error; in every one ee = y_{n+1} - y_pred, y_pred the predictor of
 * degree k, and err_k, err_km1 dae_err.c's order-k and order-(k-1) estimates):
 *   DAE_MEBDF_ERR_BDF (default): BDF's of order k (dae_err.c): ck |ee| <= 1 (ck = 1/(k+1) at a
 *     constant step), IDA's order and step rule. The solution has order k + 1: conservative.
 *   DAE_MEBDF_ERR_CASH: Cash and Considine's (J. R. Cash and S. Considine, "An MEBDF code for
 *     stiff initial value problems", ACM TOMS 18 (1992) 142-158, and their code MEBDFI,
 *     subroutines STIFF, COSET, ERRORS). Their control is of order k too: the error test is
 *     that of BDF k in Gear's constants, g_k ck |ee_1| <= 1 with g_k = 1/(1 + 1/2 + .. + 1/k)
 *     (the local error of BDF k is beta_k/(k+1) (y - y_pred); COSET's TQ(2) = (k+1)/beta_k), on
 *     the first stage's ee_1, before the second and third stages are solved; after an accepted
 *     step h and k are held for k + 2 steps (IDOUB), then the step ratios at orders k - 1, k,
 *     k + 1 are 1/PR with PR1 = 1.6 (g_{k-1} err_km1)^(1/k), PR2 = 1.5 (g_k err_k)^(1/(k+1)),
 *     PR3 = 1.7 (g_{k+1} |ee - phi[k+1]|/(k+2))^(1/(k+2)); the smallest PR wins (orders
 *     lowered when the differences grow with the order), a ratio in (1, 1.1) keeps h.
 *     Departures from MEBDFI, measured: the increase is bounded by 2 (MEBDFI: 10; on the crane
 *     at rtol 1e-10 a tenfold step after the start made the stages' interpolated past values,
 *     at t_{n+1} - j h, reach far beyond the history and Newton failed down to h = 1e-12), and
 *     MEBDFI's second test, |y - ybar_{n+1}| <= 2 in tolerance units, is not made (on nand,
 *     after each breakpoint, it failed at every step size: 10 failures and a stop at 1e-8).
 *   DAE_MEBDF_ERR_KP1: the local error of the MEBDF solution itself, of order k + 1: C_{k+2}
 *     |y_{n+1} - P_{k+1}(t_{n+1})| <= 1, P_{k+1} the predictor of degree k + 1
 *     (y_pred + beta_{k+1} phi[k+1], the recursion of set_coeffs carried one order up) and
 *     C_{k+2} = 0.667, 0.149, 0.0598, 0.0315, 0.0199 (k = 1..5) the error constant of MEBDF
 *     (lte_c below); the step ratio at order k is 1/(1.5 e^(1/(k+2))), the order chosen as
 *     in CASH, on CASH's rule and test until the last accepted step had the same order.
 *   Measured (tests/solver/test_dae_mebdf.c: transamp at rtol = atol as MEBDFI's driver;
 *   steps over MEBDFI's published steps, and scd, at 1e-4, 1e-6, 1e-8, 1e-10): BDF 1.07, 1.18,
 *   1.37, 1.76 and 3.52, 5.86, 9.06, 10.82; CASH 1.06, 1.15, 1.35, 1.70 and 3.88, 5.84, 7.68,
 *   9.94; KP1 1.07, 1.02, 1.05, 1.17 and 4.74, 5.92, 7.29, 9.21 (MEBDFI: 4.58, 6.43, 7.59,
 *   10.12, with orders up to 8 where k <= 5 here). Work at equal accuracy on the collection (Newton
 *   iterations at equal scd against BDF's control, median over the scd range both reach): CASH 0.42
 *   (pump) to 2.51 (kinks), below 0.9 on chemakzo, osc_chain, pump, above 1.2 on ap102, crane,
 *   kinks, lin2, pendulum2, robertson, smooth_ode; KP1 0.80 to 2.79, 1.4 or more on 8 of the 16
 *   problems. The step counts at a tolerance follow the estimate's constant; the work at equal
 *   accuracy does not improve on BDF's control: MEBDFI's fewer steps at tight tolerances come
 *   from its orders 7 and 8. (An earlier trial of the
 *   order-(k+1) estimate inside BDF's step rule, which changes h at every step, failed the error
 *   test on a third of transamp's steps: the estimate needs the held steps.)
 * Stops: the second stage evaluates the residual at t_{n+2}. A step that ends on a stop (a
 * breakpoint or t_stop), or whose t_{n+2} would pass one, is BDF's step alone, so that no residual
 * is evaluated beyond t_stop or across a breakpoint's jump. Newton: one matrix for the three stages
 * (its rate carries from one stage to the next); a failure in any stage is the step's Newton
 * failure (dae_step.c, handle_failure), and a Jacobian evaluated in any stage counts as current for
 * it. */
#include <math.h>
#include <string.h>

#include "bg_dae_impl.h"

#define MB_RH_KEEP 1.1 /* MEBDFI: a step ratio in (1, MB_RH_KEEP) keeps h */
#define MB_RH_MAX 2.0  /* the largest increase of h in one change (MEBDFI: 10) */

enum { V_YB1 = 0, V_YPB1, V_YPB2, V_EE1, V_SE, V_S2, V_S3 }; /* the vectors of s->mb */

/* Solves A x = b (m <= MAXORD + 2) by Gaussian elimination with partial pivoting. */
static void gsolve(int m, double A[MAXORD + 2][MAXORD + 2], double *b)
{
    for (int c = 0; c < m; c++) {
        int p = c;
        for (int r = c + 1; r < m; r++)
            if (fabs(A[r][c]) > fabs(A[p][c])) p = r;
        for (int j = 0; j < m; j++) {
            double t = A[c][j];
            A[c][j] = A[p][j];
            A[p][j] = t;
        }
        double t = b[c];
        b[c] = b[p];
        b[p] = t;
        for (int r = c + 1; r < m; r++) {
            double f = A[r][c] / A[c][c];
            for (int j = c; j < m; j++)
                A[r][j] -= f * A[c][j];
            b[r] -= f * b[c];
        }
    }
    for (int c = m - 1; c >= 0; c--) {
        double v = b[c];
        for (int j = c + 1; j < m; j++)
            v -= A[c][j] * b[j];
        b[c] = v / A[c][c];
    }
}

/* Constant-step coefficients of order k (1..MAXORD), in units of h with t_{n+1} = 0: a[1..k],
 * beta of the BDF (exact for degree <= k), ah[1..k], b1, b2 of the extended BDF (degree
 * <= k + 1): sum_j c_j (-j)^m = m (rhs derivative coefficients at 0 and at 1)^(m-1). */
static void mebdf_coeffs(int k, double *a, double *beta, double *ah, double *b1, double *b2)
{
    double A[MAXORD + 2][MAXORD + 2], r[MAXORD + 2];
    for (int m = 0; m <= k; m++) {
        for (int j = 1; j <= k; j++)
            A[m][j - 1] = pow(-j, m);
        A[m][k] = m == 1 ? -1.0 : 0.0;
        r[m] = m == 0 ? -1.0 : 0.0;
    }
    gsolve(k + 1, A, r);
    for (int j = 1; j <= k; j++)
        a[j] = r[j - 1];
    *beta = r[k];
    for (int m = 0; m <= k + 1; m++) {
        for (int j = 1; j <= k; j++)
            A[m][j - 1] = pow(-j, m);
        A[m][k] = m == 1 ? -1.0 : 0.0;
        A[m][k + 1] = -(double)m;
        r[m] = m == 0 ? -1.0 : 0.0;
    }
    gsolve(k + 2, A, r);
    for (int j = 1; j <= k; j++)
        ah[j] = r[j - 1];
    *b1 = r[k];
    *b2 = r[k + 1];
}

/* out = sum_{j=1..k} w[j] (P(t_{n+1} - j h) - y_n), P the history's predictor polynomial of
 * degree k (Newton form on the divided differences phi before set_coeffs scaled them: phi_i =
 * phi*_i / beta_i for i >= ns, and the nodes psi_old[i] = psi[i+1] - h, as restore in
 * dae_step.c): the differences phi_1 .. phi_k alone, y_n = phi_0 left out. */
static void combine_past(const dae_solver *s, const double *w, double *restrict out)
{
    int k = s->kk, n = s->n;
    double h = s->hh, psio[MAXORD + 1], cw[MAXORD + 2] = {0};
    for (int i = 0; i < k; i++)
        psio[i] = s->psi[i + 1] - h;
    for (int m = 1; m <= k; m++) {
        if (w[m] == 0) continue;
        double delt = (1 - m) * h, c = 1; /* t - t_n */
        for (int i = 1; i <= k; i++) {
            c *= (delt + (i >= 2 ? psio[i - 2] : 0.0)) / psio[i - 1];
            cw[i] += w[m] * c;
        }
    }
    for (int i = 1; i <= k; i++)
        if (i >= s->ns) cw[i] /= s->beta[i];
    memset(out, 0, (size_t)n * sizeof *out);
    for (int i = 1; i <= k; i++) {
        const double *restrict p = s->phi[i];
        double c = cw[i];
        if (c != 0)
            for (int q = 0; q < n; q++)
                out[q] += c * p[q];
    }
}

/* Gear's (and MEBDFI's) error constant of BDF of order k relative to DASSL's: the local error
 * of BDF k is beta_k / (k + 1) (y - y_pred) at a constant step (beta_k = 1 / (1 + 1/2 + .. +
 * 1/k)), where dae_err.c's estimate ck |y - y_pred| has ck = 1 / (k + 1). */
static double gear_const(int k)
{
    double hk = 0;
    for (int j = 1; j <= k; j++)
        hk += 1.0 / j;
    return k >= 1 ? 1.0 / hk : 1.0;
}

/* |C| of MEBDF's local error y_{n+1} - y(t_{n+1}) = C h^{k+2} y^{(k+2)} (order k + 1), k =
 * 1..5: the larger of its values on y' = lambda y (lambda h -> 0) and on y' = f(t), computed
 * from mebdf_coeffs' coefficients with exact past values (k = 1: -0.667 and -0.417); KP1
 * therefore needs max_order <= 5 (dae_create). */
static const double lte_c[MAXORD + 1] = {0, 0.667, 0.149, 0.0598, 0.0315, 0.0199};

/* The weighted RMS norm of a - c b (b NULL: of a) in the error test's weights. */
static double wnorm(const dae_solver *s, const double *restrict a, double c,
                    const double *restrict b)
{
    const double *restrict w = s->werr;
    double q = 0;
    for (int i = 0; i < s->n; i++) {
        double d = (b ? a[i] - c * b[i] : a[i]) * w[i];
        q += d * d;
    }
    return sqrt(q / (s->n > 0 ? s->n : 1));
}

/* Whether this step estimates its error with the predictor of degree k + 1
 * (DAE_MEBDF_ERR_KP1): the last accepted step was of order k, so that phi[k+1] holds its
 * y - y_pred and mb_psik its psi[k]. */
static int kp1_valid(const dae_solver *s)
{
    int k = s->kk;
    return s->o.mebdf_error == DAE_MEBDF_ERR_KP1 && !s->o.fixed_step && s->phase == 1 &&
           s->kused == k && s->mb_k == k && s->nst_local >= k + 2;
}

/* The weighted RMS norm of y - P_{k+1}(t_{n+1}) = ee - beta_{k+1} phi[k+1], P_{k+1} the
 * predictor of degree k + 1 (beta_{k+1} = beta_k psi[k] / psi_old[k], as set_coeffs in
 * dae_step.c continues its recursion; 1 after k + 2 steps of one size). */
static double kp1_norm(const dae_solver *s)
{
    int k = s->kk;
    double b = s->ns > k + 1 ? 1.0 : s->beta[k] * s->psi[k] / s->mb_psik;
    return wnorm(s, s->ee, b, s->phi[k + 1]);
}

/* Cash's error test on the first stage (DAE_MEBDF_ERR_CASH, and DAE_MEBDF_ERR_KP1 until its
 * estimate is there): 1 when it fails. */
static int stage1_fails(const dae_solver *s)
{
    return s->o.mebdf_error != DAE_MEBDF_ERR_BDF && !s->o.fixed_step && !kp1_valid(s) &&
           gear_const(s->kk) * s->ck * wnorm(s, s->ee, 0, NULL) > 1.0;
}

int daei_mebdf_correct(dae_solver *s, double t, double teval, int bdf_only)
{
    int nl = daei_newton(s, teval);
    if (nl != NL_OK || s->o.method != DAE_MEBDF) return nl;
    int n = s->n, k = s->kk;
    double *v[MB_NVEC];
    for (int j = 0; j < MB_NVEC; j++)
        v[j] = s->mb + (size_t)j * n;
    memcpy(v[V_EE1], s->ee, (size_t)n * sizeof(double));
    /* a step whose first stage fails the error test stops here (daei_mebdf_error_test fails it
     * on the same numbers) */
    if (bdf_only || stage1_fails(s)) return NL_OK;
    double a[MAXORD + 1], beta, ah[MAXORD + 1], b1, b2;
    mebdf_coeffs(k, a, &beta, ah, &b1, &b2);
    double cj = s->cj; /* 1 / (h beta) */
    memcpy(v[V_YB1], s->y, (size_t)n * sizeof(double));
    memcpy(v[V_YPB1], s->yp, (size_t)n * sizeof(double));
    double dn0 = s->dn0;
    int jc = s->jac_current;
    /* the past values' combinations: extrapolation to t_{n+2} (degree k through ybar_{n+1} and
     * y_n .. y_{n+1-k}: weights (-1)^j C(k+1, j+1)), stage 2's and stage 3's sums */
    double we[MAXORD + 2] = {0}, w2[MAXORD + 2] = {0}, w3[MAXORD + 2] = {0};
    double e0 = k + 1, bin = k + 1; /* C(k+1, 1) */
    for (int j = 1; j <= k; j++) {
        bin = bin * (double)(k + 1 - j) / (double)(j + 1); /* C(k+1, j+1) */
        we[j] = (j % 2 ? -1.0 : 1.0) * bin;
        if (j + 1 <= k) w2[j] = a[j + 1];
        w3[j] = ah[j];
    }
    combine_past(s, we, v[V_SE]);
    combine_past(s, w2, v[V_S2]);
    combine_past(s, w3, v[V_S3]);
    /* the stages' predictions in differences from y_n (the weights of each formula sum to 0,
     * those of the extrapolation to 1), with ybar_{n+1} - y_n = phi_1 + .. + phi_k + ee_1 (the
     * predictor's differences and stage 1's corrections): se = y_pred(t_{n+2}) - y_n, s2 =
     * ybar_{n+2} + a_1 ybar_{n+1} + sum_{j>=2} a_j y_{n+2-j} at y_pred, s3 = ybar_{n+1} + sum ah_j
     * y_{n+1-j} */
    {
        double *restrict se = v[V_SE], *restrict s2 = v[V_S2], *restrict s3 = v[V_S3];
        const double *restrict e1 = v[V_EE1];
        for (int i = 0; i < n; i++) {
            double db = 0;
            for (int j = 1; j <= k; j++)
                db += s->phi[j][i];
            db += e1[i];
            se[i] += e0 * db;
            s2[i] += se[i] + a[1] * db;
            s3[i] += db;
        }
    }
    /* stage 2: BDF at t + h */
    {
        double *restrict y = s->y, *restrict yp = s->yp;
        const double *restrict y0 = s->phi[0], *restrict se = v[V_SE], *restrict s2 = v[V_S2];
        for (int i = 0; i < n; i++) {
            y[i] = y0[i] + se[i];
            yp[i] = cj * s2[i];
        }
    }
    s->cjold = s->cj; /* the same matrix: the rate of stage 1 holds */
    nl = daei_newton(s, t + s->hh);
    jc = jc || s->jac_current;
    if (nl != NL_OK) {
        s->jac_current = jc;
        return nl;
    }
    memcpy(v[V_YPB2], s->yp, (size_t)n * sizeof(double));
    /* stage 3: the modified extended formula at t */
    {
        double *restrict y = s->y, *restrict yp = s->yp;
        const double *restrict yb = v[V_YB1], *restrict ypb1 = v[V_YPB1],
                               *restrict ypb2 = v[V_YPB2], *restrict s3 = v[V_S3];
        double c1 = (b1 - beta) / beta, c2 = b2 / beta;
        for (int i = 0; i < n; i++) {
            y[i] = yb[i];
            yp[i] = cj * s3[i] - c1 * ypb1[i] - c2 * ypb2[i];
        }
    }
    nl = daei_newton(s, teval);
    s->jac_current = jc || s->jac_current;
    s->dn0 = dn0; /* the next step's first correction compares with stage 1's */
    if (nl != NL_OK) return nl;
    /* ee = y - y_pred of stage 1 = (ybar_{n+1} - y_pred) + (y - ybar_{n+1}) */
    {
        double *restrict ee = s->ee;
        const double *restrict e1 = v[V_EE1];
        for (int i = 0; i < n; i++)
            ee[i] += e1[i];
    }
    return NL_OK;
}

int daei_mebdf_error_test(dae_solver *s)
{
    int fail = daei_error_test(s), k = s->kk;
    if (s->o.mebdf_error == DAE_MEBDF_ERR_BDF) return fail;
    /* err_k, err_km1 (dae_err.c) in Gear's constants: the order-k estimates that order
     * selection compares (MEBDFI's D, DDOWN against E, EDN) */
    s->err_k *= gear_const(k);
    s->err_km1 *= gear_const(k - 1);
    /* the order after a failure: k - 1 when its step ratio is the larger (MEBDFI: PLFAIL <
     * PRFAIL) */
    s->knew = k;
    if (k > 1 && pow(5 * s->err_km1, 1.0 / k) < pow(5 * s->err_k, 1.0 / (k + 1))) s->knew = k - 1;
    s->mb_kp1 = kp1_valid(s);
    if (s->mb_kp1) {
        double e = lte_c[k] * kp1_norm(s);
        if (e <= 1.0) return 0;
        /* daei_after_error_fail's cut 0.9 (2 err_k)^(-1/(k+1)) becomes 0.9 (2 e)^(-1/(k+2)) */
        s->knew = k;
        s->err_k = 0.5 * pow(2 * e, (k + 1.0) / (k + 2.0));
        return 1;
    }
    /* Cash's test, on the first stage's y - y_pred (that of KP1 until its estimate is there) */
    const double *e1 = s->mb + (size_t)V_EE1 * s->n;
    return gear_const(k) * s->ck * wnorm(s, e1, 0, NULL) > 1.0;
}

void daei_mebdf_choose_next(dae_solver *s, int kdiff)
{
    int k = s->kk;
    if (s->o.mebdf_error == DAE_MEBDF_ERR_BDF) {
        daei_choose_next(s, kdiff);
        return;
    }
    /* this step's estimates of MEBDF of orders k + 1 and k (KP1) */
    double ekp1 = s->mb_kp1 ? lte_c[k] * kp1_norm(s) : 0;
    double ek = k > 1 ? lte_c[k - 1] * wnorm(s, s->ee, 0, NULL) : 0;
    s->mb_psik = s->psi[k];
    s->mb_k = k;
    if (k == MAXORD) memcpy(s->phi[MAXORD + 1], s->ee, (size_t)s->n * sizeof(double));
    if (s->o.fixed_step || s->phase == 0) {
        daei_choose_next(s, kdiff);
        return;
    }
    s->err_next = s->err_k;
    if (s->ns < k + 2) return; /* h and k held for k + 2 steps after a change (IDOUB) */
    /* the step ratios at orders k - 1, k, k + 1 (MEBDFI's PR1, PR2, PR3) from the differences
     * of orders k, k + 1, k + 2 */
    double pr1 = 1e20, pr2 = 1.5 * pow(s->err_k, 1.0 / (k + 1)) + 1.6e-6, pr3 = 1e20;
    double dk = wnorm(s, s->ee, 0, NULL), dkm1 = 0, errkp1 = 0;
    if (k > 1) {
        pr1 = 1.6 * pow(s->err_km1, 1.0 / k) + 1.7e-6;
        dkm1 = s->err_km1 / (gear_const(k - 1) * s->sigma[k - 1]);
    }
    if (k < s->o.max_order && kdiff != 1) {
        double dkp1 = wnorm(s, s->ee, 1, s->phi[k + 1]);
        errkp1 = gear_const(k + 1) * dkp1 / (k + 2);
        pr3 = 1.7 * pow(errkp1, 1.0 / (k + 2)) + 1.8e-6;
        if (k > 1 && dkp1 > dk && dk > dkm1) pr2 = pr3 = 1e30; /* growing with the order */
    }
    int newk = k;
    double pr = pr2, errn = s->err_k;
    if (pr2 <= pr3) {
        if (pr2 > pr1) newk = k - 1, pr = pr1, errn = s->err_km1;
    } else if (pr3 < pr1)
        newk = k + 1, pr = pr3, errn = errkp1;
    else
        newk = k - 1, pr = pr1, errn = s->err_km1;
    if (s->mb_kp1) { /* KP1: the step from the estimate of the MEBDF solution's own order */
        if (newk == k)
            pr = 1.5 * pow(ekp1, 1.0 / (k + 2)) + 1.6e-6;
        else if (newk == k - 1)
            pr = 1.6 * pow(ek, 1.0 / (k + 1)) + 1.7e-6;
        else
            pr = 1.0;
    }
    double rh = 1.0 / pr;
    if (newk == k && rh > 1.0 && rh < MB_RH_KEEP) return;
    s->err_next = errn;
    double hnew = s->hh * fmin(rh, MB_RH_MAX);
    if (s->o.h_max > 0 && fabs(hnew) > s->o.h_max) hnew = copysign(s->o.h_max, hnew);
    s->kk = newk;
    s->hh = hnew;
}
