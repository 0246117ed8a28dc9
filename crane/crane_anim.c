/* The crane's animation (crane_anim.h): anim.dat and anim_track.dat during the run, anim.gp and
 * gnuplot's crane.gif and crane_frame.png at the end (pu_gnuplot.h: no shell between). */
#include "crane_anim.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "pu_gnuplot.h"

enum { A_PLATFORM, A_BOOM, A_BOOM_TRUE, A_LOAD, A_CW, A_TIE, A_ROPE };

struct crane_anim {
    char dir[4096], scene[64];
    double step, scale;
    FILE *dat, *track;
    int frames, cap, bad;
    double *times;
    double lo[2], hi[2]; /* extents of the side view (u, z) */
    double reach;        /* largest distance of a point from the axis (the top view) */
    double A[3];         /* the slewing joint */
    int peak_frame;      /* the frame of the largest tip deflection */
    double peak;
};

crane_anim *crane_anim_open(const char *dir, const char *scene_name, double step, double scale,
                            char *msg, size_t size)
{
    crane_anim *a = calloc(1, sizeof *a);
    char path[4200];
    if (!a) {
        snprintf(msg, size, "out of memory");
        return NULL;
    }
    snprintf(a->dir, sizeof a->dir, "%s", dir);
    snprintf(a->scene, sizeof a->scene, "%s", scene_name ? scene_name : "?");
    a->step = step;
    a->scale = scale;
    a->peak = -1;
    for (int i = 0; i < 2; i++)
        a->lo[i] = INFINITY, a->hi[i] = -INFINITY;
    snprintf(path, sizeof path, "%s/anim.dat", dir);
    a->dat = fopen(path, "w");
    if (a->dat) {
        snprintf(path, sizeof path, "%s/anim_track.dat", dir);
        a->track = fopen(path, "w");
    }
    if (!a->dat || !a->track) {
        snprintf(msg, size, "cannot write %s: %s", path, strerror(errno));
        if (a->dat) fclose(a->dat);
        free(a);
        return NULL;
    }
    fprintf(a->dat,
            "# crane scene %s: animation frames (crane_anim.h), one data set per frame;\n"
            "# columns: u (side view: along the platform's x axis from A) [m], z [m], x [m], "
            "y [m], part\n"
            "# parts: 0 platform, 1 boom (deflection x%g), 2 boom (true), 3 load, "
            "4 counterweight, 5 ties, 6 rope\n",
            a->scene, scale);
    fprintf(a->track, "# t [s], load x [m], load y [m], tip x [m], tip y [m]\n");
    return a;
}

/* One point of the frame: side view (u along the platform's x axis from A, z), top view (x, y). */
static void put(crane_anim *a, const crane_geom *g, const double *p, int part)
{
    double c = cos(g->theta), s = sin(g->theta);
    double u = c * (p[0] - g->joint_A[0]) + s * (p[1] - g->joint_A[1]);
    const double v[2] = {u, p[2]}, r = hypot(p[0] - g->joint_A[0], p[1] - g->joint_A[1]);
    for (int i = 0; i < 2; i++)
        if (isfinite(v[i])) a->lo[i] = fmin(a->lo[i], v[i]), a->hi[i] = fmax(a->hi[i], v[i]);
    if (isfinite(r)) a->reach = fmax(a->reach, r);
    fprintf(a->dat, "%.6g %.6g %.6g %.6g %d\n", u, p[2], p[0], p[1], part);
}

static void segment(crane_anim *a, const crane_geom *g, const double *p, const double *q, int part)
{
    put(a, g, p, part);
    put(a, g, q, part);
    fputc('\n', a->dat);
}

int crane_anim_frame(crane_anim *a, const crane_geom *g, char *msg, size_t size)
{
    if (!a || !g || a->bad) return -1;
    if (a->frames == a->cap) {
        int cap = a->cap ? 2 * a->cap : 256;
        double *t = realloc(a->times, (size_t)cap * sizeof *t);
        if (!t) {
            snprintf(msg, size, "out of memory");
            return a->bad = -1;
        }
        a->times = t;
        a->cap = cap;
    }
    a->times[a->frames] = g->t;
    memcpy(a->A, g->joint_A, sizeof a->A);
    fprintf(a->dat, "%s# frame %d, t = %.10g s\n", a->frames ? "\n\n" : "", a->frames, g->t);
    /* the platform: deck outline, gantry masts and bar */
    for (int k = 0; k <= 4; k++)
        put(a, g, g->deck[k % 4], A_PLATFORM);
    fputc('\n', a->dat);
    for (int k = 0; k < g->ngantry; k++)
        segment(a, g, g->gantry_base[k], g->gantry[k], A_PLATFORM);
    if (g->ngantry == 2) segment(a, g, g->gantry[0], g->gantry[1], A_PLATFORM);
    /* the boom, magnified (the start position carried round plus scale times the deflection),
     * and true */
    for (int k = 0; k < g->nodes; k++) {
        double p[3];
        for (int i = 0; i < 3; i++)
            p[i] = g->node[k][i] + (a->scale - 1) * g->defl[k][i];
        put(a, g, p, A_BOOM);
    }
    fputc('\n', a->dat);
    for (int k = 0; k < g->nodes; k++)
        put(a, g, g->node[k], A_BOOM_TRUE);
    fputc('\n', a->dat);
    const double *tip = g->node[g->nodes - 1];
    for (int k = 0; k < g->nties; k++)
        segment(a, g, g->ngantry == 2 ? g->gantry[k] : g->gantry[0], tip, A_TIE);
    if (g->rope) {
        segment(a, g, tip, g->load, A_ROPE);
        put(a, g, g->load, A_LOAD);
        fputc('\n', a->dat);
    }
    if (g->counterweight) {
        put(a, g, g->cw, A_CW);
        fputc('\n', a->dat);
    }
    fprintf(a->track, "%.10g %.6g %.6g %.6g %.6g\n", g->t, g->rope ? g->load[0] : NAN,
            g->rope ? g->load[1] : NAN, tip[0], tip[1]);
    double d = hypot(g->defl_luff[g->nodes - 1], g->defl_side[g->nodes - 1]);
    if (d > a->peak) a->peak = d, a->peak_frame = a->frames;
    a->frames++;
    if (ferror(a->dat) || ferror(a->track)) {
        snprintf(msg, size, "writing %s/anim.dat failed", a->dir);
        return a->bad = -1;
    }
    return 0;
}

/* The range [lo, hi] widened by a margin, at least 10 m wide. */
static void range(FILE *f, const char *axis, double lo, double hi)
{
    if (!(lo <= hi)) lo = -1, hi = 1;
    double m = 0.05 * (hi - lo) + 2, mid = 0.5 * (lo + hi);
    lo -= m, hi += m;
    if (hi - lo < 10) lo = mid - 5, hi = mid + 5;
    fprintf(f, "set %srange [%.4g:%.4g]\n", axis, lo, hi);
}

/* The drawing of frame i (gnuplot variable i, 0-based): the side view on the left, the top
 * view (a square round the axis) with the key on the right, the time in the top left corner. */
static void frame_body(FILE *f, const crane_anim *a, const double *A)
{
    double R = 1.05 * a->reach + 2;
    fprintf(f,
            "  set multiplot title sprintf('crane scene %s: boom deflection x%g (thick) over its "
            "true shape (thin)')\n"
            "  set label 1 sprintf('t = %%.2f s', real(word(times, i + 1))) at screen 0.015, "
            "screen 0.96 left front\n",
            a->scene, a->scale);
    fprintf(f, "  set origin 0, 0\n  set size 0.36, 0.93\n  unset key\n"
               "  set title 'side view, turning with the platform'\n"
               "  set xlabel 'along the platform x axis from A [m]'\n  set ylabel 'z [m]'\n");
    range(f, "  x", a->lo[0], a->hi[0]);
    range(f, "  y", a->lo[1], a->hi[1]);
    fprintf(f, "  plot 'anim.dat' index i using ($5 == 1 ? $1 : NaN):2 with linespoints lw 3 "
               "pt 7 ps 0.6 lc rgb '#1f4e9c', \\\n"
               "       '' index i using (thin($5) ? $1 : NaN):2:(colour($5)) with lines lw 1 "
               "lc rgb variable, \\\n"
               "       '' index i using (mass($5) ? $1 : NaN):2:(colour($5)) with points pt 7 "
               "ps 2.5 lc rgb variable\n"
               "  unset label 1\n");
    fprintf(f,
            "  set origin 0.36, 0\n  set size 0.64, 0.93\n"
            "  set title 'top view'\n  set xlabel 'x [m]'\n  set ylabel 'y [m]'\n"
            "  set xrange [%.4g:%.4g]\n  set yrange [%.4g:%.4g]\n"
            "  set key outside right top vertical\n"
            "  plot 'anim_track.dat' every ::0::i using 2:3 with lines lw 1 lc rgb '#f0a0a0' "
            "title 'load path', \\\n"
            "       'anim.dat' index i using ($5 == 1 ? $3 : NaN):4 with linespoints lw 3 pt 7 "
            "ps 0.6 lc rgb '#1f4e9c' title 'boom x%g', \\\n"
            "       '' index i using (thin($5) ? $3 : NaN):4:(colour($5)) with lines lw 1 "
            "lc rgb variable notitle, \\\n"
            "       '' index i using (mass($5) ? $3 : NaN):4:(colour($5)) with points pt 7 "
            "ps 2.5 lc rgb variable notitle, \\\n"
            "       NaN with lines lw 1 lc rgb '#999999' title 'boom (true)', \\\n"
            "       NaN with lines lw 1 lc rgb '#000000' title 'platform', \\\n"
            "       NaN with lines lw 1 lc rgb '#8a8a00' title 'ties', \\\n"
            "       NaN with lines lw 1 lc rgb '#b05a00' title 'rope', \\\n"
            "       NaN with points pt 7 ps 2 lc rgb '#d02020' title 'load', \\\n"
            "       NaN with points pt 7 ps 2 lc rgb '#208020' title 'counterweight'\n"
            "  unset multiplot\n",
            A[0] - R, A[0] + R, A[1] - R, A[1] + R, a->scale);
}

static int write_script(crane_anim *a)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/anim.gp", a->dir);
    FILE *f = fopen(path, "w");
    if (!f) return -1;
    /* real time: the mean interval of the frames (the output step when it is the longer) */
    double dt = a->frames > 1 ? (a->times[a->frames - 1] - a->times[0]) / (a->frames - 1) : a->step;
    /* GIF's delay: hundredths of a second in 16 bits; viewers show delays below 2 slower */
    int delay = !(100 * dt < 65535) ? 65535 : !(100 * dt >= 2) ? 2 : (int)lround(100 * dt);
    fprintf(f,
            "# Animation of the crane run (crane --animate, crane/crane_anim.h) from anim.dat and\n"
            "# anim_track.dat; run in this folder: gnuplot anim.gp\n"
            "# %d frames every %g s, boom deflection x%g; global frame, Z0 up, m\n"
            "colour(p) = p == 0 ? 0x000000 : p == 2 ? 0x999999 : p == 3 ? 0xd02020 : "
            "p == 4 ? 0x208020 : p == 5 ? 0x8a8a00 : 0xb05a00\n"
            "thin(p) = p == 0 || p == 2 || p == 5 || p == 6\n"
            "mass(p) = p == 3 || p == 4\n"
            "set size ratio -1\nset grid\n",
            a->frames, a->step, a->scale);
    fprintf(f, "times = \"");
    for (int k = 0; k < a->frames; k++)
        fprintf(f, "%s%.6g", k ? " " : "", a->times[k]);
    fprintf(f,
            "\"\n\nset terminal gif animate delay %d size 1000,560 noenhanced\n"
            "set output 'crane.gif'\ndo for [i = 0:%d] {\n",
            delay, a->frames - 1);
    frame_body(f, a, a->A);
    fprintf(f,
            "}\nunset output\n\n# the frame of the largest tip deflection as a still\n"
            "set terminal png size 1000,560 noenhanced\nset output 'crane_frame.png'\n"
            "i = %d\n",
            a->peak_frame);
    frame_body(f, a, a->A);
    fprintf(f, "unset output\n");
    int bad = ferror(f);
    return fclose(f) != 0 || bad ? -1 : 0;
}

/* gnuplot anim.gp in the folder, its messages into anim.log (pu_gnuplot.h); crane.gif and
 * crane_frame.png checked whole. 0, or -1 with the reason in msg (the pictures removed). */
static int render_gif(const crane_anim *a, const char *exe, const volatile sig_atomic_t *stop,
                      char *msg, size_t size)
{
    char gif[4200], png[4200], why[512], first[256];
    pu_gnuplot_job job = {exe, a->dir, "anim.gp", NULL, "anim.log", stop};
    int st = pu_gnuplot_run(&job, why, sizeof why);
    snprintf(gif, sizeof gif, "%s/crane.gif", a->dir);
    snprintf(png, sizeof png, "%s/crane_frame.png", a->dir);
    int gif_ok = pu_gif_whole(gif), png_ok = pu_png_whole(png);
    if (st != -1 && WIFEXITED(st) && WEXITSTATUS(st) == 0 && gif_ok && png_ok) {
        char log[4200];
        snprintf(log, sizeof log, "%s/anim.log", a->dir);
        remove(log); /* gnuplot's count of the frames */
        return 0;
    }
    pu_gnuplot_log_first(a->dir, "anim.log", 0, first, sizeof first);
    const char *sep = first[0] ? ": " : "";
    if (st == -1)
        snprintf(msg, size, "gnuplot on the animation: %s", why);
    else if (stop && *stop)
        snprintf(msg, size, "a signal stopped gnuplot on the animation");
    else if (!WIFEXITED(st))
        snprintf(msg, size, "gnuplot on the animation ended by signal %d%s%s (see %s/anim.log)",
                 WTERMSIG(st), sep, first, a->dir);
    else if (WEXITSTATUS(st) != 0)
        snprintf(msg, size, "gnuplot on the animation exited with %d%s%s (see %s/anim.log)",
                 WEXITSTATUS(st), sep, first, a->dir);
    else /* gnuplot says nothing when its output cannot be written (a full disk) */
        snprintf(msg, size, "gnuplot on the animation exited with 0 but %s not written whole%s%s",
                 !gif_ok ? "crane.gif was" : "crane_frame.png was", sep, first);
    remove(gif); /* no partial picture behind: a GIF cut by a full disk would keep it full */
    remove(png);
    return -1;
}

int crane_anim_close(crane_anim **ap, int render, int quiet, const volatile sig_atomic_t *stop,
                     char *msg, size_t size)
{
    if (!ap || !*ap) return 0;
    crane_anim *a = *ap;
    int n = a->bad ? -1 : a->frames;
    if (a->bad) snprintf(msg, size, "writing %s/anim.dat failed", a->dir);
    int e1 = fclose(a->dat) != 0 ? errno : 0, e2 = fclose(a->track) != 0 ? errno : 0;
    if (n >= 0 && (e1 || e2)) {
        snprintf(msg, size, "cannot write %s/%s: %s", a->dir, e1 ? "anim.dat" : "anim_track.dat",
                 strerror(e1 ? e1 : e2));
        n = -1;
    }
    if (n > 0 && write_script(a) != 0) {
        snprintf(msg, size, "cannot write %s/anim.gp: %s", a->dir, strerror(errno));
        n = -1;
    }
    if (n < 0) { /* the data cut short: removed with the script, none of it kept half */
        static const char *const parts[] = {"anim.dat", "anim_track.dat", "anim.gp"};
        for (int k = 0; k < 3; k++) {
            char path[4200];
            snprintf(path, sizeof path, "%s/%s", a->dir, parts[k]);
            remove(path);
        }
    }
    if (n > 0 && render) {
        char exe[4200];
        if (!pu_gnuplot_find(exe, sizeof exe)) {
            if (!quiet) printf("gnuplot not found: animation skipped (anim.gp written)\n");
        } else if (render_gif(a, exe, stop, msg, size) != 0) {
            n = -1;
        } else if (!quiet) {
            printf("crane: animation %s/crane.gif, %d frames every %g s, boom deflection x%g\n",
                   a->dir, a->frames, a->step, a->scale);
        }
    }
    free(a->times);
    free(a);
    *ap = NULL;
    return n;
}
