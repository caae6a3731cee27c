/* SPDX-License-Identifier: MIT */
/*
 * lex.c - the line lexer of scene, OBJ and MTL text (lex.h; the rules in
 * format.md, "Text").
 */
#include <string.h>
#include "lex.h"
#include "../core/error.h"

#if !TG_NO_SCENE_TEXT /* the whole file is left out with TG_NO_SCENE_TEXT=1 (tinygi.h "FEATURE SWITCHES") */

static int is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

void tgi_lex_init(tgi_lexer *lx, const char *text, size_t size, const char *file)
{
    memset(lx, 0, sizeof *lx);
    if (!text) { text = ""; size = 0; }
    lx->text = text;
    lx->end = text + size;
    lx->next = text;
    lx->file = file;
    if (size >= 3 && (unsigned char)text[0] == 0xEFu &&
        (unsigned char)text[1] == 0xBBu && (unsigned char)text[2] == 0xBFu)
        lx->next = text + 3; /* UTF-8 byte order mark */
}

const char *tgi_number_text(size_t v, char buf[24])
{
    char tmp[24];
    int n = 0, i;
    do { tmp[n++] = (char)('0' + v % 10u); v /= 10u; } while (v && n < 23);
    for (i = 0; i < n; i++) buf[i] = tmp[n - 1 - i];
    buf[n] = '\0';
    return buf;
}

tg_status tgi_limit_fail(tg_error *err, const char *file, int line, int col,
                         const char *name, long lo, long hi, const char *got)
{
    tgi_error_set(err, TG_ERR_INPUT, file, line, col, name);
    tgi_error_append(err, " must be ");
    tgi_error_append_int(err, lo);
    tgi_error_append(err, "..");
    tgi_error_append_int(err, hi);
    tgi_error_append(err, ", got ");
    tgi_error_append(err, got);
    return TG_ERR_INPUT;
}

/* A line ends at "\n", "\r\n" or a lone "\r" (old Mac text). */
static int is_line_end(char c) { return c == '\n' || c == '\r'; }

int tgi_lex_line(tgi_lexer *lx, tg_error *err)
{
    const char *s = lx->next, *e = s, *next;
    char got[24];
    if (s >= lx->end) return 0;
    while (e < lx->end && !is_line_end(*e)) {
        if (*e == '\0') {
            tgi_error_set(err, TG_ERR_INPUT, lx->file, lx->lineno + 1,
                         (int)(e - s) + 1, "NUL byte in the input; expected text");
            return -1;
        }
        e++;
    }
    if (e - s > TG_MAX_LINE) {
        tgi_limit_fail(err, lx->file, lx->lineno + 1, TG_MAX_LINE + 1, "line length in bytes",
                       0, TG_MAX_LINE, tgi_number_text((size_t)(e - s), got));
        return -1;
    }
    next = e;
    if (next < lx->end) next += (*next == '\r' && next + 1 < lx->end && next[1] == '\n') ? 2 : 1;
    lx->lineno++;
    lx->line = s;
    lx->line_end = e;
    lx->cur = s;
    lx->next = next;
    return 1;
}

int tgi_lex_token(tgi_lexer *lx, tgi_token *t)
{
    const char *c = lx->cur;
    while (c < lx->line_end && is_blank(*c)) c++;
    if (c >= lx->line_end || *c == '#') { lx->cur = lx->line_end; return 0; }
    t->s = c;
    t->col = (int)(c - lx->line) + 1;
    while (c < lx->line_end && !is_blank(*c) && *c != '#') c++;
    t->n = (size_t)(c - t->s);
    lx->cur = c;
    return 1;
}

int tgi_lex_peek(tgi_lexer *lx, tgi_token *t)
{
    const char *save = lx->cur;
    int r = tgi_lex_token(lx, t);
    lx->cur = save;
    return r;
}

int tgi_lex_eol_col(const tgi_lexer *lx)
{
    const char *c = lx->line, *last = lx->line;
    while (c < lx->line_end && *c != '#') {
        if (!is_blank(*c)) last = c + 1;
        c++;
    }
    return (int)(last - lx->line) + 1;
}

int tgi_lex_rest(tgi_lexer *lx, tgi_token *t)
{
    const char *c = lx->cur, *e;
    while (c < lx->line_end && is_blank(*c)) c++;
    e = c;
    while (e < lx->line_end && *e != '#') e++;
    while (e > c && is_blank(e[-1])) e--;
    lx->cur = lx->line_end;
    if (e == c) return 0;
    t->s = c;
    t->n = (size_t)(e - c);
    t->col = (int)(c - lx->line) + 1;
    return 1;
}

int tgi_tok_is(const tgi_token *t, const char *word)
{
    size_t n = strlen(word);
    return t->n == n && memcmp(t->s, word, n) == 0;
}

int tgi_tok_eq_name(const tgi_token *t, const char *name)
{
    return t->n <= TG_MAX_NAME && memcmp(t->s, name, t->n) == 0 && name[t->n] == '\0';
}

int tgi_tok_real(const tgi_token *t, tg_real *out)
{
    int overflow = 0;
    tg_real v = 0;
    size_t used;
    if (t->n == 0) return 1;
    used = tg_parse_real(t->s, t->n, &v, &overflow);
    if (used != t->n) return 1;
    if (overflow || !tg_isfinite(v)) return 2;
    *out = v;
    return 0;
}

int tgi_tok_int(const tgi_token *t, long *out)
{
    size_t i = 0;
    long v = 0;
    int neg = 0;
    if (t->n && (t->s[0] == '-' || t->s[0] == '+')) { neg = t->s[0] == '-'; i = 1; }
    if (i >= t->n) return 1;
    for (; i < t->n; i++) {
        char c = t->s[i];
        if (c < '0' || c > '9') return 1;
        if (v > 100000000L) return 2; /* keeps |v| below 1e9 + 9 */
        v = v * 10 + (c - '0');
    }
    *out = neg ? -v : v;
    return 0;
}

int tgi_tok_rounds_to_zero(const tgi_token *t, tg_real v)
{
    size_t i;
    if (v != 0) return 0;
    for (i = 0; i < t->n && t->s[i] != 'e' && t->s[i] != 'E'; i++)
        if (t->s[i] >= '1' && t->s[i] <= '9') return 1;
    return 0;
}

const char *tgi_tok_str(const tgi_token *t, char buf[48])
{
    size_t n = t->n > 40 ? 40 : t->n;
    memcpy(buf, t->s, n);
    if (t->n > 40) { memcpy(buf + n, "...", 3); n += 3; }
    buf[n] = '\0';
    return buf;
}

#endif /* !TG_NO_SCENE_TEXT */
