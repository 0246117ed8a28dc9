/* The bench's command line (bench_cli.h): a table of options, the parser that walks it, the help
 * generated from it, and the resolution of the lists.
 *
 * Method: every argument is looked up by name (or alias) in the table, never by its place in it;
 * an entry says the kind of its value, the field of bench_cli it fills (offsetof), the range of a
 * number, and its help. Reordering the table reorders the help only. The table is plain data, to
 * be carried over to a shared table-driven parser as it stands. */
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_cli.h"
#include "bench_util.h"
#include "problems.h"

#define STR_(x) #x
#define STR(x) STR_(x)

typedef enum opt_kind {
    OPT_FLAG, /* no value: the int field set to 1 */
    OPT_TEXT, /* a value kept as given (char *): a list, a name, a path; hi > 0: at most hi chars */
    OPT_INT,  /* a whole number in [lo, hi] (int) */
    OPT_NUM,  /* a finite number in [lo, hi] (double) */
    OPT_HELP, /* the help on the standard output, then the end */
} opt_kind;

typedef struct opt {
    const char *name;  /* "--repeat" */
    const char *alias; /* another name ("-h"), or NULL */
    opt_kind kind;
    const char *meta; /* the value's name in the help ("K"); NULL for a flag */
    size_t field;     /* offsetof(bench_cli, the field it fills); unused by OPT_HELP */
    double lo, hi;    /* OPT_INT, OPT_NUM: the range; OPT_TEXT: hi the longest value, 0 none */
    /* OPT_INT, OPT_NUM: what it takes, for the message "NAME takes WHAT, not 'VALUE'" and the
     * help; OPT_TEXT with a limit: what the value is, for "NAME: WHAT has N characters, ..." */
    const char *takes;
    const char *help; /* NULL: internal, not in the help */
} opt;

#define F(field) offsetof(bench_cli, field)

/* In the order of the usage line. */
static const opt options[] = {
    {"--problems", NULL, OPT_TEXT, "LIST|none", F(problems_text), 0, 0, NULL,
     "the problems, comma-separated (default: all); none: no work-precision runs (and, unless "
     "asked for, no crane scaling or real-time runs)"},
    {"--solvers", NULL, OPT_TEXT, "LIST", F(solvers_text), 0, 0, NULL,
     "the solvers, comma-separated (default: all)"},
    {"--rtols", NULL, OPT_TEXT, "LIST", F(rtols_text), 0, 0, NULL,
     "the tolerances, numbers in (0, 1), comma-separated (default 1e-4 .. 1e-10; --quick: 1e-4, "
     "1e-7)"},
    {"--repeat", NULL, OPT_INT, "K", F(repeat), 1, BENCH_MAXREP,
     "a whole number from 1 to " STR(BENCH_MAXREP),
     "timed runs of each problem, solver and tolerance (default 3; --quick 1)"},
    {"--stability", NULL, OPT_FLAG, NULL, F(stability), 0, 0, NULL,
     "the stability suite of stiff and extreme cases (stability.csv)"},
    {"--quick", NULL, OPT_FLAG, NULL, F(quick), 0, 0, NULL,
     "a short run (fewer tolerances, runs and elements, a shorter crane horizon, no real-time "
     "runs) with the error estimate"},
    {"--out", NULL, OPT_TEXT, "DIR", F(out), 0, BENCH_OUT_MAX, "the folder's name",
     "the output folder, created with its parents (default results/bench)"},
    {"--crane-horizon", NULL, OPT_NUM, "T", F(horizon), 1e-6, 1e4, "a time in s in [1e-6, 1e4]",
     "the crane's horizon in seconds (default 1; --quick 0.1)"},
    {"--crane-realtime", NULL, OPT_INT, "K", F(realtime_runs), 0, 99, "a number of runs 0..99",
     "runs of each scene over its 20 s, paper (or --crane-scene) and paper-undamped.ini, for "
     "realtime.csv with the mesh series over 1 s (default 5; --quick 0)"},
    {"--scaling", NULL, OPT_TEXT, "LIST|none", F(scaling_text), 0, 0, NULL,
     "boom element counts 1..512 (scaling.csv and realtime.csv's mesh series; default 8, 16, "
     ".., 512; --quick 8 .. 64)"},
    {"--crane-scene", NULL, OPT_TEXT, "FILE", F(scene_file), 0, 0, NULL,
     "the crane's scene (default: the paper scene)"},
    {"--stability-filter", NULL, OPT_TEXT, "TEXT", F(stab_filter), 0, 0, NULL,
     "the stability cases whose name contains TEXT"},
    {"--strict", NULL, OPT_FLAG, NULL, F(strict), 0, 0, NULL,
     "exit status 1 also when a run of ours or of the crane failed or a stability case ended "
     "wrong, at its time limit or without its set-up"},
    {"--crane-full", NULL, OPT_FLAG, NULL, F(crane_full), 0, 0, NULL,
     "paper-undamped.ini over 20 s, ours and IDA at rtol 1e-4..1e-9 (--crane-full-rtols) "
     "against ours at 1e-10 (crane_wp.csv)"},
    {"--crane-full-scene", NULL, OPT_TEXT, "FILE", F(full_scene), 0, 0, NULL,
     "the scene of --crane-full (implies it)"},
    {"--crane-full-rtols", NULL, OPT_TEXT, "LIST", F(full_rtols_text), 0, 0, NULL,
     "the tolerances of --crane-full, numbers in (0, 1) (implies it)"},
    {"--newton-dgmax", NULL, OPT_NUM, "G", F(newton_dgmax), 0, 0.999, "a number in [0, 1)",
     "options.newton_dgmax of ours on the collection (default 0; the crane runs as its scene "
     "says)"},
    {"--error-estimate", NULL, OPT_FLAG, NULL, F(errest), 0, 0, NULL,
     "crane --error-estimate's estimate against the true error (--quick: always, on its "
     "tolerances)"},
    {"--help", "-h", OPT_HELP, NULL, 0, 0, 0, NULL, "this help"},
    {"--realtime-child", NULL, OPT_FLAG, NULL, F(child), 0, 0, NULL, NULL},
};

#define NOPT ((int)(sizeof options / sizeof options[0]))

/* ------------------------------------------------------------------ the help ---- */

#define HELP_WIDTH 80
#define HELP_COL 28 /* where an option's help starts */

/* Prints text from column col (the cursor there) in words, wrapped before HELP_WIDTH onto lines
 * that start at column indent. Returns the column after it. */
static int print_wrapped(FILE *f, const char *text, int col, int indent)
{
    const char *p = text;
    while (*p) {
        size_t w = strcspn(p, " ");
        if (col > indent && col + 1 + (int)w > HELP_WIDTH) {
            fprintf(f, "\n%*s", indent, "");
            col = indent;
        } else if (col > indent) {
            fputc(' ', f);
            col++;
        }
        fprintf(f, "%.*s", (int)w, p);
        col += (int)w;
        p += w;
        while (*p == ' ')
            p++;
    }
    return col;
}

static void usage_text(FILE *f)
{
    static const char lead[] = "usage: bench";
    int col = fprintf(f, "%s", lead);
    for (int i = 0; i < NOPT; i++) {
        const opt *o = &options[i];
        char item[64];
        if (!o->help) continue;
        snprintf(item, sizeof item, "[%s%s%s]", o->name, o->meta ? " " : "",
                 o->meta ? o->meta : "");
        int w = (int)strlen(item);
        if (col + 1 + w > HELP_WIDTH) {
            fprintf(f, "\n%*s", (int)sizeof lead - 1, "");
            col = (int)sizeof lead - 1;
        }
        col += fprintf(f, " %s", item);
    }
    fprintf(f, "\n  solvers:");
    for (int s = 0; s < bench_nsolvers; s++)
        fprintf(f, " %s", bench_solvers[s].name);
    fprintf(f, "\n  problems:");
    for (int i = 0; i < bp_count(); i++)
        fprintf(f, " %s", bp_get(i)->name);
    for (int i = 0; i < bp_testset_count(); i++)
        fprintf(f, " %s", bp_testset_get(i)->name);
    for (int i = 0; i < bp_osc_count(); i++)
        fprintf(f, " %s", bp_osc_get(i)->name);
    fprintf(f, " crane\noptions:\n");
    for (int i = 0; i < NOPT; i++) {
        const opt *o = &options[i];
        if (!o->help) continue;
        int c = fprintf(f, "  %s%s%s%s%s", o->name, o->alias ? ", " : "", o->alias ? o->alias : "",
                        o->meta ? " " : "", o->meta ? o->meta : "");
        if (c >= HELP_COL) {
            fprintf(f, "\n");
            c = 0;
        }
        fprintf(f, "%*s", HELP_COL - c, "");
        c = print_wrapped(f, o->help, HELP_COL, HELP_COL);
        if ((o->kind == OPT_INT || o->kind == OPT_NUM) && o->takes) {
            fputc(';', f);
            c = print_wrapped(f, "takes", c + 1, HELP_COL);
            print_wrapped(f, o->takes, c, HELP_COL);
        }
        fprintf(f, "\n");
    }
    fprintf(f, "see the header of bench/bench.c\n");
}

int bench_cli_usage(const char *bad)
{
    fprintf(stderr, "bench: %s\n", bad);
    usage_text(stderr);
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

/* The table's entry named arg (by its name or alias), or NULL. */
static const opt *find_option(const char *arg)
{
    for (int i = 0; i < NOPT; i++)
        if (!strcmp(arg, options[i].name) || (options[i].alias && !strcmp(arg, options[i].alias)))
            return &options[i];
    return NULL;
}

/* Puts value v of option o into its field. 0, or -1 with the message in m. */
static int set_value(bench_cli *c, const opt *o, char *v, char *m, size_t msz)
{
    char *field = (char *)c + o->field;
    if (o->kind == OPT_TEXT) {
        /* never cut: the folder's name and a file's must fit the paths */
        if (o->hi > 0 && strlen(v) > (size_t)o->hi) {
            snprintf(m, msz, "%s: %s has %zu characters, more than the %d allowed", o->name,
                     o->takes, strlen(v), (int)o->hi);
            return -1;
        }
        memcpy(field, &v, sizeof v);
        return 0;
    }
    int bad;
    if (o->kind == OPT_INT) {
        int x;
        bad = parse_int(v, (int)o->lo, (int)o->hi, &x);
        if (!bad) memcpy(field, &x, sizeof x);
    } else {
        double x;
        bad = parse_num(v, o->lo, o->hi, &x);
        if (!bad) memcpy(field, &x, sizeof x);
    }
    if (bad) snprintf(m, msz, "%s takes %s, not '%s'", o->name, o->takes, v);
    return bad ? -1 : 0;
}

int bench_cli_parse(bench_cli *c, int argc, char **argv)
{
    memset(c, 0, sizeof *c);
    c->out = "results/bench";
    c->realtime_runs = -1;
    char m[512];
    for (int a = 1; a < argc; a++) {
        const char *arg = argv[a];
        const opt *o = find_option(arg);
        if (!o) {
            snprintf(m, sizeof m, "unknown argument '%s'", arg);
            return bench_cli_usage(m);
        }
        if (o->kind == OPT_HELP) {
            usage_text(stdout);
            if (fflush(stdout) != 0 || ferror(stdout)) {
                fprintf(stderr, "bench: cannot write the standard output: %s\n", strerror(errno));
                return 1;
            }
            return 0;
        }
        if (o->kind == OPT_FLAG) {
            const int one = 1;
            memcpy((char *)c + o->field, &one, sizeof one);
            continue;
        }
        if (a + 1 >= argc || !argv[a + 1][0] || !strncmp(argv[a + 1], "--", 2)) {
            snprintf(m, sizeof m, "option %s needs a value", arg);
            return bench_cli_usage(m);
        }
        if (set_value(c, o, argv[++a], m, sizeof m) != 0) return bench_cli_usage(m);
    }
    /* the options that imply another */
    if (c->full_scene || c->full_rtols_text) c->crane_full = 1;
    return BENCH_CLI_RUN;
}

/* ---------------------------------------------------------------- resolving ---- */

/* Splits a comma-separated list in place; the number of items, or -1 if more than max. */
static int split_list(char *s, char **items, int max)
{
    int n = 0;
    for (char *tok = strtok(s, ","); tok; tok = strtok(NULL, ",")) {
        if (n == max) return -1;
        items[n++] = tok;
    }
    return n;
}

/* Tolerances from list (of option name) into rtols: each in (0, 1), at least one, at most
 * BENCH_MAXRTOL. Their number, or -1 with the message in m. */
static int tolerance_list(const char *name, char *list, double *rtols, char *m, size_t msz)
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
