/* seamquad: the double-conversion adapter (core/adapter_double_conversion.cpp),
 * a thin extern "C" wrapper around Google's double-conversion library
 * (Debian libdouble-conversion-dev, BSD-3-Clause): the shortest decimal
 * string that reads back (strtod) as the same double, sign of zero kept.
 * Only sq_format_double (core/sq_format_double.c) calls it. */
#ifndef SQ_DTOA_ADAPTER_H
#define SQ_DTOA_ADAPTER_H

#ifdef __cplusplus
extern "C" {
#endif

/* Writes x into buf (cap bytes, at least 32) NUL-terminated; returns the
 * length, or -1 where it does not fit. */
int sq_dtoa_shortest(double x, char *buf, int cap);

#ifdef __cplusplus
}
#endif

#endif
