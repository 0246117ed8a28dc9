/* Folders and atomic writes of the programs (pu_fs.h). */
#include "pu_fs.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

const char *pu_fs_kind(unsigned mode)
{
    mode_t m = (mode_t)mode;
    return S_ISREG(m)    ? "a regular file"
           : S_ISDIR(m)  ? "a directory"
           : S_ISFIFO(m) ? "a FIFO (named pipe)"
           : S_ISCHR(m)  ? "a character device"
           : S_ISBLK(m)  ? "a block device"
           : S_ISSOCK(m) ? "a socket"
           : S_ISLNK(m)  ? "a symbolic link"
                         : "not a regular file";
}

/* msg (may be NULL) from the format; errno is kept. */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static void
say(char *msg, size_t size, const char *fmt, ...)
{
    if (!msg || !size) return;
    int e = errno;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, size, fmt, ap);
    va_end(ap);
    errno = e;
}

/* Each prefix of the path that ends before a '/' (and the whole path) is made a folder in
 * turn: stat first, mkdir when it is missing, stat again (mkdir through a symbolic link to
 * nothing fails with EEXIST), and a prefix that exists as anything but a folder stops it. */
int pu_mkdir_p(const char *dir, unsigned mode, char *msg, size_t size)
{
    char buf[PU_FS_PATH_MAX + 1];
    if (msg && size) msg[0] = '\0';
    if (snprintf(buf, sizeof buf, "%s", dir) >= (int)sizeof buf) {
        errno = ENAMETOOLONG;
        say(msg, size, "the name is too long");
        return -1;
    }
    size_t n = strlen(buf);
    if (n == 0) {
        errno = ENOENT;
        say(msg, size, "the folder's name is empty");
        return -1;
    }
    for (size_t i = 1; i <= n; i++) {
        if (buf[i] != '/' && buf[i] != '\0') continue;
        if (buf[i - 1] == '/') continue; /* "a//b" */
        char keep = buf[i];
        buf[i] = '\0';
        struct stat st;
        if (stat(buf, &st) != 0) {
            if (errno != ENOENT) {
                say(msg, size, "%s: %s", buf, strerror(errno));
                return -1;
            }
            if (mkdir(buf, (mode_t)mode) != 0 && errno != EEXIST) {
                say(msg, size, "cannot create %s: %s", buf, strerror(errno));
                return -1;
            }
            if (stat(buf, &st) != 0) {
                int e = errno;
                if (lstat(buf, &st) == 0 && S_ISLNK(st.st_mode))
                    say(msg, size, "%s is a symbolic link to nothing, not a folder", buf);
                else
                    say(msg, size, "cannot create %s: %s", buf, strerror(e));
                errno = e;
                return -1;
            }
        }
        if (!S_ISDIR(st.st_mode)) {
            errno = ENOTDIR;
            say(msg, size, "%s is %s, not a folder", buf, pu_fs_kind((unsigned)st.st_mode));
            return -1;
        }
        buf[i] = keep;
    }
    return 0;
}

int pu_write_all(int fd, const void *p, size_t n)
{
    const char *c = p;
    while (n > 0) {
        ssize_t w = write(fd, c, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) {
            if (w == 0) errno = EIO;
            return -1;
        }
        c += w;
        n -= (size_t)w;
    }
    return 0;
}

int pu_atomic_temp_name(const char *path, char *tmp, size_t size)
{
    int len = snprintf(tmp, size, "%s.tmp", path);
    if (len < 0 || (size_t)len >= size) {
        errno = ENAMETOOLONG;
        return -1;
    }
    return 0;
}

int pu_write_atomic_via(const char *path, const char *tmp, const void *data, size_t len)
{
    int fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) return -1;
    int e = 0;
    if (pu_write_all(fd, data, len) != 0 || fsync(fd) != 0) e = errno;
    if (close(fd) != 0 && !e) e = errno;
    if (!e && rename(tmp, path) != 0) e = errno;
    if (e) unlink(tmp);
    errno = e;
    return e ? -1 : 0;
}

int pu_write_atomic(const char *path, const void *data, size_t len)
{
    char tmp[PU_FS_PATH_MAX + 1];
    if (pu_atomic_temp_name(path, tmp, sizeof tmp) != 0) return -1;
    return pu_write_atomic_via(path, tmp, data, len);
}
