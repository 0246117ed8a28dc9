/* A case's crane process: started with posix_spawn (its standard output and error into the
 * case's crane.log, standard input from /dev/null, the default signal dispositions and an empty
 * signal mask), watched without blocking (wait4 with WNOHANG: its exit status and its CPU time),
 * stopped at the time limit (SIGTERM, then SIGKILL SWEEP_KILL_GRACE s later) or when the sweep is
 * stopped. posix_spawn (vfork-like in glibc) rather than fork: an MPI process should not copy
 * itself. */
#ifndef SWEEP_PROC_H
#define SWEEP_PROC_H

#include <stddef.h>
#include <sys/types.h>

#include "sweep_row.h"

#define SWEEP_KILL_GRACE 5.0 /* s between SIGTERM and SIGKILL */

typedef struct sweep_proc {
    pid_t pid; /* 0: the slot is free */
    long index;
    double t0, term_at; /* start; when SIGTERM was sent (0: not yet) */
    double time_limit;  /* s, 0: none */
    sweep_outcome out;
    char dir[SWEEP_DIR_SIZE]; /* the case's folder */
} sweep_proc;

double sweep_now(void); /* monotonic clock, s */

/* Starts exe with argv (argv[0] first, NULL last) for case index in folder dir (which exists),
 * its output into dir/log (crane.log, bgsim.log). 0, or -1 with p->out.started = 0 and
 * p->out.errno_start (p is then free: the case is over). */
int sweep_proc_start(sweep_proc *p, long index, const char *exe, char *const argv[],
                     const char *dir, const char *log, double time_limit);
/* Checks the process: its time limit, whether it ended. 1 when it has ended (p->out filled, p
 * free again), 0 while it runs. */
int sweep_proc_poll(sweep_proc *p);
/* The sweep was stopped by signal sig: SIGTERM to the process (the crane stops between two
 * solver steps and writes its status), or SIGKILL when hard (a second signal). */
void sweep_proc_stop(sweep_proc *p, int sig, int hard);

/* The program a case runs (name: crane or bgsim): given (--crane, --bgsim), next to this
 * program (/proc/self/exe), the build's (build, NULL if unknown); its path in out. 1 found; 0 not
 * found (tried: where it was looked for); -1 the given one is there but cannot be run (tried:
 * "PATH: why": "is a directory, not a program", "not executable (no execute permission)"). */
int sweep_find_program(const char *name, const char *given, const char *build, char *out,
                       size_t size, char *tried, size_t tsize);

#endif
