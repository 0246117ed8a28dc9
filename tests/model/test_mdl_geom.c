/* mdl_geometry: the model drawn at a state, against positions known by hand: the double
 * pendulum's rods at their start (hinges at L1 (sin th1, 0, -cos th1) and the free end one rod
 * further), a spring drawn between the fixed point and the mass it holds, a beam chain through
 * its nodes. */
#include <math.h>
#include <string.h>

#include "bgr_model.h"
#include "mdl_model.h"
#include "tap.h"

#ifndef MODELS_DIR
#define MODELS_DIR "examples/models"
#endif

static int part(const mdl_geom *g, const char *path)
{
    for (int i = 0; i < g->nparts; i++)
        if (!strcmp(g->part_path[i], path)) return i;
    return -1;
}

/* the largest distance of the points of part p from x (the nearest of them) */
static double nearest(const mdl_geom *g, int p, const double *x)
{
    double best = HUGE_VAL;
    for (int i = 0; i < g->npoints; i++)
        if (g->point_part[i] == p)
            best = fmin(best, hypot(hypot(g->x[3 * i] - x[0], g->x[3 * i + 1] - x[1]), g->x[3 * i + 2] - x[2]));
    return best;
}

int main(void)
{
    bg_error e = {0};
    mdl_model *mm = mdl_load(MODELS_DIR "/double-pendulum.yaml", NULL, 0, &e);
    tap_ok(mm != NULL, "double pendulum loads (%s)", mm ? "ok" : e.message);
    if (!mm) return tap_done();
    mdl_geom g = {0};
    tap_ok(mdl_geometry(mm, bgr_y0(mdl_bgr(mm)), &g, &e) == BG_OK, "drawn (%s)", e.message);
    tap_ok(g.nparts == 3 && part(&g, "ground") >= 0 && part(&g, "rod1.body") >= 0 &&
               part(&g, "rod2.body") >= 0,
           "three parts: the ground and the two rods (%d)", g.nparts);
    tap_ok(g.npoints == 7 && g.nlines == 4 && g.nmarks == 3,
           "7 points, 4 lines (centre to each end), 3 marks (%d, %d, %d)", g.npoints, g.nlines, g.nmarks);
    double th1 = 60 * acos(-1.0) / 180, th2 = -30 * acos(-1.0) / 180, L1 = 1, L2 = 0.7;
    double h2[3] = {L1 * sin(th1), 0, -L1 * cos(th1)};
    double tip[3] = {h2[0] + L2 * sin(th2), 0, h2[2] - L2 * cos(th2)};
    tap_ok(nearest(&g, part(&g, "rod1.body"), h2) < 1e-12 && nearest(&g, part(&g, "rod2.body"), h2) < 1e-12,
           "both rods reach the second hinge");
    tap_ok(nearest(&g, part(&g, "rod2.body"), tip) < 1e-12, "the lower rod's free end");
    double origin[3] = {0, 0, 0};
    tap_ok(nearest(&g, part(&g, "ground"), origin) < 1e-15, "the ground at the origin");
    mdl_free(&mm);

    static const char *text2 =
        "format: bgsim 1\nname: t\n"
        "components:\n"
        "  top: {type: mech.support, dim: 3, position: [0, 0, 2]}\n"
        "  s: {type: mech.spring, k: 100, L0: 1}\n"
        "  m: {type: mech.point_mass, mass: 1, position: [0.5, 0, 0.5]}\n"
        "  base: {type: mech.support}\n"
        "  beam: {type: mech.beam_chain, elements: 4, start: [0, 1, 0], end: [2, 1, 0], E: 2e11,\n"
        "         G: 8e10, A: 1e-3, Iy: 1e-6, Iz: 1e-6, J: 1e-6, rho: 7850,\n"
        "         ports: {foot: {node: 0}, tip: {node: 4, dim: 3}}}\n"
        "  f: {type: mech.free, dim: 3}\n"
        "bonds: [top.p -> s.a, s.b -> m.p, base.p -> beam.foot, beam.tip -> f.p]\n";
    mm = mdl_load_string(text2, "t.yaml", NULL, 0, &e);
    tap_ok(mm != NULL, "spring, mass and beam chain load (%s)", mm ? "ok" : e.message);
    if (mm && mdl_geometry(mm, bgr_y0(mdl_bgr(mm)), &g, &e) == BG_OK) {
        int ps = part(&g, "s"), pb = part(&g, "beam");
        int ls = -1, lb = -1;
        for (int i = 0; i < g.nlines; i++) {
            if (g.line_part[i] == ps) ls = i;
            if (g.line_part[i] == pb) lb = i;
        }
        tap_ok(ls >= 0 && g.line_start[ls + 1] - g.line_start[ls] == 2,
               "the spring is one segment");
        if (ls >= 0) {
            const double *a = g.x + 3 * g.line_conn[g.line_start[ls]],
                         *b = g.x + 3 * g.line_conn[g.line_start[ls] + 1];
            tap_ok(a[2] == 2 && a[0] == 0 && b[0] == 0.5 && b[2] == 0.5,
                   "from the fixed point (0, 0, 2) to the mass (0.5, 0, 0.5)");
        }
        tap_ok(lb >= 0 && g.line_start[lb + 1] - g.line_start[lb] == 5, "the chain: a polyline of 5 nodes");
        if (lb >= 0) {
            const double *n3 = g.x + 3 * g.line_conn[g.line_start[lb] + 3];
            tap_close(n3[0], 1.5, 0, 1e-15, "its node 3 at x = 1.5");
        }
    }
    mdl_geom_clear(&g);
    mdl_free(&mm);
    return tap_done();
}
