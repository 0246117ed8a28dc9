/* The programs' run machinery (librunner: static, not installed, prefix rn_), shared by the
 * crane program (crane/crane.c, crane/program/) and bgsim (bgsim/): what a program does around a
 * solver run, the same for every model.
 *
 *   rn_status.c  the signal handler (SIGINT, SIGTERM, SIGHUP) and the status.txt it writes,
 *                status.txt's lifecycle (running -> completed / interrupted / failed, with the
 *                reason), failures, the atomic writes of the small files, the output folder
 *                made ready (created, "in use by a running program" refused, an earlier run's
 *                files removed), the command line quoted for status.txt
 *   rn_csv.c     results.csv: rows formatted into a buffer, written whole
 *   rn_fmt.c     its numbers as printf's %.12g writes them, without printf
 *   rn_loop.c    the solver started (consistent initial values), the run loop over the output
 *                times (a signal stops it between two steps), the progress line,
 *                solver_stats.txt, modes.csv
 *   rn_estimate.c  --error-estimate [K]: the companion run (rn_errest.c, rn_errest.h) beside
 *                the run, error_estimate.csv, its lines in status.txt and solver_stats.txt, the
 *                summary's line
 *
 * Unlike libprogutil this is a program's part, not a general library: it says failures on
 * stderr ("PROGRAM: what: why"), and its signal handler writes status.txt and ends the program
 * (_exit) when a signal comes during set-up. Its one global state is that handler's (a process
 * has one): the signal received, the phase and the status.txt prepared for it. A program runs
 * one rn_run at a time.
 *
 * Invariants: status.txt is always whole (written to a temporary file, fsync, rename; on a full
 * disk, which has no room for the copy, rewritten in place: rn_write_status), first
 * "running", at the end what became of the run; results.csv holds whole rows at every moment
 * (a write that fails is cut back to the last whole row). */
#ifndef RN_RUN_H
#define RN_RUN_H

#include <signal.h>
#include <stdio.h>
#include <sys/types.h>

#include "bg_api.h"
#include "bg_dae.h"
#include "bg_modes.h"
#include "rn_errest.h"

/* paths: the output folder's name is at most RN_OUT_MAX characters, so that its files' names
 * fit */
#define RN_PATH_SIZE 4096
#define RN_OUT_MAX (RN_PATH_SIZE - 64)

enum { RN_EXIT_OK = 0, RN_EXIT_RUN = 1, RN_EXIT_USAGE = 2 };

typedef struct rn_run rn_run;
/* Lines a program adds to status.txt or solver_stats.txt. */
typedef void (*rn_lines_fn)(const rn_run *r, FILE *f);

/* --error-estimate [K] of a run (rn_estimate.c): on and factor set by the program after rn_init
 * (before the run, so that status.txt says "unavailable" when the run fails before the
 * companion starts); the rest by rn_estimate_open. */
typedef struct rn_estimate {
    int on;                   /* asked for */
    double factor;            /* K, in (1, RN_ERREST_MAX_FACTOR] */
    const char *const *names; /* the row's columns (names[0]: t, never compared) */
    int ncols;
    int (*ranked)(const char *name); /* NULL, or 0 for a column the summary passes over */
    rn_errest *e;                    /* the companion; NULL when off or not started */
    char note[BG_MESSAGE_SIZE + 64]; /* why the estimate is unavailable */
} rn_estimate;

struct rn_run {
    /* set by the program before rn_prepare_folder */
    const char *program;  /* "crane": messages, the name the folder-in-use check looks for */
    const char *subject;  /* "scene", "model": the line of status.txt and solver_stats.txt */
    const char *name;     /* the scene's or model's name */
    const char *path;     /* and its file */
    double t_end;         /* of the run (status.txt) */
    rn_lines_fn status_lines; /* NULL: none */
    void *owner;              /* the program's own run, for its hooks */
    char outdir[RN_PATH_SIZE];
    char command[4096]; /* the command line, quoted as for the shell (rn_format_command) */
    char started[64];   /* local start time */
    dae_solver *s;      /* the solver (its steps in status.txt; freed by the program) */
    /* results.csv (rn_csv.c): rows are formatted into csv_buf and written whole (write(2)) when
     * it is full or a second has passed since the last write; a write that fails is cut back to
     * the last whole row (ftruncate), so that the file holds whole rows at every moment */
    int csv_fd;
    char *csv_buf;
    size_t csv_len, csv_cap;
    off_t csv_size;       /* bytes on disk */
    double csv_written;   /* wall time of the last write */
    int csv_ncols;        /* columns, t included */
    long rows, rows_disk; /* rows formatted; rows on disk */
    double t_row, t_disk; /* time of the last row formatted; on disk */
    long nout;            /* output times after t = 0 */
    double t, t_start, wall0; /* t: how far the integration got */
    const char *status;       /* "running", "completed", "interrupted", "failed" */
    int sig;                  /* the signal that interrupted the run */
    char reason[2 * BG_MESSAGE_SIZE + 512];
    rn_estimate est; /* --error-estimate (rn_estimate.c) */
};

/* Clears r and sets what every run starts with (status "running", the wall clock, no files). */
void rn_init(rn_run *r, const char *program, const char *subject);

/* --------------------------------------------------------------- rn_status.c ---- */

/* Phases: RN_PHASE_SETUP, a signal ends the program at once (long library calls that cannot be
 * stopped); RN_PHASE_LOOP, the first signal stops the integration between two steps and a
 * second one ends the program at once; RN_PHASE_OTHER, the program ends the run in order. */
enum { RN_PHASE_OTHER = 0, RN_PHASE_SETUP = 1, RN_PHASE_LOOP = 2 };

/* The handler for SIGINT, SIGTERM and SIGHUP ("program: SIGTERM received: stopped at once" on
 * stderr when it ends the program), and SIGPIPE ignored. program: at most 31 characters. */
void rn_signals_install(const char *program);
/* The first signal received (0: none), and the flag itself (rn_errest_spec.stop,
 * pu_gnuplot_job.stop). */
int rn_signal(void);
const volatile sig_atomic_t *rn_signal_flag(void);
const char *rn_signal_name(int sig);
/* Enters a phase (RN_PHASE_SETUP: status.txt says "interrupted while what" if a signal comes;
 * one that came just before ends the program now). */
void rn_set_phase(rn_run *r, int phase, const char *what);
int rn_phase(void);
/* status.txt written by the handler from now on (ready 1) or not (0); the paths are r's. */
void rn_status_ready(const rn_run *r, int ready);
/* The status.txt the handler writes on a second signal while integrating, and after the
 * integration. */
void rn_arm_loop(rn_run *r);
void rn_arm_finishing(rn_run *r);
/* status.txt from r->status and r->reason (final: with the end), atomically; on a full disk
 * (ENOSPC, EDQUOT: no room for the temporary copy) rewritten in place, truncated first so that
 * its own blocks take the new text. 0, or RN_EXIT_RUN. */
int rn_write_status(rn_run *r, int final);

/* Records a failure and says it on stderr ("program: what: msg"); the first failure's reason
 * leads. Returns RN_EXIT_RUN. */
int rn_fail_run(rn_run *r, const char *what, const char *msg);
int rn_write_failed(rn_run *r, const char *path, int e);
/* Writes len bytes to path through path.tmp (write, fsync, close, rename). 0, or -1 with
 * errno. */
int rn_save_atomic(const char *path, const char *text, size_t len);
/* Writes DIR/name atomically from what print prints into memory (print: 0, or -1). 0, or
 * RN_EXIT_RUN. */
typedef int (*rn_print_fn)(rn_run *r, FILE *f, const void *ctx);
int rn_save_file(rn_run *r, const char *name, rn_print_fn print, const void *ctx);
/* DIR/name (rn_set_outdir has checked that the folder's name leaves room). */
void rn_path_in(const rn_run *r, const char *name, char *buf, size_t size);
double rn_wall_now(void);
void rn_local_time(char *buf, size_t size);

/* The command line into r->command, quoted for the shell where needed, control characters as
 * '?', cut at the buffer's end with "...". */
void rn_format_command(rn_run *r, int argc, char **argv);
/* r->outdir: out, or results/<name> when out is NULL, without trailing slashes. 0, or
 * RN_EXIT_USAGE when the name is too long (said on stderr). */
int rn_set_outdir(rn_run *r, const char *out);
/* Makes the output folder ready and the run started: a signal already received ends the program
 * (nothing written: 128 + N), the folder created, refused when its status.txt names this program
 * still running there, status.txt "running" written (with r->command and r->started), the
 * handler armed (RN_PHASE_SETUP "preparing the output folder"), then the files named in files
 * (NULL-terminated; their .tmp and .signal.tmp too) left by an earlier run removed. 0, or the
 * exit status (RN_EXIT_RUN; r->status "failed" once status.txt exists). */
int rn_prepare_folder(rn_run *r, const char *const *files);
/* The exit status of a run that ended: 0 completed, 128 + N interrupted, else usage_error ?
 * RN_EXIT_USAGE : RN_EXIT_RUN. */
int rn_exit_status(const rn_run *r, int usage_error);

/* ------------------------------------------------------------------ rn_fmt.c ---- */

/* x as snprintf(buf, RN_FMT_SIZE, "%.12g", x) writes it, the same text, several times faster
 * (rn_fmt.c); buf holds at least RN_FMT_SIZE characters. The length. */
#define RN_FMT_SIZE 32
int rn_fmt_g12(char *buf, double x);

/* ------------------------------------------------------------------ rn_csv.c ---- */

/* Opens DIR/results.csv with its header, the ncols names (t first; buffered). 0, or the failure
 * (RN_EXIT_RUN). */
int rn_csv_open(rn_run *r, const char *const *names, int ncols);
/* One row: t, then out[1 .. ncols - 1] (out[0] is not written: t's place). Buffered; written
 * when the buffer is full or a second has passed. 0, or the failure of a write. */
int rn_csv_row(rn_run *r, double t, const double *out);
/* Writes the rows formatted so far. 0, or the failure (the file cut back to its last whole
 * row). */
int rn_csv_flush(rn_run *r);
/* Writes the rest, makes it durable and closes. 0, or the failure. */
int rn_csv_close(rn_run *r);

/* ----------------------------------------------------------------- rn_loop.c ---- */

/* Creates r->s for problem p with options o, from y0, yp0 at t = 0, and finds consistent
 * initial values (RN_PHASE_SETUP "computing consistent initial values"; a warning of the solver
 * is said on stderr, not fatal). 0, or RN_EXIT_RUN (r->status failed). */
int rn_solver_start(rn_run *r, const dae_problem *p, const dae_options *o, const double *y0,
                    const double *yp0);

/* What the run loop needs of the program. out holds ncols values, out[0] t's place. */
enum { RN_LOOP_STOP = 1 };
typedef struct rn_loop_spec {
    double output_step, t_end; /* rows at k output_step (k < r->nout) and at t_end */
    int ncols;
    /* the outputs at (t, y, yp) into out[1 .. ncols - 1] (and out[0]): 0, or -1 with the
     * reason in msg (the run fails) */
    int (*outputs)(void *ctx, double t, const double *y, const double *yp, double *out,
                   char *msg, size_t size);
    /* optional: called for each row formatted (even when its write then failed): the
     * program's watches of the values (peaks) */
    void (*watch)(void *ctx, double t, const double *out);
    /* optional: called after each row written (t = 0 included; row k of r->nout): 0, or
     * RN_LOOP_STOP (a signal stopped a companion: the run ends interrupted after this row) */
    int (*row)(void *ctx, long k, double t, const double *y, const double *yp, const double *out);
    void *ctx;
    int progress; /* the progress line on stderr (a terminal, not --quiet) */
    /* optional: the unknowns outputs (and row) read of y and yp, nunknowns of them: the rows
     * after t = 0 then interpolate these alone (dae_set_output_unknowns); NULL: all */
    const int *unknowns;
    int nunknowns;
} rn_loop_spec;

/* The t = 0 row and the loop over the output times: r->s steps one step at a time up to each
 * (dae_step) with a look at the signal flag between two steps, the row interpolated in the last
 * step (the values dae_solve_to alone would give); after each row written the program's row
 * hook, then the error estimate's companion to the same time (rn_estimate_row: a signal that
 * stops it on its way ends the run interrupted after the row). results.csv must be open. Sets
 * r->status (completed, interrupted with the reason, failed). 0, 128 + N, or RN_EXIT_RUN. y, yp: n
 * values each, the state of the last row (sp->unknowns given: at those unknowns). */
int rn_loop(rn_run *r, const rn_loop_spec *sp, double *y, double *yp);
/* After the loop (or a failure before it): results.csv written whole and closed, the handler's
 * status.txt for what follows, and with --error-estimate error_estimate.csv (when results.csv
 * has been opened). 0, or RN_EXIT_RUN. */
int rn_loop_end(rn_run *r);

/* solver_stats.txt's text: the settings, how far the run got, the error estimate's lines,
 * dae_stats_line and the CSV block. */
typedef struct rn_stats_info {
    const dae_options *dopt;
    int nbk;
    const double *bk;
    double output_step;
    int nominal_scales;
    rn_lines_fn extra; /* NULL: none */
} rn_stats_info;
int rn_print_solver_stats(rn_run *r, FILE *f, const void *info);

/* modes.csv: index,frequency_hz,damping_ratio,kind,part,dominant; part(M, k) names the part of
 * the model a mode lives in (NULL: rn_mode_part_top, the top-level component under the model's
 * root with the largest share). */
typedef const char *(*rn_part_fn)(const dae_modes *M, int k, char *buf, size_t size);
int rn_modes_write(const dae_modes *M, rn_part_fn part, FILE *f);
/* The same with the kind "drift" for an elastic mode below drift_hz (0: none), a mode of the
 * constraints' invariants drifting rather than a motion (crane_static.h: crane_modes_drift). */
int rn_modes_write_drift(const dae_modes *M, rn_part_fn part, double drift_hz, FILE *f);
/* Mode k's kind as modes.csv names it: dae_mode_kind_name, or "drift" as above. */
const char *rn_mode_kind(const dae_modes *M, int k, double drift_hz);
const char *rn_mode_part_top(const dae_modes *M, int k, char *buf, size_t size);

/* ------------------------------------------------------------- rn_estimate.c ---- */

/* --error-estimate [K]: a companion run of the same problem at rtol / K, atol / K (rn_errest.h:
 * reintegration at a reduced tolerance), in lockstep with the run over its rows; per output
 * column the largest difference estimates the run's error. What the program gives it: */
typedef struct rn_estimate_spec {
    const dae_problem *p; /* the run's problem and options */
    const dae_options *o;
    const double *y0, *yp0;   /* its start at t = 0, before the consistent values */
    const char *const *names; /* the row's ncols columns, names[0] t's (kept, not copied:
                                 valid until the summary) */
    int ncols;
    rn_errest_out_fn out; /* the row's values at a state into out[0 .. ncols - 1] (out[0]
                             t's place), as the run's outputs give them */
    void *ctx;
    int (*ranked)(const char *name); /* NULL: every column may be the summary's largest */
} rn_estimate_spec;

/* With r->est.on: the companion started from the run's start (RN_PHASE_SETUP "starting the run
 * at the tighter tolerances"; the program sets the next phase). A companion that cannot start
 * makes the estimate unavailable (said on stderr), never the run fail. */
void rn_estimate_open(rn_run *r, const rn_estimate_spec *sp);
/* Row k at t with the run's values out: the companion advanced there and compared (rn_loop
 * calls it). RN_LOOP_STOP when a signal came first (k > 0), else 0 (a failure of the companion
 * is kept, said on stderr once, and the run goes on). */
int rn_estimate_row(rn_run *r, long k, double t, const double *out);
/* error_estimate.csv (available or not; rn_loop_end writes it). 0, or RN_EXIT_RUN. */
int rn_estimate_write(rn_run *r);
/* The estimate's lines of status.txt and of solver_stats.txt (their writers add them), and the
 * summary's line on stdout; nothing when it was not asked for. */
void rn_estimate_status_lines(const rn_run *r, FILE *f);
void rn_estimate_stats_lines(const rn_run *r, FILE *f);
void rn_estimate_summary(const rn_run *r);
/* The companion freed (before the problem it calls). */
void rn_estimate_free(rn_run *r);

#endif
