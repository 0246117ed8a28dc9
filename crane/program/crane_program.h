/* The crane program's parts (private to the program: crane/crane.c and crane/program/cp_*.c,
 * prefix cp_), on the run machinery it shares with bgsim (runner/rn_run.h: the signal handler
 * and status.txt, results.csv and its numbers, the output folder, the run loop,
 * solver_stats.txt, modes.csv). crane.c has the program's contract (files, signals, exit
 * statuses); here the crane's own:
 *
 *   cp_cli.c     the command line (options' table for pu_cli.h, --set overrides), the scene's
 *                file
 *   cp_plots.c   plots.gp and the figures of Fig. 5, modes.png (gnuplot, pu_gnuplot.h)
 *   cp_columns.c results.csv read back by column name (the figures, the model file's summary)
 *   cp_model.c   a model file SCENE: bgsim's run of it (bgsim.h: bs_run_file) with Fig. 5 and
 *                the crane's summary lines on top
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
    cp_set_item sets[CP_MAX_SETS]; /* --set and --t-end, --rtol, ...: scene keys */
    int nsets;
    const char *set_raw[CP_MAX_SETS]; /* every --set as given (a model file's PATH=VALUE) */
    int nset_raw;
    char set_error[512]; /* the first --set that is no SECTION.KEY=VALUE ("": none) */
    int no_plots, quiet;
    int static_only, modes; /* --static, --modes [T] (crane_static.h) */
    double modes_t;
    int errest;            /* --error-estimate [K] (rn_run.h: rn_estimate) */
    double errest_factor;  /* K */
    crane_viz_options viz; /* --vtk, --animate (crane_viz.h) */
    const char *viz_given; /* the first of --vtk, --vtk-step, --animate, ... given (NULL: none) */
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
 * no regular file (its path and what it is) or that cannot be reached for another reason than
 * its absence (its path and the system's error: a loop of symbolic links). */
int cp_find_scene(const char *arg, char *path, size_t size, char *tried, size_t tsize, char *odd,
                  size_t osize);

/* ---------------------------------------------------------------- cp_model.c ---- */

/* A SCENE ending in .yaml is a model file (docs/model-format.md); any other is an INI scene. */
int cp_is_model_file(const char *arg);
/* Finds the model file arg: as given, then (bare names) in crane/models/ relative to the
 * current folder, then to the source tree. 1 with its path in path; 0 with the paths tried. */
int cp_find_model(const char *arg, char *path, size_t size, char *tried, size_t tsize);
/* Runs the model file o->scene (bgsim.h: bs_run_file) with Fig. 5 and the crane's summary lines
 * on top; the options of INI scenes only are refused (exit 2). Returns the exit status. */
int cp_run_model(const cp_options *o, int argc, char **argv);

/* The files a run writes into its folder, from a scene or a model file (crane.c), removed at the
 * start of either so that nothing of an earlier run of the other stays. NULL-terminated. */
extern const char *const cp_run_files[];

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
    double drift_hz; /* --modes T: elastic modes below it are drift (crane_modes_drift) */
} cp_run;

/* The crane's run of a runner's hook (rn.owner). */
#define CP_RUN(rn) ((cp_run *)(rn)->owner)

/* -------------------------------------------------------------- cp_columns.c ---- */

#define CP_MAX_COLS 256

/* The columns of results.csv by name, from its header ("theta [rad]": a scene's; "theta": a
 * model file's), at most CP_MAX_COLS, each name cut to 63 characters. */
typedef struct cp_columns {
    int n;
    char name[CP_MAX_COLS][64];
} cp_columns;

/* Reads the header of the file csv. 0, or -1 with errno. */
int cp_columns_read(const char *csv, cp_columns *cs);
/* The column named key (followed in the header by the end or a space), -1 if none. */
int cp_column(const cp_columns *cs, const char *key);
/* Column i's label: its header name, or without a unit there the crane's output of that name
 * with its unit (crane_output_names: "theta" -> "theta [rad]"). */
const char *cp_column_label(const cp_columns *cs, int i);

/* What the crane takes from the rows of results.csv: the first and last row (each a value per
 * column), the peaks of |tip_defl_1| and |tip_defl_2|, the reach: the largest |tip_x - cx| and
 * |tip_y - cy| (cx, cy: the slewing axis). Rows are read up to the first that is not whole. */
typedef struct cp_rows {
    long rows;
    double first[CP_MAX_COLS], last[CP_MAX_COLS];
    double peak[2], reach;
} cp_rows;

/* 0, or -1 with errno. */
int cp_rows_scan(const char *csv, const cp_columns *cs, double cx, double cy, cp_rows *s);

/* ---------------------------------------------------------------- cp_plots.c ---- */

/* What Fig. 5 takes besides results.csv's columns. */
typedef struct cp_fig_info {
    const char *source;     /* the titles' "(...)": "scene paper", "model file paper.yaml" */
    double cx, cy;          /* the slewing axis */
    double radius;          /* fig. 5a's circle: the tip's initial distance from the axis */
    double reach;           /* largest |tip_x - cx|, |tip_y - cy| of the run */
    double fallback_radius; /* without radius and reach: the plot's half-width 1.1 * this + 1 */
} cp_fig_info;

/* plots.gp from results.csv's columns found by name (a figure whose columns are missing is left
 * out), then the figures with gnuplot (skipped when it is missing); each figure checked. 0, or
 * the failure (RN_EXIT_RUN, recorded in rn). A signal stops gnuplot: the figures drawn are
 * removed. */
int cp_figures(rn_run *rn, const cp_fig_info *fi, int quiet);
/* cp_figures for a scene's run: the axis at the scene's joint A, the radius from the first
 * row. */
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
