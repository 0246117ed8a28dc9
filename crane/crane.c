/* crane: simulates the hydraulically driven rotary crane of the crane paper (docs/crane.md) from a
 * scene file and writes the results.
 *
 *   crane [SCENE] [--out DIR] [--t-end T] [--rtol R] [--atol A] [--elements N]
 *         [--output-step DT] [--max-rows N] [--set SECTION.KEY=VALUE]... [--no-plots]
 *         [--quiet] [--help] [--version] [--vtk] [--vtk-step DT] [--animate]
 *         [--anim-step DT] [--anim-scale K] [--static] [--modes [T]]
 *
 * --static and --modes replace the dynamic run by the analyses of crane/crane_static.h: the
 * static equilibrium (equilibrium.csv, static.txt) and the modes at time T (modes.csv, modes.gp,
 * modes.png). A static start whose checks fail (scene keys that cannot be met together) ends
 * with exit status 2, status.txt and static.txt naming the keys.
 *
 * Flow: scene file (crane_scene_load) -> command-line overrides -> crane_build -> static
 * equilibrium (crane_static_start, if the scene asks: the static solver, the ties corrected, the
 * start verified, static.txt) -> bgr_dae_problem -> bg_dae (rtol, atol, stop at
 * t_end, the reference's corners as breakpoints, algebraic variables out of the error test) ->
 * consistent initial values -> dae_step up to each output time, one CSV row there
 * (crane_outputs), buffered -> statistics, figures (gnuplot, skipped when it is missing), summary.
 *
 * Writes into DIR (default results/<scene name>/): status.txt first ("running", with the pid, the
 * scene, the command line and the start time), then scene.ini (the scene as run, overrides
 * included), model_stats.txt, results.csv (one row per output time, buffered, whole rows only),
 * solver_stats.txt, plots.gp and fig5a.png .. fig5f.png, and status.txt again when the run ends
 * (completed, interrupted or failed, with the reason). The results and figures of an earlier run
 * in DIR are removed first; a DIR whose status.txt names a crane still running is refused. Every
 * write is checked: a failure names the file and the system's error and ends the run (exit 1,
 * status failed); status.txt and the other small files are replaced atomically (a temporary file
 * in DIR, fsync, rename), results.csv is cut back to its last whole row. The number of output rows
 * is limited (--max-rows, default 1000000).
 * Signals: SIGINT, SIGTERM and SIGHUP stop the integration between two solver steps (within a
 * second whatever the output step or the model size): the rows written stay, status.txt says
 * when. During set-up (model, static equilibrium, consistent initial values: long library calls)
 * and on a second signal the program writes status.txt and ends at once. A run that reached t_end
 * is completed, whenever a signal comes (the figures are then not drawn). SIGKILL leaves
 * "running" with a pid that no longer exists.
 * Exit status: 0 completed; 1 the model or the solver failed, or a file could not be written; 2
 * bad command line or scene file (nothing is written then); 128 + signal number when interrupted.
 */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "crane_model.h"
#include "crane_scene.h"
#include "crane_static.h"
#include "crane_viz.h"

#ifndef CRANE_VERSION
#define CRANE_VERSION "unknown"
#endif

#define DEFAULT_SCENE "crane/scenes/paper.ini"
#define MAX_SETS 64
/* paths: the output folder's name is at most OUT_MAX characters, so that its files' names fit */
#define PATH_SIZE 4096
#define OUT_MAX (PATH_SIZE - 64)
/* output rows: at most --max-rows (default DEFAULT_MAX_ROWS, about 300 MB of results.csv) */
#define DEFAULT_MAX_ROWS 1000000LL
#define MAX_MAX_ROWS 1000000000000LL

enum { EXIT_OK = 0, EXIT_RUN = 1, EXIT_USAGE = 2 };

/* ------------------------------------------------------------------ signals ---- */

/* The handler (SIGINT, SIGTERM, SIGHUP) records the first signal in g_signal; the program looks
 * at it between solver steps and between its other tasks, and ends the run in order. It ends the
 * program itself when the signal comes during set-up (PHASE_SETUP: the model's build, the static
 * equilibrium and the initial values are long library calls that cannot be stopped) or is a
 * second one (g_signal set already), after writing the status.txt prepared for that moment
 * (g_pre, the signal's name, g_post) with async-signal-safe calls: a temporary file, fsync,
 * rename. Two slots: the program fills the one not in use, then switches g_slot. */
enum { PHASE_OTHER = 0, PHASE_SETUP = 1, PHASE_LOOP = 2 };
static volatile sig_atomic_t g_signal = 0, g_phase = PHASE_OTHER, g_status_ready = 0;
static volatile sig_atomic_t g_slot = 0, g_temp_live = 0;
static char g_status_path[PATH_SIZE], g_signal_tmp[PATH_SIZE], g_temp_path[PATH_SIZE];
#define SLOT_SIZE 16384
static char g_pre[2][SLOT_SIZE], g_post[2][SLOT_SIZE];
static size_t g_pre_len[2], g_post_len[2];

static const char *signal_name(int sig)
{
    return sig == SIGINT    ? "SIGINT"
           : sig == SIGTERM ? "SIGTERM"
           : sig == SIGHUP  ? "SIGHUP"
                            : "signal";
}

/* write(2) until all is written; 0, or -1 with errno (EIO for a write of nothing). */
static int write_all(int fd, const char *p, size_t n)
{
    while (n > 0) {
        ssize_t w = write(fd, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) {
            if (w == 0) errno = EIO;
            return -1;
        }
        p += w;
        n -= (size_t)w;
    }
    return 0;
}

static void on_signal(int sig)
{
    int saved = errno, second = g_signal != 0;
    if (!second) g_signal = sig;
    if (!second && g_phase != PHASE_SETUP) {
        errno = saved;
        return;
    }
    if (g_status_ready) {
        if (g_temp_live) unlink(g_temp_path); /* a file the program was writing */
        int k = g_slot;
        const char *name = signal_name(sig);
        int fd = open(g_signal_tmp, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) {
            int bad = write_all(fd, g_pre[k], g_pre_len[k]) || write_all(fd, name, strlen(name)) ||
                      write_all(fd, g_post[k], g_post_len[k]) || fsync(fd) != 0;
            if (close(fd) != 0) bad = 1;
            if (bad || rename(g_signal_tmp, g_status_path) != 0) unlink(g_signal_tmp);
        }
    }
    static const char note[] = " received: stopped at once\n";
    if (write_all(STDERR_FILENO, "crane: ", 7) == 0 &&
        write_all(STDERR_FILENO, signal_name(sig), strlen(signal_name(sig))) == 0 &&
        write_all(STDERR_FILENO, note, sizeof note - 1) == 0) {
    }
    _exit(128 + sig);
}

static const char *USAGE =
    "usage: crane [SCENE] [options]\n"
    "\n"
    "Simulates the hydraulically driven rotary crane (docs/crane.md) described by the\n"
    "scene file SCENE (default " DEFAULT_SCENE "; a bare name such as 'rigid-boom' is looked up\n"
    "in crane/scenes/) and writes the results into DIR.\n"
    "\n"
    "options (a value may also be given as --option=VALUE):\n"
    "  --out DIR            output folder (default results/<scene name>/)\n"
    "  --t-end T            end time in s (scene [solver] t_end; paper: 20)\n"
    "  --rtol R             relative tolerance (scene [solver] rtol; paper: 1e-6)\n"
    "  --atol A             absolute tolerance (scene [solver] atol; paper: 1e-6)\n"
    "  --elements N         beam elements of the boom, 0..512 (0: rigid boom)\n"
    "  --output-step DT     output interval in s (scene [solver] output_step; paper: 0.001)\n"
    "  --max-rows N         at most N output rows (default 1000000): t_end / output_step + 1\n"
    "                       beyond it is refused\n"
    "  --set SEC.KEY=VALUE  set any scene key, e.g. --set hydraulics.enabled=false\n"
    "  --no-plots           do not draw the figures\n"
    "  --static             the static equilibrium only: equilibrium.csv and static.txt (the\n"
    "                       checks of the start), no dynamic run\n"
    "  --modes [T]          the modes at time T (default 0: the static start) instead of the\n"
    "                       run: modes.csv, modes.gp, modes.png (frequency against damping)\n"
    "  --quiet              no progress line and no summary (errors only)\n"
    CRANE_VIZ_USAGE
    "  --help               this text\n"
    "  --version            the program's version\n"
    "\n"
    "files in DIR: status.txt (\"running\" with the pid from the start, then completed,\n"
    "interrupted or failed, with the reason), results.csv (one row per output time),\n"
    "model_stats.txt, solver_stats.txt, scene.ini (the scene as run), plots.gp,\n"
    "fig5a.png .. "
    "fig5f.png (with gnuplot); crane.pvd, vtk/ (--vtk); anim.dat, anim_track.dat, anim.gp,\n"
    "crane.gif, crane_frame.png (--animate); static.txt (the checks of the static start);\n"
    "equilibrium.csv (--static); modes.csv, modes.gp, modes.png (--modes).\n"
    "The results and figures of an earlier run in DIR are removed at the start.\n"
    "SIGINT, SIGTERM and SIGHUP stop the run within a step; status.txt says so.\n"
    "exit status: 0 completed, 1 the run failed or a file could not be written, 2 bad\n"
    "command line or scene file (nothing written), or scene keys that cannot be met together\n"
    "(found at the static start: status.txt and static.txt say which), 128 + N interrupted by\n"
    "signal N.\n";

/* ------------------------------------------------------------ command line ---- */

typedef struct set_item {
    char section[64], key[64];
    const char *value;
    char origin[96];
} set_item;

typedef struct options {
    const char *scene, *out;
    set_item sets[MAX_SETS];
    int nsets;
    int no_plots, quiet;
    int static_only, modes; /* --static, --modes [T] (crane_static.h) */
    double modes_t;
    crane_viz_options viz; /* --vtk, --animate (crane_viz.h) */
    long long max_rows;    /* --max-rows */
    int argc;              /* the command line, for status.txt */
    char **argv;
} options;

static int usage_error(const char *fmt, const char *a, const char *b)
{
    fprintf(stderr, "crane: ");
    fprintf(stderr, fmt, a, b);
    fprintf(stderr, "\n(crane --help lists the options)\n");
    return EXIT_USAGE;
}

static int add_set(options *o, const char *section, const char *key, const char *value,
                   const char *origin)
{
    if (o->nsets >= MAX_SETS) return usage_error("too many overrides (at most %s)%s", "64", "");
    set_item *it = &o->sets[o->nsets++];
    snprintf(it->section, sizeof it->section, "%s", section);
    snprintf(it->key, sizeof it->key, "%s", key);
    it->value = value;
    snprintf(it->origin, sizeof it->origin, "%s", origin);
    return EXIT_OK;
}

/* Returns -1 to go on, or an exit status (help and version: 0). */
static int parse_args(int argc, char **argv, options *o)
{
    static const struct {
        const char *name, *section, *key;
    } valued[] = {{"--out", NULL, NULL},
                  {"--t-end", "solver", "t_end"},
                  {"--rtol", "solver", "rtol"},
                  {"--atol", "solver", "atol"},
                  {"--elements", "boom", "elements"},
                  {"--output-step", "solver", "output_step"},
                  {"--max-rows", NULL, NULL},
                  {"--set", NULL, NULL},
                  {"--vtk-step", NULL, NULL},
                  {"--anim-step", NULL, NULL},
                  {"--anim-scale", NULL, NULL}};
    static const char *flags[] = {"--no-plots", "--quiet", "--help", "--version", "--vtk",
                                  "--animate", "--static", "--modes"};
    const int nvalued = (int)(sizeof valued / sizeof *valued),
              nflags = (int)(sizeof flags / sizeof *flags);
    int positional_only = 0;
    memset(o, 0, sizeof *o);
    o->max_rows = DEFAULT_MAX_ROWS;
    o->argc = argc;
    o->argv = argv;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (positional_only || a[0] != '-' || !strcmp(a, "-")) {
            if (o->scene)
                return usage_error("more than one scene given ('%s' and '%s')", o->scene, a);
            o->scene = a;
            continue;
        }
        if (!strcmp(a, "--")) {
            positional_only = 1;
            continue;
        }
        if (!strcmp(a, "-h")) a = "--help";
        if (!strcmp(a, "-q")) a = "--quiet";
        if (!strcmp(a, "-V")) a = "--version";
        char name[64];
        const char *eq = strchr(a, '='), *value = NULL;
        size_t n = eq ? (size_t)(eq - a) : strlen(a);
        if (n >= sizeof name) return usage_error("unknown option '%.40s...'%s", a, "");
        memcpy(name, a, n);
        name[n] = '\0';
        int found = 0;
        if (!strcmp(name, "--modes")) { /* --modes [T]: an optional time */
            const char *tv = eq ? eq + 1 : NULL;
            if (!tv && i + 1 < argc && argv[i + 1][0] != '-') {
                char *end;
                (void)strtod(argv[i + 1], &end);
                if (end != argv[i + 1] && !*end) tv = argv[++i];
            }
            o->modes = 1;
            if (tv) {
                char *end;
                o->modes_t = strtod(tv, &end);
                if (!*tv || *end || !(o->modes_t >= 0) || isinf(o->modes_t) || strchr(tv, 'x') ||
                    strchr(tv, 'X'))
                    return usage_error("option --modes needs a time >= 0 in s (got '%s')%s", tv,
                                       "");
            }
            continue;
        }
        for (int k = 0; k < nflags && !found; k++)
            if (!strcmp(name, flags[k])) {
                found = 1;
                if (eq) return usage_error("option %s takes no value (got '%s')", name, eq + 1);
                if (k == 0) o->no_plots = 1;
                if (k == 1) o->quiet = 1;
                if (k == 4 || k == 5) crane_viz_option(&o->viz, name, NULL);
                if (k == 6) o->static_only = 1;
                if (k == 2) {
                    fputs(USAGE, stdout);
                    return EXIT_OK;
                }
                if (k == 3) {
                    printf("crane (bgdae) %s\n", CRANE_VERSION);
                    return EXIT_OK;
                }
            }
        for (int k = 0; k < nvalued && !found; k++) {
            if (strcmp(name, valued[k].name)) continue;
            found = 1;
            if (eq)
                value = eq + 1;
            else if (i + 1 < argc)
                value = argv[++i];
            else
                return usage_error("option %s needs a value%s", name, "");
            if (!*value) return usage_error("option %s needs a value (got '%s')", name, value);
            if (!eq && !strncmp(value, "--", 2))
                return usage_error("option %s needs a value (got the option '%s')", name, value);
            if (!strcmp(name, "--out")) {
                o->out = value;
            } else if (!strcmp(name, "--max-rows")) {
                /* decimal digits only (no sign, no hexadecimal), 1 .. MAX_MAX_ROWS */
                char *end;
                errno = 0;
                long long v = strtoll(value, &end, 10);
                if (strspn(value, "0123456789") != strlen(value) || *end || errno == ERANGE ||
                    v < 1 || v > MAX_MAX_ROWS)
                    return usage_error("option --max-rows needs a decimal integer in "
                                       "1..1000000000000 (got '%s')%s",
                                       value, "");
                o->max_rows = v;
            } else if (!strcmp(name, "--set")) {
                const char *dot = strchr(value, '.'), *veq = strchr(value, '=');
                if (!dot || !veq || dot > veq || dot == value || veq == dot + 1)
                    return usage_error("--set expects SECTION.KEY=VALUE, got '%s'%s", value, "");
                if (dot - value >= 64 || veq - dot - 1 >= 64)
                    return usage_error("--set %.60s...: the section or key name is longer than "
                                       "63 characters%s",
                                       value, "");
                char sec[64], key[64];
                snprintf(sec, sizeof sec, "%.*s", (int)(dot - value), value);
                snprintf(key, sizeof key, "%.*s", (int)(veq - dot - 1), dot + 1);
                char origin[96];
                snprintf(origin, sizeof origin, "--set %.40s.%.40s", sec, key);
                int r = add_set(o, sec, key, veq + 1, origin);
                if (r) return r;
            } else if (!valued[k].section) { /* --vtk-step, --anim-step, --anim-scale */
                if (strchr(value, 'x') || strchr(value, 'X')) /* decimal, as the scene's */
                    return usage_error("option %s needs a decimal number (got '%s')", name, value);
                if (crane_viz_option(&o->viz, name, value) != 0)
                    return usage_error("option %s needs a positive number (got '%s')", name, value);
            } else {
                int r = add_set(o, valued[k].section, valued[k].key, value, name);
                if (r) return r;
            }
        }
        if (!found) {
            const char *best = NULL;
            int bd = 1 << 30;
            for (int k = 0; k < nvalued + nflags; k++) {
                const char *cand = k < nvalued ? valued[k].name : flags[k - nvalued];
                int d = crane_scene_edit_distance(name, cand);
                if (d < bd) bd = d, best = cand;
            }
            return usage_error("unknown option '%s'; did you mean %s?", name, best);
        }
    }
    return -1;
}

/* ---------------------------------------------------------------- files ---- */

/* Finds the scene: as given, then (bare names) in crane/scenes/ with or without .ini, relative
 * to the current folder, then to the source tree and the installed data folder. A candidate
 * that exists but is no regular file (a directory, a FIFO, a device) is remembered in odd (its
 * path and what it is), for the message when nothing is found. */
static int find_scene(const char *arg, char *path, size_t size, char *tried, size_t tsize,
                      char *odd, size_t osize)
{
    const char *roots[3] = {"", NULL, NULL};
    int nroots = 1;
#ifdef CRANE_SOURCE_ROOT
    roots[nroots++] = CRANE_SOURCE_ROOT "/";
#endif
    const char *base = strrchr(arg, '/');
    base = base ? base + 1 : arg;
    /* forms: as given; bare names in crane/scenes/, with or without .ini */
    const char *pre[3] = {"", "crane/scenes/", "crane/scenes/"}, *suf[3] = {"", "", ".ini"};
    int nforms = strchr(arg, '/') ? 1 : 3;
    size_t tl = 0;
    tried[0] = odd[0] = '\0';
    for (int r = 0; r < nroots; r++) {
        if (r > 0 && arg[0] == '/') break;
        for (int f = 0; f < nforms; f++) {
            int len = snprintf(path, size, "%s%s%s%s", roots[r], pre[f], arg, suf[f]);
            if (len < 0 || (size_t)len >= size) continue;
            struct stat st;
            if (stat(path, &st) == 0 && S_ISREG(st.st_mode)) return 1;
            if (stat(path, &st) == 0 && !odd[0])
                snprintf(odd, osize, "%s is %s, not a scene file", path,
                         crane_file_kind((unsigned)st.st_mode));
            if (tl < tsize) {
                len = snprintf(tried + tl, tsize - tl, "%s%s", tl ? ", " : "", path);
                tl = len < 0 ? tsize : tl + (size_t)len;
            }
        }
    }
#ifdef CRANE_DATA_DIR
    for (int f = 1; f < 3; f++) {
        struct stat st;
        int len = snprintf(path, size, "%s/%s%s", CRANE_DATA_DIR, base, suf[f]);
        if (len >= 0 && (size_t)len < size && stat(path, &st) == 0 && S_ISREG(st.st_mode)) return 1;
    }
#else
    (void)base;
#endif
    return 0;
}

/* Creates the folder dir and its parents. 0, or -1 with the reason in msg: a part of the path
 * that is not a folder says what it is ("out/a is a regular file, not a folder"). */
static int make_folder(const char *dir, char *msg, size_t size)
{
    char buf[PATH_SIZE];
    if (snprintf(buf, sizeof buf, "%s", dir) >= (int)sizeof buf) {
        snprintf(msg, size, "the name is too long");
        return -1;
    }
    size_t n = strlen(buf);
    for (size_t i = 1; i <= n; i++) {
        if (buf[i] != '/' && buf[i] != '\0') continue;
        if (buf[i - 1] == '/') continue; /* "a//b" */
        char keep = buf[i];
        buf[i] = '\0';
        struct stat st;
        if (stat(buf, &st) != 0) {
            if (errno != ENOENT) {
                snprintf(msg, size, "%s: %s", buf, strerror(errno));
                return -1;
            }
            if (mkdir(buf, 0777) != 0 && errno != EEXIST) {
                snprintf(msg, size, "cannot create %s: %s", buf, strerror(errno));
                return -1;
            }
            if (stat(buf, &st) != 0) { /* a symbolic link to nothing */
                if (lstat(buf, &st) == 0 && S_ISLNK(st.st_mode))
                    snprintf(msg, size, "%s is a symbolic link to nothing, not a folder", buf);
                else
                    snprintf(msg, size, "cannot create %s: %s", buf, strerror(errno));
                return -1;
            }
        }
        if (!S_ISDIR(st.st_mode)) {
            snprintf(msg, size, "%s is %s, not a folder", buf,
                     crane_file_kind((unsigned)st.st_mode));
            return -1;
        }
        buf[i] = keep;
    }
    return 0;
}

static double wall_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* ---------------------------------------------------------------- figures ---- */

/* The path of gnuplot (searched in PATH, as the shell would) in buf; 0 if it is not there. */
static int find_gnuplot(char *buf, size_t size)
{
    const char *path = getenv("PATH");
    if (!path || !*path) path = "/usr/local/bin:/usr/bin:/bin";
    for (const char *p = path;; p++) {
        const char *e = strchr(p, ':');
        size_t n = e ? (size_t)(e - p) : strlen(p);
        int len = snprintf(buf, size, "%.*s%sgnuplot", (int)n, p, n ? "/" : "./");
        struct stat st;
        if (len > 0 && (size_t)len < size && stat(buf, &st) == 0 && S_ISREG(st.st_mode) &&
            access(buf, X_OK) == 0)
            return 1;
        if (!e) return 0;
        p = e;
    }
}

/* A curve of the figures: an output column, or the difference ref - val of two (the errors,
 * when the model gives the quantities and their references only). */
typedef struct curve {
    char using[32]; /* gnuplot "using" part: "8" or "($5-$4)" */
    char label[96]; /* with unit */
} curve;

/* Column of output a, or of b if the model has no a (-1: neither). */
static int col_any(const char *a, const char *b)
{
    int c = crane_output_index(a);
    return c >= 0 || !b ? c : crane_output_index(b);
}

static int curve_col(curve *cv, int c)
{
    if (c < 0) return 0;
    snprintf(cv->using, sizeof cv->using, "%d", c + 1);
    snprintf(cv->label, sizeof cv->label, "%s", crane_output_names[c]);
    return 1;
}

/* err_name if the model has it, else ref - val labelled "err_name = ref - val [unit]". */
static int curve_err(curve *cv, const char *err_name, const char *val, const char *ref)
{
    if (curve_col(cv, crane_output_index(err_name))) return 1;
    int v = crane_output_index(val), r = crane_output_index(ref);
    if (v < 0 || r < 0) return 0;
    const char *unit = strchr(crane_output_names[v], '[');
    snprintf(cv->using, sizeof cv->using, "($%d-$%d)", r + 1, v + 1);
    snprintf(cv->label, sizeof cv->label, "%s = %s - %s %s", err_name, ref, val, unit ? unit : "");
    return 1;
}

static void gp_head(FILE *f, const char *file, const char *title, const crane_scene *s,
                    const curve *x, const curve *y)
{
    fprintf(f, "\nreset\nset datafile separator ','\nset grid\nset key top right\n");
    fprintf(f, "set output '%s'\nset title '%s (scene %s)'\n", file, title, s->name);
    fprintf(f, "set xlabel '%s'\nset ylabel '%s'\n", x->label, y->label);
}

/* Writes plots.gp (the paper's Fig. 5 a-f from results.csv) to f; returns the number of
 * figures in it. */
static int write_plot_script(FILE *f, const crane_scene *s, double radius, double reach)
{
    int nfig = 0;
    curve t, a, b;
    fprintf(f, "# Figures of the crane run (paper Fig. 5) from results.csv; run in this folder:\n"
               "#   gnuplot plots.gp\n"
               "set terminal png size 900,600 noenhanced\n");
    if (!curve_col(&t, crane_output_index("t"))) return 0;
    /* (a) the tip's path seen from above, with the circle of the tip radius */
    if (curve_col(&a, crane_output_index("tip_x")) && curve_col(&b, crane_output_index("tip_y"))) {
        gp_head(f, "fig5a.png", "(a) boom tip trajectory in the X0Y0 plane", s, &a, &b);
        /* the whole circle through the tip's start, centred on the slewing axis */
        double cx = s->joint_A[0], cy = s->joint_A[1], h = fmax(1.1 * radius, 1.05 * reach);
        if (!(h > 0)) h = 1.1 * s->boom_tip_radius + 1;
        fprintf(f, "set size ratio -1\nset key below\n");
        fprintf(f, "set xrange [%.9g:%.9g]\nset yrange [%.9g:%.9g]\n", cx - h, cx + h, cy - h,
                cy + h);
        fprintf(f,
                "set object 1 circle at %.17g,%.17g size %.17g fs empty border lc rgb 'gray' "
                "dt 2\n",
                cx, cy, radius);
        fprintf(f,
                "plot 'results.csv' using %s:%s with lines lw 2 title 'boom tip', \\\n"
                "     NaN with lines lc rgb 'gray' dt 2 title 'circle of the initial radius "
                "%.4g m'\n",
                a.using, b.using, radius);
        nfig++;
    }
    /* (b), (c) the tip's transversal deflections */
    static const char *defl[2][3] = {{"fig5b.png", "tip_defl_1", "defl_luff"},
                                     {"fig5c.png", "tip_defl_2", "defl_side"}};
    static const char *defl_title[2] = {
        "(b) transversal deflection of the boom tip in the luffing plane",
        "(c) transversal deflection of the boom tip out of the luffing plane"};
    for (int k = 0; k < 2; k++)
        if (curve_col(&a, col_any(defl[k][1], defl[k][2]))) {
            gp_head(f, defl[k][0], defl_title[k], s, &t, &a);
            fprintf(f, "plot 'results.csv' using 1:%s with lines lw 2 notitle\n", a.using);
            nfig++;
        }
    /* (d), (e) angle and angular velocity with their references */
    static const char *ref[2][4] = {
        {"fig5d.png", "theta", "theta_ref", "(d) platform rotation angle"},
        {"fig5e.png", "omega", "omega_ref", "(e) platform angular velocity"}};
    for (int k = 0; k < 2; k++)
        if (curve_col(&a, crane_output_index(ref[k][1])) &&
            curve_col(&b, crane_output_index(ref[k][2]))) {
            gp_head(f, ref[k][0], ref[k][3], s, &t, &a);
            fprintf(f,
                    "plot 'results.csv' using 1:%s with lines lw 2 title '%s', \\\n"
                    "     'results.csv' using 1:%s with lines lw 1 dt 2 title '%s'\n",
                    a.using, a.label, b.using, b.label);
            nfig++;
        }
    /* (f) velocity error (left axis) and acceleration error (right axis) */
    if (curve_err(&a, "omega_err", "omega", "omega_ref") &&
        curve_err(&b, "alpha_err", "alpha", "alpha_ref")) {
        gp_head(f, "fig5f.png", "(f) angular velocity and acceleration errors", s, &t, &a);
        fprintf(f, "set y2label '%s'\nset ytics nomirror\nset y2tics\n", b.label);
        fprintf(f,
                "plot 'results.csv' using 1:%s with lines lw 2 title '%s' axes x1y1, \\\n"
                "     'results.csv' using 1:%s with lines lw 1 title '%s' axes x1y2\n",
                a.using, a.label, b.using, b.label);
        nfig++;
    }
    fprintf(f, "\nunset output\n");
    return nfig;
}

/* --------------------------------------------------------------- the run ---- */

typedef struct run {
    const options *o;
    crane_scene scene;
    char scene_path[PATH_SIZE], outdir[PATH_SIZE];
    char command[4096]; /* the command line, quoted as for the shell (status.txt) */
    char started[64];   /* local start time */
    crane *c;
    dae_solver *s;
    /* results.csv: rows are formatted into csv_buf and written whole (write(2)) when it is full
     * or a second has passed since the last write; a write that fails is cut back to the last
     * whole row (ftruncate), so that the file holds whole rows at every moment */
    int csv_fd;
    char *csv_buf;
    size_t csv_len, csv_cap;
    off_t csv_size;           /* bytes on disk */
    double csv_written;       /* wall time of the last write */
    long rows, rows_disk;     /* rows formatted; rows on disk */
    double t_row, t_disk;     /* time of the last row formatted; on disk */
    long nout;                /* output times after t = 0 (main bounds it by --max-rows) */
    double t, t_start, wall0; /* t: how far the integration got */
    const char *status;       /* "running", "completed", "interrupted", "failed" */
    int sig;                  /* the signal that interrupted the run */
    char reason[2 * BG_MESSAGE_SIZE + 512];
    double peak[2], first_out[CRANE_NOUT], final_out[CRANE_NOUT];
    double reach; /* largest |tip_x - A_x|, |tip_y - A_y| */
    int have_final;
    crane_viz *viz; /* --vtk, --animate (crane_viz.h); NULL when off */
    int bad_scene;  /* the static start found scene keys that cannot be met together: exit 2 */
} run;

static void local_time(char *buf, size_t size)
{
    time_t now = time(NULL);
    struct tm tm;
    if (!localtime_r(&now, &tm) || !strftime(buf, size, "%Y-%m-%d %H:%M:%S %z", &tm))
        snprintf(buf, size, "%lld s after 1970", (long long)now);
}

/* DIR/name (main has checked that the folder's name leaves room: never cut). */
static void path_in(const run *r, const char *name, char *buf, size_t size)
{
    int n = snprintf(buf, size, "%s/%s", r->outdir, name);
    if (n < 0 || (size_t)n >= size) buf[0] = '\0';
}

/* The text of status.txt: how the run stands (status, reason), what it is (pid, scene, command
 * line, start) and how far it got; final: with the end time and the wall time. NULL: out of
 * memory. */
static char *status_text(const run *r, const char *status, const char *reason, int final)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f) return NULL;
    const dae_stats *st = r->s ? dae_get_stats(r->s) : NULL;
    fprintf(f, "status: %s\nreason: %s\n", status, reason && reason[0] ? reason : "-");
    fprintf(f, "pid: %ld\nscene: %s (%s)\ncommand: %s\nstarted: %s\n", (long)getpid(),
            r->scene.name, r->scene_path, r->command, r->started);
    fprintf(f, "t_reached: %.9g s\nt_end: %.9g s\nrows: %ld\n", r->t, r->scene.t_end, r->rows_disk);
    if (r->rows_disk > 0) fprintf(f, "t_last_row: %.9g s\n", r->t_disk);
    fprintf(f, "steps: %ld\n", st ? st->steps : 0L);
    if (final) {
        char now[64];
        local_time(now, sizeof now);
        fprintf(f, "ended: %s\nwall_time: %.3f s\n", now, wall_now() - r->wall0);
    }
    if (fclose(f) != 0) {
        free(buf);
        return NULL;
    }
    return buf;
}

/* Prepares the status.txt that on_signal writes: status, and reason with \x01 where the signal's
 * name goes. */
static void arm_signal_status(const run *r, const char *status, const char *reason)
{
    char *text = status_text(r, status, reason, 0);
    if (!text) return; /* out of memory: the slot in use stays */
    const char *mark = strchr(text, '\x01'), *post = mark ? mark + 1 : "";
    size_t npre = mark ? (size_t)(mark - text) : strlen(text), npost = strlen(post);
    if (npre > SLOT_SIZE) npre = SLOT_SIZE;
    if (npost > SLOT_SIZE) npost = SLOT_SIZE;
    int k = !g_slot;
    memcpy(g_pre[k], text, npre);
    memcpy(g_post[k], post, npost);
    g_pre_len[k] = npre;
    g_post_len[k] = npost;
    g_slot = k;
    free(text);
}

/* Records a failure and says it on stderr; the first failure's reason leads, later ones are
 * added. Returns EXIT_RUN. */
static int fail_run(run *r, const char *what, const char *msg)
{
    fprintf(stderr, "crane: %s: %s\n", what, msg);
    size_t n = strlen(r->reason);
    /* cut to what fits (the reason is a summary; the full message went to stderr) */
    if (n < sizeof r->reason &&
        snprintf(r->reason + n, sizeof r->reason - n, "%s%s: %.*s", n ? "; then " : "", what,
                 (int)(sizeof r->reason - 1), msg) < 0)
        r->reason[n] = '\0';
    r->status = "failed";
    return EXIT_RUN;
}

static int write_failed(run *r, const char *path, int e)
{
    char what[PATH_SIZE + 32];
    snprintf(what, sizeof what, "cannot write %s", path);
    return fail_run(r, what, strerror(e));
}

/* Writes len bytes of text to path through path.tmp (write, fsync, close, rename): path is then
 * whole, or as it was. 0, or -1 with errno. The handler removes the temporary file when it ends
 * the program meanwhile. */
static int save_atomic(const char *path, const char *text, size_t len)
{
    char tmp[PATH_SIZE];
    if (snprintf(tmp, sizeof tmp, "%s.tmp", path) >= (int)sizeof tmp) {
        errno = ENAMETOOLONG;
        return -1;
    }
    g_temp_live = 0;
    memcpy(g_temp_path, tmp, strlen(tmp) + 1);
    int fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) return -1;
    g_temp_live = 1;
    int e = 0;
    if (write_all(fd, text, len) != 0 || fsync(fd) != 0) e = errno;
    if (close(fd) != 0 && !e) e = errno;
    if (!e && rename(tmp, path) != 0) e = errno;
    if (e) unlink(tmp);
    g_temp_live = 0;
    errno = e;
    return e ? -1 : 0;
}

/* Writes DIR/name, atomically, from what print prints (into memory: print returns 0, or -1 on
 * failure). 0, or the failure (EXIT_RUN). */
typedef int (*print_fn)(run *r, FILE *f, const void *ctx);
static int save_file(run *r, const char *name, print_fn print, const void *ctx)
{
    char path[PATH_SIZE];
    path_in(r, name, path, sizeof path);
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f) return write_failed(r, path, errno);
    int bad = print(r, f, ctx) != 0 || ferror(f);
    if (fclose(f) != 0 || bad) {
        free(buf);
        return write_failed(r, path, ENOMEM);
    }
    int rc = save_atomic(path, buf, len), e = errno;
    free(buf);
    return rc ? write_failed(r, path, e) : 0;
}

/* status.txt from r->status and r->reason (final: with the end). 0, or EXIT_RUN when it cannot
 * be written (said on stderr; the status.txt before stays). */
static int write_status(run *r, int final)
{
    char path[PATH_SIZE];
    path_in(r, "status.txt", path, sizeof path);
    char *text = status_text(r, r->status, r->reason, final);
    int rc = text ? save_atomic(path, text, strlen(text)) : -1, e = text ? errno : ENOMEM;
    free(text);
    if (rc == 0) return 0;
    fprintf(stderr, "crane: cannot write %s: %s\n", path, strerror(e));
    r->status = "failed";
    return EXIT_RUN;
}

/* The slot for a second signal while integrating. */
static void arm_loop(run *r)
{
    char reason[512];
    snprintf(reason, sizeof reason,
             "\x01 received while integrating, after an earlier signal: stopped at once "
             "(results.csv keeps %ld whole rows)",
             r->rows_disk);
    arm_signal_status(r, "interrupted", reason);
}

/* The slot for a signal after the integration: the run stays as it ended. */
static void arm_finishing(run *r)
{
    char reason[sizeof r->reason + 256];
    int done = !strcmp(r->status, "completed");
    snprintf(reason, sizeof reason,
             "%s%s\x01 received while writing the statistics and figures: stopped at once (they "
             "may be missing)",
             r->reason[0] ? r->reason
             : done       ? "the integration reached t_end"
                          : "",
             r->reason[0] || done ? "; " : "");
    arm_signal_status(r, strcmp(r->status, "running") ? r->status : "failed", reason);
}

#define CSV_BUF_SIZE (1 << 16)
#define CSV_ROW_MAX (32 * CRANE_NOUT) /* a row's text: at most 20 characters a number */

/* Writes the rows formatted so far to results.csv. 0, or the failure (EXIT_RUN), after which
 * the file is cut back to the last whole row that reached it. */
static int csv_flush(run *r)
{
    if (r->csv_len == 0) return 0;
    size_t done = 0;
    int e = 0;
    while (done < r->csv_len && !e) {
        ssize_t w = write(r->csv_fd, r->csv_buf + done, r->csv_len - done);
        if (w > 0)
            done += (size_t)w;
        else if (w == 0 || errno != EINTR)
            e = w == 0 ? EIO : errno;
    }
    if (e) {
        /* keep the whole lines written (the first holds the header), cut the rest */
        size_t keep = done, rows = 0, start = 0;
        while (keep > 0 && r->csv_buf[keep - 1] != '\n')
            keep--;
        for (size_t i = 0; i < keep; i++)
            if (r->csv_buf[i] == '\n') {
                if (i + 1 < keep) start = i + 1; /* the last line kept starts here */
                rows++;
            }
        if (r->csv_size == 0 && rows > 0) rows--; /* the header */
        if (rows > 0) {
            r->rows_disk += (long)rows;
            r->t_disk = strtod(r->csv_buf + start, NULL);
        }
        r->csv_size += (off_t)keep;
        if (ftruncate(r->csv_fd, r->csv_size) != 0 || lseek(r->csv_fd, r->csv_size, SEEK_SET) < 0)
            e = errno;
        r->csv_len = 0;
        char path[PATH_SIZE], what[PATH_SIZE + 32], msg[256];
        path_in(r, "results.csv", path, sizeof path);
        snprintf(what, sizeof what, "cannot write %s", path);
        snprintf(msg, sizeof msg, "%s (%ld whole rows kept, up to t = %.9g s)", strerror(e),
                 r->rows_disk, r->rows_disk ? r->t_disk : 0.0);
        return fail_run(r, what, msg);
    }
    r->csv_size += (off_t)r->csv_len;
    r->csv_len = 0;
    r->rows_disk = r->rows;
    r->t_disk = r->t_row;
    r->csv_written = wall_now();
    if (g_phase == PHASE_LOOP) arm_loop(r);
    return 0;
}

/* One row of results.csv (buffered). 0, or the failure of a write. */
static int write_row(run *r, double t, const double *out)
{
    if (r->csv_cap - r->csv_len < CSV_ROW_MAX) {
        int rc = csv_flush(r);
        if (rc) return rc;
    }
    char *p = r->csv_buf + r->csv_len;
    size_t room = CSV_ROW_MAX - 1, n = (size_t)snprintf(p, room, "%.12g", t);
    for (int i = 1; i < CRANE_NOUT && n < room; i++)
        n += (size_t)snprintf(p + n, room - n, ",%.12g", out[i]);
    if (n >= room) return fail_run(r, "results.csv", "a row longer than expected");
    p[n++] = '\n';
    r->csv_len += n;
    r->rows++;
    r->t_row = t;
    int d1 = col_any("tip_defl_1", "defl_luff"), d2 = col_any("tip_defl_2", "defl_side");
    if (d1 >= 0 && fabs(out[d1]) > r->peak[0]) r->peak[0] = fabs(out[d1]);
    if (d2 >= 0 && fabs(out[d2]) > r->peak[1]) r->peak[1] = fabs(out[d2]);
    int tx = crane_output_index("tip_x"), ty = crane_output_index("tip_y");
    if (tx >= 0 && ty >= 0) {
        double ex = fabs(out[tx] - r->scene.joint_A[0]), ey = fabs(out[ty] - r->scene.joint_A[1]);
        if (isfinite(ex) && ex > r->reach) r->reach = ex;
        if (isfinite(ey) && ey > r->reach) r->reach = ey;
    }
    if (r->rows == 1) memcpy(r->first_out, out, sizeof r->first_out);
    memcpy(r->final_out, out, sizeof r->final_out);
    r->final_out[0] = t;
    r->have_final = 1;
    return wall_now() - r->csv_written >= 1.0 ? csv_flush(r) : 0;
}

/* Writes the rows still buffered, makes them durable and closes results.csv. */
static int csv_close(run *r)
{
    if (r->csv_fd < 0) return 0;
    char path[PATH_SIZE];
    path_in(r, "results.csv", path, sizeof path);
    int rc = csv_flush(r);
    if (!rc && fsync(r->csv_fd) != 0) rc = write_failed(r, path, errno);
    if (close(r->csv_fd) != 0 && !rc) rc = write_failed(r, path, errno);
    r->csv_fd = -1;
    free(r->csv_buf);
    r->csv_buf = NULL;
    return rc;
}

static void progress(run *r, int tty, double *last)
{
    if (!tty) return;
    double now = wall_now();
    if (now - *last < 0.25) return;
    *last = now;
    const dae_stats *st = dae_get_stats(r->s);
    double el = now - r->t_start, frac = r->t / r->scene.t_end;
    char eta[32] = "?";
    if (frac > 1e-3) snprintf(eta, sizeof eta, "%.0f s", el * (1 - frac) / frac);
    fprintf(stderr, "\r  t = %8.4f s  %5.1f %%  steps %7ld  h %9.3e s  left %-10s", r->t,
            100 * frac, st->steps, st->h_last, eta);
    fflush(stderr);
}

typedef struct solver_stats_ctx {
    const dae_options *dopt;
    int nbk;
    const double *bk;
} solver_stats_ctx;

static int print_solver_stats(run *r, FILE *f, const void *ctx)
{
    const solver_stats_ctx *c = ctx;
    const dae_options *dopt = c->dopt;
    char line[2048], head[2048], row[2048];
    const dae_stats *st = dae_get_stats(r->s);
    double wall = wall_now() - r->wall0;
    dae_stats_line(st, line, sizeof line);
    dae_stats_csv_header(head, sizeof head);
    dae_stats_csv(st, row, sizeof row);
    fprintf(f, "# crane solver statistics\n");
    fprintf(f, "scene: %s (%s)\nstatus: %s\n", r->scene.name, r->scene_path, r->status);
    fprintf(f, "rtol: %g\natol: %g\nt_end: %g s\noutput_step: %g s\n", dopt->rtol, dopt->atol,
            r->scene.t_end, r->scene.output_step);
    fprintf(f, "error test: algebraic and index-2 variables excluded\n");
    fprintf(f, "absolute tolerances: %s\nstability guard: %s\nbreakpoints:",
            r->scene.nominal_scales
                ? "atol times each unknown's nominal magnitude (the scales in model_stats.txt)"
                : "atol in SI units",
            dopt->stability_guard ? "on (order 2 where fast modes hold orders 3..5)" : "off");
    for (int i = 0; i < c->nbk; i++)
        fprintf(f, " %g", c->bk[i]);
    fprintf(f, "%s\n", c->nbk ? "" : " none");
    fprintf(f, "t_reached: %.9g s\nrows: %ld\nwall_time: %.3f s\n", r->t, r->rows_disk, wall);
    fprintf(f, "%s\n\n# CSV\n%s,wall_s\n%s,%.3f\n", line, head, row, wall);
    return 0;
}

static int print_model_stats(run *r, FILE *f, const void *ctx)
{
    (void)ctx;
    fprintf(f, "# crane model statistics\nscene: %s (%s)\n", r->scene.name, r->scene_path);
    crane_stats_print(r->c, f);
    return 0;
}

static int print_scene_copy(run *r, FILE *f, const void *ctx)
{
    (void)ctx;
    fprintf(f, "; the scene as run: %s with the command-line overrides\n", r->scene_path);
    return crane_scene_write(&r->scene, f) == BG_OK ? 0 : -1;
}

/* Runs gnuplot (exe) on plots.gp in the output folder, its messages into gnuplot.log. Stops it
 * when a signal comes. Its wait status, or -1 (with errno) if it could not be started. */
static int run_gnuplot(run *r, const char *exe, const char *script)
{
    sigset_t block, old;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    sigaddset(&block, SIGHUP);
    sigprocmask(SIG_BLOCK, &block, &old); /* the child must not run our handler */
    pid_t pid = fork();
    if (pid == 0) {
        signal(SIGINT, SIG_DFL);
        signal(SIGTERM, SIG_DFL);
        signal(SIGHUP, SIG_DFL);
        signal(SIGPIPE, SIG_DFL);
        sigprocmask(SIG_SETMASK, &old, NULL);
        if (chdir(r->outdir) != 0) _exit(126);
        int fo = open("/dev/null", O_WRONLY),
            fe = open("gnuplot.log", O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fo < 0 || fe < 0 || dup2(fo, STDOUT_FILENO) < 0 || dup2(fe, STDERR_FILENO) < 0)
            _exit(126);
        execl(exe, "gnuplot", script, (char *)NULL);
        _exit(127);
    }
    int e = errno;
    sigprocmask(SIG_SETMASK, &old, NULL);
    if (pid < 0) {
        errno = e;
        return -1;
    }
    int status = 0, stopped = 0;
    for (;;) {
        pid_t w = waitpid(pid, &status, WNOHANG);
        if (w == pid) break;
        if (w < 0 && errno != EINTR) return -1;
        if (g_signal && !stopped) {
            kill(pid, SIGTERM);
            stopped = 1;
        }
        struct timespec ts = {0, 20000000L};
        nanosleep(&ts, NULL);
    }
    return status;
}

/* A PNG file that is whole: it ends with the IEND chunk. */
static int png_whole(const char *path)
{
    static const unsigned char iend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
    unsigned char tail[12];
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    int ok =
        fseek(f, -12L, SEEK_END) == 0 && fread(tail, 1, 12, f) == 12 && !memcmp(tail, iend, 12);
    fclose(f);
    return ok;
}

/* plots.gp, then the figures with gnuplot (skipped when it is missing); every figure is checked.
 * 0, or the failure (EXIT_RUN). A signal stops gnuplot: the figures drawn are then removed. */
static int draw_figures(run *r)
{
    int tx = crane_output_index("tip_x"), ty = crane_output_index("tip_y");
    double radius = tx >= 0 && ty >= 0 ? hypot(r->first_out[tx] - r->scene.joint_A[0],
                                               r->first_out[ty] - r->scene.joint_A[1])
                                       : r->scene.boom_tip_radius;
    char path[PATH_SIZE], exe[PATH_SIZE];
    path_in(r, "plots.gp", path, sizeof path);
    char *gp = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&gp, &len);
    if (!f) return write_failed(r, path, errno);
    int n = write_plot_script(f, &r->scene, radius, r->reach);
    if (fclose(f) != 0) {
        free(gp);
        return write_failed(r, path, ENOMEM);
    }
    if (n == 0) {
        free(gp);
        return 0;
    }
    if (save_atomic(path, gp, len) != 0) {
        int e = errno;
        free(gp);
        return write_failed(r, path, e);
    }
    if (!find_gnuplot(exe, sizeof exe)) {
        free(gp);
        if (!r->o->quiet) printf("gnuplot not found: figures skipped (plots.gp written)\n");
        return 0;
    }
    int st = run_gnuplot(r, exe, "plots.gp"), rc = 0;
    if (st == -1) {
        rc = fail_run(r, "drawing the figures: cannot start gnuplot", strerror(errno));
    } else {
        /* each figure the script names ("set output 'fig5a.png'") must be a whole PNG */
        char missing[512] = "", msg[1024];
        size_t ml = 0;
        for (const char *p = gp; (p = strstr(p, "set output '")) != NULL;) {
            p += strlen("set output '");
            const char *e = strchr(p, '\'');
            if (!e) break;
            char name[64], fig[PATH_SIZE];
            snprintf(name, sizeof name, "%.*s", (int)(e - p), p);
            path_in(r, name, fig, sizeof fig);
            if (g_signal)
                remove(fig);
            else if (!png_whole(fig) && ml < sizeof missing)
                ml += (size_t)snprintf(missing + ml, sizeof missing - ml, "%s%s", ml ? ", " : "",
                                       name);
            p = e;
        }
        char log[PATH_SIZE], first[256] = "";
        path_in(r, "gnuplot.log", log, sizeof log);
        FILE *lf = fopen(log, "r");
        if (lf) {
            if (!fgets(first, sizeof first, lf)) first[0] = '\0';
            first[strcspn(first, "\n")] = '\0';
            fclose(lf);
        }
        if (!g_signal && (!WIFEXITED(st) || WEXITSTATUS(st) != 0 || missing[0])) {
            snprintf(msg, sizeof msg, "gnuplot %s %d%s%s%s%s%s",
                     WIFEXITED(st) ? "exited with" : "ended by signal",
                     WIFEXITED(st) ? WEXITSTATUS(st) : WTERMSIG(st),
                     missing[0] ? "; not written whole: " : "", missing,
                     first[0] ? " (gnuplot.log: " : "", first, first[0] ? ")" : "");
            rc = fail_run(r, "drawing the figures", msg);
        } else if (!first[0]) {
            remove(log);
        }
    }
    free(gp);
    return rc;
}

static void summary(run *r)
{
    const dae_stats *st = r->s ? dae_get_stats(r->s) : NULL;
    int th = crane_output_index("theta"), thr = crane_output_index("theta_ref");
    printf("crane: scene %s, %s at t = %g s (of %g s)\n", r->scene.name, r->status, r->t,
           r->scene.t_end);
    if (r->have_final && th >= 0)
        printf("  final angle     theta = %.6f rad%s", r->final_out[th], thr >= 0 ? "" : "\n");
    if (r->have_final && th >= 0 && thr >= 0) printf(" (reference %.6f rad)\n", r->final_out[thr]);
    if (r->rows > 0 && col_any("tip_defl_1", "defl_luff") >= 0)
        printf("  peak tip deflections  %.6g m (luffing plane), %.6g m (sideways)\n", r->peak[0],
               r->peak[1]);
    if (st)
        printf("  steps %ld (rejected %ld), Newton iterations %ld, Jacobians %ld\n", st->steps,
               st->rejected_error, st->newton_iters, st->jac_evals);
    printf("  wall time %.2f s; results in %s/\n", wall_now() - r->wall0, r->outdir);
}

/* Enters a phase. PHASE_SETUP: a signal ends the program at once, with the status "interrupted"
 * while what; PHASE_LOOP: a second signal does. */
static void set_phase(run *r, int phase, const char *what)
{
    g_phase = PHASE_OTHER;
    if (phase == PHASE_SETUP) {
        char reason[512];
        snprintf(reason, sizeof reason, "\x01 received while %s (no results written)", what);
        arm_signal_status(r, "interrupted", reason);
    }
    if (phase == PHASE_LOOP) arm_loop(r);
    g_phase = phase;
    if (phase == PHASE_SETUP && g_signal) on_signal((int)g_signal); /* arrived just before */
}

/* static.txt, equilibrium.csv, modes.csv and modes.gp (crane_static.h) */
static int print_start(run *r, FILE *f, const void *ctx)
{
    (void)r;
    return crane_start_print(ctx, f);
}

static int print_equilibrium(run *r, FILE *f, const void *ctx)
{
    return crane_equilibrium_write(r->c, ctx, f);
}

static int print_modes(run *r, FILE *f, const void *ctx)
{
    (void)r;
    return crane_modes_write(ctx, f);
}

static int print_modes_plot(run *r, FILE *f, const void *ctx)
{
    return crane_modes_plot_script(ctx, r->scene.name, r->o->modes_t, f);
}

/* The static start (crane_static_start) with its checks in static.txt, and with --static
 * equilibrium.csv. Scene keys that cannot be met together end the run with exit 2. 0 or an exit
 * status. */
static int static_start(run *r)
{
    static crane_start_report rep;
    bg_error err = {0};
    int rc = crane_static_start(r->c, &rep, &err);
    if (rc != BG_OK && rc != CRANE_ERR_START) return fail_run(r, "the static start", err.message);
    if (save_file(r, "static.txt", print_start, &rep) != 0) return EXIT_RUN;
    if (r->o->static_only && save_file(r, "equilibrium.csv", print_equilibrium, &rep) != 0)
        return EXIT_RUN;
    if (rc == CRANE_ERR_START) {
        r->bad_scene = 1;
        fail_run(r, "the static start", err.message);
        return EXIT_USAGE;
    }
    if (!r->o->quiet && (r->o->static_only || r->o->modes))
        printf("crane: static start verified in %.3f s (%d static solves): tip radius %.9g m, "
               "ties' unstretched length %.9g m, kinetic energy %.2g J\n",
               rep.seconds, rep.solves, rep.radius, rep.tie_L0, rep.kinetic);
    return 0;
}

static int run_gnuplot(run *r, const char *exe, const char *script);
static int find_gnuplot(char *buf, size_t size);
static int png_whole(const char *path);

/* crane --static, crane --modes [T]: the analyses instead of the dynamic run. */
static int analyse(run *r)
{
    bg_error err = {0};
    r->c = crane_build(&r->scene, &err);
    if (!r->c) return fail_run(r, "building the model", err.message);
    if (save_file(r, "model_stats.txt", print_model_stats, NULL) != 0) return EXIT_RUN;
    set_phase(r, PHASE_SETUP, "finding the static equilibrium");
    int rc = static_start(r);
    if (rc != 0) return rc;
    if (r->o->modes) {
        set_phase(r, PHASE_SETUP, "computing the modes");
        dae_modes *M = NULL;
        double t0 = wall_now();
        rc = crane_modes(r->c, r->o->modes_t, &M, NULL, &err);
        if (rc != BG_OK && rc != DAE_CONV_FAIL) {
            dae_modes_free(&M);
            return fail_run(r, "the modes", err.message);
        }
        r->t = r->o->modes_t;
        int ne = 0, nr = 0, nc = 0, method = 0;
        dae_modes_info(M, &ne, &nr, &nc, NULL, NULL, &method);
        if (save_file(r, "modes.csv", print_modes, M) != 0 ||
            save_file(r, "modes.gp", print_modes_plot, M) != 0) {
            dae_modes_free(&M);
            return EXIT_RUN;
        }
        if (!r->o->quiet) {
            printf("crane: %d elastic, %d rigid, %d constraint modes at t = %g s (%s, %.3f s)\n",
                   ne, nr, nc, r->o->modes_t,
                   method == DAE_MODES_DENSE ? "dense" : "lowest 20 by ARPACK",
                   wall_now() - t0);
            for (int k = 0; k < dae_modes_count(M) && k < 5; k++) {
                const dae_mode *md = dae_modes_get(M, k);
                char d[256];
                dae_modes_describe(M, k, 2, 2, 0, d, sizeof d);
                printf("  mode %d: %.6g Hz, damping ratio %.3g, %s\n", k + 1, md->freq_hz,
                       md->damping, d);
            }
        }
        dae_modes_free(&M);
        char exe[PATH_SIZE], png[PATH_SIZE];
        if (!r->o->no_plots && find_gnuplot(exe, sizeof exe)) {
            int gs = run_gnuplot(r, exe, "modes.gp");
            path_in(r, "modes.png", png, sizeof png);
            if (gs == -1 || !WIFEXITED(gs) || WEXITSTATUS(gs) != 0 || !png_whole(png))
                return fail_run(r, "drawing modes.png", "gnuplot failed (see gnuplot.log)");
            char log[PATH_SIZE];
            struct stat sb;
            path_in(r, "gnuplot.log", log, sizeof log);
            if (stat(log, &sb) == 0 && sb.st_size == 0) remove(log);
        }
    }
    r->status = "completed";
    return 0;
}

static int simulate(run *r)
{
    const options *o = r->o;
    bg_error err = {0};
    int tty = isatty(STDERR_FILENO) && !o->quiet;
    double *bk = NULL, *y = NULL, *yp = NULL;
    int code = EXIT_OK, nbk = 0;
    dae_options dopt;
    dae_options_default(&dopt);

    if (tty) fprintf(stderr, "crane: building the model (scene %s)\n", r->scene.name);
    set_phase(r, PHASE_SETUP, "building the model");
    r->c = crane_build(&r->scene, &err);
    if (!r->c) return fail_run(r, "building the model", err.message);
    if (save_file(r, "model_stats.txt", print_model_stats, NULL) != 0) return EXIT_RUN;
    if (r->scene.static_start) {
        if (tty) fprintf(stderr, "crane: static equilibrium under gravity\n");
        set_phase(r, PHASE_SETUP, "finding the static equilibrium");
        int rc = static_start(r);
        if (rc != 0) return rc;
    }
    bgr_model *m = crane_model(r->c);
    dae_problem p;
    if (crane_dae_problem(r->c, &p) != BG_OK)
        return fail_run(r, "problem", bgr_model_error(m)->message);
    int n = p.n;

    int cap = 64;
    bk = malloc((size_t)cap * sizeof *bk);
    y = malloc((size_t)n * sizeof *y);
    yp = malloc((size_t)n * sizeof *yp);
    if (!bk || !y || !yp) {
        code = fail_run(r, "memory", "out of memory");
        goto done;
    }
    nbk = crane_breakpoints(r->c, bk, cap);
    if (nbk > cap) { /* more than fit: ask again with room for all */
        double *nb = realloc(bk, (size_t)nbk * sizeof *bk);
        if (!nb) {
            code = fail_run(r, "memory", "out of memory");
            goto done;
        }
        bk = nb;
        cap = nbk;
        nbk = crane_breakpoints(r->c, bk, cap);
    }
    if (nbk < 0) nbk = 0;
    if (nbk > cap) nbk = cap;

    dopt.rtol = r->scene.rtol;
    dopt.atol = r->scene.atol;
    dopt.has_t_stop = 1;
    dopt.t_stop = r->scene.t_end;
    dopt.breakpoints = bk;
    dopt.nbreakpoints = nbk;
    dopt.exclude_alg = 1;
    dopt.stability_guard = r->scene.stability_guard;
    bg_error_clear(&err);
    r->s = dae_create(&p, &dopt, &err);
    if (!r->s) {
        code = fail_run(r, "solver", err.message);
        goto done;
    }
    set_phase(r, PHASE_SETUP, "computing consistent initial values");
    int rc = dae_init(r->s, 0.0, bgr_y0(m), bgr_yp0(m));
    if (rc == BG_OK) rc = dae_consistent_init(r->s);
    if (rc != BG_OK) {
        code = fail_run(r, "consistent initial values", dae_get_error(r->s)->message);
        goto done;
    }

    char path[PATH_SIZE];
    path_in(r, "results.csv", path, sizeof path);
    r->csv_buf = malloc(CSV_BUF_SIZE);
    if (!r->csv_buf) {
        code = fail_run(r, "memory", "out of memory");
        goto done;
    }
    r->csv_cap = CSV_BUF_SIZE;
    r->csv_fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (r->csv_fd < 0) {
        code = write_failed(r, path, errno);
        goto done;
    }
    for (int i = 0; i < CRANE_NOUT; i++)
        r->csv_len += (size_t)snprintf(r->csv_buf + r->csv_len, r->csv_cap - r->csv_len, "%s%s",
                                       i ? "," : "", crane_output_names[i]);
    r->csv_buf[r->csv_len++] = '\n';
    r->viz = crane_viz_open(&o->viz, r->c, r->outdir, r->scene.name, o->quiet);

    double out[CRANE_NOUT];
    dae_dense(r->s, 0.0, y, yp);
    crane_outputs(r->c, 0.0, y, yp, out);
    if ((code = write_row(r, 0.0, out)) != 0 || (code = csv_flush(r)) != 0) goto done;
    if (r->viz) crane_viz_row(r->viz, 0.0, y, yp);

    /* Output times k dt (k < nout) and t_end. The solver steps one step at a time up to each
     * (dae_step), with a look at g_signal between two steps, so that a signal stops the run
     * within a step whatever the output step; the row is then interpolated in the last step
     * (dae_solve_to without a step: the values dae_solve_to alone would give). */
    double dt = r->scene.output_step, tend = r->scene.t_end, last = 0, tret = 0;
    long nout = r->nout, k;
    r->t_start = wall_now();
    set_phase(r, PHASE_LOOP, NULL);
    for (k = 1; k <= nout; k++) {
        double tout = k == nout ? tend : (double)k * dt;
        if (tout > tend) tout = tend;
        while (dae_current_time(r->s) < tout) {
            if (g_signal) goto stopped;
            rc = dae_step(r->s, tout, &tret, y, yp);
            if (rc < 0) goto solver_failed;
            r->t = tret;
            progress(r, tty, &last);
        }
        rc = dae_solve_to(r->s, tout, &tret, y, yp);
        if (rc == BG_ERR_ARGUMENT) {
            /* tout within the round-off gap of a restart at a jump, just behind the last step:
             * the values where that step starts */
            double t0 = dae_current_time(r->s) - dae_get_stats(r->s)->h_last;
            if (t0 > tout && t0 - tout <= 1e-9 * fmax(1.0, fabs(tout)) &&
                dae_dense(r->s, t0, y, yp) == BG_OK) {
                tret = t0;
                rc = DAE_SUCCESS;
            }
        }
        if (rc < 0) goto solver_failed;
        if (tret > r->t) r->t = tret;
        crane_outputs(r->c, tret, y, yp, out);
        if ((code = write_row(r, tret, out)) != 0) goto done;
        if (r->viz) crane_viz_row(r->viz, tret, y, yp);
    }
stopped:
    if (tty) fprintf(stderr, "\r%*s\r", 78, "");
    if (k <= nout) { /* a signal before t_end */
        r->sig = (int)g_signal;
        r->status = "interrupted";
        snprintf(r->reason, sizeof r->reason,
                 "%s received at t = %.9g s: stopped between two solver steps", signal_name(r->sig),
                 r->t);
        fprintf(stderr, "crane: interrupted (%s) at t = %g s; %ld rows kept in %s/results.csv\n",
                signal_name(r->sig), r->t, r->rows, r->outdir);
        code = 128 + r->sig;
    } else {
        r->status = "completed";
    }
    goto done;

solver_failed:
    r->t = tret;
    if (tty) fprintf(stderr, "\n");
    {
        char msg[BG_MESSAGE_SIZE + 64];
        snprintf(msg, sizeof msg, "%s (%s)", dae_get_error(r->s)->message, dae_return_name(rc));
        code = fail_run(r, "solver", msg);
    }

done:
    if (g_phase != PHASE_LOOP) { /* a failure during set-up: it stays a failure */
        g_phase = PHASE_OTHER;
        arm_finishing(r);
    }
    if (csv_close(r) != 0) code = EXIT_RUN; /* the last rows, then what a signal leaves */
    g_phase = PHASE_OTHER;
    arm_finishing(r);
    /* the animation is rendered only for a run that reached t_end with no signal pending */
    if (crane_viz_close(&r->viz, !strcmp(r->status, "completed") && !g_signal) != 0 &&
        !strcmp(r->status, "completed"))
        code = fail_run(r, "writing the ParaView series or the animation", "see above");
    if (r->s) {
        solver_stats_ctx ctx = {&dopt, nbk, bk};
        if (save_file(r, "solver_stats.txt", print_solver_stats, &ctx) != 0) code = EXIT_RUN;
    }
    free(bk);
    free(y);
    free(yp);
    return code;
}

/* The command line, quoted for the shell where needed, control characters as '?', cut at the
 * buffer's end with "...". */
static void format_command(run *r, int argc, char **argv)
{
    char *b = r->command;
    size_t n = 0, size = sizeof r->command - 8;
    for (int i = 0; i < argc && n < size; i++) {
        const char *a = argv[i];
        int plain = a[0] && strspn(a, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                      "0123456789-_./=:,+@%") == strlen(a);
        if (i) b[n++] = ' ';
        if (!plain) b[n++] = '\'';
        for (; *a && n < size; a++) {
            if (*a == '\'' && n + 4 < size) {
                memcpy(b + n, "'\\''", 4);
                n += 4;
            } else {
                b[n++] = (unsigned char)*a < 32 || *a == 127 ? '?' : *a;
            }
        }
        if (!plain && n < size) b[n++] = '\'';
    }
    if (n >= size) memcpy(b + n, " ...", 4), n += 4;
    b[n] = '\0';
}

/* The status.txt in dir names a crane that is still running (its pid is alive and, where /proc
 * tells, called crane): 1, with its pid and start in msg. */
static int folder_in_use(const run *r, char *msg, size_t size)
{
    char path[PATH_SIZE], text[8192];
    path_in(r, "status.txt", path, sizeof path);
    FILE *f = fopen(path, "r");
    if (!f) return 0;
    size_t len = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[len] = '\0';
    const char *p = strstr(text, "\npid: "), *st = strstr(text, "\nstarted: ");
    if (strncmp(text, "status: running\n", 16) || !p) return 0;
    long pid = strtol(p + 6, NULL, 10);
    if (pid <= 0 || pid == (long)getpid() || (kill((pid_t)pid, 0) != 0 && errno != EPERM)) return 0;
    char comm[PATH_SIZE], name[64] = "";
    snprintf(comm, sizeof comm, "/proc/%ld/comm", pid);
    if ((f = fopen(comm, "r")) != NULL) {
        if (!fgets(name, sizeof name, f)) name[0] = '\0';
        fclose(f);
        if (strncmp(name, "crane", 5)) return 0; /* the pid is another program's now */
    }
    char started[64] = "?";
    if (st) snprintf(started, sizeof started, "%.*s", (int)strcspn(st + 10, "\n"), st + 10);
    snprintf(msg, size, "pid %ld, started %s", pid, started);
    return 1;
}

/* The files a run writes into its folder (this program's, crane_vtk.h's and crane_anim.h's,
 * with their temporary names), removed at the start so that nothing of an earlier run stays
 * beside the new results; and vtk/frame_*.vtp with the folder vtk/. 0, or the failure. */
static const char *const RUN_FILES[] = {
    "results.csv", "model_stats.txt", "solver_stats.txt", "scene.ini",       "plots.gp",
    "gnuplot.log", "fig5a.png",       "fig5b.png",        "fig5c.png",       "fig5d.png",
    "fig5e.png",   "fig5f.png",       "crane.pvd",        "anim.dat",        "anim_track.dat",
    "anim.gp",     "anim.log",        "crane.gif",        "crane_frame.png", "status.txt",
    "static.txt",  "equilibrium.csv", "modes.csv",        "modes.gp",        "modes.png",
    NULL};

static int remove_old_outputs(run *r)
{
    char path[PATH_SIZE + 16], msg[PATH_SIZE + 128];
    for (int i = 0; RUN_FILES[i]; i++)
        for (int tmp = 0; tmp < 3; tmp++) {
            if (!strcmp(RUN_FILES[i], "status.txt") && tmp == 0) continue; /* ours, new */
            path_in(r, RUN_FILES[i], path, sizeof path);
            if (tmp) strcat(path, tmp == 1 ? ".tmp" : ".signal.tmp");
            if (unlink(path) != 0 && errno != ENOENT) {
                snprintf(msg, sizeof msg, "cannot remove %s, left by an earlier run", path);
                return fail_run(r, msg, strerror(errno));
            }
        }
    path_in(r, "vtk", path, sizeof path);
    DIR *d = opendir(path);
    if (d) {
        struct dirent *e;
        int bad = 0;
        while (!bad && (e = readdir(d)) != NULL) {
            size_t l = strlen(e->d_name);
            if (strncmp(e->d_name, "frame_", 6) || l < 10 || strcmp(e->d_name + l - 4, ".vtp"))
                continue;
            snprintf(msg, sizeof msg, "%s/%s", path, e->d_name);
            if (unlink(msg) != 0 && errno != ENOENT) bad = errno;
        }
        closedir(d);
        if (bad) {
            snprintf(msg, sizeof msg, "cannot remove the frames in %s, left by an earlier run",
                     path);
            return fail_run(r, msg, strerror(bad));
        }
        rmdir(path); /* if it holds nothing else */
    }
    return 0;
}

int main(int argc, char **argv)
{
    /* signals first: one during the scene's checks ends the program before it writes anything */
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaddset(&sa.sa_mask, SIGINT);
    sigaddset(&sa.sa_mask, SIGTERM);
    sigaddset(&sa.sa_mask, SIGHUP);
    sa.sa_flags = SA_RESTART;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
    /* a closed standard output (crane | head) is a failed write, not the end without a status */
    signal(SIGPIPE, SIG_IGN);

    options o;
    int rc = parse_args(argc, argv, &o);
    if (rc >= 0) {
        if (fflush(stdout) != 0 || ferror(stdout)) {
            fprintf(stderr, "crane: cannot write the standard output: %s\n", strerror(errno));
            return EXIT_RUN;
        }
        return rc;
    }

    run r;
    memset(&r, 0, sizeof r);
    r.o = &o;
    r.wall0 = wall_now();
    r.status = "running";
    r.csv_fd = -1;

    char tried[2048], odd[PATH_SIZE + 128];
    const char *arg = o.scene ? o.scene : DEFAULT_SCENE;
    if (strlen(arg) > OUT_MAX) {
        fprintf(stderr, "crane: the scene's path is %zu characters long, more than %d\n",
                strlen(arg), OUT_MAX);
        return EXIT_USAGE;
    }
    if (!find_scene(arg, r.scene_path, sizeof r.scene_path, tried, sizeof tried, odd, sizeof odd)) {
        if (odd[0])
            fprintf(stderr, "crane: scene '%s': %s\n", arg, odd);
        else
            fprintf(stderr, "crane: scene file '%s' not found (tried %s)\n", arg, tried);
        return EXIT_USAGE;
    }
    bg_error err = {0};
    int nkeys = 0;
    if (crane_scene_load_counted(&r.scene, r.scene_path, &nkeys, &err) != BG_OK) {
        fprintf(stderr, "%s\n", err.message);
        return EXIT_USAGE;
    }
    if (o.scene && nkeys == 0) {
        fprintf(stderr,
                "crane: the scene file %s sets no keys (it is empty or holds only comments and "
                "section headers): refused, as it is likely not the file meant. To run the default "
                "scene, run crane without a scene file (or with 'paper'); --set and the other "
                "options change it\n",
                r.scene_path);
        return EXIT_USAGE;
    }
    for (int i = 0; i < o.nsets; i++) {
        set_item *it = &o.sets[i];
        if (crane_scene_set(&r.scene, it->section, it->key, it->value, it->origin, &err) != BG_OK) {
            fprintf(stderr, "crane: %s\n", err.message);
            return EXIT_USAGE;
        }
    }
    if (o.nsets && crane_scene_check(&r.scene, "command line", &err) != BG_OK) {
        fprintf(stderr, "crane: %s\n", err.message);
        return EXIT_USAGE;
    }
    /* the number of output rows, in floating point before any conversion to an integer */
    double nout = ceil(r.scene.t_end / r.scene.output_step - 1e-9);
    if (!(nout >= 1)) nout = 1;
    if (!(nout + 1 <= (double)o.max_rows)) {
        fprintf(stderr,
                "crane: t_end = %g s at output_step = %g s makes %.4g output rows, more than the "
                "limit of %lld: choose a longer --output-step or a shorter --t-end, or allow more "
                "rows with --max-rows N\n",
                r.scene.t_end, r.scene.output_step, nout + 1, o.max_rows);
        return EXIT_USAGE;
    }
    r.nout = (long)nout;

    if (o.out && strlen(o.out) > OUT_MAX) {
        fprintf(stderr, "crane: --out: the folder's name is %zu characters long, more than %d\n",
                strlen(o.out), OUT_MAX);
        return EXIT_USAGE;
    }
    if (o.out)
        snprintf(r.outdir, sizeof r.outdir, "%s", o.out);
    else
        snprintf(r.outdir, sizeof r.outdir, "results/%s", r.scene.name);
    size_t ol = strlen(r.outdir);
    while (ol > 1 && r.outdir[ol - 1] == '/')
        r.outdir[--ol] = '\0';
    if (g_signal) {
        fprintf(stderr, "crane: %s received before the run started: nothing written\n",
                signal_name((int)g_signal));
        return 128 + (int)g_signal;
    }
    char msg[PATH_SIZE + 256];
    if (make_folder(r.outdir, msg, sizeof msg) != 0) {
        fprintf(stderr, "crane: cannot use the output folder %s: %s\n", r.outdir, msg);
        return EXIT_RUN;
    }
    if (folder_in_use(&r, msg, sizeof msg)) {
        fprintf(stderr,
                "crane: the output folder %s is in use: its status.txt names a crane still "
                "running there (%s). Choose another --out, or stop that run (if it is gone, "
                "remove %s/status.txt)\n",
                r.outdir, msg, r.outdir);
        return EXIT_RUN;
    }

    /* status.txt "running" first (it replaces an earlier run's), then the earlier results go */
    format_command(&r, argc, argv);
    local_time(r.started, sizeof r.started);
    path_in(&r, "status.txt", g_status_path, sizeof g_status_path);
    path_in(&r, "status.txt.signal.tmp", g_signal_tmp, sizeof g_signal_tmp);
    if (write_status(&r, 0) != 0) return EXIT_RUN;
    g_status_ready = 1;
    set_phase(&r, PHASE_SETUP, "preparing the output folder");
    if (remove_old_outputs(&r) == 0 && save_file(&r, "scene.ini", print_scene_copy, NULL) == 0)
        (o.static_only || o.modes ? analyse : simulate)(&r);
    g_phase = PHASE_OTHER;
    arm_finishing(&r);

    int completed = !strcmp(r.status, "completed");
    if (completed && g_signal) {
        snprintf(r.reason, sizeof r.reason,
                 "the integration reached t_end; %s received afterwards%s",
                 signal_name((int)g_signal),
                 r.rows > 1 && !o.no_plots ? ": the figures were not drawn" : "");
    } else if (completed && r.rows > 1 && !o.no_plots) {
        draw_figures(&r);
        if (g_signal && !strcmp(r.status, "completed"))
            snprintf(r.reason, sizeof r.reason,
                     "the integration reached t_end; %s received while drawing the figures: "
                     "they were not drawn",
                     signal_name((int)g_signal));
    }
    if (!o.quiet) summary(&r);
    if (fflush(stdout) != 0 || ferror(stdout))
        fail_run(&r, "cannot write the standard output", strerror(errno));
    write_status(&r, 1);
    g_status_ready = 0;
    dae_free(&r.s);
    crane_free(&r.c);
    free(r.csv_buf);
    return !strcmp(r.status, "completed")     ? EXIT_OK
           : !strcmp(r.status, "interrupted") ? 128 + r.sig
           : r.bad_scene                      ? EXIT_USAGE
                                              : EXIT_RUN;
}
