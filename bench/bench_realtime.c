/* The crane's real-time check (bench_realtime.h). */
#include "bench_realtime.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bench_crane.h"
#include "bench_util.h"
#include "crane_setup.h"

/* the window after a corner of the reference counted as its transient */
#define CORNER_WINDOW 0.25

typedef struct rt_run {
    int status, n;
    double setup_wall, setup_cpu, int_wall, int_cpu, res_s, jac_s, lin_s, theta, maxrss_mb, hwm_mb;
    double out_s; /* the output rows' own work (crane_outputs), wall */
    long steps, rejected, newton, jac, corners;
    char msg[512];
} rt_run;

/* Peak resident memory of this process (Linux: ru_maxrss in kilobytes; it includes the resident
 * size of the process this one was forked from, kept across execve). */
static long peak_kb(void)
{
    struct rusage ru;
    memset(&ru, 0, sizeof ru);
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss;
}

/* Peak resident memory of this program image (VmHWM of /proc/self/status, kilobytes), -1 if
 * unknown. */
static long hwm_kb(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    if (!f) return -1;
    char line[256];
    long kb = -1;
    while (fgets(line, sizeof line, f))
        if (!strncmp(line, "VmHWM:", 6)) kb = strtol(line + 6, NULL, 10);
    fclose(f);
    return kb;
}

/* The residual's and Jacobian's timing wrappers (bench_prof_wrap) with the problem's regimes
 * callback timed as well: it evaluates the model (the switching elements' states at a state
 * the integrator gives), work of the problem as the residual's is, and is counted with it. pw
 * first: the callbacks' user pointer is &pw, the record's address. */
typedef struct rt_prof {
    bench_prof pw;
    double t_reg;
} rt_prof;

static int rt_regimes(void *u, double t, const double *y, int *r)
{
    rt_prof *p = u;
    double t0 = bench_wall_now();
    int k = p->pw.in->regimes(p->pw.in->user, t, y, r);
    p->t_reg += bench_wall_now() - t0;
    return k;
}

/* One run of scene s in this process: set-up, then the integration to t_end with the outputs
 * computed at every output step. 0, or -1 with o->msg. */
static int rt_measure(const crane_scene *s0, rt_run *o)
{
    crane_scene s = *s0;
    memset(o, 0, sizeof *o);
    o->status = -1;
    o->theta = NAN;
    double w0 = bench_wall_now(), c0 = bench_cpu_now();
    bench_case bc;
    int r = bench_crane_case(&bc, &s, s.static_start, s.t_end, "crane", o->msg, sizeof o->msg);
    if (r == 0) r = bench_case_start(&bc, s.rtol, o->msg, sizeof o->msg);
    if (r != 0) {
        o->status = r;
        if (r != BG_OK) bench_case_free(&bc);
        return -1;
    }
    double w1 = bench_wall_now(), c1 = bench_cpu_now();
    rt_prof rp = {.t_reg = 0};
    dae_problem dp;
    bench_prof_wrap(&rp.pw, &bc.dp, &dp);
    if (dp.regimes) dp.regimes = rt_regimes;
    dae_options opt; /* as the crane program; the case's breakpoints (inside (0, t_end)) */
    crane_solver_setup(&s, NULL, &opt, NULL, NULL);
    opt.breakpoints = bc.breakpoints;
    opt.nbreakpoints = bc.nbreakpoints;
    opt.max_steps = 10000000;
    double *y = malloc((size_t)bc.n * sizeof *y), *yp = malloc((size_t)bc.n * sizeof *yp);
    bg_error err = {0};
    dae_solver *sv = y && yp ? dae_create(&dp, &opt, &err) : NULL;
    r = sv ? dae_init(sv, 0.0, bc.ys, bc.yps) : BG_ERR_MEMORY;
    /* the rows interpolate the unknowns the outputs read, as the crane program's */
    int ounk[CRANE_MAX_OUTPUT_UNKNOWNS];
    if (r == BG_OK) r = dae_set_output_unknowns(sv, ounk, crane_output_unknowns(bc.ext, ounk));
    double out[CRANE_NOUT], t = 0;
    long nout = (long)ceil(s.t_end / s.output_step - 1e-9), last = 0;
    if (nout < 1) nout = 1;
    const dae_stats *st = sv ? dae_get_stats(sv) : NULL;
    for (long k = 1; k <= nout && r >= 0; k++) {
        double tout = k == nout ? s.t_end : (double)k * s.output_step;
        if (tout > s.t_end) tout = s.t_end;
        r = dae_solve_to(sv, tout, &t, y, yp);
        if (r < 0) break;
        r = 0;
        double wo = bench_wall_now();
        crane_outputs(bc.ext, t, y, yp, out);
        o->out_s += bench_wall_now() - wo;
        o->theta = out[1];
        /* the steps of this output interval, counted at a corner's transient if the interval
         * ends within the window after one */
        int corner = t <= CORNER_WINDOW;
        for (int b = 0; b < bc.nbreakpoints; b++)
            corner |= t > bc.breakpoints[b] && t <= bc.breakpoints[b] + CORNER_WINDOW;
        if (corner) o->corners += st->steps - last;
        last = st->steps;
    }
    double w2 = bench_wall_now(), c2 = bench_cpu_now();
    if (r < 0 || !sv)
        snprintf(o->msg, sizeof o->msg, "run failed at t = %g: %.400s", t,
                 sv ? dae_get_error(sv)->message : err.message);
    o->status = r < 0 ? r : sv ? 0 : -1;
    o->n = bc.n;
    o->setup_wall = w1 - w0;
    o->setup_cpu = c1 - c0;
    o->int_wall = w2 - w1;
    o->int_cpu = c2 - c1;
    if (st) {
        o->steps = st->steps;
        o->rejected = st->rejected_error;
        o->newton = st->newton_iters;
        o->jac = st->jac_evals;
        o->lin_s = st->t_linalg;
    }
    o->res_s = rp.pw.t_res + rp.t_reg;
    o->jac_s = rp.pw.t_jac;
    dae_free(&sv);
    free(y);
    free(yp);
    bench_case_free(&bc);
    return o->status == 0 ? 0 : -1;
}

int bench_crane_realtime_child(const crane_scene *s)
{
    rt_run o;
    int r = rt_measure(s, &o);
    if (r != 0)
        printf("status %d %s\n", o.status ? o.status : -1, o.msg);
    else
        printf("status 0 setup_wall %.6f setup_cpu %.6f int_wall %.6f int_cpu %.6f steps %ld "
               "rejected %ld newton %ld jac %ld res_s %.6f jac_s %.6f lin_s %.6f theta %.9g n %d "
               "corners %ld maxrss_kb %ld hwm_kb %ld out_s %.6f\n",
               o.setup_wall, o.setup_cpu, o.int_wall, o.int_cpu, o.steps, o.rejected, o.newton,
               o.jac, o.res_s, o.jac_s, o.lin_s, o.theta, o.n, o.corners, peak_kb(), hwm_kb(),
               o.out_s);
    fflush(stdout);
    return r != 0;
}

/* Runs one child; 0 if it completed. */
static int rt_child(const char *exe, const char *scene_file, rt_run *o)
{
    memset(o, 0, sizeof *o);
    o->status = -1;
    int fd[2];
    if (pipe(fd) != 0) {
        snprintf(o->msg, sizeof o->msg, "pipe: %s", strerror(errno));
        return -1;
    }
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) {
        snprintf(o->msg, sizeof o->msg, "fork: %s", strerror(errno));
        close(fd[0]);
        close(fd[1]);
        return -1;
    }
    if (pid == 0) {
        close(fd[0]);
        if (dup2(fd[1], STDOUT_FILENO) < 0) _exit(127);
        close(fd[1]);
        if (scene_file)
            execl(exe, exe, "--realtime-child", "--crane-scene", scene_file, (char *)NULL);
        else
            execl(exe, exe, "--realtime-child", (char *)NULL);
        _exit(127);
    }
    close(fd[1]);
    char buf[2048];
    size_t len = 0;
    ssize_t k;
    while (len + 1 < sizeof buf && (k = read(fd[0], buf + len, sizeof buf - 1 - len)) != 0) {
        if (k < 0) {
            if (errno == EINTR) continue;
            break;
        }
        len += (size_t)k;
    }
    buf[len] = '\0';
    close(fd[0]);
    int wst = 0;
    while (waitpid(pid, &wst, 0) < 0 && errno == EINTR)
        ;
    char *nl = strchr(buf, '\n');
    if (nl) *nl = '\0';
    long kb = 0, hwm = -1;
    int got = sscanf(buf,
                     "status %d setup_wall %lf setup_cpu %lf int_wall %lf int_cpu %lf steps %ld "
                     "rejected %ld newton %ld jac %ld res_s %lf jac_s %lf lin_s %lf theta %lf n %d "
                     "corners %ld maxrss_kb %ld hwm_kb %ld out_s %lf",
                     &o->status, &o->setup_wall, &o->setup_cpu, &o->int_wall, &o->int_cpu,
                     &o->steps, &o->rejected, &o->newton, &o->jac, &o->res_s, &o->jac_s, &o->lin_s,
                     &o->theta, &o->n, &o->corners, &kb, &hwm, &o->out_s);
    o->maxrss_mb = (double)kb / 1024.0;
    o->hwm_mb = hwm >= 0 ? (double)hwm / 1024.0 : NAN;
    if (got != 18 || !WIFEXITED(wst) || WEXITSTATUS(wst) != 0) {
        snprintf(o->msg, sizeof o->msg, "%.400s (exit status %d)", len ? buf : "no output",
                 WIFEXITED(wst) ? WEXITSTATUS(wst) : -1);
        if (o->status == 0) o->status = -1;
        return -1;
    }
    return 0;
}

static void csv_row(FILE *f, const char *cas, const char *scene, int elements, double t_end,
                    const char *run, const rt_run *o)
{
    if (!f) return;
    double other = o->int_wall - o->res_s - o->jac_s - o->lin_s;
    fprintf(f,
            "%s,%s,%d,%g,%s,%d,%d,%.4f,%.4f,%.4f,%ld,%ld,%ld,%ld,%ld,%.4f,%.4f,%.4f,%.4f,%.6g,"
            "%.4g,%.4g,%.4g,%.2f,%.2f,%.9g,\"%s\"\n",
            cas, scene, elements, t_end, run, o->status, o->n, o->setup_wall, o->int_wall,
            o->int_cpu, o->steps, o->corners, o->rejected, o->newton, o->jac, o->res_s, o->jac_s,
            o->lin_s, other, o->steps > 0 ? o->int_cpu / (double)o->steps : 0,
            o->int_cpu > 0 ? t_end / o->int_cpu : 0, o->int_wall > 0 ? t_end / o->int_wall : 0,
            o->int_wall + o->setup_wall > 0 ? t_end / (o->int_wall + o->setup_wall) : 0,
            o->maxrss_mb, o->hwm_mb, o->theta, o->status == 0 ? "" : o->msg);
}

/* Medians of the completed runs of one scene into res and a median row into mo. */
static void medians(const rt_run *runs, int K, bench_rt_result *res, rt_run *mo, double t_end)
{
    double *v = calloc((size_t)(K > 0 ? K : 1), sizeof *v);
    int m = 0;
    if (!v) return;
    memset(mo, 0, sizeof *mo);
#define MED(field, dst)                                                                            \
    do {                                                                                           \
        m = 0;                                                                                     \
        for (int k = 0; k < K; k++)                                                                \
            if (runs[k].status == 0) v[m++] = runs[k].field;                                       \
        dst = bench_median(v, m);                                                                  \
    } while (0)
    MED(int_wall, mo->int_wall);
    MED(int_cpu, mo->int_cpu);
    MED(setup_wall, mo->setup_wall);
    MED(setup_cpu, mo->setup_cpu);
#undef MED
    res->runs = m;
    res->wall_int = mo->int_wall;
    res->cpu_int = mo->int_cpu;
    res->rt_factor = t_end / mo->int_wall;
    res->rt_factor_cpu = t_end / mo->int_cpu;
    res->rt_factor_all = t_end / (mo->int_wall + mo->setup_wall);
    m = 0;
    for (int k = 0; k < K; k++)
        if (runs[k].status == 0)
            v[m++] = (runs[k].int_wall - runs[k].res_s - runs[k].jac_s - runs[k].lin_s -
                      runs[k].out_s) /
                     runs[k].int_wall;
    res->bookkeeping = bench_median(v, m);
    double best = INFINITY;
    res->peak_mb = 0;
    for (int k = 0; k < K; k++) {
        const rt_run *o = &runs[k];
        if (o->status != 0) continue;
        res->peak_mb = fmax(res->peak_mb, o->maxrss_mb);
        mo->maxrss_mb = res->peak_mb;
        mo->hwm_mb = fmax(mo->hwm_mb, o->hwm_mb);
        res->steps = mo->steps = o->steps;
        res->newton = mo->newton = o->newton;
        res->jac = mo->jac = o->jac;
        res->steps_corners = mo->corners = o->corners;
        res->n = mo->n = o->n;
        mo->rejected = o->rejected;
        mo->theta = o->theta;
        if (fabs(o->int_wall - res->wall_int) < best) { /* the parts of the median run */
            best = fabs(o->int_wall - res->wall_int);
            res->res_s_med = mo->res_s = o->res_s;
            res->jac_s_med = mo->jac_s = o->jac_s;
            res->lin_s_med = mo->lin_s = o->lin_s;
            res->out_s_med = mo->out_s = o->out_s;
        }
    }
    free(v);
}

static void scene_report(FILE *rep, const bench_rt_scene *sc, const bench_rt_result *r, int K)
{
    const crane_scene *s = &sc->s;
    fprintf(rep,
            "### %s\n\n%d boom elements, %d unknowns, %g s at rtol %g, atol %g, the stability "
            "guard %s; %d of %d runs completed.\n\n",
            sc->label, s->boom_elements, r->n, s->t_end, s->rtol, s->atol,
            s->stability_guard ? "on" : "off", r->runs, K);
    if (r->runs == 0) return;
    char verdict[96] = "";
    if (sc->target > 0)
        snprintf(verdict, sizeof verdict, ">= %g: %s", sc->target,
                 r->rt_factor_cpu >= sc->target ? "met" : "MISSED");
    char sv[64] = "";
    if (sc->max_steps > 0)
        snprintf(sv, sizeof sv, "<= %ld: %s", sc->max_steps,
                 r->steps <= sc->max_steps ? "met" : "MISSED");
    double w = r->wall_int;
    fprintf(rep,
            "| quantity | median | target |\n|---|---|---|\n"
            "| integration CPU time | %.3f s | |\n"
            "| real-time factor, simulated / CPU time of the integration | %.2f | %s |\n"
            "| the same on wall time (%.3f s; other work on the shared machine counts) | %.2f | "
            "|\n"
            "| real-time factor including set-up (build, static start, consistent values) | "
            "%.2f | |\n"
            "| steps | %ld (%.3g ms CPU per step) | %s |\n"
            "| steps within %g s after the reference's corners | %ld (%.0f %%) | |\n"
            "| Newton iterations, Jacobians | %ld, %ld | |\n"
            "| residual (with the regimes callback), Jacobian, linear algebra, output rows "
            "(crane_outputs), the rest (the integrator's bookkeeping; wall) | %.0f, %.0f, %.0f, "
            "%.0f, %.0f %% | |\n"
            "| peak resident memory | %.1f MB | |\n\n",
            r->cpu_int, r->rt_factor_cpu, verdict, w, r->rt_factor, r->rt_factor_all, r->steps,
            r->steps ? 1e3 * r->cpu_int / (double)r->steps : 0, sv, CORNER_WINDOW,
            r->steps_corners, r->steps ? 100.0 * (double)r->steps_corners / (double)r->steps : 0,
            r->newton, r->jac, 100 * r->res_s_med / w, 100 * r->jac_s_med / w,
            100 * r->lin_s_med / w, 100 * r->out_s_med / w,
            100 * (w - r->res_s_med - r->jac_s_med - r->lin_s_med - r->out_s_med) / w,
            r->peak_mb);
    if (sc->target > 0 && r->rt_factor_cpu < sc->target && r->steps > 0) {
        double budget = s->t_end / sc->target, per = r->cpu_int / (double)r->steps;
        fprintf(rep,
                "Missed by a factor %.1f: %.0f times real time leaves %.3g s of CPU for the %g s; "
                "at the measured %.3g ms per step that is %.0f steps (the run took %ld, %ld of "
                "them in the %g s after the %s corners of the reference), or at the measured "
                "step count %.3g ms per step.\n\n",
                sc->target / r->rt_factor_cpu, sc->target, budget, s->t_end, 1e3 * per,
                budget / per, r->steps, r->steps_corners, CORNER_WINDOW,
                "start and the", 1e3 * budget / (double)r->steps);
    }
}

int bench_crane_realtime(const char *exe, const bench_rt_scene *sc, int nsc, int K, const int *elems,
                         int nel, double mesh_t_end, const char *dir, FILE *rep,
                         bench_rt_result *res, bench_mesh_result *mesh)
{
    memset(mesh, 0, sizeof *mesh);
    mesh->slope_el = mesh->slope_n = mesh->steps_spread = NAN;
    bench_file bf;
    FILE *f = bench_file_open(&bf, dir, "realtime.csv") == 0 ? bf.f : NULL;
    if (f)
        fprintf(f, "case,scene,elements,t_end,run,status,unknowns,setup_wall_s,int_wall_s,"
                   "int_cpu_s,steps,steps_at_corners,rejected,newton,jacobians,res_s,jac_s,"
                   "linalg_s,other_s,cpu_per_step_s,realtime_factor_cpu,realtime_factor_wall,"
                   "realtime_factor_with_setup,peak_rss_mb,vm_hwm_mb,theta_end,message\n");
    rt_run *runs = calloc((size_t)(K > 0 ? K : 1), sizeof *runs);
    int fails = 0;
    fprintf(rep, "## Crane real-time check\n\n");
    fprintf(rep,
            "Each scene over its full horizon, %d runs, each in a fresh process: set-up and "
            "integration timed apart, output at the scene's output step computed (not written), "
            "bgdae-klu as the crane program runs it (exclude_alg, the reference's breakpoints, "
            "the scene's stability guard); medians (realtime.csv has every run). The real-time "
            "factor is the simulated time over the CPU time of the integration; the steps "
            "within %g s after t = 0 and after each corner of the reference are the drive's "
            "transients.\n\n",
            K, CORNER_WINDOW);
    for (int i = 0; i < nsc && runs; i++) {
        const crane_scene *s = &sc[i].s;
        memset(&res[i], 0, sizeof res[i]);
        for (int k = 0; k < K; k++) {
            rt_run *o = &runs[k];
            int r = rt_child(exe, sc[i].file, o);
            char run[16];
            snprintf(run, sizeof run, "%d", k + 1);
            csv_row(f, "scene", sc[i].label, s->boom_elements, s->t_end, run, o);
            fprintf(stderr,
                    "crane real time, %s, run %d/%d: %s, %ld steps, integration %.2f s CPU "
                    "(%.2fx real time), %.2f s wall, set-up %.2f s\n",
                    sc[i].label, k + 1, K, r == 0 ? "ok" : o->msg, o->steps, o->int_cpu,
                    o->int_cpu > 0 ? s->t_end / o->int_cpu : 0, o->int_wall, o->setup_wall);
            if (r != 0) fails++;
        }
        rt_run mo;
        medians(runs, K, &res[i], &mo, s->t_end);
        if (res[i].runs > 0) csv_row(f, "scene", sc[i].label, s->boom_elements, s->t_end, "median", &mo);
        scene_report(rep, &sc[i], &res[i], K);
    }
    /* the mesh series */
    double xe[BENCH_MESH_MAX], xn[BENCH_MESH_MAX], yt[BENCH_MESH_MAX];
    long smin = 0, smax = 0;
    for (int e = 0; e < nel && e < BENCH_MESH_MAX && nsc > 0; e++) {
        crane_scene s = sc[0].s;
        s.boom_elements = elems[e];
        s.t_end = mesh_t_end;
        if (s.output_step > mesh_t_end) s.output_step = mesh_t_end;
        rt_run o;
        int r = rt_measure(&s, &o);
        csv_row(f, "mesh", sc[0].label, elems[e], mesh_t_end, "1", &o);
        fprintf(stderr, "crane mesh series: %3d elements, %5d unknowns: %s, %ld steps, %.3g ms CPU per step\n",
                elems[e], o.n, r == 0 ? "ok" : o.msg, o.steps,
                o.steps ? 1e3 * o.int_cpu / (double)o.steps : 0);
        if (r != 0 || o.steps <= 0) {
            fails++;
            continue;
        }
        int k = mesh->n++;
        mesh->elements[k] = elems[e];
        mesh->unknowns[k] = o.n;
        mesh->steps[k] = o.steps;
        mesh->cpu_per_step[k] = o.int_cpu / (double)o.steps;
        xe[k] = elems[e];
        xn[k] = o.n;
        yt[k] = mesh->cpu_per_step[k];
        smin = k == 0 ? o.steps : (o.steps < smin ? o.steps : smin);
        smax = k == 0 ? o.steps : (o.steps > smax ? o.steps : smax);
    }
    if (mesh->n > 0) {
        mesh->slope_el = bench_loglog_slope(xe, yt, mesh->n);
        mesh->slope_n = bench_loglog_slope(xn, yt, mesh->n);
        mesh->steps_spread = (double)smax / (double)smin;
        fprintf(rep,
                "### Mesh series\n\nScene %s over [0, %g] s with the boom in 8 .. 512 elements, "
                "one run each in this process (realtime.csv, case mesh).\n\n"
                "| elements | unknowns | steps | CPU per step |\n|---|---|---|---|\n",
                sc[0].label, mesh_t_end);
        for (int k = 0; k < mesh->n; k++)
            fprintf(rep, "| %d | %d | %ld | %.3g ms |\n", mesh->elements[k], mesh->unknowns[k],
                    mesh->steps[k], 1e3 * mesh->cpu_per_step[k]);
        fprintf(rep,
                "\nLog-log slope of the CPU time per step: %.3f against the elements (target <= "
                "1.1: %s), %.3f against the unknowns. Steps from %ld to %ld, largest / smallest "
                "%.2f (target <= 1.3, the steps independent of the mesh within 30 %%: %s).\n\n",
                mesh->slope_el, mesh->slope_el <= 1.1 ? "met" : "MISSED", mesh->slope_n, smin,
                smax, mesh->steps_spread, mesh->steps_spread <= 1.3 ? "met" : "MISSED");
        int last = mesh->n - 1;
        if (mesh->steps_spread > 1.3 && mesh->steps[last] < mesh->steps[0])
            fprintf(rep,
                    "The steps fall as the mesh is refined. The solver's error norm is a root mean "
                    "square over the unknowns: where the error lies in a few unknowns of a fixed "
                    "number (the drive's, at the corners of the reference), %d unknowns instead "
                    "of %d dilute it by sqrt(%d / %d) = %.2f, as a tolerance that many times "
                    "looser would (docs/crane.md measures it so).\n\n",
                    mesh->unknowns[last], mesh->unknowns[0], mesh->unknowns[last],
                    mesh->unknowns[0], sqrt((double)mesh->unknowns[last] / mesh->unknowns[0]));
    }
    if (fails) fprintf(rep, "%d runs failed (see realtime.csv).\n\n", fails);
    if (f) bench_file_close(&bf);
    free(runs);
    return fails;
}
