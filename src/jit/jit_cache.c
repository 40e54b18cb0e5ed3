/* SPDX-License-Identifier: BSD-3-Clause */
/* The jit layer's cache directory: where it is ($DYNKIT_CACHE_DIR, $XDG_CACHE_HOME/dynkit,
 * ~/.cache/dynkit), the embedded public headers written into it once per version and header
 * set (checked before each use, jit_trust.c), unique temporary names for concurrent
 * compilations, and the text given to the compilers. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

#include "jit_internal.h"

/* mkdir -p: each missing component created for this user alone (0700) */
static int make_dirs(const char *path, char *err, size_t errlen)
{
    char buf[1024];
    size_t n = strlen(path);
    if (n == 0 || n >= sizeof buf)
        return jit_fail(err, errlen, "cache directory path '%s' is empty or too long", path);
    memcpy(buf, path, n + 1);
    for (size_t i = 1; i <= n; i++) {
        if (buf[i] != '/' && buf[i] != '\0')
            continue;
        char c = buf[i];
        buf[i] = '\0';
        if (mkdir(buf, 0700) != 0 && errno != EEXIST) {
            const int e = errno;
            jit_fail(err, errlen, "cannot create the cache directory %s: %s", buf, strerror(e));
            return jit_cannot_write(e) ? JIT_UNWRITABLE : 1;
        }
        buf[i] = c;
    }
    return 0;
}

int dyn_jit_cache_dir(const dyn_jit_opts *opts, char *buf, size_t size)
{
    const char *env;
    int n;
    if (opts && opts->cache_dir && opts->cache_dir[0])
        n = snprintf(buf, size, "%s", opts->cache_dir);
    else if ((env = getenv("DYNKIT_CACHE_DIR")) && env[0])
        n = snprintf(buf, size, "%s", env);
    else if ((env = getenv("XDG_CACHE_HOME")) && env[0] == '/')
        n = snprintf(buf, size, "%s/dynkit", env);
    else if ((env = getenv("HOME")) && env[0])
        n = snprintf(buf, size, "%s/.cache/dynkit", env);
    else
        return 1;
    return (n < 0 || (size_t)n >= size) ? 1 : 0;
}

int jit_cache_dir(const dyn_jit_opts *opts, char *dir, size_t size, char *err, size_t errlen)
{
    if (dyn_jit_cache_dir(opts, dir, size) != 0)
        return jit_fail(err, errlen,
                        "no cache directory for compiled models: set DYNKIT_CACHE_DIR (or HOME)");
    char given[1024];
    snprintf(given, sizeof given, "%s", dir);
    const int made = make_dirs(given, err, errlen);
    if (made != 0)
        return made;
    return jit_trust_cache_dir(given, dir, size, err, errlen);
}

void jit_unique_path(const char *dir, const char *prefix, const char *suffix, char *out,
                     size_t size)
{
    static _Atomic unsigned long counter;
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    unsigned long n = ++counter;
    snprintf(out, size, "%s/%s%ld-%lu-%lx%lx%s", dir, prefix, (long)getpid(), n,
             (unsigned long)ts.tv_sec, (unsigned long)ts.tv_nsec, suffix);
}

int jit_write_new(const char *path, const void *data, size_t len)
{
    int fd = open(path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0)
        return -1;
    int bad = jit_write_fd(fd, data, len);
    return close(fd) != 0 || bad ? -1 : 0;
}

/* Remove a tree this user wrote (a temporary or replaced headers directory): what belongs to
 * someone else, and what lies deeper than dynkit writes, stays. */
static void remove_tree(const char *path, int depth)
{
    struct stat st;
    if (lstat(path, &st) != 0 || st.st_uid != geteuid())
        return;
    if (!S_ISDIR(st.st_mode)) {
        unlink(path);
        return;
    }
    DIR *d = depth < 3 ? opendir(path) : NULL;
    struct dirent *e;
    char sub[1600];
    while (d && (e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        snprintf(sub, sizeof sub, "%s/%s", path, e->d_name);
        remove_tree(sub, depth + 1);
    }
    if (d)
        closedir(d);
    rmdir(path);
}

int jit_cannot_write(int e)
{
    return e == ENOSPC || e == EDQUOT || e == EROFS || e == EACCES || e == EPERM || e == EFBIG;
}

int jit_move_aside(const char *cache, const char *path, char *moved, size_t size)
{
    jit_unique_path(cache, "tmp-replaced-", "", moved, size);
    if (rename(path, moved) != 0)
        return errno == ENOENT ? 0 : -1; /* gone already: another process moved it */
    remove_tree(moved, 0);
    return 0;
}

void jit_sweep_stale(const char *cache)
{
    DIR *d = opendir(cache);
    if (!d)
        return;
    time_t now = time(NULL);
    struct dirent *e;
    char path[1400];
    while ((e = readdir(d)) != NULL) {
        if (strncmp(e->d_name, "tmp-", 4) != 0)
            continue;
        snprintf(path, sizeof path, "%s/%s", cache, e->d_name);
        struct stat st;
        if (lstat(path, &st) != 0 || st.st_uid != geteuid() || now - st.st_mtime < 3600)
            continue;
        remove_tree(path, 0);
    }
    closedir(d);
}

int jit_include_dir(const char *cache, char *dir, size_t size, char *note, size_t notelen,
                    char *err, size_t errlen)
{
    int n = snprintf(dir, size, "%s/include-%s-%.16s", cache, DYNKIT_VERSION, dyn_jit_headers_hash);
    if (n < 0 || (size_t)n >= size)
        return jit_fail(err, errlen, "cache directory path too long: %s", cache);
    char why[1400], tmp[1024], path[1200];
    int rc = jit_include_check(dir, why, sizeof why, err, errlen);
    if (rc == JIT_OK)
        return 0; /* complete: it appears only by the rename below, and nothing changed it */
    if (rc == JIT_REFUSED)
        return 1;
    if (rc == JIT_STALE) { /* moved aside and removed, then written anew */
        if (jit_move_aside(cache, dir, tmp, sizeof tmp) != 0) {
            const int e = errno;
            jit_fail(err, errlen, "cannot replace %s (%s): %s", dir, why, strerror(e));
            return jit_cannot_write(e) ? JIT_UNWRITABLE : 1;
        }
        char text[1600];
        snprintf(text, sizeof text, "replaced the headers in the cache: %s", why);
        jit_note(note, notelen, text);
    }

    jit_unique_path(cache, "tmp-include-", "", tmp, sizeof tmp);
    snprintf(path, sizeof path, "%s/dynkit", tmp);
    if (mkdir(tmp, 0755) != 0 || mkdir(path, 0755) != 0) {
        int e = errno;
        remove_tree(tmp, 0);
        jit_fail(err, errlen, "cannot write into the cache directory %s: %s", cache, strerror(e));
        return jit_cannot_write(e) ? JIT_UNWRITABLE : 1;
    }
    for (int i = 0; i < dyn_jit_header_count; i++) {
        snprintf(path, sizeof path, "%s/dynkit/%s", tmp, dyn_jit_headers[i].name);
        if (jit_write_new(path, dyn_jit_headers[i].data, dyn_jit_headers[i].size) != 0) {
            int e = errno;
            remove_tree(tmp, 0);
            jit_fail(err, errlen, "cannot write %s: %s", path, strerror(e));
            return jit_cannot_write(e) ? JIT_UNWRITABLE : 1;
        }
    }
    if (rename(tmp, dir) != 0) {
        int e = errno;
        remove_tree(tmp, 0);
        /* another process put the same directory in place first: use it */
        if (jit_include_check(dir, why, sizeof why, err, errlen) == JIT_OK)
            return 0;
        jit_fail(err, errlen, "cannot create %s: %s", dir, strerror(e));
        return jit_cannot_write(e) ? JIT_UNWRITABLE : 1;
    }
    return 0;
}

char *jit_source_with_line(const char *source, size_t len, const char *source_name, size_t *out_len)
{
    const char *name = source_name && source_name[0] ? source_name : "model.c";
    size_t nlen = strlen(name);
    char stamp[160];
    int slen = snprintf(stamp, sizeof stamp,
                        "#line 1 \"<dynkit: model ABI stamp>\"\n"
                        "extern const unsigned dynkit_model_abi;\n"
                        "const unsigned dynkit_model_abi = %uu;\n",
                        (unsigned)DYN_MODEL_ABI);
    char *buf = malloc(16 + 4 * nlen + len + 2 + (size_t)slen);
    if (!buf)
        return NULL;
    size_t k = 0;
    memcpy(buf, "#line 1 \"", 9);
    k = 9;
    /* the name as a string literal by the rule of the model files' C text
     * (src/lang/emit_out.c): printable ASCII as itself (" \ and ? after a backslash, so
     * no trigraph forms), every other byte as a three-digit octal escape */
    for (size_t i = 0; i < nlen; i++) {
        const unsigned char c = (unsigned char)name[i];
        if (c == '"' || c == '\\' || c == '?') {
            buf[k++] = '\\';
            buf[k++] = (char)c;
        } else if (c >= 32 && c < 127) {
            buf[k++] = (char)c;
        } else {
            k += (size_t)snprintf(buf + k, 5, "\\%03o", c);
        }
    }
    buf[k++] = '"';
    buf[k++] = '\n';
    memcpy(buf + k, source, len);
    k += len;
    if (len == 0 || source[len - 1] != '\n')
        buf[k++] = '\n';
    memcpy(buf + k, stamp, (size_t)slen);
    k += (size_t)slen;
    buf[k] = '\0';
    if (out_len)
        *out_len = k;
    return buf;
}
