/* The expressions of the model files (model/mdl_expr.h): precedence and associativity, numbers,
 * every function against libm, the constants, lazy if/&&/||, names with evaluated indices,
 * evaluation and syntax errors with their messages and columns, the names a tree refers to,
 * path substitution and the depth limit against hostile nesting. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mdl_expr.h"
#include "tap.h"

/* ---- a lookup over a fixed table that records the names asked for ---- */

static const struct {
    const char *name;
    double value;
} table[] = {
    {"a", 2},        {"b", 3},        {"k", 2},        {"n", 4},         {"x", 0.5},
    {"big", 1e10},   {"seg[1].L", 5}, {"seg[3].L", 7}, {"seg[-1].L", 9}, {"boom.node[4].x", 1.5},
    {"nan_param", 0}};

typedef struct asked {
    char names[16][MDL_EXPR_NAME_MAX];
    int n;
} asked;

static int lookup(void *user, const char *name, double *value, char *msg, size_t msz)
{
    asked *a = user;
    if (a && a->n < 16) strcpy(a->names[a->n++], name);
    if (!strcmp(name, "refused")) {
        snprintf(msg, msz, "parameter '%s' is refused here", name);
        return -1;
    }
    if (!strcmp(name, "nan_param")) {
        *value = NAN;
        return 0;
    }
    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++)
        if (!strcmp(table[i].name, name)) {
            *value = table[i].value;
            return 0;
        }
    return -1;
}

/* Parses and evaluates text; NAN on any failure (with a diagnostic). */
static double value_of(const char *text)
{
    mdl_expr_error e = {0, ""};
    mdl_expr *x = mdl_expr_parse(text, &e);
    if (!x) {
        tap_diag("parse '%s': %s (column %d)", text, e.message, e.column);
        return NAN;
    }
    double v;
    int r = mdl_expr_eval(x, lookup, NULL, &v, &e);
    mdl_expr_free(x);
    if (r != 0) {
        tap_diag("eval '%s': %s (column %d)", text, e.message, e.column);
        return NAN;
    }
    return v;
}

static void is(const char *text, double want)
{
    tap_close(value_of(text), want, 0, 0, "%s = %.17g", text, want);
}

/* A syntax error: message and column. */
static void parse_error(const char *text, const char *message, int column)
{
    mdl_expr_error e = {-1, ""};
    mdl_expr *x = mdl_expr_parse(text, &e);
    if (!tap_ok(!x && !strcmp(e.message, message) && e.column == column,
                "parse error '%s': %s at %d", text, message, column))
        tap_diag("got %s, '%s' at %d", x ? "a tree" : "NULL", e.message, e.column);
    mdl_expr_free(x);
}

/* An evaluation error: message and column. */
static void eval_error(const char *text, const char *message, int column)
{
    mdl_expr_error e = {-1, ""};
    mdl_expr *x = mdl_expr_parse(text, &e);
    double v = 0;
    int r = x ? mdl_expr_eval(x, lookup, NULL, &v, &e) : 1;
    if (!tap_ok(x && r == -1 && !strcmp(e.message, message) && e.column == column,
                "eval error '%s': %s at %d", text, message, column))
        tap_diag("got r=%d v=%g, '%s' at %d", r, v, e.message, e.column);
    mdl_expr_free(x);
}

static void test_precedence(void)
{
    is("1+2*3", 7);
    is("(1+2)*3", 9);
    is("10-4-3", 3);
    is("24/4/2", 3);
    is("2^3^2", 512);
    is("(2^3)^2", 64);
    is("-2^2", -4);
    is("(-2)^2", 4);
    is("2^-1", 0.5);
    is("2*3^2", 18);
    is("-3*-2", 6);
    is("--3", 3);
    is("+4", 4);
    is("2 - -2", 4);
    is("1+1 == 2", 1);
    is("1 < 2", 1);
    is("2 <= 2", 1);
    is("3 > 4", 0);
    is("3 >= 4", 0);
    is("1 == 1", 1);
    is("1 != 1", 0);
    is("1 < 2 == 1", 1);
    is("1 < 2 && 2 < 1", 0);
    is("0 || 3", 1);
    is("1 || 0 && 0", 1);
    is("(1 || 0) && 0", 0);
    is("!0", 1);
    is("!5", 0);
    is("!0 + 1", 2);
    is("-a^2", -4);
    is("  7  ", 7);
    is("1e-3", 1e-3);
    is(".5", 0.5);
    is("1.", 1);
    is("1.5E+2", 150);
    is("2.5e0*4", 10);
}

static void test_functions(void)
{
    tap_close(value_of("sqrt(2)"), sqrt(2), 0, 0, "sqrt");
    tap_close(value_of("exp(0.7)"), exp(0.7), 0, 0, "exp");
    tap_close(value_of("log(3)"), log(3), 0, 0, "log");
    tap_close(value_of("log10(200)"), log10(200), 0, 0, "log10");
    tap_close(value_of("sin(0.3)"), sin(0.3), 0, 0, "sin");
    tap_close(value_of("cos(0.3)"), cos(0.3), 0, 0, "cos");
    tap_close(value_of("tan(0.3)"), tan(0.3), 0, 0, "tan");
    tap_close(value_of("asin(0.4)"), asin(0.4), 0, 0, "asin");
    tap_close(value_of("acos(0.4)"), acos(0.4), 0, 0, "acos");
    tap_close(value_of("atan(2)"), atan(2), 0, 0, "atan");
    tap_close(value_of("atan2(1, -2)"), atan2(1, -2), 0, 0, "atan2");
    tap_close(value_of("sinh(0.5)"), sinh(0.5), 0, 0, "sinh");
    tap_close(value_of("cosh(0.5)"), cosh(0.5), 0, 0, "cosh");
    tap_close(value_of("tanh(0.5)"), tanh(0.5), 0, 0, "tanh");
    tap_close(value_of("hypot(3, 4)"), 5, 0, 0, "hypot");
    tap_close(value_of("abs(-2.5)"), 2.5, 0, 0, "abs");
    tap_close(value_of("min(3, 1, 2)"), 1, 0, 0, "min variadic");
    tap_close(value_of("max(3, 1, 2)"), 3, 0, 0, "max variadic");
    tap_close(value_of("min(5)"), 5, 0, 0, "min of one");
    tap_close(value_of("floor(-1.5)"), -2, 0, 0, "floor");
    tap_close(value_of("ceil(-1.5)"), -1, 0, 0, "ceil");
    tap_close(value_of("round(2.5)"), 3, 0, 0, "round half away from zero");
    tap_close(value_of("round(-2.5)"), -3, 0, 0, "round negative");
    tap_close(value_of("pow(2, 0.5)"), pow(2, 0.5), 0, 0, "pow");
    tap_close(value_of("sqrt (a*8)"), 4, 0, 0, "blank before '('");
    tap_close(value_of("max(a, b) - min(a, b)"), 1, 0, 0, "min/max of names");
}

static void test_constants(void)
{
    const double pi = 3.14159265358979323846;
    tap_close(value_of("pi"), pi, 0, 0, "pi");
    tap_close(value_of("90*deg"), pi / 2, 1e-16, 0, "90 deg");
    tap_close(value_of("bar"), 1e5, 0, 0, "bar");
    tap_close(value_of("MPa"), 1e6, 0, 0, "MPa");
    tap_close(value_of("mm"), 1e-3, 0, 0, "mm");
    tap_close(value_of("lpm"), 1e-3 / 60, 0, 0, "lpm");
    tap_close(value_of("rpm"), 2 * pi / 60, 0, 0, "rpm");
    tap_close(value_of("g0"), 9.80665, 0, 0, "g0");
    tap_close(value_of("200*bar"), 2e7, 0, 0, "200 bar");
    tap_close(value_of("60*lpm"), 1e-3, 1e-15, 0, "60 l/min is a litre per second");
    tap_ok(mdl_expr_is_reserved("sqrt") && mdl_expr_is_reserved("pi") &&
               mdl_expr_is_reserved("if") && mdl_expr_is_reserved("deg") &&
               mdl_expr_is_reserved("min"),
           "functions and constants are reserved");
    tap_ok(!mdl_expr_is_reserved("mass") && !mdl_expr_is_reserved("Pi") &&
               !mdl_expr_is_reserved("sqrt2") && !mdl_expr_is_reserved(""),
           "other names are not reserved");
}

static void test_lazy(void)
{
    is("if(1, 2, 1/0)", 2);
    is("if(0, 1/0, 3)", 3);
    is("if(a > 1, a, nosuch)", 2);
    is("if(a - 2, nosuch, b)", 3);
    is("0 && 1/0", 0);
    is("1 || nosuch", 1);
    is("if(a < b, if(0, 1, 5), 6) + 1", 6);
}

static void test_names(void)
{
    asked got = {.n = 0};
    mdl_expr_error e;
    mdl_expr *x = mdl_expr_parse("seg[k+1].L + boom.node[n].x + seg[seg[1].L - 6].L", &e);
    double v = 0;
    int r = x ? mdl_expr_eval(x, lookup, &got, &v, &e) : -1;
    tap_ok(r == 0 && v == 7 + 1.5 + 9, "names with indices evaluate (%g)", v);
    tap_ok(got.n == 6 && !strcmp(got.names[0], "k") && !strcmp(got.names[1], "seg[3].L") &&
               !strcmp(got.names[2], "n") && !strcmp(got.names[3], "boom.node[4].x") &&
               !strcmp(got.names[4], "seg[1].L") && !strcmp(got.names[5], "seg[-1].L"),
           "the lookup gets the full paths with integer indices");
    tap_ok(x && !strcmp(mdl_expr_text(x), "seg[k+1].L + boom.node[n].x + seg[seg[1].L - 6].L"),
           "the text is kept");
    mdl_expr_free(x);
    is("a + b", 5);
    is("seg[ 1 ].L", 5);
    is("seg[2.0 - 1].L", 5);
}

static void test_eval_errors(void)
{
    eval_error("a / (b - 3)", "division by zero in 'a / (b - 3)'", 0);
    eval_error("1 + a/(b-3)", "division by zero in 'a/(b-3)'", 4);
    eval_error("sqrt(-1)", "square root of a negative number in 'sqrt(-1)'", 0);
    eval_error("2*log(0)", "logarithm of zero in 'log(0)'", 2);
    eval_error("log10(-a)", "logarithm of a negative number in 'log10(-a)'", 0);
    eval_error("exp(1000)", "overflow in 'exp(1000)'", 0);
    eval_error("1e308 * 10", "overflow in '1e308 * 10'", 0);
    eval_error("big^big", "overflow in 'big^big'", 0);
    eval_error("acos(2)", "argument outside [-1, 1] in 'acos(2)'", 0);
    eval_error("0^-1", "zero to a negative power in '0^-1'", 0);
    eval_error("pow(0, -1)", "zero to a negative power in 'pow(0, -1)'", 0);
    eval_error("(-8)^(1/3)", "negative number to a non-integer power in '(-8)^(1/3)'", 0);
    eval_error("cosh(1000)", "overflow in 'cosh(1000)'", 0);
    eval_error("a + zz", "unknown name 'zz'", 4);
    eval_error("1 + refused", "parameter 'refused' is refused here", 4);
    eval_error("nan_param * 0", "'nan_param' is not a finite number", 0);
    eval_error("seg[x].L", "index 'x' of 'seg' is not an integer (0.5)", 4);
    eval_error("b + boom.node[k / 4 ].x", "index 'k / 4' of 'boom.node' is not an integer (0.5)",
               14);
    eval_error("seg[big].L", "index 'big' of 'seg' is out of range (10000000000)", 4);
    eval_error("seg[k].L", "unknown name 'seg[2].L'", 0);
    eval_error("if(1, 1/0, 2)", "division by zero in '1/0'", 6);
    eval_error("1 && 1/0", "division by zero in '1/0'", 5);
    /* a long sub-expression is cut */
    eval_error("(1000000000 + 1000000000 + 1000000000 + 1000000000 + 1000000000 + a) / 0",
               "division by zero in '(1000000000 + 1000000000 + 1000000000 + 1000000000 + "
               "1000...'",
               0);
    mdl_expr_error e;
    mdl_expr *x = mdl_expr_parse("a", &e);
    double v;
    tap_ok(x && mdl_expr_eval(x, NULL, NULL, &v, &e) == -1 &&
               !strcmp(e.message, "unknown name 'a'"),
           "no lookup: every name is unknown");
    mdl_expr_free(x);
}

static void test_parse_errors(void)
{
    parse_error(")", "unexpected ')'", 0);
    parse_error("1 + )", "unexpected ')'", 4);
    parse_error("(1+2", "expected ')' to close '(' at column 0 before the end of the expression",
                4);
    parse_error("2*(a 3)", "expected ')' to close '(' at column 2", 5);
    parse_error("sqr(2)", "unknown function 'sqr' (did you mean 'sqrt'?)", 0);
    parse_error("1 + atn(2)", "unknown function 'atn' (did you mean 'atan'?)", 4);
    parse_error("frobnicate(2)", "unknown function 'frobnicate'", 0);
    parse_error("a.b(2)", "unknown function 'a.b'", 0);
    parse_error("atan2(1)", "atan2 takes 2 arguments, got 1", 0);
    parse_error("sqrt(1, 2)", "sqrt takes 1 argument, got 2", 0);
    parse_error("if(1, 2)", "if takes 3 arguments, got 2", 0);
    parse_error("min()", "min takes at least 1 argument, got 0", 0);
    parse_error("max(1, 2",
                "expected ')' to close '(' at column 3 before the end of the expression", 8);
    parse_error("hypot(1 2)", "expected ',' or ')' to close '(' at column 5", 8);
    parse_error("", "empty expression", 0);
    parse_error("   ", "empty expression", 3);
    parse_error("1 2", "unexpected number '2'", 2);
    parse_error("a b", "unexpected name 'b'", 2);
    parse_error("2x", "malformed number '2x'", 0);
    parse_error("1 + 1e", "malformed number '1e'", 4);
    parse_error("1.2.3", "malformed number '1.2.3'", 0);
    parse_error("1e999", "number '1e999' is too large", 0);
    parse_error("a.", "expected a name after '.'", 2);
    parse_error("a.1", "expected a name after '.'", 2);
    parse_error("seg[1", "expected ']' to close '[' at column 3 before the end of the expression",
                5);
    parse_error("seg[1).L", "expected ']' to close '[' at column 3", 5);
    parse_error("sqrt + 1", "'sqrt' is a function: call it as sqrt(...)", 0);
    parse_error("a & b", "unexpected '&'", 2);
    parse_error("a = b", "unexpected '='", 2);
    parse_error("1 +", "unexpected end of expression", 3);
    parse_error("1 + \x01", "unexpected character 0x01", 4);
    parse_error("!= 1", "unexpected '!'", 0);
    parse_error("seg[].L", "unexpected ']'", 4);
}

static char *repeat(const char *head, const char *unit, int n, const char *tail)
{
    size_t lu = strlen(unit);
    char *s = malloc(strlen(head) + lu * (size_t)n + strlen(tail) + 1);
    strcpy(s, head);
    char *p = s + strlen(head);
    for (int i = 0; i < n; i++, p += lu)
        memcpy(p, unit, lu);
    strcpy(p, tail);
    return s;
}

static void deep(const char *what, char *text, int ok)
{
    mdl_expr_error e = {0, ""};
    mdl_expr *x = mdl_expr_parse(text, &e);
    if (ok)
        tap_ok(x != NULL, "%s: parsed", what);
    else
        tap_ok(!x && strstr(e.message, "nested too deeply"), "%s: refused (%s at %d)", what,
               e.message, e.column);
    mdl_expr_free(x);
    free(text);
}

static void test_depth(void)
{
    char *open = repeat("", "(", 10000, "1");
    char *s = repeat(open, ")", 10000, "");
    free(open);
    deep("10000 nested parentheses", s, 0);
    deep("10000 unary minus", repeat("", "-", 10000, "1"), 0);
    deep("a sum of 5000 terms", repeat("1", "+1", 5000, ""), 0);
    deep("2^2^...^2 1000 times", repeat("2", "^2", 1000, ""), 0);
    deep("seg[seg[...]] 1000 times", repeat("", "s[", 1000, "1]"), 0);
    deep("a sum of 200 terms", repeat("1", "+1", 200, ""), 1);
    open = repeat("", "(", 100, "1");
    deep("100 nested parentheses", repeat(open, ")", 100, ""), 1);
    free(open);
    s = repeat("1", "+1", 200, "");
    tap_close(value_of(s), 201, 0, 0, "the sum of 200 terms");
    free(s);
}

typedef struct seen {
    char names[8][MDL_EXPR_NAME_MAX];
    int n;
} seen;

static void visit(void *user, const char *name)
{
    seen *s = user;
    if (s->n < 8) strcpy(s->names[s->n], name);
    s->n++;
}

static void test_names_listing(void)
{
    mdl_expr_error e;
    mdl_expr *x =
        mdl_expr_parse("a + seg[k+1].L * sqrt(b) + seg[2*3].x + pi + if(c, d.e[1.5], 2)", &e);
    seen s = {.n = 0};
    int n = mdl_expr_names(x, visit, &s);
    tap_ok(n == 7 && s.n == 7, "seven names listed (%d)", n);
    tap_ok(s.n == 7 && !strcmp(s.names[0], "a") && !strcmp(s.names[1], "k") &&
               !strcmp(s.names[2], "seg[*].L") && !strcmp(s.names[3], "b") &&
               !strcmp(s.names[4], "seg[6].x") && !strcmp(s.names[5], "c") &&
               !strcmp(s.names[6], "d.e[*]"),
           "names in text order, index names first, constant indices folded");
    tap_ok(!mdl_expr_is_constant(x), "an expression with names is not constant");
    mdl_expr_free(x);
    x = mdl_expr_parse("2*pi + sqrt(2) * bar", &e);
    s.n = 0;
    tap_ok(x && mdl_expr_is_constant(x) && mdl_expr_names(x, visit, &s) == 0 && s.n == 0,
           "numbers, constants and functions are constant");
    mdl_expr_free(x);
    x = mdl_expr_parse("p.q", &e);
    tap_ok(x && mdl_expr_names(x, NULL, NULL) == 1, "counting without a visitor");
    mdl_expr_free(x);
}

static void subst(const char *path, const char *want)
{
    char out[64] = "";
    mdl_expr_error e = {0, ""};
    int r = mdl_expr_subst(path, lookup, NULL, out, sizeof out, &e);
    if (!tap_ok(r == 0 && !strcmp(out, want), "subst '%s' -> '%s'", path, want))
        tap_diag("got %d '%s' (%s)", r, out, e.message);
}

static void subst_error(const char *path, size_t osz, const char *message, int column)
{
    char out[64] = "";
    mdl_expr_error e = {-1, ""};
    int r = mdl_expr_subst(path, lookup, NULL, out, osz, &e);
    if (!tap_ok(r == -1 && !strcmp(e.message, message) && e.column == column,
                "subst error '%s': %s at %d", path, message, column))
        tap_diag("got %d '%s' at %d", r, e.message, e.column);
}

static void test_subst(void)
{
    subst("seg[k].b", "seg[2].b");
    subst(" boom.tip ", "boom.tip");
    subst("seg[k+1].node[2*k].x", "seg[3].node[4].x");
    subst("seg[seg[1].L].a", "seg[5].a");
    subst("pi", "pi");
    subst("rope[-n]", "rope[-4]");
    subst_error("seg[x].b", 64, "index 'x' of 'seg' is not an integer (0.5)", 4);
    subst_error("seg[k", 64,
                "expected ']' to close '[' at column 3 before the end of the expression", 5);
    subst_error("1abc", 64, "expected a path (name.name[index]...)", 0);
    subst_error("", 64, "empty path", 0);
    subst_error("a.b c", 64, "unexpected name 'c'", 4);
    subst_error("a + b", 64, "unexpected '+'", 2);
    subst_error("seg[zz].a", 64, "unknown name 'zz'", 4);
    subst_error("seg[k].bbbbbbbb", 8, "path 'seg[2].bbbbbbbb' too long for its buffer (8 bytes)",
                0);
}

/* A path within the parser's length limit whose indices, written out, pass MDL_EXPR_NAME_MAX. */
static void test_long_names(void)
{
    char *text = repeat("a[1e9]", ".a[1e9]", 20, "");
    mdl_expr_error e = {0, ""};
    mdl_expr *x = mdl_expr_parse(text, &e);
    double v;
    tap_ok(x && mdl_expr_eval(x, lookup, NULL, &v, &e) == -1 &&
               !strcmp(e.message, "name too long (more than 254 characters)"),
           "a name too long once its indices are written: %s", e.message);
    mdl_expr_free(x);
    free(text);
    text = repeat("a", ".a", 200, "");
    tap_ok(!mdl_expr_parse(text, &e) &&
               !strcmp(e.message, "name too long (more than 240 characters)"),
           "a name too long to parse: %s", e.message);
    free(text);
}

int main(void)
{
    test_precedence();
    test_functions();
    test_constants();
    test_lazy();
    test_names();
    test_eval_errors();
    test_parse_errors();
    test_depth();
    test_names_listing();
    test_subst();
    test_long_names();
    return tap_done();
}
