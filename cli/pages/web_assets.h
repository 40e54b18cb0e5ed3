/* SPDX-License-Identifier: BSD-3-Clause */
/* The page's files of web/ (HTML, CSS, JavaScript), embedded into the tool at build time by
 * cmake/embed_web.cmake: cli_web_assets[] in the order the build lists them. */
#ifndef DYNKIT_CLI_WEB_ASSETS_H
#define DYNKIT_CLI_WEB_ASSETS_H

#include <stddef.h>

typedef struct cli_web_asset {
    const char *name;          /* path under web/, e.g. "page.html", "js/plot.js" */
    const unsigned char *data; /* size bytes, followed by a NUL */
    size_t size;
} cli_web_asset;

extern const cli_web_asset cli_web_assets[];
extern const int cli_web_asset_count;

#endif
