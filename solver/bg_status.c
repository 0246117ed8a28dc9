/* Status names and the error record: format a message, keep it, pass it to the handler. */
#include "bg_status.h"

#include <stdio.h>
#include <string.h>

const char *bg_status_name(int status)
{
    switch (status) {
    case BG_OK:
        return "BG_OK";
    case BG_RECOVERABLE:
        return "BG_RECOVERABLE";
    case BG_ERR_MEMORY:
        return "BG_ERR_MEMORY";
    case BG_ERR_ARGUMENT:
        return "BG_ERR_ARGUMENT";
    case BG_ERR_SINGULAR:
        return "BG_ERR_SINGULAR";
    case BG_ERR_NOT_POSDEF:
        return "BG_ERR_NOT_POSDEF";
    case BG_ERR_LIBRARY:
        return "BG_ERR_LIBRARY";
    case BG_ERR_CALLBACK:
        return "BG_ERR_CALLBACK";
    case BG_ERR_IO:
        return "BG_ERR_IO";
    case BG_ERR_PATTERN:
        return "BG_ERR_PATTERN";
    case BG_ERR_NONFINITE:
        return "BG_ERR_NONFINITE";
    case BG_ERR_STATE:
        return "BG_ERR_STATE";
    default:
        return "unknown status";
    }
}

int bg_error_vraise(bg_error *e, int status, const char *where, const char *fmt, va_list ap)
{
    if (!e) return status;
    e->status = status;
    if (fmt)
        vsnprintf(e->message, sizeof e->message, fmt, ap);
    else
        e->message[0] = '\0';
    if (e->handler) e->handler(e->user, status, where ? where : "", e->message);
    return status;
}

int bg_error_raise(bg_error *e, int status, const char *where, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    bg_error_vraise(e, status, where, fmt, ap);
    va_end(ap);
    return status;
}

void bg_error_clear(bg_error *e)
{
    if (!e) return;
    e->status = BG_OK;
    e->message[0] = '\0';
}
