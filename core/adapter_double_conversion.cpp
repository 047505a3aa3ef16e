// seamquad: the double-conversion adapter (sq_dtoa_adapter.h). No algorithm
// here: one converter, configured once, asked for the shortest form.
#include "sq_dtoa_adapter.h"

#include <double-conversion/double-to-string.h>
#include <double-conversion/utils.h>

extern "C" int sq_dtoa_shortest(double x, char *buf, int cap)
{
    // plain decimal where %g would write it (1e-4 up to 1e17), else an
    // exponent ("1e-5": strtod reads it as it reads "1e-05"); "-0" kept;
    // inf and nan as C prints them
    static const double_conversion::DoubleToStringConverter conv(
        double_conversion::DoubleToStringConverter::NO_FLAGS, "inf", "nan", 'e', -4, 17, 0, 0);
    double_conversion::StringBuilder sb(buf, cap);
    if (!conv.ToShortest(x, &sb)) return -1;
    int n = sb.position();
    sb.Finalize();
    return n;
}
