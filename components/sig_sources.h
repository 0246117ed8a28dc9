/* Signal sources: functions of time as signals of the model, with their corners as breakpoints.
 *
 * Every source is an element without ports with one algebraic unknown z of its own, the signal
 * (named "value", "rate" or "integral"; other elements read it as bgr_ref {BGR_OWN, id, 0}), and
 * one equation ("signal"):
 *   z = g(t),   g = u (SIG_VALUE), u' (SIG_RATE) or integral_0^t u(s) ds (SIG_INTEGRAL),
 * for the source function u below, all three in closed form (no numerical differentiation or
 * quadrature):
 *   trapezoid  0 for t <= t0, rising linearly to h at t1, h until t2, falling linearly to 0 at
 *              t3, 0 after (t0 < t1 <= t2 < t3): a point-to-point velocity profile (constant
 *              acceleration, cruise, constant deceleration). With t0 = 0, t1 = 2, t2 = 10,
 *              t3 = 12, h = 0.5:
 *                u = 0.25 t (t <= 2), 0.5 (2 < t <= 10), 0.25 (12 - t) (10 < t <= 12),
 *                0 (t > 12);
 *              its integral is 0.125 t^2, 0.5 t - 0.5, ..., and 5 from t = 12 on.
 *   pwl        piecewise linear through (t_k, v_k), k = 0 .. n-1, t_k strictly increasing,
 *              constant v_0 before t_0 and v_{n-1} after t_{n-1}.
 *   step       before for t <= t_s, after for t > t_s.
 *   ramp       offset for t <= t_s, offset + slope (t - t_s) after.
 *   sine       offset + a sin(w t + phi).
 *   constant   value.
 * Breakpoints (the element class's breakpoints hook, collected by bgr_breakpoints for
 * dae_options.breakpoints): the times where u is not smooth (the knots of pwl and trapezoid,
 * t_s of step and ramp; none for sine and constant), whatever the output. At a breakpoint
 * itself the functions take their left limit (u' there is the slope before it), so that the step
 * that lands on it sees a smooth function; the solver restarts there.
 * A signal that jumps at a breakpoint (the value of a step; the rate at a corner of the
 * trapezoid, of pwl or of a ramp) is an algebraic unknown with a jump: the integrator must
 * restart there from the right limits (and start from them when a corner coincides with the
 * initial time). bg_dae (at the time of writing) restarts from values
 * computed at the breakpoint itself, i.e. the left limits, and its error test then fails; until
 * it takes the right limits, restart by hand at nextafter(t_b, INFINITY) with dae_reinit and
 * dae_consistent_init (tests/components/test_ctl_pid.c and test_sig_sources.c do so). Continuous
 * outputs (values of trapezoid, pwl, ramp, sine; every integral) need nothing of the kind.
 * Nominal magnitude of the signal (bgr_declare_nominal): the largest |z| the parameters bound:
 * max |v_k| (values of pwl, trapezoid, constant, step), the steepest slope (rates of pwl and
 * trapezoid, |slope| of a ramp), |a| + |offset| and |a omega| (sine), the largest |integral| at
 * the knots when the function ends at 0 (trapezoid); none (1) where the output is unbounded or 0.
 * The integrals and derivatives are exact (piecewise polynomials integrated and differentiated
 * piece by piece). */
#ifndef SIG_SOURCES_H
#define SIG_SOURCES_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sig_output { SIG_VALUE = 0, SIG_RATE = 1, SIG_INTEGRAL = 2 } sig_output;

/* Each returns the element id (signal bgr_ref {BGR_OWN, id, 0}) or < 0 (message in the model's
 * error record). Accepted: out one of the three outputs; every number finite (times, values,
 * height, slope, offset, amplitude, omega, phase: any sign); trapezoid t0 < t1 <= t2 < t3; pwl
 * n >= 1 points, t and v not NULL, t strictly increasing; pwl and trapezoid with finite slopes
 * and segment areas (no overflow from knots too close or values too large). Anything else gives
 * BG_ERR_ARGUMENT before anything is built, with a message naming the signal's path and the
 * parameter (nothing is added to the model). */
BG_API int sig_trapezoid(bgr_model *m, bgr_comp c, const char *name, double t0, double t1,
                         double t2, double t3, double height, sig_output out);
BG_API int sig_pwl(bgr_model *m, bgr_comp c, const char *name, int n, const double *t,
                   const double *v, sig_output out);
BG_API int sig_step(bgr_model *m, bgr_comp c, const char *name, double t_step, double before,
                    double after, sig_output out);
BG_API int sig_ramp(bgr_model *m, bgr_comp c, const char *name, double t_start, double slope,
                    double offset, sig_output out);
BG_API int sig_sine(bgr_model *m, bgr_comp c, const char *name, double amplitude, double omega,
                    double phase, double offset, sig_output out);
BG_API int sig_constant(bgr_model *m, bgr_comp c, const char *name, double value, sig_output out);

/* The source function of signal element id at t: u(t), u'(t) and its integral from 0 to t (any
 * pointer may be NULL). BG_OK, or BG_ERR_ARGUMENT if id is not a signal source. */
BG_API int sig_evaluate(bgr_model *m, int id, double t, double *value, double *rate,
                        double *integral);

/* The output (SIG_VALUE, SIG_RATE, SIG_INTEGRAL) of signal element id; BG_ERR_ARGUMENT if id
 * is not a signal source. */
BG_API int sig_source_output(bgr_model *m, int id);

BG_API extern const bgr_element_class sig_class_source;

#ifdef __cplusplus
}
#endif
#endif
