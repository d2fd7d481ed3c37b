#include "data/schema/errors.h"

#include <cstdio>
#include <cstdlib>

namespace kelvin {

void CheckFailed(const char* expr, const char* file, int line, const std::string& msg) {
  std::fprintf(stderr, "kelvin: internal error at %s:%d: check '%s' failed: %s\n", file, line, expr,
               msg.c_str());
  std::abort();
}

}  // namespace kelvin
