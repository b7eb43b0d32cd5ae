/* SPDX-License-Identifier: MIT */
/* html_report.h -- what html_report.c, html_material.c and html_index.c share. */
#ifndef BRDFFIT_HTML_REPORT_H
#define BRDFFIT_HTML_REPORT_H

#include "batch.h"
#include "cli.h"
#include "svg.h"

/* ---- html_report.c: small text helpers, files, HTML pieces ---- */

/* x with fmt, or "-" when it is not finite. */
const char *rp_num(char *buf, size_t len, const char *fmt, double x);
/* x with sig significant digits, short ("0.006531", "2.8e4"), or "-". */
const char *rp_compact(char *buf, size_t len, int sig, double x);
/* A path segment of a relative URL: every byte but [A-Za-z0-9._~-] percent-encoded. */
const char *rp_url_segment(char *buf, size_t len, const char *s);
/* Finish a page written with the XML writer: commit it, or report the failure. */
int rp_finish(out_file *o, xml_writer *w, brdffit_error *err);
/* The rows of a material in the TSV of fits (fit_record.h): its failure, or its fits. */
void rp_tsv_material(FILE *f, const rp_report *rep, const rp_material *m);
void rp_html_begin(xml_writer *w, FILE *f, const char *title);
void rp_html_end(xml_writer *w);
void rp_link(xml_writer *w, const char *href, const char *text);
/* A warning paragraph when the published fits' scale is not the tables' (rep->scale_note). */
void rp_scale_warning(xml_writer *w, const rp_report *rep);
void rp_cell(xml_writer *w, const char *tag, const char *cls, const char *text);

/* ---- html_material.c: DIR/<material>/ ---- */

int rp_write_params_tsv(const rp_report *rep, const rp_material *m, const out_dir *dir,
                        brdffit_error *err);
int rp_write_params_json(const rp_report *rep, const rp_material *m, const out_dir *dir,
                         brdffit_error *err);
int rp_write_material_page(const rp_report *rep, const rp_material *m, int best,
                           const out_dir *dir, brdffit_error *err);

/* html_gltf.c: the .gltf file of each glTF fit of m into dir
 * (MATERIAL-MODEL.gltf, as `brdffit export` writes it), and their section
 * of m's page (the material to paste, its values in a line, the file). */
int rp_write_gltf_files(const rp_report *rep, const rp_material *m, const out_dir *dir,
                        brdffit_error *err);
void rp_gltf_section(xml_writer *w, const rp_report *rep, const rp_material *m);
/* html_mitsuba.c: each ok fit of m as a Mitsuba 3 scene into dir
 * (MATERIAL-MODEL.xml, as `brdffit export --format mitsuba` writes it), and
 * the line of m's page linking them. */
int rp_write_mitsuba_files(const rp_report *rep, const rp_material *m, const out_dir *dir,
                           brdffit_error *err);
void rp_mitsuba_section(xml_writer *w, const rp_report *rep, const rp_material *m);
/* html_energy.c: the energy section of m's page (each fit's albedo, flags, plots). */
void rp_energy_section(xml_writer *w, const rp_report *rep, const rp_material *m);

/* ---- html_index.c: DIR/ ---- */

/* html_headline.c: DIR/headline.svg */
int rp_write_headline(const rp_report *rep, const out_dir *dir, int sort_k, brdffit_error *err);
int rp_write_fits_tsv(const rp_report *rep, const out_dir *dir, brdffit_error *err);
int rp_write_index(const rp_report *rep, const out_dir *dir, int sort_k, brdffit_error *err);

#endif
