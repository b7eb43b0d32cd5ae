/* SPDX-License-Identifier: MIT */
/* draw.c -- the shared run of `render` and `plot` (see draw.h). */
#define _POSIX_C_SOURCE 200809L
#include "draw.h"
#include "image_io.h"
#include "material_fits.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int draw_init(draw_job *j, int argc)
{
    memset(j, 0, sizeof *j);
    rf_settings_default(&j->s, BRDFFIT_SCALE_STANDARD);
    j->rest = malloc((size_t)(argc > 0 ? argc : 1) * sizeof *j->rest);
    if (!j->rest) {
        cli_error("out of memory");
        return CLI_FAILED;
    }
    return CLI_OK;
}

int draw_option(int argc, char **argv, int *i, const char *name, const char **value)
{
    const char *a = argv[*i];
    size_t n = strlen(name);
    if (strncmp(a, name, n) != 0)
        return 0;
    if (a[n] == '=') {
        *value = a + n + 1;
        return 1;
    }
    if (a[n] != '\0')
        return 0;
    if (*i + 1 >= argc)
        return cli_usage_error("%s needs a value", name);
    *value = argv[++*i];
    return 1;
}

int draw_numbers(const char *s, double *v, int n)
{
    int k = 0;
    for (;;) {
        char buf[64];
        size_t len = strcspn(s, ",");
        if (k >= n || len == 0 || len >= sizeof buf)
            return -1;
        memcpy(buf, s, len);
        buf[len] = '\0';
        if (cli_parse_double(buf, &v[k++]) != 0)
            return -1;
        if (s[len] == '\0')
            return k;
        s += len + 1;
    }
}

int draw_light(const char *v, brdffit_light *l)
{
    char dir[192];
    const char *colon = strchr(v, ':');
    size_t n = colon ? (size_t)(colon - v) : strlen(v);
    double rgb[3] = { 1, 1, 1 };
    int ok = n < sizeof dir;
    if (ok) {
        memcpy(dir, v, n);
        dir[n] = '\0';
        ok = draw_numbers(dir, l->dir, 3) == 3 && (!colon || draw_numbers(colon + 1, rgb, 3) == 3);
    }
    if (!ok)
        return cli_usage_error("--light '%s': expected X,Y,Z or X,Y,Z:R,G,B (finite numbers)", v);
    if (l->dir[0] == 0 && l->dir[1] == 0 && l->dir[2] == 0)
        return cli_usage_error("--light '%s': the direction is zero", v);
    if (rgb[0] < 0 || rgb[1] < 0 || rgb[2] < 0)
        return cli_usage_error("--light '%s': the irradiance must be >= 0", v);
    memcpy(l->rgb, rgb, sizeof rgb);
    return CLI_OK;
}

int draw_common_option(draw_job *j, int argc, char **argv, int *i)
{
    const char *v;
    int r;
    if ((r = draw_option(argc, argv, i, "--out", &v)) != 0) {
        if (r == 1)
            j->out = v;
        return r != 1 ? r : CLI_OK;
    }
    if ((r = draw_option(argc, argv, i, "--fits", &v)) != 0) {
        if (r == 1)
            j->fits = v;
        return r != 1 ? r : CLI_OK;
    }
    if (strcmp(argv[*i], "--allow-scale-mismatch") == 0) {
        j->allow_scale_mismatch = 1;
        return CLI_OK;
    }
    if ((r = draw_option(argc, argv, i, "--interp", &v)) != 0) {
        if (r != 1)
            return r;
        if (strcmp(v, "trilinear") == 0 || strcmp(v, "nearest") == 0) {
            brdffit_interp in = v[0] == 't' ? BRDFFIT_INTERP_TRILINEAR : BRDFFIT_INTERP_NEAREST;
            j->s.render_opt.interp = j->s.curve_opt.interp = in;
            return CLI_OK;
        }
        return cli_usage_error("--interp '%s': expected trilinear or nearest", v);
    }
    return 1;
}

void draw_keep(draw_job *j, char *arg)
{
    j->rest[j->nrest++] = arg;
}

void draw_free(draw_job *j)
{
    cli_options_free(&j->o);
    free((void *)j->s.render_opt.env);
    free(j->rest);
    j->rest = NULL;
}

/* --env: the map into the render options. */
static int read_env(draw_job *j)
{
    float *rgb = NULL;
    int w = 0, h = 0;
    brdffit_error err;
    if (exr_read_rgb(j->env, &rgb, NULL, &w, &h, &err) != 0) {
        cli_error("--env %s", err.message);
        return CLI_FAILED;
    }
    j->s.render_opt.env = rgb;
    j->s.render_opt.env_width = w;
    j->s.render_opt.env_height = h;
    j->s.env_file = j->env;
    return CLI_OK;
}

/* The fits to draw: from --fits, or fitted now.  An exit status. */
static int get_fits(draw_job *j, const brdffit_table *t, const char *material, rf_fit *fits,
                    int *nfits)
{
    if (j->fits) {
        brdffit_error err;
        mf_scale sc = { j->o.sample.scale, j->allow_scale_mismatch };
        if (mf_read(j->fits, material, j->o.models, j->o.nmodels, &sc, fits, nfits, &err) != 0) {
            cli_error("--fits %s", err.message);
            return CLI_FAILED;
        }
        /* a TSV of parameters holds no Error: it is computed here, as score does */
        if (j->s.render && mf_score(t, &j->o.sample, &j->o.context, fits, *nfits, &err) != 0) {
            cli_error("--fits %s: %s", j->fits, err.message);
            return CLI_FAILED;
        }
        return CLI_OK;
    }
    int rc = mf_fit(t, material, j->o.models, j->o.nmodels, &j->o.sample, &j->o.fit,
                    &j->o.context, fits, nfits);
    return rc < 0 || *nfits == 0 ? CLI_FAILED : rc > 0 ? CLI_FAILED : CLI_OK;
}

static void print_summary(const draw_job *j, const char *material, const rf_fit *fits,
                          int nfits, const rf_result *r)
{
    printf("%s: files in %s\n", material, j->out);
    if (j->s.render) {
        printf("  renders %dx%d, exposure %.4g (%s), differences in L* of the PNGs, full "
               "scale +-%g\n",
               j->s.render_opt.width, j->s.render_opt.width, r->exposure,
               j->s.exposure > 0 ? "--exposure" : "from the reference", r->diff_scale);
        printf("  reference: %zu covered pixels, %zu with masked lookups (%zu filled from "
               "covered neighbours)\n", r->covered, r->masked, r->filled);
        printf("  %-18s %12s %12s %12s\n", "model", "Error", "image error", "relative RMS");
        for (int k = 0; k < nfits; k++)
            printf("  %-18s %12.4g %12.4g %12.4g\n", brdffit_model_get(fits[k].model)->name,
                   fits[k].error, r->image_error[k], r->relative_rms[k]);
    }
    for (int i = 0; i < r->nfiles; i++) {
        printf("  %-26s ", r->files[i].file);
        plain_string(stdout, r->files[i].caption);
        putchar('\n');
    }
}

static int draw_files(draw_job *j, const out_dir *d);

int draw_run(draw_job *j, const char *command)
{
    int rc = cli_parse_options(j->nrest, j->rest, &j->o);
    if (rc != CLI_OK)
        return rc;
    if (j->o.nfiles != 1)
        return cli_usage_error("%s needs one MERL table (got %d files)", command, j->o.nfiles);
    if (!j->out || !*j->out)
        return cli_usage_error("%s needs --out DIR", command);
    j->s.render_opt.scale = j->s.curve_opt.scale = j->o.sample.scale;
    brdffit_error err;
    out_dir d;
    if (od_open(&d, j->out, 1, &err) != 0) {
        cli_error("--out: %s", err.message);
        return CLI_FAILED;
    }
    rc = draw_files(j, &d);
    od_close(&d);
    return rc;
}

/* The table read, its fits got or made, the files written into d. */
static int draw_files(draw_job *j, const out_dir *d)
{
    int rc;
    brdffit_error err;
    if (j->env && (rc = read_env(j)) != CLI_OK)
        return rc;
    brdffit_table *t = NULL;
    if (brdffit_table_read(j->o.files[0], &t, &err) != BRDFFIT_OK) {
        cli_error("%s", err.message);
        cli_hint_unreadable_table(j->o.files[0]);
        return CLI_FAILED;
    }
    char name[256];
    const char *material = cli_material_name(j->o.files[0], name, sizeof name);
    rf_fit fits[RF_MAX_FITS];
    int nfits = 0;
    rc = get_fits(j, t, material, fits, &nfits);
    if (nfits > 0 || j->fits == NULL) {
        rf_result *r = malloc(sizeof *r);
        if (!r || rf_write_material_at(d, material, t, fits, nfits, &j->s, r, &err) != 0) {
            cli_error("%s", r ? err.message : "out of memory");
            rc = CLI_FAILED;
        } else {
            print_summary(j, material, fits, nfits, r);
        }
        free(r);
    }
    brdffit_table_free(t);
    return rc;
}
