#pragma once
// Writing a whole small file so that readers see either the old or the new content, never a half
// written one: summary.json and the .xdmf index are rewritten this way, so a run killed at any
// moment leaves valid files behind.
#include <filesystem>
#include <string_view>

namespace isomuscle::io {

// Writes content to a temporary file next to path, flushes it to disk (fsync), then renames it
// over path (atomic within one file system, POSIX rename). Throws std::runtime_error naming the
// path and the system's reason on any failure; the temporary file is removed then.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace isomuscle::io
