/* Private to libcrane's scene files (crane_scene_keys.c: the key table and what it drives;
 * crane_scene.c: the parser): the table's record and the look-ups the parser uses. */
#ifndef CRANE_SCENE_IMPL_H
#define CRANE_SCENE_IMPL_H

#include <stddef.h>

#include "crane_scene.h"
#include "pu_ini.h" /* pu_ini_ieq: names any case */

typedef enum range_kind {
    R_ANY,    /* finite */
    R_POS,    /* > 0 */
    R_NONNEG, /* >= 0 */
    R_OPEN01, /* in (0, 1) */
    R_UNIT0,  /* in [0, 1) */
    R_INT     /* integer in lo..hi */
} range_kind;

/* A key of crane_scene: its public description, its field (offset), range and default, and a
 * note for the key list (docs/scene-keys.md). The table of them is the one place where the keys,
 * their defaults, ranges, units and meanings are written. */
typedef struct key_def {
    crane_scene_key pub;
    size_t off;
    range_kind range;
    int lo, hi;           /* R_INT */
    double def[3];        /* default: a number or integer (def[0]), a vector */
    const char *def_name; /* default of the name (CRANE_KEY_NAME) */
    const char *note;     /* more on the key for the key list, or NULL */
} key_def;

/* The table (crane_scene_keys.c), one entry per key in the order of the sections. */
#define CRANE_SCENE_NKEYS 72
extern const key_def crane_scene_keys[];
#define KEYS crane_scene_keys
#define NKEYS CRANE_SCENE_NKEYS

/* The field of key k in s. */
static inline double *dfield(crane_scene *s, const key_def *k)
{
    return (double *)(void *)((char *)s + k->off);
}
static inline const double *cdfield(const crane_scene *s, const key_def *k)
{
    return (const double *)(const void *)((const char *)s + k->off);
}
static inline int *ifield(crane_scene *s, const key_def *k)
{
    return (int *)(void *)((char *)s + k->off);
}
static inline const int *cifield(const crane_scene *s, const key_def *k)
{
    return (const int *)(const void *)((const char *)s + k->off);
}

/* The section of the table named name (any case), or NULL. */
const char *csk_known_section(const char *name);
/* The section nearest to name by pu_cli_edit_distance, its distance in *dist. */
const char *csk_nearest_section(const char *name, int *dist);
/* Index of the key (any case), or -1. */
int csk_find_key(const char *section, const char *key);
/* Nearest key of section (-1 if it has none), its distance in *dist. */
int csk_nearest_key(const char *section, const char *key, int *dist);
/* "elements, foot, length, ..." (the keys of section); "[scene], [environment], ..." */
void csk_list_keys(const char *section, char *buf, size_t size);
void csk_list_sections(char *buf, size_t size);
/* x within the range kind r. */
int csk_in_range(range_kind r, double x);

#endif
