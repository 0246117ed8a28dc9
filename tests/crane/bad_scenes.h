/* A catalogue of malformed scene files, shared by the parser test (parsed from memory) and the
 * program test (written to files and run through the crane program). Each must be refused with
 * a message that names the file, the line ("FILE:LINE:") and the key (or section) at fault. */
#ifndef CRANE_BAD_SCENES_H
#define CRANE_BAD_SCENES_H

typedef struct bad_scene {
    const char *what; /* short description, also the file name stem */
    const char *text;
    int line;         /* the line the message must name */
    const char *key;  /* must appear in the message */
    const char *also; /* another piece of the message (NULL: none) */
} bad_scene;

#define LONG_VALUE                                                                                 \
    "1111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111"  \
    "1111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111"  \
    "1111111111111111111111111111111111111111111111111111111111111111111111111111111111111111111"

static const bad_scene BAD_SCENES[] = {
    {"unknown-section", "[bom]\nlength = 76\n", 1, "[bom]", "did you mean [boom]"},
    {"unknown-key", "[boom]\nlenght = 76\n", 2, "'lenght'", "did you mean 'length'"},
    {"negative-mass", "[platform]\nmass = -5\n", 2, "key 'mass' in [platform]",
     "expected a number > 0 (kg), got '-5'"},
    {"zero-length", "[boom]\n\nlength = 0\n", 3, "key 'length' in [boom]", "got '0'"},
    {"not-a-number", "[boom]\nE = abc\n", 2, "key 'E' in [boom]", "got 'abc'"},
    {"nan", "[rope]\nA = nan\n", 2, "key 'A' in [rope]", "got 'nan'"},
    {"infinity", "[rope]\nE = inf\n", 2, "key 'E' in [rope]", "got 'inf'"},
    {"overflow", "[ties]\nA = 1e400\n", 2, "key 'A' in [ties]", "got '1e400'"},
    {"unit-in-value", "[boom]\nlength = 76 m\n", 2, "key 'length' in [boom]", "got '76 m'"},
    {"too-many-elements", "[boom]\nelements = 513\n", 2, "key 'elements' in [boom]",
     "an integer in 0..512"},
    {"negative-elements", "[boom]\nelements = -1\n", 2, "key 'elements'", "got '-1'"},
    {"fractional-elements", "[boom]\nelements = 1.5\n", 2, "key 'elements'", "got '1.5'"},
    {"bad-boolean", "[ties]\nenabled = maybe\n", 2, "key 'enabled' in [ties]", "a boolean"},
    {"short-vector", "[boom]\nfoot = 1.5, 0\n", 2, "key 'foot' in [boom]", "three"},
    {"long-vector", "[counterweight]\npos = 1, 2, 3, 4\n", 2, "key 'pos' in [counterweight]",
     "got '1, 2, 3, 4'"},
    {"nan-in-vector", "[platform]\ncom = 0, nan, 1\n", 2, "key 'com' in [platform]", NULL},
    {"negative-inertia", "[platform]\ninertia = 1e5, -1, 1e5\n", 2, "key 'inertia'",
     "three numbers > 0"},
    {"empty-value", "[load]\nmass =\n", 2, "key 'mass' in [load]", "got ''"},
    {"duplicate-key", "[load]\nmass = 1\nmass = 2\n", 3, "'mass'", "first on line 2"},
    {"key-before-section", "; scene\ng = 9.81\n", 2, "'g'", "[environment]"},
    {"missing-equals", "[boom]\nlength 76\n", 2, "length 76", "key = value"},
    {"unclosed-section", "[scene]\nname = x\n[boom\n", 3, "[boom", "']'"},
    {"continuation-line", "[boom]\nlength = 76\n    80\n", 3, "80", "continuation"},
    {"key-of-other-section", "[boom]\nmass = 5\n", 2, "'mass'", "[platform]"},
    {"rtol-too-large", "[solver]\nrtol = 1\n", 2, "key 'rtol' in [solver]", "(0, 1)"},
    {"bad-name", "[scene]\nname = a/b\n", 2, "key 'name' in [scene]", "got 'a/b'"},
    {"boom-cannot-reach", "[boom]\nlength = 10\n", 2, "key 'length' in [boom]", "reaches"},
    {"reference-order", "[reference]\nt1 = 2\nt2 = 1\n", 3, "key 't2' in [reference]", "t1 <= t2"},
    {"output-step-beyond-end", "[solver]\nt_end = 0.5\noutput_step = 1\n", 3,
     "key 'output_step' in [solver]", "t_end"},
    {"line-too-long", "[boom]\nlength = " LONG_VALUE "\n", 2, "line longer", "'length'"},
    {"text-after-section", "[boom] x\n", 1, "[boom]", "unexpected text"},
    {"far-section", "[xyzzy]\n", 1, "[xyzzy]", "sections:"},
    {"line-count", "; comment\n\n[boom]\n\n# another\nlength = 76\nrho = -1 ; bad\n", 7,
     "key 'rho' in [boom]", "got '-1'"},
    {"negative-gravity", "[environment]\ng = -9.81\n", 2, "key 'g' in [environment]", ">= 0"},
    {"negative-gain", "[controller]\nkd = -50\n", 2, "key 'kd' in [controller]", NULL},
    {"hash-comment-inline", "[rope]\nlength = 71.51 # m\n", 2, "key 'length' in [rope]",
     "got '71.51 # m'"},
    {"hex-number", "[boom]\nlength = 0x4c\n", 2, "key 'length' in [boom]",
     "numbers are decimal"},
    {"hex-in-vector", "[platform]\ncom = 0, 0x1p3, 1\n", 2, "key 'com' in [platform]",
     "numbers are decimal"},
    {"hex-integer", "[boom]\nelements = 0x10\n", 2, "key 'elements' in [boom]",
     "numbers are decimal"},
    {"vertical-boom", "[boom]\ntip_radius = 1.5\n", 2, "key 'tip_radius' in [boom]",
     "vertical flexible boom"},
    {"cr-only-line-ends", "[boom]\rlength = 76\rrho = -1\r", 3, "key 'rho' in [boom]",
     "got '-1'"},
};
#define NBAD ((int)(sizeof BAD_SCENES / sizeof *BAD_SCENES))

#endif
