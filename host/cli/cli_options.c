/* SPDX-License-Identifier: Apache-2.0 */
/* cli_options.c - the table-driven option parser and usage printer
 * (cli_options.h). */
#include "cli_options.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cli_number.h"

enum { USAGE_WIDTH = 79, HELP_COLUMN = 20 };

void cli_usage_error(const cli_command *command, const char *fmt, ...) {
    va_list args;
    va_start(args, fmt);
    fprintf(stderr, "rtcl %s: ", command->name);
    vfprintf(stderr, fmt, args);
    fprintf(stderr, "; see 'rtcl %s --help'\n", command->name);
    va_end(args);
}

/* ---- the tables ---------------------------------------------------------- */

typedef struct found {
    const cli_option *option;
    char *base; /* the group's struct */
} found;

static int lookup_long(const cli_command *c, void *args, const char *name, size_t len, found *out) {
    for (const cli_group *g = c->groups; g->options; g++)
        for (const cli_option *o = g->options; o->name; o++)
            if (strlen(o->name) == len && !strncmp(o->name, name, len)) {
                out->option = o;
                out->base = (char *)args + g->offset;
                return 1;
            }
    return 0;
}

static int lookup_letter(const cli_command *c, void *args, char letter, found *out) {
    for (const cli_group *g = c->groups; g->options; g++)
        for (const cli_option *o = g->options; o->name; o++)
            if (o->letter && o->letter == letter) {
                out->option = o;
                out->base = (char *)args + g->offset;
                return 1;
            }
    return 0;
}

/* Edit distance of a and b (short option names), capped at 9. */
static int distance(const char *a, const char *b) {
    size_t n = strlen(a), m = strlen(b);
    if (n > 40 || m > 40) return 9;
    int row[41];
    for (size_t j = 0; j <= m; j++) row[j] = (int)j;
    for (size_t i = 1; i <= n; i++) {
        int diag = row[0];
        row[0] = (int)i;
        for (size_t j = 1; j <= m; j++) {
            int up = row[j];
            int best = diag + (a[i - 1] != b[j - 1]);
            if (row[j - 1] + 1 < best) best = row[j - 1] + 1;
            if (up + 1 < best) best = up + 1;
            row[j] = best;
            diag = up;
        }
    }
    return row[m] > 9 ? 9 : row[m];
}

/* The option name nearest to name, when it is close (a typo), else NULL. */
static const char *nearest(const cli_command *c, const char *name) {
    const char *best = NULL;
    int best_d = 3; /* at most two edits */
    for (const cli_group *g = c->groups; g->options; g++)
        for (const cli_option *o = g->options; o->name; o++) {
            int d = distance(name, o->name);
            if (d < best_d) best_d = d, best = o->name;
        }
    int d = distance(name, "--help");
    if (d < best_d) best = "--help";
    return best;
}

/* ---- values ----------------------------------------------------------------- */

/* The range of a number option in words: "1..32768", "> 0", "(0, 1000]", or
 * "" when any finite number goes. */
static void range_text(const cli_option *o, char *buf, size_t cap) {
    int lo = isfinite(o->min), hi = isfinite(o->max);
    int lo_open = (o->flags & CLI_MIN_OPEN) != 0, hi_open = (o->flags & CLI_MAX_OPEN) != 0;
    if (o->kind == CLI_INT)
        snprintf(buf, cap, "%.0f..%.0f", o->min, o->max);
    else if (lo && hi)
        snprintf(buf, cap, "%c%g, %g%c", lo_open ? '(' : '[', o->min, o->max, hi_open ? ')' : ']');
    else if (lo)
        snprintf(buf, cap, "%s %g", lo_open ? ">" : ">=", o->min);
    else if (hi)
        snprintf(buf, cap, "%s %g", hi_open ? "<" : "<=", o->max);
    else
        buf[0] = '\0';
}

static int in_range(const cli_option *o, double v) {
    if (o->flags & CLI_MIN_OPEN ? !(v > o->min) : !(v >= o->min)) return 0;
    if (o->flags & CLI_MAX_OPEN ? !(v < o->max) : !(v <= o->max)) return 0;
    return 1;
}

/* Choice k of o (0, 1, ...): its name and value; NULL after the last. */
static const char *choice_at(const cli_option *o, int k, int *value) {
    if (o->choice_name) {
        *value = k;
        return o->choice_name(k);
    }
    if (!o->choices[k].name) return NULL;
    *value = o->choices[k].value;
    return o->choices[k].name;
}

/* "a, b or c" from o's choices. */
static void choice_list(const cli_option *o, char *buf, size_t cap) {
    size_t used = 0;
    int value;
    buf[0] = '\0';
    for (int k = 0; choice_at(o, k, &value); k++) {
        const char *sep = k == 0 ? "" : choice_at(o, k + 1, &value) ? ", " : " or ";
        int w = snprintf(buf + used, cap - used, "%s%s", sep, choice_at(o, k, &value));
        if (w < 0 || (size_t)w >= cap - used) break;
        used += (size_t)w;
    }
}

/* Stores text as option o's value; 0 after printing the error. */
static int store(const cli_command *c, const found *f, const char *text) {
    const cli_option *o = f->option;
    void *dest = f->base + o->offset;
    char range[64];
    switch (o->kind) {
    case CLI_FLAG:
        *(int *)dest = 1;
        return 1;
    case CLI_STRING:
        if ((o->flags & CLI_NONEMPTY) && !text[0]) {
            cli_usage_error(c, "%s needs a %s, not an empty text", o->name, o->value_name);
            return 0;
        }
        *(const char **)dest = text;
        return 1;
    case CLI_CHOICE: {
        int value;
        const char *name;
        for (int k = 0; (name = choice_at(o, k, &value)); k++)
            if (!strcmp(name, text)) {
                *(int *)dest = value;
                return 1;
            }
        if (o->choice_parse && o->choice_parse(text, &value)) {
            *(int *)dest = value;
            return 1;
        }
        char names[512];
        choice_list(o, names, sizeof names);
        cli_usage_error(c, "%s: '%s' is not one of %s", o->name, text, names);
        return 0;
    }
    case CLI_INT:
    case CLI_FLOAT: {
        double v;
        int integer = o->kind == CLI_INT;
        cli_number_fault fault = cli_parse_number(text, integer, &v);
        range_text(o, range, sizeof range);
        if (fault == CLI_NUMBER_MALFORMED && integer) fault = CLI_NUMBER_NOT_INTEGER;
        if (fault != CLI_NUMBER_OK) {
            cli_usage_error(c, "%s: '%s' %s (give %s%s%s)", o->name, text,
                            cli_number_fault_text(fault), integer ? "an integer" : "a number",
                            range[0] ? " " : "", range);
            return 0;
        }
        if (!in_range(o, v)) {
            cli_usage_error(c, "%s: '%s' is out of range (%s)", o->name, text, range);
            return 0;
        }
        if (integer)
            *(int *)dest = (int)v;
        else
            *(double *)dest = v;
        return 1;
    }
    }
    return 0;
}

/* ---- parsing --------------------------------------------------------------- */

static int operands_error(const cli_command *c, char **operands, int n) {
    if (n < c->min_operands) {
        if (c->min_operands == 1)
            cli_usage_error(c, "no %s given", c->operand_noun);
        else
            cli_usage_error(c, "%s needs %d %ss (%s), %d given", c->name, c->min_operands,
                            c->operand_noun, c->operands, n);
        return 1;
    }
    if (c->max_operands >= 0 && n > c->max_operands) {
        if (c->max_operands == 0)
            cli_usage_error(c, "unexpected argument '%s'", operands[0]);
        else if (c->max_operands == 1)
            cli_usage_error(c, "more than one %s given ('%s' and '%s')", c->operand_noun,
                            operands[0], operands[1]);
        else
            cli_usage_error(c, "one %s too many: '%s' (%s)", c->operand_noun,
                            operands[c->max_operands], c->operands);
        return 1;
    }
    return 0;
}

int cli_parse(const cli_command *c, void *args, int argc, char **argv, int *status) {
    int n = 0, only_operands = 0;
    *status = 2;
    for (int i = 1; i < argc; i++) {
        char *a = argv[i];
        if (only_operands || a[0] != '-' || a[1] == '\0') {
            argv[n++] = a; /* n <= i - 1: never overwrites what is still to read */
            continue;
        }
        if (!strcmp(a, "--")) {
            only_operands = 1;
            continue;
        }
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            cli_print_usage(c, stdout);
            *status = 0;
            return -1;
        }
        found f;
        const char *value = NULL;
        if (a[1] == '-') {
            const char *eq = strchr(a, '=');
            size_t len = eq ? (size_t)(eq - a) : strlen(a);
            if (!lookup_long(c, args, a, len, &f)) {
                char name[64];
                snprintf(name, sizeof name, "%.*s", (int)(len < 60 ? len : 60), a);
                const char *near = nearest(c, name);
                if (near)
                    cli_usage_error(c, "unknown option '%s' (did you mean '%s'?)", name, near);
                else
                    cli_usage_error(c, "unknown option '%s'", name);
                return -1;
            }
            if (eq) value = eq + 1;
        } else {
            if (!lookup_letter(c, args, a[1], &f)) {
                cli_usage_error(c, "unknown option '%s'", a);
                return -1;
            }
            if (a[2]) value = a + 2; /* -oFILE */
        }
        if (f.option->kind == CLI_FLAG) {
            if (value) {
                cli_usage_error(c, "option %s takes no value (found '%s')", f.option->name, value);
                return -1;
            }
        } else if (!value) {
            if (i + 1 >= argc) {
                cli_usage_error(c, "option %s needs a value (%s)", f.option->name,
                                f.option->value_name);
                return -1;
            }
            value = argv[++i];
        }
        if (!store(c, &f, value)) return -1;
    }
    if (operands_error(c, argv, n)) return -1;
    return n;
}

/* ---- usage ----------------------------------------------------------------- */

/* Writes text wrapped at USAGE_WIDTH, the first line going on from column
 * (already reached), the others indented to indent. Breaks at blanks, and
 * at every '\n' of the text. */
static void wrap(FILE *out, const char *text, int column, int indent) {
    int line_start = 1;
    for (const char *p = text; *p;) {
        if (*p == '\n') {
            fprintf(out, "\n%*s", indent, "");
            column = indent, line_start = 1, p++;
            continue;
        }
        if (*p == ' ') {
            p++;
            continue;
        }
        const char *w = p;
        while (*p && *p != ' ' && *p != '\n') p++;
        int len = (int)(p - w);
        if (!line_start && column + 1 + len > USAGE_WIDTH) {
            fprintf(out, "\n%*s", indent, "");
            column = indent, line_start = 1;
        }
        if (!line_start) fputc(' ', out), column++;
        fwrite(w, 1, (size_t)len, out);
        column += len, line_start = 0;
    }
    fputc('\n', out);
}

/* "-o, --output FILE" or "--width W". */
static void option_label(const cli_option *o, char *buf, size_t cap) {
    if (o->letter)
        snprintf(buf, cap, "-%c, %s", o->letter, o->name);
    else
        snprintf(buf, cap, "%s", o->name);
    if (o->kind != CLI_FLAG) {
        size_t n = strlen(buf);
        snprintf(buf + n, cap - n, " %s", o->value_name);
    }
}

/* The help of o as printed: its text with {choices} filled in, then the
 * range and the default. */
static void option_help(const cli_option *o, char *buf, size_t cap) {
    char text[2048], names[512] = "";
    if (o->dynamic_help)
        o->dynamic_help(o->help ? o->help : "", text, sizeof text);
    else
        snprintf(text, sizeof text, "%s", o->help ? o->help : "");
    if (o->kind == CLI_CHOICE) choice_list(o, names, sizeof names);
    const char *mark = strstr(text, "{choices}");
    size_t used;
    if (mark)
        used = (size_t)snprintf(buf, cap, "%.*s%s%s", (int)(mark - text), text, names, mark + 9);
    else if (o->kind == CLI_CHOICE)
        used = (size_t)snprintf(buf, cap, "%s (%s)", text, names);
    else
        used = (size_t)snprintf(buf, cap, "%s", text);
    if (used >= cap) return;
    if ((o->kind == CLI_INT || o->kind == CLI_FLOAT) && !(o->flags & CLI_NO_RANGE)) {
        char range[64];
        range_text(o, range, sizeof range);
        if (range[0]) used += (size_t)snprintf(buf + used, cap - used, " (%s)", range);
    }
    if (used < cap && o->fallback) snprintf(buf + used, cap - used, " [%s]", o->fallback);
}

static void print_option(const cli_option *o, FILE *out) {
    char label[96], help[4096];
    option_label(o, label, sizeof label);
    option_help(o, help, sizeof help);
    int n = fprintf(out, "  %s", label);
    if (n + 2 > HELP_COLUMN) { /* at least two blanks between the label and its help */
        fprintf(out, "\n%*s", HELP_COLUMN, "");
    } else {
        fprintf(out, "%*s", HELP_COLUMN - n, "");
    }
    wrap(out, help, HELP_COLUMN, HELP_COLUMN);
}

void cli_print_synopsis(const cli_command *c, FILE *out, const char *prefix) {
    int column = fprintf(out, "%srtcl %s", prefix, c->name);
    const int indent = column + 1; /* continuation lines start under the operands */
    if (c->operands && c->operands[0]) column += fprintf(out, " %s", c->operands);
    for (int pass = 0; pass < 2; pass++) /* required options first */
        for (const cli_group *g = c->groups; g->options; g++)
            for (const cli_option *o = g->options; o->name; o++) {
                int required = (o->flags & CLI_REQUIRED) != 0;
                if (pass == 0 ? !required : required) continue;
                char item[128], label[96];
                if (o->kind == CLI_FLAG)
                    snprintf(label, sizeof label, "%s", o->name);
                else if (o->letter)
                    snprintf(label, sizeof label, "-%c %s", o->letter, o->value_name);
                else
                    snprintf(label, sizeof label, "%s %s", o->name, o->value_name);
                snprintf(item, sizeof item, pass ? "[%s]" : "%s", label);
                int len = (int)strlen(item);
                if (column + 1 + len > USAGE_WIDTH) {
                    fprintf(out, "\n%*s", indent - 1, "");
                    column = indent - 1;
                }
                column += fprintf(out, " %s", item);
            }
    fputc('\n', out);
}

void cli_print_usage(const cli_command *c, FILE *out) {
    cli_print_synopsis(c, out, "usage: ");
    if (c->description) fprintf(out, "\n%s", c->description);
    /* Groups in order; consecutive groups of one title under one heading,
     * --help at the end of the command's own options. */
    int help_shown = 0;
    const char *last = NULL;
    for (const cli_group *g = c->groups; g->options; g++) {
        const char *title = g->title ? g->title : "Options";
        if (!last || strcmp(title, last) != 0) {
            if (last && !help_shown && !strcmp(last, "Options"))
                fprintf(out, "  -h, --help%*sprint this help and exit\n", HELP_COLUMN - 12, ""),
                    help_shown = 1;
            fprintf(out, "\n%s:\n", title);
        }
        last = title;
        for (const cli_option *o = g->options; o->name; o++) print_option(o, out);
    }
    if (last && !help_shown && !strcmp(last, "Options"))
        fprintf(out, "  -h, --help%*sprint this help and exit\n", HELP_COLUMN - 12, ""),
            help_shown = 1;
    if (!help_shown)
        fprintf(out, "\nOptions:\n  -h, --help%*sprint this help and exit\n", HELP_COLUMN - 12, "");
    if (c->epilogue) fprintf(out, "\n%s", c->epilogue);
    if (c->extra_help) c->extra_help(out);
}
