/* The crane program's parts (private to the program: crane/crane.c and crane/program/cp_*.c,
 * prefix cp_), on the run machinery it shares with bgsim (runner/rn_run.h: the signal handler
 * and status.txt, results.csv and its numbers, the output folder, the run loop,
 * solver_stats.txt, modes.csv). crane.c has the program's contract (files, signals, exit
 * statuses); here the crane's own:
 *
 *   cp_cli.c     the command line (options' table for pu_cli.h, --set overrides), the scene's
 *                file
 *   cp_plots.c   plots.gp and the figures of Fig. 5, modes.png (gnuplot, pu_gnuplot.h)
 *   cp_sim.c     the dynamic run (the crane's outputs, watches and viz around rn_loop), --static
 *                and --modes, model_stats.txt and the summary
 *   cp_errest.c  --error-estimate: the crane's part of the runner's estimate (rn_estimate.c):
 *                the companion's outputs, the columns the summary ranks */
#ifndef CRANE_PROGRAM_H
#define CRANE_PROGRAM_H

#include <signal.h>
#include <stdio.h>
#include <sys/types.h>

#include "crane_model.h"
#include "crane_viz.h"
#include "rn_run.h"

#ifndef CRANE_VERSION
#define CRANE_VERSION "unknown"
#endif

#define CP_DEFAULT_SCENE "crane/scenes/paper.ini"
#define CP_MAX_SETS 64
/* output rows: at most --max-rows (default CP_DEFAULT_MAX_ROWS, about 300 MB of results.csv) */
#define CP_DEFAULT_MAX_ROWS 1000000LL
#define CP_MAX_MAX_ROWS 1000000000000LL

/* ------------------------------------------------------------------ cp_cli.c ---- */

typedef struct cp_set_item {
    char section[64], key[64];
    const char *value;
    char origin[96];
} cp_set_item;

typedef struct cp_options {
    const char *scene, *out;
    cp_set_item sets[CP_MAX_SETS];
    int nsets;
    int no_plots, quiet;
    int static_only, modes; /* --static, --modes [T] (crane_static.h) */
    double modes_t;
    int errest;            /* --error-estimate [K] (rn_run.h: rn_estimate) */
    double errest_factor;  /* K */
    crane_viz_options viz; /* --vtk, --animate (crane_viz.h) */
    long long max_rows;    /* --max-rows */
    int argc;              /* the command line, for status.txt */
    char **argv;
} cp_options;

/* Returns -1 to go on, or an exit status (help and version: 0; a bad command line: 2, said on
 * stderr). */
int cp_parse_args(int argc, char **argv, cp_options *o);
/* Finds the scene arg: as given, then (bare names) in crane/scenes/ with or without .ini,
 * relative to the current folder, then to the source tree and the installed data folder. 1 with
 * its path in path; 0 with the paths tried in tried, and in odd a candidate that exists but is
 * no regular file (its path and what it is). */
int cp_find_scene(const char *arg, char *path, size_t size, char *tried, size_t tsize, char *odd,
                  size_t osize);

/* ------------------------------------------------------------------ the run ---- */

typedef struct cp_run {
    rn_run rn; /* status.txt, results.csv, the folder, the solver (rn_run.h); rn.owner = this */
    const cp_options *o;
    crane_scene scene;
    char scene_path[RN_PATH_SIZE];
    crane *c;
    /* columns of the outputs the rows are watched for (-1: the model has none) */
    int col_d1, col_d2, col_tx, col_ty;
    double peak[2], first_out[CRANE_NOUT], final_out[CRANE_NOUT];
    double reach; /* largest |tip_x - A_x|, |tip_y - A_y| */
    int have_final;
    crane_viz *viz; /* --vtk, --animate (crane_viz.h); NULL when off */
    int bad_scene;  /* the static start found scene keys that cannot be met together: exit 2 */
} cp_run;

/* The crane's run of a runner's hook (rn.owner). */
#define CP_RUN(rn) ((cp_run *)(rn)->owner)

/* ---------------------------------------------------------------- cp_plots.c ---- */

/* plots.gp, then the figures with gnuplot (skipped when it is missing); each figure checked.
 * 0, or the failure (RN_EXIT_RUN). A signal stops gnuplot: the figures drawn are removed. */
int cp_draw_figures(cp_run *r);
/* modes.png from modes.gp (--modes). 0, or the failure. */
int cp_draw_modes(cp_run *r);

/* ------------------------------------------------------------------ cp_sim.c ---- */

/* The dynamic run; --static and --modes. 0 or an exit status; r->status says how it ended. */
int cp_simulate(cp_run *r);
int cp_analyse(cp_run *r);
/* The summary on stdout. */
void cp_summary(cp_run *r);

/* --------------------------------------------------------------- cp_errest.c ---- */

/* With --error-estimate (r->rn.est.on): the runner's companion run (rn_estimate_open) started
 * from the first run's start with the crane's outputs (p and dopt: its problem and options, y0,
 * yp0: the start before the consistent values). A companion that cannot start makes the
 * estimate unavailable (said on stderr), never the run fail. The runner does the rest: the
 * rows compared (rn_loop), error_estimate.csv, the lines of status.txt and solver_stats.txt,
 * the summary's line (rn_estimate_summary). */
void cp_errest_open(cp_run *r, const dae_problem *p, const dae_options *dopt, const double *y0,
                    const double *yp0);

#endif
