/* The crane program's command line (crane_program.h): the --help text, the options, the
 * overrides of scene keys, the scene file's path and the output folder. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>

#include "crane_program.h"
#include "crane_scene.h"

static const char *USAGE =
    "usage: crane [SCENE] [options]\n"
    "\n"
    "Simulates the hydraulically driven rotary crane (docs/crane.md) described by the\n"
    "scene file SCENE (default " CP_DEFAULT_SCENE
    "; a bare name such as 'rigid-boom' is looked up\n"
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
    "  --error-estimate [K] a second run at rtol / K and atol / K (default K = 100) beside the\n"
    "                       first over the same output times: error_estimate.csv, per output\n"
    "                       column the largest difference, an estimate of the first run's error\n"
    "  --quiet              no progress line and no summary (errors only)\n" CRANE_VIZ_USAGE
    "  --help               this text\n"
    "  --version            the program's version\n"
    "\n"
    "files in DIR: status.txt (\"running\" with the pid from the start, then completed,\n"
    "interrupted or failed, with the reason), results.csv (one row per output time),\n"
    "model_stats.txt, solver_stats.txt, scene.ini (the scene as run), plots.gp,\n"
    "fig5a.png .. "
    "fig5f.png (with gnuplot); crane.pvd, vtk/ (--vtk); anim.dat, anim_track.dat, anim.gp,\n"
    "crane.gif, crane_frame.png (--animate); static.txt (the checks of the static start);\n"
    "equilibrium.csv (--static); modes.csv, modes.gp, modes.png (--modes); error_estimate.csv\n"
    "(--error-estimate).\n"
    "The results and figures of an earlier run in DIR are removed at the start.\n"
    "SIGINT, SIGTERM and SIGHUP stop the run within a step; status.txt says so.\n"
    "exit status: 0 completed, 1 the run failed or a file could not be written, 2 bad\n"
    "command line or scene file (nothing written), or scene keys that cannot be met together\n"
    "(found at the static start: status.txt and static.txt say which), 128 + N interrupted by\n"
    "signal N.\n";

/* ------------------------------------------------------------ command line ---- */

static int usage_error(const char *fmt, const char *a, const char *b)
{
    fprintf(stderr, "crane: ");
    fprintf(stderr, fmt, a, b);
    fprintf(stderr, "\n(crane --help lists the options)\n");
    return CP_EXIT_USAGE;
}

static int add_set(cp_options *o, const char *section, const char *key, const char *value,
                   const char *origin)
{
    if (o->nsets >= CP_MAX_SETS) return usage_error("too many overrides (at most %s)%s", "64", "");
    cp_set_item *it = &o->sets[o->nsets++];
    snprintf(it->section, sizeof it->section, "%s", section);
    snprintf(it->key, sizeof it->key, "%s", key);
    it->value = value;
    snprintf(it->origin, sizeof it->origin, "%s", origin);
    return CP_EXIT_OK;
}

/* Returns -1 to go on, or an exit status (help and version: 0). */
int cp_parse_args(int argc, char **argv, cp_options *o)
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
    static const char *flags[] = {"--no-plots", "--quiet",  "--help",  "--version",       "--vtk",
                                  "--animate",  "--static", "--modes", "--error-estimate",
                                  "--list-keys"};
    const int nvalued = (int)(sizeof valued / sizeof *valued),
              nflags = (int)(sizeof flags / sizeof *flags);
    int positional_only = 0;
    memset(o, 0, sizeof *o);
    o->max_rows = CP_DEFAULT_MAX_ROWS;
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
        if (!strcmp(name, "--error-estimate")) { /* --error-estimate [K]: an optional factor */
            const char *kv = eq ? eq + 1 : NULL;
            if (!kv && i + 1 < argc && argv[i + 1][0] != '-') {
                char *end;
                (void)strtod(argv[i + 1], &end);
                if (end != argv[i + 1] && !*end) kv = argv[++i];
            }
            o->errest = 1;
            o->errest_factor = CRANE_ERREST_FACTOR;
            if (kv) {
                char *end;
                o->errest_factor = strtod(kv, &end);
                if (!*kv || *end || !(o->errest_factor > 1) ||
                    !(o->errest_factor <= CRANE_ERREST_MAX_FACTOR) || strchr(kv, 'x') ||
                    strchr(kv, 'X'))
                    return usage_error("option --error-estimate needs a factor K with 1 < K <= "
                                       "1e12 (got '%s')%s",
                                       kv, "");
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
                    return CP_EXIT_OK;
                }
                if (k == 3) {
                    printf("crane (bgdae) %s\n", CRANE_VERSION);
                    return CP_EXIT_OK;
                }
                if (k == 9) return crane_scene_keys_markdown(stdout) ? CP_EXIT_RUN : CP_EXIT_OK;
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
                /* decimal digits only (no sign, no hexadecimal), 1 .. CP_MAX_MAX_ROWS */
                char *end;
                errno = 0;
                long long v = strtoll(value, &end, 10);
                if (strspn(value, "0123456789") != strlen(value) || *end || errno == ERANGE ||
                    v < 1 || v > CP_MAX_MAX_ROWS)
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
    if (o->errest && (o->static_only || o->modes))
        return usage_error("option --error-estimate belongs to the dynamic run, not to %s%s",
                           o->static_only ? "--static" : "--modes", "");
    return -1;
}

/* ---------------------------------------------------------------- files ---- */

/* Finds the scene: as given, then (bare names) in crane/scenes/ with or without .ini, relative
 * to the current folder, then to the source tree and the installed data folder. A candidate
 * that exists but is no regular file (a directory, a FIFO, a device) is remembered in odd (its
 * path and what it is), for the message when nothing is found. */
int cp_find_scene(const char *arg, char *path, size_t size, char *tried, size_t tsize, char *odd,
                  size_t osize)
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
int cp_make_folder(const char *dir, char *msg, size_t size)
{
    char buf[CP_PATH_SIZE];
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
