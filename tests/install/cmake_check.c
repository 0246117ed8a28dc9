/* Built by tools/test.sh against the installed library through its CMake package
 * (tests/install/CMakeLists.txt: find_package(bgdae), target bgdae::bgdae), with the umbrella
 * header: a bond-graph capacitor discharging through a resistor, q' = -k q / R, compiled to a
 * DAE and integrated to t = 1; checks q(1) = q0 exp(-k / R). */
#include <math.h>
#include <stdio.h>

#include <bgdae/bgdae.h>

int main(void)
{
    const double k = 2.0, R = 1.0, q0 = 1.0;
    int ok = 0;
    double q = NAN, tret = 0;
    bgr_model *m = bgr_model_create("rc");
    int C = bgr_C(m, 0, "C", 1, k), Rr = bgr_R(m, 0, "R", 1, R);
    /* the bond points out of the capacitor: q' = -f, e = k q = R f */
    if (C >= 0 && Rr >= 0 &&
        bgr_bond(m, 0, "b", 1, bgr_port_of(m, C, 0), bgr_port_of(m, Rr, 0), NULL, NULL) >= 0 &&
        bgr_compile(m) == BG_OK) {
        int vq = bgr_find_var(m, "rc/C/q");
        dae_problem p;
        dae_options o;
        bg_error err = {0};
        dae_options_default(&o);
        o.rtol = 1e-9;
        o.atol = 1e-12;
        if (vq >= 0) bgr_y0(m)[vq] = q0;
        dae_solver *s = vq >= 0 && bgr_dae_problem(m, &p) == BG_OK ? dae_create(&p, &o, &err)
                                                                     : NULL;
        int r = s ? dae_init(s, 0.0, bgr_y0(m), bgr_yp0(m)) : BG_ERR_ARGUMENT;
        if (r == BG_OK) r = dae_consistent_init(s);
        if (r == DAE_WARNING) r = BG_OK;
        int n = bgr_n(m);
        double y[8];
        if (r == BG_OK && n <= 8) r = dae_solve_to(s, 1.0, &tret, y, NULL);
        if (r == DAE_SUCCESS && n <= 8) q = y[vq];
        ok = r == DAE_SUCCESS && tret == 1.0 && fabs(q - q0 * exp(-k / R)) < 1e-7;
        if (!ok)
            fprintf(stderr, "cmake_check: %s (%s), q(1) = %.17g\n", dae_return_name(r),
                    s ? dae_get_error(s)->message : err.message, q);
        dae_free(&s);
    } else {
        fprintf(stderr, "cmake_check: model: %s\n", bgr_model_error(m)->message);
    }
    bgr_model_free(&m);
    if (ok) printf("cmake_check: bgdae %s, q(1) = %.12f\n", BGDAE_VERSION, q);
    return ok ? 0 : 1;
}
