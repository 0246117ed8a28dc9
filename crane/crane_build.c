/* The rotary crane's construction (crane_model.h: crane_build): the parts of a scene as
 * bond-graph components, in a fixed order (the order fixes the unknowns' numbering, hence the
 * outputs): structure (platform, base, slewing joint), boom (hinge, beam chain or rigid body),
 * ties, rope and load, counterweight, reference, drive (held, prescribed, or the hydraulic
 * drive with its controller and valves); then the initial values and the unknowns' nominal
 * scales. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bgr_elements.h"
#include "crane_model_impl.h"
#include "ctl_pid.h"
#include "hyd_motor.h"
#include "hyd_pump.h"
#include "hyd_source.h"
#include "hyd_valve.h"
#include "hyd_volume.h"
#include "mech_axial.h"
#include "mech_beam.h"
#include "mech_body.h"
#include "mech_parts.h"
#include "mech_sensor.h"
#include "rot_gear.h"
#include "rot_inertia.h"
#include "sensors.h"
#include "sig_sources.h"

static int fail_here(bg_error *err, const char *what, bgr_model *m)
{
    return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_build", "%s: %s", what,
                          m ? bgr_model_error(m)->message : "out of memory");
}

/* In a part's builder: on failure, the status with the step named in err. */
#define TRY(x, what)                                                                               \
    do {                                                                                           \
        if ((x) < 0) return fail_here(err, what, c->m);                                            \
    } while (0)

static int set_initial(crane *c);
static int state_scales(crane *c);

/* A one-dimensional bond from port pa of element a to port pb of element b. */
typedef struct bond1 {
    const char *name;
    int a, pa, b, pb;
} bond1;

/* Bonds a table in component comp; < 0 at the first failure, its bond named in err. */
static int bonds1(bgr_model *m, bgr_comp comp, const bond1 *t, size_t n, bg_error *err)
{
    for (size_t i = 0; i < n; i++)
        if (bgr_bond(m, comp, t[i].name, 1, bgr_port_of(m, t[i].a, t[i].pa),
                     bgr_port_of(m, t[i].b, t[i].pb), NULL, NULL) < 0)
            return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_build", "bond %s: %s", t[i].name,
                                  bgr_model_error(m)->message);
    return BG_OK;
}

/* What the parts' builders share: the crane being built, the geometry of its undeformed start,
 * the nominal scales of the forces, and the platform's and the boom tip's ports as the parts
 * take them. */
typedef struct build_ctx {
    crane *c;
    int settle, nties;
    double tie_L0;
    bg_error *err;
    double g[3];           /* gravity */
    double B[3], tip[3];   /* hinge (platform frame) and undeformed tip (global) */
    double d[3];           /* tip - B */
    double W_load, W_boom; /* forces: in the rope; in boom, hinge and ties */
    double W_all, M_all;   /* force and moment in the slewing joint */
    double M_hinge;        /* moment in the hinge */
    int pport;             /* next free platform port */
    bgr_port tip_ports[3]; /* the boom tip's: ties, then the rope */
} build_ctx;

/* Geometry: the boom from B to a tip at the stated radius, its transverse directions; the
 * nominal scales. */
static int build_geometry(build_ctx *b)
{
    crane *c = b->c;
    const crane_scene *s = &c->s;
    bg_error *err = b->err;
    double *B = b->B, *tip = b->tip, *d = b->d;
    memcpy(B, s->boom_foot, 3 * sizeof *B);
    double dx = s->boom_tip_radius - B[0], dz2 = s->boom_length * s->boom_length - dx * dx;
    if (!(dz2 > 0))
        return bg_error_raise(
            err, BG_ERR_ARGUMENT, "crane_build",
            "boom of length %g cannot reach a tip radius of %g from the foot at x = %g",
            s->boom_length, s->boom_tip_radius, B[0]);
    tip[0] = s->boom_tip_radius;
    tip[1] = B[1];
    tip[2] = B[2] + sqrt(dz2);
    memcpy(c->tip0, tip, 3 * sizeof *tip);
    sub3(tip, B, d);
    for (int i = 0; i < 3; i++)
        c->e2[i] = 0; /* e2: in the luffing plane, normal to the boom, pointing up-outwards */
    c->e2[0] = -d[2] / s->boom_length;
    c->e2[2] = d[0] / s->boom_length;
    if (c->e2[2] < 0)
        for (int i = 0; i < 3; i++)
            c->e2[i] = -c->e2[i];
    c->e3[1] = 1; /* out of the luffing plane */

    c->nties = b->nties;
    /* Nominal scales of the unknowns (the solver's absolute tolerance of an unknown is atol times
     * its nominal magnitude; crane_scene.h): the weights the parts carry. The boom, its hinge and
     * the ties carry the boom's weight and the load's (the rope the load's); the slewing joint
     * everything, with the larger of the overturning moments about the axis of boom and load (at
     * the tip radius) and of the counterweight as its moment scale; the hinge's moments scale with
     * the moment of that weight about the hinge (the ties balance it). Bodies and point masses
     * declare their own weights; a zero gravity states nothing (0 keeps the components' own). */
    const double gg = fabs(s->g);
    /* a weightless load (crane_load_weightless) states no force scale for the rope */
    b->W_load = s->rope && !crane_load_weightless(s) ? s->load_mass * gg : 0.0;
    b->W_boom = s->boom_rho * s->boom_A * s->boom_length * gg + b->W_load;
    const double W_cw = s->counterweight ? s->cw_mass * gg : 0.0;
    b->W_all = b->W_boom + W_cw + s->platform_mass * gg;
    b->M_all = fmax(b->W_boom * s->boom_tip_radius, W_cw * hypot(s->cw_pos[0], s->cw_pos[1]));
    b->M_hinge = b->W_boom * fabs(s->boom_tip_radius - B[0]);
    return BG_OK;
}

/* Structure: the platform (ports 0 slewing joint (6D), 1 boom hinge (6D), then ties (3D),
 * counterweight), the base, the slewing joint about Z0 and the platform's rotation sensor. */
static int build_structure(build_ctx *b)
{
    crane *c = b->c;
    bgr_model *m = c->m;
    const crane_scene *s = &c->s;
    bg_error *err = b->err;
    const double *g = b->g, *B = b->B, z[3] = {0, 0, 1};
    const int nties = b->nties;
    {
        double r[5 * 3];
        int dims[5], np = 0;
        sub3(s->joint_A, s->platform_com, r + 3 * np), dims[np++] = 6;
        sub3(B, s->platform_com, r + 3 * np), dims[np++] = 6;
        for (int k = 0; k < nties; k++) {
            gantry_point(s, k, nties, r + 3 * np);
            sub3(r + 3 * np, s->platform_com, r + 3 * np), dims[np++] = 3;
        }
        if (s->counterweight) sub3(s->cw_pos, s->platform_com, r + 3 * np), dims[np++] = 3;
        double J[9] = {s->platform_inertia[0], 0, 0, 0, s->platform_inertia[1], 0, 0, 0,
                       s->platform_inertia[2]};
        TRY(c->platform = mech_body(m, 0, "platform", s->platform_mass, J, g, np, r, dims),
            "platform");
    }
    b->pport = 2; /* next free platform port */
    int ground = mech_support(m, 0, "base", 6);
    TRY(ground, "base");
    TRY(c->slew = mech_revolute(m, 0, "slewing_joint", -1, z, 1), "slewing joint");
    TRY(mech_set_nominal(m, ground, b->W_all, b->M_all, 0), "base scales");
    TRY(mech_set_nominal(m, c->slew, b->W_all, b->M_all, 0), "slewing joint scales");
    TRY(bgr_bond(m, 0, "b_base", 6, bgr_port_of(m, ground, 0), bgr_port_of(m, c->slew, 0), NULL,
                 NULL),
        "bond base");
    TRY(bgr_bond(m, 0, "b_slew", 6, bgr_port_of(m, c->slew, 1), bgr_port_of(m, c->platform, 0),
                 NULL, NULL),
        "bond slewing joint");
    TRY(c->sensor = mech_rotation_sensor(m, 0, "platform_sensor", c->platform, z), "sensor");
    return BG_OK;
}

/* The boom, hinged at B about the platform's y axis: a chain of beam elements or one rigid body,
 * with a port at its tip for each tie and the rope. */
static int build_boom(build_ctx *b)
{
    crane *c = b->c;
    bgr_model *m = c->m;
    const crane_scene *s = &c->s;
    bg_error *err = b->err;
    const double *g = b->g, *B = b->B, *tip = b->tip, *d = b->d, yax[3] = {0, 1, 0};
    const int nties = b->nties, settle = b->settle;
    const double tie_L0 = b->tie_L0, W_boom = b->W_boom, M_hinge = b->M_hinge;
    bgr_port *tip_ports = b->tip_ports;
    TRY(c->hinge = mech_revolute(m, 0, "boom_hinge", c->platform, yax, 0), "boom hinge");
    TRY(mech_set_nominal(m, c->hinge, W_boom, M_hinge, 0), "boom hinge scales");
    TRY(bgr_bond(m, 0, "b_hinge_a", 6, bgr_port_of(m, c->hinge, 0), bgr_port_of(m, c->platform, 1),
                 NULL, NULL),
        "bond hinge");
    bgr_port foot;
    int ntip = nties + s->rope;
    c->n = s->boom_elements;
    /* The ties' mass, rho A L0 each, lumped half at each end (a truss's lumped mass matrix): the
     * halves at the tip go into the boom's tip; those at the gantry top, a point of the rigid
     * platform, count in the platform's mass. */
    double tie_tip_mass = 0;
    for (int k = 0; k < nties && s->tie_rho > 0; k++) {
        double gt[3], dt[3];
        gantry_point(s, k, nties, gt);
        sub3(tip, gt, dt);
        tie_tip_mass +=
            0.5 * s->tie_rho * s->tie_A * (tie_L0 > 0 ? tie_L0 : sqrt(mech_dot(dt, dt)));
    }
    if (c->n > 0) {
        mech_section sec = {.E = s->boom_E,
                            .G = s->boom_G,
                            .A = s->boom_A,
                            .Iy = s->boom_I_side,
                            .Iz = s->boom_I_luff,
                            .J = s->boom_J,
                            .rho = s->boom_rho,
                            .beta = settle ? 0.05 : s->boom_beta,
                            .element = s->boom_quartic      ? MECH_BEAM_QUARTIC
                                       : s->boom_consistent ? MECH_BEAM_CONSISTENT
                                                            : MECH_BEAM_LUMPED};
        int extra[MAXEL + 1] = {0}, extra3[MAXEL + 1] = {0};
        extra[0] = 1;
        extra3[c->n] = ntip;
        const double up[3] = {0, 0, 1};
        TRY(mech_beam_chain(m, 0, "boom", c->n, B, tip, up, &sec, g, extra, extra3, c->nodes,
                            c->elems),
            "boom");
        for (int k = 0; k < c->n; k++) /* moments: that force times the element length */
            TRY(mech_set_nominal(m, c->elems[k], W_boom, 0, 0), "boom scales");
        if (tie_tip_mass > 0)
            TRY(mech_body_add_mass(m, c->nodes[c->n], tie_tip_mass), "ties' mass at the tip");
        foot = mech_beam_chain_port(m, c->nodes, c->n, extra, 0, 0);
        for (int j = 0; j < ntip; j++)
            tip_ports[j] = mech_beam_chain_port(m, c->nodes, c->n, extra, c->n, j);
    } else { /* one rigid body */
        double mass = s->boom_rho * s->boom_A * s->boom_length, L = s->boom_length;
        double u[3];
        for (int i = 0; i < 3; i++)
            u[i] = d[i] / L;
        /* rod about its centre: m L^2/12 across, small about the axis */
        double Jax = s->boom_rho * (s->boom_I_luff + s->boom_I_side) * L, Jtr = mass * L * L / 12;
        double J[9];
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++)
                J[i + 3 * k] = Jtr * ((i == k) - u[i] * u[k]) + Jax * u[i] * u[k];
        for (int i = 0; i < 3; i++)
            for (int k = i + 1; k < 3; k++)
                J[k + 3 * i] = J[i + 3 * k];
        if (tie_tip_mass > 0) { /* the ties' share at the tip: the mass centre moves to it */
            double mt = tie_tip_mass, rt[3];
            for (int i = 0; i < 3; i++)
                c->boom_cs[i] = mt * 0.5 * d[i] / (mass + mt);
            for (int i = 0; i < 3; i++)
                rt[i] = 0.5 * d[i] - c->boom_cs[i];
            double cc = mech_dot(c->boom_cs, c->boom_cs), rr = mech_dot(rt, rt);
            for (int i = 0; i < 3; i++) /* parallel axes: the rod's and the point's */
                for (int k = 0; k < 3; k++)
                    J[i + 3 * k] += mass * (cc * (i == k) - c->boom_cs[i] * c->boom_cs[k]) +
                                    mt * (rr * (i == k) - rt[i] * rt[k]);
            mass += mt;
        }
        double r[4 * 3];
        int dims[4] = {6, 3, 3, 3}; /* hinge, then ntip <= 3 tip ports */
        for (int i = 0; i < 3; i++) {
            c->foot_r[i] = r[i] = -0.5 * d[i] - c->boom_cs[i];
            c->tip_r[i] = r[3 + i] = r[6 + i] = r[9 + i] = 0.5 * d[i] - c->boom_cs[i];
        }
        TRY(c->boom = mech_body(m, 0, "boom", mass, J, g, 1 + ntip, r, dims), "rigid boom");
        TRY(mech_set_nominal(m, c->boom, W_boom, M_hinge, 0), "rigid boom scales");
        foot = bgr_port_of(m, c->boom, 0);
        for (int j = 0; j < ntip; j++)
            tip_ports[j] = bgr_port_of(m, c->boom, 1 + j);
    }
    TRY(bgr_bond(m, 0, "b_hinge_b", 6, bgr_port_of(m, c->hinge, 1), foot, NULL, NULL),
        "bond hinge boom");
    return BG_OK;
}

/* The suspension ties from the gantry (one, or a laterally spread pair) to the boom tip, the
 * tip's first ports; both ties of a pair have the same length. */
static int build_ties(build_ctx *b)
{
    crane *c = b->c;
    bgr_model *m = c->m;
    const crane_scene *s = &c->s;
    bg_error *err = b->err;
    const double *tip = b->tip;
    const int nties = b->nties, settle = b->settle;
    const double tie_L0 = b->tie_L0, W_boom = b->W_boom;
    const bgr_port *tip_ports = b->tip_ports;
    int pport = b->pport, tp = 0;
    double d[3];
    for (int k = 0; k < nties; k++) { /* both ties of a pair have the same length */
        static const char *const names[3][3] = {
            {"ties", "b_tie_gantry", "b_tie_tip"},
            {"ties_left", "b_tie_left_gantry", "b_tie_left_tip"},
            {"ties_right", "b_tie_right_gantry", "b_tie_right_tip"}};
        const char *const *nm = names[nties == 1 ? 0 : 1 + k];
        double gt[3], L0;
        gantry_point(s, k, nties, gt);
        sub3(tip, gt, d);
        L0 = tie_L0 > 0 ? tie_L0 : sqrt(mech_dot(d, d));
        c->tie_L0 = L0;
        double c_tie = settle ? 1e6 : s->tie_beta * s->tie_E * s->tie_A / L0;
        TRY(c->tie[k] = mech_truss(m, 0, nm[0], s->tie_E, s->tie_A, L0, c_tie), "ties");
        TRY(mech_set_nominal(m, c->tie[k], W_boom, 0, 0), "tie scales");
        TRY(bgr_bond(m, 0, nm[1], 3, bgr_port_of(m, c->platform, pport++),
                     bgr_port_of(m, c->tie[k], 0), NULL, NULL),
            "bond tie gantry");
        TRY(bgr_bond(m, 0, nm[2], 3, tip_ports[tp++], bgr_port_of(m, c->tie[k], 1), NULL, NULL),
            "bond tie tip");
    }
    b->pport = pport;
    return BG_OK;
}

/* The rope from the tip's last port to the load (in the settling model with a damper on the
 * load: it swings as a 71 m pendulum). */
static int build_rope(build_ctx *b)
{
    crane *c = b->c;
    bgr_model *m = c->m;
    const crane_scene *s = &c->s;
    bg_error *err = b->err;
    const double *g = b->g, W_load = b->W_load;
    const int settle = b->settle;
    const bgr_port *tip_ports = b->tip_ports;
    int tp = b->nties; /* after the ties */
    if (!s->rope) return BG_OK;
    double k = s->rope_E * s->rope_A / s->rope_length;
    double damp = settle ? 2 * sqrt(k * s->load_mass) : s->rope_damping;
    TRY(c->rope = mech_rope(m, 0, "rope", k, damp, s->rope_length, 0), "rope");
    TRY(mech_set_nominal(m, c->rope, W_load, 0, 0), "rope scales");
    TRY(c->load = mech_point_mass(m, 0, "load", s->load_mass, g), "load");
    TRY(bgr_bond(m, 0, "b_rope_tip", 3, tip_ports[tp++], bgr_port_of(m, c->rope, 0), NULL, NULL),
        "bond rope tip");
    if (settle) { /* the load swings as a 71 m pendulum: damp it to rest */
        int j = bgr_one(m, 0, "load_node", 3, 3), r;
        TRY(j, "load node");
        TRY(r = bgr_R(m, 0, "load_damper", 3, 2 * s->load_mass * sqrt(s->g / s->rope_length)),
            "load damper");
        TRY(bgr_bond(m, 0, "b_rope_load", 3, bgr_port_of(m, c->rope, 1), bgr_port_of(m, j, 0), NULL,
                     NULL),
            "bond rope load");
        TRY(bgr_bond(m, 0, "b_load", 3, bgr_port_of(m, j, 1), bgr_port_of(m, c->load, 0), NULL,
                     NULL),
            "bond load");
        TRY(bgr_bond(m, 0, "b_load_damper", 3, bgr_port_of(m, j, 2), bgr_port_of(m, r, 0), NULL,
                     NULL),
            "bond load damper");
    } else {
        TRY(bgr_bond(m, 0, "b_rope_load", 3, bgr_port_of(m, c->rope, 1), bgr_port_of(m, c->load, 0),
                     NULL, NULL),
            "bond rope load");
    }
    return BG_OK;
}

/* The counterweight, a point mass on the platform's last port. */
static int build_counterweight(build_ctx *b)
{
    crane *c = b->c;
    bgr_model *m = c->m;
    const crane_scene *s = &c->s;
    bg_error *err = b->err;
    const double *g = b->g;
    int pport = b->pport;
    if (!s->counterweight) return BG_OK;
    TRY(c->cw = mech_point_mass(m, 0, "counterweight", s->cw_mass, g), "counterweight");
    TRY(bgr_bond(m, 0, "b_cw", 3, bgr_port_of(m, c->platform, pport++), bgr_port_of(m, c->cw, 0),
                 NULL, NULL),
        "bond counterweight");
    b->pport = pport;
    return BG_OK;
}

/* The reference (Eq. 8): value, rate, integral (not in the settling model: the platform is
 * held). */
static int build_reference(build_ctx *b)
{
    crane *c = b->c;
    bgr_model *m = c->m;
    const crane_scene *s = &c->s;
    bg_error *err = b->err;
    if (b->settle) return BG_OK;
    TRY(c->ref_value = sig_trapezoid(m, 0, "omega_ref", 0, s->ref_t1, s->ref_t2, s->ref_t3,
                                     s->ref_rate, SIG_VALUE),
        "reference");
    TRY(c->ref_rate = sig_trapezoid(m, 0, "alpha_ref", 0, s->ref_t1, s->ref_t2, s->ref_t3,
                                    s->ref_rate, SIG_RATE),
        "reference rate");
    TRY(c->ref_int = sig_trapezoid(m, 0, "theta_ref", 0, s->ref_t1, s->ref_t2, s->ref_t3,
                                   s->ref_rate, SIG_INTEGRAL),
        "reference angle");
    return BG_OK;
}

/* The controller: the paper's PID on the platform's rate against the reference, its output x
 * the fraction of the pump's displacement; its derivative term on the measured acceleration
 * (the motor's, through the gear) or on a filtered rate. */
static int build_controller(build_ctx *b, bgr_comp hy, int inertia)
{
    crane *c = b->c;
    bgr_model *m = c->m;
    const crane_scene *s = &c->s;
    bg_error *err = b->err;
    int acc;
    ctl_pid_spec spec = {.kp = s->kp,
                         .ki = s->ki,
                         .kd = s->kd,
                         .reference = {BGR_OWN, c->ref_value, 0},
                         .measurement = {BGR_OWN, c->sensor, 0},
                         .use_reference_rate = 1,
                         .reference_rate = {BGR_OWN, c->ref_rate, 0},
                         .derivative_filter = s->kd_filter,
                         .limit = s->x_limit > 0,
                         .out_min = -s->x_limit,
                         .out_max = s->x_limit,
                         .smoothing = 0.01 * (s->x_limit > 0 ? s->x_limit : 1)};
    c->motor_acc = -1;
    if (s->kd_filter == 0) { /* the measured acceleration: the motor's, through the gear */
        TRY(acc = rot_sensor(m, hy, "motor_acceleration", inertia, ROT_ACCELERATION), "sensor");
        TRY(c->motor_acc = bgr_gain(m, hy, "platform_acceleration", (bgr_ref){BGR_OWN, acc, 0},
                                    1.0 / s->gear_ratio),
            "gain");
        spec.use_measurement_rate = 1;
        spec.measurement_rate = (bgr_ref){BGR_OWN, c->motor_acc, 0};
    }
    TRY(c->pid = ctl_pid(m, hy, "pid", &spec), "pid");
    return BG_OK;
}

/* Cross-port relief valves between the lines vh and vl and check valves into them. */
static int build_valves(build_ctx *b, bgr_comp hy, int vh, int vl)
{
    crane *c = b->c;
    bgr_model *m = c->m;
    const crane_scene *s = &c->s;
    bg_error *err = b->err;
    /* Cross-port relief valves (full flow at 5 MPa above cracking) and anti-cavitation
     * check valves from the charge pressure into each line (cracking at 0.1 MPa, full
     * flow at 0.5 MPa), all rated for twice the pump's full flow: the most that pump
     * and motor can drive through them together at the plateau's motor speed. */
    double qmax = s->pump_disp * s->pump_speed / 3.14159265358979323846;
    double pc = s->relief_pressure;
    int rhl, rlh, ch, cl, th, tl;
    TRY(rhl = hyd_relief_valve(m, hy, "relief_hl", pc, pc + 5e6, qmax, 5e4), "relief");
    TRY(rlh = hyd_relief_valve(m, hy, "relief_lh", pc, pc + 5e6, qmax, 5e4), "relief");
    TRY(ch = hyd_relief_valve(m, hy, "check_high", 1e5, 5e5, qmax, 1e4), "check valve");
    TRY(cl = hyd_relief_valve(m, hy, "check_low", 1e5, 5e5, qmax, 1e4), "check valve");
    TRY(th = hyd_tank(m, hy, "charge_high", s->charge_pressure), "charge");
    TRY(tl = hyd_tank(m, hy, "charge_low", s->charge_pressure), "charge");
    c->tanks[c->ntanks++] = th;
    c->tanks[c->ntanks++] = tl;
    const bond1 vb[] = {{"b_rhl_in", vh, 2, rhl, 0}, {"b_rhl_out", rhl, 1, vl, 3},
                        {"b_rlh_in", vl, 4, rlh, 0}, {"b_rlh_out", rlh, 1, vh, 3},
                        {"b_chh_in", th, 0, ch, 0},  {"b_chh_out", ch, 1, vh, 4},
                        {"b_chl_in", tl, 0, cl, 0},  {"b_chl_out", cl, 1, vl, 5}};
    return bonds1(m, hy, vb, sizeof vb / sizeof vb[0], err);
}

/* The hydraulic drive: PID -> variable-displacement pump -> closed circuit (two line volumes,
 * leakage, charge) -> motor -> motor inertia -> gear, bonded to the drive port. */
static int build_hydraulics(build_ctx *b, bgr_port drive)
{
    crane *c = b->c;
    bgr_model *m = c->m;
    const crane_scene *s = &c->s;
    bg_error *err = b->err;
    bgr_comp hy = bgr_component(m, 0, "hydraulics");
    TRY(hy, "hydraulics");
    double w = s->pump_speed;
    int prime, pump, motor, vh, vl, tank, charge, jm, inertia, gear;
    /* motor shaft, its acceleration (the platform's through the gear) and the PID first:
     * the pump's command refers to the PID's output */
    TRY(jm = bgr_one(m, hy, "motor_shaft", 3, 1), "shaft");
    TRY(inertia = rot_inertia(m, hy, "motor_inertia", s->motor_inertia), "motor inertia");
    TRY(gear = rot_gear(m, hy, "gear", s->gear_ratio), "gear");
    if (build_controller(b, hy, inertia) < 0) return BG_ERR_ARGUMENT;
    TRY(prime = bgr_Sf(m, hy, "prime_mover", 1, &w), "prime mover");
    TRY(pump = hyd_pump_servo(m, hy, "pump", s->pump_disp, s->pump_leak,
                              (bgr_ref){BGR_OWN, c->pid, 0}, s->pump_servo_bw),
        "pump");
    TRY(motor = hyd_motor(m, hy, "motor", s->motor_disp, s->motor_leak, 0), "motor");
    int valves = s->relief_pressure > 0; /* two reliefs and two check valves */
    TRY(vh = hyd_volume(m, hy, "line_high", 2 + 3 * valves, s->line_volume, s->bulk_modulus),
        "line");
    TRY(vl = hyd_volume(m, hy, "line_low", 3 + 3 * valves, s->line_volume, s->bulk_modulus),
        "line");
    /* Scales of the drive: the pressure the relief valves let the lines reach at full flow
     * (cracking + 5 MPa; without valves the charge pressure, the one pressure the scene
     * states), the pump's drive speed (its flows: the full displacement times it), the
     * motor's speed on the reference's plateau (rate times the gear ratio; its flows: its
     * displacement times it) */
    double p_nom = valves ? s->relief_pressure + 5e6 : s->charge_pressure;
    double w_motor = fabs(s->ref_rate) * s->gear_ratio;
    TRY(hyd_volume_set_nominal(m, vh, p_nom), "line scales");
    TRY(hyd_volume_set_nominal(m, vl, p_nom), "line scales");
    TRY(hyd_pump_set_nominal(m, pump, p_nom, s->pump_speed), "pump scales");
    TRY(hyd_motor_set_nominal(m, motor, p_nom, w_motor), "motor scales");
    TRY(rot_inertia_set_nominal(m, inertia, w_motor), "motor inertia scales");
    TRY(tank = hyd_tank(m, hy, "charge_pump", s->charge_pressure), "charge");
    c->prime = prime;
    c->tanks[c->ntanks++] = tank;
    TRY(charge = hyd_leakage(m, hy, "charge_valve", 1e-9), "charge valve");
    c->vol_h = vh;
    c->vol_l = vl;
    c->pump = pump;
    const bond1 hb[] = {{"b_prime", prime, 0, pump, 0},   {"b_pump_in", vl, 0, pump, 1},
                        {"b_pump_out", pump, 2, vh, 0},   {"b_motor_in", vh, 1, motor, 0},
                        {"b_motor_out", motor, 1, vl, 1}, {"b_tank", tank, 0, charge, 0},
                        {"b_charge", charge, 1, vl, 2},   {"b_shaft", motor, 2, jm, 0},
                        {"b_inertia", jm, 1, inertia, 0}, {"b_gear_in", jm, 2, gear, 0}};
    if (bonds1(m, hy, hb, sizeof hb / sizeof hb[0], err) < 0) return BG_ERR_ARGUMENT;
    if (valves && build_valves(b, hy, vh, vl) < 0) return BG_ERR_ARGUMENT;
    TRY(c->drive_bond = bgr_bond(m, 0, "b_drive", 1, bgr_port_of(m, gear, 1), drive, NULL, NULL),
        "bond drive");
    return BG_OK;
}

/* The drive into the slewing joint's port: held (the settling model), the reference's rate
 * prescribed (no hydraulics), or the hydraulic drive. */
static int build_drive(build_ctx *b)
{
    crane *c = b->c;
    bgr_model *m = c->m;
    const crane_scene *s = &c->s;
    bg_error *err = b->err;
    const int settle = b->settle;
    bgr_port drive = bgr_port_of(m, c->slew, 2);
    if (settle) {
        double zero = 0;
        int hold;
        TRY(hold = bgr_Sf(m, 0, "hold", 1, &zero), "hold");
        TRY(c->drive_bond =
                bgr_bond(m, 0, "b_drive", 1, bgr_port_of(m, hold, 0), drive, NULL, NULL),
            "bond hold");
    } else if (!s->hydraulics) {
        int pres;
        TRY(pres = bgr_Sf_signal(m, 0, "prescribed_rate", (bgr_ref){BGR_OWN, c->ref_value, 0}),
            "prescribed rate");
        TRY(c->drive_bond =
                bgr_bond(m, 0, "b_drive", 1, bgr_port_of(m, pres, 0), drive, NULL, NULL),
            "bond drive");
    } else {
        return build_hydraulics(b, drive);
    }
    return BG_OK;
}

crane *crane_build_model(const crane_scene *sc, int settle, double tie_L0, bg_error *err)
{
    crane *c = calloc(1, sizeof *c);
    if (!c) {
        bg_error_raise(err, BG_ERR_MEMORY, "crane_build", "out of memory");
        return NULL;
    }
    c->s = *sc;
    c->settle = settle;
    const crane_scene *s = &c->s;
    int nties = s->ties ? (s->tie_spread > 0 ? 2 : 1) : 0;
    if (s->boom_elements < 0 || s->boom_elements > MAXEL) {
        bg_error_raise(err, BG_ERR_ARGUMENT, "crane_build", "boom_elements %d outside 0..%d",
                       s->boom_elements, MAXEL);
        free(c);
        return NULL;
    }
    c->m = bgr_model_create("crane");
    if (!c->m) {
        bg_error_raise(err, BG_ERR_MEMORY, "crane_build", "out of memory");
        free(c);
        return NULL;
    }
    build_ctx b = {
        .c = c, .settle = settle, .nties = nties, .tie_L0 = tie_L0, .err = err, .g = {0, 0, -s->g}};
    if (build_geometry(&b) < 0 || build_structure(&b) < 0 || build_boom(&b) < 0 ||
        build_ties(&b) < 0 || build_rope(&b) < 0 || build_counterweight(&b) < 0 ||
        build_reference(&b) < 0 || build_drive(&b) < 0)
        goto fail;
    bgr_model *m = c->m;
    if (bgr_compile(m) != BG_OK) {
        fail_here(err, "compile", m);
        goto fail;
    }
    if (set_initial(c) != 0) {
        fail_here(err, "initial values", m);
        goto fail;
    }
    if (state_scales(c) != BG_OK) {
        fail_here(err, "nominal scales", m);
        goto fail;
    }
    return c;
fail:
    crane_free(&c);
    return NULL;
}

static int set_initial(crane *c)
{
    bgr_model *m = c->m;
    const crane_scene *s = &c->s;
    double *y0 = bgr_y0(m), tip[3], B[3], gantry[3], load[3];
    memcpy(tip, c->tip0, sizeof tip);
    memcpy(B, s->boom_foot, sizeof B);
    if (mech_body_set(m, c->platform, s->platform_com, NULL, NULL, NULL) != BG_OK) return -1;
    if (c->n > 0) {
        if (mech_beam_chain_set(m, c->nodes, c->n, B, tip) != BG_OK) return -1;
        c->v_tip = mech_body_var(m, c->nodes[c->n], 'x');
        c->v_node0 = mech_body_var(m, c->nodes[0], 'x');
    } else {
        double mid[3];
        for (int i = 0; i < 3; i++)
            mid[i] = 0.5 * (B[i] + tip[i]) + c->boom_cs[i];
        if (mech_body_set(m, c->boom, mid, NULL, NULL, NULL) != BG_OK) return -1;
        c->v_tip = mech_body_var(m, c->boom, 'x');
        c->v_tipq = mech_body_var(m, c->boom, 'q');
    }
    c->v_plat_x = mech_body_var(m, c->platform, 'x');
    c->v_plat_q = mech_body_var(m, c->platform, 'q');
    for (int k = 0; k < c->nties; k++) {
        gantry_point(s, k, c->nties, gantry);
        if (mech_axial_set(m, c->tie[k], gantry, tip) != BG_OK) return -1;
    }
    c->v_load = -1;
    if (s->rope) {
        memcpy(load, tip, sizeof load);
        load[2] -= s->rope_length;
        if (mech_axial_set(m, c->rope, tip, load) != BG_OK ||
            mech_point_mass_set(m, c->load, load, NULL) != BG_OK)
            return -1;
        c->v_load = bgr_ref_var(m, (bgr_ref){BGR_STATE, c->load, 0});
    }
    if (s->counterweight && mech_point_mass_set(m, c->cw, s->cw_pos, NULL) != BG_OK) return -1;
    c->v_theta = bgr_ref_var(m, (bgr_ref){BGR_STATE, c->sensor, 0});
    c->v_omega = bgr_ref_var(m, (bgr_ref){BGR_OWN, c->sensor, 0});
    if (!c->settle) {
        c->v_theta_ref = bgr_ref_var(m, (bgr_ref){BGR_OWN, c->ref_int, 0});
        c->v_omega_ref = bgr_ref_var(m, (bgr_ref){BGR_OWN, c->ref_value, 0});
        c->v_alpha_ref = bgr_ref_var(m, (bgr_ref){BGR_OWN, c->ref_rate, 0});
    }
    c->v_x = c->v_ph = c->v_pl = c->v_alpha = -1;
    if (s->hydraulics && !c->settle) {
        /* the pump's displacement: its swash plate with an actuator, else the PID's command */
        c->v_x = s->pump_servo_bw > 0 ? bgr_ref_var(m, (bgr_ref){BGR_STATE, c->pump, 0})
                                      : bgr_ref_var(m, (bgr_ref){BGR_OWN, c->pid, 0});
        c->v_ph = bgr_ref_var(m, (bgr_ref){BGR_STATE, c->vol_h, 0});
        c->v_pl = bgr_ref_var(m, (bgr_ref){BGR_STATE, c->vol_l, 0});
        if (c->motor_acc >= 0) c->v_alpha = bgr_ref_var(m, (bgr_ref){BGR_OWN, c->motor_acc, 0});
        y0[c->v_ph] = y0[c->v_pl] = s->charge_pressure;
        /* the bonds at what their volumes and sources hold at the start (the lines' and the
         * tanks' pressure at every port, the prime mover's speed), as the model files' reader
         * starts them (model/mdl_types_hyd.c): the static start then begins consistent there */
        const int vols[2] = {c->vol_h, c->vol_l};
        for (int j = 0; j < 2 + c->ntanks; j++) {
            const bgr_element *el = bgr_element_get(m, j < 2 ? vols[j] : c->tanks[j - 2]);
            for (int k = 0; el && k < el->nports; k++)
                if (bgr_ev(el, m, k, 0) >= 0) y0[bgr_ev(el, m, k, 0)] = s->charge_pressure;
        }
        const bgr_element *pm = bgr_element_get(m, c->prime);
        if (pm && bgr_fv(pm, m, 0, 0) >= 0) y0[bgr_fv(pm, m, 0, 0)] = s->pump_speed;
    }
    return 0; /* c->tip0: the undeformed tip until crane_settle puts the static one there */
}

crane *crane_build(const crane_scene *s, bg_error *err)
{
    return crane_build_model(s, 0, 0.0, err);
}

/* Hooks of the static start (crane_static.c). */
crane *crane_build_ties(const crane_scene *s, double tie_L0, bg_error *err)
{
    return crane_build_model(s, 0, tie_L0, err);
}

void crane_free(crane **c)
{
    if (!c || !*c) return;
    bgr_model_free(&(*c)->m);
    free(*c);
    *c = NULL;
}

/* The physical quantity of an unknown of the crane model, from its path (for the table of the
 * nominal scales): the hydraulic bonds carry pressure and volume flow, the other 1D bonds torque
 * and speed; the 3D and 6D bonds force (e0..e2), moment (e3..e5), velocity and angular velocity;
 * the states by their names. */
const char *crane_domain_of(const char *nm)
{
    static const char *const hyd_bonds[] = {
        "b_pump_in/", "b_pump_out/", "b_motor_in/", "b_motor_out/", "b_tank/",
        "b_charge/",  "b_rhl_",      "b_rlh_",      "b_chh_",       "b_chl_"};
    const char *leaf = strrchr(nm, '/');
    leaf = leaf ? leaf + 1 : nm;
    int digit = leaf[0] && leaf[1] >= '0' && leaf[1] <= '9', low = digit && leaf[1] < '3';
    if (strstr(nm, "/line_high/p") || strstr(nm, "/line_low/p")) return "pressure [Pa]";
    for (size_t k = 0; k < sizeof hyd_bonds / sizeof *hyd_bonds; k++)
        if (strstr(nm, hyd_bonds[k]))
            return leaf[0] == 'e' ? "pressure [Pa]" : "volume flow [m^3/s]";
    if (strstr(nm, "/b_") && !digit) return leaf[0] == 'e' ? "torque [N m]" : "shaft speed [rad/s]";
    if (strstr(nm, "/b_") || strstr(nm, "/ba") || strstr(nm, "/bb")) {
        if (leaf[0] == 'e') return low ? "force [N]" : "moment [N m]";
        return low ? "velocity [m/s]" : "angular velocity [rad/s]";
    }
    if (strstr(nm, "motor_inertia/p")) return "angular momentum [N m s]";
    if (digit && (leaf[0] == 'x' || leaf[0] == 'd')) return "position [m]";
    if (digit && leaf[0] == 'v') return "velocity [m/s]";
    if (digit && leaf[0] == 'w') return "angular velocity [rad/s]";
    if (digit && leaf[0] == 'q') return "orientation quaternion [-]";
    return "angles, controller, signals";
}

/* The scene's nominal magnitudes of positions, velocities and angular velocities (crane_scene:
 * the quantities no parameter gives a size), by the quantity domain_of finds for each unknown
 * (0: what the components declared, 1 in SI units); a member's stretch vector keeps its length
 * if that is larger. */
static int state_scales(crane *c)
{
    const crane_scene *s = &c->s;
    const double *nom = bgr_nominals(c->m);
    if (!nom) return BG_OK;
    for (int i = 0; i < bgr_n(c->m); i++) {
        const char *nm = bgr_var_name(c->m, i), *d = crane_domain_of(nm), *leaf = strrchr(nm, '/');
        int stretch = leaf && leaf[1] == 'd';
        double v = !strcmp(d, "position [m]")               ? s->nominal_length
                   : !strcmp(d, "velocity [m/s]")           ? s->nominal_velocity
                   : !strcmp(d, "angular velocity [rad/s]") ? s->nominal_angular_velocity
                                                            : 0.0;
        if (stretch && v < nom[i]) v = 0.0;
        if (v > 0 && v != nom[i]) {
            int st = bgr_set_nominal(c->m, i, v);
            if (st != BG_OK) return st;
        }
    }
    return BG_OK;
}

int crane_load_weightless(const crane_scene *s)
{
    double W = s->load_mass * fabs(s->g), fs = s->rope_E * s->rope_A * 1e-4 * log(2.0);
    return s->rope && !(W > DBL_EPSILON * fs);
}
