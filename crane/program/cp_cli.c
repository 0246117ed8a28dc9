/* The crane program's command line (crane_program.h): the options' table (pu_cli.h: the parser
 * and the --help text generated from it), the overrides of scene keys, the scene file's path. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>

#include "crane_program.h"
#include "crane_scene.h"
#include "pu_cli.h"
#include "pu_fs.h"

/* ------------------------------------------------------------ command line ---- */

static int add_set(cp_options *o, const char *section, const char *key, const char *value,
                   const char *origin, char *msg, size_t size)
{
    if (o->nsets >= CP_MAX_SETS) {
        snprintf(msg, size, "too many overrides (at most %d)", CP_MAX_SETS);
        return -1;
    }
    cp_set_item *it = &o->sets[o->nsets++];
    snprintf(it->section, sizeof it->section, "%s", section);
    snprintf(it->key, sizeof it->key, "%s", key);
    it->value = value;
    snprintf(it->origin, sizeof it->origin, "%s", origin);
    return 0;
}

/* --t-end, --rtol, ...: an override of the scene key opt->data ("section.key"), checked with the
 * scene. */
static int take_key(const pu_cli_option *opt, const char *value, void *base, char *msg,
                    size_t size)
{
    const char *sk = opt->data, *dot = strchr(sk, '.');
    char sec[64];
    snprintf(sec, sizeof sec, "%.*s", (int)(dot - sk), sk);
    return add_set(base, sec, dot + 1, value, opt->name, msg, size);
}

/* --set SECTION.KEY=VALUE for a scene; kept as given too, for a model file's --set PATH=VALUE
 * (cp_model.c). A value that is no SECTION.KEY=VALUE is refused after the parse, unless SCENE is
 * a model file: the first such message is kept (set_error) and the parse goes on. */
static int take_set(const pu_cli_option *opt, const char *value, void *base, char *msg,
                    size_t size)
{
    (void)opt;
    cp_options *o = base;
    if (o->nset_raw >= CP_MAX_SETS) {
        snprintf(msg, size, "too many overrides (at most %d)", CP_MAX_SETS);
        return -1;
    }
    o->set_raw[o->nset_raw++] = value;
    const char *dot = strchr(value, '.'), *veq = strchr(value, '=');
    char bad[sizeof o->set_error] = "";
    if (!dot || !veq || dot > veq || dot == value || veq == dot + 1)
        snprintf(bad, sizeof bad, "--set expects SECTION.KEY=VALUE, got '%s'", value);
    else if (dot - value >= 64 || veq - dot - 1 >= 64)
        snprintf(bad, sizeof bad,
                 "--set %.60s...: the section or key name is longer than 63 characters", value);
    if (bad[0]) {
        if (!o->set_error[0]) snprintf(o->set_error, sizeof o->set_error, "%s", bad);
        return 0;
    }
    char sec[64], key[64], origin[96];
    snprintf(sec, sizeof sec, "%.*s", (int)(dot - value), value);
    snprintf(key, sizeof key, "%.*s", (int)(veq - dot - 1), dot + 1);
    snprintf(origin, sizeof origin, "--set %.40s.%.40s", sec, key);
    return add_set(base, sec, key, veq + 1, origin, msg, size);
}

/* --vtk, --animate (no value); --vtk-step, --anim-step, --anim-scale (crane_viz.h) */
static int take_viz(const pu_cli_option *opt, const char *value, void *base, char *msg,
                    size_t size)
{
    cp_options *o = base;
    if (value && (strchr(value, 'x') || strchr(value, 'X'))) { /* decimal, as the scene's */
        snprintf(msg, size, "option %s needs a decimal number (got '%s')", opt->name, value);
        return -1;
    }
    if (crane_viz_option(&o->viz, opt->name, value) != 0) {
        snprintf(msg, size, "option %s needs a positive number (got '%s')", opt->name,
                 value ? value : "");
        return -1;
    }
    if (!o->viz_given) o->viz_given = opt->name;
    return 0;
}

#define AT(m) PU_CLI_AT(cp_options, m)

/* clang-format off: one option per entry, its fields in the order of pu_cli_option */
static const pu_cli_option OPTIONS[] = {
    {.name = "--out", .kind = PU_CLI_STRING, .arg = "DIR", .at = AT(out),
     .help = "output folder (default results/<scene name>/)"},
    {.name = "--t-end", .kind = PU_CLI_CALL, .arg = "T", .take = take_key, .data = "solver.t_end",
     .help = "end time in s (scene [solver] t_end; paper: 20)"},
    {.name = "--rtol", .kind = PU_CLI_CALL, .arg = "R", .take = take_key, .data = "solver.rtol",
     .help = "relative tolerance (scene [solver] rtol; paper: 1e-6)"},
    {.name = "--atol", .kind = PU_CLI_CALL, .arg = "A", .take = take_key, .data = "solver.atol",
     .help = "absolute tolerance (scene [solver] atol; paper: 1e-6)"},
    {.name = "--elements", .kind = PU_CLI_CALL, .arg = "N", .take = take_key,
     .data = "boom.elements", .help = "beam elements of the boom, 0..512 (0: rigid boom)"},
    {.name = "--output-step", .kind = PU_CLI_CALL, .arg = "DT", .take = take_key,
     .data = "solver.output_step",
     .help = "output interval in s (scene [solver] output_step; paper: 0.001)"},
    {.name = "--max-rows", .kind = PU_CLI_LLONG, .arg = "N", .at = AT(max_rows), .min = 1,
     .max = (double)CP_MAX_MAX_ROWS, .what = "a decimal integer in 1..1000000000000",
     .help = "at most N output rows (default 1000000): t_end / output_step + 1 beyond it is "
             "refused"},
    {.name = "--set", .kind = PU_CLI_CALL, .arg = "SEC.KEY=VALUE", .take = take_set,
     .help = "set any scene key, e.g. --set hydraulics.enabled=false (a model file: --set "
             "PATH=VALUE, a parameter as bgsim takes it, e.g. --set kp=8)"},
    {.name = "--no-plots", .kind = PU_CLI_FLAG, .at = AT(no_plots),
     .help = "do not draw the figures"},
    {.name = "--static", .kind = PU_CLI_FLAG, .at = AT(static_only),
     .help = "the static equilibrium only: equilibrium.csv and static.txt (the checks of the "
             "start), no dynamic run"},
    {.name = "--modes", .kind = PU_CLI_DOUBLE, .value = PU_CLI_OPTIONAL, .arg = "[T]",
     .at = AT(modes_t), .seen = AT(modes), .min = 0, .max = HUGE_VAL,
     .what = "a time >= 0 in s",
     .help = "the modes at time T, 0 <= T <= t_end (default 0: the static start) instead of "
             "the run, the drift modes apart: modes.csv, "
             "modes.gp, modes.png (frequency against damping)"},
    {.name = "--error-estimate", .kind = PU_CLI_DOUBLE, .value = PU_CLI_OPTIONAL, .arg = "[K]",
     .at = AT(errest_factor), .seen = AT(errest), .min = 1, .min_open = 1,
     .max = RN_ERREST_MAX_FACTOR, .what = "a factor K with 1 < K <= 1e12",
     .help = "a second run at rtol / K and atol / K (default K = 100) beside the first over the "
             "same output times: error_estimate.csv, per output column the largest difference, "
             "an estimate of the first run's error"},
    {.name = "--quiet", .alias = "-q", .kind = PU_CLI_FLAG, .at = AT(quiet),
     .help = "no progress line and no summary (errors only)"},
    {.name = "--vtk", .kind = PU_CLI_CALL, .value = PU_CLI_NONE, .take = take_viz,
     .help = "ParaView time series: crane.pvd and vtk/frame_NNNNN.vtp"},
    {.name = "--vtk-step", .kind = PU_CLI_CALL, .arg = "DT", .take = take_viz,
     .help = "its frame interval in s (default 0.05; implies --vtk)"},
    {.name = "--animate", .kind = PU_CLI_CALL, .value = PU_CLI_NONE, .take = take_viz,
     .help = "animated GIF crane.gif (side and top view, with gnuplot)"},
    {.name = "--anim-step", .kind = PU_CLI_CALL, .arg = "DT", .take = take_viz,
     .help = "its frame interval in s (default 0.1; implies --animate)"},
    {.name = "--anim-scale", .kind = PU_CLI_CALL, .arg = "K", .take = take_viz,
     .help = "its magnification of the boom's deflection (default 10; implies --animate)"},
    {.name = "--list-keys", .kind = PU_CLI_STOP,
     .help = "every scene key with its section, type, range, default and meaning (Markdown, as "
             "docs/scene-keys.md)"},
    {.name = "--help", .alias = "-h", .kind = PU_CLI_STOP, .help = "this text"},
    {.name = "--version", .alias = "-V", .kind = PU_CLI_STOP, .help = "the program's version"},
};

static const pu_cli CLI = {
    .program = "crane",
    .usage = "[SCENE] [options]",
    .intro = "Simulates the hydraulically driven rotary crane (docs/crane.md) described by the\n"
             "scene file SCENE (default " CP_DEFAULT_SCENE
             "; a bare name such as 'rigid-boom' is looked up\n"
             "in crane/scenes/) and writes the results into DIR. A SCENE ending in .yaml is a model\n"
             "file (docs/model-format.md; a bare name such as 'paper.yaml' is looked up in\n"
             "crane/models/), run as bgsim runs it, with Fig. 5 on top; the options of INI scenes\n"
             "only (--elements, --animate, --anim-step, --anim-scale) are refused\n"
             "for it.\n",
    .options_title = "options (a value may also be given as --option=VALUE):",
    .epilogue =
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
        "signal N.\n",
    .options = OPTIONS,
    .noptions = (int)(sizeof OPTIONS / sizeof *OPTIONS),
    .positional = AT(scene),
    .positional_many = "more than one scene given ('%s' and '%s')",
    .suggest = 1,
    .column = 23,
    .width = 92,
};
/* clang-format on */

static int usage_error(const char *msg)
{
    fprintf(stderr, "crane: %s\n(crane --help lists the options)\n", msg);
    return RN_EXIT_USAGE;
}

/* The one rule for options that cannot go together: those of the dynamic run (they act on its
 * rows: --error-estimate, --vtk, --vtk-step, --animate, --anim-step, --anim-scale) are refused
 * with the analyses that make no run (--static, --modes). 0, or -1 with the message. */
static int check_combination(const cp_options *o, char *msg, size_t size)
{
    const char *analysis = o->static_only ? "--static" : o->modes ? "--modes" : NULL;
    const char *run_only = o->errest ? "--error-estimate" : o->viz_given;
    if (!analysis || !run_only) return 0;
    snprintf(msg, size,
             "option %s belongs to the dynamic run, not to %s (an analysis without a run: it "
             "would be ignored)",
             run_only, analysis);
    return -1;
}

/* Returns -1 to go on, or an exit status (help and version: 0). */
int cp_parse_args(int argc, char **argv, cp_options *o)
{
    memset(o, 0, sizeof *o);
    o->max_rows = CP_DEFAULT_MAX_ROWS;
    o->errest_factor = RN_ERREST_FACTOR; /* --error-estimate without K */
    o->argc = argc;
    o->argv = argv;
    const pu_cli_option *stop;
    char msg[512];
    int rc = pu_cli_parse(&CLI, argc, argv, o, &stop, msg, sizeof msg);
    /* a --set that is no SECTION.KEY=VALUE came before whatever stopped the parse: refused
     * unless the scene is a model file (its --set takes PATH=VALUE) */
    if (o->set_error[0] && !(o->scene && cp_is_model_file(o->scene)))
        return usage_error(o->set_error);
    if (rc == PU_CLI_ERROR) return usage_error(msg);
    if (rc == PU_CLI_STOPPED && !strcmp(stop->name, "--help")) {
        char *text = pu_cli_help(&CLI);
        if (!text) {
            fprintf(stderr, "crane: out of memory\n");
            return RN_EXIT_RUN;
        }
        fputs(text, stdout);
        free(text);
        return RN_EXIT_OK;
    }
    if (rc == PU_CLI_STOPPED && !strcmp(stop->name, "--list-keys"))
        return crane_scene_keys_markdown(stdout) ? RN_EXIT_RUN : RN_EXIT_OK;
    if (rc == PU_CLI_STOPPED) { /* --version */
        printf("crane (bgdae) %s\n", CRANE_VERSION);
        return RN_EXIT_OK;
    }
    if (check_combination(o, msg, sizeof msg) != 0) return usage_error(msg);
    return -1;
}

/* ---------------------------------------------------------------- files ---- */

/* Finds the scene: as given, then (bare names) in crane/scenes/ with or without .ini, relative
 * to the current folder, then to the source tree and the installed data folder. A candidate
 * that exists but is no regular file (a directory, a FIFO, a device) is remembered in odd (its
 * path and what it is), and so is one that stat cannot reach for another reason than its absence
 * (a loop of symbolic links: ELOOP; EACCES; ENAMETOOLONG, with the system's message), for the
 * message when nothing is found. */
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
            int e = stat(path, &st) == 0 ? 0 : errno;
            if (!e && S_ISREG(st.st_mode)) return 1;
            if (!e && !odd[0])
                snprintf(odd, osize, "%s is %s, not a scene file", path,
                         pu_fs_kind((unsigned)st.st_mode));
            /* there but unusable (a loop of symbolic links, a folder on the way that cannot be
             * searched, a name too long): the system's reason, not "not found" */
            if (e && e != ENOENT && e != ENOTDIR && !odd[0])
                snprintf(odd, osize, "%s: %s", path, strerror(e));
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
