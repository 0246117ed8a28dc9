/* Model-file types of the mechanical library (components/mechanics/): bodies, point masses,
 * supports, joints, axial elements and the rotation sensor. The equations are the headers'
 * (mech_body.h, mech_parts.h, mech_axial.h, mech_sensor.h), restated here for the type reference. */
#include <math.h>
#include <string.h>

#include "mdl_impl.h"
#include "mech_axial.h"
#include "mech_body.h"
#include "mech_parts.h"
#include "mech_sensor.h"
#include "mech_util.h"
#include "bgr_elements.h"

#define INF HUGE_VAL
#define NOMINALS                                                                                   \
    {"nominal_force", MDL_NUMBER, 0, "N", "0", 0, INF, 0, NULL,                                    \
     "force scale of its port forces for the error test (0: what the element states)"},            \
        {"nominal_moment", MDL_NUMBER, 0, "N m", "0", 0, INF, 0, NULL,                             \
         "moment scale of its port moments (0: what the element states)"},                         \
        {"nominal_length", MDL_NUMBER, 0, "m", "0", 0, INF, 0, NULL,                               \
         "length scale of its positions (0: what the element states)"}

#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

static int nominals(bgr_model *m, int id, const mdl_args *a, bg_error *err)
{
    double f = mdl_arg_num(a, "nominal_force"), mo = mdl_arg_num(a, "nominal_moment"),
           l = mdl_arg_num(a, "nominal_length");
    if (f == 0 && mo == 0 && l == 0) return BG_OK;
    int r = mech_set_nominal(m, id, f, mo, l);
    return r == BG_OK ? r : mdl_fail_model(err, m, r);
}

/* one element with fixed ports: record them and the element */
static int single(bgr_model *m, int id, mdl_instance *out, const char *const *names, const int *dims,
                  mdl_domain dom, int n, bg_error *err)
{
    if (id < 0) return mdl_fail_model(err, m, id);
    int r = mdl_instance_element(out, id);
    for (int k = 0; r == BG_OK && k < n; k++)
        r = mdl_instance_port(out, names[k], bgr_port_of(m, id, k), dims[k], dom);
    return r;
}

static mdl_domain mech_domain(int dim)
{
    return dim == 3 ? MDL_MECH3 : MDL_MECH6;
}

/* ---- mech.body ---- */

static const mdl_param_def body_params[] = {
    {"mass", MDL_NUMBER, 0, "kg", NULL, 0, INF, MDL_LO_OPEN, NULL, "mass"},
    {"inertia", MDL_VECTOR, 9, "kg m^2", NULL, -INF, INF, MDL_FINITE, NULL,
     "inertia tensor about the mass centre in the body frame, 3x3 by columns, symmetric positive "
     "definite"},
    {"gravity", MDL_VECTOR, 3, "m/s^2", "[0, 0, 0]", -INF, INF, MDL_FINITE, NULL,
     "acceleration of gravity (global)"},
    {"points", MDL_POINTS, 0, "m", NULL, -INF, INF, MDL_FINITE, NULL,
     "the attachment points, name: {r: [x, y, z] in the body frame from the mass centre, dim: 6 or "
     "3}; each is a port"},
    {"position", MDL_VECTOR, 3, "m", "[0, 0, 0]", -INF, INF, MDL_FINITE, NULL,
     "initial position of the mass centre (global)"},
    {"velocity", MDL_VECTOR, 3, "m/s", "[0, 0, 0]", -INF, INF, MDL_FINITE, NULL,
     "initial velocity of the mass centre (global)"},
    {"angular_velocity", MDL_VECTOR, 3, "rad/s", "[0, 0, 0]", -INF, INF, MDL_FINITE, NULL,
     "initial angular velocity (body frame)"},
    {"rotation_axis", MDL_VECTOR, 3, "1", "[0, 0, 1]", -INF, INF, MDL_FINITE, NULL,
     "initial orientation: the body frame turned about this global axis ..."},
    {"rotation_angle", MDL_NUMBER, 0, "rad", "0", -INF, INF, MDL_FINITE, NULL,
     "... by this angle (right hand)"},
    NOMINALS,
};
static const mdl_port_def body_ports[] = {
    {"*", 0, MDL_MECH6, "one per point (mechanical 6D, or 3D where the point says dim: 3)"}};

static int body_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                      mdl_instance *out, bg_error *err)
{
    int np = mdl_arg_npoints(a, "points");
    double r[64 * 3];
    int dims[64];
    if (np > 64) return bg_error_raise(err, BG_ERR_ARGUMENT, "model", "points: %d of them, at most 64", np);
    for (int k = 0; k < np; k++)
        mdl_arg_point(a, "points", k, r + 3 * k, &dims[k]);
    int id = mech_body(m, c, name, mdl_arg_num(a, "mass"), mdl_arg_vec(a, "inertia", NULL),
                       mdl_arg_vec(a, "gravity", NULL), np, r, dims);
    if (id < 0) return mdl_fail_model(err, m, id);
    int rc = mdl_instance_element(out, id);
    for (int k = 0; rc == BG_OK && k < np; k++)
        rc = mdl_instance_port(out, mdl_arg_point(a, "points", k, NULL, NULL), bgr_port_of(m, id, k),
                               dims[k], mech_domain(dims[k]));
    return rc == BG_OK ? nominals(m, id, a, err) : rc;
}

/* the quaternion of a turn by angle about axis (normalised; a zero axis: no turn) */
static void axis_angle_quat(const double *axis, double angle, double q[4])
{
    double n = sqrt(mech_dot(axis, axis));
    q[0] = 1, q[1] = q[2] = q[3] = 0;
    if (!(n > 0) || angle == 0) return;
    double s = sin(angle / 2) / n;
    q[0] = cos(angle / 2), q[1] = axis[0] * s, q[2] = axis[1] * s, q[3] = axis[2] * s;
}

static int body_place(bgr_model *m, const mdl_instance *in, const mdl_args *a, mdl_locator *loc,
                      bg_error *err)
{
    (void)loc;
    double q[4];
    axis_angle_quat(mdl_arg_vec(a, "rotation_axis", NULL), mdl_arg_num(a, "rotation_angle"), q);
    int r = mech_body_set(m, mdl_instance_main(in), mdl_arg_vec(a, "position", NULL),
                          mdl_arg_vec(a, "velocity", NULL), mdl_arg_vec(a, "angular_velocity", NULL), q);
    return r == BG_OK ? r : mdl_fail_model(err, m, r);
}

static int body_port_position(const bgr_model *m, const mdl_instance *in, int port, const double *y,
                              double x[3])
{
    const mdl_args *a = &in->args;
    double r[3], R[9], Rr[3];
    if (!mdl_arg_point(a, "points", port, r, NULL)) return BG_ERR_ARGUMENT;
    int body = mdl_instance_main(in);
    int ix = mech_body_var(m, body, 'x'), iq = mech_body_var(m, body, 'q');
    if (ix < 0 || iq < 0) return BG_ERR_ARGUMENT;
    mech_quat_R(y + iq, R, NULL);
    mech_mv(R, r, Rr);
    for (int i = 0; i < 3; i++)
        x[i] = y[ix + i] + Rr[i];
    return BG_OK;
}

static const mdl_type body_type = {
    "mech.body", "3D rigid body with ports at material points (mech_body.h)",
    "x' = v\n"
    "m v' = sum_k s_k F_k + m g                                  (global frame)\n"
    "J w' + w x (J w) = sum_k [r_k x (R^T s_k F_k) + R^T s_k M_k]  (body frame)\n"
    "q' = q (x) (0, w) / 2\n"
    "v_k = v + R (w x r_k),  omega_k = R w  at each point k",
    body_params, COUNT(body_params), body_ports, COUNT(body_ports), NULL, 0, 0,
    body_build, body_place, body_port_position};

/* ---- mech.point_mass ---- */

static const mdl_param_def pm_params[] = {
    {"mass", MDL_NUMBER, 0, "kg", NULL, 0, INF, MDL_LO_OPEN, NULL, "mass"},
    {"gravity", MDL_VECTOR, 3, "m/s^2", "[0, 0, 0]", -INF, INF, MDL_FINITE, NULL,
     "acceleration of gravity (global)"},
    {"position", MDL_VECTOR, 3, "m", NULL, -INF, INF, MDL_OPTIONAL | MDL_FINITE, NULL,
     "initial position (left out: where its port's neighbour is)"},
    {"velocity", MDL_VECTOR, 3, "m/s", "[0, 0, 0]", -INF, INF, MDL_FINITE, NULL, "initial velocity"},
    NOMINALS,
};
static const mdl_port_def pm_ports[] = {{"p", 3, MDL_MECH3, "the mass's point"}};

static int pm_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a, mdl_instance *out,
                    bg_error *err)
{
    static const char *const names[] = {"p"};
    static const int dims[] = {3};
    int id = mech_point_mass(m, c, name, mdl_arg_num(a, "mass"), mdl_arg_vec(a, "gravity", NULL));
    int r = single(m, id, out, names, dims, MDL_MECH3, 1, err);
    return r == BG_OK ? nominals(m, id, a, err) : r;
}

static int pm_place(bgr_model *m, const mdl_instance *in, const mdl_args *a, mdl_locator *loc,
                    bg_error *err)
{
    double x[3];
    const double *p = mdl_arg_vec(a, "position", NULL);
    if (!p) {
        int r = mdl_locate(loc, 0, x);
        if (r != BG_OK) return r;
        p = x;
    }
    int r = mech_point_mass_set(m, mdl_instance_main(in), p, mdl_arg_vec(a, "velocity", NULL));
    return r == BG_OK ? r : mdl_fail_model(err, m, r);
}

static int pm_port_position(const bgr_model *m, const mdl_instance *in, int port, const double *y,
                            double x[3])
{
    (void)port;
    int v = bgr_ref_var(m, (bgr_ref){BGR_STATE, mdl_instance_main(in), 0});
    if (v < 0) return BG_ERR_ARGUMENT;
    memcpy(x, y + v, 3 * sizeof *x);
    return BG_OK;
}

static const mdl_type pm_type = {
    "mech.point_mass", "point mass (mech_parts.h)",
    "x' = v\nm v' = s F + m g\nv_p = v", pm_params, COUNT(pm_params), pm_ports, COUNT(pm_ports),
    NULL, 0, 0, pm_build, pm_place, pm_port_position};

/* ---- mech.support ---- */

static const mdl_param_def support_params[] = {
    {"dim", MDL_INTEGER, 0, "1", "6", 3, 6, 0, NULL, "3 (a fixed point) or 6 (clamped)"},
    {"position", MDL_VECTOR, 3, "m", "[0, 0, 0]", -INF, INF, MDL_FINITE, NULL,
     "where it stands (for the start geometry of what is bonded to it)"},
    NOMINALS,
};
static const mdl_port_def support_ports[] = {{"p", 0, MDL_MECH6, "the fixed point (dim 3 or 6)"}};

static int support_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                         mdl_instance *out, bg_error *err)
{
    int dim = mdl_arg_int(a, "dim");
    if (dim != 3 && dim != 6)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "model", "dim: %d, expected 3 or 6", dim);
    static const char *const names[] = {"p"};
    int id = mech_support(m, c, name, dim);
    int r = single(m, id, out, names, &dim, mech_domain(dim), 1, err);
    return r == BG_OK ? nominals(m, id, a, err) : r;
}

static int support_port_position(const bgr_model *m, const mdl_instance *in, int port,
                                 const double *y, double x[3])
{
    (void)m, (void)port, (void)y;
    memcpy(x, mdl_arg_vec(&in->args, "position", NULL), 3 * sizeof *x);
    return BG_OK;
}

static const mdl_type support_type = {
    "mech.support", "fixed support (mech_parts.h): the ground",
    "v_p = 0 (and omega_p = 0 for dim 6); the efforts are the reactions (index 2)",
    support_params, COUNT(support_params), support_ports, COUNT(support_ports), NULL, 0, 0,
    support_build, NULL, support_port_position};

/* ---- joints ---- */

static const mdl_param_def spherical_params[] = {
    {"dim", MDL_INTEGER, 0, "1", "6", 3, 6, 0, NULL, "3 or 6: the ports' dimension"},
    NOMINALS,
};
static const mdl_port_def joint_ports[] = {
    {"a", 0, MDL_MECH6, "first side (dim 3 or 6)"},
    {"b", 0, MDL_MECH6, "second side"},
};

static int spherical_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                           mdl_instance *out, bg_error *err)
{
    int dim = mdl_arg_int(a, "dim");
    if (dim != 3 && dim != 6)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "model", "dim: %d, expected 3 or 6", dim);
    static const char *const names[] = {"a", "b"};
    int dims[2] = {dim, dim};
    int id = mech_spherical(m, c, name, dim);
    int r = single(m, id, out, names, dims, mech_domain(dim), 2, err);
    return r == BG_OK ? nominals(m, id, a, err) : r;
}

static const mdl_type spherical_type = {
    "mech.spherical", "spherical joint (mech_parts.h)",
    "v_a = v_b,  s_a F_a + s_b F_b = 0  (6D ports: s_a M_a = 0, s_b M_b = 0)", spherical_params,
    COUNT(spherical_params), joint_ports, COUNT(joint_ports), NULL, 0, MDL_PASS_POSITION,
    spherical_build, NULL, NULL};

static const mdl_param_def revolute_params[] = {
    {"axis", MDL_VECTOR, 3, "1", NULL, -INF, INF, MDL_FINITE, NULL,
     "the joint's axis, nonzero: in the frame of axis_body, or global"},
    {"axis_body", MDL_ELEMENT, 0, "-", NULL, 0, 0, MDL_OPTIONAL, NULL,
     "the body (mech.body) whose frame carries the axis; left out: a fixed global axis"},
    {"drive", MDL_FLAG, 0, "-", "false", 0, 0, 0, NULL,
     "a rotational port d: the relative rotation rate and the drive torque"},
    NOMINALS,
};
static const mdl_port_def revolute_ports[] = {
    {"a", 6, MDL_MECH6, "the side whose body carries the axis"},
    {"b", 6, MDL_MECH6, "the other side"},
    {"d", 1, MDL_ROTATIONAL, "with drive: relative rotation rate about the axis, torque on b"},
};

static int revolute_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                          mdl_instance *out, bg_error *err)
{
    static const char *const names[] = {"a", "b", "d"};
    int drive = mdl_arg_flag(a, "drive");
    int id = mech_revolute(m, c, name, mdl_arg_has(a, "axis_body") ? mdl_arg_element(a, "axis_body") : -1,
                           mdl_arg_vec(a, "axis", NULL), drive);
    int r = single(m, id, out, names, (const int[]){6, 6}, MDL_MECH6, 2, err);
    if (r == BG_OK && drive) r = mdl_instance_port(out, "d", bgr_port_of(m, id, 2), 1, MDL_ROTATIONAL);
    return r == BG_OK ? nominals(m, id, a, err) : r;
}

static const mdl_type revolute_type = {
    "mech.revolute", "revolute joint with an optional drive port (mech_parts.h)",
    "v_a = v_b,  (w_b - w_a).e1 = 0,  (w_b - w_a).e2 = 0   (e1, e2 _|_ the axis)\n"
    "s_a F_a + s_b F_b = 0,  s_a M_a + s_b M_b = 0\n"
    "(s_b M_b).axis + s_d e_d = 0  (no drive: 0),  f_d = (w_b - w_a).axis",
    revolute_params, COUNT(revolute_params), revolute_ports, COUNT(revolute_ports), NULL, 0,
    MDL_PASS_POSITION, revolute_build, NULL, NULL};

static const mdl_param_def revolute_angle_params[] = {
    {"axis", MDL_VECTOR, 3, "1", NULL, -INF, INF, MDL_FINITE, NULL,
     "the joint's axis, nonzero: in the frame of axis_body, or global"},
    {"axis_body", MDL_ELEMENT, 0, "-", NULL, 0, 0, MDL_OPTIONAL, NULL,
     "the body (mech.body) at a, whose frame carries the axis; left out: the ground"},
    {"body", MDL_ELEMENT, 0, "-", NULL, 0, 0, MDL_OPTIONAL, NULL,
     "the body (mech.body) at b; left out: the ground"},
    {"angle", MDL_SIGNAL, 0, "rad", NULL, 0, 0, 0, NULL,
     "theta_ref: a sig.* source's output, value (theta_ref = u) or integral (theta_ref' = u)"},
    NOMINALS,
};
static const mdl_signal_def revolute_angle_signals[] = {
    {"torque", "N m", "the drive torque tau on b about the axis"},
};

static int revolute_angle_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                                mdl_instance *out, bg_error *err)
{
    static const char *const names[] = {"a", "b"};
    bgr_ref src = mdl_arg_signal(a, "angle");
    int id = mech_revolute_angle_source(
        m, c, name, mdl_arg_has(a, "axis_body") ? mdl_arg_element(a, "axis_body") : -1,
        mdl_arg_vec(a, "axis", NULL), mdl_arg_has(a, "body") ? mdl_arg_element(a, "body") : -1,
        src.type == BGR_OWN ? src.id : -1);
    int r = single(m, id, out, names, (const int[]){6, 6}, MDL_MECH6, 2, err);
    if (r == BG_OK) r = mdl_instance_signal(out, "torque", (bgr_ref){BGR_OWN, id, 0});
    return r == BG_OK ? nominals(m, id, a, err) : r;
}

static const mdl_type revolute_angle_type = {
    "mech.revolute_angle",
    "revolute joint whose angle follows a profile, held by projection (mech_parts.h)",
    "v_a = v_b,  (w_b - w_a).e1 = 0,  (w_b - w_a).e2 = 0   (e1, e2 _|_ the axis)\n"
    "s_a F_a + s_b F_b = 0,  s_a M_a + s_b M_b = 0,  (s_b M_b).axis + tau = 0\n"
    "(w_b - w_a).axis = theta_ref'(t)\n"
    "invariant: angle of b's frame from a's about the axis = theta_ref(t) (projected)",
    revolute_angle_params, COUNT(revolute_angle_params), revolute_ports, 2,
    revolute_angle_signals, COUNT(revolute_angle_signals), MDL_PASS_POSITION,
    revolute_angle_build, NULL, NULL};

/* ---- axial elements ---- */

static const mdl_port_def axial_ports[] = {
    {"a", 3, MDL_MECH3, "end A"},
    {"b", 3, MDL_MECH3, "end B"},
};

static int axial_finish(bgr_model *m, int id, const mdl_args *a, mdl_instance *out, bg_error *err)
{
    static const char *const names[] = {"a", "b"};
    int r = single(m, id, out, names, (const int[]){3, 3}, MDL_MECH3, 2, err);
    return r == BG_OK ? nominals(m, id, a, err) : r;
}

/* d = x_B - x_A from the neighbours' positions */
static int axial_place(bgr_model *m, const mdl_instance *in, const mdl_args *a, mdl_locator *loc,
                       bg_error *err)
{
    (void)a;
    double xa[3], xb[3];
    int r = mdl_locate(loc, 0, xa);
    if (r == BG_OK) r = mdl_locate(loc, 1, xb);
    if (r != BG_OK) return r;
    r = mech_axial_set(m, mdl_instance_main(in), xa, xb);
    return r == BG_OK ? r : mdl_fail_model(err, m, r);
}

static const mdl_param_def spring_params[] = {
    {"k", MDL_NUMBER, 0, "N/m", NULL, 0, INF, 0, NULL, "stiffness"},
    {"c", MDL_NUMBER, 0, "N s/m", "0", 0, INF, 0, NULL, "damping"},
    {"L0", MDL_NUMBER, 0, "m", NULL, 0, INF, MDL_LO_OPEN, NULL, "unstretched length"},
    NOMINALS,
};

static int spring_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                        mdl_instance *out, bg_error *err)
{
    int id = mech_spring(m, c, name, mdl_arg_num(a, "k"), mdl_arg_num(a, "c"), mdl_arg_num(a, "L0"));
    return axial_finish(m, id, a, out, err);
}

#define AXIAL_EQS                                                                                  \
    "d = x_b - x_a (state),  L = |d|,  u = d / L,  L' = u.(v_b - v_a)\n"                            \
    "s_a F_a = T u,  s_b F_b = -T u\n"

static const mdl_type spring_type = {
    "mech.spring", "linear spring with damper between two points (mech_axial.h)",
    AXIAL_EQS "T = k (L - L0) + c L'", spring_params, COUNT(spring_params), axial_ports,
    COUNT(axial_ports), NULL, 0, 0, spring_build, axial_place, NULL};

static const mdl_param_def truss_params[] = {
    {"E", MDL_NUMBER, 0, "Pa", NULL, 0, INF, MDL_LO_OPEN, NULL, "Young's modulus"},
    {"A", MDL_NUMBER, 0, "m^2", NULL, 0, INF, MDL_LO_OPEN, NULL, "cross-section area"},
    {"L0", MDL_NUMBER, 0, "m", NULL, 0, INF, MDL_LO_OPEN, NULL, "unstretched length"},
    {"c", MDL_NUMBER, 0, "N s/m", "0", 0, INF, 0, NULL, "damping"},
    NOMINALS,
};

static int truss_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                       mdl_instance *out, bg_error *err)
{
    int id = mech_truss(m, c, name, mdl_arg_num(a, "E"), mdl_arg_num(a, "A"), mdl_arg_num(a, "L0"),
                        mdl_arg_num(a, "c"));
    return axial_finish(m, id, a, out, err);
}

static const mdl_type truss_type = {
    "mech.truss", "truss bar: large displacement, small strain (mech_axial.h)",
    AXIAL_EQS "T = (E A / L0) (L - L0) + c L'", truss_params, COUNT(truss_params), axial_ports,
    COUNT(axial_ports), NULL, 0, 0, truss_build, axial_place, NULL};

static const mdl_param_def rope_params[] = {
    {"k", MDL_NUMBER, 0, "N/m", NULL, 0, INF, 0, NULL, "axial stiffness when taut"},
    {"c", MDL_NUMBER, 0, "N s/m", "0", 0, INF, 0, NULL, "damping when taut"},
    {"L0", MDL_NUMBER, 0, "m", NULL, 0, INF, MDL_LO_OPEN, NULL, "unstretched length"},
    {"eps", MDL_NUMBER, 0, "m", "0", -INF, INF, MDL_FINITE, NULL,
     "width of the smooth slack transition (<= 0: 1e-4 L0)"},
    NOMINALS,
};

static int rope_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                      mdl_instance *out, bg_error *err)
{
    int id = mech_rope(m, c, name, mdl_arg_num(a, "k"), mdl_arg_num(a, "c"), mdl_arg_num(a, "L0"),
                       mdl_arg_num(a, "eps"));
    return axial_finish(m, id, a, out, err);
}

static const mdl_type rope_type = {
    "mech.rope", "rope: tension only, smooth at slack (mech_axial.h)",
    AXIAL_EQS "T = k s(L - L0) + c L' h(L - L0),  s(x) = eps ln(1 + e^(x/eps)),  h = s'",
    rope_params, COUNT(rope_params), axial_ports, COUNT(axial_ports), NULL, 0, 0, rope_build,
    axial_place, NULL};

/* ---- mech.free ---- */

static const mdl_param_def free_params[] = {
    {"dim", MDL_INTEGER, 0, "1", "6", 3, 6, 0, NULL, "3 or 6: the dimension of the port it ends"},
};
static const mdl_port_def free_ports[] = {{"p", 0, MDL_MECH6, "the free point (dim 3 or 6)"}};

static int free_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                      mdl_instance *out, bg_error *err)
{
    static const double zero[6] = {0};
    static const char *const names[] = {"p"};
    int dim = mdl_arg_int(a, "dim");
    if (dim != 3 && dim != 6)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "model", "dim: %d, expected 3 or 6", dim);
    return single(m, bgr_Se(m, c, name, dim, zero), out, names, &dim, mech_domain(dim), 1, err);
}

static const mdl_type free_type = {
    "mech.free", "a free end: a point that nothing holds (no force, no moment)",
    "F_p = 0 (and M_p = 0 for dim 6): a zero effort source", free_params, COUNT(free_params),
    free_ports, COUNT(free_ports), NULL, 0, 0, free_build, NULL, NULL};

/* ---- mech.rotation_sensor ---- */

static const mdl_param_def rsensor_params[] = {
    {"body", MDL_ELEMENT, 0, "-", NULL, 0, 0, 0, NULL, "the body (mech.body) it measures"},
    {"axis", MDL_VECTOR, 3, "1", "[0, 0, 1]", -INF, INF, MDL_FINITE, NULL,
     "the fixed global axis, nonzero"},
};
static const mdl_signal_def rsensor_signals[] = {
    {"theta", "rad", "the angle about the axis (counts past +-pi)"},
    {"omega", "rad/s", "the angular velocity about the axis"},
};

static int rsensor_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                         mdl_instance *out, bg_error *err)
{
    int id = mech_rotation_sensor(m, c, name, mdl_arg_element(a, "body"), mdl_arg_vec(a, "axis", NULL));
    if (id < 0) return mdl_fail_model(err, m, id);
    int r = mdl_instance_element(out, id);
    if (r == BG_OK) r = mdl_instance_signal(out, "theta", (bgr_ref){BGR_STATE, id, 0});
    if (r == BG_OK) r = mdl_instance_signal(out, "omega", (bgr_ref){BGR_OWN, id, 0});
    return r;
}

static const mdl_type rsensor_type = {
    "mech.rotation_sensor", "angle and rate of a body about a fixed axis (mech_sensor.h)",
    "theta' = (R w).axis,  omega = (R w).axis", rsensor_params, COUNT(rsensor_params), NULL, 0,
    rsensor_signals, COUNT(rsensor_signals), 0, rsensor_build, NULL, NULL};

const mdl_type *const mdl_types_mech[] = {
    &body_type,  &pm_type,    &support_type, &spherical_type, &revolute_type,
    &revolute_angle_type,
    &spring_type, &truss_type, &rope_type,   &rsensor_type,   &free_type,
};
const int mdl_types_mech_count = COUNT(mdl_types_mech);
