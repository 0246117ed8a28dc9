/* Model-file types of the control library: the PID controller (ctl_pid.h), the signal sources
 * (sig_sources.h) and the signal gain (bgr_gain of bgr_elements.h). None has ports: each offers
 * signals (its algebraic output, its states) and reads others' through MDL_SIGNAL parameters.
 * The equations are the headers', restated here for the type reference. */
#include <math.h>
#include <string.h>

#include "bgr_elements.h"
#include "ctl_pid.h"
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
    int id = ctl_pid(m, c, name, &s);
    int r = output(m, id, "u", out, err);
    if (r == BG_OK) r = mdl_instance_signal(out, "integral", (bgr_ref){BGR_STATE, id, 0});
    if (r == BG_OK && s.derivative_filter > 0)
        r = mdl_instance_signal(out, "filter", (bgr_ref){BGR_STATE, id, 1});
    return r;
}

static const mdl_type pid_type = {
    "ctl.pid", "PID controller with optional smooth output limits (ctl_pid.h)",
    "I' = r - y                                         integral (state I)\n"
    "u  = sat(Kp (r - y) + Kd (r' - y') + Ki I)         output\n"
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

const mdl_type *const mdl_types_ctl[] = {
    &pid_type, &trap_type, &pwl_type, &step_type, &ramp_type, &sine_type, &const_type, &gain_type,
};
const int mdl_types_ctl_count = COUNT(mdl_types_ctl);
