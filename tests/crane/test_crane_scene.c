/* Scene files (crane/crane_scene.h): the key table, the edit distance behind the suggestions,
 * exact round trips through crane_scene_write, the shipped scenes (paper.ini is exactly
 * crane_scene_default(); the others differ in what their names say; every key written out with a
 * comment), accepted syntax variants, a catalogue of malformed scenes (each refused with file,
 * line and key in the message), crane_scene_set / crane_scene_check, and that a scene builds only
 * the parts it asks for (the model's size). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "crane_model.h"
#include "crane_scene.h"
#include "pu_cli.h"
#include "tap.h"

#include "bad_scenes.h"

#ifndef CRANE_SCENES_DIR
#define CRANE_SCENES_DIR "crane/scenes"
#endif

static int contains(const char *hay, const char *needle)
{
    return needle == NULL || strstr(hay, needle) != NULL;
}

static void test_keys(void)
{
    int n = crane_scene_nkeys(), dup = 0, doc = 1;
    tap_ok(n >= 50, "the key table has %d keys", n);
    for (int i = 0; i < n; i++) {
        const crane_scene_key *a = crane_scene_key_at(i);
        doc = doc && a->meaning && a->meaning[0] && a->expected && a->expected[0] && a->unit;
        for (int j = i + 1; j < n; j++) {
            const crane_scene_key *b = crane_scene_key_at(j);
            if (!strcmp(a->section, b->section) && !strcmp(a->key, b->key)) dup++;
        }
    }
    tap_ok(dup == 0, "no key appears twice in a section");
    tap_ok(doc, "every key has a meaning, an expected range and a unit field");
    tap_ok(crane_scene_key_at(-1) == NULL && crane_scene_key_at(n) == NULL,
           "crane_scene_key_at outside the table is NULL");
}

static void test_distance(void)
{
    tap_ok(pu_cli_edit_distance("lenght", "length") == 1, "distance lenght/length = 1");
    tap_ok(pu_cli_edit_distance("bom", "boom") == 1, "distance bom/boom = 1");
    tap_ok(pu_cli_edit_distance("kitten", "sitting") == 3, "distance kitten/sitting = 3");
    tap_ok(pu_cli_edit_distance("", "abc") == 3, "distance to the empty string");
    tap_ok(pu_cli_edit_distance("I_LUFF", "i_luff") == 0, "distance ignores case");
}

static int parse_text(crane_scene *s, const char *text, bg_error *err)
{
    crane_scene_default(s);
    bg_error_clear(err);
    return crane_scene_parse_string(s, text, "bad.ini", err);
}

static void test_round_trip(void)
{
    crane_scene d, r;
    bg_error err = {0};
    char what[256];
    crane_scene_default(&d);
    tap_ok(crane_scene_check(&d, "default", &err) == BG_OK,
           "crane_scene_default passes the checks %s", err.message);

    /* default -> text -> scene */
    FILE *f = tmpfile();
    tap_ok(f && crane_scene_write(&d, f) == BG_OK, "crane_scene_write");
    if (!f) return;
    rewind(f);
    memset(&r, 0x5a, sizeof r);
    crane_scene_default(&r);
    strcpy(r.name, "other");
    int rc = crane_scene_parse_file(&r, f, "written.ini", &err);
    fclose(f);
    tap_ok(rc == BG_OK, "the written default parses back %s", err.message);
    tap_ok(crane_scene_compare(&d, &r, what, sizeof what) == 0, "and is the default exactly %s",
           what);

    /* awkward values survive exactly */
    crane_scene a = d;
    a.g = 0.1 + 0.2;
    a.boom_E = 1.0 / 3.0 * 1e11;
    a.boom_beta = 1e-300;
    a.platform_com[0] = -0.0;
    a.platform_com[1] = 123456789.123456789;
    a.boom_elements = 0;
    a.rope = 0;
    a.ties = 0;
    a.hydraulics = 0;
    a.ref_rate = -0.7;
    a.rtol = 0.999999999999;
    strcpy(a.name, "odd.name-1_x");
    f = tmpfile();
    crane_scene_write(&a, f);
    rewind(f);
    crane_scene_default(&r);
    rc = crane_scene_parse_file(&r, f, "odd.ini", &err);
    fclose(f);
    tap_ok(rc == BG_OK && crane_scene_compare(&a, &r, what, sizeof what) == 0,
           "awkward values round-trip exactly %s %s", err.message, what);
    tap_ok(crane_scene_compare(&a, &d, what, sizeof what) >= 10 &&
               !strncmp(what, "[scene] name: odd.name-1_x vs paper", 35),
           "crane_scene_compare counts and names differences (%s)", what);
}

/* Every field of crane_scene has a key: set every key in a scene filled with 0x00 bytes and in
 * one filled with 0xff; the bytes that still differ are padding (at most 4 in a row after an
 * int) or a field the table misses (8 aligned bytes). */
static void test_coverage(void)
{
    crane_scene a, b, d;
    crane_scene_default(&d);
    memset(&a, 0x00, sizeof a);
    memset(&b, 0xff, sizeof b);
    bg_error err = {0};
    int ok = 1;
    FILE *f = tmpfile();
    crane_scene_write(&d, f);
    rewind(f);
    ok = crane_scene_parse_file(&a, f, "a.ini", &err) == BG_OK;
    rewind(f);
    ok = crane_scene_parse_file(&b, f, "b.ini", &err) == BG_OK && ok;
    fclose(f);
    tap_ok(ok, "the default text parses into blank scenes %s", err.message);
    const unsigned char *pa = (const unsigned char *)&a, *pb = (const unsigned char *)&b;
    size_t uncovered = (size_t)-1;
    for (size_t i = 0; i + 8 <= sizeof a; i += 8) {
        int diff = 1;
        for (size_t k = i; k < i + 8; k++)
            diff = diff && pa[k] != pb[k];
        if (diff && uncovered == (size_t)-1) uncovered = i;
    }
    tap_ok(uncovered == (size_t)-1,
           "every field of crane_scene has a key (first uncovered "
           "byte offset %zu of %zu)",
           uncovered == (size_t)-1 ? (size_t)0 : uncovered, sizeof a);
}

/* Every key of the table appears in the file, in its section, with a comment. */
static void check_written_out(const char *path, const char *label)
{
    FILE *f = fopen(path, "r");
    int n = crane_scene_nkeys();
    int *seen = calloc((size_t)n, sizeof *seen);
    int uncommented = 0;
    char line[512], section[64] = "";
    while (f && fgets(line, sizeof line, f)) {
        char *p = line;
        while (*p == ' ' || *p == '\t')
            p++;
        if (*p == '[') {
            sscanf(p + 1, "%63[^]]", section);
            continue;
        }
        if (*p == ';' || *p == '#' || *p == '\n' || !*p) continue;
        char key[64];
        if (sscanf(p, "%63[^ =]", key) != 1) continue;
        for (int i = 0; i < n; i++) {
            const crane_scene_key *k = crane_scene_key_at(i);
            if (!strcmp(k->section, section) && !strcmp(k->key, key)) seen[i] = 1;
        }
        /* a comment on the line, or (for the few keys without unit) at least on the line */
        if (!strstr(p, " ;") && strcmp(key, "enabled")) uncommented++;
    }
    int missing = 0;
    const char *first = "";
    for (int i = 0; i < n; i++)
        if (!seen[i]) {
            if (!missing) first = crane_scene_key_at(i)->key;
            missing++;
        }
    tap_ok(f && missing == 0, "%s writes out every key (%d missing, first '%s')", label, missing,
           first);
    tap_ok(f && uncommented == 0, "%s comments every value (%d without)", label, uncommented);
    if (f) fclose(f);
    free(seen);
}

static void test_scenes(void)
{
    static const char *names[] = {"paper", "rigid-boom", "prescribed-rotation", "fine-mesh",
                                  "table-kg"};
    crane_scene d;
    crane_scene_default(&d);
    for (int i = 0; i < 5; i++) {
        char path[1024], what[256];
        snprintf(path, sizeof path, "%s/%s.ini", CRANE_SCENES_DIR, names[i]);
        crane_scene s, want = d;
        bg_error err = {0};
        int rc = crane_scene_load(&s, path, &err);
        tap_ok(rc == BG_OK, "%s.ini parses %s", names[i], err.message);
        snprintf(want.name, sizeof want.name, "%s", names[i]);
        if (i == 1) want.boom_elements = 0;
        if (i == 2) want.hydraulics = 0;
        if (i == 3) want.boom_elements = 64;
        if (i == 4) {
            want.platform_mass = 53;
            want.load_mass = 60.526;
            want.cw_mass = 150;
        }
        int ndiff = crane_scene_compare(&want, &s, what, sizeof what);
        if (i == 0)
            tap_ok(ndiff == 0, "paper.ini is exactly crane_scene_default() %s", what);
        else
            tap_ok(ndiff == 0, "%s.ini differs from the default only where its name says %s",
                   names[i], what);
        check_written_out(path, names[i]);
    }
    crane_scene s;
    bg_error err = {0};
    tap_ok(crane_scene_load(&s, CRANE_SCENES_DIR "/no-such-scene.ini", &err) == BG_ERR_IO &&
               strstr(err.message, "no-such-scene.ini"),
           "a missing file is BG_ERR_IO naming the file (%s)", err.message);
    bg_error_clear(&err);
    tap_ok(crane_scene_load(&s, CRANE_SCENES_DIR, &err) == BG_ERR_IO &&
               strstr(err.message, "a directory, not a scene file"),
           "a directory is BG_ERR_IO saying what it is (%s)", err.message);
    bg_error_clear(&err);
    tap_ok(crane_scene_load(&s, "/dev/null", &err) == BG_ERR_IO &&
               strstr(err.message, "a character device, not a scene file"),
           "a device is BG_ERR_IO saying what it is (%s)", err.message);
}

/* crane_scene_load_counted: the keys a file sets (0: nothing but comments and sections). */
static void test_counted(void)
{
    static const struct {
        const char *text;
        int nkeys;
    } cases[] = {{"", 0},
                 {"; only a comment\n[boom]\n# and another\n", 0},
                 {"[boom]\nlength = 70\nelements = 4\n[solver]\nt_end = 1\n", 3},
                 {"[boom]\r\nlength = 70\r\n", 1},
                 {"[boom]\rlength = 70\rrho = 7000\r", 2}};
    const char *tdir = getenv("TMPDIR");
    char path[1024];
    snprintf(path, sizeof path, "%s/crane_counted_%ld.ini", tdir && *tdir ? tdir : "/tmp",
             (long)time(NULL));
    for (int i = 0; i < 5; i++) {
        FILE *f = fopen(path, "w");
        if (f) {
            fputs(cases[i].text, f);
            fclose(f);
        }
        crane_scene s;
        bg_error err = {0};
        int n = -1, rc = crane_scene_load_counted(&s, path, &n, &err);
        tap_ok(rc == BG_OK && n == cases[i].nkeys, "a file that sets %d keys: counted %d %s",
               cases[i].nkeys, n, err.message);
    }
    remove(path);
}

static void test_syntax_variants(void)
{
    crane_scene s, d;
    bg_error err = {0};
    char what[256];
    crane_scene_default(&d);
    int rc = parse_text(&s,
                        "\xEF\xBB\xBF; a BOM, comments of both kinds\r\n"
                        "# hash comment\n"
                        "\n"
                        "[BOOM]\r\n"
                        "  Length: 70 ; colon separator, indented key after a section\n"
                        "i_luff = 0.09\n"
                        "foot =1.5 ,  0,2.5\n"
                        "[ties] ; comment after a section\n"
                        "enabled = OFF\n"
                        "[rope]\n"
                        "enabled = no\n"
                        "[counterweight]\n"
                        "enabled = 0\n"
                        "[initial]\n"
                        "static_start = Yes\n"
                        "[boom]\n"
                        "elements = +3\n"
                        "[solver]\n"
                        "t_end = 2.5e0\n",
                        &err);
    tap_ok(rc == BG_OK, "syntax variants are accepted %s", err.message);
    d.boom_length = 70;
    d.boom_I_luff = 0.09;
    d.ties = 0;
    d.rope = 0;
    d.counterweight = 0;
    d.boom_elements = 3;
    d.t_end = 2.5;
    tap_ok(crane_scene_compare(&d, &s, what, sizeof what) == 0,
           "and give the values meant (case-insensitive names, reopened section) %s", what);
    rc = parse_text(&s, "", &err);
    crane_scene_default(&d);
    tap_ok(rc == BG_OK && crane_scene_compare(&d, &s, NULL, 0) == 0,
           "an empty scene is the default");
}

static void test_catalogue(void)
{
    tap_diag("%d malformed scenes", NBAD);
    tap_ok(NBAD >= 20, "the catalogue has at least twenty malformed scenes");
    for (int i = 0; i < NBAD; i++) {
        const bad_scene *b = &BAD_SCENES[i];
        crane_scene s;
        bg_error err = {0};
        int rc = parse_text(&s, b->text, &err);
        char where[32];
        snprintf(where, sizeof where, "bad.ini:%d: ", b->line);
        int ok = rc == BG_ERR_ARGUMENT && !strncmp(err.message, where, strlen(where)) &&
                 contains(err.message, b->key) && contains(err.message, b->also);
        tap_ok(ok, "%s: refused at line %d naming %s", b->what, b->line, b->key);
        if (!ok) tap_diag("status %d, message: %s", rc, err.message);
    }
    /* the same through a FILE, with a NUL byte inside */
    FILE *f = tmpfile();
    fwrite("[boom]\nlength = 7\0 6\n", 1, 21, f);
    rewind(f);
    crane_scene s;
    bg_error err = {0};
    crane_scene_default(&s);
    int rc = crane_scene_parse_file(&s, f, "nul.ini", &err);
    fclose(f);
    tap_ok(rc == BG_ERR_ARGUMENT && strstr(err.message, "nul.ini:2:"),
           "a NUL byte is refused at its line (%s)", err.message);
}

static void test_set_and_check(void)
{
    crane_scene s;
    bg_error err = {0};
    crane_scene_default(&s);
    tap_ok(crane_scene_set(&s, "boom", "elements", "8", "--elements", &err) == BG_OK &&
               s.boom_elements == 8,
           "crane_scene_set sets a key");
    tap_ok(crane_scene_set(&s, "solver", "rtol", "abc", "--rtol", &err) == BG_ERR_ARGUMENT &&
               strstr(err.message, "--rtol: key 'rtol' in [solver]") &&
               strstr(err.message, "got 'abc'"),
           "crane_scene_set refuses a bad value with its origin (%s)", err.message);
    tap_ok(crane_scene_set(&s, "bom", "length", "3", "--set", &err) == BG_ERR_ARGUMENT &&
               strstr(err.message, "[boom]"),
           "crane_scene_set suggests the section (%s)", err.message);
    tap_ok(crane_scene_set(&s, "boom", "lenght", "3", "--set", &err) == BG_ERR_ARGUMENT &&
               strstr(err.message, "'length'"),
           "crane_scene_set suggests the key (%s)", err.message);

    crane_scene_default(&s);
    s.boom_elements = 600;
    tap_ok(crane_scene_check(&s, "test", &err) == BG_ERR_ARGUMENT &&
               strstr(err.message, "test: key 'elements' in [boom]") && strstr(err.message, "600"),
           "crane_scene_check: element count (%s)", err.message);
    crane_scene_default(&s);
    s.load_mass = NAN;
    tap_ok(crane_scene_check(&s, "test", &err) == BG_ERR_ARGUMENT &&
               strstr(err.message, "key 'mass' in [load]"),
           "crane_scene_check: NaN mass (%s)", err.message);
    crane_scene_default(&s);
    s.ties = 2;
    tap_ok(crane_scene_check(&s, NULL, &err) == BG_ERR_ARGUMENT &&
               strstr(err.message, "key 'enabled' in [ties]"),
           "crane_scene_check: boolean out of range (%s)", err.message);
    crane_scene_default(&s);
    s.ref_t3 = s.ref_t2;
    tap_ok(crane_scene_check(&s, NULL, &err) == BG_ERR_ARGUMENT && strstr(err.message, "'t3'"),
           "crane_scene_check: reference times (%s)", err.message);
    crane_scene_default(&s);
    s.name[0] = '\0';
    tap_ok(crane_scene_check(&s, NULL, &err) == BG_ERR_ARGUMENT && strstr(err.message, "'name'"),
           "crane_scene_check: empty name (%s)", err.message);
}

/* A scene builds only what it needs: the model's size follows the scene. */
static int model_size(const char *name, int *eq)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.ini", CRANE_SCENES_DIR, name);
    crane_scene s;
    bg_error err = {0};
    *eq = -1;
    if (crane_scene_load(&s, path, &err) != BG_OK) return -1;
    crane *c = crane_build(&s, &err);
    if (!c) {
        tap_diag("%s: crane_build: %s", name, err.message);
        return -1;
    }
    bgr_stats st;
    int rc = bgr_get_stats(crane_model(c), &st);
    crane_free(&c);
    tap_ok(c == NULL, "crane_free clears the pointer (%s)", name);
    if (rc != BG_OK) return -1;
    *eq = st.equations;
    return 0;
}

static void test_parts(void)
{
    int paper, rigid, presc, fine;
    int ok = model_size("paper", &paper) == 0;
    ok = model_size("rigid-boom", &rigid) == 0 && ok;
    ok = model_size("prescribed-rotation", &presc) == 0 && ok;
    ok = model_size("fine-mesh", &fine) == 0 && ok;
    tap_ok(ok,
           "every scene builds (equations: paper %d, rigid-boom %d, prescribed-rotation %d, "
           "fine-mesh %d)",
           paper, rigid, presc, fine);
    tap_ok(rigid < paper, "the rigid boom has fewer equations than the beam chain (%d < %d)", rigid,
           paper);
    tap_ok(presc < paper, "without hydraulics and PID the model is smaller (%d < %d)", presc,
           paper);
    tap_ok(fine > paper, "64 elements make a larger model than 16 (%d > %d)", fine, paper);
}

/* [solver] nominal_scales: on by default, false turns the scales off, anything but a boolean is
 * refused naming the key, and crane_scene_write writes it back. */
static void test_nominal_scales_key(void)
{
    crane_scene s, d;
    bg_error err = {0};
    crane_scene_default(&d);
    tap_ok(d.nominal_scales == 1, "nominal_scales defaults to true");
    int rc = parse_text(&s, "[solver]\nnominal_scales = false ; SI units\n", &err);
    tap_ok(rc == BG_OK && s.nominal_scales == 0, "[solver] nominal_scales = false parses to 0 %s",
           err.message);
    rc = parse_text(&s, "[solver]\nnominal_scales = sometimes\n", &err);
    tap_ok(rc == BG_ERR_ARGUMENT && strstr(err.message, "nominal_scales") &&
               strstr(err.message, "boolean"),
           "nominal_scales = sometimes is refused (%s)", err.message);
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    s = d;
    s.nominal_scales = 0;
    crane_scene_write(&s, f);
    fclose(f);
    tap_ok(buf && strstr(buf, "nominal_scales = false"), "crane_scene_write writes nominal_scales");
    free(buf);
}

int main(void)
{
    test_keys();
    test_distance();
    test_round_trip();
    test_coverage();
    test_scenes();
    test_counted();
    test_syntax_variants();
    test_catalogue();
    test_set_and_check();
    test_parts();
    test_nominal_scales_key();
    return tap_done();
}
