/* SPDX-License-Identifier: MIT */
/* xmldoc.c -- an XML file parsed by expat into a flat list of elements (see testutil.h):
 * the independent check that what the program writes is well-formed XML. */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"

#include <expat.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct parse_state {
    tu_xml_doc *doc;
    int stack[256]; /* indices of the open elements */
    int depth;
    int oom;
} parse_state;

static char *dup_str(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d)
        memcpy(d, s, n);
    return d;
}

static void on_start(void *user, const XML_Char *name, const XML_Char **atts)
{
    parse_state *st = user;
    tu_xml_doc *doc = st->doc;
    if (st->oom || st->depth >= 256) {
        st->oom = 1;
        return;
    }
    tu_xml_elem *grown = realloc(doc->e, (size_t)(doc->n + 1) * sizeof *doc->e);
    if (!grown) {
        st->oom = 1;
        return;
    }
    doc->e = grown;
    tu_xml_elem *e = &doc->e[doc->n];
    memset(e, 0, sizeof *e);
    e->name = dup_str(name);
    e->depth = st->depth;
    int na = 0;
    while (atts[na])
        na++;
    e->attrs = calloc((size_t)na + 1, sizeof *e->attrs);
    for (int i = 0; e->attrs && i < na; i++)
        e->attrs[i] = dup_str(atts[i]);
    e->text = dup_str("");
    st->stack[st->depth++] = doc->n++;
}

static void on_end(void *user, const XML_Char *name)
{
    (void)name;
    parse_state *st = user;
    if (st->depth > 0)
        st->depth--;
}

static void on_text(void *user, const XML_Char *s, int len)
{
    parse_state *st = user;
    if (st->oom || st->depth == 0)
        return;
    tu_xml_elem *e = &st->doc->e[st->stack[st->depth - 1]];
    size_t old = strlen(e->text);
    char *t = realloc(e->text, old + (size_t)len + 1);
    if (!t) {
        st->oom = 1;
        return;
    }
    memcpy(t + old, s, (size_t)len);
    t[old + (size_t)len] = '\0';
    e->text = t;
}

int tu_xml_load(const char *path, tu_xml_doc *doc)
{
    memset(doc, 0, sizeof *doc);
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(doc->error, sizeof doc->error, "%s: cannot open", path);
        return -1;
    }
    XML_Parser p = XML_ParserCreate("UTF-8");
    parse_state st = { doc, { 0 }, 0, 0 };
    XML_SetUserData(p, &st);
    XML_SetElementHandler(p, on_start, on_end);
    XML_SetCharacterDataHandler(p, on_text);
    char buf[65536];
    int ok = 1;
    for (;;) {
        size_t n = fread(buf, 1, sizeof buf, f);
        int last = n < sizeof buf;
        if (XML_Parse(p, buf, (int)n, last) == XML_STATUS_ERROR) {
            snprintf(doc->error, sizeof doc->error, "%s: line %lu column %lu: %s", path,
                     (unsigned long)XML_GetCurrentLineNumber(p),
                     (unsigned long)XML_GetCurrentColumnNumber(p),
                     XML_ErrorString(XML_GetErrorCode(p)));
            ok = 0;
            break;
        }
        if (last)
            break;
    }
    XML_ParserFree(p);
    fclose(f);
    if (ok && st.oom) {
        snprintf(doc->error, sizeof doc->error, "%s: out of memory", path);
        ok = 0;
    }
    return ok ? 0 : -1;
}

const char *tu_xml_attr(const tu_xml_elem *e, const char *name)
{
    for (int i = 0; e->attrs && e->attrs[i] && e->attrs[i + 1]; i += 2)
        if (strcmp(e->attrs[i], name) == 0)
            return e->attrs[i + 1];
    return NULL;
}

int tu_xml_count(const tu_xml_doc *doc, const char *name)
{
    int n = 0;
    for (int i = 0; i < doc->n; i++)
        n += strcmp(doc->e[i].name, name) == 0;
    return n;
}

void tu_xml_free(tu_xml_doc *doc)
{
    for (int i = 0; i < doc->n; i++) {
        tu_xml_elem *e = &doc->e[i];
        for (int k = 0; e->attrs && e->attrs[k]; k++)
            free(e->attrs[k]);
        free(e->attrs);
        free(e->name);
        free(e->text);
    }
    free(doc->e);
    memset(doc, 0, sizeof *doc);
}
