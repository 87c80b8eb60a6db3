/* QUADRA_API marks what libquadra.so exports: the public classes and
 * functions of quadra/quadra.hpp and quadra/quadra.h. The library is built
 * with hidden visibility, so nothing else of the engine is in its ABI. */
#ifndef QUADRA_EXPORT_H
#define QUADRA_EXPORT_H

#if defined(__GNUC__)
#define QUADRA_API __attribute__((visibility("default")))
#else
#define QUADRA_API
#endif

#endif /* QUADRA_EXPORT_H */
