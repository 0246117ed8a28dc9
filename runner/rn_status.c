/* The programs' status and files (rn_run.h): the signal handler with the status.txt it
 * writes, status.txt itself, failures, the atomic writes of the small files, the output folder
 * made ready. */
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "rn_run.h"
#include "pu_fs.h"

/* ------------------------------------------------------------------ signals ---- */

/* The handler (SIGINT, SIGTERM, SIGHUP) records the first signal in g_signal; the program looks
 * at it between solver steps and between its other tasks, and ends the run in order. It ends the
 * program itself when the signal comes during set-up (RN_PHASE_SETUP: the model's build, the static
 * equilibrium and the initial values are long library calls that cannot be stopped) or is a
 * second one (g_signal set already), after writing the status.txt prepared for that moment
 * (g_pre, the signal's name, g_post) with async-signal-safe calls: a temporary file, fsync,
 * rename. Two slots: the program fills the one not in use, then switches g_slot. */
static volatile sig_atomic_t g_signal = 0, g_phase = RN_PHASE_OTHER, g_status_ready = 0;
static volatile sig_atomic_t g_slot = 0, g_temp_live = 0;
static char g_status_path[RN_PATH_SIZE], g_signal_tmp[RN_PATH_SIZE], g_temp_path[RN_PATH_SIZE];
#define SLOT_SIZE 16384
static char g_pre[2][SLOT_SIZE], g_post[2][SLOT_SIZE];
/* "program: " for the handler's message */
static char g_prefix[40] = "program: ";
static size_t g_prefix_len = 9;
static size_t g_pre_len[2], g_post_len[2];

const char *rn_signal_name(int sig)
{
    return sig == SIGINT    ? "SIGINT"
           : sig == SIGTERM ? "SIGTERM"
           : sig == SIGHUP  ? "SIGHUP"
                            : "signal";
}

static void on_signal(int sig)
{
    int saved = errno, second = g_signal != 0;
    if (!second) g_signal = sig;
    if (!second && g_phase != RN_PHASE_SETUP) {
        errno = saved;
        return;
    }
    if (g_status_ready) {
        if (g_temp_live) unlink(g_temp_path); /* a file the program was writing */
        int k = g_slot;
        const char *name = rn_signal_name(sig);
        int fd = open(g_signal_tmp, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) {
            int bad = pu_write_all(fd, g_pre[k], g_pre_len[k]) ||
                      pu_write_all(fd, name, strlen(name)) ||
                      pu_write_all(fd, g_post[k], g_post_len[k]) || fsync(fd) != 0;
            if (close(fd) != 0) bad = 1;
            if (bad || rename(g_signal_tmp, g_status_path) != 0) unlink(g_signal_tmp);
        }
    }
    static const char note[] = " received: stopped at once\n";
    if (pu_write_all(STDERR_FILENO, g_prefix, g_prefix_len) == 0 &&
        pu_write_all(STDERR_FILENO, rn_signal_name(sig), strlen(rn_signal_name(sig))) == 0 &&
        pu_write_all(STDERR_FILENO, note, sizeof note - 1) == 0) {
    }
    _exit(128 + sig);
}

double rn_wall_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void rn_local_time(char *buf, size_t size)
{
    time_t now = time(NULL);
    struct tm tm;
    if (!localtime_r(&now, &tm) || !strftime(buf, size, "%Y-%m-%d %H:%M:%S %z", &tm))
        snprintf(buf, size, "%lld s after 1970", (long long)now);
}

/* DIR/name (rn_set_outdir has checked that the folder's name leaves room: never cut). */
void rn_path_in(const rn_run *r, const char *name, char *buf, size_t size)
{
    int n = snprintf(buf, size, "%s/%s", r->outdir, name);
    if (n < 0 || (size_t)n >= size) buf[0] = '\0';
}

/* The text of status.txt: how the run stands (status, reason), what it is (pid, scene or
 * model, command line, start) and how far it got; final: with the end time and the wall time.
 * NULL: out of memory. */
static char *status_text(const rn_run *r, const char *status, const char *reason, int final)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f) return NULL;
    const dae_stats *st = r->s ? dae_get_stats(r->s) : NULL;
    fprintf(f, "status: %s\nreason: %s\n", status, reason && reason[0] ? reason : "-");
    fprintf(f, "pid: %ld\n%s: %s (%s)\ncommand: %s\nstarted: %s\n", (long)getpid(), r->subject,
            r->name, r->path, r->command, r->started);
    fprintf(f, "t_reached: %.9g s\nt_end: %.9g s\nrows: %ld\n", r->t, r->t_end, r->rows_disk);
    if (r->rows_disk > 0) fprintf(f, "t_last_row: %.9g s\n", r->t_disk);
    fprintf(f, "steps: %ld\n", st ? st->steps : 0L);
    rn_estimate_status_lines(r, f);
    if (r->status_lines) r->status_lines(r, f);
    if (final) {
        char now[64];
        rn_local_time(now, sizeof now);
        fprintf(f, "ended: %s\nwall_time: %.3f s\n", now, rn_wall_now() - r->wall0);
    }
    if (fclose(f) != 0) {
        free(buf);
        return NULL;
    }
    return buf;
}

/* Prepares the status.txt that on_signal writes: status, and reason with \x01 where the signal's
 * name goes. */
static void arm_signal_status(const rn_run *r, const char *status, const char *reason)
{
    char *text = status_text(r, status, reason, 0);
    if (!text) return; /* out of memory: the slot in use stays */
    const char *mark = strchr(text, '\x01'), *post = mark ? mark + 1 : "";
    size_t npre = mark ? (size_t)(mark - text) : strlen(text), npost = strlen(post);
    if (npre > SLOT_SIZE) npre = SLOT_SIZE;
    if (npost > SLOT_SIZE) npost = SLOT_SIZE;
    int k = !g_slot;
    memcpy(g_pre[k], text, npre);
    memcpy(g_post[k], post, npost);
    g_pre_len[k] = npre;
    g_post_len[k] = npost;
    g_slot = k;
    free(text);
}

/* Records a failure and says it on stderr; the first failure's reason leads, later ones are
 * added. Returns RN_EXIT_RUN. */
int rn_fail_run(rn_run *r, const char *what, const char *msg)
{
    fprintf(stderr, "%s: %s: %s\n", r->program, what, msg);
    size_t n = strlen(r->reason);
    /* cut to what fits (the reason is a summary; the full message went to stderr) */
    if (n < sizeof r->reason &&
        snprintf(r->reason + n, sizeof r->reason - n, "%s%s: %.*s", n ? "; then " : "", what,
                 (int)(sizeof r->reason - 1), msg) < 0)
        r->reason[n] = '\0';
    r->status = "failed";
    return RN_EXIT_RUN;
}

int rn_write_failed(rn_run *r, const char *path, int e)
{
    char what[RN_PATH_SIZE + 32];
    snprintf(what, sizeof what, "cannot write %s", path);
    return rn_fail_run(r, what, strerror(e));
}

/* Writes len bytes of text to path through path.tmp (write, fsync, close, rename): path is then
 * whole, or as it was. 0, or -1 with errno. The handler removes the temporary file when it ends
 * the program meanwhile. */
int rn_save_atomic(const char *path, const char *text, size_t len)
{
    char tmp[RN_PATH_SIZE];
    if (pu_atomic_temp_name(path, tmp, sizeof tmp) != 0) return -1;
    g_temp_live = 0;
    memcpy(g_temp_path, tmp, strlen(tmp) + 1);
    g_temp_live = 1; /* from here the handler removes it (perhaps before it exists) */
    int rc = pu_write_atomic_via(path, tmp, text, len), e = errno;
    g_temp_live = 0;
    errno = e;
    return rc;
}

/* Writes DIR/name, atomically, from what print prints (into memory: print returns 0, or -1 on
 * failure). 0, or the failure (RN_EXIT_RUN). */
int rn_save_file(rn_run *r, const char *name, rn_print_fn print, const void *ctx)
{
    char path[RN_PATH_SIZE];
    rn_path_in(r, name, path, sizeof path);
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f) return rn_write_failed(r, path, errno);
    int bad = print(r, f, ctx) != 0 || ferror(f);
    if (fclose(f) != 0 || bad) {
        free(buf);
        return rn_write_failed(r, path, ENOMEM);
    }
    int rc = rn_save_atomic(path, buf, len), e = errno;
    free(buf);
    return rc ? rn_write_failed(r, path, e) : 0;
}

/* status.txt from r->status and r->reason (final: with the end). 0, or RN_EXIT_RUN when it cannot
 * be written (said on stderr; the status.txt before stays). */
int rn_write_status(rn_run *r, int final)
{
    char path[RN_PATH_SIZE];
    rn_path_in(r, "status.txt", path, sizeof path);
    char *text = status_text(r, r->status, r->reason, final);
    int rc = text ? rn_save_atomic(path, text, strlen(text)) : -1, e = text ? errno : ENOMEM;
    if (rc != 0 && (e == ENOSPC || e == EDQUOT)) {
        /* a full disk has no room for the temporary copy: status.txt rewritten in place, its
         * own blocks freed by the truncation first (the new text fits in them unless it needs
         * more blocks than the old: a status of some hundred bytes fits in one) */
        int fd = open(path, O_WRONLY | O_TRUNC);
        if (fd >= 0) {
            int bad = pu_write_all(fd, text, strlen(text)) || fsync(fd) != 0;
            if (close(fd) != 0) bad = 1;
            if (!bad) rc = 0;
        }
    }
    free(text);
    if (rc == 0) return 0;
    fprintf(stderr, "%s: cannot write %s: %s\n", r->program, path, strerror(e));
    r->status = "failed";
    return RN_EXIT_RUN;
}

/* The slot for a second signal while integrating. */
void rn_arm_loop(rn_run *r)
{
    char reason[512];
    snprintf(reason, sizeof reason,
             "\x01 received while integrating, after an earlier signal: stopped at once "
             "(results.csv keeps %ld whole rows)",
             r->rows_disk);
    arm_signal_status(r, "interrupted", reason);
}

/* The slot for a signal after the integration: the run stays as it ended. */
void rn_arm_finishing(rn_run *r)
{
    char reason[sizeof r->reason + 256];
    int done = !strcmp(r->status, "completed");
    snprintf(reason, sizeof reason,
             "%s%s\x01 received while writing the statistics and figures: stopped at once (they "
             "may be missing)",
             r->reason[0] ? r->reason
             : done       ? "the integration reached t_end"
                          : "",
             r->reason[0] || done ? "; " : "");
    arm_signal_status(r, strcmp(r->status, "running") ? r->status : "failed", reason);
}

/* Enters a phase. RN_PHASE_SETUP: a signal ends the program at once, with the status "interrupted"
 * while what; RN_PHASE_LOOP: a second signal does. */
void rn_set_phase(rn_run *r, int phase, const char *what)
{
    g_phase = RN_PHASE_OTHER;
    if (phase == RN_PHASE_SETUP) {
        char reason[512];
        snprintf(reason, sizeof reason, "\x01 received while %s (no results written)", what);
        arm_signal_status(r, "interrupted", reason);
    }
    if (phase == RN_PHASE_LOOP) rn_arm_loop(r);
    g_phase = phase;
    if (phase == RN_PHASE_SETUP && g_signal) on_signal((int)g_signal); /* arrived just before */
}

int rn_phase(void)
{
    return (int)g_phase;
}

int rn_signal(void)
{
    return (int)g_signal;
}

const volatile sig_atomic_t *rn_signal_flag(void)
{
    return &g_signal;
}

void rn_status_ready(const rn_run *r, int ready)
{
    g_status_ready = 0;
    if (ready) {
        rn_path_in(r, "status.txt", g_status_path, sizeof g_status_path);
        rn_path_in(r, "status.txt.signal.tmp", g_signal_tmp, sizeof g_signal_tmp);
    }
    g_status_ready = ready;
}

void rn_signals_install(const char *program)
{
    snprintf(g_prefix, sizeof g_prefix, "%.31s: ", program);
    g_prefix_len = strlen(g_prefix);
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaddset(&sa.sa_mask, SIGINT);
    sigaddset(&sa.sa_mask, SIGTERM);
    sigaddset(&sa.sa_mask, SIGHUP);
    sa.sa_flags = SA_RESTART;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
    /* a closed standard output (program | head) is a failed write, not the end without a status */
    signal(SIGPIPE, SIG_IGN);
}
