/* A table-driven command line (libprogutil, prefix pu_): the programs' options are a table of
 * pu_cli_option, each found by its name; the parser stores typed, range-checked values into the
 * fields of the caller's options struct (PU_CLI_AT offsets), and the --help text is generated
 * from the same table.
 *
 * Syntax: "--name VALUE" and "--name=VALUE"; an alias ("-j") stands for its option; "--" ends
 * the options (what follows is positional); "-" alone is positional. An option with an optional
 * value ("--modes [T]") takes the next argument only when it has the form of its kind (a number
 * for PU_CLI_DOUBLE, also a negative one, which the range then refuses with the option's
 * message); with "=" the value is always its own.
 *
 * Messages name the option and the value (without the program's name, which the caller puts
 * in front): "option --jobs needs an integer in 1..64 (got '0')", "option --out needs a value",
 * "option --quiet takes no value (got '1')", "unknown option '--rtoll'; did you mean --rtol?".
 * No output, no exit, no global state. */
#ifndef PU_CLI_H
#define PU_CLI_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The field member of the options struct type: its offset + 1 (0 means no field). */
#define PU_CLI_AT(type, member) (offsetof(type, member) + 1)

typedef enum pu_cli_kind {
    PU_CLI_FLAG,   /* no value: the int field becomes 1 */
    PU_CLI_STRING, /* const char * field: the value as given (argv's own string) */
    PU_CLI_INT,    /* int field: decimal digits only (no sign), in [min, max] */
    PU_CLI_LLONG,  /* long long field: the same */
    PU_CLI_DOUBLE, /* double field: a decimal number (digits, sign, point, exponent: never
                      hexadecimal, inf or nan), finite, within the range */
    PU_CLI_CHOICE, /* const char * field: one of choices ("auto|local|mpi") */
    PU_CLI_CALL,   /* take(opt, value, base, msg, size) stores it (value NULL: none given) */
    PU_CLI_STOP    /* no value: parsing stops there (--help, --version) */
} pu_cli_kind;

typedef enum pu_cli_value {
    PU_CLI_REQUIRED = 0, /* the option needs a value */
    PU_CLI_OPTIONAL,     /* the value may be left out (the field then keeps its value) */
    PU_CLI_NONE          /* PU_CLI_CALL without a value (FLAG and STOP never take one) */
} pu_cli_value;

typedef struct pu_cli_option pu_cli_option;
/* Stores value (NULL: none given) for opt into base; 0, or -1 with the message in msg. */
typedef int (*pu_cli_take_fn)(const pu_cli_option *opt, const char *value, void *base, char *msg,
                              size_t size);

struct pu_cli_option {
    const char *name;  /* "--out" */
    const char *alias; /* a short form ("-j"), or NULL */
    pu_cli_kind kind;
    pu_cli_value value; /* required (default), optional or none */
    const char *arg;    /* the value's name in the help ("DIR"; optional ones are shown "[T]") */
    const char *help;   /* its description, wrapped at the help's width; "\n" breaks a line */
    size_t at;          /* PU_CLI_AT of the value's field; 0: none */
    size_t seen;        /* PU_CLI_AT of an int set to 1 when the option is given; 0: none */
    double min, max;    /* the range of INT, LLONG and DOUBLE values (both 0 for INT, LLONG: the
                           type's range) */
    int min_open, max_open; /* the bound itself excluded */
    const char *what;       /* the values expected, for the messages ("an integer in 1..64") */
    const char *bad;        /* or the whole message: a format with two %s, the name and the
                               value ("%s takes a whole number from 1 to 9, not '%s'") */
    const char *choices;    /* PU_CLI_CHOICE: the values, separated by '|' */
    pu_cli_take_fn take;    /* PU_CLI_CALL */
    const void *data;       /* for take */
    int hidden;             /* left out of the help and of the suggestions */
};

typedef struct pu_cli {
    const char *program;       /* "crane" */
    const char *usage;         /* after "usage: PROGRAM ": "[SCENE] [options]"; NULL: every
                                  option of the help as "[--name ARG]", wrapped */
    const char *intro;         /* paragraph(s) after the usage line, or NULL */
    const char *options_title; /* the line before the options ("options:"), or NULL */
    const char *epilogue;      /* text after the options, or NULL */
    const pu_cli_option *options;
    int noptions;
    size_t positional;           /* PU_CLI_AT of the const char * of the one positional
                                    argument; 0: none is allowed */
    const char *positional_many; /* a format with two %s for a second one ("more than one
                                    scene given ('%s' and '%s')") */
    int suggest;                 /* unknown options: "; did you mean --X?" (the nearest) */
    int column, width;           /* the help's description column and line width (0: 23, 92) */
} pu_cli;

enum { PU_CLI_DONE = 0, PU_CLI_STOPPED = 1, PU_CLI_ERROR = -1 };

/* Parses argv[1..argc-1] into base (the fields keep their values where no option sets them).
 * PU_CLI_DONE; PU_CLI_STOPPED at a PU_CLI_STOP option (*stopped: which; the rest is not read);
 * PU_CLI_ERROR with the message in msg. stopped may be NULL. */
int pu_cli_parse(const pu_cli *cli, int argc, char **argv, void *base,
                 const pu_cli_option **stopped, char *msg, size_t size);

/* The --help text (usage line, intro, options with their descriptions, epilogue), allocated
 * (free()); NULL when out of memory. */
char *pu_cli_help(const pu_cli *cli);

/* The option called name (or with alias name); NULL if none. */
const pu_cli_option *pu_cli_find(const pu_cli *cli, const char *name);
/* The visible option nearest to name by pu_cli_edit_distance (the first of equals); *dist (may
 * be NULL) its distance. NULL when the table has none. */
const pu_cli_option *pu_cli_nearest(const pu_cli *cli, const char *name, int *dist);
/* Optimal string alignment distance (insert, delete, substitute, swap of neighbours), case
 * ignored, over the first 64 characters of each. */
int pu_cli_edit_distance(const char *a, const char *b);

#ifdef __cplusplus
}
#endif
#endif
