/* SPDX-License-Identifier: MIT */
/* exr_io.c -- OpenEXR files through OpenEXR's C API (OpenEXRCore): the
 * renders out (RGBA float) and environment maps in (RGB, any pixel type). */
#define _POSIX_C_SOURCE 200809L
#include "image_io.h"
#include "cli.h"

#include <openexr.h>

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The last message OpenEXR reported (its handler has no user pointer before
 * a context exists); the program is single-threaded where it uses files. */
static _Thread_local char exr_message[512];

static void on_exr_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    snprintf(exr_message, sizeof exr_message, "%s", msg ? msg : exr_get_default_error_message(code));
}

static exr_context_initializer_t initializer(void)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = on_exr_error;
    exr_message[0] = '\0';
    return init;
}

static int fail(brdffit_error *err, brdffit_status st, const char *path, const char *what,
                exr_result_t rv)
{
    if (err) {
        err->status = st;
        if (rv == EXR_ERR_SUCCESS)
            snprintf(err->message, sizeof err->message, "%s: %s", path, what);
        else
            snprintf(err->message, sizeof err->message, "%s: %s (OpenEXR: %s)", path, what,
                     exr_message[0] ? exr_message : exr_get_default_error_message(rv));
    }
    return -1;
}

/* ------------------------------------------------------------------ writing */

/* The file (a temporary of outdir.h) is opened here and written through
 * write_fn, so that OpenEXR never creates, replaces or unlinks a path itself
 * (its default stream unlinks the path of a failed write, whatever it names). */
static int64_t write_at(exr_const_context_t ctxt, void *user, const void *buf, uint64_t sz,
                        uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    int fd = *(const int *)user;
    const char *p = buf;
    uint64_t done = 0;
    while (done < sz) {
        ssize_t n = pwrite(fd, p + done, (size_t)(sz - done), (off_t)(offset + done));
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            if (error_cb)
                error_cb(ctxt, EXR_ERR_WRITE_IO, "%s", strerror(n < 0 ? errno : EIO));
            return -1;
        }
        done += (uint64_t)n;
    }
    return (int64_t)done;
}

/* Which of R, G, B, A a channel name is (0..3), or -1. */
static int rgba_index(const char *name)
{
    static const char *const names[4] = { "R", "G", "B", "A" };
    for (int c = 0; c < 4; c++)
        if (strcmp(name, names[c]) == 0)
            return c;
    return -1;
}

/* The part's header: one scanline part of float R, G, B, A, RLE-compressed (lossless; ZIP
 * made the files 18% smaller, but its deflate took ~0.1 s of the ~0.26 s that a material's
 * renders, plots and files take: the batch's renders then outlasted the next fits). */
static exr_result_t write_header(exr_context_t f, int width, int height, int *part)
{
    exr_result_t rv = exr_add_part(f, "rgba", EXR_STORAGE_SCANLINE, part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(f, *part, width, height, EXR_COMPRESSION_RLE);
    static const char *const order[4] = { "R", "G", "B", "A" };
    for (int c = 0; c < 4 && rv == EXR_ERR_SUCCESS; c++)
        rv = exr_add_channel(f, *part, order[c], EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1, 1);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_write_header(f);
    return rv;
}

/* Every scanline chunk of the part, encoded from rgba (stride floats per row). */
static exr_result_t write_pixels(exr_context_t f, int part, const float *rgba, int height,
                                 size_t stride)
{
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    int have_enc = 0;
    int32_t lines = 1;
    exr_result_t rv = exr_get_scanlines_per_chunk(f, part, &lines);
    for (int y = 0; rv == EXR_ERR_SUCCESS && y < height; y += lines) {
        exr_chunk_info_t ci;
        rv = exr_write_scanline_chunk_info(f, part, y, &ci);
        if (rv != EXR_ERR_SUCCESS)
            break;
        rv = have_enc ? exr_encoding_update(f, part, &ci, &enc)
                      : exr_encoding_initialize(f, part, &ci, &enc);
        if (rv != EXR_ERR_SUCCESS)
            break;
        for (int k = 0; k < enc.channel_count; k++) {
            exr_coding_channel_info_t *ch = &enc.channels[k];
            int c = rgba_index(ch->channel_name);
            ch->encode_from_ptr = (const uint8_t *)(rgba + (size_t)ci.start_y * stride + c);
            ch->user_pixel_stride = 4 * (int32_t)sizeof(float);
            ch->user_line_stride = (int32_t)(stride * sizeof(float));
            ch->user_data_type = EXR_PIXEL_FLOAT;
            ch->user_bytes_per_element = 4;
        }
        if (!have_enc) {
            have_enc = 1;
            rv = exr_encoding_choose_default_routines(f, part, &enc);
            if (rv != EXR_ERR_SUCCESS)
                break;
        }
        rv = exr_encoding_run(f, part, &enc);
    }
    if (have_enc)
        exr_encoding_destroy(f, &enc);
    return rv;
}

int exr_write_rgba(const out_dir *dir, const char *name, const float *rgba, int width, int height,
                   size_t stride, brdffit_error *err)
{
    if (stride == 0)
        stride = 4 * (size_t)width;
    out_file o;
    if (out_open(&o, dir, name, err) != 0)
        return -1;
    const char *path = o.path;
    exr_context_initializer_t init = initializer();
    exr_context_t f = NULL;
    int part = 0, rc = -1, fd = fileno(o.f); /* written with pwrite alone, never through o.f */
    const char *what = "cannot write the header";
    init.user_data = &fd;
    init.write_fn = write_at;
    exr_result_t rv = exr_start_write(&f, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS)
        rv = write_header(f, width, height, &part);
    if (rv == EXR_ERR_SUCCESS) {
        what = "cannot write the pixels";
        rv = write_pixels(f, part, rgba, height, stride);
    }
    if (rv == EXR_ERR_SUCCESS)
        rc = 0;
    if (f) {
        exr_result_t fr = exr_finish(&f);
        if (rc == 0 && fr != EXR_ERR_SUCCESS) {
            rc = -1, rv = fr;
            what = "cannot finish the file";
        }
    }
    if (rc != 0) {
        fail(err, BRDFFIT_E_FILE_WRITE, path, what, rv);
        out_abandon(&o);
        return -1;
    }
    return out_commit(&o, err);
}

/* ------------------------------------------------------------------ reading */

typedef struct exr_image {
    int x0, y0, w, h;   /* data window origin and size */
    float *rgb;         /* w x h x 3 */
    float *a;           /* w x h, or NULL */
    int have[5];        /* R, G, B, A, Y present */
} exr_image;

static int channel_slot(const char *name)
{
    int c = rgba_index(name);
    return c >= 0 ? c : strcmp(name, "Y") == 0 ? 4 : -1;
}

/* Decode one chunk (scanlines or a tile at pixel x, y) into img. */
static exr_result_t decode_chunk(exr_context_t f, const exr_chunk_info_t *ci, int px, int py,
                                 exr_decode_pipeline_t *dec, int *have_dec, exr_image *img)
{
    exr_result_t rv = *have_dec ? exr_decoding_update(f, 0, ci, dec)
                                : exr_decoding_initialize(f, 0, ci, dec);
    if (rv != EXR_ERR_SUCCESS)
        return rv;
    int first = !*have_dec;
    *have_dec = 1;
    for (int k = 0; k < dec->channel_count; k++) {
        exr_coding_channel_info_t *ch = &dec->channels[k];
        int s = channel_slot(ch->channel_name);
        ch->decode_to_ptr = NULL;
        if (s < 0 || ch->height == 0 || ch->width == 0)
            continue;
        if (ch->x_samples != 1 || ch->y_samples != 1)
            continue; /* subsampled channels: refused by the caller */
        size_t at = (size_t)(py - img->y0) * (size_t)img->w + (size_t)(px - img->x0);
        if (s == 3) {
            ch->decode_to_ptr = (uint8_t *)(img->a + at);
            ch->user_pixel_stride = (int32_t)sizeof(float);
            ch->user_line_stride = (int32_t)(sizeof(float) * (size_t)img->w);
        } else {
            int c = s == 4 ? 0 : s;
            ch->decode_to_ptr = (uint8_t *)(img->rgb + 3 * at + c);
            ch->user_pixel_stride = 3 * (int32_t)sizeof(float);
            ch->user_line_stride = (int32_t)(3 * sizeof(float) * (size_t)img->w);
        }
        ch->user_data_type = EXR_PIXEL_FLOAT;
        ch->user_bytes_per_element = 4;
    }
    if (first) {
        rv = exr_decoding_choose_default_routines(f, 0, dec);
        if (rv != EXR_ERR_SUCCESS)
            return rv;
    }
    return exr_decoding_run(f, 0, dec);
}

static exr_result_t read_pixels(exr_context_t f, exr_storage_t storage, exr_image *img,
                                const char **what)
{
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    int have_dec = 0;
    exr_result_t rv = EXR_ERR_SUCCESS;
    *what = "cannot read the pixels";
    if (storage == EXR_STORAGE_SCANLINE) {
        int32_t lines = 1;
        rv = exr_get_scanlines_per_chunk(f, 0, &lines);
        for (int y = img->y0; rv == EXR_ERR_SUCCESS && y < img->y0 + img->h; y += lines) {
            exr_chunk_info_t ci;
            rv = exr_read_scanline_chunk_info(f, 0, y, &ci);
            if (rv == EXR_ERR_SUCCESS)
                rv = decode_chunk(f, &ci, img->x0, ci.start_y, &dec, &have_dec, img);
        }
    } else {
        int32_t tw = 0, th = 0;
        rv = exr_get_tile_sizes(f, 0, 0, 0, &tw, &th);
        if (rv == EXR_ERR_SUCCESS && (tw <= 0 || th <= 0))
            rv = EXR_ERR_BAD_CHUNK_LEADER;
        int nx = rv == EXR_ERR_SUCCESS ? (img->w + tw - 1) / tw : 0;
        int ny = rv == EXR_ERR_SUCCESS ? (img->h + th - 1) / th : 0;
        for (int ty = 0; rv == EXR_ERR_SUCCESS && ty < ny; ty++)
            for (int tx = 0; rv == EXR_ERR_SUCCESS && tx < nx; tx++) {
                exr_chunk_info_t ci;
                rv = exr_read_tile_chunk_info(f, 0, tx, ty, 0, 0, &ci);
                if (rv == EXR_ERR_SUCCESS)
                    rv = decode_chunk(f, &ci, img->x0 + tx * tw, img->y0 + ty * th, &dec,
                                      &have_dec, img);
            }
    }
    if (have_dec)
        exr_decoding_destroy(f, &dec);
    return rv;
}

/* The part's channels: which of R, G, B, A, Y it has; a message when unusable. */
static const char *check_channels(exr_context_t f, exr_image *img)
{
    const exr_attr_chlist_t *chl = NULL;
    if (exr_get_channels(f, 0, &chl) != EXR_ERR_SUCCESS || !chl)
        return "no channel list";
    for (int k = 0; k < chl->num_channels; k++) {
        const exr_attr_chlist_entry_t *e = &chl->entries[k];
        int s = channel_slot(e->name.str);
        if (s < 0)
            continue;
        if (e->x_sampling != 1 || e->y_sampling != 1)
            return "subsampled R/G/B/A/Y channels are not supported";
        img->have[s] = 1;
    }
    if (!(img->have[0] && img->have[1] && img->have[2]) && !img->have[4])
        return "no R, G, B (or Y) channels";
    return NULL;
}

/* The file's layout: one scanline or tiled part with a plausible data window
 * (into img).  What OpenEXR could not read is its status; a layout it read
 * but that is not supported here is EXR_ERR_SUCCESS with *refusal set. */
static exr_result_t read_layout(exr_context_t f, exr_image *img, exr_storage_t *storage,
                                const char **refusal)
{
    int parts = 0;
    exr_attr_box2i_t dw;
    exr_result_t rv = exr_get_count(f, &parts);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_storage(f, 0, storage);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_data_window(f, 0, &dw);
    if (rv != EXR_ERR_SUCCESS)
        return rv;
    if (*storage != EXR_STORAGE_SCANLINE && *storage != EXR_STORAGE_TILED) {
        *refusal = "deep images are not supported";
        return EXR_ERR_SUCCESS;
    }
    if (parts != 1) {
        *refusal = "multi-part files are not supported (one part of R, G, B)";
        return EXR_ERR_SUCCESS;
    }
    img->x0 = dw.min.x, img->y0 = dw.min.y;
    img->w = dw.max.x - dw.min.x + 1, img->h = dw.max.y - dw.min.y + 1;
    if (img->w < 1 || img->h < 1 || (double)img->w * img->h > 1e9) {
        *refusal = "impossible data window";
        return EXR_ERR_SUCCESS;
    }
    return EXR_ERR_SUCCESS;
}

/* The first texel that is not finite and >= 0, described into buf; NULL if none. */
static const char *bad_texel(const exr_image *img, char *buf, size_t len)
{
    for (size_t i = 0; i < (size_t)img->w * (size_t)img->h * 3; i++)
        if (!isfinite(img->rgb[i]) || img->rgb[i] < 0) {
            snprintf(buf, len, "pixel (%zu, %zu) channel %c is %g (radiance must be finite and >= 0)",
                     (i / 3) % (size_t)img->w, (i / 3) / (size_t)img->w, "RGB"[i % 3],
                     (double)img->rgb[i]);
            return buf;
        }
    return NULL;
}

/* Reading goes through a descriptor opened here (cli_open_regular): a FIFO or
 * a device is refused before OpenEXR would open and wait on it. */
static int64_t read_at(exr_const_context_t ctxt, void *user, void *buf, uint64_t sz,
                       uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    int fd = *(const int *)user;
    char *p = buf;
    uint64_t done = 0;
    while (done < sz) {
        ssize_t r = pread(fd, p + done, (size_t)(sz - done), (off_t)(offset + done));
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0) {
            error_cb(ctxt, EXR_ERR_READ_IO, "cannot read: %s", strerror(errno));
            return -1;
        }
        if (r == 0)
            break;
        done += (uint64_t)r;
    }
    return (int64_t)done;
}

static int64_t size_of(exr_const_context_t ctxt, void *user)
{
    (void)ctxt;
    struct stat st;
    return fstat(*(const int *)user, &st) == 0 ? (int64_t)st.st_size : -1;
}

int exr_read_rgb(const char *path, float **rgb, float **alpha, int *width, int *height,
                 brdffit_error *err)
{
    exr_context_initializer_t init = initializer();
    exr_context_t f = NULL;
    exr_image img;
    memset(&img, 0, sizeof img);
    const char *what = "not a readable OpenEXR file";
    char texel[160];
    int rc = -1;
    brdffit_status st = BRDFFIT_E_FILE_READ;
    *rgb = NULL;
    if (alpha)
        *alpha = NULL;
    brdffit_error oerr;
    int fd = cli_open_regular(path, &oerr);
    if (fd < 0) {
        if (err)
            *err = oerr;
        return -1;
    }
    init.user_data = &fd;
    init.read_fn = read_at;
    init.size_fn = size_of;
    exr_result_t rv = exr_start_read(&f, path, &init);
    if (rv == EXR_ERR_FILE_ACCESS)
        st = BRDFFIT_E_FILE_OPEN;
    if (rv != EXR_ERR_SUCCESS)
        goto done;
    exr_storage_t storage = EXR_STORAGE_SCANLINE;
    const char *bad = NULL;
    rv = read_layout(f, &img, &storage, &bad);
    if (rv != EXR_ERR_SUCCESS || bad) {
        what = bad ? bad : what;
        goto done;
    }
    bad = check_channels(f, &img);
    if (bad) {
        what = bad;
        rv = EXR_ERR_SUCCESS; /* OpenEXR had nothing to say */
        goto done;
    }
    size_t npix = (size_t)img.w * (size_t)img.h;
    img.rgb = calloc(npix * 3, sizeof(float));
    img.a = malloc(npix * sizeof(float));
    if (!img.rgb || !img.a) {
        what = "out of memory";
        goto done;
    }
    for (size_t i = 0; i < npix; i++)
        img.a[i] = 1.0f;
    rv = read_pixels(f, storage, &img, &what);
    if (rv != EXR_ERR_SUCCESS)
        goto done;
    if (!img.have[0] && img.have[4]) /* grey: Y into G and B too */
        for (size_t i = 0; i < npix; i++)
            img.rgb[3 * i + 1] = img.rgb[3 * i + 2] = img.rgb[3 * i];
    if ((bad = bad_texel(&img, texel, sizeof texel)) != NULL) {
        what = bad;
        st = BRDFFIT_E_FILE_NONFINITE;
        goto done;
    }
    rc = 0;
done:
    if (f)
        exr_finish(&f);
    close(fd);
    if (rc != 0) {
        free(img.rgb);
        free(img.a);
        return fail(err, st, path, what, rv);
    }
    *rgb = img.rgb;
    if (alpha)
        *alpha = img.a;
    else
        free(img.a);
    *width = img.w;
    *height = img.h;
    return 0;
}
