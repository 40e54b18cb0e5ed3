/* dynkit/io.h — writing results: CSV with numbers that round-trip (%.17g).
 *
 * The library writes only to streams the caller opened and hands in; it reports failures
 * by status (DYN_ERR_IO) and never closes the stream.
 */
#ifndef DYNKIT_IO_H
#define DYNKIT_IO_H

#include <stdio.h>

#include "dynkit/model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Header line "t,<names of vars>,<names of extra>" (extra may be NULL with m = 0).
 * Returns DYN_OK or DYN_ERR_IO. */
int dyn_csv_write_header(FILE *out, const dyn_var *vars, int n, const dyn_var *extra, int m);
/* One row "t,y...,extra..." with %.17g. Returns DYN_OK or DYN_ERR_IO. */
int dyn_csv_write_row(FILE *out, double t, const double *y, int n, const double *extra, int m);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_IO_H */
