/* pu_cli.h: options found by name, both value forms, optional values (a negative number taken
 * and refused by range), typed values and their messages, suggestions, the generated help. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pu_cli.h"
#include "tap.h"

typedef struct opts {
    const char *pos, *out, *engine;
    int jobs, quiet, modes, ncalls;
    long long rows;
    double t, modes_t;
    const char *last_call;
} opts;

static int take_note(const pu_cli_option *opt, const char *value, void *base, char *msg,
                     size_t size)
{
    opts *o = base;
    if (value && !strcmp(value, "bad")) {
        snprintf(msg, size, "%s refuses '%s'", opt->name, value);
        return -1;
    }
    o->ncalls++;
    o->last_call = value ? value : "(none)";
    return 0;
}

#define AT(m) PU_CLI_AT(opts, m)
/* clang-format off: one option per entry, its fields in the order of pu_cli_option */
static const pu_cli_option OPT[] = {
    {.name = "--out", .kind = PU_CLI_STRING, .arg = "DIR", .at = AT(out), .help = "output folder"},
    {.name = "--jobs",
     .alias = "-j",
     .kind = PU_CLI_INT,
     .arg = "N",
     .at = AT(jobs),
     .min = 1,
     .max = 64,
     .what = "an integer in 1..64",
     .help = "cases at a time"},
    {.name = "--rows",
     .kind = PU_CLI_LLONG,
     .arg = "N",
     .at = AT(rows),
     .min = 1,
     .max = 1e12,
     .bad = "%s takes a whole number from 1 to 1e12, not '%s'",
     .help = "rows"},
    {.name = "--t-end",
     .kind = PU_CLI_DOUBLE,
     .arg = "T",
     .at = AT(t),
     .min = 0,
     .min_open = 1,
     .max = 100,
     .what = "a time in (0, 100] s",
     .help = "end time; a long description that has to be wrapped over more than one line of "
             "the help text by the generator"},
    {.name = "--modes",
     .kind = PU_CLI_DOUBLE,
     .value = PU_CLI_OPTIONAL,
     .arg = "[T]",
     .at = AT(modes_t),
     .seen = AT(modes),
     .min = 0,
     .max = HUGE_VAL,
     .what = "a time >= 0 in s",
     .help = "the modes at T"},
    {.name = "--engine",
     .kind = PU_CLI_CHOICE,
     .arg = "E",
     .at = AT(engine),
     .choices = "auto|local|mpi",
     .what = "auto, local or mpi",
     .help = "the engine"},
    {.name = "--note", .kind = PU_CLI_CALL, .arg = "X", .take = take_note, .help = "a note"},
    {.name = "--mark",
     .kind = PU_CLI_CALL,
     .value = PU_CLI_NONE,
     .take = take_note,
     .help = "a mark"},
    {.name = "--quiet", .alias = "-q", .kind = PU_CLI_FLAG, .at = AT(quiet), .help = "quiet"},
    {.name = "--secret", .kind = PU_CLI_FLAG, .hidden = 1},
    {.name = "--help", .alias = "-h", .kind = PU_CLI_STOP, .help = "this text"},
};
static const pu_cli CLI = {.program = "prog",
                           .usage = "[FILE] [options]",
                           .intro = "Does things.\n",
                           .options_title = "options:",
                           .epilogue = "exit status: 0.\n",
                           .options = OPT,
                           .noptions = (int)(sizeof OPT / sizeof *OPT),
                           .positional = AT(pos),
                           .positional_many = "two files ('%s' and '%s')",
                           .suggest = 1,
                           .column = 16,
                           .width = 60};
/* clang-format on */

static char msg[512];

/* Parses the NULL-terminated arguments (argv[0] "prog") into o. */
static int parse(opts *o, const char *const *args, const pu_cli_option **stop)
{
    char *argv[32];
    int argc = 0;
    argv[argc++] = "prog";
    for (int i = 0; args[i]; i++)
        argv[argc++] = (char *)args[i];
    memset(o, 0, sizeof *o);
    o->engine = "auto";
    return pu_cli_parse(&CLI, argc, argv, o, stop, msg, sizeof msg);
}

#define ARGS(...) ((const char *const[]){__VA_ARGS__, NULL})

static void test_values(void)
{
    opts o;
    int rc = parse(&o,
                   ARGS("--out", "dir", "-j", "4", "--rows=12", "--t-end", "2.5", "file",
                        "--engine=mpi", "-q"),
                   NULL);
    tap_ok(rc == PU_CLI_DONE && !strcmp(o.out, "dir") && o.jobs == 4 && o.rows == 12 &&
               o.t == 2.5 && !strcmp(o.pos, "file") && !strcmp(o.engine, "mpi") && o.quiet,
           "both forms, alias, every kind stored (rc %d: %s)", rc, msg);
    rc = parse(&o, ARGS("--", "-x"), NULL);
    tap_ok(rc == PU_CLI_DONE && !strcmp(o.pos, "-x"), "after -- an argument is positional");
    rc = parse(&o, ARGS("-"), NULL);
    tap_ok(rc == PU_CLI_DONE && !strcmp(o.pos, "-"), "'-' alone is positional");
    rc = parse(&o, ARGS("a", "b"), NULL);
    tap_ok(rc == PU_CLI_ERROR && !strcmp(msg, "two files ('a' and 'b')"), "second positional: %s",
           msg);
    rc = parse(&o, ARGS("--note", "n1", "--mark"), NULL);
    tap_ok(rc == PU_CLI_DONE && o.ncalls == 2 && !strcmp(o.last_call, "(none)"),
           "calls with and without a value");
    rc = parse(&o, ARGS("--note=bad"), NULL);
    tap_ok(rc == PU_CLI_ERROR && !strcmp(msg, "--note refuses 'bad'"), "a call's message: %s", msg);
}

static void test_errors(void)
{
    opts o;
    struct {
        const char *const *args;
        const char *want;
    } bad[] = {
        {ARGS("--jobs", "0"), "option --jobs needs an integer in 1..64 (got '0')"},
        {ARGS("-j", "65"), "option --jobs needs an integer in 1..64 (got '65')"},
        {ARGS("--jobs=+3"), "option --jobs needs an integer in 1..64 (got '+3')"},
        {ARGS("--jobs", "0x10"), "option --jobs needs an integer in 1..64 (got '0x10')"},
        {ARGS("--rows", "0"), "--rows takes a whole number from 1 to 1e12, not '0'"},
        {ARGS("--t-end", "0"), "option --t-end needs a time in (0, 100] s (got '0')"},
        {ARGS("--t-end", "nan"), "option --t-end needs a time in (0, 100] s (got 'nan')"},
        {ARGS("--t-end", "0x1p3"), "option --t-end needs a time in (0, 100] s (got '0x1p3')"},
        {ARGS("--t-end", "1e999"), "option --t-end needs a time in (0, 100] s (got '1e999')"},
        {ARGS("--engine", "pvm"), "option --engine needs auto, local or mpi (got 'pvm')"},
        {ARGS("--out"), "option --out needs a value"},
        {ARGS("--out="), "option --out needs a value (got '')"},
        {ARGS("--out", "--quiet"), "option --out needs a value (got the option '--quiet')"},
        {ARGS("--quiet=1"), "option --quiet takes no value (got '1')"},
        {ARGS("--mark=1"), "option --mark takes no value (got '1')"},
        {ARGS("--qiuet"), "unknown option '--qiuet'; did you mean --quiet?"},
        {ARGS("--modes", "-1"), "option --modes needs a time >= 0 in s (got '-1')"},
        {ARGS("--modes=-0.5"), "option --modes needs a time >= 0 in s (got '-0.5')"},
        {ARGS("--modes="), "option --modes needs a time >= 0 in s (got '')"},
        {ARGS("--a-very-long-option-name-that-goes-on-and-on-beyond-sixty-three-characters"),
         "unknown option '--a-very-long-option-name-that-goes-on-a...'"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        int rc = parse(&o, bad[i].args, NULL);
        tap_ok(rc == PU_CLI_ERROR && !strcmp(msg, bad[i].want), "%s %s: '%s'", bad[i].args[0],
               bad[i].args[1] ? bad[i].args[1] : "", msg);
    }
    /* the hidden option is parsed but never suggested */
    int rc = parse(&o, ARGS("--secret"), NULL);
    tap_ok(rc == PU_CLI_DONE, "a hidden option is parsed");
    rc = parse(&o, ARGS("--secre"), NULL);
    tap_ok(rc == PU_CLI_ERROR && strstr(msg, "did you mean") && !strstr(msg, "--secret"),
           "a hidden option is never suggested: '%s'", msg);
}

static void test_optional(void)
{
    opts o;
    int rc = parse(&o, ARGS("--modes"), NULL);
    tap_ok(rc == PU_CLI_DONE && o.modes && o.modes_t == 0, "--modes alone: seen, default time");
    rc = parse(&o, ARGS("--modes", "0.5", "file"), NULL);
    tap_ok(rc == PU_CLI_DONE && o.modes_t == 0.5 && !strcmp(o.pos, "file"),
           "--modes 0.5 takes the number, the file stays positional");
    rc = parse(&o, ARGS("--modes", "file.ini"), NULL);
    tap_ok(rc == PU_CLI_DONE && o.modes && o.modes_t == 0 && !strcmp(o.pos, "file.ini"),
           "--modes FILE: the file is no time");
    rc = parse(&o, ARGS("--modes", "-q"), NULL);
    tap_ok(rc == PU_CLI_DONE && o.modes && o.quiet, "--modes -q: the option is no time");
    rc = parse(&o, ARGS("--modes=3"), NULL);
    tap_ok(rc == PU_CLI_DONE && o.modes_t == 3, "--modes=3");
}

static void test_stop_and_lookup(void)
{
    opts o;
    const pu_cli_option *stop = NULL;
    int rc = parse(&o, ARGS("-q", "-h", "--jobs", "0"), &stop);
    tap_ok(rc == PU_CLI_STOPPED && stop && !strcmp(stop->name, "--help") && o.quiet,
           "-h stops before the rest is read");
    tap_ok(pu_cli_find(&CLI, "-j") == &OPT[1] && pu_cli_find(&CLI, "--jobs") == &OPT[1] &&
               !pu_cli_find(&CLI, "--job"),
           "pu_cli_find by name and alias");
    int d;
    tap_ok(pu_cli_nearest(&CLI, "--ot", &d) == &OPT[0] && d == 1, "nearest --ot: --out at 1");
    tap_ok(pu_cli_edit_distance("lenght", "LENGTH") == 1 && pu_cli_edit_distance("", "abc") == 3,
           "edit distance: a swap counts 1, case ignored");
}

static void test_help(void)
{
    char *h = pu_cli_help(&CLI);
    tap_ok(h != NULL, "help text made");
    if (!h) return;
    tap_ok(!strncmp(h, "usage: prog [FILE] [options]\n\nDoes things.\n\noptions:\n", 52),
           "usage line, intro, title");
    tap_ok(strstr(h, "\n  --out DIR     output folder\n") != NULL, "an option at the column");
    tap_ok(strstr(h, "\n  --jobs N      cases at a time\n") != NULL, "--jobs line");
    tap_ok(strstr(h, "\n  --modes [T]   the modes at T\n") != NULL, "an optional value shown");
    tap_ok(strstr(h, "--secret") == NULL, "a hidden option is left out");
    int longest = 0, n = 0;
    for (const char *p = h; *p; p++) {
        n = *p == '\n' ? 0 : n + 1;
        if (n > longest) longest = n;
    }
    tap_ok(longest <= 60, "lines within the width (longest %d)", longest);
    tap_ok(strstr(h, "\n                wrapped over") || strstr(h, "\n                the help"),
           "continuation lines indented to the column");
    size_t len = strlen(h);
    tap_ok(len > 16 && !strcmp(h + len - 16, "exit status: 0.\n"), "epilogue last");
    free(h);
    /* no usage given: the synopsis lists the options */
    pu_cli c2 = CLI;
    c2.usage = NULL;
    h = pu_cli_help(&c2);
    tap_ok(h && !strncmp(h, "usage: prog [--out DIR] [--jobs N]", 34),
           "synopsis generated from the table");
    int first_line = h ? (int)strcspn(h, "\n") : 0;
    tap_ok(h && first_line <= 60 && strstr(h, "\n            [") != NULL,
           "synopsis wrapped under the program's name");
    free(h);
}

int main(void)
{
    test_values();
    test_errors();
    test_optional();
    test_stop_and_lookup();
    test_help();
    return tap_done();
}
