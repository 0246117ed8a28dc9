/* libFuzzer target: the model files' YAML loader (model/mdl_yaml.h) and, for every scalar of a
 * loaded document, the expression parser and evaluator (model/mdl_expr.h).
 *
 * Besides "no crash, no leak, no undefined behaviour", the modules' documented properties are
 * checked:
 *   - a refusal leaves no document and has a message that starts with the file's name;
 *   - an accepted document's nodes have positions >= 1:1 and the file's name, mapping keys are
 *     scalars, scalar texts have their stated length (no NUL inside);
 *   - an expression that does not parse has a message and a column within its text; one that
 *     parses lists its names (as many as mdl_expr_names counts), is constant exactly when it
 *     lists none, and evaluates either to a finite value or to an error with a message and a
 *     column within the text;
 *   - mdl_expr_subst on the scalar gives a path or an error with a message.
 * The walk visits at most WALK_MAX nodes (an accepted document may expand to 10^6 through its
 * aliases). A violated property ends the run with a message and __builtin_trap(). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mdl_expr.h"
#include "mdl_yaml.h"

#define FILE_NAME "fuzz.yaml"
#define WALK_MAX 2000

static void fail(const char *what, const char *detail)
{
    fprintf(stderr, "fuzz_model_yaml: %s%s%s\n", what, detail ? ": " : "", detail ? detail : "");
    __builtin_trap();
}

/* Every name has a value derived from its text, except those starting with 'u' (unknown). */
static int lookup(void *user, const char *name, double *value, char *msg, size_t msz)
{
    (void)user;
    if (name[0] == 'u') {
        snprintf(msg, msz, "no parameter '%s'", name);
        return -1;
    }
    *value = (double)(strlen(name) % 7) - 2;
    return 0;
}

static void count_name(void *user, const char *name)
{
    if (!name[0]) fail("mdl_expr_names visited an empty name", NULL);
    ++*(int *)user;
}

static void check_expr(const char *text)
{
    int len = (int)strlen(text);
    mdl_expr_error e = {-1, ""};
    mdl_expr *x = mdl_expr_parse(text, &e);
    if (!x) {
        if (!e.message[0]) fail("a parse error without a message", text);
        if (e.column < 0 || e.column > len) fail("a parse error's column outside the text", text);
    } else {
        int seen = 0;
        int n = mdl_expr_names(x, count_name, &seen);
        if (n != seen) fail("mdl_expr_names counts another number than it visits", text);
        if (mdl_expr_is_constant(x) != (n == 0)) fail("constant although it has names", text);
        if (strcmp(mdl_expr_text(x), text) != 0) fail("the expression's text differs", text);
        double v = 0;
        if (mdl_expr_eval(x, lookup, NULL, &v, &e) == 0) {
            if (!isfinite(v)) fail("a non-finite value evaluated without error", text);
        } else if (!e.message[0] || e.column < 0 || e.column > len) {
            fail("an evaluation error without a message or with a column outside", text);
        }
        mdl_expr_free(x);
    }
    char out[MDL_EXPR_NAME_MAX];
    e.message[0] = '\0';
    if (mdl_expr_subst(text, lookup, NULL, out, sizeof out, &e) != 0 && !e.message[0])
        fail("mdl_expr_subst failed without a message", text);
}

static void walk(const mdl_y_node *n, int *budget)
{
    if (!n || --*budget < 0) return;
    if (n->line < 1 || n->column < 1 || strcmp(n->file, FILE_NAME) != 0)
        fail("a node without a position in the file", NULL);
    switch (n->kind) {
    case MDL_Y_SCALAR:
        if (!n->text || strlen(n->text) != n->len) fail("a scalar's length is wrong", NULL);
        check_expr(n->text);
        break;
    case MDL_Y_SEQUENCE:
        for (int i = 0; i < n->n; i++) walk(mdl_y_item(n, i), budget);
        break;
    case MDL_Y_MAPPING:
        for (int i = 0; i < n->n; i++) {
            const mdl_y_node *k = mdl_y_key(n, i);
            if (!k || k->kind != MDL_Y_SCALAR) fail("a mapping key that is not a scalar", NULL);
            if (mdl_y_get(n, k->text) != mdl_y_value(n, i) && strlen(k->text) == k->len)
                fail("mdl_y_get does not find a key's value (duplicate keys?)", k->text);
            walk(k, budget);
            walk(mdl_y_value(n, i), budget);
        }
        break;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    mdl_y_doc *d = NULL;
    mdl_y_error e;
    int r = mdl_y_load_string((const char *)data, size, FILE_NAME, &d, &e);
    if (r != 0) {
        if (d) fail("a refusal left a document", e.message);
        if (strncmp(e.message, FILE_NAME ":", strlen(FILE_NAME) + 1) != 0)
            fail("the message does not start with the file name", e.message);
        return 0;
    }
    if (!d) fail("an accepted text without a document", NULL);
    int budget = WALK_MAX;
    walk(mdl_y_root(d), &budget);
    mdl_y_free(d);
    return 0;
}
