/* SPDX-License-Identifier: Apache-2.0 */
/* cli_number.h - the one number parser of rtcl's options: the whole text,
 * strictly, in the grammar of the scene loaders (formats/parse_number.h):
 * [+-] digits [. digits] [(e|E) [+-] digits] for numbers, [+-] digits for
 * integers; no blanks, no hex, no "inf" or "nan". A fault is named, never
 * guessed: a subnormal value such as 5e-324 is the finite number it is. */
#ifndef RTCL_CLI_NUMBER_H
#define RTCL_CLI_NUMBER_H

typedef enum cli_number_fault {
    CLI_NUMBER_OK = 0,
    CLI_NUMBER_EMPTY,       /* "" */
    CLI_NUMBER_BLANKS,      /* blank space before or after the number */
    CLI_NUMBER_MALFORMED,   /* not a number in the grammar */
    CLI_NUMBER_NOT_INTEGER, /* a number, but not an integer's digits */
    CLI_NUMBER_NOT_FINITE,  /* "inf", "nan" and the like */
    CLI_NUMBER_TOO_LARGE    /* beyond the largest finite double (or long long) */
} cli_number_fault;

/* Parses text as a number (integer 0) or an integer (integer 1) into *out:
 * numbers correctly rounded to the nearest double (strtod on the checked
 * text; underflow gives the subnormal or zero that rounding gives),
 * integers exact up to 2^53. *out is set only on CLI_NUMBER_OK. */
cli_number_fault cli_parse_number(const char *text, int integer, double *out);

/* What was wrong, for "'TEXT' " + this: "is empty", "has blank space around
 * it", "is not a number", "is not an integer", "is not a finite number",
 * "is too large". */
const char *cli_number_fault_text(cli_number_fault fault);

#endif /* RTCL_CLI_NUMBER_H */
