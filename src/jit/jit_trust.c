/* SPDX-License-Identifier: BSD-3-Clause */
/* The trust rules of the jit layer's cache (docs/model-files.md, "Who may write the cache"):
 * the cache directory and every directory above it, the headers directory with each header,
 * and each compiled object are checked for owner and mode before use (lstat, O_NOFOLLOW, and
 * fstat on the opened descriptor). An entry may belong to the user or to root; no one else
 * may write the cache or a directory above it (a sticky directory such as /tmp excepted, as
 * in OpenSSH's safe_path). A compiled object ends with the SHA-256 of its bytes, recomputed
 * on every load, and is loaded from a private copy of the bytes that were checked
 * (memfd_create, then /proc/self/fd/N), so what runs is what was verified. */
#define _GNU_SOURCE /* memfd_create */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <pwd.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include "jit_internal.h"

#define OBJECT_TAG "\ndynkit-object-sha256 "
#define OBJECT_TAG_LEN (sizeof OBJECT_TAG - 1)
#define TRAILER_LEN (OBJECT_TAG_LEN + 64 + 1)
#define OBJECT_MAX ((off_t)1 << 30)

static int owner_ok(uid_t uid) { return uid == geteuid() || uid == 0; }

static void who(uid_t uid, char *buf, size_t size)
{
    struct passwd pw, *res = NULL;
    char tmp[1024];
    if (getpwuid_r(uid, &pw, tmp, sizeof tmp, &res) == 0 && res)
        snprintf(buf, size, "user %s (uid %u)", res->pw_name, (unsigned)uid);
    else
        snprintf(buf, size, "uid %u", (unsigned)uid);
}

/* "you (user NAME (uid N)) or root", or "you (root)" */
static void you(char *buf, size_t size)
{
    char me[160];
    who(geteuid(), me, sizeof me);
    snprintf(buf, size, geteuid() == 0 ? "you (root)" : "you (%s) or root", me);
}

static int refuse_owner(const char *path, uid_t uid, char *err, size_t errlen)
{
    char them[160], me[200];
    who(uid, them, sizeof them);
    you(me, sizeof me);
    return jit_fail(err, errlen,
                    "refusing %s in the cache: it belongs to %s, not to %s, so it may hold "
                    "another user's code: remove it (rm -rf '%s'; the cache is rebuilt as "
                    "needed), or set DYNKIT_CACHE_DIR to a directory of your own",
                    path, them, me, path);
}

static void say(char *why, size_t whylen, const char *fmt, const char *path, unsigned mode)
{
    if (why && whylen)
        snprintf(why, whylen, fmt, path, mode);
}

/* ---- the cache directory ---- */

int jit_trust_cache_dir(const char *path, char *canon, size_t size, char *err, size_t errlen)
{
    char *real = realpath(path, NULL);
    if (!real)
        return jit_fail(err, errlen, "cannot use the cache directory %s: %s", path,
                        strerror(errno));
    if (strlen(real) >= size) {
        free(real);
        return jit_fail(err, errlen, "cache directory path too long: %s", path);
    }
    strcpy(canon, real);
    free(real);
    struct stat st;
    if (lstat(canon, &st) != 0 || !S_ISDIR(st.st_mode))
        return jit_fail(err, errlen, "the cache directory %s is not a directory", canon);
    char me[200], them[160];
    you(me, sizeof me);
    if (!owner_ok(st.st_uid)) {
        who(st.st_uid, them, sizeof them);
        return jit_fail(err, errlen,
                        "refusing the cache directory %s: it belongs to %s, not to %s, and a "
                        "compiled model in it would run as you: set DYNKIT_CACHE_DIR to a "
                        "directory of your own",
                        canon, them, me);
    }
    if (st.st_mode & 022)
        return jit_fail(err, errlen,
                        "refusing the cache directory %s: it is writable by %s (mode %04o), who "
                        "could put code in it that would run as you: chmod go-w '%s' and remove "
                        "what you did not put there, or set DYNKIT_CACHE_DIR to a directory of "
                        "your own",
                        canon, (st.st_mode & 002) ? "everyone" : "its group",
                        (unsigned)(st.st_mode & 07777), canon);
    /* every directory above: a writer there could move the cache away and put another */
    char up[1024];
    snprintf(up, sizeof up, "%s", canon);
    while (strcmp(up, "/") != 0) {
        char *slash = strrchr(up, '/');
        if (!slash)
            break;
        if (slash == up)
            slash[1] = '\0';
        else
            *slash = '\0';
        if (lstat(up, &st) != 0)
            return jit_fail(err, errlen, "cannot check %s above the cache directory: %s", up,
                            strerror(errno));
        const int open_to_others = (st.st_mode & 022) && !(st.st_mode & S_ISVTX);
        if (!owner_ok(st.st_uid) || open_to_others) {
            if (!owner_ok(st.st_uid))
                who(st.st_uid, them, sizeof them);
            else
                snprintf(them, sizeof them, "%s (mode %04o, no sticky bit)",
                         (st.st_mode & 002) ? "everyone" : "its group",
                         (unsigned)(st.st_mode & 07777));
            return jit_fail(err, errlen,
                            "refusing the cache directory %s: the directory %s above it is "
                            "writable by %s, who could put another cache in its place: "
                            "chmod go-w '%s' if it is yours, or set DYNKIT_CACHE_DIR to a "
                            "directory whose parents belong to you or root and are not "
                            "writable by others",
                            canon, up, them, up);
        }
    }
    return 0;
}

/* ---- entries of the cache ---- */

/* lstat'ed entry st at path: OK, STALE (why), or REFUSED (err); dir: a directory expected */
static int check_entry(const char *path, const struct stat *st, int dir, char *why, size_t whylen,
                       char *err, size_t errlen)
{
    if (!owner_ok(st->st_uid)) {
        refuse_owner(path, st->st_uid, err, errlen);
        return JIT_REFUSED;
    }
    if (S_ISLNK(st->st_mode)) {
        say(why, whylen, "%s is a symbolic link", path, 0);
        return JIT_STALE;
    }
    if (dir ? !S_ISDIR(st->st_mode) : !S_ISREG(st->st_mode)) {
        say(why, whylen, dir ? "%s is not a directory" : "%s is not a regular file", path, 0);
        return JIT_STALE;
    }
    if (st->st_mode & 022) {
        say(why, whylen, "%s is writable by its group or others (mode %04o)", path,
            (unsigned)(st->st_mode & 07777));
        return JIT_STALE;
    }
    return JIT_OK;
}

/* open path without following a link and check the open file: JIT_OK with *fd, else as
 * check_entry (JIT_ABSENT when there is nothing) */
static int open_entry(const char *path, int *fd, struct stat *st, char *why, size_t whylen,
                      char *err, size_t errlen)
{
    *fd = open(path, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (*fd < 0) {
        int e = errno;
        if (e == ENOENT)
            return JIT_ABSENT;
        if (lstat(path, st) == 0) {
            int rc = check_entry(path, st, 0, why, whylen, err, errlen);
            if (rc != JIT_OK)
                return rc;
        }
        snprintf(why, whylen, "%s cannot be opened: %s", path, strerror(e));
        return JIT_STALE;
    }
    int rc = fstat(*fd, st) != 0 ? JIT_STALE : check_entry(path, st, 0, why, whylen, err, errlen);
    if (rc != JIT_OK) {
        close(*fd);
        *fd = -1;
    }
    return rc;
}

static int read_all(int fd, unsigned char *buf, size_t len)
{
    size_t got = 0;
    while (got < len) {
        ssize_t r = pread(fd, buf + got, len - got, (off_t)got);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            return -1;
        got += (size_t)r;
    }
    return 0;
}

int jit_write_fd(int fd, const void *data, size_t len)
{
    const char *p = data;
    while (len > 0) {
        ssize_t w = write(fd, p, len);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return -1;
        p += w;
        len -= (size_t)w;
    }
    return 0;
}

/* The trailer of an object: the SHA-256 of its file name (which holds its key) and its
 * bytes, so that an object copied under another model's name does not pass either. */
static void trailer_of(const char *path, const unsigned char *data, size_t len,
                       char out[TRAILER_LEN + 1])
{
    jit_sha256 h;
    char hex[65];
    const char *name = strrchr(path, '/');
    name = name ? name + 1 : path;
    jit_sha256_init(&h);
    jit_sha256_update(&h, name, strlen(name) + 1);
    jit_sha256_update(&h, data, len);
    jit_sha256_hex(&h, hex);
    snprintf(out, TRAILER_LEN + 1, "%s%s\n", OBJECT_TAG, hex);
}

int jit_object_seal(const char *path, const char *final, char *err, size_t errlen)
{
    int fd = open(path, O_RDWR | O_NOFOLLOW | O_CLOEXEC);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size > OBJECT_MAX) {
        int e = errno;
        if (fd >= 0)
            close(fd);
        return jit_fail(err, errlen, "cannot read the compiled model %s: %s", path,
                        fd < 0 ? strerror(e) : "not a regular file of at most 1 GiB");
    }
    size_t len = (size_t)st.st_size;
    unsigned char *data = malloc(len ? len : 1);
    char trailer[TRAILER_LEN + 1];
    int bad = !data || read_all(fd, data, len) != 0;
    if (!bad) {
        trailer_of(final, data, len, trailer);
        bad = lseek(fd, 0, SEEK_END) < 0 || jit_write_fd(fd, trailer, TRAILER_LEN) != 0;
    }
    int e = bad ? errno : 0;
    free(data);
    if (close(fd) != 0 && !bad)
        e = errno, bad = 1;
    if (bad) {
        jit_fail(err, errlen, "cannot record the hash of the compiled model %s: %s", path,
                 strerror(e));
        errno = e; /* the caller tells a full disk from other failures */
        return 1;
    }
    return 0;
}

int jit_object_open(const char *path, int *out_fd, char *why, size_t whylen, char *err,
                    size_t errlen)
{
    *out_fd = -1;
    why[0] = '\0';
    int fd;
    struct stat st;
    int rc = open_entry(path, &fd, &st, why, whylen, err, errlen);
    if (rc != JIT_OK)
        return rc;
    if (st.st_size < (off_t)TRAILER_LEN || st.st_size > OBJECT_MAX) {
        close(fd);
        snprintf(why, whylen, "%s is %s (%lld bytes)", path,
                 st.st_size < (off_t)TRAILER_LEN ? "truncated" : "too large",
                 (long long)st.st_size);
        return JIT_STALE;
    }
    size_t len = (size_t)st.st_size, body = len - TRAILER_LEN;
    unsigned char *data = malloc(len);
    if (!data || read_all(fd, data, len) != 0) {
        free(data);
        close(fd);
        snprintf(why, whylen, "%s cannot be read", path);
        return JIT_STALE;
    }
    close(fd);
    char trailer[TRAILER_LEN + 1];
    trailer_of(path, data, body, trailer);
    if (memcmp(trailer, data + body, TRAILER_LEN) != 0) {
        free(data);
        snprintf(why, whylen,
                 "%s does not match the SHA-256 it records (it was truncated or changed)", path);
        return JIT_STALE;
    }
    /* a private copy of the checked bytes: no one can change what is loaded */
#ifdef MFD_CLOEXEC
    int mfd = memfd_create("dynkit-model", MFD_CLOEXEC);
    if (mfd >= 0 && jit_write_fd(mfd, data, body) != 0) {
        close(mfd);
        mfd = -1;
    }
    *out_fd = mfd; /* -1 when memfd_create is missing: the checked path is loaded */
#endif
    free(data);
    return JIT_OK;
}

/* ---- the headers directory ---- */

static int header_index(const char *name)
{
    for (int i = 0; i < dyn_jit_header_count; i++)
        if (strcmp(dyn_jit_headers[i].name, name) == 0)
            return i;
    return -1;
}

static int check_header(const char *path, int i, char *why, size_t whylen, char *err,
                        size_t errlen)
{
    int fd;
    struct stat st;
    int rc = open_entry(path, &fd, &st, why, whylen, err, errlen);
    if (rc != JIT_OK)
        return rc == JIT_ABSENT ? JIT_STALE : rc;
    const dyn_jit_header *h = &dyn_jit_headers[i];
    unsigned char *data = malloc(h->size + 1);
    int same = data && (size_t)st.st_size == h->size && read_all(fd, data, h->size) == 0 &&
               memcmp(data, h->data, h->size) == 0;
    free(data);
    close(fd);
    if (!same) {
        snprintf(why, whylen, "%s differs from the header this dynkit holds", path);
        return JIT_STALE;
    }
    return JIT_OK;
}

/* dir holds exactly what dynkit writes there (headers: the embedded headers, else dynkit/),
 * each checked */
static int check_listing(const char *dir, int headers, char *why, size_t whylen, char *err,
                         size_t errlen)
{
    DIR *d = opendir(dir);
    if (!d) {
        snprintf(why, whylen, "%s cannot be read: %s", dir, strerror(errno));
        return JIT_STALE;
    }
    int rc = JIT_OK, found = 0;
    struct dirent *e;
    char path[1600];
    while (rc == JIT_OK && (e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        struct stat st;
        if (lstat(path, &st) != 0) {
            snprintf(why, whylen, "%s cannot be checked: %s", path, strerror(errno));
            rc = JIT_STALE;
            break;
        }
        if (!owner_ok(st.st_uid)) {
            refuse_owner(path, st.st_uid, err, errlen);
            rc = JIT_REFUSED;
            break;
        }
        int i = headers ? header_index(e->d_name) : (strcmp(e->d_name, "dynkit") == 0 ? 0 : -1);
        if (i < 0) {
            snprintf(why, whylen, "%s is not a file dynkit writes there", path);
            rc = JIT_STALE;
        } else if (headers) {
            rc = check_header(path, i, why, whylen, err, errlen);
        } else if ((rc = check_entry(path, &st, 1, why, whylen, err, errlen)) == JIT_OK) {
            rc = check_listing(path, 1, why, whylen, err, errlen);
        }
        found++;
    }
    closedir(d);
    if (rc == JIT_OK && found != (headers ? dyn_jit_header_count : 1)) {
        snprintf(why, whylen, "%s misses %s", dir, headers ? "a header" : "dynkit/");
        rc = JIT_STALE;
    }
    return rc;
}

int jit_include_check(const char *dir, char *why, size_t whylen, char *err, size_t errlen)
{
    why[0] = '\0';
    struct stat st;
    if (lstat(dir, &st) != 0)
        return errno == ENOENT ? JIT_ABSENT : JIT_STALE;
    int rc = check_entry(dir, &st, 1, why, whylen, err, errlen);
    return rc != JIT_OK ? rc : check_listing(dir, 0, why, whylen, err, errlen);
}
