/* The unknowns the crane's outputs read (crane_output_unknowns), the list the crane program's
 * rows interpolate alone: crane_outputs at a generic state (the start perturbed at random) must
 * give the same bits when every other unknown of y and y' is replaced, by NaN, by +-1e300 and by
 * random values, on the crane's variants: the beam boom with its rope, ties, hydraulics and
 * counterweight (the paper scene), the rigid boom, no rope, no hydraulics (the rate
 * prescribed), no counterweight, no ties, the derivative term on a filtered rate. An unknown an
 * output reads and the list lacks changes that output. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "crane_model.h"
#include "tap.h"

typedef struct variant {
    const char *name;
    void (*set)(crane_scene *s);
} variant;

static void v_paper(crane_scene *s)
{
    (void)s;
}
static void v_rigid(crane_scene *s)
{
    s->boom_elements = 0;
}
static void v_norope(crane_scene *s)
{
    s->rope = 0;
}
static void v_nohyd(crane_scene *s)
{
    s->hydraulics = 0;
}
static void v_nocw(crane_scene *s)
{
    s->counterweight = 0;
}
static void v_noties(crane_scene *s)
{
    s->ties = 0;
}
static void v_filter(crane_scene *s)
{
    s->kd_filter = 0.01;
}
static void v_rigid_bare(crane_scene *s)
{
    s->boom_elements = 0;
    s->rope = 0;
    s->hydraulics = 0;
}

static void check(const variant *v)
{
    crane_scene s;
    bg_error err = {0};
    crane_scene_default(&s);
    s.boom_elements = 4;
    v->set(&s);
    crane *c = crane_build(&s, &err);
    if (!c) {
        tap_ok(0, "%s: the crane builds: %s", v->name, err.message);
        return;
    }
    bgr_model *m = crane_model(c);
    int n = bgr_n(m), idx[CRANE_MAX_OUTPUT_UNKNOWNS];
    int k = crane_output_unknowns(c, idx);
    double *y = malloc(4 * (size_t)n * sizeof *y), *yp = y + n, *z = yp + n, *zp = z + n;
    char *listed = calloc((size_t)n, 1);
    tap_rng g = tap_rng_seed(11);
    memcpy(y, bgr_y0(m), (size_t)n * sizeof *y);
    for (int i = 0; i < n; i++) {
        y[i] *= 1 + 1e-3 * (tap_rng_unif(&g) - 0.5);
        y[i] += 1e-3 * (tap_rng_unif(&g) - 0.5);
        yp[i] = 1e-2 * (tap_rng_unif(&g) - 0.5);
    }
    int inrange = k > 0 && k <= CRANE_MAX_OUTPUT_UNKNOWNS;
    for (int j = 0; j < k; j++) {
        if (idx[j] < 0 || idx[j] >= n)
            inrange = 0;
        else
            listed[idx[j]] = 1;
    }
    tap_ok(inrange, "%s: %d unknowns listed, all in 0 .. %d", v->name, k, n - 1);
    double ref[CRANE_NOUT], out[CRANE_NOUT];
    crane_outputs(c, 1.0, y, yp, ref);
    const char *poison[3] = {"NaN", "+-1e300", "random values"};
    for (int p = 0; p < 3 && inrange; p++) {
        for (int i = 0; i < n; i++) {
            double r = tap_rng_unif(&g);
            double bad = p == 0 ? NAN : p == 1 ? (r < 0.5 ? -1e300 : 1e300) : 1e3 * (r - 0.5);
            z[i] = listed[i] ? y[i] : bad;
            zp[i] = listed[i] ? yp[i] : p == 2 ? -bad : bad;
        }
        crane_outputs(c, 1.0, z, zp, out);
        int diff = -1;
        for (int j = CRANE_NOUT - 1; j >= 0; j--)
            if (memcmp(&out[j], &ref[j], sizeof out[j])) diff = j;
        char why[160] = "";
        if (diff >= 0)
            snprintf(why, sizeof why, "; differs: %s, %g instead of %g", crane_output_names[diff],
                     out[diff], ref[diff]);
        tap_ok(diff < 0, "%s: the outputs are the same bits with the %d unlisted unknowns %s%s",
               v->name, n - k, poison[p], why);
    }
    free(listed);
    free(y);
    crane_free(&c);
}

int main(void)
{
    const variant vs[] = {{"paper (4 beam elements)", v_paper},
                          {"rigid boom", v_rigid},
                          {"no rope", v_norope},
                          {"no hydraulics", v_nohyd},
                          {"no counterweight", v_nocw},
                          {"no ties", v_noties},
                          {"filtered derivative term", v_filter},
                          {"rigid boom, no rope, no hydraulics", v_rigid_bare}};
    for (size_t i = 0; i < sizeof vs / sizeof *vs; i++)
        check(&vs[i]);
    tap_ok(crane_output_unknowns(NULL, NULL) == 0, "no crane: no unknowns");
    return tap_done();
}
