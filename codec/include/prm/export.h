/* prm/export.h: PRM_API marks the public functions of the PRM libraries (prm/codec.h, prm/prm.h). The libraries
 * are built with hidden visibility, so a shared library exports those functions and nothing else. A C header. */
#ifndef PRM_EXPORT_H
#define PRM_EXPORT_H

#if defined(PRM_STATIC_DEFINE)
#define PRM_API
#elif defined(_WIN32) || defined(__CYGWIN__)
#if defined(PRM_BUILDING_LIBRARY)
#define PRM_API __declspec(dllexport)
#else
#define PRM_API __declspec(dllimport)
#endif
#elif defined(__GNUC__) || defined(__clang__)
#define PRM_API __attribute__((visibility("default")))
#else
#define PRM_API
#endif

#endif /* PRM_EXPORT_H */
