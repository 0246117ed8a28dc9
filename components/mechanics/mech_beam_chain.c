/* The chain builder of the co-rotational beam (declared in mech_beam_chain.h): a straight chain
 * of n elements (mech_beam.c), of equal lengths or between given stations (graded), between
 * n + 1 node bodies (mech_body) that carry the lumped mass, half of each element's mass
 * rho A l and the rotary inertia of its section rho I l at either end. The chain's elements
 * share one AD scratch (mech_beam_impl.h). */
#include "mech_beam_chain.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "mech_beam_impl.h"
#include "mech_body.h"
#include "mech_util.h"

static int frame(const double *p0, const double *p1, const double *up, double *E0, double *L)
{
    double d[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
    *L = sqrt(mech_dot(d, d));
    if (!(*L > 0) || !up) return 0;
    for (int i = 0; i < 3; i++)
        E0[i] = d[i] / *L;
    double pu = mech_dot(up, E0), w[3];
    for (int i = 0; i < 3; i++)
        w[i] = up[i] - pu * E0[i];
    double nw = sqrt(mech_dot(w, w));
    if (!(nw > 1e-12 * sqrt(mech_dot(up, up)))) return 0;
    for (int i = 0; i < 3; i++)
        E0[3 + i] = w[i] / nw;
    mech_cross(E0, E0 + 3, E0 + 6);
    return 1;
}

static int node_ports(int k, int n, const int *extra, const int *extra3)
{
    return (k > 0) + (k < n) + (extra ? extra[k] : 0) + (extra3 ? extra3[k] : 0);
}

/* The lumped mass and the global inertia tensor J (exactly symmetric) of a chain node that
 * stands for the length l of rod with the local frame E0. */
static double node_inertia(const mech_section *sec, const double *E0, double l, double *J)
{
    /* rotary inertia of the section over that length, local frame: torsion (polar), then
     * bending; the rod's own length-wise distribution of mass is carried by the neighbouring
     * nodes' translation (adding rho A l^3/12 here too lowered the third bending frequency
     * of a 20-element cantilever by 1.4 %, to 0.6 % without it) */
    double Jl[3] = {sec->rho * (sec->Iy + sec->Iz) * l, sec->rho * sec->Iy * l,
                    sec->rho * sec->Iz * l};
    for (int i = 0; i < 3; i++) /* E0 diag(Jl) E0^T */
        for (int j = 0; j < 3; j++) {
            double sum = 0;
            for (int a = 0; a < 3; a++)
                sum += E0[i + 3 * a] * Jl[a] * E0[j + 3 * a];
            J[i + 3 * j] = sum;
        }
    for (int i = 0; i < 3; i++) /* exact symmetry for the body's check */
        for (int j = i + 1; j < 3; j++)
            J[j + 3 * i] = J[i + 3 * j];
    double mass = sec->rho * sec->A * l;
    return mass > 0 ? mass : 1e-12;
}

/* The length of element k of a chain of length L. */
static double element_length(const double *xi, int k, int n, double L)
{
    return xi ? (xi[k + 1] - xi[k]) * L : L / n;
}

/* The length of rod node k stands for: half of each adjacent element. */
static double node_length(const double *xi, int k, int n, double L)
{
    double a = k > 0 ? element_length(xi, k - 1, n, L) : 0.0;
    double b = k < n ? element_length(xi, k, n, L) : 0.0;
    return 0.5 * (a + b);
}

/* The stations of a graded chain: n + 1 finite numbers rising strictly from 0 to 1. */
static int bad_stations(bgr_model *m, bgr_comp c, const char *name, const char *w, int n,
                        const double *xi)
{
    if (!xi) return bgr_refuse(m, c, name, w, "the stations xi are NULL");
    if (bgr_check_values(m, c, name, w, "xi", xi, n + 1, BGR_FINITE)) return 1;
    if (xi[0] != 0.0 || xi[n] != 1.0)
        return bgr_refuse(m, c, name, w, "xi[0] = %g, xi[%d] = %g: expected 0 and 1 (the ends)",
                          xi[0], n, xi[n]);
    for (int k = 0; k < n; k++)
        if (!(xi[k + 1] > xi[k]))
            return bgr_refuse(m, c, name, w,
                              "xi[%d] = %g, xi[%d] = %g: expected strictly increasing stations", k,
                              xi[k], k + 1, xi[k + 1]);
    return 0;
}

static int chain(bgr_model *m, bgr_comp c, const char *name, const char *w, int n, const double *xi,
                 const double *p0, const double *p1, const double *up, const mech_section *sec,
                 const double *gravity, const int *extra, const int *extra3, int *nodes, int *elems)
{
    bg_error *err = bgr_model_error_mut(m);
    /* everything is checked before the component is made: a refused chain leaves nothing */
    if (mech_beam_bad_section_(m, c, name, w, sec)) return BG_ERR_ARGUMENT;
    if (!(sec->rho > 0))
        return bgr_refuse(m, c, name, w,
                          "section.rho = %g, expected a finite number > 0 (the chain lumps the "
                          "mass rho A l and the rotary inertia rho I l into its nodes)",
                          sec->rho);
    if (n < 1) return bgr_refuse(m, c, name, w, "n = %d, expected at least 1 element", n);
    if (!p0 || !p1) return bgr_refuse(m, c, name, w, "the end point %s is NULL", p0 ? "p1" : "p0");
    if (!up) return bgr_refuse(m, c, name, w, "the up vector is NULL");
    if (bgr_check_values(m, c, name, w, "p0", p0, 3, BGR_FINITE) ||
        bgr_check_values(m, c, name, w, "p1", p1, 3, BGR_FINITE) ||
        bgr_check_values(m, c, name, w, "up", up, 3, BGR_FINITE) ||
        bgr_check_values(m, c, name, w, "gravity", gravity, 3, BGR_FINITE))
        return BG_ERR_ARGUMENT;
    double E0[9], L;
    if (!frame(p0, p1, up, E0, &L) || !isfinite(L))
        return bgr_refuse(m, c, name, w,
                          "p0 = (%g, %g, %g), p1 = (%g, %g, %g), up = (%g, %g, %g): expected two "
                          "distinct end points at a finite distance and an up vector not along "
                          "the beam",
                          p0[0], p0[1], p0[2], p1[0], p1[1], p1[2], up[0], up[1], up[2]);
    if (!nodes || !elems)
        return bgr_refuse(m, c, name, w, "the arrays for the node and element ids are NULL");
    for (int k = 0; k <= n; k++) {
        if ((extra && extra[k] < 0) || (extra3 && extra3[k] < 0))
            return bgr_refuse(m, c, name, w, "node %d has a negative number of extra ports (%d)", k,
                              extra && extra[k] < 0 ? extra[k] : extra3[k]);
        int np = node_ports(k, n, extra, extra3);
        if (np > MECH_MAXPORTS)
            return bgr_refuse(m, c, name, w, "node %d has %d ports, expected at most %d", k, np,
                              MECH_MAXPORTS);
    }
    for (int k = 0; k < n; k++)
        if (mech_beam_bad_stiffness_(m, c, name, w, sec, element_length(xi, k, n, L)))
            return BG_ERR_ARGUMENT;
    for (int k = 0; k <= n; k++) { /* the lumped inertias of the nodes */
        double J[9], l = node_length(xi, k, n, L);
        double mass = node_inertia(sec, E0, l, J);
        if (!isfinite(mass) || bgr_check_spd(m, c, name, w, "the lumped inertia of a node", J, 3))
            return bgr_refuse(m, c, name, w,
                              "a node standing for l = %g m of rod gets the mass %g and the "
                              "inertia diag(%g, %g, %g): expected finite section properties "
                              "that make them finite and > 0",
                              l, mass, sec->rho * (sec->Iy + sec->Iz) * l, sec->rho * sec->Iy * l,
                              sec->rho * sec->Iz * l);
    }
    bgr_comp cc = bgr_component(m, c, name);
    if (cc < 0) return cc;
    for (int k = 0; k <= n; k++) {
        double l = node_length(xi, k, n, L); /* length of rod the node stands for */
        double J[9], mass = node_inertia(sec, E0, l, J);
        int np = node_ports(k, n, extra, extra3);
        double *r = calloc((size_t)3 * np + 3, sizeof *r);
        int *dims = malloc(((size_t)np + 1) * sizeof *dims);
        if (!r || !dims) {
            free(r);
            free(dims);
            return bg_error_raise(err, BG_ERR_MEMORY, "mech_beam_chain", "out of memory");
        }
        for (int j = 0; j < np; j++)
            dims[j] = j < np - (extra3 ? extra3[k] : 0) ? 6 : 3;
        char nm[32];
        snprintf(nm, sizeof nm, "node%02d", k);
        nodes[k] = mech_body(m, cc, nm, mass, J, gravity, np, r, dims);
        free(r);
        free(dims);
        if (nodes[k] < 0) return nodes[k];
    }
    /* one scratch for the chain, held here until its elements have taken their references */
    beam_work *shared = mech_beam_work_new_();
    if (!shared) return bg_error_raise(err, BG_ERR_MEMORY, "mech_beam_chain", "out of memory");
    for (int k = 0; k < n; k++) {
        char nm[32];
        snprintf(nm, sizeof nm, "el%02d", k);
        double Le = element_length(xi, k, n, L);
        elems[k] = mech_beam_add_(m, cc, nm, nodes[k], nodes[k + 1], sec, E0, Le, shared, gravity);
        if (elems[k] < 0) {
            mech_beam_work_release_(shared);
            return elems[k];
        }
        /* the weight of the whole chain, rho A L |g|, as the elements' force scale: what a chain
         * supported at one end carries there (mech_set_nominal may state more, e.g. a load) */
        double W = sec->rho * sec->A * L * (gravity ? sqrt(mech_dot(gravity, gravity)) : 0.0);
        if (W > 0 && isfinite(W)) mech_beam_scales_(bgr_element_get(m, elems[k]))->force = W;
        int pa = k > 0 ? 1 : 0; /* node k: next port; node k+1: prev port (0) */
        snprintf(nm, sizeof nm, "ba%02d", k);
        int st = bgr_bond(m, cc, nm, 6, bgr_port_of(m, nodes[k], pa), bgr_port_of(m, elems[k], 0),
                          NULL, NULL);
        if (st < 0) {
            mech_beam_work_release_(shared);
            return st;
        }
        snprintf(nm, sizeof nm, "bb%02d", k);
        st = bgr_bond(m, cc, nm, 6, bgr_port_of(m, nodes[k + 1], 0), bgr_port_of(m, elems[k], 1),
                      NULL, NULL);
        if (st < 0) {
            mech_beam_work_release_(shared);
            return st;
        }
    }
    mech_beam_work_release_(shared);
    return cc;
}

int mech_beam_chain(bgr_model *m, bgr_comp c, const char *name, int n, const double *p0,
                    const double *p1, const double *up, const mech_section *sec,
                    const double *gravity, const int *extra, const int *extra3, int *nodes,
                    int *elems)
{
    return chain(m, c, name, "mech_beam_chain", n, NULL, p0, p1, up, sec, gravity, extra, extra3,
                 nodes, elems);
}

int mech_beam_chain_at(bgr_model *m, bgr_comp c, const char *name, int n, const double *xi,
                       const double *p0, const double *p1, const double *up,
                       const mech_section *sec, const double *gravity, const int *extra,
                       const int *extra3, int *nodes, int *elems)
{
    const char *w = "mech_beam_chain_at";
    if (n >= 1 && bad_stations(m, c, name, w, n, xi)) return BG_ERR_ARGUMENT;
    return chain(m, c, name, w, n, xi, p0, p1, up, sec, gravity, extra, extra3, nodes, elems);
}

bgr_port mech_beam_chain_port(const bgr_model *m, const int *nodes, int n, const int *extra, int k,
                              int j)
{
    bgr_port none = {-1, -1};
    (void)extra;
    if (!m || !nodes || k < 0 || k > n || j < 0) return none;
    return bgr_port_of(m, nodes[k], (k > 0) + (k < n) + j); /* 6D extras, then 3D ones */
}

static int chain_set(bgr_model *m, const char *w, const int *nodes, int n, const double *xi,
                     const double *p0, const double *p1)
{
    if (!nodes || n < 1 || !p0 || !p1)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, w,
                              "needs the node ids, n >= 1 and both end points");
    for (int k = 0; k <= n; k++) {
        double x[3];
        for (int i = 0; i < 3; i++)
            x[i] = xi ? p0[i] + (p1[i] - p0[i]) * xi[k] : p0[i] + (p1[i] - p0[i]) * k / n;
        int st = mech_body_set(m, nodes[k], x, NULL, NULL, NULL);
        if (st != BG_OK) return st;
    }
    return BG_OK;
}

int mech_beam_chain_set(bgr_model *m, const int *nodes, int n, const double *p0, const double *p1)
{
    return chain_set(m, "mech_beam_chain_set", nodes, n, NULL, p0, p1);
}

int mech_beam_chain_set_at(bgr_model *m, const int *nodes, int n, const double *xi,
                           const double *p0, const double *p1)
{
    if (!xi)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "mech_beam_chain_set_at",
                              "the stations xi are NULL");
    return chain_set(m, "mech_beam_chain_set_at", nodes, n, xi, p0, p1);
}
