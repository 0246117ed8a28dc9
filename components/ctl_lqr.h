/* State feedback designed by the linear-quadratic regulator (LQR), and the feedback element.
 *
 * Design (ctl_lqr): for the linear model x' = A x + B u (n states, m inputs) and the cost
 *   J = integral (x^T Q x + u^T R u) dt,   Q symmetric >= 0, R symmetric > 0,
 * the optimal law is u = -K x with K = R^-1 B^T P, P the stabilising solution of the continuous
 * algebraic Riccati equation
 *   A^T P + P A - P B R^-1 B^T P + Q = 0.
 * P is found by the Schur method of A. J. Laub, "A Schur method for solving algebraic Riccati
 * equations", IEEE Trans. Autom. Control 24 (1979) 913-921: the Hamiltonian matrix
 *   H = [ A   -B R^-1 B^T ]
 *       [ -Q  -A^T        ]
 * has its 2n eigenvalues in pairs (s, -s); its real Schur form H U = U T, ordered so that the n
 * eigenvalues with Re s < 0 come first (LAPACK dgees with a selection function), gives the
 * stable invariant subspace spanned by U's first n columns [U11; U21], and P = U21 U11^-1
 * (symmetrised). A stabilisable (A, B) and detectable (Q^1/2, A) make U11 invertible; otherwise
 * (an eigenvalue of H on the imaginary axis, U11 singular) the design is refused.
 *
 * Feedback element (ctl_state_feedback): n measured signals x_i with optional references r_i
 * (the deviations e_i = x_i - r_i are the design model's states), gains K_i, and an optional
 * bias signal b (with its rate b' for the integrating form). Two forms:
 *   value:      u = b - sum_i K_i e_i                                           ("output")
 *   integral:   w' = -sum_i K_i e_i                                             ("integral")
 *               u = b + w,   rate = b' - sum_i K_i e_i                 ("output", "rate")
 * The integrating form serves a design whose input is the rate of the command (the crane's: the
 * platform's angular acceleration as input, the commanded rate u = omega_ref + w fed to the rate
 * loop as its reference and `rate` as its reference's rate). Signals: u (own 0), in the
 * integral form rate (own 1) and w (state 0, named "integral"). The measured quantities a
 * crane design needs are named in docs/control.md (angle and rate errors of the platform, the
 * load's sway and sway rate from ctl_sway.h). */
#ifndef CTL_LQR_H
#define CTL_LQR_H

#include "bg_api.h"
#include "bg_status.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

#define CTL_SF_MAX 16

/* The LQR gain K (m x n, column-major, K[i + j m]) of A (n x n), B (n x m), Q (n x n), R (m x m),
 * all column-major; P (n x n) may be NULL. n in 1..CTL_SF_MAX, m in 1..n. BG_OK, BG_ERR_ARGUMENT
 * (a size out of range, a NULL matrix, a value not finite, R not positive definite),
 * BG_ERR_SINGULAR (no stabilising solution: H has eigenvalues on the imaginary axis or U11 is
 * singular), BG_ERR_MEMORY or BG_ERR_LIBRARY (LAPACK failed); the message in err (may be NULL). */
BG_API int ctl_lqr(int n, int m, const double *A, const double *B, const double *Q,
                   const double *R, double *K, double *P, bg_error *err);

typedef struct ctl_sf_spec {
    int n;                       /* 1..CTL_SF_MAX measured signals */
    double gain[CTL_SF_MAX];     /* K_i, finite */
    bgr_ref x[CTL_SF_MAX];       /* measured */
    int use_ref[CTL_SF_MAX];     /* 1: r_i given */
    bgr_ref r[CTL_SF_MAX];
    int integrate;               /* 0: value form, 1: integral form */
    int use_bias, use_bias_rate; /* b, b' (b' only in the integral form) */
    bgr_ref bias, bias_rate;
} ctl_sf_spec;

/* Returns the element id or < 0 (message in the model's error record). Accepted: spec not
 * NULL, n in 1..CTL_SF_MAX, gains finite, use_bias_rate only with integrate. */
BG_API int ctl_state_feedback(bgr_model *m, bgr_comp c, const char *name, const ctl_sf_spec *spec);

BG_API extern const bgr_element_class ctl_class_state_feedback;

#ifdef __cplusplus
}
#endif
#endif
