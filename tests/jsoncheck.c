/* SPDX-License-Identifier: MIT */
/* jsoncheck.c -- a small strict JSON parser for the tests: it checks that a
 * line is one well-formed JSON object (RFC 8259 grammar: no NaN, no trailing
 * comma, no raw control characters) and reads members out of it.  Written
 * independently of the program's writer (src/cli/text/json.c) so the tests can
 * judge its output.  See testutil.h. */
#include "testutil.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct jp {
    const char *p;
} jp;

static void j_ws(jp *j)
{
    while (*j->p == ' ' || *j->p == '\t' || *j->p == '\n' || *j->p == '\r')
        j->p++;
}

static int j_value(jp *j, int depth);

static int hexval(char c)
{
    return c >= '0' && c <= '9' ? c - '0'
         : c >= 'a' && c <= 'f' ? c - 'a' + 10
         : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                : -1;
}

/* A JSON string; decoded into out (when not NULL; \u escapes up to U+07FF). */
static int j_string(jp *j, char *out, size_t len)
{
    size_t n = 0;
    if (*j->p != '"')
        return 0;
    j->p++;
    for (;;) {
        unsigned char c = (unsigned char)*j->p;
        if (c == '\0' || c < 0x20)
            return 0;
        j->p++;
        if (c == '"')
            break;
        unsigned cp = c;
        if (c == '\\') {
            char e = *j->p++;
            switch (e) {
            case '"': cp = '"'; break;
            case '\\': cp = '\\'; break;
            case '/': cp = '/'; break;
            case 'b': cp = '\b'; break;
            case 'f': cp = '\f'; break;
            case 'n': cp = '\n'; break;
            case 'r': cp = '\r'; break;
            case 't': cp = '\t'; break;
            case 'u': {
                cp = 0;
                for (int k = 0; k < 4; k++) {
                    int h = hexval(*j->p++);
                    if (h < 0)
                        return 0;
                    cp = cp * 16 + (unsigned)h;
                }
                break;
            }
            default: return 0;
            }
        }
        if (out && n + 3 < len) {
            if (cp < 0x80 || c != '\\') {
                out[n++] = (char)cp;
            } else if (cp < 0x800) {
                out[n++] = (char)(0xC0 | (cp >> 6));
                out[n++] = (char)(0x80 | (cp & 0x3F));
            } else {
                out[n++] = '?';
            }
        }
    }
    if (out && len)
        out[n] = '\0';
    return 1;
}

static int j_number(jp *j, double *x)
{
    const char *s = j->p;
    if (*s == '-')
        s++;
    if (*s == '0')
        s++;
    else if (*s >= '1' && *s <= '9')
        while (*s >= '0' && *s <= '9')
            s++;
    else
        return 0;
    if (*s == '.') {
        s++;
        if (!(*s >= '0' && *s <= '9'))
            return 0;
        while (*s >= '0' && *s <= '9')
            s++;
    }
    if (*s == 'e' || *s == 'E') {
        s++;
        if (*s == '+' || *s == '-')
            s++;
        if (!(*s >= '0' && *s <= '9'))
            return 0;
        while (*s >= '0' && *s <= '9')
            s++;
    }
    if (x)
        *x = strtod(j->p, NULL);
    j->p = s;
    return 1;
}

/* An object; when key is not NULL, *val gets the start of that member's value. */
static int j_object(jp *j, int depth, const char *key, const char **val)
{
    if (*j->p != '{' || depth > 32)
        return 0;
    j->p++;
    j_ws(j);
    if (*j->p == '}') {
        j->p++;
        return 1;
    }
    for (;;) {
        char name[256];
        j_ws(j);
        if (!j_string(j, name, sizeof name))
            return 0;
        j_ws(j);
        if (*j->p++ != ':')
            return 0;
        j_ws(j);
        if (key && val && strcmp(name, key) == 0)
            *val = j->p;
        if (!j_value(j, depth + 1))
            return 0;
        j_ws(j);
        if (*j->p == ',') {
            j->p++;
            continue;
        }
        if (*j->p == '}') {
            j->p++;
            return 1;
        }
        return 0;
    }
}

static int j_array(jp *j, int depth)
{
    if (*j->p != '[' || depth > 32)
        return 0;
    j->p++;
    j_ws(j);
    if (*j->p == ']') {
        j->p++;
        return 1;
    }
    for (;;) {
        j_ws(j);
        if (!j_value(j, depth + 1))
            return 0;
        j_ws(j);
        if (*j->p == ',') {
            j->p++;
            continue;
        }
        if (*j->p == ']') {
            j->p++;
            return 1;
        }
        return 0;
    }
}

static int j_value(jp *j, int depth)
{
    switch (*j->p) {
    case '{': return j_object(j, depth, NULL, NULL);
    case '[': return j_array(j, depth);
    case '"': return j_string(j, NULL, 0);
    case 't': return strncmp(j->p, "true", 4) == 0 ? (j->p += 4, 1) : 0;
    case 'f': return strncmp(j->p, "false", 5) == 0 ? (j->p += 5, 1) : 0;
    case 'n': return strncmp(j->p, "null", 4) == 0 ? (j->p += 4, 1) : 0;
    default: return j_number(j, NULL);
    }
}

/* 1 when line is exactly one JSON object (nothing after it). */
int tu_json_object_line(const char *line)
{
    jp j = { line };
    if (!j_object(&j, 0, NULL, NULL))
        return 0;
    j_ws(&j);
    return *j.p == '\0';
}

/* The start of member key's value in the object at obj, or NULL. */
const char *tu_json_member(const char *obj, const char *key)
{
    jp j = { obj };
    const char *v = NULL;
    if (!j_object(&j, 0, key, &v))
        return NULL;
    return v;
}

int tu_json_get_string(const char *obj, const char *key, char *out, size_t len)
{
    const char *v = tu_json_member(obj, key);
    jp j = { v };
    return v && j_string(&j, out, len);
}

int tu_json_get_number(const char *obj, const char *key, double *x)
{
    const char *v = tu_json_member(obj, key);
    jp j = { v };
    return v && j_number(&j, x);
}

/* Element i of the number array member key. */
int tu_json_get_element(const char *obj, const char *key, int i, double *x)
{
    const char *v = tu_json_member(obj, key);
    if (!v || *v != '[')
        return 0;
    jp j = { v + 1 };
    for (int k = 0;; k++) {
        j_ws(&j);
        double y;
        if (!j_number(&j, &y))
            return 0;
        if (k == i) {
            *x = y;
            return 1;
        }
        j_ws(&j);
        if (*j.p++ != ',')
            return 0;
    }
}

/* Length of the number array member key, or -1. */
int tu_json_array_len(const char *obj, const char *key)
{
    const char *v = tu_json_member(obj, key);
    if (!v || *v != '[')
        return -1;
    jp j = { v };
    if (!j_array(&j, 0))
        return -1;
    int n = 0;
    for (const char *s = v + 1; s < j.p - 1; s++)
        n += (*s == ',');
    return (j.p - v > 2) ? n + 1 : 0;
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The keys of the object at obj (text may follow it), sorted, joined by ','
 * into out; the number of keys, or -1 when obj is not an object. */
int tu_json_keys(const char *obj, char *out, size_t len)
{
    char names[128][64];
    char *sorted[128];
    int n = 0;
    jp j = { obj };
    if (!obj || *j.p != '{')
        return -1;
    j.p++;
    j_ws(&j);
    if (*j.p != '}') {
        for (;;) {
            j_ws(&j);
            if (n >= 128 || !j_string(&j, names[n], sizeof names[n]))
                return -1;
            sorted[n] = names[n];
            n++;
            j_ws(&j);
            if (*j.p++ != ':')
                return -1;
            j_ws(&j);
            if (!j_value(&j, 1))
                return -1;
            j_ws(&j);
            if (*j.p == ',') {
                j.p++;
                continue;
            }
            if (*j.p == '}')
                break;
            return -1;
        }
    }
    qsort(sorted, (size_t)n, sizeof *sorted, cmp_str);
    size_t used = 0;
    out[0] = '\0';
    for (int i = 0; i < n; i++) {
        int w = snprintf(out + used, len - used, "%s%s", i ? "," : "", sorted[i]);
        if (w < 0 || (size_t)w >= len - used)
            return -1;
        used += (size_t)w;
    }
    return n;
}

/* The start of element i of the array at arr, or NULL. */
const char *tu_json_element(const char *arr, int i)
{
    if (!arr || *arr != '[')
        return NULL;
    jp j = { arr + 1 };
    for (int k = 0;; k++) {
        j_ws(&j);
        if (*j.p == ']')
            return NULL;
        if (k == i)
            return j.p;
        if (!j_value(&j, 1))
            return NULL;
        j_ws(&j);
        if (*j.p++ != ',')
            return NULL;
    }
}
