/* SPDX-License-Identifier: MIT */
/* testutil.h -- helpers the test files share (and bench/ reuses the data ones):
 *
 *   testutil.c   ../shared data, MERL tables and sample sets, contexts,
 *                temporary files, random directions, the environment
 *   jsoncheck.c  a strict JSON parser that judges the program's --json output
 *   xmldoc.c     XML documents parsed with expat (the SVG/HTML output)
 *
 * Nothing here uses Check: helpers return a status (and a message in a
 * brdffit_error) for the caller to assert. */
#ifndef BRDFFIT_TESTUTIL_H
#define BRDFFIT_TESTUTIL_H

#include "brdffit.h"

#include <stddef.h>

/* Path of a file under ../shared (or $BRDFFIT_SHARED), into buf. */
const char *tu_shared(const char *rel, char *buf, size_t len);
/* 1 when ../shared (or $BRDFFIT_SHARED) has the tools and data the tests
 * read; else 0 and, in why, one line: what is missing and where it comes from. */
int tu_shared_present(char *why, size_t len);
/* The Check tag of the test cases that read ../shared: they are left out when
 * it is missing (tests/check_main.c).  tcase_set_tags(tc, TU_NEEDS_SHARED). */
#define TU_NEEDS_SHARED "shared"
/* Run ../shared/tools/merl-table NAME and return its path in buf (NULL on failure). */
const char *tu_merl_table(const char *name, char *buf, size_t len);
/* A fresh temporary file path (the file exists, empty) into buf. */
const char *tu_tmpfile(char *buf, size_t len);

/* A Ward-Duer table file (35 MB in $TMPDIR) for the program's tests, made
 * once for a test case by an unchecked fixture (no OpenCL in it):
 * tcase_add_unchecked_fixture(tc, tu_table_fixture_make,
 * tu_table_fixture_remove); tu_table_fixture() is its path (the test aborts,
 * saying why, when it could not be made). */
void tu_table_fixture_make(void);
void tu_table_fixture_remove(void);
const char *tu_table_fixture(void);
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

/* Run fn(arg, out, len) in a child process (a fresh fork: state the library
 * keeps per process, such as PoCL's set-up, starts anew) and copy what it
 * wrote into out back.  Returns 0 when the child exited with status 0, else
 * its exit status (or 128 + signal); what a crash or a sanitizer report
 * left on stderr stays there. */
int tu_in_child(void (*fn)(void *arg, void *out, size_t len), void *arg, void *out, size_t len);

/* What a run of the brdffit program left. */
typedef struct tu_run_out {
    int status; /* exit status; 128 + signal when killed; -1 when it could not run */
    char *out;  /* stdout, NUL-terminated (free with tu_run_free) */
    char *err;  /* stderr */
} tu_run_out;
/* Run `[env] brdffit args` through the shell ($BRDFFIT_CLI, default
 * ./build/brdffit; env such as "env -u POCL_CACHE_DIR HOME=/x" or ""; args
 * already quoted), stdin from /dev/null. */
tu_run_out tu_run_cli(const char *env, const char *args);
/* The same with the tests' build of the program, fault injection compiled in
 * ($BRDFFIT_CLI_FAULTS, default ./build/brdffit-faults): env sets BRDFFIT_FAULT. */
tu_run_out tu_run_cli_faults(const char *env, const char *args);
/* The program tu_run_cli / tu_run_cli_faults runs. */
const char *tu_cli(void);
const char *tu_cli_faults(void);
void tu_run_free(tu_run_out *r);
/* Fails the test, showing both outputs, unless the run exited with want. */
#define TU_EXPECT_STATUS(r, want, args)                                                        \
    ck_assert_msg((r).status == (want), "brdffit %s: exit %d, expected %d\nstdout:\n%s\nstderr:\n%s", \
                  (args), (r).status, (want), (r).out, (r).err)
/* The number of '\n' in s. */
int tu_count_lines(const char *s);

/* What the code between tu_capture_begin and tu_capture_end writes to file
 * descriptor 2 (a compiler inside PoCL writes its diagnostics there): kept
 * out of the test run's output, for the test to look at. */
typedef struct tu_capture {
    int saved;       /* the descriptor 2 was, -1 when nothing is captured */
    char path[512];  /* where it goes meanwhile                           */
} tu_capture;
/* Start: fd 2 into a temporary file.  0, or -1 (nothing captured). */
int tu_capture_begin(tu_capture *c);
/* End: fd 2 back; the captured text, NUL-terminated (free it; "" when
 * nothing was captured). */
char *tu_capture_end(tu_capture *c);

/* The whole of a file, NUL-terminated (free it), or NULL when it cannot be read. */
char *tu_slurp(const char *path);

/* Every lobe parameter of a model at the registry's start value (unused 0). */
void tu_start_params(brdffit_model model, double p[BRDFFIT_MAX_LOBE_PARAMS]);

/* Relative difference |a - b| / max(|a|, |b|, tiny). */
double tu_reldiff(double a, double b);

/* ---- MERL tables, sample sets and contexts ---- */

/* Read the MERL table of a material (../shared/tools/merl-table NAME). */
brdffit_status tu_merl_read(const char *material, brdffit_table **out, brdffit_error *err);
/* Its sample set with options opt (NULL: the defaults). */
brdffit_status tu_merl_samples(const char *material, const brdffit_sample_options *opt,
                               brdffit_samples **out, brdffit_error *err);
/* The sample set of a synthetic table (a Ward-Duer lobe, alpha 0.15, over a
 * Lambertian term; every bin above the horizon filled), within cutoff_deg
 * (<= 0: the default cutoff): no ../shared needed. */
brdffit_status tu_ward_duer_samples(double cutoff_deg, brdffit_samples **out, brdffit_error *err);
/* A context on backend (device: the default). */
brdffit_status tu_context(brdffit_backend backend, brdffit_context **out, brdffit_error *err);

/* ---- random directions (a fixed LCG: every run draws the same) ---- */

/* Uniform in (0, 1). */
double tu_urand(unsigned *state);
/* The unit vector at polar angle theta and azimuth phi (degrees). */
void tu_dir_at(double theta_deg, double phi_deg, double w[3]);
/* A random direction, uniform over the hemisphere where cos theta >= zmin. */
void tu_rand_dir(unsigned *state, double zmin, double w[3]);

/* ---- the environment ----
 * A test that changes OCL_ICD_VENDORS, HOME, XDG_CACHE_HOME, POCL_CACHE_DIR,
 * BRDFFIT_DEVICE or BRDFFIT_CL_OPTIONS runs in a TCase with the checked fixture
 * (tu_env_save, tu_env_restore): they are put back as they were afterwards,
 * also when it fails (and so also with CK_FORK=no). */
void tu_env_save(void);
void tu_env_restore(void);
/* The same for a caller's copy: get saves those variables, put restores them
 * (and frees the copy). */
#define TU_ENV_N 6
typedef struct tu_env {
    char *value[TU_ENV_N]; /* a copy of each value, or NULL when unset */
} tu_env;
void tu_env_get(tu_env *e);
void tu_env_put(tu_env *e);

/* Remove a directory tree (a test's temporary HOME); 0 on success. */
int tu_remove_tree(const char *path);

/* ---- jsoncheck.c: a strict JSON parser ---- */

/* 1 when line is exactly one JSON object (nothing after it). */
int tu_json_object_line(const char *line);
/* The start of member key's value in the object at obj, or NULL. */
const char *tu_json_member(const char *obj, const char *key);
/* The string member key, decoded into out; 1 on success. */
int tu_json_get_string(const char *obj, const char *key, char *out, size_t len);
/* The number member key; 1 on success. */
int tu_json_get_number(const char *obj, const char *key, double *x);
/* Element i of the number array member key; 1 on success. */
int tu_json_get_element(const char *obj, const char *key, int i, double *x);
/* Length of the array member key, or -1. */
int tu_json_array_len(const char *obj, const char *key);
/* The keys of the object at obj (text may follow it), sorted, joined by ','
 * into out; their number, or -1 when obj is not an object. */
int tu_json_keys(const char *obj, char *out, size_t len);
/* The start of element i of the array at arr (a member's value), or NULL. */
const char *tu_json_element(const char *arr, int i);

#endif
