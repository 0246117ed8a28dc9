/* Shared by the tests of the crane program (test_crane_program.c, test_crane_robust.c): start
 * the program in a child process (arguments, folder, standard output, PATH, a file-size limit),
 * wait for it with a time limit, read its output and check its files.
 *
 * The test sets exe (the program, absolute), scenes (the scene folder, absolute) and tmp (its
 * working folder) before the first start. */
#ifndef CRANE_SPAWN_H
#define CRANE_SPAWN_H

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "crane_model.h"

static char exe[2048], scenes[2048], tmp[1024];

typedef struct result {
    int exited, code, signaled, sig, timed_out;
    double seconds; /* from the start (or from mark_time) to the end */
    char out[8192], err[8192];
} result;

/* How a child is started besides its arguments (all optional). */
typedef struct spawn_opts {
    const char *cwd;       /* folder to run in (NULL: here) */
    const char *stdout_to; /* file for the standard output (NULL: tmp/TAG.out) */
    const char *path_env;  /* PATH (NULL: unchanged) */
    long fsize_limit;      /* RLIMIT_FSIZE in bytes, with SIGXFSZ ignored (0: none) */
} spawn_opts;

static inline double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static inline void sleep_ms(int ms)
{
    struct timespec ts = {ms / 1000, (long)(ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

static inline void slurp(const char *path, char *buf, size_t size)
{
    buf[0] = '\0';
    FILE *f = fopen(path, "r");
    if (!f) return;
    size_t n = fread(buf, 1, size - 1, f);
    buf[n] = '\0';
    fclose(f);
}

/* Starts the program with args (NULL-terminated); standard input /dev/null, standard error into
 * tmp/TAG.err. */
static inline pid_t start_with(const spawn_opts *so, const char *const *args, const char *tag)
{
    char po[4200], pe[4200];
    snprintf(po, sizeof po, "%s/%s.out", tmp, tag);
    snprintf(pe, sizeof pe, "%s/%s.err", tmp, tag);
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
        const char *out = so && so->stdout_to ? so->stdout_to : po;
        int fo = open(out, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int fe = open(pe, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int fi = open("/dev/null", O_RDONLY);
        if (fo < 0 || fe < 0 || fi < 0) _exit(127);
        dup2(fi, 0);
        dup2(fo, 1);
        dup2(fe, 2);
        if (so && so->cwd && chdir(so->cwd) != 0) _exit(127);
        if (so && so->path_env) setenv("PATH", so->path_env, 1);
        if (so && so->fsize_limit > 0) {
            /* writes beyond the limit fail with EFBIG instead of killing the program */
            signal(SIGXFSZ, SIG_IGN);
            struct rlimit rl = {(rlim_t)so->fsize_limit, (rlim_t)so->fsize_limit};
            if (setrlimit(RLIMIT_FSIZE, &rl) != 0) _exit(127);
        }
        const char *argv[64];
        int n = 0;
        argv[n++] = exe;
        for (int i = 0; args[i] && n < 63; i++)
            argv[n++] = args[i];
        argv[n] = NULL;
        execv(exe, (char *const *)argv);
        _exit(127);
    }
    return pid;
}

static inline pid_t start(const char *cwd, const char *const *args, const char *tag)
{
    spawn_opts so = {cwd, NULL, NULL, 0};
    return start_with(&so, args, tag);
}

/* Waits for pid at most timeout seconds (then kills it: timed_out), from t0 (now_s() of the
 * start or of a signal sent: r->seconds) and reads its output. */
static inline void finish_from(pid_t pid, double timeout, const char *tag, double t0, result *r)
{
    memset(r, 0, sizeof *r);
    int status = 0;
    for (;;) {
        pid_t w = waitpid(pid, &status, WNOHANG);
        if (w == pid) break;
        if (w < 0 && errno != EINTR) break;
        if (now_s() - t0 > timeout) {
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            r->timed_out = 1;
            break;
        }
        sleep_ms(5);
    }
    r->seconds = now_s() - t0;
    r->exited = WIFEXITED(status);
    r->code = r->exited ? WEXITSTATUS(status) : -1;
    r->signaled = WIFSIGNALED(status);
    r->sig = r->signaled ? WTERMSIG(status) : 0;
    char p[8192];
    snprintf(p, sizeof p, "%s/%s.out", tmp, tag);
    slurp(p, r->out, sizeof r->out);
    snprintf(p, sizeof p, "%s/%s.err", tmp, tag);
    slurp(p, r->err, sizeof r->err);
}

static inline void finish(pid_t pid, double timeout, const char *tag, result *r)
{
    finish_from(pid, timeout, tag, now_s(), r);
}

static inline void run(const char *cwd, const char *const *args, const char *tag, double timeout,
                       result *r)
{
    finish(start(cwd, args, tag), timeout, tag, r);
}

static inline void run_with(const spawn_opts *so, const char *const *args, const char *tag,
                            double timeout, result *r)
{
    finish(start_with(so, args, tag), timeout, tag, r);
}

/* dir/name into buf */
static inline void path2(char *buf, size_t size, const char *a, const char *b)
{
    snprintf(buf, size, "%s/%s", a, b);
}

/* A stand-in for gnuplot in its own folder: script is the shell script's body. Returns the
 * PATH that finds it first. */
static inline const char *fake_gnuplot(const char *name, const char *script, char *path_env,
                                       size_t size)
{
    char dir[4200], exe_path[4300];
    path2(dir, sizeof dir, tmp, name);
    mkdir(dir, 0777);
    snprintf(exe_path, sizeof exe_path, "%s/gnuplot", dir);
    FILE *f = fopen(exe_path, "w");
    if (f) {
        fprintf(f, "#!/bin/sh\n%s\n", script);
        fclose(f);
    }
    chmod(exe_path, 0755);
    snprintf(path_env, size, "%s:/usr/local/bin:/usr/bin:/bin", dir);
    return path_env;
}

static inline int file_exists(const char *dir, const char *name)
{
    char p[8192];
    struct stat st;
    snprintf(p, sizeof p, "%s/%s", dir, name);
    return lstat(p, &st) == 0;
}

static inline int file_nonempty(const char *dir, const char *name)
{
    char p[8192];
    struct stat st;
    snprintf(p, sizeof p, "%s/%s", dir, name);
    return stat(p, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0;
}

static inline int first_line_is(const char *dir, const char *name, const char *want)
{
    char p[8192], line[4096];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "r");
    if (!f) return 0;
    int ok = fgets(line, sizeof line, f) && !strncmp(line, want, strlen(want));
    fclose(f);
    return ok;
}

static inline int file_contains(const char *dir, const char *name, const char *want)
{
    char p[8192];
    static char buf[1 << 16];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    slurp(p, buf, sizeof buf);
    return strstr(buf, want) != NULL;
}

/* results.csv: the header of crane_output_names, then rows of CRANE_NOUT numbers with
 * increasing t, all finite (allow_nan: or NaN, which the model writes for the parts a scene does
 * not build). Returns the number of rows (< 0: malformed) and the last t. */
static inline long check_csv(const char *dir, int allow_nan, double *t_last, char *why,
                             size_t wsize)
{
    char p[8192], header[4096] = "";
    size_t len = 0;
    for (int i = 0; i < CRANE_NOUT; i++)
        len += (size_t)snprintf(header + len, sizeof header - len, "%s%s", i ? "," : "",
                                crane_output_names[i]);
    snprintf(p, sizeof p, "%s/results.csv", dir);
    FILE *f = fopen(p, "r");
    snprintf(why, wsize, "ok");
    *t_last = NAN;
    if (!f) {
        snprintf(why, wsize, "no results.csv");
        return -1;
    }
    static char line[1 << 14];
    long rows = 0;
    double tprev = -1;
    if (!fgets(line, sizeof line, f) || strncmp(line, header, strlen(header)) ||
        line[strlen(header)] != '\n') {
        snprintf(why, wsize, "header is not crane_output_names");
        fclose(f);
        return -1;
    }
    while (fgets(line, sizeof line, f)) {
        size_t n = strlen(line);
        if (n == 0 || line[n - 1] != '\n') {
            snprintf(why, wsize, "row %ld is cut short", rows + 1);
            fclose(f);
            return -1;
        }
        char *s = line, *end;
        int fields = 0, finite = 1;
        double t = NAN;
        for (;;) {
            double v = strtod(s, &end);
            if (end == s) break;
            if (fields == 0) t = v;
            finite = finite && (isfinite(v) || (allow_nan && isnan(v) && fields > 0));
            fields++;
            if (*end != ',') break;
            s = end + 1;
        }
        if (fields != CRANE_NOUT || *end != '\n' || !finite || !(t > tprev)) {
            snprintf(why, wsize, "row %ld: %d fields, finite %d, t %g after %g", rows + 1, fields,
                     finite, t, tprev);
            fclose(f);
            return -1;
        }
        tprev = t;
        rows++;
    }
    fclose(f);
    *t_last = tprev;
    return rows;
}

/* path made absolute (the program runs in other folders too) */
static inline int absolute(const char *path, char *buf, size_t size)
{
    char cwd[1024];
    int n;
    if (path[0] == '/')
        n = snprintf(buf, size, "%s", path);
    else if (getcwd(cwd, sizeof cwd))
        n = snprintf(buf, size, "%s/%s", cwd, path);
    else
        return 0;
    return n > 0 && (size_t)n < size;
}

/* exe and scenes from the command line, tmp made: 0, or -1 after a "Bail out!" */
static inline int spawn_setup(int argc, char **argv, const char *prefix)
{
    if (!absolute(argv[1], exe, sizeof exe) || !absolute(argv[2], scenes, sizeof scenes)) {
        printf("Bail out! cannot resolve %s or %s\n", argv[1], argv[2]);
        return -1;
    }
    (void)argc;
    const char *tdir = getenv("TMPDIR");
    snprintf(tmp, sizeof tmp, "%s/%s_XXXXXX", tdir && *tdir ? tdir : "/tmp", prefix);
    if (!mkdtemp(tmp)) {
        printf("Bail out! mkdtemp failed\n");
        return -1;
    }
    return 0;
}

#endif
