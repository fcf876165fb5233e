/* SPDX-License-Identifier: Apache-2.0 */
/* cli_options.h - every rtcl command's options as a table (name, kind,
 * range, destination, help), read by one parser that also prints the
 * command's usage from the same table, so that the help lists exactly the
 * options the parser takes, with their ranges, choices and defaults.
 *
 * A command is a cli_command: its operands (SCENE, A B, DIR, ...) and a list
 * of option groups. A group is a static table of cli_option rows whose
 * destinations are offsets into one struct, placed at the group's offset in
 * the command's argument struct; so a group shared by several commands
 * (cli_util.h: the scene, renderer and kernel options) is written once, and
 * adding an option to a group, or a group to a command, is one line.
 *
 * Syntax (GNU): "--name value" and "--name=value"; "-o value" and "-ovalue"
 * for the one-letter names; options and operands in any order; "--" ends
 * the options; "-" alone is an operand; -h and --help print the usage. The
 * last of a repeated option wins. */
#ifndef RTCL_CLI_OPTIONS_H
#define RTCL_CLI_OPTIONS_H

#include <stddef.h>
#include <stdio.h>

/* What an option takes, and the type of its destination. */
typedef enum cli_kind {
    CLI_FLAG,   /* no value; int, set to 1 */
    CLI_INT,    /* an integer in [min, max]; int */
    CLI_FLOAT,  /* a finite number in the range (min, max, flags); double */
    CLI_STRING, /* any text (CLI_NONEMPTY: not ""); const char * into argv */
    CLI_CHOICE  /* one of choices' names; int, set to the choice's value */
} cli_kind;

/* Flags of an option. */
enum {
    CLI_MIN_OPEN = 1, /* CLI_FLOAT: the value must be > min (not >= min) */
    CLI_MAX_OPEN = 2, /* CLI_FLOAT: the value must be < max */
    CLI_NONEMPTY = 4, /* CLI_STRING: "" is refused */
    CLI_REQUIRED = 8, /* shown in the synopsis as required (the command checks it) */
    CLI_NO_RANGE = 16 /* CLI_INT/CLI_FLOAT: the help states the range itself */
};

typedef struct cli_choice {
    const char *name;
    int value;
} cli_choice;

typedef struct cli_option {
    const char *name; /* "--width" (NULL ends a table) */
    char letter;      /* 'o' for -o, or 0 */
    cli_kind kind;
    const char *value_name; /* "W" in "--width W" */
    size_t offset;          /* of the destination in the group's struct */
    double min, max;        /* CLI_INT, CLI_FLOAT */
    unsigned flags;
    const cli_choice *choices; /* CLI_CHOICE: ends with a NULL name; or: */
    /* CLI_CHOICE from the library's own names: the name of value 0, 1, ...
     * (NULL after the last), e.g. rt_update_policy_name's. */
    const char *(*choice_name)(int value);
    /* CLI_CHOICE: the library's own parser, which may take more names than
     * it lists (older names); NULL: the names listed only. 1 when taken. */
    int (*choice_parse)(const char *text, int *value);
    /* The help, wrapped to the terminal width by the printer. "{choices}"
     * is replaced by the choices' names; the range (numbers) and the
     * default follow it, so that they are never written twice. */
    const char *help;
    const char *fallback; /* the default in words, shown as "[...]"; NULL for flags */
    /* Help that depends on the build (the backend list, the image formats):
     * written into buf, given the help above (which it may fill in). */
    void (*dynamic_help)(const char *help, char *buf, size_t cap);
} cli_option;

typedef struct cli_group {
    const char *title;         /* "Renderer options"; NULL: the command's own ("Options") */
    const cli_option *options; /* NULL ends the list of groups */
    size_t offset;             /* of the group's struct in the command's arguments */
} cli_group;

typedef struct cli_command {
    const char *name;               /* "render" */
    const char *summary;            /* one line for 'rtcl --help' */
    const char *operands;           /* the synopsis' operands: "SCENE", "A B", "SCENE..." */
    const char *operand_noun;       /* for messages: "scene", "image", "folder" */
    int min_operands, max_operands; /* max < 0: any number */
    const char *description;        /* paragraphs, each line ending in '\n', printed as is */
    const cli_group *groups;
    const char *epilogue;          /* after the options, or NULL */
    void (*extra_help)(FILE *out); /* after the epilogue (the viewer's keys), or NULL */
} cli_command;

/* Parses argv[1 .. argc) (argv[0] is the command's name) into args by the
 * command's tables. Returns the number of operands, which it moves to
 * argv[0 ..) in their order; or -1 with *status the exit status: 0 after
 * --help (usage printed on stdout), 2 after a one-line error on stderr
 * ("rtcl CMD: ...; see 'rtcl CMD --help'") for an unknown option (with the
 * nearest name when one is close), a missing or malformed value, a value out
 * of range, or too few or too many operands. */
int cli_parse(const cli_command *command, void *args, int argc, char **argv, int *status);

/* Prints the usage: synopsis, description, each group's options with their
 * help, ranges and defaults, the epilogue. */
void cli_print_usage(const cli_command *command, FILE *out);

/* The synopsis after prefix ("usage: " or ""): "rtcl render SCENE [-o FILE]
 * ...", required options first, wrapped at 79 columns with continuation
 * lines indented under the operands. */
void cli_print_synopsis(const cli_command *command, FILE *out, const char *prefix);

/* The error line of cli_parse's kind for a command: "rtcl CMD: " + the
 * message + "; see 'rtcl CMD --help'", on stderr. */
void cli_usage_error(const cli_command *command, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

#endif /* RTCL_CLI_OPTIONS_H */
