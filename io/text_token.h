/* Blank-separated tokens of a text line (not installed): shared by the PLY and PCD readers,
 * whose headers (and ASCII bodies) are lines of words. Blanks are space, tab, CR, VT and FF; a
 * newline ends the line before these see it. */
#ifndef PNPR_TEXT_TOKEN_H
#define PNPR_TEXT_TOKEN_H

#include <stddef.h>
#include <string.h>

typedef struct pnpr_token {
    const char *s;
    size_t n;
} pnpr_token;

static inline int pnpr_is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* The token equals the literal. */
static inline int pnpr_token_is(pnpr_token t, const char *lit)
{
    size_t n = strlen(lit);
    return t.n == n && memcmp(t.s, lit, n) == 0;
}

static inline int pnpr_token_eq(pnpr_token a, pnpr_token b)
{
    return a.n == b.n && memcmp(a.s, b.s, a.n) == 0;
}

/* The next token of [*q, e) into *t, *q moved past it; 0 (and *q = e) at the end of the line. */
static inline int pnpr_token_next(const char **q, const char *e, pnpr_token *t)
{
    const char *s = *q;
    while (s < e && pnpr_is_blank(*s)) s++;
    if (s >= e) { *q = e; return 0; }
    t->s = s;
    while (s < e && !pnpr_is_blank(*s)) s++;
    t->n = (size_t)(s - t->s);
    *q = s;
    return 1;
}

/* How many tokens [q, e) holds. */
static inline size_t pnpr_token_count(const char *q, const char *e)
{
    pnpr_token t;
    size_t n = 0;
    while (pnpr_token_next(&q, e, &t)) n++;
    return n;
}

#endif
