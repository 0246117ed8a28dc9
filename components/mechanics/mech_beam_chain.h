/* Chains of co-rotational beam elements (mech_beam.h) with lumped node bodies.
 *
 * A straight chain from p0 to p1 is cut into n elements of length l = L/n (or graded:
 * mech_beam_chain_at) between n + 1 rigid
 * node bodies (mech_body). The mass is lumped into the nodes: half of each element's mass
 * rho A l to each end node, with the rotary inertia of the section over that length (rho I l;
 * rho Ip l in torsion), so an inner node stands for the length l and an end node for l/2.
 * With section.element = MECH_BEAM_CONSISTENT or MECH_BEAM_QUARTIC the elements add the rest of the
 * consistent mass (mech_beam.h: their distributed mass less these point masses) and the chain's
 * gravity as distributed weight; the default lumped masses need no coupling terms between the nodes
 * but converge at second order only. The elements of a chain state the chain's weight rho A L |g|
 * as the nominal magnitude of their port forces (mech_body.h, mech_set_nominal). */
#ifndef MECH_BEAM_CHAIN_H
#define MECH_BEAM_CHAIN_H

#include "bg_api.h"
#include "bgr_model.h"
#include "mech_beam.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A straight chain of n elements from p0 to p1 in component c (created here with the given
 * name): n + 1 node bodies named node00, node01, ... with lumped masses (gravity may be NULL),
 * elements el00, el01, ..., bonded together. up: a vector not parallel to the beam giving the
 * local e2 direction. Node k gets extra[k] additional 6D ports, then extra3[k] 3D (force only)
 * ports, at its centre (NULL: none) for the caller to bond (supports, loads, dampers, ties,
 * ropes); their handles come from mech_beam_chain_port. nodes (n+1) and elems (n) receive the
 * element ids. Returns the chain's component, or BG_ERR_ARGUMENT (a bad section or one with
 * rho = 0, n < 1, NULL, non-finite or coincident end points, up NULL, not finite or along the
 * beam, gravity not finite, nodes or elems NULL, a negative extra count or more than 64 ports at
 * a node, lumped node masses or inertias that are not finite and > 0), or the status of the
 * component, element or bond that failed. The arguments are all checked before the component is
 * made: a refused chain leaves nothing in the model (the message names the chain's path and the
 * parameter). */
BG_API int mech_beam_chain(bgr_model *m, bgr_comp c, const char *name, int n, const double *p0,
                           const double *p1, const double *up, const mech_section *sec,
                           const double *gravity, const int *extra, const int *extra3, int *nodes,
                           int *elems);
/* A graded chain: as mech_beam_chain, with node k at the station xi[k] along the chain
 * (p0 + xi[k] (p1 - p0)); xi holds n + 1 finite stations rising strictly from xi[0] = 0 to
 * xi[n] = 1. Element k has the length l_k = (xi[k+1] - xi[k]) L, and node k stands for the
 * length (l_{k-1} + l_k) / 2 (half of each adjacent element, as in the uniform chain, which is
 * the case xi[k] = k / n). Shorter elements where the field varies fast (a clamped root's
 * boundary layer in a spinning beam, docs/beam.md) buy accuracy there. The same returns as
 * mech_beam_chain, and BG_ERR_ARGUMENT for stations that are NULL, not finite, not rising
 * strictly or not 0 and 1 at the ends (the message names the station). */
BG_API int mech_beam_chain_at(bgr_model *m, bgr_comp c, const char *name, int n, const double *xi,
                              const double *p0, const double *p1, const double *up,
                              const mech_section *sec, const double *gravity, const int *extra,
                              const int *extra3, int *nodes, int *elems);
/* The j-th extra port of node k (the 6D ones first, then the 3D ones); {-1, -1} if there is no
 * such port (or m, nodes NULL). */
BG_API bgr_port mech_beam_chain_port(const bgr_model *m, const int *nodes, int n, const int *extra,
                                     int k, int j);
/* Positions of the chain's nodes into bgr_y0 (after bgr_compile), orientation identity. BG_OK,
 * or BG_ERR_ARGUMENT (NULL arrays, n < 1, a node that is not a body of a compiled model). */
BG_API int mech_beam_chain_set(bgr_model *m, const int *nodes, int n, const double *p0,
                               const double *p1);
/* The same for a graded chain (mech_beam_chain_at): node k at p0 + xi[k] (p1 - p0). BG_OK, or
 * BG_ERR_ARGUMENT as mech_beam_chain_set and for xi NULL. */
BG_API int mech_beam_chain_set_at(bgr_model *m, const int *nodes, int n, const double *xi,
                                  const double *p0, const double *p1);

#ifdef __cplusplus
}
#endif
#endif
