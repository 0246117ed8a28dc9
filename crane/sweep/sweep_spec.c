/* Sweep files (sweep_spec.h): the parser and the public entry points; the parts are listed in
 * sweep_spec_impl.h.
 *
 * inih does the INI syntax behind progutil's pu_ini (pu_ini.h), as for the scene files
 * (crane_scene.c): pu_ini feeds the text to inih line by line, checks each line and numbers it,
 * so that every message has its line; pu_ini gives each section header to open_section before
 * inih reads it, and each header opens a raw section of its own, which is how repeated [axis]
 * sections become separate axes. inih gives the keys and values. The keys are only recorded; the
 * values are checked afterwards, section by section (spec_finish, sweep_schema.c), so that the keys
 * of a section may come in any order. Every swept or set value is checked with crane_scene_set, the
 * scene files' own check, and its message is passed on behind "FILE:LINE: key '...' in [...]". */
#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "pu_fs.h"
#include "pu_ini.h"

#include "crane_scene.h"
#include "sweep_spec_impl.h"

/* ------------------------------------------------------------------ errors ---- */

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
int
spec_fail_line(parse_ctx *c, int line, const char *fmt, ...)
{
    if (c->failed) return -1;
    char msg[1536];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    c->failed = 1;
    if (line > 0)
        snprintf(c->err, c->errsize, "%s:%d: %s", c->file, line, msg);
    else
        snprintf(c->err, c->errsize, "%s: %s", c->file, msg);
    return -1;
}

/* ---------------------------------------------------------------- sections ---- */

/* A section header [name] (its line c->line): a known section, once unless [axis]; opens a raw
 * section. 1, or 0 with the error recorded. */
static int open_section(parse_ctx *c, const char *name)
{
    int kind = spec_section_kind(name);
    if (kind == SEC_NONE) {
        int d;
        char all[128];
        const char *near = spec_nearest(name, SEC_NAMES, &d);
        spec_join(SEC_NAMES, "[", "]", all, sizeof all);
        return spec_fail_line(c, c->line, "unknown section [%s]; did you mean [%s]? (sections: %s)",
                              name, near, all),
               0;
    }
    if (kind != SEC_AXIS)
        for (int i = 0; i < c->nraw; i++)
            if (c->raw[i].kind == kind)
                return spec_fail_line(c, c->line,
                                      "section [%s] given twice (first on line %d): one is "
                                      "allowed%s",
                                      SEC_NAMES[kind], c->raw[i].line,
                                      kind == SEC_LHS ? " (its keys are sampled together)" : ""),
                       0;
    int naxis = 0;
    for (int i = 0; i < c->nraw; i++)
        naxis += c->raw[i].kind == SEC_AXIS;
    if (c->nraw >= NRAW || (kind == SEC_AXIS && naxis >= SWEEP_MAX_AXES - 1))
        return spec_fail_line(c, c->line, "too many [axis] sections (at most %d)",
                              SWEEP_MAX_AXES - 1),
               0;
    raw_section *r = &c->raw[c->nraw];
    memset(r, 0, sizeof *r);
    r->kind = kind;
    r->line = c->line;
    c->cur = c->nraw++;
    return 1;
}

/* -------------------------------------------------------------------- keys ---- */

/* A key of the file (its line c->line) recorded in the current raw section; 1, or 0 with the
 * error recorded. */
static int record_key(parse_ctx *c, const char *name, const char *value)
{
    if (c->cur < 0) {
        spec_fail_line(
            c, c->line,
            "key '%s' before any section; a sweep file starts with [sweep], [set], [axis] "
            "or [lhs]",
            name);
        return 0;
    }
    raw_section *r = &c->raw[c->cur];
    const char *sec = SEC_NAMES[r->kind];
    const char *const *known = r->kind == SEC_SWEEP ? SWEEP_KEYS : AXIS_KEYS;
    /* [lhs]: every key is recorded; spec_finish_lhs tells its own from the sampled ones (a
     * model sweep's parameters need not be SECTION.KEY) */
    int scene_key = r->kind == SEC_SET || r->kind == SEC_LHS;
    if (!scene_key) {
        int found = 0;
        for (int i = 0; known[i] && !found; i++)
            found = pu_ini_ieq(known[i], name);
        if (!found) {
            int d;
            char all[160];
            const char *near = spec_nearest(name, known, &d);
            spec_join(known, "", "", all, sizeof all);
            if (r->kind == SEC_AXIS && spec_is_scene_key_name(name))
                spec_fail_line(c, c->line,
                               "unknown key '%s' in [axis]: an axis names its scene key with "
                               "'key = %s' and its values with 'values' or 'from', 'to', 'count'",
                               name, name);
            else if (d <= 3 && (size_t)d < strlen(name))
                spec_fail_line(c, c->line, "unknown key '%s' in [%s]; did you mean '%s'?", name,
                               sec, near);
            else
                spec_fail_line(c, c->line,
                               "unknown key '%s' in [%s]; did you mean '%s'? (keys of [%s]: %s)",
                               name, sec, near, sec, all);
            return 0;
        }
    }
    for (int i = 0; i < r->n; i++)
        if (pu_ini_ieq(r->kv[i].key, name)) {
            spec_fail_line(c, c->line, "key '%s' in [%s] given twice (first on line %d)", name, sec,
                           r->kv[i].line);
            return 0;
        }
    if (r->n >= RAW_MAX) {
        spec_fail_line(c, c->line, "too many keys in [%s] (at most %d)", sec, RAW_MAX);
        return 0;
    }
    if (strlen(name) >= sizeof r->kv[0].key) {
        spec_fail_line(c, c->line, "key name longer than %d characters",
                       (int)sizeof r->kv[0].key - 1);
        return 0;
    }
    raw_kv *kv = &r->kv[r->n++];
    snprintf(kv->key, sizeof kv->key, "%s", name);
    snprintf(kv->value, sizeof kv->value, "%s", value);
    kv->line = c->line;
    return 1;
}

/* ------------------------------------------------------------------- lines ---- */

/* A line with its "\n" and NUL fits in SPEC_LINE_SIZE bytes (198 characters), as in the scene
 * files (crane_scene.c): the size of inih's line buffer (INI_MAX_LINE). */
#define SPEC_LINE_SIZE 200

static int on_section(void *user, const char *name, int line)
{
    parse_ctx *c = user;
    c->line = line;
    return open_section(c, name);
}

/* inih's section is not needed: c->cur says which section instance a key is in. */
static int on_key(void *user, const char *section, const char *key, const char *value, int line)
{
    parse_ctx *c = user;
    (void)section;
    c->line = line;
    return record_key(c, key, value);
}

/* The text through pu_ini and inih into the raw sections: a header opens one, a key is recorded
 * in the current one. Stops at the first error: 0, or -1 with the error recorded. */
static int read_lines(parse_ctx *c, const char *text)
{
    pu_ini_handler h = {on_section, on_key, c};
    pu_ini_result res;
    pu_ini_status st =
        pu_ini_parse(text, strlen(text), c->file, SPEC_LINE_SIZE, &h, &res, c->err, c->errsize);
    if (st == PU_INI_OK) return 0;
    c->failed = 1;
    if (st == PU_INI_REFUSED && res.too_long && pu_ini_ieq(res.key, "values") && c->errsize) {
        size_t n = strlen(c->err);
        snprintf(c->err + n, c->errsize - n,
                 ": split the values over several [axis] sections or give a range "
                 "(from, to, count)");
    }
    return -1;
}

/* ------------------------------------------------------------------ public ---- */

int sweep_spec_parse(sweep_spec *s, const char *text, const char *file,
                     const char *const *scene_roots, char *err, size_t errsize)
{
    memset(s, 0, sizeof *s);
    snprintf(s->path, sizeof s->path, "%s", file);
    s->seed = 1;
    parse_ctx *c = calloc(1, sizeof *c);
    if (!c) {
        snprintf(err, errsize, "%s: out of memory", file);
        return -1;
    }
    c->s = s;
    c->file = file;
    c->cur = -1;
    c->err = err;
    c->errsize = errsize;
    int rc = read_lines(c, text) != 0 ? -1 : spec_finish(c, scene_roots);
    free(c->outputs);
    free(c);
    return rc;
}

int sweep_spec_load(sweep_spec *s, const char *path, const char *const *scene_roots, char *err,
                    size_t errsize)
{
    memset(s, 0, sizeof *s);
    int fd = open(path, O_RDONLY | O_NONBLOCK);
    if (fd < 0) {
        snprintf(err, errsize, "%s: cannot open: %s", path, strerror(errno));
        return -2;
    }
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        int e = errno;
        close(fd);
        if (!S_ISREG(st.st_mode))
            snprintf(err, errsize, "%s: %s, not a sweep file", path,
                     pu_fs_kind((unsigned)st.st_mode));
        else
            snprintf(err, errsize, "%s: cannot open: %s", path, strerror(e));
        return -2;
    }
    if (st.st_size > (off_t)1 << 20) {
        close(fd);
        snprintf(err, errsize, "%s: larger than 1 MB: not a sweep file", path);
        return -2;
    }
    size_t cap = (size_t)st.st_size + 1, len = 0;
    char *buf = malloc(cap + 1);
    if (!buf) {
        close(fd);
        snprintf(err, errsize, "%s: out of memory", path);
        return -2;
    }
    for (;;) {
        ssize_t n = read(fd, buf + len, cap - len);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            int e = errno;
            close(fd);
            free(buf);
            snprintf(err, errsize, "%s: read error: %s", path, strerror(e));
            return -2;
        }
        if (n == 0 || len + (size_t)n >= cap) {
            len += (size_t)n;
            break;
        }
        len += (size_t)n;
    }
    close(fd);
    buf[len] = '\0';
    if (strlen(buf) < len) {
        int line = 1;
        for (size_t i = 0; i < strlen(buf); i++)
            line += buf[i] == '\n';
        free(buf);
        snprintf(err, errsize, "%s:%d: the line contains a NUL character (not a text file?)", path,
                 line);
        return -1;
    }
    int rc = sweep_spec_parse(s, buf, path, scene_roots, err, errsize);
    s->text = buf;
    s->text_len = len;
    return rc;
}

void sweep_spec_free(sweep_spec *s)
{
    for (int a = 0; a < s->naxes && a < SWEEP_MAX_AXES; a++) {
        free(s->axes[a].values);
        s->axes[a].values = NULL;
    }
    /* an axis that failed half-way is not counted in naxes */
    if (s->naxes < SWEEP_MAX_AXES) {
        free(s->axes[s->naxes].values);
        s->axes[s->naxes].values = NULL;
    }
    free(s->text);
    s->text = NULL;
}
