/* The engines of crane-sweep: the cases to run are handed to crane processes (sweep_proc.h),
 * each in its folder OUT/cases/NNNN/; each finished case makes one row (sweep_row.h), which the
 * process that keeps the rows (the only one locally, rank 0 under MPI) records and appends to
 * sweep.csv at once.
 *
 *   local  --jobs N processes at a time, started from one queue in case order.
 *   MPI    (sweep_mpi.c, built with MPI) rank 0 holds the queue and hands out one case at a time
 *          to each rank that asks (itself included), so that a long case holds up only its own
 *          rank; the ranks send their rows back to rank 0. Every rank runs its cases as crane
 *          processes of its own, --jobs at a time (default 1), in the shared output folder.
 *
 * A signal to the sweep (SIGINT, SIGTERM, SIGHUP; under MPI to any rank, which rank 0 passes on)
 * stops the start of new cases and passes SIGTERM on to the running ones (a second signal:
 * SIGKILL); they end as "interrupted" rows, the cases not started as "not_run" rows. */
#ifndef SWEEP_ENGINE_H
#define SWEEP_ENGINE_H

#include <signal.h>
#include <stddef.h>

#include "sweep_proc.h"
#include "sweep_row.h"
#include "sweep_spec.h"

#define SWEEP_MAX_JOBS 1024

/* the first signal received and how many (set by the handler in crane_sweep.c) */
extern volatile sig_atomic_t sweep_signal, sweep_signal_count;

typedef struct sweep_run {
    const sweep_spec *spec;
    char outdir[SWEEP_PATH_SIZE]; /* absolute */
    char crane[SWEEP_PATH_SIZE];  /* the program: crane, or bgsim for a model sweep */
    double time_limit;            /* s per case, 0: none */
    int jobs, quiet;
    int rank, size; /* MPI rank and size (0, 1 locally) */
    /* the keeper of the rows (rank 0) */
    sweep_row *rows; /* ncases */
    char *have;      /* ncases: the row is there */
    long ndone, nrun;
    long *queue; /* cases to run, in order */
    long nqueue;
    int csv_fd; /* sweep.csv (appended) */
    int write_failed;
    char write_msg[SWEEP_PATH_SIZE + 256];
    double t0;
} sweep_run;

/* The folder of case index: OUT/cases/NNNN (at least 4 digits). */
void sweep_case_dir(const sweep_run *r, long index, char *buf, size_t size);
/* Prepares the case's folder (created, the old status.txt, case.txt, results.csv,
 * solver_stats.txt and log removed, case.txt "running" written) and starts its crane process in
 * p. 0, or -1 when it could not be started (p->out says why; the case is over); a folder in
 * which a crane of an earlier sweep still runs (sweep_case_busy) is left alone
 * (p->out.busy_pid). */
int sweep_case_start(sweep_run *r, sweep_proc *p, long index);
/* The pid of a crane (or bgsim) still running in the case folder dir, left by an earlier sweep:
 * its status.txt says running with its pid, that process exists and has "--out dir" on its
 * command line (/proc/PID/cmdline; without /proc, its existence suffices). 0: none. */
long sweep_case_busy(const char *dir);
/* --resume of a model sweep: the completed case in dir ran the command it would run now (case.txt)
 * on the model file as it is now (model.yaml starts with its text) and has its results.csv. */
int sweep_model_case_done(const sweep_run *r, long index, const char *dir);
/* The row of the case whose process p has ended; case.txt final. */
void sweep_case_finish(sweep_run *r, const sweep_proc *p, sweep_row *row);
/* Keeps the row (rank 0) and appends it to sweep.csv; prints a line unless quiet. */
void sweep_record(sweep_run *r, const sweep_row *row, int from_rank);

/* The file at path replaced by data (pu_write_atomic). On a full disk (ENOSPC, EDQUOT) the
 * atomic copy, whose temporary pu_write_atomic removes, needs room the disk lacks: the file is
 * then rewritten in place, its old blocks freed first (O_TRUNC), and if that falls short too it is
 * cut back to its last whole line (no partial line left). 0, or -1 with errno. */
int sweep_write_file(const char *path, const char *data, size_t len);

/* The local engine: every case of the queue. */
void sweep_engine_local(sweep_run *r);
#ifdef CRANE_SWEEP_MPI
/* The MPI engine (every rank calls it; MPI initialised). */
void sweep_engine_mpi(sweep_run *r);
#endif

#endif
