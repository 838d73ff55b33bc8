/*
 * gslerr.h - GSL's error handler around the library's GSL calls, the
 * caller's left as it was.
 *
 * GSL reports an error by calling one process-wide handler, which by
 * default prints and calls abort() (gsl_errno.h). The library checks the
 * return code of every GSL call itself, so while its GSL calls run the
 * handler is off, and afterwards the handler the caller had set (GSL's
 * default, gsl_set_error_handler_off(), or the caller's own function) is
 * back: the library changes no process-wide state behind its caller's back.
 *
 * The calls nest and may come from several threads at once (sl_slide_batch
 * runs motions on OpenMP threads): the first sl_gsl_quiet_begin() saves the
 * caller's handler and turns GSL's off, the last sl_gsl_quiet_end() puts it
 * back (a counter under a mutex). The handler being process-wide, code of
 * the caller's that calls GSL on another thread while the library runs
 * finds it off too, and a handler the caller sets meanwhile is replaced by
 * the saved one at the end.
 *
 * Not part of the public interface (seislide.h); used by slide/refmodel.c.
 */
#ifndef SL_GSLERR_H
#define SL_GSLERR_H

/* Turn GSL's error handler off, saving the caller's (the first of nested or
 * concurrent calls). Pair every call with sl_gsl_quiet_end(). */
void sl_gsl_quiet_begin(void);

/* Undo one sl_gsl_quiet_begin(); the last one restores the saved handler. */
void sl_gsl_quiet_end(void);

#endif
