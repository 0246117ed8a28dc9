/* Model-file types of the standard bond-graph elements (bondgraph/bgr_elements.h) with constant
 * parameters or signals: I, C, R, the sources, TF, GY and the junctions. Their ports are generic:
 * they take the domain of what they are bonded to. The equations are the header's, restated
 * here for the type reference; d is the dimension `dim` of every port of the element. */
#include <math.h>
#include <string.h>

#include "bgr_elements.h"
#include "mdl_impl.h"

#define INF HUGE_VAL
#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

#define DIM(max)                                                                                   \
    {"dim", MDL_INTEGER, 0, "1", "1", 1, max, 0, NULL, "the dimension d of its ports"}

/* one element with fixed generic ports, each of dimension dim: record them and the element */
static int single(bgr_model *m, int id, mdl_instance *out, const char *const *names, int n,
                  int dim, bg_error *err)
{
    if (id < 0) return mdl_fail_model(err, m, id);
    int r = mdl_instance_element(out, id);
    for (int k = 0; r == BG_OK && k < n; k++)
        r = mdl_instance_port(out, names[k], bgr_port_of(m, id, k), dim, MDL_GENERIC);
    return r;
}

static const char *const name_p[] = {"p"};
static const char *const names_ab[] = {"a", "b"};

static const mdl_port_def oneport_in[] = {{"p", 0, MDL_GENERIC, "the port (power in)"}};
static const mdl_port_def oneport_out[] = {{"p", 0, MDL_GENERIC, "the port (power out)"}};
static const mdl_port_def oneport1_out[] = {{"p", 1, MDL_GENERIC, "the port (power out)"}};
static const mdl_port_def twoport[] = {
    {"a", 0, MDL_GENERIC, "port 0 (power in): e0, f0"},
    {"b", 0, MDL_GENERIC, "port 1 (power out): e1, f1"},
};
static const mdl_port_def twoport1[] = {
    {"a", 1, MDL_GENERIC, "port 0 (power in): e0, f0"},
    {"b", 1, MDL_GENERIC, "port 1 (power out): e1, f1"},
};

/* ---- I, C, R ---- */

static const mdl_param_def I_params[] = {
    DIM(16),
    {"mass", MDL_NUMBER, 0, "-", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "the inertance m (kg, kg m^2, ...: what the domain makes it)"},
};
static const mdl_signal_def I_signals[] = {
    {"p", "-", "the momentum p (a state; its first component when dim > 1)"}};

static int I_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a, mdl_instance *out,
                   bg_error *err)
{
    int d = mdl_arg_int(a, "dim");
    int id = bgr_I(m, c, name, d, mdl_arg_num(a, "mass"));
    int r = single(m, id, out, name_p, 1, d, err);
    if (r == BG_OK) r = mdl_instance_signal(out, "p", (bgr_ref){BGR_STATE, id, 0});
    return r;
}

static const mdl_type I_type = {
    "bg.I", "inertia: the I element (bgr_elements.h)",
    "p' = e        (state p, d components)\n"
    "m f_in = p",
    I_params, COUNT(I_params), oneport_in, COUNT(oneport_in), I_signals, COUNT(I_signals), 0,
    I_build, NULL, NULL};

static const mdl_param_def C_params[] = {
    DIM(16),
    {"stiffness", MDL_NUMBER, 0, "-", NULL, 0, INF, 0, NULL,
     "the stiffness k, the inverse of the capacitance (N/m, Pa/m^3, ...)"},
};
static const mdl_signal_def C_signals[] = {
    {"q", "-", "the displacement q (a state; its first component when dim > 1)"}};

static int C_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a, mdl_instance *out,
                   bg_error *err)
{
    int d = mdl_arg_int(a, "dim");
    int id = bgr_C(m, c, name, d, mdl_arg_num(a, "stiffness"));
    int r = single(m, id, out, name_p, 1, d, err);
    if (r == BG_OK) r = mdl_instance_signal(out, "q", (bgr_ref){BGR_STATE, id, 0});
    return r;
}

static const mdl_type C_type = {
    "bg.C", "capacitance: the C element (bgr_elements.h)",
    "q' = f_in     (state q, d components)\n"
    "e = k q",
    C_params, COUNT(C_params), oneport_in, COUNT(oneport_in), C_signals, COUNT(C_signals), 0,
    C_build, NULL, NULL};

static const mdl_param_def R_params[] = {
    DIM(INF),
    {"resistance", MDL_NUMBER, 0, "-", NULL, 0, INF, 0, NULL,
     "the resistance r (N s/m, Pa s/m^3, ...)"},
};

static int R_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a, mdl_instance *out,
                   bg_error *err)
{
    int d = mdl_arg_int(a, "dim");
    return single(m, bgr_R(m, c, name, d, mdl_arg_num(a, "resistance")), out, name_p, 1, d, err);
}

static const mdl_type R_type = {
    "bg.R", "resistance: the R element (bgr_elements.h)", "e = r f_in  (dissipates r f.f)",
    R_params, COUNT(R_params), oneport_in, COUNT(oneport_in), NULL, 0, 0, R_build, NULL, NULL};

/* ---- sources ---- */

static const mdl_param_def S_params[] = {
    DIM(INF),
    {"value", MDL_VECTOR, 0, "-", NULL, -INF, INF, MDL_OPTIONAL | MDL_FINITE, NULL,
     "the d values it imposes (left out: zeros)"},
};

static int S_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a, mdl_instance *out,
                   bg_error *err, int effort)
{
    int d = mdl_arg_int(a, "dim"), n;
    const double *v = mdl_arg_vec(a, "value", &n);
    if (v && n != d)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "model", "value: %d numbers, expected dim = %d",
                              n, d);
    int id = effort ? bgr_Se(m, c, name, d, v) : bgr_Sf(m, c, name, d, v);
    return single(m, id, out, name_p, 1, d, err);
}

static int Se_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                    mdl_instance *out, bg_error *err)
{
    return S_build(m, c, name, a, out, err, 1);
}

/* the start: what the source imposes at its value at t = 0 (mdl_place_source) */
static int Se_place(bgr_model *m, const mdl_instance *in, const mdl_args *a, mdl_locator *loc,
                    bg_error *err)
{
    (void)a, (void)loc;
    return mdl_place_source(m, mdl_instance_main(in), MDL_SRC_EFFORT, NULL, err);
}
static int Sf_place(bgr_model *m, const mdl_instance *in, const mdl_args *a, mdl_locator *loc,
                    bg_error *err)
{
    (void)a, (void)loc;
    return mdl_place_source(m, mdl_instance_main(in), MDL_SRC_FLOW, NULL, err);
}
static int Se_signal_place(bgr_model *m, const mdl_instance *in, const mdl_args *a,
                           mdl_locator *loc, bg_error *err)
{
    (void)loc;
    bgr_ref r = mdl_arg_signal(a, "signal");
    return mdl_place_source(m, mdl_instance_main(in), MDL_SRC_EFFORT, &r, err);
}
static int Sf_signal_place(bgr_model *m, const mdl_instance *in, const mdl_args *a,
                           mdl_locator *loc, bg_error *err)
{
    (void)loc;
    bgr_ref r = mdl_arg_signal(a, "signal");
    return mdl_place_source(m, mdl_instance_main(in), MDL_SRC_FLOW, &r, err);
}

static int Sf_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                    mdl_instance *out, bg_error *err)
{
    return S_build(m, c, name, a, out, err, 0);
}

static const mdl_type Se_type = {
    "bg.Se", "constant effort source (bgr_elements.h)",
    "e = E  (E: value; zeros make a free end of what it is bonded to)", S_params, COUNT(S_params),
    oneport_out, COUNT(oneport_out), NULL, 0, 0, Se_build, Se_place, NULL};

static const mdl_type Sf_type = {
    "bg.Sf", "constant flow source (bgr_elements.h)",
    "f_out = F  (F: value; zeros make the effort a constraint effort)", S_params, COUNT(S_params),
    oneport_out, COUNT(oneport_out), NULL, 0, 0, Sf_build, Sf_place, NULL};

static const mdl_param_def Ssig_params[] = {
    {"signal", MDL_SIGNAL, 0, "-", NULL, 0, 0, 0, NULL, "the signal that gives the value"},
};

static int Se_signal_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                           mdl_instance *out, bg_error *err)
{
    return single(m, bgr_Se_signal(m, c, name, mdl_arg_signal(a, "signal")), out, name_p, 1, 1,
                  err);
}

static int Sf_signal_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                           mdl_instance *out, bg_error *err)
{
    return single(m, bgr_Sf_signal(m, c, name, mdl_arg_signal(a, "signal")), out, name_p, 1, 1,
                  err);
}

static const mdl_type Se_signal_type = {
    "bg.Se_signal", "effort source following a signal (bgr_elements.h)", "e = x  (x: signal)",
    Ssig_params, COUNT(Ssig_params), oneport1_out, COUNT(oneport1_out), NULL, 0, 0, Se_signal_build,
    Se_signal_place, NULL};

static const mdl_type Sf_signal_type = {
    "bg.Sf_signal", "flow source following a signal (bgr_elements.h)", "f_out = x  (x: signal)",
    Ssig_params, COUNT(Ssig_params), oneport1_out, COUNT(oneport1_out), NULL, 0, 0, Sf_signal_build,
    Sf_signal_place, NULL};

/* ---- TF, GY ---- */

static const mdl_param_def TF_params[] = {
    DIM(INF),
    {"modulus", MDL_NUMBER, 0, "-", NULL, -INF, INF, MDL_FINITE, NULL, "the modulus m, != 0"},
};

static int modulus(const mdl_args *a, double *mod, bg_error *err)
{
    *mod = mdl_arg_num(a, "modulus");
    if (*mod == 0)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "model", "modulus: 0, expected a number != 0");
    return BG_OK;
}

static int TF_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                    mdl_instance *out, bg_error *err)
{
    double mod;
    int d = mdl_arg_int(a, "dim"), r = modulus(a, &mod, err);
    return r != BG_OK ? r : single(m, bgr_TF(m, c, name, d, mod), out, names_ab, 2, d, err);
}

static int GY_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                    mdl_instance *out, bg_error *err)
{
    double mod;
    int d = mdl_arg_int(a, "dim"), r = modulus(a, &mod, err);
    return r != BG_OK ? r : single(m, bgr_GY(m, c, name, d, mod), out, names_ab, 2, d, err);
}

static const mdl_type TF_type = {
    "bg.TF", "transformer (bgr_elements.h)",
    "e0 = m e1\n"
    "f1_out = m f0_in     (power conserved)",
    TF_params, COUNT(TF_params), twoport, COUNT(twoport), NULL, 0, 0, TF_build, NULL, NULL};

static const mdl_type GY_type = {
    "bg.GY", "gyrator (bgr_elements.h)",
    "e0 = r f1_out\n"
    "e1 = r f0_in         (r: modulus; power conserved)",
    TF_params, COUNT(TF_params), twoport, COUNT(twoport), NULL, 0, 0, GY_build, NULL, NULL};

static const mdl_param_def TFsig_params[] = {
    {"modulus", MDL_SIGNAL, 0, "-", NULL, 0, 0, 0, NULL, "the signal that gives the modulus m"},
};

static int TF_signal_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                           mdl_instance *out, bg_error *err)
{
    int id = bgr_TF_signal(m, c, name, mdl_arg_signal(a, "modulus"));
    return single(m, id, out, names_ab, 2, 1, err);
}

static const mdl_type TF_signal_type = {
    "bg.TF_signal", "transformer with a signal modulus (bgr_elements.h)",
    "e0 = m e1\n"
    "f1_out = m f0_in     (m: the signal `modulus`)",
    TFsig_params, COUNT(TFsig_params), twoport1, COUNT(twoport1), NULL, 0, 0, TF_signal_build, NULL,
    NULL};

/* ---- junctions ---- */

static const mdl_param_def J_params[] = {
    DIM(INF),
    {"ports", MDL_NAMES, 0, "-", NULL, 0, 0, 0, NULL, "the names of its ports, two or more"},
};
static const mdl_port_def J_ports[] = {
    {"*", 0, MDL_GENERIC, "one per name of `ports` (either orientation)"}};

static int J_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                   mdl_instance *out, bg_error *err, int one)
{
    int n, d = mdl_arg_int(a, "dim");
    const char *const *names = mdl_arg_names(a, "ports", &n);
    if (n < 2)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                              "ports: %d name, a junction needs two or more", n);
    int id = one ? bgr_one(m, c, name, n, d) : bgr_zero(m, c, name, n, d);
    return single(m, id, out, names, n, d, err);
}

static int zero_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                      mdl_instance *out, bg_error *err)
{
    return J_build(m, c, name, a, out, err, 0);
}

static int one_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                     mdl_instance *out, bg_error *err)
{
    return J_build(m, c, name, a, out, err, 1);
}

static const mdl_type zero_type = {
    "bg.zero", "0-junction: common effort (bgr_elements.h)",
    "e_k = e_0  (k > 0)\n"
    "sum_k s_k f_k = 0   (s_k = +1 for a bond ending here, -1 otherwise)",
    J_params, COUNT(J_params), J_ports, COUNT(J_ports), NULL, 0, 0, zero_build, NULL, NULL};

static const mdl_type one_type = {
    "bg.one", "1-junction: common flow (bgr_elements.h)",
    "f_k = f_0  (k > 0)\n"
    "sum_k s_k e_k = 0   (s_k = +1 for a bond ending here, -1 otherwise)",
    J_params, COUNT(J_params), J_ports, COUNT(J_ports), NULL, 0, 0, one_build, NULL, NULL};

const mdl_type *const mdl_types_bg[] = {
    &I_type,  &C_type,         &R_type,         &Se_type, &Sf_type, &Se_signal_type,
    &Sf_signal_type, &TF_type, &GY_type, &TF_signal_type, &zero_type, &one_type,
};
const int mdl_types_bg_count = COUNT(mdl_types_bg);
