/* SPDX-License-Identifier: BSD-3-Clause */
/* bench_output: writing every sample as text (docs/performance.md, "Output"; issue 12's
 * targets for shortest round-trip output):
 * 1. one number: dyn_format_double (Ryu, src/io/shortest_double.c) against
 *    snprintf("%.17g"), ns per number on four kinds of numbers (a van der Pol trajectory's
 *    states, its time grid k * 1e-5, uniform in [-1, 1), random bit patterns over every
 *    exponent); target: at least 5x faster on each;
 * 2. the rows of that trajectory (2,000,001 rows of t, y1, y2) written to a file in
 *    $TMPDIR: dyn_csv_write_row_to (one fwrite per 64 KiB) against one fprintf("%.17g") per
 *    number, the way rows were written before;
 * 3. end to end: `dynkit run vanderpol --method rk4 --step 1e-5 --tspan 0:20 --output
 *    FILE.csv` against the same run with --final (one row): target at most 4x.
 * Times are the best of --reps repetitions (default 5) of CPU time (user + system: on a
 * shared machine the wall time includes waiting for a core; both are printed for the runs
 * of the tool), the two sides of each ratio measured alternately in the same run.
 *   bench_output            the measurements and the table of targets
 *   bench_output --quick    checks only (untimed; run by CTest): every benchmark number
 *                           reads back, and a short run's CSV ends with its --final row */
#define _DEFAULT_SOURCE /* wait4 */
#include <fcntl.h>
#include <math.h>
#include <spawn.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "dynkit/io.h"
#include "dynkit/ode.h"
#include "bench_clock.h"

extern char **environ;

static int failures;

static void check(int ok, const char *what)
{
    if (!ok) {
        fprintf(stderr, "bench_output: FAILED: %s\n", what);
        failures++;
    }
}

/* van der Pol (mu = 1) by RK4 from (2, 0) with step h: steps + 1 rows of t, y1, y2; the
 * samples dynkit's CLI writes for the same run (t_k = k h, never accumulated). */
static double *vanderpol_rows(long steps, double h)
{
    double *r = malloc((size_t)(steps + 1) * 3 * sizeof *r);
    if (!r)
        return NULL;
    double y1 = 2.0, y2 = 0.0;
    for (long k = 0; k <= steps; k++) {
        r[3 * k] = (double)k * h;
        r[3 * k + 1] = y1;
        r[3 * k + 2] = y2;
        double k1a = y2, k1b = (1 - y1 * y1) * y2 - y1;
        double a = y1 + 0.5 * h * k1a, b = y2 + 0.5 * h * k1b;
        double k2a = b, k2b = (1 - a * a) * b - a;
        a = y1 + 0.5 * h * k2a, b = y2 + 0.5 * h * k2b;
        double k3a = b, k3b = (1 - a * a) * b - a;
        a = y1 + h * k3a, b = y2 + h * k3b;
        double k4a = b, k4b = (1 - a * a) * b - a;
        y1 += h / 6 * (k1a + 2 * k2a + 2 * k3a + k4a);
        y2 += h / 6 * (k1b + 2 * k2b + 2 * k3b + k4b);
    }
    return r;
}

static uint64_t next_random(uint64_t *s) /* xorshift64* */
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return *s * UINT64_C(2685821657736338717);
}

/* Seconds to format the n numbers once; chars counts what was written (kept live). */
static double time_format(const double *x, long n, int printf_way, long *chars)
{
    char buf[64];
    long total = 0;
    const double t0 = bench_process_cpu_seconds();
    if (printf_way)
        for (long i = 0; i < n; i++)
            total += snprintf(buf, sizeof buf, "%.17g", x[i]);
    else
        for (long i = 0; i < n; i++)
            total += dyn_format_double(x[i], buf);
    const double t = bench_process_cpu_seconds() - t0;
    *chars = total;
    return t;
}

/* Seconds to write the rows to path: the shortest strings through dyn_text_writer, or one
 * fprintf("%.17g") per number. */
static double time_rows(const char *path, const double *r, long rows, int printf_way)
{
    static dyn_text_writer w;
    FILE *f = fopen(path, "wb");
    if (!f)
        return NAN;
    const double t0 = bench_process_cpu_seconds();
    int bad = fputs("t,y1,y2\n", f) < 0;
    if (printf_way) {
        for (long k = 0; k < rows; k++)
            bad |= fprintf(f, "%.17g,%.17g,%.17g\n", r[3 * k], r[3 * k + 1], r[3 * k + 2]) < 0;
    } else {
        dyn_text_writer_init(&w, f);
        for (long k = 0; k < rows; k++)
            bad |= dyn_csv_write_row_to(&w, r[3 * k], r + 3 * k + 1, 2, NULL, 0) != DYN_OK;
        bad |= dyn_text_writer_flush(&w) != DYN_OK;
    }
    bad |= fclose(f) != 0;
    const double t = bench_process_cpu_seconds() - t0;
    return bad ? NAN : t;
}

/* Seconds of `dynkit ARGS...` with standard output to out_path: CPU time (user + system)
 * of the process, its wall time in *wall; NAN when it fails. */
static double time_cli(char *const argv[], const char *out_path, double *wall)
{
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, out_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid;
    int status = 0;
    struct rusage ru;
    const double t0 = bench_wall_seconds();
    int ok = posix_spawn(&pid, argv[0], &fa, NULL, argv, environ) == 0 &&
             wait4(pid, &status, 0, &ru) == pid && WIFEXITED(status) &&
             WEXITSTATUS(status) == 0;
    *wall = bench_wall_seconds() - t0;
    posix_spawn_file_actions_destroy(&fa);
    const double cpu = (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
                       (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
    return ok ? cpu : NAN;
}

static double min2(double a, double b) { return isnan(a) ? b : (b < a ? b : a); }

/* The last line of a file (without its newline) into buf. */
static int last_line(const char *path, char *buf, size_t size)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    char line[512];
    buf[0] = '\0';
    while (fgets(line, sizeof line, f))
        snprintf(buf, size, "%s", line);
    fclose(f);
    buf[strcspn(buf, "\n")] = '\0';
    return 0;
}

static long count_lines(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    long n = 0;
    int c;
    while ((c = getc(f)) != EOF)
        n += c == '\n';
    fclose(f);
    return n;
}

int main(int argc, char **argv)
{
    int quick = 0, reps = 5;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--quick") == 0)
            quick = 1;
        else if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc)
            reps = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_output [--quick] [--reps N]\n");
            return 2;
        }
    }
    if (reps < 1)
        reps = 1;
    const char *tmp = getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp";
    char csv[512], final_csv[512];
    snprintf(csv, sizeof csv, "%s/bench_output_%ld.csv", tmp, (long)getpid());
    snprintf(final_csv, sizeof final_csv, "%s/bench_output_final_%ld.csv", tmp, (long)getpid());

    /* ---- 1. one number ---- */
    const long steps = quick ? 2000 : 2000000, n = quick ? 20000 : 1L << 20;
    const double h = 20.0 / (double)steps;
    double *rows = vanderpol_rows(steps, h);
    double *kinds[4];
    const char *kind_name[4] = {"van der Pol states", "time grid k h", "uniform in [-1, 1)",
                                "random bit patterns"};
    uint64_t s = 2018;
    for (int c = 0; c < 4; c++) {
        kinds[c] = malloc((size_t)n * sizeof(double));
        if (!kinds[c] || !rows)
            return 1;
        for (long i = 0; i < n; i++) {
            double x;
            switch (c) {
            case 0: x = rows[3 * ((i / 2) % (steps + 1)) + 1 + i % 2]; break;
            case 1: x = rows[3 * (i % (steps + 1))]; break;
            case 2: x = (double)(next_random(&s) >> 11) * 0x1p-52 - 1.0; break;
            default:
                do {
                    uint64_t u = next_random(&s);
                    memcpy(&x, &u, sizeof x);
                } while (!isfinite(x));
            }
            kinds[c][i] = x;
        }
    }
    /* every number of the benchmark reads back */
    for (int c = 0; c < 4; c++)
        for (long i = 0; i < n; i++) {
            char b[DYN_DOUBLE_CHARS];
            dyn_format_double(kinds[c][i], b);
            if (strtod(b, NULL) != kinds[c][i]) {
                check(0, "a benchmark number does not read back");
                break;
            }
        }

    {
        char *fin[] = {(char *)BENCH_DYNKIT_CLI, (char *)"run", (char *)"vanderpol",
                       (char *)"--method", (char *)"rk4", (char *)"--step",
                       (char *)(quick ? "0.01" : "1e-5"), (char *)"--tspan", (char *)"0:20",
                       (char *)"--final", NULL};
        char *all[] = {(char *)BENCH_DYNKIT_CLI, (char *)"run", (char *)"vanderpol",
                       (char *)"--method", (char *)"rk4", (char *)"--step",
                       (char *)(quick ? "0.01" : "1e-5"), (char *)"--tspan", (char *)"0:20",
                       (char *)"--output", csv, NULL};
        if (quick) {
            double wall;
            check(!isnan(time_cli(all, "/dev/null", &wall)), "dynkit run --output failed");
            check(!isnan(time_cli(fin, final_csv, &wall)), "dynkit run --final failed");
            char a[512], b[512];
            check(last_line(csv, a, sizeof a) == 0 && last_line(final_csv, b, sizeof b) == 0 &&
                      strcmp(a, b) == 0,
                  "the last row of the CSV is not the --final row");
            check(count_lines(csv) == 2002, "the CSV of 0:20 at 0.01 does not have 2001 rows");
            check(!isnan(time_rows(csv, rows, steps + 1, 0)), "writing the rows failed");
            remove(csv);
            remove(final_csv);
            printf("bench_output --quick: %s\n", failures ? "FAILED" : "ok");
            for (int c = 0; c < 4; c++)
                free(kinds[c]);
            free(rows);
            return failures ? 1 : 0;
        }

        printf("## Output: numbers as text\n\n");
        printf("### One number: `dyn_format_double` (Ryu) against `snprintf(\"%%.17g\")`\n\n");
        printf("%ld numbers of each kind, best of %d; ns of CPU time per number.\n\n", n, reps);
        printf("| numbers | %%.17g | dyn_format_double | ratio | chars %%.17g | chars shortest |\n");
        printf("|---|---:|---:|---:|---:|---:|\n");
        double worst = INFINITY;
        const char *worst_kind = "";
        for (int c = 0; c < 4; c++) {
            double tp = NAN, ts = NAN;
            long cp = 0, cs = 0;
            for (int r = 0; r < reps; r++) {
                tp = min2(tp, time_format(kinds[c], n, 1, &cp));
                ts = min2(ts, time_format(kinds[c], n, 0, &cs));
            }
            const double ratio = tp / ts;
            if (ratio < worst) {
                worst = ratio;
                worst_kind = kind_name[c];
            }
            printf("| %s | %.1f | %.1f | %.2f | %.1f | %.1f |\n", kind_name[c], 1e9 * tp / n,
                   1e9 * ts / n, ratio, (double)cp / n, (double)cs / n);
        }

        printf("\n### Rows to a file: %ld rows of t, y1, y2 into %s\n\n", steps + 1, tmp);
        double tr_p = NAN, tr_s = NAN;
        for (int r = 0; r < reps; r++) {
            tr_p = min2(tr_p, time_rows(csv, rows, steps + 1, 1));
            tr_s = min2(tr_s, time_rows(csv, rows, steps + 1, 0));
        }
        check(!isnan(tr_p) && !isnan(tr_s), "writing the rows failed");
        printf("| writer | CPU s | ns per number | ratio |\n|---|---:|---:|---:|\n");
        printf("| one `fprintf(\"%%.17g\")` per number | %.3f | %.1f | %.2f |\n", tr_p,
               1e9 * tr_p / (3.0 * (steps + 1)), tr_p / tr_s);
        printf("| `dyn_csv_write_row_to` (shortest, one fwrite per 64 KiB) | %.3f | %.1f | 1.00 "
               "|\n",
               tr_s, 1e9 * tr_s / (3.0 * (steps + 1)));

        printf("\n### End to end: `dynkit run vanderpol --method rk4 --step 1e-5 --tspan 0:20`\n\n");
        double t_all = NAN, t_fin = NAN, w_all = NAN, w_fin = NAN;
        for (int r = 0; r < reps; r++) {
            double w;
            t_all = min2(t_all, time_cli(all, "/dev/null", &w));
            w_all = min2(w_all, w);
            t_fin = min2(t_fin, time_cli(fin, final_csv, &w));
            w_fin = min2(w_fin, w);
        }
        check(!isnan(t_all) && !isnan(t_fin), "dynkit run failed");
        const long lines = count_lines(csv);
        check(lines == steps + 2, "the CSV does not have 2,000,001 rows");
        char a[512], b[512];
        check(last_line(csv, a, sizeof a) == 0 && last_line(final_csv, b, sizeof b) == 0 &&
                  strcmp(a, b) == 0,
              "the last row of the CSV is not the --final row");
        printf("| run | CPU s (best of %d) | ratio | wall s | ratio |\n|---|---:|---:|---:|---:|\n",
               reps);
        printf("| `--final` (one row) | %.3f | 1.00 | %.3f | 1.00 |\n", t_fin, w_fin);
        struct stat st;
        const double mb = stat(csv, &st) == 0 ? (double)st.st_size / 1e6 : NAN;
        printf("| `--output FILE.csv` (%ld rows, %.0f MB) | %.3f | %.2f | %.3f | %.2f |\n",
               lines - 1, mb, t_all, t_all / t_fin, w_all, w_all / w_fin);
        remove(csv);
        remove(final_csv);

        printf("\n### Targets (output)\n\n| task | dynkit | measured | target | met |\n"
               "|---|---|---|---|---|\n");
        printf("| output: one number as text | dyn_format_double vs %%.17g (worst of 4 kinds: "
               "%s) | %.1f x faster | >= 5 x faster | %s |\n",
               worst_kind, worst, worst >= 5.0 ? "yes" : "**no**");
        printf("| output: every sample, van der Pol RK4 h = 1e-5 (2,000,001 rows) | dynkit run "
               "--output FILE.csv vs --final, CPU time | %.2f x | <= 4 x | %s |\n",
               t_all / t_fin, t_all / t_fin <= 4.0 ? "yes" : "**no**");
    }
    for (int c = 0; c < 4; c++)
        free(kinds[c]);
    free(rows);
    return failures ? 1 : 0;
}
