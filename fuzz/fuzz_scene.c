/* libFuzzer target: the scene-file parser (crane/crane_scene.h).
 *
 * The input is the text of a scene file. Besides "no crash, no leak, no undefined behaviour",
 * the parser's documented properties are checked:
 *   - crane_scene_parse_string (the text up to its first NUL) and crane_scene_parse_file (all the
 *     bytes, through fmemopen) agree when the input holds no NUL: same status, same message,
 *     same scene; with a NUL the file parser refuses the input;
 *   - a refusal has a negative status and a message that starts with the file's name;
 *   - an accepted scene passes crane_scene_check, and crane_scene_write followed by a parse of
 *     the written text gives the same scene back (crane_scene_compare = 0);
 *   - the first line, read as "section.key=value", goes through crane_scene_set (the crane
 *     program's --set) without harm; a scene it accepts still writes and reads back.
 * A violated property ends the run with a message and __builtin_trap(). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "crane_scene.h"
#include "pu_cli.h"

#define FILE_NAME "fuzz.ini"

static void fail(const char *what, const char *detail)
{
    fprintf(stderr, "fuzz_scene: %s%s%s\n", what, detail ? ": " : "", detail ? detail : "");
    __builtin_trap();
}

/* Writes s and parses the text into a default scene: must give s back. */
static void check_roundtrip(const crane_scene *s)
{
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f) return;
    int w = crane_scene_write(s, f);
    fclose(f);
    if (w != BG_OK) fail("crane_scene_write failed", NULL);
    crane_scene back;
    crane_scene_default(&back);
    bg_error err = {0};
    if (crane_scene_parse_string(&back, text, "written.ini", &err) != BG_OK) {
        fprintf(stderr, "%s\n", text);
        fail("the written scene does not parse", err.message);
    }
    char what[256];
    if (crane_scene_compare(s, &back, what, sizeof what) != 0)
        fail("the written scene reads back different", what);
    free(text);
}

static void check_refusal(int r, const bg_error *err)
{
    if (r >= 0) fail("status of a refusal not negative", err->message);
    if (err->status != r) fail("error record holds another status than returned", err->message);
    if (r != BG_ERR_MEMORY && strncmp(err->message, FILE_NAME, strlen(FILE_NAME)) != 0)
        fail("message does not start with the file name", err->message);
}

/* The first line as "section.key=value" through crane_scene_set. */
static void fuzz_set(const char *text)
{
    char line[256];
    size_t n = strcspn(text, "\n");
    if (n >= sizeof line) n = sizeof line - 1;
    memcpy(line, text, n);
    line[n] = '\0';
    char *dot = strchr(line, '.');
    char *eq = dot ? strchr(dot + 1, '=') : NULL;
    if (!dot || !eq) return;
    *dot = '\0';
    *eq = '\0';
    crane_scene s;
    crane_scene_default(&s);
    bg_error err = {0};
    if (crane_scene_set(&s, line, dot + 1, eq + 1, "--set", &err) == BG_OK) {
        if (crane_scene_check(&s, "--set", &err) == BG_OK) check_roundtrip(&s);
    } else if (err.status >= 0 || !err.message[0]) {
        fail("crane_scene_set refused without a message", NULL);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    int has_nul = strlen(text) < size;

    crane_scene a, b;
    crane_scene_default(&a);
    crane_scene_default(&b);
    bg_error ea = {0}, eb = {0};
    int ra = crane_scene_parse_string(&a, text, FILE_NAME, &ea);
    if (ra != BG_OK) check_refusal(ra, &ea);

    FILE *f = size ? fmemopen(text, size, "r") : NULL;
    if (f) {
        int rb = crane_scene_parse_file(&b, f, FILE_NAME, &eb);
        fclose(f);
        if (has_nul) {
            if (rb == BG_OK) fail("a text with a NUL character was accepted from a file", NULL);
            check_refusal(rb, &eb);
        } else {
            if (ra != rb) fail("parse_string and parse_file disagree on the status", eb.message);
            if (strcmp(ea.message, eb.message) != 0)
                fail("parse_string and parse_file disagree on the message", eb.message);
            char what[256];
            if (ra == BG_OK && crane_scene_compare(&a, &b, what, sizeof what) != 0)
                fail("parse_string and parse_file give different scenes", what);
        }
    }

    if (ra == BG_OK) {
        bg_error ec = {0};
        if (crane_scene_check(&a, NULL, &ec) != BG_OK)
            fail("an accepted scene fails crane_scene_check", ec.message);
        check_roundtrip(&a);
    }

    fuzz_set(text);

    /* the suggestions' edit distance on the two halves of the text (it compares at most 64
     * characters of each): symmetric, 0 against itself, at most the longer length */
    size_t len = strlen(text), h = len / 2;
    char *first = malloc(h + 1);
    if (first) {
        memcpy(first, text, h);
        first[h] = '\0';
        const char *second = text + h;
        int d = pu_cli_edit_distance(first, second);
        int back = pu_cli_edit_distance(second, first);
        size_t lmax = len - h < 64 ? len - h : 64;
        if (d < 0 || d != back || (size_t)d > lmax || pu_cli_edit_distance(second, second))
            fail("edit distance not a distance", NULL);
        free(first);
    }

    free(text);
    return 0;
}
