/* libFuzzer target: the whole model-file reader (model/mdl_model.h: mdl_load_string), from the
 * YAML text through the instance tree, the type table's checks, the build, the bonds, the
 * compilation and the start, then the outputs at the start.
 *
 * Besides "no crash, no leak, no undefined behaviour", its documented contract is checked: a
 * refused model gives NULL and a message that begins with the file's name (every error of the
 * reader is positioned: "fuzz.yaml:LINE:COL: ..." or "fuzz.yaml: ..."); an accepted one has a
 * compiled bond graph with as many unknowns as equations and outputs that are finite or refused
 * with a message. The input is cut at 64 kB (the repetitions `for:` allow are bounded by the
 * reader). A violated property ends the run with __builtin_trap(). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bgr_model.h"
#include "mdl_model.h"

#define FILE_NAME "fuzz.yaml"

static void fail(const char *what, const char *detail)
{
    fprintf(stderr, "fuzz_model: %s%s%s\n", what, detail ? ": " : "", detail ? detail : "");
    __builtin_trap();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > 65536) size = 65536;
    char *text = malloc(size + 1);
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = 0;
    if (strlen(text) != size) { /* a NUL inside: the string API cannot carry it */
        free(text);
        return 0;
    }
    bg_error e = {0};
    mdl_model *mm = mdl_load_string(text, FILE_NAME, NULL, 0, &e);
    free(text);
    if (!mm) {
        if (strncmp(e.message, FILE_NAME, strlen(FILE_NAME)) && e.status != BG_ERR_MEMORY)
            fail("a refusal without the file's name", e.message);
        return 0;
    }
    bgr_model *m = mdl_bgr(mm);
    int n = bgr_n(m);
    if (n < 1 || !bgr_y0(m)) fail("an accepted model without unknowns", NULL);
    int no = mdl_noutputs(mm);
    double *out = malloc((size_t)(no > 0 ? no : 1) * sizeof *out);
    if (out && mdl_outputs(mm, 0.0, bgr_y0(m), out, &e) == BG_OK)
        for (int i = 0; i < no; i++)
            if (!isfinite(out[i]) && isfinite(bgr_y0(m)[0])) {
                /* an output of finite unknowns may still overflow: it must then be refused */
                fail("an output not finite without an error", mdl_output_name(mm, i));
            }
    free(out);
    mdl_free(&mm);
    return 0;
}
