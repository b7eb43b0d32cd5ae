/* SPDX-License-Identifier: MIT */
/* bench_render.c -- part 5 of the bench: a material's renders and plots
 * (library renders, curves, and the program's files), see docs/performance.md.
 * Recorded as render/every-model/alum-bronze, plot/every-model/alum-bronze,
 * material-files/every-model/alum-bronze and render-env/MODEL/alum-bronze
 * (render-env/table/alum-bronze: the table itself). */
#include "bench_render.h"
#include "bench_record.h"
#include "internal.h"
#include "render_files.h"
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Parameters to render a model at: the published alum-bronze fit when there
 * is one, else the model's start values on a grey material. */
static brdffit_params params_of(brdffit_model m)
{
    brdffit_params p;
    if (tu_published("alum-bronze", m, &p))
        return p;
    memset(&p, 0, sizeof p);
    const brdffit_model_info *mi = brdffit_model_get(m);
    for (int c = 0; c < 3; c++)
        p.d[c] = 0.1, p.s[c] = 0.1;
    for (int k = 0; k < mi->nparams; k++)
        p.p[k] = mi->params[k].start;
    return p;
}

/* A synthetic sky: a blue gradient and a small bright sun, W x H texels. */
static float *sky(int w, int h)
{
    float *e = malloc(sizeof(float) * 3 * (size_t)w * (size_t)h);
    for (int j = 0; e && j < h; j++)
        for (int i = 0; i < w; i++) {
            float *t = e + 3 * ((size_t)j * w + i);
            double up = cos(M_PI * (j + 0.5) / h);
            t[0] = (float)(0.3 + 0.2 * up), t[1] = (float)(0.4 + 0.2 * up), t[2] = (float)(0.6 + 0.3 * up);
            if (abs(i - w / 3) < 2 && abs(j - h / 4) < 2)
                t[0] = t[1] = t[2] = 500.0f;
        }
    return e;
}

int bench_renders(int quick)
{
    char path[1024];
    brdffit_error err;
    brdffit_table *t = NULL;
    if (!tu_merl_table("alum-bronze", path, sizeof path) ||
        brdffit_table_read(path, &t, &err) != BRDFFIT_OK) {
        fprintf(stderr, "bench: alum-bronze table: %s\n", err.message);
        return 1;
    }
    int nm = BRDFFIT_MODEL_COUNT;
    rf_fit fits[RF_MAX_FITS];
    for (int m = 0; m < nm; m++) {
        memset(&fits[m], 0, sizeof fits[m]);
        fits[m].model = (brdffit_model)m;
        fits[m].params = params_of((brdffit_model)m);
        fits[m].error = NAN;
    }
    float *img = malloc(sizeof(float) * 4 * 256 * 256);
    brdffit_render_options o;
    brdffit_render_options_default(&o);
    printf("\n5. renders and plots of one material (alum-bronze, %d models), fastest of %d\n", nm,
           quick ? 1 : 3);
    double best[3] = { 1e30, 1e30, 1e30 };
    for (int r = 0; r < (quick ? 1 : 3); r++) {
        double t0 = bf_now();
        brdffit_render_table(t, &o, img, 0, NULL);
        for (int m = 0; m < nm; m++)
            brdffit_render_model(fits[m].model, &fits[m].params, &o, img, 0, NULL);
        double t1 = bf_now();
        rf_settings s;
        rf_settings_default(&s, BRDFFIT_SCALE_STANDARD);
        s.render = 0;
        if (rf_write_material("build/bench-render", "alum-bronze", t, fits, nm, &s, NULL, &err) != 0)
            fprintf(stderr, "bench: %s\n", err.message);
        double t2 = bf_now();
        s.render = 1;
        if (rf_write_material("build/bench-render", "alum-bronze", t, fits, nm, &s, NULL, &err) != 0)
            fprintf(stderr, "bench: %s\n", err.message);
        double t3 = bf_now();
        best[0] = fmin(best[0], t1 - t0), best[1] = fmin(best[1], t2 - t1), best[2] = fmin(best[2], t3 - t2);
    }
    printf("   renders 256^2, default lights, reference + every model (library): %.3f s (target <= 1 s)\n", best[0]);
    printf("   plots of every model (SVG files, curves included):               %.3f s\n", best[1]);
    printf("   all files of the material (renders EXR+PNG+diff, plots, json):   %.3f s\n", best[2]);
    bench_record("render/every-model/alum-bronze", "256^2 default lights seconds", best[0]);
    bench_record("plot/every-model/alum-bronze", "SVG files seconds", best[1]);
    bench_record("material-files/every-model/alum-bronze", "seconds", best[2]);
    o.width = 128;
    o.nlights = 0;
    o.env_width = 256, o.env_height = 128;
    float *env = sky(256, 128);
    o.env = env;
    o.env_samples = 256;
    printf("   environment 128^2, 256 samples per pixel:\n");
    double t0 = bf_now();
    brdffit_render_table(t, &o, img, 0, NULL);
    double seconds = bf_now() - t0;
    printf("     %-18s %7.3f s\n", "reference", seconds);
    bench_record("render-env/table/alum-bronze", "128^2 256 samples seconds", seconds);
    double env_s[BRDFFIT_MODEL_COUNT] = { 0 };
    for (int m = 0; m < nm; m++) {
        t0 = bf_now();
        brdffit_render_model(fits[m].model, &fits[m].params, &o, img, 0, NULL);
        env_s[m] = bf_now() - t0;
        printf("     %-18s %7.3f s\n", brdffit_model_get(fits[m].model)->name, env_s[m]);
    }
    bench_record_models("render-env", "alum-bronze", "128^2 256 samples seconds", env_s);
    free(env);
    free(img);
    brdffit_table_free(t);
    return 0;
}
