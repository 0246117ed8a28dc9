/* The bench's command line (bench_cli.h): its table of options for progutil's table-driven
 * parser (pu_cli.h), the help generated from it, and the resolution of the lists.
 *
 * Method: every argument is looked up by name (or alias) in the table, never by its place in it;
 * an entry says the kind of its value, the field of bench_cli it fills (PU_CLI_AT), the range of
 * a number with the bench's own message for a value out of it (.bad), and its help. Reordering
 * the table reorders the help only. --crane-full-scene and --crane-full-rtols imply --crane-full
 * (their .seen is its field); --out's length is checked by a take callback (never cut: the
 * folder's name must fit the paths built in it). */
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_cli.h"
#include "bench_util.h"
#include "problems.h"
#include "pu_cli.h"

#define STR_(x) #x
#define STR(x) STR_(x)

#define AT(field) PU_CLI_AT(bench_cli, field)

/* --out DIR: at most BENCH_OUT_MAX characters (data: what the value is, for the message). */
static int take_out(const pu_cli_option *o, const char *value, void *base, char *msg, size_t size)
{
    if (strlen(value) > BENCH_OUT_MAX) {
        snprintf(msg, size, "%s: %s has %zu characters, more than the %d allowed", o->name,
                 (const char *)o->data, strlen(value), (int)BENCH_OUT_MAX);
        return -1;
    }
    ((bench_cli *)base)->out = value;
    return 0;
}

/* In the order of the usage line. */
static const pu_cli_option options[] = {
    {.name = "--problems", .kind = PU_CLI_STRING, .arg = "LIST|none", .at = AT(problems_text),
     .help = "the problems, comma-separated (default: all); none: no work-precision runs (and, "
             "unless asked for, no crane scaling or real-time runs)"},
    {.name = "--solvers", .kind = PU_CLI_STRING, .arg = "LIST", .at = AT(solvers_text),
     .help = "the solvers, comma-separated (default: all)"},
    {.name = "--rtols", .kind = PU_CLI_STRING, .arg = "LIST", .at = AT(rtols_text),
     .help = "the tolerances, numbers in (0, 1), comma-separated (default 1e-4 .. 1e-10; "
             "--quick: 1e-4, 1e-7)"},
    {.name = "--repeat", .kind = PU_CLI_INT, .arg = "K", .at = AT(repeat), .min = 1,
     .max = BENCH_MAXREP, .bad = "%s takes a whole number from 1 to " STR(BENCH_MAXREP) ", not '%s'",
     .help = "timed runs of each problem, solver and tolerance (default 3; --quick 1); takes a "
             "whole number from 1 to " STR(BENCH_MAXREP)},
    {.name = "--stability", .kind = PU_CLI_FLAG, .at = AT(stability),
     .help = "the stability suite of stiff and extreme cases (stability.csv)"},
    {.name = "--quick", .kind = PU_CLI_FLAG, .at = AT(quick),
     .help = "a short run (fewer tolerances, runs and elements, a shorter crane horizon, no "
             "real-time runs) with the error estimate"},
    {.name = "--out", .kind = PU_CLI_CALL, .arg = "DIR", .take = take_out,
     .data = "the folder's name",
     .help = "the output folder, created with its parents (default results/bench)"},
    {.name = "--crane-horizon", .kind = PU_CLI_DOUBLE, .arg = "T", .at = AT(horizon), .min = 1e-6,
     .max = 1e4, .bad = "%s takes a time in s in [1e-6, 1e4], not '%s'",
     .help = "the crane's horizon in seconds (default 1; --quick 0.1); takes a time in s in "
             "[1e-6, 1e4]"},
    {.name = "--crane-realtime", .kind = PU_CLI_INT, .arg = "K", .at = AT(realtime_runs),
     .min = 0, .max = 99, .bad = "%s takes a number of runs 0..99, not '%s'",
     .help = "runs of each scene over its 20 s, paper (or --crane-scene) and paper-undamped.ini, "
             "for realtime.csv with the mesh series over 1 s (default 5; --quick 0); takes a "
             "number of runs 0..99"},
    {.name = "--scaling", .kind = PU_CLI_STRING, .arg = "LIST|none", .at = AT(scaling_text),
     .help = "boom element counts 1..512 (scaling.csv and realtime.csv's mesh series; default 8, "
             "16, .., 512; --quick 8 .. 64)"},
    {.name = "--crane-scene", .kind = PU_CLI_STRING, .arg = "FILE", .at = AT(scene_file),
     .help = "the crane's scene (default: the paper scene)"},
    {.name = "--stability-filter", .kind = PU_CLI_STRING, .arg = "TEXT", .at = AT(stab_filter),
     .help = "the stability cases whose name contains TEXT"},
    {.name = "--strict", .kind = PU_CLI_FLAG, .at = AT(strict),
     .help = "exit status 1 also when a run of ours or of the crane failed or a stability case "
             "ended wrong, at its time limit or without its set-up"},
    {.name = "--crane-full", .kind = PU_CLI_FLAG, .at = AT(crane_full),
     .help = "paper-undamped.ini and paper.ini over 20 s, ours and IDA at rtol 1e-4..1e-9 "
             "(--crane-full-rtols) against ours at 1e-10 (crane_wp.csv, crane_wp_paper.csv)"},
    {.name = "--crane-full-scene", .kind = PU_CLI_STRING, .arg = "FILE", .at = AT(full_scene),
     .seen = AT(crane_full), .help = "the one scene of --crane-full (implies it)"},
    {.name = "--crane-full-rtols", .kind = PU_CLI_STRING, .arg = "LIST",
     .at = AT(full_rtols_text), .seen = AT(crane_full),
     .help = "the tolerances of --crane-full, numbers in (0, 1) (implies it)"},
    {.name = "--crane-full-repeat", .kind = PU_CLI_INT, .arg = "K", .at = AT(full_repeat),
     .min = 1, .max = 99, .bad = "%s takes a whole number from 1 to 99, not '%s'",
     .help = "runs of each solver and tolerance in --crane-full, the CPU time their median "
             "(default 1); takes a whole number from 1 to 99"},
    {.name = "--crane-full-max-order", .kind = PU_CLI_INT, .arg = "K", .at = AT(full_max_order),
     .min = 1, .max = 5, .bad = "%s takes a whole number from 1 to 5, not '%s'",
     .seen = AT(crane_full),
     .help = "the largest BDF order of bgdae-klu's runs in --crane-full (implies it; the "
             "reference's stays 5, MEBDF's its own); takes a whole number from 1 to 5"},
    {.name = "--ida-klu-pivot-tol", .kind = PU_CLI_DOUBLE, .arg = "T", .at = AT(ida_klu_tol),
     .min = 1e-6, .max = 1, .bad = "%s takes a number in [1e-6, 1], not '%s'",
     .help = "KLU's pivot tolerance in IDA-KLU (default 1: partial pivoting; 0.001, KLU's "
             "default, was the bench's setting before); takes a number in [1e-6, 1]"},
    {.name = "--ida-scalar-atol", .kind = PU_CLI_FLAG, .at = AT(ida_scalar_atol),
     .help = "IDA gets the scalar atol also where the problem declares nominal magnitudes (the "
             "bench's setting before; default: atol times each unknown's nominal magnitude, as "
             "ours)"},
    {.name = "--ida-index2-h", .kind = PU_CLI_FLAG, .at = AT(ida_index2_h),
     .help = "IDA's weights of the index-2 unknowns times |h| (IDAWFtolerances; ours' "
             "newton_index2_scale_h)"},
    {.name = "--ida-newton-diag", .kind = PU_CLI_FLAG, .at = AT(ida_newton_diag),
     .help = "--crane-full: each IDA run's Newton corrections weighed by kind of unknown, in the "
             "report (slows IDA: not for timing)"},
    {.name = "--newton-dgmax", .kind = PU_CLI_DOUBLE, .arg = "G", .at = AT(newton_dgmax),
     .min = 0, .max = 0.999, .bad = "%s takes a number in [0, 1), not '%s'",
     .help = "options.newton_dgmax of ours on the collection (default 0; the crane runs as its "
             "scene says); takes a number in [0, 1)"},
    {.name = "--error-estimate", .kind = PU_CLI_FLAG, .at = AT(errest),
     .help = "crane --error-estimate's estimate against the true error (--quick: always, on its "
             "tolerances)"},
    {.name = "--help", .alias = "-h", .kind = PU_CLI_STOP, .help = "this help (also -h)"},
    /* internal: one real-time run in a child process (bench_realtime.h) */
    {.name = "--realtime-child", .kind = PU_CLI_FLAG, .at = AT(child), .hidden = 1},
};

#define NOPT ((int)(sizeof options / sizeof options[0]))

/* ------------------------------------------------------------------ the help ---- */

/* The help: the usage line of every option, the solvers and problems (the collection's names),
 * the options. Allocated (free()); NULL when out of memory. */
static char *help_text(void)
{
    char *intro = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&intro, &len);
    if (!f) return NULL;
    fprintf(f, "solvers:");
    for (int s = 0; s < bench_nsolvers; s++)
        fprintf(f, " %s", bench_solvers[s].name);
    fprintf(f, "\nproblems:");
    for (int i = 0; i < bp_count(); i++)
        fprintf(f, " %s", bp_get(i)->name);
    for (int i = 0; i < bp_testset_count(); i++)
        fprintf(f, " %s", bp_testset_get(i)->name);
    for (int i = 0; i < bp_osc_count(); i++)
        fprintf(f, " %s", bp_osc_get(i)->name);
    fprintf(f, " crane\n");
    if (fclose(f) != 0) {
        free(intro);
        return NULL;
    }
    const pu_cli cli = {.program = "bench",
                        .intro = intro,
                        .options_title = "options:",
                        .epilogue = "see docs/bench.md and the header of bench/bench.c\n",
                        .options = options,
                        .noptions = NOPT,
                        .column = 28,
                        .width = 80};
    char *help = pu_cli_help(&cli);
    free(intro);
    return help;
}

int bench_cli_usage(const char *bad)
{
    fprintf(stderr, "bench: %s\n", bad);
    char *help = help_text();
    if (help) fputs(help, stderr);
    free(help);
    return 2;
}

/* ------------------------------------------------------------------ parsing ---- */

/* A number in [lo, hi] from the whole of s; 0 if it is one. */
static int parse_num(const char *s, double lo, double hi, double *v)
{
    char *end;
    errno = 0;
    *v = strtod(s, &end);
    return *s && !*end && errno == 0 && isfinite(*v) && *v >= lo && *v <= hi ? 0 : -1;
}

static int parse_int(const char *s, int lo, int hi, int *v)
{
    char *end;
    errno = 0;
    long x = strtol(s, &end, 10);
    if (!*s || *end || errno || x < lo || x > hi) return -1;
    *v = (int)x;
    return 0;
}

int bench_cli_parse(bench_cli *c, int argc, char **argv)
{
    memset(c, 0, sizeof *c);
    c->out = "results/bench";
    c->realtime_runs = -1;
    const pu_cli cli = {.program = "bench", .options = options, .noptions = NOPT};
    const pu_cli_option *stopped;
    char m[512];
    int r = pu_cli_parse(&cli, argc, argv, c, &stopped, m, sizeof m);
    if (r == PU_CLI_ERROR) return bench_cli_usage(m);
    if (r == PU_CLI_STOPPED) { /* --help */
        char *help = help_text();
        if (!help) {
            fprintf(stderr, "bench: out of memory\n");
            return 1;
        }
        fputs(help, stdout);
        free(help);
        if (fflush(stdout) != 0 || ferror(stdout)) {
            fprintf(stderr, "bench: cannot write the standard output: %s\n", strerror(errno));
            return 1;
        }
        return 0;
    }
    return BENCH_CLI_RUN;
}

/* ---------------------------------------------------------------- resolving ---- */

/* Splits a comma-separated list in place (argv's own text, which is writable); the number of
 * items, or -1 if more than max. */
static int split_list(const char *s, char **items, int max)
{
    int n = 0;
    for (char *tok = strtok((char *)s, ","); tok; tok = strtok(NULL, ",")) {
        if (n == max) return -1;
        items[n++] = tok;
    }
    return n;
}

/* Tolerances from list (of option name) into rtols: each in (0, 1), at least one, at most
 * BENCH_MAXRTOL. Their number, or -1 with the message in m. */
static int tolerance_list(const char *name, const char *list, double *rtols, char *m, size_t msz)
{
    char *items[BENCH_MAXRTOL];
    int k = split_list(list, items, BENCH_MAXRTOL), nr = 0;
    if (k < 0) {
        snprintf(m, msz, "%s: too many tolerances (at most %d)", name, BENCH_MAXRTOL);
        return -1;
    }
    for (int i = 0; i < k; i++) {
        if (parse_num(items[i], 1e-300, 1, &rtols[nr]) != 0 || rtols[nr] >= 1) {
            snprintf(m, msz, "%s: '%s' is not a number in (0, 1)", name, items[i]);
            return -1;
        }
        nr++;
    }
    if (nr == 0) {
        snprintf(m, msz, "%s: empty list", name);
        return -1;
    }
    return nr;
}

/* The problems: --problems (checked: known, not twice), none, or all with a reference. */
static int resolve_problems(bench_cli *c)
{
    char *items[BENCH_MAXPROB], m[512];
    c->np = 0;
    if (c->problems_text && !strcmp(c->problems_text, "none")) {
        /* no work-precision runs */
    } else if (c->problems_text) {
        int k = split_list(c->problems_text, items, BENCH_MAXPROB);
        if (k < 0) return bench_cli_usage("--problems: too many names");
        for (int i = 0; i < k; i++) {
            if (strcmp(items[i], "crane") && !bp_find(items[i])) {
                snprintf(m, sizeof m, "unknown problem '%s'", items[i]);
                return bench_cli_usage(m);
            }
            for (int j = 0; j < c->np; j++)
                if (!strcmp(c->pnames[j], items[i])) {
                    snprintf(m, sizeof m, "problem '%s' given twice", items[i]);
                    return bench_cli_usage(m);
                }
            c->pnames[c->np++] = items[i];
        }
        if (c->np == 0) return bench_cli_usage("--problems: empty list");
    } else {
        for (int i = 0; i < bp_count() && c->np < BENCH_MAXPROB; i++)
            if (bp_get(i)->yref || bp_get(i)->exact) c->pnames[c->np++] = bp_get(i)->name;
        for (int i = 0; i < bp_testset_count() && c->np < BENCH_MAXPROB; i++)
            c->pnames[c->np++] = bp_testset_get(i)->name;
        for (int i = 0; i < bp_osc_count() && c->np < BENCH_MAXPROB; i++)
            c->pnames[c->np++] = bp_osc_get(i)->name;
        c->pnames[c->np++] = "crane";
    }
    c->want_crane = 0;
    for (int q = 0; q < c->np; q++)
        c->want_crane |= !strcmp(c->pnames[q], "crane");
    return BENCH_CLI_RUN;
}

/* The solvers: --solvers (checked: known, not twice) or all (without IDA built in: ours). */
static int resolve_solvers(bench_cli *c)
{
    char *items[BENCH_MAXSOLVERS], m[512];
    c->ns = 0;
    if (c->solvers_text) {
        int k = split_list(c->solvers_text, items, BENCH_MAXSOLVERS);
        if (k < 0) return bench_cli_usage("--solvers: too many names");
        for (int i = 0; i < k; i++) {
            const solver_def *sd = bench_solver_find(items[i]);
            if (!sd) {
                snprintf(m, sizeof m, "unknown solver '%s'", items[i]);
                return bench_cli_usage(m);
            }
            for (int j = 0; j < c->ns; j++)
                if (c->sols[j] == sd) {
                    snprintf(m, sizeof m, "solver '%s' given twice", items[i]);
                    return bench_cli_usage(m);
                }
            c->sols[c->ns++] = sd;
        }
        if (c->ns == 0) return bench_cli_usage("--solvers: empty list");
    } else
        for (int s = 0; s < bench_nsolvers; s++)
            c->sols[c->ns++] = &bench_solvers[s];
#ifndef BENCH_HAVE_IDA
    if (!c->solvers_text) { /* without IDA: ours only */
        int k = 0;
        for (int s = 0; s < c->ns; s++)
            if (!c->sols[s]->ida) c->sols[k++] = c->sols[s];
        c->ns = k;
    }
    for (int s = 0; s < c->ns; s++)
        if (c->sols[s]->ida) {
            fprintf(stderr, "bench: built without SUNDIALS IDA; solver '%s' is not available\n",
                    c->sols[s]->name);
            return 2;
        }
#endif
    for (int s = 0; s < c->ns; s++)
        c->solnames[s] = c->sols[s]->name;
    return BENCH_CLI_RUN;
}

/* The scaling series' element counts: --scaling (none: no series) or 8, 16, .. 512 (--quick:
 * .. 64). */
static int resolve_scaling(bench_cli *c)
{
    char *items[BENCH_MAXSCALE], m[512];
    c->nscale = 0;
    if (c->scaling_text) {
        if (strcmp(c->scaling_text, "none")) {
            int k = split_list(c->scaling_text, items, BENCH_MAXSCALE);
            if (k < 0) return bench_cli_usage("--scaling: too many element counts (at most 16)");
            for (int i = 0; i < k; i++)
                if (parse_int(items[i], 1, 512, &c->scale[c->nscale++]) != 0) {
                    snprintf(m, sizeof m, "--scaling: '%s' is not an element count 1..512",
                             items[i]);
                    return bench_cli_usage(m);
                }
        }
    } else {
        for (int e = 8; e <= (c->quick ? 64 : 512); e *= 2)
            c->scale[c->nscale++] = e;
    }
    return BENCH_CLI_RUN;
}

int bench_cli_resolve(bench_cli *c)
{
    char m[512];
    int rc;
    if ((rc = resolve_problems(c)) != BENCH_CLI_RUN) return rc;
    if ((rc = resolve_solvers(c)) != BENCH_CLI_RUN) return rc;
    /* tolerances */
    c->nr = 0;
    if (c->rtols_text) {
        c->nr = tolerance_list("--rtols", c->rtols_text, c->rtols, m, sizeof m);
        if (c->nr < 0) return bench_cli_usage(m);
    } else if (c->quick) {
        c->rtols[c->nr++] = 1e-4;
        c->rtols[c->nr++] = 1e-7;
    } else
        for (int e = 4; e <= 10; e++)
            c->rtols[c->nr++] = pow(10.0, -e);
    /* the defaults that depend on --quick */
    if (c->repeat == 0) c->repeat = c->quick ? 1 : 3;
    if (c->full_repeat == 0) c->full_repeat = 1;
    if (c->horizon <= 0) c->horizon = c->quick ? 0.1 : 1.0;
    c->realtime_asked = c->realtime_runs > 0;
    if (c->realtime_runs < 0) c->realtime_runs = c->quick ? 0 : 5;
    if ((rc = resolve_scaling(c)) != BENCH_CLI_RUN) return rc;
    /* the crane over its full horizon against IDA (--crane-full): the tolerances */
    c->full_nr = 0;
    if (c->crane_full) {
        if (c->full_rtols_text) {
            c->full_nr = tolerance_list("--crane-full-rtols", c->full_rtols_text, c->full_rtols, m,
                                        sizeof m);
            if (c->full_nr < 0) return bench_cli_usage(m);
        } else
            for (int e = 4; e <= 9; e++)
                c->full_rtols[c->full_nr++] = pow(10.0, -e);
    }
    return BENCH_CLI_RUN;
}
