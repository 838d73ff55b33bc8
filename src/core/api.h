/*
 * api.h - SL_API, the mark of a function of the public interface.
 *
 * libseislide.so is built with -fvisibility=hidden: a function is exported
 * only when its declaration in an installed header carries SL_API, so the
 * exported set is the declared set (tests/cli/test_install.sh checks both
 * ways). In C++ the mark also gives the declaration C linkage, so that a
 * C++ program includes <seislide/seislide.h> as it is.
 */
#ifndef SL_API_H
#define SL_API_H

#if defined(__GNUC__)
#define SL_VISIBLE __attribute__((visibility("default")))
#else
#define SL_VISIBLE
#endif

#ifdef __cplusplus
#define SL_API extern "C" SL_VISIBLE
#else
#define SL_API SL_VISIBLE
#endif

#endif
