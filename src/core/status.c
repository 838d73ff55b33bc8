/* status.c - status messages and the error record. */
#include "core/status.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static const char *const status_messages[SL_STATUS_COUNT] = {
    [SL_OK] = "success",
    [SL_EIO] = "input/output error",
    [SL_EPARSE] = "malformed input",
    [SL_EINVAL] = "invalid value",
    [SL_ENOMEM] = "out of memory",
    [SL_ENOCONV] = "did not converge",
    [SL_ESOLVER] = "numerical solver failed",
    [SL_EUNSUPPORTED] = "not supported",
};

const char *sl_status_message(sl_status code)
{
    if ((int)code < 0 || code >= SL_STATUS_COUNT || !status_messages[code])
        return "unknown status";
    return status_messages[code];
}

void sl_error_clear(sl_error *err)
{
    if (!err)
        return;
    err->code = SL_OK;
    err->line = 0;
    err->col = 0;
    err->file[0] = '\0';
    err->msg[0] = '\0';
}

sl_status sl_error_set(sl_error *err, sl_status code, const char *file,
                       long line, const char *fmt, ...)
{
    if (!err)
        return code;
    err->code = code;
    err->line = line;
    err->col = 0;
    snprintf(err->file, sizeof err->file, "%s", file ? file : "");
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    return code;
}

sl_status sl_error_set_at(sl_error *err, sl_status code, const char *file, long line,
                          long col, const char *fmt, ...)
{
    if (!err)
        return code;
    err->code = code;
    err->line = line;
    err->col = line > 0 ? col : 0;
    snprintf(err->file, sizeof err->file, "%s", file ? file : "");
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    return code;
}

char *sl_error_format(const sl_error *err, char *buf, size_t n)
{
    if (!buf || n == 0)
        return buf;
    if (!err) {
        snprintf(buf, n, "unknown error");
        return buf;
    }
    const char *msg = err->msg[0] ? err->msg : sl_status_message(err->code);
    if (err->file[0] && err->line > 0 && err->col > 0)
        snprintf(buf, n, "%s:%ld:%ld: %s", err->file, err->line, err->col, msg);
    else if (err->file[0] && err->line > 0)
        snprintf(buf, n, "%s:%ld: %s", err->file, err->line, msg);
    else if (err->file[0])
        snprintf(buf, n, "%s: %s", err->file, msg);
    else
        snprintf(buf, n, "%s", msg);
    return buf;
}
