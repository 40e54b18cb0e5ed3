/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal interface of the jit layer (src/jit): the embedded headers, SHA-256, the cache
 * directory, messages, and the two backends behind dyn_jit_load_source. */
#ifndef DYNKIT_JIT_INTERNAL_H
#define DYNKIT_JIT_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "dynkit/jit.h"

#ifndef DYNKIT_VERSION
#define DYNKIT_VERSION "unknown"
#endif

/* the public headers (include/dynkit/, every .h) as embedded at build time
 * (generated/jit_headers.c) */
typedef struct dyn_jit_header {
    const char *name; /* e.g. "model.h" */
    const unsigned char *data;
    size_t size;
} dyn_jit_header;
extern const dyn_jit_header dyn_jit_headers[];
extern const int dyn_jit_header_count;
extern const char dyn_jit_headers_hash[]; /* SHA-256 of names and contents, hex */

/* SHA-256 (FIPS 180-4), incremental */
typedef struct jit_sha256 {
    uint32_t h[8];
    uint64_t bytes;
    unsigned char buf[64];
    size_t used;
} jit_sha256;
void jit_sha256_init(jit_sha256 *s);
void jit_sha256_update(jit_sha256 *s, const void *data, size_t len);
/* the digest as 64 lowercase hex digits and a NUL into hex[65] */
void jit_sha256_hex(jit_sha256 *s, char hex[65]);

/* printf into err (always NUL-terminated when errlen > 0); returns 1 */
int jit_fail(char *err, size_t errlen, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Returned with a message when the cache cannot be written: full (ENOSPC, EDQUOT), a file
 * size limit (EFBIG), read-only (EROFS) or not permitted (EACCES, EPERM); jit_cannot_write(e)
 * says whether errno e is one of these. A refusal of the trust rules is never this. */
#define JIT_UNWRITABLE 4
int jit_cannot_write(int e);

/* The cache directory of opts (see jit.h), created (0700) with its missing parents, then
 * checked by jit_trust_cache_dir; its resolved path into dir. 0 or non-zero with a message
 * (JIT_UNWRITABLE when it cannot be created for one of the reasons above). */
int jit_cache_dir(const dyn_jit_opts *opts, char *dir, size_t size, char *err, size_t errlen);
/* <cache>/include-<version>-<hash>: the embedded headers under dynkit/, written once
 * (atomically: a whole directory renamed into place), checked by jit_include_check before
 * each use and replaced when it fails (why into note, appended). 0, JIT_UNWRITABLE or another
 * non-zero value, with a message. */
int jit_include_dir(const char *cache, char *dir, size_t size, char *note, size_t notelen,
                    char *err, size_t errlen);

/* ---- trust (jit_trust.c; docs/model-files.md, "Who may write the cache") ---- */
enum { JIT_OK = 0, JIT_ABSENT = 1, JIT_STALE = 2, JIT_REFUSED = 3 };
/* path resolved (realpath) into canon; refused unless it is a directory of this user or root,
 * not writable by group or others, under directories of this user or root that no one else
 * may write (sticky ones excepted). 0 or non-zero with a message. */
int jit_trust_cache_dir(const char *path, char *canon, size_t size, char *err, size_t errlen);
/* A compiled object of the cache, opened without following a link and checked on the open
 * descriptor: JIT_OK (*fd: a private copy of its checked bytes, -1 where memfd_create is
 * missing), JIT_ABSENT, JIT_STALE (why: to be compiled again: a link, not a regular file,
 * writable by others, truncated, or not matching the SHA-256 of its name and bytes it ends
 * with), JIT_REFUSED (err:
 * another user's). */
int jit_object_open(const char *path, int *fd, char *why, size_t whylen, char *err,
                    size_t errlen);
/* Append to a freshly compiled object the SHA-256 of the name it will have (final) and its
 * bytes; 0 or non-zero with a message. */
int jit_object_seal(const char *path, const char *final, char *err, size_t errlen);
/* The headers directory: JIT_OK, JIT_ABSENT, JIT_STALE (why) or JIT_REFUSED (err), by the
 * same rules; it must hold exactly dynkit/ with the embedded headers, byte for byte. */
int jit_include_check(const char *dir, char *why, size_t whylen, char *err, size_t errlen);
/* Move path (an entry of cache that cannot be used as it is: a directory or other file that is
 * not a regular file under an object's name, a damaged headers directory) aside to a unique
 * tmp-replaced-* name (into moved) and remove what of it is this user's; what remains goes
 * with jit_sweep_stale. 0 (also when path is gone), or -1 with errno. */
int jit_move_aside(const char *cache, const char *path, char *moved, size_t size);
/* Remove what interrupted compilations left in the cache (tmp-* entries older than an
 * hour, owned by this user). */
void jit_sweep_stale(const char *cache);
/* A name unique among concurrent processes and threads: "<prefix><pid>-<n>-<clock><suffix>"
 * inside dir. */
void jit_unique_path(const char *dir, const char *prefix, const char *suffix, char *out,
                     size_t size);
/* The text given to the compilers: `#line 1 "name"` (name escaped) so that diagnostics
 * name the user's file and lines, the source, then the model ABI stamp
 * `const unsigned dynkit_model_abi = DYN_MODEL_ABI;` after a #line of its own (one
 * translation unit: a second one would cost the system compiler a second run of cc1 and as).
 * malloc'd, NUL-terminated; NULL when out of memory. */
char *jit_source_with_line(const char *source, size_t len, const char *source_name,
                           size_t *out_len);
/* Seconds of a monotonic clock. */
double jit_now(void);

/* Check a model returned by dynkit_model() (jit_check.c): 0, or non-zero with a message
 * naming `where`. */
int jit_check_model(const dyn_model *m, const char *where, char *err, size_t errlen);

/* (jit_so.c) dlopen a shared object, check its ABI stamp and its model; `where` names it in messages
 * (the user's source for a compiled one). fd >= 0: load that file (/proc/self/fd/fd), which
 * stays open while the model is loaded (and is closed on failure); path is what so_path
 * reports. */
int jit_load_so(const char *path, int fd, const char *where, dyn_jit_model *out, char *err,
                size_t errlen);
/* Unload what jit_load_so loaded (dyn_jit_model.handle of DYN_JIT_CC). */
void jit_so_unload(void *handle);

/* Sizes of generated C (bytes) above which the system compiler gets -O1, then -O0, when no
 * flags were given, and above which DYN_JIT_AUTO compiles with libtcc (docs/model-files.md,
 * "Large models": past 1 MiB cc's compile time grows faster than the source at -O1 and -O2,
 * and at -O0 its code is no faster than libtcc's, which compiles 10 to 50 times faster). */
#define JIT_CC_O2_SOURCE (256u << 10)
#define JIT_CC_LARGE_SOURCE (1u << 20)
#define JIT_CC_MAX_SOURCE JIT_CC_LARGE_SOURCE

/* Backends: compile and load; fill out (model, handle, backend, cached, compile_seconds,
 * so_path, note). 0, or non-zero with a message: jit_cc_load returns 2 when the compiler was
 * not found, 3 when it ran out of time (JIT_CC_TIMEOUT), JIT_UNWRITABLE when the cache cannot
 * be written (why in out->note); then the caller may use libtcc. jit_tcc_load needs no cache:
 * when the headers cannot be written into it, they are put into the text in memory
 * (jit_headers_inline). */
int jit_cc_load(const char *source, size_t len, const char *source_name, const dyn_jit_opts *opts,
                dyn_jit_model *out, char *err, size_t errlen);
int jit_tcc_load(const char *source, size_t len, const char *source_name, const dyn_jit_opts *opts,
                 dyn_jit_model *out, char *err, size_t errlen);
void jit_tcc_unload(void *handle);
/* text (NUL-terminated) with each line `#include <dynkit/NAME>` or `#include "dynkit/NAME"`
 * of an embedded header replaced by the header's text, recursively, between #line lines that
 * keep the names and line numbers of diagnostics: what the compiler reads from the headers
 * directory, without one. malloc'd; NULL when out of memory. */
char *jit_headers_inline(const char *text);
/* Write len bytes to fd (0), or -1 with errno; jit_write_new: to a new file path (O_EXCL,
 * 0644). */
int jit_write_fd(int fd, const void *data, size_t len);
int jit_write_new(const char *path, const void *data, size_t len);
/* Append "text" to a note buffer ("; " between two). */
void jit_note(char *note, size_t size, const char *text);

#endif /* DYNKIT_JIT_INTERNAL_H */
