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
 * Coefficients (k = 1..5; mebdf_coeffs solves the order conditions, constant step):
 *   k  beta        b1          b2           order  stability angle
 *   1  1           1.5         -0.5         2      90 (A-stable)
 *   2  2/3         0.95652174  -0.17391304  3      90 (A-stable)
 *   3  6/11        0.76142132  -0.09137056  4      90 (A-stable)
 *   4  12/25       0.65733707  -0.05757697  5      88.36
 *   5  60/137      0.59119244  -0.04021717  6      83.07
 * The angles were computed here (the A(alpha) angle: the largest alpha for which the spectral
 * radius of the step's k x k amplification matrix on y' = lambda y stays <= 1 on the rays
 * h lambda = -r exp(+-i alpha), 1e-3 <= r <= 1e6, and on the imaginary axis for k <= 3) and
 * agree with Cash's table (1983, 2000); BDF of orders 2..6: 90, 86.03, 73.35, 51.84, 17.84.
 * tests/solver/test_dae_mebdf.c measures the amplification on the imaginary axis.
 * Variable step: as in BDF's fixed-leading-coefficient form (dae_step.c), the past values are
 * those of the history's predictor polynomial of degree k at t_{n+1} - j h (j = 1..k): the
 * variable-step history is interpolated onto the constant step h the formulas are written
 * for, which Cash's codes do by rescaling their difference arrays at a step change. Stage 1 is
 * then exactly BDF's step, and the history (phi), the error test, order and step selection,
 * dense output, roots and statistics are BDF's, applied to the MEBDF solution: the error
 * estimate ck |y_{n+1} - y_pred| is that of the BDF of order k, so that the error control is
 * that of order k while the solution has order k + 1: conservative, the solution is more
 * accurate than the tolerance asks at the steps BDF's estimate allows. (An estimate of the
 * extended formula's own error, its error constant times the divided difference of order k+2
 * of the accepted values from the last two steps, was tried: on transamp it let the error test
 * fail on a third of the steps and the scd fell, 5.71 against 5.86 at rtol 1e-6 with 28 times
 * the steps; on the index-2 pendulum at rtol 1e-9 it took 3058 steps for scd 4.6: the
 * estimate, 4000 times below BDF's there, missed the error of the constrained unknowns, whose
 * order the index lowers, and with it in place of BDF's order-k estimate the order selection
 * held order 1.)
 * Stops: the second stage evaluates the residual at t_{n+2}. A step that ends on a stop (a
 * breakpoint or t_stop), or whose t_{n+2} would pass one, is BDF's step alone, so that no residual
 * is evaluated beyond t_stop or across a breakpoint's jump. Newton: one matrix for the three stages
 * (its rate carries from one stage to the next); a failure in any stage is the step's Newton
 * failure (dae_step.c, handle_failure), and a Jacobian evaluated in any stage counts as current for
 * it. */
#include <math.h>
#include <string.h>

#include "bg_dae_impl.h"

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

/* out = sum_{j=1..k} w[j] P(t_{n+1} - j h), P the history's predictor polynomial of degree k
 * (Newton form on the divided differences phi before set_coeffs scaled them: phi_i = phi*_i /
 * beta_i for i >= ns, and the nodes psi_old[i] = psi[i+1] - h, as restore in dae_step.c). */
static void combine_past(const dae_solver *s, const double *w, double *restrict out)
{
    int k = s->kk, n = s->n;
    double h = s->hh, psio[MAXORD + 1], cw[MAXORD + 2] = {0};
    for (int i = 0; i < k; i++)
        psio[i] = s->psi[i + 1] - h;
    for (int m = 1; m <= k; m++) {
        if (w[m] == 0) continue;
        double delt = (1 - m) * h, c = 1; /* t - t_n */
        cw[0] += w[m];
        for (int i = 1; i <= k; i++) {
            c *= (delt + (i >= 2 ? psio[i - 2] : 0.0)) / psio[i - 1];
            cw[i] += w[m] * c;
        }
    }
    for (int i = 0; i <= k; i++)
        if (i >= s->ns) cw[i] /= s->beta[i];
    memset(out, 0, (size_t)n * sizeof *out);
    for (int i = 0; i <= k; i++) {
        const double *restrict p = s->phi[i];
        double c = cw[i];
        if (c != 0)
            for (int q = 0; q < n; q++)
                out[q] += c * p[q];
    }
}

int daei_mebdf_correct(dae_solver *s, double t, double teval, int bdf_only)
{
    int nl = daei_newton(s, teval);
    if (nl != NL_OK || bdf_only || s->o.method != DAE_MEBDF) return nl;
    int n = s->n, k = s->kk;
    double *v[MB_NVEC];
    for (int j = 0; j < MB_NVEC; j++)
        v[j] = s->mb + (size_t)j * n;
    double a[MAXORD + 1], beta, ah[MAXORD + 1], b1, b2;
    mebdf_coeffs(k, a, &beta, ah, &b1, &b2);
    double cj = s->cj; /* 1 / (h beta) */
    memcpy(v[V_YB1], s->y, (size_t)n * sizeof(double));
    memcpy(v[V_YPB1], s->yp, (size_t)n * sizeof(double));
    memcpy(v[V_EE1], s->ee, (size_t)n * sizeof(double));
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
    /* stage 2: BDF at t + h */
    {
        double *restrict y = s->y, *restrict yp = s->yp;
        const double *restrict yb = v[V_YB1], *restrict se = v[V_SE], *restrict s2 = v[V_S2];
        for (int i = 0; i < n; i++) {
            y[i] = e0 * yb[i] + se[i];
            yp[i] = cj * (y[i] + a[1] * yb[i] + s2[i]);
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
            yp[i] = cj * (yb[i] + s3[i]) - c1 * ypb1[i] - c2 * ypb2[i];
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
