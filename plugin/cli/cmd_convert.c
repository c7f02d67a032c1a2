/* pointnpr convert IN... -o OUT.ply|OUT.pcd: reads every input (PLY, LAS, OBJ, OFF, PCD; a directory
 * stands for the supported files in it, sorted by name), merges them into one cloud and writes PLY
 * (or binary PCD for a .pcd name). Inputs that would not fit in memory together are joined one at
 * a time (pnpr_join_ply; --stream asks for it).
 * Nothing is written unless every input was read; the output is written as every output is
 * (pointnpr/output.h: a temporary renamed over OUT when complete; "-" is standard output). */
#include "cli.h"
#include "cli_opts.h"

#include <pointnpr/lod.h>
#include <pointnpr/memory.h>

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The command's options (cli_opts.h): the output once, one PLY encoding. */
typedef struct convert_args {
    cli_common c;
    const char *out;
    pnpr_ply_encoding encoding;
    int encoding_set;
    int stream;
    int lod;
} convert_args;

static int parse_output(void *a, const char *cmd, const char *v)
{
    convert_args *ca = a;
    if (ca->out) { fprintf(stderr, "pointnpr %s: more than one output given\n", cmd); return 0; }
    ca->out = v;
    return 1;
}

static int set_encoding(convert_args *ca, const char *cmd, pnpr_ply_encoding enc)
{
    if (ca->encoding_set && ca->encoding != enc) {
        fprintf(stderr, "pointnpr %s: give only one of --ascii, --binary, --big-endian\n", cmd);
        return 0;
    }
    ca->encoding = enc;
    ca->encoding_set = 1;
    return 1;
}
static int parse_ascii(void *a, const char *cmd, const char *v) { (void)v; return set_encoding(a, cmd, PNPR_PLY_ASCII); }
static int parse_binary(void *a, const char *cmd, const char *v) { (void)v; return set_encoding(a, cmd, PNPR_PLY_BINARY_LE); }
static int parse_big(void *a, const char *cmd, const char *v) { (void)v; return set_encoding(a, cmd, PNPR_PLY_BINARY_BE); }

static const cli_opt convert_opts[] = {
    {"--output", "-o", CLI_CUSTOM, 0, 0, 0, 0, 0, NULL, parse_output, "OUT.ply",
     "output file (required; OUT.pcd writes binary PCD, - standard output)"},
    {"--binary", NULL, CLI_FLAG_CUSTOM, 0, 0, 0, 0, 0, NULL, parse_binary, NULL, "binary little endian PLY (default)"},
    {"--ascii", NULL, CLI_FLAG_CUSTOM, 0, 0, 0, 0, 0, NULL, parse_ascii, NULL, "ascii PLY"},
    {"--big-endian", NULL, CLI_FLAG_CUSTOM, 0, 0, 0, 0, 0, NULL, parse_big, NULL, "binary big endian PLY"},
    {"--stream", NULL, CLI_FLAG, offsetof(convert_args, stream), 0, 0, 0, 0, NULL, NULL, NULL,
     "PLY: join the inputs one at a time (memory: one input), as when they would not fit in memory "
     "together; they must have the same properties and no faces (docs/tiles.md)"},
    {"--lod", NULL, CLI_FLAG, offsetof(convert_args, lod), 0, 0, 0, 0, NULL, NULL, NULL,
     "one binary PLY to a .ply file ordered for drawing: render and animate then read only what a view "
     "needs of a cloud larger than memory (docs/tiles.md)"},
};

static void usage(FILE *f)
{
    fprintf(f,
            "usage: pointnpr convert IN... -o OUT.ply [options]\n"
            "  Reads every input (.ply, .las, .obj, .off, .pcd, .xyz, .pts, .pwn, .csv, .txt; a\n"
            "  directory stands for all such files in it but .csv and .txt, sorted by name), merges\n"
            "  them into one cloud and writes it as PLY\n"
            "  (binary PCD when OUT ends in .pcd). Nothing is written if any input cannot be read.\n"
            "options:\n");
    cli_opts_usage(f, convert_opts, CLI_COUNT(convert_opts));
    cli_opts_usage(f, cli_common_opts + 1, 1); /* --quiet */
    cli_memory_usage(f);
    cli_columns_usage(f);
}

/* A growable list of owned strings. */
typedef struct path_list {
    char **items;
    size_t count, cap;
} path_list;

static int list_push(path_list *l, const char *s)
{
    if (l->count == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 16;
        if (cap > SIZE_MAX / sizeof *l->items) return 0;
        char **grown = realloc(l->items, cap * sizeof *grown);
        if (!grown) return 0;
        l->items = grown;
        l->cap = cap;
    }
    size_t n = strlen(s) + 1;
    char *copy = malloc(n);
    if (!copy) return 0;
    memcpy(copy, s, n);
    l->items[l->count++] = copy;
    return 1;
}

static void list_free(path_list *l)
{
    for (size_t i = 0; i < l->count; i++) free(l->items[i]);
    free(l->items);
    memset(l, 0, sizeof *l);
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Appends the supported files of directory `dir` (sorted by name); 0 and a message on failure. */
static int expand_dir(const char *dir, path_list *out)
{
    DIR *d = opendir(dir);
    if (!d) {
        fprintf(stderr, "pointnpr convert: %s: %s\n", dir, strerror(errno));
        return 0;
    }
    path_list names = {0};
    int ok = 1;
    struct dirent *e;
    while (ok && (e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.') continue; /* hidden files, "." and ".." */
        const pnpr_file_format f = pnpr_format_from_path(e->d_name);
        if (f == PNPR_FORMAT_AUTO || f == PNPR_FORMAT_CSV) continue; /* .txt/.csv beside tiles: notes, licences */
        ok = list_push(&names, e->d_name);
    }
    closedir(d);
    if (!ok) {
        fprintf(stderr, "pointnpr convert: %s: out of memory listing the directory\n", dir);
        list_free(&names);
        return 0;
    }
    if (names.count == 0) {
        fprintf(stderr, "pointnpr convert: %s: no .ply, .las, .obj, .off or .pcd files in this directory\n", dir);
        list_free(&names);
        return 0;
    }
    qsort(names.items, names.count, sizeof *names.items, cmp_str);
    size_t dl = strlen(dir);
    int slash = dl > 0 && dir[dl - 1] == '/';
    for (size_t i = 0; ok && i < names.count; i++) {
        size_t n = dl + 1 + strlen(names.items[i]) + 1;
        char *full = malloc(n);
        if (!full) { ok = 0; break; }
        snprintf(full, n, "%s%s%s", dir, slash ? "" : "/", names.items[i]);
        struct stat sb;
        /* skip sub-directories and other non-files that happen to carry a known extension */
        if (stat(full, &sb) == 0 && !S_ISDIR(sb.st_mode)) ok = list_push(out, full);
        free(full);
    }
    list_free(&names);
    if (!ok) fprintf(stderr, "pointnpr convert: out of memory\n");
    return ok;
}

/* Whether the inputs joined in memory would not fit (their bytes twice: an input read whole and
 * the joined cloud growing; --memory-limit or the memory available) while a streamed join can
 * write OUT (a .ply file). Says so when it streams. */
static int must_stream(const path_list *inputs, const char *out, size_t limit, int quiet)
{
    if (pnpr_format_from_path(out) != PNPR_FORMAT_PLY || cli_output_is_stream(out)) return 0;
    size_t bytes = 0;
    for (size_t i = 0; i < inputs->count; i++) {
        struct stat sb;
        if (stat(inputs->items[i], &sb) == 0 && S_ISREG(sb.st_mode))
            bytes = (size_t)sb.st_size > SIZE_MAX / 2 - bytes ? SIZE_MAX / 2 : bytes + (size_t)sb.st_size;
    }
    pnpr_error err = {0};
    if (pnpr_memory_check(2 * bytes, limit, "joining the inputs in memory", &err) == PNPR_OK) return 0;
    if (!quiet) fprintf(stderr, "convert: %s; joining them one at a time (--stream)\n", err.message);
    return 1;
}

/* The inputs joined one at a time into OUT (pnpr_join_ply). */
static int convert_streamed(const path_list *inputs, const char *out, const char *columns, const pnpr_write_options *wo,
                            int quiet)
{
    pnpr_join_options jo = {0};
    jo.read.columns = columns;
    jo.write = *wo;
    jo.write.comment = "pointnpr convert";
    cli_progress_state ps = {{0}, 0, 0};
    jo.progress.fn = quiet ? NULL : cli_progress_stderr;
    jo.progress.user = &ps;
    uint64_t points = 0;
    pnpr_error err = {0};
    pnpr_status st = pnpr_join_ply((const char *const *)inputs->items, inputs->count, out, &jo, &points, &err);
    if (st != PNPR_OK) {
        cli_report_error("convert", st, &err);
        fprintf(stderr, "pointnpr convert: nothing written\n");
        return 1;
    }
    if (!quiet) fprintf(stderr, "wrote %s: %llu points from %zu inputs, one at a time\n", out, (unsigned long long)points, inputs->count);
    return 0;
}

/* IN ordered for drawing into OUT (pnpr_lod_write), in chunks that fit the memory; refused
 * before writing when they would take more than this many passes over IN (a 200M cloud under 4G
 * takes 4; under a tiny limit it would be thousands). */
#define CONVERT_LOD_PASSES 64
static int convert_lod(const char *in, const char *out, size_t limit, int quiet)
{
    if (!cli_check_output("convert", out, &in, 1, 1)) return 1;
    pnpr_lod_options lo = {0};
    double room = (limit ? (double)limit : (double)pnpr_memory_available()) - (double)pnpr_memory_resident();
    lo.memory = room > 16.0 * 1048576.0 ? (size_t)(room - 8.0 * 1048576.0) : 8u << 20;
    lo.max_passes = CONVERT_LOD_PASSES;
    cli_progress_state ps = {{0}, 0, 0};
    lo.progress.fn = quiet ? NULL : cli_progress_stderr;
    lo.progress.user = &ps;
    uint64_t points = 0;
    pnpr_error err = {0};
    pnpr_status st = pnpr_lod_write(in, out, &lo, &points, &err);
    if (st != PNPR_OK) {
        cli_report_error("convert", st, &err);
        fprintf(stderr, "pointnpr convert: nothing written\n");
        return 1;
    }
    if (!quiet) fprintf(stderr, "wrote %s: %llu points ordered for drawing\n", out, (unsigned long long)points);
    return 0;
}

int cli_convert(int argc, char **argv)
{
    convert_args A;
    memset(&A, 0, sizeof A);
    const char *columns = NULL;
    size_t memory_limit = 0;
    path_list args = {0};
    int rc = 0;
    for (int i = 1; i < argc && rc == 0; i++) {
        int r = cli_opts_parse(convert_opts, CLI_COUNT(convert_opts), &A, "convert", argc, argv, &i);
        if (r == 0) r = cli_opts_parse(cli_common_opts + 1, 2, &A.c, "convert", argc, argv, &i); /* --quiet, --help */
        if (r == 0) r = cli_columns_option(&columns, "convert", argc, argv, &i);
        if (r == 0) r = cli_memory_option(&memory_limit, "convert", argc, argv, &i);
        if (r < 0) rc = 2;
        else if (A.c.help) { usage(stdout); list_free(&args); return 0; }
        else if (r > 0) continue;
        else if (argv[i][0] == '-' && argv[i][1]) {
            fprintf(stderr, "pointnpr convert: unknown option or missing value: %s\n", argv[i]);
            rc = 2;
        } else if (!list_push(&args, argv[i])) {
            fprintf(stderr, "pointnpr convert: out of memory\n");
            rc = 1;
        }
    }
    const char *out = A.out;
    const int quiet = A.c.quiet;
    pnpr_write_options wo = {0};
    wo.encoding = A.encoding;
    if (rc == 0 && (args.count == 0 || !out)) {
        fprintf(stderr, "pointnpr convert: %s\n", args.count == 0 ? "no input given" : "no output given (-o OUT.ply)");
        rc = 2;
    }
    if (rc == 0) {
        pnpr_file_format of = pnpr_format_from_path(out);
        if (of == PNPR_FORMAT_AUTO && !cli_output_is_stream(out)) {
            fprintf(stderr, "pointnpr convert: %s: name the output .ply or .pcd (- or a device/FIFO: PLY)\n", out);
            rc = 2;
        } else if (of != PNPR_FORMAT_AUTO && of != PNPR_FORMAT_PLY && of != PNPR_FORMAT_PCD) {
            fprintf(stderr, "pointnpr convert: %s: only PLY and PCD output are supported (use a .ply or .pcd name)\n", out);
            rc = 2;
        } else if (of == PNPR_FORMAT_PCD && wo.encoding != PNPR_PLY_BINARY_LE) {
            fprintf(stderr, "pointnpr convert: %s: PCD is written binary only (--ascii and --big-endian are for PLY)\n", out);
            rc = 2;
        } else if (A.stream && (of != PNPR_FORMAT_PLY || cli_output_is_stream(out))) {
            fprintf(stderr, "pointnpr convert: %s: --stream writes a .ply file (its count is written last)\n", out);
            rc = 2;
        }
    }
    if (rc == 0 && A.lod && (args.count != 1 || pnpr_format_from_path(out) != PNPR_FORMAT_PLY || cli_output_is_stream(out) ||
                             A.stream || wo.encoding != PNPR_PLY_BINARY_LE)) {
        fprintf(stderr, "pointnpr convert: --lod orders one binary PLY into a binary .ply file (not --stream, --ascii or "
                        "--big-endian)\n");
        rc = 2;
    }
    if (rc == 2) usage(stderr);
    if (rc != 0) { list_free(&args); return rc; }
    if (A.lod) {
        rc = convert_lod(args.items[0], out, memory_limit, quiet);
        list_free(&args);
        return rc;
    }

    /* inputs: files as given, directories expanded */
    path_list inputs = {0};
    for (size_t i = 0; i < args.count && rc == 0; i++) {
        struct stat sb;
        if (stat(args.items[i], &sb) == 0 && S_ISDIR(sb.st_mode)) {
            if (!expand_dir(args.items[i], &inputs)) rc = 1;
        } else if (!list_push(&inputs, args.items[i])) {
            fprintf(stderr, "pointnpr convert: out of memory\n");
            rc = 1;
        }
    }
    list_free(&args);
    /* fail early (before reading what may be many inputs) when the output cannot be written */
    if (rc == 0 && !cli_check_output("convert", out, (const char *const *)inputs.items, inputs.count, 1)) rc = 1;
    if (rc != 0) { list_free(&inputs); return rc; }
    if (inputs.count > 1 && (A.stream || must_stream(&inputs, out, memory_limit, quiet))) {
        rc = convert_streamed(&inputs, out, columns, &wo, quiet);
        list_free(&inputs);
        return rc;
    }

    pnpr_cloud merged = {0}, one = {0};
    pnpr_error err = {0};
    const size_t n = inputs.count;
    for (size_t i = 0; i < n; i++) {
        const char *path = inputs.items[i];
        cli_progress_state ps = {{0}, 0, 0}; /* fresh per input: every file reports its stages */
        pnpr_read_options ro = {0};
        ro.columns = columns;
        ro.progress.fn = quiet ? NULL : cli_progress_stderr;
        ro.progress.user = &ps;
        pnpr_status st = pnpr_read_file(path, &ro, n == 1 ? &merged : &one, &err);
        if (st != PNPR_OK) {
            if (!strstr(err.message, path))
                fprintf(stderr, "pointnpr convert: %s: %s (%s)\n", path, err.message[0] ? err.message : "read failed",
                        pnpr_status_string(st));
            else
                cli_report_error("convert", st, &err);
            fprintf(stderr, "pointnpr convert: input %zu/%zu (%s) could not be read; nothing written\n", i + 1, n, path);
            rc = 1;
            break;
        }
        if (n > 1) {
            if (!quiet) fprintf(stderr, "read %zu/%zu: %s (%zu points)\n", i + 1, n, path, one.count);
            st = pnpr_cloud_append(&merged, &one);
            pnpr_cloud_free(&one);
            if (st != PNPR_OK) {
                fprintf(stderr, "pointnpr convert: cannot merge %s: %s\n", path, pnpr_status_string(st));
                rc = 1;
                break;
            }
        }
    }
    if (rc == 0) {
        cli_progress_state ps = {{0}, 0, 0};
        wo.progress.fn = quiet ? NULL : cli_progress_stderr;
        wo.progress.user = &ps;
        wo.comment = "pointnpr convert";
        /* a name without extension (or "-") is PLY */
        wo.format = pnpr_format_from_path(out) == PNPR_FORMAT_PCD ? PNPR_FORMAT_PCD : PNPR_FORMAT_PLY;
        pnpr_status st = pnpr_write_file(out, &merged, &wo, &err);
        if (st != PNPR_OK) {
            cli_report_error("convert", st, &err);
            rc = 1;
        } else if (!quiet) {
            fprintf(stderr, "wrote %s: %zu points\n", out, merged.count);
        }
    }
    pnpr_cloud_free(&one);
    pnpr_cloud_free(&merged);
    list_free(&inputs);
    return rc;
}
