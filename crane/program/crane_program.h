/* The crane program's parts (private to the program: crane/crane.c and crane/program/cp_*.c,
 * prefix cp_). crane.c has the program's contract (files, signals, exit statuses); here:
 *
 *   cp_cli.c     the command line (options' table for pu_cli.h, --set overrides), the scene's
 *                file
 *   cp_status.c  the signal handler, status.txt (prepared for a signal, written atomically),
 *                failures, the atomic writes of the small files, the output folder's paths
 *   cp_csv.c     results.csv: rows formatted into a buffer, written whole
 *   cp_fmt.c     its numbers as printf's %.12g writes them, without printf
 *   cp_plots.c   plots.gp and the figures of Fig. 5, modes.png (gnuplot, pu_gnuplot.h)
 *   cp_sim.c     the dynamic run (the loop over the output times), --static and --modes, the
 *                statistics files and the summary
 *   cp_errest.c  --error-estimate: the companion run (crane_errest.h) and error_estimate.csv */
#ifndef CRANE_PROGRAM_H
#define CRANE_PROGRAM_H

#include <signal.h>
#include <stdio.h>
#include <sys/types.h>

#include "crane_errest.h"
#include "crane_model.h"
#include "crane_viz.h"

#ifndef CRANE_VERSION
#define CRANE_VERSION "unknown"
#endif

#define CP_DEFAULT_SCENE "crane/scenes/paper.ini"
#define CP_MAX_SETS 64
/* paths: the output folder's name is at most CP_OUT_MAX characters, so that its files' names
 * fit */
#define CP_PATH_SIZE 4096
#define CP_OUT_MAX (CP_PATH_SIZE - 64)
/* output rows: at most --max-rows (default CP_DEFAULT_MAX_ROWS, about 300 MB of results.csv) */
#define CP_DEFAULT_MAX_ROWS 1000000LL
#define CP_MAX_MAX_ROWS 1000000000000LL

enum { CP_EXIT_OK = 0, CP_EXIT_RUN = 1, CP_EXIT_USAGE = 2 };

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
    int errest;            /* --error-estimate [K] (crane_errest.h) */
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
    const cp_options *o;
    crane_scene scene;
    char scene_path[CP_PATH_SIZE], outdir[CP_PATH_SIZE];
    char command[4096]; /* the command line, quoted as for the shell (status.txt) */
    char started[64];   /* local start time */
    crane *c;
    dae_solver *s;
    /* results.csv (cp_csv.c): rows are formatted into csv_buf and written whole (write(2)) when
     * it is full or a second has passed since the last write; a write that fails is cut back to
     * the last whole row (ftruncate), so that the file holds whole rows at every moment */
    int csv_fd;
    char *csv_buf;
    size_t csv_len, csv_cap;
    off_t csv_size;       /* bytes on disk */
    double csv_written;   /* wall time of the last write */
    long rows, rows_disk; /* rows formatted; rows on disk */
    double t_row, t_disk; /* time of the last row formatted; on disk */
    /* columns of the outputs the rows are watched for (-1: the model has none) */
    int col_d1, col_d2, col_tx, col_ty;
    long nout;                /* output times after t = 0 (main bounds it by --max-rows) */
    double t, t_start, wall0; /* t: how far the integration got */
    const char *status;       /* "running", "completed", "interrupted", "failed" */
    int sig;                  /* the signal that interrupted the run */
    char reason[2 * BG_MESSAGE_SIZE + 512];
    double peak[2], first_out[CRANE_NOUT], final_out[CRANE_NOUT];
    double reach; /* largest |tip_x - A_x|, |tip_y - A_y| */
    int have_final;
    crane_viz *viz; /* --vtk, --animate (crane_viz.h); NULL when off */
    int bad_scene;  /* the static start found scene keys that cannot be met together: exit 2 */
    crane_errest *errest;                   /* --error-estimate (cp_errest.c); NULL when off */
    int errest_written;                     /* error_estimate.csv written */
    char errest_note[BG_MESSAGE_SIZE + 64]; /* why the estimate is unavailable */
} cp_run;

/* --------------------------------------------------------------- cp_status.c ---- */

/* Phases: CP_PHASE_SETUP, a signal ends the program at once (long library calls that cannot be
 * stopped); CP_PHASE_LOOP, the first signal stops the integration between two steps and a
 * second one ends the program at once; CP_PHASE_OTHER, the program ends the run in order. */
enum { CP_PHASE_OTHER = 0, CP_PHASE_SETUP = 1, CP_PHASE_LOOP = 2 };

/* The handler for SIGINT, SIGTERM and SIGHUP, and SIGPIPE ignored. */
void cp_signals_install(void);
/* The first signal received (0: none), and the flag itself for crane_errest_spec.stop and
 * pu_gnuplot_job.stop. */
int cp_signal(void);
const volatile sig_atomic_t *cp_signal_flag(void);
const char *cp_signal_name(int sig);
/* Enters a phase (CP_PHASE_SETUP: status.txt says "interrupted while what" if a signal comes;
 * one that came just before ends the program now). */
void cp_set_phase(cp_run *r, int phase, const char *what);
int cp_phase(void);
/* status.txt written by the handler from now on (ready 1) or not (0); the paths are r's. */
void cp_status_ready(const cp_run *r, int ready);
/* The status.txt the handler writes on a second signal while integrating, and after the
 * integration. */
void cp_arm_loop(cp_run *r);
void cp_arm_finishing(cp_run *r);
/* status.txt from r->status and r->reason (final: with the end). 0, or CP_EXIT_RUN. */
int cp_write_status(cp_run *r, int final);

/* Records a failure and says it on stderr ("crane: what: msg"); the first failure's reason
 * leads. Returns CP_EXIT_RUN. */
int cp_fail_run(cp_run *r, const char *what, const char *msg);
int cp_write_failed(cp_run *r, const char *path, int e);
/* Writes len bytes to path through path.tmp (write, fsync, close, rename). 0, or -1 with
 * errno. */
int cp_save_atomic(const char *path, const char *text, size_t len);
/* Writes DIR/name atomically from what print prints into memory (0, or -1). 0, or
 * CP_EXIT_RUN. */
typedef int (*cp_print_fn)(cp_run *r, FILE *f, const void *ctx);
int cp_save_file(cp_run *r, const char *name, cp_print_fn print, const void *ctx);
/* DIR/name (main has checked that the folder's name leaves room). */
void cp_path_in(const cp_run *r, const char *name, char *buf, size_t size);
double cp_wall_now(void);
void cp_local_time(char *buf, size_t size);

/* ------------------------------------------------------------------ cp_fmt.c ---- */

/* x as snprintf(buf, CP_FMT_SIZE, "%.12g", x) writes it, the same text, several times faster
 * (cp_fmt.c); buf holds at least CP_FMT_SIZE characters. The length. */
#define CP_FMT_SIZE 32
int cp_fmt_g12(char *buf, double x);

/* ------------------------------------------------------------------ cp_csv.c ---- */

/* Opens results.csv with its header (buffered). 0, or the failure (CP_EXIT_RUN). */
int cp_csv_open(cp_run *r);
/* One row (buffered; written when the buffer is full or a second has passed). 0, or the
 * failure of a write. */
int cp_csv_row(cp_run *r, double t, const double *out);
/* Writes the rows formatted so far. 0, or the failure (the file cut back to its last whole
 * row). */
int cp_csv_flush(cp_run *r);
/* Writes the rest, makes it durable and closes. 0, or the failure. */
int cp_csv_close(cp_run *r);

/* ---------------------------------------------------------------- cp_plots.c ---- */

/* plots.gp, then the figures with gnuplot (skipped when it is missing); each figure checked.
 * 0, or the failure (CP_EXIT_RUN). A signal stops gnuplot: the figures drawn are removed. */
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

/* Starts the companion run of --error-estimate from the first run's start (p and dopt: its
 * problem and options, y0, yp0: the start before the consistent values). A companion that
 * cannot start makes the estimate unavailable (said on stderr), never the run fail. */
void cp_errest_open(cp_run *r, const dae_problem *p, const dae_options *dopt, const double *y0,
                    const double *yp0);
/* The row at t with the first run's outputs: the companion advanced there and compared.
 * CRANE_ERREST_STOPPED when a signal came first, else 0 (a failure of the companion is kept,
 * said on stderr once, and the run goes on). */
int cp_errest_row(cp_run *r, double t, const double *out);
/* error_estimate.csv (available or not). 0, or CP_EXIT_RUN. */
int cp_errest_write(cp_run *r);
/* The estimate's lines of status.txt and solver_stats.txt, and of the summary. */
void cp_errest_status_lines(const cp_run *r, FILE *f);
void cp_errest_stats_lines(const cp_run *r, FILE *f);
void cp_errest_summary(const cp_run *r);

#endif
