/* The crane program's pictures of the motion (crane_viz.h): frame selection and dispatch to the
 * ParaView series (crane_vtk.h) and the animation (crane_anim.h). */
#include "crane_viz.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "crane_anim.h"
#include "crane_vtk.h"

struct crane_viz {
    const crane *c;
    crane_geom *g;
    crane_vtk *vtk;
    crane_anim *anim;
    double vtk_step, anim_step, vtk_next, anim_next;
    int bad, quiet, vtk_frames;
    char dir[4096];
    char why[1024]; /* the first failure's reason ("" none) */
    const volatile sig_atomic_t *stop;
};

/* A failure: said on stderr now (what: msg), the first kept for crane_viz_close. */
static void failed(crane_viz *v, const char *what, const char *msg)
{
    fprintf(stderr, "crane: %s: %s\n", what, msg);
    if (!v->why[0]) snprintf(v->why, sizeof v->why, "%.200s: %.800s", what, msg);
    v->bad = 1;
}

int crane_viz_option(crane_viz_options *o, const char *name, const char *value)
{
    if (!strcmp(name, "--vtk")) return o->vtk = 1, 0;
    if (!strcmp(name, "--animate")) return o->animate = 1, 0;
    double *dst = !strcmp(name, "--vtk-step")     ? &o->vtk_step
                  : !strcmp(name, "--anim-step")  ? &o->anim_step
                  : !strcmp(name, "--anim-scale") ? &o->anim_scale
                                                  : NULL;
    if (!dst) return 1;
    char *end;
    double x = value ? strtod(value, &end) : NAN;
    if (!value || end == value || *end || !(x > 0) || !isfinite(x)) return -1;
    *dst = x;
    if (dst == &o->vtk_step)
        o->vtk = 1;
    else
        o->animate = 1;
    return 0;
}

crane_viz *crane_viz_open(const crane_viz_options *o, const crane *c, const char *dir,
                          const char *scene_name, int quiet)
{
    if (!o || (!o->vtk && !o->animate)) return NULL;
    crane_viz *v = calloc(1, sizeof *v);
    char msg[4400];
    if (v) v->g = malloc(sizeof *v->g);
    if (!v || !v->g) {
        fprintf(stderr, "crane: 3-D output and animation: out of memory\n");
        if (v) free(v);
        return NULL; /* the program goes on without */
    }
    v->c = c;
    v->quiet = quiet;
    v->stop = o->stop;
    snprintf(v->dir, sizeof v->dir, "%s", dir);
    v->vtk_step = o->vtk_step > 0 ? o->vtk_step : CRANE_VIZ_VTK_STEP;
    v->anim_step = o->anim_step > 0 ? o->anim_step : CRANE_VIZ_ANIM_STEP;
    if (o->vtk && !(v->vtk = crane_vtk_open(dir, scene_name, msg, sizeof msg)))
        failed(v, "ParaView series", msg);
    if (o->animate &&
        !(v->anim = crane_anim_open(dir, scene_name, v->anim_step,
                                    o->anim_scale > 0 ? o->anim_scale : CRANE_VIZ_ANIM_SCALE, msg,
                                    sizeof msg)))
        failed(v, "animation", msg);
    return v;
}

/* Due at t: the next frame time reached (within 1e-6 of the interval). */
static int due(double t, double next, double step)
{
    return t >= next - 1e-6 * step;
}

/* The first multiple of step after t (within 1e-6 of the interval). When t / step is beyond
 * 2^52 (an interval below the rounding of t, or t / step infinite: a denormal step), no multiple
 * of step between t and the next row can be told apart: every row is then a frame (t itself is
 * returned, which the next row, later than t, has reached). */
static double next_time(double t, double step)
{
    double q = floor(t / step + 1e-6) + 1, next = q * step;
    if (!(q < 4503599627370496.0) || !(next > t)) return t;
    return next;
}

void crane_viz_row(crane_viz *v, double t, const double *y, const double *yp)
{
    if (!v) return;
    int dv = v->vtk && due(t, v->vtk_next, v->vtk_step);
    int da = v->anim && due(t, v->anim_next, v->anim_step);
    if (!dv && !da) return;
    char msg[4400];
    if (crane_geometry(v->c, t, y, yp, v->g) != BG_OK) {
        snprintf(msg, sizeof msg, "the geometry at t = %g s failed", t);
        failed(v, "ParaView series and animation stopped", msg);
        v->vtk_frames = crane_vtk_close(&v->vtk);
        crane_anim_close(&v->anim, 0, 1, NULL, msg, sizeof msg);
        return;
    }
    if (dv) {
        v->vtk_next = next_time(t, v->vtk_step);
        if (crane_vtk_frame(v->vtk, v->g, msg, sizeof msg) != 0) {
            failed(v, "ParaView series stopped", msg);
            v->vtk_frames = crane_vtk_close(&v->vtk);
        }
    }
    if (da) {
        v->anim_next = next_time(t, v->anim_step);
        if (crane_anim_frame(v->anim, v->g, msg, sizeof msg) != 0) {
            failed(v, "animation stopped", msg);
            crane_anim_close(&v->anim, 0, 1, NULL, msg, sizeof msg);
        }
    }
}

int crane_viz_close(crane_viz **vp, int render, char *msg, size_t size)
{
    if (!vp || !*vp) return 0;
    crane_viz *v = *vp;
    char why[1200];
    if (v->vtk) {
        int n = crane_vtk_close(&v->vtk);
        if (n < 0) {
            snprintf(why, sizeof why, "cannot complete %.1100s/crane.pvd", v->dir);
            failed(v, "ParaView series", why);
        } else if (!v->quiet) {
            printf("crane: ParaView series %s/crane.pvd, %d frames every %g s\n", v->dir, n,
                   v->vtk_step);
        }
    }
    if (v->anim && crane_anim_close(&v->anim, render, v->quiet, v->stop, why, sizeof why) < 0)
        failed(v, "animation", why);
    int bad = v->bad;
    if (bad && msg && size) snprintf(msg, size, "%s", v->why);
    free(v->g);
    free(v);
    *vp = NULL;
    return bad ? -1 : 0;
}
