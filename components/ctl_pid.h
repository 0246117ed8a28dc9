/* PID controller in parallel form, with optional smooth output limits.
 *
 * Control law (the parallel form of Astrom and Hagglund, cited below):
 *   x(t) = Kp err + Kd d(err)/dt + Ki integral(err dt),   err = r - y,
 * with r the reference (e.g. a reference angular velocity) and y the measured value (the
 * angular velocity, from a sensor such as mech_sensor or rot_sensor). The derivative of the
 * error is not differenced from samples: it is err' = r' - y', with r' and y' signals of the
 * model, the reference's derivative given analytically (sig_sources, SIG_RATE) and the measured
 * one algebraic (rot_sensor, ROT_ACCELERATION: the net torque on the driven inertia over its J).
 * So y' of another element never enters this element's algebraic equation and the system stays
 * semi-explicit.
 *
 * No ports; a state I = integral of err (named "integral", bgr_ref {BGR_STATE, id, 0}, starting
 * from its initial value, 0 by default) and an algebraic output u (named "out",
 * {BGR_OWN, id, 0}). Equations:
 *   I' = r - y                                                          ("integral")
 *   u  = sat(Kp (r - y) + Kd (r' - y') + Ki I)                          ("output")
 * sat is the identity without limits. With limits [u_min, u_max] it is the smooth clamp
 *   sat(v) = u_min + sp(v - u_min) - sp(v - u_max),  sp(z) = eps ln(1 + exp(z / eps)),
 * which differs from the hard clamp min(max(v, u_min), u_max) by at most eps ln 2 (at the
 * corners; exponentially less a few eps away from them) and keeps u_min < u < u_max
 * (cmp_internal.h derives the bound). Without r' (use_reference_rate = 0) the reference is taken
 * constant (r' = 0), i.e. the derivative acts on the measurement only. No anti-windup: the
 * integral keeps growing while the output is limited.
 * Derivative filter (derivative_filter = tau > 0): the measured rate is not read from a signal
 * but estimated by a first-order filter of the measurement, the usual practical PID form
 * Kd s / (1 + tau s) on y (K. J. Astrom, T. Hagglund, PID Controllers: Theory, Design and Tuning,
 * ISA 1995, the derivative term with limited high-frequency gain). A second state z ("filter",
 * {BGR_STATE, id, 1}; start it at the measurement's initial value) with
 *   z' = (y - z) / tau                                                  ("filter")
 * and y' replaced by (y - z) / tau in the output. Use it when the measured acceleration would be
 * an index-2 quantity (a constraint reaction over an inertia): the output then depends on states
 * only, and the error control sees no index-2 noise through it.
 * Note: with Kd != 0 and r' given, the output jumps where r' jumps (the corners of the
 * trapezoidal reference): those times are the reference's breakpoints, where the integrator
 * must restart from the right limits (see the note in sig_sources.h).
 * Nominal magnitudes (bgr_declare_nominal): with limits, the output u gets the output range
 * max(|u_min|, |u_max|) and the integral I that range over |Ki| (the integral that alone drives
 * the output to its limit); without limits nothing is declared (the gains give no scale).
 *
 * Extensions (each off by default: a zeroed spec is the controller above exactly):
 * Setpoint weighting (weighted = 1, weights b and c; Astrom and Hagglund 1995, Sec. 3.4, the
 * "two-degree-of-freedom" PID): the proportional and derivative terms act on b r - y and
 * c r' - y' while the integral keeps the full error r - y, so that the steady state is still
 * y = r; b < 1 softens the response to reference changes without changing the response to
 * disturbances. Unweighted: b = c = 1.
 * Feedforward (use_feedforward = 1, signal f): f is added before the limit,
 *   v = Kp (b r - y) + Kd (c r' - y') + Ki I + f,   u = sat(v),
 * e.g. the pump displacement a reference rate needs (ctl_feedforward.h), so that the PID
 * corrects only what the feedforward misses.
 * Anti-windup by back-calculation (tracking_time Tt > 0, with limits and Ki != 0; Astrom and
 * Hagglund 1995, Sec. 3.5): while the output is held by the limit, the integral is driven back
 * towards the value that makes v = u, with time constant Tt:
 *   I' = (r - y) + (u - v) / (Ki Tt)                                   ("integral")
 * In range u = v (up to the smooth limit's eps ln 2) and the integral is the plain one; at the
 * limit the integral settles where Ki I = u - (the other terms) + Ki Tt (r - y), so that the
 * output leaves the limit as soon as the error changes sign instead of after the integral has
 * unwound. A common choice is Tt = sqrt(Ti Td) with Ti = Kp / Ki, Td = Kd / Kp. */
#ifndef CTL_PID_H
#define CTL_PID_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ctl_pid_spec {
    double kp, ki, kd;      /* gains: finite, any sign */
    bgr_ref reference;      /* r */
    bgr_ref measurement;    /* y */
    int use_reference_rate; /* 1: reference_rate holds r'; 0: r' = 0 */
    bgr_ref reference_rate;
    int use_measurement_rate; /* 1: measurement_rate holds y'; kd != 0 needs it or a filter */
    bgr_ref measurement_rate;
    double derivative_filter; /* tau > 0: y' estimated by the filter (y - z) / tau; 0: none */
    int limit;                /* 1: smooth limits [out_min, out_max] of width smoothing > 0 */
    double out_min, out_max, smoothing; /* with limit: finite, out_min < out_max, smoothing > 0 */
    int weighted;           /* 1: setpoint weights b, c (finite); 0: b = c = 1 */
    double b, c;
    int use_feedforward; /* 1: the signal feedforward is added before the limit */
    bgr_ref feedforward;
    double tracking_time; /* Tt > 0: anti-windup by back-calculation (needs limit, ki != 0) */
} ctl_pid_spec;

/* Returns the element id (its output is bgr_ref {BGR_OWN, id, 0}) or < 0 (message in the
 * model's error record). Accepted: spec not NULL; kp, ki, kd finite (any sign);
 * derivative_filter finite and >= 0 (0: none; > 0 with a finite 1 / tau), not together with
 * use_measurement_rate; kd != 0 only with the measured rate or the filter; with limit: out_min
 * and out_max finite with out_min < out_max, smoothing finite and > 0 (the limits are not read
 * without limit); with weighted: b and c finite; tracking_time finite and >= 0, > 0 only with
 * limit and ki != 0. Anything else gives BG_ERR_ARGUMENT before anything is built, with a message
 * naming the controller's path and the parameter (nothing is added to the model). The signals
 * are resolved by bgr_compile, which reports one that names no unknown. */
BG_API int ctl_pid(bgr_model *m, bgr_comp c, const char *name, const ctl_pid_spec *spec);

BG_API extern const bgr_element_class ctl_class_pid;

#ifdef __cplusplus
}
#endif
#endif
