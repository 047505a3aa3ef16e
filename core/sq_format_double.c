/* seamquad: sq_format_double (sq_format_double.h). */
#include "sq_format_double.h"

#include <stdio.h>

#ifdef SQ_HAVE_DOUBLE_CONVERSION
#include "sq_dtoa_adapter.h"
#endif

int sq_format_double(double x, char *buf)
{
#ifdef SQ_HAVE_DOUBLE_CONVERSION
    int n = sq_dtoa_shortest(x, buf, SQ_FORMAT_DOUBLE_CAP);
    if (n >= 0) return n;
#endif
    return snprintf(buf, SQ_FORMAT_DOUBLE_CAP, "%.17g", x);
}
