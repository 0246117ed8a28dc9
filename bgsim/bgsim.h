/* bgsim's parts (private to the program: bgsim/bgsim.c and bgsim/bs_*.c, prefix bs_), on the
 * run machinery it shares with the crane program (runner/rn_run.h). bgsim.c has the program's
 * contract (files, signals, exit statuses); here:
 *
 *   bs_cli.c   the command line (options' table for pu_cli.h), --list-types, --describe,
 *              --list-unknowns
 *   bs_run.c   the dynamic run on rn_loop (with --error-estimate the runner's companion run,
 *              rn_estimate.c), --static, --modes, model_stats.txt, model.yaml, static.txt,
 *              equilibrium.csv, modes.csv and the summary
 *   bs_file.c  the run of a model file from its options to its exit status (bs_run_file)
 *
 * The three make the static library bgsim_run (bgsim/meson.build), which the crane program
 * links as well: with a model file SCENE it runs bs_run_file with its extras (the figures of
 * Fig. 5, summary lines: crane/program/cp_model.c), the same code path as bgsim's. */
#ifndef BGSIM_H
#define BGSIM_H

#include <stdio.h>

#include "bgr_model.h"
#include "mdl_model.h"
#include "pu_vtk.h"
#include "rn_run.h"

#ifndef BGSIM_VERSION
#define BGSIM_VERSION "unknown"
#endif

#define BS_MAX_SETS 64
/* output rows: at most --max-rows (default BS_DEFAULT_MAX_ROWS) */
#define BS_DEFAULT_MAX_ROWS 1000000LL
#define BS_MAX_MAX_ROWS 1000000000000LL

typedef struct bs_options {
    const char *model, *out;
    mdl_set sets[BS_MAX_SETS]; /* --set PATH=VALUE: path in set_paths, value argv's */
    char set_paths[BS_MAX_SETS][256];
    int nsets;
    double t_end, rtol, atol, output_step; /* the overrides, where given: */
    int has_t_end, has_rtol, has_atol, has_output_step;
    long long max_rows;
    int static_only, modes; /* --static, --modes [T] */
    double modes_t;
    int errest;           /* --error-estimate [K] (rn_run.h: rn_estimate) */
    double errest_factor; /* K */
    int quiet;
    int vtk, has_vtk_step; /* --vtk, --vtk-step DT */
    double vtk_step;
    int list_types, markdown, list_unknowns;
    const char *describe;
    int argc; /* the command line, for status.txt */
    char **argv;
} bs_options;

/* Returns -1 to go on (a run, or --list-unknowns with the model loaded), or an exit status
 * (help, version, --list-types, --describe: 0; a bad command line or an unknown type: 2, said
 * on stderr). */
int bs_parse_args(int argc, char **argv, bs_options *o);
/* --list-unknowns: every unknown of the model as the file names it ("rod1.body.x0"), its kind
 * and initial value. 0, or RN_EXIT_RUN. */
int bs_list_unknowns(mdl_model *mm, FILE *f);
/* An unknown's name as the model file writes it: the bgr name without the model's name,
 * '/' as '.'. */
const char *bs_unknown_name(const mdl_model *mm, int var, char *buf, size_t size);

typedef struct bs_run bs_run;

/* What a program adds to the run of a model file (the crane program: Fig. 5). Every field is
 * optional. */
typedef struct bs_extras {
    const char *const *files; /* more files removed from the folder at the start (NULL-ended) */
    const char *not_done;     /* appended to the reason when a signal came after the end */
    int (*finish)(bs_run *r, void *ctx); /* after a run that reached its end with no signal */
    void (*summary)(const bs_run *r, void *ctx); /* summary lines before the wall time's */
    void *ctx;
} bs_extras;

struct bs_run {
    rn_run rn; /* status.txt, results.csv, the folder, the solver (rn_run.h); rn.owner = this */
    const bs_options *o;
    mdl_model *mm;
    mdl_solver_settings solver; /* the file's, with the command line's overrides */
    char model_path[RN_PATH_SIZE];
    char model_name[256]; /* rn.name: a copy (a trim replaces the model) */
    int static_done;  /* the static start ran: */
    mdl_trim_report trim; /* its report */
    int have_final;
    double *final_out;  /* the last row (t, outputs) */
    const char **names; /* results.csv's columns (t, outputs; kept for the estimate's summary) */
    int nmodes;        /* --modes: the modes found */
    pu_vtk *vtk;       /* --vtk: the ParaView series (NULL when off or stopped) */
    mdl_geom geom;     /* its drawing, reused frame to frame */
    long vtk_every;    /* a frame every vtk_every output rows */
    char vtk_error[BG_MESSAGE_SIZE + 64]; /* why the series stopped ("" while it goes on) */
    const bs_extras *extras;              /* the program's (NULL: none) */
};

#define BS_RUN(rn) ((bs_run *)(rn)->owner)

/* Runs the model file o->model as bgsim does (bgsim.c has the contract): program names the
 * messages and status.txt ("bgsim", "crane"), argv goes into status.txt, x adds the program's
 * own (NULL: nothing). Returns the exit status. */
int bs_run_file(const char *program, const bs_options *o, int argc, char **argv,
                const bs_extras *x);

/* The run (dynamic, or --static / --modes). 0 or an exit status; r->rn.status says how it
 * ended. */
int bs_simulate(bs_run *r);
int bs_analyse(bs_run *r);
/* model.yaml and model_stats.txt. 0, or RN_EXIT_RUN. */
int bs_save_model(bs_run *r);
/* The summary on stdout. */
void bs_summary(const bs_run *r);

#endif
