/* ParaView time series of polydata (pu_vtk.h). */
#include "pu_vtk.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pu_fs.h"

struct pu_vtk {
    char dir[4096];
    FILE *pvd;
    int frames;
    char name[64]; /* the frame being written, relative to dir */
};

/* Removes the frame files a former series left in vdir (frame_NNNNN.vtp only). */
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

pu_vtk *pu_vtk_open(const char *dir, const char *pvd_name, const char *comment, char *msg,
                    size_t size)
{
    pu_vtk *v = calloc(1, sizeof *v);
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
    snprintf(path, sizeof path, "%s/%s", dir, pvd_name);
    v->pvd = fopen(path, "w");
    if (!v->pvd) {
        snprintf(msg, size, "cannot write %s: %s", path, strerror(errno));
        free(v);
        return NULL;
    }
    fprintf(v->pvd,
            "<?xml version=\"1.0\"?>\n"
            "<!-- %s -->\n"
            "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            "  <Collection>\n",
            comment ? comment : "");
    fflush(v->pvd);
    return v;
}

FILE *pu_vtk_frame_begin(pu_vtk *v, char *msg, size_t size)
{
    char path[4200];
    if (!v || !v->pvd) return NULL;
    snprintf(v->name, sizeof v->name, "vtk/frame_%05d.vtp", v->frames);
    snprintf(path, sizeof path, "%s/%s", v->dir, v->name);
    FILE *f = fopen(path, "w");
    if (!f) snprintf(msg, size, "cannot write %s: %s", path, strerror(errno));
    return f;
}

int pu_vtk_frame_end(pu_vtk *v, FILE *f, double t, int bad, char *msg, size_t size)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/%s", v->dir, v->name);
    if (fclose(f) != 0 || bad) {
        snprintf(msg, size, "writing %s failed", path);
        remove(path); /* no partial frame behind */
        return -1;
    }
    fprintf(v->pvd, "    <DataSet timestep=\"%.10g\" group=\"\" part=\"0\" file=\"%s\"/>\n", t,
            v->name);
    fflush(v->pvd);
    v->frames++;
    return 0;
}

int pu_vtk_close(pu_vtk **v)
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

/* ---- arrays ---- */

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

void pu_vtk_ints(FILE *f, const char *name, const int *a, int n)
{
    array_head(f, "Int32", name, 1);
    for (int i = 0; i < n; i++)
        fprintf(f, " %d", a[i]);
    array_tail(f);
}

void pu_vtk_reals(FILE *f, const char *name, const double *const *rows, int n, int ncomp)
{
    array_head(f, "Float64", name, ncomp);
    for (int i = 0; i < n; i++)
        for (int k = 0; k < ncomp; k++) {
            double x = rows[i] ? rows[i][k] : 0.0;
            fprintf(f, " %.10g", isfinite(x) ? x : 0.0);
        }
    array_tail(f);
}

void pu_vtk_field(FILE *f, const char *name, const double *x, int n)
{
    fprintf(f,
            "      <DataArray type=\"Float64\" Name=\"%s\" NumberOfTuples=\"%d\" "
            "format=\"ascii\">",
            name, n);
    for (int i = 0; i < n; i++)
        fprintf(f, " %.10g", x[i]);
    fprintf(f, " </DataArray>\n");
}

void pu_vtk_cells(FILE *f, const char *tag, const int *conn, const int *off, int n)
{
    fprintf(f, "      <%s>\n", tag);
    pu_vtk_ints(f, "connectivity", conn, off[n - 1]);
    pu_vtk_ints(f, "offsets", off, n);
    fprintf(f, "      </%s>\n", tag);
}

/* ---- a tagged frame ---- */

int pu_vtk_write(pu_vtk *v, const pu_vtk_frame *fr, char *msg, size_t size)
{
    if (!v || !fr || fr->npoints < 0) return -1;
    FILE *f = pu_vtk_frame_begin(v, msg, size);
    if (!f) return -1;
    int nm = fr->nmarks, nl = fr->nlines, ncell = nm + nl;
    int *voff = malloc((size_t)(nm + 1) * sizeof *voff), *cpart = malloc((size_t)(ncell + 1) * sizeof *cpart);
    const double **rows = malloc((size_t)(fr->npoints + 1) * sizeof *rows);
    if (!voff || !cpart || !rows) {
        free(voff), free(cpart), free(rows);
        fclose(f);
        snprintf(msg, size, "out of memory");
        return -1;
    }
    for (int i = 0; i < nm; i++)
        voff[i] = i + 1, cpart[i] = fr->mark_part[i];
    for (int i = 0; i < nl; i++)
        cpart[nm + i] = fr->line_part[i];
    for (int i = 0; i < fr->npoints; i++)
        rows[i] = fr->x + 3 * i;
    fprintf(f,
            "<?xml version=\"1.0\"?>\n<!-- %s at t = %.10g s: global frame; SI units",
            fr->title ? fr->title : "model", fr->t);
    if (fr->part_name && fr->nparts > 0) {
        fprintf(f, ";\n     part (point and cell data):");
        for (int i = 0; i < fr->nparts; i++)
            fprintf(f, "%s %d %s", i ? "," : "", i, fr->part_name[i] ? fr->part_name[i] : "?");
    }
    fprintf(f, " -->\n"
               "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
               "  <PolyData>\n    <FieldData>\n");
    pu_vtk_field(f, "TimeValue", &fr->t, 1);
    fprintf(f, "    </FieldData>\n");
    fprintf(f,
            "    <Piece NumberOfPoints=\"%d\" NumberOfVerts=\"%d\" NumberOfLines=\"%d\" "
            "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n",
            fr->npoints, nm, nl);
    fprintf(f, "      <PointData Scalars=\"part\">\n");
    pu_vtk_ints(f, "part", fr->point_part, fr->npoints);
    fprintf(f, "      </PointData>\n      <CellData Scalars=\"part\">\n");
    pu_vtk_ints(f, "part", cpart, ncell);
    fprintf(f, "      </CellData>\n      <Points>\n");
    pu_vtk_reals(f, NULL, rows, fr->npoints, 3);
    fprintf(f, "      </Points>\n");
    if (nm > 0) pu_vtk_cells(f, "Verts", fr->mark_point, voff, nm);
    if (nl > 0) pu_vtk_cells(f, "Lines", fr->line_conn, fr->line_start + 1, nl);
    fprintf(f, "    </Piece>\n  </PolyData>\n</VTKFile>\n");
    int bad = ferror(f);
    free(voff), free(cpart), free(rows);
    return pu_vtk_frame_end(v, f, fr->t, bad, msg, size);
}
