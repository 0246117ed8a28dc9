/* The order of convergence of the crane boom's bending frequencies in the element size
 * (docs/beam.md, "The crane's boom"): the paper scene's modes at its static start
 * (crane_modes), the boom's elastic modes (crane_mode_part "boom") in rising frequency, with
 * the quartic element at 4, 8, 16 elements and the consistent one at 8, 16, 32. The observed
 * order p = log2((f_n - f_2n) / (f_2n - f_4n)) of a frequency that converges as C h^p needs no
 * reference. The boom is compressed (its weight, the load's through the ties: an axial strain
 * near -2e-4), so that a field whose slopes at the nodes are short of the node rotations by
 * that strain (mech_beam.h: the field over the chord L0 instead of the current one) shows as
 * an error eps (k h)^2: second order. Pinned:
 *   - quartic, f2 and f3 (the second and third bending modes, in and out of the luffing
 *     plane): order >= 3.5 between 4, 8 and 16 elements (5.5 and 5.5; 1.9 and -1 with the
 *     chord L0);
 *   - consistent, f2: order >= 3.5 between 8, 16 and 32 elements (4.0; the differences
 *     changed sign with the chord L0).
 * f1 is converged below 3e-8 from 4 elements on (its differences are not a power of h), f4
 * keeps a second-order part of 2e-7 at 16 elements from the elements' linear axial field. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "crane_model.h"
#include "crane_static.h"
#include "mech_beam.h"
#include "tap.h"

enum { NF = 4 };

/* The boom's first NF elastic frequencies (Hz, rising) of the paper scene with n elements of
 * the given kind; 0 on failure (with a TAP comment). */
static int boom_frequencies(int element, int n, double f[NF])
{
    crane_scene s;
    crane_scene_default(&s);
    s.boom_elements = n;
    s.boom_quartic = element == MECH_BEAM_QUARTIC;
    s.boom_consistent = element == MECH_BEAM_CONSISTENT;
    bg_error err = {0};
    dae_modes *M = NULL;
    crane *c = crane_build(&s, &err);
    int nf = 0;
    if (!c || crane_settle(c, &err) != BG_OK || crane_modes(c, 0.0, &M, NULL, &err) != BG_OK) {
        tap_diag("modes, %d elements: %s", n, err.message);
    } else {
        double all[256];
        int na = 0;
        char part[64];
        for (int k = 0; k < dae_modes_count(M) && na < 256; k++) {
            const dae_mode *md = dae_modes_get(M, k);
            if (md->kind != DAE_MODE_ELASTIC) continue;
            crane_mode_part(M, k, part, sizeof part);
            if (!strcmp(part, "boom")) all[na++] = md->freq_hz;
        }
        for (int i = 1; i < na; i++) /* rising: insertion sort */
            for (int j = i; j > 0 && all[j] < all[j - 1]; j--) {
                double t = all[j];
                all[j] = all[j - 1];
                all[j - 1] = t;
            }
        for (nf = 0; nf < NF && nf < na; nf++)
            f[nf] = all[nf];
    }
    dae_modes_free(&M);
    crane_free(&c);
    return nf == NF;
}

/* The observed order of frequency j from three meshes n, 2n, 4n; NaN when the differences
 * change sign (no power of h). */
static double order(double f[3][NF], int j)
{
    double d1 = f[0][j] - f[1][j], d2 = f[1][j] - f[2][j];
    return d1 / d2 > 0 ? log2(d1 / d2) : NAN;
}

static void three_meshes(int element, const char *name, int n0, const int *pinned, int npinned)
{
    double f[3][NF];
    int ok = 1;
    for (int i = 0; i < 3; i++) {
        ok &= boom_frequencies(element, n0 << i, f[i]);
        if (ok)
            tap_diag("%s, %2d elements: f1..f4 %.10f %.10f %.10f %.10f Hz", name, n0 << i, f[i][0],
                     f[i][1], f[i][2], f[i][3]);
    }
    if (!tap_ok(ok, "%s: the boom's first %d modes at %d, %d, %d elements", name, NF, n0, 2 * n0,
                4 * n0))
        return;
    tap_diag("%s: observed orders f1..f4 %.2f %.2f %.2f %.2f", name, order(f, 0), order(f, 1),
             order(f, 2), order(f, 3));
    for (int i = 0; i < npinned; i++) {
        int j = pinned[i];
        double p = order(f, j);
        tap_ok(p >= 3.5,
               "%s, f%d: observed order %.2f >= 3.5 between %d, %d, %d elements (differences "
               "%.2e, %.2e relative)",
               name, j + 1, p, n0, 2 * n0, 4 * n0, (f[0][j] - f[1][j]) / f[2][j],
               (f[1][j] - f[2][j]) / f[2][j]);
    }
}

int main(void)
{
    static const int quartic_pinned[2] = {1, 2}, consistent_pinned[1] = {1};
    three_meshes(MECH_BEAM_QUARTIC, "quartic", 4, quartic_pinned, 2);
    three_meshes(MECH_BEAM_CONSISTENT, "consistent", 8, consistent_pinned, 1);
    return tap_done();
}
