/* Pipeline files (effects/pipeline.c, effects.h) with known answers: the root's defaults, the
 * inheritance of the paper's node tree (section 4.2: a child starts from its parent's style and
 * chain and overrides what it names), overriding a parameter in place, `+EFFECT`, `no`, `clear`,
 * presets, which node draws a label (listed, unlisted, listed twice, ranges), and every kind of
 * error with its "NAME:LINE:" message and err.line, the pipeline zeroed. */
#include "testutil.h"

#include <pointnpr/effects.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

static pnpr_status parse(const char *text, pnpr_effect_pipeline *p, pnpr_error *err)
{
    memset(err, 0, sizeof *err);
    return pnpr_effect_pipeline_parse(text, strlen(text), "p.txt", p, err);
}

/* The node called `name`, NULL when none. */
static const pnpr_effect_node *node_named(const pnpr_effect_pipeline *p, const char *name)
{
    for (size_t i = 0; i < p->count; i++)
        if (!strcmp(p->nodes[i].name, name)) return &p->nodes[i];
    return NULL;
}

/* Index of parameter `name` of an effect kind (-1 when none). */
static int param_index(pnpr_effect_kind kind, const char *name)
{
    int n;
    const pnpr_effect_param_info *info = pnpr_effect_params(kind, &n);
    for (int i = 0; i < n; i++)
        if (!strcmp(info[i].name, name)) return i;
    return -1;
}

static float param(const pnpr_effect *e, const char *name)
{
    return pnpr_effect_param(e, param_index(e->kind, name));
}

/* The table default of a parameter (the tables may change: tests read them, not copies). */
static float param_default(pnpr_effect_kind kind, const char *name)
{
    const pnpr_effect_param_info *info = pnpr_effect_params(kind, NULL);
    return info[param_index(kind, name)].def;
}

static int same_effect(const pnpr_effect *a, const pnpr_effect *b)
{
    int n;
    pnpr_effect_params(a->kind, &n);
    if (a->kind != b->kind) return 0;
    for (int i = 0; i < n; i++)
        if (pnpr_effect_param(a, i) != pnpr_effect_param(b, i)) return 0;
    return 1;
}

static int is_zero(const pnpr_effect_pipeline *p)
{
    return p->nodes == NULL && p->count == 0 && p->layering == 0;
}

/* Empty text, only comments and blanks: just the root with its defaults. */
static void test_empty(void)
{
    const char *texts[] = {"", "# nothing\n\n   \t\n# more", "\n"};
    for (int k = 0; k < 3; k++) {
        pnpr_effect_pipeline p;
        pnpr_error err;
        CHECK_STATUS(parse(texts[k], &p, &err), PNPR_OK);
        CHECK(p.count == 1);
        if (p.count != 1) continue;
        const pnpr_effect_node *r = &p.nodes[0];
        CHECK(!strcmp(r->name, "root") && r->parent == -1 && r->labels == NULL && r->label_count == 0);
        CHECK(r->style == PNPR_STYLE_POINTS && r->point_scale == 0 && r->per_label == 0);
        CHECK(r->inpaint == 1 && r->inpaint_opts.threshold == PNPR_INPAINT_THRESHOLD &&
              r->inpaint_opts.radius == PNPR_INPAINT_RADIUS);
        CHECK(r->chain.count == 0 && p.layering == PNPR_LAYERING_INPAINTED);
        CHECK(pnpr_effect_pipeline_node_of(&p, 0) == 0 && pnpr_effect_pipeline_node_of(&p, 4294967295u) == 0);
        pnpr_effect_pipeline_free(&p);
        CHECK(is_zero(&p));
    }
    pnpr_effect_pipeline_free(NULL);
    CHECK(pnpr_effect_pipeline_node_of(NULL, 3) == 0);
}

/* Statements before the first node configure the root; layering is global, from anywhere. */
static void test_root_and_settings(void)
{
    static const char text[] =
        "STYLE Sketchy   # keywords and names ignore case\n"
        "size 1.5\n"
        "per_label on\n"
        "inpaint threshold=0.2 radius=5\n"
        "\tgrade\tsaturation=0.5\n"
        "node a labels 1\n"
        "inpaint off\n"
        "per_label off\n"
        "layering fragment\n"
        "node b parent a\n"
        "inpaint radius=7\n"
        "node c\n"
        "layering none\n";
    pnpr_effect_pipeline p;
    pnpr_error err;
    CHECK_STATUS(parse(text, &p, &err), PNPR_OK);
    CHECK(p.count == 4 && p.layering == PNPR_LAYERING_NONE);
    if (p.count != 4) { pnpr_effect_pipeline_free(&p); return; }
    const pnpr_effect_node *r = &p.nodes[0], *a = &p.nodes[1], *b = &p.nodes[2], *c = &p.nodes[3];
    CHECK(r->style == PNPR_STYLE_SKETCHY && r->point_scale == 1.5f && r->per_label == 1 && r->inpaint == 1);
    CHECK(r->inpaint_opts.threshold == 0.2f && r->inpaint_opts.radius == 5);
    CHECK(r->chain.count == 1 && r->chain.effects[0].kind == PNPR_EFFECT_GRADE &&
          param(&r->chain.effects[0], "saturation") == 0.5f && param(&r->chain.effects[0], "contrast") == param_default(PNPR_EFFECT_GRADE, "contrast"));
    /* a: root's configuration, inpainting and per_label switched off */
    CHECK(!strcmp(a->name, "a") && a->parent == 0 && a->style == PNPR_STYLE_SKETCHY && a->point_scale == 1.5f);
    CHECK(a->per_label == 0 && a->inpaint == 0 && a->inpaint_opts.radius == 5 && a->chain.count == 1);
    /* b: child of a; `inpaint radius=7` turns it on again, keeping a's (root's) threshold */
    CHECK(b->parent == 1 && b->inpaint == 1 && b->inpaint_opts.radius == 7 && b->inpaint_opts.threshold == 0.2f);
    CHECK(b->per_label == 0 && b->label_count == 0);
    /* c: child of root by default: per_label on, inpaint on, radius 5 */
    CHECK(c->parent == 0 && c->per_label == 1 && c->inpaint == 1 && c->inpaint_opts.radius == 5);
    pnpr_effect_pipeline_free(&p);
}

/* The paper's tree: children inherit the chain and style, override parameters in place, append
 * with +EFFECT, remove with `no`, empty with `clear`, add presets. */
static void test_inheritance(void)
{
    static const char text[] =
        "style cartoon\n"                             /* 1 */
        "smooth radius=6\n"                           /* 2 */
        "toon levels=4 sharpness=2\n"                 /* 3 */
        "node ground labels 1-3\n"                    /* 4: smooth(6), toon(4, 2) */
        "toon levels=6\n"                             /* 5: in place: toon(6, 2) */
        "+toon edge_strength=0\n"                     /* 6: a second toon */
        "node curb parent ground labels 4\n"          /* 7: starts from ground's 3 */
        "toon sharpness=5\n"                          /* 8: the last toon */
        "style points\n"                              /* 9 */
        "node trees parent ground\n"                  /* 10 */
        "no toon\n"                                   /* 11: smooth only */
        "node cars parent ground\n"                   /* 12 */
        "clear\n"                                     /* 13 */
        "preset poster\n"                             /* 14: the preset's chain */
        "watercolor density=1\n";                     /* 15: alias, appended */
    pnpr_effect_pipeline p;
    pnpr_error err;
    CHECK_STATUS(parse(text, &p, &err), PNPR_OK);
    const pnpr_effect_node *root = node_named(&p, "root"), *ground = node_named(&p, "ground"),
                           *curb = node_named(&p, "curb"), *trees = node_named(&p, "trees"),
                           *cars = node_named(&p, "cars");
    CHECK(p.count == 5 && root && ground && curb && trees && cars);
    if (!(p.count == 5 && root && ground && curb && trees && cars)) { pnpr_effect_pipeline_free(&p); return; }
    /* root: smooth(radius 6), toon(levels 4, sharpness 2) */
    CHECK(root->chain.count == 2 && root->chain.effects[0].kind == PNPR_EFFECT_SMOOTH &&
          root->chain.effects[1].kind == PNPR_EFFECT_TOON);
    CHECK(param(&root->chain.effects[1], "levels") == 4 && param(&root->chain.effects[1], "sharpness") == 2);
    /* ground: same style; toon overridden in place (position 1, sharpness kept), a second toon */
    CHECK(ground->style == PNPR_STYLE_CARTOON && ground->chain.count == 3 && ground->parent == 0);
    CHECK(ground->chain.effects[0].kind == PNPR_EFFECT_SMOOTH && param(&ground->chain.effects[0], "radius") == 6);
    CHECK(ground->chain.effects[1].kind == PNPR_EFFECT_TOON && param(&ground->chain.effects[1], "levels") == 6 &&
          param(&ground->chain.effects[1], "sharpness") == 2);
    CHECK(ground->chain.effects[2].kind == PNPR_EFFECT_TOON && param(&ground->chain.effects[2], "edge_strength") == 0 &&
          param(&ground->chain.effects[2], "levels") == param_default(PNPR_EFFECT_TOON, "levels"));
    CHECK(ground->chain.effects[2].set == (1u << param_index(PNPR_EFFECT_TOON, "edge_strength")));
    /* curb: ground's chain; its last toon (index 2) gets sharpness 5, index 1 keeps 2 */
    CHECK(curb->parent == 1 && curb->style == PNPR_STYLE_POINTS && curb->chain.count == 3);
    CHECK(param(&curb->chain.effects[1], "sharpness") == 2 && param(&curb->chain.effects[2], "sharpness") == 5);
    CHECK(param(&curb->chain.effects[2], "edge_strength") == 0);
    /* ground itself is not changed by its child */
    CHECK(param(&ground->chain.effects[2], "sharpness") == param_default(PNPR_EFFECT_TOON, "sharpness"));
    /* trees: `no toon` removed both toons */
    CHECK(trees->parent == 1 && trees->style == PNPR_STYLE_CARTOON && trees->chain.count == 1 &&
          trees->chain.effects[0].kind == PNPR_EFFECT_SMOOTH && param(&trees->chain.effects[0], "radius") == 6);
    /* cars: cleared, then the poster preset and a watercolour */
    const pnpr_effect_preset *poster = pnpr_effect_preset_find("poster");
    CHECK(poster && poster->chain.count >= 1 && cars->chain.count == poster->chain.count + 1);
    if (poster && cars->chain.count == poster->chain.count + 1) {
        for (int i = 0; i < poster->chain.count; i++)
            CHECK(same_effect(&cars->chain.effects[i], &poster->chain.effects[i]));
        const pnpr_effect *w = &cars->chain.effects[poster->chain.count];
        CHECK(w->kind == PNPR_EFFECT_WATERCOLOUR && param(w, "density") == 1);
    }
    pnpr_effect_pipeline_free(&p);
}

/* A preset's own parameters come along (muted: a grade with its own saturation); a bare EFFECT
 * that is already there changes nothing; a parameter overrides in place. */
static void test_preset_and_bare_override(void)
{
    pnpr_effect_pipeline p;
    pnpr_error err;
    CHECK_STATUS(parse("preset MUTED\ngrade\ngrade brightness=-0.25\n", &p, &err), PNPR_OK);
    const pnpr_effect_preset *muted = pnpr_effect_preset_find("muted");
    CHECK(muted && muted->chain.count == 1 && muted->chain.effects[0].kind == PNPR_EFFECT_GRADE);
    CHECK(p.count == 1 && p.nodes[0].chain.count == 1);
    if (muted && p.count == 1 && p.nodes[0].chain.count == 1) {
        const pnpr_effect *g = &p.nodes[0].chain.effects[0];
        CHECK(g->kind == PNPR_EFFECT_GRADE && param(g, "brightness") == -0.25f);
        CHECK(param(g, "saturation") == param(&muted->chain.effects[0], "saturation"));
        CHECK(param(g, "saturation") != param_default(PNPR_EFFECT_GRADE, "saturation"));
    }
    pnpr_effect_pipeline_free(&p);
}

/* Which node draws a label: the last node listing it, else the root; labels stored sorted and
 * without repeats. */
static void test_node_of(void)
{
    static const char text[] =
        "node a labels 9 5-9 1,2 2,\n"
        "node b labels 7-20,30\n"
        "node c parent a\n"
        "node d labels 4294967290-4294967295 0\n"
        "node e labels 8\n";
    pnpr_effect_pipeline p;
    pnpr_error err;
    CHECK_STATUS(parse(text, &p, &err), PNPR_OK);
    CHECK(p.count == 6);
    if (p.count != 6) { pnpr_effect_pipeline_free(&p); return; }
    static const uint32_t a_labels[] = {1, 2, 5, 6, 7, 8, 9};
    CHECK(p.nodes[1].label_count == 7 && !memcmp(p.nodes[1].labels, a_labels, sizeof a_labels));
    CHECK(p.nodes[2].label_count == 15 && p.nodes[2].labels[0] == 7 && p.nodes[2].labels[13] == 20 &&
          p.nodes[2].labels[14] == 30);
    CHECK(p.nodes[3].label_count == 0 && p.nodes[4].label_count == 7 && p.nodes[4].labels[0] == 0 &&
          p.nodes[4].labels[6] == 4294967295u);
    static const struct { uint32_t label; size_t node; } want[] = {
        {0, 4}, {1, 1}, {2, 1}, {3, 0}, {4, 0}, {5, 1}, {6, 1}, {7, 2}, {8, 5}, {9, 2}, {10, 2}, {20, 2},
        {21, 0}, {29, 0}, {30, 2}, {31, 0}, {4294967289u, 0}, {4294967290u, 4}, {4294967295u, 4},
    };
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++)
        CHECK_MSG(pnpr_effect_pipeline_node_of(&p, want[i].label) == want[i].node, "label %u: node %zu, want %zu",
                  (unsigned)want[i].label, pnpr_effect_pipeline_node_of(&p, want[i].label), want[i].node);
    pnpr_effect_pipeline_free(&p);
}

/* The file's label budget: exactly 16777216 labels parse; one more is refused. */
static void test_label_limits(void)
{
    pnpr_effect_pipeline p;
    pnpr_error err;
    CHECK_STATUS(parse("node big labels 0-16777215\n", &p, &err), PNPR_OK);
    CHECK(p.count == 2 && p.nodes[1].label_count == 16777216u);
    if (p.count == 2) {
        CHECK(p.nodes[1].labels[16777215] == 16777215u);
        CHECK(pnpr_effect_pipeline_node_of(&p, 16777215u) == 1 && pnpr_effect_pipeline_node_of(&p, 16777216u) == 0);
    }
    pnpr_effect_pipeline_free(&p);
    /* repeats count as written: 0-16777215 and 0 again are 16777217 */
    CHECK_STATUS(parse("node big labels 0-16777215\n\nnode again labels 0\n", &p, &err), PNPR_ERR_FORMAT);
    CHECK(err.line == 3 && !strncmp(err.message, "p.txt:3: too many labels", 24) && is_zero(&p));
    CHECK_STATUS(parse("node big labels 100-16777316\n", &p, &err), PNPR_ERR_FORMAT);
    CHECK(err.line == 1 && strstr(err.message, "covers 16777217 labels") && is_zero(&p));
}

/* One bad line each: status, err.line, "p.txt:LINE: " and a piece of the message; nothing kept. */
static void test_errors(void)
{
    static const struct { const char *text; long line; const char *what; } bad[] = {
        {"toon\nnosuch\n", 2, "unknown statement or effect 'nosuch'"},
        {"+nosuch levels=2\n", 1, "unknown statement or effect '+nosuch'"},
        {"no nosuch\n", 1, "unknown effect 'nosuch' (smooth, toon, watercolour"},
        {"\n\ntoon colour=3\n", 3, "toon has no parameter 'colour' ("},
        {"\n\ntoon colour=3\n", 3, "levels"},
        {"toon levels\n", 1, "toon: want PARAM=VALUE, got 'levels'"},
        {"toon levels=1000\n", 1, "toon levels=1000: want a finite number in "},
        {"toon levels=-1.5\n", 1, "toon levels=-1.5: want a finite number in "},
        {"grade brightness=nan\n", 1, "grade brightness=nan: want a finite number in "},
        {"grade brightness=-inf\n", 1, "grade brightness=-inf"},
        {"edges phi=1e99\n", 1, "edges phi=1e99"},
        {"toon levels=4x\n", 1, "toon levels=4x"},
        {"toon levels=\n", 1, "toon levels=: want"},
        {"node a\nnode b\nnode a\n", 3, "node 'a' is defined twice"},
        {"node root\n", 1, "'root' names the root node"},
        {"node a parent b\nnode b\n", 1, "unknown parent 'b'"},
        {"node a/b\n", 1, "node name 'a/b' must be"},
        {"node\n", 1, "'node' wants a name"},
        {"node a parent\n", 1, "'parent' wants"},
        {"node a extra\n", 1, "unexpected 'extra' in a node line"},
        {"node a labels\n", 1, "'labels' wants at least one label"},
        {"node a labels 1,x\n", 1, "bad label 'x'"},
        {"node a labels -3\n", 1, "bad label '-3'"},
        {"node a labels 4294967296\n", 1, "bad label '4294967296'"},
        {"node a labels 1-2-3\n", 1, "bad label '1-2-3'"},
        {"node a labels 5-3\n", 1, "reversed range '5-3'"},
        {"style lines\n", 1, "the lines style cannot be a segment layer (profile lines have no labels)"},
        {"style nosuch\n", 1, "unknown style 'nosuch' (points, sketchy, stipple, cartoon, painterly, brush, hierarchy)"},
        {"style points extra\n", 1, "unexpected 'extra' after the style"},
        {"size 0.01\n", 1, "'size' wants a number in 0.05..20"},
        {"size inf\n", 1, "'size' wants a number in 0.05..20"},
        {"per_label yes\n", 1, "'per_label' wants on or off"},
        {"inpaint threshold=0\n", 1, "inpaint threshold=0: want a number in (0, 1]"},
        {"inpaint radius=65\n", 1, "inpaint radius=65: want an integer in 1..64"},
        {"inpaint radius=2.5\n", 1, "inpaint radius=2.5"},
        {"inpaint off radius=3\n", 1, "unexpected 'radius=3' after 'inpaint off'"},
        {"inpaint sideways\n", 1, "unexpected 'sideways' after inpaint"},
        {"layering sometimes\n", 1, "'layering' wants inpainted, fragment or none"},
        {"preset nosuch\n", 1, "unknown preset 'nosuch' (cartoon, "},
        {"clear now\n", 1, "unexpected 'now' after clear"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        pnpr_effect_pipeline p;
        pnpr_error err;
        pnpr_status st = parse(bad[i].text, &p, &err);
        char prefix[32];
        snprintf(prefix, sizeof prefix, "p.txt:%ld: ", bad[i].line);
        CHECK_MSG(st == PNPR_ERR_FORMAT && err.line == bad[i].line && !strncmp(err.message, prefix, strlen(prefix)) &&
                      strstr(err.message, bad[i].what) && is_zero(&p),
                  "case %zu: status %d, line %ld, message '%s'", i, (int)st, err.line, err.message);
    }
}

/* Chains hold PNPR_EFFECT_CHAIN_MAX effects: one more, by +EFFECT or by a preset, is refused. */
static void test_chain_too_long(void)
{
    char text[1024] = "";
    for (int i = 0; i < PNPR_EFFECT_CHAIN_MAX; i++) strcat(text, "+smooth\n");
    pnpr_effect_pipeline p;
    pnpr_error err;
    CHECK_STATUS(parse(text, &p, &err), PNPR_OK);
    CHECK(p.count == 1 && p.nodes[0].chain.count == PNPR_EFFECT_CHAIN_MAX);
    pnpr_effect_pipeline_free(&p);
    strcat(text, "smooth radius=2\n"); /* an override: still fits */
    strcat(text, "node a\n+toon\n");
    CHECK_STATUS(parse(text, &p, &err), PNPR_ERR_FORMAT);
    CHECK(err.line == PNPR_EFFECT_CHAIN_MAX + 3 && strstr(err.message, "toon makes the chain longer than 16") && is_zero(&p));
    /* a preset of k effects after CHAIN_MAX - k + 1 others: one too many */
    const pnpr_effect_preset *wc = pnpr_effect_preset_find("watercolour");
    CHECK(wc && wc->chain.count >= 1);
    if (!wc || wc->chain.count < 1) return;
    char text2[1024] = "";
    int fill = PNPR_EFFECT_CHAIN_MAX - wc->chain.count + 1;
    for (int i = 0; i < fill; i++) strcat(text2, "+grade\n");
    strcat(text2, "preset watercolour\n");
    CHECK_STATUS(parse(text2, &p, &err), PNPR_ERR_FORMAT);
    CHECK(err.line == fill + 1 && strstr(err.message, "preset watercolour makes the chain longer") && is_zero(&p));
}

/* Lines of 1023 characters parse (with '\n' or "\r\n"); 1024 are refused on their line. */
static void test_long_lines(void)
{
    char *text = malloc(4096);
    char comment[1024];
    memset(comment, 'x', sizeof comment);
    comment[0] = '#';
    comment[1023] = '\0';
    snprintf(text, 4096, "toon\r\n%s\r\n%s\nnode a\n", comment, comment);
    pnpr_effect_pipeline p;
    pnpr_error err;
    CHECK_STATUS(parse(text, &p, &err), PNPR_OK);
    CHECK(p.count == 2 && p.nodes[0].chain.count == 1);
    pnpr_effect_pipeline_free(&p);
    snprintf(text, 4096, "toon\n%sx\nnode a\n", comment);
    CHECK_STATUS(parse(text, &p, &err), PNPR_ERR_FORMAT);
    CHECK(err.line == 2 && !strcmp(err.message, "p.txt:2: line longer than 1023 characters") && is_zero(&p));
    snprintf(text, 4096, "toon\n\n%sx", comment); /* the last line, without '\n' */
    CHECK_STATUS(parse(text, &p, &err), PNPR_ERR_FORMAT);
    CHECK(err.line == 3 && is_zero(&p));
    free(text);
}

static int same_pipeline(const pnpr_effect_pipeline *a, const pnpr_effect_pipeline *b)
{
    if (a->count != b->count || a->layering != b->layering) return 0;
    for (size_t i = 0; i < a->count; i++) {
        const pnpr_effect_node *x = &a->nodes[i], *y = &b->nodes[i];
        if (strcmp(x->name, y->name) || x->parent != y->parent || x->label_count != y->label_count ||
            (x->label_count && memcmp(x->labels, y->labels, x->label_count * sizeof *x->labels)) ||
            x->style != y->style || x->point_scale != y->point_scale || x->per_label != y->per_label ||
            x->inpaint != y->inpaint || x->inpaint_opts.threshold != y->inpaint_opts.threshold ||
            x->inpaint_opts.radius != y->inpaint_opts.radius || x->chain.count != y->chain.count)
            return 0;
        for (int k = 0; k < x->chain.count; k++) {
            const pnpr_effect *e = &x->chain.effects[k], *f = &y->chain.effects[k];
            if (e->kind != f->kind || e->set != f->set) return 0;
            for (int j = 0; j < PNPR_EFFECT_PARAMS_MAX; j++)
                if ((e->set >> j) & 1u && e->params[j] != f->params[j]) return 0;
        }
    }
    return 1;
}

/* CRLF line ends parse the same as LF; errors count the same lines. */
static void test_crlf(void)
{
    static const char lf[] = "layering fragment\nstyle stipple # c\ntoon levels=5\n\nnode a labels 1-4, 9\n"
                             "size 2\n+grade saturation=0\nnode b parent a labels 3\nno toon\ninpaint radius=2";
    char crlf[512];
    size_t n = 0;
    for (const char *s = lf; *s; s++) {
        if (*s == '\n') crlf[n++] = '\r';
        crlf[n++] = *s;
    }
    crlf[n] = '\0';
    pnpr_effect_pipeline a, b;
    pnpr_error err;
    CHECK_STATUS(parse(lf, &a, &err), PNPR_OK);
    CHECK_STATUS(parse(crlf, &b, &err), PNPR_OK);
    CHECK(a.count == 3 && a.layering == PNPR_LAYERING_FRAGMENT && a.nodes[1].label_count == 5 && same_pipeline(&a, &b));
    CHECK(a.count == 3 && a.nodes[2].chain.count == 1 && a.nodes[2].inpaint_opts.radius == 2 &&
          a.nodes[2].point_scale == 2.0f);
    pnpr_effect_pipeline_free(&a);
    pnpr_effect_pipeline_free(&b);
    CHECK_STATUS(parse("toon\r\n\r\nnosuch\r\n", &a, &err), PNPR_ERR_FORMAT);
    CHECK(err.line == 3 && !strncmp(err.message, "p.txt:3: unknown statement or effect 'nosuch' ", 46));
}

/* 65536 nodes (the root and 65535 more) parse; one more is refused. */
static void test_many_nodes(void)
{
    size_t cap = 65536 * 32, n = 0;
    char *text = malloc(cap);
    for (int i = 1; i < 65536; i++) n += (size_t)snprintf(text + n, cap - n, "node n%d labels %d\n", i, i);
    pnpr_effect_pipeline p;
    pnpr_error err;
    CHECK_STATUS(pnpr_effect_pipeline_parse(text, n, "p.txt", &p, &err), PNPR_OK);
    CHECK(p.count == 65536 && pnpr_effect_pipeline_node_of(&p, 65535) == 65535 &&
          pnpr_effect_pipeline_node_of(&p, 777) == 777 && pnpr_effect_pipeline_node_of(&p, 65536) == 0);
    pnpr_effect_pipeline_free(&p);
    n += (size_t)snprintf(text + n, cap - n, "node one_more\n");
    CHECK_STATUS(pnpr_effect_pipeline_parse(text, n, "p.txt", &p, &err), PNPR_ERR_FORMAT);
    CHECK(err.line == 65536 && strstr(err.message, "more than 65536 nodes") && is_zero(&p));
    free(text);
}

/* Bad arguments: no text with a size, no output. */
static void test_arguments(void)
{
    pnpr_effect_pipeline p;
    pnpr_error err;
    CHECK_STATUS(pnpr_effect_pipeline_parse(NULL, 3, "p.txt", &p, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(is_zero(&p));
    CHECK_STATUS(pnpr_effect_pipeline_parse("toon", 4, "p.txt", NULL, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_effect_pipeline_parse(NULL, 0, "p.txt", &p, &err), PNPR_OK);
    CHECK(p.count == 1);
    pnpr_effect_pipeline_free(&p);
    /* a NUL byte ends a line's content */
    CHECK_STATUS(pnpr_effect_pipeline_parse("toon\0garbage\nsmooth\n", 20, "p.txt", &p, &err), PNPR_OK);
    CHECK(p.count == 1 && p.nodes[0].chain.count == 2);
    pnpr_effect_pipeline_free(&p);
}

int main(void)
{
    test_empty();
    test_root_and_settings();
    test_inheritance();
    test_preset_and_bare_override();
    test_node_of();
    test_label_limits();
    test_errors();
    test_chain_too_long();
    test_long_lines();
    test_crlf();
    test_many_nodes();
    test_arguments();
    return pnpr_test_finish("test_effect_pipeline");
}
