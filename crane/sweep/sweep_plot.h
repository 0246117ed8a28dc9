/* Pictures of a sweep, one PNG per reported quantity (gnuplot), from the rows:
 *   one swept key (an [axis], or an [lhs] of one key)   a line plot against the key's value
 *                                                        (log axis for log spacing)
 *   two [axis] sections of one key each                 a heat map over the grid, the values
 *                                                        written in the cells (a case without a
 *                                                        value shows its status)
 *   an [lhs] of two keys                                a scatter plot coloured by the value
 *   more keys                                           none (sweep.csv has the numbers)
 * Files in the output folder: plot.dat (the numbers, whitespace-separated, a status column),
 * plots.gp (run `gnuplot plots.gp` there to draw them again), plot_<quantity>.png, and
 * gnuplot.log when gnuplot said something. */
#ifndef SWEEP_PLOT_H
#define SWEEP_PLOT_H

#include <stddef.h>

#include "sweep_row.h"
#include "sweep_spec.h"

/* 0: drawn, or nothing to draw, or gnuplot missing (msg says which; the script is written);
 * -1: a file could not be written or gnuplot failed (msg). *nfig: the pictures drawn. */
int sweep_plot(const sweep_spec *s, const sweep_row *rows, const char *outdir, int *nfig, char *msg,
               size_t size);

#endif
