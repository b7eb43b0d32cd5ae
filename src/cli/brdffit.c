/* brdffit.c -- the brdffit program: subcommands fit, demo, models, eval;
 * --help, --version.  Exit status 0 success, 1 a file or fit failed,
 * 2 a usage error.  See cli.h for the other files. */
#include "cli.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *f)
{
    char names[512];
    fprintf(f,
            "Usage: brdffit COMMAND [ARGUMENTS]\n"
            "\n"
            "Fit the analytic BRDF models of Ngan, Durand & Matusik (EGSR 2005) to MERL\n"
            "measured reflectance tables (.binary), with the library's \"%s\" Error.\n"
            "\n"
            "Commands:\n"
            "  fit FILE.binary... [OPTIONS]  fit the models to each table and print the fitted\n"
            "                                parameters (paper units) and their Error\n"
            "  demo [OPTIONS]                fit every model to a built-in synthetic material\n"
            "                                (Cook-Torrance at published alum-bronze values; no files)\n"
            "  models                        list the models, their lobe parameters and bounds\n"
            "  eval MODEL d_r d_g d_b s_r s_g s_b p0 [p1 [p2]] --wi X Y Z --wo X Y Z\n"
            "                                print f(wi, wo) per channel (1/sr, no cosine factor)\n"
            "\n"
            "Options of fit and demo:\n"
            "  --model NAME[,NAME...]|all    models to fit (repeatable; default all):\n"
            "                                %s\n"
            "  --scale standard|flat         channel scale of the stored values (default standard,\n"
            "                                (1, 1.15, 1.66)/1500; flat = 1/1500, as Ngan et al.)\n"
            "  --cutoff DEG                  fit directions with theta_i, theta_o <= DEG, in (0, 90]\n"
            "                                (default 80)\n"
            "  --starts N                    starting points screened per model, 1..1000 (default 8; He 7)\n"
            "  --backend auto|opencl|host    where the data passes run (default auto: OpenCL when a\n"
            "                                device is found, else C on the host)\n"
            "  --device SPEC                 OpenCL device, PLATFORM:DEVICE by index or name\n"
            "                                substring (default $BRDFFIT_DEVICE, else PoCL's CPU)\n"
            "  --json                        one JSON object per fit per line (JSON Lines)\n"
            "\n"
            "  brdffit --help | --version\n"
            "\n"
            "Exit status: 0 success; 1 a file could not be read or a fit failed (the other\n"
            "files and models are still fitted); 2 a usage error.\n"
            "PoCL caches kernel builds in $POCL_CACHE_DIR (set to a user cache when unset).\n",
            brdffit_metric_name(), cli_model_names(names, sizeof names));
}

/* ------------------------------------------------------------------ models */

static int cmd_models(int argc, char **argv)
{
    if (argc > 0) {
        if (strcmp(argv[0], "--help") == 0 || strcmp(argv[0], "-h") == 0) {
            usage(stdout);
            return CLI_OK;
        }
        return cli_usage_error("models takes no arguments (got '%s')", argv[0]);
    }
    printf("%-18s %-18s %s\n", "model", "title", "lobe parameters: name [lower, upper] (start)");
    for (int m = 0; m < BRDFFIT_MODEL_COUNT; m++) {
        const brdffit_model_info *mi = brdffit_model_get((brdffit_model)m);
        printf("%-18s %-18s", mi->name, mi->title);
        for (int k = 0; k < mi->nparams; k++)
            printf("%s %s [%g, %g] (%g)", k ? "," : "", mi->param_names[k], mi->lower[k],
                   mi->upper[k], mi->start[k]);
        printf("%s\n", mi->chromatic ? "; per-channel lobe" : "");
    }
    printf("\nEvery model: f_c = d_c/pi + s_c K_c(wi, wo; p) per channel c = R, G, B;\n"
           "d_c, s_c >= 0.  He: tau and sigma0 in micrometres, n a refractive index,\n"
           "wavelengths 0.645, 0.526, 0.444 um.\n");
    return CLI_OK;
}

/* ------------------------------------------------------------------ eval */

static int parse_vec3(int argc, char **argv, int *i, const char *name, double v[3])
{
    if (*i + 3 >= argc)
        return cli_usage_error("%s needs three numbers X Y Z", name);
    for (int c = 0; c < 3; c++) {
        const char *a = argv[++*i];
        if (cli_parse_double(a, &v[c]) != 0)
            return cli_usage_error("%s: '%s' is not a finite number", name, a);
    }
    return CLI_OK;
}

static int cmd_eval(int argc, char **argv)
{
    const char *model_name = NULL;
    double nums[6 + BRDFFIT_MAX_LOBE_PARAMS];
    int nnum = 0, have_wi = 0, have_wo = 0;
    double wi[3], wo[3];
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            return CLI_OK;
        }
        if (strcmp(a, "--wi") == 0 || strcmp(a, "--wo") == 0) {
            int rc = parse_vec3(argc, argv, &i, a, a[3] == 'i' ? wi : wo);
            if (rc != CLI_OK)
                return rc;
            *(a[3] == 'i' ? &have_wi : &have_wo) = 1;
            continue;
        }
        if (a[0] == '-' && a[1] == '-')
            return cli_usage_error("eval: unknown option '%s'", a);
        if (!model_name) {
            model_name = a;
            continue;
        }
        if (nnum >= (int)(sizeof nums / sizeof nums[0]))
            return cli_usage_error("eval: too many numbers (at '%s')", a);
        if (cli_parse_double(a, &nums[nnum]) != 0)
            return cli_usage_error("eval: '%s' is not a finite number", a);
        nnum++;
    }
    char names[512];
    brdffit_model model;
    if (!model_name)
        return cli_usage_error("eval needs MODEL d_r d_g d_b s_r s_g s_b p... --wi X Y Z --wo X Y Z");
    if (brdffit_model_from_name(model_name, &model) != BRDFFIT_OK)
        return cli_usage_error("unknown model '%s' (valid: %s)", model_name,
                               cli_model_names(names, sizeof names));
    const brdffit_model_info *mi = brdffit_model_get(model);
    if (nnum != 6 + mi->nparams) {
        char pn[128] = "";
        for (int k = 0; k < mi->nparams; k++) {
            strcat(pn, " ");
            strncat(pn, mi->param_names[k], 32);
        }
        return cli_usage_error("eval %s needs %d numbers (d_r d_g d_b s_r s_g s_b%s), got %d",
                               mi->name, 6 + mi->nparams, pn, nnum);
    }
    if (!have_wi || !have_wo)
        return cli_usage_error("eval needs --wi X Y Z and --wo X Y Z");

    brdffit_params p;
    memset(&p, 0, sizeof p);
    memcpy(p.d, nums, sizeof p.d);
    memcpy(p.s, nums + 3, sizeof p.s);
    memcpy(p.p, nums + 6, (size_t)mi->nparams * sizeof p.p[0]);
    brdffit_error err;
    memset(&err, 0, sizeof err);
    if (brdffit_params_check(model, &p, &err) != BRDFFIT_OK)
        return cli_usage_error("eval: %s", err.message);
    double rgb[3];
    brdffit_status st = brdffit_eval(model, &p, wi, wo, rgb);
    if (st != BRDFFIT_OK)
        return cli_usage_error("eval: %s (directions must be finite and non-zero)",
                               brdffit_strerror(st));
    printf("%.17g %.17g %.17g\n", rgb[0], rgb[1], rgb[2]);
    return CLI_OK;
}

/* ------------------------------------------------------------------ fit, demo */

static int cmd_fit_or_demo(int argc, char **argv, int demo)
{
    cli_options o;
    int rc = cli_parse_options(argc, argv, &o);
    if (rc == -1) {
        usage(stdout);
        rc = CLI_OK;
    } else if (rc == CLI_OK) {
        if (demo && o.nfiles > 0)
            rc = cli_usage_error("demo takes no files (got '%s')", o.files[0]);
        else if (!demo && o.nfiles == 0)
            rc = cli_usage_error("fit needs at least one MERL .binary file");
        else
            rc = demo ? cli_run_demo(&o) : cli_run_fit(&o);
    }
    cli_options_free(&o);
    return rc;
}

/* ------------------------------------------------------------------ main */

int main(int argc, char **argv)
{
    int rc;
    if (argc < 2) {
        usage(stderr);
        return CLI_USAGE;
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "help") == 0) {
        usage(stdout);
        rc = CLI_OK;
    } else if (strcmp(cmd, "--version") == 0 || strcmp(cmd, "version") == 0) {
        printf("brdffit %s\n", brdffit_version());
        rc = CLI_OK;
    } else if (strcmp(cmd, "fit") == 0) {
        rc = cmd_fit_or_demo(argc - 2, argv + 2, 0);
    } else if (strcmp(cmd, "demo") == 0) {
        rc = cmd_fit_or_demo(argc - 2, argv + 2, 1);
    } else if (strcmp(cmd, "models") == 0) {
        rc = cmd_models(argc - 2, argv + 2);
    } else if (strcmp(cmd, "eval") == 0) {
        rc = cmd_eval(argc - 2, argv + 2);
    } else {
        fprintf(stderr, "brdffit: unknown command '%s'\n\n", cmd);
        usage(stderr);
        return CLI_USAGE;
    }
    /* output that could not be written (a full disk, a closed pipe) is a failure */
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "brdffit: error writing the output: %s\n", strerror(errno));
        return rc == CLI_OK ? CLI_FAILED : rc;
    }
    return rc;
}
