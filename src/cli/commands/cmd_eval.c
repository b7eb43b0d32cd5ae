/* SPDX-License-Identifier: MIT */
/* cmd_eval.c -- `brdffit eval MODEL d_r d_g d_b s_r s_g s_b p... --wi X Y Z --wo X Y Z`
 * (glTF models: base colour, specular colour, metallic roughness ior specular):
 * one BRDF value per channel (1/sr, no cosine factor). */
#include "cli.h"

#include <math.h>
#include <string.h>

const cli_help_block *cli_eval_help(void)
{
    static const cli_help_item items[] = {
        { "MODEL", "a model's name (brdffit models), in any case" },
        { "d_r d_g d_b s_r s_g s_b p0 [p1 [p2 [p3]]]",
          "the Lambertian albedo d, the lobe's\nscale s and parameters p, in the paper's units;\n"
          "for gltf and gltf-ext the base colour, the specular\ncolour, metallic roughness ior specular" },
        { "--wi X Y Z, --wo X Y Z", "the directions of incidence and view, in the\n"
                                    "surface's frame" },
    };
    static const cli_help_block block = CLI_HELP_BLOCK("Arguments of eval", NULL, items);
    return &block;
}

/* What the arguments of eval say. */
typedef struct eval_args {
    const char *model_name;
    double nums[6 + BRDFFIT_MAX_LOBE_PARAMS]; /* d_rgb, s_rgb, lobe parameters */
    int nnum;
    int have_wi, have_wo;
    double wi[3], wo[3];
} eval_args;

static int parse_vec3(int argc, char **argv, int *i, const char *name, double v[3])
{
    if (*i + 3 >= argc)
        return cli_usage_error("%s needs three numbers X Y Z", name);
    for (int c = 0; c < 3; c++) {
        const char *a = argv[++*i];
        if (cli_parse_double(a, &v[c]) != 0)
            return cli_usage_error("%s: '%s' is not a finite number", name, a);
    }
    /* a direction need not be normalised: one whose squared length overflows
     * (1e308) or underflows (1e-200) is scaled by its largest component
     * first, and so is still the direction it names */
    double m = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
    if (m == 0)
        return cli_usage_error("%s 0 0 0 is not a direction", name);
    double l2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if (!(isfinite(l2) && l2 > 0))
        for (int c = 0; c < 3; c++)
            v[c] /= m;
    return CLI_OK;
}

/* CLI_OK, CLI_USAGE (message printed), or CLI_HELP. */
static int parse_eval_args(int argc, char **argv, eval_args *e)
{
    memset(e, 0, sizeof *e);
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (cli_is_help(a))
            return CLI_HELP;
        if (strcmp(a, "--wi") == 0 || strcmp(a, "--wo") == 0) {
            int rc = parse_vec3(argc, argv, &i, a, a[3] == 'i' ? e->wi : e->wo);
            if (rc != CLI_OK)
                return rc;
            *(a[3] == 'i' ? &e->have_wi : &e->have_wo) = 1;
            continue;
        }
        if (a[0] == '-' && a[1] == '-')
            return cli_usage_error("eval: unknown option '%s'", a);
        if (!e->model_name) {
            e->model_name = a;
            continue;
        }
        if (e->nnum >= (int)(sizeof e->nums / sizeof e->nums[0]))
            return cli_usage_error("eval: too many numbers (at '%s')", a);
        if (cli_parse_double(a, &e->nums[e->nnum]) != 0)
            return cli_usage_error("eval: '%s' is not a finite number", a);
        e->nnum++;
    }
    return CLI_OK;
}

/* The model and its parameters from the arguments, checked against its bounds. */
static int eval_params(const eval_args *e, brdffit_model *model, brdffit_params *p)
{
    char names[512];
    if (!e->model_name)
        return cli_usage_error("eval needs MODEL d_r d_g d_b s_r s_g s_b p... --wi X Y Z --wo X Y Z");
    if (brdffit_model_from_name(e->model_name, model, NULL) != BRDFFIT_OK)
        return cli_usage_error("unknown model '%s' (valid: %s)", e->model_name,
                               cli_model_names(names, sizeof names));
    const brdffit_model_info *mi = brdffit_model_get(*model);
    if (e->nnum != 6 + mi->nparams) {
        char pn[512];
        return cli_usage_error("eval %s needs %d numbers (%s), got %d", mi->name, 6 + mi->nparams,
                               cli_param_list(*model, ' ', pn, sizeof pn), e->nnum);
    }
    if (!e->have_wi || !e->have_wo)
        return cli_usage_error("eval needs --wi X Y Z and --wo X Y Z");
    memset(p, 0, sizeof *p);
    memcpy(p->d, e->nums, sizeof p->d);
    memcpy(p->s, e->nums + 3, sizeof p->s);
    memcpy(p->p, e->nums + 6, (size_t)mi->nparams * sizeof p->p[0]);
    brdffit_error err;
    memset(&err, 0, sizeof err);
    if (brdffit_params_check(*model, p, &err) != BRDFFIT_OK)
        return cli_usage_error("eval: %s", err.message);
    return CLI_OK;
}

int cmd_eval(int argc, char **argv)
{
    eval_args e;
    int rc = parse_eval_args(argc, argv, &e);
    brdffit_model model;
    brdffit_params p;
    if (rc == CLI_OK)
        rc = eval_params(&e, &model, &p);
    if (rc != CLI_OK)
        return rc;
    double rgb[3];
    brdffit_error err;
    if (brdffit_eval(model, &p, e.wi, e.wo, rgb, &err) != BRDFFIT_OK)
        return cli_usage_error("eval: %s", err.message);
    if (!isfinite(rgb[0]) || !isfinite(rgb[1]) || !isfinite(rgb[2])) {
        cli_error("eval: %s gives %g %g %g at these directions: not finite (d_r d_g d_b "
                  "s_r s_g s_b or the lobe parameters too large for a double)",
                  brdffit_model_get(model)->name, rgb[0], rgb[1], rgb[2]);
        return CLI_FAILED;
    }
    printf("%.17g %.17g %.17g\n", rgb[0], rgb[1], rgb[2]);
    return CLI_OK;
}
