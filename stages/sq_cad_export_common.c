/* seamquad: helpers shared by the STEP and IGES writers. */
#include <stdio.h>
#include <string.h>

#include "sq_subdiv.h"

const char *sq_cad_real(double x, char *buf)
{
    if (x == 0.0) x = 0.0; /* no "-0." */
    snprintf(buf, 32, "%.17G", x);
    if (strchr(buf, '.')) return buf;
    char *e = strchr(buf, 'E');
    size_t n = strlen(buf);
    if (!e) {
        buf[n] = '.';
        buf[n + 1] = '\0';
    } else {
        memmove(e + 1, e, n - (size_t)(e - buf) + 1);
        *e = '.';
    }
    return buf;
}
