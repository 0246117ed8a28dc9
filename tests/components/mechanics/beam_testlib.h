/* What the beam elements' tests share (test_beam_consistent.c, test_beam_quartic.c): the
 * clamped cantilever they build, the closed form of its bending frequencies, the energy of a
 * chain, its release in a mode and a run that measures energy and period. */
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

/* Releases the cantilever (nodes[0] clamped, nodes[1..n] at x = L j / n) straight in its which-th
 * (1, 2, ..) elastic mode bending in the plane of I_z (the node velocities mostly along z): the
 * node velocities and the unknowns extra[0..nextra-1] (element states: the bubbles' rates) take
 * the mode's shape, turned real by the phase of the tip's z velocity and scaled to a tip velocity
 * amplitude vtip. Returns the mode's angular frequency; NAN, with the reason in msg, if the modes
 * fail or the mode is not found. */
double bt_release_in_mode(bgr_model *m, const int *nodes, int n, double L, int which, double vtip,
                          const int *extra, int nextra, char *msg, size_t msize);

/* What bt_run measured. */
typedef struct bt_run_out {
    double drift;  /* the largest relative change of the total energy */
    double Tel;    /* the largest |kinetic energy| an element adds */
    double bmax;   /* the largest |value| of the unknowns bubbles (0 without) */
    double period; /* the mean period between upward zero crossings of y[iz] (NAN: fewer than 2) */
    int crossings;
} bt_run_out;

/* Integrates the chain m (nodes[0..n], elements elems[0..n-1]) from its initial values (consistent
 * ones computed) at rtol, atol = 1e-3 rtol, to T at nout output points, measuring bt_run_out (the
 * crossings of y[iz] if iz >= 0, the amplitudes of the nb unknowns bubbles). Returns 0 or the
 * failure (reported as a TAP diagnostic naming what). */
int bt_run(bgr_model *m, const int *nodes, const int *elems, int n, double rtol, double T, int nout,
           int iz, const int *bubbles, int nb, const char *what, bt_run_out *o);

#endif
