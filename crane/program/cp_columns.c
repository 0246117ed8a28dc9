/* results.csv read back by column name (crane_program.h): its header, and the rows' figures the
 * crane's summary and Fig. 5a take from a model file's run. A column is found by its name as
 * crane_output_index finds it: the name, then the end or a space (the unit: "theta [rad]"), so
 * that the crane's columns from a scene ("theta [rad]") and from a model file ("theta") are
 * found alike. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "crane_program.h"

int cp_columns_read(const char *csv, cp_columns *cs)
{
    memset(cs, 0, sizeof *cs);
    FILE *f = fopen(csv, "r");
    if (!f) return -1;
    char *line = NULL;
    size_t cap = 0;
    ssize_t len = getline(&line, &cap, f);
    int e = len < 0 ? (ferror(f) ? errno : EINVAL) : 0;
    fclose(f);
    if (len < 0) {
        free(line);
        errno = e;
        return -1;
    }
    line[strcspn(line, "\r\n")] = '\0';
    for (char *p = line, *q; cs->n < CP_MAX_COLS; p = q + 1) {
        q = strchr(p, ',');
        size_t l = q ? (size_t)(q - p) : strlen(p);
        snprintf(cs->name[cs->n++], sizeof cs->name[0], "%.*s", (int)l, p);
        if (!q) break;
    }
    free(line);
    return 0;
}

int cp_column(const cp_columns *cs, const char *key)
{
    if (!key) return -1;
    size_t n = strlen(key);
    for (int i = 0; i < cs->n; i++) {
        const char *nm = cs->name[i];
        if (!strncmp(nm, key, n) && (nm[n] == '\0' || nm[n] == ' ')) return i;
    }
    return -1;
}

const char *cp_column_label(const cp_columns *cs, int i)
{
    const char *nm = cs->name[i];
    int c = strchr(nm, '[') ? -1 : crane_output_index(nm);
    return c >= 0 ? crane_output_names[c] : nm;
}

int cp_rows_scan(const char *csv, const cp_columns *cs, double cx, double cy, cp_rows *s)
{
    memset(s, 0, sizeof *s);
    FILE *f = fopen(csv, "r");
    if (!f) return -1;
    int d1 = cp_column(cs, "tip_defl_1"), d2 = cp_column(cs, "tip_defl_2");
    int tx = cp_column(cs, "tip_x"), ty = cp_column(cs, "tip_y");
    char *line = NULL;
    size_t cap = 0;
    double *v = s->last;
    for (long k = 0; getline(&line, &cap, f) >= 0; k++) {
        if (k == 0) continue; /* the header */
        /* a row of numbers, one per column (a short row is no row) */
        char *p = line, *end;
        int i = 0;
        for (; i < cs->n; i++) {
            v[i] = strtod(p, &end);
            if (end == p) break;
            p = *end == ',' ? end + 1 : end;
        }
        if (i < cs->n) break;
        if (s->rows++ == 0) memcpy(s->first, v, (size_t)cs->n * sizeof *v);
        if (d1 >= 0 && fabs(v[d1]) > s->peak[0]) s->peak[0] = fabs(v[d1]);
        if (d2 >= 0 && fabs(v[d2]) > s->peak[1]) s->peak[1] = fabs(v[d2]);
        if (tx >= 0 && ty >= 0) {
            double ex = fabs(v[tx] - cx), ey = fabs(v[ty] - cy);
            if (isfinite(ex) && ex > s->reach) s->reach = ex;
            if (isfinite(ey) && ey > s->reach) s->reach = ey;
        }
    }
    int bad = ferror(f);
    free(line);
    fclose(f);
    return bad ? -1 : 0;
}
