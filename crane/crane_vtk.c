/* The crane's ParaView time series (crane_vtk.h): crane.pvd and vtk/frame_NNNNN.vtp. */
#include "crane_vtk.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pu_vtk.h"

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
    pu_vtk *series;
    frame fr; /* the frame being written */
};

crane_vtk *crane_vtk_open(const char *dir, const char *scene_name, char *msg, size_t size)
{
    crane_vtk *v = calloc(1, sizeof *v);
    char comment[512];
    if (!v) {
        snprintf(msg, size, "out of memory");
        return NULL;
    }
    snprintf(comment, sizeof comment,
             "crane scene %s: the motion as a time series, one PolyData file per frame;\n"
             "     global frame, Z0 up; SI units (m, kg, s, N, N m, Pa); see crane/crane_vtk.h",
             scene_name ? scene_name : "?");
    v->series = pu_vtk_open(dir, "crane.pvd", comment, msg, size);
    if (!v->series) {
        free(v);
        return NULL;
    }
    return v;
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
    pu_vtk_field(f, "TimeValue", &g->t, 1);
    pu_vtk_field(f, "theta", &g->theta, 1);
    pu_vtk_field(f, "omega", &g->omega, 1);
    if (g->rope) pu_vtk_field(f, "rope_tension", &g->rope_tension, 1);
    if (g->nties) pu_vtk_field(f, "tie_tension", g->tie_tension, g->nties);
    if (isfinite(g->pump_x)) pu_vtk_field(f, "pump_x", &g->pump_x, 1);
    if (isfinite(g->p_high)) pu_vtk_field(f, "p_high", &g->p_high, 1);
    if (isfinite(g->p_low)) pu_vtk_field(f, "p_low", &g->p_low, 1);
    fprintf(f, "    </FieldData>\n");
    fprintf(f,
            "    <Piece NumberOfPoints=\"%d\" NumberOfVerts=\"%d\" NumberOfLines=\"%d\" "
            "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n",
            fr->np, fr->nv, fr->nl);
    fprintf(f, "      <PointData Scalars=\"part\" Vectors=\"deflection\">\n");
    pu_vtk_ints(f, "part", fr->part, fr->np);
    pu_vtk_ints(f, "node", fr->node, fr->np);
    for (int i = 0; i < nb; i++)
        rows[i] = fr->mass + i;
    pu_vtk_reals(f, "mass", rows, nb, 1);
    /* boom data: rows of the boom's points, NULL elsewhere */
#define BOOM_ARRAY(name, expr, ncomp)                                                              \
    do {                                                                                           \
        for (int i = 0; i < nb; i++)                                                               \
            rows[i] = fr->node[i] >= 0 ? (expr) : NULL;                                            \
        pu_vtk_reals(f, name, rows, nb, ncomp);                                                    \
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
    pu_vtk_ints(f, "part", cpart, fr->nv + fr->nl);
    for (int i = 0; i < fr->nv + fr->nl; i++)
        rows[i] = ctens + i;
    pu_vtk_reals(f, "tension", rows, fr->nv + fr->nl, 1);
    fprintf(f, "      </CellData>\n      <Points>\n");
    pu_vtk_reals(f, NULL, fr->x, fr->np, 3);
    fprintf(f, "      </Points>\n");
    pu_vtk_cells(f, "Verts", fr->vconn, fr->voff, fr->nv);
    pu_vtk_cells(f, "Lines", fr->lconn, fr->loff, fr->nl);
    fprintf(f, "    </Piece>\n  </PolyData>\n</VTKFile>\n");
    return ferror(f) ? -1 : 0;
}

int crane_vtk_frame(crane_vtk *v, const crane_geom *g, char *msg, size_t size)
{
    if (!v || !g || !v->series) return -1;
    FILE *f = pu_vtk_frame_begin(v->series, msg, size);
    if (!f) return -1;
    build_frame(g, &v->fr);
    int bad = write_vtp(f, g, &v->fr);
    return pu_vtk_frame_end(v->series, f, g->t, bad, msg, size);
}

int crane_vtk_close(crane_vtk **v)
{
    if (!v || !*v) return 0;
    int n = pu_vtk_close(&(*v)->series);
    free(*v);
    *v = NULL;
    return n;
}
