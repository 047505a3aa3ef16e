/* seamquad: the library's version (sq_version.h). */
#include "sq_version.h"

#ifndef SQ_VERSION_STRING
#error "SQ_VERSION_STRING is defined by core/CMakeLists.txt from project()'s version"
#endif

const char *sq_version(void) { return SQ_VERSION_STRING; }
