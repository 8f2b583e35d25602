#pragma once
// Helpers shared by the test suites.

#include <string>

#include "core/context.h"

namespace penumbra::test {

/// Absolute path of a file in the source tree (e.g. "data/cornell/scene.json").
std::string source_path(const std::string& relative);

/// A fresh empty temporary folder, unique per call.
std::string temp_dir(const std::string& tag);

/// A context that logs warnings and errors to stderr only, with the given thread count.
Context quiet_context(int threads = 0);

} // namespace penumbra::test
