/* SPDX-License-Identifier: BSD-3-Clause */
/* Opening the file of a model file's `table NAME FILE` (XPPAUT's manual, "table"). A model
 * file is data, so what it names must not reach beyond it: FILE is read only when it is a
 * regular file in the model file's folder, named without a folder (no '/', so neither an
 * absolute path nor ".." can appear), and not a symbolic link (O_NOFOLLOW); it is opened
 * with O_NONBLOCK and checked with fstat on the descriptor opened, so a FIFO or a device
 * is refused at once instead of blocking, and nothing can change between the check and the
 * read. A file anywhere else is read only when the caller names it for the table
 * (dyn_ode_to_c_tables; the command line's --table NAME=FILE): a regular file, at the path
 * given. POSIX open(2), fstat(2), fdopen(3). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "lang/lang_internal.h"

#ifndef O_CLOEXEC
#define O_CLOEXEC 0
#endif

static const char *file_kind(mode_t mode)
{
    return S_ISDIR(mode)    ? "a directory"
           : S_ISFIFO(mode) ? "a FIFO"
           : S_ISCHR(mode)  ? "a character device"
           : S_ISBLK(mode)  ? "a block device"
           : S_ISSOCK(mode) ? "a socket"
                            : "not a regular file";
}

/* What is accepted, for the messages. */
#define ACCEPTED                                                                             \
    "a table file is a regular file beside the model file, named without a folder, or a "  \
    "file named for the table by the caller (dynkit's --table %s=FILE)"

FILE *lang_open_table_file(lang_ctx *c, const char *table, const char *file, lpos pos,
                           const char **shown)
{
    const char *given = NULL;
    for (int k = 0; k < c->n_table_files; k++)
        if (strcasecmp(c->table_files[k].name, table) == 0) {
            given = c->table_files[k].path;
            c->table_file_used[k] = 1;
        }
    const char *path;
    int flags = O_RDONLY | O_NONBLOCK | O_CLOEXEC;
    if (given) {
        path = given;
    } else {
        if (strchr(file, '/') || strcmp(file, ".") == 0 || strcmp(file, "..") == 0)
            lang_fail(c, pos, "table '%s': '%s' is not read: " ACCEPTED, table, file, table);
        const char *slash = c->path ? strrchr(c->path, '/') : NULL;
        path = slash ? lang_printf(c, "%.*s/%s", (int)(slash - c->path), c->path, file) : file;
        flags |= O_NOFOLLOW;
    }
    *shown = path;
    const int fd = open(path, flags);
    if (fd < 0 && errno == ELOOP && !given)
        lang_fail(c, pos, "table '%s': '%s' is a symbolic link: " ACCEPTED, table, path, table);
    if (fd < 0)
        lang_fail(c, pos, "table '%s': cannot read '%s': %s", table, path, strerror(errno));
    struct stat st;
    if (fstat(fd, &st) != 0) {
        const int err = errno;
        close(fd);
        lang_fail(c, pos, "table '%s': cannot read '%s': %s", table, path, strerror(err));
    }
    if (!S_ISREG(st.st_mode)) {
        close(fd);
        if (given)
            lang_fail(c, pos, "table '%s': '%s', the file named for it, is %s: a table is read "
                      "from a regular file", table, path, file_kind(st.st_mode));
        lang_fail(c, pos, "table '%s': '%s' is %s: " ACCEPTED, table, path,
                  file_kind(st.st_mode), table);
    }
    FILE *fp = fdopen(fd, "r");
    if (!fp) {
        close(fd);
        lang_oom(c);
    }
    return fp;
}

void lang_check_table_files(lang_ctx *c)
{
    for (int k = 0; k < c->n_table_files; k++)
        if (!c->table_file_used[k])
            lang_fail(c, (lpos){0, 0},
                      "a file is named for table '%s', but the model reads no table '%s' from "
                      "a file ('table %s FILE')",
                      c->table_files[k].name, c->table_files[k].name, c->table_files[k].name);
}
