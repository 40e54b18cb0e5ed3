/* SPDX-License-Identifier: BSD-3-Clause */
/* Output files that a failed run never destroys: a regular file (or a new one) is written
 * under a temporary name in the same directory and renamed over the real name only when the
 * command keeps it; devices, pipes and standard output are written directly. Also: the
 * check that two options do not name the same file, and the check of standard output at
 * exit. */
#define _XOPEN_SOURCE 700
#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "util/out_file.h"

/* The directory part of path ("." when it has none) into buf. */
static void dir_of(const char *path, char *buf, size_t size)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        snprintf(buf, size, ".");
    else if (slash == path)
        snprintf(buf, size, "/");
    else
        snprintf(buf, size, "%.*s", (int)(slash - path), path);
}

/* ---- the files the command reads, which no output may replace ---- */

#define MAX_INPUTS 64
static struct {
    dev_t dev;
    ino_t ino;
    const char *what;
} inputs[MAX_INPUTS];
static int n_inputs;

void cli_input_note(const char *path, const char *what)
{
    struct stat st;
    if (!path || n_inputs == MAX_INPUTS || stat(path, &st) != 0 || !S_ISREG(st.st_mode))
        return;
    for (int i = 0; i < n_inputs; i++)
        if (inputs[i].dev == st.st_dev && inputs[i].ino == st.st_ino)
            return;
    inputs[n_inputs].dev = st.st_dev;
    inputs[n_inputs].ino = st.st_ino;
    inputs[n_inputs].what = what;
    n_inputs++;
}

const char *cli_input_named(const char *path)
{
    struct stat st;
    if (!path || strcmp(path, "-") == 0 || stat(path, &st) != 0 || !S_ISREG(st.st_mode))
        return NULL; /* a file not there yet is no input */
    for (int i = 0; i < n_inputs; i++)
        if (inputs[i].dev == st.st_dev && inputs[i].ino == st.st_ino)
            return inputs[i].what;
    return NULL;
}

int cli_is_stdout_format(const char *path)
{
    if (!path || path[0] != '-' || path[1] != '.' || !path[2])
        return 0;
    for (const char *p = path + 2; *p; p++)
        if (!isalnum((unsigned char)*p))
            return 0;
    return 1;
}

int cli_is_stdout_name(const char *path)
{
    return path && (strcmp(path, "/dev/stdout") == 0 || strcmp(path, "/dev/fd/1") == 0 ||
                    strcmp(path, "/proc/self/fd/1") == 0 || cli_is_stdout_format(path));
}

int cli_out_open(cli_out *o, const char *what, const char *path)
{
    memset(o, 0, sizeof *o);
    o->what = what;
    o->path = path;
    if (!path || strcmp(path, "-") == 0 || cli_is_stdout_name(path)) {
        o->f = stdout;
        o->path = NULL;
        return CLI_OK;
    }
    char dir[PATH_MAX];
    struct stat st;
    if (path[0] == '\0') {
        cli_error("%s: an empty file name", what);
        return CLI_FAILED;
    }
    const char *input = cli_input_named(path);
    if (input)
        return cli_out_refuse_input(NULL, what, path, input);
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
        cli_error("%s '%s' is a directory", what, path);
        return CLI_FAILED;
    }
    if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
        /* a device or a pipe (/dev/null, /dev/stdout, a FIFO): written in place */
        if (!(o->f = fopen(path, "w"))) {
            cli_error("cannot open %s '%s' for writing: %s", what, path,
                    strerror(errno));
            return CLI_FAILED;
        }
        return CLI_OK;
    }
    /* a regular file or a new one: write a temporary file beside it (a symbolic link is
     * followed, so the file it points to is the one replaced) */
    const char *target = path;
    char resolved[PATH_MAX];
    if (stat(path, &st) == 0 && realpath(path, resolved))
        target = resolved;
    dir_of(target, dir, sizeof dir);
    struct stat dst;
    if (stat(dir, &dst) != 0 || !S_ISDIR(dst.st_mode)) {
        cli_error("cannot write %s '%s': the directory '%s' %s", what, path,
                dir,
                errno == ENOENT || stat(dir, &dst) != 0 ? "does not exist" : "is not a directory");
        return CLI_FAILED;
    }
    size_t len = strlen(target) + 16;
    o->tmp = malloc(len);
    o->target = malloc(strlen(target) + 1);
    if (!o->tmp || !o->target) {
        free(o->tmp);
        free(o->target);
        o->tmp = o->target = NULL;
        cli_error("out of memory");
        return CLI_FAILED;
    }
    strcpy(o->target, target);
    snprintf(o->tmp, len, "%s.tmpXXXXXX", target);
    int fd = mkstemp(o->tmp);
    if (fd < 0) {
        cli_error("cannot write %s '%s': %s", what, path, strerror(errno));
        free(o->tmp);
        free(o->target);
        o->tmp = o->target = NULL;
        return CLI_FAILED;
    }
    /* the permissions a plain fopen would give: the existing file's, or 0666 & ~umask */
    mode_t mode;
    if (stat(target, &st) == 0) {
        mode = st.st_mode & 07777;
    } else {
        mode_t mask = umask(0);
        umask(mask);
        mode = 0666 & ~mask;
    }
    (void)fchmod(fd, mode);
    if (!(o->f = fdopen(fd, "w"))) {
        cli_error("cannot write %s '%s': %s", what, path, strerror(errno));
        close(fd);
        unlink(o->tmp);
        free(o->tmp);
        free(o->target);
        o->tmp = o->target = NULL;
        return CLI_FAILED;
    }
    cli_signals_track(o->tmp);
    return CLI_OK;
}

int cli_out_close(cli_out *o, int keep)
{
    int rc = CLI_OK;
    if (!o->f)
        return CLI_OK;
    if (o->f == stdout) {
        o->f = NULL;
        if (fflush(stdout) != 0 || ferror(stdout))
            rc = CLI_FAILED; /* reported at exit (cli_stdout_check) */
        return rc;
    }
    /* a failed write is an error whether or not the file is kept: the command ends with
     * exit 1 and a message naming the file (a full disk is never a silent loss) */
    errno = 0;
    int bad = fflush(o->f) != 0;
    int err = errno;
    bad |= ferror(o->f) != 0;
    errno = 0;
    if (fclose(o->f) != 0) {
        bad = 1;
        err = err ? err : errno;
    }
    o->f = NULL;
    if (bad && !o->failure_told)
        cli_error("writing %s '%s' failed: %s%s", o->what, o->path,
                  err ? strerror(err) : "a write failed",
                  o->tmp ? "; the file was left as it was" : "");
    if (bad) {
        rc = CLI_FAILED;
        keep = 0;
    }
    const char *input = keep && o->tmp ? cli_input_named(o->target) : NULL;
    if (input) { /* an input named after the output was opened */
        cli_out_refuse_input(NULL, o->what, o->path, input);
        rc = CLI_USAGE;
        keep = 0;
    }
    if (o->tmp) {
        if (keep && rename(o->tmp, o->target) != 0) {
            cli_error("cannot write %s '%s': %s", o->what, o->path, strerror(errno));
            rc = CLI_FAILED;
            keep = 0;
        }
        if (!keep)
            unlink(o->tmp);
        cli_signals_track(NULL);
        free(o->tmp);
        free(o->target);
        o->tmp = o->target = NULL;
    }
    return rc;
}

int cli_has_extension(const char *path, const char *ext)
{
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash + 1 : path, '.');
    return dot && strcasecmp(dot, ext) == 0;
}

int cli_out_check_extension(const char *command, const char *option, const char *path,
                            const char *const *exts)
{
    if (!path || strcmp(path, "-") == 0)
        return CLI_OK;
    char accepted[128] = "";
    for (int i = 0; exts[i]; i++) {
        if (cli_has_extension(path, exts[i]))
            return CLI_OK;
        snprintf(accepted + strlen(accepted), sizeof accepted - strlen(accepted), "%sFILE%s",
                 i ? (exts[i + 1] ? ", " : " or ") : "", exts[i]);
    }
    struct stat st;
    if ((cli_is_stdout_name(path) && !cli_is_stdout_format(path)) ||
        (stat(path, &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode)))
        return CLI_OK; /* standard output, a device or a pipe */
    return cli_usage_error(command,
                           "%s '%s': %s writes %s ('-' is standard output, '-%s' standard "
                           "output in that format)",
                           option, path, command, accepted, exts[0]);
}

int cli_same_file(const char *a, const char *b)
{
    if (!a || !b || strcmp(a, "-") == 0 || strcmp(b, "-") == 0)
        return 0;
    if (strcmp(a, b) == 0)
        return 1;
    struct stat sa, sb;
    if (stat(a, &sa) == 0 && stat(b, &sb) == 0)
        return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino && S_ISREG(sa.st_mode);
    /* not both there yet: the same name in the same directory */
    const char *na = strrchr(a, '/'), *nb = strrchr(b, '/');
    na = na ? na + 1 : a;
    nb = nb ? nb + 1 : b;
    if (strcmp(na, nb) != 0)
        return 0;
    char da[PATH_MAX], db[PATH_MAX], ra[PATH_MAX], rb[PATH_MAX];
    dir_of(a, da, sizeof da);
    dir_of(b, db, sizeof db);
    return realpath(da, ra) && realpath(db, rb) && strcmp(ra, rb) == 0;
}

int cli_out_refuse_input(const char *command, const char *option, const char *path,
                         const char *what)
{
    const char *fmt = "%s '%s' is %s that dynkit reads: writing it would destroy that input; "
                      "name another file";
    if (command)
        return cli_usage_error(command, fmt, option, path, what);
    cli_error(fmt, option, path, what);
    return CLI_USAGE;
}

int cli_stdout_check(int rc)
{
    errno = 0;
    if (fflush(stdout) == 0 && !ferror(stdout))
        return rc;
    struct stat st;
    const int pipe_out = fstat(fileno(stdout), &st) == 0 && S_ISFIFO(st.st_mode);
    if (errno != EPIPE && !pipe_out) /* a closed pipe (| head) ends quietly */
        cli_error("cannot write to standard output: %s",
                errno ? strerror(errno) : "a write failed");
    return rc == CLI_OK ? CLI_FAILED : rc;
}

/* ---- SIGINT and SIGTERM ---- */

volatile sig_atomic_t cli_stop_signal;
static volatile sig_atomic_t graceful;
static const char *volatile tracked;

static void on_signal(int sig)
{
    cli_stop_signal = sig;
    if (graceful)
        return; /* the run finishes its row and stops (cli_signals_graceful) */
    const char *tmp = tracked;
    if (tmp)
        unlink(tmp);
    signal(sig, SIG_DFL);
    raise(sig);
}

void cli_signals_install(void)
{
    static const int sigs[] = {SIGINT, SIGTERM};
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
        struct sigaction old, sa;
        if (sigaction(sigs[i], NULL, &old) == 0 && old.sa_handler == SIG_IGN)
            continue; /* ignored by whoever started us (nohup, a background job): keep it */
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_signal;
        sigemptyset(&sa.sa_mask);
        sigaction(sigs[i], &sa, NULL);
    }
}

void cli_signals_graceful(int on) { graceful = on; }

void cli_signals_track(const char *tmp_path) { tracked = tmp_path; }

int cli_signal_status(void) { return cli_stop_signal ? 128 + cli_stop_signal : 0; }

const char *cli_signal_name(void)
{
    return cli_stop_signal == SIGINT    ? "SIGINT"
           : cli_stop_signal == SIGTERM ? "SIGTERM"
                                        : "a signal";
}
