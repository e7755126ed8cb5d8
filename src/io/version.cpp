// The version of the build (io/version.hpp, \ref output_h5md "docs/output.md").
#include "io/version.hpp"

// Generated in the build tree by cmake/GitVersion.cmake: #define GDSMC_BUILD_VERSION "...".
#include "gdsmc_build_version.hpp"

namespace gdsmc::io {

const char* build_version() { return GDSMC_BUILD_VERSION; }

}  // namespace gdsmc::io
