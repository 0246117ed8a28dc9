/* The YAML tree of the model files (model/mdl_yaml.h): kinds, texts, quoted vs plain, key order,
 * the exact line and column of nodes and keys, lookups, aliases, and the refusals with their
 * "FILE:LINE:COL: message": syntax errors, duplicate keys, non-scalar keys, tags, NUL
 * characters, a second document, unknown aliases, an alias bomb, deep nesting; files. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mdl_yaml.h"
#include "tap.h"

static mdl_y_doc *load(const char *text, const char *name)
{
    mdl_y_doc *d = NULL;
    mdl_y_error e;
    if (mdl_y_load_string(text, strlen(text), name, &d, &e) != 0)
        tap_diag("load %s: %s", name, e.message);
    return d;
}

/* n is a node of the kind at line:column (and a scalar with the text when text is given). */
static int at(const mdl_y_node *n, mdl_y_kind kind, int line, int column, const char *text,
              const char *what)
{
    int ok = n && n->kind == kind && n->line == line && n->column == column &&
             (!text || (n->kind == MDL_Y_SCALAR && !strcmp(n->text, text)));
    if (!tap_ok(ok, "%s: %s at %d:%d%s%s", what, mdl_y_kind_name(kind), line, column,
                text ? " " : "", text ? text : ""))
        tap_diag("got %s at %d:%d '%s'", n ? mdl_y_kind_name(n->kind) : "NULL", n ? n->line : 0,
                 n ? n->column : 0, n && n->text ? n->text : "");
    return ok;
}

/* Loading text fails with exactly message. */
static void refused(const char *text, size_t len, const char *message, const char *what)
{
    mdl_y_doc *d = (mdl_y_doc *)1;
    mdl_y_error e;
    int r = mdl_y_load_string(text, len, "bad.yaml", &d, &e);
    if (!tap_ok(r < 0 && d == NULL && !strcmp(e.message, message), "%s: %s", what, message))
        tap_diag("got %d: '%s'", r, e.message);
    mdl_y_free(r == 0 ? d : NULL);
}

static const char model[] = "name: crane\n"              /* 1 */
                            "params:\n"                  /* 2 */
                            "  mass: 12.5\n"             /* 3 */
                            "  label: \"1e3\"\n"         /* 4 */
                            "  expr: 2*pi   # comment\n" /* 5 */
                            "components:\n"              /* 6 */
                            "  - type: hyd_pump\n"       /* 7 */
                            "    p: [1, 'two', 3]\n"     /* 8 */
                            "  - {type: rot, j: 0.1}\n"  /* 9 */
                            "text: |\n"                  /* 10 */
                            "  two lines\n"              /* 11 */
                            "  here\n"                   /* 12 */
                            "empty:\n"                   /* 13 */
                            "\xc3\xa4: \xc3\xb6\n";      /* 14: a-umlaut: o-umlaut */

static void test_tree(void)
{
    mdl_y_doc *d = load(model, "model.yaml");
    const mdl_y_node *r = mdl_y_root(d);
    at(r, MDL_Y_MAPPING, 1, 1, NULL, "root");
    tap_ok(mdl_y_count(r) == 6, "six pairs at the top (%d)", mdl_y_count(r));
    const char *order[] = {"name", "params", "components", "text", "empty", "\xc3\xa4"};
    int in_order = 1;
    for (int i = 0; i < 6; i++)
        in_order &= mdl_y_key(r, i) && !strcmp(mdl_y_key(r, i)->text, order[i]);
    tap_ok(in_order, "keys in the document's order");
    at(mdl_y_key(r, 0), MDL_Y_SCALAR, 1, 1, "name", "key name");
    at(mdl_y_value(r, 0), MDL_Y_SCALAR, 1, 7, "crane", "value of name");
    const mdl_y_node *p = mdl_y_get(r, "params");
    at(mdl_y_get_key(r, "params"), MDL_Y_SCALAR, 2, 1, "params", "key params");
    at(p, MDL_Y_MAPPING, 3, 3, NULL, "params");
    at(mdl_y_get_key(p, "mass"), MDL_Y_SCALAR, 3, 3, "mass", "key mass");
    const mdl_y_node *mass = mdl_y_get(p, "mass");
    at(mass, MDL_Y_SCALAR, 3, 9, "12.5", "mass");
    tap_ok(mass && !mass->quoted && mass->len == 4, "mass is plain");
    const mdl_y_node *label = mdl_y_get(p, "label");
    at(label, MDL_Y_SCALAR, 4, 10, "1e3", "label (at its quote)");
    tap_ok(label && label->quoted, "\"1e3\" is quoted");
    at(mdl_y_get(p, "expr"), MDL_Y_SCALAR, 5, 9, "2*pi", "expr, comment dropped");
    const mdl_y_node *c = mdl_y_get(r, "components");
    at(c, MDL_Y_SEQUENCE, 7, 3, NULL, "components");
    tap_ok(mdl_y_count(c) == 2, "two components");
    const mdl_y_node *c0 = mdl_y_item(c, 0);
    at(c0, MDL_Y_MAPPING, 7, 5, NULL, "component 0");
    at(mdl_y_get_key(c0, "type"), MDL_Y_SCALAR, 7, 5, "type", "key type");
    at(mdl_y_get(c0, "type"), MDL_Y_SCALAR, 7, 11, "hyd_pump", "type");
    const mdl_y_node *pl = mdl_y_get(c0, "p");
    at(pl, MDL_Y_SEQUENCE, 8, 8, NULL, "flow sequence");
    at(mdl_y_item(pl, 0), MDL_Y_SCALAR, 8, 9, "1", "item 0");
    at(mdl_y_item(pl, 1), MDL_Y_SCALAR, 8, 12, "two", "item 1");
    at(mdl_y_item(pl, 2), MDL_Y_SCALAR, 8, 19, "3", "item 2");
    tap_ok(mdl_y_item(pl, 1) && mdl_y_item(pl, 1)->quoted && !mdl_y_item(pl, 2)->quoted,
           "'two' quoted, 3 plain");
    const mdl_y_node *c1 = mdl_y_item(c, 1);
    at(c1, MDL_Y_MAPPING, 9, 5, NULL, "flow mapping");
    at(mdl_y_get_key(c1, "j"), MDL_Y_SCALAR, 9, 17, "j", "key j");
    at(mdl_y_get(c1, "j"), MDL_Y_SCALAR, 9, 20, "0.1", "j");
    const mdl_y_node *t = mdl_y_get(r, "text");
    at(t, MDL_Y_SCALAR, 10, 7, "two lines\nhere\n", "literal block");
    tap_ok(t && t->quoted && t->len == 15, "a block scalar counts as quoted");
    const mdl_y_node *empty = mdl_y_get(r, "empty");
    tap_ok(mdl_y_is_null(empty) && !mdl_y_is_null(mass) && empty->line == 13,
           "an empty value is null (line %d)", empty ? empty->line : 0);
    at(mdl_y_get(r, "\xc3\xa4"), MDL_Y_SCALAR, 14, 4, "\xc3\xb6", "columns count characters");
    char where[64];
    tap_ok(!strcmp(mdl_y_where(mass, where, sizeof where), "model.yaml:3:9"), "mdl_y_where: %s",
           where);
    tap_ok(!strcmp(mdl_y_where(NULL, where, sizeof where), "?"), "mdl_y_where of NULL");
    tap_ok(!mdl_y_get(r, "nosuch") && !mdl_y_get(mass, "x") && !mdl_y_item(c, 2) &&
               !mdl_y_item(c, -1) && !mdl_y_key(c, 0) && mdl_y_count(mass) == 0,
           "lookups out of range or of the wrong kind give NULL");
    tap_ok(mass && !strcmp(mass->file, "model.yaml") && !strcmp(mdl_y_file(d), "model.yaml"),
           "nodes carry the file name");
    mdl_y_free(d);
}

static void test_small_documents(void)
{
    mdl_y_doc *d = load("", "empty.yaml");
    tap_ok(d && mdl_y_root(d) == NULL, "an empty text: a document without a root");
    mdl_y_free(d);
    d = load("# only a comment\n", "c.yaml");
    tap_ok(d && mdl_y_root(d) == NULL, "only comments: no root");
    mdl_y_free(d);
    d = load("---\n42\n...\n", "s.yaml");
    at(mdl_y_root(d), MDL_Y_SCALAR, 2, 1, "42", "a scalar document");
    mdl_y_free(d);
    d = load("a: !!str 12\nb: ! 13\n", "t.yaml");
    const mdl_y_node *a = mdl_y_get(mdl_y_root(d), "a");
    tap_ok(a && a->quoted && !strcmp(a->text, "12") && a->column == 4, "!!str makes a string");
    tap_ok(mdl_y_get(mdl_y_root(d), "b") && mdl_y_get(mdl_y_root(d), "b")->quoted,
           "the non-specific tag too");
    mdl_y_free(d);
    d = load("a: {x: 1}\nb: {x: 2}\n", "k.yaml");
    tap_ok(d != NULL, "the same key in two mappings is no duplicate");
    mdl_y_free(d);
}

static void test_aliases(void)
{
    mdl_y_doc *d = load("base: &b\n  m: 1\n  n: [2, 3]\nuse: *b\nv: &s 5\nw: *s\n", "a.yaml");
    const mdl_y_node *r = mdl_y_root(d);
    const mdl_y_node *base = mdl_y_get(r, "base"), *use = mdl_y_get(r, "use");
    tap_ok(base && base == use, "an alias shares the anchored node");
    at(use, MDL_Y_MAPPING, 1, 7, NULL, "the alias has the anchor's position");
    at(mdl_y_get(r, "w"), MDL_Y_SCALAR, 5, 4, "5", "a scalar alias");
    mdl_y_free(d);
    refused("a: *nope\n", 9, "bad.yaml:1:4: alias '*nope' refers to no anchor defined before it",
            "unknown alias");
    refused("a: &x [1, *x]\n", 14,
            "bad.yaml:1:11: alias '*x' refers to no anchor defined before it",
            "an alias inside its own anchor");
    /* 10 levels of 10 aliases: 10^10 nodes */
    char bomb[2048];
    int k = snprintf(bomb, sizeof bomb, "l0: &l0 [x, x, x, x, x, x, x, x, x, x]\n");
    for (int i = 1; i < 10; i++) {
        k += snprintf(bomb + k, sizeof bomb - (size_t)k, "l%d: &l%d [", i, i);
        for (int j = 0; j < 10; j++)
            k += snprintf(bomb + k, sizeof bomb - (size_t)k, "*l%d%s", i - 1, j < 9 ? ", " : "]\n");
    }
    mdl_y_error e;
    d = NULL;
    int rr = mdl_y_load_string(bomb, strlen(bomb), "bomb.yaml", &d, &e);
    tap_ok(rr < 0 && !d && strstr(e.message, "bomb.yaml:") == e.message &&
               strstr(e.message, "more than 1000000 nodes with its aliases expanded"),
           "the billion laughs are refused: %s", e.message);
}

static void test_refusals(void)
{
    refused("a: 1\nb: 2\na: 3\n", 15, "bad.yaml:3:1: duplicate key 'a' (first at line 1)",
            "duplicate key");
    refused("m:\n  mass: 1\n  k: 2\n  mass: 3\n", 30,
            "bad.yaml:4:3: duplicate key 'mass' (first at line 2)", "nested duplicate key");
    refused("{x: 1, \"x\": 2}", 14, "bad.yaml:1:8: duplicate key 'x' (first at line 1)",
            "quoted and plain keys are the same key");
    refused("a: 1\n---\nb: 2\n", 14,
            "bad.yaml:2:1: a model file holds one YAML document; a second one starts here",
            "a second document");
    refused("? [a]\n: 1\n", 10, "bad.yaml:1:3: a mapping key must be a scalar, not a sequence",
            "a sequence as key");
    refused("a: !!int 12\n", 12, "bad.yaml:1:4: tags are not supported ('tag:yaml.org,2002:int')",
            "other tags");
    refused("a: \"x\\0y\"\n", 10, "bad.yaml:1:4: a scalar holds a NUL character", "NUL escape");
    refused("a: 1\nb: x\0y\n", 11, "bad.yaml:2:5: NUL character in the text", "NUL byte");
    refused("a: b: c\n", 8, "bad.yaml:1:5: mapping values are not allowed in this context",
            "a scanner error");
    refused("a: [1, 2\nb: 3\n", 14,
            "bad.yaml:2:2: did not find expected ',' or ']' (while parsing a flow sequence at line "
            "1, column 4)",
            "an unclosed flow sequence");
    refused("a:\n  b: 1\n c: 2\n", 16,
            "bad.yaml:3:2: did not find expected key (while parsing a block mapping at line 1, "
            "column 1)",
            "bad indentation");
    refused("a: 1\n\tb: 2\n", 11,
            "bad.yaml:2:1: found a tab character that violates indentation (while scanning a "
            "plain scalar at line 1, column 4)",
            "a tab");
    refused("a: ok\nb: \xff\n", 11, "bad.yaml:2:4: invalid leading UTF-8 octet (byte 0xFF)",
            "invalid UTF-8");
    char deep[20001];
    memset(deep, '[', 10000);
    memset(deep + 10000, ']', 10000);
    deep[20000] = '\0';
    refused(deep, 20000, "bad.yaml:1:65: collections nested too deeply (more than 64 levels)",
            "10000 nested flow sequences");
    char block[4096];
    int k = 0;
    for (int i = 0; i < 70; i++)
        k += snprintf(block + k, sizeof block - (size_t)k, "%*sk%d:\n", i, "", i);
    mdl_y_error e;
    mdl_y_doc *d = NULL;
    int r = mdl_y_load_string(block, (size_t)k, "bad.yaml", &d, &e);
    tap_ok(r < 0 && !d && strstr(e.message, "nested too deeply"), "70 nested block mappings: %s",
           e.message);
    memset(deep, '[', 64);
    memset(deep + 64, ']', 64);
    d = NULL;
    r = mdl_y_load_string(deep, 128, "ok.yaml", &d, &e);
    tap_ok(r == 0 && d, "64 nested sequences are allowed");
    mdl_y_free(d);
    d = (mdl_y_doc *)1;
    r = mdl_y_load_string("a", 1, NULL, &d, &e);
    tap_ok(r == 0 && d && !strcmp(mdl_y_file(d), "<string>"), "a string without a name");
    mdl_y_free(d);
}

/* 5000 keys (the hash table grows several times), then a duplicate of the second one. */
static void test_many_keys(void)
{
    size_t size = 5001 * 16;
    char *text = malloc(size);
    int k = 0;
    for (int i = 0; i < 5000; i++)
        k += snprintf(text + k, size - (size_t)k, "key%d: %d\n", i, i);
    mdl_y_doc *d = NULL;
    mdl_y_error e;
    int r = mdl_y_load_string(text, (size_t)k, "many.yaml", &d, &e);
    const mdl_y_node *v = mdl_y_get(mdl_y_root(d), "key4321");
    tap_ok(r == 0 && mdl_y_count(mdl_y_root(d)) == 5000 && v && !strcmp(v->text, "4321") &&
               v->line == 4322,
           "5000 keys load, in order");
    mdl_y_free(d);
    k += snprintf(text + k, size - (size_t)k, "key1: again\n");
    r = mdl_y_load_string(text, (size_t)k, "many.yaml", &d, &e);
    tap_ok(r < 0 && !strcmp(e.message, "many.yaml:5001:1: duplicate key 'key1' (first at line 2)"),
           "a duplicate among 5000 keys: %s", e.message);
    free(text);
}

static void test_files(void)
{
    char path[] = "/tmp/test_mdl_yaml_XXXXXX";
    int fd = mkstemp(path);
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (f) {
        fputs("model:\n  mass: 3\n  mass: 4\n", f);
        fclose(f);
    }
    mdl_y_doc *d = NULL;
    mdl_y_error e;
    char want[256];
    snprintf(want, sizeof want, "%s:3:3: duplicate key 'mass' (first at line 2)", path);
    tap_ok(mdl_y_load_file(path, &d, &e) < 0 && !strcmp(e.message, want) && e.line == 3 &&
               e.column == 3,
           "a file's error carries its name: %s", e.message);
    f = fopen(path, "w");
    if (f) {
        fputs("model:\n  mass: 3\n", f);
        fclose(f);
    }
    tap_ok(mdl_y_load_file(path, &d, &e) == 0 && d, "a file loads");
    const mdl_y_node *m = mdl_y_get(mdl_y_get(mdl_y_root(d), "model"), "mass");
    char where[300];
    snprintf(want, sizeof want, "%s:2:9", path);
    tap_ok(m && !strcmp(mdl_y_where(m, where, sizeof where), want), "position in a file: %s",
           where);
    mdl_y_free(d);
    remove(path);
    tap_ok(
        mdl_y_load_file("/nonexistent/model.yaml", &d, &e) < 0 && !d &&
            !strcmp(e.message, "/nonexistent/model.yaml: cannot open: No such file or directory"),
        "a missing file: %s", e.message);
}

int main(void)
{
    test_tree();
    test_small_documents();
    test_aliases();
    test_refusals();
    test_many_keys();
    test_files();
    return tap_done();
}
