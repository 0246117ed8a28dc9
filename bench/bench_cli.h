/* The bench's command line: a table of options (bench_cli.c) for progutil's parser (pu_cli.h),
 * each found by its name, fills a bench_cli; the help is generated from the same table. The lists given as text (problems,
 * solvers, tolerances, element counts) are then checked and resolved against the problem
 * collection and the solvers by bench_cli_resolve, with the defaults that depend on --quick.
 *
 * Messages: "bench: WHAT" on stderr followed by the usage, exit status 2 (a bad command line);
 * the help on stdout, exit status 0 (1 if the standard output cannot be written). */
#ifndef BG_BENCH_CLI_H
#define BG_BENCH_CLI_H

#include "bench_case.h"

/* The command line's limits: tolerances of a series, problems, element counts of the scaling
 * series, timed runs (--repeat), solvers. */
#define BENCH_MAXRTOL 16
#define BENCH_MAXPROB 32
#define BENCH_MAXSCALE 16
#define BENCH_MAXREP 64
#define BENCH_MAXSOLVERS 16

/* bench_cli_parse and bench_cli_resolve: go on with the run (any other value is the exit status
 * to end with, the messages said). */
#define BENCH_CLI_RUN (-1)

typedef struct bench_cli {
    /* as given, filled through the table; NULL, 0 or -1 where not given (bench_cli_resolve sets
     * the defaults of repeat, realtime_runs and horizon) */
    const char *problems_text;   /* --problems LIST|none */
    const char *solvers_text;    /* --solvers LIST */
    const char *rtols_text;      /* --rtols LIST */
    const char *scaling_text;    /* --scaling LIST|none */
    const char *full_rtols_text; /* --crane-full-rtols LIST */
    const char *out;       /* --out DIR, default results/bench */
    const char *scene_file, *stab_filter, *full_scene;
    int repeat;          /* --repeat K; 0: not given */
    int realtime_runs;   /* --crane-realtime K; -1: not given */
    double horizon;      /* --crane-horizon T; 0: not given */
    double newton_dgmax; /* --newton-dgmax G: the collection's problems (the crane: its scene) */
    int stability, quick, strict, crane_full, errest;
    double ida_klu_tol;  /* --ida-klu-pivot-tol T; 0: BENCH_IDA_KLU_TOL (bench_util.h) */
    int ida_scalar_atol; /* --ida-scalar-atol: IDA without the problems' nominal magnitudes */
    int ida_index2_h;    /* --ida-index2-h: IDA's index-2 weights times |h| (bench_ida_ewt) */
    int full_repeat;     /* --crane-full-repeat K: runs of each solver in the series (default 1) */
    int full_max_order;  /* --crane-full-max-order K: our BDF runs' largest order (0: 5) */
    int ida_newton_diag; /* --ida-newton-diag: where IDA's Newton corrections sit (--crane-full) */
    int child; /* --realtime-child: internal, one real-time run (bench_realtime.h) */

    /* resolved by bench_cli_resolve: the lists, the defaults */
    const char *pnames[BENCH_MAXPROB]; /* the problems, "crane" among them */
    int np;
    const solver_def *sols[BENCH_MAXSOLVERS];
    const char *solnames[BENCH_MAXSOLVERS];
    int ns;
    double rtols[BENCH_MAXRTOL];
    int nr;
    int scale[BENCH_MAXSCALE]; /* the scaling series' boom element counts */
    int nscale;
    double full_rtols[BENCH_MAXRTOL]; /* --crane-full's tolerances */
    int full_nr;
    int realtime_asked; /* --crane-realtime K > 0 given: the real-time runs without the crane */
    int want_crane;     /* the crane among the problems */
} bench_cli;

/* Fills o from argv (every option found by its name in the table; a value checked against its
 * kind and range as it comes, in the order given). BENCH_CLI_RUN, or the exit status: 0 after
 * --help, 1 if the help could not be written, 2 for a bad command line. */
int bench_cli_parse(bench_cli *o, int argc, char **argv);

/* Checks and resolves the lists given as text (problems, solvers, tolerances, element counts,
 * --crane-full's tolerances; the text is split in place) and sets the defaults (--quick's among
 * them). BENCH_CLI_RUN, or 2 (said). */
int bench_cli_resolve(bench_cli *o);

/* Says "bench: bad" and the usage on stderr; returns 2, the exit status of a bad command line. */
int bench_cli_usage(const char *bad);

#endif
