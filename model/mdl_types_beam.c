/* Model-file type of the beam chain (mech_beam_chain.h): a straight chain of co-rotational beam
 * elements (mech_beam.h) between lumped node bodies, with named ports at its nodes. */
#include <math.h>
#include <string.h>

#include "mdl_impl.h"
#include "mech_beam_chain.h"
#include "mech_body.h"

#define INF HUGE_VAL
#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))
#define MAX_ELEMENTS 4096

static const mdl_param_def chain_params[] = {
    {"elements", MDL_INTEGER, 0, "1", NULL, 1, MAX_ELEMENTS, 0, NULL, "number of beam elements n"},
    {"start", MDL_VECTOR, 3, "m", NULL, -INF, INF, MDL_FINITE, NULL, "the first node (node 0)"},
    {"end", MDL_VECTOR, 3, "m", NULL, -INF, INF, MDL_FINITE, NULL, "the last node (node n)"},
    {"up", MDL_VECTOR, 3, "1", "[0, 0, 1]", -INF, INF, MDL_FINITE, NULL,
     "a direction not along the beam: the sections' local e2 axis"},
    {"E", MDL_NUMBER, 0, "Pa", NULL, 0, INF, MDL_LO_OPEN, NULL, "Young's modulus"},
    {"G", MDL_NUMBER, 0, "Pa", NULL, 0, INF, MDL_LO_OPEN, NULL, "shear modulus"},
    {"A", MDL_NUMBER, 0, "m^2", NULL, 0, INF, MDL_LO_OPEN, NULL, "cross-section area"},
    {"Iy", MDL_NUMBER, 0, "m^4", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "second moment of area about the local y (e2) axis"},
    {"Iz", MDL_NUMBER, 0, "m^4", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "second moment of area about the local z (e3) axis"},
    {"J", MDL_NUMBER, 0, "m^4", NULL, 0, INF, MDL_LO_OPEN, NULL, "torsion constant"},
    {"rho", MDL_NUMBER, 0, "kg/m^3", NULL, 0, INF, MDL_LO_OPEN, NULL,
     "density (the masses lumped into the nodes)"},
    {"element", MDL_CHOICE, 0, "-", "lumped", 0, 0, 0, "lumped|consistent|quartic",
     "the beam element: lumped (masses in the nodes, second order in 1/n), consistent (the "
     "elements' distributed inertia with a higher-order bending mass, rotation angles and "
     "bowing: a cantilever's bending frequencies of eighth order, statics of fourth) or quartic "
     "(the consistent element's field with a bubble per bending plane, four states of the "
     "element: accurate at eight elements spinning too; mech_beam.h)"},
    {"kappa", MDL_NUMBER, 0, "1", "0", 0, INF, 0, NULL,
     "shear correction factor: 0 Euler-Bernoulli, > 0 Timoshenko"},
    {"beta", MDL_NUMBER, 0, "s", "0", 0, INF, 0, NULL,
     "stiffness-proportional damping (modal damping ratio beta omega / 2)"},
    {"gravity", MDL_VECTOR, 3, "m/s^2", "[0, 0, 0]", -INF, INF, MDL_FINITE, NULL,
     "acceleration of gravity (global)"},
    {"ports", MDL_NODE_PORTS, 0, "-", NULL, 0, 0, 0, NULL,
     "its ports: name: {node: k (0 .. n), dim: 6 or 3}, each at the node's centre"},
    {"end_mass", MDL_NUMBER, 0, "kg", "0", 0, INF, 0, NULL,
     "a point mass added to the last node (a member's lumped share there)"},
    {"nominal_force", MDL_NUMBER, 0, "N", "0", 0, INF, 0, NULL,
     "force scale of the elements' port forces for the error test (0: the chain's weight)"},
};
static const mdl_port_def chain_ports[] = {
    {"*", 0, MDL_MECH6, "one per entry of ports (mechanical 6D, or 3D where it says dim: 3)"}};

/* the element kind of the choice "element" */
static int element_kind(const char *choice)
{
    return !strcmp(choice, "consistent") ? MECH_BEAM_CONSISTENT
           : !strcmp(choice, "quartic")  ? MECH_BEAM_QUARTIC
                                         : MECH_BEAM_LUMPED;
}

static int chain_build(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a,
                       mdl_instance *out, bg_error *err)
{
    int n = mdl_arg_int(a, "elements"), np = mdl_arg_npoints(a, "ports");
    int extra[MAX_ELEMENTS + 1], extra3[MAX_ELEMENTS + 1], nodes[MAX_ELEMENTS + 1],
        elems[MAX_ELEMENTS];
    memset(extra, 0, (size_t)(n + 1) * sizeof *extra);
    memset(extra3, 0, (size_t)(n + 1) * sizeof *extra3);
    for (int i = 0; i < np; i++) {
        double r[3];
        int dim;
        const char *pn = mdl_arg_point(a, "ports", i, r, &dim);
        int k = (int)r[0];
        if (k > n)
            return bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                                  "ports.%s: node %d, the chain has nodes 0 .. %d", pn, k, n);
        if (dim == 6) extra[k]++;
        else extra3[k]++;
    }
    mech_section sec = {mdl_arg_num(a, "E"),  mdl_arg_num(a, "G"),   mdl_arg_num(a, "A"),
                        mdl_arg_num(a, "Iy"), mdl_arg_num(a, "Iz"),  mdl_arg_num(a, "J"),
                        mdl_arg_num(a, "rho"), mdl_arg_num(a, "kappa"), mdl_arg_num(a, "beta"),
                        element_kind(mdl_arg_choice(a, "element"))};
    int comp = mech_beam_chain(m, c, name, n, mdl_arg_vec(a, "start", NULL), mdl_arg_vec(a, "end", NULL),
                               mdl_arg_vec(a, "up", NULL), &sec, mdl_arg_vec(a, "gravity", NULL), extra,
                               extra3, nodes, elems);
    if (comp < 0) return mdl_fail_model(err, m, comp);
    int rc = mdl_instance_element(out, nodes[0]);
    for (int k = 1; rc == BG_OK && k <= n; k++)
        rc = mdl_instance_add(out, nodes[k]);
    for (int k = 0; rc == BG_OK && k < n; k++)
        rc = mdl_instance_add(out, elems[k]);
    /* the ports in the order given: at node k the 6D ones first, then the 3D ones */
    int used6[MAX_ELEMENTS + 1], used3[MAX_ELEMENTS + 1];
    memset(used6, 0, (size_t)(n + 1) * sizeof *used6);
    memset(used3, 0, (size_t)(n + 1) * sizeof *used3);
    for (int i = 0; rc == BG_OK && i < np; i++) {
        double r[3];
        int dim;
        const char *pn = mdl_arg_point(a, "ports", i, r, &dim);
        int k = (int)r[0], j = dim == 6 ? used6[k]++ : extra[k] + used3[k]++;
        rc = mdl_instance_port(out, pn, mech_beam_chain_port(m, nodes, n, extra, k, j), dim,
                               dim == 6 ? MDL_MECH6 : MDL_MECH3);
    }
    double dm = mdl_arg_num(a, "end_mass"), f = mdl_arg_num(a, "nominal_force");
    if (rc == BG_OK && dm > 0 && (rc = mech_body_add_mass(m, nodes[n], dm)) != BG_OK)
        return mdl_fail_model(err, m, rc);
    for (int k = 0; rc == BG_OK && f > 0 && k < n; k++)
        if ((rc = mech_set_nominal(m, elems[k], f, 0, 0)) != BG_OK) return mdl_fail_model(err, m, rc);
    return rc;
}

static int chain_place(bgr_model *m, const mdl_instance *in, const mdl_args *a, mdl_locator *loc,
                       bg_error *err)
{
    (void)loc;
    int n = mdl_arg_int(a, "elements"), nodes[MAX_ELEMENTS + 1];
    for (int k = 0; k <= n; k++)
        nodes[k] = mdl_instance_elem(in, k);
    int r = mech_beam_chain_set(m, nodes, n, mdl_arg_vec(a, "start", NULL), mdl_arg_vec(a, "end", NULL));
    return r == BG_OK ? r : mdl_fail_model(err, m, r);
}

static int chain_port_position(const bgr_model *m, const mdl_instance *in, int port, const double *y,
                               double x[3])
{
    double r[3];
    if (!mdl_arg_point(&in->args, "ports", port, r, NULL)) return BG_ERR_ARGUMENT;
    int ix = mech_body_var(m, mdl_instance_elem(in, (int)r[0]), 'x');
    if (ix < 0) return BG_ERR_ARGUMENT;
    memcpy(x, y + ix, 3 * sizeof *x);
    return BG_OK;
}

static const mdl_type chain_type = {
    "mech.beam_chain",
    "straight chain of co-rotational beam elements between lumped node bodies (mech_beam_chain.h)",
    "n + 1 node bodies (mech.body, lumped masses: half of rho A l of each element at its ends)\n"
    "  (element: consistent: each element adds its distributed inertia less those masses)\n"
    "n co-rotational beam elements between them (mech_beam.h: the element's local deformations\n"
    "  from its end nodes' positions and rotations, the linear Euler-Bernoulli or Timoshenko\n"
    "  stiffness in the co-rotated frame, stiffness-proportional damping beta)\n"
    "its ports at the nodes' centres",
    chain_params, COUNT(chain_params), chain_ports, COUNT(chain_ports), NULL, 0, 0, chain_build,
    chain_place, chain_port_position};

const mdl_type *const mdl_types_beam[] = {&chain_type};
const int mdl_types_beam_count = COUNT(mdl_types_beam);
