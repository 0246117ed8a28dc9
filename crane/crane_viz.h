/* The crane program's pictures of the motion, written from the output stream: the ParaView time
 * series (--vtk, crane_vtk.h) and the animated GIF (--animate, crane_anim.h).
 *
 * The program hands every output row (t, y, yp) to crane_viz_row; a row becomes a frame of a
 * writer when its time has reached that writer's next frame time (0, DT, 2 DT, ... within 1e-6
 * DT; with an output step longer than DT every row is a frame, and so with a DT below the
 * rounding of the times, where t / DT exceeds 2^52 or overflows), and only then is the geometry
 * computed (crane_geometry). Nothing is allocated or computed when neither option is given:
 * crane_viz_open returns NULL and the program skips the calls. */
#ifndef CRANE_VIZ_H
#define CRANE_VIZ_H

#include <signal.h>

#include "crane_model.h"

#ifdef __cplusplus
extern "C" {
#endif

#define CRANE_VIZ_VTK_STEP 0.05  /* s between ParaView frames */
#define CRANE_VIZ_ANIM_STEP 0.1  /* s between animation frames (shown in real time) */
#define CRANE_VIZ_ANIM_SCALE 10. /* magnification of the boom's deflection in the animation */

typedef struct crane_viz_options {
    int vtk, animate;
    double vtk_step, anim_step, anim_scale; /* 0: the defaults above */
    const volatile sig_atomic_t *stop; /* non-zero: stop drawing the animation (NULL: never) */
} crane_viz_options;

/* Takes the option name (--vtk, --animate: value NULL; --vtk-step, --anim-step, --anim-scale: a
 * positive number). 0 taken, 1 not one of these names, -1 a bad value. */
int crane_viz_option(crane_viz_options *o, const char *name, const char *value);

typedef struct crane_viz crane_viz;

/* NULL if neither option is given; else the writers, started in dir (a writer that cannot start
 * says why on stderr and counts as a failure at crane_viz_close). */
crane_viz *crane_viz_open(const crane_viz_options *o, const crane *c, const char *dir,
                          const char *scene_name, int quiet);
/* One output row. */
void crane_viz_row(crane_viz *v, double t, const double *y, const double *yp);
/* Completes the files and, with render, draws the animation (gnuplot); a line per writer on
 * stdout unless quiet; frees v (NULL: nothing). 0, or -1 if a file could not be written or
 * gnuplot failed on the animation: the first failure's reason in msg (each was said on stderr
 * when it happened; the files cut short are removed, crane_anim.h). */
int crane_viz_close(crane_viz **v, int render, char *msg, size_t size);

#ifdef __cplusplus
}
#endif
#endif
