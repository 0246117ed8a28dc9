/* Status names and the error record: format a message, keep it, pass it to the handler. */
#include "bg_status.h"

#include <stdio.h>
#include <string.h>

/* DAE_SUCCESS shares 0 with BG_OK: the first entry of the table with a value wins */
#define BG_STATUS_NAME_(name, value, text)                                                         \
    if (status == (value)) return #name;
#define BG_STATUS_TEXT_(name, value, text)                                                         \
    if (status == (value)) return text;

const char *bg_status_name(int status)
{
    BG_STATUS_TABLE(BG_STATUS_NAME_)
    return "unknown status";
}

const char *bg_status_message(int status)
{
    BG_STATUS_TABLE(BG_STATUS_TEXT_)
    return "unknown status";
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
