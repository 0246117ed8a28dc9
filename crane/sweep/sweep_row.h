/* One case of a sweep: how it ended and its summary figures, read from its folder (the crane's
 * status.txt, results.csv, solver_stats.txt; the sweep's case.txt), and its row of sweep.csv.
 *
 * Statuses of a case (the column status):
 *   completed    the crane reached t_end (exit 0, status.txt completed)
 *   failed       the crane ended the run with a failure (exit 1: the model, the solver or a
 *                write; the message is status.txt's reason), or could not be started (the
 *                case's folder is a file, ...); a case whose crane ended without a final
 *                status.txt on a full disk ("the disk is full") or by SIGXFSZ (the file size
 *                limit)
 *   invalid      the crane refused the case's scene (exit 2: e.g. an inconsistent scene made by
 *                the case's values; the message is the crane's)
 *   timeout      stopped at the sweep's per-case time limit (SIGTERM, SIGKILL 5 s later)
 *   crashed      ended by a signal it did not handle (SIGSEGV, SIGKILL from outside, ...) or
 *                ended without a final status.txt
 *   interrupted  stopped by a signal: to the sweep (which passes it on) or to the crane alone
 *   not_run      the sweep was stopped before the case started, or the case's folder is in
 *                use by a crane of an earlier sweep still running there (sweep_case_busy)
 * The figures read from results.csv are given for completed cases only (a partial run's peaks
 * would be read as the case's); steps, cpu_s, wall_s and t_reached for every case that ran. */
#ifndef SWEEP_ROW_H
#define SWEEP_ROW_H

#include <stddef.h>
#include <stdio.h>

#include "sweep_spec.h"

typedef enum sweep_status {
    SWEEP_COMPLETED,
    SWEEP_FAILED,
    SWEEP_INVALID,
    SWEEP_TIMEOUT,
    SWEEP_CRASHED,
    SWEEP_INTERRUPTED,
    SWEEP_NOT_RUN
} sweep_status;
const char *sweep_status_name(int status);

/* The summary quantities (the report key): name, unit, meaning, in this order. */
enum {
    SQ_OMEGA_ERR_MAX,   /* max |omega - omega_ref| */
    SQ_THETA_END,       /* theta at the last row */
    SQ_THETA_ERR_END,   /* theta_ref - theta at the last row */
    SQ_TIP_RADIUS_MEAN, /* mean distance of the tip from the slewing axis */
    SQ_DEFL_LUFF_MAX,   /* max |tip_defl_1| */
    SQ_DEFL_SIDE_MAX,   /* max |tip_defl_2| */
    SQ_P_HIGH_MAX,      /* max p_high */
    SQ_P_LOW_MAX,       /* max p_low */
    SQ_P_MIN,           /* min of p_high and p_low */
    SQ_ROPE_FORCE_MAX,  /* max rope_force */
    SQ_STEPS,           /* solver steps (solver_stats.txt) */
    SQ_CPU_S,           /* CPU time of the case's process, user + system */
    SQ_WALL_S,          /* wall time of the case */
    SWEEP_NQ
};
typedef struct sweep_quantity {
    const char *name, *unit, *meaning;
    int is_default; /* in the default report */
    int is_time;    /* differs between runs of the same case */
} sweep_quantity;
extern const sweep_quantity sweep_quantities[SWEEP_NQ];
/* Index of the quantity called name (case-insensitive), -1 if none. */
int sweep_quantity_index(const char *name);

#define SWEEP_MESSAGE_SIZE 512
/* A case's row; plain data (sent as bytes between MPI ranks of one build). */
typedef struct sweep_row {
    long index;
    int status;                       /* sweep_status */
    int exit_code;                    /* the crane's exit status, 128 + N for signal N, -1 none */
    double t_reached;                 /* s (NaN: unknown) */
    double q[SWEEP_NQ];               /* NaN: not available */
    double mq[SWEEP_MAX_REPORT];      /* a model sweep's FUNC(COLUMN) quantities (spec->mq) */
    char message[SWEEP_MESSAGE_SIZE]; /* one line */
} sweep_row;

/* How the sweep saw the crane's process end (sweep_proc.h). */
typedef struct sweep_outcome {
    int started; /* 0: the process could not be started (errno_start says why) */
    int errno_start;
    int wait_status;   /* from wait4 */
    int timed_out;     /* the time limit stopped it */
    int killed;        /* SIGKILL was needed (after SIGTERM) */
    int stopped_by;    /* the sweep passed this signal on (0: none) */
    double time_limit; /* s */
    double cpu_s, wall_s;
    long busy_pid; /* not started: an earlier sweep's crane (this pid) still runs in the folder */
    char why[384]; /* not started: why, when more than errno_start says (the folder's state) */
} sweep_outcome;

/* The reported quantity report[i] of a sweep: its name (sweep.csv's header), unit, the stem of
 * its picture's file (plot_<stem>.png) and its value in a row. */
const char *sweep_report_name(const sweep_spec *s, int i);
const char *sweep_report_unit(const sweep_spec *s, int i);
const char *sweep_report_stem(const sweep_spec *s, int i);
double sweep_report_value(const sweep_spec *s, const sweep_row *row, int i);

/* The row of case index of sweep s whose files are in dir, after the process ended as o (o
 * NULL: a case found completed by --resume: cpu_s and wall_s from case.txt). */
void sweep_row_read(const sweep_spec *s, sweep_row *row, long index, const char *dir,
                    const sweep_outcome *o);
/* A model sweep's quantities (s->mq) from results.csv in dir (sweep_model.c); NaN: none. */
void sweep_model_results(const sweep_spec *s, const char *dir, double *mq);
/* A row for a case that did not run. */
void sweep_row_not_run(sweep_row *row, long index, const char *why);

/* The header and a row of sweep.csv (one line each, ending in '\n'): case, the swept keys,
 * status, message, t_reached, the reported quantities. Returns the length, or -1 if size is
 * too small. */
int sweep_csv_header(const sweep_spec *s, char *buf, size_t size);
int sweep_csv_row(const sweep_spec *s, const sweep_row *row, char *buf, size_t size);

/* A file the sweep reads (status.txt, the log, results.csv, ...) opened for reading if it is a
 * regular file (not a device, FIFO or folder: /dev/zero never ends) of at most max bytes (0: any
 * size), without blocking; its size then in *size (the readers stop there: a file that grows
 * while read ends where it was). NULL with errno (EISDIR, EINVAL: not a regular file; EFBIG). */
FILE *sweep_open_regular(const char *path, long long max, long long *size);
#define SWEEP_TEXT_MAX (1LL << 20) /* status.txt, case.txt, solver_stats.txt: 1 MB at most */

/* The first line of the file's "key: value" line for key (e.g. "status"), or "" (0). */
int sweep_read_field(const char *path, const char *key, char *value, size_t size);
/* The numbers of a results.csv line into v (ncols of them; a field that is not a number: NaN):
 * how many fields the line has, up to ncols (fewer: not a whole row). */
int sweep_parse_row(const char *line, double *v, int ncols);

#endif
