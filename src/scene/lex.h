/* SPDX-License-Identifier: MIT */
/*
 * lex.h - the line lexer the scene parser (parse.c) and the OBJ/MTL loader
 * (obj.c) read their text with: one line at a time, tokens split by blanks,
 * '#' starts a comment (rules in format.md, "Text").
 */
#ifndef TG_LEX_H
#define TG_LEX_H

#include "../tinygi.h"
#include "../core/abi_names.h"

typedef struct tgi_token {
    const char *s;
    size_t n;
    int col;                            /* 1-based byte column */
} tgi_token;

typedef struct tgi_lexer {
    const char *text, *end;             /* the whole input */
    const char *next;                   /* start of the next line */
    const char *line, *line_end;        /* the current line (no line end) */
    const char *cur;                    /* cursor within the line */
    int lineno;                         /* 1-based */
    const char *file;                   /* name used in messages */
} tgi_lexer;

void tgi_lex_init(tgi_lexer *lx, const char *text, size_t size, const char *file);
/* Advance to the next line; 0 at the end of input.  A line ends at "\n",
 * "\r\n" or a lone "\r"; the line end is not part of the line (nor of its
 * TG_MAX_LINE bytes).  Rejects NUL bytes and over-long lines (returns -1
 * with the error set). */
int tgi_lex_line(tgi_lexer *lx, tg_error *err);
/* Next token on the line ('#' ends it); 0 at the end of the line. */
int tgi_lex_token(tgi_lexer *lx, tgi_token *t);
int tgi_lex_peek(tgi_lexer *lx, tgi_token *t);
/* Column just past the last character of the line (for "missing" errors). */
int tgi_lex_eol_col(const tgi_lexer *lx);
/* The rest of the line trimmed (without a comment), as a token. */
int tgi_lex_rest(tgi_lexer *lx, tgi_token *t);

int tgi_tok_is(const tgi_token *t, const char *word);
/* Whether a token equals a NUL-terminated name. */
int tgi_tok_eq_name(const tgi_token *t, const char *name);
/* Whole token as a number: 0 ok, 1 not a number, 2 out of range. */
int tgi_tok_real(const tgi_token *t, tg_real *out);
/* Whole token as a decimal integer (optional sign): 0 ok, 1 not, 2 range. */
int tgi_tok_int(const tgi_token *t, long *out);
/* 1 when a number token is not zero but its value v rounded to 0 (Q16.16
 * steps by 2^-16; float underflows below about 1e-45). */
int tgi_tok_rounds_to_zero(const tgi_token *t, tg_real v);
/* What messages add about the number type's range and step. */
#if TG_FIXED
#define TGI_RANGE_NOTE " (Q16.16 fixed point holds -32767.99998..32767.99998)"
#define TGI_ZERO_NOTE " (it rounds to 0 in Q16.16 fixed point, whose step is 2^-16 = 0.0000153)"
#else
#define TGI_RANGE_NOTE " (float holds about -3.4e38..3.4e38)"
#define TGI_ZERO_NOTE " (it rounds to 0 in float)"
#endif
/* A token quoted for messages (at most 40 bytes, then "..."). */
const char *tgi_tok_str(const tgi_token *t, char buf[48]);

/* The words of every limit (tinygi.h's block), as the CLI and the API say
 * them too: "NAME must be LO..HI, got GOT", at FILE:LINE:COL.  Returns
 * TG_ERR_INPUT. */
tg_status tgi_limit_fail(tg_error *err, const char *file, int line, int col,
                         const char *name, long lo, long hi, const char *got);
/* v in decimal, into buf; returns buf. */
const char *tgi_number_text(size_t v, char buf[24]);

#endif
