/* pu_vtk: a series of two tagged frames read back (counts, points, cells, the collection's
 * entries), earlier frames removed at open, and a frame that cannot be written refused. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "pu_vtk.h"
#include "tap.h"

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) return NULL;
    char *s = calloc(1, 1 << 16);
    if (s) fread(s, 1, (1 << 16) - 1, f);
    fclose(f);
    return s;
}

static int count(const char *s, const char *sub)
{
    int n = 0;
    for (const char *p = s; (p = strstr(p, sub)); p++)
        n++;
    return n;
}

int main(void)
{
    char dir[] = "/tmp/pu_vtk_XXXXXX", path[256], msg[256];
    if (!mkdtemp(dir)) return tap_done();
    snprintf(path, sizeof path, "%s/vtk", dir);
    mkdir(path, 0777);
    snprintf(path, sizeof path, "%s/vtk/frame_00007.vtp", dir);
    FILE *old = fopen(path, "w");
    if (old) fclose(old);
    pu_vtk *v = pu_vtk_open(dir, "m.pvd", "model m", msg, sizeof msg);
    tap_ok(v != NULL, "opened (%s)", v ? "ok" : msg);
    tap_ok(access(path, F_OK) != 0, "an earlier frame file removed");
    /* a body: centre (marked) with two lines to its points; a member from point 1 to a mass */
    const double x[] = {0, 0, 0, 1, 0, 0, -1, 0, 0, 3, 0, -2};
    const int point_part[] = {0, 0, 0, 1}, marks[] = {0, 3}, mark_part[] = {0, 1};
    const int start[] = {0, 2, 4}, conn[] = {0, 1, 0, 2}, line_part[] = {0, 0};
    const char *const names[] = {"body", "member"};
    pu_vtk_frame fr = {0.5,   "test", 4,    x,         point_part, 2, marks, mark_part, 2,
                       start, conn,   line_part, 2, names};
    tap_ok(pu_vtk_write(v, &fr, msg, sizeof msg) == 0, "frame 0 written");
    fr.t = 1.0;
    tap_ok(pu_vtk_write(v, &fr, msg, sizeof msg) == 0, "frame 1 written");
    tap_ok(pu_vtk_close(&v) == 2 && !v, "closed with 2 frames");
    snprintf(path, sizeof path, "%s/vtk/frame_00001.vtp", dir);
    char *s = slurp(path);
    tap_ok(s && strstr(s, "NumberOfPoints=\"4\" NumberOfVerts=\"2\" NumberOfLines=\"2\""),
           "frame 1: 4 points, 2 marks, 2 lines");
    tap_ok(s && strstr(s, "part (point and cell data): 0 body, 1 member -->"),
           "the parts named in the comment");
    tap_ok(s && strstr(s, " 3 0 -2") && strstr(s, "Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\"> 1 "),
           "its points and its time");
    tap_ok(s && strstr(s, "Name=\"connectivity\" format=\"ascii\">\n          0 1 0 2") &&
               strstr(s, "Name=\"offsets\" format=\"ascii\">\n          2 4"),
           "the lines' connectivity and offsets");
    free(s);
    snprintf(path, sizeof path, "%s/m.pvd", dir);
    s = slurp(path);
    tap_ok(s && count(s, "<DataSet ") == 2 && strstr(s, "timestep=\"0.5\"") && strstr(s, "</VTKFile>") &&
               strstr(s, "<!-- model m -->"),
           "the collection lists both frames and is closed");
    free(s);
    /* a frame that cannot be written: the folder is gone */
    v = pu_vtk_open(dir, "m.pvd", "again", msg, sizeof msg);
    snprintf(path, sizeof path, "%s/vtk", dir);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", path);
    if (system(cmd) != 0) tap_diag("rm failed");
    tap_ok(v && pu_vtk_write(v, &fr, msg, sizeof msg) == -1 && strstr(msg, "frame_00000.vtp"),
           "a frame that cannot be written is refused, naming it (%s)", msg);
    pu_vtk_close(&v);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0) tap_diag("rm failed");
    return tap_done();
}
