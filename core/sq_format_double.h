/* seamquad: a double as the shortest decimal that reads back as the same
 * bits (strtod), for the OBJ writers. With double-conversion (Debian
 * libdouble-conversion-dev; core/adapter_double_conversion.cpp) the
 * shortest form; without it, printf's %.17g (exact too, longer, and 3 to 5
 * times slower). */
#ifndef SQ_FORMAT_DOUBLE_H
#define SQ_FORMAT_DOUBLE_H

#define SQ_FORMAT_DOUBLE_CAP 32

/* Writes x into buf (SQ_FORMAT_DOUBLE_CAP bytes) NUL-terminated; returns
 * the length. */
int sq_format_double(double x, char *buf);

#endif
