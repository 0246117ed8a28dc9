/* A user's controller: a C function of time and signals, as an element with signal inputs and
 * outputs.
 *
 * With inputs x_1..x_n (signals, bgr_ref) and outputs u_1..u_m (the element's own algebraic
 * unknowns {BGR_OWN, id, j}), the equations are
 *   u_j = f_j(t, x),   j = 1..m                                              ("output j")
 * f is the callback; it fills out[m] and, when jac is not NULL, jac[j + i m] = d f_j / d x_i (m x n,
 * column-major). A callback that has no derivatives sets has_jacobian = 0: they are then taken
 * by central differences with the step h_i = 1e-6 (|x_i| + scale_i) (scale_i: the spec's, 1 when
 * 0). f must be smooth in x (the Newton iteration and the BDF error estimate need it) and may
 * depend on t only continuously; a law with a state is written with states of other elements
 * (an integrator is ctl_pid with kp = 0, ki = 1, or ctl_state_feedback's integral form). It
 * returns 0, or non-zero to refuse the point (the residual reports a failure, the step is
 * retried smaller).
 *
 * Example: a saturated proportional law with a velocity feedforward,
 *
 *   static int law(void *user, double t, const double *x, double *u, double *jac)
 *   {
 *       const double *k = user;                 // gains: kp, kff
 *       double v = k[0] * (x[0] - x[1]) + k[1] * x[2], th = tanh(v);
 *       u[0] = th;                              // a smooth limit to (-1, 1)
 *       if (jac) {
 *           double d = 1 - th * th;
 *           jac[0] = d * k[0];  jac[1] = -d * k[0];  jac[2] = d * k[1];
 *       }
 *       return 0;
 *   }
 *   static double gains[2] = {5, 0.05};
 *   ctl_user_spec s = {.n_in = 3, .n_out = 1, .fn = law, .user = gains, .has_jacobian = 1,
 *                      .in = {omega_ref, omega_measured, omega_ref}};
 *   int id = ctl_user(m, 0, "my_controller", &s);  // its output: {BGR_OWN, id, 0}
 *
 * (tests/components/test_ctl_user.c runs a law of this kind in a closed loop against its closed
 * form). */
#ifndef CTL_USER_H
#define CTL_USER_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

#define CTL_USER_MAX 16

typedef int (*ctl_user_fn)(void *user, double t, const double *x, double *u, double *jac);

typedef struct ctl_user_spec {
    int n_in, n_out; /* 1..CTL_USER_MAX each */
    bgr_ref in[CTL_USER_MAX];
    double scale[CTL_USER_MAX]; /* the inputs' magnitudes for the differences (0: 1) */
    ctl_user_fn fn;
    void *user;       /* the callback's, kept by the caller */
    int has_jacobian; /* 1: fn fills jac when asked */
} ctl_user_spec;

/* Returns the element id or < 0 (message in the model's error record). Accepted: spec and fn
 * not NULL, n_in and n_out in 1..CTL_USER_MAX, scales finite and >= 0. */
BG_API int ctl_user(bgr_model *m, bgr_comp c, const char *name, const ctl_user_spec *spec);

BG_API extern const bgr_element_class ctl_class_user;

#ifdef __cplusplus
}
#endif
#endif
