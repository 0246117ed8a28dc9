/* Status codes and error reporting shared by every module of the library.
 *
 * The library never prints, exits or aborts. Every fallible call returns a status (0 success,
 * > 0 information or a recoverable condition, < 0 an error) and, on error, writes a message into
 * the bg_error record of the object concerned. A caller who wants messages as they happen installs
 * a handler; by default there is none and the last message is kept in the record's message.
 *
 * Misuse of the API is reported, never undefined: a NULL object, array or callback where one is
 * needed, a negative or inconsistent size, or a value out of range gives BG_ERR_ARGUMENT (a
 * matrix that is not the shape or structure required gives BG_ERR_PATTERN); a call in the wrong
 * order (solving before a factorization, stepping before dae_init or after a failure, changing a
 * compiled bond-graph model, querying one that is not compiled) gives BG_ERR_STATE. The message
 * goes to the error record of the object when there is one (not when the object itself is NULL,
 * nor in functions that take the object const); functions that return a pointer return NULL and
 * those that return a count or an index return a negative value, as their header says. Freeing
 * NULL, or a pointer to NULL, is always harmless. Matrices are trusted to be well formed
 * (sp_csc_check tells) except where a header says that the structure is checked. */
#ifndef BG_STATUS_H
#define BG_STATUS_H

#include <stdarg.h>

#include "bg_api.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Every status code of the library in one table: X(name, value, meaning). The integrator's
 * return codes (DAE_*, bg_dae.h) are listed here too, so that names and messages come from one
 * place; the enums below and bg_status_name / bg_status_message are generated from it. */
#define BG_STATUS_TABLE(X)                                                                        \
    X(BG_OK, 0, "success")                                                                        \
    X(BG_RECOVERABLE, 1, "a callback asked for a retry with a smaller step")                     \
    X(BG_ERR_MEMORY, -1, "allocation failed")                                                     \
    X(BG_ERR_ARGUMENT, -2, "an argument is out of range or inconsistent")                         \
    X(BG_ERR_SINGULAR, -3, "a matrix is (numerically or structurally) singular")                  \
    X(BG_ERR_NOT_POSDEF, -4, "a matrix expected positive definite is not")                        \
    X(BG_ERR_LIBRARY, -5, "SuiteSparse or LAPACK reported a failure")                             \
    X(BG_ERR_CALLBACK, -6, "a user callback returned a fatal status")                             \
    X(BG_ERR_IO, -7, "a file could not be written or read")                                       \
    X(BG_ERR_PATTERN, -8, "a matrix does not have the pattern it was declared with")              \
    X(BG_ERR_NONFINITE, -9, "NaN or Inf where a finite number is needed")                         \
    X(BG_ERR_STATE, -10,                                                                          \
      "a call in the wrong order for the object's state (a solve before a factorization, a "    \
      "step before initialisation or after a failure, a change of a compiled model)")            \
    BG_DAE_STATUS_TABLE(X)

/* The integrator's return codes besides the ones above (dae_solve_to, dae_step). */
#define BG_DAE_STATUS_TABLE(X)                                                                    \
    X(DAE_SUCCESS, 0, "reached tout")                                                             \
    X(DAE_TSTOP_RETURN, 2, "reached t_stop")                                                      \
    X(DAE_ROOT_RETURN, 3, "an event function changed sign (see dae_roots_found)")                 \
    X(DAE_WARNING, 4, "a warning, passed to the error handler (see dae_get_warning)")             \
    X(DAE_TOO_MUCH_WORK, -20, "max_steps steps taken before tout")                                \
    X(DAE_TOO_MUCH_ACC, -21, "the tolerances are below round-off")                                \
    X(DAE_ERR_FAIL, -22, "the error test failed repeatedly (10 times in one step)")               \
    X(DAE_CONV_FAIL, -23, "the Newton iteration failed repeatedly")                               \
    X(DAE_LSETUP_FAIL, -24,                                                                       \
      "the Newton matrix is singular (or the linear solver or a projection failed)")            \
    X(DAE_RES_FAIL, -25, "the residual (or Jacobian) kept failing (recoverable failures, NaN "    \
                         "or Inf)")                                                              \
    X(DAE_CALLBACK_FAIL, -26, "a callback returned a fatal status (< 0)")                         \
    X(DAE_INIT_FAIL, -27, "consistent initialisation failed")                                     \
    X(DAE_STEP_TOO_SMALL, -28, "the step size fell below h_min (or round-off)")

#define BG_STATUS_ENUM_(name, value, text) name = value,
enum bg_status_code { BG_STATUS_TABLE(BG_STATUS_ENUM_) };
#undef BG_STATUS_ENUM_

/* Name of a status code, e.g. "BG_ERR_SINGULAR" or "DAE_CONV_FAIL" (0 is "BG_OK"); "unknown
 * status" for others. Never NULL. */
BG_API const char *bg_status_name(int status);
/* What a status code means, in a few words; "unknown status" for others. Never NULL. */
BG_API const char *bg_status_message(int status);

/* Called with the status, the function that failed and the message. */
typedef void (*bg_error_handler)(void *user, int status, const char *where, const char *message);

#define BG_MESSAGE_SIZE 1024 /* a failure message with its note and hints fits */

typedef struct bg_error {
    bg_error_handler handler; /* NULL: keep the message only */
    void *user;
    int status; /* status of the last error, BG_OK if none */
    char message[BG_MESSAGE_SIZE];
} bg_error;

/* Record an error (format as printf), call the handler if any; returns status. e may be NULL
 * (nothing is recorded, the status is returned all the same). */
BG_API BG_PRINTF(4, 5) int bg_error_raise(bg_error *e, int status, const char *where,
                                          const char *fmt, ...);
BG_API int bg_error_vraise(bg_error *e, int status, const char *where, const char *fmt, va_list ap);
/* Status BG_OK and an empty message; e may be NULL. */
BG_API void bg_error_clear(bg_error *e);

#ifdef __cplusplus
}
#endif
#endif
