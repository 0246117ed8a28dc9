/* The bench's report writer (bench/bench.c runs, this writes): work_precision.csv, the
 * work-precision figures wp_<problem>.dat / .png, steps_vs_tol.csv and report.md.
 *
 * report.md is written last, when every other file has been tried: its head (machine, load,
 * commit, targets and their verdicts, where the time goes where one is missed, the ratio table),
 * the files that could not be written, the sections written in memory while the runs went on
 * (mid: steps against tolerance, MEBDFI, the oscillatory guard), a section per problem with the
 * failures, then the rest (tail: real-time check, error estimate, scaling, stability, crane-full).
 * Every file goes through bench_file (bench_util.h): a failure is said, counted and the file
 * removed. */
#ifndef BG_BENCH_REPORT_H
#define BG_BENCH_REPORT_H

#include <stdio.h>

#include "bench_case.h"
#include "bench_realtime.h"
#include "bench_util.h"
#include "problems.h"

/* One run of the work-precision series: a case, a solver, a tolerance; its counters (r), the
 * median and minimum CPU time of its timed runs and its accuracy (sc: NAN where it failed or the
 * case has no reference). */
typedef struct bench_row {
    int ci; /* the case: an index into bench_results.cases */
    const solver_def *sd;
    double rtol, atol;
    run_out r;
    double cpu_min, cpu_med;
    bp_score sc;
} bench_row;

/* What the work-precision series measured, as the writers read it. */
typedef struct bench_results {
    bench_case **cases; /* the problems run, nc of them */
    int nc;
    const char **sol; /* the solvers' names, in the order of the command line, ns of them */
    int ns;
    const bench_row *rows; /* every run, n of them */
    int n;
    const double *rtols; /* the tolerances of the series, nr of them */
    int nr;
    double wall; /* wall time of the series, s */
    int repeat;  /* timed runs per row (K) */
} bench_results;

/* The report's head beyond the series: the load at the start and the end, the crane's scaling
 * slopes (with have_scaling), the real-time check (nrt scenes) and its mesh series. */
typedef struct bench_report_extras {
    char load_start[128], load_end[128];
    int have_scaling;
    double slope_n, slope_el;
    int nrt;
    bench_rt_scene rts[2];
    bench_rt_result rt[2];
    bench_mesh_result mesh;
} bench_report_extras;

/* A section of the report written in memory (open_memstream) while the runs go on, put into
 * report.md when it is written at the end. */
typedef struct bench_text {
    FILE *f; /* where to print; NULL once closed */
    char *buf;
    size_t len;
} bench_text;

/* Opens t. 0, or -1 (out of memory; bench_text_free is still to be called). */
int bench_text_open(bench_text *t);
/* Closes t (if open) and frees its text. */
void bench_text_free(bench_text *t);

/* The first line of /proc/loadavg (the load of the shared machine), or "unknown". */
void bench_load_average(char *buf, size_t sz);

/* work_precision.csv in dir: one line per row. */
void bench_report_csv(const char *dir, const bench_results *res);

/* wp_<problem>.dat for every case and, where gnuplot is installed, wp_<problem>.png drawn from
 * it (said on stderr when it is not). */
void bench_report_plots(const char *dir, const bench_results *res);

/* steps_vs_tol.csv in dir and the report's section on it, into f: "MORE STEPS" where a looser
 * tolerance took more than 5 % more steps than a tighter one. The number of flagged (problem,
 * solver) pairs. */
int bench_report_steps_vs_tol(const char *dir, FILE *f, const bench_results *res);

/* Writes report.md into rep (opened at the start, so that a folder that cannot take it fails
 * before the runs) and closes it: the head, the files not written, mid, the problems' sections,
 * tail. mid and tail are closed here (a failure to finish them counts as rep's, ENOMEM). */
void bench_report_write(bench_file *rep, const bench_results *res, const bench_report_extras *ex,
                        bench_text *mid, bench_text *tail);

#endif
