/* The scene keys' table (crane/crane_scene_keys.c) as the one source of the keys:
 * docs/scene-keys.md is exactly the key list it generates (crane_scene_keys_markdown, which crane
 * --list-keys prints), every field of crane_scene has its key (the fields' bytes covered, padding
 * apart), and crane_scene_default is the table's defaults. Argument: the path of
 * docs/scene-keys.md. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "crane_scene.h"
#include "crane_scene_impl.h"
#include "tap.h"

/* The whole file at path (NUL-terminated, *len bytes), or NULL. */
static char *slurp(FILE *f, size_t *len)
{
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    for (size_t got; buf && (got = fread(buf + n, 1, cap - 1 - n, f)) > 0;) {
        n += got;
        if (n + 1 == cap) {
            char *nb = realloc(buf, cap *= 2);
            if (!nb) free(buf);
            buf = nb;
        }
    }
    if (buf) buf[n] = '\0';
    *len = n;
    return buf;
}

/* The 1-based line where a and b first differ, 0 if they are equal. */
static int first_difference(const char *a, const char *b, const char **la, const char **lb)
{
    int line = 1;
    *la = a, *lb = b;
    for (; *a && *a == *b; a++, b++)
        if (*a == '\n') line++, *la = a + 1, *lb = b + 1;
    return *a == *b ? 0 : line;
}

static void test_docs(const char *path)
{
    FILE *g = tmpfile(), *f = fopen(path, "rb");
    tap_ok(g && crane_scene_keys_markdown(g) == BG_OK, "the key list is generated");
    tap_ok(f != NULL, "%s is there", path);
    if (!g || !f) {
        if (g) fclose(g);
        if (f) fclose(f);
        return;
    }
    rewind(g);
    size_t ng, nf;
    char *gen = slurp(g, &ng), *doc = slurp(f, &nf);
    fclose(g);
    fclose(f);
    const char *lg = "", *ld = "";
    int line = gen && doc ? first_difference(doc, gen, &ld, &lg) : -1;
    tap_ok(line == 0 && ng == nf,
           "%s is the key list of the table (else regenerate it: crane --list-keys > "
           "docs/scene-keys.md)",
           path);
    if (line > 0) {
        tap_diag("first difference on line %d", line);
        tap_diag("  file:  %.*s", (int)strcspn(ld, "\n"), ld);
        tap_diag("  table: %.*s", (int)strcspn(lg, "\n"), lg);
    }
    free(gen);
    free(doc);
}

static size_t field_size(const key_def *k)
{
    switch (k->pub.type) {
    case CRANE_KEY_NUMBER:
        return sizeof(double);
    case CRANE_KEY_VECTOR:
        return 3 * sizeof(double);
    case CRANE_KEY_INTEGER:
    case CRANE_KEY_BOOLEAN:
        return sizeof(int);
    case CRANE_KEY_NAME:
        return sizeof((crane_scene *)0)->name;
    }
    return 0;
}

/* Every byte of crane_scene belongs to one key's field or is padding before a double: a field
 * without a key leaves a gap, two keys on one field overlap. */
static void test_coverage(void)
{
    static unsigned char owner[sizeof(crane_scene)];
    int overlap = 0;
    memset(owner, 0, sizeof owner);
    for (int i = 0; i < CRANE_SCENE_NKEYS; i++) {
        const key_def *k = &crane_scene_keys[i];
        for (size_t b = k->off; b < k->off + field_size(k) && b < sizeof owner; b++)
            overlap += owner[b]++ > 0;
    }
    /* a gap is padding only if it ends at a double's alignment and starts off it */
    size_t unowned = 0;
    for (size_t b = 0, a; b < sizeof owner;) {
        if (owner[b]) {
            b++;
            continue;
        }
        for (a = b; b < sizeof owner && !owner[b]; b++)
            ;
        if (b - a >= sizeof(double) || a % sizeof(double) == 0 || b % sizeof(double) != 0)
            unowned += b - a;
    }
    tap_ok(overlap == 0, "no two keys share a field (%d bytes)", overlap);
    tap_ok(unowned == 0, "every field of crane_scene has its key (%zu bytes without)", unowned);
    tap_ok(crane_scene_nkeys() == CRANE_SCENE_NKEYS, "crane_scene_nkeys counts the table");
}

/* crane_scene_default sets each field to the table's default and nothing else. */
static void test_defaults(void)
{
    crane_scene s, z;
    int bad = 0;
    crane_scene_default(&s);
    memset(&z, 0, sizeof z);
    for (int i = 0; i < CRANE_SCENE_NKEYS; i++) {
        const key_def *k = &crane_scene_keys[i];
        const char *p = (const char *)&s + k->off;
        int ok = 1;
        if (k->pub.type == CRANE_KEY_NUMBER || k->pub.type == CRANE_KEY_VECTOR) {
            double v[3];
            memcpy(v, p, field_size(k));
            for (size_t j = 0; j < field_size(k) / sizeof(double); j++)
                ok = ok && v[j] == k->def[j];
        } else if (k->pub.type == CRANE_KEY_NAME) {
            ok = !strcmp(p, k->def_name);
        } else {
            int v;
            memcpy(&v, p, sizeof v);
            ok = v == (int)k->def[0] && v == k->def[0];
        }
        if (!ok) tap_diag("[%s] %s: not the table's default", k->pub.section, k->pub.key);
        bad += !ok;
    }
    tap_ok(bad == 0, "crane_scene_default gives every key the table's default");
    tap_ok(crane_scene_compare(&s, &z, NULL, 0) > 0, "and the defaults are not all zero");
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: test_crane_scene_keys docs/scene-keys.md\n");
        return 2;
    }
    test_docs(argv[1]);
    test_coverage();
    test_defaults();
    return tap_done();
}
