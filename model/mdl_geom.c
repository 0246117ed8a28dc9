/* The model drawn at a state (mdl_model.h: mdl_geometry), for ParaView series: every mechanical
 * part as points, polylines and marked points in the global frame.
 *
 * Drawing is kept apart from the type table: a table here maps the mechanical types to their
 * shape, each built from what the instance offers (its elements, its ports' positions through
 * port_position, and the positions of its neighbours through the bonds):
 *   mech.body          its mass centre (marked) and a line from it to each of its points
 *   mech.point_mass    its position (marked)
 *   mech.support       its position (marked)
 *   mech.spring, mech.truss, mech.rope, hyd.cylinder
 *                      a line between the positions its two mechanical ports are bonded to
 *   mech.beam_chain    a polyline through its nodes
 * Types without a shape (joints, sensors, hydraulics, signals) are not drawn. */
#include <stdlib.h>
#include <string.h>

#include "mdl_priv.h"
#include "mech_body.h"

typedef struct drawing {
    const mdl_model *mm;
    const mdl_inode *leaf;
    const double *y;
    mdl_geom *g;
    int part;
} drawing;

static int grow(void **p, int *cap, int need, size_t size)
{
    if (need <= *cap) return 0;
    int nc = *cap ? *cap : 64;
    while (nc < need)
        nc *= 2;
    void *q = realloc(*p, (size_t)nc * size);
    if (!q) return -1;
    *p = q;
    *cap = nc;
    return 0;
}

static int point(drawing *d, const double x[3])
{
    mdl_geom *g = d->g;
    if (grow((void **)&g->x, &g->cap_x, 3 * (g->npoints + 1), sizeof *g->x) ||
        grow((void **)&g->point_part, &g->cap_pp, g->npoints + 1, sizeof *g->point_part))
        return BG_ERR_MEMORY;
    memcpy(g->x + 3 * g->npoints, x, 3 * sizeof *x);
    g->point_part[g->npoints] = d->part;
    return g->npoints++;
}

static int line(drawing *d, const int *pts, int n)
{
    mdl_geom *g = d->g;
    if (grow((void **)&g->line_conn, &g->cap_lc, g->line_start[g->nlines] + n, sizeof *g->line_conn) ||
        grow((void **)&g->line_part, &g->cap_lp, g->nlines + 1, sizeof *g->line_part) ||
        grow((void **)&g->line_start, &g->cap_ls, g->nlines + 2, sizeof *g->line_start))
        return BG_ERR_MEMORY;
    memcpy(g->line_conn + g->line_start[g->nlines], pts, (size_t)n * sizeof *pts);
    g->line_part[g->nlines] = d->part;
    g->line_start[g->nlines + 1] = g->line_start[g->nlines] + n;
    g->nlines++;
    return BG_OK;
}

static int mark(drawing *d, int p)
{
    mdl_geom *g = d->g;
    if (grow((void **)&g->mark_point, &g->cap_mp, g->nmarks + 1, sizeof *g->mark_point) ||
        grow((void **)&g->mark_part, &g->cap_mk, g->nmarks + 1, sizeof *g->mark_part))
        return BG_ERR_MEMORY;
    g->mark_point[g->nmarks] = p;
    g->mark_part[g->nmarks++] = d->part;
    return BG_OK;
}

/* ---- the shapes ---- */

static int body_shape(drawing *d)
{
    const mdl_instance *in = &d->leaf->inst;
    int ix = mech_body_var(d->mm->m, mdl_instance_main(in), 'x');
    if (ix < 0) return BG_ERR_ARGUMENT;
    int c = point(d, d->y + ix);
    if (c < 0) return c;
    int r = mark(d, c);
    for (int k = 0; r == BG_OK && k < in->nports; k++) {
        double x[3];
        if ((r = in->type->port_position(d->mm->m, in, k, d->y, x)) != BG_OK) break;
        int p = point(d, x), ids[2] = {c, p};
        r = p < 0 ? p : line(d, ids, 2);
    }
    return r;
}

static int own_point_shape(drawing *d)
{
    double x[3];
    const mdl_instance *in = &d->leaf->inst;
    int r = in->type->port_position(d->mm->m, in, 0, d->y, x);
    if (r != BG_OK) return r;
    int p = point(d, x);
    return p < 0 ? p : mark(d, p);
}

/* a line between what the first two (mechanical) ports are bonded to */
static int member_shape(drawing *d)
{
    double a[3], b[3];
    int r = mdl_neighbour_position(d->mm, d->leaf, 0, d->y, a);
    if (r == BG_OK) r = mdl_neighbour_position(d->mm, d->leaf, 1, d->y, b);
    if (r != BG_OK) return r;
    int pa = point(d, a), pb = point(d, b), ids[2] = {pa, pb};
    return pa < 0 || pb < 0 ? BG_ERR_MEMORY : line(d, ids, 2);
}

/* the nodes are the instance's first elements (mdl_types_beam.c), n + 1 of them */
static int chain_shape(drawing *d)
{
    const mdl_instance *in = &d->leaf->inst;
    int nn = (in->nelems + 1) / 2;
    int *ids = malloc((size_t)nn * sizeof *ids);
    if (!ids) return BG_ERR_MEMORY;
    int r = BG_OK;
    for (int k = 0; r == BG_OK && k < nn; k++) {
        int ix = mech_body_var(d->mm->m, mdl_instance_elem(in, k), 'x');
        if (ix < 0) r = BG_ERR_ARGUMENT;
        else if ((ids[k] = point(d, d->y + ix)) < 0) r = ids[k];
    }
    if (r == BG_OK) r = line(d, ids, nn);
    free(ids);
    return r;
}

static const struct {
    const char *type;
    int (*shape)(drawing *d);
} shapes[] = {
    {"mech.body", body_shape},        {"mech.point_mass", own_point_shape},
    {"mech.support", own_point_shape}, {"mech.spring", member_shape},
    {"mech.truss", member_shape},      {"mech.rope", member_shape},
    {"hyd.cylinder", member_shape},    {"mech.beam_chain", chain_shape},
};

void mdl_geom_clear(mdl_geom *g)
{
    if (!g) return;
    free(g->x);
    free(g->point_part);
    free(g->line_start);
    free(g->line_conn);
    free(g->line_part);
    free(g->mark_point);
    free(g->mark_part);
    free(g->part_path);
    free(g->part_type);
    memset(g, 0, sizeof *g);
}

int mdl_geometry(const mdl_model *mm, const double *y, mdl_geom *g, bg_error *err)
{
    if (!mm || !y || !g) return bg_error_raise(err, BG_ERR_ARGUMENT, "mdl_geometry", "a NULL argument");
    g->npoints = g->nlines = g->nmarks = g->nparts = 0;
    if (grow((void **)&g->line_start, &g->cap_ls, 1, sizeof *g->line_start) ||
        grow((void **)&g->part_path, &g->cap_pa, mm->nleaves, sizeof *g->part_path) ||
        grow((void **)&g->part_type, &g->cap_pt, mm->nleaves, sizeof *g->part_type))
        return bg_error_raise(err, BG_ERR_MEMORY, "mdl_geometry", "out of memory");
    g->line_start[0] = 0;
    for (int i = 0; i < mm->nleaves; i++) {
        const mdl_inode *l = mm->leaves[i];
        for (size_t s = 0; s < sizeof shapes / sizeof *shapes; s++) {
            if (strcmp(shapes[s].type, l->type->name)) continue;
            drawing d = {mm, l, y, g, g->nparts};
            g->part_path[g->nparts] = l->dotpath;
            g->part_type[g->nparts++] = l->type->name;
            int r = shapes[s].shape(&d);
            if (r != BG_OK)
                return bg_error_raise(err, r, "mdl_geometry", "%s (%s): %s", l->dotpath, l->type->name,
                                      r == BG_ERR_MEMORY ? "out of memory" : "its position cannot be found");
            break;
        }
    }
    return BG_OK;
}
