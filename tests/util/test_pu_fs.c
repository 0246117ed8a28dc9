/* pu_fs.h: mkdir -p of nested paths and its refusals with the part named; the atomic write
 * replaces whole and leaves no temporary file when it fails. */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <signal.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "pu_fs.h"
#include "tap.h"

static char root[256];

static int is_dir(const char *p)
{
    struct stat st;
    return stat(p, &st) == 0 && S_ISDIR(st.st_mode);
}

static int exists(const char *p)
{
    struct stat st;
    return lstat(p, &st) == 0;
}

static char *slurp(const char *p)
{
    static char buf[256];
    FILE *f = fopen(p, "r");
    if (!f) return NULL;
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

static void test_mkdir(void)
{
    char p[512], msg[512], q[512];
    snprintf(p, sizeof p, "%s/a/b//c/d/", root);
    tap_ok(pu_mkdir_p(p, 0777, msg, sizeof msg) == 0, "mkdir -p of a nested path (%s)", msg);
    snprintf(q, sizeof q, "%s/a/b/c/d", root);
    tap_ok(is_dir(q), "every level exists");
    tap_ok(pu_mkdir_p(p, 0777, msg, sizeof msg) == 0, "again: the folders are kept");

    snprintf(q, sizeof q, "%s/a/file", root);
    FILE *f = fopen(q, "w");
    if (f) fclose(f);
    snprintf(p, sizeof p, "%s/a/file/sub", root);
    errno = 0;
    int rc = pu_mkdir_p(p, 0777, msg, sizeof msg);
    char want[600];
    snprintf(want, sizeof want, "%s/a/file is a regular file, not a folder", root);
    tap_ok(rc == -1 && errno == ENOTDIR && !strcmp(msg, want), "a file on the way: '%s'", msg);

    snprintf(q, sizeof q, "%s/a/dangling", root);
    snprintf(p, sizeof p, "%s/nowhere", root);
    tap_ok(symlink(p, q) == 0, "symbolic link to nothing made");
    rc = pu_mkdir_p(q, 0777, msg, sizeof msg);
    tap_ok(rc == -1 && strstr(msg, "a/dangling is a symbolic link to nothing, not a folder"),
           "a link to nothing: '%s'", msg);

    char *longp = malloc(PU_FS_PATH_MAX + 10);
    memset(longp, 'x', PU_FS_PATH_MAX + 8);
    longp[PU_FS_PATH_MAX + 8] = '\0';
    errno = 0;
    rc = pu_mkdir_p(longp, 0777, msg, sizeof msg);
    tap_ok(rc == -1 && errno == ENAMETOOLONG && !strcmp(msg, "the name is too long"),
           "an overlong name: '%s'", msg);
    free(longp);
    tap_ok(pu_mkdir_p("", 0777, NULL, 0) == -1, "an empty name refused (msg NULL allowed)");
    if (geteuid() != 0) { /* root may write anywhere */
        snprintf(q, sizeof q, "%s/ro", root);
        mkdir(q, 0555);
        snprintf(p, sizeof p, "%s/ro/x/y", root);
        rc = pu_mkdir_p(p, 0777, msg, sizeof msg);
        tap_ok(rc == -1 && strstr(msg, "cannot create ") && strstr(msg, "/ro/x: "),
               "no permission: the part named: '%s'", msg);
    } else {
        tap_ok(1, "# SKIP no permission test as root");
    }
    tap_ok(!strcmp(pu_fs_kind(S_IFIFO), "a FIFO (named pipe)") &&
               !strcmp(pu_fs_kind(S_IFDIR), "a directory"),
           "kinds of files");
}

static void test_atomic(void)
{
    char p[512], tmp[600];
    snprintf(p, sizeof p, "%s/f.txt", root);
    tap_ok(pu_write_atomic(p, "first\n", 6) == 0, "atomic write");
    const char *got = slurp(p);
    tap_ok(got && !strcmp(got, "first\n"), "the text written");
    tap_ok(pu_write_atomic(p, "second\n", 7) == 0 && (got = slurp(p)) && !strcmp(got, "second\n"),
           "replaced whole");
    tap_ok(pu_atomic_temp_name(p, tmp, sizeof tmp) == 0 && !exists(tmp), "no temporary file left");
    char small[8];
    errno = 0;
    tap_ok(pu_atomic_temp_name(p, small, sizeof small) == -1 && errno == ENAMETOOLONG,
           "temporary name that does not fit: ENAMETOOLONG");

    /* rename fails (the target is a non-empty folder): the old target stays, no temporary */
    char d[512], inner[600];
    snprintf(d, sizeof d, "%s/dirtarget", root);
    mkdir(d, 0777);
    snprintf(inner, sizeof inner, "%s/keep", d);
    FILE *f = fopen(inner, "w");
    if (f) fclose(f);
    errno = 0;
    int rc = pu_write_atomic(d, "x", 1);
    int e = errno;
    snprintf(tmp, sizeof tmp, "%s.tmp", d);
    tap_ok(rc == -1 && e != 0 && !exists(tmp) && is_dir(d),
           "a failed rename: -1 (%s), the folder kept, no temporary file", strerror(e));

    /* a write that fails part way (a file size limit of 4 bytes, SIGXFSZ ignored): -1 with
     * EFBIG, the file as it was, no temporary file */
    struct rlimit old, lim;
    getrlimit(RLIMIT_FSIZE, &old);
    lim = old;
    lim.rlim_cur = 4;
    signal(SIGXFSZ, SIG_IGN);
    setrlimit(RLIMIT_FSIZE, &lim);
    errno = 0;
    rc = pu_write_atomic(p, "0123456789", 10);
    e = errno;
    setrlimit(RLIMIT_FSIZE, &old);
    snprintf(tmp, sizeof tmp, "%s.tmp", p);
    tap_ok(rc == -1 && e == EFBIG && (got = slurp(p)) && !strcmp(got, "second\n") && !exists(tmp),
           "a write that fails: EFBIG (%s), the file as it was, no temporary file", strerror(e));
    /* the temporary cannot be created (no folder): nothing changes */
    snprintf(p, sizeof p, "%s/missing/f.txt", root);
    errno = 0;
    tap_ok(pu_write_atomic(p, "x", 1) == -1 && errno == ENOENT, "no folder: ENOENT");

    int fd = open("/dev/null", O_WRONLY);
    tap_ok(fd >= 0 && pu_write_all(fd, "abc", 3) == 0, "pu_write_all");
    if (fd >= 0) close(fd);
}

int main(void)
{
    snprintf(root, sizeof root, "/tmp/test_pu_fs.XXXXXX");
    if (!mkdtemp(root)) {
        tap_ok(0, "temporary folder");
        return tap_done();
    }
    test_mkdir();
    test_atomic();
    char cmd[600];
    snprintf(cmd, sizeof cmd, "chmod -R u+w '%s' && rm -rf '%s'", root, root);
    if (system(cmd) != 0) tap_diag("could not remove %s", root);
    return tap_done();
}
