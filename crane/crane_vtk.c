/* The crane's ParaView time series (crane_vtk.h): crane.pvd and vtk/frame_NNNNN.vtp. */
#include "crane_vtk.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "pu_fs.h"

enum { P_PLATFORM, P_BOOM, P_GANTRY, P_LOAD, P_CW, P_TIE, P_ROPE, P_FOOT };

enum { MAXP = CRANE_MAX_NODES + 16, MAXC = 16, MAXCONN = CRANE_MAX_NODES + 64 };

typedef struct frame {
    int np, part[MAXP], node[MAXP];
    const double *x[MAXP];
    double mass[MAXP];
    int nv, vconn[MAXC], voff[MAXC], vpart[MAXC];
    int nl, lconn[MAXCONN], loff[MAXC], lpart[MAXC], nlconn;
    double ltension[MAXC];
} frame;

struct crane_vtk {
    char dir[4096];
    FILE *pvd;
    int frames;
    frame fr; /* the frame being written */
};

/* Removes the frame files a former run left in dir/vtk (frame_NNNNN.vtp only). */
static void remove_old_frames(const char *vdir)
{
    DIR *d = opendir(vdir);
    if (!d) return;
    struct dirent *e;
    char path[4400];
    while ((e = readdir(d))) {
        unsigned k;
        char tail[8];
        if (sscanf(e->d_name, "frame_%5u%7s", &k, tail) == 2 && !strcmp(tail, ".vtp") &&
            strlen(e->d_name) == 15) {
            snprintf(path, sizeof path, "%s/%s", vdir, e->d_name);
            remove(path);
        }
    }
    closedir(d);
}

crane_vtk *crane_vtk_open(const char *dir, const char *scene_name, char *msg, size_t size)
{
    crane_vtk *v = calloc(1, sizeof *v);
    char path[4200];
    if (!v) {
        snprintf(msg, size, "out of memory");
        return NULL;
    }
    snprintf(v->dir, sizeof v->dir, "%s", dir);
    snprintf(path, sizeof path, "%s/vtk", dir);
    if (pu_mkdir_p(path, 0777, msg, size) != 0) {
        free(v);
        return NULL;
    }
    remove_old_frames(path);
    snprintf(path, sizeof path, "%s/crane.pvd", dir);
    v->pvd = fopen(path, "w");
    if (!v->pvd) {
        snprintf(msg, size, "cannot write %s: %s", path, strerror(errno));
        free(v);
        return NULL;
    }
    fprintf(v->pvd,
            "<?xml version=\"1.0\"?>\n"
            "<!-- crane scene %s: the motion as a time series, one PolyData file per frame;\n"
            "     global frame, Z0 up; SI units (m, kg, s, N, N m, Pa); see crane/crane_vtk.h -->\n"
            "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            "  <Collection>\n",
            scene_name ? scene_name : "?");
    fflush(v->pvd);
    return v;
}

/* ------------------------------------------------------------ arrays ---- */

static void array_head(FILE *f, const char *type, const char *name, int ncomp)
{
    fprintf(f, "        <DataArray type=\"%s\"", type);
    if (name) fprintf(f, " Name=\"%s\"", name);
    if (ncomp > 1) fprintf(f, " NumberOfComponents=\"%d\"", ncomp);
    fprintf(f, " format=\"ascii\">\n         ");
}

static void array_tail(FILE *f)
{
    fprintf(f, "\n        </DataArray>\n");
}

static void ints(FILE *f, const char *name, const int *a, int n)
{
    array_head(f, "Int32", name, 1);
    for (int i = 0; i < n; i++)
        fprintf(f, " %d", a[i]);
    array_tail(f);
}

/* n tuples of ncomp values; NULL rows (rows[i] == NULL) are zeros */
static void reals(FILE *f, const char *name, const double *const *rows, int n, int ncomp)
{
    array_head(f, "Float64", name, ncomp);
    for (int i = 0; i < n; i++)
        for (int k = 0; k < ncomp; k++) {
            double x = rows[i] ? rows[i][k] : 0.0;
            fprintf(f, " %.10g", isfinite(x) ? x : 0.0);
        }
    array_tail(f);
}

static void field(FILE *f, const char *name, const double *x, int n)
{
    fprintf(f,
            "      <DataArray type=\"Float64\" Name=\"%s\" NumberOfTuples=\"%d\" "
            "format=\"ascii\">",
            name, n);
    for (int i = 0; i < n; i++)
        fprintf(f, " %.10g", x[i]);
    fprintf(f, " </DataArray>\n");
}

/* cells: connectivity and offsets */
static void cells(FILE *f, const char *tag, const int *conn, const int *off, int n)
{
    fprintf(f, "      <%s>\n", tag);
    ints(f, "connectivity", conn, off[n - 1]);
    ints(f, "offsets", off, n);
    fprintf(f, "      </%s>\n", tag);
}

/* ------------------------------------------------------------ frames ---- */

static int point(frame *fr, const double *x, int part, int node, double mass)
{
    fr->x[fr->np] = x;
    fr->part[fr->np] = part;
    fr->node[fr->np] = node;
    fr->mass[fr->np] = mass;
    return fr->np++;
}

static void vert(frame *fr, int p, int part)
{
    fr->vconn[fr->nv] = p;
    fr->vpart[fr->nv] = part;
    fr->voff[fr->nv] = fr->nv + 1;
    fr->nv++;
}

static void line(frame *fr, const int *ids, int n, int part, double tension)
{
    for (int i = 0; i < n; i++)
        fr->lconn[fr->nlconn++] = ids[i];
    fr->loff[fr->nl] = fr->nlconn;
    fr->lpart[fr->nl] = part;
    fr->ltension[fr->nl] = tension;
    fr->nl++;
}

static void build_frame(const crane_geom *g, frame *fr)
{
    int deck[5], base[2], node0, gant[2], load = -1, cw = -1;
    fr->np = fr->nv = fr->nl = fr->nlconn = 0;
    for (int k = 0; k < 4; k++)
        deck[k] = point(fr, g->deck[k], P_PLATFORM, -1, 0);
    deck[4] = deck[0];
    for (int k = 0; k < g->ngantry; k++)
        base[k] = point(fr, g->gantry_base[k], P_PLATFORM, -1, 0);
    node0 = fr->np;
    for (int k = 0; k < g->nodes; k++)
        point(fr, g->node[k], P_BOOM, k, 0);
    int tip = node0 + g->nodes - 1;
    for (int k = 0; k < g->ngantry; k++)
        gant[k] = point(fr, g->gantry[k], P_GANTRY, -1, 0);
    if (g->rope) load = point(fr, g->load, P_LOAD, -1, g->load_mass);
    if (g->counterweight) cw = point(fr, g->cw, P_CW, -1, g->cw_mass);
    /* verts */
    vert(fr, node0, P_FOOT);
    for (int k = 0; k < g->ngantry; k++)
        vert(fr, gant[k], P_GANTRY);
    if (load >= 0) vert(fr, load, P_LOAD);
    if (cw >= 0) vert(fr, cw, P_CW);
    /* lines */
    line(fr, deck, 5, P_PLATFORM, 0);
    for (int k = 0; k < g->ngantry; k++) {
        int ids[2] = {base[k], gant[k]};
        line(fr, ids, 2, P_PLATFORM, 0);
    }
    if (g->ngantry == 2) line(fr, gant, 2, P_PLATFORM, 0);
    int boom[CRANE_MAX_NODES];
    for (int k = 0; k < g->nodes; k++)
        boom[k] = node0 + k;
    line(fr, boom, g->nodes, P_BOOM, 0);
    for (int k = 0; k < g->nties; k++) {
        int ids[2] = {gant[g->ngantry == 2 ? k : 0], tip};
        line(fr, ids, 2, P_TIE, g->tie_tension[k]);
    }
    if (load >= 0) {
        int ids[2] = {tip, load};
        line(fr, ids, 2, P_ROPE, g->rope_tension);
    }
}

static int write_vtp(FILE *f, const crane_geom *g, const frame *fr)
{
    const double *rows[MAXP];
    double scal[MAXP];
    const int nb = fr->np;
    fprintf(f,
            "<?xml version=\"1.0\"?>\n"
            "<!-- crane at t = %.10g s: global frame, Z0 up; SI units (m, kg, s, N, N m, "
            "Pa); see crane/crane_vtk.h -->\n"
            "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            "  <PolyData>\n    <FieldData>\n",
            g->t);
    field(f, "TimeValue", &g->t, 1);
    field(f, "theta", &g->theta, 1);
    field(f, "omega", &g->omega, 1);
    if (g->rope) field(f, "rope_tension", &g->rope_tension, 1);
    if (g->nties) field(f, "tie_tension", g->tie_tension, g->nties);
    if (isfinite(g->pump_x)) field(f, "pump_x", &g->pump_x, 1);
    if (isfinite(g->p_high)) field(f, "p_high", &g->p_high, 1);
    if (isfinite(g->p_low)) field(f, "p_low", &g->p_low, 1);
    fprintf(f, "    </FieldData>\n");
    fprintf(f,
            "    <Piece NumberOfPoints=\"%d\" NumberOfVerts=\"%d\" NumberOfLines=\"%d\" "
            "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n",
            fr->np, fr->nv, fr->nl);
    fprintf(f, "      <PointData Scalars=\"part\" Vectors=\"deflection\">\n");
    ints(f, "part", fr->part, fr->np);
    ints(f, "node", fr->node, fr->np);
    for (int i = 0; i < nb; i++)
        rows[i] = fr->mass + i;
    reals(f, "mass", rows, nb, 1);
    /* boom data: rows of the boom's points, NULL elsewhere */
#define BOOM_ARRAY(name, expr, ncomp)                                                              \
    do {                                                                                           \
        for (int i = 0; i < nb; i++)                                                               \
            rows[i] = fr->node[i] >= 0 ? (expr) : NULL;                                            \
        reals(f, name, rows, nb, ncomp);                                                           \
    } while (0)
    BOOM_ARRAY("deflection", g->defl[fr->node[i]], 3);
    for (int i = 0; i < nb; i++)
        scal[i] = fr->node[i] >= 0 ? g->defl_luff[fr->node[i]] : 0.0;
    BOOM_ARRAY("deflection_luff", scal + i, 1);
    for (int i = 0; i < nb; i++)
        scal[i] = fr->node[i] >= 0 ? g->defl_side[fr->node[i]] : 0.0;
    BOOM_ARRAY("deflection_side", scal + i, 1);
    if (g->beam) {
        BOOM_ARRAY("section_force", g->force[fr->node[i]], 3);
        BOOM_ARRAY("section_moment", g->moment[fr->node[i]], 3);
        BOOM_ARRAY("section_force_local", g->force_local[fr->node[i]], 3);
        BOOM_ARRAY("section_moment_local", g->moment_local[fr->node[i]], 3);
    }
#undef BOOM_ARRAY
    fprintf(f, "      </PointData>\n      <CellData Scalars=\"part\">\n");
    int cpart[2 * MAXC];
    double ctens[2 * MAXC];
    for (int i = 0; i < fr->nv; i++)
        cpart[i] = fr->vpart[i], ctens[i] = 0;
    for (int i = 0; i < fr->nl; i++)
        cpart[fr->nv + i] = fr->lpart[i], ctens[fr->nv + i] = fr->ltension[i];
    ints(f, "part", cpart, fr->nv + fr->nl);
    for (int i = 0; i < fr->nv + fr->nl; i++)
        rows[i] = ctens + i;
    reals(f, "tension", rows, fr->nv + fr->nl, 1);
    fprintf(f, "      </CellData>\n      <Points>\n");
    reals(f, NULL, fr->x, fr->np, 3);
    fprintf(f, "      </Points>\n");
    cells(f, "Verts", fr->vconn, fr->voff, fr->nv);
    cells(f, "Lines", fr->lconn, fr->loff, fr->nl);
    fprintf(f, "    </Piece>\n  </PolyData>\n</VTKFile>\n");
    return ferror(f) ? -1 : 0;
}

int crane_vtk_frame(crane_vtk *v, const crane_geom *g, char *msg, size_t size)
{
    char name[64], path[4200];
    if (!v || !g || !v->pvd) return -1;
    snprintf(name, sizeof name, "vtk/frame_%05d.vtp", v->frames);
    snprintf(path, sizeof path, "%s/%s", v->dir, name);
    FILE *f = fopen(path, "w");
    if (!f) {
        snprintf(msg, size, "cannot write %s: %s", path, strerror(errno));
        return -1;
    }
    build_frame(g, &v->fr);
    int bad = write_vtp(f, g, &v->fr);
    if (fclose(f) != 0 || bad) {
        snprintf(msg, size, "writing %s failed", path);
        return -1;
    }
    fprintf(v->pvd, "    <DataSet timestep=\"%.10g\" group=\"\" part=\"0\" file=\"%s\"/>\n", g->t,
            name);
    fflush(v->pvd);
    v->frames++;
    return 0;
}

int crane_vtk_close(crane_vtk **v)
{
    if (!v || !*v) return 0;
    int n = (*v)->frames;
    fprintf((*v)->pvd, "  </Collection>\n</VTKFile>\n");
    int bad = ferror((*v)->pvd);
    if (fclose((*v)->pvd) != 0 || bad) n = -1;
    free(*v);
    *v = NULL;
    return n;
}
