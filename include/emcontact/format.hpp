#pragma once
#include <string>

namespace emc {
/// printf-style formatting into a std::string of whatever length it needs.
std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
}  // namespace emc
