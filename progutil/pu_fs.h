/* Files of the programs (libprogutil, prefix pu_): folders created with their parents
 * (mkdir -p) and files replaced atomically (a temporary file written whole, made durable, then
 * renamed over the file: a reader sees the old file or the new one, never a part).
 *
 * No output, no exit, no global state: failures are returned (-1 with errno) and, where a
 * buffer is given, said in it. */
#ifndef PU_FS_H
#define PU_FS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* What a file of mode st_mode is, for messages: "a regular file", "a directory", "a FIFO (named
 * pipe)", "a character device", "a block device", "a socket", "a symbolic link". */
const char *pu_fs_kind(unsigned mode);

/* Creates the folder dir and its parents (permissions mode, less the umask); folders that
 * exist are kept. 0, or -1 with errno and the reason in msg (NULL: none): "cannot create
 * out/a: Permission denied", "out/a is a regular file, not a folder" (ENOTDIR), "out/a is a
 * symbolic link to nothing, not a folder", "the name is too long" (ENAMETOOLONG, over
 * PU_FS_PATH_MAX characters). */
#define PU_FS_PATH_MAX 4095
int pu_mkdir_p(const char *dir, unsigned mode, char *msg, size_t size);

/* Writes the n bytes at p to the descriptor fd, again after EINTR and short writes. 0, or -1
 * with errno (a write of 0 bytes: EIO). */
int pu_write_all(int fd, const void *p, size_t n);

/* The temporary file of path's atomic write: "path.tmp" into tmp. 0, or -1 with errno
 * ENAMETOOLONG when it does not fit. */
int pu_atomic_temp_name(const char *path, char *tmp, size_t size);

/* Replaces path by the len bytes at data through the temporary file tmp (created with
 * permissions 0644 less the umask, written whole, fsync, closed, renamed to path): path is then
 * whole, or as it was. On failure tmp is removed. 0, or -1 with errno. A program that removes
 * the temporary file from a signal handler names tmp itself (pu_atomic_temp_name). */
int pu_write_atomic_via(const char *path, const char *tmp, const void *data, size_t len);
/* The same through pu_atomic_temp_name(path). */
int pu_write_atomic(const char *path, const void *data, size_t len);

#ifdef __cplusplus
}
#endif
#endif
