/* seamquad: the library's version ("MAJOR.MINOR.PATCH", the project()
 * version of CMakeLists.txt), so that a program linked against an
 * installed libseamquad can say which one it runs. */
#ifndef SQ_VERSION_H
#define SQ_VERSION_H

#ifdef __cplusplus
extern "C" {
#endif

const char *sq_version(void);

#ifdef __cplusplus
}
#endif
#endif
