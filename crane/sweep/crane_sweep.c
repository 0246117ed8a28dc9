/* crane-sweep: many crane runs at once, a parameter sweep, locally or under MPI.
 *
 *   crane-sweep SWEEP.ini [--out DIR] [--jobs N] [--resume] [--time-limit S] [--crane PATH]
 *               [--bgsim PATH] [--engine auto|local|mpi] [--no-plots] [--list] [--quiet]
 *               [--help] [--version]
 *
 * A sweep of a model file ([sweep] model = FILE) runs bgsim instead of the crane, each case with
 * --set PATH=VALUE per swept and fixed parameter (sweep_model.c).
 *
 * The sweep file (sweep_spec.h) names a base scene, fixed scene keys and the axes: a key with a
 * list of values, a range with a count, or a Latin-hypercube sample of several keys with a seed;
 * and the summary quantities to report (sweep_row.h). Each case is an ordinary run of the crane
 * program, a process of its own (so that a crashing case cannot take the sweep down), in its
 * folder OUT/cases/NNNN/ with the crane's usual files, its output in crane.log and the sweep's
 * record case.txt; and one row of OUT/sweep.csv: the case's index, the swept keys' values, the
 * status and message, and the summary figures computed from the case's results.csv and
 * solver_stats.txt. Rows are appended as the cases finish, whole rows; at the end the file is
 * rewritten in case order (atomically). Engines (sweep_engine.h): local processes (--jobs N,
 * default the number of processors) or, when started under mpirun or srun (built with MPI),
 * one queue on rank 0 that hands the cases out one at a time. Then the pictures
 * (sweep_plot.h), and OUT/status.txt: running (pid, host, command, start), then completed,
 * interrupted or failed, replaced atomically.
 *
 * --resume keeps the cases whose folder holds a completed status.txt and whose scene.ini is the
 * case's scene (the same base scene, [set] and values), and runs the rest; a case folder in
 * which a crane of an earlier sweep still runs is left to it (a not_run row, sweep_engine.h).
 *
 * Exit status: 0 every case completed; 1 the sweep ran but a case did not complete (see
 * sweep.csv), or a file of the sweep could not be written; 2 bad command line or sweep file
 * (nothing run); 128 + N interrupted by signal N (the rows of the cases run are kept). */
#define _XOPEN_SOURCE 700 /* realpath */
#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#ifdef CRANE_SWEEP_MPI
#include <mpi.h>
#endif

#include "crane_scene.h"
#include "pu_cli.h"
#include "pu_fs.h"
#include "sweep_engine.h"
#include "sweep_plot.h"
#include "sweep_row.h"
#include "sweep_spec.h"

#ifndef CRANE_VERSION
#define CRANE_VERSION "unknown"
#endif

enum { EXIT_OK = 0, EXIT_RUN = 1, EXIT_USAGE = 2 };

/* the programs at their build paths (meson), NULL when not known */
#ifdef CRANE_SWEEP_BUILD_CRANE
#define SWEEP_BUILD_CRANE CRANE_SWEEP_BUILD_CRANE
#else
#define SWEEP_BUILD_CRANE NULL
#endif
#ifdef CRANE_SWEEP_BUILD_BGSIM
#define SWEEP_BUILD_BGSIM CRANE_SWEEP_BUILD_BGSIM
#else
#define SWEEP_BUILD_BGSIM NULL
#endif

volatile sig_atomic_t sweep_signal = 0, sweep_signal_count = 0;

/* 1 until the sweep writes its first file: till then (reading and expanding the sweep file,
 * --list) a signal ends the program at once, by the signal, as if it had no handler: nothing is
 * written that would need a final status, and no loop has to look for it. */
static volatile sig_atomic_t g_end_on_signal = 1;

static void on_signal(int sig)
{
    if (g_end_on_signal) { /* async-signal-safe: signal and raise */
        signal(sig, SIG_DFL);
        raise(sig);
        return;
    }
    if (!sweep_signal) sweep_signal = sig;
    if (sweep_signal_count < 100) sweep_signal_count++;
}

static const char *signal_name(int sig)
{
    return sig == SIGINT    ? "SIGINT"
           : sig == SIGTERM ? "SIGTERM"
           : sig == SIGHUP  ? "SIGHUP"
                            : "signal";
}

typedef struct options {
    const char *sweep, *out, *crane, *bgsim, *engine;
    int jobs, resume, no_plots, list, quiet;
    double time_limit; /* < 0: the sweep file's */
    int argc;
    char **argv;
} options;

static int g_print = 1; /* messages from this process (rank 0 only under a launcher) */

#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
static int
usage_error(const char *fmt, ...)
{
    if (!g_print) return EXIT_USAGE;
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "crane-sweep: ");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n(crane-sweep --help lists the options)\n");
    va_end(ap);
    return EXIT_USAGE;
}

#define AT(m) PU_CLI_AT(options, m)
#define STR_(x) #x
#define STR(x) STR_(x)

/* clang-format off: one option per entry, its fields in the order of pu_cli_option */
static const pu_cli_option OPTIONS[] = {
    {.name = "--out", .kind = PU_CLI_STRING, .arg = "DIR", .at = AT(out),
     .help = "output folder (default results/sweeps/<sweep name>/)"},
    {.name = "--jobs", .alias = "-j", .kind = PU_CLI_INT, .arg = "N", .at = AT(jobs), .min = 1,
     .max = SWEEP_MAX_JOBS, .what = "an integer in 1.." STR(SWEEP_MAX_JOBS),
     .help = "cases at a time (default: the number of processors, at most 64; under MPI per "
             "rank, default 1)"},
    {.name = "--resume", .kind = PU_CLI_FLAG, .at = AT(resume),
     .help = "keep the cases whose folder holds a completed run of the same scene, run the "
             "rest"},
    {.name = "--time-limit", .kind = PU_CLI_DOUBLE, .arg = "S", .at = AT(time_limit), .min = 0,
     .max = HUGE_VAL, .what = "a number of seconds >= 0",
     .help = "wall time per case in s (0: none; default [sweep] time_limit): the case then gets "
             "SIGTERM, 5 s later SIGKILL, and is recorded as timeout"},
    {.name = "--crane", .kind = PU_CLI_STRING, .arg = "PATH", .at = AT(crane),
     .help = "the crane program (default: next to crane-sweep, then the build's)"},
    {.name = "--bgsim", .kind = PU_CLI_STRING, .arg = "PATH", .at = AT(bgsim),
     .help = "bgsim, for a sweep of a model file (default: next to crane-sweep, then the "
             "build's)"},
    {.name = "--engine", .kind = PU_CLI_CHOICE, .arg = "E", .at = AT(engine),
     .choices = "auto|local|mpi", .what = "auto, local or mpi",
     .help = "auto (default: MPI when started by mpirun or srun), local or mpi"},
    {.name = "--no-plots", .kind = PU_CLI_FLAG, .at = AT(no_plots), .help = "no pictures"},
    {.name = "--list", .kind = PU_CLI_FLAG, .at = AT(list),
     .help = "print the cases and exit (nothing is run or written)"},
    {.name = "--quiet", .alias = "-q", .kind = PU_CLI_FLAG, .at = AT(quiet),
     .help = "no line per case"},
    {.name = "--help", .alias = "-h", .kind = PU_CLI_STOP, .help = "this text"},
    {.name = "--version", .alias = "-V", .kind = PU_CLI_STOP, .help = "the program's version"},
};

static const pu_cli CLI = {
    .program = "crane-sweep",
    .usage = "SWEEP.ini [options]",
    .intro =
        "Runs the crane program once per case of the sweep file (a base scene, fixed keys, axes:\n"
        "a key with a list of values, a range, or a Latin-hypercube sample; the summary "
        "quantities)\n"
        "and gathers one row per case into sweep.csv, with a picture per quantity for 1-D and 2-D\n"
        "sweeps. A sweep file naming a model file ([sweep] model = FILE) sweeps its parameters,\n"
        "each case a run of bgsim. The format: crane/sweep/sweep_spec.h and docs/sweeps.md.\n",
    .options_title = "options (a value may also be given as --option=VALUE):",
    .epilogue =
        "files in DIR: status.txt (running, then completed, interrupted or failed), sweep.ini "
        "(the\n"
        "sweep file as run), sweep.csv (case, the swept keys, status, message, t_reached, the\n"
        "quantities), cases/NNNN/ (the crane's files, crane.log, case.txt), plot.dat, plots.gp,\n"
        "plot_<quantity>.png.\n"
        "case statuses: completed, failed, invalid (the crane refused the case's scene), timeout,\n"
        "crashed, interrupted, not_run.\n"
        "exit status: 0 every case completed, 1 a case did not complete or a file could not be\n"
        "written, 2 bad command line or sweep file, 128 + N interrupted by signal N.\n",
    .options = OPTIONS,
    .noptions = (int)(sizeof OPTIONS / sizeof *OPTIONS),
    .positional = AT(sweep),
    .positional_many = "more than one sweep file given ('%s' and '%s')",
    .suggest = 1,
    .column = 21,
    .width = 92,
};
/* clang-format on */

static int parse_args(int argc, char **argv, options *o)
{
    memset(o, 0, sizeof *o);
    o->time_limit = -1;
    o->engine = "auto";
    o->argc = argc;
    o->argv = argv;
    const pu_cli_option *stop;
    char msg[512];
    int rc = pu_cli_parse(&CLI, argc, argv, o, &stop, msg, sizeof msg);
    if (rc == PU_CLI_ERROR) return usage_error("%s", msg);
    if (rc == PU_CLI_STOPPED && !strcmp(stop->name, "--help")) {
        char *text = pu_cli_help(&CLI);
        if (!text) {
            if (g_print) fprintf(stderr, "crane-sweep: out of memory\n");
            return EXIT_RUN;
        }
        if (g_print) fputs(text, stdout);
        free(text);
        return EXIT_OK;
    }
    if (rc == PU_CLI_STOPPED) { /* --version */
        if (g_print) printf("crane-sweep (bgdae) %s\n", CRANE_VERSION);
        return EXIT_OK;
    }
    if (!o->sweep) return usage_error("no sweep file given (e.g. crane/sweeps/pid-kp-kd.ini)");
    return -1;
}

/* ---------------------------------------------------------------- helpers ---- */

static double wall_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void local_time(char *buf, size_t size)
{
    time_t now = time(NULL);
    struct tm tm;
    if (!localtime_r(&now, &tm) || !strftime(buf, size, "%Y-%m-%d %H:%M:%S %z", &tm))
        snprintf(buf, size, "%lld s after 1970", (long long)now);
}

static int env_int(const char *name, long *v)
{
    const char *e = getenv(name);
    if (!e || !*e) return 0;
    char *end;
    long x = strtol(e, &end, 10);
    if (*end) return 0;
    *v = x;
    return 1;
}

/* Started by an MPI launcher (mpirun, mpiexec, srun with PMI/PMIx, or srun with several tasks
 * and no PMI, which the MPI engine then refuses): 1, with the rank and the number of processes
 * it announces (-1 when it does not say). */
static int under_launcher(long *rank, long *size)
{
    *rank = -1;
    *size = -1;
    int found = 0;
    found |= env_int("OMPI_COMM_WORLD_RANK", rank);
    env_int("OMPI_COMM_WORLD_SIZE", size);
    if (*rank < 0) found |= env_int("PMIX_RANK", rank);
    if (*rank < 0) found |= env_int("PMI_RANK", rank);
    if (*size < 0) env_int("PMI_SIZE", size);
    long tasks;
    if (!found && env_int("SLURM_STEP_NUM_TASKS", &tasks) && tasks > 1 &&
        env_int("SLURM_PROCID", rank)) { /* srun without PMI: several copies of the sweep */
        *size = tasks;
        found = 1;
    }
    return found;
}

/* ----------------------------------------------------------- status.txt ---- */

typedef struct sweep_state {
    options *o;
    sweep_spec *spec;
    sweep_run *run;
    char started[64], command[4096], engine[128];
    const char *status; /* running, completed, interrupted, failed */
    char reason[1024];
    double wall0;
} sweep_state;

static void format_command(sweep_state *st, int argc, char **argv)
{
    size_t n = 0, size = sizeof st->command - 8;
    char *b = st->command;
    for (int i = 0; i < argc && n < size; i++) {
        const char *a = argv[i];
        int plain = a[0] && !strpbrk(a, " \t'\"\\$`!*?;&|<>()");
        int k = snprintf(b + n, size - n, "%s%s%s%s", i ? " " : "", plain ? "" : "'", a,
                         plain ? "" : "'");
        if (k < 0) break;
        n += (size_t)k;
    }
    if (n >= size) snprintf(b + size, 8, " ...");
}

static int write_status(sweep_state *st, int final)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f) return -1;
    const sweep_run *r = st->run;
    char host[256] = "?";
    gethostname(host, sizeof host - 1);
    host[sizeof host - 1] = '\0';
    fprintf(f, "status: %s\nreason: %s\n", st->status, st->reason[0] ? st->reason : "-");
    fprintf(f, "pid: %ld\nhost: %s\nsweep: %s\nname: %s\ncommand: %s\nstarted: %s\n",
            (long)getpid(), host, st->spec->path, st->spec->name, st->command, st->started);
    fprintf(f, "engine: %s\ncases: %ld\n", st->engine, st->spec->ncases);
    if (final) {
        long count[SWEEP_NOT_RUN + 1] = {0};
        for (long c = 0; c < st->spec->ncases; c++)
            if (r->have[c]) count[r->rows[c].status]++;
        for (int k = 0; k <= SWEEP_NOT_RUN; k++)
            fprintf(f, "%s: %ld\n", sweep_status_name(k), count[k]);
        char now[64];
        local_time(now, sizeof now);
        fprintf(f, "ended: %s\nwall_time: %.3f s\n", now, wall_now() - st->wall0);
    }
    if (fclose(f) != 0) {
        free(buf);
        return -1;
    }
    char path[SWEEP_PATH_SIZE + 16];
    snprintf(path, sizeof path, "%s/status.txt", r->outdir);
    int rc = sweep_write_file(path, buf, len);
    int e = errno;
    free(buf);
    if (rc) fprintf(stderr, "crane-sweep: cannot write %s: %s\n", path, strerror(e));
    return rc;
}

/* The status.txt in dir names a crane-sweep still running on this host: 1, with its pid. */
static int folder_in_use(const char *dir, char *msg, size_t size)
{
    char path[SWEEP_PATH_SIZE + 16], status[64], pid_s[64], host[256], me[256] = "", st[128];
    snprintf(path, sizeof path, "%s/status.txt", dir);
    if (!sweep_read_field(path, "status", status, sizeof status) || strcmp(status, "running"))
        return 0;
    sweep_read_field(path, "pid", pid_s, sizeof pid_s);
    sweep_read_field(path, "host", host, sizeof host);
    sweep_read_field(path, "started", st, sizeof st);
    gethostname(me, sizeof me - 1);
    long pid = strtol(pid_s, NULL, 10);
    if (pid <= 0 || pid == (long)getpid() || strcmp(host, me)) return 0;
    if (kill((pid_t)pid, 0) != 0 && errno != EPERM) return 0;
    char comm[64], name[64] = "";
    snprintf(comm, sizeof comm, "/proc/%ld/comm", pid);
    FILE *f = fopen(comm, "r");
    if (f) {
        if (!fgets(name, sizeof name, f)) name[0] = '\0';
        fclose(f);
        if (strncmp(name, "crane-sweep", 11)) return 0;
    }
    snprintf(msg, size, "pid %ld, started %s", pid, st);
    return 1;
}

/* ------------------------------------------------------------ the sweep ---- */

static void print_cases(const sweep_spec *s)
{
    printf("# sweep %s: %ld cases of the %s %s\ncase", s->name, s->ncases,
           s->is_model ? "model" : "scene", s->scene_path);
    for (int p = 0; p < s->nparams; p++)
        printf(",%s", s->params[p].name);
    printf("\n");
    for (long c = 0; c < s->ncases; c++) {
        printf("%ld", c);
        for (int p = 0; p < s->nparams; p++) { /* a vector's value quoted, as in sweep.csv */
            const char *v = sweep_case_value(s, c, p);
            printf(strchr(v, ',') ? ",\"%s\"" : ",%s", v);
        }
        printf("\n");
    }
}

/* --resume: the case's folder holds a completed run of this case's scene (a model sweep's: of
 * the same command, and the model file as read then, model.yaml's text, starts as it does now). */
static int case_done(const sweep_run *r, long c)
{
    char dir[SWEEP_DIR_SIZE], path[SWEEP_DIR_SIZE + 32], status[64], err[1024];
    sweep_case_dir(r, c, dir, sizeof dir);
    snprintf(path, sizeof path, "%s/status.txt", dir);
    if (!sweep_read_field(path, "status", status, sizeof status) || strcmp(status, "completed"))
        return 0;
    if (r->spec->is_model) return sweep_model_case_done(r, c, dir);
    crane_scene want, have;
    if (sweep_case_scene(r->spec, c, &want, err, sizeof err) != 0) return 0;
    snprintf(path, sizeof path, "%s/scene.ini", dir);
    bg_error e = {0};
    if (crane_scene_load(&have, path, &e) != BG_OK) return 0;
    snprintf(path, sizeof path, "%s/results.csv", dir);
    struct stat sb;
    if (stat(path, &sb) != 0) return 0;
    return crane_scene_compare(&want, &have, NULL, 0) == 0;
}

/* sweep.csv in case order, every case (atomically). 0 or -1. */
static int write_final_csv(sweep_run *r, char *msg, size_t size)
{
    const sweep_spec *s = r->spec;
    char *buf = NULL, line[16384];
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f) {
        snprintf(msg, size, "out of memory");
        return -1;
    }
    if (sweep_csv_header(s, line, sizeof line) > 0) fputs(line, f);
    for (long c = 0; c < s->ncases; c++)
        if (sweep_csv_row(s, &r->rows[c], line, sizeof line) > 0) fputs(line, f);
    if (fclose(f) != 0) {
        free(buf);
        snprintf(msg, size, "out of memory");
        return -1;
    }
    char path[SWEEP_PATH_SIZE + 16];
    snprintf(path, sizeof path, "%s/sweep.csv", r->outdir);
    int rc = sweep_write_file(path, buf, len);
    if (rc) snprintf(msg, size, "cannot write %s: %s", path, strerror(errno));
    free(buf);
    return rc;
}

/* Rank 0 (or the only process): the output folder, status.txt, sweep.ini, sweep.csv's header
 * and the rows kept by --resume, the queue. 0, or an exit status. */
static int prepare(sweep_state *st)
{
    sweep_run *r = st->run;
    const sweep_spec *s = st->spec;
    char msg[SWEEP_PATH_SIZE + 256], path[SWEEP_PATH_SIZE + 32];
    if (pu_mkdir_p(r->outdir, 0777, msg, sizeof msg) != 0) {
        fprintf(stderr, "crane-sweep: cannot use the output folder %s: %s\n", r->outdir, msg);
        return EXIT_RUN;
    }
    char abs[PATH_MAX];
    if (realpath(r->outdir, abs) && strlen(abs) < sizeof r->outdir - 64)
        snprintf(r->outdir, sizeof r->outdir, "%s", abs);
    if (strlen(r->outdir) > sizeof r->outdir - 64) {
        fprintf(stderr, "crane-sweep: the output folder's name is too long\n");
        return EXIT_USAGE;
    }
    if (folder_in_use(r->outdir, msg, sizeof msg)) {
        fprintf(stderr,
                "crane-sweep: the output folder %s is in use: its status.txt names a crane-sweep "
                "still running (%s). Choose another --out, or stop that sweep\n",
                r->outdir, msg);
        return EXIT_RUN;
    }
    if (write_status(st, 0) != 0) return EXIT_RUN;
    snprintf(path, sizeof path, "%s/sweep.ini", r->outdir);
    if (pu_write_atomic(path, s->text ? s->text : "", s->text ? s->text_len : 0) != 0) {
        fprintf(stderr, "crane-sweep: cannot write %s: %s\n", path, strerror(errno));
        return EXIT_RUN;
    }
    snprintf(path, sizeof path, "%s/cases", r->outdir);
    if (pu_mkdir_p(path, 0777, msg, sizeof msg) != 0) {
        fprintf(stderr, "crane-sweep: cannot create %s: %s\n", path, msg);
        return EXIT_RUN;
    }
    snprintf(path, sizeof path, "%s/sweep.csv", r->outdir);
    r->csv_fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_CLOEXEC, 0644);
    char head[16384];
    int n = sweep_csv_header(s, head, sizeof head);
    if (r->csv_fd < 0 || n < 0 || write(r->csv_fd, head, (size_t)n) != n) {
        fprintf(stderr, "crane-sweep: cannot write %s: %s\n", path, strerror(errno));
        return EXIT_RUN;
    }
    long kept = 0;
    for (long c = 0; c < s->ncases; c++) {
        if (sweep_signal) break; /* the cases not looked at: not_run rows (conclude) */
        if (st->o->resume && case_done(r, c)) {
            char dir[SWEEP_DIR_SIZE];
            sweep_case_dir(r, c, dir, sizeof dir);
            sweep_row row;
            sweep_row_read(s, &row, c, dir, NULL);
            int q = r->quiet;
            r->quiet = 1;
            sweep_record(r, &row, 0);
            r->quiet = q;
            kept++;
        } else {
            r->queue[r->nqueue++] = c;
        }
    }
    if (!r->quiet) {
        printf("crane-sweep: sweep %s: %ld cases of %s, engine %s; results in %s\n", s->name,
               s->ncases, s->scene_path, st->engine, r->outdir);
        if (st->o->resume)
            printf("crane-sweep: --resume: %ld cases completed earlier are kept, %ld to run\n",
                   kept, r->nqueue);
        fflush(stdout);
    }
    return 0;
}

/* Rank 0 at the end: not_run rows, sweep.csv in order, pictures, status.txt. The exit status. */
static int conclude(sweep_state *st)
{
    sweep_run *r = st->run;
    const sweep_spec *s = st->spec;
    int sig = (int)sweep_signal;
    for (long c = 0; c < s->ncases; c++)
        if (!r->have[c]) {
            sweep_row_not_run(&r->rows[c], c,
                              sig ? "the sweep was stopped before the case started"
                                  : "the case was not run");
            r->have[c] = 1;
        }
    if (r->csv_fd >= 0) close(r->csv_fd);
    r->csv_fd = -1;
    char msg[SWEEP_PATH_SIZE + 512] = "", plot_msg[1024] = "";
    int failed = 0;
    if (write_final_csv(r, msg, sizeof msg) != 0) {
        fprintf(stderr, "crane-sweep: %s\n", msg);
        failed = 1;
    } else if (r->write_failed) {
        r->write_failed = 0; /* the final file has every row */
    }
    int nfig = 0;
    if (!failed && !sig && !st->o->no_plots) {
        int prc = sweep_plot(s, r->rows, r->outdir, &nfig, plot_msg, sizeof plot_msg);
        if (sweep_signal) { /* while drawing (gnuplot may have had it too): interrupted */
            sig = (int)sweep_signal;
            snprintf(plot_msg, sizeof plot_msg, "stopped while drawing the pictures");
        } else if (prc != 0) {
            fprintf(stderr, "crane-sweep: pictures: %s\n", plot_msg);
            failed = 1;
            snprintf(msg, sizeof msg, "pictures: %s", plot_msg);
        }
    }
    long count[SWEEP_NOT_RUN + 1] = {0};
    for (long c = 0; c < s->ncases; c++)
        count[r->rows[c].status]++;
    char counts[512];
    size_t cl = 0;
    for (int k = 0; k <= SWEEP_NOT_RUN; k++)
        if (count[k])
            cl += (size_t)snprintf(counts + cl, sizeof counts - cl, "%s%ld %s", cl ? ", " : "",
                                   count[k], sweep_status_name(k));
    int code;
    if (sig) {
        st->status = "interrupted";
        snprintf(st->reason, sizeof st->reason, "%s received: %ld cases not run; %s",
                 signal_name(sig), count[SWEEP_NOT_RUN], counts);
        code = 128 + sig;
    } else if (failed) {
        st->status = "failed";
        snprintf(st->reason, sizeof st->reason, "%s; %ld cases: %s", msg, s->ncases, counts);
        code = EXIT_RUN;
    } else {
        st->status = "completed";
        snprintf(st->reason, sizeof st->reason, "%ld cases: %s", s->ncases, counts);
        code = count[SWEEP_COMPLETED] == s->ncases ? EXIT_OK : EXIT_RUN;
    }
    if (write_status(st, 1) != 0 && code == EXIT_OK) code = EXIT_RUN;
    if (!r->quiet || code != EXIT_OK) {
        printf("crane-sweep: %s: %s; %s/sweep.csv", st->status, st->reason, r->outdir);
        if (nfig) printf(", %d pictures", nfig);
        if (plot_msg[0] && !nfig) printf(" (%s)", plot_msg);
        printf(" (%.1f s)\n", wall_now() - st->wall0);
    }
    fflush(stdout);
    return code;
}

int main(int argc, char **argv)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
    signal(SIGPIPE, SIG_IGN);

    long lrank, lsize;
    int launched = under_launcher(&lrank, &lsize);
    g_print = lrank <= 0;
    options o;
    int rc = parse_args(argc, argv, &o);
    if (rc >= 0) return rc;

    int use_mpi = !strcmp(o.engine, "mpi") || (!strcmp(o.engine, "auto") && launched);
    int rank = 0, size = 1;
#ifdef CRANE_SWEEP_MPI
    if (use_mpi) {
        MPI_Init(&argc, &argv);
        MPI_Comm_rank(MPI_COMM_WORLD, &rank);
        MPI_Comm_size(MPI_COMM_WORLD, &size);
        long tasks;
        if (size == 1 && env_int("SLURM_STEP_NUM_TASKS", &tasks) && tasks > 1) {
            if (g_print) /* the first task only (SLURM_PROCID 0) */
                fprintf(stderr,
                        "crane-sweep: srun started %ld tasks but MPI sees one: each would run the "
                        "whole "
                        "sweep. Start it with srun --mpi=pmix (or pmi2), or run one task\n",
                        tasks);
            MPI_Finalize();
            return EXIT_USAGE;
        }
        g_print = rank == 0;
    }
#define FINISH(code) (use_mpi ? (MPI_Finalize(), (code)) : (code))
#else
    if (use_mpi && (!strcmp(o.engine, "mpi") || lsize > 1)) {
        if (g_print)
            fprintf(stderr,
                    "crane-sweep: %s, but this crane-sweep was built without MPI (meson found "
                    "none): every process would run the whole sweep. Install Open MPI "
                    "(tools/install-deps.sh) and rebuild, or run crane-sweep alone with --jobs\n",
                    !strcmp(o.engine, "mpi") ? "--engine mpi" : "started by an MPI launcher");
        return EXIT_USAGE;
    }
    use_mpi = 0;
#define FINISH(code) (code)
#endif

    /* the sweep file; scene names in crane/scenes/ here, in the sources, in the installation */
    const char *roots[4];
    int nr = 0;
    roots[nr++] = "crane/scenes";
#ifdef CRANE_SOURCE_ROOT
    roots[nr++] = CRANE_SOURCE_ROOT "/crane/scenes";
#endif
#ifdef CRANE_DATA_DIR
    roots[nr++] = CRANE_DATA_DIR;
#endif
    roots[nr] = NULL;
    static sweep_spec spec;
    char err[4096];
    if (sweep_spec_load(&spec, o.sweep, roots, err, sizeof err) != 0) {
        if (g_print) fprintf(stderr, "%s\n", err);
        sweep_spec_free(&spec);
        return FINISH(EXIT_USAGE);
    }
    if (o.list) {
        if (g_print) print_cases(&spec);
        sweep_spec_free(&spec);
        return FINISH(fflush(stdout) == 0 ? EXIT_OK : EXIT_RUN);
    }

    static sweep_run run;
    memset(&run, 0, sizeof run);
    run.spec = &spec;
    run.rank = rank;
    run.size = size;
    run.quiet = o.quiet;
    run.csv_fd = -1;
    run.time_limit = o.time_limit >= 0 ? o.time_limit : spec.time_limit;
    long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
    run.jobs = o.jobs ? o.jobs : size > 1 ? 1 : ncpu > 0 ? (int)(ncpu < 64 ? ncpu : 64) : 1;
    char tried[SWEEP_PATH_SIZE * 2];
    const char *prog = sweep_program(&spec);
    int found = sweep_find_program(prog, spec.is_model ? o.bgsim : o.crane,
                                   spec.is_model ? SWEEP_BUILD_BGSIM : SWEEP_BUILD_CRANE, run.crane,
                                   sizeof run.crane, tried, sizeof tried);
    if (found != 1) {
        if (g_print && found < 0)
            fprintf(stderr, "crane-sweep: --%s %s; give the %s program with --%s PATH\n", prog,
                    tried, prog, prog);
        else if (g_print)
            fprintf(stderr,
                    "crane-sweep: the %s program was not found (tried %s); give it "
                    "with --%s PATH\n",
                    prog, tried[0] ? tried : "nothing", prog);
        sweep_spec_free(&spec);
        return FINISH(EXIT_USAGE);
    }
    if (o.out)
        snprintf(run.outdir, sizeof run.outdir, "%s", o.out);
    else
        snprintf(run.outdir, sizeof run.outdir, "results/sweeps/%s", spec.name);
    size_t ol = strlen(run.outdir);
    while (ol > 1 && run.outdir[ol - 1] == '/')
        run.outdir[--ol] = '\0';
    if (ol > sizeof run.outdir - 128) {
        if (g_print) fprintf(stderr, "crane-sweep: --out: the folder's name is too long\n");
        sweep_spec_free(&spec);
        return FINISH(EXIT_USAGE);
    }

    static sweep_state st;
    st.o = &o;
    st.spec = &spec;
    st.run = &run;
    st.status = "running";
    st.wall0 = wall_now();
    local_time(st.started, sizeof st.started);
    format_command(&st, argc, argv);
    if (size > 1)
        snprintf(st.engine, sizeof st.engine, "MPI, %d ranks x %d job%s", size, run.jobs,
                 run.jobs > 1 ? "s" : "");
    else
        snprintf(st.engine, sizeof st.engine, "local, %d job%s", run.jobs, run.jobs > 1 ? "s" : "");

    int code = EXIT_OK;
    g_end_on_signal = 0; /* from here a signal stops the sweep in order (sweep_engine.h) */
    if (rank == 0) {
        run.rows = calloc((size_t)spec.ncases, sizeof *run.rows);
        run.have = calloc((size_t)spec.ncases, 1);
        run.queue = malloc((size_t)spec.ncases * sizeof *run.queue);
        if (!run.rows || !run.have || !run.queue) {
            fprintf(stderr, "crane-sweep: out of memory for %ld cases\n", spec.ncases);
            code = EXIT_RUN;
        } else {
            code = prepare(&st);
        }
    }
#ifdef CRANE_SWEEP_MPI
    if (use_mpi) { /* every rank learns whether to go on, and the folder (absolute) */
        int go = code;
        MPI_Bcast(&go, 1, MPI_INT, 0, MPI_COMM_WORLD);
        MPI_Bcast(run.outdir, (int)sizeof run.outdir, MPI_CHAR, 0, MPI_COMM_WORLD);
        if (go != EXIT_OK) {
            sweep_spec_free(&spec);
            return FINISH(rank == 0 ? go : EXIT_OK);
        }
    }
#endif
    if (code != EXIT_OK) {
        sweep_spec_free(&spec);
        return code;
    }

    run.t0 = wall_now();
#ifdef CRANE_SWEEP_MPI
    if (use_mpi && size > 1)
        sweep_engine_mpi(&run);
    else
#endif
        if (!sweep_signal)
        sweep_engine_local(&run);
    /* rank 0's files before MPI_Finalize: a launcher that ends the job meanwhile (mpirun's
     * SIGKILL a second after its SIGTERM) finds them written */
    if (rank == 0) code = conclude(&st);
#ifdef CRANE_SWEEP_MPI
    if (use_mpi) MPI_Finalize();
#endif
    free(run.rows);
    free(run.have);
    free(run.queue);
    sweep_spec_free(&spec);
    return code;
}
