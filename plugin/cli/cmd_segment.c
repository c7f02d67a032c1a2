/* pointnpr segment IN -o OUT.ply: segments (3D JSEG, connected components, colour region growing,
 * or labels imported from a property), optionally a level of the region hierarchy. */
#include "cli.h"
#include "cli_opts.h"

#include <pointnpr/options.h>
#include <pointnpr/props.h>
#include <pointnpr/segment.h>
#include <pointnpr/tiles.h>

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


/* The methods' options tables (options.h); the first that has an option gives its range. */
typedef const pnpr_option_desc *(*table_fn)(size_t *r_count);
static const struct { const char *method; table_fn table; } method_tables[3] = {
    {"jseg", pnpr_jseg_option_table}, {"rgbgrow", pnpr_rgbgrow_option_table}, {"components", pnpr_components_option_table}};

/* The options that set a field of the method's struct (the values: 0 = not given). */
typedef struct method_option {
    const char *name, *metavar, *help;
} method_option;
static const method_option method_options[] = {
    {"radius", "R", "jseg: J neighbourhood radius; components/rgbgrow: neighbour distance"},
    {"min-size", "M", "smaller segments merge into a neighbour"},
    {"k", "N", "neighbourhood size"},
    {"classes", "C", "colour classes of the quantiser"},
};
enum { METHOD_OPTIONS = sizeof method_options / sizeof method_options[0] };

static const pnpr_option_desc *first_entry(const char *name)
{
    for (int t = 0; t < 3; t++) {
        size_t n;
        const pnpr_option_desc *table = method_tables[t].table(&n);
        const pnpr_option_desc *d = pnpr_option_find(table, n, name);
        if (d) return d;
    }
    return NULL;
}

/* "  --k N            neighbourhood size (default jseg 24, rgbgrow 16; in 2..256)" */
static void method_usage(FILE *f, const method_option *m)
{
    char left[64], range[64], def[64];
    snprintf(left, sizeof left, "--%s %s", m->name, m->metavar);
    fprintf(f, "  %-16s %s\n                   (default", left, m->help);
    const char *sep = " ";
    for (int t = 0; t < 3; t++) {
        size_t n;
        const pnpr_option_desc *table = method_tables[t].table(&n);
        const pnpr_option_desc *d = pnpr_option_find(table, n, m->name);
        if (!d) continue;
        pnpr_option_default_text(d, def, sizeof def);
        fprintf(f, "%s%s %s", sep, method_tables[t].method, def);
        sep = ", ";
    }
    pnpr_option_range_text(first_entry(m->name), range, sizeof range);
    fprintf(f, "; %s)\n", range);
}

/* Sets the given values (0 = not given) in the method's struct and checks it through its table;
 * 0 after saying why. */
static int apply_options(const char *method, const double *values, void *opts)
{
    size_t n = 0;
    const pnpr_option_desc *table = NULL;
    for (int t = 0; t < 3; t++)
        if (!strcmp(method, method_tables[t].method)) table = method_tables[t].table(&n);
    for (int o = 0; o < METHOD_OPTIONS; o++) {
        const pnpr_option_desc *d = pnpr_option_find(table, n, method_options[o].name);
        if (d && values[o] > 0) pnpr_option_set(d, opts, values[o]);
    }
    pnpr_error err = {0};
    if (pnpr_option_check(table, n, opts, &err) == PNPR_OK) return 1;
    fprintf(stderr, "pointnpr segment: --method %s: %s\n", method, err.message);
    return 0;
}

/* argv[*i] is one of method_options: its value (checked against the first table that has it) in
 * values[]; 1 taken, 0 not one of them, -1 a bad value (reported). */
static int method_option_arg(double *values, int argc, char **argv, int *i)
{
    if (*i + 1 >= argc || strncmp(argv[*i], "--", 2) != 0) return 0;
    for (int o = 0; o < METHOD_OPTIONS; o++) {
        if (strcmp(argv[*i] + 2, method_options[o].name)) continue;
        return cli_option_value(first_entry(method_options[o].name), "segment", argv[++*i], &values[o]) ? 1 : -1;
    }
    return 0;
}

/* The command's own arguments (cli_opts.h). */
static const char *const method_names[] = {"jseg", "components", "rgbgrow", "labels", NULL};
typedef struct segment_args {
    cli_common c;
    int method; /* method_names */
    const char *property;
    uint32_t segments;
    double threshold;
    int threads, ascii;
} segment_args;
static const cli_opt segment_opts[] = {
    {"--method", NULL, CLI_CHOICE, offsetof(segment_args, method), 0, 0, 0, 0, method_names, NULL, NULL,
     "the segmentation (above)"},
    {"--segments", NULL, CLI_UINT, offsetof(segment_args, segments), 1, 4294967294.0, 0, 0, NULL, NULL, "N",
     "cut the region hierarchy (HSI colour, size rule) at N segments"},
    {"--threshold", NULL, CLI_NUMBER, offsetof(segment_args, threshold), 0, 1e9, 1, 0, NULL, NULL, "T",
     "cut the region hierarchy where the HSI colour distance exceeds T"},
    {"--property", NULL, CLI_TEXT, offsetof(segment_args, property), 0, 0, 0, 0, NULL, NULL, "NAME",
     "labels: the property to read (default 'segment')"},
    CLI_THREADS_OPT(segment_args, threads),
    CLI_ASCII_OPT(segment_args, ascii),
};

static void usage(FILE *f)
{
    fprintf(f,
            "usage: pointnpr segment IN -o OUT.ply [--method jseg|components|rgbgrow|labels] [options]\n"
            "  Writes every input property, in input order, plus per point `segment` (uint, 0..S-1)\n"
            "  and seg_red/seg_green/seg_blue (uchar, the segment's mean colour; only when the input\n"
            "  has colours). Points with non-finite coordinates share the last segment.\n"
            "methods:\n"
            "  jseg        3D JSEG colour segmentation (default; needs colours)\n"
            "  components  connected components at a distance (--radius)\n"
            "  rgbgrow     colour region growing (needs colours)\n"
            "  labels      segments from a per-point property (--property, default 'segment')\n"
            "options:\n");
    cli_opts_usage(f, segment_opts + 1, 2); /* --segments, --threshold */
    for (int i = 0; i < METHOD_OPTIONS; i++) method_usage(f, &method_options[i]);
    size_t ns;
    const pnpr_option_desc *split = pnpr_split_option_table(&ns);
    fprintf(f, "  then, with --split, each segment is split along its direction of greatest variation\n"
               "  (Chi & Lee's covariance split):\n");
    cli_table_usage(f, split, ns, "split", "V");
    cli_table_usage(f, split, ns, "split-min", "M");
    cli_opts_usage(f, segment_opts + 3, CLI_COUNT(segment_opts) - 3);
    cli_opts_usage(f, cli_common_opts + 1, 1); /* --quiet */
    cli_outlier_usage(f);
    cli_columns_usage(f);
    cli_memory_usage(f);
    fprintf(f, "tiles (clouds larger than memory; --method components only; binary PLY input; the halo is the\n"
               "  distance; the result equals a run in memory; docs/tiles.md):\n");
    cli_tile_usage(f, 0);
}

/* ---- components in tiles (tiles.h) ---------------------------------------------------------- */

typedef struct segment_tile_run {
    const char *in;
    float distance; /* > 0 (FLT_MIN for 0: its square is 0 as well) */
    int threads, quiet;
} segment_tile_run;

/* Whether a halo holds the points within the distance of a tile; 0 after saying why. */
static int halo_holds(double halo, const pnpr_tile_grid *g, float distance)
{
    double need = pnpr_tile_components_halo(g, distance);
    if (halo >= need) return 1;
    fprintf(stderr, "pointnpr segment: --halo %.9g: the components' distance %.9g needs a halo of %.9g\n", halo,
            (double)distance, need);
    return 0;
}

/* One tile: read with its halo, its own components, written with the halo marked. */
static int segment_tile_job(const void *ctx, const char *out, const pnpr_tile_grid *g, const pnpr_tile *t, double halo,
                            size_t *r_uncertain)
{
    const segment_tile_run *r = ctx;
    (void)r_uncertain; /* every component is exact: nothing uncertain */
    if (!halo_holds(halo, g, r->distance)) return 2;
    pnpr_cloud c = {0};
    uint8_t *core = NULL;
    pnpr_error err = {0};
    pnpr_status st = pnpr_tile_read(r->in, g, t, halo, NULL, &c, &core, &err);
    if (st != PNPR_OK) { cli_report_error("segment", st, &err); return 1; }
    uint32_t own = 0;
    st = pnpr_tile_components_job(&c, core, r->distance, r->threads, &own);
    size_t halo_points = 0;
    for (size_t i = 0; i < c.count; i++) halo_points += !core[i];
    free(core);
    if (st == PNPR_OK) {
        char comment[256];
        snprintf(comment, sizeof comment, "pointnpr segment method=components distance=%.9g tile %u,%u,%u,%u",
                 (double)r->distance, t->lo[0], t->lo[1], t->hi[0], t->hi[1]);
        pnpr_write_options wo = {0}; /* binary PLY: the merge places its records */
        wo.format = PNPR_FORMAT_PLY;
        wo.comment = comment;
        st = pnpr_write_file(out, &c, &wo, &err);
    } else {
        pnpr_error_set(&err, st, "%s: tile: %s", r->in, pnpr_status_string(st));
    }
    if (st == PNPR_OK && !r->quiet)
        fprintf(stderr, "tile %u,%u..%u,%u: %zu points and %zu in the halo, %u components of its own\n", t->lo[0], t->lo[1],
                t->hi[0], t->hi[1], c.count - halo_points, halo_points, own);
    pnpr_cloud_free(&c);
    if (st != PNPR_OK) { cli_report_error("segment", st, &err); return 1; }
    return 0;
}

static pnpr_status segment_merge(const void *ctx, const char *const *paths, size_t n, uint64_t points, const char *out,
                                 const pnpr_progress *prog, pnpr_error *err)
{
    const segment_tile_run *r = ctx;
    uint32_t S = 0;
    pnpr_status st = pnpr_tile_merge_segments(paths, n, points, out, prog, &S, err);
    if (st == PNPR_OK && !r->quiet) fprintf(stderr, "%u segments\n", S);
    return st;
}

/* --method components in tiles: a job (--tile-grid), or the plan, the distance and the run or
 * the manifest. */
static int segment_tiles(segment_tile_run *r, const char *out, const cli_tile_args *a, size_t memory_limit,
                         pnpr_progress prog, int argc, char **argv)
{
    if (a->grid[4] > 0) {
        pnpr_tile_grid g;
        pnpr_tile t;
        size_t none = 0;
        if (!(r->distance > 0)) {
            fprintf(stderr, "pointnpr segment: a tile's job needs --radius (the manifest writes it)\n");
            return 2;
        }
        return cli_tile_job_args("segment", a, &g, &t) ? segment_tile_job(r, out, &g, &t, a->halo, &none) : 2;
    }
    char extra[64] = "";
    cli_tile_cmd c = {"segment", r->in, out, r->quiet, prog, extra, "--segments", 0, PNPR_TILE_COMPONENTS_BYTES,
                      segment_tile_job, segment_merge, r};
    pnpr_tile_plan plan;
    int rc = cli_tile_plan(&c, a, memory_limit, 0, &plan);
    if (rc) return rc;
    pnpr_components_options o = {0};
    o.distance = r->distance;
    pnpr_error err = {0};
    size_t limit = memory_limit ? memory_limit : pnpr_memory_available();
    pnpr_status st = pnpr_tile_components_distance(r->in, &plan, &o, limit, &r->distance, &err);
    if (st != PNPR_OK) { cli_report_error("segment", st, &err); pnpr_tile_plan_free(&plan); return 1; }
    if (!(o.distance > 0)) {
        if (!r->quiet) fprintf(stderr, "components: distance %.9g (the automatic one of the whole file)\n", (double)r->distance);
        if (!(r->distance > 0)) r->distance = FLT_MIN;
        snprintf(extra, sizeof extra, "--radius %.9g", (double)r->distance);
    }
    if (a->halo > 0 && !halo_holds(a->halo, &plan.grid, r->distance)) {
        pnpr_tile_plan_free(&plan);
        return 2;
    }
    plan.halo = a->halo > 0 ? a->halo : pnpr_tile_components_halo(&plan.grid, r->distance);
    /* the tiles were sized for a halo of PNPR_TILE_HALO_SHARE of their points: a large distance
     * reads more (as an area: the core's sides grown by the halo on each side) */
    double most = 1;
    for (size_t t = 0; t < plan.count; t++) {
        double w = (plan.tiles[t].hi[0] - plan.tiles[t].lo[0]) * plan.grid.cell[0];
        double h = (plan.tiles[t].hi[1] - plan.tiles[t].lo[1]) * plan.grid.cell[1];
        most = fmax(most, (w + 2 * plan.halo) * (h + 2 * plan.halo) / (w * h));
    }
    if (!r->quiet && a->tiled && !a->tile_points && most > 2 * (1 + PNPR_TILE_HALO_SHARE))
        fprintf(stderr, "pointnpr segment: warning: the distance %.6g is large against the tiles: a tile may read %.0f "
                        "times its core's area, beyond what --tiles sized it for (give --tile-points)\n",
                (double)r->distance, most);
    rc = cli_tile_execute(&c, a, &plan, argc, argv);
    pnpr_tile_plan_free(&plan);
    return rc;
}

int cli_segment(int argc, char **argv)
{
    const char *in = NULL;
    segment_args A;
    memset(&A, 0, sizeof A);
    pnpr_split_options split = {0};
    size_t nsplit;
    const pnpr_option_desc *split_table = pnpr_split_option_table(&nsplit);
    static const char *const split_names[] = {"split", "split-min", NULL};
    double values[METHOD_OPTIONS] = {0}; /* method_options */
    pnpr_write_options wo = {0};
    cli_outliers outliers = {0, 0};
    const char *columns = NULL;
    size_t memory_limit = 0;
    cli_tile_args tiles;
    memset(&tiles, 0, sizeof tiles);
    for (int i = 1; i < argc; i++) {
        int oo = cli_outlier_option(&outliers, "segment", argc, argv, &i);
        if (oo == 0) oo = cli_memory_option(&memory_limit, "segment", argc, argv, &i);
        if (oo == 0) oo = cli_tile_option(&tiles, "segment", argc, argv, &i);
        if (oo == 0) oo = cli_columns_option(&columns, "segment", argc, argv, &i);
        if (oo == 0) oo = cli_table_option(split_table, nsplit, split_names, &split, "segment", argc, argv, &i);
        if (oo == 0) oo = method_option_arg(values, argc, argv, &i);
        if (oo == 0) oo = cli_opts_parse(segment_opts, CLI_COUNT(segment_opts), &A, "segment", argc, argv, &i);
        if (oo == 0) oo = cli_opts_parse(cli_common_opts, CLI_COUNT(cli_common_opts), &A.c, "segment", argc, argv, &i);
        if (oo < 0) return 2;
        if (A.c.help) { usage(stdout); return 0; }
        if (oo == 0 && cli_operand("segment", argv[i], &in, usage)) return 2;
    }
    const char *out = A.c.out, *method = method_names[A.method], *property = A.property;
    const int quiet = A.c.quiet;
    const double segments = A.segments, threshold = A.threshold, threads = A.threads;
    if (A.ascii) wo.encoding = PNPR_PLY_ASCII;
    if (!cli_need_in_out("segment", in, out, "OUT.ply")) return 2;
    int out_rc = cli_cloud_output("segment", out, in, &wo);
    if (out_rc) return out_rc;
    if (segments > 0 && threshold > 0) { fprintf(stderr, "pointnpr segment: give --segments or --threshold, not both\n"); return 2; }
    if (property && strcmp(method, "labels")) { fprintf(stderr, "pointnpr segment: --property needs --method labels\n"); return 2; }

    cli_progress_state ps = {{0}, 0, 0};
    pnpr_progress prog = {quiet ? NULL : cli_progress_stderr, &ps};
    pnpr_read_options ro = {0};
    ro.columns = columns;
    ro.progress = prog;
    wo.progress = prog;
    if (cli_tile_wanted(&tiles)) {
        const char *why = strcmp(method, "components") ? "--method jseg, rgbgrow and labels need the whole cloud (regions "
                                                          "grow and merge in one order over it): use --method components"
                          : segments > 0 || threshold > 0 ? "the region hierarchy (--segments, --threshold) merges "
                                                             "across the whole cloud"
                          : values[1] > 1 ? "--min-size joins a small component to its nearest kept one, which may "
                                            "lie anywhere"
                          : split.max_variation > 0 ? "--split needs each segment whole"
                          : outliers.drop || columns ? "tiles read binary PLY as it is: --drop-outliers and --columns "
                                                       "do not apply"
                          : A.ascii || wo.format != PNPR_FORMAT_PLY ? "a tiled run writes binary PLY: OUT must end in "
                                                                     ".ply, without --ascii"
                          : NULL;
        if (why) { fprintf(stderr, "pointnpr segment: in tiles: %s (docs/tiles.md)\n", why); return 2; }
        pnpr_components_options o = {0};
        if (!apply_options(method, values, &o)) return 2;
        segment_tile_run run = {in, o.distance, (int)threads, quiet};
        return segment_tiles(&run, out, &tiles, memory_limit, prog, argc, argv);
    }
    pnpr_cloud cloud = {0};
    pnpr_error err = {0};
    if (!cli_memory_check_file("segment", in, memory_limit)) return 1;
    pnpr_status st = pnpr_read_file(in, &ro, &cloud, &err);
    if (st != PNPR_OK) { cli_report_error("segment", st, &err); return 1; }
    if (cli_outliers_apply(&outliers, "segment", in, &cloud, quiet, NULL)) { pnpr_cloud_free(&cloud); return 1; }
    int rc = 1;
    uint32_t *labels = NULL, *knn = NULL;
    pnpr_segment_merge *merges = NULL;
    float *mean = NULL;
    pnpr_kdtree *tree = NULL;
    if (cloud.count && !cloud.rgb && (!strcmp(method, "jseg") || !strcmp(method, "rgbgrow"))) {
        fprintf(stderr, "pointnpr segment: %s has no colours: --method %s needs them (use components or labels)\n", in, method);
        goto done;
    }
    if (cloud.count && !cloud.rgb && (segments > 0 || threshold > 0)) {
        fprintf(stderr, "pointnpr segment: %s has no colours: the region hierarchy (--segments/--threshold) needs them\n", in);
        goto done;
    }
    labels = malloc((cloud.count ? cloud.count : 1) * sizeof *labels);
    if (!labels) { st = PNPR_ERR_OUT_OF_MEMORY; goto fail; }
    pnpr_segment_info info = {0};
    if (!strcmp(method, "jseg")) {
        pnpr_jseg_options o = {0};
        if (!apply_options(method, values, &o)) goto done;
        o.threads = (int)threads; o.progress = prog;
        st = pnpr_segment_jseg(cloud.xyz, cloud.rgb, cloud.count, &o, labels, &info);
    } else if (!strcmp(method, "components")) {
        pnpr_components_options o = {0};
        if (!apply_options(method, values, &o)) goto done;
        o.threads = (int)threads; o.progress = prog;
        st = pnpr_segment_components(cloud.xyz, cloud.count, &o, labels, &info);
    } else if (!strcmp(method, "rgbgrow")) {
        pnpr_rgbgrow_options o = {0};
        if (!apply_options(method, values, &o)) goto done;
        o.threads = (int)threads; o.progress = prog;
        st = pnpr_segment_rgbgrow(cloud.xyz, cloud.rgb, cloud.count, &o, labels, &info);
    } else {
        const char *name = property ? property : PNPR_PROP_SEGMENT;
        pnpr_property *p = pnpr_cloud_find_property(&cloud, name);
        if (p) st = pnpr_segment_from_values(p->type, p->data, cloud.count, labels, &info.segment_count);
        else if (cloud.label && (!strcmp(name, PNPR_PROP_SEGMENT) || !strcmp(name, PNPR_PROP_LABEL)))
            st = pnpr_segment_from_values(PNPR_TYPE_UINT32, cloud.label, cloud.count, labels, &info.segment_count);
        else {
            fprintf(stderr, "pointnpr segment: %s has no per-point property '%s'\n", in, name);
            goto done;
        }
        info.invalid_segment = PNPR_LABEL_NONE;
    }
    if (st != PNPR_OK) goto fail;
    uint32_t S = info.segment_count;
    if ((segments > 0 || threshold > 0) && S > 1) {
        /* the region hierarchy over the invalid-free segments (the invalid segment stays apart) */
        uint32_t hs = info.invalid_segment != PNPR_LABEL_NONE ? S - 1 : S;
        size_t kk = cloud.count > 10 ? 10 : cloud.count;
        knn = malloc(cloud.count * kk * sizeof *knn);
        merges = malloc((hs > 1 ? hs - 1 : 1) * sizeof *merges);
        if (!knn || !merges) { st = PNPR_ERR_OUT_OF_MEMORY; goto fail; }
        if ((st = pnpr_kdtree_build_threads(cloud.xyz, cloud.count, 0, (int)threads, &tree)) != PNPR_OK) goto fail;
        pnpr_knn_options ko = {(int)threads, prog, 0};
        if ((st = pnpr_knn_self(tree, cloud.count, kk, &ko, knn, NULL)) != PNPR_OK) goto fail;
        pnpr_region_graph g = {knn, kk, kk};
        pnpr_hierarchy_options ho = {0};
        ho.progress = prog;
        uint32_t nm = 0;
        if ((st = pnpr_segment_hierarchy(cloud.rgb, cloud.count, &g, labels, hs, &ho, merges, &nm)) != PNPR_OK) goto fail;
        uint32_t target = segments > 0 ? (uint32_t)segments : 0;
        if (target && info.invalid_segment != PNPR_LABEL_NONE) target = target > 1 ? target - 1 : 1;
        if ((st = pnpr_segment_hierarchy_cut(labels, cloud.count, hs, merges, nm, target, (float)threshold, labels, &S)) != PNPR_OK)
            goto fail;
        if (!quiet) fprintf(stderr, "hierarchy: %u regions, %u merges, cut at %u segments\n", hs, nm, S);
    }
    if (split.max_variation > 0) { /* --split given */
        /* the invalid segment (last) stays as it is: split only 0 .. S-2 then */
        uint32_t regions = info.invalid_segment != PNPR_LABEL_NONE && S ? S - 1 : S, before = S;
        if ((st = pnpr_segment_covariance_split(cloud.xyz, cloud.count, labels, regions, split.max_variation, split.min_size,
                                                labels, &S)) != PNPR_OK)
            goto fail;
        if (!quiet) fprintf(stderr, "covariance split: %u segments -> %u\n", before, S);
    }
    if (!quiet)
        fprintf(stderr, "points %zu, method %s, %u segments%s\n", cloud.count, method, S,
                info.invalid_segment != PNPR_LABEL_NONE ? " (the last one: points with non-finite coordinates)" : "");
    if (!strcmp(method, "jseg") && !quiet)
        fprintf(stderr, "  colour classes %u, mean J %.4f, seed regions %u, grown regions %u, %.3f s\n",
                info.classes, info.mean_j, info.seed_regions, info.grown_regions, info.seconds);

    if ((st = pnpr_cloud_alloc_labels(&cloud)) != PNPR_OK) goto fail;
    if (cloud.count) memcpy(cloud.label, labels, cloud.count * sizeof *labels);
    if (cloud.rgb) {
        mean = malloc(3 * (size_t)(S ? S : 1) * sizeof *mean);
        if (!mean) { st = PNPR_ERR_OUT_OF_MEMORY; goto fail; }
        if ((st = pnpr_segment_mean_colors(cloud.rgb, labels, cloud.count, S, mean, NULL)) != PNPR_OK) goto fail;
        if ((st = pnpr_segment_add_colors(&cloud, mean, S)) != PNPR_OK) goto fail;
    }
    char comment[256];
    snprintf(comment, sizeof comment, "pointnpr segment method=%s segments=%u", method, S);
    wo.comment = comment;
    st = pnpr_write_file(out, &cloud, &wo, &err);
    if (st != PNPR_OK) { cli_report_error("segment", st, &err); goto done; }
    if (!quiet) fprintf(stderr, "wrote %s\n", out);
    rc = 0;
    goto done;
fail:
    fprintf(stderr, "pointnpr segment: %s: %s\n", in, pnpr_status_string(st));
done:
    pnpr_kdtree_free(tree);
    free(labels); free(knn); free(merges); free(mean);
    pnpr_cloud_free(&cloud);
    return rc;
}
