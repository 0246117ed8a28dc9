/* LQR design (ctl_lqr) and the state-feedback element against closed forms.
 *
 * Double integrator x1' = x2, x2' = u with Q = diag(q1, q2), R = r: the Riccati equation's
 * stabilising solution gives K = [sqrt(q1 / r), sqrt(q2 / r + 2 sqrt(q1 / r))] (solve
 * A^T P + P A - P B B^T P / r + Q = 0 entry by entry: p12 = sqrt(q1 r),
 * p22 = sqrt(r (q2 + 2 p12)), K = [p12, p22] / r). Scalar plant x' = a x + b u:
 * p = (a r + sqrt(a^2 r^2 + q b^2 r)) / b^2, k = b p / r. A four-state plant (two coupled
 * oscillators, one unstable): the Riccati residual at the P returned, relative to |Q|, and the
 * closed loop A - B K stable (its eigenvalues by LAPACK dgeev, an independent routine of the
 * design's dgees). The element: an inertia theta'' = u under u = -K [theta, omega] from the model
 * file's design for q1 = 4, q2 = 1, r = 1 (K = [2, sqrt 5]), from theta(0) = 1: the closed form
 * theta = e^(s t) (cos(b t) - (s / b) sin(b t)), s = -sqrt 5 / 2, b = sqrt 3 / 2. */
#include "ctl_lqr.h"
#include "ctltest.h"

extern void dgeev_(const char *jobvl, const char *jobvr, const int *n, double *a, const int *lda,
                   double *wr, double *wi, double *vl, const int *ldvl, double *vr,
                   const int *ldvr, double *work, const int *lwork, int *info);

static void test_double_integrator(void)
{
    const double cases[3][3] = {{1, 1, 1}, {4, 0.5, 2}, {100, 0, 0.01}};
    for (int c = 0; c < 3; c++) {
        double q1 = cases[c][0], q2 = cases[c][1], r = cases[c][2];
        double A[4] = {0, 0, 1, 0}, B[2] = {0, 1}, Q[4] = {q1, 0, 0, q2}, K[2], P[4];
        bg_error e = {0};
        int st = ctl_lqr(2, 1, A, B, Q, &r, K, P, &e);
        double k1 = sqrt(q1 / r), k2 = sqrt(q2 / r + 2 * sqrt(q1 / r));
        tap_ok(st == BG_OK && fabs(K[0] - k1) < 1e-10 * k1 && fabs(K[1] - k2) < 1e-10 * k2,
               "double integrator q1 = %g, q2 = %g, r = %g: K = [%.12g, %.12g], closed form "
               "[%.12g, %.12g]",
               q1, q2, r, K[0], K[1], k1, k2);
        if (st) tap_diag("%s", e.message);
    }
}

static void test_scalar(void)
{
    const double a = 0.7, b = 2.0, q = 3.0, r = 0.4;
    double K, P;
    int st = ctl_lqr(1, 1, &a, &b, &q, &r, &K, &P, NULL);
    double p = (a * r + sqrt(a * a * r * r + q * b * b * r)) / (b * b), k = b * p / r;
    tap_ok(st == BG_OK && fabs(P - p) < 1e-12 * p && fabs(K - k) < 1e-12 * k,
           "unstable scalar plant: P = %.14g (closed form %.14g), K = %.14g (%.14g)", P, p, K, k);
}

static void test_four_states(void)
{
    /* column-major: two oscillators coupled by a spring, the second with negative stiffness */
    const int n = 4;
    double A[16] = {0}, B[4] = {0, 0, 0, 1}, Q[16] = {0}, R = 0.1, K[4], P[16];
    A[0 + 2 * n] = 1;
    A[1 + 3 * n] = 1;
    A[2 + 0 * n] = -2;
    A[2 + 1 * n] = 1;
    A[3 + 0 * n] = 1;
    A[3 + 1 * n] = 0.5; /* -1 + 1.5: a negative net stiffness */
    A[2 + 2 * n] = -0.1;
    for (int i = 0; i < n; i++) Q[i + i * n] = 1 + i;
    int st = ctl_lqr(n, 1, A, B, Q, &R, K, P, NULL);
    /* residual A^T P + P A - P B B^T P / R + Q */
    double res = 0, qn = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double s = Q[i + j * n], pb_i = 0, pb_j = 0;
            for (int k = 0; k < n; k++) {
                s += A[k + i * n] * P[k + j * n] + P[i + k * n] * A[k + j * n];
                pb_i += P[i + k * n] * B[k];
                pb_j += P[j + k * n] * B[k];
            }
            s -= pb_i * pb_j / R;
            res = fmax(res, fabs(s));
            qn = fmax(qn, fabs(Q[i + j * n]));
        }
    double C[16], wr[4], wi[4], work[64];
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) C[i + j * n] = A[i + j * n] - B[i] * K[j];
    int lw = 64, info;
    dgeev_("N", "N", &n, C, &n, wr, wi, NULL, &n, NULL, &n, work, &lw, &info);
    double rmax = -INFINITY;
    for (int i = 0; i < n; i++) rmax = fmax(rmax, wr[i]);
    tap_ok(st == BG_OK && res < 1e-10 * qn,
           "four states, one unstable mode: Riccati residual %.1e of |Q|", res / qn);
    tap_ok(st == BG_OK && info == 0 && rmax < 0,
           "the closed loop A - B K is stable: largest real part %.4f", rmax);
    double Az[1] = {0}, Bz[1] = {0}, Qz[1] = {1}, Rz = 1, Kz;
    bg_error e = {0};
    st = ctl_lqr(1, 1, Az, Bz, Qz, &Rz, &Kz, NULL, &e);
    tap_ok(st == BG_ERR_SINGULAR && strstr(e.message, "stabilisable"),
           "an uncontrollable marginal plant is refused: %s", e.message);
    double Rn = -1;
    st = ctl_lqr(1, 1, &A[0], B, Qz, &Rn, &Kz, NULL, &e);
    tap_ok(st == BG_ERR_ARGUMENT && strstr(e.message, "positive definite"),
           "R <= 0 is refused: %s", e.message);
}

static const char *loop_model =
    "format: bgsim 1\n"
    "name: di\n"
    "components:\n"
    "  body: {type: rot.inertia, J: 1, angle: 1}\n"
    "  angle: {type: rot.sensor, inertia: body, quantity: angle}\n"
    "  speed: {type: rot.sensor, inertia: body, quantity: velocity}\n"
    "  lqr: {type: ctl.state_feedback, x1: angle.value, x2: speed.value, A: [0, 1, 0, 0], "
    "B: [0, 1], Q: [4, 1], R: 1}\n"
    "  torque: {type: bg.Se_signal, signal: lqr.u}\n"
    "bonds:\n"
    "  - {from: torque.p, to: body.p}\n"
    "outputs:\n"
    "  theta: angle.value\n"
    "  u: lqr.u\n";

static void test_closed_loop(void)
{
    ctl_run r;
    if (!tap_ok(cr_open(&r, loop_model, 1e-9, 1e-11), "inertia under LQR feedback loads")) {
        cr_close(&r);
        return;
    }
    double s = -sqrt(5.0) / 2, b = sqrt(3.0) / 2, worst = 0;
    int ok = 1;
    for (int k = 1; k <= 10 && ok; k++) {
        double t = 0.5 * k;
        ok = cr_to(&r, t);
        double th = exp(s * t) * (cos(b * t) - (s / b) * sin(b * t));
        worst = fmax(worst, fabs(cr_out(&r, "theta") - th));
    }
    tap_ok(ok && worst < 1e-6, "theta(t) under u = -K x against the closed form: largest error "
                               "%.1e over 0.5 .. 5 s",
           worst);
    cr_close(&r);
}

int main(void)
{
    test_double_integrator();
    test_scalar();
    test_four_states();
    test_closed_loop();
    return tap_done();
}
