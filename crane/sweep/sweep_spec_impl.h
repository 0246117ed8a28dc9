/* The sweep file's reading (sweep_spec.h for the format), shared by its parts. Private: not
 * installed.
 *
 *   sweep_spec.c    the parser: the lines parsed by inih behind progutil's pu_ini (pu_ini.h,
 *                   which also trims, quotes and reads the numbers), the keys recorded section by
 *                   section (the raw sections below); sweep_spec_parse, sweep_spec_load,
 *                   sweep_spec_free
 *   sweep_schema.c  the schema: the sections and their keys, the scene keys' check, the base
 *                   scene, [sweep] and [set], and the whole file checked (spec_finish)
 *   sweep_axes.c    the axes: value lists, ranges, the Latin-hypercube sample; the cases as
 *                   their product (sweep_case_*)
 *   sweep_model.c   a model sweep ([sweep] model): the model file, its parameters' values checked
 *                   by loading the model with them, the quantities FUNC(COLUMN)
 *
 * The parser only records; the schema checks afterwards, so that a section's keys may come in
 * any order. Every check fails through spec_fail_line, which keeps the first message only. */
#ifndef SWEEP_SPEC_IMPL_H
#define SWEEP_SPEC_IMPL_H

#include <stddef.h>

#include "crane_scene.h"
#include "pu_ini.h"
#include "sweep_spec.h"

/* ------------------------------------------------------------ the sections ---- */

enum { SEC_NONE = -1, SEC_SWEEP, SEC_SET, SEC_AXIS, SEC_LHS, NSEC };
/* The section names in the order of the enum, and each section's own keys (NULL ends a list;
 * [set] has only scene keys, [lhs] also the sampled scene keys as SECTION.KEY). */
extern const char *const SEC_NAMES[NSEC + 1];
extern const char *const SWEEP_KEYS[];
extern const char *const AXIS_KEYS[];
extern const char *const LHS_KEYS[];

#define RAW_MAX (SWEEP_MAX_SETS + 8)
#define NRAW (SWEEP_MAX_AXES + 4)

/* A key as written: its value unchecked, its line for the messages. */
typedef struct raw_kv {
    char key[64];
    char value[SWEEP_VALUE_SIZE];
    int line;
} raw_kv;

/* One section as written ([axis] may repeat: one raw section each). */
typedef struct raw_section {
    int kind, line, n;
    raw_kv kv[RAW_MAX];
} raw_section;

/* The state of one parse: the line being read, the raw sections, the first error (failed: err
 * holds "FILE:LINE: ..."). */
typedef struct parse_ctx {
    sweep_spec *s;
    const char *file;
    int line, failed;
    int cur; /* the raw section being read, -1 before the first */
    int nraw;
    raw_section raw[NRAW];
    char *err;
    size_t errsize;
    char (*outputs)[64]; /* a model sweep: t and the model's outputs (results.csv's columns) */
    int noutputs;
} parse_ctx;

/* ------------------------------------------------ sweep_spec.c: the parser ---- */

/* Records the message "FILE:LINE: ..." ("FILE: ..." for line 0) unless one is recorded; -1. */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
int spec_fail_line(parse_ctx *c, int line, const char *fmt, ...);

/* ---------------------------------------------- sweep_schema.c: the schema ---- */

/* The candidate nearest to name by edit distance (dist: the distance). */
const char *spec_nearest(const char *name, const char *const *cands, int *dist);
/* names as "PRE name POST, ..." into buf. */
void spec_join(const char *const *names, const char *pre, const char *post, char *buf, size_t size);
/* The SEC_ value of a section name (any case), SEC_NONE if none. */
int spec_section_kind(const char *name);
/* A scene key is written SECTION.KEY. */
int spec_is_scene_key_name(const char *name);
/* The key of r (any case), NULL if not given. */
raw_kv *spec_get(raw_section *r, const char *key);
/* "key 'K' in [SEC]: expected EXPECTED, got 'V'" at the key's line; -1. */
int spec_bad_value(parse_ctx *c, const raw_kv *kv, const char *sec, const char *expected);
/* The scene key "section.key" (any case) -> its table entry; NULL with a message. */
const crane_scene_key *spec_scene_key(parse_ctx *c, const char *name, int line, const char *where);
/* Checks value for scene key k with the scene files' own check (crane_scene_set on a scratch
 * copy of the base scene); what leads the message. 0, or -1 with the error recorded. */
int spec_check_scene_value(parse_ctx *c, const crane_scene *base, const crane_scene_key *k,
                           const char *value, int line, const char *what);
/* The raw sections -> the spec: [sweep] and the base scene, [set], the axes, [lhs], then the
 * limits and every sampled value. 0, or -1 with the error recorded. */
int spec_finish(parse_ctx *c, const char *const *roots);

/* -------------------------------------------------- sweep_axes.c: the axes ---- */

/* The first repeat among n value texts: the smallest i with v[i] equal to an earlier v[j] (*j),
 * -1 if none, -2 out of memory; O(n log n) (a sort of the indices). */
int spec_first_repeat(const char (*v)[SWEEP_VALUE_SIZE], int n, int *j);
/* An [axis] section -> the next axis and its swept key (values checked against base). */
int spec_finish_axis(parse_ctx *c, raw_section *r, const crane_scene *base);
/* The [lhs] section -> the last axis: its keys sampled together (the interval's ends checked
 * against base; the samples are checked by spec_finish). */
int spec_finish_lhs(parse_ctx *c, raw_section *r, const crane_scene *base);

/* ------------------------------------------ sweep_model.c: a model sweep ---- */

/* [sweep] model = FILE: the file (relative to dir, the sweep file's folder) loaded, its outputs
 * kept in c->outputs; s->is_model set. 0, or -1 with the error recorded. */
int spec_model_base(parse_ctx *c, const raw_kv *kv, const char *dir);
/* [set] of a model sweep: PATH = VALUE lines, each checked by loading the model with it and the
 * lines before it. */
int spec_model_set(parse_ctx *c, raw_section *r);
/* name is a parameter's path as bgsim --set takes it (the characters; whether the model has it
 * is the load's check). 0, or -1 with the error recorded ("WHERE: ..."). */
int spec_model_path(parse_ctx *c, const char *name, int line, const char *where);
/* value for the parameter at path, checked by loading the model with [set] and it; what leads
 * the message. 0, or -1 with the error recorded. */
int spec_check_model_value(parse_ctx *c, const char *path, const char *value, int line,
                           const char *what);
/* [sweep] quantities (kv NULL: the default) of a model sweep into s->report and s->mq. */
int spec_model_quantities(parse_ctx *c, const raw_kv *kv);

#endif
