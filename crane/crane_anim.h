/* The crane's motion as an animated GIF (crane --animate): a side view turning with the platform
 * (the horizontal axis along the platform's x axis from the slewing joint A, z up) and a top
 * view (global x, y), the boom drawn with its deflection magnified by a stated factor over its
 * true shape, the platform's deck and gantry, the ties, the rope, the load (with its path so far
 * in the top view) and the counterweight at their true positions, the time in the top left
 * corner. Units: m, s; global frame, Z0 up.
 *
 * During the run the frames go into DIR/anim.dat (one gnuplot data set per frame; columns: side
 * view horizontal, z, x, y, part code: 0 platform, 1 boom magnified, 2 boom true, 3 load,
 * 4 counterweight, 5 ties, 6 rope) and DIR/anim_track.dat (t, load x, y, tip x, y); at the end
 * DIR/anim.gp, which gnuplot (gif terminal, animate) turns into DIR/crane.gif, one image per
 * frame shown for the frame interval (real time), and DIR/crane_frame.png, the frame of the
 * largest tip deflection as a still. */
#ifndef CRANE_ANIM_H
#define CRANE_ANIM_H

#include <signal.h>
#include <stddef.h>

#include "crane_model.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct crane_anim crane_anim;

/* Starts the animation's data files in dir (which exists); step: the frame interval in s (for
 * the GIF's delay), scale: the boom deflection's magnification. NULL with the reason in msg. */
crane_anim *crane_anim_open(const char *dir, const char *scene_name, double step, double scale,
                            char *msg, size_t size);
/* Adds a frame from g. 0, or -1 if the data could not be written (the reason in msg). */
int crane_anim_frame(crane_anim *a, const crane_geom *g, char *msg, size_t size);
/* Closes the data files, writes anim.gp and, with render and gnuplot installed, makes crane.gif
 * and crane_frame.png (the messages on stdout unless quiet; gnuplot is stopped when *stop
 * becomes non-zero, stop NULL: never). Frees a. The number of frames, or
 * -1 with the reason in msg: a file could not be written, or gnuplot failed (it exited with an
 * error or a signal, or left crane.gif or crane_frame.png not whole; its messages in anim.log,
 * the first named in msg): crane.gif and crane_frame.png are then removed (a GIF cut short by a
 * full disk keeps no space); a file that could not be written removes the animation's data
 * files (anim.dat, anim_track.dat, anim.gp) likewise. */
int crane_anim_close(crane_anim **a, int render, int quiet, const volatile sig_atomic_t *stop,
                     char *msg, size_t size);

#ifdef __cplusplus
}
#endif
#endif
