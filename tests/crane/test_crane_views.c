/* The crane program's analyses and views against misuse and faults (issue 36): each case run as
 * a user would, the exit status, the message and the files asserted.
 *   - frames: --vtk-step and --anim-step below the times' rounding (1e-320: t / DT overflows)
 *     make a frame of every output row (the rows counted in results.csv);
 *   - combinations: the options of the dynamic run (--vtk, --vtk-step, --animate, --anim-step,
 *     --anim-scale, --error-estimate) refused with --static and --modes by one rule, nothing
 *     written; --modes T beyond t_end refused at once;
 *   - the animation: gnuplot failing on it, or leaving a GIF cut short with exit 0, fails the run
 *     (exit 1, status failed with the reason itself, no crane.gif), said with --quiet too; a
 *     signal while gnuplot draws it stops gnuplot and the program within the bound; a view
 *     that cannot start (vtk/ a file) fails the run with its reason in status.txt; a signal
 *     while --modes T runs to T ends the program at once (interrupted);
 *   - a full disk (a small tmpfs, when this test may mount one) during --vtk and --animate: the
 *     final status written (failed, naming the file and the system's error), no partial picture;
 *   - messages: a loop of symbolic links as the scene, the static start's keys (the ground's
 *     height [platform] joint_A, a rope too thin [rope] A);
 *   - a load without weight on the rope (g = 0 or 1e-300 kg): the static start stands, the
 *     crane as without the rope, the load at rest on it, floating through a run with g = 0;
 *   - drift modes: the modes at t = 12.5 s of the paper scene list as their slowest elastic mode
 *     the drive's PID mode of the static start (the same physics at any T), the drift modes of the
 *     constraints' invariants apart (kind "drift").
 *
 *   test_crane_views CRANE_EXECUTABLE SCENES_DIR */
#include "crane_spawn.h"
#include "tap.h"

#include <sys/mount.h>

static double g_bound = 2.0; /* seconds from a signal to the end of the program */

/* Lines of DIR/name that contain want. */
static int count_lines(const char *dir, const char *name, const char *want)
{
    char p[8192], line[8192];
    path2(p, sizeof p, dir, name);
    FILE *f = fopen(p, "r");
    if (!f) return -1;
    int n = 0;
    while (fgets(line, sizeof line, f))
        n += strstr(line, want) != NULL;
    fclose(f);
    return n;
}


/* ------------------------------------------------------------------ frames ---- */

static void test_frames(void)
{
    char out[4200], why[256];
    double t_last;
    result r;
    /* 3 output rows (0, 0.01, 0.02 s): a frame each */
    path2(out, sizeof out, tmp, "vtk-denormal");
    run(NULL,
        (const char *[]){"rigid-boom", "--t-end", "0.02", "--output-step", "0.01", "--vtk-step",
                         "1e-320", "--no-plots", "--quiet", "--out", out, NULL},
        "vtkden", 60, &r);
    long rows = check_csv(out, 1, &t_last, why, sizeof why);
    int frames = count_lines(out, "crane.pvd", "<DataSet ");
    tap_ok(r.exited && r.code == 0 && rows == 3 && frames == 3,
           "--vtk-step 1e-320: a frame per output row (%d frames, %ld rows; exit %d %.200s)",
           frames, rows, r.code, r.err);
    path2(out, sizeof out, tmp, "anim-denormal");
    spawn_opts so = {NULL, NULL, NULL, 0};
    run_with(&so,
             (const char *[]){"rigid-boom", "--t-end", "0.02", "--output-step", "0.01",
                              "--anim-step", "1e-320", "--no-plots", "--quiet", "--out", out,
                              NULL},
             "animden", 60, &r);
    frames = count_lines(out, "anim.dat", "# frame ");
    tap_ok(r.exited && r.code == 0 && frames == 3,
           "--anim-step 1e-320: a frame per output row (%d frames; exit %d %.200s)", frames, r.code,
           r.err);
    /* a huge interval: the first row only, and a GIF delay that stays in range */
    path2(out, sizeof out, tmp, "anim-huge");
    run_with(&so,
             (const char *[]){"rigid-boom", "--t-end", "0.02", "--output-step", "0.01",
                              "--anim-step", "1e308", "--anim-scale", "1e308", "--no-plots",
                              "--quiet", "--out", out, NULL},
             "animhuge", 60, &r);
    frames = count_lines(out, "anim.dat", "# frame ");
    tap_ok(r.exited && r.code == 0 && frames == 1 &&
               file_contains(out, "anim.gp", "gif animate delay 65535 "),
           "--anim-step 1e308 --anim-scale 1e308: one frame, the GIF's delay at its 16-bit "
           "largest (%d frames; exit %d %.200s)",
           frames, r.code, r.err);
}

/* ------------------------------------------------------------ combinations ---- */

static void test_combinations(void)
{
    struct {
        const char *args[6];
        const char *want;
    } bad[] = {
        {{"--vtk", "--static", NULL}, "option --vtk belongs to the dynamic run, not to --static"},
        {{"--static", "--vtk-step", "0.1", NULL}, "option --vtk-step belongs to the dynamic run"},
        {{"--animate", "--modes", NULL}, "option --animate belongs to the dynamic run, not to "
                                         "--modes"},
        {{"--modes", "3", "--anim-step", "0.5", NULL}, "option --anim-step belongs to the"},
        {{"--anim-scale", "4", "--static", NULL}, "option --anim-scale belongs to the"},
        {{"--error-estimate", "--modes", NULL}, "option --error-estimate belongs to the dynamic "
                                                "run, not to --modes"},
        {{"--modes", "1e300", NULL}, "T must be within [0, t_end] = [0, 20] s"},
        {{"--modes", "2", "--t-end", "1", NULL}, "T must be within [0, t_end] = [0, 1] s"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char out[4200], tag[32];
        const char *args[12];
        int n = 0;
        snprintf(tag, sizeof tag, "comb%zu", i);
        path2(out, sizeof out, tmp, tag);
        for (int k = 0; bad[i].args[k]; k++)
            args[n++] = bad[i].args[k];
        args[n++] = "--out";
        args[n++] = out;
        args[n] = NULL;
        result r;
        run(NULL, args, tag, 30, &r);
        struct stat st;
        tap_ok(r.exited && r.code == 2 && strstr(r.err, bad[i].want) && stat(out, &st) != 0 &&
                   r.seconds < 10,
               "%s %s ...: exit 2 at once, nothing written (exit %d, %.1f s: %.200s)",
               bad[i].args[0], bad[i].args[1], r.code, r.seconds, r.err);
    }
}

/* ------------------------------------------------------------ the animation ---- */

static void test_animation_failures(void)
{
    char out[4200], path_env[4400];
    result r;
    spawn_opts so = {NULL, NULL, NULL, 0};
    so.path_env = fake_gnuplot("gp-anim-fails",
                               "echo 'anim.gp, line 3: unknown terminal gif' >&2; exit 1",
                               path_env, sizeof path_env);
    path2(out, sizeof out, tmp, "anim-fails");
    run_with(&so,
             (const char *[]){"rigid-boom", "--t-end", "0.2", "--animate", "--no-plots",
                              "--quiet", "--out", out, NULL},
             "animfails", 60, &r);
    tap_ok(r.exited && r.code == 1 && strstr(r.err, "gnuplot on the animation exited with 1") &&
               strstr(r.err, "unknown terminal gif") &&
               first_line_is(out, "status.txt", "status: failed") &&
               file_contains(out, "status.txt", "reason: animation: gnuplot on the animation "
                                                "exited with 1: anim.gp, line 3") &&
               !file_contains(out, "status.txt", "see above") && !file_exists(out, "crane.gif"),
           "gnuplot failing on the animation (--quiet): exit 1, said, status.txt failed with the "
           "reason itself, no crane.gif (exit %d: %.300s)",
           r.code, r.err);
    so.path_env = fake_gnuplot("gp-anim-cut", "printf 'GIF89a' > crane.gif; exit 0", path_env,
                               sizeof path_env);
    path2(out, sizeof out, tmp, "anim-cut");
    run_with(&so,
             (const char *[]){"rigid-boom", "--t-end", "0.2", "--animate", "--no-plots",
                              "--quiet", "--out", out, NULL},
             "animcut", 60, &r);
    tap_ok(r.exited && r.code == 1 && strstr(r.err, "crane.gif was not written whole") &&
               first_line_is(out, "status.txt", "status: failed") &&
               !file_exists(out, "crane.gif"),
           "a GIF cut short with gnuplot's exit 0: exit 1, status failed, the GIF removed (exit "
           "%d: %.300s)",
           r.code, r.err);
    /* a signal while gnuplot draws: gnuplot stopped, the program ends within the bound */
    so.path_env = fake_gnuplot("gp-anim-slow", "printf 'drawing' >&2; sleep 60", path_env,
                               sizeof path_env);
    path2(out, sizeof out, tmp, "anim-signal");
    pid_t pid = start_with(&so,
                           (const char *[]){"rigid-boom", "--t-end", "0.2", "--animate",
                                            "--no-plots", "--quiet", "--out", out, NULL},
                           "animsig");
    char log[4300];
    path2(log, sizeof log, out, "anim.log");
    double t0 = now_s();
    struct stat st;
    while (now_s() - t0 < 60 && !(stat(log, &st) == 0 && st.st_size > 0) &&
           waitpid(pid, NULL, WNOHANG) == 0)
        sleep_ms(10);
    kill(pid, SIGTERM);
    finish_from(pid, 30, "animsig", now_s(), &r);
    tap_ok(r.exited && r.code == 0 && r.seconds < g_bound &&
               first_line_is(out, "status.txt", "status: completed") &&
               file_contains(out, "status.txt", "the animation was not drawn") &&
               !file_exists(out, "crane.gif"),
           "SIGTERM while gnuplot draws the animation: ended in %.2f s (bound %.0f s), completed "
           "saying the animation was not drawn (exit %d: %.200s)",
           r.seconds, g_bound, r.code, r.err);
}

/* A view that cannot start (vtk/ is a file): the run fails with that reason in status.txt; a
 * signal while --modes T runs to T ends the program at once, status.txt saying so. */
static void test_view_reason_and_modes_signal(void)
{
    char out[4200], vfile[4300];
    result r;
    path2(out, sizeof out, tmp, "vtk-file");
    mkdir(out, 0777);
    path2(vfile, sizeof vfile, out, "vtk");
    FILE *f = fopen(vfile, "w");
    if (f) {
        fputs("a file where the frames' folder goes\n", f);
        fclose(f);
    }
    run(NULL,
        (const char *[]){"rigid-boom", "--t-end", "0.02", "--vtk", "--no-plots", "--quiet",
                         "--out", out, NULL},
        "vtkfile", 60, &r);
    tap_ok(r.exited && r.code == 1 && first_line_is(out, "status.txt", "status: failed") &&
               file_contains(out, "status.txt", "reason: ParaView series: ") &&
               file_contains(out, "status.txt", "not a folder") &&
               !file_contains(out, "status.txt", "see above"),
           "--vtk where vtk/ is a file: exit 1, status.txt failed with that reason (exit %d: "
           "%.200s)",
           r.code, r.err);
    path2(out, sizeof out, tmp, "modes-signal");
    pid_t pid = start(NULL,
                      (const char *[]){"paper", "--modes", "12.5", "--no-plots", "--quiet",
                                       "--out", out, NULL},
                      "modessig");
    double t0 = now_s();
    while (now_s() - t0 < 60 && !file_contains(out, "status.txt", "status: running") &&
           waitpid(pid, NULL, WNOHANG) == 0)
        sleep_ms(10);
    sleep_ms(300);
    kill(pid, SIGTERM);
    finish_from(pid, 30, "modessig", now_s(), &r);
    tap_ok(r.signaled == 0 && r.exited && r.code == 128 + SIGTERM && r.seconds < g_bound &&
               first_line_is(out, "status.txt", "status: interrupted") &&
               file_contains(out, "status.txt", "SIGTERM received while") &&
               !file_exists(out, "modes.csv"),
           "SIGTERM during --modes 12.5: exit %d in %.2f s, status.txt interrupted, no modes.csv",
           r.code, r.seconds);
}

/* ------------------------------------------------------------- a full disk ---- */

static void test_full_disk(void)
{
    char mnt[4200];
    path2(mnt, sizeof mnt, tmp, "small");
    mkdir(mnt, 0777);
    struct {
        const char *size, *view, *step, *t_end, *leftover;
    } cases[] = {{"size=256k", "--vtk", "--vtk-step", "6", "vtk/"},
                 {"size=160k", "--animate", "--anim-step", "5", "crane.gif"}};
    for (int i = 0; i < 2; i++) {
        if (mount("tmpfs", mnt, "tmpfs", 0, cases[i].size) != 0) {
            tap_ok(1, "a full disk during %s # SKIP no tmpfs can be mounted here (%s)",
                   cases[i].view, strerror(errno));
            continue;
        }
        char out[4300];
        path2(out, sizeof out, mnt, "run");
        result r;
        run(NULL,
            (const char *[]){"rigid-boom", "--t-end", cases[i].t_end, "--output-step", "0.05",
                             cases[i].step, "0.05", "--no-plots", "--quiet", "--out", out, NULL},
            "full", 120, &r);
        int partial = 0;
        if (i == 1) partial = file_exists(out, "crane.gif") && !file_nonempty(out, "crane.gif");
        tap_ok(r.exited && r.code == 1 && first_line_is(out, "status.txt", "status: failed") &&
                   !file_contains(out, "status.txt", "see above") &&
                   (file_contains(out, "status.txt", "No space left on device") ||
                    file_contains(out, "status.txt", "not written whole")) &&
                   !partial,
               "a full disk (tmpfs %s) during %s: exit 1, status.txt failed with the reason "
               "(exit %d: %.300s)",
               cases[i].size, cases[i].view, r.code, r.err);
        if (umount(mnt) != 0) tap_diag("umount %s: %s", mnt, strerror(errno));
    }
}

/* ---------------------------------------------------------------- messages ---- */

/* The row of DIR/name whose first field is key: its fields 1..3 into xyz (if not NULL) and
 * field 4 into value (if not NULL); 1 if found with those fields numbers. */
static int csv_row(const char *dir, const char *name, const char *key, double *xyz, double *value)
{
    char p[8192], line[8192];
    path2(p, sizeof p, dir, name);
    FILE *f = fopen(p, "r");
    if (!f) return 0;
    int ok = 0;
    size_t kl = strlen(key);
    while (!ok && fgets(line, sizeof line, f)) {
        if (strncmp(line, key, kl) || line[kl] != ',') continue;
        double v[4];
        char *s = line + kl + 1, *e;
        ok = 1;
        for (int k = 0; k < 4; k++) {
            v[k] = strtod(s, &e);
            int empty = e == s;
            if (empty && (xyz && k < 3)) ok = 0;
            if (empty && value && k == 3) ok = 0;
            s = strchr(e, ',');
            if (!s) {
                if (k < 3) ok = 0;
                break;
            }
            s++;
        }
        if (ok && xyz)
            for (int k = 0; k < 3; k++)
                xyz[k] = v[k];
        if (ok && value) *value = v[3];
    }
    fclose(f);
    return ok;
}

/* The smallest and largest value of the column named col of the CSV file DIR/name; the rows
 * read, or -1. */
static int csv_column_range(const char *dir, const char *name, const char *col, double *lo,
                            double *hi)
{
    char p[8192], line[65536];
    path2(p, sizeof p, dir, name);
    FILE *f = fopen(p, "r");
    if (!f) return -1;
    int idx = -1, rows = 0;
    if (fgets(line, sizeof line, f)) {
        char *s = line;
        for (int k = 0; s && idx < 0; k++) {
            size_t cl = strlen(col);
            if (!strncmp(s, col, cl) && (s[cl] == ',' || s[cl] == '\n' || s[cl] == '\r')) idx = k;
            s = strchr(s, ',');
            if (s) s++;
        }
    }
    while (idx >= 0 && fgets(line, sizeof line, f)) {
        char *s = line;
        for (int k = 0; k < idx && s; k++) {
            s = strchr(s, ',');
            if (s) s++;
        }
        if (!s) continue;
        double v = strtod(s, NULL);
        *lo = rows ? fmin(*lo, v) : v;
        *hi = rows ? fmax(*hi, v) : v;
        rows++;
    }
    fclose(f);
    return idx < 0 ? -1 : rows;
}

static void test_messages(void)
{
    char a[4200], b[4200], out[4200];
    result r;
    path2(a, sizeof a, tmp, "loop-a.ini");
    path2(b, sizeof b, tmp, "loop-b.ini");
    if (symlink(b, a) != 0 || symlink(a, b) != 0) tap_diag("symlink: %s", strerror(errno));
    path2(out, sizeof out, tmp, "loop");
    run(NULL, (const char *[]){a, "--out", out, NULL}, "loop", 30, &r);
    tap_ok(r.exited && r.code == 2 && strstr(r.err, "Too many levels of symbolic links") &&
               !strstr(r.err, "not found"),
           "a loop of symbolic links as the scene: its cause named (%.200s)", r.err);
    path2(out, sizeof out, tmp, "joint-a");
    run(NULL, (const char *[]){"--static", "--set", "platform.joint_A=5,5,5", "--out", out, NULL},
        "jointa", 60, &r);
    tap_ok(r.exited && r.code == 2 && strstr(r.err, "[platform] joint_A") &&
               (strstr(r.err, "below the ground") || strstr(r.err, "from the axis")),
           "the slewing joint moved (joint_A): the key named (%.300s)", r.err);
    path2(out, sizeof out, tmp, "rope-a");
    run(NULL, (const char *[]){"--static", "--set", "rope.A=1e-12", "--out", out, NULL}, "ropea",
        60, &r);
    tap_ok(r.exited && r.code == 2 && strstr(r.err, "the keys [rope] A") &&
               !strstr(r.err, "[rope] length") && strstr(r.err, "the rope stretches"),
           "a rope of 1e-12 m^2: [rope] A blamed, not [rope] length (%.300s)", r.err);
    /* no weight on the rope (g = 0, a 1e-300 kg load): the load carries nothing, so the crane
     * stands as it does without the rope (the boom's tip to the bit), and the load hangs at rest
     * on the rope: slack with g = 0 (the rope's force at the rounding of its force, the load within
     * 1 % of the rope's length below the tip), taut with its weight otherwise (the rope's tension
     * equal to m g) */
    const char *weightless[2] = {"environment.g=0", "load.mass=1e-300"};
    const char *bare[2] = {"environment.g=0", "environment.g=9.81"};
    for (int i = 0; i < 2; i++) {
        char out2[8192];
        path2(out, sizeof out, tmp, i ? "light-load" : "no-gravity");
        path2(out2, sizeof out2, tmp, i ? "light-load-bare" : "no-gravity-bare");
        run(NULL, (const char *[]){"--static", "--set", weightless[i], "--out", out, NULL},
            "weightless", 60, &r);
        tap_ok(r.exited && r.code == 0 && first_line_is(out, "status.txt", "status: completed"),
               "--set %s: the static start verified (exit %d: %.300s)", weightless[i], r.code,
               r.err);
        run(NULL,
            (const char *[]){"--static", "--set", bare[i], "--set", "rope.enabled=false", "--out",
                             out2, NULL},
            "weightless-bare", 60, &r);
        double tip[3], tipb[3], load[3], T = NAN, mass = NAN, L = 71.51; /* paper.ini [rope] length */
        int got = csv_row(out, "equilibrium.csv", "boom_tip", tip, NULL) &&
                  csv_row(out2, "equilibrium.csv", "boom_tip", tipb, NULL) &&
                  csv_row(out, "equilibrium.csv", "load", load, &mass) &&
                  csv_row(out, "equilibrium.csv", "rope_tension", NULL, &T);
        tap_ok(got && tip[0] == tipb[0] && tip[1] == tipb[1] && tip[2] == tipb[2],
               "--set %s: the boom's tip where the crane without the rope has it (%.17g %.17g)",
               weightless[i], got ? tip[2] : NAN, got ? tipb[2] : NAN);
        double below = got ? tip[2] - load[2] : NAN, W = i ? 1e-300 * 9.81 : 0.0;
        if (i == 0)
            tap_ok(got && T >= 0 && T <= 1e-9 && fabs(load[0] - tip[0]) < 1e-9 &&
                       fabs(load[1] - tip[1]) < 1e-9 && below <= L && below >= 0.99 * L,
                   "g = 0: the load at rest below the tip on the slack rope (%.9g m below, "
                   "rope %.4g m; tension %.3g N)",
                   below, L, T);
        else
            tap_ok(got && fabs(T - W) <= 1e-9 * W && below <= L && below >= 0.9 * L,
                   "a 1e-300 kg load: the rope's tension its weight (%.6g N against m g = %.6g N), "
                   "the load %.6g m below the tip",
                   T, W, below);
    }
    /* g = 0: the load floats where it was hung while the crane turns (no force on it): its
     * height over 2 s within the run's tolerance */
    path2(out, sizeof out, tmp, "no-gravity-run");
    run(NULL,
        (const char *[]){"--set", "environment.g=0", "--t-end", "2", "--no-plots", "--out", out,
                         NULL},
        "weightless-run", 120, &r);
    double zmin = NAN, zmax = NAN;
    int rows = csv_column_range(out, "results.csv", "load_z [m]", &zmin, &zmax);
    tap_ok(r.exited && r.code == 0 && first_line_is(out, "status.txt", "status: completed") &&
               rows > 1000 && zmax - zmin <= 1e-5,
           "g = 0: a 2 s run completed, the floating load's height constant within 1e-5 m over "
           "%d rows (range %.3g m; exit %d: %.200s)",
           rows, zmax - zmin, r.code, r.err);
    path2(out, sizeof out, tmp, "no-gravity-no-rope");
    run(NULL,
        (const char *[]){"--static", "--set", "environment.g=0", "--set", "rope.enabled=false",
                         "--out", out, NULL},
        "norope", 60, &r);
    tap_ok(r.exited && r.code == 0 && first_line_is(out, "status.txt", "status: completed"),
           "g = 0 without the rope: the unloaded crane's static start verified (exit %d: %.200s)",
           r.code, r.err);
}

/* ------------------------------------------------------------------ drift ---- */

/* The first row of modes.csv of kind (its frequency), and the rows of that kind. */
static double first_of_kind(const char *dir, const char *kind, int *count)
{
    char p[8192], line[8192], want[64];
    path2(p, sizeof p, dir, "modes.csv");
    snprintf(want, sizeof want, ",%s,", kind);
    FILE *f = fopen(p, "r");
    double fz = NAN;
    *count = 0;
    if (!f) return NAN;
    while (fgets(line, sizeof line, f)) {
        char *k = strstr(line, want);
        if (!k) continue;
        if (!*count) {
            char *c = strchr(line, ',');
            fz = c ? strtod(c + 1, NULL) : NAN;
        }
        (*count)++;
    }
    fclose(f);
    return fz;
}

static void test_drift_modes(void)
{
    char out0[4200], out[4200];
    result r0, r;
    path2(out0, sizeof out0, tmp, "modes0");
    path2(out, sizeof out, tmp, "modes12");
    run(NULL, (const char *[]){"paper", "--modes", "--no-plots", "--out", out0, NULL}, "modes0",
        300, &r0);
    run(NULL, (const char *[]){"paper", "--modes", "12.5", "--no-plots", "--out", out, NULL},
        "modes12", 300, &r);
    int n0, n, nd, nd0;
    double f0 = first_of_kind(out0, "elastic", &n0), f = first_of_kind(out, "elastic", &n);
    double fd = first_of_kind(out, "drift", &nd);
    first_of_kind(out0, "drift", &nd0);
    tap_ok(r0.code == 0 && r.code == 0 && fabs(f - f0) <= 0.05 * f0 && nd > 0 && nd0 == 0 &&
               fd < 0.1 * f0,
           "paper --modes 12.5: the slowest elastic mode %.5g Hz is the static start's %.5g Hz "
           "(the drive's PID, within 5 %%); %d drift modes from %.3g Hz apart (0 at the start)",
           f, f0, nd, fd);
    tap_ok(strstr(r.out, "drift modes below") && !strstr(r.out, "mode 1: "),
           "the summary counts the drift modes apart and lists none of them");
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        printf("1..0 # SKIP usage: test_crane_views CRANE_EXECUTABLE SCENES_DIR\n");
        return 0;
    }
    if (spawn_setup(argc, argv, "crane_views") != 0) return 1;
    tap_diag("working folder %s", tmp);
    if (getenv("ASAN_OPTIONS") || getenv("UBSAN_OPTIONS") || getenv("VALGRIND_OPTS"))
        g_bound = 10.0;

    test_frames();
    test_combinations();
    test_animation_failures();
    test_view_reason_and_modes_signal();
    test_full_disk();
    test_messages();
    test_drift_modes();

    int rc = tap_done();
    if (rc == 0) {
        char cmd[4200];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp);
        if (system(cmd) != 0) tap_diag("could not remove %s", tmp);
    }
    return rc;
}
