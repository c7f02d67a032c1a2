/* Blank-separated tokens of a text line (not installed): shared by the PLY and PCD readers,
 * whose headers (and ASCII bodies) are lines of words. Blanks are space, tab, CR, VT and FF; a
 * newline ends the line before these see it. */
#ifndef PNPR_TEXT_TOKEN_H
#define PNPR_TEXT_TOKEN_H

#include <float.h>
#include <locale.h>
#include <stddef.h>
#include <stdlib.h>
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

/* Copies n characters of a number in the "C" form into buf (n + 1 bytes, NUL-terminated) with
 * '.' replaced by the locale's decimal point, so that strtod/strtof read it whatever LC_NUMERIC
 * says. */
static inline void pnpr_token_c_number(const char *s, size_t n, char *buf)
{
    memcpy(buf, s, n);
    buf[n] = '\0';
    const struct lconv *lc = localeconv();
    char dp = lc && lc->decimal_point && lc->decimal_point[0] ? lc->decimal_point[0] : '.';
    char *dot = dp != '.' ? memchr(buf, '.', n) : NULL;
    if (dot) *dot = dp;
}

/* A decimal number in the "C" form, whatever LC_NUMERIC says: [+-]digits[.digits][(e|E)[+-]digits]
 * with at least one mantissa digit (no hex, no nan/inf, no trailing text), at most 256 characters,
 * finite as a double (1e400 is refused; underflow to 0 is accepted). *has_fraction (may be NULL):
 * whether it is written with a '.' or an exponent. Used by the OFF and text point readers. */
static inline int pnpr_token_decimal(pnpr_token t, double *out, int *has_fraction)
{
    char buf[257];
    size_t i = 0;
    int digits = 0, frac = 0;
    if (t.n == 0 || t.n >= sizeof buf) return 0;
    if (t.s[i] == '+' || t.s[i] == '-') i++;
    for (; i < t.n && t.s[i] >= '0' && t.s[i] <= '9'; i++) digits++;
    if (i < t.n && t.s[i] == '.') {
        frac = 1;
        for (i++; i < t.n && t.s[i] >= '0' && t.s[i] <= '9'; i++) digits++;
    }
    if (!digits) return 0;
    if (i < t.n && (t.s[i] == 'e' || t.s[i] == 'E')) {
        frac = 1;
        i++;
        if (i < t.n && (t.s[i] == '+' || t.s[i] == '-')) i++;
        if (i == t.n || t.s[i] < '0' || t.s[i] > '9') return 0;
        while (i < t.n && t.s[i] >= '0' && t.s[i] <= '9') i++;
    }
    if (i != t.n) return 0;
    pnpr_token_c_number(t.s, t.n, buf);
    double v = strtod(buf, NULL);
    if (v != v || v > DBL_MAX || v < -DBL_MAX) return 0;
    *out = v;
    if (has_fraction) *has_fraction = frac;
    return 1;
}

#endif
