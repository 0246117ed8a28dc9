/* ParaView time series of polydata (libprogutil, prefix pu_vtk_): a collection file (NAME.pvd,
 * one data set per time) and vtk/frame_NNNNN.vtp (VTK's XML polydata, ASCII), written frame by
 * frame so that a series cut short by a signal or a full disk stays readable up to its last
 * whole frame. The file formats: "VTK File Formats", Kitware (XML PolyData and Collection).
 *
 * Two levels: the series and its frames' files with the array writers (a program that lays out
 * its own frame: the crane's), and pu_vtk_write for a frame given as points, marked points and
 * polylines tagged with their parts (a model file's drawing). No output to the terminal, no
 * exit, no global state. */
#ifndef PU_VTK_H
#define PU_VTK_H

#include <stddef.h>
#include <stdio.h>

typedef struct pu_vtk pu_vtk;

/* Opens the series in dir: dir/pvd_name with comment (its text, inside <!-- -->, may span
 * lines) and the folder dir/vtk (made; frame files an earlier series left there removed). NULL
 * with the reason in msg. */
pu_vtk *pu_vtk_open(const char *dir, const char *pvd_name, const char *comment, char *msg,
                    size_t size);
/* The next frame's file opened for writing (its XML is the caller's); NULL with the reason in
 * msg. */
FILE *pu_vtk_frame_begin(pu_vtk *v, char *msg, size_t size);
/* Closes the frame's file (bad: the caller's writing failed) and adds it to the collection at
 * time t. 0, or -1 with the reason in msg. */
int pu_vtk_frame_end(pu_vtk *v, FILE *f, double t, int bad, char *msg, size_t size);
/* Closes the collection: the number of frames, or -1 when it could not be completed. *v
 * becomes NULL. */
int pu_vtk_close(pu_vtk **v);

/* Array writers of a frame's XML (indented for <PointData>, <CellData>, <Points>). */
void pu_vtk_ints(FILE *f, const char *name, const int *a, int n);
/* n tuples of ncomp values; a NULL row (rows[i] == NULL) and values not finite are zeros */
void pu_vtk_reals(FILE *f, const char *name, const double *const *rows, int n, int ncomp);
/* a <FieldData> array of n values */
void pu_vtk_field(FILE *f, const char *name, const double *x, int n);
/* a cell block (Verts, Lines): connectivity and offsets of n cells (n > 0) */
void pu_vtk_cells(FILE *f, const char *tag, const int *conn, const int *off, int n);

/* A frame of points (global x, y, z), marked points and polylines, each tagged with its part. */
typedef struct pu_vtk_frame {
    double t;
    const char *title; /* a line for the file's comment */
    int npoints;
    const double *x;       /* 3 per point */
    const int *point_part; /* per point */
    int nmarks;
    const int *mark_point, *mark_part;
    int nlines;
    const int *line_start; /* line i: line_conn[line_start[i] .. line_start[i + 1]) */
    const int *line_conn, *line_part;
    int nparts;
    const char *const *part_name; /* the parts' names, listed in a comment (NULL: none) */
} pu_vtk_frame;
/* Writes f as the next frame (point and cell array "part"). 0, or -1 with the reason in msg. */
int pu_vtk_write(pu_vtk *v, const pu_vtk_frame *f, char *msg, size_t size);

#endif
