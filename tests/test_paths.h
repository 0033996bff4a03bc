#pragma once
// Where the tests find the source tree (samples) and the built program.
#ifndef SLOWLIGHT_SOURCE_DIR
#error "SLOWLIGHT_SOURCE_DIR must be defined by the build"
#endif
namespace sl::test {
inline const char* source_dir() { return SLOWLIGHT_SOURCE_DIR; }
inline const char* binary() { return SLOWLIGHT_BINARY; }
}  // namespace sl::test
