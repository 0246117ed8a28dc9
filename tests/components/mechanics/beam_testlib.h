/* What the beam elements' tests share (test_beam_consistent.c, test_beam_quartic.c): the
 * clamped cantilever they build, the closed form of its bending frequencies, and the energy of
 * a chain. */
#ifndef BEAM_TESTLIB_H
#define BEAM_TESTLIB_H

#include "bgr_model.h"
#include "mech_beam.h"

/* A cantilever of n (<= 64) elements of the given kind along x from the origin to (L, 0, 0),
 * clamped at node 0, gravity g (NULL: none), a dead load (Px, 0, -P) at the tip; compiled and
 * set straight; NULL (with a TAP comment) if it does not compile. */
bgr_model *bt_cantilever(const mech_section *section, int element, int n, double L, const double *g,
                         double Px, double P, int *nodes, int *elems);
/* Root n (0, 1, 2) of cos b cosh b + 1 = 0: the clamped-free beam's (beta_n L). */
double bt_clamped_free_root(int n);
/* int phi'^2 / int phi^2 over [0, 1] of the clamped-free mode of root b (x in units of L): the
 * rotary inertia's first-order effect on the frequency, omega = b^2 sqrt(E I / (rho A L^4))
 * (1 - (I / A) slope_ratio / 2) (Rayleigh's quotient). */
double bt_slope_ratio(double b);
/* The total mechanical energy of a chain at y: the node bodies' kinetic energies, the elements'
 * strain energies and the kinetic energies their distributed inertia adds. */
double bt_total_energy(const bgr_model *m, const int *nodes, const int *elems, int n,
                       const double *y);

#endif
