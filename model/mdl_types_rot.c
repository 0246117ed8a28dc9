/* Model-file types of the rotational library (components/rot_*.h, sensors.h): inertia, gear,
 * damper and the sensor on an inertia. The equations are the headers' (rot_inertia.h,
 * rot_gear.h, rot_damper.h, sensors.h), restated here for the type reference. Ports are
 * rotational (angular velocity / torque), of dimension 1. */
#include <math.h>
#include <string.h>

#include "mdl_impl.h"
#include "rot_damper.h"
#include "rot_gear.h"
#include "rot_inertia.h"
#include "sensors.h"

#define INF HUGE_VAL
#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

/* one element with fixed rotational ports: record them and the element */
static int single(bgr_model *m, int id, mdl_instance *out, const char *const *names, int n,
                  bg_error *err)
{
    if (id < 0) return mdl_fail_model(err, m, id);
    int r = mdl_instance_element(out, id);
    for (int k = 0; r == BG_OK && k < n; k++)
        r = mdl_instance_port(out, names[k], bgr_port_of(m, id, k), 1, MDL_ROTATIONAL);
    return r;
}

static const char *const name_p[] = {"p"};

/* ---- rot.inertia ---- */

static const mdl_param_def inertia_params[] = {
    {"J", MDL_NUMBER, 0, "kg m^2", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "moment of inertia about the axis"},
    {"speed", MDL_NUMBER, 0, "rad/s", "0", -INF, INF, MDL_FINITE, NULL, "initial angular velocity"},
    {"angle", MDL_NUMBER, 0, "rad", "0", -INF, INF, MDL_FINITE, NULL, "initial angle"},
    {"nominal_speed", MDL_NUMBER, 0, "rad/s", "0", 0, INF, 0, NULL,
     "speed scale of w (and, times J, of p) for the error test (0: none stated, 1 rad/s)"},
};
static const mdl_port_def inertia_ports[] = {
    {"p", 1, MDL_ROTATIONAL, "the body (power in): net torque T on it, its angular velocity w"}};
static const mdl_signal_def inertia_signals[] = {
    {"p", "N m s", "the angular momentum J w (a state)"},
    {"angle", "rad", "the angle theta (a state)"},
};

static int inertia_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                         mdl_instance *out, bg_error *err)
{
    int id = rot_inertia(m, c, name, mdl_arg_num(a, "J"));
    int r = single(m, id, out, name_p, 1, err);
    if (r == BG_OK) r = mdl_instance_signal(out, "p", (bgr_ref){BGR_STATE, id, 0});
    if (r == BG_OK) r = mdl_instance_signal(out, "angle", (bgr_ref){BGR_STATE, id, 1});
    double w = mdl_arg_num(a, "nominal_speed");
    if (r == BG_OK && w > 0 && (r = rot_inertia_set_nominal(m, id, w)) != BG_OK)
        return mdl_fail_model(err, m, r);
    return r;
}

/* the states from the initial speed and angle: p = J w, theta */
static int inertia_place(bgr_model *m, const mdl_instance *in, const mdl_args *a, mdl_locator *loc,
                         bg_error *err)
{
    (void)loc;
    int id = mdl_instance_main(in);
    int ip = bgr_ref_var(m, (bgr_ref){BGR_STATE, id, 0}),
        ia = bgr_ref_var(m, (bgr_ref){BGR_STATE, id, 1});
    double *y = bgr_y0(m);
    if (ip < 0 || ia < 0 || !y)
        return bg_error_raise(err, BG_ERR_STATE, "model",
                              "%s: the inertia's states are not numbered", mdl_arg_path(a));
    y[ip] = mdl_arg_num(a, "J") * mdl_arg_num(a, "speed");
    y[ia] = mdl_arg_num(a, "angle");
    return BG_OK;
}

static const mdl_type inertia_type = {
    "rot.inertia", "rotational inertia about a fixed axis, with its angle (rot_inertia.h)",
    "p'     = T                                         Euler's law (state p)\n"
    "J w    = p                                         constitutive law\n"
    "theta' = p / J                                     the angle (state theta)",
    inertia_params, COUNT(inertia_params), inertia_ports, COUNT(inertia_ports), inertia_signals,
    COUNT(inertia_signals), 0, inertia_build, inertia_place, NULL};

/* ---- rot.gear ---- */

static const mdl_param_def gear_params[] = {
    {"ratio", MDL_NUMBER, 0, "1", NULL, -INF, INF, MDL_FINITE, NULL,
     "i = w_in / w_out, != 0 (> 1 reduces the speed, < 0 reverses the sense)"},
};
static const mdl_port_def gear_ports[] = {
    {"in", 1, MDL_ROTATIONAL, "input shaft (power in): torque T_in, speed w_in"},
    {"out", 1, MDL_ROTATIONAL, "output shaft (power out): torque T_out, speed w_out"},
};

static int gear_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                      mdl_instance *out, bg_error *err)
{
    static const char *const names[] = {"in", "out"};
    double i = mdl_arg_num(a, "ratio");
    if (i == 0)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "model", "ratio: 0, expected a number != 0");
    return single(m, rot_gear(m, c, name, i), out, names, 2, err);
}

static const mdl_type gear_type = {
    "rot.gear", "gear unit: an ideal transformer between two shafts (rot_gear.h)",
    "T_in  = T_out / i\n"
    "w_out = w_in / i                                   (i: ratio; T_in w_in = T_out w_out)",
    gear_params, COUNT(gear_params), gear_ports, COUNT(gear_ports), NULL, 0, 0, gear_build, NULL,
    NULL};

/* ---- rot.damper ---- */

static const mdl_param_def damper_params[] = {
    {"b", MDL_NUMBER, 0, "N m s/rad", NULL, 0, INF, 0, NULL, "viscous friction coefficient"},
};
static const mdl_port_def damper_ports[] = {
    {"p", 1, MDL_ROTATIONAL, "power in: friction torque T, relative angular velocity w"}};

static int damper_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                        mdl_instance *out, bg_error *err)
{
    return single(m, rot_damper(m, c, name, mdl_arg_num(a, "b")), out, name_p, 1, err);
}

static const mdl_type damper_type = {
    "rot.damper", "linear viscous rotary damper (rot_damper.h)", "T = b w_in  (dissipates b w^2)",
    damper_params, COUNT(damper_params), damper_ports, COUNT(damper_ports), NULL, 0, 0,
    damper_build, NULL, NULL};

/* ---- rot.sensor ---- */

static const mdl_param_def sensor_params[] = {
    {"inertia", MDL_ELEMENT, 0, "-", NULL, 0, 0, 0, NULL, "the inertia (rot.inertia) it reads"},
    {"quantity", MDL_CHOICE, 0, "-", NULL, 0, 0, 0, "angle|velocity|acceleration",
     "what it measures"},
};
static const mdl_signal_def sensor_signals[] = {
    {"value", "rad, rad/s or rad/s^2", "the measured quantity z"},
};

static int sensor_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                        mdl_instance *out, bg_error *err)
{
    const char *q = mdl_arg_choice(a, "quantity");
    rot_quantity k = !strcmp(q, "angle")      ? ROT_ANGLE
                     : !strcmp(q, "velocity") ? ROT_VELOCITY
                                              : ROT_ACCELERATION;
    int j = mdl_arg_element(a, "inertia");
    if (!(rot_inertia_moment(bgr_element_get(m, j)) > 0))
        return bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                              "inertia: the element it names is no rot.inertia");
    int id = rot_sensor(m, c, name, j, k);
    if (id < 0) return mdl_fail_model(err, m, id);
    int r = mdl_instance_element(out, id);
    if (r == BG_OK) r = mdl_instance_signal(out, "value", (bgr_ref){BGR_OWN, id, 0});
    return r;
}

static const mdl_type sensor_type = {
    "rot.sensor", "ideal sensor of an inertia's angle, velocity or acceleration (sensors.h)",
    "angle          z = theta\n"
    "velocity       z = p / J                           (= w)\n"
    "acceleration   z = T / J                           (= w', algebraic: the net torque over J)",
    sensor_params, COUNT(sensor_params), NULL, 0, sensor_signals, COUNT(sensor_signals), 0,
    sensor_build, NULL, NULL};

const mdl_type *const mdl_types_rot[] = {&inertia_type, &gear_type, &damper_type, &sensor_type};
const int mdl_types_rot_count = COUNT(mdl_types_rot);
