/**
 * \file version.hpp
 * \brief The version of this build of granular-dsmc, as `granular-dsmc --version` prints it and as
 *        the output file records it in `/h5md/creator@version` (\ref output_h5md "docs/output.md").
 */
#pragma once

namespace gdsmc::io {

/// The version of this build: the project's version followed by "+" and
/// `git describe --always --dirty --tags` of the source tree when it was built from a git checkout
/// with git installed (e.g. "0.1.0+d5e9272", "0.1.0+d5e9272-dirty"), else the project's version
/// alone (e.g. "0.1.0", a source tarball). Refreshed at every build by cmake/GitVersion.cmake; only
/// io/version.cpp depends on it, so a new commit recompiles that one file.
const char* build_version();

}  // namespace gdsmc::io
