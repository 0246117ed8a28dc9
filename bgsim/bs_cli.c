/* bgsim's command line (bgsim.h): the options' table (pu_cli.h: the parser and the --help text
 * generated from it), the type table's listings and --list-unknowns. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bgsim.h"
#include "mdl_types.h"
#include "pu_cli.h"

/* --set PATH=VALUE: a model parameter or a component's (mdl_set) */
static int take_set(const pu_cli_option *opt, const char *value, void *base, char *msg,
                    size_t size)
{
    (void)opt;
    bs_options *o = base;
    const char *eq = strchr(value, '=');
    if (!eq || eq == value || !eq[1]) {
        snprintf(msg, size, "--set expects PATH=VALUE (a parameter or COMPONENT.PARAM), got '%s'",
                 value);
        return -1;
    }
    if (eq - value >= (long)sizeof o->set_paths[0]) {
        snprintf(msg, size, "--set %.60s...: the path is longer than %zu characters", value,
                 sizeof o->set_paths[0] - 1);
        return -1;
    }
    if (o->nsets >= BS_MAX_SETS) {
        snprintf(msg, size, "too many --set (at most %d)", BS_MAX_SETS);
        return -1;
    }
    int k = o->nsets++;
    snprintf(o->set_paths[k], sizeof o->set_paths[k], "%.*s", (int)(eq - value), value);
    o->sets[k].path = o->set_paths[k];
    o->sets[k].value = eq + 1;
    return 0;
}

#define AT(m) PU_CLI_AT(bs_options, m)

/* clang-format off: one option per entry, its fields in the order of pu_cli_option */
static const pu_cli_option OPTIONS[] = {
    {.name = "--out", .kind = PU_CLI_STRING, .arg = "DIR", .at = AT(out),
     .help = "output folder (default results/<model name>/)"},
    {.name = "--set", .kind = PU_CLI_CALL, .arg = "PATH=VALUE", .take = take_set,
     .help = "replace a parameter before evaluation: a model parameter (--set L1=1.2) or a "
             "component's (--set rod1.m=2); the value is an expression"},
    {.name = "--t-end", .kind = PU_CLI_DOUBLE, .arg = "T", .at = AT(t_end), .seen = AT(has_t_end),
     .min = 0, .min_open = 1, .max = 1e300, .what = "a time > 0 in s",
     .help = "end time in s (the file's solver: t_end)"},
    {.name = "--rtol", .kind = PU_CLI_DOUBLE, .arg = "R", .at = AT(rtol), .seen = AT(has_rtol),
     .min = 0, .min_open = 1, .max = 1, .what = "a number in (0, 1]",
     .help = "relative tolerance (solver: rtol)"},
    {.name = "--atol", .kind = PU_CLI_DOUBLE, .arg = "A", .at = AT(atol), .seen = AT(has_atol),
     .min = 0, .min_open = 1, .max = 1e300, .what = "a number > 0",
     .help = "absolute tolerance (solver: atol)"},
    {.name = "--output-step", .kind = PU_CLI_DOUBLE, .arg = "DT", .at = AT(output_step),
     .seen = AT(has_output_step), .min = 0, .min_open = 1, .max = 1e300,
     .what = "a time > 0 in s", .help = "output interval in s (solver: output_step)"},
    {.name = "--max-rows", .kind = PU_CLI_LLONG, .arg = "N", .at = AT(max_rows), .min = 1,
     .max = (double)BS_MAX_MAX_ROWS, .what = "a decimal integer in 1..1000000000000",
     .help = "at most N output rows (default 1000000): t_end / output_step + 1 beyond it is "
             "refused"},
    {.name = "--static", .kind = PU_CLI_FLAG, .at = AT(static_only),
     .help = "the static equilibrium only (and the file's trim): static.txt, equilibrium.csv; "
             "no dynamic run"},
    {.name = "--modes", .kind = PU_CLI_DOUBLE, .value = PU_CLI_OPTIONAL, .arg = "[T]",
     .at = AT(modes_t), .seen = AT(modes), .min = 0, .max = HUGE_VAL,
     .what = "a time >= 0 in s",
     .help = "the modes at time T instead of the run: modes.csv (T = 0, the default: at the static "
             "equilibrium, with the file's trim; T > 0: at time T of a run from the start)"},
    {.name = "--error-estimate", .kind = PU_CLI_DOUBLE, .value = PU_CLI_OPTIONAL, .arg = "[K]",
     .at = AT(errest_factor), .seen = AT(errest), .min = 1, .min_open = 1,
     .max = RN_ERREST_MAX_FACTOR, .what = "a factor K with 1 < K <= 1e12",
     .help = "a second run at rtol / K and atol / K (default K = 100) beside the first over the "
             "same output times: error_estimate.csv, per output column the largest difference, "
             "an estimate of the first run's error"},
    {.name = "--vtk", .kind = PU_CLI_FLAG, .at = AT(vtk),
     .help = "ParaView time series model.pvd and vtk/frame_NNNNN.vtp: every body, point mass, "
             "support, axial member, cylinder and beam chain drawn (docs/bgsim.md)"},
    {.name = "--vtk-step", .kind = PU_CLI_DOUBLE, .arg = "DT", .at = AT(vtk_step),
     .seen = AT(has_vtk_step), .min = 0, .min_open = 1, .max = 1e300, .what = "a time > 0 in s",
     .help = "its frame interval in s (default: every output row; rounded to a whole number of "
             "output steps; implies --vtk)"},
    {.name = "--quiet", .alias = "-q", .kind = PU_CLI_FLAG, .at = AT(quiet),
     .help = "no progress line and no summary (errors only)"},
    {.name = "--list-types", .kind = PU_CLI_FLAG, .at = AT(list_types),
     .help = "the library's types with their summaries (with --markdown: docs/model-types.md)"},
    {.name = "--markdown", .kind = PU_CLI_FLAG, .at = AT(markdown),
     .help = "--list-types and --describe as Markdown"},
    {.name = "--describe", .kind = PU_CLI_STRING, .arg = "TYPE", .at = AT(describe),
     .help = "a type's parameters, ports, signals and equations"},
    {.name = "--list-unknowns", .kind = PU_CLI_FLAG, .at = AT(list_unknowns),
     .help = "the model's unknowns as `initial:` names them, their kinds and start values"},
    {.name = "--help", .alias = "-h", .kind = PU_CLI_STOP, .help = "this text"},
    {.name = "--version", .alias = "-V", .kind = PU_CLI_STOP, .help = "the program's version"},
};

static const pu_cli CLI = {
    .program = "bgsim",
    .usage = "MODEL [options]",
    .intro = "Runs the bond-graph model of the model file MODEL (docs/model-format.md) and\n"
             "writes the results into DIR.\n",
    .options_title = "options (a value may also be given as --option=VALUE):",
    .epilogue =
        "files in DIR: status.txt (\"running\" with the pid from the start, then completed,\n"
        "interrupted or failed, with the reason), model.yaml (the model as run), model_stats.txt,\n"
        "results.csv (t and the outputs, one row per output time), solver_stats.txt; static.txt\n"
        "(the static start and the trim: start: static, --static); equilibrium.csv (--static);\n"
        "modes.csv (--modes); model.pvd, vtk/ (--vtk); error_estimate.csv (--error-estimate).\n"
        "The files of an earlier run in DIR are removed at the start.\n"
        "SIGINT, SIGTERM and SIGHUP stop the run within a step; status.txt says so.\n"
        "exit status: 0 completed, 1 the run failed or a file could not be written, 2 bad\n"
        "command line or model file (nothing written), 128 + N interrupted by signal N.\n",
    .options = OPTIONS,
    .noptions = (int)(sizeof OPTIONS / sizeof *OPTIONS),
    .positional = AT(model),
    .positional_many = "more than one model given ('%s' and '%s')",
    .suggest = 1,
    .column = 23,
    .width = 92,
};
/* clang-format on */

static int usage_error(const char *msg)
{
    fprintf(stderr, "bgsim: %s\n(bgsim --help lists the options)\n", msg);
    return RN_EXIT_USAGE;
}

/* The types nearest to name by edit distance (up to three, within half the name's length). */
static void nearest_types(const char *name, char *buf, size_t size)
{
    int best[3] = {-1, -1, -1}, dist[3] = {0, 0, 0};
    for (int i = 0; i < mdl_type_count(); i++) {
        int d = pu_cli_edit_distance(name, mdl_type_at(i)->name);
        for (int j = 0; j < 3; j++)
            if (best[j] < 0 || d < dist[j]) {
                for (int q = 2; q > j; q--)
                    best[q] = best[q - 1], dist[q] = dist[q - 1];
                best[j] = i, dist[j] = d;
                break;
            }
    }
    size_t n = 0, lim = strlen(name) / 2 + 2;
    buf[0] = '\0';
    for (int j = 0; j < 3 && best[j] >= 0; j++)
        if ((size_t)dist[j] <= lim || j == 0)
            n += (size_t)snprintf(buf + n, n < size ? size - n : 0, "%s%s", n ? ", " : "",
                                  mdl_type_at(best[j])->name);
}

static int list_types(int markdown)
{
    if (markdown) return mdl_types_markdown(stdout) == BG_OK ? RN_EXIT_OK : RN_EXIT_RUN;
    int w = 0;
    for (int i = 0; i < mdl_type_count(); i++) {
        int l = (int)strlen(mdl_type_at(i)->name);
        if (l > w) w = l;
    }
    for (int i = 0; i < mdl_type_count(); i++)
        printf("%-*s  %s\n", w, mdl_type_at(i)->name, mdl_type_at(i)->summary);
    return RN_EXIT_OK;
}

static int describe(const char *name, int markdown)
{
    const mdl_type *t = mdl_type_find(name);
    if (!t) {
        char near[256];
        nearest_types(name, near, sizeof near);
        fprintf(stderr, "bgsim: --describe: unknown type '%s' (nearest: %s; bgsim --list-types "
                        "lists them)\n", name, near);
        return RN_EXIT_USAGE;
    }
    return mdl_type_describe(t, markdown, stdout) == BG_OK ? RN_EXIT_OK : RN_EXIT_RUN;
}

int bs_parse_args(int argc, char **argv, bs_options *o)
{
    memset(o, 0, sizeof *o);
    o->max_rows = BS_DEFAULT_MAX_ROWS;
    o->errest_factor = RN_ERREST_FACTOR; /* --error-estimate without K */
    o->argc = argc;
    o->argv = argv;
    const pu_cli_option *stop;
    char msg[512];
    int rc = pu_cli_parse(&CLI, argc, argv, o, &stop, msg, sizeof msg);
    if (rc == PU_CLI_ERROR) return usage_error(msg);
    if (rc == PU_CLI_STOPPED && !strcmp(stop->name, "--help")) {
        char *text = pu_cli_help(&CLI);
        if (!text) {
            fprintf(stderr, "bgsim: out of memory\n");
            return RN_EXIT_RUN;
        }
        fputs(text, stdout);
        free(text);
        return RN_EXIT_OK;
    }
    if (rc == PU_CLI_STOPPED) { /* --version */
        printf("bgsim (bgdae) %s\n", BGSIM_VERSION);
        return RN_EXIT_OK;
    }
    if (o->list_types && o->describe)
        return usage_error("--list-types and --describe: one of them");
    if (o->list_types) return list_types(o->markdown);
    if (o->describe) return describe(o->describe, o->markdown);
    if (o->markdown) return usage_error("--markdown belongs to --list-types or --describe");
    if (!o->model) return usage_error("no model file given (bgsim MODEL [options])");
    if (o->static_only && o->modes) return usage_error("--static and --modes: one of them");
    if (o->errest && (o->static_only || o->modes)) { /* as the crane refuses it */
        snprintf(msg, sizeof msg, "option --error-estimate belongs to the dynamic run, not to %s",
                 o->static_only ? "--static" : "--modes");
        return usage_error(msg);
    }
    if (o->has_vtk_step) o->vtk = 1;
    if (o->vtk && (o->static_only || o->modes))
        return usage_error(o->static_only ? "--vtk belongs to the dynamic run, not to --static"
                                          : "--vtk belongs to the dynamic run, not to --modes");
    return -1;
}

const char *bs_unknown_name(const mdl_model *mm, int var, char *buf, size_t size)
{
    const char *n = bgr_var_name(mdl_bgr((mdl_model *)mm), var), *model = mdl_name(mm);
    size_t l = strlen(model);
    if (!n) n = "?";
    if (!strncmp(n, model, l) && n[l] == '/') n += l + 1;
    snprintf(buf, size, "%s", n);
    for (char *p = buf; *p; p++)
        if (*p == '/') *p = '.';
    return buf;
}

int bs_list_unknowns(mdl_model *mm, FILE *f)
{
    bgr_model *m = mdl_bgr(mm);
    const int *kind = bgr_kinds(m);
    const double *y0 = bgr_y0(m);
    static const char *const KIND[] = {"differential", "algebraic", "algebraic (index 2)"};
    fprintf(f, "# %s: %d unknowns (name as `initial:` writes it, kind, start value)\n",
            mdl_name(mm), bgr_n(m));
    for (int i = 0; i < bgr_n(m); i++) {
        int k = kind && kind[i] >= 0 && kind[i] <= 2 ? kind[i] : 0;
        char name[1024];
        fprintf(f, "%s  %s  %.9g\n", bs_unknown_name(mm, i, name, sizeof name), KIND[k], y0[i]);
    }
    return ferror(f) ? RN_EXIT_RUN : RN_EXIT_OK;
}
