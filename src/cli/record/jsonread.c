/* SPDX-License-Identifier: MIT */
/* jsonread.c -- a small strict reader for the flat JSON objects of the journal:
 * members with null, booleans, numbers, strings (well-formed UTF-8 only, as
 * json.c writes them; its \udc80..\udcff escapes become the bytes 0x80..0xff
 * that were not UTF-8), arrays of numbers (nulls and strings in them read as
 * NAN; the strings of an array kept in its str, one a line) and one level of
 * nested flat objects. */
#include "batch.h"
#include "utf8.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct jr_parser {
    const char *p;
    jr_object *o;
} jr_parser;

static void ws(jr_parser *j)
{
    while (*j->p == ' ' || *j->p == '\t' || *j->p == '\n' || *j->p == '\r')
        j->p++;
}

static int hexval(char c)
{
    return c >= '0' && c <= '9' ? c - '0'
         : c >= 'a' && c <= 'f' ? c - 'a' + 10
         : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                : -1;
}

static int hex4(const char *s, unsigned *cp)
{
    unsigned v = 0;
    for (int k = 0; k < 4; k++) {
        int h = hexval(s[k]);
        if (h < 0)
            return -1;
        v = v * 16 + (unsigned)h;
    }
    *cp = v;
    return 0;
}

static size_t put_utf8(char *out, unsigned cp)
{
    if (cp < 0x80) {
        out[0] = (char)cp;
        return 1;
    }
    if (cp < 0x800) {
        out[0] = (char)(0xC0 | (cp >> 6));
        out[1] = (char)(0x80 | (cp & 0x3F));
        return 2;
    }
    if (cp < 0x10000) {
        out[0] = (char)(0xE0 | (cp >> 12));
        out[1] = (char)(0x80 | ((cp >> 6) & 0x3F));
        out[2] = (char)(0x80 | (cp & 0x3F));
        return 3;
    }
    out[0] = (char)(0xF0 | (cp >> 18));
    out[1] = (char)(0x80 | ((cp >> 12) & 0x3F));
    out[2] = (char)(0x80 | ((cp >> 6) & 0x3F));
    out[3] = (char)(0x80 | (cp & 0x3F));
    return 4;
}

/* A string at j->p; decoded into a new buffer (*out, when out is not NULL). */
static int string(jr_parser *j, char **out)
{
    if (*j->p != '"')
        return -1;
    const char *s = ++j->p;
    size_t cap = 0;
    while (s[cap] && s[cap] != '"') /* an upper bound of the decoded length */
        cap += s[cap] == '\\' && s[cap + 1] ? 2 : 1;
    char *buf = malloc(cap * 2 + 8);
    if (!buf)
        return -1;
    size_t n = 0;
    for (;;) {
        unsigned char c = (unsigned char)*j->p;
        if (c == '\0' || c < 0x20)
            goto bad;
        j->p++;
        if (c == '"')
            break;
        if (c >= 0x80) { /* raw UTF-8: well-formed, as the writer writes it */
            unsigned cp;
            int len = utf8_seq((const unsigned char *)j->p - 1, &cp);
            if (len == 0)
                goto bad;
            memcpy(buf + n, j->p - 1, (size_t)len);
            n += (size_t)len;
            j->p += len - 1;
            continue;
        }
        if (c != '\\') {
            buf[n++] = (char)c;
            continue;
        }
        char e = *j->p++;
        unsigned cp;
        switch (e) {
        case '"': cp = '"'; break;
        case '\\': cp = '\\'; break;
        case '/': cp = '/'; break;
        case 'b': cp = '\b'; break;
        case 'f': cp = '\f'; break;
        case 'n': cp = '\n'; break;
        case 'r': cp = '\r'; break;
        case 't': cp = '\t'; break;
        case 'u':
            if (hex4(j->p, &cp) != 0)
                goto bad;
            j->p += 4;
            if (cp >= 0xD800 && cp <= 0xDBFF && j->p[0] == '\\' && j->p[1] == 'u') {
                unsigned lo;
                if (hex4(j->p + 2, &lo) == 0 && lo >= 0xDC00 && lo <= 0xDFFF) {
                    cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
                    j->p += 6;
                }
            }
            if (cp >= 0xDC80 && cp <= 0xDCFF) { /* a byte that is not UTF-8 (json.c) */
                buf[n++] = (char)(cp - 0xDC00);
                continue;
            }
            if (cp >= 0xD800 && cp <= 0xDFFF)
                cp = 0xFFFD;
            break;
        default: goto bad;
        }
        n += put_utf8(buf + n, cp);
    }
    buf[n] = '\0';
    if (out)
        *out = buf;
    else
        free(buf);
    return 0;
bad:
    free(buf);
    return -1;
}

static int number(jr_parser *j, double *x)
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
        return -1;
    if (*s == '.') {
        s++;
        if (!(*s >= '0' && *s <= '9'))
            return -1;
        while (*s >= '0' && *s <= '9')
            s++;
    }
    if (*s == 'e' || *s == 'E') {
        s++;
        if (*s == '+' || *s == '-')
            s++;
        if (!(*s >= '0' && *s <= '9'))
            return -1;
        while (*s >= '0' && *s <= '9')
            s++;
    }
    /* a number beyond the double range (1e999) is refused: it would read as
     * inf, which no writer here writes and JSON cannot say back */
    double v = strtod(j->p, NULL);
    if (!isfinite(v))
        return -1;
    *x = v;
    j->p = s;
    return 0;
}

static int literal(jr_parser *j, const char *word)
{
    size_t n = strlen(word);
    if (strncmp(j->p, word, n) != 0)
        return -1;
    j->p += n;
    return 0;
}

static int object(jr_parser *j, int depth);

static int value(jr_parser *j, jr_member *m, int depth)
{
    ws(j);
    char c = *j->p;
    if (c == '"') {
        m->type = JR_STRING;
        return string(j, &m->str);
    }
    if (c == 'n') {
        m->type = JR_NULL;
        m->num = NAN;
        return literal(j, "null");
    }
    if (c == 't' || c == 'f') {
        m->type = JR_BOOL;
        m->num = c == 't';
        return literal(j, c == 't' ? "true" : "false");
    }
    if (c == '[') {
        m->type = JR_ARRAY;
        j->p++;
        ws(j);
        if (*j->p == ']') {
            j->p++;
            return 0;
        }
        for (;;) {
            ws(j);
            double x;
            if (*j->p == 'n') {
                if (literal(j, "null") != 0)
                    return -1;
                x = NAN;
            } else if (*j->p == '"') { /* a string element: NAN, its text in str */
                char *str = NULL;
                if (string(j, &str) != 0)
                    return -1;
                size_t had = m->str ? strlen(m->str) : 0, add = strlen(str);
                char *joined = realloc(m->str, had + add + 2);
                if (!joined) {
                    free(str);
                    return -1;
                }
                if (had)
                    joined[had++] = '\n';
                memcpy(joined + had, str, add + 1);
                m->str = joined;
                free(str);
                x = NAN;
            } else if (number(j, &x) != 0) {
                return -1;
            }
            if (m->narr >= JR_MAX_ARRAY)
                return -1;
            m->arr[m->narr++] = x;
            ws(j);
            if (*j->p == ',') {
                j->p++;
                continue;
            }
            if (*j->p == ']') {
                j->p++;
                return 0;
            }
            return -1;
        }
    }
    if (c == '{') {
        if (depth >= 1)
            return -1;
        m->type = JR_OBJECT;
        m->sub = j->o->n;
        int rc = object(j, depth + 1);
        m->nsub = j->o->n - m->sub;
        return rc;
    }
    m->type = JR_NUMBER;
    return number(j, &m->num);
}

static int object(jr_parser *j, int depth)
{
    ws(j);
    if (*j->p != '{')
        return -1;
    j->p++;
    ws(j);
    if (*j->p == '}') {
        j->p++;
        return 0;
    }
    for (;;) {
        ws(j);
        char *key = NULL;
        if (string(j, &key) != 0)
            return -1;
        if (strlen(key) >= sizeof j->o->m[0].key || j->o->n >= JR_MAX_MEMBERS) {
            free(key);
            return -1;
        }
        /* members of a nested object are stored after its own slot */
        int slot = j->o->n++;
        jr_member *m = &j->o->m[slot];
        memset(m, 0, sizeof *m);
        strcpy(m->key, key);
        free(key);
        ws(j);
        if (*j->p++ != ':')
            return -1;
        if (value(j, &j->o->m[slot], depth) != 0)
            return -1;
        ws(j);
        if (*j->p == ',') {
            j->p++;
            continue;
        }
        if (*j->p == '}') {
            j->p++;
            return 0;
        }
        return -1;
    }
}

int jr_parse(const char *s, jr_object *o)
{
    memset(o, 0, sizeof *o);
    jr_parser j = { s, o };
    if (object(&j, 0) != 0) {
        jr_free(o);
        return -1;
    }
    ws(&j);
    if (*j.p != '\0') {
        jr_free(o);
        return -1;
    }
    return 0;
}

void jr_free(jr_object *o)
{
    for (int i = 0; i < o->n; i++) {
        free(o->m[i].str);
        o->m[i].str = NULL;
    }
    o->n = 0;
}

/* Top-level members: those not inside a nested object. */
const jr_member *jr_get(const jr_object *o, const char *key)
{
    for (int i = 0; i < o->n; i++) {
        const jr_member *m = &o->m[i];
        if (strcmp(m->key, key) == 0)
            return m;
        if (m->type == JR_OBJECT)
            i += m->nsub;
    }
    return NULL;
}

const jr_member *jr_get_in(const jr_object *o, const jr_member *obj, const char *key)
{
    if (!obj || obj->type != JR_OBJECT)
        return NULL;
    for (int i = obj->sub; i < obj->sub + obj->nsub && i < o->n; i++)
        if (strcmp(o->m[i].key, key) == 0)
            return &o->m[i];
    return NULL;
}
