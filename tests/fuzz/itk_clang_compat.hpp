#pragma once
/// @brief Lets clang compile Debian's ITK 5.2 headers (fuzz builds only). Debian ships ITK's
/// compiler detection as generated for gcc: for any other compiler it stops with "Unsupported
/// compiler". Forced-included before stages/labelmap/itk_label_io.cpp in clang builds, this
/// runs that detection once as if for gcc 12 (whose feature set clang 14 has), then restores the
/// compiler's own macros, so nothing else in the file sees the change.

#pragma push_macro("__clang__")
#pragma push_macro("__GNUC__")
#pragma push_macro("__GNUC_MINOR__")
#undef __clang__
#undef __GNUC__
#undef __GNUC_MINOR__
#define __GNUC__ 12
#define __GNUC_MINOR__ 2
#include <itk_compiler_detection.h>
#pragma pop_macro("__GNUC_MINOR__")
#pragma pop_macro("__GNUC__")
#pragma pop_macro("__clang__")
