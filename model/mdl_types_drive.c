/* Model-file types of the linear hydraulic drive: the double-acting cylinder (hyd_cylinder.h)
 * and the 4/3 proportional directional valve (hyd_directional.h). The equations are the
 * headers', restated for the type reference. */
#include <math.h>

#include "hyd_cylinder.h"
#include "hyd_directional.h"
#include "mdl_impl.h"

#define INF HUGE_VAL
#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

/* ---- hyd.cylinder ---- */

static const mdl_param_def cyl_params[] = {
    {"area_a", MDL_NUMBER, 0, "m^2", NULL, 0, INF, MDL_LO_OPEN, NULL, "piston area A_a (cap side)"},
    {"area_b", MDL_NUMBER, 0, "m^2", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "rod-side annulus area A_b, at most A_a"},
    {"length_min", MDL_NUMBER, 0, "m", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "distance A-B at zero stroke"},
    {"stroke", MDL_NUMBER, 0, "m", NULL, 0, INF, MDL_LO_OPEN, NULL, "the stroke"},
    {"volume_a0", MDL_NUMBER, 0, "m^3", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "dead volume of the cap side at zero extension (with its line)"},
    {"volume_b0", MDL_NUMBER, 0, "m^3", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "dead volume of the rod side at full extension (with its line)"},
    {"beta", MDL_NUMBER, 0, "Pa", NULL, 0, INF, MDL_LO_OPEN, NULL, "bulk modulus of the oil"},
    {"friction", MDL_NUMBER, 0, "N s/m", "0", 0, INF, 0, NULL, "viscous friction c"},
    {"leakage", MDL_NUMBER, 0, "m^3/(s Pa)", "0", 0, INF, 0, NULL,
     "internal leakage conductance across the piston"},
    {"p_a0", MDL_NUMBER, 0, "Pa", "0", -INF, INF, MDL_FINITE, NULL, "initial cap-side pressure"},
    {"p_b0", MDL_NUMBER, 0, "Pa", "0", -INF, INF, MDL_FINITE, NULL, "initial rod-side pressure"},
    {"nominal_pressure", MDL_NUMBER, 0, "Pa", "0", 0, INF, 0, NULL,
     "pressure scale of the chambers for the error test (0: SI units)"},
    {"nominal_speed", MDL_NUMBER, 0, "m/s", "0", 0, INF, 0, NULL,
     "piston speed scale of the flows (0: SI units)"},
};
static const mdl_port_def cyl_ports[] = {
    {"A", 3, MDL_MECH3, "the barrel's attachment point"},
    {"B", 3, MDL_MECH3, "the rod end's attachment point"},
    {"a", 1, MDL_HYDRAULIC, "cap side: pressure p_a, flow into the cap chamber"},
    {"b", 1, MDL_HYDRAULIC, "rod side: pressure p_b, flow into the rod chamber"},
};

static int cyl_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                     mdl_instance *out, bg_error *err)
{
    hyd_cylinder_spec s = {mdl_arg_num(a, "area_a"),    mdl_arg_num(a, "area_b"),
                           mdl_arg_num(a, "length_min"), mdl_arg_num(a, "stroke"),
                           mdl_arg_num(a, "volume_a0"),  mdl_arg_num(a, "volume_b0"),
                           mdl_arg_num(a, "beta"),       mdl_arg_num(a, "friction"),
                           mdl_arg_num(a, "leakage")};
    int id = hyd_cylinder(m, c, name, &s);
    if (id < 0) return mdl_fail_model(err, m, id);
    static const char *const names[] = {"A", "B", "a", "b"};
    static const int dims[] = {3, 3, 1, 1};
    int r = mdl_instance_element(out, id);
    for (int k = 0; r == BG_OK && k < 4; k++)
        r = mdl_instance_port(out, names[k], bgr_port_of(m, id, k), dims[k],
                              k < 2 ? MDL_MECH3 : MDL_HYDRAULIC);
    if (r == BG_OK) r = mdl_instance_signal(out, "p_a", (bgr_ref){BGR_STATE, id, 3});
    if (r == BG_OK) r = mdl_instance_signal(out, "p_b", (bgr_ref){BGR_STATE, id, 4});
    double pn = mdl_arg_num(a, "nominal_pressure"), vn = mdl_arg_num(a, "nominal_speed");
    if (r == BG_OK && (pn > 0 || vn > 0)) {
        r = hyd_cylinder_set_nominal(m, id, pn, vn);
        if (r != BG_OK) return mdl_fail_model(err, m, r);
    }
    return r;
}

/* d from the neighbours' positions, the chambers' pressures as given */
static int cyl_place(bgr_model *m, const mdl_instance *in, const mdl_args *a, mdl_locator *loc,
                     bg_error *err)
{
    double xa[3], xb[3];
    int r = mdl_locate(loc, 0, xa);
    if (r == BG_OK) r = mdl_locate(loc, 1, xb);
    if (r != BG_OK) return r;
    r = hyd_cylinder_set(m, mdl_instance_main(in), xa, xb, mdl_arg_num(a, "p_a0"), mdl_arg_num(a, "p_b0"));
    return r == BG_OK ? r : mdl_fail_model(err, m, r);
}

static const mdl_signal_def cyl_signals[] = {
    {"p_a", "Pa", "cap-side pressure"},
    {"p_b", "Pa", "rod-side pressure"},
};

static const mdl_type cyl_type = {
    "hyd.cylinder", "double-acting hydraulic cylinder between two points (hyd_cylinder.h)",
    "d = x_B - x_A (state),  L = |d|,  u = d / L,  x = L - L_min,  x' = u.(v_B - v_A)\n"
    "V_a = V_a0 + A_a x,  V_b = V_b0 + A_b (stroke - x),  q_l = G (p_a - p_b)\n"
    "p_a' = (beta / V_a) (q_a - A_a x' - q_l)\n"
    "p_b' = (beta / V_b) (q_b + A_b x' + q_l)\n"
    "T = -(p_a A_a - p_b A_b) + c x',  s_A F_A = -T u,  s_B F_B = T u",
    cyl_params, COUNT(cyl_params), cyl_ports, COUNT(cyl_ports), cyl_signals, COUNT(cyl_signals),
    0, cyl_build, cyl_place, NULL};

/* ---- hyd.directional_valve ---- */

static const mdl_param_def dv_params[] = {
    {"command", MDL_SIGNAL, 0, "1", NULL, 0, 0, 0, NULL,
     "the spool command u (-1 .. 1 in normal use; u > 0 opens P->A and B->T)"},
    {"flow_rated", MDL_NUMBER, 0, "m^3/s", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "rated flow q_n of one metering edge at dp_rated"},
    {"dp_rated", MDL_NUMBER, 0, "Pa", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "pressure drop dp_n across one edge at the rated flow (catalogues: 35 bar per edge)"},
    {"underlap", MDL_NUMBER, 0, "1", "0", 0, 0.5, 0, NULL,
     "underlap u0, a fraction of the rated travel (0: critically centred)"},
    {"leakage", MDL_NUMBER, 0, "m^3/(s Pa)", "0", 0, INF, 0, NULL,
     "laminar leakage conductance of each edge"},
    {"dp_laminar", MDL_NUMBER, 0, "Pa", "0", 0, INF, 0, NULL,
     "the orifice's laminar width, at most dp_rated (0: 0.01 dp_rated)"},
    {"spool_smoothing", MDL_NUMBER, 0, "1", "0", 0, 0.1, 0, NULL,
     "width of the smooth opening, a fraction of the travel (0: 1e-3)"},
};
static const mdl_port_def dv_ports[] = {
    {"P", 1, MDL_HYDRAULIC, "supply"},
    {"T", 1, MDL_HYDRAULIC, "tank"},
    {"A", 1, MDL_HYDRAULIC, "service port A (fed from P for u > 0)"},
    {"B", 1, MDL_HYDRAULIC, "service port B (fed from P for u < 0)"},
};

static int dv_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                    mdl_instance *out, bg_error *err)
{
    hyd_directional_spec s = {mdl_arg_num(a, "flow_rated"), mdl_arg_num(a, "dp_rated"),
                              mdl_arg_num(a, "underlap"),   mdl_arg_num(a, "leakage"),
                              mdl_arg_num(a, "dp_laminar"), mdl_arg_num(a, "spool_smoothing")};
    int id = hyd_directional_valve(m, c, name, mdl_arg_signal(a, "command"), &s);
    if (id < 0) return mdl_fail_model(err, m, id);
    static const char *const names[] = {"P", "T", "A", "B"};
    int r = mdl_instance_element(out, id);
    for (int k = 0; r == BG_OK && k < 4; k++)
        r = mdl_instance_port(out, names[k], bgr_port_of(m, id, k), 1, MDL_HYDRAULIC);
    return r;
}

static const mdl_type dv_type = {
    "hyd.directional_valve", "4/3 proportional directional valve (hyd_directional.h)",
    "Q_XY = K a_XY(u) f(p_X - p_Y) + G_l (p_X - p_Y)   for the edges P->A, B->T, P->B, A->T\n"
    "a_PA = a_BT = o(u),  a_PB = a_AT = o(-u),  o(z) = sp(z + u0) / sp(1 + u0)\n"
    "f(dp) = dp (dp^2 + dp_l^2)^(-1/4),  K = q_n / f(dp_n)\n"
    "q_P = Q_PA + Q_PB,  q_A = Q_AT - Q_PA,  q_B = Q_BT - Q_PB,  q_P + q_T + q_A + q_B = 0",
    dv_params, COUNT(dv_params), dv_ports, COUNT(dv_ports), NULL, 0, 0, dv_build, NULL, NULL};

const mdl_type *const mdl_types_drive[] = {&cyl_type, &dv_type};
const int mdl_types_drive_count = COUNT(mdl_types_drive);
