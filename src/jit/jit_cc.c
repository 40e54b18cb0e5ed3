/* SPDX-License-Identifier: BSD-3-Clause */
/* The system C compiler backend of the jit layer: the model's source compiled into a shared
 * object in the cache directory, named by the SHA-256 of (source, source name, dynkit's
 * version, the model ABI, the embedded headers, the compiler command and flags). A cached
 * run only dlopens. Concurrent runs compile to unique temporary names and rename(2) the
 * result into place, so a reader never sees a half-written file. The compiler runs through
 * posix_spawnp with an argument vector (no shell), its diagnostics captured for the caller,
 * within a time limit; large sources get a lower optimisation level. What is read from the
 * cache is checked first (jit_trust.c). */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "jit_internal.h"

extern char **environ;

#define MAX_ARGS 64
/* The optimisation level by the size of the source (docs/model-files.md, "Large models"):
 * -O2 costs little to compile a small source; from 256 KiB -O1, whose code is as fast and
 * which compiles in less time; above 1 MiB (given to cc only when it is named: DYN_JIT_AUTO
 * takes libtcc) -O0, whose compile time grows with the source, not faster (-O1: 51 s for
 * 1.6 MB of chained fixed quantities, -O2 69 s; -O0: 2.2 s). */
#define DEFAULT_CFLAGS "-O2"
#define LARGE_CFLAGS "-O1"
#define HUGE_CFLAGS "-O0"
#define DEFAULT_TIMEOUT 60.0 /* seconds; DYNKIT_CC_TIMEOUT */
#define RUN_TIMEOUT 1000     /* run(): the time limit was reached */
/* Always passed before the flags (which may override it): no contraction of a*b + c into
 * fused multiply-adds, so that a model computes the same numbers as the library (compiled as
 * ISO C, where GCC does not contract) whatever the target and the compiler's default. */
#define FIXED_CFLAGS "-ffp-contract=off"
#define MAX_OUTPUT (256 * 1024) /* compiler output kept */

/* An argument vector whose strings live in the struct itself. */
typedef struct words {
    char arena[8192];
    size_t used;
    char *argv[MAX_ARGS + 1];
    int n;
} words;

static int add_word(words *w, const char *s, size_t len)
{
    if (w->n >= MAX_ARGS || w->used + len + 1 > sizeof w->arena)
        return 1;
    char *p = w->arena + w->used;
    memcpy(p, s, len);
    p[len] = '\0';
    w->used += len + 1;
    w->argv[w->n++] = p;
    w->argv[w->n] = NULL;
    return 0;
}

/* Split s at blanks; a command that names an existing file as a whole (a path with blanks)
 * stays one word. */
static int add_split(words *w, const char *s, int whole_if_file)
{
    if (whole_if_file && strpbrk(s, " \t") && access(s, X_OK) == 0)
        return add_word(w, s, strlen(s));
    while (*s) {
        while (*s == ' ' || *s == '\t' || *s == '\n')
            s++;
        size_t len = strcspn(s, " \t\n");
        if (len > 0 && add_word(w, s, len) != 0)
            return 1;
        s += len;
    }
    return 0;
}

static const char *pick(const char *given, const char *env1, const char *env2, const char *fallback)
{
    const char *v;
    if (given && given[0])
        return given;
    if (env1 && (v = getenv(env1)) && v[0])
        return v;
    if (env2 && (v = getenv(env2)) && v[0])
        return v;
    return fallback;
}

/* The compiler's output: the first MAX_OUTPUT bytes. */
typedef struct capture {
    char *buf;
    size_t len, cap;
} capture;

static void capture_add(capture *c, const char *p, size_t n)
{
    if (c->len + n > MAX_OUTPUT)
        n = MAX_OUTPUT - c->len;
    if (n == 0)
        return;
    if (c->len + n + 1 > c->cap) {
        size_t cap = c->cap ? c->cap : 4096;
        while (cap < c->len + n + 1)
            cap *= 2;
        char *b = realloc(c->buf, cap);
        if (!b)
            return;
        c->buf = b;
        c->cap = cap;
    }
    memcpy(c->buf + c->len, p, n);
    c->len += n;
    c->buf[c->len] = '\0';
}

/* The parent of process pid (from /proc/PID/stat), or -1. */
static pid_t parent_of(pid_t pid)
{
    char path[64], line[512];
    snprintf(path, sizeof path, "/proc/%ld/stat", (long)pid);
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    size_t n = fread(line, 1, sizeof line - 1, f);
    fclose(f);
    line[n] = '\0';
    const char *close_paren = strrchr(line, ')'); /* the command name may hold anything */
    long ppid;
    return close_paren && sscanf(close_paren + 1, " %*c %ld", &ppid) == 1 ? (pid_t)ppid : -1;
}

/* SIGKILL pid and the processes it started (the compiler driver's cc1, as, collect2, ld):
 * each stopped first, so that it starts no more, found through /proc where there is one. The
 * compiler stays in the caller's process group, so that Ctrl-C still reaches it. */
static void kill_tree(pid_t pid)
{
    enum { MAX_TREE = 64 };
    pid_t tree[MAX_TREE];
    int n = 1, grown = 1;
    tree[0] = pid;
    kill(pid, SIGSTOP);
    for (int round = 0; grown && round < 16; round++) {
        grown = 0;
        DIR *d = opendir("/proc");
        struct dirent *e;
        while (d && n < MAX_TREE && (e = readdir(d)) != NULL) {
            char *end;
            long p = strtol(e->d_name, &end, 10);
            if (*end != '\0' || p <= 0)
                continue;
            pid_t parent = parent_of((pid_t)p);
            int known = 0, under = 0;
            for (int i = 0; i < n; i++) {
                known |= tree[i] == (pid_t)p;
                under |= tree[i] == parent;
            }
            if (under && !known) {
                kill((pid_t)p, SIGSTOP);
                tree[n++] = (pid_t)p;
                grown = 1;
            }
        }
        if (d)
            closedir(d);
    }
    for (int i = n - 1; i >= 0; i--)
        kill(tree[i], SIGKILL);
}

/* Run argv with stdin from /dev/null and stdout+stderr into out, killed with what it started
 * (kill_tree) after `limit` seconds. Returns the exit status (0..255), 256 + signal when
 * killed, RUN_TIMEOUT when the limit was reached, or -errno when it could not start. */
static int run(char *const argv[], double limit, capture *out)
{
    int fds[2];
    if (pipe(fds) != 0)
        return -errno;
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&fa, fds[1], 1);
    posix_spawn_file_actions_adddup2(&fa, fds[1], 2);
    posix_spawn_file_actions_addclose(&fa, fds[0]);
    posix_spawn_file_actions_addclose(&fa, fds[1]);
    pid_t pid;
    int rc = posix_spawnp(&pid, argv[0], &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    close(fds[1]);
    if (rc != 0) {
        close(fds[0]);
        return -rc;
    }
    const double deadline = jit_now() + limit;
    int timed_out = 0;
    char chunk[4096];
    for (;;) {
        double left = deadline - jit_now();
        if (left <= 0) {
            timed_out = 1;
            break;
        }
        struct pollfd p = {.fd = fds[0], .events = POLLIN};
        int ready = poll(&p, 1, left > 3600 ? 3600000 : (int)(left * 1000) + 1);
        if (ready < 0 && errno != EINTR)
            break;
        if (ready <= 0)
            continue;
        ssize_t r = read(fds[0], chunk, sizeof chunk);
        if (r > 0)
            capture_add(out, chunk, (size_t)r);
        else if (r == 0 || errno != EINTR)
            break;
    }
    close(fds[0]);
    if (timed_out)
        kill_tree(pid);
    int status;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return -errno;
    if (timed_out)
        return RUN_TIMEOUT;
    if (WIFEXITED(status))
        return WEXITSTATUS(status);
    return 256 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

/* The time limit of the compiler: opts, else $DYNKIT_CC_TIMEOUT, else DEFAULT_TIMEOUT. */
static int time_limit(const dyn_jit_opts *opts, double *limit, char *err, size_t errlen)
{
    *limit = DEFAULT_TIMEOUT;
    if (opts && opts->cc_timeout > 0) {
        *limit = opts->cc_timeout;
        return 0;
    }
    const char *env = getenv("DYNKIT_CC_TIMEOUT");
    if (!env || !env[0])
        return 0;
    char *end = NULL;
    errno = 0;
    /* decimal only: strtod would also read hexadecimal (0x10 = 16), inf and nan */
    const int decimal = strspn(env, "0123456789.eE+-") == strlen(env);
    double v = decimal ? strtod(env, &end) : 0.0;
    if (!decimal || end == env || *end != '\0' || errno || !isfinite(v) || v <= 0)
        return jit_fail(err, errlen,
                        "DYNKIT_CC_TIMEOUT=%s is not a number of seconds > 0 written in decimal "
                        "(e.g. 30 or 2.5: the time the C compiler may take for one model, %g s "
                        "when unset)",
                        env, DEFAULT_TIMEOUT);
    *limit = v;
    return 0;
}

/* "head: text" into err, cut at a line end when the room is short, with a note of how many
 * lines were left out (the first diagnostics are the ones that matter). */
static void report_output(char *err, size_t errlen, const char *head, const char *text)
{
    if (!err || errlen == 0)
        return;
    int n = snprintf(err, errlen, "%s", head);
    size_t used = n < 0 ? 0 : (size_t)n;
    if (used >= errlen - 1 || !text)
        return;
    size_t len = strlen(text);
    while (len > 0 && (text[len - 1] == '\n' || text[len - 1] == ' '))
        len--;
    size_t room = errlen - 1 - used;
    if (len <= room) {
        memcpy(err + used, text, len);
        err[used + len] = '\0';
        return;
    }
    const size_t cut = room > 40 ? room - 40 : 0;
    size_t keep = cut;
    while (keep > 0 && text[keep] != '\n')
        keep--;
    int more = keep > 0 ? 0 : 1; /* a first line longer than the room: cut inside it */
    if (keep == 0)
        keep = cut;
    for (size_t i = keep; i < len; i++)
        more += text[i] == '\n';
    memcpy(err + used, text, keep);
    snprintf(err + used + keep, errlen - used - keep, "\n[... %d more line%s]", more,
             more == 1 ? "" : "s");
}

/* A readable stem for the cached file: the source's base name without its extension. */
static void stem_of(const char *name, char *stem, size_t size)
{
    const char *b = name ? strrchr(name, '/') : NULL;
    b = b ? b + 1 : (name ? name : "model");
    size_t k = 0;
    for (; *b && *b != '.' && k + 1 < size && k < 40; b++)
        stem[k++] = ((*b >= 'a' && *b <= 'z') || (*b >= 'A' && *b <= 'Z') ||
                     (*b >= '0' && *b <= '9') || *b == '_' || *b == '-')
                        ? *b
                        : '_';
    if (k == 0)
        stem[k++] = 'm';
    stem[k] = '\0';
}

/* The cache cannot be written (the message in err): its first line into out->note, what to
 * do appended to err, JIT_UNWRITABLE returned, so that dyn_jit_load_source may compile in
 * memory with libtcc. */
static int unwritable(dyn_jit_model *out, char *err, size_t errlen)
{
    if (!err || errlen == 0) {
        snprintf(out->note, sizeof out->note, "the cache of compiled models cannot be written");
        return JIT_UNWRITABLE;
    }
    snprintf(out->note, sizeof out->note, "%.*s", (int)strcspn(err, "\n"), err);
    const size_t used = strlen(err);
    snprintf(err + used, errlen - used,
             "\n(the cache of compiled models cannot be written: free some space, or set "
             "DYNKIT_CACHE_DIR to a directory that can be written%s)",
             dyn_jit_backend_available(DYN_JIT_TCC) ? ", or compile in memory: DYNKIT_JIT=tcc"
                                                    : "");
    return JIT_UNWRITABLE;
}

/* The reason, when the compiler failed for want of room or of a writable disk (its output
 * says so, or it was killed by SIGXFSZ, the file size limit), else NULL. */
static const char *disk_failure(int status, const char *output)
{
    static const char *const reasons[] = {"No space left on device", "Disk quota exceeded",
                                          "File too large", "Read-only file system"};
#ifdef SIGXFSZ
    if (status == 256 + SIGXFSZ)
        return "File size limit exceeded";
#endif
    for (size_t i = 0; output && i < sizeof reasons / sizeof reasons[0]; i++)
        if (strstr(output, reasons[i]))
            return reasons[i];
    return NULL;
}

/* An entry under an object's name that a compiled object cannot replace by rename(2) (a
 * directory, or another file that is not a regular file nor a link) moved aside, said in
 * note; 0, or non-zero with a message (JIT_UNWRITABLE as jit_cannot_write says). */
static int clear_object_name(const char *cache, const char *so, char *note, size_t notelen,
                             char *err, size_t errlen)
{
    struct stat st;
    if (lstat(so, &st) != 0 || S_ISREG(st.st_mode) || S_ISLNK(st.st_mode))
        return 0;
    char moved[1200], text[1400];
    if (jit_move_aside(cache, so, moved, sizeof moved) != 0) {
        const int e = errno;
        jit_fail(err, errlen,
                 "%s in the cache is not a regular file and cannot be moved aside (%s): remove "
                 "it (rm -rf '%s'; the cache is rebuilt as needed)",
                 so, strerror(e), so);
        return jit_cannot_write(e) ? JIT_UNWRITABLE : 1;
    }
    const char *base = strrchr(moved, '/');
    snprintf(text, sizeof text, "moved it aside to %s", base ? base + 1 : moved);
    jit_note(note, notelen, text);
    return 0;
}

int jit_cc_load(const char *source, size_t len, const char *source_name, const dyn_jit_opts *opts,
                dyn_jit_model *out, char *err, size_t errlen)
{
    const char *where = source_name && source_name[0] ? source_name : "model.c";
    char cache[1024], inc[1100];
    int made = jit_cache_dir(opts, cache, sizeof cache, err, errlen);
    if (made != 0)
        return made == JIT_UNWRITABLE ? unwritable(out, err, errlen) : 1;
    const char *cc = pick(opts ? opts->cc : NULL, "DYNKIT_CC", "CC", "cc");
    const char *cflags = pick(opts ? opts->cflags : NULL, "DYNKIT_CFLAGS", NULL,
                              len > JIT_CC_LARGE_SOURCE  ? HUGE_CFLAGS
                              : len > JIT_CC_O2_SOURCE ? LARGE_CFLAGS
                                                       : DEFAULT_CFLAGS);
    double limit;
    if (time_limit(opts, &limit, err, errlen) != 0)
        return 1;

    words *argv = malloc(sizeof *argv); /* 9 KB: not on the stack */
    if (!argv)
        return jit_fail(err, errlen, "out of memory");
    argv->used = 0;
    argv->n = 0;
    argv->argv[0] = NULL;
    if (add_split(argv, cc, 1) != 0 || argv->n == 0 || add_split(argv, FIXED_CFLAGS, 0) != 0 ||
        add_split(argv, cflags, 0) != 0 || add_split(argv, "-fPIC -shared", 0) != 0) {
        free(argv);
        return jit_fail(err, errlen, "the compiler command is empty or too long: %s %s", cc,
                        cflags);
    }
    int n_command = argv->n;

    /* the key: everything that changes the compiled code */
    char key[65], ver[64];
    jit_sha256 h;
    jit_sha256_init(&h);
    /* "cc2": objects end with the SHA-256 of their bytes (jit_object_seal) */
    snprintf(ver, sizeof ver, "dynkit-jit-cc2 %s abi %d ", DYNKIT_VERSION, DYN_MODEL_ABI);
    jit_sha256_update(&h, ver, strlen(ver) + 1);
    jit_sha256_update(&h, dyn_jit_headers_hash, strlen(dyn_jit_headers_hash) + 1);
    for (int i = 0; i < n_command; i++)
        jit_sha256_update(&h, argv->argv[i], strlen(argv->argv[i]) + 1);
    jit_sha256_update(&h, where, strlen(where) + 1);
    jit_sha256_update(&h, source, len);
    jit_sha256_hex(&h, key);

    char stem[48], so[1200];
    stem_of(where, stem, sizeof stem);
    int k = snprintf(so, sizeof so, "%s/%s-%.32s.so", cache, stem, key);
    if (k < 0 || (size_t)k >= sizeof so || (size_t)k >= sizeof out->so_path) {
        free(argv);
        return jit_fail(err, errlen, "cache directory path too long: %s", cache);
    }

    char note[sizeof out->note] = "", why[1400];
    int fd;
    int state = jit_object_open(so, &fd, why, sizeof why, err, errlen);
    if (state == JIT_REFUSED) {
        free(argv);
        return 1;
    }
    if (state == JIT_OK) {
        free(argv);
        if (jit_load_so(so, fd, where, out, err, errlen) != 0)
            return 1;
        out->cached = 1;
        return 0;
    }
    if (state == JIT_STALE) { /* replaced by the rename below */
        char text[1600];
        snprintf(text, sizeof text, "compiled again: %s", why);
        jit_note(note, sizeof note, text);
        if ((made = clear_object_name(cache, so, note, sizeof note, err, errlen)) != 0) {
            free(argv);
            return made == JIT_UNWRITABLE ? unwritable(out, err, errlen) : 1;
        }
    }

    jit_sweep_stale(cache); /* rare: on a compilation only */
    if ((made = jit_include_dir(cache, inc, sizeof inc, note, sizeof note, err, errlen)) != 0) {
        free(argv);
        return made == JIT_UNWRITABLE ? unwritable(out, err, errlen) : 1;
    }
    char tmp_c[1200], tmp_so[1200];
    jit_unique_path(cache, "tmp-", ".c", tmp_c, sizeof tmp_c);
    jit_unique_path(cache, "tmp-", ".so", tmp_so, sizeof tmp_so);
    size_t text_len;
    char *text = jit_source_with_line(source, len, where, &text_len);
    if (!text) {
        free(argv);
        return jit_fail(err, errlen, "out of memory");
    }
    if (jit_write_new(tmp_c, text, text_len) != 0) {
        int e = errno;
        free(text);
        free(argv);
        unlink(tmp_c);
        jit_fail(err, errlen, "cannot write into the cache directory %s: %s", cache, strerror(e));
        return jit_cannot_write(e) ? unwritable(out, err, errlen) : 1;
    }
    free(text);
    if (add_word(argv, "-I", 2) || add_word(argv, inc, strlen(inc)) || add_word(argv, "-o", 2) ||
        add_word(argv, tmp_so, strlen(tmp_so)) || add_word(argv, tmp_c, strlen(tmp_c)) ||
        add_word(argv, "-lm", 3)) {
        unlink(tmp_c);
        free(argv);
        return jit_fail(err, errlen, "the compiler command is too long");
    }

    capture output = {0};
    double t_start = jit_now();
    int status = run(argv->argv, limit, &output);
    double seconds = jit_now() - t_start;
    unlink(tmp_c);
    int rc = 0;
    if (status < 0) {
        if (-status == ENOENT)
            rc = 1 + jit_fail(err, errlen,
                              "cannot compile %s: the C compiler '%s' was not found: install one "
                              "(apt-get install gcc), or set DYNKIT_CC to a C compiler%s",
                              where, argv->argv[0],
                              dyn_jit_backend_available(DYN_JIT_TCC)
                                  ? ", or use the built-in libtcc (DYNKIT_JIT=tcc)"
                                  : "");
        else
            rc = jit_fail(err, errlen, "cannot run the C compiler '%s': %s", argv->argv[0],
                          strerror(-status));
    } else if (status == RUN_TIMEOUT) {
        jit_fail(err, errlen,
                 "compiling %s: the C compiler '%s' did not finish within %g s and was stopped "
                 "(the bound is DYNKIT_CC_TIMEOUT, in seconds: raise it, or compile with "
                 "libtcc: DYNKIT_JIT=tcc)",
                 where, argv->argv[0], limit);
        snprintf(out->note, sizeof out->note,
                 "the C compiler '%.200s' did not finish within %g s (DYNKIT_CC_TIMEOUT=SECONDS "
                 "allows more)",
                 argv->argv[0], limit);
        rc = 3;
    } else if (status != 0) {
        char head[600];
        const char *disk = disk_failure(status, output.buf);
        if (disk)
            snprintf(head, sizeof head,
                     "compiling %s: the C compiler '%s' could not write its output (%s):\n", where,
                     argv->argv[0], disk);
        else if (status > 255)
            snprintf(head, sizeof head, "compiling %s: the compiler '%s' was killed (signal %d)\n",
                     where, argv->argv[0], status - 256);
        else if (output.len == 0)
            snprintf(head, sizeof head,
                     "compiling %s: the compiler '%s' failed (exit status %d) without a message",
                     where, argv->argv[0], status);
        else
            head[0] = '\0';
        report_output(err, errlen, head, output.buf);
        rc = 1;
        if (disk) {
            unwritable(out, err, errlen);
            snprintf(out->note, sizeof out->note,
                     "the C compiler '%.200s' could not write its output (%s)", argv->argv[0],
                     disk);
            rc = JIT_UNWRITABLE;
        }
    }
    free(output.buf);
    free(argv);
    if (rc != 0) {
        unlink(tmp_so);
        return rc;
    }
    if (jit_object_seal(tmp_so, so, err, errlen) != 0) {
        const int e = errno;
        unlink(tmp_so);
        return jit_cannot_write(e) ? unwritable(out, err, errlen) : 1;
    }
    if (rename(tmp_so, so) != 0) {
        int e = errno;
        unlink(tmp_so);
        jit_fail(err, errlen, "cannot put the compiled model in place (%s): %s", so, strerror(e));
        return jit_cannot_write(e) ? unwritable(out, err, errlen) : 1;
    }
    state = jit_object_open(so, &fd, why, sizeof why, err, errlen);
    if (state == JIT_REFUSED)
        return 1;
    if (state != JIT_OK)
        return jit_fail(err, errlen, "the model just compiled cannot be loaded: %s", why);
    if (jit_load_so(so, fd, where, out, err, errlen) != 0)
        return 1;
    out->cached = 0;
    out->compile_seconds = seconds;
    snprintf(out->note, sizeof out->note, "%s", note);
    return 0;
}
