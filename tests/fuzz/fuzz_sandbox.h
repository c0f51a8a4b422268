// The folder a fuzz harness works in: a fresh temporary directory (the process's working directory
// too), holding copies of the side files the seeds refer to (external buffers, images, glTF files
// named by scene files) and nothing else. The loader reads external URIs only from the glTF file's
// folder and the scene-file harness skips sources outside it, so a harness never reads outside it.
#pragma once

#include <string>

namespace vplgi::fuzz {

// Created on the first call: a new directory under $TMPDIR (or /tmp), filled from the folder named by
// $VPLGI_FUZZ_FILES when that is set (scripts/fuzz and the ctest runs set it), removed at exit.
const std::string& sandboxDir();

} // namespace vplgi::fuzz
