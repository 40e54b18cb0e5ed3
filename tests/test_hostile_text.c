/* SPDX-License-Identifier: BSD-3-Clause */
/* Text from outside never becomes markup. A sweep table's column names, a model file's
 * title, units and descriptions, its file name, an animation file's text and a --title are
 * written into SVG and HTML only through cli/util/escape.c, so:
 *
 * - the escaping functions give XML 1.0's and RFC 8259's forms exactly (entities, \u
 *   escapes), nothing that ends a <script> element ("</script", "<!--"), and U+FFFD for
 *   bytes that are not UTF-8 or characters XML does not allow;
 * - every SVG written from hostile names (<script>, "><img onerror=...>, ]]>, </script>,
 *   control bytes, invalid UTF-8; plots and a bifurcation diagram) parses as XML with no
 *   script element or event attribute, and the names come back intact as text
 *   (tests/markup/markup_check.py, Python's xml.etree);
 * - every page written from them (animations, a bifurcation diagram) has as many script
 *   elements as one written from plain names, no img element, and its data parses as JSON
 *   giving the names back (Python's html.parser, which splits script data where a browser
 *   does);
 * - the pages' scripts never parse a string as HTML. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "util/escape.h"
#include "test_cli_run.h"
#include "test_util.h"

#define PYTHON "/usr/bin/python3"
#define CHECKER DYNKIT_SOURCE_DIR "/tests/markup/markup_check.py"

static int setup(void **state)
{
    (void)state;
    return cli_make_tmpdir("hostile");
}

static void write_text(const char *name, const char *text)
{
    assert_int_equal(cli_write_file(name, text), 0);
}

/* s escaped by fn into a static buffer. */
static const char *escaped(int (*fn)(FILE *, const char *), const char *s)
{
    static char buf[1024];
    memset(buf, 0, sizeof buf);
    FILE *f = fmemopen(buf, sizeof buf, "w");
    assert_non_null(f);
    assert_int_equal(fn(f, s), 0);
    fclose(f);
    return buf;
}

/* "U+FFFD" in UTF-8 */
#define REPL "\xEF\xBF\xBD"

static void test_escaping_functions(void **state)
{
    (void)state;
    /* XML 1.0 sec. 2.4: markup characters as entity references, in text and attributes */
    assert_string_equal(escaped(cli_xml_escaped, "<a href=\"x\">&'</a>]]>"),
                        "&lt;a href=&quot;x&quot;&gt;&amp;&#39;&lt;/a&gt;]]&gt;");
    /* tab and line ends kept as references (an attribute would normalise them to spaces) */
    assert_string_equal(escaped(cli_xml_escaped, "a\tb\nc\rd"), "a&#9;b&#10;c&#13;d");
    /* UTF-8 kept: 2, 3 and 4 byte sequences */
    assert_string_equal(escaped(cli_xml_escaped, "\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80"),
                        "\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80");
    /* XML 1.0's Char excludes the other controls and U+FFFE; each bad byte is U+FFFD:
     * \xFF, an overlong '/', a surrogate (3 bytes), a sequence cut by the end */
    assert_string_equal(escaped(cli_xml_escaped, "a\x01" "b\x7F" "c\xEF\xBF\xBE" "d"),
                        "a" REPL "b" REPL "c" REPL "d");
    assert_string_equal(escaped(cli_xml_escaped, "\xFF|\xC0\xAF|\xED\xA0\x80|\xE2\x82"),
                        REPL "|" REPL REPL "|" REPL REPL REPL "|" REPL REPL);
    assert_string_equal(escaped(cli_xml_escaped, NULL), "");

    /* RFC 8259 sec. 7, and nothing that ends script data or opens a comment in it */
    assert_string_equal(escaped(cli_json_escaped, "</script><!--\"\\"),
                        "\"\\u003c/script\\u003e\\u003c!--\\\"\\\\\"");
    assert_string_equal(escaped(cli_json_escaped, "a\x01\n\t\r&"),
                        "\"a\\u0001\\n\\t\\r\\u0026\"");
    /* U+2028, U+2029 (line ends in JavaScript before ES2019) and a bad byte */
    assert_string_equal(escaped(cli_json_escaped, "\xE2\x80\xA8\xE2\x80\xA9\xFF\xC3\xA9"),
                        "\"\\u2028\\u2029\\ufffd\xC3\xA9\"");
    assert_string_equal(escaped(cli_json_escaped, NULL), "\"\"");
}

/* Run the checker on the file name of the temporary directory with the texts (NULL
 * terminated) that must come back; returns the number of script elements it saw. */
static int markup_check(const char *name, const char *const *texts)
{
    char cmd[8192];
    size_t n = (size_t)snprintf(cmd, sizeof cmd, "'%s' '%s' '%s'", PYTHON, CHECKER, cli_path(name));
    for (int i = 0; texts[i]; i++) {
        n += (size_t)snprintf(cmd + n, sizeof cmd - n, " '");
        for (const char *p = texts[i]; *p && n + 8 < sizeof cmd; p++)
            n += (size_t)(*p == '\'' ? snprintf(cmd + n, sizeof cmd - n, "'\\''")
                                     : snprintf(cmd + n, sizeof cmd - n, "%c", *p));
        n += (size_t)snprintf(cmd + n, sizeof cmd - n, "'");
    }
    assert_true(n < sizeof cmd);
    int status;
    char *out = cli_capture(cmd, &status);
    CHECK(status == 0 && strncmp(out, "scripts ", 8) == 0, "%s: %s", name, out);
    const int scripts = atoi(out + 8);
    free(out);
    return scripts;
}

static int have_python(void) { return access(PYTHON, X_OK) == 0; }

/* Column names of a sweep's table: two varied names and a reduced column. */
#define X_NAME "a<script>alert(1)</script>"
#define Y_NAME "b\"><img src=x onerror=alert(1)>'"
#define Z_NAME "max:]]></script><!--&amp;"
/* a control byte and a byte that is not UTF-8 */
#define BAD_NAME "c\x01" "d\xFF" "e"
#define BAD_SHOWN "c" REPL "d" REPL "e"          /* in XML */
#define BAD_JSON "c\x01" "d" REPL "e"              /* in JSON: \u0001 and \ufffd */

static void test_table_names_are_text_in_plots_and_pages(void **state)
{
    (void)state;
    if (!have_python())
        skip();
    /* a grid (heat map of cells), values at random (points), and plain names */
    write_text("grid.csv", "run," X_NAME "," Y_NAME "," Z_NAME ",status\n"
                           "0,1,1,0.5,ok\n1,2,1,0.7,ok\n2,1,2,0.1,ok\n3,2,2,0.3,ok\n");
    write_text("random.csv", "run," X_NAME "," BAD_NAME "," Z_NAME "\n"
                             "0,0.1,0.7,1\n1,0.5,0.2,2\n2,0.9,0.4,3\n3,0.3,0.9,4\n");
    write_text("plain.csv", "run,a,b,max:c,status\n"
                            "0,1,1,0.5,ok\n1,2,1,0.7,ok\n2,1,2,0.1,ok\n3,2,2,0.3,ok\n");
    static const char *const grid[] = {X_NAME, Y_NAME, Z_NAME, NULL};
    static const char *const random[] = {X_NAME, BAD_SHOWN, Z_NAME, NULL};
    cli_result r = cli_in_tmpdir("plot grid.csv --output heat.svg");
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    assert_int_equal(markup_check("heat.svg", grid), 0);
    /* lines against one varied name, a line per value of the other (a legend of names) */
    r = cli_in_tmpdir("plot grid.csv --x '" X_NAME "' --output lines.svg");
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    assert_int_equal(markup_check("lines.svg", grid), 0);
    r = cli_in_tmpdir("plot random.csv --y '" Z_NAME "' --output points.svg");
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    assert_int_equal(markup_check("points.svg", random), 0);
    /* a --title of markup, in the SVG and as the page's title */
    r = cli_in_tmpdir("plot grid.csv --title '</title><script>alert(5)</script>' --output t.svg");
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    static const char *const title[] = {"</title><script>alert(5)</script>", NULL};
    assert_int_equal(markup_check("t.svg", title), 0);

    /* pages: the same script elements as a page of plain names */
    r = cli_in_tmpdir("plot plain.csv --output plain.html");
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    static const char *const none[] = {NULL};
    const int scripts = markup_check("plain.html", none);
    assert_true(scripts >= 2);
    r = cli_in_tmpdir("plot grid.csv --output grid.html");
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    assert_int_equal(markup_check("grid.html", grid), scripts);
    r = cli_in_tmpdir("plot random.csv --title '</title><script>alert(5)</script>' "
                      "--output random.html");
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    static const char *const random_page[] = {X_NAME, BAD_JSON, Z_NAME,
                                              "</title><script>alert(5)</script>", NULL};
    assert_int_equal(markup_check("random.html", random_page), scripts);
}

/* A model file whose every free text is markup; its file name holds '&' and a quote. */
#define TITLE "<script>alert(1)</script> \"><img src=x onerror=alert(1)>"
#define DESCRIPTION "]]></script><!-- & 'q'"
#define UNIT "<script>u</script>"
#define STATE_DOC "a state \"><img onerror=alert(2)>"
#define PAR_UNIT "</script>"
#define ANI_TEXT "</script><script>alert(3)</script>"

static void test_model_text_is_text_in_plots_and_pages(void **state)
{
    (void)state;
    if (!have_python())
        skip();
    write_text("q&x'.ode", "#: title " TITLE "\n"
                           "#: description " DESCRIPTION "\n"
                           "#: x [" UNIT "] " STATE_DOC "\n"
                           "#: k [" PAR_UNIT "] stiffness ]]>\n"
                           "par k=1\nx'=-k*x\naux e=x*x\ninit x=1\ndone\n");
    write_text("q&x'.ani", "text 0.5;0.5;" ANI_TEXT "\nline 0;0;x;1\n"
                           "vtext 0.2;0.2;\"><img onerror=alert(4)>;x\nend\n");
    write_text("plain.ode", "par k=1\nx'=-k*x\ninit x=1\ndone\n");
    cli_result r = cli_in_tmpdir("plot \"q&x'.ode\" --y x,e --output model.svg");
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    static const char *const svg[] = {"x [" UNIT "]", "q&x'", NULL};
    assert_int_equal(markup_check("model.svg", svg), 0);

    r = cli_in_tmpdir("animate plain.ode --output plain.html");
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    static const char *const none[] = {NULL};
    const int scripts = markup_check("plain.html", none);
    r = cli_in_tmpdir("animate \"q&x'.ode\" --output model.html");
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    static const char *const page[] = {"dynkit animate q&x'", TITLE, UNIT, STATE_DOC, PAR_UNIT,
                                       ANI_TEXT, NULL};
    assert_int_equal(markup_check("model.html", page), scripts);

    /* a bifurcation diagram with a periodic branch (the Hopf normal form), as SVG and page */
    write_text("h&p'.ode", "#: title " TITLE "\n"
                           "#: x [" UNIT "] " STATE_DOC "\n"
                           "#: p [" PAR_UNIT "] ]]>\n"
                           "par p=-0.5\ninit x=0, y=0\n"
                           "x'=p*x-y-x*(x^2+y^2)\ny'=x+p*y-y*(x^2+y^2)\n"
                           "@ parmin=-1, parmax=1\ndone\n");
    r = cli_in_tmpdir("continue \"h&p'.ode\" --par p --output diagram.svg");
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    static const char *const diagram_svg[] = {"x [" UNIT "]", "p [" PAR_UNIT "]", "h&p'", NULL};
    assert_int_equal(markup_check("diagram.svg", diagram_svg), 0);
    r = cli_in_tmpdir("continue \"h&p'.ode\" --par p --output diagram.html");
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    static const char *const diagram_page[] = {"dynkit continue h&p': p", TITLE, UNIT, PAR_UNIT,
                                               NULL};
    assert_int_equal(markup_check("diagram.html", diagram_page), scripts);
}

/* The pages' scripts put text into the page only as text: none of them parses a string as
 * HTML (innerHTML, outerHTML, insertAdjacentHTML, document.write, eval-like constructors). */
static void test_page_scripts_never_parse_text_as_html(void **state)
{
    (void)state;
    static const char *const sinks[] = {"innerHTML", "outerHTML", "insertAdjacentHTML",
                                        "document.write", "new Function", "eval(",
                                        "createContextualFragment", NULL};
    DIR *d = opendir(DYNKIT_SOURCE_DIR "/web/js");
    assert_non_null(d);
    int files = 0;
    for (struct dirent *e; (e = readdir(d));) {
        const size_t n = strlen(e->d_name);
        if (n < 4 || strcmp(e->d_name + n - 3, ".js") != 0)
            continue;
        char path[1024];
        snprintf(path, sizeof path, "%s/web/js/%s", DYNKIT_SOURCE_DIR, e->d_name);
        char *text = cli_read_file(path, NULL);
        for (int k = 0; sinks[k]; k++)
            CHECK(!strstr(text, sinks[k]), "web/js/%s uses %s", e->d_name, sinks[k]);
        free(text);
        files++;
    }
    closedir(d);
    assert_true(files >= 5);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_escaping_functions),
        cmocka_unit_test(test_table_names_are_text_in_plots_and_pages),
        cmocka_unit_test(test_model_text_is_text_in_plots_and_pages),
        cmocka_unit_test(test_page_scripts_never_parse_text_as_html),
    };
    return cmocka_run_group_tests(tests, setup, cli_remove_tmpdir);
}
