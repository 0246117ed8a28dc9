/* Scene files of the rotary crane (see crane_scene.h): the parser, driven by the key table
 * (crane_scene_keys.c): values, overrides, the consistency checks, reading INI text, loading.
 *
 * inih does the INI syntax, behind progutil's pu_ini (pu_ini.h): pu_ini feeds the text to
 * inih's ini_parse_stream line by line, numbers each line and checks it before inih sees it
 * (lines without '=', indented continuation lines, over-long lines, a NUL), with the file's name
 * and the line; the section names are checked here as their headers come, and inih gives each
 * key to the handler with the section it keeps, pu_ini with the line, so that every message can
 * say what is wrong and where. The parse stops at the first error. */
#include "crane_scene_impl.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "pu_cli.h"
#include "pu_fs.h"
#include "pu_ini.h"

/* ------------------------------------------------------------------ values ---- */

static void expected_text(const key_def *k, char *buf, size_t size)
{
    if (k->pub.unit[0])
        snprintf(buf, size, "%s (%s)", k->pub.expected, k->pub.unit);
    else
        snprintf(buf, size, "%s", k->pub.expected);
}

static int value_error(bg_error *err, const char *origin, const key_def *k, const char *got)
{
    char exp[160], q[80];
    expected_text(k, exp, sizeof exp);
    pu_ini_quote(got, q, sizeof q);
    int hex =
        k->pub.type != CRANE_KEY_NAME && k->pub.type != CRANE_KEY_BOOLEAN && pu_ini_looks_hex(got);
    return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene",
                          "%s%skey '%s' in [%s]: expected %s, got '%s'%s", origin ? origin : "",
                          origin ? ": " : "", k->pub.key, k->pub.section, exp, q,
                          hex ? " (numbers are decimal: hexadecimal is not accepted)" : "");
}

static int valid_name(const char *v)
{
    size_t n = strlen(v);
    if (n < 1 || n > 63) return 0;
    for (size_t i = 0; i < n; i++) {
        int c = (unsigned char)v[i];
        if (!(isalnum(c) || c == '_' || c == '.' || c == '-')) return 0;
    }
    return strcmp(v, ".") && strcmp(v, "..");
}

/* Parse value for key k into s. */
static int set_value(crane_scene *s, const key_def *k, const char *value, const char *origin,
                     bg_error *err)
{
    switch (k->pub.type) {
    case CRANE_KEY_NUMBER: {
        double x;
        if (!pu_ini_parse_double(value, &x) || !csk_in_range(k->range, x))
            return value_error(err, origin, k, value);
        *dfield(s, k) = x;
        return BG_OK;
    }
    case CRANE_KEY_VECTOR: {
        double x[3];
        const char *p = value;
        char part[128];
        for (int i = 0; i < 3; i++) {
            const char *e = strchr(p, ',');
            size_t n = e ? (size_t)(e - p) : strlen(p);
            if ((i < 2) != (e != NULL) || n >= sizeof part)
                return value_error(err, origin, k, value);
            memcpy(part, p, n);
            part[n] = '\0';
            if (!pu_ini_parse_double(part, &x[i]) || !csk_in_range(k->range, x[i]))
                return value_error(err, origin, k, value);
            p = e ? e + 1 : p + n;
        }
        memcpy(dfield(s, k), x, sizeof x);
        return BG_OK;
    }
    case CRANE_KEY_INTEGER: {
        const char *v = value;
        char *end;
        while (isspace((unsigned char)*v))
            v++;
        errno = 0;
        long x = strtol(v, &end, 10);
        while (isspace((unsigned char)*end))
            end++;
        if (!*v || *end || errno == ERANGE || x < k->lo || x > k->hi)
            return value_error(err, origin, k, value);
        *ifield(s, k) = (int)x;
        return BG_OK;
    }
    case CRANE_KEY_BOOLEAN: {
        static const char *yes[] = {"true", "yes", "on", "1"}, *no[] = {"false", "no", "off", "0"};
        for (int i = 0; i < 4; i++) {
            if (pu_ini_ieq(value, yes[i])) {
                *ifield(s, k) = 1;
                return BG_OK;
            }
            if (pu_ini_ieq(value, no[i])) {
                *ifield(s, k) = 0;
                return BG_OK;
            }
        }
        return value_error(err, origin, k, value);
    }
    case CRANE_KEY_NAME:
        if (!valid_name(value)) return value_error(err, origin, k, value);
        memset(s->name, 0, sizeof s->name);
        memcpy(s->name, value, strlen(value));
        return BG_OK;
    }
    return BG_ERR_ARGUMENT;
}

int crane_scene_set(crane_scene *s, const char *section, const char *key, const char *value,
                    const char *origin, bg_error *err)
{
    const char *o = origin ? origin : "", *sep = origin ? ": " : "";
    if (!s || !section || !key || !value)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_set", "%s%snull argument", o, sep);
    if (!csk_known_section(section)) {
        int d;
        const char *near = csk_nearest_section(section, &d);
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_set",
                              "%s%sunknown section [%s]; did you mean [%s]?", o, sep, section,
                              near);
    }
    int i = csk_find_key(section, key);
    if (i < 0) {
        int d;
        int j = csk_nearest_key(section, key, &d);
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_set",
                              "%s%sunknown key '%s' in [%s]; did you mean '%s'?", o, sep, key,
                              csk_known_section(section), j >= 0 ? KEYS[j].pub.key : "");
    }
    return set_value(s, &KEYS[i], value, origin, err);
}

/* ------------------------------------------------------------- consistency ---- */

/* Where a key was set: a "FILE:LINE" of the parse, or the caller's origin. */
typedef struct origin_map {
    const char *file; /* NULL: use fixed */
    const int *line;  /* NKEYS lines (0: not in the file) */
    const char *fixed;
} origin_map;

static const char *origin_of(const origin_map *om, int key, char *buf, size_t size)
{
    if (om->file && om->line && om->line[key] > 0) {
        snprintf(buf, size, "%s:%d", om->file, om->line[key]);
        return buf;
    }
    if (om->file) {
        snprintf(buf, size, "%s", om->file);
        return buf;
    }
    return om->fixed;
}

/* The first of keys a, b, c that the file sets (a if none). */
static int blame(const origin_map *om, int a, int b, int c)
{
    if (!om->line) return a;
    if (om->line[a] > 0) return a;
    if (b >= 0 && om->line[b] > 0) return b;
    if (c >= 0 && om->line[c] > 0) return c;
    return a;
}

static int key_index(const char *section, const char *key)
{
    return csk_find_key(section, key);
}

static int check_scene(const crane_scene *s, const origin_map *om, bg_error *err)
{
    char ob[1200], got[64];
    /* every field in its range */
    for (int i = 0; i < NKEYS; i++) {
        const key_def *k = &KEYS[i];
        int ok = 1;
        switch (k->pub.type) {
        case CRANE_KEY_NUMBER:
            ok = csk_in_range(k->range, *cdfield(s, k));
            snprintf(got, sizeof got, "%.17g", *cdfield(s, k));
            break;
        case CRANE_KEY_VECTOR:
            for (int j = 0; j < 3; j++)
                ok = ok && csk_in_range(k->range, cdfield(s, k)[j]);
            snprintf(got, sizeof got, "%.6g, %.6g, %.6g", cdfield(s, k)[0], cdfield(s, k)[1],
                     cdfield(s, k)[2]);
            break;
        case CRANE_KEY_INTEGER:
        case CRANE_KEY_BOOLEAN:
            ok = *cifield(s, k) >= k->lo && *cifield(s, k) <= k->hi;
            snprintf(got, sizeof got, "%d", *cifield(s, k));
            break;
        case CRANE_KEY_NAME:
            ok = memchr(s->name, '\0', sizeof s->name) != NULL && valid_name(s->name);
            snprintf(got, sizeof got, "%.*s", (int)sizeof s->name - 1, s->name);
            break;
        }
        if (!ok) return value_error(err, origin_of(om, i, ob, sizeof ob), k, got);
    }
    /* the boom reaches its tip radius */
    double dx = s->boom_tip_radius - s->boom_foot[0];
    if (!(fabs(dx) < s->boom_length)) {
        int k = blame(om, key_index("boom", "tip_radius"), key_index("boom", "length"),
                      key_index("boom", "foot"));
        const char *o = origin_of(om, k, ob, sizeof ob);
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_check",
                              "%s%skey '%s' in [boom]: expected a boom that reaches its tip "
                              "(|tip_radius - foot.x| < length), got tip_radius %g m, foot.x %g "
                              "m, length %g m",
                              o ? o : "", o ? ": " : "", KEYS[k].pub.key, s->boom_tip_radius,
                              s->boom_foot[0], s->boom_length);
    }
    /* a flexible boom leans: a vertical one (tip_radius = foot.x) has no luffing plane to orient
     * its cross-section by (mech_beam_chain: "an up vector not along the beam") */
    if (s->boom_elements > 0 && !(fabs(dx) > 1e-9 * s->boom_length)) {
        int k = blame(om, key_index("boom", "tip_radius"), key_index("boom", "foot"),
                      key_index("boom", "elements"));
        const char *o = origin_of(om, k, ob, sizeof ob);
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_check",
                              "%s%skey '%s' in [boom]: expected a boom that leans (tip_radius != "
                              "foot.x), got tip_radius %g m = foot.x %g m: a vertical flexible "
                              "boom (elements = %d) has no luffing plane; move [boom] tip_radius "
                              "or foot, or make it rigid (elements = 0)",
                              o ? o : "", o ? ": " : "", KEYS[k].pub.key, s->boom_tip_radius,
                              s->boom_foot[0], s->boom_elements);
    }
    /* one beam element */
    if (s->boom_consistent && s->boom_quartic) {
        int k = blame(om, key_index("boom", "quartic"), key_index("boom", "consistent"), -1);
        const char *o = origin_of(om, k, ob, sizeof ob);
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_check",
                              "%s%skey '%s' in [boom]: expected one beam element, got consistent "
                              "= true and quartic = true; set one of them false",
                              o ? o : "", o ? ": " : "", KEYS[k].pub.key);
    }
    /* the reference's times are ordered: 0 < t1 <= t2 < t3 */
    if (!(s->ref_t1 <= s->ref_t2 && s->ref_t2 < s->ref_t3)) {
        int i1 = key_index("reference", "t1"), i2 = key_index("reference", "t2"),
            i3 = key_index("reference", "t3");
        int k = s->ref_t1 > s->ref_t2 ? blame(om, i2, i1, -1) : blame(om, i3, i2, -1);
        const char *o = origin_of(om, k, ob, sizeof ob);
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_check",
                              "%s%skey '%s' in [reference]: expected times 0 < t1 <= t2 < t3, got "
                              "t1 = %g s, t2 = %g s, t3 = %g s",
                              o ? o : "", o ? ": " : "", KEYS[k].pub.key, s->ref_t1, s->ref_t2,
                              s->ref_t3);
    }
    if (!(s->output_step <= s->t_end)) {
        int k = blame(om, key_index("solver", "output_step"), key_index("solver", "t_end"), -1);
        const char *o = origin_of(om, k, ob, sizeof ob);
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_check",
                              "%s%skey '%s' in [solver]: expected output_step <= t_end, got "
                              "output_step = %g s, t_end = %g s",
                              o ? o : "", o ? ": " : "", KEYS[k].pub.key, s->output_step, s->t_end);
    }
    return BG_OK;
}

int crane_scene_check(const crane_scene *s, const char *origin, bg_error *err)
{
    if (!s) return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_check", "null scene");
    origin_map om = {NULL, NULL, origin};
    return check_scene(s, &om, err);
}

/* ------------------------------------------------------------------ parsing ---- */

typedef struct parse_ctx {
    crane_scene *s;
    const char *file;
    bg_error *err;
    const char *text;
    size_t len;
    int line; /* number of the line last read */
    int failed;
    int seen[NKEYS]; /* line that set each key (0: none) */
} parse_ctx;

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static int
fail_at(parse_ctx *c, const char *fmt, ...)
{
    char msg[BG_MESSAGE_SIZE];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    c->failed = 1;
    return bg_error_raise(c->err, BG_ERR_ARGUMENT, "crane_scene_parse", "%s:%d: %s", c->file,
                          c->line, msg);
}

/* One key of the file: found in the table (else the suggestions), set once, its line kept for
 * the consistency messages. */
static int handler(void *user, const char *section, const char *name, const char *value)
{
    parse_ctx *c = user;
    if (c->failed) return 0;
    if (!section[0]) {
        int best = -1, bd = 1 << 30;
        for (int i = 0; i < NKEYS; i++) {
            int d = pu_cli_edit_distance(name, KEYS[i].pub.key);
            if (d < bd) bd = d, best = i;
        }
        fail_at(c, "key '%s' before any [section]; did you mean '%s' in [%s]?", name,
                KEYS[best].pub.key, KEYS[best].pub.section);
        return 0;
    }
    const char *sec = csk_known_section(section);
    if (!sec) { /* the reader has rejected it already */
        fail_at(c, "key '%s' in unknown section [%s]", name, section);
        return 0;
    }
    int i = csk_find_key(sec, name);
    if (i < 0) {
        int d, j = csk_nearest_key(sec, name, &d);
        char other[200] = "";
        size_t len = 0;
        for (int k = 0; k < NKEYS; k++)
            if (pu_ini_ieq(KEYS[k].pub.key, name) && len < sizeof other)
                len += (size_t)snprintf(other + len, sizeof other - len, "%s[%s]", len ? ", " : "",
                                        KEYS[k].pub.section);
        if (other[0])
            fail_at(c, "unknown key '%s' in [%s]; did you mean '%s'? ('%s' is a key of %s)", name,
                    sec, KEYS[j].pub.key, name, other);
        else if (d <= 3 && (size_t)d < strlen(name))
            fail_at(c, "unknown key '%s' in [%s]; did you mean '%s'?", name, sec, KEYS[j].pub.key);
        else {
            char all[400];
            csk_list_keys(sec, all, sizeof all);
            fail_at(c, "unknown key '%s' in [%s]; did you mean '%s'? (keys of [%s]: %s)", name, sec,
                    KEYS[j].pub.key, sec, all);
        }
        return 0;
    }
    if (c->seen[i]) {
        fail_at(c, "key '%s' in [%s] given twice (first on line %d)", KEYS[i].pub.key, sec,
                c->seen[i]);
        return 0;
    }
    char origin[1100];
    snprintf(origin, sizeof origin, "%s:%d", c->file, c->line);
    if (set_value(c->s, &KEYS[i], value, origin, c->err) != BG_OK) {
        c->failed = 1;
        return 0;
    }
    c->seen[i] = c->line;
    return 1;
}

/* ------------------------------------------------------------ INI reading ---- */

/* A line with its "\n" and NUL fits in SCENE_LINE_SIZE bytes (198 characters): the size of
 * inih's line buffer (INI_MAX_LINE). */
#define SCENE_LINE_SIZE 200

/* A section header (pu_ini has checked its syntax): a section of the table, else the
 * suggestions. */
static int section_handler(void *user, const char *name, int line)
{
    parse_ctx *c = user;
    c->line = line;
    if (csk_known_section(name)) return 1;
    int d;
    const char *near = csk_nearest_section(name, &d);
    if (d <= 3 && (size_t)d < strlen(name))
        fail_at(c, "unknown section [%s]; did you mean [%s]?", name, near);
    else {
        char all[400];
        csk_list_sections(all, sizeof all);
        fail_at(c, "unknown section [%s]; did you mean [%s]? (sections: %s)", name, near, all);
    }
    return 0;
}

/* A key line as inih split it, on line line. inih's section is the header's text between the
 * brackets as written (not trimmed, at most 49 characters), so that a header with spaces inside
 * its brackets ("[ boom ]") passes the check of its name but its keys are refused. */
static int key_handler(void *user, const char *section, const char *key, const char *value,
                       int line)
{
    parse_ctx *c = user;
    c->line = line;
    return handler(c, section, key, value);
}

/* The text of c through pu_ini and inih into the handlers, c->line the line being handled. Stops
 * at the first error: 0, or -1 with the message set (c->failed). */
static int ini_read(parse_ctx *c)
{
    pu_ini_handler h = {section_handler, key_handler, c};
    pu_ini_result res;
    char msg[BG_MESSAGE_SIZE];
    pu_ini_status st =
        pu_ini_parse(c->text, c->len, c->file, SCENE_LINE_SIZE, &h, &res, msg, sizeof msg);
    if (st == PU_INI_OK) return 0;
    c->failed = 1;
    if (st != PU_INI_STOPPED) /* a handler's message is set already */
        bg_error_raise(c->err, st == PU_INI_NOMEM ? BG_ERR_MEMORY : BG_ERR_ARGUMENT,
                       "crane_scene_parse", "%s", msg);
    return -1;
}

/* ------------------------------------------------------------------ loading ---- */

/* The number of keys set (*nkeys, may be NULL) besides the statuses of parse_string. */
static int parse_counted(crane_scene *s, const char *text, const char *filename, int *nkeys,
                         bg_error *err)
{
    const char *file = filename ? filename : "<string>";
    if (nkeys) *nkeys = 0;
    if (!s || !text)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_parse", "%s: null argument", file);
    parse_ctx c;
    memset(&c, 0, sizeof c);
    c.s = s;
    c.file = file;
    c.err = err;
    c.text = text;
    c.len = strlen(text);
    if (ini_read(&c) != 0) return err && err->status != BG_OK ? err->status : BG_ERR_ARGUMENT;
    if (nkeys)
        for (int i = 0; i < NKEYS; i++)
            *nkeys += c.seen[i] > 0;
    origin_map om = {file, c.seen, NULL};
    return check_scene(s, &om, err);
}

int crane_scene_parse_string(crane_scene *s, const char *text, const char *filename, bg_error *err)
{
    return parse_counted(s, text, filename, NULL, err);
}

static int parse_file_counted(crane_scene *s, FILE *f, const char *filename, int *nkeys,
                              bg_error *err)
{
    if (nkeys) *nkeys = 0;
    const char *file = filename ? filename : "<file>";
    if (!s || !f)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_parse", "%s: null argument", file);
    size_t cap = 4096, len = 0;
    char *buf = malloc(cap);
    if (!buf) return bg_error_raise(err, BG_ERR_MEMORY, "crane_scene_parse", "out of memory");
    for (;;) {
        if (len + 1 >= cap) {
            if (cap >= (size_t)16 << 20) {
                free(buf);
                return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_parse",
                                      "%s: larger than 16 MB: not a scene file", file);
            }
            char *nb = realloc(buf, cap * 2);
            if (!nb) {
                free(buf);
                return bg_error_raise(err, BG_ERR_MEMORY, "crane_scene_parse", "out of memory");
            }
            buf = nb;
            cap *= 2;
        }
        size_t got = fread(buf + len, 1, cap - 1 - len, f);
        len += got;
        if (got == 0) break;
    }
    if (ferror(f)) {
        free(buf);
        return bg_error_raise(err, BG_ERR_IO, "crane_scene_parse", "%s: read error: %s", file,
                              strerror(errno));
    }
    buf[len] = '\0';
    /* a NUL inside the text would end it early: report it at its line */
    size_t z = strlen(buf);
    int r;
    if (z < len) {
        r = bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_parse",
                           "%s:%d: the line contains a NUL character (not a text file?)", file,
                           pu_ini_line_at(buf, z));
    } else {
        r = parse_counted(s, buf, file, nkeys, err);
    }
    free(buf);
    return r;
}

int crane_scene_parse_file(crane_scene *s, FILE *f, const char *filename, bg_error *err)
{
    return parse_file_counted(s, f, filename, NULL, err);
}

int crane_scene_load(crane_scene *s, const char *path, bg_error *err)
{
    return crane_scene_load_counted(s, path, NULL, err);
}

int crane_scene_load_counted(crane_scene *s, const char *path, int *nkeys, bg_error *err)
{
    if (nkeys) *nkeys = 0;
    if (!s || !path)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_load", "null argument");
    crane_scene_default(s);
    /* the scene is named after its file unless it says otherwise */
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    char stem[sizeof s->name];
    size_t n = 0;
    for (; base[n] && n < sizeof stem - 1; n++) {
        int ch = (unsigned char)base[n];
        stem[n] = (char)(isalnum(ch) || ch == '_' || ch == '.' || ch == '-' ? ch : '_');
    }
    stem[n] = '\0';
    if (n > 4 && !strcmp(stem + n - 4, ".ini")) stem[n - 4] = '\0';
    if (valid_name(stem)) strcpy(s->name, stem);
    /* opened without blocking (a FIFO without a writer would wait for ever), then only a
     * regular file is read: a directory, FIFO or device is named as what it is */
    int fd = open(path, O_RDONLY | O_NONBLOCK);
    if (fd < 0)
        return bg_error_raise(err, BG_ERR_IO, "crane_scene_load", "%s: cannot open: %s", path,
                              strerror(errno));
    struct stat st;
    int e = fstat(fd, &st) != 0 ? errno : 0;
    if (e || !S_ISREG(st.st_mode)) {
        close(fd);
        if (e)
            return bg_error_raise(err, BG_ERR_IO, "crane_scene_load", "%s: cannot open: %s", path,
                                  strerror(e));
        return bg_error_raise(err, BG_ERR_IO, "crane_scene_load", "%s: %s, not a scene file", path,
                              pu_fs_kind((unsigned)st.st_mode));
    }
    FILE *f = fdopen(fd, "r");
    if (!f) {
        e = errno;
        close(fd);
        return bg_error_raise(err, BG_ERR_IO, "crane_scene_load", "%s: cannot open: %s", path,
                              strerror(e));
    }
    int r = parse_file_counted(s, f, path, nkeys, err);
    fclose(f);
    return r;
}
