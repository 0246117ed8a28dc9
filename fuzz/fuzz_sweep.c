/* libFuzzer target: the sweep-file reader of crane-sweep (crane/sweep/sweep_spec.h).
 *
 * The input is the text of a sweep file (up to its first NUL); the base scene is looked up in the
 * sources' crane/scenes/ (FUZZ_SCENE_DIR). Besides "no crash, no leak, no undefined behaviour",
 * the reader's documented properties are checked:
 *   - a refusal returns -1 with a message that starts with the file's name;
 *   - an accepted file has 1..SWEEP_MAX_CASES cases, 1..SWEEP_MAX_AXES axes whose points
 *     multiply to the number of cases, at most SWEEP_MAX_SETS --set arguments per case, every
 *     swept value non-empty; the first and last case's coordinates lie on their axes;
 *   - a list axis holds no value twice (a range none either: the reader refuses repeats);
 *   - the header of sweep.csv fits (sweep_csv_header) or says it does not (-1).
 * Inputs naming /proc, /sys or /dev are skipped (a scene or model path there reads the machine,
 * not the parser). A violated property ends the run with a message and __builtin_trap(). */
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sweep_row.h"
#include "sweep_spec.h"

#ifndef FUZZ_SCENE_DIR
#define FUZZ_SCENE_DIR "crane/scenes"
#endif
#define FILE_NAME "fuzz.ini"

/* crane-sweep's signal state (crane_sweep.c): never set here */
volatile sig_atomic_t sweep_signal = 0, sweep_signal_count = 0;

static void fail(const char *what, const char *detail)
{
    fprintf(stderr, "fuzz_sweep: %s%s%s\n", what, detail ? ": " : "", detail ? detail : "");
    __builtin_trap();
}

static void check_case(const sweep_spec *s, long c)
{
    int coord[SWEEP_MAX_AXES];
    sweep_case_coords(s, c, coord);
    for (int a = 0; a < s->naxes; a++)
        if (coord[a] < 0 || coord[a] >= s->axes[a].npoints)
            fail("a case's point off its axis", NULL);
    static char sets[SWEEP_MAX_SETS][SWEEP_SET_ARG_SIZE];
    int n = sweep_case_set_args(s, c, sets);
    if (n < 0 || n > SWEEP_MAX_SETS) fail("too many --set arguments", NULL);
    for (int p = 0; p < s->nparams; p++)
        if (!sweep_case_value(s, c, p)[0]) fail("an empty swept value", s->params[p].name);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    if (strstr(text, "/proc") || strstr(text, "/sys") || strstr(text, "/dev")) {
        free(text);
        return 0;
    }
    static const char *const roots[] = {FUZZ_SCENE_DIR, NULL};
    static sweep_spec s; /* large: not on the stack */
    char err[4096] = "";
    int rc = sweep_spec_parse(&s, text, FILE_NAME, roots, err, sizeof err);
    if (rc != 0) {
        if (rc != -1) fail("a refusal other than -1", err);
        if (strncmp(err, FILE_NAME, strlen(FILE_NAME)) != 0)
            fail("message does not start with the file name", err);
    } else {
        if (s.ncases < 1 || s.ncases > SWEEP_MAX_CASES) fail("number of cases out of range", NULL);
        if (s.naxes < 1 || s.naxes > SWEEP_MAX_AXES) fail("number of axes out of range", NULL);
        long prod = 1;
        for (int a = 0; a < s.naxes; a++) {
            const sweep_axis *ax = &s.axes[a];
            if (ax->npoints < 1) fail("an axis without points", NULL);
            prod *= ax->npoints;
            if (ax->kind != SWEEP_AXIS_LHS)
                for (int i = 1; i < ax->npoints && i < 64; i++)
                    for (int j = 0; j < i; j++)
                        if (!strcmp(ax->values[i], ax->values[j]))
                            fail("an axis holds a value twice", ax->values[i]);
        }
        if (prod != s.ncases) fail("the axes' points do not multiply to the cases", NULL);
        if (s.nsets + s.nparams > SWEEP_MAX_SETS) fail("too many keys", NULL);
        check_case(&s, 0);
        check_case(&s, s.ncases - 1);
        static char head[16384];
        int n = sweep_csv_header(&s, head, sizeof head);
        if (n > 0 && (size_t)n != strlen(head)) fail("sweep.csv's header length", head);
    }
    sweep_spec_free(&s);
    free(text);
    return 0;
}
