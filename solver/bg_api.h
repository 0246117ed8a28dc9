/* BG_API marks every function and object the public headers declare. The library is compiled
 * with hidden symbol visibility by default (gnu_symbol_visibility : 'hidden' in meson.build), so
 * that the shared library exports exactly the declarations carrying BG_API and nothing of its
 * internals (tools/check-exports.py compares the two). For a program that uses the library the
 * attribute changes nothing. BG_PRINTF lets the compiler check the format strings of calls. */
#ifndef BG_API_H
#define BG_API_H

#if defined(__GNUC__) || defined(__clang__)
#define BG_API __attribute__((visibility("default")))
/* A function that takes a printf format in parameter fmt, its arguments from parameter args on. */
#define BG_PRINTF(fmt, args) __attribute__((format(printf, fmt, args)))
#else
#define BG_API
#define BG_PRINTF(fmt, args)
#endif

#endif
