// Writing an output file so that a failed run never leaves a half-written file behind: the content
// goes to a temporary in the same directory (same file system, so the rename is atomic), which is
// renamed over the target only once it is complete.
#pragma once

#include <functional>
#include <string>

namespace tessera {

// Calls write(temporary) -> error ("" on success), then renames the temporary to `path`. The
// temporary is ".STEM.tmpPID.EXT" beside the target: it keeps the extension, from which image writers
// pick the format. Returns "" or one line naming `path` (a missing directory, the writer's error, a
// failed rename); the temporary is removed on every failure.
std::string write_atomically(const std::string& path,
                             const std::function<std::string(const std::string& temporary)>& write);

}  // namespace tessera
