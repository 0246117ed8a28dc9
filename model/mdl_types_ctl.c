/* Model-file types of the control library: the PID controller (ctl_pid.h), the feedforward
 * (ctl_feedforward.h), the input shaper (ctl_shaper.h), the state feedback with its LQR design
 * (ctl_lqr.h), the sway sensor (ctl_sway.h), the signal sources (sig_sources.h) and the signal
 * gain (bgr_gain of bgr_elements.h). The user's callback controller (ctl_user.h) is C only. None has ports: each offers
 * signals (its algebraic output, its states) and reads others' through MDL_SIGNAL parameters.
 * The equations are the headers', restated here for the type reference. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bgr_elements.h"
#include "ctl_feedforward.h"
#include "ctl_lqr.h"
#include "ctl_pid.h"
#include "ctl_shaper.h"
#include "ctl_sway.h"
#include "mdl_impl.h"
#include "sig_sources.h"

#define INF HUGE_VAL
#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

/* an element without ports whose output (own unknown 0) is the signal `sig` */
static int output(bgr_model *m, int id, const char *sig, mdl_instance *out, bg_error *err)
{
    if (id < 0) return mdl_fail_model(err, m, id);
    int r = mdl_instance_element(out, id);
    if (r == BG_OK) r = mdl_instance_signal(out, sig, (bgr_ref){BGR_OWN, id, 0});
    return r;
}

/* ---- ctl.pid ---- */

static const mdl_param_def pid_params[] = {
    {"kp", MDL_NUMBER, 0, "-", NULL, -INF, INF, MDL_FINITE, NULL,
     "proportional gain (units of u per unit of r)"},
    {"ki", MDL_NUMBER, 0, "-", "0", -INF, INF, MDL_FINITE, NULL, "integral gain (per second)"},
    {"kd", MDL_NUMBER, 0, "-", "0", -INF, INF, MDL_FINITE, NULL,
     "derivative gain (seconds); != 0 needs measurement_rate or derivative_filter"},
    {"reference", MDL_SIGNAL, 0, "-", NULL, 0, 0, 0, NULL, "the reference r"},
    {"measurement", MDL_SIGNAL, 0, "-", NULL, 0, 0, 0, NULL, "the measured value y"},
    {"reference_rate", MDL_SIGNAL, 0, "-", NULL, 0, 0, MDL_OPTIONAL, NULL,
     "r' (left out: r' = 0, the derivative acts on the measurement only)"},
    {"measurement_rate", MDL_SIGNAL, 0, "-", NULL, 0, 0, MDL_OPTIONAL, NULL,
     "y' (e.g. rot.sensor of the acceleration); not with derivative_filter"},
    {"derivative_filter", MDL_NUMBER, 0, "s", "0", 0, INF, 0, NULL,
     "tau > 0: y' estimated by the filter (y - z) / tau (state z); 0: none"},
    {"out_min", MDL_NUMBER, 0, "-", NULL, -INF, INF, MDL_OPTIONAL | MDL_FINITE, NULL,
     "lower output limit (with out_max; left out, both: no limits)"},
    {"out_max", MDL_NUMBER, 0, "-", NULL, -INF, INF, MDL_OPTIONAL | MDL_FINITE, NULL,
     "upper output limit, > out_min"},
    {"smoothing", MDL_NUMBER, 0, "-", NULL, 0, INF, MDL_OPTIONAL | MDL_LO_OPEN, NULL,
     "width eps of the smooth limits (left out: 1 % of out_max - out_min)"},
    {"b", MDL_NUMBER, 0, "1", "1", -INF, INF, MDL_FINITE, NULL,
     "setpoint weight of the proportional term: Kp (b r - y)"},
    {"c", MDL_NUMBER, 0, "1", "1", -INF, INF, MDL_FINITE, NULL,
     "setpoint weight of the derivative term: Kd (c r' - y')"},
    {"feedforward", MDL_SIGNAL, 0, "-", NULL, 0, 0, MDL_OPTIONAL, NULL,
     "a signal f added before the limit (e.g. ctl.feedforward's u)"},
    {"tracking_time", MDL_NUMBER, 0, "s", "0", 0, INF, 0, NULL,
     "Tt > 0: anti-windup by back-calculation, I' = r - y + (u - v) / (Ki Tt); needs the "
     "limits and ki != 0"},
};
static const mdl_signal_def pid_signals[] = {
    {"u", "-", "the controller's output"},
    {"integral", "-", "the integral I of the error (a state)"},
    {"filter", "-", "the filtered measurement z (a state; with derivative_filter > 0 only)"},
};

static int pid_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                     mdl_instance *out, bg_error *err)
{
    ctl_pid_spec s;
    memset(&s, 0, sizeof s);
    s.kp = mdl_arg_num(a, "kp");
    s.ki = mdl_arg_num(a, "ki");
    s.kd = mdl_arg_num(a, "kd");
    s.reference = mdl_arg_signal(a, "reference");
    s.measurement = mdl_arg_signal(a, "measurement");
    if ((s.use_reference_rate = mdl_arg_has(a, "reference_rate")))
        s.reference_rate = mdl_arg_signal(a, "reference_rate");
    if ((s.use_measurement_rate = mdl_arg_has(a, "measurement_rate")))
        s.measurement_rate = mdl_arg_signal(a, "measurement_rate");
    s.derivative_filter = mdl_arg_num(a, "derivative_filter");
    if (s.use_measurement_rate && s.derivative_filter > 0)
        return bg_error_raise(
            err, BG_ERR_ARGUMENT, "model",
            "measurement_rate: given with derivative_filter = %g: one or the other",
            s.derivative_filter);
    if (s.kd != 0 && !s.use_measurement_rate && !(s.derivative_filter > 0))
        return bg_error_raise(
            err, BG_ERR_ARGUMENT, "model",
            "kd: %g needs measurement_rate (e.g. a rot.sensor of the acceleration) or "
            "derivative_filter > 0",
            s.kd);
    int lo = mdl_arg_has(a, "out_min"), hi = mdl_arg_has(a, "out_max");
    if (lo != hi)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "model", "%s: give both limits or neither",
                              lo ? "out_max" : "out_min");
    if (!lo && mdl_arg_has(a, "smoothing"))
        return bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                              "smoothing: given without out_min and out_max");
    if ((s.limit = lo)) {
        s.out_min = mdl_arg_num(a, "out_min");
        s.out_max = mdl_arg_num(a, "out_max");
        if (!(s.out_max > s.out_min))
            return bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                                  "out_max: %g, expected > out_min = %g", s.out_max, s.out_min);
        s.smoothing = mdl_arg_has(a, "smoothing") ? mdl_arg_num(a, "smoothing")
                                                  : 0.01 * (s.out_max - s.out_min);
    }
    s.b = mdl_arg_num(a, "b");
    s.c = mdl_arg_num(a, "c");
    s.weighted = s.b != 1 || s.c != 1;
    if ((s.use_feedforward = mdl_arg_has(a, "feedforward")))
        s.feedforward = mdl_arg_signal(a, "feedforward");
    s.tracking_time = mdl_arg_num(a, "tracking_time");
    if (s.tracking_time > 0 && (!s.limit || s.ki == 0))
        return bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                              "tracking_time: %g (anti-windup) needs out_min, out_max and ki != 0",
                              s.tracking_time);
    int id = ctl_pid(m, c, name, &s);
    int r = output(m, id, "u", out, err);
    if (r == BG_OK) r = mdl_instance_signal(out, "integral", (bgr_ref){BGR_STATE, id, 0});
    if (r == BG_OK && s.derivative_filter > 0)
        r = mdl_instance_signal(out, "filter", (bgr_ref){BGR_STATE, id, 1});
    return r;
}

static const mdl_type pid_type = {
    "ctl.pid",
    "PID controller: smooth output limits, derivative filter, setpoint weights, feedforward, "
    "anti-windup (ctl_pid.h)",
    "I' = r - y                                         integral (state I)\n"
    "u  = sat(v),  v = Kp (b r - y) + Kd (c r' - y') + Ki I + f      output\n"
    "with tracking_time Tt > 0: I' = r - y + (u - v) / (Ki Tt)  (anti-windup)\n"
    "sat(v) = u_min + sp(v - u_min) - sp(v - u_max),  sp(z) = eps ln(1 + exp(z / eps))\n"
    "       (the identity without limits)\n"
    "with derivative_filter tau > 0:  z' = (y - z) / tau  (state z),  y' = (y - z) / tau",
    pid_params, COUNT(pid_params), NULL, 0, pid_signals, COUNT(pid_signals), 0, pid_build, NULL,
    NULL};

/* ---- signal sources ---- */

#define OUTPUT                                                                                     \
    {"output", MDL_CHOICE, 0, "-", "value", 0, 0, 0, "value|rate|integral",                        \
     "y = u(t), its derivative u'(t) or its integral from 0 to t"}
#define SIG_EQS "\ny = u, u' or integral_0^t u ds  (`output`), in closed form"

static const mdl_signal_def source_signals[] = {
    {"y", "-", "the source's output (the unit of what it stands for)"}};

static sig_output output_of(const mdl_args *a)
{
    const char *o = mdl_arg_choice(a, "output");
    return !strcmp(o, "rate") ? SIG_RATE : !strcmp(o, "integral") ? SIG_INTEGRAL : SIG_VALUE;
}

/* the start: y at t = 0, the source's own equation (mdl_place_source) */
static int source_place(bgr_model *m, const mdl_instance *in, const mdl_args *a, mdl_locator *loc,
                        bg_error *err)
{
    (void)a, (void)loc;
    return mdl_place_source(m, mdl_instance_main(in), MDL_SRC_SIGNAL, NULL, err);
}

#define SOURCE_TYPE(var, tname, summary, eqs, params, build)                                       \
    static const mdl_type var = {tname,          summary,                eqs SIG_EQS,              \
                                 params,         COUNT(params),          NULL,                     \
                                 0,              source_signals,         COUNT(source_signals),    \
                                 0,              build,                  source_place,             \
                                 NULL}

static const mdl_param_def trap_params[] = {
    {"t0", MDL_NUMBER, 0, "s", NULL, -INF, INF, MDL_FINITE, NULL, "start of the rise"},
    {"t1", MDL_NUMBER, 0, "s", NULL, -INF, INF, MDL_FINITE, NULL, "end of the rise, > t0"},
    {"t2", MDL_NUMBER, 0, "s", NULL, -INF, INF, MDL_FINITE, NULL, "start of the fall, >= t1"},
    {"t3", MDL_NUMBER, 0, "s", NULL, -INF, INF, MDL_FINITE, NULL, "end of the fall, > t2"},
    {"height", MDL_NUMBER, 0, "-", NULL, -INF, INF, MDL_FINITE, NULL, "the plateau h"},
    OUTPUT,
};

static int trap_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                      mdl_instance *out, bg_error *err)
{
    int id =
        sig_trapezoid(m, c, name, mdl_arg_num(a, "t0"), mdl_arg_num(a, "t1"), mdl_arg_num(a, "t2"),
                      mdl_arg_num(a, "t3"), mdl_arg_num(a, "height"), output_of(a));
    return output(m, id, "y", out, err);
}

SOURCE_TYPE(trap_type, "sig.trapezoid", "trapezoidal profile (sig_sources.h)",
            "u = 0 (t <= t0), linear to h at t1, h until t2, linear to 0 at t3, 0 after",
            trap_params, trap_build);

static const mdl_param_def pwl_params[] = {
    {"times", MDL_VECTOR, 0, "s", NULL, -INF, INF, MDL_FINITE, NULL,
     "the knots t_k, strictly increasing"},
    {"values", MDL_VECTOR, 0, "-", NULL, -INF, INF, MDL_FINITE, NULL,
     "the values v_k, as many as times"},
    OUTPUT,
};

static int pwl_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                     mdl_instance *out, bg_error *err)
{
    int nt, nv;
    const double *t = mdl_arg_vec(a, "times", &nt), *v = mdl_arg_vec(a, "values", &nv);
    if (nt != nv)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                              "values: %d of them, expected as many as "
                              "times (%d)",
                              nv, nt);
    for (int k = 1; k < nt; k++)
        if (!(t[k] > t[k - 1]))
            return bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                                  "times[%d] = %g, expected > times[%d] "
                                  "= %g (strictly increasing)",
                                  k, t[k], k - 1, t[k - 1]);
    return output(m, sig_pwl(m, c, name, nt, t, v, output_of(a)), "y", out, err);
}

SOURCE_TYPE(pwl_type, "sig.pwl", "piecewise linear through points (sig_sources.h)",
            "u = linear between (t_k, v_k), v_0 before t_0, v_(n-1) after t_(n-1)", pwl_params,
            pwl_build);

static const mdl_param_def step_params[] = {
    {"t_step", MDL_NUMBER, 0, "s", NULL, -INF, INF, MDL_FINITE, NULL, "the time of the step"},
    {"before", MDL_NUMBER, 0, "-", "0", -INF, INF, MDL_FINITE, NULL, "the value up to t_step"},
    {"after", MDL_NUMBER, 0, "-", NULL, -INF, INF, MDL_FINITE, NULL, "the value after t_step"},
    OUTPUT,
};

static int step_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                      mdl_instance *out, bg_error *err)
{
    int id = sig_step(m, c, name, mdl_arg_num(a, "t_step"), mdl_arg_num(a, "before"),
                      mdl_arg_num(a, "after"), output_of(a));
    return output(m, id, "y", out, err);
}

SOURCE_TYPE(step_type, "sig.step", "step (sig_sources.h)",
            "u = before (t <= t_step), after (t > t_step)", step_params, step_build);

static const mdl_param_def ramp_params[] = {
    {"t_start", MDL_NUMBER, 0, "s", "0", -INF, INF, MDL_FINITE, NULL, "where the ramp starts"},
    {"slope", MDL_NUMBER, 0, "1/s", NULL, -INF, INF, MDL_FINITE, NULL,
     "its slope (units of y per second)"},
    {"offset", MDL_NUMBER, 0, "-", "0", -INF, INF, MDL_FINITE, NULL, "the value up to t_start"},
    OUTPUT,
};

static int ramp_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                      mdl_instance *out, bg_error *err)
{
    int id = sig_ramp(m, c, name, mdl_arg_num(a, "t_start"), mdl_arg_num(a, "slope"),
                      mdl_arg_num(a, "offset"), output_of(a));
    return output(m, id, "y", out, err);
}

SOURCE_TYPE(ramp_type, "sig.ramp", "ramp (sig_sources.h)",
            "u = offset (t <= t_start), offset + slope (t - t_start) after", ramp_params,
            ramp_build);

static const mdl_param_def sine_params[] = {
    {"amplitude", MDL_NUMBER, 0, "-", NULL, -INF, INF, MDL_FINITE, NULL, "the amplitude a"},
    {"omega", MDL_NUMBER, 0, "rad/s", NULL, -INF, INF, MDL_FINITE, NULL, "the angular frequency w"},
    {"phase", MDL_NUMBER, 0, "rad", "0", -INF, INF, MDL_FINITE, NULL, "the phase phi"},
    {"offset", MDL_NUMBER, 0, "-", "0", -INF, INF, MDL_FINITE, NULL, "the mean"},
    OUTPUT,
};

static int sine_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                      mdl_instance *out, bg_error *err)
{
    int id = sig_sine(m, c, name, mdl_arg_num(a, "amplitude"), mdl_arg_num(a, "omega"),
                      mdl_arg_num(a, "phase"), mdl_arg_num(a, "offset"), output_of(a));
    return output(m, id, "y", out, err);
}

SOURCE_TYPE(sine_type, "sig.sine", "sine wave (sig_sources.h)", "u = offset + a sin(w t + phi)",
            sine_params, sine_build);

static const mdl_param_def const_params[] = {
    {"value", MDL_NUMBER, 0, "-", NULL, -INF, INF, MDL_FINITE, NULL, "the constant"},
    OUTPUT,
};

static int const_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                       mdl_instance *out, bg_error *err)
{
    int id = sig_constant(m, c, name, mdl_arg_num(a, "value"), output_of(a));
    return output(m, id, "y", out, err);
}

SOURCE_TYPE(const_type, "sig.constant", "constant (sig_sources.h)", "u = value", const_params,
            const_build);

/* ---- sig.gain ---- */

static const mdl_param_def gain_params[] = {
    {"input", MDL_SIGNAL, 0, "-", NULL, 0, 0, 0, NULL, "the signal x it scales"},
    {"gain", MDL_NUMBER, 0, "-", NULL, -INF, INF, MDL_FINITE, NULL, "the factor g (0 too)"},
};
static const mdl_signal_def gain_signals[] = {{"y", "-", "g x"}};

static int gain_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                      mdl_instance *out, bg_error *err)
{
    int id = bgr_gain(m, c, name, mdl_arg_signal(a, "input"), mdl_arg_num(a, "gain"));
    return output(m, id, "y", out, err);
}

static const mdl_type gain_type = {
    "sig.gain", "a signal times a constant (bgr_gain, bgr_elements.h)", "y = g x", gain_params,
    COUNT(gain_params), NULL, 0, gain_signals, COUNT(gain_signals), 0, gain_build, NULL, NULL};

/* ---- ctl.feedforward ---- */

static const mdl_param_def ff_params[] = {
    {"reference_rate", MDL_SIGNAL, 0, "rad/s", NULL, 0, 0, 0, NULL,
     "the reference rate omega_r of the load (e.g. a sig.trapezoid's value)"},
    {"ratio", MDL_NUMBER, 0, "1", NULL, -INF, INF, MDL_FINITE, NULL,
     "gear ratio i, motor turns per load turn (!= 0)"},
    {"motor_displacement", MDL_NUMBER, 0, "m^3/rev", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "the motor's displacement Dm"},
    {"pump_displacement", MDL_NUMBER, 0, "m^3/rev", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "the pump's displacement Dp at x = 1"},
    {"pump_speed", MDL_NUMBER, 0, "rad/s", NULL, -INF, INF, MDL_FINITE, NULL,
     "the pump's drive speed w_p (!= 0)"},
};
static const mdl_signal_def ff_signals[] = {{"u", "1", "the displacement command k omega_r"}};

static int ff_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                    mdl_instance *out, bg_error *err)
{
    ctl_ff_spec s = {.ratio = mdl_arg_num(a, "ratio"),
                     .motor_disp = mdl_arg_num(a, "motor_displacement"),
                     .pump_disp = mdl_arg_num(a, "pump_displacement"),
                     .pump_speed = mdl_arg_num(a, "pump_speed"),
                     .reference_rate = mdl_arg_signal(a, "reference_rate")};
    return output(m, ctl_feedforward(m, c, name, &s), "u", out, err);
}

static const mdl_type ff_type = {
    "ctl.feedforward", "the pump displacement a reference rate needs (ctl_feedforward.h)",
    "u = k omega_r,  k = i Dm / (Dp w_p)   (steady flow, no leakage)", ff_params,
    COUNT(ff_params), NULL, 0, ff_signals, COUNT(ff_signals), 0, ff_build, NULL, NULL};

/* ---- ctl.shaper ---- */

static const mdl_param_def shaper_params[] = {
    {"times", MDL_VECTOR, 0, "s", NULL, -INF, INF, MDL_FINITE, NULL,
     "the knots t_k of the reference r, strictly increasing"},
    {"values", MDL_VECTOR, 0, "-", NULL, -INF, INF, MDL_FINITE, NULL,
     "its values v_k, as many as times (a trapezoid: [0, h, h, 0])"},
    {"shaper", MDL_CHOICE, 0, "-", "zv", 0, 0, 0, "zv|zvd|none",
     "zero vibration (2 impulses), zero vibration derivative (3), or none (r itself)"},
    {"frequency", MDL_NUMBER, 0, "Hz", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "the natural frequency of the mode to cancel"},
    {"damping", MDL_NUMBER, 0, "1", "0", 0, 1, MDL_HI_OPEN, NULL, "its damping ratio"},
    OUTPUT,
};

static int shaper_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                        mdl_instance *out, bg_error *err)
{
    int nt, nv;
    const double *t = mdl_arg_vec(a, "times", &nt), *v = mdl_arg_vec(a, "values", &nv);
    if (nt != nv)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                              "values: %d of them, expected as many as times (%d)", nv, nt);
    for (int k = 1; k < nt; k++)
        if (!(t[k] > t[k - 1]))
            return bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                                  "times[%d] = %g, expected > times[%d] = %g (strictly "
                                  "increasing)",
                                  k, t[k], k - 1, t[k - 1]);
    const char *kn = mdl_arg_choice(a, "shaper");
    if (!strcmp(kn, "none")) return output(m, sig_pwl(m, c, name, nt, t, v, output_of(a)), "y", out, err);
    ctl_shaper_kind kind = strcmp(kn, "zvd") ? CTL_SHAPER_ZV : CTL_SHAPER_ZVD;
    int id = ctl_shaped_pwl(m, c, name, nt, t, v, kind, mdl_arg_num(a, "frequency"),
                            mdl_arg_num(a, "damping"), output_of(a));
    return output(m, id, "y", out, err);
}

static const mdl_type shaper_type = {
    "ctl.shaper",
    "a piecewise linear reference shaped by a ZV or ZVD shaper (ctl_shaper.h)",
    "r_s(t) = sum_i A_i r(t - t_i)   (r: linear between (t_k, v_k); none: r_s = r)\n"
    "ZV:  A = [1, K] / (1 + K),  t = [0, Td / 2]\n"
    "ZVD: A = [1, 2K, K^2] / (1 + K)^2,  t = [0, Td / 2, Td]\n"
    "K = exp(-z pi / sqrt(1 - z^2)),  Td = 1 / (f sqrt(1 - z^2))" SIG_EQS,
    shaper_params, COUNT(shaper_params), NULL, 0, source_signals, COUNT(source_signals), 0,
    shaper_build, source_place, NULL};

/* ---- ctl.state_feedback ---- */

#define SF_N 6
#define SF_X(k)                                                                                    \
    {"x" #k, MDL_SIGNAL, 0, "-", NULL, 0, 0, k == 1 ? 0 : MDL_OPTIONAL, NULL,                      \
     "measured signal " #k " (x1 required; x1..xn without gaps)"},                                 \
    {                                                                                              \
        "r" #k, MDL_SIGNAL, 0, "-", NULL, 0, 0, MDL_OPTIONAL, NULL,                                \
            "its reference (left out: 0)"                                                          \
    }

static const mdl_param_def sf_params[] = {
    SF_X(1), SF_X(2), SF_X(3), SF_X(4), SF_X(5), SF_X(6),
    {"gains", MDL_VECTOR, 0, "-", NULL, -INF, INF, MDL_OPTIONAL | MDL_FINITE, NULL,
     "K, one per measured signal (or leave out and give A, B, Q, R)"},
    {"A", MDL_VECTOR, 0, "-", NULL, -INF, INF, MDL_OPTIONAL | MDL_FINITE, NULL,
     "the design model's n x n matrix, row by row"},
    {"B", MDL_VECTOR, 0, "-", NULL, -INF, INF, MDL_OPTIONAL | MDL_FINITE, NULL,
     "its input column (n entries)"},
    {"Q", MDL_VECTOR, 0, "-", NULL, -INF, INF, MDL_OPTIONAL | MDL_FINITE, NULL,
     "the state weight: n entries (diagonal) or n x n row by row"},
    {"R", MDL_NUMBER, 0, "-", NULL, 0, INF, MDL_OPTIONAL | MDL_LO_OPEN, NULL,
     "the input weight (> 0)"},
    {"gain_scale", MDL_NUMBER, 0, "1", "1", -INF, INF, MDL_FINITE, NULL,
     "a factor on the gains (0: the feedback off, the bias alone passes)"},
    {"form", MDL_CHOICE, 0, "-", "value", 0, 0, 0, "value|integral",
     "u = b - K e, or w' = -K e with u = b + w and rate = b' - K e"},
    {"bias", MDL_SIGNAL, 0, "-", NULL, 0, 0, MDL_OPTIONAL, NULL, "b (left out: 0)"},
    {"bias_rate", MDL_SIGNAL, 0, "-", NULL, 0, 0, MDL_OPTIONAL, NULL,
     "b' (integral form; left out: 0)"},
};
static const mdl_signal_def sf_signals[] = {
    {"u", "-", "the command"},
    {"rate", "-", "its rate b' - K e (integral form)"},
    {"integral", "-", "the state w (integral form)"},
};

static int sf_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                    mdl_instance *out, bg_error *err)
{
    ctl_sf_spec s;
    memset(&s, 0, sizeof s);
    char key[8];
    for (int k = 0; k < SF_N; k++) {
        snprintf(key, sizeof key, "x%d", k + 1);
        if (!mdl_arg_has(a, key)) {
            snprintf(key, sizeof key, "r%d", k + 1);
            if (mdl_arg_has(a, key))
                return bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                                      "%s: given without x%d", key, k + 1);
            continue;
        }
        if (s.n != k)
            return bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                                  "%s: given without x%d (x1..xn without gaps)", key, s.n + 1);
        s.x[s.n] = mdl_arg_signal(a, key);
        snprintf(key, sizeof key, "r%d", k + 1);
        if ((s.use_ref[s.n] = mdl_arg_has(a, key))) s.r[s.n] = mdl_arg_signal(a, key);
        s.n++;
    }
    int n = s.n, ng = 0, na = 0, nb = 0, nq = 0;
    int design = mdl_arg_has(a, "A") || mdl_arg_has(a, "B") || mdl_arg_has(a, "Q") ||
                 mdl_arg_has(a, "R");
    if (mdl_arg_has(a, "gains") == design)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                              "gains: give the gains or the design (A, B, Q, R), one of them");
    if (!design) {
        const double *g = mdl_arg_vec(a, "gains", &ng);
        if (ng != n)
            return bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                                  "gains: %d of them, expected one per measured signal (%d)", ng,
                                  n);
        memcpy(s.gain, g, sizeof *g * (size_t)n);
    } else {
        const char *miss = !mdl_arg_has(a, "A")   ? "A"
                           : !mdl_arg_has(a, "B") ? "B"
                           : !mdl_arg_has(a, "Q") ? "Q"
                           : !mdl_arg_has(a, "R") ? "R"
                                                  : NULL;
        if (miss)
            return bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                                  "%s: the design needs A, B, Q and R", miss);
        const double *Ar = mdl_arg_vec(a, "A", &na), *Br = mdl_arg_vec(a, "B", &nb),
                     *Qr = mdl_arg_vec(a, "Q", &nq);
        if (na != n * n || nb != n || (nq != n && nq != n * n))
            return bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                                  "%s: %d entries, expected %d for %d measured signals",
                                  na != n * n ? "A" : nb != n ? "B" : "Q",
                                  na != n * n ? na : nb != n ? nb : nq,
                                  na != n * n ? n * n : n, n);
        double A[SF_N * SF_N], Q[SF_N * SF_N], R = mdl_arg_num(a, "R");
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                A[i + j * n] = Ar[i * n + j];
                Q[i + j * n] = nq == n ? (i == j ? Qr[i] : 0.0) : Qr[i * n + j];
            }
        int st = ctl_lqr(n, 1, A, Br, Q, &R, s.gain, NULL, err);
        if (st != BG_OK) return st;
    }
    for (int i = 0; i < n; i++) s.gain[i] *= mdl_arg_num(a, "gain_scale");
    s.integrate = !strcmp(mdl_arg_choice(a, "form"), "integral");
    if ((s.use_bias = mdl_arg_has(a, "bias"))) s.bias = mdl_arg_signal(a, "bias");
    if ((s.use_bias_rate = mdl_arg_has(a, "bias_rate"))) {
        if (!s.integrate)
            return bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                                  "bias_rate: only with form: integral");
        s.bias_rate = mdl_arg_signal(a, "bias_rate");
    }
    int id = ctl_state_feedback(m, c, name, &s);
    int r = output(m, id, "u", out, err);
    if (r == BG_OK && s.integrate) r = mdl_instance_signal(out, "rate", (bgr_ref){BGR_OWN, id, 1});
    if (r == BG_OK && s.integrate)
        r = mdl_instance_signal(out, "integral", (bgr_ref){BGR_STATE, id, 0});
    return r;
}

static const mdl_type sf_type = {
    "ctl.state_feedback", "state feedback, its gains given or designed by LQR (ctl_lqr.h)",
    "e_i = x_i - r_i   (K: the gains or the design's, times gain_scale)\n"
    "value form:     u = b - sum_i K_i e_i\n"
    "integral form:  w' = -sum_i K_i e_i,  u = b + w,  rate = b' - sum_i K_i e_i\n"
    "LQR design: K = R^-1 B^T P,  A^T P + P A - P B R^-1 B^T P + Q = 0  (Schur method, Laub 1979)",
    sf_params, COUNT(sf_params), NULL, 0, sf_signals, COUNT(sf_signals), 0, sf_build, NULL, NULL};

/* ---- ctl.sway_sensor ---- */

static const mdl_param_def sway_params[] = {
    {"load", MDL_ELEMENT, 0, "-", NULL, 0, 0, 0, NULL, "the point mass (mech.point_mass)"},
    {"angle", MDL_SIGNAL, 0, "rad", NULL, 0, 0, 0, NULL, "the plane's angle theta"},
    {"rate", MDL_SIGNAL, 0, "rad/s", NULL, 0, 0, 0, NULL, "its rate omega"},
    {"center", MDL_VECTOR, 2, "m", "[0, 0]", -INF, INF, MDL_FINITE, NULL,
     "the vertical axis (cx, cy)"},
};
static const mdl_signal_def sway_signals[] = {
    {"s", "m", "the load's offset from the turning plane"},
    {"s_rate", "m/s", "its rate in the turning frame"},
};

static int sway_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                      mdl_instance *out, bg_error *err)
{
    int load = mdl_arg_element(a, "load");
    bgr_element *el = bgr_element_get(m, load);
    if (!el || strcmp(el->cls->type, "point mass"))
        return bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                              "load: expected a point mass (mech.point_mass), got %s",
                              el ? el->cls->type : "no element");
    const double *cen = mdl_arg_vec(a, "center", NULL);
    ctl_sway_spec s = {.x = {BGR_STATE, load, 0},
                       .y = {BGR_STATE, load, 1},
                       .vx = {BGR_STATE, load, 3},
                       .vy = {BGR_STATE, load, 4},
                       .theta = mdl_arg_signal(a, "angle"),
                       .omega = mdl_arg_signal(a, "rate"),
                       .cx = cen[0],
                       .cy = cen[1]};
    int id = ctl_sway(m, c, name, &s);
    int r = output(m, id, "s", out, err);
    if (r == BG_OK) r = mdl_instance_signal(out, "s_rate", (bgr_ref){BGR_OWN, id, 1});
    return r;
}

static const mdl_type sway_type = {
    "ctl.sway_sensor", "a load's sway out of a turning vertical plane (ctl_sway.h)",
    "s  = -(x - cx) sin(theta) + (y - cy) cos(theta)\n"
    "s' = -vx sin(theta) + vy cos(theta) - omega ((x - cx) cos(theta) + (y - cy) sin(theta))",
    sway_params, COUNT(sway_params), NULL, 0, sway_signals, COUNT(sway_signals), 0, sway_build,
    NULL, NULL};

const mdl_type *const mdl_types_ctl[] = {
    &pid_type,  &ff_type,   &shaper_type, &sf_type,   &sway_type, &trap_type,
    &pwl_type,  &step_type, &ramp_type,   &sine_type, &const_type, &gain_type,
};
const int mdl_types_ctl_count = COUNT(mdl_types_ctl);
