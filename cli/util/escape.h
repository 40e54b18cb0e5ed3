/* SPDX-License-Identifier: BSD-3-Clause */
/* The escaping of text from outside (names, units, descriptions, titles, file names, column
 * names of a table) for each place the tool writes it: one function per context, and no
 * other way for such text into a picture, a page or a terminal.
 *
 * - XML (SVG documents, the HTML pages' title): character data and attribute values
 *   alike (W3C XML 1.0, sec. 2.2 and 2.4; HTML's rules are looser).
 * - JSON strings (RFC 8259, sec. 7), also safe inside an HTML <script> element (HTML's
 *   "script data" state ends at "</script"; '<', '>' and '&' are written as \u escapes, so
 *   neither "</script" nor "<!--" can appear).
 *
 * Both take bytes in UTF-8: a byte that does not begin a well-formed sequence (RFC 3629: no
 * overlong forms, no surrogates, nothing above U+10FFFF), and in XML a character that XML
 * 1.0 does not allow (control characters other than tab and line ends, U+FFFE, U+FFFF),
 * become U+FFFD, so a document never fails to parse over a name. Only stdio and the
 * library's UTF-8 reader (dyn_utf8_next): the benchmark's diagrams use it too. Each
 * returns non-zero when a write failed. */
#ifndef DYNKIT_CLI_ESCAPE_H
#define DYNKIT_CLI_ESCAPE_H

#include <stdio.h>

/* s (nothing for NULL) as XML text: <, >, &, " and ' as entity references, tab, line feed
 * and carriage return as character references (kept in attribute values, where a parser
 * would turn them into spaces), the rest as above. */
int cli_xml_escaped(FILE *out, const char *s);

/* s (NULL: the empty string) as a JSON string with its quotes: '"' and '\' escaped, control
 * characters, '<', '>', '&', U+2028 and U+2029 as \u escapes (the last two end a line in
 * JavaScript before ES2019). */
int cli_json_escaped(FILE *out, const char *s);

/* s for a terminal, into buf (size > 4): dyn_terminal_text (dynkit/io.h), the one escaper
 * of messages that quote outside text (control bytes, DEL, C1 controls and bytes that are
 * not UTF-8 written \xNN; tab and line feed kept when lines is 1). Returns buf. */
const char *cli_terminal_text(const char *s, int lines, char *buf, size_t size);

#endif
