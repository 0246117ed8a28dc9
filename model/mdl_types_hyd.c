/* Model-file types of the hydraulic library (components/hyd_*.h): pumps, the motor, volumes,
 * sources, leakage and the relief valve. The equations are the headers' (hyd_pump.h,
 * hyd_motor.h, hyd_volume.h, hyd_source.h, hyd_valve.h), restated here for the type reference.
 * Ports are hydraulic (volume flow / pressure) but for the machines' shafts (rotational). */
#include <math.h>
#include <string.h>

#include "hyd_motor.h"
#include "hyd_pump.h"
#include "hyd_source.h"
#include "hyd_valve.h"
#include "hyd_volume.h"
#include "mdl_impl.h"

#define INF HUGE_VAL
#define NOMINAL_PRESSURE                                                                           \
    {"nominal_pressure", MDL_NUMBER, 0, "Pa", "0", 0, INF, 0, NULL,                                \
     "pressure scale of its pressures for the error test (0: none stated, 1 Pa)"}
#define NOMINAL_SPEED                                                                              \
    {"nominal_speed", MDL_NUMBER, 0, "rad/s", "0", 0, INF, 0, NULL,                                \
     "shaft speed scale for the error test, and of the flows through the displacement (0: none "   \
     "stated, 1 rad/s)"}

#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

/* one element with fixed ports: record them and the element */
static int single(bgr_model *m, int id, mdl_instance *out, const char *const *names,
                  const mdl_domain *doms, int n, bg_error *err)
{
    if (id < 0) return mdl_fail_model(err, m, id);
    int r = mdl_instance_element(out, id);
    for (int k = 0; r == BG_OK && k < n; k++)
        r = mdl_instance_port(out, names[k], bgr_port_of(m, id, k), 1, doms[k]);
    return r;
}

static int fail_if(bgr_model *m, int r, bg_error *err)
{
    return r == BG_OK ? r : mdl_fail_model(err, m, r);
}

static const mdl_domain one_hyd[] = {MDL_HYDRAULIC};
static const mdl_domain two_hyd[] = {MDL_HYDRAULIC, MDL_HYDRAULIC};
static const char *const name_p[] = {"p"};
static const char *const names_ab[] = {"a", "b"};

/* ---- hyd.pump, hyd.pump_servo ---- */

#define PUMP_PARAMS                                                                                \
    {"displacement", MDL_NUMBER, 0, "m^3/rev", NULL, 0, INF, MDL_LO_OPEN, NULL,                    \
     "displacement per revolution at full command (x = 1)"},                                       \
        {"leakage", MDL_NUMBER, 0, "m^3/(s Pa)", "0", 0, INF, 0, NULL,                             \
         "laminar cross-port leakage conductance"},                                                \
        {"command", MDL_SIGNAL, 0, "1", NULL, 0, 0, 0, NULL,                                       \
         "the displacement command x, a fraction of the displacement (usually in [-1, 1])"}

static const mdl_param_def pump_params[] = {
    PUMP_PARAMS,
    NOMINAL_PRESSURE,
    NOMINAL_SPEED,
};
static const mdl_param_def pump_servo_params[] = {
    PUMP_PARAMS,
    {"bandwidth", MDL_NUMBER, 0, "Hz", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "corner frequency fc of the swash plate's first-order lag (fc = 0 is hyd.pump)"},
    NOMINAL_PRESSURE,
    NOMINAL_SPEED,
};
static const mdl_port_def pump_ports[] = {
    {"shaft", 1, MDL_ROTATIONAL, "drive shaft (power in): torque T drawn, drive speed w_p"},
    {"a", 1, MDL_HYDRAULIC, "inlet (power in): pressure p_a, flow q_a into the pump"},
    {"b", 1, MDL_HYDRAULIC, "outlet (power out): pressure p_b, flow q_b out of the pump"},
};
static const mdl_signal_def pump_servo_signals[] = {
    {"swash", "1", "the swash plate's position s, a fraction of the displacement (a state)"},
};

static int pump_finish(bgr_model *m, int id, const mdl_args *a, mdl_instance *out, bg_error *err)
{
    static const char *const names[] = {"shaft", "a", "b"};
    static const mdl_domain doms[] = {MDL_ROTATIONAL, MDL_HYDRAULIC, MDL_HYDRAULIC};
    int r = single(m, id, out, names, doms, 3, err);
    double p = mdl_arg_num(a, "nominal_pressure"), w = mdl_arg_num(a, "nominal_speed");
    if (r == BG_OK && (p > 0 || w > 0)) r = fail_if(m, hyd_pump_set_nominal(m, id, p, w), err);
    return r;
}

static int pump_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                      mdl_instance *out, bg_error *err)
{
    int id = hyd_pump(m, c, name, mdl_arg_num(a, "displacement"), mdl_arg_num(a, "leakage"),
                      mdl_arg_signal(a, "command"));
    return pump_finish(m, id, a, out, err);
}

static int pump_servo_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                            mdl_instance *out, bg_error *err)
{
    int id = hyd_pump_servo(m, c, name, mdl_arg_num(a, "displacement"), mdl_arg_num(a, "leakage"),
                            mdl_arg_signal(a, "command"), mdl_arg_num(a, "bandwidth"));
    int r = pump_finish(m, id, a, out, err);
    if (r == BG_OK) r = mdl_instance_signal(out, "swash", (bgr_ref){BGR_STATE, id, 0});
    return r;
}

#define PUMP_EQS                                                                                   \
    "T      = x Dp (p_b - p_a) / (2 pi)                 torque drawn\n"                            \
    "q_bout = x Dp w_p / (2 pi) - Cl (p_b - p_a)        delivered flow\n"                          \
    "q_ain  = q_bout                                    the leak returns inside"

static const mdl_type pump_type = {
    "hyd.pump", "variable-displacement pump with cross-port leakage (hyd_pump.h)",
    PUMP_EQS "\n(Dp: displacement, Cl: leakage, x: command)", pump_params, COUNT(pump_params),
    pump_ports, COUNT(pump_ports), NULL, 0, 0, pump_build, NULL, NULL};

static const mdl_type pump_servo_type = {
    "hyd.pump_servo",
    "pump whose swash plate follows the command with a first-order lag (hyd_pump.h)",
    "s'     = 2 pi fc (x - s)                           swash plate (state s)\n" PUMP_EQS
    "\n(s in place of x; Dp: displacement, Cl: leakage, fc: bandwidth, x: command)",
    pump_servo_params, COUNT(pump_servo_params), pump_ports, COUNT(pump_ports), pump_servo_signals,
    COUNT(pump_servo_signals), 0, pump_servo_build, NULL, NULL};

/* ---- hyd.motor ---- */

static const mdl_param_def motor_params[] = {
    {"displacement", MDL_NUMBER, 0, "m^3/rev", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "displacement per revolution"},
    {"leakage", MDL_NUMBER, 0, "m^3/(s Pa)", "0", 0, INF, 0, NULL,
     "laminar cross-port leakage conductance"},
    {"friction", MDL_NUMBER, 0, "N m s/rad", "0", 0, INF, 0, NULL,
     "viscous friction coefficient of the shaft"},
    NOMINAL_PRESSURE,
    NOMINAL_SPEED,
};
static const mdl_port_def motor_ports[] = {
    {"a", 1, MDL_HYDRAULIC, "inlet (power in): pressure p_a, flow q_a into the motor"},
    {"b", 1, MDL_HYDRAULIC, "outlet (power out): pressure p_b, flow q_b out of the motor"},
    {"shaft", 1, MDL_ROTATIONAL, "output shaft (power out): torque T delivered, shaft speed w"},
};

static int motor_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                       mdl_instance *out, bg_error *err)
{
    static const char *const names[] = {"a", "b", "shaft"};
    static const mdl_domain doms[] = {MDL_HYDRAULIC, MDL_HYDRAULIC, MDL_ROTATIONAL};
    int id = hyd_motor(m, c, name, mdl_arg_num(a, "displacement"), mdl_arg_num(a, "leakage"),
                       mdl_arg_num(a, "friction"));
    int r = single(m, id, out, names, doms, 3, err);
    double p = mdl_arg_num(a, "nominal_pressure"), w = mdl_arg_num(a, "nominal_speed");
    if (r == BG_OK && (p > 0 || w > 0)) r = fail_if(m, hyd_motor_set_nominal(m, id, p, w), err);
    return r;
}

static const mdl_type motor_type = {
    "hyd.motor",
    "fixed-displacement motor with cross-port leakage and viscous friction (hyd_motor.h)",
    "q_ain  = D w / (2 pi) + Cl (p_a - p_b)             flow drawn\n"
    "q_bout = q_ain                                     the leak leaves at b\n"
    "T      = D (p_a - p_b) / (2 pi) - b w              shaft torque\n"
    "(D: displacement, Cl: leakage, b: friction)",
    motor_params, COUNT(motor_params), motor_ports, COUNT(motor_ports), NULL, 0, 0, motor_build,
    NULL, NULL};

/* ---- hyd.volume ---- */

static const mdl_param_def volume_params[] = {
    {"volume", MDL_NUMBER, 0, "m^3", NULL, 0, INF, MDL_LO_OPEN, NULL, "the oil volume V"},
    {"bulk_modulus", MDL_NUMBER, 0, "Pa", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "effective bulk modulus beta of the oil in it"},
    {"ports", MDL_NAMES, 0, "-", "[a, b]", 0, 0, 0, NULL, "the names of its ports (1 .. 1000)"},
    {"pressure", MDL_NUMBER, 0, "Pa", "0", -INF, INF, MDL_FINITE, NULL, "initial pressure"},
    NOMINAL_PRESSURE,
};
static const mdl_port_def volume_ports[] = {
    {"*", 1, MDL_HYDRAULIC, "one per name of `ports`, each with its flow into the volume"}};
static const mdl_signal_def volume_signals[] = {{"p", "Pa", "the pressure (a state)"}};

static int volume_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                        mdl_instance *out, bg_error *err)
{
    int np;
    const char *const *names = mdl_arg_names(a, "ports", &np);
    if (np > 1000)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "model", "ports: %d of them, at most 1000", np);
    int id = hyd_volume(m, c, name, np, mdl_arg_num(a, "volume"), mdl_arg_num(a, "bulk_modulus"));
    if (id < 0) return mdl_fail_model(err, m, id);
    int r = mdl_instance_element(out, id);
    for (int k = 0; r == BG_OK && k < np; k++)
        r = mdl_instance_port(out, names[k], bgr_port_of(m, id, k), 1, MDL_HYDRAULIC);
    if (r == BG_OK) r = mdl_instance_signal(out, "p", (bgr_ref){BGR_STATE, id, 0});
    double p = mdl_arg_num(a, "nominal_pressure");
    if (r == BG_OK && p > 0) r = fail_if(m, hyd_volume_set_nominal(m, id, p), err);
    return r;
}

/* the state: the initial pressure, and its ports' efforts with it (the volume's own equations
 * e_k = p hold at the start, so that what is bonded to it sees that pressure, not 0) */
static int volume_place(bgr_model *m, const mdl_instance *in, const mdl_args *a, mdl_locator *loc,
                        bg_error *err)
{
    (void)loc;
    int id = mdl_instance_main(in), ip = bgr_ref_var(m, (bgr_ref){BGR_STATE, id, 0});
    double *y = bgr_y0(m);
    const bgr_element *el = bgr_element_get(m, id);
    if (ip < 0 || !y || !el)
        return bg_error_raise(err, BG_ERR_STATE, "model",
                              "%s: the volume's pressure is not numbered", mdl_arg_path(a));
    y[ip] = mdl_arg_num(a, "pressure");
    for (int k = 0; k < el->nports; k++) {
        int v = bgr_ev(el, m, k, 0);
        if (v >= 0) y[v] = y[ip];
    }
    return BG_OK;
}

static const mdl_type volume_type = {
    "hyd.volume", "compressible oil volume: a 0-junction with a capacitance (hyd_volume.h)",
    "p'  = (beta / V) sum_k q_k                         pressure build-up (state p)\n"
    "e_k = p  at every port k                           common pressure\n"
    "(V: volume, beta: bulk_modulus, q_k: the flow into the volume at port k)",
    volume_params, COUNT(volume_params), volume_ports, COUNT(volume_ports), volume_signals,
    COUNT(volume_signals), 0, volume_build, volume_place, NULL};

/* ---- sources ---- */

/* the start: the port's pressure (flow) at its value at t = 0 (mdl_place_source) */
static int effort_place(bgr_model *m, const mdl_instance *in, const mdl_args *a,
                        mdl_locator *loc, bg_error *err)
{
    (void)a, (void)loc;
    return mdl_place_source(m, mdl_instance_main(in), MDL_SRC_EFFORT, NULL, err);
}
static int flow_place(bgr_model *m, const mdl_instance *in, const mdl_args *a, mdl_locator *loc,
                      bg_error *err)
{
    (void)a, (void)loc;
    return mdl_place_source(m, mdl_instance_main(in), MDL_SRC_FLOW, NULL, err);
}
static int effort_signal_place(bgr_model *m, const mdl_instance *in, const mdl_args *a,
                               mdl_locator *loc, bg_error *err)
{
    (void)loc;
    bgr_ref r = mdl_arg_signal(a, "pressure");
    return mdl_place_source(m, mdl_instance_main(in), MDL_SRC_EFFORT, &r, err);
}
static int flow_signal_place(bgr_model *m, const mdl_instance *in, const mdl_args *a,
                             mdl_locator *loc, bg_error *err)
{
    (void)loc;
    bgr_ref r = mdl_arg_signal(a, "flow");
    return mdl_place_source(m, mdl_instance_main(in), MDL_SRC_FLOW, &r, err);
}

static const mdl_port_def source_ports[] = {
    {"p", 1, MDL_HYDRAULIC, "the port (power out of the source)"}};

static const mdl_param_def tank_params[] = {
    {"pressure", MDL_NUMBER, 0, "Pa", "0", -INF, INF, MDL_FINITE, NULL,
     "the reservoir's pressure (0: atmospheric, gauge)"},
};

static int tank_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                      mdl_instance *out, bg_error *err)
{
    return single(m, hyd_tank(m, c, name, mdl_arg_num(a, "pressure")), out, name_p, one_hyd, 1,
                  err);
}

static const mdl_type tank_type = {
    "hyd.tank", "reservoir at a constant pressure (hyd_source.h)", "p = P  (whatever the flow)",
    tank_params, COUNT(tank_params), source_ports, COUNT(source_ports), NULL, 0, 0, tank_build,
    effort_place, NULL};

static const mdl_param_def psource_params[] = {
    {"pressure", MDL_SIGNAL, 0, "Pa", NULL, 0, 0, 0, NULL, "the signal that gives the pressure"},
};

static int psource_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                         mdl_instance *out, bg_error *err)
{
    int id = hyd_pressure_source_signal(m, c, name, mdl_arg_signal(a, "pressure"));
    return single(m, id, out, name_p, one_hyd, 1, err);
}

static const mdl_type psource_type = {
    "hyd.pressure_source", "pressure source following a signal (hyd_source.h)",
    "p = P(t)  (the signal `pressure`, whatever the flow)", psource_params, COUNT(psource_params),
    source_ports, COUNT(source_ports), NULL, 0, 0, psource_build, effort_signal_place, NULL};

static const mdl_param_def fsource_params[] = {
    {"flow", MDL_NUMBER, 0, "m^3/s", NULL, -INF, INF, MDL_FINITE, NULL,
     "the volume flow out of the source"},
};

static int fsource_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                         mdl_instance *out, bg_error *err)
{
    int id = hyd_flow_source(m, c, name, mdl_arg_num(a, "flow"));
    return single(m, id, out, name_p, one_hyd, 1, err);
}

static const mdl_type fsource_type = {
    "hyd.flow_source", "constant flow source: an ideal pump at constant speed (hyd_source.h)",
    "q_out = Q  (whatever the pressure)", fsource_params, COUNT(fsource_params), source_ports,
    COUNT(source_ports), NULL, 0, 0, fsource_build, flow_place, NULL};

static const mdl_param_def fsource_sig_params[] = {
    {"flow", MDL_SIGNAL, 0, "m^3/s", NULL, 0, 0, 0, NULL, "the signal that gives the flow"},
};

static int fsource_sig_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                             mdl_instance *out, bg_error *err)
{
    int id = hyd_flow_source_signal(m, c, name, mdl_arg_signal(a, "flow"));
    return single(m, id, out, name_p, one_hyd, 1, err);
}

static const mdl_type fsource_sig_type = {
    "hyd.flow_source_signal", "flow source following a signal (hyd_source.h)",
    "q_out = Q(t)  (the signal `flow`, whatever the pressure)", fsource_sig_params,
    COUNT(fsource_sig_params), source_ports, COUNT(source_ports), NULL, 0, 0, fsource_sig_build,
    flow_signal_place, NULL};

/* ---- restrictions ---- */

static const mdl_port_def valve_ports[] = {
    {"a", 1, MDL_HYDRAULIC, "upstream (power in): pressure p_a, flow q into the element"},
    {"b", 1, MDL_HYDRAULIC, "downstream (power out): pressure p_b, the same flow q out"},
};

static const mdl_param_def leakage_params[] = {
    {"conductance", MDL_NUMBER, 0, "m^3/(s Pa)", NULL, 0, INF, 0, NULL,
     "laminar leakage conductance G"},
};

static int leakage_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                         mdl_instance *out, bg_error *err)
{
    int id = hyd_leakage(m, c, name, mdl_arg_num(a, "conductance"));
    return single(m, id, out, names_ab, two_hyd, 2, err);
}

static const mdl_type leakage_type = {
    "hyd.leakage", "laminar leakage between two ports (hyd_valve.h)",
    "q_ain  = G (p_a - p_b)                             characteristic\n"
    "q_bout = q_ain                                     no storage\n"
    "(G: conductance)",
    leakage_params, COUNT(leakage_params), valve_ports, COUNT(valve_ports), NULL, 0, 0,
    leakage_build, NULL, NULL};

static const mdl_param_def relief_params[] = {
    {"p_crack", MDL_NUMBER, 0, "Pa", NULL, -INF, INF, MDL_FINITE, NULL,
     "cracking pressure difference p_c (where it starts to open)"},
    {"p_full", MDL_NUMBER, 0, "Pa", NULL, -INF, INF, MDL_FINITE, NULL,
     "full-flow pressure difference p_f, > p_crack"},
    {"q_rated", MDL_NUMBER, 0, "m^3/s", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "rated flow q_r, passed at p_full"},
    {"eps", MDL_NUMBER, 0, "Pa", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "width of the smooth opening (a small fraction of p_full - p_crack, e.g. 1 %)"},
};

static int relief_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                        mdl_instance *out, bg_error *err)
{
    int id = hyd_relief_valve(m, c, name, mdl_arg_num(a, "p_crack"), mdl_arg_num(a, "p_full"),
                              mdl_arg_num(a, "q_rated"), mdl_arg_num(a, "eps"));
    return single(m, id, out, names_ab, two_hyd, 2, err);
}

static const mdl_type relief_type = {
    "hyd.relief_valve", "pressure relief valve with a smooth static characteristic (hyd_valve.h)",
    "q_ain  = G sp(p_a - p_b - p_c),  G = q_r / (p_f - p_c)     characteristic\n"
    "sp(z)  = eps ln(1 + exp(z / eps))                          (smooth max(z, 0))\n"
    "q_bout = q_ain                                             no storage\n"
    "(p_c: p_crack, p_f: p_full, q_r: q_rated)",
    relief_params, COUNT(relief_params), valve_ports, COUNT(valve_ports), NULL, 0, 0, relief_build,
    NULL, NULL};

const mdl_type *const mdl_types_hyd[] = {
    &pump_type,    &pump_servo_type, &motor_type,       &volume_type,  &tank_type,
    &psource_type, &fsource_type,    &fsource_sig_type, &leakage_type, &relief_type,
};
const int mdl_types_hyd_count = COUNT(mdl_types_hyd);
