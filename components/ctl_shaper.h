/* Input shaping of a reference: the zero-vibration (ZV) and zero-vibration-derivative (ZVD)
 * shapers of N. C. Singer and W. P. Seering, "Preshaping command inputs to reduce system
 * vibration", ASME J. Dyn. Sys. Meas. Control 112 (1990) 76-82.
 *
 * A shaper is a sequence of impulses (amplitudes A_i summing to 1, times t_i, t_0 = 0); the
 * shaped reference is the reference convolved with it,
 *   r_s(t) = sum_i A_i r(t - t_i),
 * which reaches the same final value, later by the shaper's length t_N. For a mode of natural
 * angular frequency w and damping ratio z (w_d = w sqrt(1 - z^2), K = exp(-z pi / sqrt(1 - z^2)),
 * T_d = 2 pi / w_d):
 *   ZV:  A = [1, K] / (1 + K),             t = [0, T_d / 2]
 *   ZVD: A = [1, 2K, K^2] / (1 + K)^2,     t = [0, T_d / 2, T_d]
 * The residual vibration of a mode (w, z) excited by the impulses, relative to that of a single
 * unit impulse (Singer and Seering, Eq. 3):
 *   V(w, z) = exp(-z w t_N) sqrt((sum_i A_i exp(z w t_i) cos(w_d t_i))^2
 *                                + (sum_i A_i exp(z w t_i) sin(w_d t_i))^2),
 * zero at the design mode for both shapers; for the undamped ZV shaper designed at w0 and a
 * mode at w, V = |cos(pi w / (2 w0))|. By linearity, a linear system driven by r_s has after
 * the reference's end the residual vibration of the mode V times the one r itself leaves.
 *
 * The shaped reference of a piecewise linear r (knots t_k, values v_k, constant outside) is
 * piecewise linear again with the knots t_k + t_i: ctl_shaped_pwl builds it as a sig_pwl
 * (sig_sources.h), with its value, rate or integral as output and its knots as breakpoints. The
 * shaper's frequency may be given, or taken from the model's modes (the crane-compare program
 * finds the load's pendulum mode with bgr_modes at the static start and passes it on). */
#ifndef CTL_SHAPER_H
#define CTL_SHAPER_H

#include "bg_api.h"
#include "bgr_model.h"
#include "sig_sources.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum ctl_shaper_kind { CTL_SHAPER_ZV = 0, CTL_SHAPER_ZVD = 1 } ctl_shaper_kind;

#define CTL_SHAPER_MAX 3

/* The impulses of a shaper for the mode of frequency freq_hz (> 0, finite) and damping ratio
 * zeta (in [0, 1)): A[], t[] (CTL_SHAPER_MAX each). Returns their number, or BG_ERR_ARGUMENT
 * (negative) for a kind, frequency or damping out of range. */
BG_API int ctl_shaper_impulses(ctl_shaper_kind kind, double freq_hz, double zeta, double *A,
                               double *t);

/* V(w, z) above for n impulses (A, t) and a mode of angular frequency omega > 0, damping
 * zeta in [0, 1). NaN for arguments out of range. */
BG_API double ctl_shaper_vibration(int n, const double *A, const double *t, double omega,
                                   double zeta);

/* A sig_pwl of r_s = sum_i A_i r(t - t_i) for the piecewise linear r through (t[k], v[k]),
 * k < n (n >= 1, t strictly increasing), shaped for (freq_hz, zeta). Returns the element id or
 * < 0 with the message in the model's error record (the arguments checked as above and as
 * sig_pwl checks them). */
BG_API int ctl_shaped_pwl(bgr_model *m, bgr_comp c, const char *name, int n, const double *t,
                          const double *v, ctl_shaper_kind kind, double freq_hz, double zeta,
                          sig_output out);

#ifdef __cplusplus
}
#endif
#endif
