/* testutil.h -- helpers the test files share: ../shared data, temporary files. */
#ifndef BRDFFIT_TESTUTIL_H
#define BRDFFIT_TESTUTIL_H

#include "brdffit.h"

#include <stddef.h>

/* Path of a file under ../shared (or $BRDFFIT_SHARED), into buf. */
const char *tu_shared(const char *rel, char *buf, size_t len);
/* Run ../shared/tools/merl-table NAME and return its path in buf (NULL on failure). */
const char *tu_merl_table(const char *name, char *buf, size_t len);
/* A fresh temporary file path (the file exists, empty) into buf. */
const char *tu_tmpfile(char *buf, size_t len);
/* Write len bytes to path; 0 on success. */
int tu_write_bytes(const char *path, const void *data, size_t len);

/* One row of a TSV file split into fields (tabs); comment lines start with '#'.
 * Returns the number of fields, 0 at end of file.  fields point into line. */
int tu_tsv_next(void *file, char *line, size_t len, char **fields, int maxfields);

/* d, s and p of a row of ngan2005-fits.tsv or model-reference.tsv (fields 2..10:
 * d_r d_g d_b s_r s_g s_b p0 p1 p2; an empty p is 0). */
void tu_params_from_row(char **fields, brdffit_params *p);
/* The published Ngan et al. parameters of a material and model; 0 if absent. */
int tu_published(const char *material, brdffit_model model, brdffit_params *p);

/* All published rows of a model: up to max parameter sets and their material
 * names (names may be NULL).  Returns the number of rows. */
int tu_published_all(brdffit_model model, brdffit_params *params, char (*names)[64], int max);

/* An XML file parsed (expat) into its elements in document order. */
typedef struct tu_xml_elem {
    char *name;
    char **attrs;  /* name, value, name, value, ..., NULL */
    char *text;    /* the character data directly inside it, concatenated */
    int depth;     /* 0 for the root */
} tu_xml_elem;
typedef struct tu_xml_doc {
    tu_xml_elem *e;
    int n;
    char error[512]; /* "path: line L column C: message" when not well-formed */
} tu_xml_doc;
/* 0 when path is well-formed XML (doc filled; free with tu_xml_free), else -1. */
int tu_xml_load(const char *path, tu_xml_doc *doc);
/* The value of an attribute of e, or NULL. */
const char *tu_xml_attr(const tu_xml_elem *e, const char *name);
/* How many elements are called name. */
int tu_xml_count(const tu_xml_doc *doc, const char *name);
void tu_xml_free(tu_xml_doc *doc);

/* Relative difference |a - b| / max(|a|, |b|, tiny). */
double tu_reldiff(double a, double b);

#endif
