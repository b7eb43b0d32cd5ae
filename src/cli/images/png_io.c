/* SPDX-License-Identifier: MIT */
/* png_io.c -- 8-bit RGB PNG files through libpng. */
#include "image_io.h"

#include <png.h>

#include <setjmp.h>
#include <stdio.h>
#include <string.h>

typedef struct png_failure {
    char message[256];
} png_failure;

static void on_png_error(png_structp png, png_const_charp msg)
{
    png_failure *pf = png_get_error_ptr(png);
    snprintf(pf->message, sizeof pf->message, "%s", msg ? msg : "libpng error");
    png_longjmp(png, 1);
}

static void on_png_warning(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg; /* warnings are not failures; the library never prints */
}

/* libpng's longjmp leaves only volatile locals defined: the state lives here. */
typedef struct png_job {
    FILE *f;
    png_structp png;
    png_infop info;
} png_job;

static int write_rows(png_job *job, const unsigned char *rgb, int width, int height)
{
    if (setjmp(png_jmpbuf(job->png)))
        return -1;
    png_init_io(job->png, job->f);
    png_set_IHDR(job->png, job->info, (png_uint_32)width, (png_uint_32)height, 8,
                 PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB_gAMA_and_cHRM(job->png, job->info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_set_compression_level(job->png, 3); /* most of the size of 9, a fraction of the time */
    png_write_info(job->png, job->info);
    for (int y = 0; y < height; y++)
        png_write_row(job->png, rgb + 3 * (size_t)width * (size_t)y);
    png_write_end(job->png, NULL);
    return 0;
}

int png_write_rgb8(const out_dir *dir, const char *name, const unsigned char *rgb, int width,
                   int height, brdffit_error *err)
{
    png_failure pf = { "" };
    out_file o;
    if (out_open(&o, dir, name, err) != 0)
        return -1;
    png_job job = { o.f, NULL, NULL };
    int rc = -1;
    job.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &pf, on_png_error, on_png_warning);
    job.info = job.png ? png_create_info_struct(job.png) : NULL;
    if (!job.png || !job.info)
        snprintf(pf.message, sizeof pf.message, "out of memory");
    else
        rc = write_rows(&job, rgb, width, height);
    if (job.png)
        png_destroy_write_struct(&job.png, &job.info);
    if (rc != 0) {
        out_abandon(&o);
        err->status = BRDFFIT_E_FILE_WRITE;
        snprintf(err->message, sizeof err->message, "%.1700s: cannot write the PNG: %s", o.path,
                 pf.message[0] ? pf.message : "write error");
        return -1;
    }
    return out_commit(&o, err);
}
