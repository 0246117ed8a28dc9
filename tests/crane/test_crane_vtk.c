/* The crane's geometry for the 3-D output and the animation (crane_geometry, crane_model.h) and
 * the options of crane_viz.h: at the settled start of the paper scene the boom's nodes run from
 * the foot to the tip of the outputs, nothing is deflected, the tip node is in equilibrium between
 * the last element's section force, the ties, the rope and its own weight, the boom is in
 * compression; after 0.3 s of the run the tip node, its deflections, the load and the tensions
 * are crane_outputs' ones; a rigid boom has two nodes and no section forces. The files the
 * program writes are checked by test_crane_vtk.py. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "crane_model.h"
#include "crane_viz.h"
#include "tap.h"

#include "crane_run.h"

static double dist(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

static double norm(const double *a)
{
    return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

static void paper_start(crane_geom *g)
{
    crane_scene sc;
    crane_scene_default(&sc);
    run r;
    if (start(&r, &sc, 1) != 0) {
        tap_ok(0, "paper scene: settled start");
        finish(&r);
        return;
    }
    int rc = crane_geometry(r.c, 0.0, r.y, r.yp, g);
    tap_ok(rc == BG_OK, "crane_geometry at the start: BG_OK");
    tap_ok(g->nodes == sc.boom_elements + 1 && g->beam == 1, "paper: %d nodes (%d elements)",
           g->nodes, sc.boom_elements);
    const double *tip = g->node[g->nodes - 1];
    tap_close(dist(tip, r.out + O_TIP), 0, 0, 1e-12, "start: tip node = tip_x/y/z");
    tap_close(dist(g->node[0], g->hinge), 0, 0, 1e-4, "start: node 0 at the hinge");
    tap_close(dist(g->load, r.out + O_LOAD), 0, 0, 1e-12, "start: load = load_x/y/z");
    tap_close(g->rope_tension, r.out[O_TEN], 1e-12, 0, "start: rope tension = rope_force");
    tap_close(g->p_high, r.out[O_PH], 1e-12, 0, "start: p_high");
    double dmax = 0;
    for (int k = 0; k < g->nodes; k++)
        dmax =
            fmax(dmax, fmax(norm(g->defl[k]), fmax(fabs(g->defl_luff[k]), fabs(g->defl_side[k]))));
    tap_close(dmax, 0, 0, 1e-9, "start: no deflection (the static start is the reference)");
    tap_close(dist(g->gantry_top, sc.gantry_top), 0, 0, 1e-6, "start: gantry top as the scene's");
    tap_ok(g->nties == 2 && g->ngantry == 2 && g->rope && g->counterweight,
           "paper: a pair of ties, rope, counterweight");
    tap_close(g->cw_mass, sc.cw_mass, 0, 0, "counterweight mass");
    tap_close(g->load_mass, sc.load_mass, 0, 0, "load mass");
    /* the deck spans the points fixed to the platform */
    double xmin = fmin(fmin(g->deck[0][0], g->deck[1][0]), fmin(g->deck[2][0], g->deck[3][0]));
    double xmax = fmax(fmax(g->deck[0][0], g->deck[1][0]), fmax(g->deck[2][0], g->deck[3][0]));
    tap_ok(xmin < sc.gantry_top[0] && xmin < sc.cw_pos[0] && xmax > sc.boom_foot[0],
           "deck from %g to %g m spans gantry, counterweight and hinge", xmin, xmax);
    /* the tip node at rest: the last element's section force (what the tip side exerts on it)
     * balances the ties, the rope and the node's weight: F = sum T u + m g, m the half element
     * and the halves of the ties' mass lumped there ([ties] rho) */
    double F[3] = {0, 0, 0}, u[3];
    for (int k = 0; k < 2; k++) {
        double L = dist(g->gantry[k], tip);
        for (int i = 0; i < 3; i++)
            u[i] = (g->gantry[k][i] - tip[i]) / L, F[i] += g->tie_tension[k] * u[i];
    }
    double L = dist(g->load, tip);
    for (int i = 0; i < 3; i++)
        F[i] += g->rope_tension * (g->load[i] - tip[i]) / L;
    F[2] -= sc.g * sc.boom_rho * sc.boom_A * sc.boom_length / (2 * sc.boom_elements);
    F[2] -= sc.g * 0.5 * sc.tie_rho * sc.tie_A * crane_tie_length(r.c) * g->nties; /* ties' halves */
    tap_close(dist(g->force[g->nodes - 1], F), 0, 0, 1e-4 * norm(F),
              "start: tip node in equilibrium (section force %.6g N, ties + rope + weight %.6g "
              "N)",
              norm(g->force[g->nodes - 1]), norm(F));
    tap_ok(g->force_local[0][0] < -1e6 && g->force_local[g->nodes - 1][0] < 0,
           "start: boom in compression (N = %.4g N at the foot, %.4g N at the tip)",
           g->force_local[0][0], g->force_local[g->nodes - 1][0]);
    tap_close(g->moment_local[g->nodes - 1][0], 0, 0, 1e-3 * norm(g->moment[0]) + 1,
              "start: no torsion at the tip");
    /* after 0.3 s of the run */
    if (advance(&r, 0.3) == 0) {
        crane_geometry(r.c, 0.3, r.y, r.yp, g);
        tip = g->node[g->nodes - 1];
        tap_close(dist(tip, r.out + O_TIP), 0, 0, 1e-12, "0.3 s: tip node = tip_x/y/z");
        tap_close(g->defl_luff[g->nodes - 1], r.out[O_DL], 1e-9, 1e-12,
                  "0.3 s: tip deflection_luff = tip_defl_1");
        tap_close(g->defl_side[g->nodes - 1], r.out[O_DS], 1e-9, 1e-12,
                  "0.3 s: tip deflection_side = tip_defl_2 (%.4g m)", r.out[O_DS]);
        tap_ok(fabs(g->defl_side[g->nodes - 1]) > 1e-3, "0.3 s: the tip is deflected sideways");
        tap_close(dist(g->load, r.out + O_LOAD), 0, 0, 1e-12, "0.3 s: load");
        tap_close(g->theta, r.out[O_TH], 0, 0, "0.3 s: theta");
        double dn = 0;
        for (int k = 0; k < g->nodes; k++)
            dn = fmax(dn, fabs(norm(g->defl[k]) - hypot(g->defl_luff[k], g->defl_side[k])));
        tap_ok(dn < 0.05 * norm(g->defl[g->nodes - 1]),
               "0.3 s: the deflections are transverse (axial part %.3g m)", dn);
        /* the deck turns with the platform */
        double ang = atan2(g->deck[1][1] - g->deck[0][1], g->deck[1][0] - g->deck[0][0]);
        tap_close(ang, g->theta, 0, 1e-6, "0.3 s: the deck turned by theta");
    } else {
        tap_ok(0, "0.3 s: run");
    }
    finish(&r);
}

static void rigid_boom(crane_geom *g)
{
    crane_scene sc;
    crane_scene_default(&sc);
    sc.boom_elements = 0;
    run r;
    if (start(&r, &sc, 1) != 0) {
        tap_ok(0, "rigid boom: settled start");
        finish(&r);
        return;
    }
    tap_ok(crane_geometry(r.c, 0.0, r.y, r.yp, g) == BG_OK && g->nodes == 2 && g->beam == 0,
           "rigid boom: 2 nodes, no beam elements");
    tap_close(dist(g->node[1], r.out + O_TIP), 0, 0, 1e-12, "rigid boom: node 1 = tip");
    tap_close(dist(g->node[0], g->hinge), 0, 0, 1e-4, "rigid boom: node 0 at the hinge");
    tap_ok(norm(g->force[0]) == 0 && norm(g->moment[1]) == 0, "rigid boom: section forces 0");
    finish(&r);
}

static void options(void)
{
    crane_viz_options o;
    memset(&o, 0, sizeof o);
    tap_ok(crane_viz_option(&o, "--vtk", NULL) == 0 && o.vtk && !o.animate, "--vtk");
    tap_ok(crane_viz_option(&o, "--anim-scale", "5") == 0 && o.animate && o.anim_scale == 5,
           "--anim-scale 5 (implies --animate)");
    tap_ok(crane_viz_option(&o, "--vtk-step", "0.02") == 0 && o.vtk_step == 0.02, "--vtk-step");
    tap_ok(crane_viz_option(&o, "--anim-step", "0") == -1 &&
               crane_viz_option(&o, "--anim-step", "-1") == -1 &&
               crane_viz_option(&o, "--anim-step", "1x") == -1 &&
               crane_viz_option(&o, "--anim-step", "nan") == -1,
           "bad intervals refused");
    tap_ok(crane_viz_option(&o, "--quiet", NULL) == 1, "other options are not taken");
    memset(&o, 0, sizeof o);
    tap_ok(crane_viz_open(&o, NULL, "/nonexistent", "x", 1) == NULL,
           "neither option: nothing opened (no allocation)");
}

int main(void)
{
    crane_geom *g = malloc(sizeof *g);
    if (!g) return 1;
    paper_start(g);
    rigid_boom(g);
    options();
    free(g);
    return tap_done();
}
