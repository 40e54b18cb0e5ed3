/* SPDX-License-Identifier: BSD-3-Clause */
/* MATLAB files of a run's table: a level 5 MAT-file (MathWorks, "MAT-File Format", the
 * version 5 layout that MATLAB, Octave and scipy.io.loadmat read) written with matio
 * (libmatio, BSD-2-Clause) when dynkit is built with it. Variables: t (samples x 1), y
 * (samples x states), outputs (samples x outputs, when there are any), names and units (1 x
 * columns cell arrays of char, the columns of the CSV), model, method (char), step, rtol,
 * atol (scalars, when they apply), tspan (1 x 2) and dynkit (the version); a sweep's table
 * has a variable per column (runs x 1, named as the column) in place of t, y and outputs. matio writes to a
 * file name, so the file is made in the temporary directory ($TMPDIR or /tmp) and copied to
 * the stream the caller opened (which may be a temporary file that is renamed later).
 * matio is loaded (dlopen) when a .mat file is written, not linked: it brings HDF5 and its
 * dependencies, whose loading would otherwise slow every start of the tool (docs/data-files.md). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tables/table_formats.h"

#ifndef DYNKIT_HAVE_MATIO

int cli_mat_write(FILE *out, const cli_table_info *info, const double *data, long rows,
                  char *err, size_t errlen)
{
    (void)out;
    (void)info;
    (void)data;
    (void)rows;
    snprintf(err, errlen, "dynkit was built without matio: install libmatio-dev and rebuild");
    return -1;
}

#else

#include <dlfcn.h>
#include <matio.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef DYNKIT_VERSION
#define DYNKIT_VERSION "0.1.0"
#endif

/* The functions of matio this file calls, from the library loaded at the first write. */
typedef struct matio_api {
    matvar_t *(*var_create)(const char *, enum matio_classes, enum matio_types, int, size_t *,
                            void *, int);
    void (*var_free)(matvar_t *);
    matvar_t *(*var_set_cell)(matvar_t *, int, matvar_t *);
    int (*var_write)(mat_t *, matvar_t *, enum matio_compression);
    mat_t *(*create_ver)(const char *, const char *, enum mat_ft);
    int (*close)(mat_t *);
} matio_api;

static matio_api api;

/* Load matio once; 0, or -1 with a message naming the library. */
static int load_matio(char *err, size_t errlen)
{
    static int loaded;
    if (loaded)
        return 0;
    void *lib = dlopen(DYNKIT_MATIO_SONAME, RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        snprintf(err, errlen, "cannot load matio for the .mat file (%s): install it (Debian: "
                 "libmatio11), or write .npz, .npy, .csv or .json",
                 dlerror());
        return -1;
    }
    static const char *const names[] = {"Mat_VarCreate", "Mat_VarFree",   "Mat_VarSetCell",
                                        "Mat_VarWrite",  "Mat_CreateVer", "Mat_Close"};
    void *sym[6];
    for (int i = 0; i < 6; i++)
        if (!(sym[i] = dlsym(lib, names[i]))) {
            snprintf(err, errlen, "%s has no %s: not the matio dynkit was built with",
                     DYNKIT_MATIO_SONAME, names[i]);
            dlclose(lib);
            return -1;
        }
    /* POSIX: a function pointer converts to and from void * (dlsym's contract) */
    memcpy(&api.var_create, &sym[0], sizeof sym[0]);
    memcpy(&api.var_free, &sym[1], sizeof sym[1]);
    memcpy(&api.var_set_cell, &sym[2], sizeof sym[2]);
    memcpy(&api.var_write, &sym[3], sizeof sym[3]);
    memcpy(&api.create_ver, &sym[4], sizeof sym[4]);
    memcpy(&api.close, &sym[5], sizeof sym[5]);
    loaded = 1;
    return 0;
}

static matvar_t *mat_string(const char *name, const char *s)
{
    size_t dims[2] = {1, strlen(s)};
    return api.var_create(name, MAT_C_CHAR, MAT_T_UTF8, 2, dims, (void *)s, 0);
}

static matvar_t *mat_doubles(const char *name, size_t rows, size_t cols, const double *v)
{
    size_t dims[2] = {rows, cols};
    return api.var_create(name, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, (void *)v, 0);
}

static matvar_t *mat_cell(const char *name, const char *const *s, int n)
{
    size_t dims[2] = {1, (size_t)n};
    matvar_t *cell = api.var_create(name, MAT_C_CELL, MAT_T_CELL, 2, dims, NULL, 0);
    for (int i = 0; cell && i < n; i++) {
        matvar_t *item = mat_string(NULL, s[i] ? s[i] : "");
        if (!item) {
            api.var_free(cell);
            return NULL;
        }
        api.var_set_cell(cell, i, item);
    }
    return cell;
}

/* Write var (taken) into mat; 0 on success. */
static int put(mat_t *mat, matvar_t *var)
{
    if (!var)
        return -1;
    int rc = api.var_write(mat, var, MAT_COMPRESSION_NONE);
    api.var_free(var);
    return rc != 0;
}

/* Columns [first, first + n) of the row-major table, column-major as MATLAB keeps them. */
static matvar_t *mat_columns(const char *name, const double *data, long rows, int cols, int first,
                             int n)
{
    double *v = malloc((size_t)rows * (size_t)n * sizeof *v + 1);
    if (!v)
        return NULL;
    for (int j = 0; j < n; j++)
        for (long k = 0; k < rows; k++)
            v[(size_t)j * (size_t)rows + (size_t)k] = data[k * cols + first + j];
    matvar_t *var = mat_doubles(name, (size_t)rows, (size_t)n, v);
    free(v);
    return var;
}

static int copy_file(const char *path, FILE *out)
{
    FILE *in = fopen(path, "rb");
    if (!in)
        return -1;
    char buf[1 << 16];
    size_t got;
    int bad = 0;
    while (!bad && (got = fread(buf, 1, sizeof buf, in)) > 0)
        bad = fwrite(buf, 1, got, out) != got;
    bad |= ferror(in);
    fclose(in);
    bad |= fflush(out) != 0;
    return bad ? -1 : 0;
}

int cli_mat_write(FILE *out, const cli_table_info *info, const double *data, long rows,
                  char *err, size_t errlen)
{
    if (load_matio(err, errlen))
        return -1;
    const char *dir = getenv("TMPDIR");
    char path[4096];
    snprintf(path, sizeof path, "%s/dynkit-mat-XXXXXX", dir && *dir ? dir : "/tmp");
    int fd = mkstemp(path);
    if (fd < 0) {
        snprintf(err, errlen, "cannot make a temporary file in %s for the mat file: %s",
                 dir && *dir ? dir : "/tmp", strerror(errno));
        return -1;
    }
    close(fd);
    char header[116];
    snprintf(header, sizeof header, "MATLAB 5.0 MAT-file, written by dynkit %s",
             DYNKIT_VERSION);
    mat_t *mat = api.create_ver(path, header, MAT_FT_MAT5);
    if (!mat) {
        unlink(path);
        snprintf(err, errlen, "matio could not create the mat file");
        return -1;
    }
    const int cols = info->cols, n_y = info->n_y, n_out = cols - 1 - n_y;
    int bad = 0;
    if (info->sweep) { /* a variable per column, named as the column */
        for (int j = 0; j < cols; j++)
            bad |= put(mat, mat_columns(info->names[j], data, rows, cols, j, 1));
    } else {
        bad |= put(mat, mat_columns("t", data, rows, cols, 0, 1));
        bad |= put(mat, mat_columns(info->y_name ? info->y_name : "y", data, rows, cols, 1, n_y));
        if (n_out > 0)
            bad |= put(mat, mat_columns("outputs", data, rows, cols, 1 + n_y, n_out));
    }
    bad |= put(mat, mat_cell("names", info->names, cols));
    bad |= put(mat, mat_cell("units", info->units, cols));
    bad |= put(mat, mat_string("model", info->model));
    if (info->method)
        bad |= put(mat, mat_string("method", info->method));
    if (!isnan(info->step))
        bad |= put(mat, mat_doubles("step", 1, 1, &info->step));
    if (!isnan(info->rtol))
        bad |= put(mat, mat_doubles("rtol", 1, 1, &info->rtol));
    if (!isnan(info->atol))
        bad |= put(mat, mat_doubles("atol", 1, 1, &info->atol));
    const double span[2] = {info->t0, info->t1};
    bad |= put(mat, mat_doubles("tspan", 1, 2, span));
    bad |= put(mat, mat_string("dynkit", DYNKIT_VERSION));
    bad |= api.close(mat) != 0;
    if (bad) {
        unlink(path);
        snprintf(err, errlen, "writing the mat file failed (matio; %ld rows of %d columns)",
                 rows, cols);
        return -1;
    }
    /* matio does not report every failed write (a full disk leaves a short file): the
     * file, uncompressed, holds at least its 128-byte header and every number */
    struct stat st;
    const double least = 128.0 + 8.0 * (double)rows * (double)cols;
    if (stat(path, &st) != 0 || (double)st.st_size < least) {
        const double size = stat(path, &st) == 0 ? (double)st.st_size : 0.0;
        unlink(path);
        snprintf(err, errlen,
                 "writing the mat file failed: matio's temporary file in %s holds %.0f bytes, "
                 "fewer than the %.0f of its numbers (is %s full?)",
                 dir && *dir ? dir : "/tmp", size, least, dir && *dir ? dir : "/tmp");
        return -1;
    }
    errno = 0;
    int rc = copy_file(path, out);
    unlink(path);
    if (rc)
        snprintf(err, errlen, "writing the mat file failed: %s",
                 errno ? strerror(errno) : "write error");
    return rc;
}

#endif
