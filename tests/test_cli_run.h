/* SPDX-License-Identifier: BSD-3-Clause */
/* Running the built dynkit binary (DYNKIT_CLI) from a test: stdout and stderr captured into
 * a temporary directory made by cli_setup (or cli_make_tmpdir), or stdout read through a
 * pipe (cli_capture). Shared by every test that runs the command line; it uses nothing of
 * the library. Needs _POSIX_C_SOURCE >= 200809L. */
#ifndef DYNKIT_TEST_CLI_RUN_H
#define DYNKIT_TEST_CLI_RUN_H

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

static char cli_tmpdir[256];

typedef struct cli_result {
    int status; /* exit status, or -1 if it did not exit normally */
    char *out;  /* stdout (NUL-terminated) */
    size_t out_len;
    char *err;  /* stderr */
} cli_result;

static inline char *cli_read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    size_t cap = 4096, used = 0;
    char *buf = malloc(cap);
    if (!buf)
        abort();
    if (f) {
        size_t got;
        while ((got = fread(buf + used, 1, cap - used - 1, f)) > 0) {
            used += got;
            if (cap - used < 2) {
                cap *= 2;
                buf = realloc(buf, cap);
                if (!buf)
                    abort();
            }
        }
        fclose(f);
    }
    buf[used] = '\0';
    if (len)
        *len = used;
    return buf;
}

static inline void cli_free(cli_result *r)
{
    free(r->out);
    free(r->err);
    r->out = r->err = NULL;
}

/* A path in the temporary directory. */
static inline const char *cli_path(const char *name)
{
    static char path[512];
    snprintf(path, sizeof path, "%s/%s", cli_tmpdir, name);
    return path;
}

/* Run `WRAPPER dynkit ARGS` (ARGS already formatted; WRAPPER e.g. "timeout 20 " or "")
 * from the folder dir (NULL: the current one), capturing stdout and stderr into the
 * temporary directory. */
static inline cli_result cli_run_at(const char *dir, const char *wrapper, const char *args)
{
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "%s%s%s%s'%s' %s >'%s/out' 2>'%s/err' </dev/null",
             dir ? "cd '" : "", dir ? dir : "", dir ? "' && " : "", wrapper, DYNKIT_CLI, args,
             cli_tmpdir, cli_tmpdir);
    cli_result r;
    int w = system(cmd);
    r.status = (w != -1 && WIFEXITED(w)) ? WEXITSTATUS(w) : -1;
    char path[512];
    snprintf(path, sizeof path, "%s/out", cli_tmpdir);
    r.out = cli_read_file(path, &r.out_len);
    snprintf(path, sizeof path, "%s/err", cli_tmpdir);
    r.err = cli_read_file(path, NULL);
    return r;
}

/* Run `dynkit ARGS` (ARGS already formatted), capturing stdout and stderr. With in_tmpdir
 * the command runs from inside the temporary directory, so relative file names in ARGS are
 * there. */
static inline cli_result cli_run_args(int in_tmpdir, const char *args)
{
    return cli_run_at(in_tmpdir ? cli_tmpdir : NULL, "", args);
}

/* Run `dynkit ARGS` (ARGS as for the shell), capturing stdout and stderr. */
static inline cli_result cli(const char *fmt, ...)
{
    char args[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(args, sizeof args, fmt, ap);
    va_end(ap);
    return cli_run_args(0, args);
}

/* As cli, run from inside the temporary directory. */
static inline cli_result cli_in_tmpdir(const char *fmt, ...)
{
    char args[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(args, sizeof args, fmt, ap);
    va_end(ap);
    return cli_run_args(1, args);
}

/* Make the temporary directory $TMPDIR/dynkit_<tag>_XXXXXX ($TMPDIR defaults to /tmp). */
static inline int cli_make_tmpdir(const char *tag)
{
    const char *base = getenv("TMPDIR");
    snprintf(cli_tmpdir, sizeof cli_tmpdir, "%s/dynkit_%s_XXXXXX", base && *base ? base : "/tmp",
             tag);
    return mkdtemp(cli_tmpdir) ? 0 : -1;
}

static inline int cli_setup(void **state)
{
    (void)state;
    return cli_make_tmpdir("test");
}

/* The temporary directory (as cli_make_tmpdir) with a fresh model cache in it, set as
 * DYNKIT_CACHE_DIR for every dynkit the test starts; the cache's path in cache (size). */
static inline int cli_make_tmpdir_with_cache(const char *tag, char *cache, size_t size)
{
    if (cli_make_tmpdir(tag))
        return -1;
    snprintf(cache, size, "%s/cache", cli_tmpdir);
    return setenv("DYNKIT_CACHE_DIR", cache, 1);
}

/* Write text into the file name of the temporary directory; 0, or -1 when it cannot. */
static inline int cli_write_file(const char *name, const char *text)
{
    FILE *f = fopen(cli_path(name), "wb");
    if (!f)
        return -1;
    const int bad = fputs(text, f) < 0;
    return fclose(f) != 0 || bad ? -1 : 0;
}

/* Remove the temporary directory with everything in it (a cmocka group teardown). */
static inline int cli_remove_tmpdir(void **state)
{
    (void)state;
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", cli_tmpdir);
    return system(cmd) == 0 ? 0 : -1;
}

/* Remove the temporary directory and the files named (NULL-terminated) plus out and err. */
static inline int cli_teardown_files(const char *const *files)
{
    unlink(cli_path("out"));
    unlink(cli_path("err"));
    for (int i = 0; files && files[i]; i++)
        unlink(cli_path(files[i]));
    return rmdir(cli_tmpdir);
}

/* Run cmd through the shell and return its stdout (malloc'd); *status gets the exit status
 * (-1 if it did not exit normally). */
static inline char *cli_capture(const char *cmd, int *status)
{
    FILE *f = popen(cmd, "r");
    size_t cap = 1 << 14, len = 0;
    char *buf = malloc(cap);
    if (!f || !buf)
        abort();
    size_t got;
    while ((got = fread(buf + len, 1, cap - len - 1, f)) > 0) {
        len += got;
        if (cap - len < 2) {
            cap *= 2;
            buf = realloc(buf, cap);
            if (!buf)
                abort();
        }
    }
    buf[len] = '\0';
    int st = pclose(f);
    *status = (st != -1 && WIFEXITED(st)) ? WEXITSTATUS(st) : -1;
    return buf;
}

/* 1 if `dynkit methods` lists cvode (dynkit built with SUNDIALS). */
static inline int cli_has_cvode(void)
{
    cli_result r = cli("methods");
    int has = r.status == 0 && (strncmp(r.out, "cvode ", 6) == 0 || strstr(r.out, "\ncvode "));
    cli_free(&r);
    return has;
}

/* Rows of a CSV text (lines after the header). */
static inline long csv_rows(const char *text)
{
    long lines = 0;
    for (const char *p = text; *p; p++)
        lines += *p == '\n';
    return lines > 0 ? lines - 1 : 0;
}

/* The first field (t) of each row into t (at most max); returns the rows. */
static inline long csv_times(const char *text, double *t, long max)
{
    const char *p = strchr(text, '\n');
    long k = 0;
    while (p && p[1] && k < max) {
        t[k++] = strtod(p + 1, NULL);
        p = strchr(p + 1, '\n');
    }
    return k;
}

#endif
