/* A case's crane process (sweep_proc.h). */
#define _DEFAULT_SOURCE /* wait4 (a child's CPU time), realpath */
#include "sweep_proc.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <limits.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "pu_fs.h"

extern char **environ;

double sweep_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int sweep_proc_start(sweep_proc *p, long index, const char *exe, char *const argv[],
                     const char *dir, const char *log_name, double time_limit)
{
    memset(p, 0, sizeof *p);
    p->index = index;
    p->time_limit = time_limit;
    p->out.time_limit = time_limit;
    snprintf(p->dir, sizeof p->dir, "%s", dir);
    char log[sizeof p->dir + 16];
    snprintf(log, sizeof log, "%s/%s", dir, log_name);
    posix_spawn_file_actions_t fa;
    posix_spawnattr_t at;
    int e = posix_spawn_file_actions_init(&fa);
    if (e) {
        p->out.errno_start = e;
        return -1;
    }
    if ((e = posix_spawnattr_init(&at)) != 0) {
        posix_spawn_file_actions_destroy(&fa);
        p->out.errno_start = e;
        return -1;
    }
    sigset_t none, deflt;
    sigemptyset(&none);
    sigemptyset(&deflt);
    sigaddset(&deflt, SIGINT);
    sigaddset(&deflt, SIGTERM);
    sigaddset(&deflt, SIGHUP);
    sigaddset(&deflt, SIGPIPE);
    if (!e) e = posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    if (!e)
        e = posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log,
                                             O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW, 0644);
    if (!e) e = posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
    if (!e) e = posix_spawnattr_setsigmask(&at, &none);
    if (!e) e = posix_spawnattr_setsigdefault(&at, &deflt);
    if (!e) e = posix_spawnattr_setflags(&at, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    pid_t pid = 0;
    if (!e) e = posix_spawn(&pid, exe, &fa, &at, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    posix_spawnattr_destroy(&at);
    if (e) {
        p->out.errno_start = e;
        return -1;
    }
    p->pid = pid;
    p->out.started = 1;
    p->t0 = sweep_now();
    return 0;
}

int sweep_proc_poll(sweep_proc *p)
{
    if (p->pid <= 0) return 1;
    int st = 0;
    struct rusage ru;
    memset(&ru, 0, sizeof ru);
    pid_t w = wait4(p->pid, &st, WNOHANG, &ru);
    double now = sweep_now();
    if (w == p->pid) {
        p->out.wait_status = st;
        p->out.wall_s = now - p->t0;
        p->out.cpu_s = (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
                       (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
        p->pid = 0;
        return 1;
    }
    if (w < 0 && errno != EINTR) {    /* not our child any more: cannot happen; end it as crashed */
        p->out.wait_status = SIGKILL; /* WIFSIGNALED, SIGKILL */
        p->out.wall_s = now - p->t0;
        p->pid = 0;
        return 1;
    }
    if (p->time_limit > 0 && !p->term_at && now - p->t0 >= p->time_limit) {
        p->out.timed_out = 1;
        p->term_at = now;
        kill(p->pid, SIGTERM);
    }
    if (p->term_at && !p->out.killed && now - p->term_at >= SWEEP_KILL_GRACE) {
        p->out.killed = 1;
        kill(p->pid, SIGKILL);
    }
    return 0;
}

void sweep_proc_stop(sweep_proc *p, int sig, int hard)
{
    if (p->pid <= 0) return;
    if (!p->out.stopped_by && !p->out.timed_out) p->out.stopped_by = sig;
    if (hard) {
        if (!p->out.killed) kill(p->pid, SIGKILL);
        p->out.killed = 1;
        return;
    }
    if (!p->term_at) {
        p->term_at = sweep_now();
        kill(p->pid, SIGTERM);
    }
}

/* path is a program that can be run: 1; 0 with why not in why ("not found", "is a directory, not
 * a program", "not executable (no execute permission)", the error of stat). */
static int executable(const char *path, char *why, size_t size)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        snprintf(why, size, "%s", errno == ENOENT ? "not found" : strerror(errno));
        return 0;
    }
    if (!S_ISREG(st.st_mode)) {
        snprintf(why, size, "is %s, not a program", pu_fs_kind((unsigned)st.st_mode));
        return 0;
    }
    if (access(path, X_OK) != 0) {
        snprintf(why, size, "not executable (%s)",
                 errno == EACCES ? "no execute permission" : strerror(errno));
        return 0;
    }
    return 1;
}

int sweep_find_program(const char *name, const char *given, const char *build, char *out,
                       size_t size, char *tried, size_t tsize)
{
    tried[0] = '\0';
    char why[256];
    if (given) {
        if (!executable(given, why, sizeof why)) {
            if (strcmp(why, "not found")) /* there, but not a program: said as such */
                snprintf(tried, tsize, "%s: %s", given, why);
            else
                snprintf(tried, tsize, "%s", given);
            return strcmp(why, "not found") ? -1 : 0;
        }
        if (!realpath(given, out)) snprintf(out, size, "%s", given);
        return 1;
    }
    char self[SWEEP_PATH_SIZE];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n > 0) {
        self[n] = '\0';
        char *slash = strrchr(self, '/');
        if (slash) {
            snprintf(slash + 1, sizeof self - (size_t)(slash + 1 - self), "%s", name);
            snprintf(tried, tsize, "%s", self);
            if (executable(self, why, sizeof why)) {
                snprintf(out, size, "%s", self);
                return 1;
            }
        }
    }
    if (build) {
        size_t tl = strlen(tried);
        snprintf(tried + tl, tsize - tl, "%s%s", tl ? ", " : "", build);
        if (executable(build, why, sizeof why)) {
            snprintf(out, size, "%s", build);
            return 1;
        }
    }
    return 0;
}
