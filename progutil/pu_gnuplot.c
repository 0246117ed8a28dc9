/* gnuplot for the programs (pu_gnuplot.h). */
#define _GNU_SOURCE /* posix_spawn_file_actions_addchdir_np (glibc 2.29) */
#include "pu_gnuplot.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

extern char **environ;

int pu_gnuplot_find(char *buf, size_t size)
{
    const char *path = getenv("PATH");
    if (!path || !*path) path = "/usr/local/bin:/usr/bin:/bin";
    for (const char *p = path;; p++) {
        const char *e = strchr(p, ':');
        size_t n = e ? (size_t)(e - p) : strlen(p);
        int len = snprintf(buf, size, "%.*s%sgnuplot", (int)n, p, n ? "/" : "./");
        struct stat st;
        if (len > 0 && (size_t)len < size && stat(buf, &st) == 0 && S_ISREG(st.st_mode) &&
            access(buf, X_OK) == 0)
            return 1;
        if (!e) return 0;
        p = e;
    }
}

int pu_png_whole(const char *path)
{
    static const unsigned char iend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
    unsigned char tail[12];
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    int ok =
        fseek(f, -12L, SEEK_END) == 0 && fread(tail, 1, 12, f) == 12 && !memcmp(tail, iend, 12);
    fclose(f);
    return ok;
}

int pu_gif_whole(const char *path)
{
    unsigned char head[6], tail = 0;
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    int ok = fread(head, 1, 6, f) == 6 &&
             (!memcmp(head, "GIF87a", 6) || !memcmp(head, "GIF89a", 6)) &&
             fseek(f, -1L, SEEK_END) == 0 && fread(&tail, 1, 1, f) == 1 && tail == 0x3B;
    fclose(f);
    return ok;
}

void pu_gnuplot_log_first(const char *dir, const char *log, int remove_empty, char *buf,
                          size_t size)
{
    char path[4200];
    buf[0] = '\0';
    if (snprintf(path, sizeof path, "%s/%s", dir, log) >= (int)sizeof path) return;
    FILE *f = fopen(path, "r");
    if (!f) return;
    if (!fgets(buf, (int)size, f)) buf[0] = '\0';
    buf[strcspn(buf, "\n")] = '\0';
    fclose(f);
    if (remove_empty && !buf[0]) remove(path);
}

/* Starts gnuplot with argv in job->dir, standard input and output /dev/null, standard error
 * onto err_fd (the pipe's end for writing, or -1: dir/log). *pid, or an errno value. */
static int spawn(const pu_gnuplot_job *job, char *const *argv, int err_fd, int close_fd, pid_t *pid)
{
    char logp[4200];
    if (err_fd < 0 && snprintf(logp, sizeof logp, "%s/%s", job->dir, job->log) >= (int)sizeof logp)
        return ENAMETOOLONG;
#ifdef PU_HAVE_ADDCHDIR
    posix_spawn_file_actions_t fa;
    posix_spawnattr_t at;
    sigset_t none, dfl;
    sigemptyset(&none);
    sigemptyset(&dfl);
    sigaddset(&dfl, SIGINT);
    sigaddset(&dfl, SIGTERM);
    sigaddset(&dfl, SIGHUP);
    sigaddset(&dfl, SIGPIPE);
    int e = posix_spawn_file_actions_init(&fa);
    if (e) return e;
    e = posix_spawnattr_init(&at);
    if (e) {
        posix_spawn_file_actions_destroy(&fa);
        return e;
    }
    if (!e) e = posix_spawnattr_setflags(&at, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    if (!e) e = posix_spawnattr_setsigmask(&at, &none);
    if (!e) e = posix_spawnattr_setsigdefault(&at, &dfl);
    if (!e) e = posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    if (!e) e = posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    if (!e && err_fd >= 0) e = posix_spawn_file_actions_adddup2(&fa, err_fd, STDERR_FILENO);
    if (!e && err_fd > STDERR_FILENO) e = posix_spawn_file_actions_addclose(&fa, err_fd);
    if (!e && err_fd >= 0 && close_fd >= 0) e = posix_spawn_file_actions_addclose(&fa, close_fd);
    if (!e && err_fd < 0)
        e = posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, logp, O_WRONLY | O_CREAT | O_TRUNC,
                                             0644);
    /* the actions run in order: the log (dir/log, relative to the caller's directory when dir
     * is) is opened before the change of directory, as the fork path below does */
    if (!e) e = posix_spawn_file_actions_addchdir_np(&fa, job->dir);
    if (!e) e = posix_spawn(pid, job->exe, &fa, &at, argv, environ);
    posix_spawnattr_destroy(&at);
    posix_spawn_file_actions_destroy(&fa);
    return e;
#else
    /* fork: the caller's signal handlers must not run in the child before exec */
    sigset_t block, old;
    sigfillset(&block);
    sigprocmask(SIG_BLOCK, &block, &old);
    fflush(NULL);
    pid_t p = fork();
    if (p == 0) {
        signal(SIGINT, SIG_DFL);
        signal(SIGTERM, SIG_DFL);
        signal(SIGHUP, SIG_DFL);
        signal(SIGPIPE, SIG_DFL);
        sigset_t none;
        sigemptyset(&none);
        sigprocmask(SIG_SETMASK, &none, NULL);
        if (close_fd >= 0) close(close_fd);
        int fi = open("/dev/null", O_RDONLY), fo = open("/dev/null", O_WRONLY);
        int fe = err_fd >= 0 ? err_fd : open(logp, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (chdir(job->dir) != 0 || fi < 0 || fo < 0 || fe < 0 || dup2(fi, STDIN_FILENO) < 0 ||
            dup2(fo, STDOUT_FILENO) < 0 || dup2(fe, STDERR_FILENO) < 0)
            _exit(126);
        if (err_fd > STDERR_FILENO) close(err_fd);
        execv(job->exe, argv);
        _exit(127);
    }
    int e = p < 0 ? errno : 0;
    sigprocmask(SIG_SETMASK, &old, NULL);
    *pid = p;
    return e;
#endif
}

static void pause_20ms(void)
{
    struct timespec ts = {0, 20000000L};
    nanosleep(&ts, NULL);
}

int pu_gnuplot_run(const pu_gnuplot_job *job, char *msg, size_t size)
{
    if (size > 0) msg[0] = '\0';
    if (!job || !job->exe || !job->dir || (!job->script && !job->commands)) {
        snprintf(msg, size, "cannot start gnuplot: no program, folder or script given");
        return -1;
    }
    char *argv[4] = {"gnuplot", NULL, NULL, NULL};
    if (job->script) {
        argv[1] = (char *)job->script;
    } else {
        argv[1] = "-e";
        argv[2] = (char *)job->commands;
    }
    int fd[2] = {-1, -1};
    if (!job->log && pipe(fd) != 0) {
        snprintf(msg, size, "cannot start gnuplot: %s", strerror(errno));
        return -1;
    }
    pid_t pid = 0;
    int e = spawn(job, argv, fd[1], fd[0], &pid);
    if (fd[1] >= 0) close(fd[1]);
    if (e) {
        if (fd[0] >= 0) close(fd[0]);
        snprintf(msg, size, "cannot start gnuplot: %s", strerror(e));
        return -1;
    }
    int stopped = 0;
    /* its messages: the first 2 kB kept, the rest read and dropped (a full pipe would stall it) */
    char buf[2048], drop[512];
    size_t len = 0;
    while (fd[0] >= 0) {
        if (job->stop && *job->stop && !stopped) {
            kill(pid, SIGTERM);
            stopped = 1;
        }
        struct pollfd pf = {fd[0], POLLIN, 0};
        int pr = poll(&pf, 1, 20);
        if (pr < 0 && errno != EINTR) break;
        if (pr <= 0) continue;
        ssize_t k = len + 1 < sizeof buf ? read(fd[0], buf + len, sizeof buf - 1 - len)
                                         : read(fd[0], drop, sizeof drop);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) break;
        if (len + 1 < sizeof buf) len += (size_t)k;
    }
    if (fd[0] >= 0) close(fd[0]);
    int status = 0;
    for (;;) {
        pid_t w = waitpid(pid, &status, job->stop ? WNOHANG : 0);
        if (w == pid) break;
        if (w < 0 && errno != EINTR) {
            snprintf(msg, size, "gnuplot: %s", strerror(errno));
            return -1;
        }
        if (job->stop && *job->stop && !stopped) {
            kill(pid, SIGTERM);
            stopped = 1;
        }
        if (w == 0) pause_20ms();
    }
    if (!job->log && size > 0) { /* the last line with text */
        buf[len] = '\0';
        while (len > 0 && (buf[len - 1] == '\n' || buf[len - 1] == ' '))
            buf[--len] = '\0';
        char *last = strrchr(buf, '\n');
        last = last ? last + 1 : buf;
        last += strspn(last, " ");
        snprintf(msg, size, "%s", last);
    }
    return status;
}
