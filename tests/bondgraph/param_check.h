/* Checks of the parameter validation of the element constructors and component builders
 * (header-only, all static; used by the bond-graph and component tests).
 *
 * A case calls one constructor with one parameter replaced by a bad value. It passes when the
 * call is refused with BG_ERR_ARGUMENT, the message names the element by its path and the
 * constructor ("<component path>/<name> (<constructor>)"), the parameter and what was expected,
 * nothing was added to the model (elements, bonds and components counted before and after), and
 * the same name is then accepted with valid parameters (the refused element left no trace).
 * Each case is one test point. */
#ifndef BG_TESTS_PARAM_CHECK_H
#define BG_TESTS_PARAM_CHECK_H

#include <stdio.h>
#include <string.h>

#include "bgr_model.h"
#include "tap.h"

/* Builds the element name in component c of m with parameter which replaced by x, or with
 * valid parameters for which < 0. Returns the constructor's status (an element id, a
 * component for the chain builder, or < 0). */
typedef int (*pc_make)(bgr_model *m, bgr_comp c, const char *name, int which, double x);

typedef struct pc_case {
    const char *ctor; /* the constructor, named in the message as "(ctor)" */
    pc_make make;
    int which;          /* the parameter replaced (the make function's numbering) */
    double x;           /* its bad value */
    const char *param;  /* how the message names the parameter, e.g. "mass = " */
    const char *expect; /* what the message says was expected, e.g. "a finite number > 0" */
} pc_case;

TAP_UNUSED static void pc_counts(const bgr_model *m, int *cnt)
{
    bgr_stats s;
    memset(&s, 0, sizeof s);
    bgr_get_stats(m, &s); /* BG_ERR_STATE before compilation, the counts filled all the same */
    cnt[0] = s.elements;
    cnt[1] = s.bonds;
    cnt[2] = s.components;
}

/* The n cases in component c of m, the elements named <prefix>00, <prefix>01, ...; one test
 * point each. Returns how many passed. */
TAP_UNUSED static int pc_run(bgr_model *m, bgr_comp c, const char *prefix, const pc_case *t, int n)
{
    int passed = 0;
    for (int k = 0; k < n; k++) {
        char name[64], path[512], text[BG_MESSAGE_SIZE];
        int before[3], after[3];
        snprintf(name, sizeof name, "%s%02d", prefix, k);
        snprintf(path, sizeof path, "%s/%s (%s)", bgr_component_path(m, c), name, t[k].ctor);
        pc_counts(m, before);
        int st = t[k].make(m, c, name, t[k].which, t[k].x);
        snprintf(text, sizeof text, "%s", bgr_model_error(m)->message);
        pc_counts(m, after);
        int same = !memcmp(before, after, sizeof before);
        int again = st == BG_ERR_ARGUMENT ? t[k].make(m, c, name, -1, 0.0) : -1;
        int ok = st == BG_ERR_ARGUMENT && strstr(text, path) && strstr(text, t[k].param) &&
                 strstr(text, t[k].expect) && same && again >= 0;
        passed += ok;
        tap_ok(ok,
               "%s, bad value %g: refused (%d), names %s and '%s', nothing added%s, the "
               "name then accepted (%d): '%s'",
               t[k].ctor, t[k].x, st, path, t[k].param, same ? "" : " (but the model changed)",
               again, text);
        if (!ok && again < 0 && st == BG_ERR_ARGUMENT)
            tap_diag("the valid call after the refusal failed: %s", bgr_model_error(m)->message);
    }
    return passed;
}

#endif
