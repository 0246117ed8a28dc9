/* Deprecated: gnuplot's runner moved to progutil/pu_gnuplot.h (libprogutil). These names stay
 * until their last user (bench/bench.c) calls pu_gnuplot_* itself. */
#ifndef CRANE_GNUPLOT_H
#define CRANE_GNUPLOT_H

#include "pu_gnuplot.h"

typedef pu_gnuplot_job crane_gnuplot_job;
#define crane_gnuplot_find pu_gnuplot_find
#define crane_gnuplot_run pu_gnuplot_run
#define crane_gnuplot_log_first pu_gnuplot_log_first
#define crane_png_whole pu_png_whole

#endif
