/* SPDX-License-Identifier: BSD-3-Clause */
/* NumPy files of a run's table, written without NumPy:
 * - .npy: the table as one 2-D little-endian float64 array ('<f8', C order), following the
 *   NPY format version 1.0 (numpy.lib.format; NEP 1): the magic "\x93NUMPY", the version
 *   1.0, a 2-byte little-endian header length, and the header, a Python dict literal padded
 *   with spaces and a newline so that the data starts at a multiple of 64 bytes.
 * - .npz: named arrays (t, y, outputs, names, units and the settings; for a sweep's table an
 *   array per column, named as the column, in place of t, y and outputs) as .npy members of a
 *   ZIP archive, stored without compression, following PKWARE's APPNOTE.TXT 6.3 (local file
 *   headers, central directory, end of central directory record; CRC-32 of ISO 3309 /
 *   ITU-T V.42, polynomial 0xEDB88320 reflected), which is what numpy.savez writes.
 * Strings are '<U' arrays (UTF-32 little-endian code points), so np.load reads them without
 * allow_pickle. */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "tables/table_formats.h"

#ifndef DYNKIT_VERSION
#define DYNKIT_VERSION "0.1.0"
#endif

/* ---- NPY ---- */

/* The header of an array of descr with shape dims[0..ndim) ("()" when ndim = 0), padded to
 * header_size bytes (0: the smallest multiple of 64). Returns its size or -1. */
static long npy_header_any(char *buf, size_t size, const char *descr, const long *dims, int ndim,
                           long header_size)
{
    char shape[96];
    size_t used = 0;
    shape[0] = '\0';
    for (int i = 0; i < ndim && used < sizeof shape; i++)
        used += (size_t)snprintf(shape + used, sizeof shape - used, "%ld,%s", dims[i],
                                 i + 1 < ndim ? " " : "");
    if (ndim > 1 && used > 0 && used < sizeof shape)
        shape[used - 1] = '\0'; /* "(3, 4)" but "(3,)" */
    char dict[160];
    int len = snprintf(dict, sizeof dict, "{'descr': '%s', 'fortran_order': False, 'shape': (%s), }",
                       descr, shape);
    if (len < 0 || (size_t)len >= sizeof dict)
        return -1;
    long total = 10 + len + 1; /* magic, version, length; dict; '\n' */
    if (header_size == 0)
        header_size = (total + 63) / 64 * 64;
    if (header_size < total || header_size % 64 != 0 || header_size - 10 > 65535 ||
        (size_t)header_size > size)
        return -1;
    const long hlen = header_size - 10;
    memcpy(buf, "\x93NUMPY\x01\x00", 8);
    buf[8] = (char)(hlen & 0xff);
    buf[9] = (char)(hlen >> 8);
    memcpy(buf + 10, dict, (size_t)len);
    memset(buf + 10 + len, ' ', (size_t)(header_size - 10 - len - 1));
    buf[header_size - 1] = '\n';
    return header_size;
}

long cli_npy_header(char *buf, size_t size, long rows, int cols, long header_size)
{
    const long dims[2] = {rows, cols};
    return npy_header_any(buf, size, "<f8", dims, 2, header_size);
}

static void put_f64(unsigned char *p, double v)
{
    uint64_t u;
    memcpy(&u, &v, sizeof u);
    for (int b = 0; b < 8; b++)
        p[b] = (unsigned char)(u >> (8 * b));
}

static void put16(unsigned char *p, unsigned v)
{
    p[0] = (unsigned char)(v & 0xff);
    p[1] = (unsigned char)((v >> 8) & 0xff);
}

static void put32(unsigned char *p, uint32_t v)
{
    for (int b = 0; b < 4; b++)
        p[b] = (unsigned char)((v >> (8 * b)) & 0xff);
}

int cli_npy_write(FILE *out, const double *data, long rows, int cols, char *err, size_t errlen)
{
    char header[256];
    long hs = cli_npy_header(header, sizeof header, rows, cols, 0);
    int bad = hs < 0 || fwrite(header, 1, (size_t)hs, out) != (size_t)hs;
    unsigned char bytes[8];
    for (long k = 0; k < rows * (long)cols && !bad; k++) {
        put_f64(bytes, data[k]);
        bad = fwrite(bytes, 1, 8, out) != 8;
    }
    bad |= fflush(out) != 0;
    if (bad) {
        snprintf(err, errlen, "writing the npy file failed: %s",
                 errno ? strerror(errno) : "write error");
        return -1;
    }
    return 0;
}

/* ---- members of the archive, each a whole .npy file in memory ---- */

typedef struct member {
    char name[208]; /* a column's name (at most 200 bytes) and ".npy" */
    unsigned char *bytes;
    size_t size;
    uint32_t crc;
    uint64_t offset;
} member;

/* A member holding the header for descr/dims and room for data_size bytes after it. */
static unsigned char *member_alloc(member *mb, const char *name, const char *descr,
                                   const long *dims, int ndim, size_t data_size)
{
    char header[256];
    long hs = npy_header_any(header, sizeof header, descr, dims, ndim, 0);
    snprintf(mb->name, sizeof mb->name, "%s.npy", name);
    if (hs < 0 || data_size > SIZE_MAX - (size_t)hs)
        return NULL;
    mb->size = (size_t)hs + data_size;
    mb->bytes = malloc(mb->size ? mb->size : 1);
    if (!mb->bytes)
        return NULL;
    memcpy(mb->bytes, header, (size_t)hs);
    return mb->bytes + hs;
}

/* Columns [first, first + n) of the rows x cols table as a (rows, n) array, or (rows,) when
 * vector. */
static int member_columns(member *mb, const char *name, const double *data, long rows, int cols,
                          int first, int n, int vector)
{
    const long dims[2] = {rows, n};
    unsigned char *p = member_alloc(mb, name, "<f8", dims, vector ? 1 : 2,
                                    (size_t)rows * (size_t)n * 8);
    if (!p)
        return -1;
    for (long k = 0; k < rows; k++)
        for (int j = 0; j < n; j++, p += 8)
            put_f64(p, data[k * cols + first + j]);
    return 0;
}

/* Doubles as a 1-D array, or a 0-d array when scalar. */
static int member_doubles(member *mb, const char *name, const double *v, long n, int scalar)
{
    unsigned char *p = member_alloc(mb, name, "<f8", &n, scalar ? 0 : 1, (size_t)n * 8);
    if (!p)
        return -1;
    for (long k = 0; k < n; k++, p += 8)
        put_f64(p, v[k]);
    return 0;
}

/* Next code point of UTF-8 text at *s (U+FFFD for a malformed sequence). */
static uint32_t utf8_next(const unsigned char **s)
{
    const unsigned char *p = *s;
    uint32_t c = *p++;
    int more = c < 0x80 ? 0 : (c >> 5) == 6 ? 1 : (c >> 4) == 14 ? 2 : (c >> 3) == 30 ? 3 : -1;
    if (more < 0) {
        *s = p;
        return 0xFFFD;
    }
    if (more)
        c &= 0x3Fu >> more;
    for (int i = 0; i < more; i++, p++) {
        if ((*p & 0xC0) != 0x80) {
            *s = p;
            return 0xFFFD;
        }
        c = (c << 6) | (*p & 0x3F);
    }
    *s = p;
    return c;
}

static long utf8_length(const char *s)
{
    long n = 0;
    for (const unsigned char *p = (const unsigned char *)s; *p; n++)
        utf8_next(&p);
    return n;
}

/* Strings as a '<U' array of n items ((n,)), or a 0-d array of one string when scalar. */
static int member_strings(member *mb, const char *name, const char *const *s, long n, int scalar)
{
    long width = 1;
    for (long i = 0; i < n; i++) {
        long len = utf8_length(s[i] ? s[i] : "");
        width = len > width ? len : width;
    }
    char descr[32];
    snprintf(descr, sizeof descr, "<U%ld", width);
    unsigned char *p = member_alloc(mb, name, descr, &n, scalar ? 0 : 1,
                                    (size_t)n * (size_t)width * 4);
    if (!p)
        return -1;
    memset(p, 0, (size_t)n * (size_t)width * 4);
    for (long i = 0; i < n; i++) {
        const unsigned char *q = (const unsigned char *)(s[i] ? s[i] : "");
        for (long k = 0; *q; k++)
            put32(p + 4 * (i * width + k), utf8_next(&q));
    }
    return 0;
}

/* ---- ZIP ---- */

static uint32_t crc32_of(const unsigned char *p, size_t n)
{
    static uint32_t table[256];
    static int ready;
    if (!ready) {
        for (uint32_t i = 0; i < 256; i++) {
            uint32_t c = i;
            for (int k = 0; k < 8; k++)
                c = c & 1 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            table[i] = c;
        }
        ready = 1;
    }
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; i++)
        c = table[(c ^ p[i]) & 0xff] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

/* DOS date and time of every member: 1980-01-01 00:00, so that equal runs give equal files. */
enum { ZIP_DOS_TIME = 0, ZIP_DOS_DATE = (0 << 9) | (1 << 5) | 1, ZIP_VERSION = 20 };

/* The fields shared by the local header (after its signature and version) and the central
 * directory entry: flags, method, time, date, CRC, sizes, name length. */
static void zip_common(unsigned char *p, const member *mb)
{
    put16(p, 0);                /* flags */
    put16(p + 2, 0);            /* method: stored */
    put16(p + 4, ZIP_DOS_TIME);
    put16(p + 6, ZIP_DOS_DATE);
    put32(p + 8, mb->crc);
    put32(p + 12, (uint32_t)mb->size); /* compressed size */
    put32(p + 16, (uint32_t)mb->size); /* uncompressed size */
    put16(p + 20, (unsigned)strlen(mb->name));
}

static int zip_write(FILE *out, member *mbs, int n, char *err, size_t errlen)
{
    uint64_t at = 0;
    int bad = 0;
    for (int i = 0; i < n && !bad; i++) {
        member *mb = &mbs[i];
        unsigned char h[30];
        const size_t name_len = strlen(mb->name);
        mb->crc = crc32_of(mb->bytes, mb->size);
        mb->offset = at;
        if (mb->size > 0xFFFFFFFFu || at > 0xFFFFFFFFu) {
            snprintf(err, errlen,
                     "the table is too large for an .npz file without ZIP64 (4 GiB); write "
                     ".npy or .csv, or keep fewer rows with --every K");
            return -1;
        }
        put32(h, 0x04034b50u);
        put16(h + 4, ZIP_VERSION);
        zip_common(h + 6, mb);
        put16(h + 28, 0); /* extra field length */
        bad |= fwrite(h, 1, sizeof h, out) != sizeof h;
        bad |= fwrite(mb->name, 1, name_len, out) != name_len;
        bad |= mb->size && fwrite(mb->bytes, 1, mb->size, out) != mb->size;
        at += sizeof h + name_len + mb->size;
    }
    const uint64_t cd_start = at;
    for (int i = 0; i < n && !bad; i++) {
        const member *mb = &mbs[i];
        unsigned char c[46];
        const size_t name_len = strlen(mb->name);
        put32(c, 0x02014b50u);
        put16(c + 4, (3u << 8) | ZIP_VERSION); /* made by: Unix, 2.0 */
        put16(c + 6, ZIP_VERSION);
        zip_common(c + 8, mb);
        put16(c + 30, 0);              /* extra field length */
        put16(c + 32, 0);              /* comment length */
        put16(c + 34, 0);              /* disk number start */
        put16(c + 36, 0);              /* internal attributes */
        put32(c + 38, 0100644u << 16); /* external: a regular file, rw-r--r-- */
        put32(c + 42, (uint32_t)mb->offset);
        bad |= fwrite(c, 1, sizeof c, out) != sizeof c;
        bad |= fwrite(mb->name, 1, name_len, out) != name_len;
        at += sizeof c + name_len;
    }
    if (at > 0xFFFFFFFFu) {
        snprintf(err, errlen, "the table is too large for an .npz file without ZIP64 (4 GiB)");
        return -1;
    }
    unsigned char e[22];
    put32(e, 0x06054b50u);
    put16(e + 4, 0); /* this disk */
    put16(e + 6, 0); /* disk of the central directory */
    put16(e + 8, (unsigned)n);
    put16(e + 10, (unsigned)n);
    put32(e + 12, (uint32_t)(at - cd_start));
    put32(e + 16, (uint32_t)cd_start);
    put16(e + 20, 0); /* comment length */
    bad |= fwrite(e, 1, sizeof e, out) != sizeof e;
    bad |= fflush(out) != 0;
    if (bad) {
        snprintf(err, errlen, "writing the npz file failed: %s",
                 errno ? strerror(errno) : "write error");
        return -1;
    }
    return 0;
}

int cli_npz_write(FILE *out, const cli_table_info *info, const double *data, long rows,
                  char *err, size_t errlen)
{
    const int cols = info->cols, n_y = info->n_y, n_out = cols - 1 - n_y;
    /* a run's table: t, y, outputs; a sweep's: a member per column */
    member *mbs = calloc((size_t)cols + 16, sizeof *mbs);
    if (!mbs) {
        snprintf(err, errlen, "out of memory for the npz file");
        return -1;
    }
    int n = 0, bad = 0;
    if (info->sweep) {
        for (int j = 0; j < cols; j++)
            bad |= member_columns(&mbs[n++], info->names[j], data, rows, cols, j, 1, 1);
    } else {
        bad |= member_columns(&mbs[n++], "t", data, rows, cols, 0, 1, 1);
        bad |= member_columns(&mbs[n++], info->y_name ? info->y_name : "y", data, rows, cols, 1,
                              n_y, 0);
        if (n_out > 0)
            bad |= member_columns(&mbs[n++], "outputs", data, rows, cols, 1 + n_y, n_out, 0);
    }
    bad |= member_strings(&mbs[n++], "names", info->names, cols, 0);
    bad |= member_strings(&mbs[n++], "units", info->units, cols, 0);
    const char *model = info->model;
    bad |= member_strings(&mbs[n++], "model", &model, 1, 1);
    if (info->method) {
        const char *method = info->method;
        bad |= member_strings(&mbs[n++], "method", &method, 1, 1);
    }
    if (!isnan(info->step))
        bad |= member_doubles(&mbs[n++], "step", &info->step, 1, 1);
    if (!isnan(info->rtol))
        bad |= member_doubles(&mbs[n++], "rtol", &info->rtol, 1, 1);
    if (!isnan(info->atol))
        bad |= member_doubles(&mbs[n++], "atol", &info->atol, 1, 1);
    const double span[2] = {info->t0, info->t1};
    bad |= member_doubles(&mbs[n++], "tspan", span, 2, 0);
    const char *version = DYNKIT_VERSION;
    bad |= member_strings(&mbs[n++], "dynkit", &version, 1, 1);
    int rc = 0;
    if (bad) {
        snprintf(err, errlen, "out of memory for the npz file (%ld rows of %d columns)", rows,
                 cols);
        rc = -1;
    } else {
        rc = zip_write(out, mbs, n, err, errlen);
    }
    for (int i = 0; i < n; i++)
        free(mbs[i].bytes);
    free(mbs);
    return rc;
}
