/* SPDX-License-Identifier: BSD-3-Clause */
/* Every command that writes a file, on a disk where no write succeeds: exit 1, a message
 * naming the file, the file under that name left as it was (or never made), no temporary
 * file left beside it. Two ways to make the writes fail:
 *
 * - the file size limit (POSIX setrlimit RLIMIT_FSIZE, the shell's `ulimit -f 0`, with
 *   SIGXFSZ ignored): every write to a regular file fails with EFBIG. It needs no privilege,
 *   so it runs everywhere;
 * - a full file system: a 256 KiB tmpfs, mounted in a mount namespace of its own
 *   (`unshare --mount`, so nothing is left mounted), filled with one file until ENOSPC.
 *   It needs root with CAP_SYS_ADMIN; elsewhere that half is skipped with the reason.
 *
 * Each command first runs on a normal disk (exit 0, the file written): the inputs are
 * good and the compiled models are in the cache before the writes fail. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "test_cli_run.h"
#include "test_util.h"

#define OLD_TEXT "old bytes that must survive\n"

typedef struct writer {
    const char *args; /* the command, run in the temporary directory */
    const char *file; /* the file it writes (replaced, or made when "new") */
    int made;         /* 1: a name the command chooses (animate's MODEL.html): never there before */
} writer;

static const writer writers[] = {
    {"run pendulum --tspan 0:1 -o o.csv", "o.csv", 0},
    {"run pendulum --tspan 0:1 -o o.json", "o.json", 0},
    {"run pendulum --tspan 0:1 -o o.npy", "o.npy", 0},
    {"run pendulum --tspan 0:1 -o o.npz", "o.npz", 0},
    {"run pendulum --tspan 0:1 -o o.mat", "o.mat", 0},
    {"run pendulum --final -o f.csv", "f.csv", 0},
    {"run bouncing_ball.ode --tspan 0:3 -o /dev/null --event bounce --events-output ev.csv",
     "ev.csv", 0},
    {"sweep pendulum --vary l=1:2:3 -o s.csv", "s.csv", 0},
    {"sweep pendulum --vary l=1:2:3 -o s.json", "s.json", 0},
    {"sweep pendulum --vary l=1:2:3 --bands b.csv -o /dev/null", "b.csv", 0},
    {"inverse cart -o i.csv", "i.csv", 0},
    {"inverse fourbar.mech --prescribe q1=2*pi*t --tspan 0:0.1 --quiet -o i2.csv", "i2.csv", 0},
    {"derive double_pendulum.mech --c d.c", "d.c", 0},
    {"linearize pendulum --output l.json", "l.json", 0},
    {"linearize pendulum --output l.csv", "l.csv", 0},
    {"plot pendulum --y phi -o p.svg", "p.svg", 0},
    {"plot table.csv --y final:phi -o sp.svg", "sp.svg", 0},
    {"animate pendulum -o a.html", "a.html", 0},
    {"animate pendulum", "pendulum.html", 1},
    {"report --no-studies --html r.html", "r.html", 0},
};
#define N_WRITERS (sizeof writers / sizeof writers[0])

static int setup(void **state)
{
    (void)state;
    return cli_make_tmpdir("full_disk");
}

static int teardown(void **state)
{
    (void)state;
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", cli_tmpdir);
    return system(cmd) == 0 ? 0 : -1;
}

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs(text, f);
    assert_int_equal(fclose(f), 0);
}

/* The inputs of the commands, in dir. */
static void make_inputs(const char *dir)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd,
             "cd '%s' && cp '%s/examples/models/bouncing_ball.ode' '%s/examples/mechanisms/"
             "fourbar.mech' '%s/examples/mechanisms/double_pendulum.mech' . && "
             "'%s' sweep pendulum --vary l=1:2:3 -o table.csv",
             dir, DYNKIT_SOURCE_DIR, DYNKIT_SOURCE_DIR, DYNKIT_SOURCE_DIR, DYNKIT_CLI);
    assert_int_equal(system(cmd), 0);
}

/* 1 when this dynkit writes .mat files (built with matio). */
static int have_mat(void)
{
    cli_result r = cli_in_tmpdir("run pendulum --tspan 0:0.1 -o probe.mat");
    const int yes = r.status == 0;
    cli_free(&r);
    return yes;
}

/* What `sh -c script` printed (stdout and stderr) and its exit status. */
static char *shell(const char *script, int *status)
{
    char path[600], cmd[700];
    snprintf(path, sizeof path, "%s/script.sh", cli_tmpdir);
    write_text(path, script);
    snprintf(cmd, sizeof cmd, "sh '%s' 2>&1", path);
    return cli_capture(cmd, status);
}

/* Each command: on a normal disk it writes its file; in dir (after the shell lines mount,
 * then the old file, then the lines fill), run after the shell's prefix limit, it exits 1
 * naming the file, and OLD_TEXT survives. */
static void check_writers(const char *dir, const char *limit, const char *mount,
                          const char *fill)
{
    const int mat = have_mat();
    for (size_t i = 0; i < N_WRITERS; i++) {
        const writer *w = &writers[i];
        if (!mat && strstr(w->file, ".mat"))
            continue; /* built without matio: run refuses .mat (tested in test_formats) */
        char path[600];
        snprintf(path, sizeof path, "%s/%s", dir, w->file);
        /* a normal disk first: the command works, and its model is compiled */
        char script[8192];
        snprintf(script, sizeof script, "cd '%s' && rm -f '%s' && '%s' %s >/dev/null 2>&1",
                 cli_tmpdir, w->file, DYNKIT_CLI, w->args);
        int status;
        free(shell(script, &status));
        CHECK(status == 0, "%s: exit %d on a normal disk", w->args, status);
        /* then the failing disk, over an old file (or none) */
        char prepare[256];
        if (w->made)
            snprintf(prepare, sizeof prepare, "rm -f '%s'", w->file);
        else
            snprintf(prepare, sizeof prepare, "printf '%s' > '%s'", OLD_TEXT, w->file);
        /* stderr goes to the pipe read here: no file of the test is on the failing disk */
        snprintf(script, sizeof script,
                 "%s\ncd '%s' || exit 99\n%s\n%s\n"
                 "( trap '' XFSZ; %s exec '%s' %s ) 2>&1 >/dev/null\n"
                 "echo \"status=$?\"\n"
                 "echo \"file=$(cat '%s' 2>/dev/null || echo none)\"\n"
                 "echo \"tmp=$(ls -A | grep -c '[.]tmp')\"\n",
                 mount, dir, prepare, fill, limit, DYNKIT_CLI, w->args, w->file);
        char *out = shell(script, &status);
        const int exited1 = strstr(out, "status=1\n") != NULL;
        const int named = strstr(out, w->file) != NULL && strstr(out, "writ") != NULL;
        char want_file[128];
        snprintf(want_file, sizeof want_file, "file=%s",
                 w->made ? "none" : "old bytes that must survive");
        CHECK(exited1 && named && strstr(out, want_file) && strstr(out, "tmp=0\n"),
              "%s, %s: want exit 1, a message naming %s, %s and no temporary file; got\n%s",
              w->args, mount[0] ? "a full tmpfs" : "a file size limit of 0", w->file, want_file,
              out);
        free(out);
    }
}

/* 1 when a tmpfs can be mounted in a mount namespace of its own (root with CAP_SYS_ADMIN) */
static int can_mount_tmpfs(void)
{
    int status;
    char *out = shell("unshare --mount sh -c 'mount -t tmpfs -o size=256k tmpfs /mnt && "
                      "umount /mnt' && echo yes",
                      &status);
    const int yes = strstr(out, "yes") != NULL;
    free(out);
    return yes;
}

static void test_file_size_limit(void **state)
{
    (void)state;
    make_inputs(cli_tmpdir);
    check_writers(cli_tmpdir, "ulimit -f 0;", "", "");
}

static void test_full_tmpfs(void **state)
{
    (void)state;
    if (!can_mount_tmpfs()) {
        fprintf(stderr, "test_full_tmpfs skipped: no mount namespace with tmpfs here "
                        "(needs root with CAP_SYS_ADMIN and unshare); the file size limit "
                        "half ran\n");
        skip();
    }
    make_inputs(cli_tmpdir);
    char dir[600];
    snprintf(dir, sizeof dir, "%s/full", cli_tmpdir);
    assert_int_equal(mkdir(dir, 0700), 0);
    /* the script re-executes itself in a new mount namespace, mounts a small tmpfs on dir,
     * copies the inputs, writes the old file and fills the tmpfs to ENOSPC */
    char mount[4096], fill[2048];
    snprintf(mount, sizeof mount,
             "[ -z \"$IN_NS\" ] && IN_NS=1 exec unshare --mount sh \"$0\"\n"
             "mount -t tmpfs -o size=256k tmpfs '%s' || exit 98\n"
             "cp '%s'/*.ode '%s'/*.mech '%s/table.csv' '%s'/\n",
             dir, cli_tmpdir, cli_tmpdir, cli_tmpdir, dir);
    snprintf(fill, sizeof fill,
             "dd if=/dev/zero of=fill bs=4096 2>/dev/null\n"
             "touch probe && printf x >> probe 2>/dev/null && exit 97\n");
    check_writers(dir, "", mount, fill);
}

/* The cache of compiled models where no write succeeds: a model file never compiled before
 * (its cache new, so its headers cannot be written either) runs, compiled by libtcc in
 * memory, with a note saying why, and prints what libtcc's run on a normal disk prints;
 * DYNKIT_JIT=cc (the system compiler alone) fails naming the cache and DYNKIT_CACHE_DIR; no
 * temporary file is left in the cache. `prefix` makes the writes fail (shell lines), `cache`
 * is the cache directory there. */
static void check_cache_cannot_be_written(const char *prefix, const char *cache)
{
    cli_result ref = cli_in_tmpdir("run bouncing_ball.ode --tspan 0:3 --final");
    char probe[700];
    snprintf(probe, sizeof probe,
             "DYNKIT_JIT=tcc '%s' run '%s/bouncing_ball.ode' --final "
             "--tspan 0:3 2>&1",
             DYNKIT_CLI, cli_tmpdir);
    int status;
    char *tcc = cli_capture(probe, &status);
    const int have_tcc = status == 0;
    CHECK(ref.status == 0, "the reference run: %s", ref.err);
    char script[8192];
    snprintf(script, sizeof script,
             "%s\n"
             "( trap '' XFSZ; DYNKIT_CACHE_DIR='%s' exec '%s' run '%s/bouncing_ball.ode' --final "
             "--tspan 0:3 ) 2>&1\n"
             "echo \"status=$?\"\n"
             "( trap '' XFSZ; DYNKIT_JIT=cc DYNKIT_CACHE_DIR='%s' exec '%s' run "
             "'%s/bouncing_ball.ode' --final --tspan 0:3 ) 2>&1\n"
             "echo \"cc-status=$?\"\n"
             "echo \"tmp=$(ls -A '%s' | grep -c '^tmp-')\"\n",
             prefix, cache, DYNKIT_CLI, cli_tmpdir, cache, DYNKIT_CLI, cli_tmpdir, cache);
    char *out = shell(script, &status);
    if (have_tcc)
        CHECK(strstr(out, "status=0\n") && strstr(out, tcc) &&
                  strstr(out, "compiled with libtcc instead"),
              "%s: want libtcc's run (%s) with a note; got\n%s", prefix, tcc, out);
    CHECK(!strstr(out, "cc-status=0\n") && strstr(out, "cannot be written") &&
              strstr(out, "DYNKIT_CACHE_DIR") && strstr(out, "tmp=0\n"),
          "%s: want DYNKIT_JIT=cc to fail naming the cache, nothing left; got\n%s", prefix, out);
    free(out);
    free(tcc);
    cli_free(&ref);
}

static void test_cache_on_a_full_disk(void **state)
{
    (void)state;
    make_inputs(cli_tmpdir);
    char prefix[8192], cache[700];
    snprintf(cache, sizeof cache, "%s/size-limited-cache", cli_tmpdir);
    snprintf(prefix, sizeof prefix, "ulimit -f 0");
    check_cache_cannot_be_written(prefix, cache);
    if (!can_mount_tmpfs()) {
        fprintf(stderr, "test_cache_on_a_full_disk: the full tmpfs half skipped (needs root "
                        "with CAP_SYS_ADMIN and unshare); the file size limit half ran\n");
        return;
    }
    /* a full tmpfs: a new cache (256 KiB), and one whose headers were written before it
     * filled (2 MiB: the headers take more than 256 KiB of a tmpfs' pages) */
    char dir[600];
    snprintf(dir, sizeof dir, "%s/fullcache", cli_tmpdir);
    assert_int_equal(mkdir(dir, 0700), 0);
    for (int headers = 0; headers < 2; headers++) {
        snprintf(cache, sizeof cache, "%s/cache", dir);
        snprintf(prefix, sizeof prefix,
                 "[ -z \"$IN_NS\" ] && IN_NS=1 exec unshare --mount sh \"$0\"\n"
                 "mount -t tmpfs -o size=256k tmpfs '%s' || exit 98\n"
                 "dd if=/dev/zero of='%s/fill' bs=4096 2>/dev/null\n"
                 "touch '%s/probe' && printf x >> '%s/probe' 2>/dev/null && exit 97\n",
                 dir, dir, dir, dir);
        if (headers) /* the headers directory written first, then the disk filled */
            snprintf(prefix, sizeof prefix,
                     "[ -z \"$IN_NS\" ] && IN_NS=1 exec unshare --mount sh \"$0\"\n"
                     "mount -t tmpfs -o size=2m tmpfs '%s' || exit 98\n"
                     "DYNKIT_JIT=tcc DYNKIT_CACHE_DIR='%s' '%s' run '%s/bouncing_ball.ode' "
                     "--final >/dev/null 2>&1; ls -d '%s'/include-* >/dev/null || exit 96\n"
                     "dd if=/dev/zero of='%s/fill' bs=4096 2>/dev/null\n"
                     "touch '%s/probe' && printf x >> '%s/probe' 2>/dev/null && exit 97\n",
                     dir, cache, DYNKIT_CLI, cli_tmpdir, cache, dir, dir, dir);
        check_cache_cannot_be_written(prefix, cache);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_file_size_limit),
        cmocka_unit_test(test_full_tmpfs),
        cmocka_unit_test(test_cache_on_a_full_disk),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
